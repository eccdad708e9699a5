"""Which compiled driver each ensemble path runs, and that the default lane driver gives the
scalar driver's numbers bit for bit on the models that use it.

``solve_ensemble(lanes="auto")`` (the default, used by every analysis) takes the lane driver for
every ensemble, events, resets and modes included (stick/slip of the toroidal ball, impacts of
the crusher rotor, the rub model's contact modes); a single trajectory (``solve``) stays on the
scalar driver, which is also the reference (``tests/unit/test_lanes_events.py`` compares them
on every event model).
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from rotorlab.analyses import ImpactAnalysis, simulate
from rotorlab.contact import JeffcottRub, RubRegimes, RubRotor
from rotorlab.explore import BalancerRegimes, TorusRegimes, map_starts
from rotorlab.integrate import StepControl, solve, solve_ensemble
from rotorlab.integrate import _drivers
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams, krasnov_crusher
from rotorlab.models._toroidal_ball import strautmanis_torus

ROTOR = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
BALL = BallParams(mass=0.03, radius=0.05, damping=2e-3)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(251.3))
RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0)


@pytest.fixture
def used(monkeypatch):
    """The ``lanes`` argument of every compiled driver looked up, in order.

    The spy keeps the real function's module (``functools.wraps``): the name of a generated
    driver copy hashes the modules of the integrate package's globals, so a spy from this test
    module would give every driver looked up here a copy of its own, compiled again."""
    seen = []
    real = _drivers.driver

    @functools.wraps(real)
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


def test_event_models_run_on_lanes_single_trajectories_scalar(used):
    # basin of the toroidal ball (stick/slip modes and events)
    mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=0.05, n_horizons=1)
    map_starts(mapper, {"psi": [0.5, 1.0], "dpsi": [10.0, -10.0], "alpha": [0.1, 0.1]})
    assert used == [_drivers.DEFAULT_LANES]
    # sweep of the rub model (impacts, sustained contact)
    rub = RubRegimes(JeffcottRub(RUB, spin_speed=1.2), t_end=2.0, window=1.0, position=(0.5, 0.0), n_samples=8)
    rub.run_chunk({"spin_speed": np.array([1.2, 2.0])})
    assert used[1:] == [_drivers.DEFAULT_LANES]
    # sweep of the crusher rotor (stone pushes, impacts, sliding, terminal whirl event)
    ImpactAnalysis(krasnov_crusher(), t_end=0.05).run_chunk({"stone_mass": np.array([0.5, 3.0])})
    assert used[2:] == [_drivers.DEFAULT_LANES]
    solve(MODEL, MODEL.initial_state([0.0, 1.0]), (0.0, 0.01))
    assert used[3:] == [None]  # one trajectory: the scalar driver


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


def test_verify_run_up_and_machine_paths_run_on_lanes(used):
    """The steady-state verification, the run-up of a rotor with balls and the composed
    machine's simulation from several ball starts: every ensemble on lanes (the run-up's one
    reference trajectory without balls on the scalar driver)."""
    from rotorlab.analyses._machine import machine_simulate
    from rotorlab.linear import LinearSystem
    from rotorlab.models import Ball, BallRace, Machine, Unbalance
    from rotorlab.steady import run_up, verify

    p = MODEL.critical_speed
    verify(MODEL, [2.0 * p], points=2, t_end=[0.05])
    assert used == [_drivers.DEFAULT_LANES]
    run_up(MODEL, LinearRamp(0.3 * p, 2.0 * p, 0.05), t_end=0.05, n_save=5, initial_ball_angles=[[0.0, 1.0], [0.5, 2.0]])
    assert used[1:] == [_drivers.DEFAULT_LANES, None]
    s = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.05, 0.05, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([1.0, 1.0, 5.0, 5.0]))  # fmt: skip
    mac = Machine(s, races=(BallRace(0, 0.5, (Ball(0.02, damping=0.005),) * 2),), unbalances=(Unbalance(0, 0.05),),
                  drive=ConstantSpeed(2.0), n_modes=2)  # fmt: skip
    machine_simulate(mac, [[0.0, 1.0], [0.5, 2.5]], t_end=1.0)
    assert used[3:] == [_drivers.DEFAULT_LANES]
