"""``jeffcott_balls`` is a preset of the machine (issue 24, item 3).

The oracle is the model's own hand-written kernel (:mod:`rotorlab._kernels.jeffcott_balls`, itself
checked against Zhakash et al. 2024 eqs. (1)-(3) and Filimonikhin & Filimonikhina in
tests/validation): the preset machine must give its right-hand side, its stick/slip event
functions and its energy to 1e-12 at random states, with and without ball friction, under every
speed profile the model takes. The energies differ by exactly the disc's spin energy about its
centre, ``1/2 M1 e^2 Omega^2``, which jeffcott_balls counts (``1/2 M1 |v_C|^2``) and the machine
leaves with the prescribed spin (module docstring of :mod:`rotorlab.models._machine`).
"""

import numpy as np
import pytest

from rotorlab._kernels import jeffcott_balls as oracle
from rotorlab.continuation import as_machine
from rotorlab.models import BallParams, ConstantSpeed, HillRunUp, JeffcottBalls, LinearRamp, RotorParams

M1, ECC, STIFF, DAMP = 0.96, 0.012, 1.3, 0.02
SPEEDS = [ConstantSpeed(2.5), LinearRamp(0.5, 3.0, 10.0), HillRunUp(2.5, 8.0, 3.0)]


def rotor(speed, friction=0.0):
    """Two unequal balls (one with its own inertia), friction ``friction`` on both."""
    balls = (BallParams(0.02, 0.9, 0.02 * 0.81 + 1e-3, 0.01, friction), BallParams(0.022, 0.9, None, 0.009, friction))
    return JeffcottBalls(RotorParams(M1, ECC, STIFF, DAMP), balls, speed=speed)


def oracle_rhs(jb, t, y):
    out = np.empty_like(y)
    oracle.rhs_fixed(t, y, jb.to_array(), out)
    return out


def random_states(jb, seed, n=25, t_max=20.0, modes=None):
    """Random times and states; with ``modes`` the friction modes, a stuck ball at the race's speed."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        t = rng.uniform(0.0, t_max)
        y = rng.normal(size=jb.n_state)
        if modes is not None:
            y[8:] = modes
            y[6:8][np.array(modes) == 0.0] = jb.spin(t)[1]
        yield t, y


@pytest.mark.parametrize("speed", SPEEDS, ids=["constant", "ramp", "hill"])
def test_preset_machine_has_the_rhs_and_energy_of_jeffcott_balls(speed):
    jb = rotor(speed)
    mac = jb.machine
    assert mac.state_names[:4] == ("q_1", "q_2", "dq_1", "dq_2") and mac.n_state == jb.n_state == 8
    np.testing.assert_array_equal(mac.basis[:2], np.eye(2))  # coordinates are x, y themselves
    for t, y in random_states(jb, seed=3):
        fj = oracle_rhs(jb, t, y)
        np.testing.assert_allclose(mac.rhs(t, y), fj, rtol=0, atol=1e-12 * np.abs(fj).max())
        om = jb.spin(t)[1]
        e_j = float(jb.energy(t, y))
        assert mac.energy(y, t) + 0.5 * M1 * ECC**2 * om**2 == pytest.approx(e_j, rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("speed", SPEEDS, ids=["constant", "ramp", "hill"])
def test_preset_machine_with_friction_has_the_rhs_events_and_energy_of_jeffcott_balls(speed):
    jb = rotor(speed, friction=0.2)
    mac = jb.machine
    assert mac.has_friction and [b.coulomb for b in mac.races[0].balls] == [0.2, 0.2]
    p = jb.to_array()
    for k, modes in enumerate([(1.0, -1.0), (0.0, 1.0), (-1.0, 0.0), (0.0, 0.0)]):
        for t, y in random_states(jb, seed=10 + k, n=8, modes=modes):
            om = jb.spin(t)[1]
            # a stuck ball turns with its race whatever rate the state holds (phi' = Omega exactly)
            y_any = y.copy()
            y_any[6:8] += np.where(np.array(modes) == 0.0, 0.7, 0.0)
            for yy in (y, y_any):
                fj = np.empty(10)
                oracle.rhs_fixed(t, yy, p, fj)
                np.testing.assert_allclose(mac.rhs(t, yy), fj, rtol=0, atol=1e-12 * np.abs(fj).max())
                gm, gj = np.empty(4), np.empty(4)
                mac.kernels.events(t, yy, mac.to_array(), gm)
                oracle.events_fixed(t, yy, p, gj)
                np.testing.assert_allclose(gm, gj, rtol=0, atol=1e-12 * max(1.0, np.abs(gj).max()))
            assert mac.energy(y, t) + 0.5 * M1 * ECC**2 * om**2 == pytest.approx(float(jb.energy(t, y)), rel=1e-12)


def test_continuation_machine_is_the_preset_without_friction():
    """``continuation.as_machine`` is the preset with the balls' friction stripped: the same
    structure, balls and drive, no modes in the state, and the frictionless model's right-hand side."""
    jb = rotor(ConstantSpeed(2.5), friction=0.2)
    smooth = as_machine(jb)
    assert not smooth.has_friction and smooth.n_state == 8
    assert smooth.structure is jb.machine.structure and smooth.drive == jb.speed
    free = rotor(ConstantSpeed(2.5))
    assert smooth.races == free.machine.races
    for t, y in random_states(free, seed=5, n=5):
        np.testing.assert_allclose(smooth.rhs(t, y), free.machine.rhs(t, y), rtol=0, atol=1e-15)


def test_balls_on_different_radii_keep_their_order():
    """Balls on two radii, interleaved: a race per run of equal radii, the model's ball order."""
    balls = (BallParams(0.02, 0.9, None, 0.01), BallParams(0.03, 1.1, None, 0.01), BallParams(0.02, 0.9, None, 0.01))
    jb = JeffcottBalls(RotorParams(M1, ECC, STIFF, DAMP), balls, speed=ConstantSpeed(2.0))
    mac = jb.machine
    assert [r.radius for r in mac.races] == [0.9, 1.1, 0.9] and mac.n_state == jb.n_state == 10
    for t, y in random_states(jb, seed=1, n=5):
        fj = oracle_rhs(jb, t, y)
        np.testing.assert_allclose(mac.rhs(t, y), fj, rtol=0, atol=1e-12 * np.abs(fj).max())


# ---- the co-rotating frame: the preset machine's generated co-rotating kernel (issue 24, item 3)
def rotating_rotor(speed, friction=0.0):
    return rotor(speed, friction).with_frame("rotating")


@pytest.mark.parametrize("speed", SPEEDS, ids=["constant", "ramp", "hill"])
def test_rotating_frame_runs_the_preset_machines_corotating_kernel_with_the_rhs_and_energy_of_jeffcott_balls(speed):
    """``frame="rotating"`` integrates on :attr:`Machine.rotating_kernels` (not on the hand-written
    kernels, the oracle here): the same right-hand side as ``rhs_rotating`` to 1e-12, and the
    machine's energy of the state turned into the fixed frame is the model's (plus the disc's spin
    energy, module docstring)."""
    jb = rotating_rotor(speed)
    mac = jb.machine
    assert jb.kernels.rhs is mac.rotating_kernels.rhs
    assert jb.kernels.rhs.py_func.__module__.startswith("_rotorlab_machine_")
    p, po = jb.to_array(), jb.to_array()[: 12 + 6 * jb.n_balls]
    for t, y in random_states(jb, seed=4):
        fj = np.empty_like(y)
        oracle.rhs_rotating(t, y, po, fj)
        np.testing.assert_allclose(jb.rhs(t, y), fj, rtol=0, atol=1e-12 * np.abs(fj).max())
        om = jb.spin(t)[1]
        yf = mac.to_frame(t, y, "fixed")
        np.testing.assert_allclose(yf, jb.to_frame(t, y, "fixed"), rtol=0, atol=1e-14 * np.abs(yf).max())
        np.testing.assert_allclose(mac.to_frame(t, yf, "rotating"), y, rtol=0, atol=1e-13 * np.abs(y).max())
        e_j = float(jb.energy(t, y))
        assert mac.energy(yf, t) + 0.5 * M1 * ECC**2 * om**2 == pytest.approx(e_j, rel=1e-12, abs=1e-12)
    fm = np.empty(8)
    jb.kernels.rhs(1.0, np.zeros(8), p, fm)
    assert np.abs(fm).max() > 0  # not a kernel that ignores the state


@pytest.mark.parametrize("speed", SPEEDS, ids=["constant", "ramp", "hill"])
def test_rotating_frame_with_friction_has_the_rhs_events_resets_and_energy_of_jeffcott_balls(speed):
    jb = rotating_rotor(speed, friction=0.2)
    mac = jb.machine
    k = jb.kernels
    assert k.rhs is mac.rotating_kernels.rhs and k.events is mac.rotating_kernels.events
    assert [e.name for e in k.event_specs] == ["stick_1", "slip_1", "stick_2", "slip_2"]
    p, po = jb.to_array(), jb.to_array()[: 12 + 6 * jb.n_balls]
    for j, modes in enumerate([(1.0, -1.0), (0.0, 1.0), (-1.0, 0.0), (0.0, 0.0)]):
        for t, y in random_states(jb, seed=20 + j, n=8, t_max=20.0):
            y[8:] = modes
            y[6:8][np.array(modes) == 0.0] = 0.0  # a stuck ball turns with the frame
            y_any = y.copy()  # and whatever rate the state holds, it moves with its race
            y_any[6:8] += np.where(np.array(modes) == 0.0, 0.7, 0.0)
            for yy in (y, y_any):
                fj, fm = np.empty(10), np.empty(10)
                oracle.rhs_rotating(t, yy, po, fj)
                k.rhs(t, yy, p, fm)
                np.testing.assert_allclose(fm, fj, rtol=0, atol=1e-12 * np.abs(fj).max())
                gm, gj = np.empty(4), np.empty(4)
                k.events(t, yy, p, gm)
                oracle.events_rotating(t, yy, po, gj)
                np.testing.assert_allclose(gm, gj, rtol=0, atol=1e-12 * max(1.0, np.abs(gj).max()))
                for ev in range(4):
                    rm, rj = np.empty(10), np.empty(10)
                    k.reset(ev, t, yy, p, rm)
                    oracle.reset_rotating(ev, t, yy, po, rj)
                    np.testing.assert_allclose(rm, rj, rtol=0, atol=1e-12 * np.abs(rj).max())
            om = jb.spin(t)[1]
            yf = mac.to_frame(t, y, "fixed")
            assert mac.energy(yf, t) + 0.5 * M1 * ECC**2 * om**2 == pytest.approx(float(jb.energy(t, y)), rel=1e-12)
