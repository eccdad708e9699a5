"""Compiled core of the integrator: one Dormand–Prince 5(4) trajectory with events and resets.

Everything here is ``@njit(cache=True, nogil=True)`` and works on float64 arrays only. The
model's kernels are the module globals ``rhs``, ``events`` and ``reset`` bound by the three
import lines marked ``# @kernel``: :mod:`rotorlab.integrate._codegen` compiles a copy of this
module per model with those lines pointing at the model's kernels (so numba can cache it across
processes). The entry points take the argument groups of :mod:`rotorlab.integrate._driver_args`. Python code never calls into a step: see ``_api.py`` for the public interface.

Step-size control is a line-by-line match of SciPy's ``RK45`` (RMS norm with scale
``atol + rtol * max(|y|, |y_new|)``, factor ``min(10, 0.9 err^-1/5)``, no growth right after a
rejection, ``max(0.2, ...)`` on rejection, Hairer's initial-step heuristic), so step counts match
``solve_ivp(method="RK45")`` and the C references of the benchmark (``bench/README.md``) to
round-off. ``err^-1/5`` is :func:`rotorlab._kernels._vmath.inv_fifth_root` (within 1.1 ulp of the
fifth root; SciPy's ``err ** -0.2`` is a libm ``pow`` with the double nearest -1/5), shared with
the lane driver, where it is one vector computation for all lanes instead of a ``pow`` per lane.
The stage sums, the solution, the error estimate, the stage times and the dense output are
chains of fused multiply-adds (``_vmath.fma``: ``llvm.fma``, rounded once, one instruction that
vectorises), written the same way in both drivers so that they give the same bits; the C
references are compiled with contraction too. SciPy rounds each product separately, hence
"to round-off".

Events (see :mod:`rotorlab.models._base`): after each accepted step every active event function
is compared at both ends; a sign change in the allowed direction is located to round-off on the
quartic dense output (Illinois method). The earliest ``reset``/``stop`` event truncates the step
there; ``count`` events are only recorded. After a reset the integrator restarts at the event time
with the new state and the step size the controller had proposed: a run of impacts never makes
the step size collapse, and an accumulation of impacts is resolved by the model's reset map
switching to a sustained-contact mode (a discrete state).
"""

import math
import sys

import numpy as np
from numba import njit

from rotorlab._kernels._vmath import fma, inv_fifth_root
from rotorlab.models._base import no_events as events  # @kernel events
from rotorlab.models._base import no_reset as reset  # @kernel reset
from rotorlab.models._base import no_rhs as rhs  # @kernel rhs
from rotorlab.integrate._lane_intrinsics import fetch_add as _fetch_add
from rotorlab.integrate._dp5 import _all_finite, _crosses, _dense, _rms_scaled, _save_until
from rotorlab.integrate._tableau import (  # the step-size factor err^(-1/5): _vmath.inv_fifth_root
    A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64, A65,
    B1, B3, B4, B5, B6,
    C2, C3, C4, C5,
    E1, E3, E4, E5, E6, E7,
    MAX_FACTOR, MIN_FACTOR, SAFETY,
)  # fmt: skip

EVENTS = 1  # @const EVENTS
"""0: the model has no event functions, and this copy compiles no event handling (set per
generated copy from ``Kernels.event_specs``; numba drops a branch on a constant global)."""

# status codes (mirrored by rotorlab.integrate.Status)
SUCCESS = 0
EVENT_STOP = 1
MAX_STEPS = -1
STEP_UNDERFLOW = -2
NONFINITE = -3
EVENT_LOOP = -4

# event actions
ACT_RESET = 0
ACT_STOP = 1
ACT_COUNT = 2
ACT_OFF = 3

# indices into the per-trajectory stats vector
ST_NFEV = 0
ST_NACCEPT = 1
ST_NREJECT = 2
ST_NEVENTS = 3
N_STATS = 4



def _own(kernel):
    """The kernel as this module's code calls it: its own dispatcher if its module is keyed by its
    sources, else compiled afresh from its Python source.

    A generated copy of this module is keyed on the sources of everything the kernels depend on
    (:mod:`rotorlab.integrate._codegen`); linking the kernel's own cached binary instead would
    bring back whatever numba cached for it, which only watches the kernel's own file. A kernel
    whose module says ``KEYED_BY_SOURCES = True`` (the machine's generated kernels,
    :mod:`rotorlab._kernels.machine_codegen`: the module's name changes with every source it
    depends on) is linked as it is: compiled once per model and cached with its module, it serves
    both drivers (the scalar one and the lane driver's scalar evaluations) and the Python callers.
    Linked rather than compiled again with the scalar driver's step loop, it saves that compile
    (1-16 CPU-s per layout) at the same run time (``bench/README.md``, issue 24, session 13).
    """
    if getattr(sys.modules.get(kernel.py_func.__module__), "KEYED_BY_SOURCES", False) is True:
        return kernel
    opts = {k: v for k, v in kernel.targetoptions.items() if k != "nopython"}
    opts["cache"] = False
    return njit(**opts)(kernel.py_func)


def with_kernels(fn, namespace):
    """``fn`` (a compiled function of this template) compiled against the globals ``namespace``.

    The lane driver (:mod:`rotorlab.integrate._lanes`) locates events and applies resets with
    the functions of this module, bound to its own model's ``rhs``/``events``/``reset`` (the
    template's globals here are placeholders): one source for both drivers, so that they use the
    same arithmetic. Compiled without caching, as :func:`_own`: the caller's cache holds the code.
    ``namespace["__name__"]`` must be the caller's own (generated) module name: it becomes the
    function's module, which numba's symbol names carry (see ``_lanes._EV``).
    """
    import types as _types

    f = fn.py_func
    bound = _types.FunctionType(f.__code__, namespace, f.__name__, f.__defaults__, f.__closure__)
    opts = {k: v for k, v in fn.targetoptions.items() if k != "nopython"}
    opts["cache"] = False
    return njit(**opts)(bound)


rhs = _own(rhs)
events = _own(events)
reset = _own(reset)

_MAX_RESETS_WITHOUT_PROGRESS = 1000
_PROBES = (1e-7, 1e-10, 1e-13)  # step fractions probing an event function that starts at zero


@njit(cache=True, nogil=True)
def _g_at(k, p, t, h, y, k1, k3, k4, k5, k6, k7, s, ybuf, gbuf, from_zero):
    """Event function ``k`` at fraction ``s`` of the step (divided by ``s`` if ``from_zero``)."""
    _dense(y, h, k1, k3, k4, k5, k6, k7, s, ybuf)
    events(t + s * h, ybuf, p, gbuf)
    return gbuf[k] / s if from_zero else gbuf[k]


@njit(cache=True, nogil=True)
def _locate(k, p, t, h, y, k1, k3, k4, k5, k6, k7, ga, gb, ybuf, gbuf, from_zero):
    """Locate the zero of event ``k`` in the step (Illinois method on the dense output).

    Returns the fraction ``s`` in (0, 1] of the step at which the event function has reached
    (or just passed) zero: the bracket's "after" end, so the state there is on the far side.
    With ``from_zero`` the step starts on the event surface (g(0) = 0, e.g. right after a
    reset) and the zero of g(s)/s is sought instead, which excludes the root at s = 0.
    """
    sa = 0.0
    sb = 1.0
    xtol = 4.0 * 2.220446049250313e-16 * max(abs(t), abs(t + h)) / abs(h)
    xtol = max(xtol, 1e-15)
    side = 0
    for _ in range(200):
        if sb - sa <= xtol:
            break
        if gb != ga:
            s = (sa * gb - sb * ga) / (gb - ga)
        else:
            s = 0.5 * (sa + sb)
        if not (sa < s < sb):
            s = 0.5 * (sa + sb)
        gs = _g_at(k, p, t, h, y, k1, k3, k4, k5, k6, k7, s, ybuf, gbuf, from_zero)
        if gs == 0.0:
            return s
        if (gs > 0.0) == (gb > 0.0) and gb != 0.0:
            sb = s
            gb = gs
            if side == -1:
                ga *= 0.5
            side = -1
        else:
            sa = s
            ga = gs
            if side == 1:
                gb *= 0.5
            side = 1
    return sb


@njit(cache=True, nogil=True)
def _events_in_step(
    n_ev, ev_dir, ev_act, p, t, h, tn, y, ynew, k1, k3, k4, k5, k6, k7,
    g_old, g_new, gbuf, s_ev, ybuf, ev_count, rec_t, rec_k, nrec,
):  # fmt: skip
    """Find the events of an accepted step from ``(t, y)`` to ``(tn, ynew)``; record them.

    Every active event function, evaluated by the caller at ``tn`` (``g_new``), is compared with
    its value ``g_old`` at ``t``; a sign change in the allowed direction is located on the dense
    output. Events up to the earliest ``reset``/``stop`` event (the cut) are counted in
    ``ev_count`` and recorded in ``rec_t``/``rec_k`` (from index ``nrec``), in time order.
    Shared by the scalar and the lane driver (which calls it for one lane at a time), so both
    locate events with the same arithmetic.

    Returns
    -------
    s_cut : float
        Fraction of the step at the cut (> 1: none).
    k_cut : int
        Event at the cut (-1: none).
    nrec : int
        Records written so far.
    n_found : int
        Events counted in this step.
    """
    s_cut = 2.0  # fraction of the step where a reset/stop event truncates it (>1: none)
    k_cut = -1
    n_found = 0
    max_rec = rec_t.shape[0]
    for k in range(n_ev):
        s_ev[k] = 2.0
        if ev_act[k] == ACT_OFF:
            continue
        ga = g_old[k]
        from_zero = ga == 0.0
        if from_zero:
            # The step starts on the event surface (typically right after a reset): the
            # zero at s = 0 is consumed, look for one of g(s)/s. Its sign at the start
            # is probed at shrinking fractions of the step, so that a very short
            # excursion (a tiny rebound) inside a long step is not missed.
            for probe in _PROBES:
                ga = _g_at(k, p, t, h, y, k1, k3, k4, k5, k6, k7, probe, ybuf, gbuf, True)
                if _crosses(ga, g_new[k], ev_dir[k]):
                    break
        if _crosses(ga, g_new[k], ev_dir[k]):
            if g_new[k] == 0.0:
                s_ev[k] = 1.0
            else:
                s_ev[k] = _locate(
                    k, p, t, h, y, k1, k3, k4, k5, k6, k7, ga, g_new[k], ybuf, gbuf, from_zero
                )  # fmt: skip
            if ev_act[k] != ACT_COUNT and s_ev[k] < s_cut:
                s_cut = s_ev[k]
                k_cut = k
    # record events up to the cut, in time order
    while True:
        kmin = -1
        smin = 2.0
        for k in range(n_ev):
            if s_ev[k] < smin and (s_ev[k] < s_cut or k == k_cut):
                smin = s_ev[k]
                kmin = k
        if kmin < 0:
            break
        ev_count[kmin] += 1
        n_found += 1
        if nrec < max_rec:
            rec_t[nrec] = t + smin * h
            rec_k[nrec] = kmin
            nrec += 1
        s_ev[kmin] = 2.0
        if kmin == k_cut:
            break
    return s_cut, k_cut, nrec, n_found


@njit(cache=True, nogil=True)
def _resolve_cut(
    k_cut, s_cut, act, p, t, h, tn, y, ynew, k1, k3, k4, k5, k6, k7,
    ts, i_save, ys_out, ybuf, ytmp, g_old, t_last_reset, resets_without_progress,
):  # fmt: skip
    """End a step at its cut (event ``k_cut`` with action ``act`` at fraction ``s_cut``).

    Saves the states in (t, te], then either stops there (``y`` = the state at ``te``) or
    applies the reset map into ``y`` and restarts: ``k1`` and ``g_old`` are evaluated at the new
    state. Shared by the scalar and the lane driver.

    Returns
    -------
    status : int
        ``SUCCESS`` to continue from ``(te, y)``, else how the trajectory ends there.
    te : float
        The event time, the trajectory's new time.
    i_save, t_last_reset, resets_without_progress : int, float, int
        Updated bookkeeping.
    n_rhs : int
        Right-hand side evaluations made.
    """
    n = y.shape[0]
    te = t + s_cut * h if s_cut < 1.0 else tn
    if s_cut < 1.0:
        _dense(y, h, k1, k3, k4, k5, k6, k7, s_cut, ybuf)
    else:
        for i in range(n):
            ybuf[i] = ynew[i]
    i_save = _save_until(te, ybuf, t, h, y, k1, k3, k4, k5, k6, k7, ts, i_save, ys_out, ytmp)
    if act == ACT_STOP:
        for i in range(n):
            y[i] = ybuf[i]
        return EVENT_STOP, te, i_save, t_last_reset, resets_without_progress, 0
    flag = reset(k_cut, te, ybuf, p, y)
    if te - t_last_reset <= 8.0 * 2.220446049250313e-16 * max(1.0, abs(te)):
        resets_without_progress += 1
        if resets_without_progress > _MAX_RESETS_WITHOUT_PROGRESS:
            return EVENT_LOOP, te, i_save, t_last_reset, resets_without_progress, 0
    else:
        resets_without_progress = 0
    t_last_reset = te
    if not _all_finite(y):
        return NONFINITE, te, i_save, t_last_reset, resets_without_progress, 0
    if flag != 0:
        return EVENT_STOP, te, i_save, t_last_reset, resets_without_progress, 0
    # the kernels see contiguous copies (ybuf, ytmp are free now): the lane driver passes
    # strided lane views as y and k1, and a kernel called with them would be compiled a second
    # time for that array type (seconds for a large generated kernel)
    for i in range(n):
        ybuf[i] = y[i]
    rhs(te, ybuf, p, ytmp)
    for i in range(n):
        k1[i] = ytmp[i]
    events(te, ybuf, p, g_old)
    return SUCCESS, te, i_save, t_last_reset, resets_without_progress, 1


@njit(cache=True, nogil=True)
def _initial_step(p, t0, y0, f0, t1, rtol, atol, n_cont, ytmp, f1):
    """Hairer's initial step heuristic (as SciPy's ``select_initial_step``, order 5 method)."""
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
    rhs(t0 + h0, ytmp, p, f1)
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


@njit(cache=True, nogil=True)
def integrate_one(
    n_ev, y0, p, t0, t1, ts, rtol, atol, n_cont, first_step, max_step,
    max_steps, ev_dir, ev_act, ys_out, y_final, ev_count, rec_t, rec_k, stats,
):  # fmt: skip
    """Integrate one trajectory from ``t0`` to ``t1``; return ``(status, t_end)``.

    Parameters
    ----------
    n_ev : int
        Number of event functions.
    y0 : float64, shape (n,)
    p : float64, shape (n_param,)
    t0, t1 : float
        Start and end time (s), ``t1 > t0``.
    ts : float64, shape (n_save,)
        Increasing save times in [t0, t1]; the state there is written to ``ys_out``.
    rtol : float
    atol : float64, shape (n,)
    n_cont : int
        Number of leading continuous components (the rest are discrete modes).
    first_step : float
        Initial step (s); <= 0 selects it automatically.
    max_step : float
        Largest step allowed (s).
    max_steps : int
        Maximum number of step attempts.
    ev_dir, ev_act : int64, shape (n_ev,)
        Direction (-1, 0, +1) and action (``ACT_*``) of each event.
    ys_out : float64, shape (n_save, n)   -- written; rows not reached are left untouched.
    y_final : float64, shape (n,)         -- written: the state at ``t_end``.
    ev_count : int64, shape (n_ev,)       -- written: occurrences of each event.
    rec_t : float64, shape (max_rec,)     -- written: times of the first ``max_rec`` events.
    rec_k : int64, shape (max_rec,)       -- written: which event each record is.
    stats : int64, shape (N_STATS,)       -- written: nfev, naccept, nreject, nevents.
    """
    n = y0.shape[0]
    n_save = ts.shape[0]
    max_rec = rec_t.shape[0]
    y = np.empty(n)
    ynew = np.empty(n)
    ytmp = np.empty(n)
    ybuf = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    err = np.empty(n)
    s_cut = 2.0
    g_old = np.empty(max(n_ev, 1))
    g_new = np.empty(max(n_ev, 1))
    gbuf = np.empty(max(n_ev, 1))
    s_ev = np.empty(max(n_ev, 1))
    for i in range(n):
        y[i] = y0[i]
    nfev = 0
    naccept = 0
    nreject = 0
    nrec = 0
    n_events_total = 0
    for k in range(n_ev):
        ev_count[k] = 0
    t = t0
    i_save = 0
    while i_save < n_save and ts[i_save] <= t0:
        for j in range(n):
            ys_out[i_save, j] = y[j]
        i_save += 1

    status = SUCCESS
    rhs(t, y, p, k1)
    nfev += 1
    if not (_all_finite(y) and _all_finite(k1)):
        status = NONFINITE
    if EVENTS and n_ev > 0:
        events(t, y, p, g_old)

    if first_step > 0.0:
        habs = min(first_step, t1 - t0)
    elif status == SUCCESS:
        habs = _initial_step(p, t0, y, k1, t1, rtol, atol, n_cont, ytmp, k2)
        nfev += 1
    else:
        habs = 0.0
    habs = min(habs, max_step)

    resets_without_progress = 0
    t_last_reset = -math.inf
    while status == SUCCESS and t < t1:
        min_step = 10.0 * abs(np.nextafter(t, math.inf) - t)
        if habs > max_step:
            habs = max_step
        elif habs < min_step:
            habs = min_step
        rejected = False
        last_nonfinite = False
        accepted = False
        tn = t
        h = 0.0
        while not accepted:
            if habs < min_step:
                status = NONFINITE if last_nonfinite else STEP_UNDERFLOW
                break
            if naccept + nreject >= max_steps:
                status = MAX_STEPS
                break
            tn = t + habs
            if tn > t1:
                tn = t1
            h = tn - t
            habs = abs(h)
            for i in range(n):
                ytmp[i] = fma(h, A21 * k1[i], y[i])
            rhs(fma(C2, h, t), ytmp, p, k2)
            for i in range(n):
                ytmp[i] = fma(h, fma(A32, k2[i], A31 * k1[i]), y[i])
            rhs(fma(C3, h, t), ytmp, p, k3)
            for i in range(n):
                ytmp[i] = fma(h, fma(A43, k3[i], fma(A42, k2[i], A41 * k1[i])), y[i])
            rhs(fma(C4, h, t), ytmp, p, k4)
            for i in range(n):
                a = fma(A53, k3[i], fma(A52, k2[i], A51 * k1[i]))
                ytmp[i] = fma(h, fma(A54, k4[i], a), y[i])
            rhs(fma(C5, h, t), ytmp, p, k5)
            for i in range(n):
                a = fma(A63, k3[i], fma(A62, k2[i], A61 * k1[i]))
                a = fma(A65, k5[i], fma(A64, k4[i], a))
                ytmp[i] = fma(h, a, y[i])
            rhs(tn, ytmp, p, k6)
            for i in range(n):
                a = fma(B4, k4[i], fma(B3, k3[i], B1 * k1[i]))
                a = fma(B6, k6[i], fma(B5, k5[i], a))
                ynew[i] = fma(h, a, y[i])
            rhs(tn, ynew, p, k7)
            nfev += 6
            for i in range(n):
                a = fma(E4, k4[i], fma(E3, k3[i], E1 * k1[i]))
                err[i] = h * fma(E7, k7[i], fma(E6, k6[i], fma(E5, k5[i], a)))
            err_norm = _rms_scaled(err, y, ynew, atol, rtol, n_cont)
            if not math.isfinite(err_norm) or not _all_finite(k7):
                last_nonfinite = True
                habs *= MIN_FACTOR
                rejected = True
                nreject += 1
            elif err_norm < 1.0:
                if err_norm == 0.0:
                    factor = MAX_FACTOR
                else:
                    factor = min(MAX_FACTOR, SAFETY * inv_fifth_root(err_norm))
                if rejected:
                    factor = min(1.0, factor)
                habs *= factor
                accepted = True
                naccept += 1
            else:
                habs *= max(MIN_FACTOR, SAFETY * inv_fifth_root(err_norm))
                rejected = True
                nreject += 1
        if not accepted:
            break

        # ---- events in (t, tn] -------------------------------------------------------------
        k_cut = -1
        if EVENTS and n_ev > 0:
            events(tn, ynew, p, g_new)
            s_cut, k_cut, nrec, n_found = _events_in_step(
                n_ev, ev_dir, ev_act, p, t, h, tn, y, ynew, k1, k3, k4, k5, k6, k7,
                g_old, g_new, gbuf, s_ev, ybuf, ev_count, rec_t, rec_k, nrec,
            )  # fmt: skip
            n_events_total += n_found

        if EVENTS and k_cut >= 0:
            # ---- truncated at a reset/stop event ------------------------------------------
            status, t, i_save, t_last_reset, resets_without_progress, n_rhs = _resolve_cut(
                k_cut, s_cut, ev_act[k_cut], p, t, h, tn, y, ynew, k1, k3, k4, k5, k6, k7,
                ts, i_save, ys_out, ybuf, ytmp, g_old, t_last_reset, resets_without_progress,
            )  # fmt: skip
            nfev += n_rhs
            continue

        # ---- plain accepted step: save, advance -----------------------------------------------
        i_save = _save_until(tn, ynew, t, h, y, k1, k3, k4, k5, k6, k7, ts, i_save, ys_out, ybuf)
        t = tn
        for i in range(n):
            y[i] = ynew[i]
            k1[i] = k7[i]
        if EVENTS and n_ev > 0:
            for k in range(n_ev):
                g_old[k] = g_new[k]

    for i in range(n):
        y_final[i] = y[i]
    stats[ST_NFEV] = nfev
    stats[ST_NACCEPT] = naccept
    stats[ST_NREJECT] = nreject
    stats[ST_NEVENTS] = n_events_total
    return status, t


@njit(cache=True, nogil=True)
def integrate_worker(counter, inputs, settings, event_table, outputs):
    """Integrate trajectories taken from ``counter`` until none is left (see :func:`integrate_one`).

    The arguments are the groups of :mod:`rotorlab.integrate._driver_args`; ``counter`` (one
    int64) is the next trajectory to take, shared by the threads that run this function at once
    (:func:`rotorlab.integrate._drivers.driver`). Each trajectory writes only its own rows of the
    outputs, so results are bit-identical whatever the number of threads. Inputs whose first
    dimension is 1 are shared by all trajectories.
    """
    N = outputs.STATUS.shape[0]
    while True:
        i = _fetch_add(counter, 1)
        if i >= N:
            return
        _one_of_many(i, inputs, settings, event_table, outputs)


@njit(cache=True, nogil=True)
def _one_of_many(i, inputs, settings, ev, out):
    i = np.int64(i)  # an unsigned index mixed with int64 gives float64
    iy = i if inputs.Y0.shape[0] > 1 else np.int64(0)
    ip = i if inputs.P.shape[0] > 1 else np.int64(0)
    it1 = i if inputs.T1.shape[0] > 1 else np.int64(0)
    its = i if inputs.TS.shape[0] > 1 else np.int64(0)
    st, te = integrate_one(
        ev.n_ev, inputs.Y0[iy], inputs.P[ip], settings.t0, inputs.T1[it1], inputs.TS[its],
        settings.rtol, inputs.atol, settings.n_cont, settings.first_step, settings.max_step,
        settings.max_steps, ev.ev_dir, ev.ev_act, out.YS[i], out.YF[i], out.EVC[i], out.RECT[i],
        out.RECK[i], out.STATS[i],
    )  # fmt: skip
    out.STATUS[i] = st
    out.TEND[i] = te
