"""``rotorlab._kernels._vmath``: accuracy of ``sincos`` and ``inv_fifth_root`` (in ulps), special values, ``fma``."""

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from numba import njit

from rotorlab._kernels._vmath import SINCOS_LIMIT, fma, inv_fifth_root, sincos

LONG_DOUBLE_OK = np.finfo(np.longdouble).nmant >= 63  # x87 80-bit or IEEE quad


@njit(cache=True)
def _sincos_many(x, s, c):
    for i in range(x.shape[0]):
        s[i], c[i] = sincos(x[i])


def _eval(x):
    s = np.empty_like(x)
    c = np.empty_like(x)
    _sincos_many(x, s, c)
    return s, c


def _ulps_to_numpy(got, ref):
    """Distance in units in the last place between two float64 arrays of the same sign."""
    diff = np.abs(got.view(np.int64) - ref.view(np.int64))  # exact for equal signs
    same = np.signbit(got) == np.signbit(ref)
    return np.where(same, diff, np.where(got == ref, 0, np.iinfo(np.int64).max))


RANGES = [(0.0, math.pi / 4), (0.0, 10.0), (0.0, 1e3), (1e3, 1e5), (1e5, 2e6), (2e6, SINCOS_LIMIT)]


@pytest.mark.parametrize("lo, hi", RANGES)
def test_sincos_within_one_ulp_of_numpy(lo, hi):
    rng = np.random.default_rng(int(hi))
    x = rng.uniform(lo, hi, 400_000) * rng.choice([-1.0, 1.0], 400_000)
    s, c = _eval(x)
    assert np.max(_ulps_to_numpy(s, np.sin(x))) <= 1
    assert np.max(_ulps_to_numpy(c, np.cos(x))) <= 1
    # and mostly the same bits as the C library (which is correctly rounded almost always)
    assert np.mean(s == np.sin(x)) > 0.95 and np.mean(c == np.cos(x)) > 0.95


@pytest.mark.skipif(not LONG_DOUBLE_OK, reason="needs an extended-precision long double")
@pytest.mark.parametrize("lo, hi", RANGES)
def test_sincos_error_below_0p8_ulp(lo, hi):
    """Measured error against an extended-precision reference (numpy's own is about 0.5)."""
    rng = np.random.default_rng(int(hi) + 1)
    x = rng.uniform(lo, hi, 400_000) * rng.choice([-1.0, 1.0], 400_000)
    s, c = _eval(x)
    xl = x.astype(np.longdouble)
    for got, ref in ((s, np.sin(xl)), (c, np.cos(xl))):
        ulp = np.spacing(np.abs(ref.astype(np.float64))).astype(np.longdouble)
        err = np.abs((got.astype(np.longdouble) - ref) / ulp).astype(np.float64)
        assert err.max() < 0.8


def test_sincos_near_multiples_of_half_pi():
    """Arguments closest to k pi/2 (results near 0): the reduction keeps ~100 bits."""
    mpmath.mp.prec = 200
    rng = np.random.default_rng(3)
    ks = list(range(1, 60)) + list(rng.integers(60, int(SINCOS_LIMIT / (math.pi / 2)), 300))
    worst = 0.0
    for k in ks:
        x = float(mpmath.mpf(int(k)) * mpmath.pi / 2)
        s, c = sincos(x)
        for got, ref in ((s, mpmath.sin(x)), (c, mpmath.cos(x))):
            worst = max(worst, float(abs(mpmath.mpf(got) - ref) / np.spacing(abs(float(ref)))))
    assert worst < 0.8


def test_sincos_special_values():
    assert sincos(0.0) == (0.0, 1.0)
    s, c = sincos(-0.0)
    assert s == 0.0 and math.copysign(1.0, s) == -1.0 and c == 1.0
    assert sincos(5e-324) == (5e-324, 1.0)
    assert sincos(1e-300) == (1e-300, 1.0)
    assert sincos(math.pi / 2) == (math.sin(math.pi / 2), math.cos(math.pi / 2))
    s, c = sincos(SINCOS_LIMIT)
    assert abs(s - math.sin(SINCOS_LIMIT)) <= np.spacing(abs(math.sin(SINCOS_LIMIT)))
    for bad in (math.nextafter(SINCOS_LIMIT, math.inf), -2 * SINCOS_LIMIT, 1e300, math.inf, -math.inf, math.nan):
        s, c = sincos(bad)
        assert math.isnan(s) and math.isnan(c)


def test_sincos_python_equals_compiled():
    """``.py_func`` (fma by exact fractions) gives the same bits as the compiled code."""
    rng = np.random.default_rng(5)
    for x in np.concatenate([rng.uniform(-10, 10, 300), rng.uniform(-1e7, 1e7, 300)]):
        assert sincos.py_func(float(x)) == sincos(float(x))


def test_fma_is_exactly_rounded():
    @njit
    def f(a, b, c):
        return fma(a, b, c)

    rng = np.random.default_rng(6)
    for a, b, c in rng.normal(size=(300, 3)) * [1e3, 1e-3, 1.0]:
        exact = float(Fraction(a) * Fraction(b) + Fraction(c))
        assert f(a, b, c) == exact == fma(a, b, c)
    assert f(0.1, 10.0, -1.0) == float(Fraction(0.1) * 10 - 1) != 0.1 * 10.0 - 1.0


@njit(cache=True)
def _inv_fifth_root_many(x, out):
    for i in range(x.shape[0]):
        out[i] = inv_fifth_root(x[i])


# log-uniform arguments over the whole positive range: subnormals, [1e-300, 1e-10], the
# controller's working range (error norms 6e-6 .. 2e3) and beyond, up to the largest double
LOG_RANGES = [(-744.4, -708.4), (-690.0, -23.0), (-12.0, 8.0), (8.0, 709.7)]


@pytest.mark.skipif(not LONG_DOUBLE_OK, reason="needs an extended-precision long double")
@pytest.mark.parametrize("lo, hi", LOG_RANGES)
def test_inv_fifth_root_error_below_1p1_ulp(lo, hi):
    """Against x^(-1/5) in extended precision (the exponent -1/5 rounded to 64 bits: its error,
    below 2^-66 |ln x| <= 1e-17 relative, is 0.05 ulp at most); and mostly correctly rounded."""
    rng = np.random.default_rng(int(abs(lo)))
    x = np.exp(rng.uniform(lo, hi, 200_000))
    x = x[x > 0.0]
    got = np.empty_like(x)
    _inv_fifth_root_many(x, got)
    ref = np.power(x.astype(np.longdouble), np.longdouble(-1) / np.longdouble(5))
    ulp = np.spacing(np.abs(ref.astype(np.float64))).astype(np.longdouble)
    err = np.abs((got.astype(np.longdouble) - ref) / ulp).astype(np.float64)
    assert err.max() < 1.1
    assert np.mean(got == ref.astype(np.float64)) > 0.8


def test_inv_fifth_root_exact_cases_and_special_values():
    """Exact fifth powers give exact roots; the closed form y^5 x = 1 holds to round-off."""
    for k in range(-200, 200, 7):  # x = 2^(5k): root 2^-k exactly
        assert inv_fifth_root(2.0 ** (5 * k)) == 2.0**-k
    for v in (3.0, 7.0, 10.0, 0.1):
        assert inv_fifth_root(v**-5) == pytest.approx(v, rel=2.3e-16)
    assert inv_fifth_root(1e-10) == 100.0
    assert inv_fifth_root(0.0) == math.inf
    assert inv_fifth_root(math.inf) == 0.0
    assert math.isnan(inv_fifth_root(-1.0)) and math.isnan(inv_fifth_root(math.nan))
    rng = np.random.default_rng(8)
    for x in [5e-324, 1e-320, 2.2250738585072014e-308, 1.7976931348623157e308, *np.exp(rng.uniform(-700, 700, 200))]:
        y = Fraction(inv_fifth_root(float(x)))
        assert abs(float(y**5 * Fraction(float(x))) - 1.0) < 5 * 1.1 * 2.0**-52  # 1.1 ulp <= 1.1 2^-52 relative


def test_inv_fifth_root_python_equals_compiled():
    rng = np.random.default_rng(9)
    for x in np.exp(rng.uniform(-744, 709, 300)):
        assert inv_fifth_root.py_func(float(x)) == inv_fifth_root(float(x))
