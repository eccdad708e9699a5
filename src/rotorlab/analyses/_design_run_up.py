"""The run-up designer: design-search objectives read from run-ups of a speed-commanded,
torque-limited drive (:class:`rotorlab.models.ServoDrive`).

Each design is run up from rest from :data:`SETTINGS` ``n_starts`` ball starts (uniform random
angles, the same ``seed`` for every design: common random numbers) with
:func:`rotorlab.analyses._machine_run_up.run_up_starts`, once per design (the objectives share
the ensemble). The objectives (registered in :data:`rotorlab.design.DESIGN_OBJECTIVES`):

``run-up-time``
    The time (s) the slowest start takes to reach ``REACHED`` (99 %) of the drive's operating
    speed; ``inf`` (infeasible) if any start is captured at a critical speed or never gets there.
``run-up-peak``
    The largest transient peak at a critical speed over the starts (m); bound it with
    ``limits``.
``run-up-unbalanced``
    One minus the Wilson lower bound (95 %) of P(balanced) at the end of the run-up; the limit
    0.01 is "P(balanced) >= 0.99 at 95 % confidence" (it needs >= 380 starts, all balanced).

A run lasts ``SETTLE`` (3) times the longer of the command's duration and the torque-limited
ramp ``J (W_op - W_0) / T_max(0)``, plus ``SETTINGS["settle"]`` (s, ``--settle``), so the balls
have time to settle at the operating speed (a run still settling at its end is "not settled",
never balanced).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["SETTINGS", "REACHED", "run_up_of", "run_up_time", "run_up_peak", "run_up_unbalanced", "run_up_t_end"]

#: Starts per design and their seed (common random numbers across designs).
SETTINGS: dict[str, float] = {"n_starts": 400, "seed": 0, "n_save": 2000, "settle": 0.0}
#: A run-up has reached the operating speed at this fraction of it.
REACHED = 0.99
#: The run lasts this many times the nominal run-up.
SETTLE = 3.0

_CACHE: dict[str, Any] = {}


def _drive(model):
    d = getattr(model, "drive", None)
    if d is None or not hasattr(d, "command_duration"):
        raise ValueError("the run-up objectives need a machine driven by a ServoDrive "
                         "([model.drive] profile = \"servo\")")
    return d


def run_up_t_end(model) -> float:
    """The horizon of a design's run-ups (s)."""
    d = _drive(model)
    limit = max(float(d.stall_torque), 1e-300)
    nominal = max(d.command_duration, d.polar_inertia * (d.operating_speed - d.initial_speed) / limit)
    return SETTLE * nominal + SETTINGS["settle"]


def run_up_of(model):
    """The run-up ensemble of a design (cached for the last design): a Dataset over ``ic``."""
    from rotorlab.analyses._machine_run_up import run_up_starts

    d = _drive(model)
    key = (type(model).__name__, model.layout.key if hasattr(model.layout, "key") else repr(model.layout),
           model.to_array().tobytes(), tuple(sorted(SETTINGS.items())), run_up_t_end(model))
    if _CACHE.get("key") != key:
        rng = np.random.default_rng(SETTINGS["seed"])
        n = model.n_balls
        starts = [tuple(rng.uniform(0.0, 2 * np.pi, n)) for _ in range(SETTINGS["n_starts"])] if n else [None]
        _CACHE.update(key=key, ds=run_up_starts(model, starts, t_end=run_up_t_end(model),
                                                n_save=SETTINGS["n_save"], initial_speed=d.initial_speed))
    return _CACHE["ds"]


def _reach_times(model, ds) -> np.ndarray:
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
    ds = run_up_of(point.model)
    if np.any(np.isfinite(np.asarray(ds["captured_at"].values, dtype=float))) or np.any(ds["status"].values < 0):
        return math.inf
    return float(np.max(_reach_times(point.model, ds)))


def run_up_peak(point) -> float:
    """Largest transient peak at a critical speed over the starts (m); ``inf`` if none passed."""
    peaks = np.asarray(run_up_of(point.model)["critical_peak"].values, dtype=float)
    return float(np.nanmax(peaks)) if np.any(np.isfinite(peaks)) else math.inf


def run_up_unbalanced(point) -> float:
    """One minus the Wilson lower bound (95 %) of P(balanced) at the run-up's end (1)."""
    from rotorlab._wilson import wilson_interval

    out = [str(o) for o in run_up_of(point.model)["outcome"].values]
    runs = sum(o != "failed" for o in out)
    if not runs:
        return 1.0
    return float(1.0 - wilson_interval(sum(o == "balanced" for o in out), runs, 0.95)[0])


def design_run_up(case_model, variables, *, peak_limit=None, min_balanced=None, starts=400, seed=0, settle=0.0, budget=20,
                  optimizer="tpe", optimizer_seed=0, check=None) -> dict[str, Any]:
    """The run-up designer on a case's machine: the design search minimising ``run-up-time`` with
    the limits ``run-up-peak`` <= ``peak_limit`` and ``run-up-unbalanced`` <= 1 - ``min_balanced``
    (default 0.99 with balls), each run-up ``settle`` s longer; ``check(starts, min_balanced)`` may refuse too few starts.

    Returns a JSON-ready dict: ``best`` (values, SI; None if no design is feasible),
    ``run_up_time`` (s), ``margins`` (>= 0: the limit holds), ``limits``, ``designs``.
    """
    from rotorlab.analyses._case import build_model
    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search

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
                                limits=limits)
    except ValueError as exc:
        raise ValueError(str(exc).replace("vary.", "--vary ")) from None
    old = dict(SETTINGS)
    SETTINGS.update(n_starts=int(starts), seed=int(seed), settle=float(settle))
    try:
        ds = design_search(problem, optimizer=optimizer, budget=budget, optimizer_seed=optimizer_seed, verify=False)
    finally:
        SETTINGS.update(old)
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
