"""The clearance of the composed machine when other bodies share the contact: balls in a race and
a motor (their inertia enters the Delassus matrix of every impact and every sustained contact),
and a moving housing (Crandall 1990).

Invariants: the kinetic energy of a body with a constant mass matrix changes under an impulse
``P`` by ``P . (v- + v+) / 2`` (Stronge, *Impact Mechanics*, 2000, ch. 5), so e = 1 without
friction conserves the energy exactly and e = 1 with friction loses exactly the friction work,
whatever the bodies; a housing of mass m_s on k_s struck rigidly by a rotor rolling on it whirls at
``-(R_r / delta) Omega`` with the radius of :func:`rotorlab.contact.rolling_whirl`, and past the
coupled backward natural frequency, where no rolling whirl exists, locks there: dry whip.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab.contact import RubRotor, dry_whip_frequency, rolling_whirl
from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed
from rotorlab.models._machine import Ball, BallRace, Clearance, ElasticStator, Machine, Motor, Unbalance

TIGHT = StepControl(rtol=1e-10, atol=1e-13)


def _structure(m: float, k: float) -> LinearSystem:
    return LinearSystem(M=np.diag([m, m, 1e-3, 1e-3]), C=np.zeros((4, 4)), G=np.zeros((4, 4)),
                        K=np.diag([k, k, 1.0, 1.0]))  # fmt: skip


def _balls_and_motor(friction: float) -> Machine:
    """2 kg on 2 kN/m (5 Hz) with two free 50 g balls at 40 mm, a motor, 1 mm rigid clearance."""
    k = 2.0 * (2 * math.pi * 5.0) ** 2
    race = BallRace(0, 0.04, (Ball(0.05), Ball(0.05)))
    motor = Motor(torque=2.0, polar_inertia=0.01, no_load_speed=40.0)
    cl = Clearance(0, 1e-3, restitution=1.0, friction=friction, rotor_radius=0.05)
    return Machine(_structure(2.0, k), races=(race,), unbalances=(Unbalance(0, 1e-4),),
                   drive=motor, energy_states=True, clearances=(cl,))  # fmt: skip


def _balance(m: Machine, y0, y) -> tuple[float, float]:
    """(energy gained, motor work - machine dissipation + contact drive work - contact dissipation)."""
    ie = m.layout.i_energy
    return m.energy(y) - m.energy(y0), y[ie] - y[ie + 1] + y[-4] - y[-5]


@pytest.mark.parametrize("friction", [0.0, 0.3])
def test_impacts_shared_with_balls_and_a_motor_keep_the_energy_balance(friction):
    m = _balls_and_motor(friction)
    y0 = m.initial_state(ball_angles=[0.3, 2.0], ball_rates=[5.0, -3.0], spin_speed=20.0,
                         z=[5e-4, 0.0, 0.0, 0.0], dz=[0.0, 0.05, 0.0, 0.0])  # fmt: skip
    sol = solve(m, y0, (0.0, 5.0), control=TIGHT, max_events_recorded=10)
    assert sol.status.name == "SUCCESS", sol.status.message
    y = sol.y_final
    assert y[-3] > 50  # impacts
    gain, sources = _balance(m, y0, y)
    assert gain == pytest.approx(sources, abs=1e-7 * m.energy(y0))
    if friction == 0.0:
        # an elastic frictionless impact dissipates nothing (to round-off: the races tilt with
        # the structure, and the balls' axial unknowns enter every Delassus solve)
        assert abs(y[-5]) < 1e-15 * m.energy(y0)
    else:
        assert y[-5] > 1e-3 * m.energy(y0)  # friction worked, and the balance still closes


def test_a_moving_housing_struck_by_a_rolling_rotor_whirls_on_the_closed_form_orbit():
    p = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, stator_stiffness=50.0, stator_mass=0.5,
                 friction=1.0, rotor_radius=0.1)  # fmt: skip
    w = 0.3
    wh = rolling_whirl(p, w)
    assert wh.whirl_speed == pytest.approx(-p.rotor_radius / p.clearance * w, rel=1e-12)
    cl = Clearance(0, p.clearance, ElasticStator(p.stator_stiffness, 0.0, p.stator_mass),
                   friction=p.friction, rotor_radius=p.rotor_radius)  # fmt: skip
    m = Machine(_structure(p.mass, p.stiffness), unbalances=(Unbalance(0, 0.0),),
                drive=ConstantSpeed(w), clearances=(cl,))  # fmt: skip
    om, r = wh.whirl_speed, wh.radius
    s = r - p.clearance
    y0 = m.initial_state(z=[r, 0.0, 0.0, 0.0], dz=[0.0, om * r, 0.0, 0.0], housing=[s, 0.0, 0.0, om * s])
    ih = m.layout.i_clearance
    y0[-1] = 2.0  # rolling
    ts = np.linspace(0.0, 20.0, 401)
    sol = solve(m, y0, (0.0, 20.0), control=TIGHT, save_at=SaveAt(ts=ts))
    assert sol.status.name == "SUCCESS", sol.status.message
    assert sum(sol.event_counts.values()) == 0 and np.all(sol.ys[:, -1] == 2.0)
    z = sol.ys[:, 0] + 1j * sol.ys[:, 1]
    h = sol.ys[:, ih] + 1j * sol.ys[:, ih + 1]
    assert np.allclose(np.abs(z), r, rtol=1e-7)
    assert np.allclose(np.abs(h), r - p.clearance, rtol=1e-6)
    assert np.allclose(np.abs(z - h), p.clearance, rtol=1e-9)
    assert np.allclose(np.unwrap(np.angle(z)), om * ts, atol=1e-6)


def test_past_the_coupled_frequency_the_whirl_locks_there_dry_whip():
    p = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, stator_stiffness=50.0, stator_mass=0.5,
                 friction=0.3, rotor_radius=0.1)  # fmt: skip
    w = 3.0  # rolling would need -(R/delta) Omega = -30 rad/s, far past sqrt((k + k_s) / (m + m_s))
    assert rolling_whirl(p, w) is None
    cl = Clearance(0, p.clearance, ElasticStator(p.stator_stiffness, 0.0, p.stator_mass),
                   friction=p.friction, rotor_radius=p.rotor_radius)  # fmt: skip
    m = Machine(_structure(p.mass, p.stiffness), unbalances=(Unbalance(0, 0.0),),
                drive=ConstantSpeed(w), clearances=(cl,))  # fmt: skip
    ts = np.linspace(20.0, 40.0, 2001)
    sol = solve(m, m.initial_state(z=[0.009, 0.0, 0.0, 0.0], dz=[0.05, -0.05, 0.0, 0.0]), (0.0, 40.0),
                control=TIGHT, save_at=SaveAt(ts=ts))  # fmt: skip
    assert sol.status.name == "SUCCESS", sol.status.message
    assert np.all(sol.ys[:, -1] != 0.0)  # permanent contact
    z = sol.ys[:, 0] + 1j * sol.ys[:, 1]
    whirl = np.polyfit(ts, np.unwrap(np.angle(z)), 1)[0]
    assert whirl == pytest.approx(-dry_whip_frequency(p), rel=1e-3)


def test_elastic_frictionless_impacts_on_a_moving_housing_conserve_the_energy_of_both():
    cl = Clearance(0, 1e-3, ElasticStator(500.0, 0.0, 0.5), restitution=1.0)
    m = Machine(_structure(2.0, 2.0 * (2 * math.pi * 5.0) ** 2), unbalances=(Unbalance(0, 0.0),),
                drive=ConstantSpeed(30.0), clearances=(cl,))  # fmt: skip
    y0 = m.initial_state(z=[5e-4, 0.0, 0.0, 0.0], dz=[0.0, 0.05, 0.0, 0.0])
    sol = solve(m, y0, (0.0, 20.0), control=TIGHT, max_events_recorded=10)
    assert sol.status.name == "SUCCESS", sol.status.message
    y = sol.y_final
    ih = m.layout.i_clearance
    assert y[-3] > 100 and np.hypot(y[ih], y[ih + 1]) > 1e-5  # the housing was knocked about
    assert abs(m.energy(y) - m.energy(y0)) < 1e-6 * m.energy(y0)


def test_a_conical_gap_combines_translation_and_tilt():
    cl = Clearance(0, 1e-3, conical=(math.radians(30.0), 0.2))
    m = Machine(_structure(1.0, 1.0), unbalances=(Unbalance(0, 0.0),), drive=ConstantSpeed(1.0),
                clearances=(cl,))  # fmt: skip
    y = m.initial_state(z=[1e-4, 2e-4, -1e-3, 3e-3])
    assert np.allclose(m.gap_vector(y), [0.5 * 1e-4 + 0.2 * -1e-3, 0.5 * 2e-4 + 0.2 * 3e-3], rtol=1e-14)
    with pytest.raises(ValueError, match=r"outside the rigid stator"):
        m.initial_state(z=[3e-3, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"Clearance.conical\[0\] must be in \(0, pi/2\]"):
        replace(cl, conical=(2.0, 0.1))
