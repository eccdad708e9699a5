"""The lane driver's workspace layout and its per-lane bookkeeping (a template, as :mod:`._lanes`).

The lane driver (:mod:`rotorlab.integrate._lanes`) keeps everything of a worker's lanes in one
float64 array, the workspace ``W``; this module names its rows and holds the small functions that
read and write one lane's numbers: the start of a step attempt, the smallest step, saving at
given times and the end of a trajectory. None of them calls a model's kernel, but all depend on
the lane width and the state size, which are compile-time constants: so this is a template too.
:mod:`rotorlab.integrate._codegen` generates a copy of it with the constants of each lane driver
copy and points the lane driver's import line marked ``# @template`` at that copy.
"""

from __future__ import annotations

from numba import njit

from rotorlab.integrate._core import ST_NACCEPT, ST_NEVENTS, ST_NFEV, ST_NREJECT
from rotorlab.integrate._dp5 import _dense
from rotorlab.integrate._lane_intrinsics import lane_view

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

_lane = lane_view(LANES)  # a lane of a row: view of buf[start + i * LANES], i < n

_NEG_ZERO_BITS = -(2**63)  # -0.0 seen as int64

# lane slots: ids[l] >= 0 is the trajectory in lane l; these mark empty and exhausted lanes
_EMPTY = -1
_DONE = -2


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
