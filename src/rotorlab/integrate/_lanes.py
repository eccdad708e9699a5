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
queue. This is the scheme of the benchmark's C reference ``dp5_simd.c`` (see ``bench/README.md``).

Events, reset maps and modes: after the vectorised accept/reject of a step, each lane whose step
was accepted has its events located by the scalar driver's own functions
(``_core._events_in_step``: the event functions at the step's end, a sign change located on the
dense output; ``_core._resolve_cut``: save up to the event, then stop or apply the reset map),
bound to this copy's kernels. A lane without an event costs one event evaluation and a few
comparisons; a lane with one does its root finding and reset while the other lanes wait for at
most that step, and then continues (or ends and is refilled) like any other. The same code on
the same numbers gives the same event times, records and states as the scalar driver.
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
   only, so a ``for i in range(int(p[0]))`` becomes the vectorised loop instead of the lanes).
   Sizes derived from ``y.shape[0]`` are constants here (``N_STATE`` of the generated copy):
   ``n = (y.shape[0] - 4) // 2`` balls gives loops that unroll, as in ``jeffcott_balls``;
3. has no branch with an expensive or side-effecting arm (both arms of an ``if`` are executed
   for all lanes, then selected), no ``raise``, and calls only functions compiled with
   ``inline="always"`` (a call of another compiled function is opaque to LLVM).

A kernel that breaks these rules still gives identical results on the lane path, only no faster
than the scalar path. A model declares a kernel that follows them with ``Kernels(vectorises=True)``
(``tests/unit/test_vectorise.py`` checks each). ``solve_ensemble`` uses this driver by default for
every ensemble, events or not. :func:`rotorlab.integrate._drivers.is_vectorised` reports whether it vectorised.

Why not a lane kernel ``rhs_lanes`` written by the model? It would be a second hand-written right
side per model to keep in sync with the first; the loop above vectorises the existing one.

This module is the template of per-model copies and holds only compiled code:
:mod:`rotorlab.integrate._codegen` writes a copy in which the import line marked ``# @kernel``
imports the model's ``rhs`` and the ``# @const`` lines set the lane width and the state size, so
numba caches it across processes. The entry points take the argument groups of
:mod:`rotorlab.integrate._driver_args`, as the scalar drivers of :mod:`rotorlab.integrate._core`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange, types
from numba.extending import intrinsic

from rotorlab._kernels._vmath import inv_fifth_root
from rotorlab.models._base import no_events as events  # @kernel events
from rotorlab.models._base import no_reset as reset  # @kernel reset
from rotorlab.models._base import no_rhs as rhs  # @kernel rhs
from rotorlab.integrate import _core
from rotorlab.integrate._core import (
    ACT_OFF, MAX_STEPS, NONFINITE, ST_NACCEPT, ST_NEVENTS, ST_NFEV, ST_NREJECT, STEP_UNDERFLOW,
    SUCCESS, _all_finite, _crosses, _dense, _own, with_kernels,
)  # fmt: skip
from rotorlab.integrate._tableau import (
    A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64, A65,
    B1, B3, B4, B5, B6,
    C2, C3, C4, C5,
    E1, E3, E4, E5, E6, E7,
    MAX_FACTOR, MIN_FACTOR, SAFETY,
)  # fmt: skip

LANES = 8  # @const LANES
"""Trajectories per worker stepped together (set per generated copy, see :mod:`rotorlab.integrate._drivers`)."""
N_STATE = 1  # @const N_STATE
"""Length of the model's state vector (set per generated copy)."""
NL = N_STATE * LANES

# The workspace of a worker is one float64 array, so that every vector loop below addresses a
# single base pointer at compile-time-constant offsets: LLVM then proves the loops free of
# aliasing without run-time checks (with separate arrays it needs one check per pair, gives up
# beyond eight, or refuses them for short loops). Rows of NL doubles, lane-interleaved
# (element i of lane l at row + i * LANES + l):
_Y = 0 * NL  # state at t
_YN = 1 * NL  # 5th-order solution at t + h
_T = 2 * NL  # stage argument
_H = 3 * NL  # step size of each lane, broadcast over the state
_K1 = 4 * NL
_K2 = 5 * NL
_K3 = 6 * NL
_K4 = 7 * NL
_K5 = 8 * NL
_K6 = 9 * NL
_K7 = 10 * NL
_AT = 11 * NL  # atol, broadcast over the lanes
_Q = 12 * NL  # squared scaled errors, then running sums over the state
_M = 13 * NL  # accept mask, broadcast over the state
# ... then rows of LANES doubles, one number per lane (counters are exact as floats)
_R = 14 * NL
_t = _R + 0 * LANES  # time
_t1 = _R + 1 * LANES  # end time
_tn = _R + 2 * LANES  # end of the step being attempted
_h = _R + 3 * LANES  # its signed length
_habs = _R + 4 * LANES  # |step| proposed by the controller
_mins = _R + 5 * LANES  # smallest step at t
_ms = _R + 6 * LANES  # 10 ulp(t), scratch
_tt = _R + 7 * LANES  # stage time
_en = _R + 8 * LANES  # error norm
_pw = _R + 9 * LANES  # error norm ** ERROR_EXPONENT
_rej = _R + 10 * LANES  # 1: an attempt of this step was rejected
_lnf = _R + 11 * LANES  # 1: the last rejection was for a non-finite error
_new = _R + 12 * LANES  # 1: the lane starts a new step
_live = _R + 13 * LANES  # 1: the lane holds a trajectory
_nfev = _R + 14 * LANES
_nacc = _R + 15 * LANES
_nrej = _R + 16 * LANES
_code = _R + 17 * LANES  # prologue verdict: 0 step, 1 ended, 2 step too small, 3 max steps
_W_SIZE = _R + 18 * LANES
_P = _W_SIZE  # then the lane-interleaved parameters (_P), as many rows as p has

_NEG_ZERO_BITS = -(2**63)  # -0.0 seen as int64

# lane slots: ids[l] >= 0 is the trajectory in lane l; these mark empty and exhausted lanes
_EMPTY = -1
_DONE = -2

# The model's kernel inlined at numba-IR level: LLVM does not inline a separately compiled
# dispatcher of this size, and a call is opaque to the loop vectoriser. error_model="numpy"
# removes the division-by-zero branches (an exit from the loop) of the inlined code. Everything
# this module computes is compiled here (the scalar evaluations use _core's own copy, _rhs_once
# below, compiled without a cache of its own): numba's cache of the kernel's own dispatcher does not notice a change in a
# function the kernel inlines (e.g. sincos), the generated copy's file name does (rotorlab.integrate._codegen).
_rhs_inline = njit(inline="always", nogil=True, error_model="numpy")(rhs.py_func)

# Events and resets: the scalar driver's own functions (rotorlab.integrate._core), bound to this
# copy's kernels, called for one lane at a time after its accepted step. Same source, same
# compiled kernels (_own), so the same event times, states and records bit for bit.
_EV = dict(vars(_core))
_EV.update(rhs=_own(rhs), events=_own(events), reset=_own(reset))
for _name in ("_g_at", "_locate", "_events_in_step", "_resolve_cut", "_initial_step"):
    _EV[_name] = with_kernels(getattr(_core, _name), _EV)
_events_at = _EV["events"]
# The scalar evaluations (a trajectory's first slope, the initial step's trial slope) call the
# scalar driver's own compiled kernel (one compiled copy, the same bits as _core's): inlining
# them would make numba type and LLVM optimise the kernel twice more per driver for two calls
# per trajectory.
_rhs_once = _EV["rhs"]
_events_inline = njit(inline="always", nogil=True, error_model="numpy")(events.py_func)
_events_in_step = _EV["_events_in_step"]
_resolve_cut = _EV["_resolve_cut"]
# Hairer's initial step of a trajectory starting in a lane: the scalar driver's own function
_initial_step = _EV["_initial_step"]
del _name


@intrinsic
def _lane(typingctx, buf, start, n):
    """1-D view of ``n`` elements ``buf[start + i * LANES]`` (a lane of a lane-interleaved row).

    The stride is the compile-time constant ``LANES * 8`` bytes, so that LLVM's dependence
    analysis sees all accesses of one row as one range (runtime-stride views defeat it). The
    view carries no meminfo: it lives only for one kernel call inside the owning function.
    """
    if not (isinstance(buf, types.Array) and buf.ndim == 1 and buf.layout == "C"):
        return None
    view = types.Array(buf.dtype, 1, "A")

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, args[0])
        start_v = context.cast(builder, args[1], sig.args[1], types.intp)
        n_v = context.cast(builder, args[2], sig.args[2], types.intp)
        out = context.make_array(view)(context, builder)
        itemsize = context.get_abi_sizeof(context.get_data_type(view.dtype))
        context.populate_array(
            out,
            data=builder.gep(ary.data, [start_v]),
            shape=[n_v],
            strides=[context.get_constant(types.intp, LANES * itemsize)],
            itemsize=context.get_constant(types.intp, itemsize),
            meminfo=None,
            parent=None,
        )
        return out._getvalue()

    return view(buf, start, n), codegen


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


INLINE_RHS = 0  # @const INLINE_RHS
"""1: the loop over lanes that calls the kernel is inlined into the worker (set per generated copy
from ``Kernels.inline_lanes``, see :mod:`rotorlab.integrate._drivers`)."""


# Called from one site of the worker's stage loop, with constant rows: compiled once per driver.
# Inlined into the worker (numba-IR level) where INLINE_RHS says so: the kernel's constants
# (broadcast coefficients, sincos's polynomial) then stay in registers across the stages instead
# of being reloaded by six calls a step (benchmark kernel, one thread: 0.68x the CPU time, same
# bits). Large kernels (the machine's generated ones, hundreds of parameter loads) no longer
# vectorise when inlined, so they keep the call (Kernels.inline_lanes = False).
@njit(cache=True, nogil=True, error_model="numpy", inline="always" if INLINE_RHS else "never")
def _rhs_lanes(W, nl):
    """``Q[:, l] = rhs(tt[l], T[:, l], p[:, l])`` for every lane, rows of the workspace ``W``.

    All rows, the lane-interleaved parameters (``_P`` on) included, are constant offsets into
    ``W``: LLVM proves every access apart without run-time checks (a separate parameter array
    made the 28-state Pico 21 kernel need more than LLVM allows: not vectorised). Parameters
    are interleaved even when shared: faster than LLVM hoisting them (register pressure). ``nl``
    is run-time on purpose: a constant trip count this small is "optimise for size" (no alias
    checks, no vectorisation).
    """
    n_par = (W.shape[0] - _P) // LANES
    for lane in range(nl):
        _rhs_inline(
            W[_tt + lane], _lane(W, _T + lane, N_STATE), _lane(W, _P + lane, n_par),
            _lane(W, _Q + lane, N_STATE),
        )  # fmt: skip


@njit(cache=True, nogil=True, error_model="numpy", inline="always" if INLINE_RHS else "never")
def _events_lanes(W, row_t, row_y, G, nl, ne):
    """``G[:, l] = events(t[l], Y[:, l], p[:, l])`` for every lane (``G`` lane-interleaved, ``ne``
    rows): the event functions at the end of every lane's step in one loop, which vectorises
    when the model's ``events`` is lane-friendly (as :func:`_rhs_lanes`)."""
    n_par = (W.shape[0] - _P) // LANES
    for lane in range(nl):
        _events_inline(
            W[row_t + lane], _lane(W, row_y + lane, N_STATE), _lane(W, _P + lane, n_par), _lane(G, lane, ne),
        )  # fmt: skip


@njit(cache=True, nogil=True, error_model="numpy")
def _probe(W, nl):
    """One stage's kernel call as the worker makes it (constant rows): see :func:`rotorlab.integrate._drivers.is_vectorised`."""
    _rhs_lanes(W, nl)


@njit(cache=True, nogil=True, inline="always", error_model="numpy")
def _prologue(W, lane, max_step, max_steps):
    """Start of a step attempt in one lane (as integrate_one's loops); sets the verdict ``_code``.

    Branch-free, so that the loop over lanes that calls it vectorises; the scalar pass of the
    worker calls it too for a lane it has just (re)filled.
    """
    # every load comes first: a load inside one arm of an ``if`` keeps LLVM from turning the
    # ``if`` into a select, and then from vectorising the loop
    live = W[_live + lane] != 0.0
    new_flag = W[_new + lane]
    t = W[_t + lane]
    t1 = W[_t1 + lane]
    habs = W[_habs + lane]
    ms = W[_ms + lane]
    mins = W[_mins + lane]
    rej = W[_rej + lane]
    lnf = W[_lnf + lane]
    attempts = W[_nacc + lane] + W[_nrej + lane]
    new = live and new_flag != 0.0
    ended = new and not t < t1
    clamped = max_step if habs > max_step else (ms if habs < ms else habs)
    habs = clamped if new else habs
    mins = ms if new else mins
    W[_mins + lane] = mins
    W[_rej + lane] = 0.0 if new else rej
    W[_lnf + lane] = 0.0 if new else lnf
    W[_new + lane] = 0.0 if live else new_flag
    small = habs < mins
    maxed = attempts >= max_steps
    W[_code + lane] = 1.0 if ended else (2.0 if small else (3.0 if maxed else 0.0))
    tn = t + habs
    tn = t1 if tn > t1 else tn
    h = tn - t
    W[_tn + lane] = tn
    W[_h + lane] = h if live else 0.0
    W[_habs + lane] = abs(h) if live else habs


@njit(cache=True, nogil=True, inline="always")  # on every step: a call would cost registers
def _min_steps(W, Wi, nl):
    """``W[_ms + l] = 10 * abs(np.nextafter(t, inf) - t)`` for every lane, vectorised.

    ``nextafter(t, +inf)`` of a finite ``t`` has the bits of ``t`` plus one (``t > 0``), minus
    one (``t < 0``), or 1 (``t = +-0``: the smallest subnormal). ``Wi`` is ``W`` seen as int64;
    each loop touches only one of the two views (LLVM's alias check between them would fail).
    """
    for lane in range(nl):
        bits = Wi[_t + lane]  # > 0 for t > 0; < 0 for t < 0 and for -0.0 (the minimum)
        Wi[_ms + lane] = bits + 1 if bits > 0 else (bits - 1 if bits > _NEG_ZERO_BITS else 1)
    for lane in range(nl):
        W[_ms + lane] = 10.0 * abs(W[_ms + lane] - W[_t + lane])


@njit(cache=True, nogil=True, error_model="numpy")  # no ZeroDivisionError branch in the loops
def _worker(counter, inputs, settings, event_table, outputs):
    """Integrate trajectories taken from ``counter`` until none is left (one thread)."""
    Y0, P, T1, TS, atol = inputs
    t0, rtol, n_cont, first_step, max_step, max_steps = settings
    n_ev, ev_dir, ev_act = event_table
    YS, YF, STATUS, TEND, EVC, RECT, RECK, STATS = outputs
    # LANES, but a run-time value: with a constant trip count this small, LLVM treats the loops
    # over lanes as "optimise for size" and will not emit the alias checks it needs to vectorise
    nl = LANES * (atol.shape[0] // N_STATE)
    N = STATUS.shape[0]
    n = N_STATE
    L = LANES
    n_par = P.shape[1]
    n_save = TS.shape[1]
    shared = P.shape[0] == 1
    fmax_steps = float(max_steps)
    W = np.zeros(_P + n_par * L)
    Wi = W.view(np.int64)  # the same memory, for the bits of t in _min_steps
    for k in range(NL):
        W[_AT + k] = atol[k // L]
    for k in range(n_par * L):  # lane-interleaved parameters (idle lanes keep P[0])
        W[_P + k] = P[0, k // L]
    ids = np.full(L, _EMPTY, dtype=np.int64)
    i_save = np.zeros(L, dtype=np.int64)
    ybuf = np.empty(n)
    fbuf = np.empty(n)
    f1 = np.empty(n)
    ytmp = np.empty(n)
    # events: each lane's event functions at its t, and its bookkeeping (as integrate_one's)
    has_ev = False
    for k in range(n_ev):
        has_ev = has_ev or ev_act[k] != ACT_OFF
    ne = max(n_ev, 1)
    g_old = np.zeros(L * ne)
    g_end = np.zeros(L * ne)  # the event functions at the end of each lane's step, lane-interleaved
    g_new = np.empty(ne)
    gbuf = np.empty(ne)
    s_ev = np.empty(ne)
    n_rec = np.zeros(L, dtype=np.int64)
    n_events = np.zeros(L, dtype=np.int64)
    t_last_reset = np.full(L, -math.inf)
    n_stalled = np.zeros(L, dtype=np.int64)

    while True:
        # ---- start of the step attempt in every lane: vectorised, then the rare cases --------
        _min_steps(W, Wi, nl)
        for lane in range(nl):
            _prologue(W, lane, max_step, fmax_steps)
        n_live = 0
        for lane in range(L):
            while ids[lane] != _DONE and (ids[lane] == _EMPTY or W[_code + lane] != 0.0):
                j = ids[lane]
                if j >= 0:  # the trajectory in this lane ends here
                    code = W[_code + lane]
                    if code == 1.0:
                        st = SUCCESS
                    elif code == 2.0:
                        st = NONFINITE if W[_lnf + lane] != 0.0 else STEP_UNDERFLOW
                    else:
                        st = MAX_STEPS
                    _finish(W, lane, j, st, n_events[lane], YF, STATUS, TEND, STATS)
                    ids[lane] = _EMPTY
                    W[_live + lane] = 0.0
                j = _fetch_add(counter, 1)
                if j >= N:
                    ids[lane] = _DONE
                    W[_h + lane] = 0.0
                    W[_code + lane] = 0.0
                    break
                # start trajectory j in this lane (as integrate_one does before its loop)
                iy = j if Y0.shape[0] > 1 else 0
                ip = j if P.shape[0] > 1 else 0
                it1 = j if T1.shape[0] > 1 else 0
                its = j if TS.shape[0] > 1 else 0
                for i in range(n):
                    ybuf[i] = Y0[iy, i]
                    W[_Y + i * L + lane] = ybuf[i]
                if not shared:
                    for k in range(n_par):
                        W[_P + k * L + lane] = P[ip, k]
                t1 = T1[it1]
                s = 0
                while s < n_save and TS[its, s] <= t0:
                    for i in range(n):
                        YS[j, s, i] = ybuf[i]
                    s += 1
                i_save[lane] = s
                _rhs_once(t0, ybuf, P[ip], fbuf)
                nfev = 1.0
                if has_ev:
                    _events_at(t0, ybuf, P[ip], g_old[lane * ne : (lane + 1) * ne])
                    for k in range(n_ev):
                        EVC[j, k] = 0
                n_rec[lane] = 0
                n_events[lane] = 0
                t_last_reset[lane] = -math.inf
                n_stalled[lane] = 0
                for i in range(n):
                    W[_K1 + i * L + lane] = fbuf[i]
                ok = _all_finite(ybuf) and _all_finite(fbuf)
                if first_step > 0.0:
                    h = min(first_step, t1 - t0)
                elif ok:
                    h = _initial_step(P[ip], t0, ybuf, fbuf, t1, rtol, atol, n_cont, ytmp, f1)
                    nfev += 1.0
                else:
                    h = 0.0
                W[_t + lane] = t0
                W[_t1 + lane] = t1
                W[_habs + lane] = min(h, max_step)
                W[_nfev + lane] = nfev
                W[_nacc + lane] = 0.0
                W[_nrej + lane] = 0.0
                ids[lane] = j
                if not ok:
                    _finish(W, lane, j, NONFINITE, 0, YF, STATUS, TEND, STATS)
                    ids[lane] = _EMPTY
                    continue
                W[_live + lane] = 1.0
                W[_new + lane] = 1.0
                _min_steps(W, Wi, nl)
                _prologue(W, lane, max_step, fmax_steps)
            if ids[lane] >= 0:
                n_live += 1
        if n_live == 0:
            break

        # ---- one Dormand-Prince attempt in every lane (vectorised over lanes) --------------
        # broadcast the step sizes over the state (a recurrence at distance L is a vector copy)
        for lane in range(nl):
            W[_H + lane] = W[_h + lane]
        for k in range(L, n * nl):
            W[_H + k] = W[_H + k - L]
        # The six stages in one loop with a single call site of the kernel: inlined once, so numba
        # types and LLVM optimises the kernel once per driver, not once per stage (six literal
        # row offsets made six copies: ~6x the compile time of a lane driver). Each stage's
        # argument is the same expression as before (same bits); the kernel reads and writes
        # fixed rows (_tt, _T -> _Q), copied from and to the stage's own rows; the stage index
        # is uniform over the lanes, so the branches cost nothing per lane.
        for s in range(6):
            if s == 0:
                for k in range(n * nl):
                    W[_T + k] = W[_Y + k] + W[_H + k] * (A21 * W[_K1 + k])
                for lane in range(nl):
                    W[_tt + lane] = W[_t + lane] + C2 * W[_h + lane]
            elif s == 1:
                for k in range(n * nl):
                    W[_T + k] = W[_Y + k] + W[_H + k] * (A31 * W[_K1 + k] + A32 * W[_K2 + k])
                for lane in range(nl):
                    W[_tt + lane] = W[_t + lane] + C3 * W[_h + lane]
            elif s == 2:
                for k in range(n * nl):
                    W[_T + k] = W[_Y + k] + W[_H + k] * (
                        A41 * W[_K1 + k] + A42 * W[_K2 + k] + A43 * W[_K3 + k]
                    )
                for lane in range(nl):
                    W[_tt + lane] = W[_t + lane] + C4 * W[_h + lane]
            elif s == 3:
                for k in range(n * nl):
                    W[_T + k] = W[_Y + k] + W[_H + k] * (
                        A51 * W[_K1 + k] + A52 * W[_K2 + k] + A53 * W[_K3 + k] + A54 * W[_K4 + k]
                    )
                for lane in range(nl):
                    W[_tt + lane] = W[_t + lane] + C5 * W[_h + lane]
            elif s == 4:
                for k in range(n * nl):
                    W[_T + k] = W[_Y + k] + W[_H + k] * (
                        A61 * W[_K1 + k] + A62 * W[_K2 + k] + A63 * W[_K3 + k] + A64 * W[_K4 + k]
                        + A65 * W[_K5 + k]
                    )  # fmt: skip
            else:
                for k in range(n * nl):
                    W[_YN + k] = W[_Y + k] + W[_H + k] * (
                        B1 * W[_K1 + k] + B3 * W[_K3 + k] + B4 * W[_K4 + k] + B5 * W[_K5 + k]
                        + B6 * W[_K6 + k]
                    )  # fmt: skip
            if s >= 4:  # the last two stages at t + h (a copy: the same bits)
                for lane in range(nl):
                    W[_tt + lane] = W[_tn + lane]
            if s == 5:  # the 5th-order solution is the last stage's argument
                for k in range(n * nl):
                    W[_T + k] = W[_YN + k]
            # constant rows (LLVM proves the lanes' loads and stores apart and vectorises the
            # kernel without run-time alias checks); _Q is free until the error norm
            _rhs_lanes(W, nl)
            ks = _K2 + s * NL
            for k in range(n * nl):
                W[ks + k] = W[_Q + k]

        # ---- error norm (RMS over the continuous states, as _core._rms_scaled) --------------
        # Summed over the states in the same order, by a recurrence at distance L (the last
        # row holds the sums). K7 * 0.0 (NaN unless K7 is finite) folds in _core's
        # "not _all_finite(k7)": adding +-0.0 leaves a finite sum unchanged.
        for k in range(n_cont * nl):
            e = W[_H + k] * (
                E1 * W[_K1 + k] + E3 * W[_K3 + k] + E4 * W[_K4 + k] + E5 * W[_K5 + k]
                + E6 * W[_K6 + k] + E7 * W[_K7 + k]
            )  # fmt: skip
            ya = abs(W[_Y + k])
            yb = abs(W[_YN + k])
            sc = W[_AT + k] + rtol * (yb if yb > ya else ya)  # max(ya, yb) as numba's max
            q = e / sc
            W[_Q + k] = q * q + W[_K7 + k] * 0.0
        for k in range(n_cont * nl, n * nl):
            W[_Q + k] = W[_K7 + k] * 0.0
        for k in range(L, n * nl):
            W[_Q + k] += W[_Q + k - L]

        # ---- accept or reject in every lane (as integrate_one; vectorised) -----------------
        for lane in range(nl):
            W[_en + lane] = math.sqrt(W[_Q + (n - 1) * L + lane] / n_cont)
        for lane in range(nl):  # err^(-1/5) of all lanes in one vector computation
            en = W[_en + lane]
            W[_pw + lane] = inv_fifth_root(en) if en > 0.0 else 1.0
        for lane in range(nl):
            live = W[_live + lane] != 0.0
            en = W[_en + lane]
            pw = W[_pw + lane]
            habs = W[_habs + lane]
            rej = W[_rej + lane]
            lnf = W[_lnf + lane]
            new_flag = W[_new + lane]
            bad = not math.isfinite(en)
            good = en < 1.0 and not bad
            # min(a, b), max(a, b) spelled out with numba's semantics (its builtins are calls)
            sp = SAFETY * pw
            f_acc = MAX_FACTOR if en == 0.0 else (sp if sp < MAX_FACTOR else MAX_FACTOR)
            f_acc = (f_acc if f_acc < 1.0 else 1.0) if rej != 0.0 else f_acc
            f_rej = sp if sp > MIN_FACTOR else MIN_FACTOR
            factor = MIN_FACTOR if bad else (f_acc if good else f_rej)
            take = live and good
            W[_habs + lane] = habs * factor if live else habs
            W[_lnf + lane] = 1.0 if live and bad else lnf
            W[_rej + lane] = 1.0 if live and not good else rej
            W[_nfev + lane] += 6.0 if live else 0.0
            W[_nacc + lane] += 1.0 if take else 0.0
            W[_nrej + lane] += 1.0 if live and not good else 0.0
            W[_new + lane] = 1.0 if take else new_flag
            W[_M + lane] = 1.0 if take else 0.0
        # ---- events of the accepted steps, one lane at a time (the others wait this step) ---
        if has_ev:
            _events_lanes(W, _tn, _YN, g_end, nl, ne)
            for lane in range(L):
                if W[_M + lane] == 0.0:
                    continue
                # A step in which no active event function changes sign in its direction and
                # none starts at zero has no event: _events_in_step would only hand g_new back
                # (nothing located, counted or recorded). Taking that exit here spares the call
                # (two dozen array arguments) in the steps of every lane without an event.
                quiet = True
                for k in range(n_ev):
                    ga = g_old[lane * ne + k]
                    if ev_act[k] != ACT_OFF and (ga == 0.0 or _crosses(ga, g_end[k * L + lane], ev_dir[k])):
                        quiet = False
                if quiet:
                    for k in range(n_ev):
                        g_old[lane * ne + k] = g_end[k * L + lane]
                    continue
                for k in range(n_ev):
                    g_new[k] = g_end[k * L + lane]
                j = ids[lane]
                p = P[j if not shared else 0]
                y = _lane(W, _Y + lane, n)
                yn = _lane(W, _YN + lane, n)
                k1 = _lane(W, _K1 + lane, n)
                k3 = _lane(W, _K3 + lane, n)
                k4 = _lane(W, _K4 + lane, n)
                k5 = _lane(W, _K5 + lane, n)
                k6 = _lane(W, _K6 + lane, n)
                k7 = _lane(W, _K7 + lane, n)
                g = g_old[lane * ne : (lane + 1) * ne]
                t = W[_t + lane]
                h = W[_h + lane]
                tn = W[_tn + lane]
                s_cut, k_cut, nr, n_found = _events_in_step(
                    n_ev, ev_dir, ev_act, p, t, h, tn, y, yn, k1, k3, k4, k5, k6, k7,
                    g, g_new, gbuf, s_ev, ybuf, EVC[j], RECT[j], RECK[j], n_rec[lane],
                )  # fmt: skip
                n_rec[lane] = nr
                n_events[lane] += n_found
                if k_cut < 0:
                    for k in range(n_ev):
                        g[k] = g_new[k]
                    continue
                # the step ends at the event: reset (y, k1, g written in place) or end here
                its = j if TS.shape[0] > 1 else 0
                st, te, i_s, t_lr, n_st, n_rhs = _resolve_cut(
                    k_cut, s_cut, ev_act[k_cut], p, t, h, tn, y, yn, k1, k3, k4, k5, k6, k7,
                    TS[its], i_save[lane], YS[j], ybuf, ytmp, g, t_last_reset[lane],
                    n_stalled[lane],
                )  # fmt: skip
                i_save[lane] = i_s
                t_last_reset[lane] = t_lr
                n_stalled[lane] = n_st
                W[_nfev + lane] += n_rhs
                W[_t + lane] = te
                W[_M + lane] = 0.0  # the advance below leaves this lane as it is now
                if st != SUCCESS:
                    _finish(W, lane, j, st, n_events[lane], YF, STATUS, TEND, STATS)
                    ids[lane] = _EMPTY
                    W[_live + lane] = 0.0
        if n_save > 0:  # save points in (t, tn] from the dense output of accepted steps
            for lane in range(L):
                if W[_M + lane] != 0.0:
                    # _save's own loop condition, checked here: most steps hold no save point,
                    # and a call on the step loop's common path costs the kernel's constants
                    # their registers (every vector register is caller-saved)
                    its = ids[lane] if TS.shape[0] > 1 else 0
                    if i_save[lane] < n_save and TS[its, i_save[lane]] <= W[_tn + lane]:
                        _save(W, lane, ids[lane], TS, YS, i_save, ybuf)
        for lane in range(nl):
            tn = W[_tn + lane]
            t = W[_t + lane]
            W[_t + lane] = tn if W[_M + lane] != 0.0 else t
        for k in range(L, n * nl):
            W[_M + k] = W[_M + k - L]
        for k in range(n * nl):
            a = W[_M + k] != 0.0
            yn = W[_YN + k]
            y = W[_Y + k]
            k7 = W[_K7 + k]
            k1 = W[_K1 + k]
            W[_Y + k] = yn if a else y
            W[_K1 + k] = k7 if a else k1


@njit(cache=True, nogil=True)
def _save(W, lane, j, TS, YS, i_save, ybuf):
    """Write the save points of trajectory ``j`` in (t, tn] of the accepted step of ``lane``."""
    n = N_STATE
    L = LANES
    its = j if TS.shape[0] > 1 else 0
    t = W[_t + lane]
    tn = W[_tn + lane]
    h = W[_h + lane]
    s = i_save[lane]
    while s < TS.shape[1] and TS[its, s] <= tn:
        if TS[its, s] == tn:
            for i in range(n):
                YS[j, s, i] = W[_YN + i * L + lane]
        else:
            _dense(
                _lane(W, _Y + lane, n), h, _lane(W, _K1 + lane, n), _lane(W, _K3 + lane, n),
                _lane(W, _K4 + lane, n), _lane(W, _K5 + lane, n), _lane(W, _K6 + lane, n),
                _lane(W, _K7 + lane, n), (TS[its, s] - t) / h, ybuf,
            )  # fmt: skip
            for i in range(n):
                YS[j, s, i] = ybuf[i]
        s += 1
    i_save[lane] = s


@njit(cache=True, nogil=True)
def _finish(W, lane, j, status, n_events, YF, STATUS, TEND, STATS):
    """Write the outputs of trajectory ``j``, which ends in ``lane``."""
    for i in range(N_STATE):
        YF[j, i] = W[_Y + i * LANES + lane]
    STATUS[j] = status
    TEND[j] = W[_t + lane]
    STATS[j, ST_NFEV] = int(W[_nfev + lane])
    STATS[j, ST_NACCEPT] = int(W[_nacc + lane])
    STATS[j, ST_NREJECT] = int(W[_nrej + lane])
    STATS[j, ST_NEVENTS] = n_events


@njit(cache=True, nogil=True, parallel=True)
def integrate_lanes(inputs, settings, event_table, outputs, n_threads):
    """Integrate ``outputs.STATUS.shape[0]`` trajectories, ``LANES`` at a time on each of ``n_threads``.

    The arguments are the groups of :mod:`rotorlab.integrate._driver_args`. ``inputs.atol`` must have ``N_STATE`` entries; ``n_threads`` is the number of worker
    threads (numba's current number of threads at most: pass ``numba.get_num_threads()``, which
    cannot be called here without making the function uncacheable). Each trajectory writes only
    its own rows of the outputs, with the same numbers whatever the thread that integrated it.
    """
    N = outputs.STATUS.shape[0]
    n_workers = max(1, min(n_threads, (N + LANES - 1) // LANES))
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(n_workers):
        _worker(counter, inputs, settings, event_table, outputs)


@njit(cache=True, nogil=True)
def integrate_lanes_serial(inputs, settings, event_table, outputs, n_threads):
    """Same as :func:`integrate_lanes` on the calling thread (``n_threads`` is ignored)."""
    counter = np.zeros(1, dtype=np.int64)
    _worker(counter, inputs, settings, event_table, outputs)
