"""The benchmark's RHS (rotorlab.models.BENCHMARK, the C references' model) written to rotorlab's kernel contract.

y = [x, y, vx, vy, phi1, phi2, w1, w2]; p = [M, m, R, eps, k, c, beta, Omega].
Used by ``bench/ensemble.py`` and to cross-check the ``jeffcott_balls`` model on the benchmark.

It is written to be lane-friendly (see :mod:`rotorlab.integrate._lanes`): sines and cosines come
from :func:`rotorlab._kernels._vmath.sincos`, there are no loops and no branches, and the
divisions are the three of ``dp5.c`` (``1/R`` and ``1/(m R^2)`` are multiplied, as there).
"""

import math

from numba import njit

from rotorlab._kernels._vmath import sincos


@njit(cache=True, nogil=True, error_model="numpy")
def bench_rhs(t, s, p, out):
    M, m, R, EPS, K, C, BETA, OMEGA = p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]
    MR = m * R
    INV_R = 1.0 / R
    INV_MR2 = 1.0 / (m * R * R)
    x, y, vx, vy, p1, p2, w1, w2 = s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]
    th = OMEGA * t
    st, ct = sincos(th)
    s1, c1 = sincos(p1)
    s2, c2 = sincos(p2)
    g1 = -BETA * (w1 - OMEGA)
    g2 = -BETA * (w2 - OMEGA)
    E2 = EPS * OMEGA * OMEGA
    fx = E2 * ct - C * vx - K * x
    fy = E2 * st - C * vy - K * y
    rx = fx + MR * (w1 * w1 * c1 + w2 * w2 * c2) + (s1 * g1 + s2 * g2) * INV_R
    ry = fy + MR * (w1 * w1 * s1 + w2 * w2 * s2) - (c1 * g1 + c2 * g2) * INV_R
    a11 = M - m * (s1 * s1 + s2 * s2)
    a22 = M - m * (c1 * c1 + c2 * c2)
    a12 = m * (s1 * c1 + s2 * c2)
    inv_det = 1.0 / (a11 * a22 - a12 * a12)
    ax = (a22 * rx - a12 * ry) * inv_det
    ay = (a11 * ry - a12 * rx) * inv_det
    out[0] = vx
    out[1] = vy
    out[2] = ax
    out[3] = ay
    out[4] = w1
    out[5] = w2
    out[6] = g1 * INV_MR2 + (ax * s1 - ay * c1) * INV_R
    out[7] = g2 * INV_MR2 + (ax * s2 - ay * c2) * INV_R


@njit(cache=True, nogil=True)
def bench_rhs_libm(t, s, p, out):
    """``bench_rhs`` with ``math.sin``/``math.cos``: the kernel as a user first writes it (scalar).

    Runs on the lane driver too (same results as on the scalar driver) but does not vectorise.
    """
    M, m, R, EPS, K, C, BETA, OMEGA = p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]
    MR = m * R
    INV_R = 1.0 / R
    INV_MR2 = 1.0 / (m * R * R)
    x, y, vx, vy, p1, p2, w1, w2 = s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]
    th = OMEGA * t
    st = math.sin(th)
    ct = math.cos(th)
    s1 = math.sin(p1)
    c1 = math.cos(p1)
    s2 = math.sin(p2)
    c2 = math.cos(p2)
    g1 = -BETA * (w1 - OMEGA)
    g2 = -BETA * (w2 - OMEGA)
    E2 = EPS * OMEGA * OMEGA
    fx = E2 * ct - C * vx - K * x
    fy = E2 * st - C * vy - K * y
    rx = fx + MR * (w1 * w1 * c1 + w2 * w2 * c2) + (s1 * g1 + s2 * g2) * INV_R
    ry = fy + MR * (w1 * w1 * s1 + w2 * w2 * s2) - (c1 * g1 + c2 * g2) * INV_R
    a11 = M - m * (s1 * s1 + s2 * s2)
    a22 = M - m * (c1 * c1 + c2 * c2)
    a12 = m * (s1 * c1 + s2 * c2)
    inv_det = 1.0 / (a11 * a22 - a12 * a12)
    ax = (a22 * rx - a12 * ry) * inv_det
    ay = (a11 * ry - a12 * rx) * inv_det
    out[0] = vx
    out[1] = vy
    out[2] = ax
    out[3] = ay
    out[4] = w1
    out[5] = w2
    out[6] = g1 * INV_MR2 + (ax * s1 - ay * c1) * INV_R
    out[7] = g2 * INV_MR2 + (ax * s2 - ay * c2) * INV_R
