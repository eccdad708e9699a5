"""Hamilton function, energy and steady motions of ``jeffcott_balls`` (Filimonikhin & Filimonikhina).

- H* = T2 + Pi - T0 (eq. (4)) is conserved in the co-rotating frame without damping at constant
  speed, and dH*/dt = -2 Phi with ball damping (eq. (5), with the corrected eq. (2));
- with the prescribed spin the energy is *not* conserved: dE/dt = omega tau_drive - 2 Phi;
- steady motions (eqs. (11)-(13)) are equilibria of the co-rotating kernel; H~* on them is (14),
  (15); the corrected case 2b (least H~* for all balls on the light side);
- the linearization (M, C, G, K, A) against finite differences, and the stability it predicts.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams

ROTOR = RotorParams(disc_mass=1.5, eccentricity=4e-3, stiffness=600.0)
BALLS = (
    BallParams(0.05, 0.08, inertia=0.05 * 0.08**2 * 1.4),
    BallParams(0.07, 0.10),
    BallParams(0.04, 0.09, inertia=0.04 * 0.09**2 + 2e-5),
)


def _integrate(model, y0, t1, extra=None, n_out=41, rtol=1e-12, atol=1e-14):
    """DOP853 on the compiled kernel; ``extra(t, y)`` appends an integrated quantity."""
    k, p = model.kernels.rhs, model.to_array()

    def f(t, y):
        out = np.empty(model.n_state)
        k(t, y[: model.n_state], p, out)
        if extra is None:
            return out
        return np.append(out, extra(t, y[: model.n_state]))

    z0 = np.asarray(y0, dtype=float) if extra is None else np.append(y0, 0.0)
    ts = np.linspace(0.0, t1, n_out)
    sol = solve_ivp(f, (0.0, t1), z0, method="DOP853", t_eval=ts, rtol=rtol, atol=atol)
    assert sol.success
    return sol.t, sol.y.T


def test_hamiltonian_is_conserved_without_damping():
    """Jacobi integral: |H*(t) - H*(0)| < 1e-9 of the size of its varying parts."""
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(40.0), frame="rotating")
    y0 = model.initial_state([0.4, 2.0, -2.2], ball_rates=[3.0, -5.0, 1.0])
    y0[:4] = [1e-3, -2e-3, 0.05, 0.02]
    ts, ys = _integrate(model, y0, 3.0)
    h = model.hamiltonian(ys)
    scale = np.max(np.abs(model.hamiltonian(ys) - model.reduced_hamiltonian(ys)))  # T2
    assert np.max(np.abs(h - h[0])) < 1e-9 * scale
    assert np.ptp(model.reduced_hamiltonian(ys)) > 0.1 * scale  # the motion is not trivial
    # the same in the fixed frame: H* is frame-independent given the time
    fixed = model.with_frame("fixed")
    yf = model.to_frame(ts, ys, "fixed")
    np.testing.assert_allclose(fixed.hamiltonian(yf, ts), h, rtol=1e-12, atol=1e-12 * scale)


def test_energy_is_not_conserved_but_balanced_by_the_drive():
    """dE/dt = omega tau_drive - 2 Phi (run-up with all dampings): E changes, the balance holds."""
    rotor = RotorParams(1.5, 4e-3, 600.0, damping=1.5)
    balls = tuple(BallParams(b.mass, b.radius, b.inertia, damping=2e-3) for b in BALLS)
    model = JeffcottBalls(rotor, balls, speed=LinearRamp(5.0, 45.0, 1.5), frame="fixed")
    y0 = model.initial_state([0.4, 2.0, -2.2], ball_rates=[3.0, -5.0, 1.0])

    def power(t, y):
        om = float(model.speed.spin_speed(t))
        return om * model.drive_torque(t, y) - 2.0 * model.dissipation(y, t)

    ts, zs = _integrate(model, y0, 2.0, extra=power, rtol=1e-11, atol=1e-13)
    e = model.energy(ts, zs[:, :-1])
    assert abs(e[-1] - e[0]) > 1.0  # the drive did work
    np.testing.assert_allclose(e - e[0], zs[:, -1], rtol=0, atol=1e-8 * np.max(np.abs(e)))


@pytest.mark.parametrize("rotor_damping", [0.0, 2.0])
def test_hamiltonian_rate_equals_minus_twice_rayleigh(rotor_damping):
    """Eq. (5): dH*/dt = -2 Phi (d = 0); with d > 0 the exact rate sum q' Q of eq. (2)."""
    rotor = RotorParams(1.5, 4e-3, 600.0, damping=rotor_damping)
    balls = tuple(BallParams(b.mass, b.radius, b.inertia, damping=(i + 1) * 1e-3) for i, b in enumerate(BALLS))
    model = JeffcottBalls(rotor, balls, speed=ConstantSpeed(40.0), frame="rotating")
    y0 = model.initial_state([0.4, 2.0, -2.2], ball_rates=[3.0, -5.0, 1.0])
    y0[:4] = [1e-3, -2e-3, 0.05, 0.02]
    ts, zs = _integrate(model, y0, 2.0, extra=lambda t, y: model.hamiltonian_rate(y), rtol=1e-11, atol=1e-13)
    ys = zs[:, :-1]
    h = model.hamiltonian(ys)
    assert h[-1] - h[0] < -0.05 * np.max(np.abs(h - model.reduced_hamiltonian(ys)))  # it decays
    np.testing.assert_allclose(h - h[0], zs[:, -1], rtol=0, atol=1e-8 * np.ptp(h))
    if rotor_damping == 0.0:
        np.testing.assert_allclose(model.hamiltonian_rate(ys), -2.0 * model.dissipation(ys), rtol=1e-13)
    else:
        assert not np.allclose(model.hamiltonian_rate(ys), -2.0 * model.dissipation(ys), rtol=1e-3)


def _side_motion(model, om, k_bits):
    """Eq. (13): psi_i = pi k_i, y = 0, x = om^2 (Me + s(k)) / (c - M om^2)."""
    s = sum(b.static_moment * (-1) ** k for b, k in zip(model.balls, k_bits))
    x = om**2 * (model.imbalance + s) / (model.rotor.stiffness - model.total_mass * om**2)
    y = np.zeros(model.n_state)
    y[0] = x
    y[4 : 4 + model.n_balls] = np.pi * np.asarray(k_bits, dtype=float)
    return y, s


@pytest.mark.parametrize("om", [12.0, 35.0])
def test_steady_motions_and_their_hamiltonian(om):
    """Eqs. (11)-(15): side motions are equilibria; 2 H~*(k) = -om^4 (Me + s)^2/(c - M om^2) - om^2 J."""
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(om), frame="rotating")
    const = om**2 * (model.imbalance * ROTOR.eccentricity + sum(b.inertia for b in BALLS))
    den = ROTOR.stiffness - model.total_mass * om**2
    values = {}
    for bits in itertools.product((0, 1), repeat=3):
        y, s = _side_motion(model, om, bits)
        assert np.max(np.abs(model.rhs(0.0, y))) < 1e-12
        h2 = 2.0 * model.reduced_hamiltonian(y)
        assert h2 == pytest.approx(-(om**4) * (model.imbalance + s) ** 2 / den - const, rel=1e-13)
        values[bits] = h2
    if om < model.critical_speed:  # case 1: all balls on the heavy side give the least H~*
        assert min(values, key=values.get) == (0, 0, 0)
    else:
        assert min(values, key=values.get) != (0, 0, 0)
    # main motion (12): two balls balance the rotor, eq. (14)
    two = JeffcottBalls(ROTOR, (BALLS[1], BALLS[1]), speed=ConstantSpeed(om), frame="rotating")
    gamma = math.acos(ROTOR.imbalance / (2 * BALLS[1].static_moment))
    y = np.zeros(two.n_state)
    y[4:6] = [math.pi - gamma, math.pi + gamma]
    assert np.max(np.abs(two.rhs(0.0, y))) < 1e-11
    expect = -(om**2) * (two.imbalance * ROTOR.eccentricity + 2 * BALLS[1].inertia)
    assert 2.0 * two.reduced_hamiltonian(y) == pytest.approx(expect, rel=1e-13)


def test_case_2b_corrected_least_hamiltonian_when_capacity_is_short():
    """Supercritical, Me > sum m l: the motion with all k_i = 1 has the *least* H~* (printed >)."""
    rotor = RotorParams(1.5, 0.02, 600.0)
    model = JeffcottBalls(rotor, BALLS, speed=ConstantSpeed(40.0), frame="rotating")
    assert model.imbalance > model.capacity and 40.0 > model.critical_speed
    values = {bits: model.reduced_hamiltonian(_side_motion(model, 40.0, bits)[0])
              for bits in itertools.product((0, 1), repeat=3)}  # fmt: skip
    assert min(values, key=values.get) == (1, 1, 1)
    assert max(values, key=values.get) == (0, 0, 0)


def _finite_difference_jacobian(model, y, h=1e-6):
    n = y.size
    jac = np.empty((n, n))
    for j in range(n):
        step = h * max(1.0, abs(y[j]))
        e = np.zeros(n)
        e[j] = step
        jac[:, j] = (model.rhs(0.0, y + e) - model.rhs(0.0, y - e)) / (2 * step)
    return jac


@pytest.mark.parametrize("damping", [0.0, 3.0])
def test_linearization_against_finite_differences(damping):
    rotor = RotorParams(1.5, 4e-3, 600.0, damping=damping)
    balls = tuple(BallParams(b.mass, b.radius, b.inertia, damping=2e-3) for b in BALLS)
    model = JeffcottBalls(rotor, balls, speed=ConstantSpeed(30.0), frame="rotating")
    for y in (np.r_[2e-3, -1e-3, 0, 0, 0.3, 2.0, 4.0, 0, 0, 0], np.r_[0.0, 0.0, 0, 0, 1.0, -2.0, 3.0, 0, 0, 0]):
        lin = model.linearize(y)
        fd = _finite_difference_jacobian(model, y)
        assert np.max(np.abs(lin.A - fd)) < 1e-7 * np.max(np.abs(fd))
        np.testing.assert_allclose(lin.M, lin.M.T, rtol=0, atol=0)
        assert np.all(np.linalg.eigvalsh(lin.M) > 0)
        np.testing.assert_allclose(lin.G, -lin.G.T, rtol=0, atol=0)
        np.testing.assert_allclose(lin.C, lin.C.T, rtol=0, atol=0)
    # at an equilibrium with d = 0, K is the (symmetric) Hessian of H~*
    eq, _ = _side_motion(model.with_speed(ConstantSpeed(30.0)), 30.0, (0, 1, 1))
    if damping == 0.0:
        lin = model.linearize(eq)
        assert np.max(np.abs(lin.residual)) < 1e-12
        np.testing.assert_allclose(lin.K, lin.K.T, rtol=0, atol=1e-14 * np.max(np.abs(lin.K)))
        ev = np.sort_complex(lin.eigenvalues)
        np.testing.assert_allclose(ev, np.sort_complex(ev.conj()), rtol=1e-9, atol=1e-9)


def test_balanced_state_stable_only_above_critical_speed():
    """Zhakash et al. 2024 (20)-(22) with the corrected sign of W: the main motion needs omega > p."""
    rotor = RotorParams(1.0, 1e-3, 400.0, damping=2.0)
    ball = BallParams(0.02, 0.1, damping=5e-3)
    model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0), frame="rotating")
    gamma = math.acos(rotor.imbalance / (2 * ball.static_moment))
    y = np.zeros(model.n_state)
    y[4:6] = [math.pi - gamma, math.pi + gamma]
    p = model.critical_speed
    assert np.max(model.linearize(y, spin_speed=2.0 * p).eigenvalues.real) < 0
    assert np.max(model.linearize(y, spin_speed=0.5 * p).eigenvalues.real) > 0
    with pytest.raises(ValueError, match="without Coulomb friction"):
        JeffcottBalls(rotor, (BallParams(0.02, 0.1, friction=0.1),), speed=ConstantSpeed(1.0)).linearize(np.zeros(7))


@pytest.mark.parametrize("imbalance_factor", [0.6, 1.4])
def test_fourth_side_motion_corrected_condition(imbalance_factor):
    """(pi, pi): f of eq. (18) has a minimum iff Me > m1 l1 + m2 l2 (printed '<' in case ii)."""
    b1, b2 = BallParams(0.05, 0.08), BallParams(0.07, 0.10)
    capacity = b1.static_moment + b2.static_moment
    rotor = RotorParams(1.5, imbalance_factor * capacity / 1.5, 600.0)
    om = 40.0
    model = JeffcottBalls(rotor, (b1, b2), speed=ConstantSpeed(om), frame="rotating")

    def f_of(alpha):  # f = (u^2 + v^2)/2 from H~* on the rotor equilibrium (eq. (16))
        z = model.locked_response(alpha)
        y = np.zeros(model.n_state)
        y[0], y[1], y[4:6] = z.real, z.imag, alpha
        const = 0.5 * om**2 * (rotor.imbalance * rotor.eccentricity + b1.inertia + b2.inertia)
        return -(model.reduced_hamiltonian(y) + const) * (rotor.stiffness - model.total_mass * om**2) / om**4

    a0, h = np.array([math.pi, math.pi]), 1e-4
    hess = np.empty((2, 2))
    for i in range(2):
        for j in range(2):
            ei, ej = np.eye(2)[i] * h, np.eye(2)[j] * h
            hess[i, j] = (f_of(a0 + ei + ej) - f_of(a0 + ei - ej) - f_of(a0 - ei + ej) + f_of(a0 - ei - ej)) / (4 * h * h)
    me, s1, s2 = rotor.imbalance, b1.static_moment, b2.static_moment
    expect = np.array([[s1 * (me - s2), s1 * s2], [s1 * s2, s2 * (me - s1)]])  # eq. (19)
    np.testing.assert_allclose(hess, expect, rtol=1e-5, atol=1e-7 * s1 * s2)
    is_minimum = bool(np.all(np.linalg.eigvalsh(hess) > 0))
    assert is_minimum == (me > s1 + s2)
