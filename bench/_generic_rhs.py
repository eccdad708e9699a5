"""A layout-generic, lanes-innermost right-hand side of the machine (issue 24 item 6; bench only).

The machine's production kernel is generated per layout (:mod:`rotorlab._kernels.machine_codegen`:
every count a compile-time constant, every loop unrolled) and vectorised by the lane driver
across its lanes. This module is the other choice, built to measure it (``bench/generic_kernel.py``):
one compiled function for every layout of the machine's common subset, the sizes, offsets and
attachment tables read at run time from an integer table, the lanes innermost:

- a prescribed constant drive speed (no motor), gravity, any number of unbalances;
- a linear structure of any size in the generated kernel's modal form (``H K``, ``H C``, ``H G``,
  ``H f``, each station's ``B`` and ``H B^T`` and the pair matrices ``B_s H B_s'^T``, all read
  from the packed parameters ``p`` at the layout's offsets);
- any number of races with any number of balls with viscous damping, planar or following their
  node's tilt (the layout's ``tilt``: rigid ball kinematics, one axial unknown per ball);
- no clearance, ball friction, energy states or attachment parts (refused by :func:`table`).

Every array is lane-interleaved with the lane driver's stride (element ``i`` of lane ``l`` at
``a[i * LANES + l]``) and every operation is a loop over ``nl`` lanes innermost, so that LLVM
vectorises each loop across the lanes. The arithmetic follows the generated kernel's term by
term (same order of every sum), so the two agree to round-off (the bench checks 1e-12).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorlab._kernels._vmath import sincos

LANES = 8  # the lane driver's stride (DEFAULT_LANES): a compile-time constant, as in its copies

# ---- the integer table: sizes, offsets and row numbers (T_*), then per-ball and per-unknown lists
(T_NZ, T_NR, T_NB, T_NU, T_GYRO, T_TILT, T_NS, T_NT, T_NUSED, T_NFS,
 T_SPEED, T_GRAV, T_BALLS, T_UNB, T_HK, T_HC, T_HG, T_HF, T_PTILT, T_IPHI, T_IW,
 T_STB, T_STH, T_LOFF, T_NALL,
 R_STH, R_CTH, R_S, R_C, R_EUX, R_EUY, R_TX, R_TY, R_TVX, R_TVY, R_EP, R_TP, R_NX, R_NY,
 R_MTX, R_MTY, R_F, R_H, R_A, R_LV, R_P, R_SM, R_Q, R_X, R_D, R_L, R_G, R_ACC,
 T_BRACE, T_BTS, T_USED, T_FST, T_LOADS, T_WORK) = range(59)
T_HEAD = 59
N_LOAD = 9  # per Schur unknown: its number of loads, then (station, used index, row vx, row vy) x 2


def table(lay) -> tuple[np.ndarray, int]:
    """The integer table of ``lay`` (a :class:`rotorlab._kernels.machine_layout.Layout`) and the
    number of scratch rows the kernel needs.

    Raises
    ------
    ValueError
        If the layout has a part the generic kernel does not cover (motor, speed profile other
        than constant, clearance, friction, energy states, attachment parts).
    """
    bad = {"drive": lay.drive != "profile", "speed_kind": lay.speed_kind != "constant",
           "clearance": bool(lay.clearance), "friction": lay.friction, "energy": lay.energy,
           "parts": bool(lay.parts)}
    if any(bad.values()):
        raise ValueError(f"layout {lay.key}: the generic kernel covers a constant-speed drive without "
                         f"clearance, friction, energy states or parts; this one has "
                         f"{[k for k, v in bad.items() if v]}")
    nz, nr, nb, nu, nt = lay.n_z, lay.n_races, lay.n_balls, lay.n_unbalance, lay.n_tilt
    o = lay.offsets
    ns = lay.n_schur
    used = list(range(nr)) + lay.tilt_stations  # stations of the Schur unknowns' loads
    fst = list(range(nr + nu)) + lay.tilt_stations  # stations with forces on the structure
    nused, nfs = len(used), len(fst)
    head = np.zeros(T_HEAD, dtype=np.int64)
    head[[T_NZ, T_NR, T_NB, T_NU, T_GYRO, T_TILT, T_NS, T_NT, T_NUSED, T_NFS]] = (
        nz, nr, nb, nu, int(lay.gyroscopic), int(bool(lay.tilt)), ns, nt, nused, nfs)
    head[[T_SPEED, T_GRAV, T_BALLS, T_UNB, T_HK, T_HC, T_HG, T_HF, T_PTILT, T_IPHI, T_IW]] = (
        o["speed"], o["gravity"], o["balls"], o["unbalances"], o["HK"], o["HC"], o["HG"], o["Hf"],
        o["tilt"], lay.i_phi, lay.i_w)
    head[[T_STB, T_LOFF, T_NALL]] = o["stations"], o["L"], lay.n_all_stations
    rows = [(R_STH, 1), (R_CTH, 1), (R_S, nb), (R_C, nb), (R_EUX, nu), (R_EUY, nu), (R_TX, nt),
            (R_TY, nt), (R_TVX, nt), (R_TVY, nt), (R_EP, nb), (R_TP, nb), (R_NX, nb), (R_NY, nb),
            (R_MTX, nb), (R_MTY, nb), (R_F, 2 * nfs), (R_H, nz), (R_A, 2 * nused),
            (R_LV, 4 * nused * nused), (R_P, 2 * ns * nused), (R_SM, ns * ns), (R_Q, ns), (R_X, ns),
            (R_D, ns), (R_L, ns * ns), (R_G, 2 * nused), (R_ACC, 1)]
    k = 0
    for slot, size in rows:
        head[slot] = k
        k += size
    n_work = k
    used_ix = {s: i for i, s in enumerate(used)}
    ball_ts = [used_ix[lay.tilt_station(lay.ball_race[b])] if lay.tilt else -1 for b in range(nb)]
    loads = np.full((ns, N_LOAD), -1, dtype=np.int64)
    for b in range(nb):  # a ball's acceleration acts at its race (and its race node's tilt)
        r = lay.ball_race[b]
        entry = [r, used_ix[r], head[R_MTX] + b, head[R_MTY] + b]
        if lay.tilt:
            ts = lay.tilt_station(r)
            entry += [ts, used_ix[ts], head[R_NX] + b, head[R_NY] + b]
        loads[b, 0] = len(entry) // 4
        loads[b, 1:1 + len(entry)] = entry
        if lay.tilt:  # the ball's axial unknown acts on its race node's tilt only
            loads[nb + b, 0] = 1
            loads[nb + b, 1:5] = [ts, used_ix[ts], head[R_C] + b, head[R_S] + b]
    lists = [np.array(lay.ball_race, dtype=np.int64), np.array(ball_ts, dtype=np.int64),
             np.array(used, dtype=np.int64), np.array(fst, dtype=np.int64), loads.ravel()]
    at = T_HEAD
    for slot, arr in zip((T_BRACE, T_BTS, T_USED, T_FST, T_LOADS), lists, strict=True):
        head[slot] = at
        at += arr.size
    return np.concatenate([head] + lists), n_work


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_generic(t, y, p, tab, w, out, nl):  # pragma: no cover - compiled
    """``out = rhs(t, y, p)`` for ``nl`` lanes of any layout of the common subset (module docstring).

    ``t``: the lanes' times; ``y``, ``p``, ``out``: lane-interleaved state, packed parameters and
    derivative (stride :data:`LANES`); ``tab``: :func:`table`; ``w``: scratch of ``table(...)[1]``
    rows of :data:`LANES`."""
    L = LANES
    nz, nr, nb, nu = tab[T_NZ], tab[T_NR], tab[T_NB], tab[T_NU]
    tilt, ns, nt, nused, nfs = tab[T_TILT], tab[T_NS], tab[T_NT], tab[T_NUSED], tab[T_NFS]
    kom = (tab[T_SPEED] + 1) * L  # the constant speed's row
    kgx, kgy = tab[T_GRAV] * L, (tab[T_GRAV] + 1) * L
    kb0, ku0, iphi, iw = tab[T_BALLS], tab[T_UNB], tab[T_IPHI], tab[T_IW]
    stb, nall = tab[T_STB], tab[T_NALL]
    brace, bts, used, fst, lds = tab[T_BRACE], tab[T_BTS], tab[T_USED], tab[T_FST], tab[T_LOADS]
    r_s, r_c, r_mtx, r_mty = tab[R_S] * L, tab[R_C] * L, tab[R_MTX] * L, tab[R_MTY] * L
    r_ep, r_tp, r_nx, r_ny = tab[R_EP] * L, tab[R_TP] * L, tab[R_NX] * L, tab[R_NY] * L
    r_f, r_h, r_a, r_lv, r_p = tab[R_F] * L, tab[R_H] * L, tab[R_A] * L, tab[R_LV] * L, tab[R_P] * L
    r_sm, r_q, r_x, r_d, r_l, r_g = (tab[R_SM] * L, tab[R_Q] * L, tab[R_X] * L, tab[R_D] * L,
                                     tab[R_L] * L, tab[R_G] * L)
    r_sth, r_cth, r_eux, r_euy = tab[R_STH] * L, tab[R_CTH] * L, tab[R_EUX] * L, tab[R_EUY] * L
    r_acc = tab[R_ACC] * L
    # ---- spin, ball angles, unbalance directions
    for l in range(nl):
        s, c = sincos(p[kom + l] * t[l])
        w[r_sth + l] = s
        w[r_cth + l] = c
    for b in range(nb):
        ky = (iphi + b) * L
        for l in range(nl):
            s, c = sincos(y[ky + l])
            w[r_s + b * L + l] = s
            w[r_c + b * L + l] = c
    for u in range(nu):
        k1, k2 = (ku0 + 3 * u + 1) * L, (ku0 + 3 * u + 2) * L
        for l in range(nl):
            w[r_eux + u * L + l] = w[r_cth + l] * p[k1 + l] - w[r_sth + l] * p[k2 + l]
            w[r_euy + u * L + l] = w[r_sth + l] * p[k1 + l] + w[r_cth + l] * p[k2 + l]
    # ---- tilting races: their nodes' tilt and its rate, each ball's e.phi', t.phi' and arm
    if tilt:
        for k in range(nt):
            kb = stb + 4 * nz * (nr + nu + k)  # the tilt station's T (2 x n_z)
            for row, dst, src in ((0, tab[R_TX], 0), (1, tab[R_TY], 0), (0, tab[R_TVX], nz), (1, tab[R_TVY], nz)):
                kd = (dst + k) * L
                for j in range(nz):
                    kp, kyj = (kb + row * nz + j) * L, (src + j) * L
                    if j == 0:
                        for l in range(nl):
                            w[kd + l] = p[kp + l] * y[kyj + l]
                    else:
                        for l in range(nl):
                            w[kd + l] += p[kp + l] * y[kyj + l]
        for b in range(nb):
            k = tab[bts + b] - nr  # the ball's tilt station among the tilt stations
            ktx, kty = (tab[R_TX] + k) * L, (tab[R_TY] + k) * L
            kvx, kvy = (tab[R_TVX] + k) * L, (tab[R_TVY] + k) * L
            kj = (kb0 + 4 * b + 2) * L
            for l in range(nl):
                s, c = w[r_s + b * L + l], w[r_c + b * L + l]
                w[r_ep + b * L + l] = c * w[kvx + l] + s * w[kvy + l]
                w[r_tp + b * L + l] = c * w[kvy + l] - s * w[kvx + l]
                w[r_nx + b * L + l] = 0.5 * p[kj + l] * w[kty + l]
                w[r_ny + b * L + l] = -0.5 * p[kj + l] * w[ktx + l]
    # ---- station forces: races (centrifugal), unbalances, tilt stations (the balls' velocity terms)
    for i in range(2 * nfs):
        for l in range(nl):
            w[r_f + i * L + l] = 0.0
    for b in range(nb):
        r = tab[brace + b]
        kml, kw = (kb0 + 4 * b + 1) * L, (iw + b) * L
        for l in range(nl):
            mw = p[kml + l] * y[kw + l] * y[kw + l]
            w[r_f + 2 * r * L + l] += mw * w[r_c + b * L + l]
            w[r_f + (2 * r + 1) * L + l] += mw * w[r_s + b * L + l]
    for u in range(nu):
        kU, fs = (ku0 + 3 * u) * L, nr + u
        for l in range(nl):
            om = p[kom + l]
            dom = 0.0
            eux, euy = w[r_eux + u * L + l], w[r_euy + u * L + l]
            w[r_f + 2 * fs * L + l] = p[kU + l] * (om * om * eux + dom * euy)
            w[r_f + (2 * fs + 1) * L + l] = p[kU + l] * (om * om * euy - dom * eux)
    if tilt:
        for b in range(nb):
            k = tab[bts + b] - nr
            fs = nr + nu + k
            kvx, kvy = (tab[R_TVX] + k) * L, (tab[R_TVY] + k) * L
            kj, kd, kw = (kb0 + 4 * b + 2) * L, (tab[T_PTILT] + b) * L, (iw + b) * L
            for l in range(nl):
                s, c, ep, tp = w[r_s + b * L + l], w[r_c + b * L + l], w[r_ep + b * L + l], w[r_tp + b * L + l]
                wb, D, J = y[kw + l], p[kd + l], p[kj + l]
                w[r_f + 2 * fs * L + l] += wb * (D * (tp * c - ep * s) + J * w[kvy + l])
                w[r_f + (2 * fs + 1) * L + l] += wb * (D * (tp * s + ep * c) - J * w[kvx + l])
        for i in range(2 * (nr + nu), 2 * nfs):
            for l in range(nl):
                w[r_f + i * L + l] = -w[r_f + i * L + l]
    # ---- h = H R_z: H f_g - H K z - H C z' - Omega H G z' + sum_s H B_s^T f_s
    khk, khc, khg, khf = tab[T_HK], tab[T_HC], tab[T_HG], tab[T_HF]
    for i in range(nz):
        kh = r_h + i * L
        for l in range(nl):
            w[kh + l] = p[(khf + i) * L + l]
        for j in range(nz):
            kp, kz = (khk + nz * i + j) * L, j * L
            for l in range(nl):
                w[kh + l] -= p[kp + l] * y[kz + l]
        for j in range(nz):
            kp, kv = (khc + nz * i + j) * L, (nz + j) * L
            for l in range(nl):
                w[kh + l] -= p[kp + l] * y[kv + l]
        if tab[T_GYRO]:
            for j in range(nz):
                kp, kv = (khg + nz * i + j) * L, (nz + j) * L
                if j == 0:
                    for l in range(nl):
                        w[r_acc + l] = p[kp + l] * y[kv + l]
                else:
                    for l in range(nl):
                        w[r_acc + l] += p[kp + l] * y[kv + l]
            for l in range(nl):
                w[kh + l] -= p[kom + l] * w[r_acc + l]
        for q in range(nfs):
            s = tab[fst + q]
            kp = (stb + 4 * nz * s + 2 * nz + 2 * i) * L
            kf = r_f + 2 * q * L
            for l in range(nl):
                w[kh + l] += p[kp + l] * w[kf + l] + p[kp + L + l] * w[kf + L + l]
    # ---- a_s = B_s h at the Schur unknowns' stations
    for iu in range(nused):
        s = tab[used + iu]
        for row in range(2):
            ka = r_a + (2 * iu + row) * L
            for j in range(nz):
                kp, kh = (stb + 4 * nz * s + row * nz + j) * L, r_h + j * L
                if j == 0:
                    for l in range(nl):
                        w[ka + l] = p[kp + l] * w[kh + l]
                else:
                    for l in range(nl):
                        w[ka + l] += p[kp + l] * w[kh + l]
    # ---- the loads' vectors (ml t_b); the pair matrices B_s H B_s'^T of the used stations
    for b in range(nb):
        kml = (kb0 + 4 * b + 1) * L
        for l in range(nl):
            w[r_mtx + b * L + l] = -p[kml + l] * w[r_s + b * L + l]
            w[r_mty + b * L + l] = p[kml + l] * w[r_c + b * L + l]
    for i1 in range(nused):
        s1 = tab[used + i1]
        for i2 in range(i1, nused):
            s2 = tab[used + i2]
            for k in range(4):
                row, col = k // 2, k % 2
                kd = r_lv + (4 * (i1 * nused + i2) + k) * L
                kt = r_lv + (4 * (i2 * nused + i1) + 2 * col + row) * L
                if tilt:  # B_s1 (H B_s2^T) from the packed B and H B^T (as the generated kernel)
                    for j in range(nz):
                        kb = (stb + 4 * nz * s1 + row * nz + j) * L
                        kh = (stb + 4 * nz * s2 + 2 * nz + 2 * j + col) * L
                        if j == 0:
                            for l in range(nl):
                                w[kd + l] = p[kb + l] * p[kh + l]
                        else:
                            for l in range(nl):
                                w[kd + l] += p[kb + l] * p[kh + l]
                else:  # the packed pair matrix
                    kp = (tab[T_LOFF] + 4 * (s1 * nall + s2) + k) * L
                    for l in range(nl):
                        w[kd + l] = p[kp + l]
                if i2 != i1:
                    for l in range(nl):
                        w[kt + l] = w[kd + l]
    # ---- P_j = B_s H X_j; S = diag - X^T H X (lower triangle); q
    for j in range(ns):
        nld = tab[lds + N_LOAD * j]
        for iu in range(nused):
            for row in range(2):
                kd = r_p + (2 * (j * nused + iu) + row) * L
                for m in range(nld):
                    iu2 = tab[lds + N_LOAD * j + 2 + 4 * m]
                    kvx = tab[lds + N_LOAD * j + 3 + 4 * m] * L
                    kvy = tab[lds + N_LOAD * j + 4 + 4 * m] * L
                    k0 = r_lv + (4 * (iu * nused + iu2) + 2 * row) * L
                    if m == 0:
                        for l in range(nl):
                            w[kd + l] = w[k0 + l] * w[kvx + l]
                    else:
                        for l in range(nl):
                            w[kd + l] += w[k0 + l] * w[kvx + l]
                    for l in range(nl):
                        w[kd + l] += w[k0 + L + l] * w[kvy + l]
    for i in range(ns):
        nld = tab[lds + N_LOAD * i]
        for j in range(i + 1):
            kd = r_sm + (i * ns + j) * L
            for m in range(nld):
                iu = tab[lds + N_LOAD * i + 2 + 4 * m]
                kvx = tab[lds + N_LOAD * i + 3 + 4 * m] * L
                kvy = tab[lds + N_LOAD * i + 4 + 4 * m] * L
                kpx = r_p + 2 * (j * nused + iu) * L
                if m == 0:
                    for l in range(nl):
                        w[r_acc + l] = w[kvx + l] * w[kpx + l]
                else:
                    for l in range(nl):
                        w[r_acc + l] += w[kvx + l] * w[kpx + l]
                for l in range(nl):
                    w[r_acc + l] += w[kvy + l] * w[kpx + L + l]
            if i != j:
                for l in range(nl):
                    w[kd + l] = -w[r_acc + l]
            elif i < nb:  # a ball: its inertia J
                kj = (kb0 + 4 * i + 2) * L
                for l in range(nl):
                    w[kd + l] = p[kj + l] - w[r_acc + l]
            else:  # an axial unknown: -1 / D
                kt = (tab[T_PTILT] + i - nb) * L
                for l in range(nl):
                    w[kd + l] = -1.0 / p[kt + l] - w[r_acc + l]
    for b in range(nb):
        r = tab[brace + b]
        kcb, kml, kw = (kb0 + 4 * b + 3) * L, (kb0 + 4 * b + 1) * L, (iw + b) * L
        kax, kay = r_a + 2 * r * L, r_a + (2 * r + 1) * L
        for l in range(nl):
            s, c, ml = w[r_s + b * L + l], w[r_c + b * L + l], p[kml + l]
            rel = y[kw + l] - p[kom + l]
            w[r_q + b * L + l] = (-p[kcb + l] * rel + ml * (-p[kgx + l] * s + p[kgy + l] * c)
                                  - ml * (-s * w[kax + l] + c * w[kay + l]))
        if tilt:
            it = tab[bts + b]
            kax, kay = r_a + 2 * it * L, r_a + (2 * it + 1) * L
            kd = (tab[T_PTILT] + b) * L
            for l in range(nl):
                w[r_q + b * L + l] += p[kd + l] * w[r_ep + b * L + l] * w[r_tp + b * L + l]
                w[r_q + b * L + l] -= w[r_nx + b * L + l] * w[kax + l] + w[r_ny + b * L + l] * w[kay + l]
                w[r_q + (nb + b) * L + l] = -(w[r_c + b * L + l] * w[kax + l] + w[r_s + b * L + l] * w[kay + l])
    # ---- LDL^T of S (no pivoting, as the generated kernel), forward and back substitution
    for j in range(ns):
        kdj = r_d + j * L
        for l in range(nl):
            w[kdj + l] = w[r_sm + (j * ns + j) * L + l]
        for k in range(j):
            kl = r_l + (j * ns + k) * L
            for l in range(nl):
                w[kdj + l] -= w[kl + l] * w[kl + l] * w[r_d + k * L + l]
        for i in range(j + 1, ns):
            kl = r_l + (i * ns + j) * L
            for l in range(nl):
                w[kl + l] = w[r_sm + (i * ns + j) * L + l]
            for k in range(j):
                ki, kj, kk = r_l + (i * ns + k) * L, r_l + (j * ns + k) * L, r_d + k * L
                for l in range(nl):
                    w[kl + l] -= w[ki + l] * w[kj + l] * w[kk + l]
            for l in range(nl):
                w[kl + l] = w[kl + l] / w[kdj + l]
    for i in range(ns):
        kx = r_x + i * L
        for l in range(nl):
            w[kx + l] = w[r_q + i * L + l]
        for k in range(i):
            kl, kk = r_l + (i * ns + k) * L, r_x + k * L
            for l in range(nl):
                w[kx + l] -= w[kl + l] * w[kk + l]
    for i in range(ns - 1, -1, -1):
        kx = r_x + i * L
        for l in range(nl):
            w[kx + l] = w[kx + l] / w[r_d + i * L + l]
        for k in range(i + 1, ns):
            kl, kk = r_l + (k * ns + i) * L, r_x + k * L
            for l in range(nl):
                w[kx + l] -= w[kl + l] * w[kk + l]
    # ---- the station forces of the solution: g_s = sum_j (vx, vy)_j x_j over the loads at s
    for i in range(2 * nused):
        for l in range(nl):
            w[r_g + i * L + l] = 0.0
    for b in range(nb):  # in the generated kernel's order: races, then per ball n_b x_b + (c, s) mu_b
        r = tab[brace + b]
        kml, kx, kg = (kb0 + 4 * b + 1) * L, r_x + b * L, r_g + 2 * r * L
        for l in range(nl):
            w[kg + l] += -p[kml + l] * w[kx + l] * w[r_s + b * L + l]
            w[kg + L + l] += p[kml + l] * w[kx + l] * w[r_c + b * L + l]
    if tilt:
        for b in range(nb):
            kg, kx, ka = r_g + 2 * tab[bts + b] * L, r_x + b * L, r_x + (nb + b) * L
            for l in range(nl):
                w[kg + l] += w[r_nx + b * L + l] * w[kx + l]
                w[kg + l] += w[r_c + b * L + l] * w[ka + l]
                w[kg + L + l] += w[r_ny + b * L + l] * w[kx + l]
                w[kg + L + l] += w[r_s + b * L + l] * w[ka + l]
    # ---- dy/dt
    for i in range(nz):
        kv, ko = (nz + i) * L, (nz + i) * L
        for l in range(nl):
            out[i * L + l] = y[kv + l]
            out[ko + l] = w[r_h + i * L + l]
        for iu in range(nused):
            s = tab[used + iu]
            kp = (stb + 4 * nz * s + 2 * nz + 2 * i) * L
            kg = r_g + 2 * iu * L
            for l in range(nl):
                out[ko + l] -= p[kp + l] * w[kg + l] + p[kp + L + l] * w[kg + L + l]
    for b in range(nb):
        for l in range(nl):
            out[(iphi + b) * L + l] = y[(iw + b) * L + l]
            out[(iw + b) * L + l] = w[r_x + b * L + l]
