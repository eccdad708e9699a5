"""Sine and cosine in plain float arithmetic, so that LLVM can vectorise them across lanes.

Why this module exists
----------------------
``math.sin`` and ``math.cos`` compile to the C library's scalar ``sin``/``cos``. LLVM vectorises a
loop that calls them only if numba has a vector math library, and the only one numba supports is
Intel SVML (the ``intel-cmplr-lib-rt`` wheel, about 41 MB): too heavy for a default dependency.
glibc's ``libmvec`` is not reachable from numba without changing LLVM's process-wide options and
loading a shared library by hand (hidden global state). The ensemble integrator's lane driver
(:mod:`rotorlab.integrate._lanes`) steps several trajectories in the SIMD lanes of one register
and needs the model's right-hand side, sines and cosines included, to vectorise across the lanes.
:func:`sincos` below uses only multiplications, additions, ``floor`` and selects: inlined into a
loop over lanes it becomes AVX2 (or AVX-512) code. It is also a good scalar sine/cosine pair
(one range reduction for both), so a kernel uses it in every context.

Accuracy (``tests/unit/test_vmath.py``): below 0.8 ulp against an extended-precision reference
for ``|x| <= SINCOS_LIMIT``, and equal to glibc's correctly rounded result in about 97 % of cases.

Range
-----
``|x| <= SINCOS_LIMIT`` = 2^25 pi, about 1.05e8 rad (for example 10^4 rad/s for 2.9 hours).
Beyond it, and for inf or NaN, both results are NaN, so an integrator reports a non-finite
derivative (status ``NONFINITE``) instead of a silently wrong one. There is deliberately no
``math.sin`` fallback branch: inside a vectorised loop LLVM executes such a branch for every lane
on every call (``llvm.sin`` is speculatable and has no vector version without a vector library),
which measured 2.2x slower on the benchmark right-hand side. A kernel that needs larger angles
should reduce them itself (angles modulo 2 pi are exact to the same absolute error) or call
``math.sin``/``math.cos`` (it then runs on the scalar path at scalar speed).

Algorithm
---------
Cody–Waite reduction ``r + rr = x - k pi/2``, ``k = round(2 x / pi)``, with pi/2 split into three
26-bit parts and a 53-bit tail so that every product ``k * part`` is exact for ``|k| <= 2^26 + 1``;
the subtractions are Knuth's TwoSum, so ``r + rr`` is the reduced argument to about 1e-30
absolute. Then the minimax polynomials of fdlibm's ``__kernel_sin``/``__kernel_cos`` on
``[-pi/4, pi/4]`` with the tail ``rr``, and the quadrant ``k mod 4`` applied by selects. No fused
multiply-add is used (numba does not contract ``a*b + c`` without ``fastmath``), so the result is
the same bit for bit whether the code is vectorised or not, on any IEEE machine.

The polynomial coefficients are those of fdlibm (``k_sin.c``, ``k_cos.c``), which carry this notice:

    Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
    Developed at SunSoft, a Sun Microsystems, Inc. business.
    Permission to use, copy, modify, and distribute this software is freely granted, provided
    that this notice is preserved.
"""

import math
import struct
from fractions import Fraction

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import lower_builtin, type_callable

__all__ = ["SINCOS_LIMIT", "fma", "inv_fifth_root", "sincos"]

_INV_PIO2 = 6.36619772367581382433e-01  # 2/pi
# pi/2 = _PIO2_1 + _PIO2_2 + _PIO2_3 to about 160 bits (each the rounded remainder)
_PIO2_1 = float.fromhex("0x1.921fb54442d18p+0")
_PIO2_2 = float.fromhex("0x1.1a62633145c07p-54")
_PIO2_3 = float.fromhex("-0x1.f1976b7ed8fbcp-110")

SINCOS_LIMIT = 2.0**25 * math.pi
"""Largest ``|x|`` (rad) for which :func:`sincos` is accurate; beyond it returns NaN."""


def fma(a, b, c):
    """Return ``a * b + c`` rounded once (fused multiply-add).

    Compiled code uses ``llvm.fma.f64``, which LLVM vectorises (one ``vfmadd`` instruction on
    x86-64 with FMA3 and on ARM64; other CPUs call the C library's exact ``fma``). From plain
    Python it is computed exactly with fractions.
    """
    if not (math.isfinite(a) and math.isfinite(b) and math.isfinite(c)):
        return a * b + c
    return float(Fraction(a) * Fraction(b) + Fraction(c))


@type_callable(fma)
def _type_fma(context):
    def typer(a, b, c):
        if all(isinstance(v, (types.Float, types.Integer)) for v in (a, b, c)):
            return types.float64

    return typer


@lower_builtin(fma, types.Number, types.Number, types.Number)
def _lower_fma(context, builder, sig, args):
    vals = [context.cast(builder, v, t, types.float64) for v, t in zip(args, sig.args)]
    d = ir.DoubleType()
    fn = builder.module.declare_intrinsic("llvm.fma", [d], ir.FunctionType(d, [d, d, d]))
    return builder.call(fn, vals)


_S1 = -1.66666666666666324348e-01
_S2 = 8.33333333332248946124e-03
_S3 = -1.98412698298579493134e-04
_S4 = 2.75573137070700676789e-06
_S5 = -2.50507602534068634195e-08
_S6 = 1.58969099521155010221e-10

_C1 = 4.16666666666666019037e-02
_C2 = -1.38888888888741095749e-03
_C3 = 2.48015872894767294178e-05
_C4 = -2.75573143513906633035e-07
_C5 = 2.08757232129817482790e-09
_C6 = -1.13596475577881948265e-11


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def sincos(x):
    """Return ``(sin x, cos x)`` within 1 ulp, in arithmetic that LLVM can vectorise.

    Parameters
    ----------
    x : float
        Angle (rad).

    Returns
    -------
    s, c : float
        ``sin x`` and ``cos x``; both NaN if ``|x| > SINCOS_LIMIT`` or ``x`` is not finite.

    Notes
    -----
    Branch-free (selects only), compiled with ``inline="always"``: call it from a model kernel
    instead of ``math.sin``/``math.cos`` to let the lane driver vectorise the kernel.

    Examples
    --------
    >>> from rotorlab._kernels._vmath import sincos
    >>> s, c = sincos(1.0)
    >>> float(s) == 0.8414709848078965, float(c) == 0.5403023058681398
    (True, True)
    """
    ok = abs(x) <= SINCOS_LIMIT  # False for NaN and inf
    k = np.floor(x * _INV_PIO2 + 0.5)
    # r + rr = x - k pi/2 to about 1e-30 absolute. r1 = x - k _PIO2_1 is exact (a multiple of
    # 2^-53 below 1 in magnitude, or x itself for k = 0); k _PIO2_2 = p + pe exactly (fma);
    # r1 - p is a TwoSum (Knuth), its rounding error goes to rr with -pe and -k _PIO2_3.
    r1 = fma(-k, _PIO2_1, x)
    p = k * _PIO2_2
    pe = fma(k, _PIO2_2, -p)
    r = r1 - p
    bv = r - r1
    rr = ((r1 - (r - bv)) - (p + bv)) - (pe + k * _PIO2_3)
    z = r * r
    w = z * z
    v = z * r
    # fdlibm __kernel_sin(r, rr, 1) and __kernel_cos(r, rr), Horner steps fused
    ps = fma(z, fma(z, _S4, _S3), _S2) + (z * w) * fma(z, _S6, _S5)
    sr = r - fma(-v, _S1, fma(z, fma(-v, ps, 0.5 * rr), -rr))
    pc = z * fma(z, fma(z, _C3, _C2), _C1) + (w * w) * fma(z, fma(z, _C6, _C5), _C4)
    hz = 0.5 * z
    u = 1.0 - hz
    cr = u + (((1.0 - u) - hz) + fma(z, pc, -(r * rr)))
    # quadrant q = k mod 4 (exact in float arithmetic)
    q = k - 4.0 * np.floor(k * 0.25)
    odd = q == 1.0 or q == 3.0
    s = cr if odd else sr
    c = sr if odd else cr
    s = -s if q >= 2.0 else s
    c = -c if (q == 1.0 or q == 2.0) else c
    s = s if ok else math.nan
    c = c if ok else math.nan
    return s, c


def _bits(x):
    """The bits of the float64 ``x`` as an int64 (compiled: one ``bitcast``, which vectorises)."""
    return struct.unpack("<q", struct.pack("<d", float(x)))[0]


def _from_bits(i):
    """The float64 whose bits are the int64 ``i`` (the inverse of :func:`_bits`)."""
    return struct.unpack("<d", struct.pack("<q", int(i)))[0]


@type_callable(_bits)
def _type_bits(context):
    def typer(x):
        if isinstance(x, types.Float):
            return types.int64

    return typer


@lower_builtin(_bits, types.Float)
def _lower_bits(context, builder, sig, args):
    v = context.cast(builder, args[0], sig.args[0], types.float64)
    return builder.bitcast(v, ir.IntType(64))


@type_callable(_from_bits)
def _type_from_bits(context):
    def typer(i):
        if isinstance(i, types.Integer):
            return types.float64

    return typer


@lower_builtin(_from_bits, types.Integer)
def _lower_from_bits(context, builder, sig, args):
    v = context.cast(builder, args[0], sig.args[0], types.int64)
    return builder.bitcast(v, ir.DoubleType())


# m^(-1/5) on [1, 2]: least-squares Chebyshev fit of degree 5 (numpy.polynomial), relative error
# 6.4e-6; two Newton steps then bring it below round-off (6.4e-6 -> 1.2e-10 -> 5e-20).
_R0 = 1.4333795578199562
_R1 = -0.8355689744039465
_R2 = 0.6306800658548697
_R3 = -0.2967737016068341
_R4 = 0.07656749556066474
_R5 = -0.008290818997922842
_TWO54 = 2.0**54
_MANT = (1 << 52) - 1
_ONE_BITS = 1023 << 52


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def inv_fifth_root(x):
    """Return ``x ** (-1/5)`` within 1.1 ulp, in arithmetic that LLVM can vectorise.

    The step-size factor of the Dormand–Prince 5(4) controller, ``err ** (-1/5)``: both drivers
    of :mod:`rotorlab.integrate` call this function (one vector computation per step for all
    lanes in the lane driver; ``**`` would be a scalar ``pow`` call per lane), so they agree bit
    for bit. Written here because numba has no vector ``pow`` without Intel SVML (see the module
    docstring).

    Parameters
    ----------
    x : float
        ``x >= 0``.

    Returns
    -------
    float
        ``x ** (-1/5)``: ``inf`` at 0, 0 at ``inf``, NaN for ``x < 0`` or NaN.

    Notes
    -----
    ``x = m 2^e`` (``1 <= m < 2``, subnormals scaled by ``2^54`` first) from the bits of ``x``;
    ``e = 5 q + r`` with ``r`` in 0..4; ``y ~ (m 2^r)^(-1/5)`` from a degree-5 polynomial in
    ``m`` times ``2^(-r/5)``, refined by two Newton steps ``y += y (1 - u y^5) / 5`` on
    ``u = m 2^r`` (exact), then scaled by ``2^-q`` (exact). Accuracy
    (``tests/unit/test_vmath.py``): below 1.1 ulp against an extended-precision reference over
    the whole positive range, subnormals included (1.06 measured over 1.6 million arguments;
    the rounding of the last Newton residual, about 0.6 ulp, plus the final rounding), and the
    correctly rounded result in about 87 % of cases. It is not ``x ** -0.2``: the double nearest
    -1/5 is not -1/5, so that differs from the fifth root by up to ``7e-15`` relative at the
    ends of the range.
    Branch-free (selects only); no fused multiply-add, so vectorised and scalar code give the
    same bits.

    Examples
    --------
    >>> from rotorlab._kernels._vmath import inv_fifth_root
    >>> float(inv_fifth_root(32.0)), float(inv_fifth_root(1e-10))
    (0.5, 100.0)
    """
    tiny = x < 2.2250738585072014e-308
    xs = x * _TWO54 if tiny else x
    b = _bits(xs)
    e = (b >> 52) - (1023 + 54 if tiny else 1023)
    m = _from_bits((b & _MANT) | _ONE_BITS)
    ef = float(e)
    q = np.floor(ef * 0.2)
    r = ef - 5.0 * q
    # 2^r and 2^(-r/5) for r = 0..4 by selects (a table lookup would be a gather)
    p2 = 1.0 if r == 0.0 else (2.0 if r == 1.0 else (4.0 if r == 2.0 else (8.0 if r == 3.0 else 16.0)))
    c = (1.0 if r == 0.0 else (0.8705505632961241 if r == 1.0 else (0.7578582832551990 if r == 2.0
         else (0.6597539553864471 if r == 3.0 else 0.5743491774985174))))  # fmt: skip
    u = m * p2
    y = c * (_R0 + m * (_R1 + m * (_R2 + m * (_R3 + m * (_R4 + m * _R5)))))
    for _ in range(2):
        y2 = y * y
        y = y + y * (1.0 - u * (y2 * y2 * y)) * 0.2
    scale = _from_bits((1023 - np.int64(q)) << 52)
    res = y * scale
    res = math.inf if x == 0.0 else res
    res = 0.0 if x == math.inf else res
    return res if x >= 0.0 else math.nan
