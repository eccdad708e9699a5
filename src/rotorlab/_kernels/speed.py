"""Compiled spin-speed profiles: the rotor angle theta(t), speed omega(t) and acceleration.

A profile occupies a block of ``SPEED_SIZE`` = 6 consecutive entries of a model's packed parameter
vector, starting at an offset ``k`` chosen by the model:

========  =============================================  ========================================
``p[k]``  kind                                           ``p[k+1] .. p[k+5]``
========  =============================================  ========================================
0         constant speed                                 omega (rad/s), 0, 0, 0, 0
1         linear ramp, then hold                         start (rad/s), stop (rad/s),
                                                         duration (s), 0, 0
2         Hill run-up omega_max t^n / (t_half^n + t^n)   omega_max (rad/s), t_half (s), n (1),
                                                         G(2^(-1/n)), G(2^(1/n)) (derived, 1)
========  =============================================  ========================================

``G(z) = int_0^z u^n / (1 + u^n) du = z - F(z)`` with ``F(z) = int_0^z du / (1 + u^n)``; the
Hill angle is ``theta(t) = omega_max t_half G(t / t_half)`` (equal to
``omega_max (t - t_half F(t / t_half))``, written without the cancellation at small t). The two
derived entries are filled by :meth:`rotorlab.models.HillRunUp.to_array` with
:func:`hill_integrals` so that the kernel only sums the pieces it needs.

For t < 0 every profile holds its value at t = 0 (ramp: constant ``start``; Hill: at rest).

Quadrature of F and G (all n > 0, to about 1e-15 relative), split at ``a = 2^(-1/n)`` and
``b = 2^(1/n)`` (where u^n = 1/2 and 2):

- ``[0, min(z, a)]``: the power series in ``x = u^n <= 1/2``,
  ``F = z sum_k (-x)^k / (1 + k n)``, ratio <= 1/2, exact for any real n (no quadrature across
  the branch point of u^n at 0);
- ``[a, min(z, b)]``: Gauss-Legendre (20 nodes) in ``sigma = n ln u`` in [-ln 2, ln 2], where the
  integrands ``e^(sigma/n) / (n (1 + e^(+-sigma)))`` are analytic in a strip of half-width pi;
  composite panels of width <= 10 n keep ``e^(sigma/n)`` resolved for small n;
- ``[b, z]``: ``int_b^z du / (1 + u^n) = sum_k (-1)^k int_b^z u^(-n(k+1)) du`` (ratio <= 1/2),
  each term ``b^q expm1(q ln(z/b)) / q`` with ``q = 1 - n(k+1)`` (``ln(z/b)`` when q = 0).
  For n > 1 this is the convergent tail expansion of ``int_z^inf`` used the other way round, so
  F never suffers the cancellation of ``(pi/n)/sin(pi/n) - int_z^inf`` near n = 1.
"""

import math

import numpy as np
from numba import njit

__all__ = [
    "SPEED_SIZE",
    "KIND_CONSTANT",
    "KIND_RAMP",
    "KIND_HILL",
    "profile",
    "profile_arithmetic",
    "profile_constant",
    "hill_integrals",
    "evaluate",
]

SPEED_SIZE = 6
KIND_CONSTANT = 0
KIND_RAMP = 1
KIND_HILL = 2

_GL_X, _GL_W = np.polynomial.legendre.leggauss(20)
_LN2 = math.log(2.0)
_SERIES_TOL = 1e-17
_SERIES_MAX = 400


@njit(cache=True, nogil=True)
def _low_series(z, n):
    """Return (F, G) on [0, z] for z^n <= 1/2 from the power series in x = z^n."""
    if z <= 0.0:
        return 0.0, 0.0
    x = math.exp(n * math.log(z))
    g = 0.0
    xk = x
    sign = 1.0
    for k in range(1, _SERIES_MAX):
        term = xk / (1.0 + k * n)
        g += sign * term
        if term <= _SERIES_TOL * g:
            break
        xk *= x
        sign = -sign
    return z * (1.0 - g), z * g


@njit(cache=True, nogil=True)
def _mid_quad(s_lo, s_hi, n):
    """Return (F, G) over u = e^(s/n) for s in [s_lo, s_hi] (a subset of [-ln 2, ln 2])."""
    if s_hi <= s_lo:
        return 0.0, 0.0
    inv_n = 1.0 / n
    panels = int(math.ceil((s_hi - s_lo) / (10.0 * n)))
    if panels < 1:
        panels = 1
    width = (s_hi - s_lo) / panels
    f = 0.0
    g = 0.0
    for j in range(panels):
        lo = s_lo + j * width
        half = 0.5 * width
        mid = lo + half
        for q in range(_GL_X.shape[0]):
            s = mid + half * _GL_X[q]
            du = half * _GL_W[q] * inv_n * math.exp(s * inv_n)
            f += du / (1.0 + math.exp(s))
            g += du / (1.0 + math.exp(-s))
    return f, g


@njit(cache=True, nogil=True)
def _tail_series(b, z, n):
    """Return int_b^z du / (1 + u^n) for z >= b = 2^(1/n) (alternating series, ratio <= 1/2)."""
    if z <= b:
        return 0.0
    big_l = math.log(z / b)
    log_b = math.log(b)
    total = 0.0
    sign = 1.0
    for k in range(_SERIES_MAX):
        q = 1.0 - n * (k + 1)
        if q == 0.0:
            term = big_l
        else:
            term = math.exp(q * log_b) * (math.expm1(q * big_l) / q)
        total += sign * term
        if abs(term) <= _SERIES_TOL * abs(total):
            break
        sign = -sign
    return total


@njit(cache=True, nogil=True)
def hill_integrals(z, n):
    """Return ``(F(z), G(z))``: ``F = int_0^z du/(1+u^n)``, ``G = int_0^z u^n/(1+u^n) du``.

    Parameters
    ----------
    z : float
        Upper limit (1), ``z >= 0``.
    n : float
        Hill exponent (1), ``n > 0``.

    Returns
    -------
    F, G : float
        Both computed directly (``F + G = z``), each to about 1e-15 relative.
    """
    if z <= 0.0:
        return 0.0, 0.0
    a = math.exp(-_LN2 / n)
    b = math.exp(_LN2 / n)
    if z <= a:
        return _low_series(z, n)
    fa, ga = _low_series(a, n)
    if z <= b:
        fm, gm = _mid_quad(-_LN2, n * math.log(z), n)
        return fa + fm, ga + gm
    fm, gm = _mid_quad(-_LN2, _LN2, n)
    ft = _tail_series(b, z, n)
    return fa + fm + ft, ga + gm + ((z - b) - ft)


@njit(cache=True, nogil=True)
def _hill_g(z, n, g_a, g_b):
    """G(z) using the precomputed G(a), G(b) of the profile block."""
    if z <= 0.0:
        return 0.0
    a = math.exp(-_LN2 / n)
    if z <= a:
        return _low_series(z, n)[1]
    b = math.exp(_LN2 / n)
    if z <= b:
        return g_a + _mid_quad(-_LN2, n * math.log(z), n)[1]
    return g_b + (z - b) - _tail_series(b, z, n)


@njit(cache=True, nogil=True, inline="always")
def _constant(t, p, k):
    w = p[k + 1]
    return w * t, w, 0.0


@njit(cache=True, nogil=True, inline="always")
def _ramp(t, p, k):
    w0 = p[k + 1]
    w1 = p[k + 2]
    dur = p[k + 3]
    if t < 0.0:
        return w0 * t, w0, 0.0
    slope = (w1 - w0) / dur
    if t < dur:
        return w0 * t + 0.5 * slope * t * t, w0 + slope * t, slope
    return 0.5 * (w0 + w1) * dur + w1 * (t - dur), w1, 0.0


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def profile_arithmetic(t, p, k):
    """:func:`profile` for the constant and ramp kinds only (NaN for a Hill run-up).

    Both kinds are computed and one is selected, with no library call: inlined into the lane
    driver's loop over lanes this vectorises (a kind that may vary per lane becomes a select).
    Same numbers as :func:`profile` for those kinds.
    """
    kind = p[k]
    a0, b0, c0 = _constant(t, p, k)
    a1, b1, c1 = _ramp(t, p, k)
    ramp = kind == KIND_RAMP
    ok = kind == KIND_CONSTANT or ramp
    theta = (a1 if ramp else a0) if ok else math.nan
    omega = (b1 if ramp else b0) if ok else math.nan
    domega = (c1 if ramp else c0) if ok else math.nan
    return theta, omega, domega


@njit(cache=True, nogil=True, inline="always")
def profile_constant(t, p, k):
    """:func:`profile` for the constant kind only (NaN for the others): no select between kinds.

    On the two-ball sweep of the benchmark problem the lane driver took 6 % less time with this
    than with :func:`profile_arithmetic` (``bench/README.md``, issue 11, session 8). Same
    numbers as :func:`profile` for a constant speed.
    """
    ok = p[k] == KIND_CONSTANT
    theta, omega, domega = _constant(t, p, k)
    return (theta if ok else math.nan), (omega if ok else math.nan), domega


@njit(cache=True, nogil=True, inline="always")
def profile(t, p, k):
    """Return ``(theta, omega, domega)`` of the profile stored at ``p[k:k+6]``.

    Parameters
    ----------
    t : float
        Time (s).
    p : ndarray of float64
        Packed parameters; the profile block starts at ``p[k]`` (see module docstring).
    k : int
        Offset of the block.

    Returns
    -------
    theta : float
        Spin angle (rad), ``theta(0) = 0``.
    omega : float
        Spin speed d theta/dt (rad/s).
    domega : float
        Spin acceleration (rad/s^2); right-continuous at the ends of a ramp.
    """
    kind = p[k]
    if kind == KIND_CONSTANT:
        return _constant(t, p, k)
    if kind == KIND_RAMP:
        return _ramp(t, p, k)
    # Hill run-up
    wmax = p[k + 1]
    th = p[k + 2]
    n = p[k + 3]
    if t <= 0.0:
        if t == 0.0 and n == 1.0:
            return 0.0, 0.0, wmax / th
        if t == 0.0 and n < 1.0:
            return 0.0, 0.0, math.inf
        return 0.0, 0.0, 0.0
    z = t / th
    lz = math.log(z)
    if lz > 0.0:
        r = math.exp(-n * lz)  # (t_half / t)^n <= 1
        omega = wmax / (1.0 + r)
        frac = r / ((1.0 + r) * (1.0 + r))
    else:
        x = math.exp(n * lz)  # (t / t_half)^n <= 1
        omega = wmax * x / (1.0 + x)
        frac = x / ((1.0 + x) * (1.0 + x))
    domega = wmax * n * frac / t
    theta = wmax * th * _hill_g(z, n, p[k + 4], p[k + 5])
    return theta, omega, domega


@njit(cache=True, nogil=True)
def evaluate(ts, p, k, out):
    """Fill ``out[i] = (theta, omega, domega)`` at ``ts[i]``; shapes (N,) and (N, 3)."""
    for i in range(ts.shape[0]):
        a, b, c = profile(ts[i], p, k)
        out[i, 0] = a
        out[i, 1] = b
        out[i, 2] = c
