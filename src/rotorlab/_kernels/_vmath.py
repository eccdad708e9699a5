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
from fractions import Fraction

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import lower_builtin, type_callable

__all__ = ["SINCOS_LIMIT", "fma", "sincos"]

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
