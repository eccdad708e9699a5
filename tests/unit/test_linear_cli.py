"""Command-line tests of the linear rotors: ``campbell``, ``modes``, and ``run``/``validate`` on
the built-in cases ``pico21`` and ``friswell-rotor``."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import CaseError, load_case, load_netcdf
from rotorlab.linear import RPM, campbell, critical_speeds, modal
from rotorlab.linear.cases import audit_pico21, friswell_rotor, pico21

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


def _json(result) -> dict:
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)  # stdout holds nothing but the document


# --------------------------------------------------------------------------- campbell


def test_campbell_json_friswell_matches_rotorlab_linear():
    doc = _json(invoke("campbell", "friswell-rotor", "--speeds-rpm", "0:4000:41", "--modes", "6",
                       "--json"))
    assert list(doc) == ["speed_rpm", "frequency_hz", "whirl", "critical_speeds_rpm",
                         "critical_speed_definition", "critical_speeds"]
    assert doc["speed_rpm"] == pytest.approx(np.linspace(0, 4000, 41).tolist())
    freq = np.array(doc["frequency_hz"])
    assert freq.shape == (41, 6)
    at_rest = np.sort(modal(friswell_rotor()).frequency)[:6]
    np.testing.assert_allclose(freq[0], at_rest, rtol=1e-10)
    assert freq[0].round(2).tolist() == [13.79, 13.79, 43.66, 43.66, 114.08, 114.08]
    ref = campbell(friswell_rotor(), RPM * np.linspace(0, 4000, 41), n_modes=6)
    np.testing.assert_allclose(np.sort(freq, axis=1), np.sort(ref.frequency.values, axis=1),
                               rtol=1e-12)
    assert {w for row in doc["whirl"] for w in row} <= {"F", "B", "M"}
    assert all(len(row) == 6 for row in doc["whirl"])
    # forward branches rise, backward ones fall
    for k in range(6):
        whirl = doc["whirl"][-1][k]
        assert (freq[-1, k] > freq[0, k]) == (whirl == "F")
    exact = critical_speeds(friswell_rotor(), max_speed=4000 * RPM).speed_rpm
    assert doc["critical_speeds_rpm"] == pytest.approx(exact.tolist(), rel=1e-8)
    assert doc["critical_speeds_rpm"] == pytest.approx([825.13, 829.87, 2487.76, 2756.09],
                                                       abs=0.01)


def test_campbell_defaults_from_the_case_and_plot(tmp_path):
    plot = tmp_path / "c.png"
    doc = _json(invoke("campbell", "pico21", "--json", "--plot", str(plot)))
    assert len(doc["speed_rpm"]) == 151 and doc["speed_rpm"][-1] == pytest.approx(15000.0)
    assert len(doc["frequency_hz"][0]) == 6
    assert doc["critical_speeds_rpm"] == pytest.approx([588.07, 588.26, 1940.36, 2090.41],
                                                       abs=0.01)
    ref = np.sort(modal(pico21()).frequency)[:6]
    np.testing.assert_allclose(doc["frequency_hz"][0], ref, rtol=1e-10)
    assert plot.read_bytes().startswith(b"\x89PNG")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.png"]


def test_campbell_table_and_harmonics():
    result = invoke("campbell", "friswell-rotor", "--speeds-rpm", "0:6000:61", "--modes", "4",
                    "--harmonic", "1", "--harmonic", "2")
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "friswell-rotor: critical speeds" in out and "natural frequencies (Hz)" in out
    assert "825.134" in out and "2x" in out and "backward" in out and "forward" in out


def test_campbell_harmonic_adds_a_line():
    # README: critical speeds "on the 1x (and H x) lines": --harmonic 2 adds the 2x line to the
    # case's 1x line. Both sets are checked against the exact critical speeds (no speed grid).
    base = _json(invoke("campbell", "friswell-rotor", "--json"))["critical_speeds_rpm"]
    both = _json(invoke("campbell", "friswell-rotor", "--harmonic", "2", "--json"))
    exact = critical_speeds(friswell_rotor(), harmonics=(1, 2), max_speed=4000 * RPM)
    one = exact.speed_rpm[exact.harmonic == 1]
    assert base == pytest.approx(sorted(one), rel=1e-6)
    assert len(both["critical_speeds_rpm"]) > len(base)
    assert sorted(both["critical_speeds_rpm"]) == pytest.approx(sorted(exact.speed_rpm), rel=1e-6)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["friswell-rotor", "--speeds-rpm", "5:1:0"],
         "--speeds-rpm = 5:1:0: STOP must be > START (5 rpm); N must be an integer >= 2"),
        (["friswell-rotor", "--speeds-rpm", "0:100"], "--speeds-rpm = 0:100: give START:STOP:N"),
        (["friswell-rotor", "--speeds-rpm", "0:fast:10"], "STOP = 'fast' is not a number"),
        (["friswell-rotor", "--speeds-rpm", "-5:100:3"], "START must be a finite number >= 0"),
        (["friswell-rotor", "--modes", "0"], "--modes = 0: must be an integer >= 1"),
        (["friswell-rotor", "--modes", "29"],
         "--modes = 29: must be an integer from 1 to 28 (the model's number of modes)"),
        (["friswell-rotor", "--harmonic", "0"], "--harmonic = 0: must be an integer >= 1"),
        (["friswell-rotor", "--plot", "PLOT.txt"], "unsupported file type '.txt'"),
        (["autobalancer", "--speeds-rpm", "0:1000:5"],
         "case autobalancer: its model is 'jeffcott_balls'; campbell needs a linear rotor model"),
        (["pico22"], "unknown case 'pico22'"),
    ],
)
def test_campbell_bad_input_exits_2_and_writes_nothing(tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    plot = [] if "--plot" in args else ["--plot", str(tmp_path / "never.png")]
    result = invoke("campbell", *args, *plot, "--json")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert message in result.stderr
    assert "Traceback" not in result.output
    assert list(tmp_path.iterdir()) == []


def test_campbell_case_without_campbell_analysis(tmp_path):
    case = tmp_path / "bare.toml"
    text = Path(__file__).parent.joinpath("test_linear_cases.py").read_text()
    fe = re.search(r'FE = """\n(.*?)"""', text, re.S)[1]
    case.write_text(fe.split("[[analysis]]")[0])
    result = invoke("campbell", str(case))
    assert result.exit_code == 2
    assert "case fe has no campbell analysis: give --speeds-rpm START:STOP:N" in result.stderr
    doc = _json(invoke("campbell", str(case), "--speeds-rpm", "0:3000:4", "--json"))
    assert len(doc["frequency_hz"][0]) == 6


# --------------------------------------------------------------------------- modes


def test_modes_json():
    doc = _json(invoke("modes", "friswell-rotor", "--speed-rpm", "0", "--json"))
    assert list(doc) == ["speed_rpm", "frequency_hz", "whirl", "damping_ratio", "log_decrement"]
    assert doc["speed_rpm"] == 0.0
    np.testing.assert_allclose(doc["frequency_hz"],  # the case's modes analysis keeps 6 modes
                               np.sort(modal(friswell_rotor()).frequency)[:6], rtol=1e-10)
    doc = _json(invoke("modes", "friswell-rotor", "--modes", "28", "--json"))
    np.testing.assert_allclose(doc["frequency_hz"], np.sort(modal(friswell_rotor()).frequency),
                               rtol=1e-10)
    doc = _json(invoke("modes", "pico21", "--speed-rpm", "14800", "--modes", "4", "--json"))
    ref = modal(pico21(), 14800 * RPM, n_modes=4)
    np.testing.assert_allclose(doc["frequency_hz"], ref.frequency, rtol=1e-10)
    assert doc["whirl"] == ["B", "F", "B", "F"]
    assert doc["damping_ratio"] == [0.0] * 4


def test_modes_default_speed_from_the_case_and_table():
    result = invoke("modes", "friswell-rotor")
    assert result.exit_code == 0, result.output
    assert "friswell-rotor: modes at 0 rpm" in result.stdout and "13.7921" in result.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["pico21", "--speed-rpm", "-1"], "--speed-rpm = -1: must be a finite number >= 0 (rpm)"),
        (["pico21", "--modes", "13"], "--modes = 13: must be an integer from 1 to 12"),
        (["autobalancer"], "modes needs a linear rotor model"),
    ],
)
def test_modes_bad_input(args, message):
    result = invoke("modes", *args, "--json")
    assert result.exit_code == 2 and result.stdout == ""
    assert message in result.stderr


def test_simulate_rejects_a_linear_case(tmp_path):
    result = invoke("simulate", "pico21", "--out", str(tmp_path / "x.nc"))
    assert result.exit_code == 2
    assert "simulate needs a rotor with balls" in result.stderr
    assert list(tmp_path.iterdir()) == []
    # a simulate analysis in a linear rotor's case file is refused when the case is read (it
    # was accepted, and 'rotorlab run' then failed with a traceback)
    path = tmp_path / "sim.toml"
    path.write_text(load_case("pico21").text.split("[[analysis]]")[0]
                    + '[[analysis]]\ntype = "simulate"\nspeed = "900 rpm"\nball_angle_grid = 2\nt_end = "1 s"\n')
    with pytest.raises(CaseError, match=r"analysis\[0\]\.type = \"simulate\": needs a jeffcott_balls or "
                                        r"machine model, not 'multibody'"):
        load_case(path)
    result = invoke("run", str(path), "--out", str(tmp_path / "out"))
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert "needs a jeffcott_balls or machine model, not 'multibody'" in result.stderr


# --------------------------------------------------------------------------- cases / validate


def test_cases_lists_the_linear_rotors():
    doc = _json(invoke("cases", "--json"))
    assert doc["cases"]["pico21"].startswith("Pico 21 centrifuge")
    assert "Example 5.9.1" in doc["cases"]["friswell-rotor"]


def test_validate_linear_cases():
    result = invoke("validate", "pico21")
    assert result.exit_code == 0, result.output
    assert "model: multibody: 3 rigid bodies (stator, armature, rotor), 12 DOFs" in result.stdout
    assert "analysis campbell (campbell): Campbell diagram, 6 modes, 151 speeds" in result.stdout
    doc = _json(invoke("validate", "friswell-rotor", "--json"))
    assert doc["ok"] is True and doc["n_dof"] == 28 and doc["critical_speed"] is None
    assert doc["model"]["bearings"][0]["kxx"] == 1e6
    assert [a["type"] for a in doc["analyses"]][:2] == ["campbell", "critical_speeds"]


# --------------------------------------------------------------------------- run


@pytest.fixture(scope="module")
def pico21_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "pico21"
    result = invoke("run", "pico21", "--out", str(out), "--json")
    return out, _json(result)


def test_run_pico21_writes_report_netcdf_and_figures(pico21_run):
    out, doc = pico21_run
    names = sorted(p.name for p in out.iterdir())
    analyses = ["data-audit", "campbell", "critical-speeds", "modes-at-rest",
                "modes-at-top-speed", "unbalance-response", "support-stiffness"]
    pngs = ["campbell_campbell.png", "modes-at-rest_shapes.png", "modes-at-top-speed_shapes.png",
            "unbalance-response_orbits.png"]
    assert names == sorted([".rotorlab-files", "report.html", *(f"{a}.nc" for a in analyses),
                            *pngs])
    assert doc["files"] == sorted(["report.html", *(f"{a}.nc" for a in analyses), *pngs])
    assert doc["analyses"]["campbell"]["type"] == "campbell"
    # the forward crossings (excited by unbalance on these isotropic supports) first, then the
    # backward ones, each group by speed (issue 29 item 3)
    rows = doc["analyses"]["campbell"]["rows"]
    assert [r["whirl"] for r in rows] == ["F", "F", "B", "B"]
    assert [r["excited_by_unbalance"] for r in rows] == [True, True, False, False]
    assert load_netcdf(out / "campbell.nc").frequency.shape == (151, 6)


def test_run_pico21_report_content(pico21_run):
    out, _ = pico21_run
    text = (out / "report.html").read_text(encoding="utf-8")
    # the Campbell diagram is interactive in the report (its PNG beside it, linked)
    assert '<figure class="interactive" data-stem="campbell_campbell">' in text
    assert '<a href="campbell_campbell.png">' in text and (out / "campbell_campbell.png").stat().st_size > 0
    assert "<h3>Critical speeds (damped crossings of the excitation lines)</h3>" in text
    assert "no: not excited by unbalance on isotropic supports" in text
    assert "<td class=\"num\">588.066</td>" in text
    assert "<h3>Data-audit findings</h3>" in text
    for finding in audit_pico21():
        assert f"<td>{finding.key}</td>" in text
    assert "<h3>Identified parameters</h3>" in text and "N*m/rad" in text
    assert "stator (45 mm), armature (32 mm), rotor (120 mm)" in text


def test_run_friswell_rotor(tmp_path):
    out = tmp_path / "o"
    result = invoke("run", "friswell-rotor", "--out", str(out))
    assert result.exit_code == 0, result.output
    assert "campbell: critical speeds" in result.stdout and "825.134" in result.stdout
    assert "disc 1" in result.stdout and f"Report: {out / 'report.html'}" in result.stdout
    text = (out / "report.html").read_text(encoding="utf-8")
    assert 'data-stem="campbell_campbell"' in text and "Data-audit" not in text
    assert "<h3>Modes</h3>" in text and "<td class=\"num\">13.7921</td>" in text
    ds = load_netcdf(out / "modes-at-rest.nc")
    assert ds.frequency.values.round(2).tolist() == [13.79, 13.79, 43.66, 43.66, 114.08, 114.08]


def test_run_bad_linear_case_writes_nothing(tmp_path):
    text = Path(__file__).parent.joinpath("test_linear_cases.py").read_text()
    fe = re.search(r'FE = """\n(.*?)"""', text, re.S)[1]
    case = tmp_path / "bad.toml"
    case.write_text(fe.replace('position = "0.5 m"', 'position = "1.6 m"'))
    out = tmp_path / "out"
    for command in (["run", str(case), "--out", str(out)], ["validate", str(case)],
                    ["campbell", str(case), "--speeds-rpm", "0:100:3"]):
        result = invoke(*command)
        assert result.exit_code == 2
        assert result.stderr.startswith("error: invalid case")
        assert 'model.discs[0].position = "1.6 m": must be on the shaft' in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]
