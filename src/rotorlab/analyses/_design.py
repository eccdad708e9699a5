"""Design search: which values of a model's named parameters minimise an objective while the rotor
balances with confidence over its operating range.

Layers: a :class:`DesignProblem` says what varies (named parameters with bounds), what is
minimised (one or two objectives of :data:`~rotorlab.design.DESIGN_OBJECTIVES`),
what must hold (the Wilson lower bound of P(balanced) at every operating value, upper limits on
objectives) and the random starts; :func:`design_search` lets an optimiser of
:data:`~rotorlab.design.DESIGN_OPTIMIZERS` propose designs, evaluates each on
the basin-stability sweep (:func:`rotorlab.explore.basin_stability_over`: Zarr store, resume, any
executor, the vectorised lane driver), and re-simulates the winner from fresh random starts.

Common random numbers: every design is evaluated from the same seeded starts (start ``j`` is the
same ball angles for every design), so two designs differ by their physics, not by their draws;
the winner's check uses another seed (independent starts). The search is deterministic: the same
seeds give the same designs and numbers, and a resumed run (each evaluation's store kept) replays
the optimiser on the stored results and computes only the missing ones.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from rotorlab.design import DESIGN_CONSTRAINTS, DESIGN_OBJECTIVES, DESIGN_OPTIMIZERS, DesignPoint, RunUpSettings

__all__ = ["DesignVariable", "DesignProblem", "design_search", "pareto_mask", "VERIFY_SEED_OFFSET"]

#: The winner's independent check draws its starts with seed ``seed + VERIFY_SEED_OFFSET``.
VERIFY_SEED_OFFSET = 1_000_003


@dataclass(frozen=True)
class DesignVariable:
    """A named parameter varied between bounds (SI).

    Examples
    --------
    >>> DesignVariable("ball_mass", 0.01, 0.05)
    DesignVariable(name='ball_mass', low=0.01, high=0.05)
    """

    name: str
    low: float
    high: float


@dataclass(frozen=True)
class DesignProblem:
    """What a design search varies, minimises and requires.

    Parameters
    ----------
    model : object
        The base model (its named parameters, :attr:`parameters`, and ``with_parameters``).
    variables : tuple of DesignVariable
        Named parameters (key paths, or a mapper's names such as ``ball_mass``) and bounds.
    objectives : tuple of str
        One or two names of :data:`DESIGN_OBJECTIVES` (two: a Pareto front).
    operating : numpy.ndarray
        Values of ``operating_name`` where the design must work (SI).
    operating_name : str
        The operating range's parameter (``spin_speed``).
    min_balanced : float, optional
        The Wilson lower bound of P(balanced) must reach it at every operating value.
    limits : mapping of str to float
        Upper limits on objectives (SI), e.g. ``{"residual-vibration": 1e-5}``.
    mapper : AbstractMapper, optional
        The regime mapper of the base model (needed by ``min_balanced`` and objectives that read
        random starts).
    ranges : mapping of str to (low, high)
        Start coordinates drawn uniformly (SI).
    starts : int
        Random starts per operating value and design.
    seed : int
        Seed of the starts (the same for every design).
    confidence : float
        Level of the Wilson intervals.
    horizon_given : bool
        The mapper's horizon was set (else each design gets the longest default horizon of its
        balanced state over the operating values).
    chunk : int, optional
        Starts per task of the sweep engine.
    constraints : tuple of str
        Names of :data:`~rotorlab.design.DESIGN_CONSTRAINTS` every feasible design meets
        (``no-housing-contact``).
    run_up : RunUpSettings
        How each design's run-ups are simulated (the run-up objectives and constraints): starts,
        seed, saved states, settling time. Carried by the problem, so searches never share them.
    """

    model: Any
    variables: tuple[DesignVariable, ...]
    objectives: tuple[str, ...]
    operating: np.ndarray
    operating_name: str = "spin_speed"
    min_balanced: float | None = None
    limits: Mapping[str, float] = field(default_factory=dict)
    mapper: Any = None
    ranges: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    starts: int = 1000
    seed: int = 0
    confidence: float = 0.95
    horizon_given: bool = False
    chunk: int | None = None
    constraints: tuple[str, ...] = ()
    run_up: RunUpSettings = field(default_factory=RunUpSettings)

    def __post_init__(self) -> None:
        problems = self.issues()
        if problems:
            raise ValueError("; ".join(f"{key}: {text}" for key, text in problems))

    def parameter(self, name: str) -> Any:
        """The named parameter ``name`` (a :class:`rotorlab.models.Parameter`), None if unknown."""
        if self.mapper is not None and hasattr(self.mapper, "coordinate_parameter"):
            found = self.mapper.coordinate_parameter(name)
            if found is not None:
                return found
        space, key = self.model.parameters, name.removeprefix("model.")
        return space[key] if key in space else None

    def model_at(self, values: Mapping[str, float]) -> Any:
        """The base model with a design's values set: through the mapper's variant (its aliases such
        as ``ball_mass`` and ``model.<key path>``), else ``with_parameters``."""
        values = {k: float(v) for k, v in values.items()}
        if self.mapper is None:
            return self.model.with_parameters(**{k.removeprefix("model."): v for k, v in values.items()})
        variant = getattr(self.mapper, "_variant", None)  # a machine's starts() keep the base model
        if variant is not None:
            return variant(values)
        return self.mapper.starts({k: np.array([v]) for k, v in values.items()})[0]

    def issues(self) -> list[tuple[str, str]]:
        """Every problem as ``(key path, message)``: unknown objectives, parameters, bounds."""
        out = []
        if not 1 <= len(self.objectives) <= 2:
            out.append(("objectives", f"give one or two objectives, not {len(self.objectives)}"))
        for name in (*self.objectives, *self.limits):
            if name not in DESIGN_OBJECTIVES:
                key = "objectives" if name in self.objectives else f"limits.{name}"
                out.append((key, f"{name!r} is not an objective (allowed: {', '.join(DESIGN_OBJECTIVES)})"))
            elif DESIGN_OBJECTIVES[name].needs_starts and self.mapper is None:
                out.append(("objectives", f"{name!r} needs random starts, i.e. a model with a regime mapper"))
            elif DESIGN_OBJECTIVES[name].refuses is not None and DESIGN_OBJECTIVES[name].refuses(self.model):
                key = "objectives" if name in self.objectives else f"limits.{name}"
                out.append((key, f"{name!r} {DESIGN_OBJECTIVES[name].refuses(self.model)}"))
        for name in self.constraints:
            if name not in DESIGN_CONSTRAINTS:
                out.append(("constraints", f"{name!r} is not a constraint (allowed: {', '.join(DESIGN_CONSTRAINTS)})"))
            elif DESIGN_CONSTRAINTS[name].refuses(self.model):
                out.append(("constraints", f"{name!r} {DESIGN_CONSTRAINTS[name].refuses(self.model)}"))
        if self.min_balanced is not None and self.mapper is None:
            out.append(("min_balanced", "needs a model with a regime mapper (balls)"))
        if not self.variables:
            out.append(("vary", "give one or more parameters to vary {NAME = [low, high]}"))
        names = self._known_names()
        for v in self.variables:
            p = self.parameter(v.name)
            if p is None:
                out.append((f"vary.{v.name}", f"not a named parameter of this model (allowed: {names})"))
            elif p.structural:
                out.append((f"vary.{v.name}", "changes the compiled layout (e.g. a ball count); a design search "
                                              "varies only numbers of one layout"))  # fmt: skip
            elif not (math.isfinite(v.low) and math.isfinite(v.high) and v.high > v.low):
                out.append((f"vary.{v.name}", f"[{v.low:g}, {v.high:g}]: high must be > low"))
            else:
                bad = [b for b in (v.low, v.high) if not p.admits(b)]
                if bad:
                    out.append((f"vary.{v.name}", f"{bad[0]:g} is outside the parameter's range: must be {p.allowed}"))
                else:
                    out += [(f"vary.{v.name}", text) for text in self._model_refuses(v)]
        return out

    def _model_refuses(self, v: DesignVariable) -> list[str]:
        """The model's own refusal of either bound (a ball inside its tube, ...), if any."""
        try:
            for bound in (v.low, v.high):
                if self.mapper is not None:
                    self.mapper.starts({v.name: np.array([bound])})
                else:
                    self.model.with_parameters(**{v.name.removeprefix("model."): bound})
        except ValueError as exc:
            return [str(exc)]
        return []

    def _known_names(self) -> str:
        names = list(getattr(self.mapper, "coordinate_units", {}) or [])
        names = [n for n in names if self.parameter(n) is not None and not n.startswith(("psi", "dpsi", "rotor_"))]
        names += [n for n in self.model.parameters.names if n not in names]
        return ", ".join(names[:40]) + (", ..." if len(names) > 40 else "")

    @property
    def reads_run_ups(self) -> bool:
        """Whether an objective, limit or constraint reads the designs' run-ups."""
        return any(DESIGN_OBJECTIVES[n].run_ups for n in (*self.objectives, *self.limits)) or any(
            DESIGN_CONSTRAINTS[n].run_ups for n in self.constraints)

    @property
    def needs_starts(self) -> bool:
        return self.min_balanced is not None or any(DESIGN_OBJECTIVES[n].needs_starts for n in
                                                    (*self.objectives, *self.limits))  # fmt: skip


@dataclass
class _Evaluator:
    """Evaluates designs (cached by their values), records them, optionally into stores."""

    problem: DesignProblem
    store: Path | None
    resume: bool
    executor: Any
    trials: list[dict[str, Any]] = field(default_factory=list)
    cache: dict[str, dict[str, Any]] = field(default_factory=dict)

    def key(self, values: Mapping[str, float]) -> str:
        text = json.dumps([[v.name, float(values[v.name]).hex()] for v in self.problem.variables])
        return hashlib.sha1(text.encode()).hexdigest()[:16]

    def point(self, values: Mapping[str, float], seed: int, tag: str) -> dict[str, Any]:
        """Evaluate one design from the starts of ``seed``: objectives, P(balanced), violations."""
        from rotorlab.analyses._basin_stability import horizon_over
        from rotorlab.explore import basin_stability_over
        from rotorlab.sweep import ListAxis

        pb = self.problem
        cpu = time.process_time()
        stability, model = None, None
        model = pb.model_at(values)
        if pb.mapper is not None:
            mapper = replace(pb.mapper, model=model)
        if pb.needs_starts:
            mapper = horizon_over(mapper, pb.operating_name, pb.operating, pb.horizon_given, "")[0]
            path = None if self.store is None else self.store / f"{tag}-{self.key(values)}.zarr"
            stability = basin_stability_over(
                mapper, ListAxis(pb.operating_name, np.asarray(pb.operating, dtype=float)), pb.ranges, seed=seed,
                starts=pb.starts, confidence=pb.confidence, chunk_size=pb.chunk, store=path,
                resume=self.resume and path is not None and path.exists(), executor=self.executor)  # fmt: skip
        memo: dict[str, Any] = {}
        if pb.reads_run_ups:  # the design's run-ups, on the sweep engine (store, resume, executor)
            from rotorlab.analyses._run_up_sweep import run_up_ensemble

            path = None if self.store is None else self.store / f"{tag}-runup-{self.key(values)}.zarr"
            memo["run_up"] = run_up_ensemble(model, pb.run_up, store=path, executor=self.executor,
                                             resume=self.resume and path is not None and path.exists())  # fmt: skip
        at = DesignPoint(model, np.asarray(pb.operating, dtype=float), stability, pb.run_up, memo)
        metrics = {n: float(DESIGN_OBJECTIVES[n].value(at)) for n in dict.fromkeys((*pb.objectives, *pb.limits))}
        out: dict[str, Any] = {"values": dict(values), "metrics": metrics, "t_end": math.nan}
        if stability is not None:
            k = list(stability["regime"].values).index("balanced")
            out.update(balanced=stability["probability"].values[:, k].astype(float),
                       low=stability["ci_low"].values[:, k].astype(float),
                       high=stability["ci_high"].values[:, k].astype(float),
                       t_end=float(stability["horizon"].values[-1]))  # fmt: skip
        margins = {}
        if pb.min_balanced is not None:
            margins["min_balanced"] = float(np.min(out["low"]) - pb.min_balanced)
        for name, limit in pb.limits.items():
            margins[f"limits.{name}"] = float((limit - metrics[name]) / abs(limit)) if math.isfinite(metrics[name]) \
                else -math.inf  # fmt: skip
        for name in pb.constraints:
            margins[f"constraints.{name}"] = float(DESIGN_CONSTRAINTS[name].margin(at))
        out["margins"] = margins
        out["cpu_s"] = time.process_time() - cpu
        return out

    def __call__(self, values: Mapping[str, float]) -> tuple[list[float], list[float]]:
        key = self.key(values)
        if key not in self.cache:
            self.cache[key] = self.point(values, self.problem.seed, "eval")
        rec = self.cache[key]
        self.trials.append(rec)
        violations = [-m if math.isfinite(m) else 1e300 for m in rec["margins"].values()]
        return [rec["metrics"][n] for n in self.problem.objectives], violations


class _BudgetSpent(Exception):
    """Raised by the evaluation after the budget, to stop an optimiser that asks for more."""


def pareto_mask(costs: np.ndarray, feasible: np.ndarray) -> np.ndarray:
    """The feasible rows of ``costs`` (rows: designs, columns: objectives to minimise) that no
    other feasible row dominates.

    Examples
    --------
    >>> pareto_mask(np.array([[1.0, 3.0], [2.0, 2.0], [2.0, 3.0], [0.5, 5.0]]), np.array([True] * 4)).tolist()
    [True, True, False, True]
    """
    costs = np.asarray(costs, dtype=float)
    ok = np.asarray(feasible, dtype=bool).copy()
    out = np.zeros(len(costs), dtype=bool)
    for i in np.flatnonzero(ok):
        others = costs[ok]
        dominated = np.any(np.all(others <= costs[i], axis=1) & np.any(others < costs[i], axis=1))
        out[i] = not dominated
    return out


def design_search(problem: DesignProblem, *, optimizer: str = "tpe", budget: int = 20, optimizer_seed: int = 0,
                  store: Path | str | None = None, resume: bool = False, executor: Any = None,
                  verify: bool = True, progress: Callable[[int, int], None] | None = None):  # fmt: skip
    """Search the design space and re-simulate the winner from fresh random starts.

    Parameters
    ----------
    problem : DesignProblem
    optimizer : str
        A name of :data:`DESIGN_OPTIMIZERS` (``"tpe"``, ``"differential-evolution"``).
    budget : int
        Evaluations the optimiser may ask for (a design asked twice is computed once).
    optimizer_seed : int
        Seed of the optimiser.
    store : path, optional
        Folder of the evaluations' Zarr stores (one per design, ``eval-<hash>.zarr``, and the
        check's ``verify-<hash>.zarr``; a run-up design's run-ups ``eval-runup-<hash>.zarr``); with
        ``resume`` a run continues from them.
    executor : optional
        Where the starts run (:func:`rotorlab.sweep.run_sweep`); results do not depend on it.
    verify : bool
        Re-simulate the winner from independent starts (seed + :data:`VERIFY_SEED_OFFSET`).
    progress : callable, optional
        ``progress(done, budget)`` in evaluations.

    Returns
    -------
    xarray.Dataset
        Dims ``trial`` (evaluation order), ``variable``, ``objective``, ``constraint`` and the
        operating dim: ``value`` (trial, variable; SI), ``objective_value`` (trial, objective),
        ``margin`` (trial, constraint; P(balanced): the lower bound minus the level, a limit:
        (limit - value) / limit; >= 0 holds), ``feasible`` and ``pareto`` (trial; the feasible
        designs no other feasible one dominates; one objective: the winner), ``balanced``,
        ``balanced_low``, ``balanced_high`` (trial, operating), and the winner's check
        ``verify_balanced``, ``verify_low``, ``verify_high`` (operating) and
        ``verify_objective`` (objective); attrs ``best`` (trial of the winner, -1: no feasible
        design), ``optimizer``, ``budget``, ``seed``, ``verify_seed``, ``cpu_s`` and more.

    Raises
    ------
    ValueError
        An unknown optimiser, a budget < 1, two objectives for a one-objective optimiser.
    """
    import xarray as xr

    if optimizer not in DESIGN_OPTIMIZERS:
        raise ValueError(f"optimizer = {optimizer!r}: allowed: {', '.join(DESIGN_OPTIMIZERS)}")
    entry = DESIGN_OPTIMIZERS[optimizer]
    if len(problem.objectives) > entry.objectives:
        raise ValueError(f"optimizer = {optimizer!r} takes {entry.objectives} objective(s), got "
                         f"{len(problem.objectives)} (use tpe for a Pareto front)")  # fmt: skip
    if isinstance(budget, bool) or int(budget) != budget or budget < 1:
        raise ValueError(f"budget must be an integer >= 1, got {budget!r}")
    folder = None if store is None else Path(store)
    if folder is not None:
        folder.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:  # one Dask cluster (or client) for every design, not one per design
        if executor is not None and hasattr(executor, "session"):
            executor = stack.enter_context(executor.session())
        ev = _Evaluator(problem, folder, resume, executor)

        def call(values):
            if len(ev.trials) >= budget:  # the budget holds for any optimiser (a generation may be larger)
                raise _BudgetSpent
            out = ev(values)
            if progress is not None:
                progress(len(ev.trials), int(budget))
            return out

        cpu = time.process_time()
        try:
            entry.run(call, [(v.name, v.low, v.high) for v in problem.variables], int(budget), int(optimizer_seed),
                      len(problem.objectives))  # fmt: skip
        except _BudgetSpent:
            pass
        search_cpu = time.process_time() - cpu
        trials = ev.trials
        costs = np.array([[t["metrics"][n] for n in problem.objectives] for t in trials])
        margins = np.array([list(t["margins"].values()) for t in trials]).reshape(len(trials), -1)
        feasible = np.all(margins >= 0.0, axis=1) & np.all(np.isfinite(costs), axis=1)
        pareto = pareto_mask(costs, feasible)
        best = int(np.flatnonzero(pareto)[np.argmin(costs[pareto, 0])]) if pareto.any() else -1
        if len(problem.objectives) == 1:  # one objective: the front is the winner (the first of equals)
            pareto = np.arange(len(trials)) == best
        verify_seed = int(problem.seed) + VERIFY_SEED_OFFSET
        check = None
        if verify and best >= 0 and problem.needs_starts:
            check = ev.point(trials[best]["values"], verify_seed, "verify")
    dim = problem.operating_name
    n_op = len(problem.operating)
    nan_op = np.full(n_op, np.nan)
    data = {
        "value": (("trial", "variable"), np.array([[t["values"][v.name] for v in problem.variables] for t in trials]),
                  {"units": "SI", "description": "the design's parameter values"}),
        "objective_value": (("trial", "objective"), costs, {"units": "SI"}),
        "margin": (("trial", "constraint"), margins, {"units": "1", "description": ">= 0: the constraint holds"}),
        "feasible": (("trial",), feasible, {"units": "1"}),
        "pareto": (("trial",), pareto, {"units": "1"}),
        "balanced": (("trial", dim), np.array([t.get("balanced", nan_op) for t in trials]), {"units": "1"}),
        "balanced_low": (("trial", dim), np.array([t.get("low", nan_op) for t in trials]),
                         {"units": "1", "confidence": problem.confidence}),
        "balanced_high": (("trial", dim), np.array([t.get("high", nan_op) for t in trials]),
                          {"units": "1", "confidence": problem.confidence}),
        "t_end": (("trial",), np.array([t["t_end"] for t in trials]), {"units": "s", "description": "horizon"}),
    }  # fmt: skip
    data["verify_balanced"] = ((dim,), check["balanced"] if check else nan_op, {"units": "1"})
    data["verify_low"] = ((dim,), check["low"] if check else nan_op, {"units": "1"})
    data["verify_high"] = ((dim,), check["high"] if check else nan_op, {"units": "1"})
    data["verify_objective"] = (("objective",), np.array([check["metrics"][n] if check else np.nan
                                                          for n in problem.objectives]), {"units": "SI"})  # fmt: skip
    units = {v.name: (getattr(problem.parameter(v.name), "unit", "") or "") for v in problem.variables}
    constraint_names = list(trials[0]["margins"]) if trials else []
    one = {"units": "1"}
    coords = {"trial": ("trial", np.arange(len(trials)), {"units": "1", "description": "evaluation number"}),
              "variable": ("variable", [v.name for v in problem.variables], one),
              "objective": ("objective", list(problem.objectives), one),
              "constraint": ("constraint", constraint_names, one),
              dim: (dim, np.asarray(problem.operating, dtype=float), {"units": "rad/s" if dim == "spin_speed" else ""})}
    attrs = {"best": best, "optimizer": optimizer, "budget": int(budget), "optimizer_seed": int(optimizer_seed),
             "seed": int(problem.seed), "verify_seed": verify_seed, "starts": int(problem.starts),
             "confidence": float(problem.confidence), "operating": dim, "evaluations": len(ev.cache),
             "min_balanced": math.nan if problem.min_balanced is None else float(problem.min_balanced),
             "limits": json.dumps(dict(problem.limits)), "units": json.dumps(units),
             "objective_units": json.dumps({n: DESIGN_OBJECTIVES[n].unit for n in problem.objectives}),
             "bounds": json.dumps({v.name: [v.low, v.high] for v in problem.variables}),
             "cpu_s": search_cpu, "verify_cpu_s": check["cpu_s"] if check else 0.0,
             "trial_cpu_s": json.dumps([t["cpu_s"] for t in trials]),
             "constraints": json.dumps(list(problem.constraints)),
             "run_ups": int(problem.reads_run_ups), "run_up_starts": int(problem.run_up.starts),
             "run_up_seed": int(problem.run_up.seed)}  # fmt: skip
    return xr.Dataset(data, coords=coords, attrs=attrs)
