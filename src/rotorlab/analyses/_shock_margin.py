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
    where two neighbouring balls meet: from the balanced state it is ``r = min_{i<j}
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


def _meeting_distance(angles: np.ndarray) -> float:
    """r: half the smallest angular gap between two balls (pi for one ball), rad."""
    n = angles.size
    if n < 2:
        return math.pi
    gaps = [abs(float(np.pi - np.mod(np.pi - (angles[i] - angles[j]), 2 * np.pi))) for i in range(n)
            for j in range(i + 1, n)]  # fmt: skip
    return 0.5 * min(gaps)


def linear_impulse(lin, angles, directions) -> tuple[np.ndarray, float, np.ndarray]:
    """The linearised-basin impulse ``I_lin(beta)`` (N s) of the module docstring.

    Parameters
    ----------
    lin : Linearization
        Of the rotating-frame model about the balanced state (asymptotically stable).
    angles : array_like, shape (n,)
        Balanced ball angles (rad).
    directions : array_like, shape (k,)
        beta (rad, co-rotating frame, from the unbalance).

    Returns
    -------
    bound : ndarray, shape (k,)
        ``r / g(beta)`` (N s).
    r : float
        Distance to the side motion where two balls meet (rad).
    kick : ndarray, shape (k, 2 + n)
        ``M^-1 e_beta``: the jump of ``(u', v', psi_i')`` per N s (m/s, rad/s per N s).
    """
    angles = np.asarray(angles, dtype=float)
    beta = np.asarray(directions, dtype=float)
    n = angles.size
    k = 2 + n
    minv = np.linalg.inv(lin.M)
    lam, vec = np.linalg.eig(lin.A)
    decay = -float(lam.real.max())
    fast = float(np.abs(lam).max())
    t_end = min(12.0 / decay, 4000.0 * 2.0 * math.pi / fast)
    ts = np.linspace(0.0, t_end, int(min(200_000, max(2000, 40.0 * t_end * fast / (2.0 * math.pi)))))
    inv = np.linalg.inv(vec)
    rows = []
    for unit in (np.eye(k)[0], np.eye(k)[1]):
        dq = minv @ unit
        x0 = np.zeros(2 * k)  # the model's state order: u, v, u', v', psi_i, psi_i'
        x0[2:4], x0[4 + n :] = dq[:2], dq[2:]
        coef = inv @ x0
        psi = (vec[4 : 4 + n, :][None, :, :] * np.exp(np.outer(ts, lam))[:, None, :]) @ coef
        rows.append(psi.real)  # (t, n)
    cu, su = np.cos(beta), np.sin(beta)
    resp = cu[:, None, None] * rows[0][None] + su[:, None, None] * rows[1][None]  # (k, t, n)
    g = np.abs(resp).max(axis=(1, 2))
    r = _meeting_distance(angles)
    kick = (minv[:, :2] @ np.vstack([cu, su])).T
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
    model : JeffcottBalls
        Without Coulomb friction (its balanced state is an isolated equilibrium).
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

    from rotorlab.explore._settle import default_horizon, slowest_decay_rate
    from rotorlab.models import ConstantSpeed

    if model.n_balls == 0 or model.has_friction:
        raise ValueError("shock_margin needs balls without Coulomb friction (friction = 0)")
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds) & (speeds > 0)):
        raise ValueError(f"speeds must be one or more finite numbers > 0 (rad/s), got {speeds!r}")
    if isinstance(directions, bool) or int(directions) != directions or directions < 1:
        raise ValueError(f"directions must be an integer >= 1, got {directions!r}")
    beta = np.linspace(0.0, 2.0 * math.pi, int(directions), endpoint=False)
    ns, nd, n = speeds.size, beta.size, model.n_balls
    rot = model.with_frame("rotating").with_speed(ConstantSpeed(float(speeds[0])))
    moments = np.array([b.static_moment for b in model.balls])
    shift = np.tile(load_shift_bound(model.imbalance, moments, beta), (ns, 1))
    bound = np.full((ns, nd), np.nan)
    stable = np.zeros(ns, dtype=np.int64)
    decay, horizon, dist = np.full(ns, np.nan), np.full(ns, np.nan), np.full(ns, np.nan)
    start = np.full((ns, rot.n_state), np.nan)
    kicks = np.full((ns, nd, 2 + n), np.nan)
    for i, om in enumerate(speeds):
        angles = balanced_angles(rot, float(om))
        if angles is None:
            continue
        y_eq = rot.initial_state(angles)
        lin = rot.linearize(y_eq, float(om))
        rate = slowest_decay_rate(lin.eigenvalues)
        if rate is None:
            continue
        stable[i], decay[i] = 1, rate
        horizon[i] = default_horizon(rate, float(om), 20.0)[0]
        bound[i], dist[i], kicks[i] = linear_impulse(lin, angles, beta)
        start[i] = y_eq
    shift = np.where(stable[:, None] == 1, shift, np.nan)
    simulated = np.full((ns, nd), np.nan)
    searched = np.full((ns, nd), np.nan)
    after = np.full((ns, nd), "", dtype=object).astype(str)
    below = np.full((ns, nd), -1, dtype=np.int64)
    above = np.full((ns, nd), -1, dtype=np.int64)
    if simulate and stable.any():
        ctx = _Lanes(rot, speeds, stable, start, horizon, rtol, atol, threads)
        simulated, searched, after = ctx.bisect_impulse(bound, kicks, dist, progress)
        below, above = ctx.check_shift(shift, beta, moments)
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
        attrs={"critical_speed": float(model.critical_speed), "imbalance": float(model.imbalance),
               "capacity": float(moments.sum()), "simulated": int(bool(simulate)), "bisections": BISECTIONS,
               "bracket": BRACKET, "shift_check": SHIFT_CHECK},
    )  # fmt: skip
    return ds


class _Lanes:
    """The simulations of :func:`shock_margin`: every (speed, direction) one lane of one ensemble."""

    def __init__(self, rot, speeds, stable, start, horizon, rtol, atol, threads):
        from rotorlab.integrate import StepControl

        self.rot, self.speeds, self.threads = rot, speeds, threads
        self.rows = np.flatnonzero(stable == 1)
        self.start, self.horizon = start, horizon
        self.control = StepControl(rtol=rtol, atol=atol)

    def _solve(self, y0, params, t_end):
        from rotorlab.integrate import SaveAt, solve_ensemble

        return solve_ensemble(self.rot, y0, (0.0, t_end), params=params, save_at=SaveAt(ts=[float(t_end.max())]),
                              control=self.control, threads=self.threads)  # fmt: skip

    def _params(self, i, **extra):
        return self.rot.pack({"speed.speed": float(self.speeds[i]), **extra})

    def bisect_impulse(self, bound, kicks, dist, progress):
        """Bisect the impulse magnitude of every stable (speed, direction) at once; also where the
        smallest fatal knock found left the balls (:func:`rotorlab.explore._outcome.classify`)."""
        from rotorlab.explore._outcome import classify, reference_amplitude

        ns, nd = bound.shape
        n = self.rot.n_balls
        lanes = [(i, j) for i in self.rows for j in range(nd) if np.isfinite(bound[i, j])]
        idx = tuple(np.array(v) for v in zip(*lanes))
        params = np.array([self._params(i) for i, _ in lanes])
        t_end = np.array([self.horizon[i] for i, _ in lanes])
        angles = np.array([self.start[i, 4 : 4 + n] for i, _ in lanes])
        r = np.array([dist[i] for i, _ in lanes])
        lo = np.zeros(len(lanes))
        hi = BRACKET * bound[idx]
        total = BISECTIONS + 1

        om = np.array([self.speeds[i] for i, _ in lanes])
        rotor = self.rot.rotor
        ref = reference_amplitude(rotor.imbalance, rotor.stiffness, self.rot.total_mass, rotor.damping, om)

        def fatal(mag):
            y0 = np.array([self.start[i] for i, _ in lanes])
            dq = kicks[idx] * mag[:, None]
            y0[:, 2:4] += dq[:, :2]
            y0[:, 4 + n : 4 + 2 * n] += dq[:, 2:]
            sol = self._solve(y0, params, t_end)
            yf, status = np.asarray(sol.y_final), np.asarray(sol.status)
            back = (status >= 0) & (np.abs(yf[:, 4 : 4 + n] - angles).max(axis=1) < 0.5 * r)
            where = [classify(int(st), "", float(np.hypot(y[0], y[1])), float(rf), y[4 : 4 + n],
                              float(np.abs(y[4 + n : 4 + 2 * n]).max()), float(w))
                     for st, y, rf, w in zip(status, yf, ref, om)]  # fmt: skip
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

    def check_shift(self, shift, beta, moments):
        """Simulate every (speed, direction) with the unbalance shifted by (1 -+ SHIFT_CHECK) S(beta)."""
        from rotorlab.explore._outcome import SETTLE_RATE, reference_amplitude

        ns, nd = shift.shape
        n = self.rot.n_balls
        rotor = self.rot.rotor
        lanes = [(i, j) for i in self.rows for j in range(nd) if np.isfinite(shift[i, j])]
        out = []
        for factor in (1.0 - SHIFT_CHECK, 1.0 + SHIFT_CHECK):
            new = np.array([rotor.imbalance + factor * shift[i, j] * np.exp(1j * beta[j]) for i, j in lanes])
            y0 = np.array([self.start[i] for i, _ in lanes])
            y0[:, 4 : 4 + n] -= np.angle(new)[:, None]  # angles from the new unbalance direction
            params = np.array([self._params(i, eccentricity=abs(u) / rotor.disc_mass) for (i, _), u in zip(lanes, new)])
            t_end = np.array([self._shift_horizon(i, abs(u), moments) for (i, _), u in zip(lanes, new)])
            sol = self._solve(y0, params, t_end)
            yf = np.asarray(sol.y_final)
            om = np.array([self.speeds[i] for i, _ in lanes])
            ref = reference_amplitude(np.abs(new), rotor.stiffness, self.rot.total_mass, rotor.damping, om)
            amp = np.hypot(yf[:, 0], yf[:, 1])
            settled = np.abs(yf[:, 4 + n : 4 + 2 * n]).max(axis=1) <= SETTLE_RATE * om
            label = np.where(amp <= SHIFT_BALANCED * ref, 1, np.where(settled, 0, -1))
            label = np.where(np.asarray(sol.status) >= 0, label, -1)
            grid = np.full((ns, nd), -1, dtype=np.int64)
            for (i, j), v in zip(lanes, label):
                grid[i, j] = v
            out.append(grid)
        return out[0], out[1]

    def _shift_horizon(self, i, new_imbalance, moments):
        """Ten time constants of the new balanced state (capped as the basins do), else the old horizon."""
        from dataclasses import replace

        from rotorlab.explore._settle import default_horizon, slowest_decay_rate

        om = float(self.speeds[i])
        shifted = replace(self.rot, rotor=replace(self.rot.rotor, eccentricity=new_imbalance / self.rot.rotor.disc_mass))
        angles = balanced_angles(shifted, om)
        if angles is None:
            return float(self.horizon[i])
        rate = slowest_decay_rate(shifted.linearize(shifted.initial_state(angles), om).eigenvalues)
        return max(float(self.horizon[i]), default_horizon(rate, om, float(self.horizon[i]))[0])


# --------------------------------------------------------------------------- case-file entry


def shock_margin_task_size(case_model: Any, analysis: Any) -> int:
    """Ensembles of a ``shock-margin`` analysis (its progress-bar total)."""
    return BISECTIONS + 1 if analysis.simulate else 1


def run_shock_margin_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None):
    """Run a case's ``shock-margin`` analysis (speeds from the spec, else the model's speed)."""
    from rotorlab.analyses._builders import jeffcott_balls_model

    model = jeffcott_balls_model(case_model)
    speeds = analysis.speed_values(case_model, model.critical_speed)
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
        })  # fmt: skip
    return rows
