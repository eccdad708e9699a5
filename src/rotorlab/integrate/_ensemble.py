"""Parallel ensemble driver: many independent trajectories in one compiled call.

Each trajectory is integrated by :func:`rotorlab.integrate._core.integrate_one` with its own
step-size history and writes only its own rows of the output arrays, so the results are
bit-identical whatever the number of threads or the order in which threads pick trajectories.

Input arrays whose first dimension is 1 are shared by all trajectories (broadcasting without
copies): ``Y0`` (1 or N, n), ``P`` (1 or N, n_param), ``T1`` (1 or N,), ``TS`` (1 or N, n_save).
"""

from numba import njit, prange

from rotorlab.integrate._core import integrate_one


@njit(cache=True, nogil=True, parallel=True)
def integrate_ensemble(
    rhs, events, reset, n_ev, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step,
    max_steps, ev_dir, ev_act, YS, YF, STATUS, TEND, EVC, RECT, RECK, STATS,
):  # fmt: skip
    """Integrate ``STATUS.shape[0]`` trajectories in parallel (see ``integrate_one``)."""
    N = STATUS.shape[0]
    for i in prange(N):
        iy = min(i, Y0.shape[0] - 1)
        ip = min(i, P.shape[0] - 1)
        it1 = min(i, T1.shape[0] - 1)
        its = min(i, TS.shape[0] - 1)
        st, te = integrate_one(
            rhs, events, reset, n_ev, Y0[iy], P[ip], t0, T1[it1], TS[its], rtol, atol, n_cont,
            first_step, max_step, max_steps, ev_dir, ev_act, YS[i], YF[i], EVC[i], RECT[i],
            RECK[i], STATS[i],
        )  # fmt: skip
        STATUS[i] = st
        TEND[i] = te


@njit(cache=True, nogil=True)
def integrate_serial(
    rhs, events, reset, n_ev, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step,
    max_steps, ev_dir, ev_act, YS, YF, STATUS, TEND, EVC, RECT, RECK, STATS,
):  # fmt: skip
    """Same as :func:`integrate_ensemble` on the calling thread (no threading layer)."""
    N = STATUS.shape[0]
    for i in range(N):
        iy = min(i, Y0.shape[0] - 1)
        ip = min(i, P.shape[0] - 1)
        it1 = min(i, T1.shape[0] - 1)
        its = min(i, TS.shape[0] - 1)
        st, te = integrate_one(
            rhs, events, reset, n_ev, Y0[iy], P[ip], t0, T1[it1], TS[its], rtol, atol, n_cont,
            first_step, max_step, max_steps, ev_dir, ev_act, YS[i], YF[i], EVC[i], RECT[i],
            RECK[i], STATS[i],
        )  # fmt: skip
        STATUS[i] = st
        TEND[i] = te
