"""Properties of basin bookkeeping and of the toroidal ball's stick/slip set-up (Hypothesis)."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from rotorlab.explore import GridAxis, TorusRegimes, basin_fractions, label_since, map_starts, wilson_interval
from rotorlab.models._toroidal_ball import strautmanis_torus

labels_strategy = st.integers(1, 6).flatmap(
    lambda n_lab: st.tuples(
        st.just(n_lab),
        arrays(np.int16, st.tuples(st.integers(1, 30), st.integers(1, 6)), elements=st.integers(0, n_lab - 1)),
    )
)


@given(labels_strategy)
def test_fractions_sum_to_one(data):
    n_lab, lab = data
    ds = xr.Dataset({"label": (("ic", "horizon"), lab, {"labels": [f"l{k}" for k in range(n_lab)]})},
                    coords={"horizon": np.arange(lab.shape[1], dtype=float) + 1.0})  # fmt: skip
    fr = basin_fractions(ds)
    np.testing.assert_allclose(fr.fraction.sum("regime").values, 1.0)
    assert np.all(fr["count"].sum("regime").values == lab.shape[0])
    assert np.all((fr.fraction.values >= 0) & (fr.fraction.values <= 1))


@given(labels_strategy)
def test_label_since_is_the_start_of_the_final_run(data):
    _, lab = data
    h = np.arange(1, lab.shape[1] + 1, dtype=float)
    since = label_since(lab, h)
    for row, s in zip(lab, since):
        j = int(np.flatnonzero(h == s)[0])
        assert np.all(row[j:] == row[-1])
        assert j == 0 or row[j - 1] != row[-1]


@settings(deadline=None)
@given(st.integers(1, 10_000), st.data(), st.floats(0.5, 0.999))
def test_wilson_interval_brackets_the_estimate(n, data, conf):
    k = data.draw(st.integers(0, n))
    lo, hi = wilson_interval(k, n, conf)
    assert 0.0 <= lo <= k / n <= hi <= 1.0
    lo2, hi2 = wilson_interval(4 * k, 4 * n, conf)
    assert hi2 - lo2 <= hi - lo + 1e-12  # more samples, narrower interval


@given(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.integers(1, 500))
def test_grid_axis_values(a, b, n):
    v = GridAxis("x", a, b, n).values
    assert v.size == n and v[0] == a and (n == 1 or v[-1] == b)


MODEL = strautmanis_torus(1e-4)


@settings(max_examples=60, deadline=None)
@given(st.floats(-7, 7), st.floats(-3.5, 3.5), st.sampled_from([0.0, -3.0, 5.0]), st.sampled_from([0.0, 2.0]))
def test_initial_modes_are_consistent(psi, alpha, dpsi, dalpha):
    y = MODEL.initial_state(psi, alpha, dpsi, dalpha)
    f = MODEL.forces(y)
    for i_rate, i_mode, drive, bound in ((2, 4, "F_psi", "B_psi"), (3, 5, "F_alpha", "B_alpha")):
        if y[i_rate] != 0.0:
            assert y[i_mode] == math.copysign(1.0, y[i_rate])
        elif y[i_mode] == 0.0:
            assert abs(f[drive]) <= f[bound]
        else:
            assert y[i_mode] == math.copysign(1.0, f[drive]) and abs(f[drive]) > f[bound]


@settings(max_examples=15, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0))
def test_a_held_ball_never_moves(u, v):
    wp = MODEL.working_point()
    psi = math.pi + u * 0.99 * (wp.psi_band[1] - math.pi)
    alpha = wp.alpha + v * 0.99 * (wp.alpha_band[1] - wp.alpha)
    assert bool(MODEL.holds(psi, alpha))
    ds = map_starts(TorusRegimes(MODEL, t_end=50.0, n_horizons=1), {"psi": psi, "alpha": alpha})
    assert int(ds.switches[0]) == 0 and int(ds.n_steps[0]) < 30 and int(ds.outcome[0]) == 0
    assert float(ds.ring_angle[0, 0]) == psi and float(ds.section_angle[0, 0]) == alpha


REFERENCE = {}


@settings(max_examples=8, deadline=None)
@given(st.integers(1, 9), st.sampled_from([1, 2]))
def test_labels_do_not_depend_on_chunking(chunk, threads):
    mapper = TorusRegimes(strautmanis_torus(1e-5), t_end=6.0, n_horizons=3)
    starts = {"psi": np.linspace(0.3, 6.0, 9), "dpsi": np.linspace(-260.0, 120.0, 9)}
    if "ds" not in REFERENCE:
        REFERENCE["ds"] = map_starts(mapper, starts, threads=1)
    xr.testing.assert_identical(map_starts(mapper, starts, chunk_size=chunk, threads=threads), REFERENCE["ds"])
