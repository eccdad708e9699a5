"""Lane driver: several trajectories stepped together in the SIMD lanes of one register.

What it does
------------
Each worker thread keeps ``LANES`` trajectories in flight. The state, the stages and the
derivatives of all lanes live in lane-interleaved buffers (element ``i`` of lane ``l`` at
``buf[i * LANES + l]``), so that a loop over lanes reads and writes consecutive doubles. Every
stage is one vectorised loop over all ``n * LANES`` numbers plus one call of the model's
right-hand side for all lanes, which LLVM vectorises across the lanes when the kernel allows it
(see "Lane-friendly kernels" below). Each lane has its own time, step size, accept/reject
decision and counters, with exactly the arithmetic of :func:`rotorlab.integrate._core.integrate_one`
(Dormand–Prince 5(4), SciPy's RK45 controller), so a trajectory gives the same numbers bit for
bit on either path. A lane whose trajectory ends is refilled at once with the next trajectory of
the ensemble, taken from a counter shared by the worker threads (``atomicrmw add``): the threads
pull work dynamically, so a few long trajectories never leave a thread idle while another has a
queue. This is the scheme of ``shared/bench/dp5_simd.c``.

No events: a model whose active events need locating keeps the scalar driver (``_core``).
Saving at given times uses the same quartic dense output as the scalar driver.

Lane-friendly kernels
---------------------
The driver calls the model's ``rhs`` once per lane inside a loop over lanes; the kernel is
recompiled here with ``inline="always"`` and ``error_model="numpy"`` so that LLVM sees one
straight loop body. LLVM vectorises that loop when the kernel

1. computes sines and cosines with :func:`rotorlab._kernels._vmath.sincos` (``math.sin``/``cos``
   are scalar library calls), and otherwise uses only arithmetic, ``abs``, ``min``/``max``,
   ``math.sqrt``, ``np.floor`` and comparisons (``math.exp``, ``math.pow`` ... are computed one
   lane at a time: correct, but slow);
2. has no loop whose trip count is not a compile-time constant (LLVM vectorises innermost loops
   only, so a ``for i in range(int(p[0]))`` becomes the vectorised loop instead of the lanes);
3. has no branch with an expensive or side-effecting arm (both arms of an ``if`` are executed
   for all lanes, then selected), no ``raise``, and calls only functions compiled with
   ``inline="always"`` (a call of another compiled function is opaque to LLVM).

A kernel that breaks these rules still gives identical results on the lane path, only no faster
than the scalar path. :func:`is_vectorised` reports whether it vectorised.

Why not a lane kernel ``rhs_lanes`` written by the model? It would be a second hand-written right
side per model to keep in sync with the first; the loop above vectorises the existing one.

This module is also the template of per-model copies: :func:`lane_drivers_for` writes a copy in
which the import line marked ``# @kernel`` imports the model's ``rhs`` (see
:mod:`rotorlab.integrate._specialize` for why), so numba caches it across processes.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange, types
from numba.extending import intrinsic

from rotorlab.models._base import no_rhs as rhs  # @kernel
from rotorlab.integrate._core import (
    MAX_STEPS, NONFINITE, ST_NACCEPT, ST_NEVENTS, ST_NFEV, ST_NREJECT, STEP_UNDERFLOW, SUCCESS,
    _all_finite, _dense,
)  # fmt: skip
from rotorlab.integrate._tableau import (
    A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64, A65,
    B1, B3, B4, B5, B6,
    C2, C3, C4, C5,
    E1, E3, E4, E5, E6, E7,
    ERROR_EXPONENT, MAX_FACTOR, MIN_FACTOR, SAFETY,
)  # fmt: skip

LANES = 8  # @lanes
"""Trajectories per worker stepped together (set per generated copy; see ``lane_driver``)."""

# The model's kernel inlined at numba-IR level: LLVM does not inline a separately compiled
# dispatcher of this size, and a call is opaque to the loop vectoriser. error_model="numpy"
# removes the division-by-zero branches (an exit from the loop) of the inlined code. The scalar
# evaluations (start of a trajectory) use it too, so that everything this module computes is
# compiled here: numba's cache of the kernel's own dispatcher does not notice a change in a
# function the kernel inlines (e.g. sincos), this module's file name does (_kernel_dependencies).
_rhs_inline = njit(inline="always", nogil=True, error_model="numpy")(rhs.py_func)


@intrinsic
def _lane(typingctx, buf, lane, n):
    """1-D view of lane ``lane`` of the lane-interleaved buffer ``buf`` (``n`` elements).

    The stride is the compile-time constant ``LANES * 8`` bytes, so that LLVM's dependence
    analysis sees all accesses of one buffer as one range (runtime-stride views defeat it). The
    view carries no meminfo: it lives only for one kernel call inside the owning function.
    """
    if not (isinstance(buf, types.Array) and buf.ndim == 1 and buf.layout == "C"):
        return None
    view = types.Array(buf.dtype, 1, "A")

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, args[0])
        lane_v = context.cast(builder, args[1], sig.args[1], types.intp)
        n_v = context.cast(builder, args[2], sig.args[2], types.intp)
        out = context.make_array(view)(context, builder)
        itemsize = context.get_abi_sizeof(context.get_data_type(view.dtype))
        context.populate_array(
            out,
            data=builder.gep(ary.data, [lane_v]),
            shape=[n_v],
            strides=[context.get_constant(types.intp, LANES * itemsize)],
            itemsize=context.get_constant(types.intp, itemsize),
            meminfo=None,
            parent=None,
        )
        return out._getvalue()

    return view(buf, lane, n), codegen


@intrinsic
def _fetch_add(typingctx, counter, delta):
    """Atomically add ``delta`` to ``counter[0]`` (int64 array) and return the old value."""
    if not (isinstance(counter, types.Array) and counter.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, args[0])
        d = context.cast(builder, args[1], sig.args[1], types.int64)
        return builder.atomic_rmw("add", ary.data, d, "monotonic")

    return types.int64(counter, delta), codegen


@njit(cache=True, nogil=True, error_model="numpy")
def _rhs_lanes_shared(tt, Y, p, K, n, nl):
    """``K[:, l] = rhs(tt[l], Y[:, l], p)`` for every lane, one parameter vector for all.

    ``nl`` (= LANES) is a run-time value on purpose: with a constant trip count this small, LLVM
    treats the loop as "optimise for size" and will not emit the alias checks it needs to
    vectorise.
    """
    for lane in range(nl):
        _rhs_inline(tt[lane], _lane(Y, lane, n), p, _lane(K, lane, n))


@njit(cache=True, nogil=True, error_model="numpy")
def _rhs_lanes(tt, Y, PL, K, n, n_par, nl):
    """As :func:`_rhs_lanes_shared` with one parameter vector per lane (lane-interleaved)."""
    for lane in range(nl):
        _rhs_inline(tt[lane], _lane(Y, lane, n), _lane(PL, lane, n_par), _lane(K, lane, n))


@njit(cache=True, nogil=True)
def _eval(shared, tt, Y, p, PL, K, n, n_par, nl):
    if shared:
        _rhs_lanes_shared(tt, Y, p, K, n, nl)
    else:
        _rhs_lanes(tt, Y, PL, K, n, n_par, nl)


@njit(cache=True, nogil=True)
def _initial_step(p, t0, y0, f0, t1, rtol, atol, n_cont, ytmp, f1):
    """Hairer's initial step; arithmetic identical to ``_core._initial_step`` (kept in sync by
    ``tests/unit/test_lanes.py``, which compares both drivers bit for bit)."""
    n = y0.shape[0]
    interval = abs(t1 - t0)
    d0 = 0.0
    d1 = 0.0
    for i in range(n_cont):
        sc = atol[i] + abs(y0[i]) * rtol
        d0 += (y0[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = math.sqrt(d0 / n_cont)
    d1 = math.sqrt(d1 / n_cont)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(n):
        ytmp[i] = y0[i] + h0 * f0[i]
    _rhs_inline(t0 + h0, ytmp, p, f1)
    d2 = 0.0
    for i in range(n_cont):
        sc = atol[i] + abs(y0[i]) * rtol
        d2 += ((f1[i] - f0[i]) / sc) ** 2
    d2 = math.sqrt(d2 / n_cont) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    return min(100.0 * h0, h1, interval)


# lane slots: ids[l] >= 0 is the trajectory in lane l; these mark empty and exhausted lanes
_EMPTY = -1
_DONE = -2


@njit(cache=True, nogil=True)
def _worker(
    counter, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, nl,
    YS, YF, STATUS, TEND, STATS,
):  # fmt: skip
    """Integrate trajectories taken from ``counter`` until none is left (one thread)."""
    N = STATUS.shape[0]
    n = YF.shape[1]
    n_par = P.shape[1]
    n_save = TS.shape[1]
    shared = P.shape[0] == 1
    L = LANES
    nL = n * L
    Y = np.zeros(nL)
    YN = np.zeros(nL)
    T = np.zeros(nL)
    HB = np.zeros(nL)  # step size of each lane, broadcast over the state
    K1 = np.zeros(nL)
    K2 = np.zeros(nL)
    K3 = np.zeros(nL)
    K4 = np.zeros(nL)
    K5 = np.zeros(nL)
    K6 = np.zeros(nL)
    K7 = np.zeros(nL)
    PL = np.zeros(n_par * L) if not shared else np.zeros(0)
    for k in range(PL.shape[0]):
        PL[k] = P[0, k // L]  # idle lanes keep evaluating the kernel on sane parameters
    p0 = P[0]
    tt = np.zeros(L)
    tl = np.zeros(L)
    t1l = np.zeros(L)
    tnl = np.zeros(L)
    hl = np.zeros(L)
    habs = np.zeros(L)
    min_step = np.zeros(L)
    take = np.zeros(nL)  # accepted lanes (first L entries), then broadcast over the state
    Q = np.zeros(nL)
    AB = np.zeros(nL)  # atol broadcast over the lanes
    for k in range(nL):
        AB[k] = atol[k // L]
    ids = np.full(L, _EMPTY, dtype=np.int64)
    rejected = np.zeros(L, dtype=np.bool_)
    last_nonfinite = np.zeros(L, dtype=np.bool_)
    new_step = np.zeros(L, dtype=np.bool_)
    nfev = np.zeros(L, dtype=np.int64)
    naccept = np.zeros(L, dtype=np.int64)
    nreject = np.zeros(L, dtype=np.int64)
    i_save = np.zeros(L, dtype=np.int64)
    ybuf = np.empty(n)
    fbuf = np.empty(n)
    f1 = np.empty(n)
    ytmp = np.empty(n)

    while True:
        # ---- scalar prologue: finish, refill and start the step of every lane ----------------
        n_live = 0
        for lane in range(L):
            while True:
                j = ids[lane]
                if j == _DONE:
                    break
                if j == _EMPTY:
                    j = _fetch_add(counter, 1)
                    if j >= N:
                        ids[lane] = _DONE
                        hl[lane] = 0.0
                        tnl[lane] = tl[lane]
                        break
                    # start trajectory j in this lane (as integrate_one does before its loop)
                    iy = j if Y0.shape[0] > 1 else 0
                    ip = j if P.shape[0] > 1 else 0
                    it1 = j if T1.shape[0] > 1 else 0
                    its = j if TS.shape[0] > 1 else 0
                    for i in range(n):
                        ybuf[i] = Y0[iy, i]
                        Y[i * L + lane] = ybuf[i]
                    if not shared:
                        for k in range(n_par):
                            PL[k * L + lane] = P[ip, k]
                    t1 = T1[it1]
                    tl[lane] = t0
                    t1l[lane] = t1
                    ids[lane] = j
                    s = 0
                    while s < n_save and TS[its, s] <= t0:
                        for i in range(n):
                            YS[j, s, i] = ybuf[i]
                        s += 1
                    i_save[lane] = s
                    naccept[lane] = 0
                    nreject[lane] = 0
                    _rhs_inline(t0, ybuf, P[ip], fbuf)
                    nfev[lane] = 1
                    for i in range(n):
                        K1[i * L + lane] = fbuf[i]
                    ok = _all_finite(ybuf) and _all_finite(fbuf)
                    if first_step > 0.0:
                        h = min(first_step, t1 - t0)
                    elif ok:
                        h = _initial_step(P[ip], t0, ybuf, fbuf, t1, rtol, atol, n_cont, ytmp, f1)
                        nfev[lane] += 1
                    else:
                        h = 0.0
                    habs[lane] = min(h, max_step)
                    if not ok:
                        _finish(lane, NONFINITE, ids, Y, tl, nfev, naccept, nreject, YF, STATUS, TEND, STATS)
                        continue
                    new_step[lane] = True
                if new_step[lane]:
                    t = tl[lane]
                    if not t < t1l[lane]:
                        _finish(lane, SUCCESS, ids, Y, tl, nfev, naccept, nreject, YF, STATUS, TEND, STATS)
                        continue
                    ms = 10.0 * abs(np.nextafter(t, math.inf) - t)
                    if habs[lane] > max_step:
                        habs[lane] = max_step
                    elif habs[lane] < ms:
                        habs[lane] = ms
                    min_step[lane] = ms
                    rejected[lane] = False
                    last_nonfinite[lane] = False
                    new_step[lane] = False
                if habs[lane] < min_step[lane]:
                    st = NONFINITE if last_nonfinite[lane] else STEP_UNDERFLOW
                    _finish(lane, st, ids, Y, tl, nfev, naccept, nreject, YF, STATUS, TEND, STATS)
                    continue
                if naccept[lane] + nreject[lane] >= max_steps:
                    _finish(lane, MAX_STEPS, ids, Y, tl, nfev, naccept, nreject, YF, STATUS, TEND, STATS)
                    continue
                tn = tl[lane] + habs[lane]
                if tn > t1l[lane]:
                    tn = t1l[lane]
                h = tn - tl[lane]
                habs[lane] = abs(h)
                tnl[lane] = tn
                hl[lane] = h
                n_live += 1
                break
        if n_live == 0:
            break

        # ---- one Dormand-Prince attempt in every lane (vectorised over lanes) --------------
        # broadcast the step sizes over the state: HB[i L + l] = h[l] (a recurrence at distance L
        # is a plain vector copy for LLVM; a loop over (i, l) would not vectorise)
        for lane in range(L):
            HB[lane] = hl[lane]
        for k in range(L, nL):
            HB[k] = HB[k - L]
        for k in range(nL):
            T[k] = Y[k] + HB[k] * (A21 * K1[k])
        for lane in range(L):
            tt[lane] = tl[lane] + C2 * hl[lane]
        _eval(shared, tt, T, p0, PL, K2, n, n_par, nl)
        for k in range(nL):
            T[k] = Y[k] + HB[k] * (A31 * K1[k] + A32 * K2[k])
        for lane in range(L):
            tt[lane] = tl[lane] + C3 * hl[lane]
        _eval(shared, tt, T, p0, PL, K3, n, n_par, nl)
        for k in range(nL):
            T[k] = Y[k] + HB[k] * (A41 * K1[k] + A42 * K2[k] + A43 * K3[k])
        for lane in range(L):
            tt[lane] = tl[lane] + C4 * hl[lane]
        _eval(shared, tt, T, p0, PL, K4, n, n_par, nl)
        for k in range(nL):
            T[k] = Y[k] + HB[k] * (A51 * K1[k] + A52 * K2[k] + A53 * K3[k] + A54 * K4[k])
        for lane in range(L):
            tt[lane] = tl[lane] + C5 * hl[lane]
        _eval(shared, tt, T, p0, PL, K5, n, n_par, nl)
        for k in range(nL):
            T[k] = Y[k] + HB[k] * (
                A61 * K1[k] + A62 * K2[k] + A63 * K3[k] + A64 * K4[k] + A65 * K5[k]
            )
        _eval(shared, tnl, T, p0, PL, K6, n, n_par, nl)
        for k in range(nL):
            YN[k] = Y[k] + HB[k] * (B1 * K1[k] + B3 * K3[k] + B4 * K4[k] + B5 * K5[k] + B6 * K6[k])
        _eval(shared, tnl, YN, p0, PL, K7, n, n_par, nl)
        # error norm (RMS over the continuous states, as _core._rms_scaled), summed over the
        # states in the same order; K7 * 0.0 (NaN unless K7 is finite) folds in _core's
        # "not _all_finite(k7)" test: adding +-0.0 leaves a finite sum unchanged.
        for k in range(n_cont * L):
            e = HB[k] * (
                E1 * K1[k] + E3 * K3[k] + E4 * K4[k] + E5 * K5[k] + E6 * K6[k] + E7 * K7[k]
            )
            sc = AB[k] + rtol * max(abs(Y[k]), abs(YN[k]))
            q = e / sc
            Q[k] = q * q + K7[k] * 0.0
        for k in range(n_cont * L, nL):
            Q[k] = K7[k] * 0.0
        # running sums over the states, lane by lane (a recurrence at distance L: vectorises);
        # the last row is the sum in the order of _core._rms_scaled
        for k in range(L, nL):
            Q[k] += Q[k - L]

        # ---- scalar epilogue: accept or reject in every lane --------------------------------
        for lane in range(L):
            take[lane] = 0.0
            j = ids[lane]
            if j < 0:
                continue
            nfev[lane] += 6
            err_norm = math.sqrt(Q[nL - L + lane] / n_cont)
            if not math.isfinite(err_norm):
                last_nonfinite[lane] = True
                habs[lane] *= MIN_FACTOR
                rejected[lane] = True
                nreject[lane] += 1
                continue
            if err_norm >= 1.0:
                habs[lane] *= max(MIN_FACTOR, SAFETY * err_norm**ERROR_EXPONENT)
                rejected[lane] = True
                nreject[lane] += 1
                continue
            if err_norm == 0.0:
                factor = MAX_FACTOR
            else:
                factor = min(MAX_FACTOR, SAFETY * err_norm**ERROR_EXPONENT)
            if rejected[lane]:
                factor = min(1.0, factor)
            habs[lane] *= factor
            naccept[lane] += 1
            # accepted: save points in (t, tn] from the dense output, then advance
            t = tl[lane]
            tn = tnl[lane]
            h = hl[lane]
            if n_save > 0:
                its = j if TS.shape[0] > 1 else 0
                s = i_save[lane]
                while s < n_save and TS[its, s] <= tn:
                    if TS[its, s] == tn:
                        for i in range(n):
                            YS[j, s, i] = YN[i * L + lane]
                    else:
                        _dense(
                            _lane(Y, lane, n), h, _lane(K1, lane, n), _lane(K3, lane, n),
                            _lane(K4, lane, n), _lane(K5, lane, n), _lane(K6, lane, n),
                            _lane(K7, lane, n), (TS[its, s] - t) / h, ybuf,
                        )  # fmt: skip
                        for i in range(n):
                            YS[j, s, i] = ybuf[i]
                    s += 1
                i_save[lane] = s
            tl[lane] = tn
            take[lane] = 1.0
            new_step[lane] = True
        for k in range(L, nL):
            take[k] = take[k - L]
        for k in range(nL):
            a = take[k] != 0.0
            Y[k] = YN[k] if a else Y[k]
            K1[k] = K7[k] if a else K1[k]


@njit(cache=True, nogil=True)
def _finish(lane, status, ids, Y, tl, nfev, naccept, nreject, YF, STATUS, TEND, STATS):
    """Write the outputs of the trajectory in ``lane`` and mark the lane empty."""
    j = ids[lane]
    n = YF.shape[1]
    for i in range(n):
        YF[j, i] = Y[i * LANES + lane]
    STATUS[j] = status
    TEND[j] = tl[lane]
    STATS[j, ST_NFEV] = nfev[lane]
    STATS[j, ST_NACCEPT] = naccept[lane]
    STATS[j, ST_NREJECT] = nreject[lane]
    STATS[j, ST_NEVENTS] = 0
    ids[lane] = _EMPTY


@njit(cache=True, nogil=True, parallel=True)
def integrate_lanes(
    Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, nl,
    YS, YF, STATUS, TEND, STATS, n_threads,
):  # fmt: skip
    """Integrate ``STATUS.shape[0]`` trajectories, ``LANES`` at a time on each of ``n_threads``.

    Inputs whose first dimension is 1 are shared by all trajectories: ``Y0`` (1 or N, n),
    ``P`` (1 or N, n_param), ``T1`` (1 or N,), ``TS`` (1 or N, n_save). ``nl`` must equal
    ``LANES``; ``n_threads`` is the number of worker threads (numba's current number of threads
    at most: pass ``numba.get_num_threads()``, which cannot be called here without making the
    function uncacheable). Each trajectory writes only its own rows of ``YS``, ``YF``, ``STATUS``, ``TEND``
    and ``STATS``, with the same numbers whatever the thread that integrated it.
    """
    N = STATUS.shape[0]
    n_workers = max(1, min(n_threads, (N + LANES - 1) // LANES))
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(n_workers):
        _worker(
            counter, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, nl,
            YS, YF, STATUS, TEND, STATS,
        )  # fmt: skip


@njit(cache=True, nogil=True)
def integrate_lanes_serial(
    Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, nl,
    YS, YF, STATUS, TEND, STATS, n_threads,
):  # fmt: skip
    """Same as :func:`integrate_lanes` on the calling thread (``n_threads`` is ignored)."""
    counter = np.zeros(1, dtype=np.int64)
    _worker(
        counter, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, nl,
        YS, YF, STATUS, TEND, STATS,
    )  # fmt: skip


# ------------------------------------------------------------------------------------------------
# Per-model compiled copies (Python side; unused inside the generated copies themselves)

_LOADED: dict = {}
_ACT_OFF = 3  # rotorlab.integrate._core.ACT_OFF


def lane_driver(kernels, lanes, n_ev, ev_act, serial):
    """Return a function with the signature of the scalar drivers that runs the lane driver.

    Parameters
    ----------
    kernels : Kernels
    lanes : int
        Trajectories per thread stepped together, 2 to 64; best a multiple of the SIMD width in
        doubles (4 with AVX2, 8 with AVX-512). 8 is a good choice on both.
    n_ev : int
    ev_act : int64 array
        Event actions (all must be "off": the lane driver does not locate events).
    serial : bool
        Run on the calling thread.

    Raises
    ------
    ValueError
        If ``lanes`` is out of range or an event is active.
    """
    import numba

    if isinstance(lanes, bool) or not isinstance(lanes, (int, np.integer)) or not 2 <= lanes <= 64:
        raise ValueError(f"lanes must be an integer in [2, 64] or None, got {lanes!r}")
    if n_ev > 0 and np.any(np.asarray(ev_act) != _ACT_OFF):
        raise ValueError(
            "lanes= runs without event location; this model has active events: pass events=[] "
            "to switch them off, or lanes=None to use the scalar driver"
        )
    width = int(lanes)
    parallel, single = lane_drivers_for(kernels, width)

    def run(
        n_ev, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, ev_dir,
        ev_act, YS, YF, STATUS, TEND, EVC, RECT, RECK, STATS,
    ):  # fmt: skip
        drv = single if serial else parallel
        drv(
            Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, width,
            YS, YF, STATUS, TEND, STATS, numba.get_num_threads(),
        )  # fmt: skip

    return run


def _source(width):
    """This module's source with ``LANES`` set to ``width``."""
    import inspect
    import sys
    from pathlib import Path

    lines = Path(inspect.getsourcefile(sys.modules[__name__])).read_text().splitlines()
    marked = [i for i, line in enumerate(lines) if line.rstrip().endswith("# @lanes")]
    if len(marked) != 1:
        raise RuntimeError("rotorlab.integrate._lanes must have exactly one '# @lanes' line")
    lines[marked[0]] = f"LANES = {int(width)}  # @lanes"
    return lines


def lane_drivers_for(kernels, width=LANES):
    """Return ``(parallel, serial)`` lane drivers of ``width`` lanes for the model's ``rhs``.

    Both take the arguments of :func:`integrate_lanes`. The copy of this module with the
    ``# @kernel`` line importing the model's ``rhs`` and ``LANES = width`` is written next to the
    scalar drivers of :mod:`rotorlab.integrate._specialize` (same cache directory and pruning);
    kernels that are not importable module-level functions are compiled without on-disk caching.
    """
    import importlib.util
    import os
    import sys
    import tempfile

    from rotorlab.integrate import _specialize as spec

    name = spec._importable_name(kernels.rhs)
    if name is None:
        return _uncached(kernels, width)
    key = (f"{name[0]}.{name[1]}", width)
    if key in _LOADED:
        return _LOADED[key]
    directory = spec._cache_dir()
    if directory is None:
        return _uncached(kernels, width)
    mod, fn = name
    deps = [mod, __name__, "rotorlab.integrate._core", "rotorlab.integrate._tableau"]
    deps += _kernel_dependencies(mod)
    digest = spec._source_hash(deps)
    stem = f"lanes{width}_{mod.rsplit('.', 1)[-1]}_{fn}_{digest}"
    path = directory / f"{stem}.py"
    if not path.exists():
        spec._prune(directory, stem.rsplit("_", 1)[0])
        lines = _source(width)
        marked = [i for i, line in enumerate(lines) if line.rstrip().endswith("# @kernel")]
        if len(marked) != 1:
            raise RuntimeError("rotorlab.integrate._lanes must have exactly one '# @kernel' line")
        lines[marked[0]] = f"from {mod} import {fn} as rhs  # @kernel"
        header = "# Generated by rotorlab.integrate._lanes from _lanes.py; do not edit.\n"
        fd, tmp = tempfile.mkstemp(dir=directory, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(header + "\n".join(lines) + "\n")
        os.replace(tmp, path)
    mod_name = f"_rotorlab_lanes_{stem}"
    module_spec = importlib.util.spec_from_file_location(mod_name, path)
    module = importlib.util.module_from_spec(module_spec)
    sys.modules[mod_name] = module
    module_spec.loader.exec_module(module)
    _LOADED[key] = (module.integrate_lanes, module.integrate_lanes_serial)
    return _LOADED[key]


def _kernel_dependencies(mod):
    """Modules of the compiled functions a kernel module uses (numba's cache does not see them)."""
    import importlib

    found = []
    for obj in vars(importlib.import_module(mod)).values():
        py_func = getattr(obj, "py_func", None)
        if py_func is not None and py_func.__module__ not in (mod, "__main__"):
            found.append(py_func.__module__)
    return sorted(set(found))


def _uncached(kernels, width):
    """Compile the lane driver with the kernel bound directly, without on-disk caching."""
    key = (id(kernels.rhs), width)
    if key in _LOADED:
        return _LOADED[key][1:]
    source = "\n".join(ln for ln in _source(width) if not ln.rstrip().endswith("# @kernel"))
    namespace = {"rhs": kernels.rhs, "__name__": "_rotorlab_lanes_uncached"}
    exec(compile(source.replace("cache=True", "cache=False"), "<rotorlab lane driver>", "exec"), namespace)  # noqa: S102
    _LOADED[key] = (kernels.rhs, namespace["integrate_lanes"], namespace["integrate_lanes_serial"])
    return _LOADED[key][1:]
