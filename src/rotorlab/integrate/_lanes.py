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
:mod:`rotorlab.integrate._codegen` writes a copy in which the import lines marked ``# @kernel``
import the model's kernels, so numba caches it across processes. The workspace layout and the
per-lane bookkeeping are the sibling template :mod:`rotorlab.integrate._lane_rows` (its
``# @const`` lines set the lane width and the state size), imported from its copy for the same
model by the line marked ``# @template``. The entry points take the argument groups of
:mod:`rotorlab.integrate._driver_args`, as the scalar drivers of :mod:`rotorlab.integrate._core`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rotorlab._kernels._vmath import fma, inv_fifth_root
from rotorlab.integrate._lane_intrinsics import fetch_add as _fetch_add
from rotorlab.models._base import no_events as events  # @kernel events
from rotorlab.models._base import no_reset as reset  # @kernel reset
from rotorlab.models._base import no_rhs as rhs  # @kernel rhs
from rotorlab.integrate import _core
from rotorlab.integrate._core import (
    ACT_OFF, MAX_STEPS, NONFINITE, STEP_UNDERFLOW, SUCCESS, _all_finite, _crosses, _own,
    with_kernels,
)  # fmt: skip
from rotorlab.integrate._tableau import (
    A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64, A65,
    B1, B3, B4, B5, B6,
    C2, C3, C4, C5,
    E1, E3, E4, E5, E6, E7,
    MAX_FACTOR, MIN_FACTOR, SAFETY,
)  # fmt: skip
from rotorlab.integrate._lane_rows import (  # @template
    _AT, _DONE, _EMPTY, _H, _K1, _K2, _K3, _K4, _K5, _K6, _K7, _M, _P, _Q, _T, _W_SIZE, _Y, _YN,
    LANES, N_STATE, NL,
    _code, _en, _h, _habs, _live, _lnf, _nacc, _new, _nfev, _nrej, _pw, _rej, _t, _t1, _tn, _tt,
    _finish, _lane, _min_steps, _prologue, _save,
)  # fmt: skip


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
# They take this copy's module name: numba names a compiled function by module, qualified name
# and a per-process counter, and the first definition of a name loaded in a process is the one
# every caller gets. Under _core's name, a lane driver loaded from numba's cache could call
# another model's event location compiled in another process under the same counter value
# (seen: the bouncing ball's lanes ended in another model's states, fresh-clone suite).
_EV = dict(vars(_core), __name__=__name__)
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


EVENTS = 1  # @const EVENTS
"""0: the model has no event functions, and this copy compiles no event handling (as
:data:`rotorlab.integrate._core.EVENTS`)."""

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

    The lane's time is read through ``_lane(...)[0]``, not ``W[_tt + lane]``: numba's negative-index
    wraparound of the latter (a select on ``lane < -_tt`` in the address) kept LLVM from
    vectorising this function when it is compiled on its own, and the worker calls this
    function's own machine code in the process that compiled it (numba links the callee's copy
    into the worker as a weak symbol; the first definition loaded wins). The worker's copy,
    optimised a second time, had the select folded and vectorised, so the driver ran 4x faster
    in later processes (loaded from numba's cache) than in the compiling one (Pico 21 machine).
    """
    n_par = (W.shape[0] - _P) // LANES
    for lane in range(nl):
        _rhs_inline(
            _lane(W, _tt + lane, 1)[0], _lane(W, _T + lane, N_STATE), _lane(W, _P + lane, n_par),
            _lane(W, _Q + lane, N_STATE),
        )  # fmt: skip


@njit(cache=True, nogil=True, error_model="numpy", inline="always" if INLINE_RHS else "never")
def _events_lanes(W, row_t, row_y, G, nl, ne):
    """``G[:, l] = events(t[l], Y[:, l], p[:, l])`` for every lane (``G`` lane-interleaved, ``ne``
    rows): the event functions at the end of every lane's step in one loop, which vectorises
    when the model's ``events`` is lane-friendly (as :func:`_rhs_lanes`; the time is read without
    wraparound for the same reason)."""
    n_par = (W.shape[0] - _P) // LANES
    for lane in range(nl):
        _events_inline(
            _lane(W, row_t + lane, 1)[0], _lane(W, row_y + lane, N_STATE), _lane(W, _P + lane, n_par),
            _lane(G, lane, ne),
        )  # fmt: skip


@njit(cache=True, nogil=True, error_model="numpy")
def _probe(W, nl):
    """One stage's kernel call as the worker makes it (constant rows): see :func:`rotorlab.integrate._drivers.is_vectorised`."""
    _rhs_lanes(W, nl)


@njit(cache=True, nogil=True, error_model="numpy")  # no ZeroDivisionError branch in the loops
def integrate_lanes(counter, inputs, settings, event_table, outputs):
    """Integrate trajectories taken from ``counter`` until none is left, ``LANES`` at a time.

    The arguments are the groups of :mod:`rotorlab.integrate._driver_args`; ``inputs.atol`` must
    have ``N_STATE`` entries. ``counter`` (one int64) is the next trajectory to take, shared by the
    threads that run this function at once (:func:`rotorlab.integrate._drivers.driver`). Each
    trajectory writes only its own rows of the outputs, with the same numbers whatever the thread
    that integrated it.
    """
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
                if EVENTS and has_ev:
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
                    W[_T + k] = fma(W[_H + k], A21 * W[_K1 + k], W[_Y + k])
                for lane in range(nl):
                    W[_tt + lane] = fma(C2, W[_h + lane], W[_t + lane])
            elif s == 1:
                for k in range(n * nl):
                    a = fma(A32, W[_K2 + k], A31 * W[_K1 + k])
                    W[_T + k] = fma(W[_H + k], a, W[_Y + k])
                for lane in range(nl):
                    W[_tt + lane] = fma(C3, W[_h + lane], W[_t + lane])
            elif s == 2:
                for k in range(n * nl):
                    a = fma(A43, W[_K3 + k], fma(A42, W[_K2 + k], A41 * W[_K1 + k]))
                    W[_T + k] = fma(W[_H + k], a, W[_Y + k])
                for lane in range(nl):
                    W[_tt + lane] = fma(C4, W[_h + lane], W[_t + lane])
            elif s == 3:
                for k in range(n * nl):
                    a = fma(A53, W[_K3 + k], fma(A52, W[_K2 + k], A51 * W[_K1 + k]))
                    W[_T + k] = fma(W[_H + k], fma(A54, W[_K4 + k], a), W[_Y + k])
                for lane in range(nl):
                    W[_tt + lane] = fma(C5, W[_h + lane], W[_t + lane])
            elif s == 4:
                for k in range(n * nl):
                    a = fma(A63, W[_K3 + k], fma(A62, W[_K2 + k], A61 * W[_K1 + k]))
                    a = fma(A65, W[_K5 + k], fma(A64, W[_K4 + k], a))
                    W[_T + k] = fma(W[_H + k], a, W[_Y + k])
            else:
                for k in range(n * nl):
                    a = fma(B4, W[_K4 + k], fma(B3, W[_K3 + k], B1 * W[_K1 + k]))
                    a = fma(B6, W[_K6 + k], fma(B5, W[_K5 + k], a))
                    W[_YN + k] = fma(W[_H + k], a, W[_Y + k])
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
            a = fma(E4, W[_K4 + k], fma(E3, W[_K3 + k], E1 * W[_K1 + k]))
            e = W[_H + k] * fma(E7, W[_K7 + k], fma(E6, W[_K6 + k], fma(E5, W[_K5 + k], a)))
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
        if EVENTS and has_ev:
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
