"""Wiring of the steady-motion analyses (issue 4): case-file specs, built-in cases, CLI, report.

The numbers are those of :mod:`rotorlab.steady` (validated in tests/validation/test_steady_*);
here the point is that they arrive intact through case files, the command line and the report.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import run_case
from rotorlab.analyses._steady import steady_rows
from rotorlab.cli import app
from rotorlab.io import CaseError, dump_case, load_case, parse_case
from rotorlab.steady import SEED_NOTES, steady_case

runner = CliRunner()
RPM = 60.0 / (2.0 * math.pi)
SEEDS = {"zhakash-k2": "002", "filimonikhin-n2": "003"}


def invoke(*args: str):
    return runner.invoke(app, list(args))


def _rpm(case: str, ratio: float) -> str:
    return repr(ratio * steady_case(case).critical_speed() * RPM)


def _small(name: str, analyses: str) -> str:
    """Return the built-in case ``name`` with its analyses replaced by ``analyses``."""
    text = load_case(name).text
    head = text[: text.index("[[analysis]]")]
    return head + analyses


SMALL_ANALYSES = """
[[analysis]]
type = "steady"
name = "at-2p"
regime = "enough"
speed_ratio = 2.0

[[analysis]]
type = "stability-chart"
name = "chart"
speed_ratios = [0.5, 3.0, 6]

[[analysis]]
type = "stability-chart"
name = "chart-e"
speed_ratios = [0.5, 3.0, 4]
param = "eccentricity"
values = ["0.5 mm", "2.5 mm", 3]

[[analysis]]
type = "verify"
name = "verify"
speed_ratios = [0.6, 2.0]
ball_angle_points = 2
t_end = ["20 s", "10 s"]

[[analysis]]
type = "run-up"
name = "run-up"
t_end = "3 s"
n_save = 300
[analysis.speed]
profile = "ramp"
start = "300 rpm"
stop = "2500 rpm"
duration = "0.2 s"
"""


# ------------------------------------------------------------------------------ case files


@pytest.mark.parametrize("name", ["zhakash-k2", "filimonikhin-n2"])
def test_case_file_is_the_steady_case(name):
    case, ref = load_case(name), steady_case(name)
    m = case.model
    rotor = ref.model(ref.regimes[0].name).rotor
    assert m.disc_mass == pytest.approx(rotor.disc_mass, rel=1e-12)
    assert m.stiffness == pytest.approx(rotor.stiffness, rel=1e-12)
    assert m.eccentricity == pytest.approx(rotor.eccentricity, rel=1e-12)
    assert m.damping == pytest.approx(rotor.damping, rel=1e-12)
    assert m.n_balls == len(ref.balls)
    for got, want in zip(m.balls, ref.balls):
        for key in ("mass", "radius", "inertia", "damping", "friction"):
            assert getattr(got, key) == pytest.approx(getattr(want, key), rel=1e-12, abs=0.0), key
    assert m.critical_speed() == pytest.approx(ref.critical_speed(), rel=1e-12)
    # every regime is set by the analyses labelled with it, with the SteadyCase numbers
    for regime in ref.regimes:
        labelled = [a for a in case.analyses if a.regime == regime.name]
        assert labelled, regime.name
        for a in labelled:
            e = a.eccentricity if a.eccentricity is not None else m.eccentricity
            d = a.support_damping if a.support_damping is not None else m.damping
            assert e == pytest.approx(regime.eccentricity, rel=1e-12), (regime.name, a.name)
            assert d == pytest.approx(regime.support_damping, rel=1e-12, abs=1e-15), (regime.name, a.name)
    verify = case.analysis("verify")
    assert verify.speed_ratios == pytest.approx(ref.speed_ratios)
    assert case.analysis("chart").speed_ratios == pytest.approx(ref.chart_speed_ratios)
    p = ref.critical_speed()
    for a in (case.analysis("run-up-slow"), case.analysis("run-up-fast")):
        assert a.speed.start == pytest.approx(0.3 * p, rel=1e-7)
        assert a.speed.stop == pytest.approx(2.5 * p, rel=1e-7)


@pytest.mark.parametrize("name", ["zhakash-k2", "filimonikhin-n2"])
def test_case_file_comments_cite_every_seed_note(name):
    text = load_case(name).text
    notes = [n for n in SEED_NOTES if n.seed == SEEDS[name]]
    assert notes
    flat = " ".join(line.lstrip("# ").strip() for line in text.splitlines())
    for n in notes:
        assert f"- {n.where} [{n.kind}]" in flat, n.where
        assert n.test.split("::")[-1] in flat.replace(" ", ""), n.test


@pytest.mark.parametrize("name", ["zhakash-k2", "filimonikhin-n2"])
def test_case_file_round_trips_and_validates(name):
    case = load_case(name)
    again = parse_case(dump_case(case), origin="again.toml")
    assert again.model_dump_si() == case.model_dump_si()
    result = invoke("validate", name)
    assert result.exit_code == 0, result.output
    assert f"OK: {name}" in result.stdout


# ------------------------------------------------------------------------------ steady


def test_steady_json_supercritical_main_motions():
    result = invoke("steady", "zhakash-k2", "--speed-rpm", _rpm("zhakash-k2", 2.0), "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    for key in ("case", "source", "regime", "overrides", "spin_speed", "speed_rpm", "critical_speed",
                "speed_ratio", "imbalance", "capacity", "motions", "disagreements", "stable"):  # fmt: skip
        assert key in doc, key
    assert doc["case"] == "zhakash-k2" and doc["regime"] is None
    assert doc["speed_ratio"] == pytest.approx(2.0, rel=1e-12)
    assert doc["stable"] == {"exact": ["main+", "main-"], "hamilton": ["main+", "main-"],
                             "averaged": ["main+", "main-"]}  # fmt: skip
    assert doc["disagreements"] == []
    gamma = math.degrees(math.acos(1.2 / 2.0))  # eta = 1.2, seed 002 (16)
    mains = {m["label"]: m for m in doc["motions"] if m["kind"] == "main"}
    for label, sign in (("main+", 1.0), ("main-", -1.0)):
        m = mains[label]
        assert m["verdicts"] == {"hamilton": "stable", "averaged": "stable", "exact": "stable"}
        assert m["ball_angles_deg"] == pytest.approx([sign * (180.0 - gamma), -sign * (180.0 - gamma)], abs=1e-6)
        assert m["ball_angles"] == pytest.approx(np.radians(m["ball_angles_deg"]), abs=1e-12)
        assert m["amplitude"] == pytest.approx(0.0, abs=1e-12)
        assert m["growth_rate"] < 0


def test_steady_json_subcritical_side_motion():
    result = invoke("steady", "zhakash-k2", "--speed-ratio", "0.6", "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["stable"]["exact"] == ["side 00"]
    side = next(m for m in doc["motions"] if m["label"] == "side 00")
    # both balls on the line of the deflection (turned by the support damping, seed 003 (13))
    a1, a2 = side["ball_angles_deg"]
    assert a1 == pytest.approx(a2, abs=1e-9) and a1 == pytest.approx(side["phase_deg"], abs=1e-9)
    assert -10.0 < a1 < 0.0 and side["phase_deg"] == pytest.approx(math.degrees(side["phase"]))
    assert side["amplitude"] > 0
    assert side["verdicts"]["exact"] == side["verdicts"]["hamilton"] == "stable"


def test_steady_window_reports_the_disagreements():
    result = invoke("steady", "zhakash-k2", "--speed-ratio", "1.2", "--json")
    doc = json.loads(result.stdout)
    assert doc["stable"]["exact"] == [] and doc["stable"]["averaged"] == ["main+", "main-"]
    assert {(d["label"], d["method"]) for d in doc["disagreements"]} >= {("main+", "hamilton"), ("main+", "averaged")}
    text = invoke("steady", "zhakash-k2", "--speed-ratio", "1.2")
    assert text.exit_code == 0
    assert "Exactly stable: none" in text.stdout and "disagreement: main+ at omega/p = 1.2" in text.stdout


def test_steady_regimes_of_seed_003():
    undamped = json.loads(invoke("steady", "filimonikhin-n2", "--speed-ratio", "2", "--regime", "undamped",
                                 "--json").stdout)  # fmt: skip
    assert undamped["overrides"] == {"support_damping": 0.0}
    assert undamped["stable"]["exact"] == [] and undamped["stable"]["hamilton"] == ["main+", "main-"]
    dominant = json.loads(invoke("steady", "filimonikhin-n2", "--regime", "dominant", "--json").stdout)
    assert dominant["overrides"]["eccentricity"] == pytest.approx(0.2e-3)
    assert dominant["speed_ratio"] == pytest.approx(0.9)  # the first steady analysis of that regime
    assert not any(m["exists"] for m in dominant["motions"] if m["kind"] == "main")
    assert dominant["stable"]["exact"] == []


def test_steady_default_speed_from_the_case_and_any_ball_case():
    doc = json.loads(invoke("steady", "zhakash-k2", "--json").stdout)
    assert doc["speed_ratio"] == pytest.approx(0.6)
    result = invoke("steady", "autobalancer", "--speed-rpm", "2400", "--json")
    assert result.exit_code == 0
    assert json.loads(result.stdout)["stable"]["exact"] == ["main+", "main-"]


@pytest.mark.parametrize("args, words", [
    (["--speed-rpm", "-5"], ["--speed-rpm = -5", "> 0"]),
    (["--speed-rpm", "900", "--speed-ratio", "2"], ["exclude each other"]),
    (["--regime", "nope"], ["--regime nope", "regimes: enough, short"]),
])  # fmt: skip
def test_steady_bad_options(args, words):
    result = invoke("steady", "zhakash-k2", *args)
    assert result.exit_code == 2
    assert result.stdout == ""
    for w in words:
        assert w in result.stderr


@pytest.mark.parametrize("command, case, args", [
    ("steady", "strautmanis-torus", ["--speed-rpm", "900"]),
    ("steady", "pico21", ["--speed-rpm", "900"]),
    ("stability-chart", "krasnov-crusher", ["--speeds-rpm", "300:900:3"]),
])  # fmt: skip
def test_steady_commands_need_a_rotor_with_balls(command, case, args):
    result = invoke(command, case, *args)
    assert result.exit_code == 2 and result.stdout == ""
    # the model's own check (steady_issues) says what runs them, a machine included, and what the case has
    assert f"case {case}: {command} needs a rotor with balls (a jeffcott_balls model with at least one ball, or a " \
           "machine model; this case has a model '" in result.stderr


def test_steady_needs_a_speed_when_the_case_has_no_steady_analysis():
    result = invoke("steady", "autobalancer")
    assert result.exit_code == 2 and "give --speed-rpm" in result.stderr


# ------------------------------------------------------------------------------ stability chart


def test_stability_chart_json_intervals():
    result = invoke("stability-chart", "zhakash-k2", "--speeds-rpm", "300:3000:28", "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert {"case", "param", "values", "speeds_rpm", "critical_speed", "intervals"} <= set(doc)
    assert doc["param"] is None and doc["values"] is None
    assert doc["speeds_rpm"] == pytest.approx(np.linspace(300, 3000, 28))
    assert doc["critical_speed"] == pytest.approx(steady_case("zhakash-k2").critical_speed())
    exact = {(r["motion"], r["start_rpm"] > 0) for r in doc["intervals"]["exact"]}
    assert ("main+", True) in exact and ("side 00", True) in exact
    main = next(r for r in doc["intervals"]["exact"] if r["motion"] == "main+")
    # stable from the end of the window omega* = 1.457 p on (seed 002 (20)-(22) contradicted)
    assert 1.4 < main["start_ratio"] < 1.6 and main["stop_rpm"] == pytest.approx(3000.0)
    averaged = next(r for r in doc["intervals"]["averaged"] if r["motion"] == "main+")
    assert 1.0 < averaged["start_ratio"] < 1.1


def test_stability_chart_with_parameter_plot_and_netcdf(tmp_path):
    png, nc = tmp_path / "chart.png", tmp_path / "chart.nc"
    result = invoke("stability-chart", "filimonikhin-n2", "--speed-ratios", "0.5:3:6", "--param",
                    "eccentricity=0.5mm:2.5mm:3", "--plot", str(png), "--out", str(nc), "--json")  # fmt: skip
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["param"] == "eccentricity" and doc["param_units"] == "m"
    assert doc["values"] == pytest.approx([0.5e-3, 1.5e-3, 2.5e-3])
    assert png.stat().st_size > 1000 and nc.is_file()
    shorts = [r for r in doc["intervals"]["exact"] if r["motion"] == "side 11"]
    assert shorts and all(r["eccentricity"] > 1.6e-3 for r in shorts)  # capacity short above 1.667 mm
    table = invoke("stability-chart", "zhakash-k2", "--speeds-rpm", "500:2500:5", "--param", "support_damping=0:40:3")
    assert table.exit_code == 0 and "exact eigenvalues" in table.stdout, table.output


@pytest.mark.parametrize("args, words", [
    (["--speeds-rpm", "3000:500:5"], ["--speeds-rpm = 3000:500:5", "STOP must be > START"]),
    (["--speeds-rpm", "500:3000"], ["START:STOP:N"]),
    (["--speeds-rpm", "500:3000:5", "--speed-ratios", "1:2:3"], ["exclude each other"]),
    (["--speeds-rpm", "500:3000:5", "--param", "mass=1:2:3"], ["--param = mass=1:2:3", "ball_mass"]),
    (["--speeds-rpm", "500:3000:5", "--param", "eccentricity=1kg:2kg:3"], ["--param", "length"]),
])  # fmt: skip
def test_stability_chart_bad_options_write_nothing(tmp_path, args, words):
    png = tmp_path / "c.png"
    result = invoke("stability-chart", "zhakash-k2", *args, "--plot", str(png))
    assert result.exit_code == 2, result.output
    assert not png.exists() and result.stdout == ""
    for w in words:
        assert w in result.stderr


# ------------------------------------------------------------------------------ schema errors


BAD = [
    ("speed_ratios = [0.5, 3.0, 6]", "speed_ratios = [0.5, 3.0]",
     ["analysis[1].speed_ratios = [0.5, 3.0]", "must be [start, stop, count]"]),
    ('values = ["0.5 mm", "2.5 mm", 3]', 'values = ["0.5 kg", "2.5 mm", 3]',
     ['analysis[2].values = ["0.5 kg", "2.5 mm", 3]', "start: wrong dimension"]),
    ('param = "eccentricity"\n', 'param = "eccentricty"\n',
     ['analysis[2].param = "eccentricty"', "did you mean 'eccentricity'"]),
    ('t_end = ["20 s", "10 s"]', 't_end = ["20 s", "10 s", "5 s"]',
     ["analysis[3].t_end", "3 time(s) for 2 speed(s)"]),
    ("ball_angle_points = 2", "ball_angle_points = 2\ninitial_ball_angles = [[0, 1]]",
     ["analysis[3]", "ball_angle_points and initial_ball_angles exclude each other"]),
    ('[analysis.speed]\nprofile = "ramp"', '[analysis.speed]\nprofile = "rampe"',
     ['analysis[4].speed.profile = "rampe"', "unknown speed profile"]),
    ('speed_ratio = 2.0\n', 'speed_ratio = 2.0\nspeed = "100 rpm"\n',
     ["analysis[0]", "speed_ratio and speed exclude each other"]),
    ('regime = "enough"\n', 'regime = "enough"\nsupport_damping = "-1 N*s/m"\n',
     ['analysis[0].support_damping = "-1 N*s/m"', "must be >= 0 (N*s/m)"]),
]  # fmt: skip


@pytest.mark.parametrize("old, new, words", BAD)
def test_schema_errors_name_the_key_and_write_nothing(tmp_path, old, new, words):
    text = _small("zhakash-k2", SMALL_ANALYSES)
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(CaseError) as err:
        load_case(path)
    for w in words:
        assert w in str(err.value), str(err.value)
    out = tmp_path / "out"
    result = invoke("run", str(path), "--out", str(out))
    assert result.exit_code == 2 and not out.exists()
    assert words[0] in result.stderr


def test_analyses_need_a_model_with_balls(tmp_path):
    text = _small("zhakash-k2", SMALL_ANALYSES)
    head, balls = text.split("[[model.balls]]", 1)
    path = tmp_path / "noballs.toml"
    path.write_text(head + "\n" + balls[balls.index("[[analysis]]"):])
    with pytest.raises(CaseError) as err:
        load_case(path)
    assert ('analysis[0].type = "steady": needs a rotor with balls (a jeffcott_balls model with at least one '
            'ball, or a machine model') in str(err.value)


# ------------------------------------------------------------------------------ run and report


@pytest.fixture(scope="module")
def small_runs():
    out = {}
    for name in ("zhakash-k2", "filimonikhin-n2"):
        case = parse_case(_small(name, SMALL_ANALYSES), origin=f"{name}-small.toml")
        out[name] = (case, run_case(case))
    return out


@pytest.mark.parametrize("name", ["zhakash-k2", "filimonikhin-n2"])
def test_run_case_results(small_runs, name):
    case, results = small_runs[name]
    assert list(results) == ["at-2p", "chart", "chart-e", "verify", "run-up"]
    assert results["at-2p"].attrs["analysis"] == "steady" and results["at-2p"].attrs["regime"] == "enough"
    verify = results["verify"]
    assert verify.sizes == {"speed": 2, "ic": 4, "ball": 2, "motion": 6, "outcome": 9}
    assert verify.t_end.values.tolist() == [20.0, 10.0]
    assert bool(verify.agrees_exact.all())
    rows = steady_rows(verify)
    assert rows[0]["fractions"] == {"side 00": 1.0}
    assert rows[1]["stable"]["exact"] == ["main+", "main-"]
    run_up = steady_rows(results["run-up"])[0]
    assert run_up["max_amplitude"] > 0 and run_up["max_amplitude_without"] > 0
    assert steady_rows(results["chart-e"])  # stable intervals found


@pytest.mark.parametrize("name", ["zhakash-k2", "filimonikhin-n2"])
def test_cli_run_writes_the_steady_report(tmp_path, name):
    path = tmp_path / f"{name}-small.toml"
    path.write_text(_small(name, SMALL_ANALYSES))
    out = tmp_path / "out"
    result = invoke("run", str(path), "--out", str(out), "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert {"chart_chart.png", "chart-e_chart.png", "verify_fractions.png", "run-up_run-up.png",
            "at-2p.nc", "report.html"} <= set(doc["files"])  # fmt: skip
    assert doc["analyses"]["at-2p"]["type"] == "steady"
    assert [r["motion"] for r in doc["analyses"]["at-2p"]["rows"]][:2] == ["main+", "main-"]
    page = (out / "report.html").read_text()
    for words in ("ball angles (deg)", "deflection (mm)", "seed 003 (least H~*)", "seed 002 (averaged)",
                  "The three methods agree", "Speed intervals", "agrees: exact", "peak with balls (mm)",
                  "peak without (mm)", "Seed papers: typos and contradicted conclusions",
                  f"Seed {SEEDS[name]}", "test_"):  # fmt: skip
        assert words in page, words
    assert page.count("<img") == 4


def test_stability_chart_names_the_charts_of_other_regimes():
    # issue 13: the case has three stability charts, none for regime "short"
    result = invoke("stability-chart", "filimonikhin-n2", "--regime", "short")
    assert result.exit_code == 2
    assert ("case filimonikhin-n2 has no stability-chart analysis for regime short; it has "
            "chart (regime enough), chart-support-damping (the model's parameters), "
            "chart-eccentricity (the model's parameters)") in result.stderr
