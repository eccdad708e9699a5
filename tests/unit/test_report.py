"""Unit tests of rotorlab.report (and the figures it embeds from rotorlab.plot)."""

from __future__ import annotations

import base64
import html
import os
import re

import numpy as np
import pytest

from rotorlab.analyses import run_case, summarize
from rotorlab.io import load_netcdf, parse_case
from rotorlab.plot import amplitude_figure, ball_angle_figure, orbit_figure, simulation_figures
from rotorlab.report import MANIFEST_NAME, REPORT_NAME, parameter_rows, versions, write_report

_CASE = """
name = "tiny"
description = "two balls, two speeds, short runs"
[model]
type = "jeffcott_balls"
disc_mass = "1 kg"
eccentricity = "1.5 mm"
stiffness = "16.74 kN/m"
damping = "13.32 N*s/m"
[[model.balls]]
mass = "30 g"
radius = "50 mm"
damping = "2e-3 N*m*s"
count = 2
[[analysis]]
type = "simulate"
name = "below"
speed = "720 rpm"
initial_ball_angles = [["0 deg", "90 deg"], ["45 deg", "200 deg"]]
t_end = "1 s"
n_save = 50
[[analysis]]
type = "simulate"
name = "above"
speed_ratio = 2.0
initial_ball_angles = [["120 deg", "240 deg"]]
revolutions = 20
n_save = 50
"""


@pytest.fixture(scope="module")
def run():
    case = parse_case(_CASE, origin="tiny.toml")
    results = run_case(case)
    tables = {name: summarize(ds) for name, ds in results.items()}
    return case, results, tables


def _figures(results):
    return {name: simulation_figures(ds, name) for name, ds in results.items()}


def test_report_is_one_self_contained_file(run, tmp_path):
    case, results, tables = run
    figures = _figures(results)
    out = tmp_path / "out"
    report = write_report(out, case, results, figures, tables)
    assert report == out / REPORT_NAME
    text = report.read_text(encoding="utf-8")
    # every figure embedded as a PNG data URI, decodable, and identical to the PNG file next to it
    uris = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', text)
    stems = [k for by_stem in figures.values() for k in by_stem]
    assert len(uris) == len(stems) == 6
    pngs = {p.name: p.read_bytes() for p in out.glob("*.png")}
    assert sorted(pngs) == sorted(f"{k}.png" for k in stems)
    assert sorted(base64.b64decode(u) for u in uris) == sorted(pngs.values())
    assert all(b.startswith(b"\x89PNG") for b in pngs.values())
    # nothing is fetched from anywhere
    assert not re.search(r"""(src|href)\s*=\s*["']?\s*(https?:)?//""", text, re.I)
    assert not re.search(r"url\(\s*['\"]?(https?:)?//", text, re.I)
    assert "<script" not in text.lower() and "<link" not in text.lower()
    assert "<style>" in text


def test_report_content(run, tmp_path):
    case, results, tables = run
    text = write_report(tmp_path / "o", case, results, _figures(results), tables).read_text()
    assert "rotorlab report: tiny" in text and "two balls, two speeds, short runs" in text
    for package, version in versions().items():
        assert f"<td>{package}</td><td>{version}</td>" in text
    # parameters in SI with units, speeds also in rpm and Hz
    assert "<td>model.stiffness</td><td class=\"num\">16740</td><td>N/m</td>" in text
    assert "720 rpm = 12 Hz" in text
    assert "critical speed p = sqrt(c / M)" in text and "1200.04 rpm = 20.0007 Hz" in text
    assert "±120°" in text
    # one outcome row per trajectory, the case text (escaped), links to the result files
    assert text.count('<span class="outcome-') == 3
    assert 'speed = &quot;720 rpm&quot;' in text
    assert '<a href="below.nc">below.nc</a>' in text


def test_results_and_netcdf_round_trip(run, tmp_path):
    case, results, tables = run
    write_report(tmp_path / "o", case, results, {}, tables)
    files = sorted(p.name for p in (tmp_path / "o").iterdir())
    assert files == [MANIFEST_NAME, "above.nc", "below.nc", REPORT_NAME]
    assert (tmp_path / "o" / MANIFEST_NAME).read_text().split() == ["below.nc", "above.nc", REPORT_NAME]
    back = load_netcdf(tmp_path / "o" / "below.nc")
    np.testing.assert_array_equal(back.amplitude.values, results["below"].amplitude.values)
    assert list(back.outcome.values.ravel()) == list(results["below"].outcome.values.ravel())
    assert back.speed_rpm.attrs["units"] == "rpm"


def test_failure_leaves_nothing(run, tmp_path):
    case, results, tables = run

    class Broken:
        def savefig(self, *args, **kwargs):
            raise RuntimeError("cannot render")

    with pytest.raises(RuntimeError, match="cannot render"):
        write_report(tmp_path / "o", case, results, {"below": {"below_bad": Broken()}}, tables)
    assert os.listdir(tmp_path) == []


def test_existing_folder_updated_in_place(run, tmp_path):
    case, results, tables = run
    out = tmp_path / "o"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    (out / REPORT_NAME).write_text("old")
    write_report(out, case, results, {}, tables)
    assert (out / "notes.txt").read_text() == "mine"
    assert (out / REPORT_NAME).read_text().startswith("<!DOCTYPE html>")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]  # no staging folder left


def test_rerun_removes_only_its_own_stale_files(run, tmp_path):
    case, results, tables = run
    out = tmp_path / "o"
    write_report(out, case, results, {}, tables)
    (out / "notes.txt").write_text("mine")
    write_report(out, case, {"below": results["below"]}, {}, {"below": tables["below"]})
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST_NAME, "below.nc", "notes.txt", REPORT_NAME]


def test_output_must_be_a_folder(run, tmp_path):
    case, results, tables = run
    target = tmp_path / "file"
    target.write_text("x")
    with pytest.raises(ValueError, match="exists and is not a folder"):
        write_report(target, case, results, {}, tables)


def test_bad_file_names_rejected(run, tmp_path):
    case, results, tables = run
    with pytest.raises(ValueError, match="plain file names"):
        write_report(tmp_path / "o", case, {"../escape": results["below"]}, {}, tables)
    assert not (tmp_path / "o").exists()


def test_parameter_rows_units(run):
    case = run[0]
    rows = {r[0]: r for r in parameter_rows(case.model, "model")}
    assert rows["model.disc_mass"][1:3] == ("1", "kg")
    assert rows["model.balls[1].damping"][1:3] == ("0.002", "N*m*s/rad")
    assert rows["model.balls[0].friction"][2] == ""  # dimensionless: no unit shown (not "1")
    assert "model.balls[0].count" not in rows
    rows = {r[0]: r for r in parameter_rows(case.analyses[0], "a")}
    assert rows["a.initial_ball_angles"][3] == "(0°, 90°), (45°, 200°)"


def test_figures_have_labelled_axes(run):
    ds = run[1]["below"]
    fig = amplitude_figure(ds)
    ax = fig.axes[0]
    # the time axis is stretched (asinh): its label says where it turns logarithmic (t_end / 40)
    assert ax.get_xscale() == "asinh"
    assert ax.get_xlabel() == f"time (s): linear up to {float(ds.time[-1]) / 40:.2g} s, logarithmic beyond"
    assert ax.get_ylabel() == "shaft deflection (mm)"
    assert "720 rpm" in ax.get_title() and "omega/p = 0.60" in ax.get_title()
    assert len(ax.get_lines()) == 2 + 1  # one per start + the reference
    np.testing.assert_allclose(ax.get_lines()[0].get_ydata(), ds.amplitude.values[0, 0] * 1e3)
    assert ball_angle_figure(ds).axes[0].get_ylabel() == "ball angle from unbalance (deg)"
    assert orbit_figure(ds).axes[0].get_xlabel() == "x (mm)"


def test_report_opens_with_the_findings_of_each_analysis(run, tmp_path):
    case, results, tables = run
    text = write_report(tmp_path / "o", case, results, _figures(results), tables).read_text()
    first_analysis = text.index('<h2 id="analysis-')
    assert text.index("<h2>Findings</h2>") < first_analysis < text.index("<h2>Model parameters</h2>")
    assert text.index("<h2>Case file</h2>") < text.index("<h2>Software</h2>")  # versions last
    boxes = text[:first_analysis]
    for name, rows in tables.items():
        for rpm in {round(r["speed_rpm"]) for r in rows}:
            here = [r for r in rows if round(r["speed_rpm"]) == rpm]
            for outcome in {r["outcome"] for r in here}:
                count = sum(r["outcome"] == outcome for r in here)
                assert f"{html.escape(outcome)} from {count} of {len(here)} starts" in boxes
    # the first figure of an analysis comes after the findings, inside its own section
    assert boxes.count("<img") == 0


def test_report_opens_with_the_verdict_of_the_machine(run, tmp_path):
    """The verdict block first (issue 29 item 1), one element per line with its status: the
    critical speed p = sqrt(c / (M1 + 2 m)) = sqrt(16740 / 1.06) = 125.67 rad/s = 1200 rpm, the
    720 rpm analysis below it (0.6 p: "no", with the fix), each analysis' outcomes from its rows
    with the measured ball angles to 0.1 degree, and "not computed" for what the case lacks."""
    case, results, tables = run
    text = write_report(tmp_path / "o", case, results, _figures(results), tables).read_text()
    start = text.index('<section id="verdict">')
    assert start < text.index("<h2>Findings</h2>")
    block = text[start:text.index("</section>", start)]
    lines = re.findall(r'<p class="verdict-line" data-verdict="([a-z-]+)" data-topic="([a-z -]+)">(.*?)</p>', block)
    found = {(topic, status) for status, topic, _ in lines}
    assert ("critical speeds", "info") in found and ("operating speed", "no") in found
    assert "undamped, balls locked: 1200 rpm forward (excited by unbalance)" in block
    assert "runs at 720 rpm (below) = 0.6 p" in block and "Fix: run above 1200 rpm, or soften the mounts" in block
    balance = [(status, html.unescape(body.split("</span>: ", 1)[1].split("<")[0])) for status, topic, body in lines
               if topic == "balances"]
    assert len(balance) == 2
    for rows, (status, sentence) in zip(tables.values(), balance):
        every = all(r["outcome"] == "balanced" for r in rows)
        assert status == ("yes" if every else "no")
        assert sentence.startswith("Balances" if every else "Does not balance")
        for r in rows:
            assert f"{r['outcome']} [" in sentence  # each regime named and explained
            assert f"from {sum(x['outcome'] == r['outcome'] for x in rows)} of {len(rows)}" in sentence
            if r["outcome"].startswith("side"):
                measured = ", ".join(f"{a:.1f}°" for a in r["final_ball_angles_deg"])
                assert f"measured {measured}" in sentence
    assert ("stable speeds", "info") in found and ("run-up", "info") in found
    assert "not computed; add a stability-chart analysis" in block


def test_findings_round_numbers_for_people():
    """Issue 29: "5.88e-09 mm" for zero, "3.39e+03 %" beside "33.9 x", "1.7847 deg"."""
    from rotorlab.report._findings import simulation_findings
    from rotorlab.report._machine import _simulate_findings

    rows = [{"speed_rpm": 2400.0, "speed_ratio": 2.0, "outcome": "balanced", "final_amplitude": 5.88e-12,
             "amplitude_ratio": 4e-9}]
    numbers = simulation_findings(None, rows).numbers
    assert numbers == ("final shaft deflection at 2400 rpm: < 1 nm (< 0.1 % against the unbalance alone)",)
    machine = [{"ic": 0, "outcome": "side (0°, 0°)", "amplitude": {"rotor": 33.9e-3},
                "reference_amplitude": {"rotor": 1e-3}, "final_ball_angles_deg": {"race 0": [1.7847, -16.0512]}}]
    found = _simulate_findings(None, machine)
    assert "vibration up to 33.9 × the unbalance response" in found.verdict and "e+03" not in found.verdict
    assert found.numbers == ("largest vibration / unbalance response 33.9 ×",
                             "start 0: side (0°, 0°), final ball angles race 0: 1.8°, -16.1°")


def test_basin_findings_state_the_fraction_in_words():
    import xarray as xr

    from rotorlab.report import presentation_of

    ds = xr.Dataset(coords={"horizon": [10.0, 20.0]}, attrs={"analysis": "basin"})
    rows = [{"regime": "balanced", "fraction": 1290 / 1296, "count": 1290, "n": 1296, "ci_low": None,
             "fraction_half": 1290 / 1296, "horizon_half_s": 10.0},
            {"regime": "non-synchronous", "fraction": 6 / 1296, "count": 6, "n": 1296, "ci_low": None,
             "fraction_half": 6 / 1296, "horizon_half_s": 10.0}]
    found = presentation_of("basin").findings(ds, rows)
    assert found.verdict == "balanced from 1290 of 1296 starts (99.5 %) after 20 s"
    assert found.numbers == ("non-synchronous: 6 of 1296 starts (0.463 %)",)


def test_working_point_findings_name_the_point_and_its_band():
    from rotorlab.analyses import run_analysis
    from rotorlab.io import load_case
    from rotorlab.report import presentation_of

    case = load_case("strautmanis-torus")
    ds = run_analysis(case.model, case.analysis("working-point"))
    found = presentation_of("working-point").findings(ds, summarize(ds))
    assert found.verdict == f"working point psi = {float(ds.psi):.6g} rad, alpha = {float(ds.alpha):.6g} rad"
    band = [float(v) for v in ds.psi_band.values]
    assert found.numbers[0].startswith(f"friction band psi {band[0]:.6g} to {band[1]:.6g} rad")


def test_undamped_unbalance_response_findings_say_the_peak_is_unbounded():
    from rotorlab.analyses import run_analysis
    from rotorlab.io import load_case
    from rotorlab.report import presentation_of

    case = load_case("friswell-rotor")  # undamped bearings: no finite peak
    analysis = next(a for a in case.analyses if a.type == "unbalance_response")
    ds = run_analysis(case.model, analysis)
    found = presentation_of("unbalance_response").findings(ds, summarize(ds))
    assert found.verdict.startswith("undamped rotor: the response is unbounded at the critical speeds")


def test_modes_findings_at_rest_name_no_whirl_direction():
    # An isotropic rotor at rest has no gyroscopic coupling: its modes come in x/y pairs of equal
    # frequency and have no whirl direction (issue 13: "calls modes forward/backward at standstill").
    from rotorlab.analyses import run_analysis
    from rotorlab.io import load_case
    from rotorlab.report import presentation_of

    case = load_case("friswell-rotor")
    rest, spinning = (run_analysis(case.model, case.analysis(n)) for n in ("modes-at-rest", "modes-at-3000-rpm"))
    found = presentation_of("modes").findings(rest, summarize(rest))
    assert found.numbers[0] == "at rest: no whirl direction; 3 pair(s) of equal frequency (x and y)"
    assert "forward" not in " ".join(found.numbers) and "backward" not in " ".join(found.numbers)
    found = presentation_of("modes").findings(spinning, summarize(spinning))
    assert found.numbers[0] in ("3 backward, 3 forward whirl", "3 forward, 3 backward whirl")


def test_stability_chart_findings_name_the_balanced_motion_once_and_each_parameter_value():
    # main+ and main- share their stable interval: it is said once; a side motion is not called
    # balanced; with a second parameter the verdict names its values and each has its own line.
    import xarray as xr

    from rotorlab.report import presentation_of

    def row(method, motion, a, b, **extra):
        return {"method": method, "motion": motion, "start_rpm": a, "stop_rpm": b, **extra}

    found = presentation_of("stability-chart").findings(xr.Dataset(attrs={"analysis": "stability-chart"}), [
        row("exact", "main+", 1373.7, 3763.7), row("exact", "main-", 1373.7, 3763.7),
        row("exact", "side 00", 188.2, 903.3), row("hamilton", "main+", 959.7, 3763.7)])
    assert found.verdict == "balanced motion stable (exact) at 1374 to 3764 rpm"
    assert found.numbers == ("by hamilton: 960 to 3764 rpm", "side motions (side 00) stable (exact) at 188 to 903 rpm")

    ds = xr.Dataset(coords={"support_damping": ("support_damping", [0.0, 5.0, 10.0], {"units": "N s/m"})},
                    attrs={"analysis": "stability-chart", "parameter": "support_damping"})
    rows = [row("exact", "side 00", 188.0, 922.0, support_damping=0.0),
            row("exact", "main+", 1449.0, 3764.0, support_damping=5.0),
            row("exact", "main-", 1449.0, 3764.0, support_damping=5.0),
            row("exact", "main+", 1355.0, 3764.0, support_damping=10.0)]
    found = presentation_of("stability-chart").findings(ds, rows)
    assert found.verdict == "balanced motion stable (exact) for support_damping = 5 to 10 N s/m (2 of 3 values)"
    assert found.numbers == ("support_damping = 0 N s/m: nowhere", "support_damping = 5 N s/m: 1449 to 3764 rpm",
                             "support_damping = 10 N s/m: 1355 to 3764 rpm")
