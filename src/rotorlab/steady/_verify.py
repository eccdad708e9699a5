"""Check the predicted steady motions by simulation: basin fractions from a grid of ball starts.

For each speed the steady motions and their stability are predicted (:func:`analyze_steady`);
then every start (rotor at rest on the axis, balls at rest relative to it at the grid angles) is
integrated in the co-rotating frame with :func:`rotorlab.integrate.solve_ensemble`, and its final
state is matched to a predicted motion. The fraction of starts reaching a motion is that motion's
basin fraction; starts that never settle (balls lagging behind the rotor, non-synchronous whirl)
or settle elsewhere are counted apart.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.steady._analysis import analyze_steady
from rotorlab.steady._motions import motion_labels, wrap
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls
    from rotorlab.steady._analysis import SteadyAnalysis

__all__ = ["verify", "ball_grid", "match_state", "typical_deflection", "OTHER_OUTCOMES"]

#: Outcomes of a start that reaches no predicted motion.
OTHER_OUTCOMES = ("non-synchronous", "other", "failed")
_METHODS = ("hamilton", "averaged", "exact")


def ball_grid(n_balls: int, points: int) -> np.ndarray:
    """Return a grid of start angles, ``points`` per ball, shape (points^n, n) (rad).

    Ball i uses ``-pi + (k + 1/2 + i / (2 n)) 2 pi / points``, k = 0..points-1: the offsets keep
    every start off the invariant sets (two equal balls together, all balls on the unbalance
    line) on which a trajectory could end on a motion that is unstable in the full space.

    Examples
    --------
    >>> ball_grid(2, 2).round(3)
    array([[-1.571, -0.785],
           [-1.571,  2.356],
           [ 1.571, -0.785],
           [ 1.571,  2.356]])
    """
    if points < 1 or n_balls < 1:
        raise ValueError(f"points and n_balls must be >= 1, got {points}, {n_balls}")
    h = 2.0 * math.pi / points
    axes = [-math.pi + (np.arange(points) + 0.5 + i / (2.0 * n_balls)) * h for i in range(n_balls)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, n_balls)


def typical_deflection(model: JeffcottBalls, spin_speed: float) -> float:
    """Return ``Omega^2 (M1 e + sum m_i l_i) / |c - M Omega^2 + i d Omega|``, a deflection scale (m)."""
    r = model.rotor
    den = abs(complex(r.stiffness - model.total_mass * spin_speed**2, r.damping * spin_speed))
    scale = spin_speed**2 * (model.imbalance + model.capacity) / max(den, 1e-300)
    return scale if scale > 0 else 1.0


def match_state(analysis: SteadyAnalysis, state, scale: float, *, angle_tol: float = 0.05,
                deflection_tol: float = 0.05) -> str | None:  # fmt: skip
    """Return the label of the predicted steady motion a settled state sits on, or None.

    Parameters
    ----------
    analysis : SteadyAnalysis
        Predictions at the state's speed.
    state : array_like, shape (4 + 2 n,)
        Co-rotating state ``[u, v, du, dv, psi_i, dpsi_i]``.
    scale : float
        Deflection scale (m), :func:`typical_deflection`.
    angle_tol : float
        Largest ball-angle difference to an isolated motion (rad).
    deflection_tol : float
        Largest deflection difference, as a fraction of ``scale``; a family member also needs
        ``|U| <= deflection_tol * 0.2 (M1 e + sum m_i l_i)``.

    Returns
    -------
    str or None
    """
    y = np.asarray(state, dtype=float)
    n = (y.size - 4) // 2
    psi = y[4 : 4 + n]
    z = complex(y[0], y[1])
    best, best_d = None, math.inf
    for m in analysis.motions:
        if not m.exists:
            continue
        if abs(z - m.deflection) > deflection_tol * scale:
            continue
        if m.dimension > 0:
            unb = abs(analysis.imbalance + np.sum(analysis.moments * np.exp(1j * psi)))
            if unb <= 0.2 * deflection_tol * (analysis.imbalance + analysis.capacity):
                return m.label
            continue
        d = float(np.max(np.abs(wrap(psi - m.ball_angles)))) if n else 0.0
        if d <= angle_tol and d < best_d:
            best, best_d = m.label, d
    return best


def _auto_t_end(analysis: SteadyAnalysis) -> float:
    """40 e-folding times of the slowest exactly stable motion, within 300-6000 revolutions (s)."""
    period = 2.0 * math.pi / analysis.spin_speed
    rates = [-m.stability.growth_rate for m in analysis.motions if m.exists and m.stability.exact == "stable"]
    t = 40.0 / min(rates) if rates else 0.0
    return float(min(max(t, 300.0 * period), 6000.0 * period))


def _consistent(outcome: str, method: str, analysis: SteadyAnalysis) -> bool:
    stable = analysis.stable(method)
    if outcome in OTHER_OUTCOMES:
        return outcome == "non-synchronous" and not stable
    return outcome in stable


def verify(model: JeffcottBalls, speeds: Any, *, points: int = 8, initial_ball_angles: Any = None,
           t_end: Any = None, settle_revolutions: float = 20.0, rate_tol: float = 1e-5,
           angle_tol: float = 0.05, rtol: float = 1e-8, atol: float = 1e-11, family_samples: int = 12,
           threads: int | None = None) -> xarray.Dataset:  # fmt: skip
    """Integrate a grid of ball starts to steady state and match each end to a predicted motion.

    Parameters
    ----------
    model : JeffcottBalls
        Rotor and balls, without Coulomb friction (any frame; the speed profile is replaced).
    speeds : array_like, shape (n_speed,)
        Constant spin speeds Omega (rad/s), > 0.
    points : int
        Grid points per ball (:func:`ball_grid`), used when ``initial_ball_angles`` is None.
    initial_ball_angles : array_like, shape (n_ic, n), optional
        Start angles psi_i (rad), instead of the grid.
    t_end : float or array_like, shape (n_speed,), optional
        Simulated time per speed (s); default 40 e-folding times of the slowest exactly stable
        motion, kept within 300-6000 revolutions.
    settle_revolutions : float
        Length of the final window in which a start must be at rest in the co-rotating frame.
    rate_tol : float
        At rest: every ``|psi_i'|`` and ``|(u', v')|`` / (deflection scale) below ``rate_tol * Omega``.
    angle_tol : float
        Ball-angle tolerance of the match (rad), see :func:`match_state`.
    rtol, atol : float
        Integrator tolerances.
    family_samples : int
        Samples per free angle of a family of main motions.
    threads : int, optional
        Threads of the ensemble integrator (results do not depend on it).

    Returns
    -------
    xarray.Dataset
        Dims ``speed``, ``ic``, ``ball``, ``motion`` and ``outcome`` (the motion labels, then
        ``"non-synchronous"``, ``"other"`` (settled on no predicted motion) and ``"failed"``).
        Variables: ``initial_ball_angle`` (ic, ball; rad), ``final_ball_angle`` (speed, ic, ball;
        rad), ``final_amplitude`` (m), ``final_rate`` (largest ``|psi_i'|`` / Omega in the window),
        ``mean_ball_speed`` (speed, ic, ball; absolute ball speed Omega + mean psi_i' over the
        window, rad/s: about p for balls captured in a non-synchronous whirl),
        ``status``, ``reached`` (label or other outcome), ``fraction`` (speed, outcome; the basin
        fraction of each motion), ``exists`` and ``stable_hamilton`` / ``stable_averaged`` /
        ``stable_exact`` (speed, motion), ``consistent_<method>`` (speed, ic: the start ended as the
        method predicts: on a motion it calls stable, or unsettled where it predicts none) and
        ``agrees_<method>`` (speed: every start consistent), ``t_end`` (s).

    Raises
    ------
    ValueError
        Friction in the model, bad speeds or angles.

    Notes
    -----
    Starts: the disc centre at rest on the axis, the balls at rest relative to the rotor. A start
    counts as settled when, over the last ``settle_revolutions`` revolutions, it is at rest in the
    co-rotating frame; it is then matched by :func:`match_state`.

    Examples
    --------
    Seed 002's case with enough capacity, twice the critical speed: every start balances.

    >>> from rotorlab.steady import steady_case
    >>> case = steady_case("zhakash-k2")
    >>> ds = verify(case.model("enough"), [2.0 * case.critical_speed()], points=2, t_end=10.0)
    >>> sorted(str(r) for r in set(ds.reached.values.ravel())), bool(ds.agrees_exact.values[0])
    (['main+', 'main-'], True)
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
    from rotorlab.models import ConstantSpeed

    if model.has_friction:
        raise ValueError("verify needs a model without Coulomb friction (set friction=0)")
    om_all = np.atleast_1d(np.asarray(speeds, dtype=float))
    if om_all.ndim != 1 or om_all.size == 0 or not np.all(np.isfinite(om_all)) or np.any(om_all <= 0):
        raise ValueError(f"speeds must be finite numbers > 0 (rad/s), got {speeds!r}")
    n = model.n_balls
    if initial_ball_angles is None:
        angles = ball_grid(n, int(points))
    else:
        angles = np.asarray(initial_ball_angles, dtype=float).reshape(-1, n)
        if angles.shape[0] == 0 or not np.all(np.isfinite(angles)):
            raise ValueError("initial_ball_angles must be finite, shape (n_ic, n_balls) (rad)")
    ends = None if t_end is None else np.broadcast_to(np.asarray(t_end, dtype=float), om_all.shape)
    labels = motion_labels(n)
    outcomes = labels + OTHER_OUTCOMES
    n_sp, n_ic = om_all.size, angles.shape[0]
    final_angle = np.full((n_sp, n_ic, n), np.nan)
    final_amp = np.full((n_sp, n_ic), np.nan)
    final_rate = np.full((n_sp, n_ic), np.nan)
    ball_speed = np.full((n_sp, n_ic, n), np.nan)
    status = np.zeros((n_sp, n_ic), dtype=np.int32)
    reached = np.empty((n_sp, n_ic), dtype=object)
    fraction = np.zeros((n_sp, len(outcomes)))
    exists = np.zeros((n_sp, len(labels)), dtype=bool)
    stable = {m: np.zeros((n_sp, len(labels)), dtype=bool) for m in _METHODS}
    consistent = {m: np.zeros((n_sp, n_ic), dtype=bool) for m in _METHODS}
    t_used = np.empty(n_sp)
    control = StepControl(rtol=float(rtol), atol=float(atol))
    for k, om in enumerate(om_all):
        rot = model.with_speed(ConstantSpeed(float(om))).with_frame("rotating")
        analysis = analyze_steady(rot, float(om), family_samples=family_samples)
        t1 = _auto_t_end(analysis) if ends is None else float(ends[k])
        t_used[k] = t1
        window = min(settle_revolutions * 2.0 * math.pi / om, 0.5 * t1)
        y0 = np.array([rot.initial_state(row) for row in angles])
        sol = solve_ensemble(rot, y0, (0.0, t1), save_at=SaveAt(ts=np.linspace(t1 - window, t1, 9)),
                             control=control, threads=threads)  # fmt: skip
        scale = typical_deflection(rot, float(om))
        for j, lab in enumerate(labels):
            m = analysis.motion(lab)
            exists[k, j] = m.exists
            for meth in _METHODS:
                stable[meth][k, j] = m.stability.is_stable(meth)
        for i in range(n_ic):
            status[k, i] = sol.status[i]
            yf = sol.y_final[i]
            final_angle[k, i] = wrap(yf[4 : 4 + n])
            final_amp[k, i] = math.hypot(yf[0], yf[1])
            ys = sol.ys[i]
            ball_rate = float(np.max(np.abs(ys[:, 4 + n :]))) if n else 0.0
            rotor_rate = float(np.max(np.hypot(ys[:, 2], ys[:, 3]))) / scale
            final_rate[k, i] = ball_rate / om
            if sol.status[i] >= 0:  # absolute ball speed, averaged over the window (angles unwrapped)
                ball_speed[k, i] = om + (ys[-1, 4 : 4 + n] - ys[0, 4 : 4 + n]) / window
            if sol.status[i] < 0:
                out = "failed"
            elif max(ball_rate, rotor_rate) > rate_tol * om:
                out = "non-synchronous"
            else:
                out = match_state(analysis, yf, scale, angle_tol=angle_tol) or "other"
            reached[k, i] = out
            fraction[k, outcomes.index(out)] += 1.0 / n_ic
            for meth in _METHODS:
                consistent[meth][k, i] = _consistent(out, meth, analysis)
    p = model.critical_speed
    sic, smo = ("speed", "ic"), ("speed", "motion")
    data = {
        "initial_ball_angle": (("ic", "ball"), angles, {"units": "rad", "long_name": "start angle"}),
        "final_ball_angle": (("speed", "ic", "ball"), final_angle, {"units": "rad", "long_name": "final ball angle"}),
        "final_amplitude": (sic, final_amp, {"units": "m", "long_name": "final shaft deflection"}),
        "final_rate": (sic, final_rate, {"units": "1", "long_name": "largest |ball rate| / Omega, final window"}),
        "mean_ball_speed": (("speed", "ic", "ball"), ball_speed,
                            {"units": "rad/s", "long_name": "absolute ball speed, mean over the final window"}),
        "status": (sic, status, {"units": "1", "long_name": "integrator status"}),
        "reached": (sic, reached.astype(str), {"units": "1", "long_name": "motion reached"}),
        "fraction": (("speed", "outcome"), fraction, {"units": "1", "long_name": "basin fraction"}),
        "exists": (smo, exists, {"units": "1", "long_name": "motion exists"}),
        "t_end": (("speed",), t_used, {"units": "s", "long_name": "simulated time"}),
    }  # fmt: skip
    for meth in _METHODS:
        data[f"stable_{meth}"] = (smo, stable[meth], {"units": "1", "long_name": f"stable ({meth})"})
        data[f"consistent_{meth}"] = (sic, consistent[meth], {"units": "1", "long_name": f"end as {meth} predicts"})
        data[f"agrees_{meth}"] = (("speed",), consistent[meth].all(axis=1),
                                  {"units": "1", "long_name": f"every start as {meth} predicts"})  # fmt: skip
    return xr.Dataset(
        data,
        coords={
            "speed": ("speed", om_all, {"units": "rad/s", "long_name": "spin speed"}),
            "speed_rpm": ("speed", om_all * _RPM, {"units": "rpm"}),
            "speed_ratio": ("speed", om_all / p, {"units": "1", "long_name": "omega / p"}),
            "ic": ("ic", np.arange(n_ic), {"units": "1"}),
            "ball": ("ball", np.arange(1, n + 1), {"units": "1"}),
            "motion": ("motion", list(labels), {"units": "1"}),
            "outcome": ("outcome", list(outcomes), {"units": "1"}),
        },
        attrs={
            "analysis": "verify", "model": "jeffcott_balls", "integration_frame": "rotating",
            "critical_speed": p, "settle_revolutions": settle_revolutions, "rate_tol": rate_tol,
            "angle_tol": angle_tol, "rtol": float(rtol), "atol": float(atol),
        },  # fmt: skip
    )
