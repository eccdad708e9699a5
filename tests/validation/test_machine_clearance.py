"""The clearance attachment of the composed machine against the closed forms of
:mod:`rotorlab.contact`, exact invariants, and the reference model :class:`JeffcottRub`.

Sources as in ``test_contact_theory.py``: Black (1968) and Choy & Padovan (1987) for the
synchronous full rub, Crandall (1990) for the rolling backward whirl and the moving housing;
Stronge, *Impact Mechanics* (2000) for the energy of an impulse. The machine here is the Jeffcott
rotor as a one-node structure (x, y and two decoupled tilts), so that every closed form applies;
``test_machine_clearance_balls.py`` checks the same law on a machine whose balls share the impacts.
All machines of a stator kind share one layout (an unbalance of 0 keeps it) so that they compile once.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab.contact import (
    JeffcottRub,
    RubRotor,
    chatter_time,
    full_rub,
    grazing_speeds,
    no_rub_radius,
    rolling_whirl,
)
from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed
from rotorlab.models._machine import Clearance, ElasticStator, Gravity, Machine, Unbalance

TIGHT = StepControl(rtol=1e-10, atol=1e-13)
BILLIARD = RubRotor(mass=2.0, stiffness=2.0 * (2 * math.pi * 5.0) ** 2, clearance=1e-3, rotor_radius=0.05)
RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0)
ROLL = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.05, stator_stiffness=100.0,
                friction=0.3, rotor_radius=0.1)  # fmt: skip
X, Y, VX, VY = 0, 1, 4, 5  # state indices of the rotor centre in the one-node machine


def jeffcott_machine(p: RubRotor, speed: float, restitution: float = 0.5) -> Machine:
    """The Jeffcott rotor ``p`` as a one-node machine with a clearance at its node."""
    s = LinearSystem(M=np.diag([p.mass, p.mass, 1.0, 1.0]), C=np.diag([p.damping, p.damping, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([p.stiffness, p.stiffness, 1.0, 1.0]))  # fmt: skip
    stator = "rigid" if p.rigid_stator else ElasticStator(p.stator_stiffness, p.stator_damping)
    cl = Clearance(0, p.clearance, stator, restitution=restitution, friction=p.friction,
                   rotor_radius=p.rotor_radius)  # fmt: skip
    return Machine(s, unbalances=(Unbalance(0, p.mass * p.eccentricity),), drive=ConstantSpeed(speed),
                   clearances=(cl,))  # fmt: skip


def _state(m: Machine, pos=(0.0, 0.0), vel=(0.0, 0.0)) -> np.ndarray:
    return m.initial_state(z=[pos[0], pos[1], 0.0, 0.0], dz=[vel[0], vel[1], 0.0, 0.0])


def _run(model, y0, t_end, ts=None):
    sol = solve(model, y0, (0.0, t_end), control=TIGHT, save_at=SaveAt(ts=ts), max_events_recorded=100)
    assert sol.status.name == "SUCCESS", sol.status.message
    return sol


# ---- the machine reduced to the Jeffcott rotor is JeffcottRub -----------------------------------


@pytest.mark.parametrize("p, e", [
    (replace(RUB, stator_stiffness=math.inf, friction=0.2, rotor_radius=0.5), 0.7),  # impacts, chatter, sliding
    (replace(RUB, friction=0.02), 0.5),  # elastic stator: contact onsets, lift-offs
])  # fmt: skip
def test_the_jeffcott_machine_follows_the_reference_rub_model(p, e):
    w = 1.5
    ref, m = JeffcottRub(p, w, restitution=e), jeffcott_machine(p, w, e)
    ts = np.linspace(0.0, 40.0, 41)
    a = _run(ref, ref.initial_state(), 40.0, ts)
    b = _run(m, _state(m), 40.0, ts)
    assert a.event_counts == b.event_counts and a.event_counts["contact"] > 3
    assert np.allclose(a.ys[:, :4], b.ys[:, [X, Y, VX, VY]], rtol=0.0, atol=1e-7 * p.clearance)
    # dissipated, drive work, impacts, peak impulse, mode
    assert np.allclose(a.y_final[4:], b.y_final[-5:], rtol=1e-7)


# ---- energy over thousands of impacts ----------------------------------------------------------


def test_elastic_frictionless_impacts_conserve_energy_on_the_machine():
    m = jeffcott_machine(BILLIARD, 30.0, restitution=1.0)
    y0 = _state(m, (5e-4, 0.0), (0.0, 0.05))
    y = _run(m, y0, 100.0).y_final
    assert y[-3] > 2000  # impacts
    assert abs(m.energy(y) - m.energy(y0)) < 1e-6 * m.energy(y0)
    assert y[-5] == 0.0 and y[-4] == 0.0  # nothing dissipated, no drive work
    assert math.hypot(y[X], y[Y]) <= BILLIARD.clearance * (1 + 1e-12)


def test_elastic_impacts_with_friction_lose_exactly_the_friction_work_on_the_machine():
    """With the spin held by a drive, friction pumps a backward whirl; over thousands of impacts the
    energy gained is exactly the drive work minus the friction work (Stronge's split)."""
    m = jeffcott_machine(replace(BILLIARD, friction=0.3), 5.0, restitution=1.0)
    y0 = _state(m, (5e-4, 0.0), (0.0, 0.05))
    y = _run(m, y0, 20.0).y_final
    assert y[-3] > 5000 and y[-5] > 0.0 and y[-4] > y[-5]
    gain = m.energy(y) - m.energy(y0)
    assert gain == pytest.approx(y[-4] - y[-5], rel=1e-7)
    assert gain > 10 * m.energy(y0)


# ---- chatter: accumulation into sustained contact -----------------------------------------------


def test_chatter_accumulates_at_the_nordmark_piiroinen_time_then_rests_on_the_stator():
    e, g, h0 = 0.8, 10.0, 1e-6
    rot = RubRotor(mass=1.0, stiffness=1.0, clearance=1e-3)
    m = replace(jeffcott_machine(rot, 0.0, restitution=e), gravity=Gravity((g, 0.0, 0.0)))
    y0 = _state(m, (rot.clearance - h0, 0.0))
    sol = solve(m, y0, (0.0, 0.05), control=TIGHT, save_at=SaveAt(ts=np.linspace(0.01, 0.05, 5)),
                max_events_recorded=1000)  # fmt: skip
    assert sol.status.name == "SUCCESS", sol.status.message
    a = g - rot.stiffness * rot.clearance / rot.mass  # pressing acceleration at the stator
    v0 = math.sqrt(2 * (g * h0 - 0.5 * (rot.clearance**2 - (rot.clearance - h0) ** 2)))
    t_inf = sol.event_times[0] + chatter_time(v0, a, e)
    skipped = 2 * m.clearances[0].rest_speed / (a * (1 - e))
    assert t_inf - skipped <= sol.event_times[-1] <= t_inf * (1 + 1e-6)
    # impacts until the rebound speed e^j v0 of the j-th falls below rest_speed
    assert len(sol.event_times) == math.ceil(math.log(m.clearances[0].rest_speed / v0) / math.log(e))
    assert np.all(sol.ys[:, -1] == -1.0)  # sustained contact (sliding mode, no friction), never lifts off
    assert np.allclose(sol.ys[:, X], rot.clearance, rtol=1e-9) and np.allclose(sol.ys[:, VX], 0.0, atol=1e-12)


# ---- grazing, full rub, rolling whirl (elastic stator) -------------------------------------------


@pytest.mark.parametrize("fac, touches", [(0.999, False), (1.001, True)])
def test_contact_begins_where_the_no_rub_orbit_reaches_the_clearance(fac, touches):
    p = replace(RUB, eccentricity=0.3)
    w = fac * grazing_speeds(p)[0]
    z0 = no_rub_radius(p, w) * np.exp(-1j * np.angle(complex(p.stiffness - w * w, p.damping * w)))
    v0 = 1j * w * z0
    m = jeffcott_machine(p, w)
    sol = _run(m, _state(m, (z0.real, z0.imag), (v0.real, v0.imag)), 20.0)
    assert (sol.event_counts["contact"] > 0) is touches


def test_full_annular_rub_lands_on_the_closed_form_branch():
    w = 1.5
    p = replace(RUB, friction=0.02)  # below the critical friction 0.0484 of this case
    (branch,) = full_rub(p, w)
    m = jeffcott_machine(p, w)
    ts = np.linspace(550.0, 600.0, 101)
    sol = _run(m, _state(m), 600.0, ts)
    z = sol.ys[:, X] + 1j * sol.ys[:, Y]
    assert np.allclose(np.abs(z), branch.radius, rtol=1e-5)
    assert np.allclose(np.angle(np.exp(1j * w * ts) / z), branch.phase, atol=1e-4)
    assert np.all(sol.ys[:, -1] == 1.0)  # sliding forward


def test_backward_whirl_rolls_at_minus_r_over_delta_omega_corrected_for_compliance():
    w = 0.3
    wh = rolling_whirl(ROLL, w)
    m = jeffcott_machine(ROLL, w)
    z0 = 1.01 * ROLL.clearance
    ts = np.linspace(40.0, 60.0, 1001)
    sol = _run(m, _state(m, (z0, 0.0), (0.0, -2.5 * z0)), 60.0, ts)
    assert np.all(sol.ys[:, -1] == 2.0)  # rolling
    z = sol.ys[:, X] + 1j * sol.ys[:, Y]
    whirl = np.polyfit(ts, np.unwrap(np.angle(z)), 1)[0]
    assert whirl == pytest.approx(wh.whirl_speed, rel=1e-4)
    assert abs(whirl / (-ROLL.rotor_radius / ROLL.clearance * w) - 1) > 0.05  # the correction matters
    assert np.abs(z).mean() == pytest.approx(wh.radius, rel=1e-4)


# ---- input ---------------------------------------------------------------------------------------


def test_bad_clearances_are_rejected_with_the_field_named():
    with pytest.raises(ValueError, match=r"Clearance.gap must be a finite number > 0 \(m\), got -1"):
        Clearance(0, -1)
    with pytest.raises(ValueError, match=r"Clearance.restitution must be in \[0, 1\], got 1.5"):
        Clearance(0, 1e-3, restitution=1.5)
    with pytest.raises(ValueError, match=r"Clearance.stator must be 'rigid' or an ElasticStator"):
        Clearance(0, 1e-3, stator="soft")
    m = jeffcott_machine(RUB, 1.0)
    with pytest.raises(ValueError, match=r"Machine.clearances\[0\].node must be < 1"):
        replace(m, clearances=(Clearance(3, 1e-3),))
    with pytest.raises(ValueError, match=r"at most one clearance"):
        replace(m, clearances=(Clearance(0, 1e-3), Clearance(0, 2e-3)))
