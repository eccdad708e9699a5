"""The sweep engine under the other commands: ``rotorlab sweep`` of a toroidal ball, checkpointed
``rotorlab basin`` (``--store``/``--resume``), ``sweep`` analyses in ``rotorlab run``, and the
stability chart as a per-point analysis of the engine.
"""

from __future__ import annotations

import json
from pathlib import Path

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
