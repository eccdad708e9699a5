"""The compiled ``jeffcott_balls`` right-hand sides against an independent sympy derivation.

The equations are re-derived from the Lagrangian (balls as rigid bodies, Koenig's theorem) and the
Rayleigh function in ``dev/derive_jeffcott_balls.py`` for both frames, with unequal masses, radii,
inertias and damping, and solved numerically for the accelerations; the kernels must agree to
1e-12 (relative, max norm). For n = 2 point masses the fixed-frame kernel must be exactly
the project's benchmark problem (:data:`rotorlab.models.BENCHMARK`), written out in this module.

References: Zhakash et al. 2024 eqs. (1)-(3); Filimonikhin & Filimonikhina eqs. (4), (7).
"""

from __future__ import annotations

import functools
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from rotorlab.models import (
    BENCHMARK,
    BallParams,
    ConstantSpeed,
    HillRunUp,
    JeffcottBalls,
    LinearRamp,
    RotorParams,
)

ROOT = Path(__file__).resolve().parents[2]

ROTOR = RotorParams(disc_mass=2.0, eccentricity=0.012, stiffness=350.0, damping=0.4)
BALLS = (
    BallParams(mass=0.05, radius=0.10, damping=0.002),
    BallParams(mass=0.08, radius=0.13, inertia=0.08 * 0.13**2 + 3e-4, damping=0.004),
    BallParams(mass=0.03, radius=0.07, inertia=0.03 * 0.07**2 * 1.4, damping=0.0),
)
SPEEDS = {
    "constant": (ConstantSpeed(31.0), (0.0, 5.0)),
    "ramp": (LinearRamp(4.0, 45.0, 3.0), (0.0, 3.0)),
    "hill": (HillRunUp(40.0, 1.3, 2.7), (0.05, 4.0)),
}


@functools.lru_cache(maxsize=None)
def _symbolic(n: int, frame: str):
    """Lambdified mass matrix and forcing of the derived equations."""
    sys.path.insert(0, str(ROOT / "dev"))
    try:
        from derive_jeffcott_balls import derive
    finally:
        sys.path.pop(0)
    Mm, f, q, qd, par = derive(n, frame)
    args = [q, qd, par["th"], par["Om"], par["dOm"], par["M1"], par["e"], par["c"], par["d"],
            par["m"], par["l"], par["J"], par["b"]]  # fmt: skip
    return sp.lambdify(args, Mm, "numpy"), sp.lambdify(args, f, "numpy")


def _reference(model: JeffcottBalls, t: float, y: np.ndarray) -> np.ndarray:
    """dy/dt from the symbolic equations, in the kernel's state layout."""
    n = model.n_balls
    m_fun, f_fun = _symbolic(n, model.frame)
    th, om, dom = (float(v) for v in model.spin(t))
    r = model.rotor
    q = [y[0], y[1], *y[4 : 4 + n]]
    qd = [y[2], y[3], *y[4 + n : 4 + 2 * n]]
    args = (q, qd, th, om, dom, r.disc_mass, r.eccentricity, r.stiffness, r.damping,
            [b.mass for b in model.balls], [b.radius for b in model.balls],
            [b.inertia for b in model.balls], [b.damping for b in model.balls])  # fmt: skip
    acc = np.linalg.solve(np.array(m_fun(*args), dtype=float), np.array(f_fun(*args), dtype=float).ravel())
    return np.concatenate([qd[:2], acc[:2], qd[2:], acc[2:]])


def _random_states(model: JeffcottBalls, rng, count: int, span):
    n = model.n_balls
    for _ in range(count):
        t = rng.uniform(*span)
        om = float(model.speed.spin_speed(t))
        y = np.empty(model.n_state)
        y[:2] = rng.normal(scale=0.02, size=2)
        y[2:4] = rng.normal(scale=0.5, size=2)
        y[4 : 4 + n] = rng.uniform(-7.0, 7.0, size=n)
        rates = rng.normal(scale=5.0, size=n)
        y[4 + n : 4 + 2 * n] = rates if model.frame == "rotating" else om + rates
        yield t, y


@pytest.mark.parametrize("frame", ["fixed", "rotating"])
@pytest.mark.parametrize("speed", sorted(SPEEDS))
def test_rhs_matches_lagrange_three_unequal_balls(frame, speed):
    profile, span = SPEEDS[speed]
    model = JeffcottBalls(ROTOR, BALLS, speed=profile, frame=frame)
    rng = np.random.default_rng(zlib.crc32(f"{frame}-{speed}".encode()))
    for t, y in _random_states(model, rng, 12, span):
        got = model.rhs(t, y)
        ref = _reference(model, t, y)
        err = np.max(np.abs(got - ref)) / np.max(np.abs(ref))
        assert err < 1e-12, (t, y, got, ref)


def test_rhs_matches_lagrange_without_balls():
    rng = np.random.default_rng(7)
    for balls in ((),):
        for frame in ("fixed", "rotating"):
            model = JeffcottBalls(ROTOR, balls, speed=SPEEDS["ramp"][0], frame=frame)
            for t, y in _random_states(model, rng, 6, (0.0, 3.0)):
                got, ref = model.rhs(t, y), _reference(model, t, y)
                assert np.max(np.abs(got - ref)) <= 1e-12 * np.max(np.abs(ref))


def _bench_rhs_eliminated(t: float, s: np.ndarray) -> np.ndarray:
    """The benchmark's equations (:mod:`rotorlab.models._benchmark`) with the 4 x 4 mass matrix
    eliminated by hand: w_i' = g_i / (m R^2) + (x'' s_i - y'' c_i) / R, g_i = -beta (w_i - W),
    leaves a 2 x 2 system for (x'', y'') (written apart from the kernel, as the reference)."""
    b = BENCHMARK
    M, m, R, eps, k, c, beta, om = (b.total_mass, b.ball_mass, b.race_radius, b.unbalance, b.stiffness,
                                    b.damping, b.ball_damping, b.spin_speed)  # fmt: skip
    x, y, vx, vy, p1, p2, w1, w2 = s
    s1, c1, s2, c2 = np.sin(p1), np.cos(p1), np.sin(p2), np.cos(p2)
    g1, g2 = -beta * (w1 - om), -beta * (w2 - om)
    fx = eps * om**2 * np.cos(om * t) - c * vx - k * x
    fy = eps * om**2 * np.sin(om * t) - c * vy - k * y
    rx = fx + m * R * (w1**2 * c1 + w2**2 * c2) + (s1 * g1 + s2 * g2) / R
    ry = fy + m * R * (w1**2 * s1 + w2**2 * s2) - (c1 * g1 + c2 * g2) / R
    a11, a22, a12 = M - m * (s1**2 + s2**2), M - m * (c1**2 + c2**2), m * (s1 * c1 + s2 * c2)
    det = a11 * a22 - a12 * a12
    ax, ay = (a22 * rx - a12 * ry) / det, (a11 * ry - a12 * rx) / det
    dw1 = g1 / (m * R * R) + (ax * s1 - ay * c1) / R
    dw2 = g2 / (m * R * R) + (ax * s2 - ay * c2) / R
    return np.array([vx, vy, ax, ay, w1, w2, dw1, dw2])


def _bench_rhs_solved(t: float, s: np.ndarray) -> np.ndarray:
    """The benchmark's equations as written (Zhakash et al. 2024 eqs. (1)-(3), point-mass balls):
    the full 4 x 4 mass matrix of (x'', y'', w_1', w_2'), solved numerically."""
    b = BENCHMARK
    M, m, R, eps, k, c, beta, om = (b.total_mass, b.ball_mass, b.race_radius, b.unbalance, b.stiffness,
                                    b.damping, b.ball_damping, b.spin_speed)  # fmt: skip
    x, y, vx, vy, p1, p2, w1, w2 = s
    s1, c1, s2, c2 = np.sin(p1), np.cos(p1), np.sin(p2), np.cos(p2)
    mass = np.array([[M, 0.0, -m * R * s1, -m * R * s2], [0.0, M, m * R * c1, m * R * c2],
                     [-m * R * s1, m * R * c1, m * R * R, 0.0], [-m * R * s2, m * R * c2, 0.0, m * R * R]])  # fmt: skip
    force = np.array([eps * om**2 * np.cos(om * t) - c * vx - k * x + m * R * (w1**2 * c1 + w2**2 * c2),
                      eps * om**2 * np.sin(om * t) - c * vy - k * y + m * R * (w1**2 * s1 + w2**2 * s2),
                      -beta * (w1 - om), -beta * (w2 - om)])  # fmt: skip
    ax, ay, dw1, dw2 = np.linalg.solve(mass, force)
    return np.array([vx, vy, ax, ay, w1, w2, dw1, dw2])


def test_fixed_frame_is_the_bench_model():
    """Zhakash et al. 2024 eqs. (1)-(3) as used by the benchmark: same layout, same numbers."""
    model = BENCHMARK.model()
    assert model.n_state == 8
    assert model.state_names == ("x", "y", "vx", "vy", "phi_1", "phi_2", "w_1", "w_2")
    assert model.kernels.n_discrete == 0 and model.kernels.n_events == 0
    assert model.total_mass == pytest.approx(BENCHMARK.total_mass, rel=1e-15)
    assert model.imbalance == pytest.approx(BENCHMARK.unbalance, rel=1e-15)
    rng = np.random.default_rng(0)
    out = np.empty(8)
    p = model.to_array()
    for _ in range(300):
        s = rng.normal(size=8)
        s[4:6] *= 3.0
        t = rng.uniform(0.0, 100.0)
        model.kernels.rhs(t, s, p, out)
        ref = _bench_rhs_eliminated(t, s)
        assert np.max(np.abs(out - ref)) <= 1e-13 * np.max(np.abs(ref))
        ref_solve = _bench_rhs_solved(t, s)
        assert np.max(np.abs(out - ref_solve)) <= 1e-13 * np.max(np.abs(ref_solve))


@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_stick_slip_path_equals_the_lean_path_without_friction(frame):
    """The kernel's general (stick/slip) path with f = 0 and slipping modes reproduces the lean
    frictionless path to round-off (the model's kernel here is the lane-friendly frictionless
    one, ``rhs_*_free``; the general path is the generic kernel with the modes flag set)."""
    from rotorlab._kernels import jeffcott_balls as _k

    model = JeffcottBalls(ROTOR, BALLS, speed=SPEEDS["ramp"][0], frame=frame)
    generic = _k.rhs_fixed if frame == "fixed" else _k.rhs_rotating
    p_lean = model.to_array()
    p_general = p_lean.copy()
    p_general[1] = 1.0
    rng = np.random.default_rng(17)
    for t, y in _random_states(model, rng, 10, (0.0, 3.0)):
        y_modes = np.concatenate([y, rng.choice([-1.0, 1.0], size=3)])
        lean, general = np.empty_like(y), np.empty_like(y_modes)
        model.kernels.rhs(t, y, p_lean, lean)
        generic(t, y_modes, p_general, general)
        np.testing.assert_allclose(general[: y.size], lean, rtol=1e-13, atol=1e-13 * np.max(np.abs(lean)))
        np.testing.assert_array_equal(general[y.size :], 0.0)
