"""The compiled integrator against SciPy's DOP853 on the autobalancer (differential test).

Reference: scipy.integrate.solve_ivp(method="DOP853") at rtol 1e-12, atol 1e-14 on the same
right-hand side (the model's compiled kernel called from Python).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorlab.integrate import SaveAt, StepControl, solve, solve_ensemble
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams


def _autobalancer(ratio, frame="fixed"):
    p = 2 * np.pi * 20.0
    m, R, M1 = 0.03, 0.05, 1.0
    M = M1 + 2 * m
    rotor = RotorParams(disc_mass=M1, eccentricity=m * R / M1, stiffness=p * p * M, damping=2 * 0.05 * M * p)
    ball = BallParams(mass=m, radius=R, damping=2e-4)
    return JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(ratio * p), frame=frame)


@pytest.mark.parametrize("ratio", [0.6, 2.0])
@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_autobalancer_agrees_with_scipy_dop853(ratio, frame):
    model = _autobalancer(ratio, frame)
    y0 = model.initial_state(np.radians([30.0, 200.0]))
    ts = np.linspace(0.0, 1.5, 61)
    ref = solve_ivp(model.rhs, (0.0, 1.5), y0, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=ts)
    sol = solve(model, y0, (0.0, 1.5), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-13))
    assert sol.success
    scale = np.maximum(np.abs(ref.y.T), 1e-6)
    scale[:, :4] = np.max(np.abs(ref.y[:4]))  # rotor states: relative to their amplitude
    np.testing.assert_array_less(np.abs(sol.ys - ref.y.T) / scale, 1e-7)


def test_stroboscopic_saving_once_per_revolution():
    model = _autobalancer(2.0, "fixed")
    omega = 2.0 * 2 * np.pi * 20.0
    y0 = model.initial_state(np.radians([30.0, 200.0]))
    sol = solve(model, y0, (0.0, 0.5), save_at=SaveAt(every_revolution=True), control=StepControl(rtol=1e-10, atol=1e-12))
    n_rev = int(np.floor(0.5 * omega / (2 * np.pi) + 1e-9))
    assert sol.ts.size == n_rev
    np.testing.assert_allclose(sol.ts, 2 * np.pi / omega * np.arange(1, n_rev + 1), rtol=1e-12)
    dense = solve(model, y0, (0.0, 0.5), save_at=SaveAt(ts=sol.ts), control=StepControl(rtol=1e-10, atol=1e-12))
    np.testing.assert_array_equal(sol.ys, dense.ys)


def test_ensemble_over_parameter_sets_matches_single_runs():
    models = [_autobalancer(r) for r in (0.6, 1.3, 2.0)]
    P = np.stack([m.to_array() for m in models])
    y0 = models[0].initial_state(np.radians([10.0, 100.0]))
    ens = solve_ensemble(models[0], y0, (0.0, 0.3), params=P, control=StepControl(rtol=1e-9, atol=1e-12))
    for i, m in enumerate(models):
        single = solve(m, y0, (0.0, 0.3), control=StepControl(rtol=1e-9, atol=1e-12))
        np.testing.assert_array_equal(ens.y_final[i], single.y_final)
