"""The ``toroidal_ball`` kernel against an independent sympy derivation and seed 004 as printed.

Derivation: a ball (mass m, radius r, central inertia 2/5 m r^2) rolls without slip and without
pivoting relative to the body inside the tube of a torus turning at omega about z. Its centre is
``c = s e x + (R + a sin(alpha)) (cos(psi) x + sin(psi) y) - a cos(alpha) z`` in the co-rotating
frame (a = R1 - r; s = +1 is seed 004 coordinates (1)-(2), s = -1 the convention of eqs.
(4)-(5)), its angular velocity ``omega z + (c'_rel x n) / r`` with n the outward normal of the
tube. The rolling constraint is non-holonomic, so the equations come from the
Lagrange-d'Alembert principle (Kane's equations): for each generalized speed u_j,
``(G - m a_c) . dv_c/du_j - I (dOmega/dt) . dOmega/du_j = 0``. Substituting the constraint into
the Lagrangian and applying Euler-Lagrange equations instead gives different (wrong) equations;
the difference is shown below. Everything is compared numerically at random states (sympy
expressions are lambdified, not simplified, so the module runs in seconds).

References: Strautmanis, seed 004, eqs. (1)-(6).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp

from rotorlab.models._toroidal_ball import ToroidalBall, strautmanis_torus

t = sp.Symbol("t")
R, a, r, e, w, g, m = sp.symbols("R a r e omega g m", positive=True)
s = sp.Symbol("s")
psi, al, sig = (sp.Function(n)(t) for n in ("psi", "alpha", "sigma"))
X, Y = sp.symbols("X Y")  # placeholders for psi'', alpha'' in lambdified expressions


def _vectors(pivot: bool):
    Z = sp.Matrix([0, 0, 1])
    rho = R + a * sp.sin(al)
    rhat = sp.Matrix([sp.cos(psi), sp.sin(psi), 0])
    c = s * e * sp.Matrix([1, 0, 0]) + rho * rhat - a * sp.cos(al) * Z
    n = sp.sin(al) * rhat - sp.cos(al) * Z
    wz = w * Z
    c_rel = c.diff(t)
    omega_ball = wz + c_rel.cross(n) / r + (sig * n if pivot else sp.zeros(3, 1))
    v_c = c_rel + wz.cross(c)

    def absolute_rate(v):
        return v.diff(t) + wz.cross(v)

    return c, n, v_c, absolute_rate(v_c), omega_ball, absolute_rate(omega_ball)


def _placeholders(expr):
    reps = {psi.diff(t, 2): X, al.diff(t, 2): Y, sig.diff(t): sp.Symbol("S_dot")}
    expr = expr.subs(reps)
    P, A, dP, dA, S = sp.symbols("P A dP dA S")
    expr = expr.subs({psi.diff(t): dP, al.diff(t): dA, sig: S}).subs({psi: P, al: A})
    return expr, (P, A, dP, dA, S)


@functools.lru_cache(maxsize=None)
def _equations(method: str, pivot: bool = False):
    """Lambdified (mass matrix, rhs) in the accelerations (psi'', alpha''[, sigma'])."""
    c, n, v_c, a_c, om, dom = _vectors(pivot)
    inertia = sp.Rational(2, 5) * m * r**2
    grav = sp.Matrix([0, 0, -m * g])
    speeds = [psi.diff(t), al.diff(t)] + ([sig] if pivot else [])
    if method == "kane":
        eqs = [(grav - m * a_c).dot(v_c.diff(u)) - inertia * dom.dot(om.diff(u)) for u in speeds]
    else:  # constraint substituted into L = T - V, Euler-Lagrange as if holonomic
        lag = m * v_c.dot(v_c) / 2 + inertia * om.dot(om) / 2 - m * g * c[2]
        eqs = [-(lag.diff(u).diff(t) - lag.diff(q)) for u, q in zip(speeds, [psi, al])]
    eqs = [_placeholders(eq)[0] for eq in eqs]
    acc = [X, Y] + ([sp.Symbol("S_dot")] if pivot else [])
    mass = sp.Matrix([[eq.diff(x) for x in acc] for eq in eqs])
    rest = sp.Matrix([-eq.subs({x: 0 for x in acc}) for eq in eqs])
    args = (*_placeholders(psi)[1], R, a, r, e, w, g, s, m)
    return sp.lambdify(args, mass, "numpy"), sp.lambdify(args, rest, "numpy")


def _derived(model: ToroidalBall, y, sign_e: float, method="kane", sigma=None):
    mass_f, rest_f = _equations(method, sigma is not None)
    args = (y[0], y[1], y[2], y[3], 0.0 if sigma is None else sigma, model.ring_radius,
            model.tube_offset, model.ball_radius, model.offset, model.spin_speed, model.gravity,
            sign_e, 1.0)  # fmt: skip
    return np.linalg.solve(np.array(mass_f(*args), dtype=float), np.array(rest_f(*args), dtype=float).ravel())


def _normal_derived(model: ToroidalBall, y, sign_e: float) -> float:
    """N = (g_vec - a_c) . n per unit mass (the tube pushes the ball towards the tube centre)."""
    f = _normal_fn()
    return float(f(*y[:4], model.ring_radius, model.tube_offset, model.offset, model.spin_speed,
                   model.gravity, sign_e))  # fmt: skip


@functools.lru_cache(maxsize=None)
def _normal_fn():
    c, n, v_c, a_c, om, dom = _vectors(False)
    expr = (sp.Matrix([0, 0, -g]) - a_c).dot(n)
    expr, (P, A, dP, dA, S) = _placeholders(expr)
    expr = expr.subs({X: 0, Y: 0})  # the tangential accelerations are normal to n
    return sp.lambdify((P, A, dP, dA, R, a, e, w, g, s), expr, "numpy")


def _random_states(rng, count):
    for _ in range(count):
        yield np.array([rng.uniform(-7, 7), rng.uniform(-3, 3), rng.uniform(-200, 200), rng.uniform(-500, 500)])


def _kernel(model: ToroidalBall, y4) -> np.ndarray:
    """(psi'', alpha'') of the rolling kernel without rolling resistance."""
    y = np.concatenate([y4, [1.0, 1.0, 0.0]])
    return model.rhs(0.0, y)[2:4]


MODEL = ToroidalBall(0.2, 0.015, 0.0125, 140.0, 0.02, 0.0)
ODD = ToroidalBall(0.31, 0.04, 0.011, 57.0, 0.047, 0.0, gravity=7.3)  # no accidental cancellations


@pytest.mark.parametrize("model", [MODEL, ODD], ids=["seed", "odd"])
def test_rolling_kernel_is_kanes_equations_with_offset_towards_pi(model):
    rng = np.random.default_rng(4)
    for y in _random_states(rng, 25):
        ref = _derived(model, y, -1.0)
        np.testing.assert_allclose(_kernel(model, y), ref, rtol=1e-11, atol=1e-9 * np.abs(ref).max())


def test_coordinates_1_2_put_the_working_position_at_psi_0():
    # With +e as in (1)-(2) the offset term flips sign: the far point of the ring (the stable
    # rest position) is psi = 0, while eqs. (4)-(5) and psi = 3.14156 belong to -e.
    y = np.array([0.3, math.pi / 2, 0.0, 0.0])
    plus, minus = _derived(MODEL, y, +1.0), _derived(MODEL, y, -1.0)
    rho = MODEL.ring_radius + MODEL.tube_offset
    term = 5.0 / 7.0 * MODEL.offset * MODEL.spin_speed**2 * math.sin(0.3) / rho
    assert plus[0] == pytest.approx(-term, rel=1e-12)
    assert minus[0] == pytest.approx(term, rel=1e-12)


def test_normal_force_of_kernel_is_newtons_normal_component():
    rng = np.random.default_rng(6)
    for model in (MODEL, ODD):
        for y in _random_states(rng, 10):
            n_kernel = model.forces(np.concatenate([y, [1.0, 1.0, 0.0]]))["N"]
            assert float(n_kernel) == pytest.approx(_normal_derived(model, y, -1.0), rel=1e-12, abs=1e-9)


def _printed(model: ToroidalBall, t_, y, k):
    """Seed 004 eqs. (4)-(6) exactly as printed (phi = omega t, brackets not simplified)."""
    Rr, R1, rb, om, ee, gg = (model.ring_radius, model.tube_radius, model.ball_radius,
                              model.spin_speed, model.offset, model.gravity)  # fmt: skip
    aa = R1 - rb
    p, al_, dp, da = y
    phi = om * t_
    normal = gg * math.cos(al_) + Rr * (om + dp) ** 2 * math.sin(al_) + aa * da**2
    ddp = (-10 * aa / (7 * Rr) * (om + dp) * da * math.cos(al_)
           + 5 * ee * om**2 / (7 * Rr) * (math.cos(phi) * math.sin(phi + p) - math.sin(phi) * math.cos(phi + p))
           - 5 * normal * k / (7 * Rr * rb) * np.sign(dp))
    dda = (-5 * ee * om**2 * math.cos(al_) / (7 * aa) * (math.cos(phi) * math.cos(phi + p) + math.sin(phi) * math.sin(phi + p))
           + 5 * Rr * math.cos(al_) / (7 * aa) * (om + dp) ** 2 - 5 * gg * math.sin(al_) / (7 * aa)
           - 5 * normal * k * R1 / (7 * aa**2 * rb) * np.sign(da))  # fmt: skip
    return np.array([ddp, dda]), normal


@pytest.mark.parametrize("k", [1e-5, 1e-4])
def test_paper_form_is_eqs_4_to_6_as_printed(k):
    rng = np.random.default_rng(5)
    for base in (strautmanis_torus(k, form="paper"), ToroidalBall(0.31, 0.04, 0.011, 57.0, 0.047, k, 7.3, "paper")):
        for y in _random_states(rng, 20):
            y[1] = rng.uniform(0.0, 3.0)  # alpha in (0, pi) keeps N > 0 (no clipping)
            modes = np.sign(y[2:4])
            t_ = rng.uniform(0.0, 5.0)
            ref, normal = _printed(base, t_, y, k)
            full = np.concatenate([y, modes, [0.0]])
            np.testing.assert_allclose(base.rhs(t_, full)[2:4], ref, rtol=1e-12, atol=1e-9)
            assert float(base.forces(full)["N"]) == pytest.approx(normal, rel=1e-13)


def test_paper_form_is_the_rolling_form_with_the_documented_approximations():
    # derived - printed = the terms listed in the model's docstring (items 2 and 3): rho -> R,
    # relative terms scaled by 5/7 instead of 1, Coriolis terms 10/7 omega instead of 12/7 omega.
    rng = np.random.default_rng(9)
    paper = strautmanis_torus(0.0, form="paper")
    a_, Rr, om, ee = MODEL.tube_offset, MODEL.ring_radius, MODEL.spin_speed, MODEL.offset
    for y in _random_states(rng, 10):
        p, al_, dp, da = y
        rho, ca = Rr + a_ * math.sin(al_), math.cos(al_)
        d_psi = (-(a_ * ca / rho) * da * (2 * dp + 12 / 7 * om) + 10 / 7 * (a_ * ca / Rr) * (om + dp) * da
                 + 5 / 7 * ee * om**2 * math.sin(p) * (1 / rho - 1 / Rr))
        d_alpha = (rho * ca / a_) * (dp**2 + 12 / 7 * om * dp + 5 / 7 * om**2) - 5 / 7 * (Rr * ca / a_) * (om + dp) ** 2
        np.testing.assert_allclose(_derived(MODEL, y, -1.0) - _kernel(paper, y), [d_psi, d_alpha],
                                   rtol=1e-9, atol=1e-7)  # fmt: skip


def test_naive_lagrangian_differs_by_gyroscopic_terms():
    # Treating the rolling constraint as holonomic adds terms proportional to omega r cos(alpha)
    # (here several percent of psi''); they vanish for a body at rest or a ball at alpha = pi/2.
    y = np.array([1.0, 0.7, 20.0, 150.0])
    kane, naive = _derived(MODEL, y, -1.0), _derived(MODEL, y, -1.0, method="naive")
    assert abs(naive[0] - kane[0]) > 0.01 * abs(kane[0])
    still = ToroidalBall(0.2, 0.015, 0.0125, 1e-12, 0.02)
    np.testing.assert_allclose(_derived(still, y, -1.0, method="naive"), _derived(still, y, -1.0), rtol=1e-9)
    side = np.array([1.0, math.pi / 2, 20.0, 150.0])
    np.testing.assert_allclose(_derived(MODEL, side, -1.0, method="naive"), _derived(MODEL, side, -1.0), rtol=1e-9)


def test_free_pivot_agrees_at_zero_relative_pivot_spin():
    # A ball free to pivot (Chaplygin ball) has one more speed, sigma = relative pivot spin; at
    # sigma = 0 its accelerations are the model's, and sigma' = alpha' (a omega sin(alpha) -
    # R psi') / r builds up only while the ball rolls across the tube.
    rng = np.random.default_rng(8)
    for y in _random_states(rng, 5):
        acc = _derived(MODEL, y, -1.0, sigma=0.0)
        np.testing.assert_allclose(acc[:2], _kernel(MODEL, y), rtol=1e-10)
        expected = y[3] * (MODEL.tube_offset * MODEL.spin_speed * math.sin(y[1]) - MODEL.ring_radius * y[2]) / MODEL.ball_radius
        assert acc[2] == pytest.approx(expected, rel=1e-10)


def test_rolling_resistance_lever_arms():
    # The ball's angular velocity relative to the body is (c'_rel x n) / r: |d/dpsi'| = rho / r
    # along the ring, |d/dalpha'| = a / r across it. A resistance torque k N per direction gives
    # generalized forces k N rho / r and k N a / r, over the generalized masses 7/5 rho^2 and
    # 7/5 a^2: B_psi = 5/7 k N / (rho r), B_alpha = 5/7 k N / (a r). Eq. (5) prints a factor
    # R1 / a larger (6 with the seed's numbers).
    c, n, v_c, a_c, om, dom = _vectors(False)
    rel = om - sp.Matrix([0, 0, w])
    lever_psi = sp.sqrt(sum(x**2 for x in rel.diff(psi.diff(t))))
    lever_al = sp.sqrt(sum(x**2 for x in rel.diff(al.diff(t))))
    vals = {R: 0.2, a: 0.0025, r: 0.0125, al: 1.1, psi: 0.4}
    assert float(lever_psi.subs(vals)) == pytest.approx((0.2 + 0.0025 * math.sin(1.1)) / 0.0125, rel=1e-12)
    assert float(lever_al.subs(vals)) == pytest.approx(0.0025 / 0.0125, rel=1e-12)
    k = 1e-5
    y = np.array([3.0, 1.2, 0.0, 0.0, 0.0, 0.0, 0.0])
    f_r, f_p = strautmanis_torus(k).forces(y), strautmanis_torus(k, form="paper").forces(y)
    assert float(f_r["B_alpha"]) == pytest.approx(5 / 7 * k * float(f_r["N"]) / (0.0025 * 0.0125), rel=1e-12)
    assert float(f_p["B_alpha"] / f_p["N"]) / float(f_r["B_alpha"] / f_r["N"]) == pytest.approx(0.015 / 0.0025)
