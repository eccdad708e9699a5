"""Coulomb friction of the balls as stick-slip (``jeffcott_balls``): kernels, reset map, dynamics.

The friction torque is bounded by f_i N_i l_i with the exact normal force
N_i = m_i (l_i w_i^2 - x'' cos phi_i - y'' sin phi_i); see :mod:`rotorlab._kernels.jeffcott_balls`.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams

ROTOR = RotorParams(disc_mass=1.4, eccentricity=3e-3, stiffness=900.0, damping=1.0)
BALLS = (
    BallParams(0.05, 0.09, damping=1e-3, friction=0.05),
    BallParams(0.07, 0.11, inertia=0.07 * 0.11**2 * 1.4, damping=2e-3, friction=0.1),
    BallParams(0.03, 0.10, damping=1e-3),  # frictionless: always free
)


def _reference(model: JeffcottBalls, t: float, y: np.ndarray):
    """Fixed-frame accelerations and stuck-ball holding torques from the full constrained system."""
    n = model.n_balls
    th, om, dom = (float(v) for v in model.spin(t))
    r = model.rotor
    mode = y[4 + 2 * n :]
    stuck = [i for i, b in enumerate(model.balls) if b.friction > 0 and mode[i] == 0]
    size = 2 + n + len(stuck)
    A, f = np.zeros((size, size)), np.zeros(size)
    big_m = model.total_mass
    A[0, 0] = A[1, 1] = big_m
    f[0] = r.imbalance * (om**2 * math.cos(th) + dom * math.sin(th)) - r.stiffness * y[0] - r.damping * y[2]
    f[1] = r.imbalance * (om**2 * math.sin(th) - dom * math.cos(th)) - r.stiffness * y[1] - r.damping * y[3]
    for i, b in enumerate(model.balls):
        s, c = math.sin(y[4 + i]), math.cos(y[4 + i])
        w = om if i in stuck else y[4 + n + i]
        ml = b.mass * b.radius
        A[0, 2 + i], A[1, 2 + i] = -ml * s, ml * c
        f[0] += ml * w * w * c
        f[1] += ml * w * w * s
        row = 2 + i
        A[row, 0], A[row, 1], A[row, 2 + i] = -ml * s, ml * c, b.inertia
        f[row] = -b.damping * (w - om)
        if i in stuck:  # unknown holding torque T_i; constraint phi_i'' = Omega'
            A[row, 2 + n + stuck.index(i)] = -1.0
        elif b.friction > 0:  # T_i = -mode f l m (l w^2 - x'' c - y'' s), moved to the left side
            k = mode[i] * b.friction * b.radius * b.mass
            f[row] -= k * b.radius * w * w
            A[row, 0] -= k * c
            A[row, 1] -= k * s
    cons = np.zeros((len(stuck), size))
    for j, i in enumerate(stuck):
        cons[j, 2 + i] = 1.0
    # replace the unknown-torque columns' equations: append constraints, solve least squares exactly
    full = np.vstack([A[: 2 + n], cons])
    rhs = np.concatenate([f[: 2 + n], np.full(len(stuck), dom)])
    z = np.linalg.solve(full, rhs)
    return z[:2], z[2 : 2 + n], dict(zip(stuck, z[2 + n :])), om


def _random_state(model, rng, modes):
    n = model.n_balls
    om = float(model.speed.spin_speed(0.3))
    y = np.concatenate([rng.normal(scale=2e-3, size=2), rng.normal(scale=0.1, size=2),
                        rng.uniform(-4, 4, n), om + rng.normal(scale=3.0, size=n), modes])  # fmt: skip
    return y


@pytest.mark.parametrize("modes", [(0, 0, 1), (1, -1, 1), (0, -1, -1), (-1, 0, 1)])
def test_kernel_matches_constrained_system(modes):
    """Stick: relative acceleration zero, holding torque solves the constrained system; slip:
    the friction torque -mode f l N enters with the exact normal force."""
    model = JeffcottBalls(ROTOR, BALLS, speed=LinearRamp(10.0, 60.0, 1.0))
    rng = np.random.default_rng(sum(modes) + 10)
    for _ in range(10):
        y = _random_state(model, rng, np.array(modes, dtype=float))
        acc, phidd, holding, om = _reference(model, 0.3, y)
        out = model.rhs(0.3, y)
        np.testing.assert_allclose(out[2:4], acc, rtol=1e-12, atol=1e-12 * np.max(np.abs(acc)))
        np.testing.assert_allclose(out[7:10], phidd, rtol=1e-12, atol=1e-12 * np.max(np.abs(phidd)))
        np.testing.assert_array_equal(out[10:], 0.0)
        drive, bound, normal, a = model.stick_torques(0.3, y)
        for i, torque in holding.items():
            assert out[4 + i] == om  # stuck: phi' = Omega exactly
            assert drive[i] == pytest.approx(-torque, rel=1e-11)  # D is minus the holding torque
            b = model.balls[i]
            expect_n = b.mass * (b.radius * om**2 - acc[0] * math.cos(y[4 + i]) - acc[1] * math.sin(y[4 + i]))
            assert normal[i] == pytest.approx(expect_n, rel=1e-12)
            assert bound[i] == pytest.approx(b.friction * b.radius * expect_n, rel=1e-12)


def test_slip_with_the_holding_torque_keeps_the_ball_with_the_rotor():
    """Slipping at zero relative speed with f chosen so that f l N equals |D| reproduces stick."""
    model = JeffcottBalls(ROTOR, BALLS, speed=LinearRamp(10.0, 60.0, 1.0), frame="rotating")
    rng = np.random.default_rng(4)
    y = _random_state(model, rng, np.array([0.0, 1.0, 1.0]))
    y[7:10] = [0.0, 2.0, -1.0]  # relative rates (rotating frame)
    out_stick = model.rhs(0.3, y)
    drive, bound, normal, _ = model.stick_torques(0.3, y)
    f_eq = abs(drive[0]) / (BALLS[0].radius * normal[0])
    balls = (BallParams(0.05, 0.09, damping=1e-3, friction=f_eq),) + BALLS[1:]
    slip = JeffcottBalls(ROTOR, balls, speed=model.speed, frame="rotating")
    y_slip = y.copy()
    y_slip[10] = math.copysign(1.0, drive[0])  # slipping in the direction the drive pushes
    out_slip = slip.rhs(0.3, y_slip)
    assert abs(out_slip[7]) < 1e-12 * np.max(np.abs(out_stick))
    np.testing.assert_allclose(out_slip[:7], out_stick[:7], rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(out_slip[8:], out_stick[8:], rtol=1e-11, atol=1e-12)


def _events(model, t, y):
    g = np.empty(2 * model.n_balls)
    model.kernels.events(t, y, model.to_array(), g)
    return g


@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_event_functions(frame):
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(40.0), frame=frame)
    rng = np.random.default_rng(8)
    y = _random_state(model.with_speed(ConstantSpeed(40.0)), rng, np.array([0.0, -1.0, 1.0]))
    if frame == "rotating":
        y[7:10] -= 40.0
    g = _events(model, 0.2, y)
    drive, bound, _, _ = model.stick_torques(0.2, y)
    rel = y[8] - (40.0 if frame == "fixed" else 0.0)
    assert g[0] == 1.0 and g[1] == pytest.approx(bound[0] - abs(drive[0]), rel=1e-13)
    assert g[2] == pytest.approx(-rel, rel=1e-15) and g[3] == 1.0
    assert g[4] == 1.0 and g[5] == 1.0  # frictionless ball: never switches


@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_reset_map(frame):
    om = 40.0
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(om), frame=frame)
    p, reset = model.to_array(), model.kernels.reset
    base = np.array([1e-4, -2e-4, 0.01, 0.02, 0.5, 2.0, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
    if frame == "fixed":
        base[7:10] += om
    out = np.empty_like(base)
    # ball 1 reaches zero relative speed; its race can hold it -> stick, relative speed exactly 0
    y = base.copy()
    y[7] += 1e-9
    assert reset(0, 0.1, y, p, out) == 0
    assert out[10] == 0.0 and out[7] == (om if frame == "fixed" else 0.0)
    np.testing.assert_array_equal(np.delete(out, [7, 10]), np.delete(y, [7, 10]))
    drive, bound, _, _ = model.stick_torques(0.1, out)
    assert abs(drive[0]) <= bound[0]
    # a weak race cannot hold it -> slip on, in the direction of the driving torque
    weak = JeffcottBalls(ROTOR, (BallParams(0.05, 0.09, damping=1e-3, friction=1e-4),) + BALLS[1:],
                         speed=ConstantSpeed(om), frame=frame)  # fmt: skip
    y[0], y[1] = 3e-3, 0.0  # rotor displaced: its acceleration drives the ball
    drive, bound, _, _ = weak.stick_torques(0.1, y, forced=0)
    assert abs(drive[0]) > bound[0]
    weak.kernels.reset(0, 0.1, y, weak.to_array(), out)
    assert out[10] == math.copysign(1.0, drive[0]) and out[7] == (om if frame == "fixed" else 0.0)
    # breaking away from stick: slip with the sign of the driving torque
    y_stuck = out.copy()
    y_stuck[10] = 0.0
    drive, bound, _, _ = weak.stick_torques(0.1, y_stuck)
    weak.kernels.reset(1, 0.1, y_stuck, weak.to_array(), out)
    assert out[10] == math.copysign(1.0, drive[0])


def _single_ball(speed, friction, frame="rotating", rel_rate=0.0):
    """One ball on a stiff, well-damped, balanced shaft (the rotor barely moves), rotor started
    on its steady response to the ball's centrifugal load."""
    rotor = RotorParams(1.0, 0.0, 1e6, damping=1000.0)
    ball = BallParams(0.05, 0.1, inertia=0.05 * 0.01 * 1.4, damping=2e-4, friction=friction)
    model = JeffcottBalls(rotor, (ball,), speed=speed, frame=frame)
    return model, model.initial_state([0.3], rotor="steady", ball_rates=[rel_rate]), ball


def _solve():
    from rotorlab.integrate import SaveAt, StepControl, solve

    return solve, SaveAt, StepControl


def _slip_phase_reference(model, y0, t1):
    """SciPy on the same kernel in slip mode until the relative speed reaches zero."""
    rot = model.with_frame("rotating")
    y = model.to_frame(0.0, y0, "rotating")
    k, p = rot.kernels.rhs, rot.to_array()

    def f(t, z):
        out = np.empty_like(z)
        k(t, z, p, out)
        return out

    def stop(t, z):
        return z[5]

    stop.terminal, stop.direction = True, -1
    return solve_ivp(f, (0.0, t1), y, method="DOP853", events=stop, rtol=1e-12, atol=1e-14, dense_output=True)


@pytest.mark.parametrize("frame", ["rotating", "fixed"])
def test_ball_decelerates_sticks_and_stays(frame):
    """Relative spin 8 rad/s decays under friction and damping, sticks when it reaches zero and
    stays stuck (constant speed: the race holds it)."""
    solve, SaveAt, StepControl = _solve()
    om = 50.0
    model, y0, ball = _single_ball(ConstantSpeed(om), 0.02, frame, rel_rate=8.0)
    assert y0[-1] == 1.0
    ref = _slip_phase_reference(model, y0, 1.0)
    t_stick = ref.t_events[0][0]
    # rigid-rotor estimate: J psi'' = -b psi' - f m l^2 (om + psi')^2
    rate = lambda v: -(ball.damping * v + ball.friction * ball.mass * ball.radius**2 * (om + v) ** 2) / ball.inertia
    assert t_stick == pytest.approx(quad(lambda v: 1.0 / rate(v), 8.0, 0.0)[0], rel=1e-3)
    ts = np.linspace(0.0, 3 * t_stick, 31)
    sol = solve(model, y0, (0.0, ts[-1]), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-12))
    assert sol.status.name == "SUCCESS"
    assert sol.event_counts == {"stick_1": 1, "slip_1": 0}
    assert sol.event_times[0] == pytest.approx(t_stick, rel=1e-7)
    yr = model.to_frame(ts, sol.ys, "rotating")
    after, before = ts > t_stick, ts < t_stick
    assert np.all(sol.ys[after, -1] == 0.0) and np.all(sol.ys[before, -1] == 1.0)
    assert np.all(np.abs(yr[after, 5]) < 1e-9) and np.ptp(yr[after, 4]) < 1e-9
    np.testing.assert_allclose(yr[before, 4:6], ref.sol(ts[before])[4:6].T, rtol=1e-7, atol=1e-8)
    drive, bound, _, _ = model.stick_torques(ts[-1], sol.ys[-1])
    assert abs(drive[0]) < 0.1 * bound[0]


def test_run_up_slips_then_sticks():
    """On a fast run-up the race cannot hold J Omega' (f m l^2 Omega^2 < J Omega'): the ball lags
    (mode -1), catches up after the ramp and sticks for good."""
    solve, SaveAt, StepControl = _solve()
    model, y0, ball = _single_ball(LinearRamp(30.0, 80.0, 0.5), 0.05)
    assert ball.inertia * 100.0 > ball.friction * ball.mass * ball.radius**2 * 30.0**2
    assert y0[-1] == -1.0  # initial_state sees the break-away at once
    ts = np.linspace(0, 2, 41)
    sol = solve(model, y0, (0.0, 2.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-12))
    assert sol.status.name == "SUCCESS"
    assert sol.event_counts == {"stick_1": 1, "slip_1": 0}
    assert sol.y_final[-1] == 0.0 and sol.y_final[5] == 0.0
    assert np.min(sol.ys[:, 5]) < -10.0  # it did lag behind
    t_stick = sol.event_times[0]
    assert 0.5 < t_stick < 1.0
    np.testing.assert_array_equal(sol.ys[ts > t_stick, 5], 0.0)


def test_power_balance_while_slipping():
    """Slipping balls at constant speed: dH*/dt = sum q' Q includes the Coulomb power T_i psi_i',
    and dE/dt = omega tau_drive - 2 Phi + sum T_i psi_i' (fixed-frame energy)."""
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(40.0), frame="rotating")
    y0 = model.initial_state([0.4, 2.0, -1.0], rotor="steady", ball_rates=[6.0, -5.0, 2.0])
    np.testing.assert_array_equal(y0[-3:], [1.0, -1.0, 1.0])
    f_l = np.array([b.friction * b.radius for b in BALLS])
    k, p = model.kernels.rhs, model.to_array()

    def coulomb_power(t, y):
        _, _, normal, _ = model.stick_torques(t, y)
        return np.sum(-y[-3:] * f_l * normal * y[7:10])  # f_l = 0 for the smooth ball

    def f(t, z):
        y = z[:-2]
        out = np.empty_like(y)
        k(t, y, p, out)
        e_rate = 40.0 * model.drive_torque(t, y) - 2.0 * model.dissipation(y, t) + coulomb_power(t, y)
        return np.concatenate([out, [model.hamiltonian_rate(y, t), e_rate]])

    ts = np.linspace(0.0, 0.015, 6)
    sol = solve_ivp(f, (0.0, ts[-1]), np.concatenate([y0, [0.0, 0.0]]), t_eval=ts, method="DOP853",
                    rtol=1e-10, atol=1e-13)  # fmt: skip
    ys = sol.y[:-2].T
    assert np.all(np.sign(ys[:, 7:9]) == [1.0, -1.0])  # the rough balls still slip the same way
    h = model.hamiltonian(ys)
    np.testing.assert_allclose(h - h[0], sol.y[-2], rtol=0, atol=1e-8 * np.ptp(h))
    e = model.energy(ts, ys)
    np.testing.assert_allclose(e - e[0], sol.y[-1], rtol=0, atol=1e-8 * np.ptp(e))
    assert np.ptp(h) > 1e-3 and np.ptp(e) > 1e-3
