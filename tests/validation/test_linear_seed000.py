"""Seed 000 (Pico 21 centrifuge): the printed data, their inconsistencies and our resolution.

Every number compared here is printed in the seed paper (``rotorlab.linear.cases._pico21_data``
holds them verbatim); tolerances follow the printed precision (10 significant digits for the
compliance coefficients and the energy forms, i.e. about 5e-10 relative).
"""

import dataclasses
import math

import numpy as np
import pytest
import sympy as sp

from rotorlab.linear import (
    RPM,
    FrequencyMeasurement,
    RigidBody,
    campbell,
    critical_speeds,
    identify_parameters,
    influence_compliance,
    modal,
)
from rotorlab.linear.cases import PICO21, RESOLVED_COMPLIANCE, audit_pico21, pico21
from rotorlab.linear.cases import pico21_influence_model
from rotorlab.linear.cases._pico21_audit import energy_in_displacements_matrix
from rotorlab.linear.cases._pico21_data import (
    PRINTED_COMPLIANCE,
    PRINTED_ENERGY_IN_FORCES,
    PRINTED_PARAMETERS,
    PRINTED_STIFFNESS,
)


def _rel(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)) / np.abs(np.asarray(b))


# --------------------------------------------------------------------------- finding 1
def test_printed_compliance_disagrees_with_printed_energy_only_in_the_m1_row():
    bad = {tuple(sorted(map(int, ij))) for ij in np.argwhere(_rel(PRINTED_COMPLIANCE,
                                                                  RESOLVED_COMPLIANCE) > 1e-8)}
    assert bad == {(1, 1), (1, 3), (1, 5)}
    rel = _rel(PRINTED_COMPLIANCE, RESOLVED_COMPLIANCE)
    assert rel[rel <= 1e-8].max() < 1e-9  # the others agree to the 10 printed digits
    assert RESOLVED_COMPLIANCE[1, 1] == pytest.approx(107.1893779e-5, rel=1e-12)


def test_rigid_housing_identity_holds_only_for_the_resolved_compliance():
    # delta(P1, M_k) = l_1 delta(M1, M_k): the stator is rigid and sits l_1 above O.
    l1 = PRINTED_PARAMETERS["l_1"][0] * 1e-3
    resolved = RESOLVED_COMPLIANCE[0, 1::2] / RESOLVED_COMPLIANCE[1, 1::2]
    printed = PRINTED_COMPLIANCE[0, 1::2] / PRINTED_COMPLIANCE[1, 1::2]
    assert np.all(_rel(resolved, l1) < 1e-9)
    assert np.all(_rel(printed, l1) > 4e-5)


def test_inverse_of_printed_compliance_disagrees_with_printed_stiffness_resolved_agrees():
    # The condition number 1.5e6 turns a 4e-5 misprint into a factor 2.2.
    assert np.linalg.cond(RESOLVED_COMPLIANCE) == pytest.approx(1.47e6, rel=0.01)
    from_printed = np.linalg.inv(PRINTED_COMPLIANCE)
    assert from_printed[2, 4] / PRINTED_STIFFNESS[2, 4] == pytest.approx(2.18, abs=0.01)
    assert _rel(from_printed, PRINTED_STIFFNESS).max() > 1.0
    # 10 printed digits times the condition number bound what the inverse can reproduce.
    assert _rel(np.linalg.inv(RESOLVED_COMPLIANCE), PRINTED_STIFFNESS).max() < 2e-5


def test_energy_in_forces_has_all_21_terms_and_is_delta_as_quadratic_form():
    assert len(PRINTED_ENERGY_IN_FORCES) == 21
    f = np.array([0.3, -1.1, 2.0, 0.7, -0.4, 1.3])
    printed_pi = sum(c * f[["P1", "M1", "P2", "M2", "P3", "M3"].index(a)]
                     * f[["P1", "M1", "P2", "M2", "P3", "M3"].index(b)]
                     for (a, b), c in PRINTED_ENERGY_IN_FORCES.items())
    assert 0.5 * f @ RESOLVED_COMPLIANCE @ f == pytest.approx(printed_pi, rel=1e-14)


# --------------------------------------------------------------------------- findings 2, 3
def test_stiffness_row_p1_misprinted_labels_and_symmetry():
    K = PRINTED_STIFFNESS
    assert np.abs(K - K.T).max() / np.abs(K).max() < 1e-12
    findings = {f.key: f for f in audit_pico21()}
    assert findings["stiffness-labels"].measure == 2.0


def test_energy_in_displacements_misprints_are_found_and_y_plane_is_complete():
    Cx, nx = energy_in_displacements_matrix("x")
    Cy, ny = energy_in_displacements_matrix("y")
    assert sorted(k for k, v in nx.items() if v > 1) == [(0, 1), (3, 3)]
    assert len(ny) == 21 and set(ny.values()) == {1}
    Ks = 0.5 * (PRINTED_STIFFNESS + PRINTED_STIFFNESS.T)
    # eta1^2: 1.2333251673e8 has an extra digit; 1.233251673e8 matches K11 / 2
    assert _rel(Cy[0, 0], Ks[0, 0]) == pytest.approx(6.0e-5, rel=0.01)
    assert _rel(2 * 1.233251673e8, Ks[0, 0]) < 1e-7
    rest = _rel(Cy, Ks)
    rest[0, 0] = 0.0
    assert rest.max() < 1e-5
    # the x-plane misprints: psi2^2 printed twice (16203.81 is theta3^2's twin) ...
    assert Cy[5, 5] == pytest.approx(2 * 16203.81435)
    # ... and psi1 xi1 printed twice (5.229e6 is theta1 eta2's twin)
    assert Cy[1, 2] == pytest.approx(5.229315675e6)


# --------------------------------------------------------------------------- finding 4
def test_per_body_kinetic_energy_has_the_gyroscopic_term_the_printed_total_drops():
    t = sp.symbols("t")
    Om, Ia, Ip, m = sp.symbols("Omega I_A I_P m", positive=True)
    xi, eta, psi, theta = (sp.Function(n)(t) for n in ("xi", "eta", "psi", "theta"))
    gamma_dot = Om
    # T_3R of the seed, linearised (psi' theta is the small product kept)
    T_body = (m * (xi.diff(t) ** 2 + eta.diff(t) ** 2) / 2
              + Ia * (psi.diff(t) ** 2 + theta.diff(t) ** 2) / 2
              + Ip * (gamma_dot + psi.diff(t) * theta) ** 2 / 2)
    T_total = (m * (xi.diff(t) ** 2 + eta.diff(t) ** 2) / 2
               + Ia * (psi.diff(t) ** 2 + theta.diff(t) ** 2) / 2 + Ip * gamma_dot ** 2 / 2)

    def lagrange(T, q):
        return sp.expand(sp.diff(T.diff(q.diff(t)), t) - T.diff(q))

    eps = sp.Symbol("epsilon")

    def linear(eq):  # the part of first order in the small coordinates
        scaled = eq.subs({psi: eps * psi, theta: eps * theta}).doit()
        return sp.expand(scaled).coeff(eps, 1)

    eqs_body = [linear(lagrange(T_body, q)) for q in (psi, theta)]
    eqs_total = [linear(lagrange(T_total, q)) for q in (psi, theta)]
    # psi-equation: I_A psi'' + I_P Omega theta'; theta-equation: I_A theta'' - I_P Omega psi'
    assert sp.simplify(eqs_body[0] - (Ia * psi.diff(t, 2) + Ip * Om * theta.diff(t))) == 0
    assert sp.simplify(eqs_body[1] - (Ia * theta.diff(t, 2) - Ip * Om * psi.diff(t))) == 0
    assert sp.simplify(eqs_total[0] - Ia * psi.diff(t, 2)) == 0  # no gyroscopic coupling
    # our rigid body: G[phi_x, phi_y] = +I_p, G[phi_y, phi_x] = -I_p (psi -> phi_x, theta -> phi_y)
    g = RigidBody(0, 1.0, 1.0, 1.5).G()
    assert (g[2, 3], g[3, 2]) == (1.5, -1.5)


def test_without_gyroscopic_terms_the_frequencies_would_not_depend_on_speed():
    s = pico21()
    frozen = dataclasses.replace(s, G=np.zeros_like(s.G))
    at_speed = modal(frozen, 10000 * RPM).frequency
    np.testing.assert_allclose(at_speed, modal(frozen, 0.0).frequency, rtol=1e-10)
    assert np.ptp(modal(s, 10000 * RPM).frequency[2:4]) > 1.0  # split by > 1 Hz


# --------------------------------------------------------------------------- findings 5, 6
def test_stator_inertia_units_and_armature_pair():
    findings = {f.key: f for f in audit_pico21()}
    assert findings["stator-inertia-units"].measure < 0.01
    assert findings["armature-inertia-pair"].measure > 2.0
    with pytest.raises(ValueError, match="RigidBody.polar_inertia must be <="):
        RigidBody(1, 0.6, 93e-6, 425e-6)  # the armature as printed
    body = PICO21.bodies()[1]
    assert body.polar_inertia / body.diametral_inertia == pytest.approx(93 / 425)
    assert math.sqrt(PICO21.stator_diametral_inertia / PICO21.stator_mass) == pytest.approx(
        0.0866, abs=1e-4)


def test_audit_lists_every_finding_in_order():
    keys = [f.key for f in audit_pico21()]
    assert keys == ["compliance-digits", "stiffness-labels", "energy-in-displacements",
                    "kinetic-energy-gyroscopic", "stator-inertia-units", "armature-inertia-pair",
                    "degrees-of-freedom"]
    for f in audit_pico21():
        assert f.printed and f.resolved and f.evidence


# --------------------------------------------------------------------------- geometry
def test_geometry_reproduces_every_printed_compliance_coefficient():
    delta = influence_compliance(pico21_influence_model())
    assert _rel(delta, RESOLVED_COMPLIANCE).max() < 6e-10


def _seed_energy_matrix(d):
    """Pi = 1/2 v^T Q v, v = (P1, M1, P2, M2, P3, M3, X), from the seed's integrals."""
    ei, L1, L2, L3, l = (d.shaft_flexural_rigidity, d.stator_position, d.armature_position,
                         d.rotor_position, d.bearing_position)
    b1, b2, b3 = L3 - l, L3 - L2, L3  # x from the rotor down to the clamp at O
    gx, gw = np.polynomial.legendre.leggauss(3)
    Q = np.zeros((7, 7))
    for a, b in ((0.0, b1), (b1, b2), (b2, b3)):
        for xi, wi in zip(gx, gw):
            x = 0.5 * (a + b) + 0.5 * (b - a) * xi
            c = np.zeros(7)  # bending moment M(x) = c . v
            c[5], c[4] = 1.0, x
            if x > b1:
                c[6] = -(x - b1)
            if x > b2:
                c[3], c[2] = 1.0, x - b2
            Q += 0.5 * (b - a) * wi * np.outer(c, c) / ei
    Q[6, 6] += 1.0 / d.bearing_stiffness
    q0 = np.array([-1, 0, -1, 0, -1, 0, 0.0])
    m0 = np.array([L1, 1, L2, 1, L3, 1, 0.0])
    Q += np.outer(q0, q0) / d.support_translational_stiffness
    Q += np.outer(m0, m0) / d.support_rotational_stiffness
    return Q, (b1, b2, b3)


def test_castigliano_menabrea_from_the_seed_integrals_gives_our_influence_coefficients():
    Q, (b1, b2, b3) = _seed_energy_matrix(PICO21)
    x_of_loads = -Q[6, :6] / Q[6, 6]  # Menabrea: dPi/dX = 0
    delta = Q[:6, :6] - np.outer(Q[:6, 6], Q[6, :6]) / Q[6, 6]
    np.testing.assert_allclose(delta, influence_compliance(pico21_influence_model()), rtol=1e-11)
    # the seed's printed X, with 2K = 2((b3 - b1)^3 + 3 EI / C_Pi)
    ei, cpi = PICO21.shaft_flexural_rigidity, PICO21.bearing_stiffness
    K2 = 2.0 * ((b3 - b1) ** 3 + 3.0 * ei / cpi)
    printed_x = np.array([
        0.0, 0.0,
        (-3 * b3**2 * b1 + 6 * b1 * b2 * b3 - 3 * b2**2 * b1 + 2 * b3**3 + b2**3
         - 3 * b3**2 * b2) / K2,
        (6 * b1 * b2 - 3 * b2**2 + 3 * b3**2 - 6 * b1 * b3) / K2,
        (b1**3 - 3 * b3**2 * b1 + 2 * b3**3) / K2,
        (3 * b3**2 - 6 * b1 * b3 + 3 * b1**2) / K2,
    ])
    np.testing.assert_allclose(x_of_loads, printed_x, rtol=1e-12, atol=1e-15)


def test_printed_closed_forms_of_pi1_and_pi2_are_the_integrals():
    x, b1, b2, EI, M3, P3, X = sp.symbols("x b1 b2 EI M3 P3 X")
    pi1 = sp.integrate((M3 + P3 * x) ** 2, (x, 0, b1)) / (2 * EI)
    printed1 = (3 * M3**2 * b1 + 3 * M3 * P3 * b1**2 + P3**2 * b1**3) / (6 * EI)
    assert sp.simplify(pi1 - printed1) == 0
    pi2 = sp.integrate((M3 + P3 * x - X * (x - b1)) ** 2, (x, b1, b2)) / (2 * EI)
    printed2 = ((b2**3 - b1**3) * P3**2 + (-3 * b1**2 + 3 * b2**2) * M3 * P3
                + (3 * b1 * b2**2 - 2 * b2**3 - b1**3) * X * P3 + (3 * b2 - 3 * b1) * M3**2
                + (-3 * b1**2 + 6 * b1 * b2 - 3 * b2**2) * X * M3
                + (b2**3 - 3 * b1 * b2**2 + 3 * b2 * b1**2 - b1**3) * X**2) / (6 * EI)
    assert sp.simplify(pi2 - printed2) == 0


def test_three_sources_give_the_same_machine():
    f = [modal(pico21(source=s), 8000 * RPM).frequency
         for s in ("compliance", "stiffness", "geometry")]
    np.testing.assert_allclose(f[1], f[0], rtol=2e-6)
    np.testing.assert_allclose(f[2], f[0], rtol=2e-6)
    with pytest.raises(ValueError, match="source must be"):
        pico21(source="printed")


# --------------------------------------------------------------------------- dynamics
def test_pico21_campbell_invariants():
    ds = campbell(pico21(), RPM * np.linspace(0.0, 15000.0, 61), n_modes=6)
    f0 = ds.frequency.isel(speed=0).values
    np.testing.assert_allclose(f0[0::2], f0[1::2], rtol=1e-10)  # equal pairs at rest
    assert bool(ds.stable.all())
    np.testing.assert_array_equal(ds.growth_rate.values, 0.0)  # undamped: neutrally stable
    for k in range(6):
        w = np.unique(ds.whirl.values[:, k])
        assert w.size == 1 and w[0] != 0
        d = np.diff(ds.frequency.values[:, k])
        if k >= 2:  # rocking and tilting modes: forward rises, backward falls
            assert np.all(d * w[0] > 0)
    # 1x crossings equal the exact critical speeds of the undamped pencil
    exact = critical_speeds(pico21(), max_speed=15000 * RPM).speed_rpm
    np.testing.assert_allclose(ds.critical_speed_rpm.values, exact, rtol=1e-9)


def test_identify_support_stiffness_from_frequencies_at_rest_and_at_speed():
    true = PICO21

    def build(p):
        return pico21(dataclasses.replace(true, support_translational_stiffness=p[0],
                                          support_rotational_stiffness=p[1]), source="geometry")

    meas = []
    for rpm, modes in ((0.0, (0, 2)), (3000.0, (2, 3)), (6000.0, (2, 3))):
        f = np.sort(modal(build([true.support_translational_stiffness,
                                 true.support_rotational_stiffness]), rpm * RPM).frequency)
        meas += [FrequencyMeasurement(rpm * RPM, k, f[k]) for k in modes]
    res = identify_parameters(build, [2.0 * true.support_translational_stiffness,
                                      0.5 * true.support_rotational_stiffness], meas,
                              names=("C_Q", "C_M"))
    assert res.success
    assert res.as_dict()["C_Q"] == pytest.approx(true.support_translational_stiffness, rel=1e-6)
    assert res.as_dict()["C_M"] == pytest.approx(true.support_rotational_stiffness, rel=1e-6)
    assert res.rms < 1e-8
    # 1 % noise: the estimate moves by about that much and the residual shows it
    rng = np.random.default_rng(1)
    noisy = [dataclasses.replace(m, frequency=m.frequency * (1 + 0.01 * rng.standard_normal()))
             for m in meas]
    res = identify_parameters(build, [13000.0, 1000.0], noisy, names=("C_Q", "C_M"))
    assert 0.002 < res.rms < 0.02
    assert res.as_dict()["C_Q"] == pytest.approx(true.support_translational_stiffness, rel=0.05)
    assert np.all(res.relative_std < 0.05)
    ds = res.to_dataset()
    assert ds.residual.attrs["units"] == "1" and ds.sizes["measurement"] == 6
