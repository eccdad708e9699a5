"""Property tests of ``jeffcott_balls`` (Hypothesis): relabelling, n = 0, frames, invariants."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams

from _jeffcott_strategies import ball_sets  # tests/property/_jeffcott_strategies.py
from _jeffcott_strategies import rotors as jeffcott_rotors

SETTINGS = settings(max_examples=15, deadline=None)

rotors = jeffcott_rotors(eccentricity=(0.0, 5e-3), damping=(0.0, 2.0))


def balls(min_size=1, max_size=4):
    return ball_sets(min_size, max_size, damping=(0.0, 5e-3))


speeds = st.one_of(
    st.builds(ConstantSpeed, st.floats(5.0, 60.0)),
    st.builds(LinearRamp, st.floats(5.0, 30.0), st.floats(30.0, 60.0), st.floats(0.2, 2.0)),
)


def _state(model, seed):
    rng = np.random.default_rng(seed)
    n = model.n_balls
    y = np.concatenate([rng.normal(scale=2e-3, size=2), rng.normal(scale=0.05, size=2),
                        rng.uniform(-math.pi, math.pi, n), rng.normal(scale=3.0, size=n)])  # fmt: skip
    return y  # a rotating-frame state


def _integrate(model, y0, t1, ts):
    k, p = model.kernels.rhs, model.to_array()

    def f(t, y):
        out = np.empty_like(y)
        k(t, y, p, out)
        return out

    sol = solve_ivp(f, (0.0, t1), y0, method="DOP853", t_eval=ts, rtol=1e-11, atol=1e-13)
    assert sol.success
    return sol.y.T


def _permute(y, perm, n):
    perm = np.asarray(perm)
    idx = np.concatenate([np.arange(4), 4 + perm, 4 + n + perm])
    return y[..., idx]


@SETTINGS
@given(rotors, balls(min_size=2), speeds, st.randoms(use_true_random=False), st.integers(0, 2**31))
def test_relabelling_the_balls_permutes_the_rhs(rotor, bs, speed, rand, seed):
    perm = list(range(len(bs)))
    rand.shuffle(perm)
    for frame in ("fixed", "rotating"):
        a = JeffcottBalls(rotor, bs, speed=speed, frame=frame)
        b = JeffcottBalls(rotor, tuple(bs[i] for i in perm), speed=speed, frame=frame)
        y = _state(a, seed)
        np.testing.assert_allclose(
            b.rhs(0.4, _permute(y, perm, len(bs))), _permute(a.rhs(0.4, y), perm, len(bs)), rtol=1e-13, atol=1e-13
        )


@settings(max_examples=5, deadline=None)
@given(rotors, balls(min_size=2, max_size=3), st.integers(0, 2**31))
def test_relabelling_the_balls_permutes_the_solution(rotor, bs, seed):
    perm = list(range(len(bs)))[::-1]
    a = JeffcottBalls(rotor, bs, speed=ConstantSpeed(35.0), frame="rotating")
    b = JeffcottBalls(rotor, tuple(bs[i] for i in perm), speed=ConstantSpeed(35.0), frame="rotating")
    y0 = _state(a, seed)
    ts = np.linspace(0.0, 0.5, 11)
    ya = _integrate(a, y0, 0.5, ts)
    yb = _integrate(b, _permute(y0, perm, len(bs)), 0.5, ts)
    np.testing.assert_allclose(yb, _permute(ya, perm, len(bs)), rtol=1e-8, atol=1e-9)


@SETTINGS
@given(st.floats(0.5, 3.0), st.floats(100.0, 1000.0), st.floats(0.0, 50.0), st.floats(1e-4, 1e-2))
def test_no_balls_is_the_plain_jeffcott_rotor(mass, stiffness, speed, x0):
    """n = 0, e = 0, d = 0: free whirl x = x0 cos(p t), p = sqrt(c / M), whatever the spin."""
    model = JeffcottBalls(RotorParams(mass, 0.0, stiffness), (), speed=ConstantSpeed(speed))
    p = model.critical_speed
    assert p == math.sqrt(stiffness / mass)
    ts = np.linspace(0.0, 3.0 * 2 * math.pi / p, 13)
    ys = _integrate(model, np.array([x0, 0.0, 0.0, x0 * p]), ts[-1], ts)
    np.testing.assert_allclose(ys[:, 0], x0 * np.cos(p * ts), atol=1e-9 * max(abs(x0), 1e-3))
    np.testing.assert_allclose(ys[:, 1], x0 * np.sin(p * ts), atol=1e-9 * max(abs(x0), 1e-3))
    # in the rotating frame the whirl frequencies are |p - Omega| and p + Omega
    rot = model.with_frame("rotating")
    freqs = np.sort(np.abs(rot.linearize(np.zeros(4)).eigenvalues.imag))
    np.testing.assert_allclose(freqs, np.sort([abs(p - speed)] * 2 + [p + speed] * 2), rtol=1e-10, atol=1e-10)


@SETTINGS
@given(rotors, balls(max_size=3), speeds, st.integers(0, 2**31))
def test_frames_agree_along_trajectories(rotor, bs, speed, seed):
    """Integrate the same initial state in both frames; converted, the trajectories coincide."""
    fixed = JeffcottBalls(rotor, bs, speed=speed, frame="fixed")
    rot = fixed.with_frame("rotating")
    y0r = _state(rot, seed)
    y0f = rot.to_frame(0.0, y0r, "fixed")
    ts = np.linspace(0.0, 0.4, 9)
    yf = _integrate(fixed, y0f, 0.4, ts)
    yr = _integrate(rot, y0r, 0.4, ts)
    conv = rot.to_frame(ts, yr, "fixed")
    scale = np.max(np.abs(yf), axis=0) + 1e-3
    assert np.all(np.abs(conv - yf) <= 1e-8 * scale)


@SETTINGS
@given(rotors, balls(max_size=3), st.floats(5.0, 60.0), st.integers(0, 2**31))
def test_linear_matrices_are_structured(rotor, bs, speed, seed):
    """M symmetric positive definite, C symmetric, G skew; eigenvalues come in conjugate pairs."""
    model = JeffcottBalls(rotor, bs, speed=ConstantSpeed(speed), frame="rotating")
    y = _state(model, seed)
    lin = model.linearize(y)
    assert np.array_equal(lin.M, lin.M.T) and np.all(np.linalg.eigvalsh(lin.M) > 0)
    assert np.array_equal(lin.C, lin.C.T) and np.array_equal(lin.G, -lin.G.T)
    ev = lin.eigenvalues
    np.testing.assert_allclose(np.sort_complex(ev), np.sort_complex(ev.conj()), rtol=1e-8, atol=1e-8 * np.max(np.abs(ev)))


@SETTINGS
@given(rotors, balls(max_size=3), st.floats(5.0, 60.0), st.integers(0, 2**31))
def test_hamiltonian_conserved_without_damping(rotor, bs, speed, seed):
    """Zero damping, constant speed: H* is constant (to the integration tolerance)."""
    rotor = RotorParams(rotor.disc_mass, rotor.eccentricity, rotor.stiffness)
    bs = tuple(BallParams(b.mass, b.radius, b.inertia) for b in bs)
    model = JeffcottBalls(rotor, bs, speed=ConstantSpeed(speed), frame="rotating")
    ts = np.linspace(0.0, 0.3, 7)
    ys = _integrate(model, _state(model, seed), 0.3, ts)
    h = model.hamiltonian(ys)
    t2 = h - model.reduced_hamiltonian(ys)
    assert np.max(np.abs(h - h[0])) < 1e-8 * (np.max(np.abs(t2)) + np.ptp(model.reduced_hamiltonian(ys)))
