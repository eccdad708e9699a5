"""``rotorlab sweep`` / ``rotorlab show`` and the ``sweep`` analysis of case files.

The SIGKILL test runs the command line as a subprocess (with this worktree's ``src`` on
PYTHONPATH), kills it at random moments several times, resumes it, and checks that the store
ends bit-identical to an uninterrupted run and that no finished chunk was computed again.
"""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

import rotorlab
from rotorlab.analyses import run_analysis
from rotorlab.cli import app
from rotorlab.io import CaseError, SweepSpec, load_case, parse_case
from rotorlab.sweep import open_sweep, store_info

runner = CliRunner()
SRC = str(Path(rotorlab.__file__).resolve().parents[1])
GRID = ["--speed-ratio", "2", "--ic", "psi_1=0:6:8", "--ic", "psi_2=0:6:8", "--t-end", "1", "--chunk", "4"]


def invoke(*args: str):
    return runner.invoke(app, list(args))


def _bits(ds: xr.Dataset) -> dict[str, bytes]:
    return {name: ds[name].values.tobytes() for name in ds.variables}


def _marks(store: Path) -> tuple[list[int], dict[int, int]]:
    """Completion marks and the modification times of the finished chunks of ``label``."""
    if not store.exists():
        return [], {}
    done = store_info(store)["done"].tolist()
    times = {}
    for k, run in enumerate(done):
        if run:
            times[k] = (store / "label" / "c" / str(k) / "0").stat().st_mtime_ns
    return done, times


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "rotorlab.cli", *args]


def test_sigkill_at_random_moments_then_resume_is_bit_identical(tmp_path):
    env = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", "")}
    ref = tmp_path / "ref.zarr"
    subprocess.run(_cli("sweep", "autobalancer", *GRID, "--out", str(ref), "--json"), env=env, check=True,
                   capture_output=True, timeout=300)  # fmt: skip
    store = tmp_path / "killed.zarr"
    rng = random.Random(7)
    kills = 0
    before_done, before_times = [], {}
    for attempt in range(8):
        proc = subprocess.Popen(_cli("sweep", "autobalancer", *GRID, "--out", str(store), "--resume", "--json"),
                                env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                start_new_session=True)  # fmt: skip
        # kill once a random number (1-3) of new chunks are marked, i.e. mid-run, at a random moment
        target = len([d for d in before_done if d]) + rng.randint(1, 3)
        while proc.poll() is None and attempt < 6:
            try:
                if int(np.count_nonzero(store_info(store)["done"])) >= target:
                    break
            except Exception:  # noqa: BLE001 - the store does not exist yet, or is being written
                pass
            time.sleep(0.01)
        time.sleep(rng.uniform(0.0, 0.05))
        if proc.poll() is None and attempt < 6:
            os.killpg(proc.pid, signal.SIGKILL)
            kills += 1
        out, err = proc.communicate(timeout=300)
        done, times = _marks(store)
        # chunks finished before this run keep their mark (the run that wrote them) and their files
        assert all(done[k] == before_done[k] for k in range(len(before_done)) if before_done[k]), attempt
        assert all(times[k] == t for k, t in before_times.items()), attempt
        missing_before = sum(1 for k in range(len(done)) if not (k < len(before_done) and before_done[k]))
        before_done, before_times = done, times
        if proc.returncode == 0:
            doc = json.loads(out)
            assert doc["chunks"]["computed"] + doc["chunks"]["skipped"] == doc["chunks"]["total"] == 16
            # only the chunks missing before this run were computed
            assert doc["chunks"]["computed"] == missing_before
            break
        assert proc.returncode == -signal.SIGKILL, err.decode()
    assert kills >= 2 and proc.returncode == 0
    assert len(set(before_done)) >= 2  # really written by several runs
    a, b = open_sweep(ref), open_sweep(store)
    a.attrs.pop("complete"), b.attrs.pop("complete")
    xr.testing.assert_identical(a, b)
    assert _bits(a) == _bits(b)


def test_sweep_cli_local_dask_cluster_matches_in_process(tmp_path):
    args = ["sweep", "autobalancer", "--speed-ratio", "2", "--ic", "psi_1=0deg:300deg:6", "--param",
            "ball_damping=1e-3:4e-3:2", "--t-end", "0.5", "--chunk", "5"]  # fmt: skip
    one = invoke(*args, "--out", str(tmp_path / "one.zarr"), "--json")
    assert one.exit_code == 0, one.output
    two = invoke(*args, "--out", str(tmp_path / "two.zarr"), "--workers", "2", "--json")
    assert two.exit_code == 0, two.output
    doc = json.loads(two.stdout)
    assert doc["executor"] == "Dask LocalCluster of 2 workers" and doc["dims"] == ["ball_damping", "psi_1"]
    assert doc["chunks"] == {"total": 3, "computed": 3, "skipped": 0}
    a, b = open_sweep(tmp_path / "one.zarr"), open_sweep(tmp_path / "two.zarr")
    assert _bits(a) == _bits(b)
    assert a.ball_damping.attrs["units"] == "N m s/rad" and a.psi_1.values[-1] == pytest.approx(np.radians(300))
    assert sum(doc["fractions"].values()) == pytest.approx(1.0) and doc["n"] == 12


def test_sweep_cli_thread_workers_of_a_fresh_process_match_in_process(tmp_path):
    """``--workers`` runs its workers as threads of the command. In a fresh process their first
    chunks ask for the compiled drivers at the same moment: with 4 workers this command failed in
    6 of 6 runs (KeyError 'integrate_lanes_serial', SystemError from ``ast``) until generating and
    importing a driver took a lock (``rotorlab.integrate._codegen.BUILD_LOCK``)."""
    args = ["sweep", "autobalancer", "--speed-ratio", "2", "--ic", "psi_1=0deg:300deg:6", "--param",
            "ball_damping=1e-3:4e-3:2", "--t-end", "0.5", "--chunk", "2"]  # fmt: skip
    one = invoke(*args, "--out", str(tmp_path / "one.zarr"), "--json")
    assert one.exit_code == 0, one.output
    env = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", "")}
    four = subprocess.run(_cli(*args, "--out", str(tmp_path / "four.zarr"), "--workers", "4", "--json"), env=env,
                          capture_output=True, text=True, timeout=600)  # fmt: skip
    assert four.returncode == 0, four.stderr
    doc = json.loads(four.stdout)
    assert doc["executor"] == "Dask LocalCluster of 4 workers" and doc["chunks"]["computed"] == 6
    assert _bits(open_sweep(tmp_path / "one.zarr")) == _bits(open_sweep(tmp_path / "four.zarr"))


def test_sweep_cli_bad_input_exits_2_and_writes_nothing(tmp_path):
    out = tmp_path / "s.zarr"
    base = ["sweep", "autobalancer", "--speed-ratio", "2", "--t-end", "0.2", "--out", str(out)]
    cases = [
        (["--ic", "psi_1=0:1:2", "--workers", "0"], "--workers = 0"),
        (["--ic", "psi_1=0:1:2", "--scheduler", "localhost:8786"], "--scheduler = localhost:8786"),
        (["--ic", "psi_1=0:1:2", "--scheduler", "tcp://a:1", "--workers", "2"], "exclude each other"),
        (["--param", "mass=1:2:3"], "unknown parameter 'mass'"),
        (["--ic", "psi_3=0:1:2"], "has 2 ball(s)"),
        (["--ic", "psi_1=0:1"], "--ic = psi_1=0:1: must be NAME=START:STOP:N"),
        (["--ic", "psi_1=0:1:2", "--sample", "4"], "NAME=LOW:HIGH"),
        (["--param", "ball_mass=1kg*m:2:3"], "--param"),
        (["--ic", "psi_1=0:1:2", "--chunk", "0"], "--chunk = 0"),
        (["--ic", "psi_1=0:1:2", "--seed", "3"], "--seed needs --sample"),
        ([], "give --param and/or --ic"),
    ]
    for extra, message in cases:
        res = invoke(*base, *extra)
        assert res.exit_code == 2, (extra, res.output)
        assert message in res.stderr and "Traceback" not in res.output, (extra, res.stderr)
        assert not out.exists()
    res = invoke("sweep", "pico21", "--ic", "psi_1=0:1:2", "--out", str(out))
    assert res.exit_code == 2 and "jeffcott_balls" in res.stderr and not out.exists()
    # a toroidal ball's state names are not a rotor with balls' initial conditions
    res = invoke(*base, "--ic", "psi=0:1:2")
    assert res.exit_code == 2 and "'psi' is not an initial condition of this jeffcott_balls model" in res.stderr
    # a machine needs a constant speed as a rotor with balls does: the case's own analyses that need
    # one (its tolerances study) already refuse the ramp, naming their key path
    res = invoke("sweep", "pico21-balancer", "--set", 'model.drive={profile="ramp",start=0,stop=1000,duration=1}',
                 "--ic", "psi_1=0:1:2", "--out", str(out))  # fmt: skip
    assert res.exit_code == 2 and "analysis[6].speed: give the constant spin speed" in res.stderr and not out.exists()


def test_sweep_cli_refuses_foreign_existing_and_damaged_stores(tmp_path):
    out = tmp_path / "s.zarr"
    args = ["sweep", "autobalancer", "--speed-ratio", "2", "--ic", "psi_1=0:1:3", "--t-end", "0.2", "--out", str(out)]
    assert invoke(*args).exit_code == 0
    res = invoke(*args)
    assert res.exit_code == 2 and "exists; give --resume" in res.stderr
    res = invoke(*args[:-3], "0.3", "--out", str(out), "--resume")
    assert res.exit_code == 2 and "holds a different sweep" in res.stderr and "t_end: stored 0.2, now 0.3" in res.stderr
    assert "Traceback" not in res.output
    assert store_info(out)["runs"] == 1  # the refused resume did not touch the store
    other = tmp_path / "other"
    other.mkdir()
    res = invoke(*args[:-1], str(other), "--resume")
    assert res.exit_code == 2 and "not a rotorlab sweep store" in res.stderr
    chunk = out / "amplitude" / "c" / "0" / "0"
    chunk.write_bytes(chunk.read_bytes()[:-5])
    res = invoke(*args, "--resume")
    assert res.exit_code == 2 and "damaged" in res.stderr and "Traceback" not in res.output
    res = invoke("show", str(out))
    assert res.exit_code == 2 and "damaged" in res.stderr
    res = invoke("show", str(tmp_path / "missing.zarr"))
    assert res.exit_code == 2 and "does not exist" in res.stderr


def test_show_prints_summary_and_writes_figures(tmp_path):
    out = tmp_path / "b.zarr"
    args = ["sweep", "autobalancer", "--speed-ratio", "2", "--ic", "psi_1=0:6:4", "--ic", "psi_2=0:6:3",
            "--t-end", "0.3", "--chunk", "5", "--out", str(out)]  # fmt: skip
    res = invoke(*args)
    assert res.exit_code == 0 and "12 points, 3 chunk(s) computed, 0 already in the store" in res.stdout
    res = invoke("--quiet", "show", str(out), "--json")
    doc = json.loads(res.stdout)
    assert doc["complete"] and doc["chunks"] == {"total": 3, "done": 3} and doc["n"] == 12
    assert sorted(Path(f).name for f in doc["figures"]) == ["basin.png", "fractions.png"]
    assert all(Path(f).stat().st_size > 1000 for f in doc["figures"])
    res = invoke("show", str(out), "--figures", str(tmp_path / "figs"))
    assert "12 points (psi_1 4 x psi_2 3); 3 of 3 chunks done" in res.stdout
    assert (tmp_path / "figs" / "basin.png").exists()


def test_sweep_analysis_in_a_case_file():
    text = load_case("autobalancer").text
    head = text[: text.index("[[analysis]]")]
    case = parse_case(head + """
[[analysis]]
type = "sweep"
name = "mass-map"
speed_ratio = 2.0
param = { ball_mass = ["20 g", "40 g", 2] }
ic = { psi_1 = ["0 deg", "180 deg", 3] }
t_end = "0.3 s"
n_horizons = 2
chunk = 4
""", origin="test")
    spec = case.analysis("mass-map")
    assert isinstance(spec, SweepSpec) and spec.param["ball_mass"] == (0.02, 0.04, 2)
    ds = run_analysis(case.model, spec)
    assert ds.outcome.dims == ("ball_mass", "psi_1") and ds.label.shape == (2, 3, 2)
    assert ds.attrs["analysis"] == "sweep" and ds.ball_mass.attrs["units"] == "kg"
    with pytest.raises(CaseError) as err:
        parse_case(head + """
[[analysis]]
type = "sweep"
speed_ratio = 2.0
param = { mass = [1, 2, 3] }
ic = { psi_7 = [0, 1, 2] }
t_end = 1
""", origin="test")
    text = str(err.value)
    assert "unknown param coordinate" in text and "analysis[" in text
    with pytest.raises(CaseError, match="give a range"):
        parse_case(head + """
[[analysis]]
type = "sweep"
speed_ratio = 2.0
ic = { psi_1 = [0, 1, 2] }
sample = 10
t_end = 1
""", origin="test")


def test_show_draws_ball_angles_in_the_unit_the_sweep_was_given(tmp_path):
    """``--ic psi_1=0deg:300deg:N`` is stored in radians (SI) with the unit it was written in;
    ``open_sweep`` returns it as ``input_units_psi_1`` and the basin map is drawn in degrees
    (issue 13: basin maps were drawn in radians although the input was in degrees)."""
    from rotorlab.plot import sweep_figures

    base = ["sweep", "autobalancer", "--speed-ratio", "2", "--t-end", "0.2", "--chunk", "9"]
    deg = invoke(*base, "--ic", "psi_1=0deg:300deg:3", "--ic", "psi_2=0:5:3", "--out", str(tmp_path / "d.zarr"))
    assert deg.exit_code == 0, deg.output
    ds = open_sweep(tmp_path / "d.zarr")
    assert ds.psi_1.values[-1] == pytest.approx(np.radians(300))  # SI inside
    assert ds.attrs["input_units_psi_1"] == "deg" and ds.attrs["input_units_psi_2"] == "rad"
    ax = sweep_figures(ds)["basin"].axes[0]
    labels = ax.get_xlabel() + " | " + ax.get_ylabel()
    assert "deg" in labels and "rad" in labels, labels
    assert max(ax.get_xlim() + ax.get_ylim()) > 250  # 300 deg drawn as degrees, not 5.2 rad
    shown = invoke("show", str(tmp_path / "d.zarr"), "--figures", str(tmp_path / "f"))
    assert shown.exit_code == 0, shown.output and (tmp_path / "f" / "basin.png").exists()
