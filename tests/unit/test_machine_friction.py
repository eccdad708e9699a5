"""Ball Coulomb and rolling friction with stick-slip in the composed machine (issue 12).

References: the planar single-mass machine with one race is ``jeffcott_balls`` (the stick-slip
law, events and modes there: :mod:`rotorlab._kernels.jeffcott_balls`), whose friction f on a
race of radius l bounds the race's torque by ``f l N``; in the machine that bound is
``(coulomb l + rolling) N``, so a ball with ``coulomb = f / 2, rolling = f l / 2`` is the same
ball. The energy identity (drive work = change of T + V + dissipated energy, friction included)
follows from Lagrange's equations with the friction torques as non-conservative forces.
"""

import numpy as np
import pytest

from rotorlab.integrate import SaveAt, StepControl, solve, solve_ensemble
from rotorlab.models import (
    Ball,
    BallParams,
    BallRace,
    ConstantSpeed,
    Gravity,
    JeffcottBalls,
    LinearRamp,
    Machine,
    Motor,
    RotorParams,
    Unbalance,
)
from test_machine import BC, BL, BM, DAMP, ECC, M1, STIFF, from_machine, planar_structure, rigid_two_plane, to_machine


def planar_pair(speed, f, n_modes=2):
    """The same rotor as ``machine`` (friction split between Coulomb and rolling on the second
    ball) and as ``jeffcott_balls`` with friction f on both balls."""
    balls = (Ball(BM, inertia=1e-3, damping=BC, coulomb=f),
             Ball(1.1 * BM, damping=0.9 * BC, coulomb=0.5 * f, rolling=0.5 * f * BL))
    mac = Machine(planar_structure(), races=(BallRace(0, BL, balls),),
                  unbalances=(Unbalance(0, M1 * ECC),), drive=speed, n_modes=n_modes)
    jb = JeffcottBalls(RotorParams(M1, ECC, STIFF, DAMP),
                       (BallParams(BM, BL, BM * BL**2 + 1e-3, BC, f), BallParams(1.1 * BM, BL, None, 0.9 * BC, f)),
                       speed=speed)
    return mac, jb


@pytest.mark.parametrize("modes", [(1.0, -1.0), (0.0, 1.0), (-1.0, 0.0), (0.0, 0.0)])
def test_planar_machine_with_friction_is_jeffcott_balls_rhs(modes):
    mac, jb = planar_pair(LinearRamp(0.5, 3.0, 10.0), 0.3)
    assert mac.state_names[-2:] == ("mode_1_1", "mode_1_2")
    rng = np.random.default_rng(11)
    for _ in range(20):
        t = rng.uniform(0.0, 20.0)
        yj = rng.normal(size=10)
        yj[8:] = modes
        om = jb.spin(t)[1]
        yj[6:8][np.array(modes) == 0.0] = om  # a stuck ball moves with its race
        fm = from_machine(mac, mac.rhs(t, to_machine(mac, yj)))
        fj = jb.rhs(t, yj)
        np.testing.assert_allclose(fm, fj, rtol=0, atol=1e-12 * np.abs(fj).max())
        # the event functions too (stick: relative speed; slip: bound - |driving torque|)
        gm, gj = np.empty(4), np.empty(4)
        mac.kernels.events(t, to_machine(mac, yj), mac.to_array(), gm)
        jb.kernels.events(t, yj, jb.to_array(), gj)
        np.testing.assert_allclose(gm, gj, rtol=0, atol=1e-12 * max(1.0, np.abs(gj).max()))


def test_planar_machine_with_friction_is_jeffcott_balls_trajectory():
    """A run-down through stick, slip and stick again: same states, same event counts."""
    mac, jb = planar_pair(LinearRamp(1.5, 0.5, 10.0), 0.1)
    yj0 = jb.initial_state([0.3, 2.0])
    ym0 = mac.initial_state([0.3, 2.0])
    np.testing.assert_allclose(from_machine(mac, ym0), yj0, atol=1e-15)  # the same initial modes
    ctl = StepControl(rtol=1e-10, atol=1e-12)
    sj = solve(jb, yj0, (0.0, 20.0), control=ctl)
    sm = solve(mac, ym0, (0.0, 20.0), control=ctl)
    assert sj.success and sm.success
    counts_j = {k: v for k, v in sj.event_counts.items()}
    counts_m = {k.replace("_1_", "_"): v for k, v in sm.event_counts.items()}
    assert counts_m == counts_j
    assert counts_j["slip_1"] >= 1 and counts_j["stick_1"] >= 2  # the run visits every transition
    np.testing.assert_allclose(from_machine(mac, sm.y_final), sj.y_final, rtol=0, atol=1e-7)


def with_friction(mac, coulomb, rolling_fraction=0.2):
    races = tuple(BallRace(r.node, r.radius, tuple(
        Ball(b.mass, b.inertia, b.damping, coulomb=coulomb, rolling=rolling_fraction * coulomb * r.radius)
        for b in r.balls), axial_offset=r.axial_offset) for r in mac.races)
    return Machine(mac.structure, races=races, unbalances=mac.unbalances, gravity=mac.gravity,
                   drive=mac.drive, energy_states=True)


@pytest.mark.parametrize("drive", [ConstantSpeed(1.3), Motor(0.4, polar_inertia=0.6, no_load_speed=2.0)])
def test_power_balance_with_friction(drive):
    """Two tilting races under gravity, the balls sticking and slipping: drive work = change of
    T + V + dissipated energy (viscous and friction) to 1e-6 of the work."""
    mac = with_friction(rigid_two_plane(motor=drive, gravity=Gravity((0.0, -0.2, -9.8))), 0.2)
    y0 = mac.initial_state([0.1, 2.0, 4.0, 5.0], ball_rates=[0.3, -0.2, 0.0, 0.1], spin_speed=0.1)
    ts = np.linspace(0.0, 25.0, 26)
    sol = solve(mac, y0, (0.0, 25.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-13))
    assert sol.success
    assert all(sol.event_counts[f"{k}_{b}"] >= 1 for k in ("stick", "slip") for b in ("1_1", "2_2"))
    ie = mac.layout.i_energy
    work = np.abs(sol.ys[:, ie]).max()
    assert work > 1e-2
    res = mac.energy_balance(sol.ts, sol.ys)
    assert np.abs(res).max() < 1e-6 * work


def test_lanes_with_friction_give_the_scalar_numbers():
    """Stick/slip events on the lane driver: the same numbers as the scalar driver."""
    from rotorlab.integrate._drivers import is_vectorised

    mac, _ = planar_pair(ConstantSpeed(2.5), 0.1)  # (a ramp's kernel runs scalar, friction or not)
    assert mac.kernels.vectorises and is_vectorised(mac.kernels, lanes=8)
    rng = np.random.default_rng(0)
    y0 = np.array([mac.initial_state(a, ball_rates=r) for a, r in
                   zip(rng.uniform(0, 2 * np.pi, (5, 2)), rng.uniform(-1.0, 1.0, (5, 2)))])
    a = solve_ensemble(mac, y0, (0.0, 12.0), threads=1, lanes=None)
    b = solve_ensemble(mac, y0, (0.0, 12.0), threads=1, lanes=8)
    np.testing.assert_allclose(b.y_final, a.y_final, rtol=0, atol=1e-9)
    assert np.all(np.asarray(a.status) == 0)
    assert np.all(y0[:, -2:] != 0.0) and np.any(a.y_final[:, -2:] == 0.0)  # slipping balls stuck


def test_friction_has_no_co_rotating_equilibria_and_no_clearance_together():
    mac, _ = planar_pair(ConstantSpeed(2.5), 0.1)
    assert not mac.has_rotating_frame
    assert "friction" in mac.why_no_rotating_frame()
    from rotorlab.models import Clearance, ElasticStator

    with pytest.raises(ValueError, match="ball friction .* together with a clearance"):
        Machine(mac.structure, races=mac.races, unbalances=mac.unbalances, drive=mac.drive,
                clearances=(Clearance(0, 1.0, ElasticStator(10.0)),))
