"""Accuracy of the Dormand-Prince 5(4) integrator: order, SciPy agreement, dense output."""

import math

import numpy as np
from scipy.integrate import solve_ivp

from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.models.examples import HarmonicOscillator


def _fixed_step(h):
    # every step accepted (huge atol) and capped at h: a fixed-step run
    return StepControl(rtol=0.5, atol=1e6, first_step=h, max_step=h)


def test_empirical_convergence_order_is_five():
    osc = HarmonicOscillator(frequency=1.0)
    T = 8.0
    errs = []
    for n in (32, 64, 128, 256):
        sol = solve(osc, [1.0, 0.0], (0.0, T), control=_fixed_step(T / n))
        assert sol.stats["naccept"] == n
        errs.append(np.max(np.abs(sol.y_final - osc.exact([T], [1.0, 0.0])[0])))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    np.testing.assert_allclose(orders, 5.0, atol=0.15)


def test_dense_output_is_fourth_order_between_steps():
    osc = HarmonicOscillator(frequency=1.0)
    T = 8.0
    errs = []
    for n in (32, 64, 128):
        h = T / n
        ts = np.arange(n) * h + 0.5 * h  # mid-step points: dense output only
        sol = solve(osc, [1.0, 0.0], (0.0, T), save_at=SaveAt(ts=ts), control=_fixed_step(h))
        errs.append(np.max(np.abs(sol.ys - osc.exact(ts, [1.0, 0.0]))))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(orders > 3.8), orders


def test_same_steps_and_values_as_scipy_rk45():
    w = 3.0
    osc = HarmonicOscillator(frequency=w)
    ts = np.linspace(0.0, 10.0, 41)
    ref = solve_ivp(lambda t, y: [y[1], -w * w * y[0]], (0.0, 10.0), [1.0, 0.5], method="RK45",
                    rtol=1e-8, atol=1e-10, t_eval=ts)
    sol = solve(osc, [1.0, 0.5], (0.0, 10.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-8, atol=1e-10))
    assert sol.stats["nfev"] == ref.nfev
    np.testing.assert_allclose(sol.ys, ref.y.T, rtol=0, atol=1e-13)


def test_tight_tolerance_matches_closed_form():
    osc = HarmonicOscillator(frequency=2.0)
    ts = np.linspace(0.0, 20.0, 101)
    sol = solve(osc, [0.3, -1.0], (0.0, 20.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-12, atol=1e-14))
    np.testing.assert_allclose(sol.ys, osc.exact(ts, [0.3, -1.0]), atol=1e-10)


def test_save_grid_includes_start_and_end_exactly():
    osc = HarmonicOscillator(frequency=1.0)
    sol = solve(osc, [1.0, 0.0], (0.0, math.pi), save_at=SaveAt(ts=[0.0, math.pi]))
    np.testing.assert_array_equal(sol.ys[0], [1.0, 0.0])
    np.testing.assert_array_equal(sol.ys[1], sol.y_final)
