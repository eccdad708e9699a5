"""``jeffcott_balls`` against Zhakash et al. 2024 (seed 002) and its corrected formulas.

Each test names the equation it checks; the corrections are listed in the docstring of
:mod:`rotorlab.models._jeffcott_balls` ("Corrections to the seeds").
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import fsolve

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams

M1, R_ECC, C_STIFF, D_ROTOR = 1.2, 2.5e-3, 250.0, 0.3
M_BALL, R_RACE, BETA0 = 0.02, 0.11, 40.0  # seed 002: equal balls, beta0 = b / (m R^2)


def _seed_accelerations(k, om, t, x, y, vx, vy, phi, w, *, M1=M1, r=R_ECC, c=C_STIFF, beta=D_ROTOR):
    """Solve eqs. (1)-(3) exactly as printed for (x'', y'', phi_s'')."""
    m, R = M_BALL, R_RACE
    M = M1 + k * m
    A = np.zeros((2 + k, 2 + k))
    f = np.zeros(2 + k)
    A[0, 0] = M
    A[0, 2:] = -m * R * np.sin(phi)
    f[0] = M1 * r * om**2 * np.cos(om * t) + m * R * np.sum(w**2 * np.cos(phi)) - beta * vx - c * x
    A[1, 1] = M
    A[1, 2:] = -m * R * np.cos(phi)
    f[1] = -M1 * r * om**2 * np.sin(om * t) - m * R * np.sum(w**2 * np.sin(phi)) - beta * vy - c * y
    for s in range(k):
        A[2 + s, 2 + s] = 1.0
        A[2 + s, 0] = -np.sin(phi[s]) / R
        A[2 + s, 1] = -np.cos(phi[s]) / R
        f[2 + s] = -BETA0 * (w[s] - om)
    return np.linalg.solve(A, f)


def _model(k, speed, *, friction=0.0, frame="fixed", eccentricity=R_ECC, damping=D_ROTOR):
    rotor = RotorParams(M1, eccentricity, C_STIFF, damping)
    ball = BallParams(M_BALL, R_RACE, damping=BETA0 * M_BALL * R_RACE**2, friction=friction)
    return JeffcottBalls(rotor, (ball,) * k, speed=ConstantSpeed(speed), frame=frame)


def test_equations_1_to_3_in_mirrored_axes():
    """Eqs. (1)-(3) are the model in the axes x_s = x, y_s = -y with phi_s = phi (omega > 0),
    or y_s = y, phi_s = -phi for the model spun clockwise; not y -> -y with phi -> -phi."""
    k, om = 3, 37.0
    ccw, cw = _model(k, om), _model(k, -om)
    rng = np.random.default_rng(2)
    worst = {"mirror": 0.0, "clockwise": 0.0, "both": 0.0}
    for _ in range(30):
        t = rng.uniform(0, 3)
        y = np.concatenate([rng.normal(scale=1e-3, size=2), rng.normal(scale=0.05, size=2),
                            rng.uniform(-6, 6, k), om + rng.normal(scale=4.0, size=k)])  # fmt: skip
        a = ccw.rhs(t, y)
        got = np.concatenate([a[2:3], -a[3:4], a[4 + k :]])
        ref = _seed_accelerations(k, om, t, y[0], -y[1], y[2], -y[3], y[4 : 4 + k], y[4 + k :])
        worst["mirror"] = max(worst["mirror"], np.max(np.abs(got - ref)) / np.max(np.abs(ref)))
        # the model turning clockwise (theta = -om t) in the seed's axes: y = y_s, phi = -phi_s
        yc = y.copy()
        yc[1], yc[3] = -y[1], -y[3]
        yc[4:] = -y[4:]
        a = cw.rhs(t, yc)
        got = np.concatenate([a[2:4], -a[4 + k :]])
        worst["clockwise"] = max(worst["clockwise"], np.max(np.abs(got - ref)) / np.max(np.abs(ref)))
        ref_both = _seed_accelerations(k, om, t, y[0], -y[1], y[2], -y[3], -y[4 : 4 + k], -y[4 + k :])
        a = ccw.rhs(t, y)
        got = np.concatenate([a[2:3], -a[3:4], -a[4 + k :]])
        worst["both"] = max(worst["both"], np.max(np.abs(got - ref_both)) / np.max(np.abs(ref_both)))
    assert worst["mirror"] < 1e-13 and worst["clockwise"] < 1e-13
    assert worst["both"] > 0.1


def _stuck_run(model, angles, t1):
    """Integrate with the balls held by friction; return final state and the smallest slip margin."""
    y0 = model.initial_state(angles)
    assert np.all(y0[-model.n_balls :] == 0.0)
    k, ev, p = model.kernels.rhs, model.kernels.events, model.to_array()

    def f(t, y):
        out = np.empty_like(y)
        k(t, y, p, out)
        return out

    sol = solve_ivp(f, (0.0, t1), y0, method="DOP853", rtol=1e-10, atol=1e-14, dense_output=True)
    assert sol.success
    g = np.empty(2 * model.n_balls)
    margin = np.inf
    for t in np.linspace(0.0, t1, 400):
        ev(t, sol.sol(t), p, g)
        margin = min(margin, g.min())
    return sol.y[:, -1], margin


@pytest.mark.parametrize("angles", [(0.7, 2.5), (0.0, 0.0), (math.pi, 1.0)])
def test_steady_response_eqs_9_10_use_the_total_mass(angles):
    """Eq. (9) with the corrected (10), W = m/M omega^2/(p^2 - omega^2): balls locked at alpha_j."""
    om = 40.0
    model = _model(2, om, friction=2.0, frame="rotating", damping=3.0)
    y_end, margin = _stuck_run(model, angles, 20.0)
    assert margin > 0  # the race held the balls all along
    amplitude = math.hypot(y_end[0], y_end[1])
    z = model.locked_response(angles)
    assert amplitude == pytest.approx(abs(z), rel=1e-7)
    np.testing.assert_allclose([y_end[0], y_end[1]], [z.real, z.imag], rtol=0, atol=1e-9 * abs(z))
    # undamped closed form of eq. (9)-(10): W R |eta + sum e^{i alpha}|, exact up to O(d^2)
    M = model.total_mass
    p2 = C_STIFF / M
    eta = M1 * R_ECC / (M_BALL * R_RACE)
    unbalance = abs(eta + sum(np.exp(1j * a) for a in angles))
    W = M_BALL / M * om**2 / (p2 - om**2)
    W_printed = M_BALL / M1 * om**2 / (p2 - om**2)
    assert amplitude == pytest.approx(abs(W) * R_RACE * unbalance, rel=5e-3)
    assert abs(abs(W_printed) * R_RACE * unbalance / amplitude - 1.0) > 0.02


def test_steady_response_without_balls():
    """n = 0: amplitude M1 e omega^2 / |c - M1 omega^2 + i d omega| after a long run."""
    om = 11.0
    model = JeffcottBalls(RotorParams(M1, R_ECC, C_STIFF, 1.5), (), speed=ConstantSpeed(om))
    k, p = model.kernels.rhs, model.to_array()

    def f(t, y):
        out = np.empty(4)
        k(t, y, p, out)
        return out

    sol = solve_ivp(f, (0.0, 40.0), np.zeros(4), method="DOP853", rtol=1e-11, atol=1e-14)
    amp = math.hypot(sol.y[0, -1], sol.y[1, -1])
    expect = M1 * R_ECC * om**2 / abs(C_STIFF - M1 * om**2 + 1j * 1.5 * om)
    assert amp == pytest.approx(expect, rel=1e-8)


def _p_corrected(alpha, om, model):
    M = model.total_mass
    W = M_BALL / M * om**2 / (C_STIFF / M - om**2)
    eta = M1 * R_ECC / (M_BALL * R_RACE)
    a = np.asarray(alpha)
    return -(om**2 * W / BETA0) * (eta * np.sin(a) + np.sum(np.sin(a[:, None] - a[None, :]), axis=1))


def test_averaged_equation_11_by_quadrature():
    """P_s = <x0'' sin phi_s + y0'' cos phi_s> / (beta0 R) on the generating solution (9)."""
    om, alpha = 30.0, np.array([0.4, 2.9, -1.7])
    model = _model(3, om, damping=0.0)
    M = model.total_mass
    W = M_BALL / M * om**2 / (C_STIFF / M - om**2)
    eta = M1 * R_ECC / (M_BALL * R_RACE)

    def xdd(t):  # seed axes: x0, y0 of eq. (9), differentiated twice
        return -(om**2) * W * R_RACE * (eta * np.cos(om * t) + np.sum(np.cos(om * t + alpha)))

    def ydd(t):
        return om**2 * W * R_RACE * (eta * np.sin(om * t) + np.sum(np.sin(om * t + alpha)))

    period = 2 * math.pi / om
    for s in range(3):
        mean = quad(lambda t: xdd(t) * np.sin(om * t + alpha[s]) + ydd(t) * np.cos(om * t + alpha[s]),
                    0.0, period, epsabs=0, epsrel=1e-12)[0] / period  # fmt: skip
        assert mean / (BETA0 * R_RACE) == pytest.approx(_p_corrected(alpha, om, model)[s], rel=1e-10)


def test_averaged_equation_11_by_simulation():
    """Strongly damped balls drift at the corrected rate P_s (no factor 1/2, negative sign)."""
    om = 2.0 * math.sqrt(C_STIFF / (M1 + 2 * M_BALL))
    model = _model(2, om, frame="rotating", damping=0.0, eccentricity=M_BALL * R_RACE / M1)
    a0 = np.array([0.5, 2.0])

    def p_s(alpha):
        M = model.total_mass
        W = M_BALL / M * om**2 / (C_STIFF / M - om**2)
        return -(om**2 * W / BETA0) * (np.sin(alpha) + np.sin(alpha - alpha[::-1]))

    y0 = model.initial_state(a0, rotor="steady", ball_rates=p_s(a0))
    k, p = model.kernels.rhs, model.to_array()

    def f(t, y):
        out = np.empty_like(y)
        k(t, y, p, out)
        return out

    t1 = 2.0
    full = solve_ivp(f, (0.0, t1), y0, method="DOP853", rtol=1e-10, atol=1e-13).y[4:6, -1] - a0
    avg = solve_ivp(lambda t, a: p_s(a), (0.0, t1), a0, rtol=1e-12, atol=1e-14).y[:, -1] - a0
    assert np.linalg.norm(full - avg) < 0.05 * np.linalg.norm(avg)
    assert np.linalg.norm(full - 0.5 * avg) > 0.3 * np.linalg.norm(avg)  # printed factor 1/2


def _jacobian_A_B(alpha, om, model):
    h = 1e-6
    jac = np.empty((2, 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = h
        jac[:, j] = (_p_corrected(alpha + e, om, model) - _p_corrected(alpha - e, om, model)) / (2 * h)
    return -np.trace(jac), np.linalg.det(jac)


@pytest.mark.parametrize("factor", [0.6, 1.8])
def test_stability_coefficients_19_to_23(factor):
    """A, B of (19) from the corrected P_s: (21), (23) without the factors 1/2, 1/4."""
    model = _model(2, 1.0)
    om = factor * math.sqrt(C_STIFF / model.total_mass)
    M = model.total_mass
    W = M_BALL / M * om**2 / (C_STIFF / M - om**2)
    K = om**2 * W / BETA0
    eta = M1 * R_ECC / (M_BALL * R_RACE)
    gamma = math.acos(eta / 2)
    cases = {
        1: ((math.pi - gamma, -(math.pi - gamma)), -2 * K, K**2 * eta**2 * (1 - eta**2 / 4)),
        2: ((0.0, 0.0), 2 * K * (1 + eta), K**2 * eta * (eta + 2)),
        3: ((math.pi, math.pi), 2 * K * (1 - eta), K**2 * eta * (eta - 2)),
        4: ((0.0, math.pi), -2 * K, -(K**2) * eta**2),
    }
    for case, (alpha, a_expect, b_expect) in cases.items():
        a, b = _jacobian_A_B(np.array(alpha), om, model)
        assert a == pytest.approx(a_expect, rel=1e-7, abs=1e-9 * abs(K)), case
        assert b == pytest.approx(b_expect, rel=1e-6, abs=1e-9 * K**2), case
    stable = {case: (a > 0 and b > 0) for case, (alpha, a, b) in cases.items()}
    assert stable == {1: factor > 1, 2: factor < 1, 3: False, 4: False}  # eta < 2 here


def _steady(model, guess):
    n = model.n_balls

    def residual(q):
        y = np.zeros(model.n_state)
        y[:2], y[4 : 4 + n] = q[:2], q[2:]
        out = model.rhs(0.0, y)
        return np.concatenate([out[2:4], out[4 + n :]])

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        q = fsolve(residual, guess, xtol=1e-13)
    y = np.zeros(model.n_state)
    y[:2], y[4 : 4 + n] = q[:2], q[2:]
    assert np.max(np.abs(model.rhs(0.0, y))) < 1e-9
    return y


@pytest.mark.parametrize("eta", [1.2, 2.6])
def test_light_side_motion_needs_short_capacity(eta):
    """Full model, (pi, pi) above p: unstable for eta < 2, stable for eta > 2 (correction to (23))."""
    model = _model(2, 1.0, frame="rotating", eccentricity=eta * M_BALL * R_RACE / M1, damping=2.0)
    om = 2.0 * model.critical_speed
    model = model.with_speed(ConstantSpeed(om))
    x = om**2 * model.rotor.imbalance * (1 - 2 / eta) / (C_STIFF - model.total_mass * om**2)
    y = _steady(model, [x, 0.0, math.pi, math.pi])
    growth = np.max(model.linearize(y).eigenvalues.real)
    assert (growth < 0) == (eta > 2)


def test_eq_25_corrected_equals_reduced_hamiltonian():
    """D = -m om^2 R^2 W [eta sum cos + 1/2 sum sum cos] - 1/2 m om^2 R^2 W eta^2 = H~* + const."""
    om = 27.0
    model = _model(3, om, frame="rotating", damping=0.0)
    M = model.total_mass
    W = M_BALL / M * om**2 / (C_STIFF / M - om**2)
    eta = M1 * R_ECC / (M_BALL * R_RACE)
    const = 0.5 * om**2 * (M1 * R_ECC**2 + 3 * M_BALL * R_RACE**2)
    rng = np.random.default_rng(5)
    for _ in range(10):
        alpha = rng.uniform(-math.pi, math.pi, 3)
        d = -M_BALL * om**2 * R_RACE**2 * W * (
            eta * np.sum(np.cos(alpha)) + 0.5 * np.sum(np.cos(alpha[:, None] - alpha[None, :]))
        )
        z = model.locked_response(alpha)
        y = np.zeros(model.n_state)
        y[0], y[1], y[4:7] = z.real, z.imag, alpha
        h = model.reduced_hamiltonian(y) + const
        assert h == pytest.approx(d - 0.5 * M_BALL * om**2 * R_RACE**2 * W * eta**2, rel=1e-12)
        # and P_s = -dD/dalpha_s / (beta0 m R^2) (gradient flow)
        grad = -M_BALL * om**2 * R_RACE**2 * W * (
            -eta * np.sin(alpha) - np.sum(np.sin(alpha[:, None] - alpha[None, :]), axis=1)
        )
        np.testing.assert_allclose(-grad / (BETA0 * M_BALL * R_RACE**2), _p_corrected(alpha, om, model), rtol=1e-12)
