"""The model-independent arithmetic of a Dormand–Prince 5(4) step, shared by both drivers.

The quartic dense output, saving at given times, the controller's RMS error norm and two small
tests. Nothing here calls a model's kernel, so it is an ordinary cached module rather than part of
the driver templates that :mod:`rotorlab.integrate._codegen` copies per model (its source is in
every copy's cache key, as every module a template imports). The lane driver
(:mod:`rotorlab.integrate._lanes`) uses the same functions for its saves and event location, so
both drivers give the same bits.
"""

import math

from numba import njit

from rotorlab._kernels._vmath import fma
from rotorlab.integrate._tableau import (
    P11, P12, P13, P14, P32, P33, P34, P42, P43, P44, P52, P53, P54, P62, P63, P64,
    P72, P73, P74,
)  # fmt: skip


@njit(cache=True, nogil=True)
def _dense(y, h, k1, k3, k4, k5, k6, k7, s, out):
    """State at ``t + s h`` from the quartic continuous extension of the last step."""
    s2 = s * s
    s3 = s2 * s
    s4 = s3 * s
    b1 = P11 * s + P12 * s2 + P13 * s3 + P14 * s4
    b3 = P32 * s2 + P33 * s3 + P34 * s4
    b4 = P42 * s2 + P43 * s3 + P44 * s4
    b5 = P52 * s2 + P53 * s3 + P54 * s4
    b6 = P62 * s2 + P63 * s3 + P64 * s4
    b7 = P72 * s2 + P73 * s3 + P74 * s4
    for i in range(y.shape[0]):
        a = fma(b4, k4[i], fma(b3, k3[i], b1 * k1[i]))
        out[i] = fma(h, fma(b7, k7[i], fma(b6, k6[i], fma(b5, k5[i], a))), y[i])


@njit(cache=True, nogil=True)
def _save_until(t_end, y_end, t, h, y, k1, k3, k4, k5, k6, k7, ts, i_save, ys_out, buf):
    """Write the states at the save times in (t, t_end] of the last step; return the next index.

    ``y_end`` is the state at ``t_end`` (saved exactly there); other save times use the dense
    output, with ``buf`` as scratch.
    """
    n = y.shape[0]
    while i_save < ts.shape[0] and ts[i_save] <= t_end:
        if ts[i_save] == t_end:
            for j in range(n):
                ys_out[i_save, j] = y_end[j]
        else:
            _dense(y, h, k1, k3, k4, k5, k6, k7, (ts[i_save] - t) / h, buf)
            for j in range(n):
                ys_out[i_save, j] = buf[j]
        i_save += 1
    return i_save


@njit(cache=True, nogil=True)
def _rms_scaled(v, a, b, atol, rtol, n_cont):
    """RMS over the continuous components of ``v / (atol + rtol max(|a|, |b|))``."""
    acc = 0.0
    for i in range(n_cont):
        sc = atol[i] + rtol * max(abs(a[i]), abs(b[i]))
        q = v[i] / sc
        acc += q * q
    return math.sqrt(acc / n_cont)


@njit(cache=True, nogil=True)
def _all_finite(v):
    for i in range(v.shape[0]):
        if not math.isfinite(v[i]):
            return False
    return True


@njit(cache=True, nogil=True)
def _crosses(ga, gb, direction):
    """True if the event function changes sign from ``ga`` to ``gb`` in the allowed direction."""
    if direction <= 0 and ga > 0.0 and gb <= 0.0:
        return True
    if direction >= 0 and ga < 0.0 and gb >= 0.0:
        return True
    return False
