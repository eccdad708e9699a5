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
vectorises each loop across the lanes; the dense products (the structure's and the stations'
matrices) come in two forms, a loop over lanes per term or eight accumulators kept in registers
(:func:`kernel`). The arithmetic follows the generated kernel's term by
term (same order of every sum), so the two agree to round-off (the bench checks 1e-12).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorlab._kernels._vmath import sincos
from rotorlab.integrate._lane_intrinsics import lane_view

LANES = 8  # the lane driver's stride (DEFAULT_LANES): a compile-time constant, as in its copies

# ---- the integer table: sizes, offsets and row numbers (T_*), then per-ball and per-unknown lists
(T_NZ, T_NR, T_NB, T_NU, T_GYRO, T_TILT, T_NS, T_NT, T_NUSED, T_NFS,
 T_SPEED, T_GRAV, T_BALLS, T_UNB, T_HK, T_HC, T_HG, T_HF, T_PTILT, T_IPHI, T_IW,
 T_STB, T_STH, T_LOFF, T_NALL,
 R_STH, R_CTH, R_S, R_C, R_EUX, R_EUY, R_TX, R_TY, R_TVX, R_TVY, R_EP, R_TP, R_NX, R_NY,
 R_MTX, R_MTY, R_F, R_H, R_A, R_LV, R_P, R_SM, R_Q, R_X, R_D, R_L, R_G, R_ACC,
 T_BRACE, T_BTS, T_USED, T_FST, T_LOADS, _T_SPARE) = range(59)
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


_view = lane_view(1)


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def V(a, row):  # pragma: no cover - compiled
    """Row ``row`` of the lane-interleaved array ``a`` (its ``LANES`` lanes): a view without a
    reference count whose index ``l >= 0`` carries no wraparound select, so that the loops over
    lanes vectorise (``a[row * LANES + l]`` with a run-time ``row`` does not)."""
    return _view(a, row * LANES, LANES)


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def zero(w, row, n, nl):  # pragma: no cover - compiled
    """Set the rows ``row .. row + n - 1`` of ``w`` to 0 in every lane."""
    for i in range(n):
        d = V(w, row + i)
        for l in range(nl):
            d[l] = 0.0

# ---- the dense products, in two forms (``kernel(dense=...)``): a loop over lanes per term, or
# eight accumulators held in registers over the terms (the lanes fixed at LANES = 8, written out)

@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def dot_loops(d, a, ka, sa, b, kb, sb, n, nl):  # pragma: no cover - compiled
    """``d = sum_j a[ka + j sa] * b[kb + j sb]`` (rows; the first term, then the others added)."""
    r, q = V(a, ka), V(b, kb)
    for l in range(nl):
        d[l] = r[l] * q[l]
    for j in range(1, n):
        r, q = V(a, ka + j * sa), V(b, kb + j * sb)
        for l in range(nl):
            d[l] += r[l] * q[l]


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def less_dot_loops(d, a, ka, b, kb, n, nl):  # pragma: no cover - compiled
    """``d -= a[ka + j] * b[kb + j]`` for j = 0 .. n - 1 in turn (rows)."""
    for j in range(n):
        r, q = V(a, ka + j), V(b, kb + j)
        for l in range(nl):
            d[l] -= r[l] * q[l]


def _blocked_source() -> str:
    lanes = range(LANES)
    acc = ", ".join(f"x{l}" for l in lanes)
    load = "\n".join(f"    x{l} = r[{l}] * q[{l}]" for l in lanes)
    add = "\n".join(f"        x{l} += r[{l}] * q[{l}]" for l in lanes)
    sub = "\n".join(f"        x{l} -= r[{l}] * q[{l}]" for l in lanes)
    get = "\n".join(f"    x{l} = d[{l}]" for l in lanes)
    put = "\n".join(f"    d[{l}] = x{l}" for l in lanes)
    return (f"def dot_blocked(d, a, ka, sa, b, kb, sb, n, nl):\n    r, q = V(a, ka), V(b, kb)\n{load}\n"
            f"    for j in range(1, n):\n        r, q = V(a, ka + j * sa), V(b, kb + j * sb)\n{add}\n{put}\n\n"
            f"def less_dot_blocked(d, a, ka, b, kb, n, nl):\n{get}\n    for j in range(n):\n"
            f"        r, q = V(a, ka + j), V(b, kb + j)\n{sub}\n{put}\n")


_ns: dict = {"V": V}
exec(_blocked_source(), _ns)  # noqa: S102 - eight accumulators written out, one per lane
dot_blocked = njit(nogil=True, inline="always", error_model="numpy")(_ns["dot_blocked"])
less_dot_blocked = njit(nogil=True, inline="always", error_model="numpy")(_ns["less_dot_blocked"])
dot, less_dot = dot_loops, less_dot_loops  # what rhs_generic (cached) uses


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_generic(t, y, p, tab, w, out, nl):  # pragma: no cover - compiled
    """``out = rhs(t, y, p)`` for ``nl`` lanes of any layout of the common subset (module docstring).

    ``t``: the lanes' times; ``y``, ``p``, ``out``: lane-interleaved state, packed parameters and
    derivative (stride :data:`LANES`); ``tab``: :func:`table`; ``w``: scratch of ``table(...)[1]``
    rows of :data:`LANES`."""
    nz, nr, nb, nu = tab[T_NZ], tab[T_NR], tab[T_NB], tab[T_NU]
    tilt, ns, nt, nused, nfs = tab[T_TILT], tab[T_NS], tab[T_NT], tab[T_NUSED], tab[T_NFS]
    kom = tab[T_SPEED] + 1  # the constant speed's row of p
    kb0, ku0, iphi, iw, kti = tab[T_BALLS], tab[T_UNB], tab[T_IPHI], tab[T_IW], tab[T_PTILT]
    stb, nall = tab[T_STB], tab[T_NALL]
    brace, bts, used, fst, lds = tab[T_BRACE], tab[T_BTS], tab[T_USED], tab[T_FST], tab[T_LOADS]
    r_s, r_c, r_mtx, r_mty = tab[R_S], tab[R_C], tab[R_MTX], tab[R_MTY]
    r_ep, r_tp, r_nx, r_ny = tab[R_EP], tab[R_TP], tab[R_NX], tab[R_NY]
    r_f, r_h, r_a, r_lv, r_p = tab[R_F], tab[R_H], tab[R_A], tab[R_LV], tab[R_P]
    r_sm, r_q, r_x, r_d, r_l, r_g = tab[R_SM], tab[R_Q], tab[R_X], tab[R_D], tab[R_L], tab[R_G]
    r_tx, r_ty, r_tvx, r_tvy = tab[R_TX], tab[R_TY], tab[R_TVX], tab[R_TVY]
    om, gx, gy = V(p, kom), V(p, tab[T_GRAV]), V(p, tab[T_GRAV] + 1)
    sth, cth, acc = V(w, tab[R_STH]), V(w, tab[R_CTH]), V(w, tab[R_ACC])
    # ---- spin, ball angles, unbalance directions
    for l in range(nl):
        s, c = sincos(om[l] * t[l])
        sth[l] = s
        cth[l] = c
    for b in range(nb):
        ph, sb, cb = V(y, iphi + b), V(w, r_s + b), V(w, r_c + b)
        for l in range(nl):
            s, c = sincos(ph[l])
            sb[l] = s
            cb[l] = c
    for u in range(nu):
        p1, p2, ex, ey = V(p, ku0 + 3 * u + 1), V(p, ku0 + 3 * u + 2), V(w, tab[R_EUX] + u), V(w, tab[R_EUY] + u)
        for l in range(nl):
            ex[l] = cth[l] * p1[l] - sth[l] * p2[l]
            ey[l] = sth[l] * p1[l] + cth[l] * p2[l]
    # ---- tilting races: their nodes' tilt and its rate, each ball's e.phi', t.phi' and arm
    if tilt:
        for k in range(nt):
            kb = stb + 4 * nz * (nr + nu + k)  # the tilt station's T (2 x n_z)
            for row, dst, src in ((0, r_tx, 0), (1, r_ty, 0), (0, r_tvx, nz), (1, r_tvy, nz)):
                dot(V(w, dst + k), p, kb + row * nz, 1, y, src, 1, nz, nl)
        for b in range(nb):
            k = tab[bts + b] - nr  # the ball's tilt station among the tilt stations
            tx, ty, tvx, tvy = V(w, r_tx + k), V(w, r_ty + k), V(w, r_tvx + k), V(w, r_tvy + k)
            sb, cb, J = V(w, r_s + b), V(w, r_c + b), V(p, kb0 + 4 * b + 2)
            ep, tp, nx, ny = V(w, r_ep + b), V(w, r_tp + b), V(w, r_nx + b), V(w, r_ny + b)
            for l in range(nl):
                ep[l] = cb[l] * tvx[l] + sb[l] * tvy[l]
                tp[l] = cb[l] * tvy[l] - sb[l] * tvx[l]
                nx[l] = 0.5 * J[l] * ty[l]
                ny[l] = -0.5 * J[l] * tx[l]
    # ---- station forces: races (centrifugal), unbalances, tilt stations (the balls' velocity terms)
    zero(w, r_f, 2 * nfs, nl)
    for b in range(nb):
        r = tab[brace + b]
        ml, wb, sb, cb = V(p, kb0 + 4 * b + 1), V(y, iw + b), V(w, r_s + b), V(w, r_c + b)
        fx, fy = V(w, r_f + 2 * r), V(w, r_f + 2 * r + 1)
        for l in range(nl):
            mw = ml[l] * wb[l] * wb[l]
            fx[l] += mw * cb[l]
            fy[l] += mw * sb[l]
    for u in range(nu):
        fs = nr + u
        U, ex, ey = V(p, ku0 + 3 * u), V(w, tab[R_EUX] + u), V(w, tab[R_EUY] + u)
        fx, fy = V(w, r_f + 2 * fs), V(w, r_f + 2 * fs + 1)
        for l in range(nl):
            o = om[l]
            dom = 0.0
            fx[l] = U[l] * (o * o * ex[l] + dom * ey[l])
            fy[l] = U[l] * (o * o * ey[l] - dom * ex[l])
    if tilt:
        for b in range(nb):
            k = tab[bts + b] - nr
            fs = nr + nu + k
            tvx, tvy, J, D, wb = V(w, r_tvx + k), V(w, r_tvy + k), V(p, kb0 + 4 * b + 2), V(p, kti + b), V(y, iw + b)
            sb, cb, ep, tp = V(w, r_s + b), V(w, r_c + b), V(w, r_ep + b), V(w, r_tp + b)
            fx, fy = V(w, r_f + 2 * fs), V(w, r_f + 2 * fs + 1)
            for l in range(nl):
                fx[l] += wb[l] * (D[l] * (tp[l] * cb[l] - ep[l] * sb[l]) + J[l] * tvy[l])
                fy[l] += wb[l] * (D[l] * (tp[l] * sb[l] + ep[l] * cb[l]) - J[l] * tvx[l])
        for i in range(2 * (nr + nu), 2 * nfs):
            f = V(w, r_f + i)
            for l in range(nl):
                f[l] = -f[l]
    # ---- h = H R_z: H f_g - H K z - H C z' - Omega H G z' + sum_s H B_s^T f_s
    khk, khc, khg, khf = tab[T_HK], tab[T_HC], tab[T_HG], tab[T_HF]
    for i in range(nz):
        h, hf = V(w, r_h + i), V(p, khf + i)
        for l in range(nl):
            h[l] = hf[l]
        less_dot(h, p, khk + nz * i, y, 0, nz, nl)
        less_dot(h, p, khc + nz * i, y, nz, nz, nl)
        if tab[T_GYRO]:
            dot(acc, p, khg + nz * i, 1, y, nz, 1, nz, nl)
            for l in range(nl):
                h[l] -= om[l] * acc[l]
        for q in range(nfs):
            s = tab[fst + q]
            a0, a1 = V(p, stb + 4 * nz * s + 2 * nz + 2 * i), V(p, stb + 4 * nz * s + 2 * nz + 2 * i + 1)
            fx, fy = V(w, r_f + 2 * q), V(w, r_f + 2 * q + 1)
            for l in range(nl):
                h[l] += a0[l] * fx[l] + a1[l] * fy[l]
    # ---- a_s = B_s h at the Schur unknowns' stations
    for iu in range(nused):
        s = tab[used + iu]
        for row in range(2):
            dot(V(w, r_a + 2 * iu + row), p, stb + 4 * nz * s + row * nz, 1, w, r_h, 1, nz, nl)
    # ---- the loads' vectors (m l t_b); the pair matrices B_s H B_s'^T of the used stations
    for b in range(nb):
        ml, sb, cb, mx, my = V(p, kb0 + 4 * b + 1), V(w, r_s + b), V(w, r_c + b), V(w, r_mtx + b), V(w, r_mty + b)
        for l in range(nl):
            mx[l] = -ml[l] * sb[l]
            my[l] = ml[l] * cb[l]
    for i1 in range(nused):
        s1 = tab[used + i1]
        for i2 in range(i1, nused):
            s2 = tab[used + i2]
            for k in range(4):
                row, col = k // 2, k % 2
                d = V(w, r_lv + 4 * (i1 * nused + i2) + k)
                if tilt:  # B_s1 (H B_s2^T) from the packed B and H B^T (as the generated kernel)
                    dot(d, p, stb + 4 * nz * s1 + row * nz, 1, p, stb + 4 * nz * s2 + 2 * nz + col, 2, nz, nl)
                else:  # the packed pair matrix
                    a = V(p, tab[T_LOFF] + 4 * (s1 * nall + s2) + k)
                    for l in range(nl):
                        d[l] = a[l]
                if i2 != i1:
                    e = V(w, r_lv + 4 * (i2 * nused + i1) + 2 * col + row)
                    for l in range(nl):
                        e[l] = d[l]
    # ---- P_j = B_s H X_j; S = diag - X^T H X (lower triangle); q
    for j in range(ns):
        nld = tab[lds + N_LOAD * j]
        for iu in range(nused):
            for row in range(2):
                d = V(w, r_p + 2 * (j * nused + iu) + row)
                for m in range(nld):
                    iu2 = tab[lds + N_LOAD * j + 2 + 4 * m]
                    vx, vy = V(w, tab[lds + N_LOAD * j + 3 + 4 * m]), V(w, tab[lds + N_LOAD * j + 4 + 4 * m])
                    l0 = V(w, r_lv + 4 * (iu * nused + iu2) + 2 * row)
                    l1 = V(w, r_lv + 4 * (iu * nused + iu2) + 2 * row + 1)
                    if m == 0:
                        for l in range(nl):
                            d[l] = l0[l] * vx[l]
                    else:
                        for l in range(nl):
                            d[l] += l0[l] * vx[l]
                    for l in range(nl):
                        d[l] += l1[l] * vy[l]
    for i in range(ns):
        nld = tab[lds + N_LOAD * i]
        for j in range(i + 1):
            for m in range(nld):
                iu = tab[lds + N_LOAD * i + 2 + 4 * m]
                vx, vy = V(w, tab[lds + N_LOAD * i + 3 + 4 * m]), V(w, tab[lds + N_LOAD * i + 4 + 4 * m])
                px, py = V(w, r_p + 2 * (j * nused + iu)), V(w, r_p + 2 * (j * nused + iu) + 1)
                if m == 0:
                    for l in range(nl):
                        acc[l] = vx[l] * px[l]
                else:
                    for l in range(nl):
                        acc[l] += vx[l] * px[l]
                for l in range(nl):
                    acc[l] += vy[l] * py[l]
            d = V(w, r_sm + i * ns + j)
            if i != j:
                for l in range(nl):
                    d[l] = -acc[l]
            elif i < nb:  # a ball: its inertia J
                J = V(p, kb0 + 4 * i + 2)
                for l in range(nl):
                    d[l] = J[l] - acc[l]
            else:  # an axial unknown: -1 / D
                D = V(p, kti + i - nb)
                for l in range(nl):
                    d[l] = -1.0 / D[l] - acc[l]
    for b in range(nb):
        r = tab[brace + b]
        cb_, ml, wb, sb, cb = V(p, kb0 + 4 * b + 3), V(p, kb0 + 4 * b + 1), V(y, iw + b), V(w, r_s + b), V(w, r_c + b)
        ax, ay, q = V(w, r_a + 2 * r), V(w, r_a + 2 * r + 1), V(w, r_q + b)
        for l in range(nl):
            s, c, m = sb[l], cb[l], ml[l]
            rel = wb[l] - om[l]
            q[l] = -cb_[l] * rel + m * (-gx[l] * s + gy[l] * c) - m * (-s * ax[l] + c * ay[l])
        if tilt:
            it = tab[bts + b]
            ax, ay, D, qa = V(w, r_a + 2 * it), V(w, r_a + 2 * it + 1), V(p, kti + b), V(w, r_q + nb + b)
            ep, tp, nx, ny = V(w, r_ep + b), V(w, r_tp + b), V(w, r_nx + b), V(w, r_ny + b)
            for l in range(nl):
                q[l] += D[l] * ep[l] * tp[l]
                q[l] -= nx[l] * ax[l] + ny[l] * ay[l]
                qa[l] = -(cb[l] * ax[l] + sb[l] * ay[l])
    # ---- LDL^T of S (no pivoting, as the generated kernel), forward and back substitution
    for j in range(ns):
        dj, sjj = V(w, r_d + j), V(w, r_sm + j * ns + j)
        for l in range(nl):
            dj[l] = sjj[l]
        for k in range(j):
            ljk, dk = V(w, r_l + j * ns + k), V(w, r_d + k)
            for l in range(nl):
                dj[l] -= ljk[l] * ljk[l] * dk[l]
        for i in range(j + 1, ns):
            lij, sij = V(w, r_l + i * ns + j), V(w, r_sm + i * ns + j)
            for l in range(nl):
                lij[l] = sij[l]
            for k in range(j):
                lik, ljk, dk = V(w, r_l + i * ns + k), V(w, r_l + j * ns + k), V(w, r_d + k)
                for l in range(nl):
                    lij[l] -= lik[l] * ljk[l] * dk[l]
            for l in range(nl):
                lij[l] = lij[l] / dj[l]
    for i in range(ns):
        xi, qi = V(w, r_x + i), V(w, r_q + i)
        for l in range(nl):
            xi[l] = qi[l]
        for k in range(i):
            lik, xk = V(w, r_l + i * ns + k), V(w, r_x + k)
            for l in range(nl):
                xi[l] -= lik[l] * xk[l]
    for i in range(ns - 1, -1, -1):
        xi, di = V(w, r_x + i), V(w, r_d + i)
        for l in range(nl):
            xi[l] = xi[l] / di[l]
        for k in range(i + 1, ns):
            lki, xk = V(w, r_l + k * ns + i), V(w, r_x + k)
            for l in range(nl):
                xi[l] -= lki[l] * xk[l]
    # ---- the station forces of the solution, in the generated kernel's order: the races, then
    # per ball n_b x_b + (c, s) mu_b at its race's tilt station
    zero(w, r_g, 2 * nused, nl)
    for b in range(nb):
        r = tab[brace + b]
        ml, xb, sb, cb = V(p, kb0 + 4 * b + 1), V(w, r_x + b), V(w, r_s + b), V(w, r_c + b)
        gx_, gy_ = V(w, r_g + 2 * r), V(w, r_g + 2 * r + 1)
        for l in range(nl):
            gx_[l] += -ml[l] * xb[l] * sb[l]
            gy_[l] += ml[l] * xb[l] * cb[l]
    if tilt:
        for b in range(nb):
            it = tab[bts + b]
            gx_, gy_, xb, xa = V(w, r_g + 2 * it), V(w, r_g + 2 * it + 1), V(w, r_x + b), V(w, r_x + nb + b)
            nx, ny, sb, cb = V(w, r_nx + b), V(w, r_ny + b), V(w, r_s + b), V(w, r_c + b)
            for l in range(nl):
                gx_[l] += nx[l] * xb[l]
                gx_[l] += cb[l] * xa[l]
                gy_[l] += ny[l] * xb[l]
                gy_[l] += sb[l] * xa[l]
    # ---- dy/dt
    for i in range(nz):
        o0, o1, v, h = V(out, i), V(out, nz + i), V(y, nz + i), V(w, r_h + i)
        for l in range(nl):
            o0[l] = v[l]
            o1[l] = h[l]
        for iu in range(nused):
            s = tab[used + iu]
            a0, a1 = V(p, stb + 4 * nz * s + 2 * nz + 2 * i), V(p, stb + 4 * nz * s + 2 * nz + 2 * i + 1)
            g0, g1 = V(w, r_g + 2 * iu), V(w, r_g + 2 * iu + 1)
            for l in range(nl):
                o1[l] -= a0[l] * g0[l] + a1[l] * g1[l]
    for b in range(nb):
        o0, o1, wb, xb = V(out, iphi + b), V(out, iw + b), V(y, iw + b), V(w, r_x + b)
        for l in range(nl):
            o0[l] = wb[l]
            o1[l] = xb[l]


def kernel(dense: str = "loops", cache: bool = False):
    """``rhs_generic`` compiled with the dense products of ``dense`` (``"loops"``: a loop over
    lanes per term; ``"blocked"``: eight accumulators in registers, all lanes always computed)."""
    import types

    fn = rhs_generic.py_func
    g = dict(fn.__globals__, dot=globals()[f"dot_{dense}"], less_dot=globals()[f"less_dot_{dense}"])
    return njit(nogil=True, error_model="numpy", cache=cache)(
        types.FunctionType(fn.__code__, g, f"rhs_generic_{dense}"))
