"""Command-line tests (typer's CliRunner), plus the start-up budget of ``rotorlab --version``."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import rotorlab
from rotorlab.cli import app

runner = CliRunner()

SMALL = """
name = "small"
description = "quick two-speed check"
[model]
type = "jeffcott_balls"
disc_mass = "1 kg"
eccentricity = "1.5 mm"
stiffness = "16.74 kN/m"
damping = "13.32 N*s/m"
[model.speed]
profile = "constant"
speed = "2400 rpm"
[[model.balls]]
mass = "30 g"
radius = "50 mm"
damping = "2e-3 N*m*s"
count = 2
[[analysis]]
type = "simulate"
name = "below"
speed_ratio = 0.6
initial_ball_angles = [["0 deg", "90 deg"], ["45 deg", "200 deg"]]
t_end = "8 s"
n_save = 40
[[analysis]]
type = "simulate"
name = "above"
speed_ratio = 2.0
initial_ball_angles = [["120 deg", "240 deg"]]
t_end = "1 s"
n_save = 40
"""

# (file name, text replacement applied to SMALL, words the message must contain)
BAD_CASES = [
    ("unknown_key.toml", ("n_save = 40\n", "n_savee = 40\n"),
     ["analysis[0].n_savee = 40", "unknown key 'n_savee'", "did you mean 'n_save'?"]),
    ("negative_mass.toml", ('mass = "30 g"', 'mass = "-30 g"'),
     ['model.balls[0].mass = "-30 g"', "must be > 0 (kg)"]),
    ("nan.toml", ('eccentricity = "1.5 mm"', "eccentricity = nan"),
     ["model.eccentricity = nan", "finite"]),
    ("unknown_unit.toml", ('stiffness = "16.74 kN/m"', 'stiffness = "16.74 kN/furlong"'),
     ['model.stiffness = "16.74 kN/furlong"', "unit"]),
    ("unknown_model.toml", ('type = "jeffcott_balls"', 'type = "jefcott_balls"'),
     ['model.type = "jefcott_balls"', "unknown model", "jeffcott_balls"]),
    ("syntax.toml", ("n_save = 40\n", "n_save = = 40\n"), ["line", "column"]),
]  # fmt: skip


def invoke(*args: str):
    return runner.invoke(app, list(args))


@pytest.fixture()
def small(tmp_path: Path) -> Path:
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    return path


def _bad(tmp_path: Path, name: str, replace: tuple[str, str]) -> Path:
    assert replace[0] in SMALL
    path = tmp_path / name
    path.write_text(SMALL.replace(replace[0], replace[1], 1))
    return path


# ------------------------------------------------------------------------------ version


def test_version_option():
    result = invoke("--version")
    assert result.exit_code == 0
    assert result.stdout == f"rotorlab {rotorlab.__version__}\n"


def _timed(cmd: list[str]) -> tuple[float, subprocess.CompletedProcess]:
    """CPU seconds (user + system) of the child process: unlike wall time, not inflated when the
    suite's other workers share the cores."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), done


def test_version_under_one_second_in_a_fresh_process():
    commands = [[sys.executable, "-m", "rotorlab.cli", "--version"]]
    exe = shutil.which("rotorlab")
    if exe is not None:
        commands.append([exe, "--version"])
    for cmd in commands:
        _timed(cmd)  # warm the file-system cache
        seconds, done = min((_timed(cmd) for _ in range(3)), key=lambda x: x[0])
        assert done.returncode == 0, done.stderr
        assert done.stdout.strip() == f"rotorlab {rotorlab.__version__}"
        assert seconds < 1.0, f"{cmd}: {seconds:.2f} CPU-s"


def test_cli_import_is_light():
    code = (
        "import sys, rotorlab.cli; "
        "print(sorted(m for m in ('numpy', 'numba', 'xarray', 'matplotlib', 'pydantic', 'pint', 'scipy')"
        " if m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_no_arguments_shows_help():
    result = invoke()
    assert "Usage: rotorlab" in result.output
    for command in ("run", "simulate", "validate", "cases"):
        assert command in result.output


def test_quiet_and_verbose_exclude_each_other():
    result = invoke("-q", "-v", "cases")
    assert result.exit_code == 2
    assert "-q/--quiet and -v/--verbose exclude each other" in result.stderr


# ------------------------------------------------------------------------------ cases / validate


def test_cases():
    result = invoke("cases")
    assert result.exit_code == 0
    assert "autobalancer" in result.stdout and "two-ball automatic balancer" in result.stdout
    result = invoke("cases", "--json")
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert doc["cases"]["autobalancer"].startswith("Jeffcott rotor with a two-ball")


def test_validate_builtin():
    result = invoke("validate", "autobalancer")
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert out.startswith("OK: autobalancer (builtin:autobalancer)")
    assert "2 ball(s)" in out and "125.668 rad/s = 1200.04 rpm = 20.0007 Hz" in out
    assert "analysis subcritical (simulate): 6 start configuration(s), 20 s at" in out
    assert "720.025 rpm" in out and "(ω/p = 0.6)" in out


def test_validate_json(small):
    result = invoke("validate", str(small), "--json")
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert doc["ok"] is True and doc["case"] == "small" and doc["n_balls"] == 2
    assert doc["critical_speed"] == pytest.approx(125.6677, rel=1e-5)
    assert doc["model"]["stiffness"] == 16740.0
    assert [a["name"] for a in doc["analyses"]] == ["below", "above"]
    assert doc["analyses"][1]["speed_rpm"] == pytest.approx(2400.08, rel=1e-5)
    assert doc["analyses"][0]["configurations"] == 2 and doc["analyses"][0]["t_end"] == 8.0


@pytest.mark.parametrize(("name", "replace", "words"), BAD_CASES, ids=[c[0] for c in BAD_CASES])
def test_validate_bad_case(tmp_path, name, replace, words):
    path = _bad(tmp_path, name, replace)
    result = invoke("validate", str(path))
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr.startswith("error: ")
    for word in words:
        assert word in result.stderr
    assert "Traceback" not in result.output


def test_validate_bad_case_json(tmp_path):
    path = _bad(tmp_path, *BAD_CASES[1][:2])
    result = invoke("validate", str(path), "--json")
    assert result.exit_code == 2
    doc = json.loads(result.stdout)
    assert doc["ok"] is False
    assert doc["problems"] == ['model.balls[0].mass = "-30 g": must be > 0 (kg), got -0.03 kg']


@pytest.mark.parametrize("command", ["validate", "run", "simulate"])
def test_unknown_case(command, tmp_path):
    args = [command, "autobalanser"] + (["--out", str(tmp_path / "o")] if command == "run" else [])
    result = invoke(*args)
    assert result.exit_code == 2
    assert "unknown case 'autobalanser'" in result.stderr
    assert "did you mean 'autobalancer'?" in result.stderr
    assert not (tmp_path / "o").exists()


# ------------------------------------------------------------------------------ run


@pytest.mark.parametrize(("name", "replace", "words"), BAD_CASES, ids=[c[0] for c in BAD_CASES])
def test_run_bad_case_writes_nothing(tmp_path, name, replace, words):
    path = _bad(tmp_path, name, replace)
    out = tmp_path / "out"
    result = invoke("run", str(path), "--out", str(out))
    assert result.exit_code == 2
    assert words[0] in result.stderr
    assert "Traceback" not in result.output
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


def test_run_writes_report_results_and_figures(small, tmp_path):
    out = tmp_path / "out"
    result = invoke("run", str(small), "--out", str(out))
    assert result.exit_code == 0, result.output
    assert "Outcomes" in result.stdout and f"Report: {out / 'report.html'}" in result.stdout
    assert "below" in result.stdout and "side (0°, 0°) ×2" in result.stdout
    assert "balanced ×1" in result.stdout
    # the sanity warning before the run (the run goes on), the verdict first on stdout (issue 29)
    assert "warning (below-critical): analysis below is 720 rpm" in result.stderr
    assert "\nVerdict\n" in result.stdout and result.stdout.index("Verdict") < result.stdout.index("Outcomes")
    verdict = result.stdout[result.stdout.index("Verdict"):result.stdout.index("Outcomes")]
    assert "  NO           operating speed: p = 1200 rpm" in verdict
    assert max(len(line) for line in verdict.splitlines()) <= 100
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted([".rotorlab-files", "report.html", "below.nc", "above.nc"] + [
        f"{a}_{k}.png" for a in ("below", "above") for k in ("amplitude", "ball_angles", "final_positions")
    ])  # fmt: skip
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "small.toml"]


def test_run_json(small, tmp_path):
    out = tmp_path / "out"
    result = invoke("run", str(small), "--out", str(out), "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)  # stdout is nothing but the JSON document
    assert set(doc) == {"case", "source", "out_dir", "report", "files", "seconds", "analyses", "warnings", "verdict"}
    assert [w["check"] for w in doc["warnings"]] == ["below-critical"]
    assert [(v["topic"], v["status"]) for v in doc["verdict"][:2]] == [("critical speeds", "info"),
                                                                      ("operating speed", "no")]
    assert doc["case"] == "small" and doc["source"] == str(small.resolve())
    assert doc["report"] == str(out / "report.html") and "below.nc" in doc["files"]
    assert set(doc["analyses"]) == {"below", "above"}
    below = doc["analyses"]["below"]
    assert below["type"] == "simulate" and len(below["rows"]) == 2
    row = below["rows"][0]
    assert row["outcome"] == "side (0°, 0°)"
    assert row["speed_ratio"] == pytest.approx(0.6)
    assert row["initial_ball_angles_deg"] == [0.0, 90.0]
    assert row["final_amplitude"] == pytest.approx(2.97 * row["reference_amplitude"], rel=0.01)
    balances = [v["sentence"] for v in doc["verdict"] if v["topic"] == "balances"]
    measured = ", ".join(f"{a:.1f}°" for a in row["final_ball_angles_deg"])
    assert balances[0].startswith("Does not balance at 720 rpm (below) within 8 s: side (0°, 0°) [the balls settled "
                                  "on the line through the unbalance, all on the unbalance's side, adding to it; "
                                  f"nominal angles, measured {measured}] from 2 of 2 (100 %) starts")
    above = doc["analyses"]["above"]["rows"][0]
    assert above["outcome"] == "balanced" and sorted(above["final_ball_angles_deg"]) == [-120.0, 120.0]


def test_run_default_case_into_default_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = invoke("-q", "run")
    assert result.exit_code == 0, result.output
    # -q hides progress and messages, not results (issue 13)
    assert "Running autobalancer" not in result.stdout and result.stderr == ""
    assert "balanced" in result.stdout and "Report:" in result.stdout
    out = tmp_path / "rotorlab-out"
    assert (out / "report.html").is_file()
    assert (out / "subcritical.nc").is_file() and (out / "supercritical.nc").is_file()


def test_run_out_is_a_file(small, tmp_path):
    target = tmp_path / "taken"
    target.write_text("x")
    result = invoke("run", str(small), "--out", str(target))
    assert result.exit_code == 2
    assert f"--out {target}: exists and is not a folder" in result.stderr
    assert target.read_text() == "x"


def test_run_case_without_analyses(tmp_path):
    path = tmp_path / "none.toml"
    path.write_text(SMALL.split("[[analysis]]")[0])
    result = invoke("run", str(path), "--out", str(tmp_path / "o"))
    assert result.exit_code == 2
    assert "lists no [[analysis]] to run" in result.stderr
    assert not (tmp_path / "o").exists()


def test_internal_error_exit_1(small, tmp_path, monkeypatch):
    import rotorlab.analyses

    def broken(*args, **kwargs):
        raise RuntimeError("solver exploded")

    monkeypatch.setattr(rotorlab.analyses, "run_case", broken)
    result = invoke("run", str(small), "--out", str(tmp_path / "o"))
    assert result.exit_code == 1
    assert "internal error: RuntimeError: solver exploded" in result.stderr
    assert "Traceback" not in result.stderr and "run with -v" in result.stderr
    assert not (tmp_path / "o").exists()
    result = invoke("-v", "run", str(small), "--out", str(tmp_path / "o"))
    assert result.exit_code == 1
    assert "Traceback" in result.stderr and "solver exploded" in result.stderr


# ------------------------------------------------------------------------------ simulate


def test_simulate_table(small):
    result = invoke("simulate", str(small))
    assert result.exit_code == 0, result.output
    assert "small: below" in result.stdout
    assert result.stdout.count("side (0°, 0°)") == 2


def test_simulate_json_two_speeds_and_netcdf(small, tmp_path):
    from rotorlab.io import load_netcdf

    out = tmp_path / "s.nc"
    result = invoke("simulate", str(small), "--analysis", "above", "--speed-rpm", "720",
                    "--speed-rpm", "2400", "--t-end", "1.5", "--out", str(out), "--json")  # fmt: skip
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert set(doc) == {"case", "source", "analysis", "t_end", "out", "rows"}
    assert doc["analysis"] == "above" and doc["t_end"] == 1.5 and doc["out"] == str(out)
    assert [r["speed_rpm"] for r in doc["rows"]] == pytest.approx([720.0, 2400.0])
    assert doc["rows"][1]["outcome"] == "balanced"
    ds = load_netcdf(out)
    assert dict(ds.sizes) == {"speed": 2, "ic": 1, "time": 40, "ball": 2}
    assert ds.time.values[-1] == 1.5
    assert ds.attrs["name"] == "above" and ds.attrs["case"] == "small"


def test_simulate_speed_ratio(small):
    result = invoke("simulate", str(small), "--speed-ratio", "2", "--t-end", "0.5", "--json")
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)["rows"]
    assert len(rows) == 2 and rows[0]["speed_ratio"] == pytest.approx(2.0)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--speed-rpm", "-3"], "--speed-rpm = -3: must be a finite number > 0 (rpm)"),
        (["--speed-rpm", "inf"], "--speed-rpm = inf: must be a finite number > 0 (rpm)"),
        (["--speed-ratio", "0"], "--speed-ratio = 0: must be a finite number > 0"),
        (["--speed-rpm", "100", "--speed-ratio", "2"], "--speed-rpm and --speed-ratio exclude each other"),
        (["--t-end", "nan"], "--t-end = nan: must be a finite number > 0 (s)"),
        (["--analysis", "sideways"], "--analysis = sideways: no simulate analysis of that name "
                                      "(simulate analyses: below, above)"),
        (["--speed-rpm", "fast"], "Invalid value for '--speed-rpm'"),
    ],
)  # fmt: skip
def test_simulate_bad_options(small, tmp_path, args, message):
    out = tmp_path / "never.nc"
    result = invoke("simulate", str(small), *args, "--out", str(out))
    assert result.exit_code == 2
    assert message in result.stderr
    assert "Traceback" not in result.output
    assert not out.exists()


def test_simulate_out_must_be_a_file_in_an_existing_folder(small, tmp_path):
    result = invoke("simulate", str(small), "--out", str(tmp_path))
    assert result.exit_code == 2 and "is a folder" in result.stderr
    result = invoke("simulate", str(small), "--out", str(tmp_path / "no" / "x.nc"))
    assert result.exit_code == 2 and "does not exist" in result.stderr
    assert sorted(os.listdir(tmp_path)) == ["small.toml"]


def test_progress_is_plain_lines_when_piped():
    # issue 13: under a pipe (CliRunner's stderr is not a terminal) progress is printed as
    # plain lines, first and last at least; -q hides it but not the results.
    result = invoke("simulate", "autobalancer", "--speed-ratio", "2", "--t-end", "0.2")
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert any(line.endswith("/6 trajectories") and ": 0/" in line for line in lines)
    assert any(line.endswith(": 6/6 trajectories") for line in lines)
    quiet = invoke("-q", "simulate", "autobalancer", "--speed-ratio", "2", "--t-end", "0.2")
    assert quiet.exit_code == 0 and quiet.stderr == ""
    assert "balanced" in quiet.stdout or "non-synchronous" in quiet.stdout


def test_compile_notice_only_without_a_numba_cache(tmp_path, caplog):
    import logging

    from rotorlab.integrate._codegen import announce_compile

    with caplog.at_level(logging.INFO, logger="rotorlab.compile"):
        assert announce_compile(tmp_path, "drv_x_rhs_abc", "integrator for x") == "integrator for x"
    assert caplog.messages == ["compiling the integrator for x (first run only) ..."]
    caplog.clear()
    (tmp_path / "__pycache__").mkdir()
    (tmp_path / "__pycache__" / "drv_x_rhs_abc.integrate_ensemble-12.py311.nbi").write_bytes(b"")
    with caplog.at_level(logging.INFO, logger="rotorlab.compile"):
        assert announce_compile(tmp_path, "drv_x_rhs_abc", "integrator for x") is None
    assert caplog.messages == []
