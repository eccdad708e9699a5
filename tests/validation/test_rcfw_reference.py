"""The reference for Rodrigues, Champneys, Friswell & Wilson (2008): closed forms vs. equations.

Rodrigues, Champneys, Friswell & Wilson, "Automatic two-plane balancing for rigid rotors", Int.
J. Non-Linear Mech. 43 (2008) 527-541; numbers below are quoted from the authors' preprint
(University of Bristol, hdl 1983/946), whose equation and figure numbers are used. The "long
rotor" (eqs. (18), (20)): M = 1, R = 1, Jt = 3.25, Jp = 0.5, supports k = 0.5, c = 0.01 at
z = +-3 (k11 = 1, k12 = 0, k22 = 9, c11 = 0.02, c22 = 0.18), races at z = +-2 with two balls
each, ball damping c_b = 0.01 in the paper's scaling c_b = b / (m Omega_1 R^2), static
imbalance eps = 0.01 (beta = 0).

From the paper (printed numbers and statements):
- m_c = eps / 4 = 0.0025, eq. (21); the balanced state B, eq. (16); its conditions, eq. (14).
- Omega_1 = sqrt(k11 / M) = 1 and Omega_2 = sqrt(k22 / (Jt - Jp)) ~= 1.81, eq. (19).
- Equations of motion (9), (10) (lateral) and (13) (balls), co-rotating frame.
- The four runs of Fig. 11, placed in Figs. 5 and 7: (Omega, eps, m) = (2.0, 0.01, 0.025) in the
  secondary stable region of B just above Omega_2; (2.5, 0.01, 0.005) outside any stable region;
  (4.0, 0.01, 0.005) in the primary stable region; (1.5, 0.025, 0.025) "well outside any region of
  balanced operation" (Section 4).
- "the balancing process only works for sufficiently high rotation speeds above the second
  critical frequency" (Section 5); for large Omega B is stable (Hcon, Section 3.2.1).
- The boundaries of B's stable regions in Fig. 5(a), read from the figure's vector graphics
  (``FIG5A_BOUNDARIES``): the rigid-kinematics reference meets every one within 0.01.
- A disc rotor (Jp > Jt) has no conical critical speed and no stable balanced state (m = eps):
  Rodrigues et al. 2011, IJNLM 46, Section 5 and Fig. 13(b).

Derived here (closed forms, checked against the sympy equations of ``dev/derive_rcfw.py``): the
ball angles of B at m = 0.025 (pi +- arccos(0.1)), the whirl frequencies and the gyroscopic split
of the conical mode, the backward conical critical speed sqrt(k22 / (Jt + Jp)), and the
eigenvalues of the linearisation about B (complex-step Jacobian of the co-rotating equations).
Two ball kinematics are checked: "rigid" (the ball follows its tilting race, as eqs. (9)-(13) and
``rotorlab.models.Machine``) and "lateral" (in-plane only, as Rodrigues et al. 2011 eq. (2)).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import least_squares

import _rcfw_reference as ref

KINEMATICS = ("rigid", "lateral")


def test_paper_constants_are_the_closed_forms():
    """Eq. (21) m_c = eps / 4 = 0.0025 and eq. (19) Omega_1 = 1, Omega_2 ~= 1.81."""
    sys_ = ref.TwoPlane.long_rotor(0.025)
    assert ref.critical_mass(ref.EPS) == pytest.approx(ref.M_CRIT, rel=1e-15)
    assert (sys_.k11, sys_.k22) == (1.0, 9.0)
    om1, om2, om2_back = ref.critical_speeds(sys_.mass, sys_.jt, sys_.jp, sys_.k11, sys_.k22)
    assert om1 == 1.0
    assert om2 == pytest.approx(ref.OMEGA_CON, abs=0.005)  # printed to two decimals
    assert om2 == pytest.approx(np.sqrt(9.0 / 2.75), rel=1e-15)
    assert om2_back == pytest.approx(np.sqrt(9.0 / 3.75), rel=1e-15)


@pytest.mark.parametrize("kinematics", KINEMATICS)
@pytest.mark.parametrize("omega", [1.5, 4.0])
def test_balanced_state_is_an_equilibrium(kinematics, omega):
    """Eq. (16): alpha_bar = pi, alpha_hat = arccos(eps / (4 m)) cancels force and moment (14)."""
    sys_ = ref.TwoPlane.long_rotor(0.025, kinematics=kinematics)
    s = ref.balanced_state(sys_)
    hat = np.arccos(0.1)
    np.testing.assert_allclose(s[4:8], [np.pi + hat, np.pi - hat] * 2, rtol=1e-15)
    assert np.degrees(hat) == pytest.approx(84.2608295, abs=1e-6)
    a = s[4:8]
    # eq. (14): cos sums s_x = -eps/m, c_x = 0; sine sums zero
    assert np.sum(np.cos(a)) == pytest.approx(-ref.EPS / 0.025, rel=1e-14)
    assert np.cos(a[:2]).sum() - np.cos(a[2:]).sum() == pytest.approx(0.0, abs=1e-15)
    assert np.max(np.abs(np.sin(a[:2]).sum() + np.sin(a[2:]).sum())) < 1e-15
    res = ref.rotating_rhs(sys_, s, omega)
    assert np.max(np.abs(res)) < 1e-15 * omega**2
    # an unbalanced ball layout is not an equilibrium: the check can fail
    s2 = s.copy()
    s2[4] += 0.1
    assert np.max(np.abs(ref.rotating_rhs(sys_, s2, omega))) > 1e-4


@pytest.mark.parametrize("kinematics", KINEMATICS)
def test_critical_ball_mass_from_the_equations(kinematics):
    """Below m_c = eps / 4 no ball layout stills the rotor (the best leaves eps - 4 m); above it
    one does (eq. (21)). Found by least squares on the rotor accelerations of the equations."""
    omega = 3.0

    def rotor_acc(sys_, angles):
        s = np.zeros(16)
        s[4:8] = angles
        return ref.rotating_rhs(sys_, s, omega)[8:12]

    for factor, expect_zero in ((0.9, False), (1.1, True)):
        m = factor * ref.M_CRIT
        sys_ = ref.TwoPlane.long_rotor(m, kinematics=kinematics)
        best = min((least_squares(lambda a: rotor_acc(sys_, a), x0, xtol=1e-15, ftol=1e-15,
                                  gtol=1e-15) for x0 in ([3.0, 3.3, 3.0, 3.3], [2.0, 4.0, 2.5, 3.5])),
                   key=lambda r: r.cost)
        worst_force = np.linalg.norm(rotor_acc(sys_, best.x)[:2]) * (1.0 + 4 * m)
        if expect_zero:
            assert worst_force < 1e-13
        else:  # all four balls opposite the imbalance: (eps - 4 m) Omega^2
            assert worst_force == pytest.approx((ref.EPS - 4 * m) * omega**2, rel=1e-6)
            np.testing.assert_allclose(np.cos(best.x), -1.0, atol=1e-6)


@pytest.mark.parametrize("omega", [0.0, 1.0, ref.OMEGA_CON, 3.0])
def test_rigid_body_whirl_frequencies(omega):
    """Bare undamped rotor: the equations' eigenfrequencies are the closed forms, the conical pair
    split by the gyroscopic moment Jp Omega (Jt w^2 -+ Jp Omega w = k22)."""
    sys_ = ref.TwoPlane(supports=((0.5, 0.0, 3.0), (0.5, 0.0, -3.0)), eps=0.0)
    J = ref.jacobian(lambda y: ref.fixed_rhs(sys_, y, 0.0, omega), np.zeros(8))
    lam = np.linalg.eigvals(J)
    assert np.max(np.abs(lam.real)) < 1e-12
    freqs = np.sort(lam.imag[lam.imag > 0])
    cyl, fw, bw = ref.whirl_frequencies(omega, 1.0, ref.JT, ref.JP, 1.0, 9.0)
    np.testing.assert_allclose(freqs, np.sort([cyl, cyl, fw, bw]), rtol=1e-12)
    if omega > 0:  # forward whirl is the sense of spin: phi_x + i phi_y turns like exp(+i w t)
        vals, vecs = np.linalg.eig(J)
        v = vecs[:4, np.argmin(np.abs(vals - 1j * fw))]
        assert abs(v[3] + 1j * v[2]) < 1e-9 * abs(v[2])


def test_conical_critical_speed_is_the_forward_whirl_crossing():
    """At Omega_2 (eq. (19)) the forward conical whirl frequency equals the spin speed."""
    _, om2, om2b = ref.critical_speeds(1.0, ref.JT, ref.JP, 1.0, 9.0)
    _, fw, _ = ref.whirl_frequencies(om2, 1.0, ref.JT, ref.JP, 1.0, 9.0)
    _, _, bw = ref.whirl_frequencies(om2b, 1.0, ref.JT, ref.JP, 1.0, 9.0)
    assert fw == pytest.approx(om2, rel=1e-14)
    assert bw == pytest.approx(om2b, rel=1e-14)


def _random_rotating_states(n_states: int, scale: float, seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(n_states):
        s = np.empty(16)
        s[:4] = rng.normal(scale=scale, size=4)
        s[4:8] = rng.uniform(-np.pi, np.pi, size=4)
        s[8:12] = rng.normal(scale=scale, size=4)
        s[12:16] = rng.normal(scale=0.3, size=4)
        yield s


def _paper_residuals(sys_: ref.TwoPlane, s, sd, omega: float):
    """Residuals of eqs. (9), (10) (rotor translation) and (13) (each ball), co-rotating frame.

    The paper's (x, y, phi_x, phi_y) are our (u, v, -a_y, a_x); its race centre
    (x + z phi_y, y - z phi_x) is our (u + z a_x, v + z a_y). Written dimensionally: rotor mass M
    times its centre's acceleration, plus each ball's, plus the supports, equals M eps Omega^2.
    """
    u, v, ax, ay = s[:4]
    ud, vd, axd, ayd = s[8:12]
    udd, vdd, axdd, aydd = sd[8:12]
    al, ald, aldd = s[4:8], s[12:16], sd[12:16]
    c11 = sum(c for _, c, _ in sys_.supports)
    fx = sys_.mass * (udd - 2 * omega * vd - omega**2 * u) + sys_.k11 * u + c11 * (ud - omega * v)
    fy = sys_.mass * (vdd + 2 * omega * ud - omega**2 * v) + sys_.k11 * v + c11 * (vd + omega * u)
    ball = []
    for i, (m, r, z, b) in enumerate(sys_.balls):
        uc, vc = u + z * ax, v + z * ay
        ucd, vcd = ud + z * axd, vd + z * ayd
        ucdd, vcdd = udd + z * axdd, vdd + z * aydd
        a, w, wd = al[i], ald[i], aldd[i]
        fx += m * (ucdd - r * np.sin(a) * wd - r * np.cos(a) * w**2
                   - 2 * omega * (vcd + r * np.cos(a) * w) - omega**2 * (uc + r * np.cos(a)))
        fy += m * (vcdd + r * np.cos(a) * wd - r * np.sin(a) * w**2
                   + 2 * omega * (ucd - r * np.sin(a) * w) - omega**2 * (vc + r * np.sin(a)))
        big_x = ucdd - omega**2 * uc - 2 * omega * vcd
        big_y = vcdd - omega**2 * vc + 2 * omega * ucd
        ball.append(m * r * r * wd + b * w - m * r * (big_x * np.sin(a) - big_y * np.cos(a)))
    return np.array([fx - sys_.mass * sys_.eps * omega**2, fy]), np.array(ball)


def _axial_term(sys_: ref.TwoPlane, s, sd, omega: float) -> np.ndarray:
    """What a ball's axial motion on its tilting race adds to eq. (13) (rigid kinematics).

    In fixed-frame tilts (at theta = 0: phi = a, phi' = a' + Omega J a, phi'' = a'' + 2 Omega J
    a' - Omega^2 a) and the absolute ball angle psi = alpha, the sympy Lagrangian gives
    ``m R^2 / 2 (phi_x'' phi_y - phi_y'' phi_x + (phi_x'^2 - phi_y'^2) sin 2 psi
    - 2 phi_x' phi_y' cos 2 psi)``: second order in the rotor's tilt and its rates.
    """
    ax, ay, axd, ayd, axdd, aydd = s[2], s[3], s[10], s[11], sd[10], sd[11]
    px, py = ax, ay
    pxd, pyd = axd - omega * ay, ayd + omega * ax
    pxdd = axdd - 2 * omega * ayd - omega**2 * ax
    pydd = aydd + 2 * omega * axd - omega**2 * ay
    out = []
    for i, (m, r, _, _) in enumerate(sys_.balls):
        psi = s[4 + i]
        out.append(m * r * r / 2 * (pxdd * py - pydd * px + (pxd**2 - pyd**2) * np.sin(2 * psi)
                                    - 2 * pxd * pyd * np.cos(2 * psi)))
    return np.array(out)


@pytest.mark.parametrize("kinematics", KINEMATICS)
def test_equations_are_the_papers_9_10_13(kinematics):
    """On random co-rotating states the derived equations satisfy eqs. (9), (10) exactly and the
    ball equation (13) exactly with lateral kinematics; with rigid ones eq. (13) gains the
    second-order term of the ball's axial motion (the paper keeps eq. (13) to first order)."""
    omega = 2.5
    for s in _random_rotating_states(6, 0.05, seed=3):
        sys_ = ref.TwoPlane.long_rotor(0.025, kinematics=kinematics)
        sd = ref.rotating_rhs(sys_, s, omega)
        rotor, ball = _paper_residuals(sys_, s, sd, omega)
        assert np.max(np.abs(rotor)) < 1e-14
        extra = _axial_term(sys_, s, sd, omega)
        assert np.max(np.abs(extra)) > 1e-6  # the states tilt enough to tell the two apart
        if kinematics == "lateral":
            assert np.max(np.abs(ball)) < 1e-15
        else:
            np.testing.assert_allclose(ball, -extra, rtol=1e-11, atol=1e-16)


@pytest.mark.parametrize("kinematics", KINEMATICS)
@pytest.mark.parametrize(("omega", "eps", "m", "stable"), [
    (2.0, 0.01, 0.025, True),    # Fig. 11 (i): secondary stable region of Fig. 5
    (2.5, 0.01, 0.005, False),   # Fig. 11 (ii): outside the stable region
    (4.0, 0.01, 0.005, True),    # Fig. 11 (iii): primary stable region
    (1.5, 0.025, 0.025, False),  # Fig. 11 (iv): well outside any region (Fig. 7)
])
def test_balanced_state_stability_at_the_fig11_points(kinematics, omega, eps, m, stable):
    sys_ = ref.TwoPlane.long_rotor(m, eps, kinematics=kinematics)
    a = ref.spectral_abscissa(sys_, omega)
    assert (a < 0) == stable, a
    assert abs(a) > 1e-3  # not marginal: the verdict does not hinge on round-off


def _stable_intervals(sys_, omegas):
    st = np.array([ref.spectral_abscissa(sys_, o) < 0 for o in omegas])
    edges = np.flatnonzero(np.diff(st.astype(int))) + 1
    runs = np.split(np.arange(omegas.size), edges)
    return [(omegas[r[0]], omegas[r[-1]]) for r in runs if st[r[0]]]


#: Fig. 5(a) of the preprint, the stability chart of B in the (Omega, m) plane, read from the
#: figure's vector graphics (its shaded polygons, the frame mapped to 0 <= Omega <= 6,
#: 0 <= m <= 0.04; the line m = m_c = 0.0025 lands at 0.0025): the speeds where a horizontal
#: line m = const enters (+1) or leaves (-1) the shaded region, each bracketed by the 0.01 grid
#: it was sampled on. Above the last entry B stays stable up to the chart's end, Omega = 6.
#: Regenerate with ``python dev/digitize_rcfw_fig5a.py abbspecialissue.pdf`` (the preprint).
#: (m = 0.015 is left out: there the secondary region ends in a sliver 0.01 wide at 2.03.)
FIG5A_BOUNDARIES = {
    0.005: [(2.94, 2.95, +1)],
    0.01: [(3.52, 3.53, +1)],
    0.02: [(1.96, 1.97, +1), (2.08, 2.09, -1), (4.27, 4.28, +1)],
    0.025: [(1.91, 1.92, +1), (2.15, 2.16, -1), (4.59, 4.60, +1)],
    0.03: [(1.96, 1.97, +1), (2.23, 2.24, -1), (4.90, 4.91, +1)],
}


@pytest.mark.parametrize("m", sorted(FIG5A_BOUNDARIES))
def test_stability_boundaries_of_fig5a(m):
    """The rigid-kinematics reference crosses each boundary of Fig. 5(a) within its 0.01 bracket
    (widened by 0.005 for the drawing): the paper's Hopf curves H_cyl, H_con are reproduced."""
    sys_ = ref.TwoPlane.long_rotor(m, kinematics="rigid")
    for lo, hi, sign in FIG5A_BOUNDARIES[m]:
        before = ref.spectral_abscissa(sys_, lo - 0.005)
        after = ref.spectral_abscissa(sys_, hi + 0.005)
        assert (before < 0) != (after < 0), (lo, hi, before, after)
        assert (after < 0) == (sign > 0)


def test_lateral_kinematics_shifts_the_boundaries():
    """Without the balls' axial motion (lateral kinematics, the model of Rodrigues et al. 2011;
    rotorlab's Machine has the rigid kinematics) the primary region starts at Omega ~= 4.48
    instead of the paper's 4.60 at m = 0.025 (and 4.74 instead of 4.90 at m = 0.03): the balls' own tilt inertia matters."""
    lateral = ref.TwoPlane.long_rotor(0.025, kinematics="lateral")
    assert ref.spectral_abscissa(lateral, 4.47) > 0 > ref.spectral_abscissa(lateral, 4.49)
    assert ref.spectral_abscissa(lateral, 4.55) < 0  # the paper (and rigid kinematics): unstable
    assert ref.spectral_abscissa(ref.TwoPlane.long_rotor(0.025, kinematics="rigid"), 4.55) > 0


@pytest.mark.parametrize("kinematics", KINEMATICS)
def test_stability_over_speed(kinematics):
    """m = 0.025 (Fig. 5(a)): B is unstable at every speed below Omega_2 ("the balancing process
    only works for sufficiently high rotation speeds above the second critical frequency",
    Section 5); it is stable in a narrow secondary region just above Omega_2 (holding Omega = 2,
    Fig. 11 (i)), unstable again, and stable in the primary region up to the chart's end."""
    omegas = np.round(np.arange(0.2, 6.0001, 0.05), 6)
    sys_ = ref.TwoPlane.long_rotor(0.025, kinematics=kinematics)
    runs = _stable_intervals(sys_, omegas)
    assert len(runs) == 2, runs
    (lo1, hi1), (lo2, hi2) = runs
    assert ref.OMEGA_CON < lo1 < 2.0 < hi1 < 2.3
    assert 4.3 < lo2 < 4.8 and hi2 == omegas[-1]


@pytest.mark.parametrize("kinematics", KINEMATICS)
def test_disc_rotor_has_no_stable_balanced_state(kinematics):
    """Jp > Jt: no conical critical speed, hence no self-alignment and no stable B at any speed
    (Rodrigues et al. 2011, Section 5, Fig. 13(b), m = eps). Heavy balls that make the rotor with
    its balls long again (Jt + 4 m z^2 > Jp, whose conical critical speed is 2011 eq. (32)) give
    a stable range back: the scan can find one."""
    jt, jp = 0.5, 0.9
    assert ref.critical_speeds(1.0, jt, jp, 1.0, 9.0)[1] is None
    omegas = np.arange(0.25, 10.001, 0.25)
    for o in omegas[::8]:  # the forward conical whirl stays above the spin speed
        assert ref.whirl_frequencies(o, 1.0, jt, jp, 1.0, 9.0)[1] > o
    for eps in (0.002, 0.01, 0.025):
        sys_ = ref.TwoPlane.long_rotor(eps, eps, kinematics=kinematics, jt=jt, jp=jp)
        assert _stable_intervals(sys_, omegas) == []
    heavy = ref.TwoPlane.long_rotor(0.1, 0.01, kinematics=kinematics, jt=jt, jp=jp)
    assert jt + 4 * 0.1 * ref.RACE_Z**2 > jp
    assert _stable_intervals(heavy, np.arange(10.0, 20.01, 1.0)) != []
