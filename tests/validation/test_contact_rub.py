"""The contact law in simulation (:class:`rotorlab.contact.JeffcottRub` on rotorlab's integrator)
against the closed forms of :mod:`rotorlab.contact` and exact invariants.

Sources as in ``test_contact_theory.py``: Black (1968) and Choy & Padovan (1987) for the
synchronous full rub and its friction instability, Crandall (1990) for the rolling backward whirl,
Nordmark & Piiroinen (2009) for complete chatter; Stronge, *Impact Mechanics* (2000) for the
energy of an impulse (``Delta T = P . (v- + v+) / 2``).
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
    critical_friction,
    friction_to_roll,
    full_rub,
    full_rub_jacobian,
    grazing_speeds,
    no_rub_radius,
    rolling_whirl,
    slipping_whip,
)
from rotorlab.integrate import SaveAt, StepControl, solve

TIGHT = StepControl(rtol=1e-10, atol=1e-13)
# 2 kg rotor at 5 Hz in a 1 mm clearance, no damping: a billiard in a harmonic well
BILLIARD = RubRotor(mass=2.0, stiffness=2.0 * (2 * math.pi * 5.0) ** 2, clearance=1e-3, rotor_radius=0.05)
RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0)
ROLL = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.05, stator_stiffness=100.0,
                friction=0.3, rotor_radius=0.1)  # fmt: skip


def _run(model, y0, t_end, ts=None):
    sol = solve(model, y0, (0.0, t_end), control=TIGHT, save_at=SaveAt(ts=ts), max_events_recorded=100)
    assert sol.status.name == "SUCCESS", sol.status.message
    return sol


# ---- energy over thousands of impacts ----------------------------------------------------------


def test_elastic_frictionless_impacts_conserve_energy():
    model = JeffcottRub(BILLIARD, spin_speed=30.0, restitution=1.0)
    y0 = model.initial_state((5e-4, 0.0), (0.0, 0.05))
    sol = _run(model, y0, 100.0)
    y = sol.y_final
    assert y[6] > 2000  # impacts
    # 500 periods at rtol 1e-10: the integrator's own drift is ~2e-7; an impact law that lost or
    # made energy would show at 1 / 2500 per impact
    assert abs(model.energy(y) - model.energy(y0)) < 1e-6 * model.energy(y0)
    assert y[4] == 0.0 and y[5] == 0.0  # nothing dissipated, no drive work
    assert abs(math.hypot(y[0], y[1])) <= BILLIARD.clearance * (1 + 1e-12)


def test_elastic_impacts_with_friction_lose_exactly_the_angular_momentum_energy():
    """No spin: the friction impulses end the whirl; the orbit's angular momentum L = m x0 vy0 sets
    the tangential speed L / (m delta) at every contact, and the energy lost is 1/2 m (L/(m delta))^2
    whether the first impulse sticks (mu = 0.3) or several slip (mu = 0.05)."""
    for mu in (0.3, 0.05):
        model = JeffcottRub(replace(BILLIARD, friction=mu), spin_speed=0.0, restitution=1.0)
        y0 = model.initial_state((5e-4, 0.0), (0.0, 0.05))
        y = _run(model, y0, 20.0).y_final
        vt = 5e-4 * 0.05 / BILLIARD.clearance
        loss = 0.5 * BILLIARD.mass * vt * vt
        assert y[4] == pytest.approx(loss, rel=1e-9)  # the dissipated state: friction work only
        assert model.energy(y0) - model.energy(y) == pytest.approx(loss, rel=1e-6)


def test_elastic_impacts_with_friction_and_spin_balance_drive_work_and_friction_work():
    """With the spin held by a drive, friction pumps a backward whirl: over thousands of impacts the
    energy gained is exactly the drive work minus the friction work."""
    model = JeffcottRub(replace(BILLIARD, friction=0.3), spin_speed=5.0, restitution=1.0)
    y0 = model.initial_state((5e-4, 0.0), (0.0, 0.05))
    y = _run(model, y0, 20.0).y_final
    assert y[6] > 5000 and y[4] > 0.0 and y[5] > y[4]
    gain = model.energy(y) - model.energy(y0)
    assert gain == pytest.approx(y[5] - y[4], rel=1e-7)
    assert gain > 10 * model.energy(y0)


# ---- chatter: accumulation into sustained contact -----------------------------------------------


def test_chatter_accumulates_at_the_nordmark_piiroinen_time_then_rests_on_the_stator():
    e, g, h0 = 0.8, 10.0, 1e-6
    rot = RubRotor(mass=1.0, stiffness=1.0, clearance=1e-3)
    model = JeffcottRub(rot, spin_speed=0.0, restitution=e, rest_speed=1e-5, gravity=(g, 0.0))
    y0 = model.initial_state((rot.clearance - h0, 0.0))
    sol = solve(model, y0, (0.0, 0.05), control=TIGHT, save_at=SaveAt(ts=np.linspace(0.01, 0.05, 5)),
                max_events_recorded=1000)  # fmt: skip
    assert sol.status.name == "SUCCESS"
    a = g - rot.stiffness * rot.clearance / rot.mass  # pressing acceleration at the stator
    v0 = math.sqrt(2 * (g * h0 - 0.5 * (rot.clearance**2 - (rot.clearance - h0) ** 2)))
    t1 = sol.event_times[0]
    t_inf = t1 + chatter_time(v0, a, e)
    t_settle = sol.event_times[-1]  # the last impact: it put the rotor in sustained contact
    skipped = 2 * model.rest_speed / (a * (1 - e))
    assert t_inf - skipped <= t_settle <= t_inf * (1 + 1e-6)
    # impacts until the rebound speed e^j v0 of the j-th falls below rest_speed
    assert len(sol.event_times) == math.ceil(math.log(model.rest_speed / v0) / math.log(e))
    assert np.all(sol.ys[:, 8] == -1.0)  # sustained contact (sliding mode, no friction), never lifts off
    assert np.allclose(sol.ys[:, 0], rot.clearance, rtol=1e-9) and np.all(sol.ys[:, 2] == 0.0)


# ---- grazing onset -------------------------------------------------------------------------------


@pytest.mark.parametrize("fac, touches", [(0.999, False), (1.001, True)])
def test_contact_begins_where_the_no_rub_orbit_reaches_the_clearance(fac, touches):
    p = replace(RUB, eccentricity=0.3)
    w = fac * grazing_speeds(p)[0]
    z0 = no_rub_radius(p, w) * np.exp(-1j * np.angle(complex(p.stiffness - w * w, p.damping * w)))
    v0 = 1j * w * z0
    model = JeffcottRub(p, w)
    sol = _run(model, model.initial_state((z0.real, z0.imag), (v0.real, v0.imag)), 20.0)
    assert (sol.event_counts["contact"] > 0) is touches


# ---- synchronous full rub ------------------------------------------------------------------------


def test_full_rub_from_rest_lands_on_the_closed_form_branch():
    w = 1.5
    p = replace(RUB, friction=0.5 * critical_friction(RUB, w))
    assert no_rub_radius(p, w) > p.clearance  # no contact-free orbit at this speed
    (branch,) = full_rub(p, w)
    model = JeffcottRub(p, w)
    ts = np.linspace(550.0, 600.0, 201)
    sol = _run(model, model.initial_state(), 600.0, ts)
    rad = np.hypot(sol.ys[:, 0], sol.ys[:, 1])
    assert np.allclose(rad, branch.radius, rtol=1e-5)
    lag = np.angle(np.exp(1j * w * ts) / (sol.ys[:, 0] + 1j * sol.ys[:, 1]))
    assert np.allclose(lag, branch.phase, atol=1e-4)


def test_the_no_rub_orbit_and_the_full_rub_coexist_where_the_closed_form_says_so():
    """Below the fold and above the upper grazing speed (e = 0.3, Omega = 2) the closed form has
    the no-rub orbit inside the clearance and two full-rub branches, the upper one stable
    (frictionless), the lower a saddle (test_contact_theory.py). In simulation both attractors
    are reached: from rest the rotor never touches the stator (the transient stays below twice the
    orbit radius 0.40 < delta) and settles on the no-rub radius; started on the upper branch it
    stays there, pressing the stator, with the closed-form radius and phase."""
    w = 2.0
    p = replace(RUB, eccentricity=0.3)
    hi, lo = full_rub(p, w)
    r0 = no_rub_radius(p, w)
    assert r0 < p.clearance < lo.radius < hi.radius
    model = JeffcottRub(p, w)
    ts = np.linspace(280.0, 300.0, 81)
    rest = _run(model, model.initial_state(), 300.0, ts)
    assert rest.event_counts["contact"] == 0
    assert np.allclose(np.hypot(rest.ys[:, 0], rest.ys[:, 1]), r0, rtol=1e-5)  # transient: 0.4 exp(-0.05 t)
    z0 = hi.radius * np.exp(-1j * hi.phase)
    v0 = 1j * w * z0
    rub = _run(model, model.initial_state((z0.real, z0.imag), (v0.real, v0.imag)), 300.0, ts)
    assert rub.event_counts["lift_off"] == 0
    assert np.allclose(np.hypot(rub.ys[:, 0], rub.ys[:, 1]), hi.radius, rtol=1e-6)
    lag = np.angle(np.exp(1j * w * ts) / (rub.ys[:, 0] + 1j * rub.ys[:, 1]))
    assert np.allclose(lag, hi.phase, atol=1e-5)


@pytest.mark.parametrize("fac", [0.7, 1.4])
def test_full_rub_leaves_the_branch_at_the_growth_rate_above_critical_friction(fac):
    w = 1.5
    p = replace(RUB, friction=fac * critical_friction(RUB, w))
    b = full_rub(p, w)[0]
    lam, vec = np.linalg.eig(full_rub_jacobian(p, w, b.radius))
    i = int(np.argmax(lam.real))
    rot = np.exp(-1j * b.phase)
    d = 1e-5 * vec[:, i].real / np.abs(vec[:2, i]).max()
    z0 = rot * complex(b.radius + d[0], d[1])
    v0 = rot * complex(d[2], d[3]) + 1j * w * z0
    model = JeffcottRub(p, w)
    ts = np.linspace(0.0, 150.0, 6001)
    sol = _run(model, model.initial_state((z0.real, z0.imag), (v0.real, v0.imag)), 150.0, ts)
    assert sol.event_counts["lift_off"] == 0
    dev = np.abs((sol.ys[:, 0] + 1j * sol.ys[:, 1]) * np.exp(-1j * w * ts) - b.radius * rot)
    n_per = int(2 * math.pi / abs(lam[i].imag) / (ts[1] - ts[0])) + 1
    starts = range(0, len(ts) - n_per, n_per)
    peaks = np.array([dev[k : k + n_per].max() for k in starts])
    tp = np.array([ts[k + int(np.argmax(dev[k : k + n_per]))] for k in starts])
    rate = np.polyfit(tp[5:], np.log(peaks[5:]), 1)[0]
    assert rate == pytest.approx(lam[i].real, abs=0.1 * abs(lam[i].real))


# ---- dry-friction backward whirl ----------------------------------------------------------------


def test_backward_whirl_rolls_at_the_compliance_corrected_frequency():
    w = 0.3
    wh = rolling_whirl(ROLL, w)
    model = JeffcottRub(ROLL, w)
    z0 = 1.01 * ROLL.clearance
    ts = np.linspace(40.0, 60.0, 2001)
    sol = _run(model, model.initial_state((z0, 0.0), (0.0, -2.5 * z0)), 60.0, ts)
    assert sol.event_counts["stick"] >= 1 and np.all(sol.ys[:, 8] == 2.0)  # rolling
    z = sol.ys[:, 0] + 1j * sol.ys[:, 1]
    whirl = np.polyfit(ts, np.unwrap(np.angle(z)), 1)[0]
    assert whirl == pytest.approx(wh.whirl_speed, rel=1e-4)  # rigid -(R/delta) Omega = -3 is 7 % off
    assert np.abs(z).mean() == pytest.approx(wh.radius, rel=1e-4)


def test_backward_whirl_below_the_friction_to_roll_slips_and_loses_contact():
    w = 0.3
    p = replace(ROLL, friction=0.5 * friction_to_roll(ROLL, w))
    model = JeffcottRub(p, w)
    z0 = 1.01 * ROLL.clearance
    sol = _run(model, model.initial_state((z0, 0.0), (0.0, -2.5 * z0)), 60.0, np.linspace(40.0, 60.0, 201))
    assert sol.event_counts["stick"] == 0 and sol.event_counts["lift_off"] >= 1
    assert np.all(np.hypot(sol.ys[:, 0], sol.ys[:, 1]) < ROLL.clearance) and np.all(sol.ys[:, 8] == 0.0)


def test_the_slipping_whip_of_a_massless_stator_is_a_saddle_that_the_simulation_leaves():
    """Issue 28 item 6: started on the closed-form slipping whip (m = k = 1, zeta = 0.05,
    mu = 0.3: w = -(zeta + sqrt(zeta^2 + mu^2)) / mu = -1.1805) the rotor stays on it to round-off,
    so the state exists; 1e-9 along the unstable eigenvector it departs at the positive eigenvalue
    and ends by losing contact: a saddle, not a whirl that locks near the coupled frequency."""
    p = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.1, stator_stiffness=100.0, friction=0.3,
                 rotor_radius=0.1)  # fmt: skip
    whip = slipping_whip(p)
    assert whip.whirl_speed == pytest.approx(-(0.05 + math.hypot(0.05, 0.3)) / 0.3, rel=1e-14)
    spin = 1.0
    assert spin > whip.min_spin_speed  # positive slip: friction drives the backward whirl
    model = JeffcottRub(p, spin)
    om, r = whip.whirl_speed, whip.radius
    ts = np.linspace(0.0, 60.0, 601)
    on = _run(model, model.whirl_state(r, om), 10.0, ts[ts <= 10.0])
    z = on.ys[:, 0] + 1j * on.ys[:, 1]
    assert np.allclose(z, r * np.exp(1j * om * ts[ts <= 10.0]), rtol=0.0, atol=1e-9 * r)  # integration error 3e-11 r
    lam, vec = np.linalg.eig(full_rub_jacobian(p, om, r))
    i = int(np.argmax(lam.real))
    assert lam[i].real == pytest.approx(whip.growth_rate, rel=1e-12) and abs(lam[i].imag) < 1e-12
    d = 1e-9 * r * vec[:, i].real / np.abs(vec[:2, i].real).max()
    z0 = complex(r + d[0], d[1])
    v0 = complex(d[2], d[3]) + 1j * om * z0
    sol = _run(model, model.initial_state((z0.real, z0.imag), (v0.real, v0.imag)), 60.0, ts)
    dev = np.abs((sol.ys[:, 0] + 1j * sol.ys[:, 1]) * np.exp(-1j * om * ts) - r)
    grow = (ts >= 2.0) & (dev < 1e-3 * r)
    assert grow.sum() > 100
    rate = np.polyfit(ts[grow], np.log(dev[grow]), 1)[0]
    assert rate == pytest.approx(whip.growth_rate, rel=0.02)
    assert sol.event_counts["lift_off"] >= 1 and sol.ys[-1, 8] == 0.0
    assert np.hypot(sol.ys[-1, 0], sol.ys[-1, 1]) < p.clearance


# ---- starts pressed into the stator -------------------------------------------------------------


def _slip_sign(z: complex, v: complex, surface_speed: float) -> float:
    """Sign of the contact point's slip, the tangential speed ``Im(conj(z) v) / |z|`` (the tangent
    90 degrees ahead of the normal ``z / |z|``) plus the rotor's surface speed; 0 counts as +."""
    return 1.0 if (z.conjugate() * v).imag / abs(z) + surface_speed >= 0.0 else -1.0


def test_a_start_pressed_into_the_stator_slides_along_its_slip_as_the_machine_does():
    """Issue 28 item 1: the slip of a pressed start had its tangent wrong (``(-x vx + y vy) / r``),
    so that friction pushed along the slip for the whole contact. Forward, backward and radial
    starts all round the circle take the sign of their slip, as the machine's clearance does."""
    from rotorlab.linear import LinearSystem
    from rotorlab.models import ConstantSpeed
    from rotorlab.models._machine import Clearance, ElasticStator, Machine, Unbalance

    p, w = replace(ROLL, friction=0.02), 0.3
    model = JeffcottRub(p, w)
    s = LinearSystem(M=np.diag([p.mass, p.mass, 1.0, 1.0]), C=np.diag([p.damping, p.damping, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([p.stiffness, p.stiffness, 1.0, 1.0]))  # fmt: skip
    cl = Clearance(0, p.clearance, ElasticStator(p.stator_stiffness, 0.0), friction=p.friction,
                   rotor_radius=p.rotor_radius)  # fmt: skip
    machine = Machine(s, unbalances=(Unbalance(0, 0.0),), drive=ConstantSpeed(w), clearances=(cl,))
    seen = set()
    for angle in np.linspace(0.0, 2.0 * math.pi, 12, endpoint=False):
        z = 1.02 * p.clearance * np.exp(1j * angle)
        for whirl in (1.5, -1.5, -5.0, 0.0):
            for radial in (0.0, 0.3):
                v = (1j * whirl + radial) * z
                want = _slip_sign(z, v, p.rotor_radius * w)
                seen.add(want)
                y0 = model.initial_state((z.real, z.imag), (v.real, v.imag))
                assert y0[8] == want, (angle, whirl, radial)
                ym = machine.initial_state(z=[z.real, z.imag, 0.0, 0.0], dz=[v.real, v.imag, 0.0, 0.0])
                assert ym[-1] == want, (angle, whirl, radial)
    assert seen == {1.0, -1.0}
    # a backward whirl faster than the surface speed (-5 rad/s x 10.2 mm > 0.1 m x 0.3 rad/s)
    assert model.whirl_state(1.02 * p.clearance, -5.0)[8] == -1.0
    assert machine.whirl_state(1.02 * p.clearance, -5.0)[-1] == -1.0


def test_a_backward_whirl_pressed_into_the_stator_dissipates_from_the_first_instant():
    """Friction opposes the slip: the friction work ``-F_t s = mu N |s|`` only grows. With the
    slip's sign wrong the start slid with ``F_t`` along the slip and the dissipated energy fell."""
    model = JeffcottRub(ROLL, 0.3)
    y0 = model.whirl_state(1.02 * ROLL.clearance, -5.0)
    ts = np.linspace(0.0, 0.2, 201)
    sol = _run(model, y0, 0.2, ts)
    diss = sol.ys[:, 4]
    assert diss[-1] > 0.0 and np.all(np.diff(diss) >= -1e-15 * diss[-1])


def test_full_rub_from_a_start_pressed_into_the_stator_settles_on_the_closed_form_for_plus_mu():
    """mu = 0.02, started 2 % beyond the synchronous full-rub radius on a synchronous whirl: the run
    settles on the closed form for +mu (the old slip sign settled on the one for -mu, 1.5e-3 away)."""
    w = 1.5
    p = replace(RUB, friction=0.02)
    (branch,) = full_rub(p, w)
    # the closed form for -mu, from the same quadratic (full_rub takes mu >= 0 only)
    m_, k_, c_, ks, d = p.mass, p.stiffness, p.damping, p.stator_stiffness, p.clearance
    a_, b_, f = k_ - m_ * w * w + ks, c_ * w - p.friction * ks, m_ * p.eccentricity * w * w
    r_minus = max(np.roots([a_ * a_ + b_ * b_, -2 * ks * d * (a_ - p.friction * b_),
                            (ks * d) ** 2 * (1 + p.friction**2) - f * f]).real)  # fmt: skip
    assert abs(r_minus / branch.radius - 1.0) > 1e-3
    model = JeffcottRub(p, w)
    ts = np.linspace(280.0, 300.0, 41)
    for angle in (-math.pi / 3, 2 * math.pi / 3, 0.0):
        z0 = 1.02 * branch.radius * np.exp(1j * angle)
        v0 = 1j * w * z0
        sol = _run(model, model.initial_state((z0.real, z0.imag), (v0.real, v0.imag)), 300.0, ts)
        # rtol 1e-4: the -mu radius is 15 times further
        assert np.allclose(np.hypot(sol.ys[:, 0], sol.ys[:, 1]), branch.radius, rtol=1e-4), angle
        assert np.all(sol.ys[:, 8] == 1.0)


def test_a_rub_map_gives_each_point_the_contact_mode_of_its_own_spin_and_clearance(monkeypatch):
    """A rub map from a pressed start: the slip depends on each point's spin speed (its surface
    speed ``R_r Omega``) and the contact on its clearance; the old map gave every point the mode
    of the base model's start."""
    import rotorlab.integrate as integrate
    from rotorlab.contact import RubRegimes

    z, v = 1.02 * ROLL.clearance, -2.5j * 1.02 * ROLL.clearance  # slip -0.0255 + 0.1 Omega
    rub = RubRegimes(JeffcottRub(ROLL, 0.3), t_end=1.0, window=0.5, position=(z, 0.0), velocity=(v.real, v.imag))
    seen = {}

    def capture(model, y0, *args, **kwargs):
        seen["y0"] = np.asarray(y0)
        raise RuntimeError("captured")

    monkeypatch.setattr(integrate, "solve_ensemble", capture)
    with pytest.raises(RuntimeError, match="captured"):
        rub.run_chunk({"spin_speed": np.array([0.3, 0.1, 0.3]), "clearance": np.array([0.01, 0.01, 0.011])})
    assert seen["y0"][:, 8].tolist() == [1.0, -1.0, 0.0]
    assert [_slip_sign(complex(z), v, ROLL.rotor_radius * om) for om in (0.3, 0.1)] == [1.0, -1.0]


def test_bad_values_are_rejected_with_the_field_named():
    with pytest.raises(ValueError, match=r"JeffcottRub.restitution must be a finite number >= 0 and <= 1, got 1.5"):
        JeffcottRub(RUB, 1.0, restitution=1.5)
    with pytest.raises(ValueError, match=r"stator_mass must be 0"):
        JeffcottRub(replace(RUB, stator_mass=1.0), 1.0)
    with pytest.raises(ValueError, match=r"outside the rigid stator"):
        JeffcottRub(BILLIARD, 1.0).initial_state((2e-3, 0.0))
