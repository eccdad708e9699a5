"""Spin-speed profiles: closed forms, the Hill integral against quadrature, revolution times."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from rotorlab._kernels.speed import hill_integrals
from rotorlab.models import ConstantSpeed, HillRunUp, LinearRamp, speed_from_array


def _quad_reference(z: float, n: float):
    """F and G by adaptive quadrature, split where u^n = 1/2, 1, 2 and beyond."""
    b = 2.0 ** (1.0 / n)
    cuts = [0.0] + [c for c in (2.0 ** (-1.0 / n), 1.0, b, 2 * b, 10 * b) if c < z] + [z]

    def frac(u, sign):  # 1/(1+u^n) (sign=+1) or u^n/(1+u^n) (sign=-1) without overflow
        if u <= 0.0:
            return 1.0 if sign > 0 else 0.0
        return 1.0 / (1.0 + math.exp(max(-700.0, min(700.0, sign * n * math.log(u)))))

    f = g = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for lo, hi in zip(cuts[:-1], cuts[1:]):
            f += quad(frac, lo, hi, args=(1.0,), epsabs=0.0, epsrel=1e-13, limit=500)[0]
            g += quad(frac, lo, hi, args=(-1.0,), epsabs=0.0, epsrel=1e-13, limit=500)[0]
    return f, g


@pytest.mark.parametrize("n", [0.05, 0.5, 0.999999, 1.0, 1.000001, 1.5, 2.0, 3.0, 4.7, 12.0, 80.0])
def test_hill_integrals_against_quad(n):
    """F(z) = int_0^z du/(1+u^n) and G = z - F to 1e-12 relative over z in [1e-4, 1e3]."""
    for z in np.logspace(-4, 3, 22):
        f, g = hill_integrals(z, n)
        f_ref, g_ref = _quad_reference(z, n)
        assert abs(f - f_ref) <= 1e-12 * f_ref, (n, z, f, f_ref)
        assert abs(g - g_ref) <= 1e-12 * g_ref or g_ref < 1e-290, (n, z, g, g_ref)


@pytest.mark.parametrize("n", [1.2, 2.0, 3.5, 10.0])
def test_hill_integral_tends_to_closed_form(n):
    """int_0^inf du/(1+u^n) = (pi/n)/sin(pi/n) for n > 1."""
    z = 1e6 ** (1.0 / (n - 1.0)) if n < 2 else 1e8
    f, _ = hill_integrals(z, n)
    tail = z ** (1.0 - n) / (n - 1.0)  # leading term of int_z^inf
    assert f + tail == pytest.approx((math.pi / n) / math.sin(math.pi / n), rel=1e-12)


def test_constant_and_ramp_closed_forms():
    t = np.linspace(-1.0, 6.0, 71)
    c = ConstantSpeed(-7.5)
    np.testing.assert_allclose(c.spin_angle(t), -7.5 * t, rtol=1e-15)
    np.testing.assert_array_equal(c.spin_speed(t), -7.5)
    np.testing.assert_array_equal(c.spin_acceleration(t), 0.0)
    r = LinearRamp(2.0, 50.0, 4.0)
    th, om, dom = r.spin_angle(t), r.spin_speed(t), r.spin_acceleration(t)
    tc = np.clip(t, 0.0, 4.0)
    expect_th = np.where(t < 0, 2.0 * t, 2.0 * tc + 6.0 * tc**2 + 50.0 * (t - tc))
    np.testing.assert_allclose(th, expect_th, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(om, np.where(t < 0, 2.0, 2.0 + 12.0 * tc), rtol=1e-15)
    np.testing.assert_array_equal(dom, np.where((t >= 0) & (t < 4.0), 12.0, 0.0))


@pytest.mark.parametrize("n", [0.7, 1.0, 2.0, 4.5])
def test_hill_profile_is_consistent(n):
    """theta' = omega and omega' = domega (finite differences); theta = int omega dt (quad)."""
    hill = HillRunUp(120.0, 1.5, n)
    t = np.array([0.01, 0.3, 1.0, 1.5, 1.9, 3.0, 8.0, 40.0])
    h = 1e-5 * t
    th, om, dom = (hill._evaluate(t)[..., k] for k in range(3))
    num_om = (hill.spin_angle(t + h) - hill.spin_angle(t - h)) / (2 * h)
    num_dom = (hill.spin_speed(t + h) - hill.spin_speed(t - h)) / (2 * h)
    np.testing.assert_allclose(num_om, om, rtol=1e-8)
    np.testing.assert_allclose(num_dom, dom, rtol=1e-6, atol=1e-9 * 120.0)
    exact_dom = 120.0 * n * t ** (n - 1) * 1.5**n / (1.5**n + t**n) ** 2
    np.testing.assert_allclose(dom, exact_dom, rtol=1e-13)
    np.testing.assert_allclose(om, 120.0 * t**n / (1.5**n + t**n), rtol=1e-14)
    for ti, thi in zip(t, th):
        ref = quad(lambda s: 120.0 / (1.0 + (1.5 / s) ** n), 0.0, ti, epsabs=0, epsrel=1e-13, limit=200)[0]
        assert thi == pytest.approx(ref, rel=1e-11)


def test_hill_start():
    assert HillRunUp(10.0, 2.0, 1.0).spin_acceleration(0.0) == pytest.approx(5.0)
    assert HillRunUp(10.0, 2.0, 3.0).spin_acceleration(0.0) == 0.0
    assert HillRunUp(10.0, 2.0, 3.0).spin_angle(-1.0) == 0.0


@pytest.mark.parametrize(
    "profile", [ConstantSpeed(13.0), ConstantSpeed(-13.0), LinearRamp(1.0, 30.0, 2.0), HillRunUp(40.0, 1.0, 2.0)]
)
def test_revolution_times(profile):
    ts = profile.revolution_times(0.2, 6.0)
    turns = np.abs(profile.spin_angle(ts) - profile.spin_angle(0.2)) / (2 * np.pi)
    np.testing.assert_allclose(turns, np.arange(1, ts.size + 1), rtol=0, atol=1e-11)
    total = abs(profile.spin_angle(6.0) - profile.spin_angle(0.2)) / (2 * np.pi)
    assert ts.size == math.floor(total)
    assert np.all(np.diff(ts) > 0) and ts[-1] <= 6.0


def test_speed_from_array_inverts_to_array():
    for prof in (ConstantSpeed(2.0), LinearRamp(1.0, 2.0, 3.0), HillRunUp(4.0, 5.0, 6.0)):
        assert speed_from_array(prof.to_array()) == prof
    with pytest.raises(ValueError, match="unknown speed-profile kind"):
        speed_from_array([7, 0, 0, 0, 0, 0])
