r"""The ``shock-margin`` analysis: how hard a knock or a load shift throws the balls out of balance.

A ball balancer that has balanced its rotor sits at the *balanced state*: in the co-rotating frame
the rotor stands still on the axis and ball i at the angle psi_i* from the unbalance (seed 002
eqs. (15)-(17); :func:`rotorlab.steady.find_steady_motions`, motion ``main+``). Two disturbances
a machine meets in service are measured here, over speed and over their direction (in the
co-rotating frame, from the unbalance, positive in the direction of rotation):

Lateral impulse (a knock), N s
    A force impulse ``I (cos beta, sin beta)`` on the disc centre changes only velocities:
    ``M dq' = (I cos beta, I sin beta, 0, ..., 0)`` with M the mass matrix of
    ``q = (u, v, psi_1..psi_n)`` (:func:`rotorlab.models.JeffcottBalls.linearize`). The knock is
    *fatal* when the balls do not come back to the balanced angles they held (they settle at
    another arrangement, e.g. the balls swapped, after passing the side motion where they meet,
    or they end in another motion).

    Closed-form bound (the linearised basin). Let ``x(t) = exp(A t) x0`` be the response of the
    linearisation ``x' = A x`` about the balanced state (:attr:`Linearization.A`) to the unit
    impulse, ``x0 = (0, M^-1 e_beta)``; it is linear in ``(cos beta, sin beta)``, so two
    responses give every direction. The nearest place where balancing fails is the side motion
    where two neighbouring balls of one race meet: from the balanced state it is ``r = min_{i<j}
    |wrap(psi_i* - psi_j*)| / 2`` away in every ball angle (the max-norm distance to the
    invariant plane psi_i = psi_j; for two equal balls r = gamma = arccos(eta / 2), seed 002
    eq. (16), the balls meeting on the light side at psi = pi). The impulse whose linear
    response just carries a ball that far is::

        I_lin(beta) = r / g(beta),   g(beta) = max_{t >= 0} max_i |psi_i(t; unit impulse at beta)|

    and ``min_beta I_lin`` is the minimal fatal shock of the linearised basin (one ball: r = pi,
    the opposite side motion). It is an estimate, not a rigorous bound: the motion is not linear
    that far out. On the built-in ``autobalancer`` at 2 p the simulated minimal fatal impulse over
    24 directions is within 10 % of it (``tests/validation/test_shock_margin.py``).

Step change of unbalance (a load shift), kg m
    The unbalance ``U = M1 e`` (along the u axis) becomes ``U' = U + S e^{i beta}``. The balls can
    cancel ``U'`` (a balanced state exists) exactly when the polygon of ``|U'|`` and the static
    moments ``a_i = m_i l_i`` closes: ``|U'| <= C = sum a_i`` and ``|U'| >= 2 max a_i - C``.
    The smallest fatal shift in direction beta is therefore the smallest ``S > 0`` with
    ``|U + S e^{i beta}|`` outside ``[U_min, C]``::

        S_out(beta) = -U cos beta + sqrt(C^2 - U^2 sin^2 beta)
        S_in(beta)  = -U cos beta - sqrt(U_min^2 - U^2 sin^2 beta)   (when real and > 0)

    worst along the unbalance (beta = 0): ``S = C - U``. A simulation from the old balanced
    state with the new unbalance checks each direction just below and just above it.

Every simulation starts from the balanced state and runs, on the lane driver, for the horizon the
balanced state's slowest eigenvalue gives (:func:`rotorlab.explore.default_horizon`). The impulse
threshold is bisected for all speeds and directions at once (each lane one of them).

A ``machine`` with balls is measured the same way (the knock and the load shift at its first
unbalance's station; its load-shift bound in closed form where one race and the unbalances share a
plane, else searched): the pieces that differ between model types are registered in
:mod:`rotorlab.analyses._shock_subjects`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["shock_margin", "balanced_angles", "linear_impulse", "load_shift_bound", "run_shock_margin_analysis",
           "shock_margin_rows", "shock_margin_task_size"]  # fmt: skip

#: Bisection steps of the simulated impulse threshold (its bracket shrinks by 2 each step).
BISECTIONS = 8
#: The first bracket of the simulated threshold, in units of the linearised bound.
BRACKET = 3.0
#: The load-shift check simulates at (1 -+ this) times the closed-form shift.
SHIFT_CHECK = 0.1
#: A rotor counts as balanced after a load shift when its deflection is below this fraction of
#: the deflection the new unbalance alone would cause (stricter than the basin's 5 %: just past
#: the capacity the residual is small).
SHIFT_BALANCED = 1e-3


def balanced_angles(model, spin_speed: float) -> np.ndarray | None:
    """The ball angles of the balanced state at ``spin_speed`` (rad, from the unbalance), or None.

    The first existing main motion of :func:`rotorlab.steady.find_steady_motions` (``main+``;
    for three or more balls the first sample of the family).
    """
    from rotorlab.steady import find_steady_motions

    for motion in find_steady_motions(model, spin_speed):
        if motion.kind == "main" and motion.exists:
            return np.asarray(motion.samples[0], dtype=float)
    return None


def _meeting_distance(angles: np.ndarray, races=None) -> float:
    """r: half the smallest angular gap between two balls of one race (pi for a ball alone in its race), rad."""
    n = angles.size
    races = np.zeros(n, dtype=int) if races is None else np.asarray(races)
    gaps = [abs(float(np.pi - np.mod(np.pi - (angles[i] - angles[j]), 2 * np.pi))) for i in range(n)
            for j in range(i + 1, n) if races[i] == races[j]]  # fmt: skip
    return 0.5 * min(gaps) if gaps else math.pi


def linear_impulse(lin, angles, directions, unit=None, psi=None, races=None) -> tuple[np.ndarray, float, np.ndarray]:
    """The linearised-basin impulse ``I_lin(beta)`` (N s) of the module docstring.

    Parameters
    ----------
    lin : Linearization
        Of the rotating-frame model about the balanced state (asymptotically stable).
    angles : array_like, shape (n,)
        Balanced ball angles (rad).
    directions : array_like, shape (k,)
        beta (rad, co-rotating frame, from the unbalance).
    unit : array_like, shape (2, n_lin), optional
        The jump of ``lin``'s state per N s along beta = 0 and 90 deg; default ``jeffcott_balls``'
        ``M^-1 e`` on ``(u', v', psi_i')`` (state order u, v, u', v', psi_i, psi_i').
    psi : slice, optional
        The ball angles in ``lin``'s state (default ``jeffcott_balls``': 4 .. 4 + n).
    races : array_like of int, shape (n,), optional
        The race of each ball (balls of different races never meet); default one race.

    Returns
    -------
    bound : ndarray, shape (k,)
        ``r / g(beta)`` (N s).
    r : float
        Distance to the side motion where two balls meet (rad).
    kick : ndarray, shape (k, n_lin)
        The jump of ``lin``'s state per N s along each beta.
    """
    angles = np.asarray(angles, dtype=float)
    beta = np.asarray(directions, dtype=float)
    n = angles.size
    if unit is None:
        dq = np.linalg.solve(lin.M, np.vstack([np.eye(2), np.zeros((n, 2))])).T
        unit = np.zeros((2, lin.A.shape[0]))
        unit[:, 2:4], unit[:, 4 + n :] = dq[:, :2], dq[:, 2:]
        psi = slice(4, 4 + n)
    from rotorlab.explore._settle import slowest_decay_rate

    lam, vec = np.linalg.eig(lin.A)
    decay = slowest_decay_rate(lam)  # neutral modes (a family of balanced states) left out
    fast = float(np.abs(lam).max())
    t_end = min(12.0 / decay, 4000.0 * 2.0 * math.pi / fast)
    ts = np.linspace(0.0, t_end, int(min(200_000, max(2000, 40.0 * t_end * fast / (2.0 * math.pi)))))
    inv = np.linalg.inv(vec)
    rows = []
    for x0 in np.asarray(unit, dtype=float):
        coef = inv @ x0
        resp = (vec[psi, :][None, :, :] * np.exp(np.outer(ts, lam))[:, None, :]) @ coef
        rows.append(resp.real)  # (t, n)
    cu, su = np.cos(beta), np.sin(beta)
    resp = cu[:, None, None] * rows[0][None] + su[:, None, None] * rows[1][None]  # (k, t, n)
    g = np.abs(resp).max(axis=(1, 2))
    r = _meeting_distance(angles, races)
    kick = np.outer(cu, unit[0]) + np.outer(su, unit[1])
    return r / g, r, kick


def load_shift_bound(imbalance: float, moments, directions) -> np.ndarray:
    """The smallest fatal step change of unbalance ``S(beta)`` (kg m) of the module docstring.

    Examples
    --------
    >>> load_shift_bound(1.5e-3, [1.5e-3, 1.5e-3], [0.0, math.pi]).round(6).tolist()
    [0.0015, 0.0045]
    """
    a = np.asarray(moments, dtype=float)
    cap = float(a.sum())
    low = max(0.0, 2.0 * float(a.max()) - cap)
    u = float(imbalance)
    beta = np.asarray(directions, dtype=float)
    c, s = np.cos(beta), np.sin(beta)
    out = -u * c + np.sqrt(np.maximum(cap**2 - (u * s) ** 2, 0.0))
    disc = low**2 - (u * s) ** 2
    inner = np.where(disc >= 0.0, -u * c - np.sqrt(np.maximum(disc, 0.0)), np.inf)
    inner = np.where(inner > 0.0, inner, np.inf)
    return np.minimum(out, inner)


def shock_margin(model, speeds, *, directions: int = 24, simulate: bool = True, rtol: float = 1e-7,
                 atol: float = 1e-9, threads: int | None = None,
                 progress: Callable[[int, int], None] | None = None):  # fmt: skip
    """Minimal fatal impulse and load shift of the balanced state, over speed and direction.

    Parameters
    ----------
    model : JeffcottBalls or Machine
        Without Coulomb friction (its balanced state is an isolated equilibrium); a machine also
        isotropic, without gravity across the axis (:meth:`Machine.why_no_rotating_frame`), the
        knock and the load shift at the station of its first unbalance (the per-type pieces:
        :mod:`rotorlab.analyses._shock_subjects`).
    speeds : array_like, shape (n_s,)
        Spin speeds (rad/s), > 0.
    directions : int
        Directions beta, evenly spaced over a turn (co-rotating frame, from the unbalance).
    simulate : bool
        Also bisect the impulse threshold and check the load-shift bound by simulation.
    rtol, atol : float
        Integrator tolerances.

    Returns
    -------
    xarray.Dataset
        Over ``(speed, direction)``: ``impulse_linear`` (N s, the linearised-basin estimate), ``impulse_simulated``
        (N s, bisected; NaN where even ``BRACKET`` times the bound returned, see
        ``impulse_searched_to``), ``fatal_outcome`` (where the smallest fatal knock found left the
        balls: ``"balanced"`` (again, in another arrangement), ``"side (...)"``,
        ``"non-synchronous"``, ...; empty where none was found), ``load_shift_bound`` (kg m, closed form), ``shift_below`` and
        ``shift_above`` (1: balanced, 0: not, -1: not settled or failed; simulated at
        ``1 -+ SHIFT_CHECK`` times the bound). Over ``speed``: ``stable`` (1 if the balanced state
        exists and is stable), ``decay_rate`` (1/s), ``horizon`` (s), ``meeting_distance`` (rad),
        ``min_impulse_linear``, ``min_impulse_simulated``, ``min_load_shift`` and the worst
        directions ``worst_linear_direction`` (of the estimate), ``worst_impulse_direction`` (of the
        simulated impulse where one was found, else of the estimate), ``worst_shift_direction`` (rad).

    Raises
    ------
    ValueError
        A model with friction or without balls, bad speeds or directions.
    """
    import xarray as xr

    from rotorlab.analyses._shock_subjects import shock_subject
    from rotorlab.explore._settle import default_horizon

    subject = shock_subject(model)
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds) & (speeds > 0)):
        raise ValueError(f"speeds must be one or more finite numbers > 0 (rad/s), got {speeds!r}")
    if isinstance(directions, bool) or int(directions) != directions or directions < 1:
        raise ValueError(f"directions must be an integer >= 1, got {directions!r}")
    beta = np.linspace(0.0, 2.0 * math.pi, int(directions), endpoint=False)
    ns, nd = speeds.size, beta.size
    shift = np.tile(subject.load_shift_bound(beta), (ns, 1))
    bound = np.full((ns, nd), np.nan)
    stable = np.zeros(ns, dtype=np.int64)
    decay, horizon, dist = np.full(ns, np.nan), np.full(ns, np.nan), np.full(ns, np.nan)
    states: list = [None] * ns
    kicks = np.full((ns, nd, subject.sim.n_state), np.nan)
    for i, om in enumerate(speeds):
        bal = subject.balanced(float(om))
        if bal is None:
            continue
        stable[i], decay[i], states[i] = 1, bal.rate, bal
        horizon[i] = default_horizon(bal.rate, float(om), 20.0)[0]
        bound[i], dist[i], _ = linear_impulse(bal.lin, bal.angles, beta, bal.unit, bal.psi, subject.races)
        kicks[i] = np.outer(np.cos(beta), bal.kick[0]) + np.outer(np.sin(beta), bal.kick[1])
    shift = np.where(stable[:, None] == 1, shift, np.nan)
    simulated = np.full((ns, nd), np.nan)
    searched = np.full((ns, nd), np.nan)
    after = np.full((ns, nd), "", dtype=object).astype(str)
    below = np.full((ns, nd), -1, dtype=np.int64)
    above = np.full((ns, nd), -1, dtype=np.int64)
    if simulate and stable.any():
        ctx = _Lanes(subject, speeds, stable, states, horizon, rtol, atol, threads)
        simulated, searched, after = ctx.bisect_impulse(bound, kicks, dist, progress)
        below, above = ctx.check_shift(shift, beta)
    worst_i = np.where(stable == 1, np.argmin(np.where(np.isfinite(bound), bound, np.inf), axis=1), -1)
    has_sim = np.any(np.isfinite(simulated), axis=1)
    worst_sim = np.where(has_sim, np.argmin(np.where(np.isfinite(simulated), simulated, np.inf), axis=1), worst_i)
    worst_s = np.where(stable == 1, np.argmin(np.where(np.isfinite(shift), shift, np.inf), axis=1), -1)

    def pick(values, idx):
        return np.array([values[i, j] if j >= 0 else np.nan for i, j in enumerate(idx)])

    with np.errstate(all="ignore"):
        min_sim = np.array([np.nanmin(row) if np.any(np.isfinite(row)) else np.nan for row in simulated])
    dims = ("speed", "direction")
    ds = xr.Dataset(
        {
            "impulse_linear": (dims, bound, {"units": "N s"}),
            "impulse_simulated": (dims, simulated, {"units": "N s"}),
            "impulse_searched_to": (dims, searched, {"units": "N s"}),
            "fatal_outcome": (dims, after, {"units": "1"}),
            "load_shift_bound": (dims, shift, {"units": "kg m"}),
            "shift_below": (dims, below, {"units": "1"}),
            "shift_above": (dims, above, {"units": "1"}),
            "stable": (("speed",), stable, {"units": "1"}),
            "decay_rate": (("speed",), decay, {"units": "1/s"}),
            "horizon": (("speed",), horizon, {"units": "s"}),
            "meeting_distance": (("speed",), dist, {"units": "rad"}),
            "min_impulse_linear": (("speed",), pick(bound, worst_i), {"units": "N s"}),
            "min_impulse_simulated": (("speed",), min_sim, {"units": "N s"}),
            "min_load_shift": (("speed",), pick(shift, worst_s), {"units": "kg m"}),
            "worst_linear_direction": (("speed",), np.where(worst_i >= 0, beta[np.maximum(worst_i, 0)], np.nan),
                                       {"units": "rad"}),
            "worst_impulse_direction": (("speed",), np.where(worst_sim >= 0, beta[np.maximum(worst_sim, 0)], np.nan),
                                        {"units": "rad"}),
            "worst_shift_direction": (("speed",), np.where(worst_s >= 0, beta[np.maximum(worst_s, 0)], np.nan),
                                      {"units": "rad"}),
        },
        coords={"speed": ("speed", speeds, {"units": "rad/s"}),
                "direction": ("direction", beta, {"units": "rad"})},
        attrs={"critical_speed": float(subject.critical_speed), "imbalance": float(subject.imbalance),
               "capacity": float(subject.capacity), "station": subject.station,
               "simulated": int(bool(simulate)), "bisections": BISECTIONS,
               "bracket": BRACKET, "shift_check": SHIFT_CHECK},
    )  # fmt: skip
    return ds


class _Lanes:
    """The simulations of :func:`shock_margin`: every (speed, direction) one lane of one ensemble."""

    def __init__(self, subject, speeds, stable, states, horizon, rtol, atol, threads):
        from rotorlab.integrate import StepControl

        self.subject, self.speeds, self.threads = subject, speeds, threads
        self.rows = np.flatnonzero(stable == 1)
        self.states, self.horizon = states, horizon
        self.control = StepControl(rtol=rtol, atol=atol)

    def _solve(self, y0, params, t_end):
        from rotorlab.integrate import SaveAt, solve_ensemble

        sol = solve_ensemble(self.subject.sim, y0, (0.0, t_end), params=params,
                             save_at=SaveAt(ts=[float(t_end.max())]), control=self.control, threads=self.threads)
        return np.asarray(sol.y_final), np.asarray(sol.status)

    def bisect_impulse(self, bound, kicks, dist, progress):
        """Bisect the impulse magnitude of every stable (speed, direction) at once; also where the
        smallest fatal knock found left the balls (the subject's label: balanced again, a side
        motion, non-synchronous, ...)."""
        ns, nd = bound.shape
        sub = self.subject
        lanes = [(i, j) for i in self.rows for j in range(nd) if np.isfinite(bound[i, j])]
        idx = tuple(np.array(v) for v in zip(*lanes))
        params = np.array([sub.params(float(self.speeds[i])) for i, _ in lanes])
        t_end = np.array([self.horizon[i] for i, _ in lanes])
        angles = np.array([self.states[i].angles for i, _ in lanes])
        r = np.array([dist[i] for i, _ in lanes])
        lo = np.zeros(len(lanes))
        hi = BRACKET * bound[idx]
        total = BISECTIONS + 1
        om = np.array([self.speeds[i] for i, _ in lanes])
        ref = sub.reference([sub.unbalance(0.0)] * len(lanes), om)

        def fatal(mag):
            y0 = np.array([self.states[i].y for i, _ in lanes]) + kicks[idx] * mag[:, None]
            yf, status = self._solve(y0, params, t_end)
            psi, amp, rate = sub.ends(yf, t_end, om)
            moved = np.abs(psi - angles).max(axis=1)  # a ball gone round a turn is not back
            back = (status >= 0) & (moved < 0.5 * r)
            where = [sub.label(int(st), float(a), float(rf), p, float(w), float(o))
                     for st, a, rf, p, w, o in zip(status, amp, ref, psi, rate, om)]  # fmt: skip
            return ~back, status < 0, np.array(where, dtype=object)

        top, failed, outcome = fatal(hi)
        if progress is not None:
            progress(1, total)
        for step in range(BISECTIONS):
            mid = 0.5 * (lo + hi)
            f, _, where = fatal(mid)
            hi = np.where(f, mid, hi)
            lo = np.where(f, lo, mid)
            outcome = np.where(f, where, outcome)
            if progress is not None:
                progress(step + 2, total)
        simulated = np.full((ns, nd), np.nan)
        searched = np.full((ns, nd), np.nan)
        after = np.full((ns, nd), "", dtype=object)
        simulated[idx] = np.where(top & ~failed, 0.5 * (lo + hi), np.nan)
        searched[idx] = BRACKET * bound[idx]
        after[idx] = np.where(top & ~failed, outcome, "")
        return simulated, searched, after.astype(str)

    def check_shift(self, shift, beta):
        """Simulate every (speed, direction) with the unbalance shifted by (1 -+ SHIFT_CHECK) S(beta)."""
        from rotorlab.explore._outcome import SETTLE_RATE

        ns, nd = shift.shape
        sub = self.subject
        lanes = [(i, j) for i in self.rows for j in range(nd) if np.isfinite(shift[i, j])]
        om = np.array([self.speeds[i] for i, _ in lanes])
        out = []
        for factor in (1.0 - SHIFT_CHECK, 1.0 + SHIFT_CHECK):
            new = [sub.unbalance(factor * shift[i, j] * np.exp(1j * beta[j])) for i, j in lanes]
            y0 = np.array([sub.shift_start(self.states[i].y, u) for (i, _), u in zip(lanes, new)])
            params = np.array([sub.params(float(self.speeds[i]), u) for (i, _), u in zip(lanes, new)])
            t_end = np.array([self._shift_horizon(i, u) for (i, _), u in zip(lanes, new)])
            yf, status = self._solve(y0, params, t_end)
            ref = sub.reference(new, om)
            _, amp, rate = sub.ends(yf, t_end, om)
            settled = rate <= SETTLE_RATE * om
            label = np.where(amp <= SHIFT_BALANCED * ref, 1, np.where(settled, 0, -1))
            label = np.where(status >= 0, label, -1)
            grid = np.full((ns, nd), -1, dtype=np.int64)
            for (i, j), v in zip(lanes, label):
                grid[i, j] = v
            out.append(grid)
        return out[0], out[1]

    def _shift_horizon(self, i, unbalance):
        """Ten time constants of the new balanced state (capped as the basins do), else the old horizon."""
        from rotorlab.explore._settle import default_horizon

        om = float(self.speeds[i])
        bal = self.subject.balanced(om, unbalance)
        if bal is None:
            return float(self.horizon[i])
        return max(float(self.horizon[i]), default_horizon(bal.rate, om, float(self.horizon[i]))[0])


# --------------------------------------------------------------------------- case-file entry


def shock_margin_task_size(case_model: Any, analysis: Any) -> int:
    """Ensembles of a ``shock-margin`` analysis (its progress-bar total)."""
    return BISECTIONS + 1 if analysis.simulate else 1


def run_shock_margin_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None):
    """Run a case's ``shock-margin`` analysis (speeds from the spec, else the model's speed)."""
    from rotorlab.analyses._case import build_model

    model = build_model(case_model)
    speeds = analysis.speed_values(case_model)
    ds = shock_margin(model, speeds, directions=analysis.directions, simulate=analysis.simulate,
                      rtol=analysis.rtol, atol=analysis.atol, progress=progress)  # fmt: skip
    ds.attrs["name"] = analysis.name
    return ds


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def _outcome_at(ds, i: int) -> str | None:
    """Where the smallest fatal knock at the worst direction of speed ``i`` left the balls, or None."""
    b = ds.worst_impulse_direction.values[i]
    if not np.isfinite(b):
        return None
    label = str(ds.fatal_outcome.values[i, int(np.argmin(np.abs(ds.direction.values - b)))])
    return label or None


def shock_margin_rows(ds) -> list[dict[str, Any]]:
    """One row per speed: the minimal fatal impulse (bound and simulated) and load shift, worst directions."""
    from rotorlab._constants import RPM_PER_RAD_S

    rows = []
    for i, om in enumerate(ds.speed.values):
        below = ds.shift_below.values[i]
        above = ds.shift_above.values[i]
        finite = np.isfinite(ds.load_shift_bound.values[i])
        rows.append({
            "speed_rpm": float(om) * RPM_PER_RAD_S,
            "stable": bool(ds.stable.values[i]),
            "min_impulse_linear": _num(ds.min_impulse_linear.values[i]),
            "min_impulse_simulated": _num(ds.min_impulse_simulated.values[i]),
            "worst_impulse_direction_deg": _num(np.degrees(ds.worst_impulse_direction.values[i])),
            "fatal_outcome": _outcome_at(ds, i),
            "min_load_shift": _num(ds.min_load_shift.values[i]),
            "worst_shift_direction_deg": _num(np.degrees(ds.worst_shift_direction.values[i])),
            "shift_checked": int(np.sum(finite & (below == 1) & (above == 0))),
            "shift_directions": int(np.sum(finite)),
            "horizon": _num(ds.horizon.values[i]),
            "station": str(ds.attrs.get("station", "the disc centre")),
        })  # fmt: skip
    return rows
