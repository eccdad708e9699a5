"""Which compiled driver each ensemble path runs, and that the default lane driver gives the
scalar driver's numbers bit for bit on the models that use it.

``solve_ensemble(lanes="auto")`` (the default, used by every analysis) takes the lane driver for
an ensemble of a model whose kernel is lane-friendly (``Kernels.vectorises``) with no active
event; a single trajectory (``solve``) and models with active events (stick/slip, impacts) stay
on the scalar driver, which is also the reference.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.analyses import simulate
from rotorlab.explore import BalancerRegimes, TorusRegimes, map_starts
from rotorlab.integrate import StepControl, solve, solve_ensemble
from rotorlab.integrate import _drivers
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams
from rotorlab.models._toroidal_ball import strautmanis_torus

ROTOR = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
BALL = BallParams(mass=0.03, radius=0.05, damping=2e-3)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(251.3))


@pytest.fixture
def used(monkeypatch):
    """The ``lanes`` argument of every compiled driver looked up, in order."""
    seen = []
    real = _drivers.driver

    def spy(kernels, lanes, serial):
        seen.append(lanes)
        return real(kernels, lanes, serial)

    monkeypatch.setattr(_drivers, "driver", spy)
    return seen


def test_simulate_runs_on_lanes(used):
    simulate(MODEL, speeds=[150.0, 250.0], initial_ball_angles=[[0.0, 1.6], [0.8, 3.5]], t_end=0.05, n_save=3)
    assert used and set(used) == {_drivers.DEFAULT_LANES}


def test_balancer_mapper_runs_on_lanes(used):
    mapper = BalancerRegimes(MODEL, t_end=0.05, n_horizons=1)
    map_starts(mapper, {"psi_1": [0.5, 1.0, 2.0], "psi_2": [2.5, 3.0, 0.1]})
    assert used and set(used) == {_drivers.DEFAULT_LANES}


def test_event_models_and_single_trajectories_stay_scalar(used):
    mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=0.05, n_horizons=1)
    map_starts(mapper, {"psi": [0.5, 1.0], "dpsi": [10.0, -10.0], "alpha": [0.1, 0.1]})
    solve(MODEL, MODEL.initial_state([0.0, 1.0]), (0.0, 0.01))
    assert used == [None, None]  # stick/slip events need the scalar driver; so does one trajectory


@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_jeffcott_lanes_bit_identical_to_scalar(frame):
    model = JeffcottBalls(ROTOR, (BALL, BALL, BALL), speed=LinearRamp(100.0, 300.0, 0.05), frame=frame)
    rng = np.random.default_rng(1)
    y0 = np.array([model.initial_state(a) for a in rng.uniform(0.0, 2 * np.pi, (11, 3))])
    kw = dict(control=StepControl(rtol=1e-8, atol=1e-10), threads=2)
    auto = solve_ensemble(model, y0, (0.0, 0.1), **kw)
    ref = solve_ensemble(model, y0, (0.0, 0.1), lanes=None, **kw)
    assert auto.driver == "lanes8" and ref.driver == "scalar"
    np.testing.assert_array_equal(auto.y_final, ref.y_final)
    np.testing.assert_array_equal(auto.stats, ref.stats)
    np.testing.assert_array_equal(auto.status, ref.status)
    assert np.all(ref.status == 0)
