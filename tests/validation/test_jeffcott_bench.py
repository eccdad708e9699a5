"""``jeffcott_balls`` on the shared benchmark problem (``shared/bench``), physics check.

The benchmark README: with rtol 1e-8, atol 1e-10 and 2000 revolutions, every off-diagonal grid
point balances (final amplitude <= about 2e-9) and the diagonal phi1 = phi2 (the two balls move
together and cannot balance) ends at amplitude 0.0357191.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams

BENCH = Path("/work/shared/bench")


def _bench():
    sys.path.insert(0, str(BENCH))
    try:
        import model as bench
    finally:
        sys.path.pop(0)
    return bench


def test_benchmark_physics_check():
    from rotorlab.integrate import StepControl, solve_ensemble

    bench = _bench()
    disc = bench.M - 2 * bench.m
    model = JeffcottBalls(
        RotorParams(disc, bench.EPS / disc, bench.K, bench.C),
        (BallParams(bench.m, bench.R, damping=bench.BETA),) * 2,
        speed=ConstantSpeed(bench.OMEGA),
    )
    idx = np.concatenate([bench.subset_indices(4, offdiag=True), [37 * bench.NGRID + 37]])
    y0 = bench.initial_state(idx)
    np.testing.assert_array_equal(model.initial_state(y0[0, 4:6])[4:], y0[0, 4:])  # same layout
    sol = solve_ensemble(model, y0, (0.0, bench.T1), control=StepControl(rtol=bench.RTOL, atol=bench.ATOL))
    assert np.all(sol.status == 0)
    amplitude = np.hypot(sol.y_final[:, 0], sol.y_final[:, 1])
    assert np.all(amplitude[:-1] < 3e-9)
    assert amplitude[-1] == pytest.approx(0.0357191, abs=1e-7)
