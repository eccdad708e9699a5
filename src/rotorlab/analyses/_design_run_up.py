"""The run-up designer: design-search objectives and constraints read from run-ups of a
speed-commanded, torque-limited drive (:class:`rotorlab.models.ServoDrive`).

Each design is run up from rest from its problem's :class:`~rotorlab.design.RunUpSettings`
``starts`` ball starts (uniform random angles, the same ``seed`` for every design: common random
numbers) on the sweep engine (:func:`rotorlab.analyses._run_up_sweep.run_up_ensemble`: a store
per design, resume, Dask), once per design: the ensemble is kept in the design point's ``memo``,
which the objectives of that design share and which dies with it (no state outlives a design,
none is shared between searches). The objectives
(registered in :data:`rotorlab.design.DESIGN_OBJECTIVES`):

``run-up-time``
    The time (s) the slowest start takes to reach ``REACHED`` (99 %) of the drive's operating
    speed; ``inf`` (infeasible) if any start is captured at a critical speed or never gets there.
``run-up-peak``
    The largest transient peak at a critical speed over the starts (m); bound it with
    ``limits``.
``run-up-unbalanced``
    One minus the Wilson lower bound (95 %) of P(balanced) at the end of the run-up; the limit
    0.01 is "P(balanced) >= 0.99 at 95 % confidence" (it needs >= 380 starts, all balanced).

and the constraint ``no-housing-contact`` (:data:`rotorlab.design.DESIGN_CONSTRAINTS`,
:func:`housing_margin`).

A run lasts ``SETTLE`` (3) times the longer of the command's duration and the torque-limited
ramp ``J (W_op - W_0) / T_max(0)``, plus the settings' ``settle`` (s, ``--settle``), so the balls
have time to settle at the operating speed (a run still settling at its end is "not settled",
never balanced).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["REACHED", "run_up_of", "reach_times", "run_up_time", "run_up_peak", "run_up_unbalanced", "run_up_t_end",
           "housing_margin", "no_servo_drive", "no_housing_run_up", "design_run_up"]

#: A run-up has reached the operating speed at this fraction of it.
REACHED = 0.99
#: The run lasts this many times the nominal run-up.
SETTLE = 3.0

_NEEDS_SERVO = "needs a machine driven by a ServoDrive ([model.drive] profile = \"servo\")"


def no_servo_drive(model) -> str | None:
    """Why a model's run-ups cannot be designed (None: it has a servo drive)."""
    d = getattr(model, "drive", None)
    return None if d is not None and hasattr(d, "command_duration") else _NEEDS_SERVO


def no_housing_run_up(model) -> str | None:
    """Why ``no-housing-contact`` cannot apply (None: a servo-driven machine with a clearance)."""
    if not getattr(model, "clearances", ()):
        return "needs a machine with a clearance ([[model.clearances]]): this one has none, so it cannot touch"
    return no_servo_drive(model)


def _drive(model):
    why = no_servo_drive(model)
    if why is not None:
        raise ValueError(f"the run-up objectives {why}")
    return model.drive


def run_up_t_end(model, settings) -> float:
    """The horizon of a design's run-ups (s), ``settings`` a :class:`~rotorlab.design.RunUpSettings`."""
    d = _drive(model)
    limit = max(float(d.stall_torque), 1e-300)
    nominal = max(d.command_duration, d.polar_inertia * (d.operating_speed - d.initial_speed) / limit)
    return SETTLE * nominal + float(settings.settle)


def run_up_of(point):
    """The run-ups of a design point (computed once per point, in-process unless the design search
    ran them on the sweep engine): a Dataset over ``start``
    (:func:`rotorlab.analyses._run_up_sweep.run_up_ensemble`)."""
    from rotorlab.analyses._run_up_sweep import run_up_ensemble

    if "run_up" not in point.memo:
        _drive(point.model)
        point.memo["run_up"] = run_up_ensemble(point.model, point.run_up)
    return point.memo["run_up"]


def reach_times(model, ds) -> np.ndarray:
    """Per run-up of ``ds`` (over ``ic``, with ``time`` and ``speed``): when it reached
    :data:`REACHED` of the operating speed (s, interpolated between saves; inf: never)."""
    target = REACHED * _drive(model).operating_speed
    t = np.asarray(ds["time"].values, dtype=float)
    w = np.asarray(ds["speed"].values, dtype=float).reshape(-1, t.size)
    out = np.full(w.shape[0], math.inf)
    for k, row in enumerate(w):
        hit = np.nonzero(row >= target)[0]
        if hit.size:
            i = hit[0]
            out[k] = t[i] if i == 0 else t[i - 1] + (target - row[i - 1]) * (t[i] - t[i - 1]) / (row[i] - row[i - 1])
    return out


def run_up_time(point) -> float:
    """Time (s) the slowest start needs to reach 99 % of the operating speed; ``inf`` when a start
    is captured (or failed, or never gets there)."""
    ds = run_up_of(point)
    if np.any(np.isfinite(np.asarray(ds["captured_at"].values, dtype=float))) or np.any(ds["status"].values < 0):
        return math.inf
    return float(np.max(ds["reach_time"].values))


def run_up_peak(point) -> float:
    """Largest transient peak at a critical speed over the starts (m); ``inf`` if none passed."""
    peaks = np.asarray(run_up_of(point)["critical_peak"].values, dtype=float)
    return float(np.nanmax(peaks)) if np.any(np.isfinite(peaks)) else math.inf


def run_up_unbalanced(point) -> float:
    """One minus the Wilson lower bound (95 %) of P(balanced) at the run-up's end (1)."""
    from rotorlab._wilson import wilson_interval

    ds = run_up_of(point)
    runs = int(np.sum(~np.asarray(ds["failed"].values, dtype=bool)))
    if not runs:
        return 1.0
    return float(1.0 - wilson_interval(int(np.sum(np.asarray(ds["balanced"].values, dtype=bool))), runs, 0.95)[0])


def housing_margin(point) -> float:
    """Margin of ``no-housing-contact`` (1): ``(gap - d_max) / gap``, ``d_max`` the largest distance
    of the clearance station from the stator's centre over every saved state of every run-up;
    where a run-up touched (an impact or sustained contact recorded, or ``d_max >= gap``) minus
    the share of run-ups that touched; a failed run-up counts as touched (nothing is known)."""
    ds = run_up_of(point)
    gap = float(ds.attrs["gap"])
    worst = np.asarray(ds["clearance_far"].values, dtype=float)
    touched = (np.asarray(ds["impacts"].values, dtype=float) > 0) | ~(worst < gap) | (ds["status"].values < 0)
    if touched.any():
        return -float(np.mean(touched))
    return float((gap - np.max(worst)) / gap)


def design_run_up(case_model, variables, *, peak_limit=None, min_balanced=None, starts=400, seed=0, settle=0.0, budget=20,
                  optimizer="tpe", optimizer_seed=0, check=None, constraints=()) -> dict[str, Any]:
    """The run-up designer on a case's machine: the design search minimising ``run-up-time`` with
    the limits ``run-up-peak`` <= ``peak_limit`` and ``run-up-unbalanced`` <= 1 - ``min_balanced``
    (default 0.99 with balls) and the named ``constraints`` (:data:`rotorlab.design.DESIGN_CONSTRAINTS`),
    each run-up ``settle`` s longer; ``check(starts, min_balanced)`` may refuse too few starts. The
    settings travel with the problem (:class:`~rotorlab.design.RunUpSettings`): two calls never
    share them.

    Returns a JSON-ready dict: ``best`` (values, SI; None if no design is feasible),
    ``run_up_time`` (s), ``margins`` (>= 0: the limit holds), ``limits``, ``designs``.
    """
    from rotorlab.analyses._case import build_model
    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search
    from rotorlab.design import RunUpSettings

    model = build_model(case_model)
    _drive(model)
    if min_balanced is None and model.n_balls:
        min_balanced = 0.99
    limits = {}
    if peak_limit is not None:
        limits["run-up-peak"] = float(peak_limit)
    if min_balanced is not None:
        if not model.n_balls:
            raise ValueError("--min-balanced: this machine has no balls (nothing balances)")
        if check is not None:
            check(starts, min_balanced)
        limits["run-up-unbalanced"] = 1.0 - float(min_balanced)
    vs = tuple(DesignVariable(k, lo, hi) for k, (lo, hi) in variables.items())
    try:
        problem = DesignProblem(model, vs, ("run-up-time",), np.array([_drive(model).operating_speed]),
                                limits=limits, constraints=tuple(constraints),
                                run_up=RunUpSettings(starts=int(starts), seed=int(seed), settle=float(settle)))
    except ValueError as exc:
        raise ValueError(str(exc).replace("vary.", "--vary ").replace("constraints: ", "--constraint ")) from None
    ds = design_search(problem, optimizer=optimizer, budget=budget, optimizer_seed=optimizer_seed, verify=False)
    names = [str(n) for n in ds["variable"].values] if "variable" in ds.coords else list(variables)
    best = np.flatnonzero(ds["pareto"].values & ds["feasible"].values)
    doc: dict[str, Any] = {"designs": int(ds.sizes["trial"]), "limits": limits, "best": None, "run_up_time": None,
                           "margins": None}
    if best.size:
        k = int(best[0])
        doc["best"] = {n: float(v) for n, v in zip(names, ds["value"].values[k])}
        doc["run_up_time"] = float(ds["objective_value"].values[k, 0])
        doc["margins"] = {str(c): float(v) for c, v in zip(ds["constraint"].values, ds["margin"].values[k])} \
            if "constraint" in ds.coords else {}
    return doc
