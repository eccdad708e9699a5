"""rotorlab.explore: grids, mapping start points, fractions, basin stability, argument checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from rotorlab.explore import (
    AbstractMapper,
    GridAxis,
    TorusRegimes,
    basin_fractions,
    basin_map,
    basin_stability,
    label_since,
    map_starts,
    wilson_interval,
)
from rotorlab.integrate import StepControl
from rotorlab.models._toroidal_ball import strautmanis_torus

# mixed regimes within 10 s at k = 1e-5 m: working, spare, still oscillating
MAPPER = TorusRegimes(strautmanis_torus(1e-5), t_end=10.0, n_horizons=5)
STARTS = {"psi": np.linspace(0.0, 6.0, 12), "dpsi": np.linspace(-250.0, 100.0, 12)}


@pytest.fixture(scope="module")
def reference():
    return map_starts(MAPPER, STARTS, threads=1)


def test_grid_axis():
    ax = GridAxis.parse(" psi = 0 : 6.5 : 14 ")
    assert (ax.name, ax.num) == ("psi", 14) and ax.values[-1] == 6.5
    for bad in ("psi=0:1", "psi:0:1:3", "=0:1:2", "psi=a:1:2", "psi=0:1:0", "psi=0:1:2.5"):
        with pytest.raises(ValueError):
            GridAxis.parse(bad)
    with pytest.raises(ValueError, match="GridAxis.start"):
        GridAxis("psi", math.nan, 1.0, 3)
    with pytest.raises(ValueError, match="GridAxis.num"):
        GridAxis("psi", 0.0, 1.0, 0)


def test_wilson_interval():
    lo, hi = wilson_interval(np.array([0, 10, 20]), 20, 0.95)
    assert lo[0] == 0.0 and hi[2] == 1.0 and lo[1] < 0.5 < hi[1]
    assert hi[0] == pytest.approx(0.1611, abs=1e-4)  # Wilson upper bound for 0 / 20
    with pytest.raises(ValueError, match="confidence"):
        wilson_interval(1, 10, 1.0)
    with pytest.raises(ValueError, match="n must"):
        wilson_interval(0, 0)


def test_label_since():
    h = np.array([1.0, 2.0, 3.0, 4.0])
    got = label_since(np.array([[0, 0, 0, 0], [1, 2, 1, 1], [2, 2, 2, 0]]), h)
    np.testing.assert_array_equal(got, [1.0, 3.0, 4.0])


def test_map_starts_dataset(reference):
    ds = reference
    assert ds.label.dims == ("ic", "horizon") and ds.sizes["ic"] == 12
    assert ds.horizon.values.tolist() == [2.0, 4.0, 6.0, 8.0, 10.0]
    assert ds.label.attrs["labels"] == ["working", "spare", "other"]
    assert ds.label.attrs["flag_meanings"] == "working spare other"
    assert ds.psi.attrs["units"] == "rad" and ds.dpsi.attrs["units"] == "rad/s"
    for name in ("ring_rate", "ring_angle", "section_angle", "settle_time", "lift_off", "stuck"):
        assert "units" in ds[name].attrs
    assert set(np.unique(ds.outcome.values)) == {0, 1, 2}
    assert np.all(ds.status.values == 0)
    working = ds.outcome.values == 0
    assert np.all(np.isfinite(ds.settle_time.values[working]))
    assert np.all(ds.settle_time.values[working] <= 10.0 - MAPPER.window)
    assert np.all(np.cos(ds.ring_angle.values[working, -1]) < -0.99)


@pytest.mark.parametrize("threads, chunk", [(1, 1), (2, 5), (2, None), (1, 7)])
def test_results_do_not_depend_on_chunks_or_threads(reference, threads, chunk):
    ds = map_starts(MAPPER, STARTS, threads=threads, chunk_size=chunk)
    xr.testing.assert_identical(ds, reference)
    xr.testing.assert_identical(basin_fractions(ds), basin_fractions(reference))


def test_progress_is_reported():
    calls = []
    map_starts(MAPPER, {"psi": [3.0, 3.1, 3.2], "alpha": 1.5685}, chunk_size=2, progress=lambda d, n: calls.append((d, n)))
    assert calls == [(2, 3), (3, 3)]


def test_map_starts_argument_checks():
    with pytest.raises(ValueError, match="unknown coordinate 'theta'"):
        map_starts(MAPPER, {"theta": [1.0]})
    with pytest.raises(ValueError, match="disagree"):
        map_starts(MAPPER, {"psi": [1.0, 2.0], "dpsi": [1.0, 2.0, 3.0]})
    with pytest.raises(ValueError, match="finite"):
        map_starts(MAPPER, {"psi": [np.nan]})
    with pytest.raises(ValueError, match="chunk_size"):
        map_starts(MAPPER, {"psi": [1.0]}, chunk_size=0)
    with pytest.raises(TypeError, match="AbstractMapper"):
        map_starts(object(), {"psi": [1.0]})
    with pytest.raises(ValueError, match=r"rolling_friction = -1: must be >= 0"):
        map_starts(MAPPER, {"rolling_friction": [-1.0]})


def test_torus_mapper_checks():
    model = strautmanis_torus()
    assert isinstance(MAPPER, AbstractMapper)
    for kwargs, field in (({"t_end": 0.0}, "t_end"), ({"n_horizons": 0}, "n_horizons"),
                          ({"window_revolutions": -1.0}, "window_revolutions"),
                          ({"spare_turns": math.inf}, "spare_turns"), ({"base_state": (0.0, 1.0)}, "base_state"),
                          ({"control": 1e-6}, "control")):  # fmt: skip
        with pytest.raises(ValueError, match=f"TorusRegimes.{field}"):
            TorusRegimes(model, **kwargs)
    with pytest.raises(ValueError, match="TorusRegimes.model"):
        TorusRegimes(object())
    m = TorusRegimes(model, t_end=1.0, n_horizons=2, window_revolutions=30.0)
    ts = m.save_times()
    assert ts[0] == 0.0 and ts[-1] == 1.0 and np.all(np.diff(ts) > 0)


def test_basin_map_grid_and_parameters():
    mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=6.0, n_horizons=2)
    ds = basin_map(mapper, GridAxis("rolling_friction", 5e-5, 1e-4, 3), GridAxis("offset", 0.01, 0.03, 2),
                   fixed={"psi": 2.0, "alpha": 1.56})  # fmt: skip
    assert ds.label.dims == ("offset", "rolling_friction", "horizon")
    assert ds.rolling_friction.attrs["units"] == "m" and ds.attrs["fixed_psi"] == 2.0
    assert np.all(ds.outcome.values == 0)  # everything slides to psi = pi and sticks
    with pytest.raises(ValueError, match="different coordinates"):
        basin_map(mapper, GridAxis("psi", 0, 1, 2), GridAxis("psi", 0, 1, 2))
    with pytest.raises(ValueError, match="both varied and fixed"):
        basin_map(mapper, GridAxis("psi", 0, 1, 2), GridAxis("dpsi", 0, 1, 2), fixed={"psi": 1.0})


def test_basin_fractions_sum_to_one(reference):
    fr = basin_fractions(reference)
    assert fr.fraction.dims == ("horizon", "regime")
    np.testing.assert_allclose(fr.fraction.sum("regime").values, 1.0)
    assert fr.attrs["n"] == 12 and int(fr["count"].sum()) == 12 * 5


def test_basin_stability_is_seeded_and_has_intervals():
    mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=6.0, n_horizons=3)
    ranges = {"psi": (0.0, 2 * math.pi), "dpsi": (-50.0, 50.0)}
    a = basin_stability(mapper, ranges, 10, seed=3, fixed={"alpha": 0.0})
    b = basin_stability(mapper, ranges, 10, seed=3, fixed={"alpha": 0.0}, chunk_size=3)
    xr.testing.assert_identical(a, b)
    c = basin_stability(mapper, ranges, 10, seed=4, fixed={"alpha": 0.0})
    assert not np.array_equal(a.psi.values, c.psi.values)
    p, lo, hi = (a[v].isel(horizon=-1).values for v in ("probability", "ci_low", "ci_high"))
    assert np.all(lo <= p) and np.all(p <= hi) and a.attrs["seed"] == 3
    assert p[0] >= 0.7  # k = 1e-4 m: slow starts work
    with pytest.raises(ValueError, match="n must"):
        basin_stability(mapper, ranges, 0, seed=1)
    with pytest.raises(ValueError, match="range of 'psi'"):
        basin_stability(mapper, {"psi": (1.0, 0.0)}, 3, seed=1)
    with pytest.raises(ValueError, match="both drawn and fixed"):
        basin_stability(mapper, ranges, 3, seed=1, fixed={"psi": 1.0})


def test_mapper_control_is_used():
    coarse = TorusRegimes(strautmanis_torus(1e-4), t_end=2.0, n_horizons=1, control=StepControl(rtol=1e-3, atol=1e-5))
    fine = TorusRegimes(strautmanis_torus(1e-4), t_end=2.0, n_horizons=1)
    starts = {"psi": [2.0], "dpsi": [30.0]}
    assert int(map_starts(coarse, starts).n_steps[0]) < int(map_starts(fine, starts).n_steps[0])
