"""Unit tests of :mod:`rotorlab.steady._motions`: existence, main family, damped side motions."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams
from rotorlab.steady import (
    find_steady_motions,
    main_family_angles,
    main_motions_exist,
    motion_labels,
    side_deflection,
)


def _model(balls, *, e=2e-3, d=0.0, om=60.0, m1=1.5, c=600.0):
    return JeffcottBalls(RotorParams(m1, e, c, d), balls, speed=ConstantSpeed(om), frame="rotating")


def _residual(model, y):
    return float(np.max(np.abs(model.rhs(0.0, y))))


@pytest.mark.parametrize(
    "imbalance, moments, expected",
    [
        (1.0, [0.8, 0.8], True),
        (1.6, [0.8, 0.8], False),  # Me = sum: degenerate, the balls merge into side motion 11
        (2.0, [0.8, 0.8], False),
        (0.2, [0.5, 1.0], False),  # one ball dominates although Me < sum
        (0.2, [0.5, 1.0, 0.4], True),
        (1.0, [1.0], False),  # n = 1 has no main motion listed
        (0.0, [1.0, 1.0], False),  # balanced disc: opposite balls are the side motions 01, 10 (z = 0)
    ],
)
def test_main_motions_exist_is_the_polygon_inequality(imbalance, moments, expected):
    assert main_motions_exist(imbalance, moments) == expected


def test_main_family_angles_close_the_polygon():
    rng = np.random.default_rng(1)
    s = np.array([0.7, 0.9, 0.5, 0.3])
    hits = 0
    for _ in range(200):
        free = rng.uniform(-np.pi, np.pi, 2)
        for branch in (1, -1):
            psi = main_family_angles(0.6, s, free, branch)
            if psi is None:
                rest = 0.6 + np.sum(s[2:] * np.exp(1j * free))
                assert not (abs(s[0] - s[1]) < abs(rest) < s[0] + s[1])
                continue
            hits += 1
            assert abs(0.6 + np.sum(s * np.exp(1j * psi))) < 1e-13
            np.testing.assert_allclose(psi[2:], free)
            assert np.all((psi > -np.pi) & (psi <= np.pi))
    assert hits > 100
    with pytest.raises(ValueError, match="n - 2 = 2"):
        main_family_angles(0.6, s, [0.1], 1)


def test_two_equal_balls_give_seed_002_solution_1():
    """psi = +-(pi - gamma), gamma = arccos(eta / 2) (seed 002 (16), solution 1)."""
    eta = 1.3
    gamma = math.acos(eta / 2)
    plus = main_family_angles(eta, [1.0, 1.0], [], +1)
    minus = main_family_angles(eta, [1.0, 1.0], [], -1)
    np.testing.assert_allclose(plus, [math.pi - gamma, -(math.pi - gamma)], atol=1e-14)
    np.testing.assert_allclose(minus, -plus, atol=1e-14)


def test_labels_and_order():
    assert motion_labels(1) == ("side 0", "side 1")
    assert motion_labels(3)[:3] == ("main", "side 000", "side 001")
    assert len(motion_labels(4)) == 1 + 16
    model = _model((BallParams(0.05, 0.08), BallParams(0.07, 0.1)))
    assert tuple(m.label for m in find_steady_motions(model)) == motion_labels(2)


@pytest.mark.parametrize("damping", [0.0, 4.0])
@pytest.mark.parametrize("om", [12.0, 35.0])
def test_every_listed_motion_is_an_equilibrium(damping, om):
    balls = (BallParams(0.05, 0.08, inertia=0.05 * 0.08**2 * 1.4), BallParams(0.07, 0.10), BallParams(0.04, 0.09))
    model = _model(balls, d=damping, om=om)
    motions = find_steady_motions(model, family_samples=6)
    main = motions[0]
    assert main.label == "main" and main.exists and main.dimension == 1 and main.samples.shape[0] > 4
    for m in motions:
        assert m.exists
        for y in m.states():
            assert _residual(model, y) < 1e-10 * om**2
        if m.kind == "side":
            line = np.exp(1j * m.ball_angles) * np.exp(-1j * m.phase)  # every ball on the line of z
            np.testing.assert_allclose(line.imag, 0.0, atol=1e-12)
        y = m.states()[0]
        assert m.h_tilde == pytest.approx(float(model.reduced_hamiltonian(y)), rel=1e-12)


def test_undamped_side_motions_are_eq_13():
    """d = 0: psi_i = pi k_i, y = 0, x = Omega^2 (Me + s(k)) / (c - M Omega^2)."""
    balls = (BallParams(0.05, 0.08), BallParams(0.07, 0.10))
    model = _model(balls, om=30.0)
    s = np.array([b.static_moment for b in balls])
    for m in find_steady_motions(model)[2:]:
        k = np.array(m.bits)
        x = 30.0**2 * (model.imbalance + np.sum(s * (-1.0) ** k)) / (600.0 - model.total_mass * 900.0)
        assert m.deflection == pytest.approx(complex(x, 0.0), abs=1e-15)
        np.testing.assert_allclose(np.cos(m.ball_angles), (-1.0) ** k, atol=1e-15)


def test_support_damping_removes_side_motion_pairs():
    """Pair k, k' with |s| > Me exists iff d Omega |s| <= Me |c - M Omega^2 + i d Omega|."""
    moments = [0.02, 0.03]
    me, c, big_m = 0.004, 5e4, 3.1
    for d, om in itertools.product([0.0, 5.0, 30.0, 80.0], np.linspace(60.0, 200.0, 15)):
        dd = complex(c - big_m * om * om, d * om)
        for bits in itertools.product((0, 1), repeat=2):
            s = sum(m * (-1) ** b for m, b in zip(moments, bits))
            res = side_deflection(me, moments, bits, om, c, big_m, d)
            assert (res is not None) == (d * om * abs(s) <= me * abs(dd)), (d, om, bits)
            if res is None:
                continue
            z, theta = res
            unb = me + sum(m * np.exp(1j * (theta + np.pi * b)) for m, b in zip(moments, bits))
            assert abs(dd * z - om * om * unb) < 1e-12 * om * om * (me + sum(moments))


def test_flipped_bits_give_the_other_root():
    """Both roots of the side-motion equation: motion k and motion k' (all bits flipped)."""
    me, moments, om, c, big_m, d = 0.004, [0.003, 0.0025], 140.0, 5e4, 3.1, 20.0
    z1, t1 = side_deflection(me, moments, (0, 1), om, c, big_m, d)
    z2, t2 = side_deflection(me, moments, (1, 0), om, c, big_m, d)
    dd = complex(c - big_m * om * om, d * om)
    s = moments[0] - moments[1]
    roots = np.roots([abs(dd) ** 2, -2 * om * om * s * dd.real, om**4 * (s * s - me * me)])
    rho1 = (z1 * np.exp(-1j * t1)).real
    rho2 = (z2 * np.exp(-1j * (t2 + np.pi))).real  # motion (1, 0) = (0, 1) turned by pi
    np.testing.assert_allclose(sorted([rho1, rho2]), sorted(roots.real), rtol=1e-10)


def test_balanced_disc_without_support_damping():
    """Me = 0, d = 0: the side motions lie along U (theta = 0); with d > 0 only s = 0 remains."""
    z, theta = side_deflection(0.0, [0.01, 0.01], (0, 0), 5.0, 100.0, 1.0, 0.0)
    assert theta == 0.0 and z == pytest.approx(25.0 * 0.02 / 75.0, rel=1e-14)
    assert side_deflection(0.0, [0.01, 0.01], (0, 0), 5.0, 100.0, 1.0, 1.0) is None
    z, _ = side_deflection(0.0, [0.01, 0.01], (0, 1), 5.0, 100.0, 1.0, 1.0)
    assert z == 0
    assert side_deflection(1e-3, [0.01], (0,), 10.0, 100.0, 1.0, 0.0) is None  # at resonance


def test_main_motions_absent_are_listed_with_nan():
    model = _model((BallParams(0.01, 0.1), BallParams(0.01, 0.1)), e=0.02)  # Me = 0.03 > 0.002
    main = find_steady_motions(model)[0]
    assert not main.exists and np.all(np.isnan(main.ball_angles)) and np.isnan(main.h_tilde)
    assert main.samples.shape == (0, 2)


def test_speed_argument_checks():
    model = _model((BallParams(0.05, 0.08),))
    ramp = model.with_speed(LinearRamp(1.0, 2.0, 1.0))
    with pytest.raises(ValueError, match="spin_speed must be given"):
        find_steady_motions(ramp)
    with pytest.raises(ValueError, match="> 0"):
        find_steady_motions(model, -3.0)
    assert find_steady_motions(ramp, 5.0)[0].spin_speed == 5.0
