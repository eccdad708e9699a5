"""The sweep engine under the other commands: ``rotorlab sweep`` of a toroidal ball, checkpointed
``rotorlab basin`` (``--store``/``--resume``), ``sweep`` analyses in ``rotorlab run``, and the
stability chart as a per-point analysis of the engine.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from rotorlab.analyses import basin_mapper, run_analysis
from rotorlab.cli import app
from rotorlab.explore import map_starts
from rotorlab.io import SweepSpec, load_case, parse_case
from rotorlab.sweep import open_sweep, store_info

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


def _bits(ds: xr.Dataset) -> dict[str, bytes]:
    return {name: ds[name].values.tobytes() for name in ds.variables}


# --------------------------------------------------------------------------- toroidal ball sweeps


def test_sweep_cli_runs_a_toroidal_ball_like_map_starts(tmp_path):
    out = tmp_path / "torus.zarr"
    res = invoke("sweep", "strautmanis-torus", "--param", "rolling_friction=1e-5:1e-4:2", "--ic", "psi=0:6:3",
                 "--ic", "dpsi=-280:140:3", "--t-end", "2", "--chunk", "5", "--out", str(out), "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["dims"] == ["rolling_friction", "psi", "dpsi"] and doc["n_points"] == 18
    assert doc["chunks"] == {"total": 4, "computed": 4, "skipped": 0}
    assert set(doc["fractions"]) == {"working", "spare", "other"} and sum(doc["fractions"].values()) == pytest.approx(1)
    ds = open_sweep(out)
    assert ds.attrs["mapper"] == "TorusRegimes" and ds.rolling_friction.attrs["units"] == "m"
    assert ds.label.dims == ("rolling_friction", "psi", "dpsi", "horizon")
    # the same starts through the explore API with the mapper a basin analysis of the case builds
    case = load_case("strautmanis-torus")
    mapper = basin_mapper(case.model, SweepSpec(revolutions=1.0), t_end=2.0)
    assert mapper == ds_mapper(case, 2.0)
    grid = np.meshgrid(ds.rolling_friction.values, ds.psi.values, ds.dpsi.values, indexing="ij")
    ref = map_starts(mapper, {"rolling_friction": grid[0].ravel(), "psi": grid[1].ravel(),
                              "dpsi": grid[2].ravel()}, chunk_size=7)  # fmt: skip
    assert ds.label.values.reshape(18, -1).tobytes() == ref.label.values.tobytes()
    assert ds.n_steps.values.ravel().tobytes() == ref.n_steps.values.tobytes()
    # physics: larger friction never loses working starts on this grid after 2 s
    working = (ds.outcome == 0).sum(["psi", "dpsi"]).values
    assert working[1] >= working[0]


def ds_mapper(case, t_end):
    """The toroidal-ball mapper with the basin defaults (what build_sweep must use)."""
    from rotorlab.analyses import build_model
    from rotorlab.explore import TorusRegimes

    return TorusRegimes(build_model(case.model), t_end=t_end, n_horizons=4)


def test_sweep_analysis_of_a_toroidal_ball_case(tmp_path):
    case = load_case("strautmanis-torus")
    spec = SweepSpec(name="k-map", param={"rolling_friction": ["0.01 mm", "0.1 mm", 2]},
                     ic={"psi": ["0 deg", "300 deg", 3]}, t_end="1 s", n_horizons=2, chunk=4)  # fmt: skip
    assert not spec.case_issues(case.model)
    ds = run_analysis(case.model, spec)
    assert ds.attrs["analysis"] == "sweep" and ds.label.shape == (2, 3, 2)
    assert float(ds.horizon[-1]) == 1.0 and ds.attrs["mapper"] == "TorusRegimes"
    bad = SweepSpec(speed_ratio=2.0, ic={"psi_1": [0, 1, 2]}, spare_turns=2.0, t_end=1.0)
    messages = " | ".join(i.message for i in bad.case_issues(case.model))
    assert "not an initial condition of this toroidal_ball model" in messages
    assert "applies to a rotor with balls only" in messages
    jeff = load_case("autobalancer")
    assert any("toroidal_ball model only" in i.message for i in
               SweepSpec(ic={"psi_1": [0, 1, 2]}, spare_turns=2.0, t_end=1.0).case_issues(jeff.model))  # fmt: skip


def test_sweep_cli_toroidal_ball_bad_input_exits_2(tmp_path):
    out = tmp_path / "t.zarr"
    base = ["sweep", "strautmanis-torus", "--t-end", "1", "--out", str(out)]
    for extra, message in [
        (["--ic", "psi_1=0:1:2"], "'psi_1' is not an initial condition of this toroidal_ball model"),
        (["--ic", "psi=0:1:2", "--param", "ball_mass=1:2:2"], "'ball_mass' is not a parameter of this toroidal_ball"),
        (["--ic", "psi=0:1:2", "--speed-ratio", "2"], "--speed-ratio: a toroidal_ball spins"),
        (["--param", "psi=0:1:2"], "unknown parameter 'psi'"),
    ]:
        res = invoke(*base, *extra)
        assert res.exit_code == 2 and message in res.stderr and "Traceback" not in res.output, (extra, res.stderr)
        assert not out.exists()


# --------------------------------------------------------------------------- checkpointed basins


def _basin_spec(case, name="basin-k1e-4", **updates):
    """The spec ``rotorlab basin CASE --analysis NAME --x ... --y ... --t-end ...`` builds."""
    from rotorlab.io import BasinSpec

    base = case.analysis(name)
    return BasinSpec.model_validate({**base.model_dump(), **updates})


class _Stop:
    """A progress callback that raises KeyboardInterrupt (Ctrl-C) after ``k`` finished chunks."""

    def __init__(self, k: int) -> None:
        self.k, self.calls = k, 0

    def __call__(self, done: int, total: int) -> None:
        self.calls += 1
        if self.calls >= self.k:
            raise KeyboardInterrupt


GRID = {"x": ("psi", 0.0, 6.0, 4), "y": ("dpsi", -280.0, 140.0, 3), "t_end": 2.0}


def test_basin_interrupted_then_resumed_is_bit_identical_python(tmp_path):
    from rotorlab.analyses import run_basin_analysis

    case = load_case("strautmanis-torus")
    spec = _basin_spec(case, **GRID)
    ref = run_basin_analysis(case.model, spec, chunk_size=5)  # in memory, other chunking
    store = tmp_path / "b.zarr"
    with pytest.raises(KeyboardInterrupt):
        run_basin_analysis(case.model, spec, chunk_size=4, store=store, progress=_Stop(2))
    info = store_info(store)
    assert info["chunks_done"] == 2 and not info["complete"] and info["n_chunks"] == 3
    calls = []
    ds = run_basin_analysis(case.model, spec, store=store, resume=True,
                            progress=lambda done, total: calls.append(done))  # fmt: skip
    assert calls == [12]  # only the missing chunk was computed (the store keeps its chunk size)
    assert store_info(store)["done"].tolist() == [1, 1, 2]
    xr.testing.assert_identical(ref, ds)
    assert _bits(ref) == _bits(ds)
    assert set(np.unique(ds.outcome.values)) <= {0, 1, 2} and ds["count"].values[-1].sum() == 12
    # random starts (basin stability) through a store give the in-memory result too
    rnd = _basin_spec(case, **GRID, samples=7, seed=3)
    a = run_basin_analysis(case.model, rnd, chunk_size=3)
    b = run_basin_analysis(case.model, rnd, chunk_size=2, store=tmp_path / "r.zarr")
    xr.testing.assert_identical(a, b)
    assert _bits(a) == _bits(b) and float(b.ci_low.min()) >= 0.0
    with pytest.raises(ValueError, match="working-point"):
        run_basin_analysis(case.model, case.analysis("working-point"), store=tmp_path / "w.zarr")


def test_basin_cli_store_resume_gives_the_in_memory_json_and_netcdf(tmp_path):
    from rotorlab.analyses import run_basin_analysis

    case = load_case("strautmanis-torus")
    args = ["basin", "strautmanis-torus", "--analysis", "basin-k1e-4", "--x", "psi=0:6:4", "--y", "dpsi=-280:140:3",
            "--t-end", "2", "--json"]  # fmt: skip
    plain = invoke(*args, "--out", str(tmp_path / "plain.nc"))
    assert plain.exit_code == 0, plain.output
    store = tmp_path / "b.zarr"
    # an interrupted checkpointed run (Ctrl-C after one chunk of four points) ...
    with pytest.raises(KeyboardInterrupt):
        run_basin_analysis(case.model, _basin_spec(case, **GRID), chunk_size=4, store=store, progress=_Stop(1))
    assert store_info(store)["chunks_done"] == 1
    # ... is refused without --resume, and continued with it
    again = invoke(*args, "--store", str(store))
    assert again.exit_code == 2 and "--store = " in again.stderr and "--resume" in again.stderr
    resumed = invoke(*args, "--store", str(store), "--resume", "--out", str(tmp_path / "resumed.nc"))
    assert resumed.exit_code == 0, resumed.output
    assert store_info(store)["done"].tolist() == [1, 2, 2]
    a, b = json.loads(plain.stdout), json.loads(resumed.stdout)
    assert a.pop("files") != b.pop("files")
    assert a == b and a["n"] == 12
    from rotorlab.io import load_netcdf

    x, y = load_netcdf(tmp_path / "plain.nc"), load_netcdf(tmp_path / "resumed.nc")
    xr.testing.assert_identical(x, y)
    assert x.label.values.tobytes() == y.label.values.tobytes()
    # a store of another basin (another --t-end) is refused, naming what differs
    other = invoke(*[a if a != "2" else "3" for a in args], "--store", str(store), "--resume")
    assert other.exit_code == 2 and "holds a different sweep" in other.stderr and "t_end" in other.stderr
    bad = invoke(*args, "--resume")
    assert bad.exit_code == 2 and "--resume needs --store" in bad.stderr


# --------------------------------------------------------------------------- sweep analyses in rotorlab run

SWEEP_CASE = """\
schema_version = 1
name = "torus-sweep"
description = "toroidal ball: regimes over friction and the ring angle"

[model]
type = "toroidal_ball"
ring_radius = "0.2 m"
tube_radius = "0.015 m"
ball_radius = "0.0125 m"
spin_speed = "140 rad/s"
offset = "0.02 m"
rolling_friction = "1e-4 m"

[[analysis]]
type = "sweep"
name = "k-map"
param = { rolling_friction = ["1e-5 m", "1e-4 m", 3] }
ic = { psi = ["0 deg", "300 deg", 6] }
t_end = "2 s"
n_horizons = 2
chunk = 7

[[analysis]]
type = "sweep"
name = "random"
ic = { psi = ["0 deg", "360 deg"], dpsi = [-280, 140] }
sample = 9
seed = 4
t_end = "1 s"
n_horizons = 2
"""


def test_run_command_runs_sweep_analyses(tmp_path):
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.io import load_netcdf
    from rotorlab.sweep import run_sweep

    path = tmp_path / "torus-sweep.toml"
    path.write_text(SWEEP_CASE)
    res = invoke("run", str(path), "--out", str(tmp_path / "out"), "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert {"k-map.nc", "random.nc", "k-map_basin.png", "k-map_fractions.png", "random_fractions.png",
            "report.html"} == set(doc["files"])  # fmt: skip
    rows = doc["analyses"]["k-map"]["rows"]
    assert doc["analyses"]["k-map"]["type"] == "sweep" and [r["regime"] for r in rows] == ["working", "spare", "other"]
    assert sum(r["count"] for r in rows) == 18 and sum(r["fraction"] for r in rows) == pytest.approx(1.0)
    # the saved results are the engine's, bit for bit (grid and seeded sample)
    case = parse_case(SWEEP_CASE, origin=str(path))
    for name, dims in (("k-map", ("rolling_friction", "psi", "horizon")), ("random", ("sample", "horizon"))):
        saved = load_netcdf(tmp_path / "out" / f"{name}.nc")
        spec = case.analysis(name)
        ref = run_sweep(build_sweep(case.model, spec), chunk_size=3)
        assert saved.label.dims == dims and saved.label.values.tobytes() == ref.label.values.tobytes()
        assert saved.attrs["analysis"] == "sweep" and saved.fraction.attrs["units"] == "1"
        counts = np.bincount(ref.outcome.values.ravel(), minlength=3)
        assert saved["count"].values[-1].tolist() == counts.tolist()
    html = (tmp_path / "out" / "report.html").read_text()
    assert "Analysis: k-map (sweep)" in html and "Regimes of a grid of 18 starts over rolling_friction × psi" in html
    assert "Regimes of 9 random points (seed 4) over psi × dpsi" in html
    # sweep results are explored: each figure is an interactive twin, its PNG linked
    assert html.count('<figure class="interactive"') == 3 and "<img" not in html
    for stem in ("k-map_basin", "k-map_fractions", "random_fractions"):
        assert f'data-stem="{stem}"' in html and f'<a href="{stem}.png">' in html


# --------------------------------------------------------------------------- stability chart on the engine


def test_stability_chart_is_a_sweep_of_steady_stability(tmp_path):
    from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams
    from rotorlab.steady import EXACT_VERDICTS, SteadyStability, stability_chart
    from rotorlab.sweep import ListAxis, LocalProcesses, Sweep, run_sweep

    ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    rotor = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
    model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0))
    speeds, masses = np.array([40.0, 90.0, 150.0, 300.0]), np.array([0.01, 0.03, 0.06])
    chart = stability_chart(model, speeds, param="ball_mass", values=masses)
    sweep = Sweep(SteadyStability(model, "ball_mass"), axes=(ListAxis("ball_mass", masses), ListAxis("spin_speed", speeds)))
    # chunked into a store on two worker processes: the chart's numbers, bit for bit
    res = run_sweep(sweep, store=tmp_path / "chart.zarr", chunk_size=5, executor=LocalProcesses(workers=2, threads=1))
    for name in ("exists", "stable_exact", "stable_hamilton", "growth_rate", "amplitude", "ball_angle"):
        assert res[name].values.tobytes() == chart[name].values.tobytes(), name
    verdicts = np.array(EXACT_VERDICTS)[res.verdict_exact.values]
    assert (verdicts == chart.verdict_exact.values).all()
    assert res.growth_rate.attrs["units"] == "1/s" and res.spin_speed.attrs["units"] == "rad/s"
    # physics (seed 002): with eta = M1 e / (m R) < 2 the balanced motions are stable only above
    # the critical speed (here at 3 p); with eta > 2 (the lightest balls) they do not exist
    p = res.critical_speed.values
    main = chart.kind.values == "main"
    eta = rotor.disc_mass * rotor.eccentricity / (masses * ball.radius)
    assert eta.round(2).tolist() == [3.6, 1.2, 0.6]
    ratio = speeds[None, :] / p
    assert chart.speed_ratio.values.tobytes() == ratio.tobytes()
    assert not chart.balanced.values[ratio < 1].any() and (ratio < 1).sum() == 6
    assert chart.balanced.values[1:, -1].all() and ratio[1:, -1].min() > 3
    assert not chart.exists.values[0][:, main].any() and not chart.balanced.values[0].any()
    with pytest.raises(ValueError, match="unknown chart parameter"):
        SteadyStability(model, "disc_mass")
