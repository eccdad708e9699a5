"""The closed forms of rotor-stator contact (:mod:`rotorlab.contact`) against limits, identities
and independent simulations.

Sources: H. F. Black, J. Mech. Eng. Sci. 10 (1968) 1-12 (synchronous full rub with an elastic
stator, dry-friction backward whirl); F. K. Choy & J. Padovan, J. Sound Vib. 113 (1987) 529-545
(rub events, friction destabilising the full rub); S. H. Crandall, 3rd IFToMM Rotordynamics
(1990) 19-26 (dry whirl -(R/delta) Omega rolling, dry whip at the coupled natural frequency);
A. B. Nordmark & P. T. Piiroinen, Nonlinear Dyn. 58 (2009) 85-106 (complete chatter,
t = 2 e v0 / (a (1 - e))). The simulations here are SciPy ``solve_ivp`` runs of the Jeffcott rotor
with the contact force written out directly, independent of the closed forms and of rotorlab's
integrator.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from rotorlab.contact import (
    RubRotor,
    chatter_impact_times,
    chatter_time,
    critical_friction,
    dry_whip_frequency,
    friction_to_roll,
    full_rub,
    full_rub_characteristic,
    full_rub_fold_speeds,
    full_rub_jacobian,
    grazing_speeds,
    hurwitz_stable,
    no_rub_radius,
    rolling_whirl,
    slipping_whip,
)
from rotorlab.models.examples import BouncingBall

# nondimensional rotor (m = k = 1, natural frequency 1 rad/s), 5 % damping, stator 10x stiffer
RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0)


def _contact_force(p: RubRotor, z: complex, v: complex, speed: float, eps_v: float | None = None) -> complex:
    """Contact force on the rotor written directly (fixed frame): normal k_s (|z| - delta), Coulomb
    friction against the slip speed of the rotor surface (translation + R_r Omega); ``eps_v``
    smooths the sign as tanh(v / eps_v)."""
    r = abs(z)
    if r <= p.clearance:
        return 0j
    n = z / r
    t = 1j * n
    normal = p.stator_stiffness * (r - p.clearance)
    slip = (v * t.conjugate()).real + p.rotor_radius * speed
    s = np.sign(slip) if eps_v is None else math.tanh(slip / eps_v)
    return -normal * n - p.friction * normal * s * t


def _simulate(p: RubRotor, speed: float, z0: complex, v0: complex, t_end: float, ts, eps_v=None):
    def f(t, y):
        z, v = complex(y[0], y[1]), complex(y[2], y[3])
        a = (-p.stiffness * z - p.damping * v + _contact_force(p, z, v, speed, eps_v)) / p.mass
        a += p.eccentricity * speed**2 * complex(math.cos(speed * t), math.sin(speed * t))
        return [v.real, v.imag, a.real, a.imag]

    sol = solve_ivp(f, (0.0, t_end), [z0.real, z0.imag, v0.real, v0.imag], method="LSODA",
                    rtol=1e-10, atol=1e-13, dense_output=True)  # fmt: skip
    assert sol.status == 0
    y = sol.sol(ts)
    return y[0] + 1j * y[1]


# ---- onset of contact: the no-rub orbit reaches the clearance -----------------------------------


def test_grazing_speeds_undamped_closed_form():
    # c = 0: m eps W^2 = delta |k - m W^2|  ->  W^2 = k delta / (m (delta +- eps))
    p = RubRotor(mass=2.0, stiffness=8.0, clearance=1e-3, eccentricity=2e-4)
    lo, hi = grazing_speeds(p)
    assert lo == pytest.approx(math.sqrt(8.0 * 1e-3 / (2.0 * 1.2e-3)), rel=1e-12)
    assert hi == pytest.approx(math.sqrt(8.0 * 1e-3 / (2.0 * 0.8e-3)), rel=1e-12)


@pytest.mark.parametrize("eps, n", [(0.3, 2), (0.6, 2), (1.5, 1), (0.02, 0)])
def test_no_rub_orbit_touches_the_clearance_exactly_at_the_grazing_speeds(eps, n):
    p = replace(RUB, eccentricity=eps)
    ws = grazing_speeds(p)
    assert len(ws) == n  # eps = 0.02: the damped peak 10 eps = 0.2 stays inside the clearance
    for w in ws:
        assert no_rub_radius(p, w) == pytest.approx(p.clearance, rel=1e-12)
    if n == 2:  # in contact between them only
        assert no_rub_radius(p, 0.5 * (ws[0] + ws[1])) > p.clearance
        assert no_rub_radius(p, 0.9 * ws[0]) < p.clearance < no_rub_radius(p, 1.01 * ws[0])
        assert no_rub_radius(p, 1.1 * ws[1]) < p.clearance
    if n == 1:  # eps > delta: in contact from there on
        assert no_rub_radius(p, 50.0 * ws[0]) > p.clearance


# ---- synchronous full annular rub ---------------------------------------------------------------


def _rotating_frame_residual(p: RubRotor, speed: float, w: complex) -> complex:
    """Equilibrium residual of m w'' + (c + 2 i m W) w' + (k - m W^2 + i c W) w + F(w) = m eps W^2."""
    f = _contact_force(p, w, 1j * speed * w, speed)  # at rest in the rotating frame: v = i W z
    return (p.stiffness - p.mass * speed**2 + 1j * p.damping * speed) * w - f - p.mass * p.eccentricity * speed**2


@pytest.mark.parametrize("mu", [0.0, 0.05, 0.3])
@pytest.mark.parametrize("speed", [0.8, 1.5, 3.0])
def test_full_rub_radius_is_an_equilibrium_of_the_rotor_in_the_rotating_frame(mu, speed):
    p = replace(RUB, friction=mu)
    for b in full_rub(p, speed):
        w0 = b.radius * np.exp(-1j * b.phase)
        assert abs(_rotating_frame_residual(p, speed, w0)) < 1e-12 * p.mass * p.eccentricity * speed**2
        assert b.normal_force == pytest.approx(p.stator_stiffness * (b.radius - p.clearance), rel=1e-14)
        # an independent root finder started 5 % off lands on the same orbit
        sol = fsolve(lambda x: [_rotating_frame_residual(p, speed, complex(*x)).real,
                                _rotating_frame_residual(p, speed, complex(*x)).imag],
                     [1.05 * w0.real, 0.95 * w0.imag], xtol=1e-12)  # fmt: skip
        assert abs(complex(*sol)) == pytest.approx(b.radius, rel=1e-9)


def test_full_rub_tends_to_the_rigid_stator_as_the_stator_stiffens():
    rigid = full_rub(replace(RUB, stator_stiffness=math.inf, friction=0.2), 2.0)
    assert len(rigid) == 2 and all(b.radius == RUB.clearance for b in rigid)
    for ks in (1e4, 1e6):
        elastic = full_rub(replace(RUB, stator_stiffness=ks, friction=0.2), 2.0)
        assert len(elastic) == 2  # upper and lower branch <-> larger and smaller normal force
        for b, rb in zip(elastic, rigid):
            assert b.radius - RUB.clearance == pytest.approx(rb.normal_force / ks, rel=100.0 / ks)
            assert b.normal_force == pytest.approx(rb.normal_force, rel=100.0 / ks)
            assert b.phase == pytest.approx(rb.phase, abs=100.0 / ks)


def test_fold_coexistence_and_the_saddle_at_the_lower_branch():
    p = replace(RUB, eccentricity=0.3)
    (w_fold,) = full_rub_fold_speeds(p, 5.0)
    assert len(full_rub(p, 0.999 * w_fold)) == 2 and len(full_rub(p, 1.001 * w_fold)) == 0
    hi, lo = full_rub(p, 0.999999 * w_fold)
    assert hi.radius == pytest.approx(lo.radius, rel=1e-2)
    # at the fold the orbit is a double root: the characteristic quartic has a zero root (a4 = 0)
    a = full_rub_characteristic(p, w_fold, 0.5 * (hi.radius + lo.radius))
    assert abs(a[-1] / a[-2]) < 1e-5
    # below the fold (and above the upper grazing speed) the no-rub orbit coexists with the rub
    w = 2.0
    assert w > grazing_speeds(p)[1]
    assert no_rub_radius(p, w) < p.clearance and len(full_rub(p, w)) == 2
    hi, lo = full_rub(p, w)
    assert hurwitz_stable(full_rub_characteristic(p, w, hi.radius))  # frictionless upper branch: stable
    assert full_rub_characteristic(p, w, lo.radius)[-1] < 0.0  # lower branch: a saddle


@pytest.mark.parametrize("mu", [0.0, 0.04, 0.2])
def test_characteristic_quartic_matches_the_jacobian_and_the_jacobian_the_equations(mu):
    p = replace(RUB, friction=mu, stator_damping=0.3)
    w = 1.5
    r = full_rub(p, w)[0].radius
    jac = full_rub_jacobian(p, w, r)
    roots = np.sort_complex(np.roots(full_rub_characteristic(p, w, r)))
    assert np.allclose(roots, np.sort_complex(np.linalg.eigvals(jac)), atol=1e-10)
    # trace identity: the four roots sum to -(2 c + c_s) / m
    assert roots.sum().real == pytest.approx(-(2 * p.damping + p.stator_damping) / p.mass, abs=1e-12)
    # finite differences of the rotating-frame equations around the orbit on the real axis
    b = full_rub(p, w)[0]
    w0 = complex(r, 0.0)
    forcing = p.mass * p.eccentricity * w**2 * np.exp(1j * b.phase)  # rotate the orbit onto the axis

    def accel(x):
        z, v = complex(x[0], x[1]), complex(x[2], x[3])
        n = z / abs(z)
        t = 1j * n
        rdot = (v * n.conjugate()).real
        normal = p.stator_stiffness * (abs(z) - p.clearance) + p.stator_damping * rdot
        fc = -normal * (n + mu * t)
        acc = (forcing + fc - (p.stiffness - p.mass * w**2 + 1j * p.damping * w) * z
               - (p.damping + 2j * p.mass * w) * v) / p.mass  # fmt: skip
        return np.array([v.real, v.imag, acc.real, acc.imag])

    x0 = np.array([r, 0.0, 0.0, 0.0])
    assert np.abs(accel(x0)).max() < 1e-12
    h = 1e-6
    fd = np.column_stack([(accel(x0 + h * e) - accel(x0 - h * e)) / (2 * h) for e in np.eye(4)])
    assert np.allclose(fd, jac, atol=1e-7)


def test_frictionless_full_rub_decays_like_the_free_rotor():
    # mu = 0: conservative radial contact; the upper branch's slowest mode decays at -c / (2 m)
    for w in (1.0, 1.5, 2.0, 3.0):
        r = full_rub(RUB, w)[0].radius
        assert np.linalg.eigvals(full_rub_jacobian(RUB, w, r)).real.max() == pytest.approx(-0.05, abs=1e-9)


def test_critical_friction_is_a_flutter_boundary():
    w = 1.5
    mu_c = critical_friction(RUB, w)
    assert 0.0 < mu_c < 0.2
    at = replace(RUB, friction=mu_c)
    lam = np.linalg.eigvals(full_rub_jacobian(at, w, full_rub(at, w)[0].radius))
    crit = lam[np.argmax(lam.real)]
    assert abs(crit.real) < 1e-9 and abs(crit.imag) > 1.0  # a pair crosses the axis (Hopf), not a fold
    for fac, stable in ((0.99, True), (1.01, False)):
        q = replace(RUB, friction=fac * mu_c)
        assert hurwitz_stable(full_rub_characteristic(q, w, full_rub(q, w)[0].radius)) is stable
    # more rotor damping, more friction tolerated
    assert critical_friction(replace(RUB, damping=0.2), w) > mu_c


@pytest.mark.parametrize("fac", [0.7, 1.4])
def test_simulated_rub_stays_on_the_branch_below_critical_friction_and_leaves_at_the_growth_rate(fac):
    w = 1.5
    p = replace(RUB, friction=fac * critical_friction(RUB, w))
    b = full_rub(p, w)[0]
    lam, vec = np.linalg.eig(full_rub_jacobian(p, w, b.radius))
    i = int(np.argmax(lam.real))
    # start on the orbit displaced along the least damped mode (rotating frame -> fixed frame at t = 0)
    rot = np.exp(-1j * b.phase)
    d = 1e-5 * vec[:, i].real / np.abs(vec[:2, i]).max()
    w0 = rot * complex(b.radius + d[0], d[1])
    v0 = rot * complex(d[2], d[3]) + 1j * w * w0
    ts = np.linspace(0.0, 150.0, 6001)
    z = _simulate(p, w, w0, v0, 150.0, ts)
    dev = np.abs(z * np.exp(-1j * w * ts) - b.radius * rot)
    # envelope: maxima per period of the mode, log-slope against the eigenvalue's real part
    period = 2 * math.pi / abs(lam[i].imag)
    n_per = int(period / (ts[1] - ts[0])) + 1
    peaks = np.array([dev[k : k + n_per].max() for k in range(0, len(ts) - n_per, n_per)])
    tp = np.array([ts[k + int(np.argmax(dev[k : k + n_per]))] for k in range(0, len(ts) - n_per, n_per)])
    rate = np.polyfit(tp[5:], np.log(peaks[5:]), 1)[0]
    assert rate == pytest.approx(lam[i].real, abs=0.1 * abs(lam[i].real))
    assert (rate < 0) == (fac < 1)


# ---- dry-friction backward whirl ----------------------------------------------------------------

ROLL = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.05, stator_stiffness=100.0,
                friction=0.3, rotor_radius=0.1)  # fmt: skip


def test_rolling_whirl_rigid_stator_is_minus_r_over_delta_omega():
    p = replace(ROLL, stator_stiffness=math.inf)
    for w in (0.2, 0.5, 3.0):
        wh = rolling_whirl(p, w)
        assert wh.whirl_speed == pytest.approx(-p.rotor_radius / p.clearance * w, rel=1e-15)
        assert wh.radius == p.clearance
        assert wh.normal_force == pytest.approx(p.clearance * (wh.whirl_speed**2 - 1.0), rel=1e-14)
        assert wh.friction_needed == pytest.approx(p.damping * p.clearance * abs(wh.whirl_speed) / wh.normal_force)
    # it presses the stator only while the whirl is faster than the natural frequency
    w_min = p.clearance / p.rotor_radius * p.natural_frequency
    assert rolling_whirl(p, 0.999 * w_min) is None and rolling_whirl(p, 1.001 * w_min) is not None
    assert friction_to_roll(p, 0.999 * w_min) == math.inf


def test_rolling_whirl_compliance_correction_and_its_limits():
    w = 0.3
    wh = rolling_whirl(ROLL, w)
    # rolling: the contact point is at rest; radial balance; compliance N = k_s (r - delta)
    assert wh.radius * wh.whirl_speed + ROLL.rotor_radius * w == pytest.approx(0.0, abs=1e-15)
    assert wh.normal_force == pytest.approx(wh.radius * (wh.whirl_speed**2 - 1.0), rel=1e-12)
    assert wh.normal_force == pytest.approx(100.0 * (wh.radius - ROLL.clearance), rel=1e-12)
    assert -3.0 < wh.whirl_speed < -2.79  # slower than the rigid -(R/delta) Omega = -3
    stiff = rolling_whirl(replace(ROLL, stator_stiffness=1e9), w)
    assert stiff.whirl_speed == pytest.approx(-3.0, rel=1e-7)
    # fast spin: the whirl frequency tends to the coupled natural frequency sqrt((k + k_s)/m)
    assert rolling_whirl(ROLL, 1e4).whirl_speed == pytest.approx(-math.sqrt(101.0), rel=1e-3)


def test_simulated_backward_whirl_rolls_at_the_corrected_frequency_and_slips_below_the_friction_to_roll():
    """Coulomb friction smoothed as tanh(v / 1e-6 m/s) (near-rolling), started whirling backwards."""
    w = 0.3
    wh = rolling_whirl(ROLL, w)
    ts = np.linspace(40.0, 60.0, 2001)
    z0 = 1.01 * ROLL.clearance
    z = _simulate(ROLL, w, z0, -2.5j * z0, 60.0, ts, eps_v=1e-6)
    whirl = np.polyfit(ts, np.unwrap(np.angle(z)), 1)[0]
    assert whirl == pytest.approx(wh.whirl_speed, rel=1e-4)  # the rigid value -3 is 7 % off
    assert np.abs(z).mean() == pytest.approx(wh.radius, rel=1e-3)
    # half the friction needed to roll: the whirl slips, contact is lost, the free rotor remains
    p = replace(ROLL, friction=0.5 * friction_to_roll(ROLL, w))
    z = _simulate(p, w, z0, -2.5j * z0, 60.0, ts, eps_v=1e-6)
    assert np.abs(z).max() < ROLL.clearance


def test_dry_whip_at_the_coupled_backward_natural_frequency_with_a_moving_housing():
    p = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, stator_stiffness=50.0, stator_mass=0.5,
                 rotor_radius=0.1)  # fmt: skip
    w_whip = dry_whip_frequency(p)
    assert w_whip == pytest.approx(math.sqrt(51.0 / 1.5), rel=1e-15)
    spin_whip = w_whip * p.clearance / p.rotor_radius
    for w in (0.5 * spin_whip, 0.9 * spin_whip):
        wh = rolling_whirl(p, w)
        om = wh.whirl_speed
        assert om == pytest.approx(-p.rotor_radius / p.clearance * w, rel=1e-15)  # rigid contact: exactly -(R/delta) Omega
        # both bodies on their circles: rotor m r om^2 = k r + N, housing m_s s om^2 = k_s s - N
        s = wh.radius - p.clearance
        assert p.mass * wh.radius * om**2 == pytest.approx(p.stiffness * wh.radius + wh.normal_force, rel=1e-12)
        assert p.stator_mass * s * om**2 == pytest.approx(p.stator_stiffness * s - wh.normal_force, rel=1e-12)
    # the rolling whirl's radius diverges as the whirl approaches the coupled frequency
    assert rolling_whirl(p, 0.999 * spin_whip).radius > 100 * rolling_whirl(p, 0.5 * spin_whip).radius
    assert rolling_whirl(p, 1.001 * spin_whip) is None


# slipping whip of a massless stator: m = k = 1 (omega in units of sqrt(k/m)), zeta = 0.05
WHIP = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.1, stator_stiffness=100.0, friction=0.3,
                rotor_radius=0.1)  # fmt: skip


def test_slipping_whip_solves_the_force_balance_derived_with_sympy():
    """Issue 28 item 6. The whirl z = r e^{i w t} in permanent contact, sliding with a positive
    slip (F_t = -mu N), put into m z'' + c z' + k z = (-N + i F_t) z / |z| with sympy: the radial
    and tangential parts give N = r (m w^2 - k) and c w = mu (k - m w^2); the backward root, with
    N = k_s (r - delta) > 0, is the closed form. Its linearisation, taken by sympy from the
    equations of motion in the whirling frame (not from full_rub_jacobian), has a zero (the
    phase), and a3 = mu (k + m w^2)(k + k_s - m w^2) / w < 0: a real positive eigenvalue, a saddle."""
    import sympy as sp

    m, k, c, ks, d, mu, r, w, t = sp.symbols("m k c k_s delta mu r w t", real=True)
    n_ = sp.Symbol("N", real=True)
    z = r * sp.exp(sp.I * w * t)
    res = sp.simplify((m * z.diff(t, 2) + c * z.diff(t) + k * z - (-n_ - sp.I * mu * n_) * sp.exp(sp.I * w * t)) / z)
    n_sol = sp.solve(sp.re(sp.expand(res)), n_)[0]
    assert sp.simplify(n_sol - r * (m * w**2 - k)) == 0
    w_roots = sp.solve(sp.im(sp.expand(res)).subs(n_, n_sol), w)
    vals = {m: 1, k: 1, c: WHIP.damping, mu: WHIP.friction, ks: WHIP.stator_stiffness, d: WHIP.clearance}
    back = [float(x.subs(vals)) for x in w_roots if float(x.subs(vals)) < 0.0]
    whip = slipping_whip(WHIP)
    zeta = WHIP.damping / 2.0
    assert whip.whirl_speed == pytest.approx(-(zeta + math.sqrt(zeta**2 + WHIP.friction**2)) / WHIP.friction, rel=1e-14)
    assert back == [pytest.approx(whip.whirl_speed, rel=1e-13)]
    r_val = WHIP.stator_stiffness * WHIP.clearance / (1.0 + WHIP.stator_stiffness - whip.whirl_speed**2)
    assert whip.radius == pytest.approx(r_val, rel=1e-14)
    assert whip.normal_force == pytest.approx(r_val * (whip.whirl_speed**2 - 1.0), rel=1e-12) and whip.normal_force > 0
    assert whip.min_spin_speed == pytest.approx(r_val * abs(whip.whirl_speed) / WHIP.rotor_radius, rel=1e-14)
    # linearisation in the frame whirling at w: q = u + i v, z = q e^{i w t}
    u, v, du, dv = sp.symbols("u v du dv", real=True)
    q, dq = u + sp.I * v, du + sp.I * dv
    rad = sp.sqrt(u**2 + v**2)
    force = -ks * (rad - d) * (1 + sp.I * mu) * q / rad
    acc = (force - c * (dq + sp.I * w * q) - k * q) / m - 2 * sp.I * w * dq + w**2 * q
    f = sp.Matrix([du, dv, sp.re(sp.expand(acc)), sp.im(sp.expand(acc))])
    vals.update({w: whip.whirl_speed, r: whip.radius})
    at = {u: whip.radius, v: 0, du: 0, dv: 0}
    assert max(abs(float(x.subs(vals).subs(at))) for x in f) < 1e-12  # the whip is an equilibrium there
    jac = np.array(f.jacobian([u, v, du, dv]).subs(vals).subs(at).evalf(), dtype=float)
    lam = np.sort_complex(np.linalg.eigvals(jac))
    assert np.allclose(lam, np.sort_complex(whip.eigenvalues), atol=1e-10)
    assert np.min(np.abs(lam)) < 1e-10  # the phase
    a3 = WHIP.friction * (1 + whip.whirl_speed**2) * (1 + WHIP.stator_stiffness - whip.whirl_speed**2) / whip.whirl_speed
    assert a3 < 0 and np.prod([x for x in lam if abs(x) > 1e-10]).real == pytest.approx(-a3, rel=1e-9)
    assert whip.growth_rate == pytest.approx(max(lam.real), rel=1e-10) and whip.growth_rate > 0.3


def test_slipping_whip_exists_below_the_coupled_frequency_and_needs_damping_and_friction():
    # |w| -> sqrt((k + k_s) / m): the radius diverges; beyond it no whip (nondimensional w^2 < 1 + k_s / k = 101)
    mu = 0.3
    seen = []
    for zeta in (0.05, 0.5, 2.0, 5.0):
        om = -(zeta + math.sqrt(zeta**2 + mu**2)) / mu
        whip = slipping_whip(replace(WHIP, damping=2.0 * zeta))
        if om * om < 101.0:
            assert whip.whirl_speed == pytest.approx(om, rel=1e-14) and whip.growth_rate > 0.0
            assert whip.whirl_speed > -dry_whip_frequency(WHIP)
        else:
            assert whip is None
        seen.append(whip is None)
    assert seen == [False, False, True, True]
    assert slipping_whip(replace(WHIP, friction=0.0)) is None
    assert slipping_whip(replace(WHIP, damping=0.0)) is None  # w = -1, N = 0: no contact force
    with pytest.raises(ValueError, match="massless elastic stator"):
        slipping_whip(replace(WHIP, stator_mass=0.5))


# ---- chatter ------------------------------------------------------------------------------------


@pytest.mark.parametrize("e", [0.3, 0.8, 0.95])
def test_chatter_time_is_the_sum_of_the_flight_times(e):
    v0, a = 2.0, 9.81
    t_inf = chatter_time(v0, a, e)
    assert t_inf == pytest.approx(2 * e * v0 / (a * (1 - e)), rel=1e-15)
    # impact j: the speed e^j v0 after j restitutions, flight 2 e^j v0 / a to the next one
    times = chatter_impact_times(v0, a, e, 40)
    flights = np.diff(np.concatenate([[0.0], times]))
    assert np.allclose(flights, 2 * v0 * e ** np.arange(1, 41) / a, rtol=1e-9)
    assert chatter_impact_times(v0, a, e, 2000)[-1] == pytest.approx(t_inf, rel=1e-12)
    assert BouncingBall(gravity=a, restitution=e).accumulation_time(v0) == pytest.approx(t_inf, rel=1e-12)


def test_chatter_time_rejects_elastic_impacts():
    with pytest.raises(ValueError, match=r"chatter_time.restitution must be .*< 1.*got 1.0"):
        chatter_time(1.0, 9.81, 1.0)
