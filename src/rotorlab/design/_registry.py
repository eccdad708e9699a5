"""What a design search minimises and how it searches: the registries of objectives and optimisers.

An objective is one :class:`Objective` in :data:`DESIGN_OBJECTIVES` (a design search names it in
``objectives``, and any objective can also be bounded in ``limits``); an optimiser is one
:class:`Optimizer` in :data:`DESIGN_OPTIMIZERS`. The search (:mod:`rotorlab.analyses._design`)
looks both up and never branches on their names.

For implementers
----------------
1. An objective: ``register_objective(Objective(name, unit, description, needs_starts, value))``
   where ``value(point) -> float`` reads a :class:`DesignPoint` (the design's model, the operating
   values and, if ``needs_starts``, the basin-stability Dataset of the design's random starts
   there) and returns a number in SI to minimise (``inf``: not computable for this design).
2. An optimiser: ``register_optimizer(Optimizer(name, description, run, objectives))`` where
   ``run(evaluate, variables, budget, seed, n_objectives)`` calls ``evaluate(values) ->
   (objective values, constraint violations)`` at most ``budget`` times (violations <= 0 mean
   feasible) and returns nothing: the search records every evaluation itself. ``objectives`` is
   the largest number of objectives it takes.

Choice of the default optimiser (measured in ``bench/design.py``, see bench/README): on the same
budget and seeds Optuna's TPE sampler came closer to the known optimum than SciPy's differential
evolution on both problems measured: Den Hartog's absorber (60 evaluations, 10 seeds: median best
peak 1.2 % above the floor against 7.6 %) and the least ball mass of ``zhakash-k2`` with
P(balanced) >= 0.99 over its operating range (30 designs of 3000 starts, 3 seeds: 1.4-3.8 % above
the closed form against 4.6-26 %), at the same CPU time (the evaluations dominate). It takes the
constraints (``Trial.set_constraint``) and two objectives (a Pareto front) in one sampler and
proposes one design at a time, so every evaluation counts; differential evolution spends whole
generations (5 designs per variable) before it exploits anything.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorlab._registry import Registry, lazy

__all__ = ["DesignPoint", "RunUpSettings", "Objective", "Optimizer", "DESIGN_OBJECTIVES", "DESIGN_OPTIMIZERS",
           "register_objective", "register_optimizer"]  # fmt: skip

#: A ball's mass among a model's named parameters (``balls[0].mass``, ``races[1].balls[2].mass``).
_BALL_MASS = re.compile(r"(^|\.)balls\[\d+\]\.mass$")


@dataclass(frozen=True)
class RunUpSettings:
    """How a design's run-ups are simulated (the run-up objectives and constraints): part of the
    design problem, so two searches with different settings never share them.

    Parameters
    ----------
    starts : int
        Run-ups from random ball starts per design (uniform angles), >= 1.
    seed : int
        Seed of those starts, the same for every design (common random numbers), >= 0.
    n_save : int
        Saved states per run-up, >= 10.
    settle : float
        Time added to each run-up for the balls to settle at the operating speed (s), >= 0.

    Examples
    --------
    >>> RunUpSettings(starts=8, seed=1)
    RunUpSettings(starts=8, seed=1, n_save=2000, settle=0.0)
    """

    starts: int = 400
    seed: int = 0
    n_save: int = 2000
    settle: float = 0.0

    def __post_init__(self) -> None:
        for name, low in (("starts", 1), ("seed", 0), ("n_save", 10)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
                raise ValueError(f"RunUpSettings.{name} must be an integer >= {low}, got {v!r}")
        if not (isinstance(self.settle, (int, float)) and math.isfinite(self.settle) and self.settle >= 0):
            raise ValueError(f"RunUpSettings.settle must be a finite number >= 0 (s), got {self.settle!r}")


@dataclass(frozen=True)
class DesignPoint:
    """One evaluated design, as an objective sees it.

    Parameters
    ----------
    model : object
        The design's model (the base model with the design's named parameters set).
    operating : numpy.ndarray
        Values of the operating range's parameter (SI, e.g. spin speeds in rad/s).
    stability : xarray.Dataset or None
        :func:`rotorlab.explore.basin_stability_over`'s result at ``operating`` (None when no
        objective or constraint needs random starts).
    run_up : RunUpSettings
        How the design's run-ups are simulated (the problem's).
    memo : dict
        Results shared by the objectives of this one design (its run-up ensemble); it lives and
        dies with the point.
    """

    model: Any
    operating: np.ndarray
    stability: Any = None
    run_up: RunUpSettings = field(default_factory=RunUpSettings)
    memo: dict = field(default_factory=dict, compare=False, repr=False)


@dataclass(frozen=True)
class Objective:
    """A number a design search minimises (or bounds with ``limits``).

    Parameters
    ----------
    name : str
        Its key (``objectives = ["residual-vibration"]``).
    unit : str
        SI unit of its value.
    description : str
        What it is, in words.
    needs_starts : bool
        Whether it reads the design's random starts (``point.stability``).
    value : callable
        ``value(point) -> float`` (SI).
    refuses : callable, optional
        ``refuses(model) -> str | None``: why the objective cannot be computed for this model
        (None: it can), checked before anything runs.
    run_ups : bool
        Whether it reads the design's run-ups (``point.run_up`` settings): a case's design search
        then builds the machine as written, with its drive, and P(balanced) is that of the
        run-ups (``run-up-unbalanced``).
    """

    name: str
    unit: str
    description: str
    needs_starts: bool
    value: Callable[[DesignPoint], float]
    refuses: Callable[[Any], str | None] | None = None
    run_ups: bool = False


@dataclass(frozen=True)
class Optimizer:
    """A search strategy over box-bounded variables.

    Parameters
    ----------
    name : str
    description : str
    run : callable
        ``run(evaluate, variables, budget, seed, n_objectives) -> None``; ``variables`` a
        sequence of ``(name, low, high)``.
    objectives : int
        The most objectives it takes.
    """

    name: str
    description: str
    run: Callable[..., None]
    objectives: int = 1


#: Objectives by name.
DESIGN_OBJECTIVES: Registry[Objective] = Registry("design objective")
#: Optimisers by name.
DESIGN_OPTIMIZERS: Registry[Optimizer] = Registry("design optimiser")


def register_objective(entry: Objective, *, replace: bool = False) -> None:
    """Add an :class:`Objective` to :data:`DESIGN_OBJECTIVES`."""
    DESIGN_OBJECTIVES.register(entry.name, entry, replace=replace)


def register_optimizer(entry: Optimizer, *, replace: bool = False) -> None:
    """Add an :class:`Optimizer` to :data:`DESIGN_OPTIMIZERS`."""
    DESIGN_OPTIMIZERS.register(entry.name, entry, replace=replace)


# --------------------------------------------------------------------------- objectives


def ball_mass(point: DesignPoint) -> float:
    """Total mass of the balls (kg): the sum of every ``...balls[i].mass`` named parameter."""
    space = point.model.parameters
    return float(sum(space[n].value for n in space.names if _BALL_MASS.search(n)))


def residual_vibration(point: DesignPoint) -> float:
    """Mean deflection of the disc centre at the horizon over the random starts (m), the largest
    over the operating values: the vibration a machine is expected to keep after start-up."""
    ds = point.stability
    amp = np.asarray(ds["amplitude"].values, dtype=float)  # (value, start), NaN where not computed
    computed = np.asarray(ds["computed"].values, dtype=bool)
    means = [float(np.mean(a[c])) if c.any() else math.inf for a, c in zip(amp, computed)]
    return float(np.max(means)) if means else math.inf


def settle_time(point: DesignPoint) -> float:
    """Time (s) by which 95 % of the balanced starts had balanced for good (the horizon from which
    each stayed balanced, ``label_since``), the largest over the operating values; ``inf`` where
    no start balanced. Resolved to the classification horizons (``n_horizons``)."""
    ds = point.stability
    k = list(ds["regime"].values).index("balanced")
    since = np.asarray(ds["label_since"].values, dtype=float)
    outcome = np.asarray(ds["outcome"].values)
    out = []
    for s, o in zip(since, outcome):
        s = s[(o == k) & np.isfinite(s)]
        out.append(float(np.quantile(s, 0.95)) if s.size else math.inf)
    return float(np.max(out)) if out else math.inf


def receptance_peak(point: DesignPoint) -> float:
    """Largest linear receptance (m/N) of the first unbalance's station over the operating range:
    its response to a unit rotating force, with the balls locked and the absorbers' dynamic
    stiffness (:func:`rotorlab.models.absorber_response`). A constant-force amplitude, so its
    minimum over an absorber's tuning is Den Hartog's (tested)."""
    from rotorlab.models import absorber_response

    model = point.model
    node = model.unbalances[0].node if getattr(model, "unbalances", ()) else 0
    values = np.asarray(point.operating, dtype=float)
    speeds = np.linspace(values.min(), values.max(), 801) if values.size > 1 else values
    peak = float(np.max(absorber_response(model, node, speeds)["receptance"].values))
    return peak if math.isfinite(peak) else math.inf


# --------------------------------------------------------------------------- optimisers


def _optuna_run(evaluate, variables: Sequence[tuple[str, float, float]], budget: int, seed: int,
                n_objectives: int) -> None:  # fmt: skip
    """Optuna's TPE sampler (multivariate; multi-objective with two objectives), constraints from
    the violations each evaluation returns (``Trial.set_constraint``: <= 0 feasible)."""
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    sampler = optuna.samplers.TPESampler(seed=int(seed), multivariate=True, n_startup_trials=max(4, budget // 4))
    study = optuna.create_study(directions=["minimize"] * n_objectives, sampler=sampler)

    def objective(trial):
        values = {name: trial.suggest_float(name, low, high) for name, low, high in variables}
        objectives, violations = evaluate(values)
        for k, v in enumerate(violations):
            trial.set_constraint(f"c{k}", float(v))
        finite = [v if math.isfinite(v) else 1e300 for v in objectives]
        return finite[0] if n_objectives == 1 else tuple(finite)

    study.optimize(objective, n_trials=int(budget))


def _de_run(evaluate, variables: Sequence[tuple[str, float, float]], budget: int, seed: int,
            n_objectives: int) -> None:  # fmt: skip
    """SciPy's differential evolution (Latin hypercube initial population, no polishing), a
    generation of 5 designs per variable (at least 6) and as many generations as the budget holds; an
    infeasible design ranks after every feasible one (by its total violation)."""
    from scipy.optimize import differential_evolution

    dim = len(variables)
    per = max(5, -(-6 // dim))  # SciPy's popsize: the generation holds per * dim designs
    generations = max(0, budget // (per * dim) - 1)

    def f(x):
        objectives, violations = evaluate(dict(zip([v[0] for v in variables], map(float, x))))
        excess = float(sum(max(0.0, v) for v in violations))
        if excess > 0 or not math.isfinite(objectives[0]):  # after every feasible design, by its violation
            return 1e30 * (1.0 + min(excess, 1e6))
        return float(objectives[0])

    differential_evolution(f, [(lo, hi) for _, lo, hi in variables], seed=int(seed), popsize=per, maxiter=generations,
                           init="latinhypercube", polish=False, tol=0.0, atol=0.0, updating="deferred")  # fmt: skip


def _run_up_objectives() -> tuple[Objective, ...]:
    """The run-up designer's objectives (:mod:`rotorlab.analyses._design_run_up`), imported when
    first evaluated (``lazy``: no import of the analyses here)."""
    def lazy_value(name):
        return lazy(f"rotorlab.analyses._design_run_up:{name}")

    refuses = lazy_value("no_servo_drive")
    return (Objective("run-up-time", "s", "time the slowest start needs to reach 99 % of the servo drive's "
                      "operating speed; infinite (infeasible) when a start is captured", False, lazy_value("run_up_time"),
                      refuses, True),
            Objective("run-up-peak", "m", "largest transient peak at a critical speed over the run-ups",
                      False, lazy_value("run_up_peak"), refuses, True),
            Objective("run-up-unbalanced", "1", "one minus the Wilson lower bound (95 %) of P(balanced) at the "
                      "end of the run-up (limit 0.01: P(balanced) >= 0.99)", False, lazy_value("run_up_unbalanced"),
                      refuses, True))


def _register_builtins() -> None:
    for entry in (
        Objective("ball-mass", "kg", "total mass of the balls", False, ball_mass),
        Objective("residual-vibration", "m", "mean disc deflection after start-up from random starts, the largest "
                  "over the operating range", True, residual_vibration),
        Objective("settle-time", "s", "time by which 95 % of the balanced random starts had balanced, the largest "
                  "over the operating range", True, settle_time),
        Objective("receptance-peak", "m/N", "largest linear receptance of the unbalance's station over the operating "
                  "range (response to a unit rotating force)", False, receptance_peak),
        *_run_up_objectives(),
    ):  # fmt: skip
        register_objective(entry)
    register_optimizer(Optimizer("tpe", "Optuna's tree-structured Parzen estimator (constrained, multi-objective)",
                                 _optuna_run, objectives=2))  # fmt: skip
    register_optimizer(Optimizer("differential-evolution", "SciPy's differential evolution (one objective; "
                                 "constraints ranked after the objective)", _de_run))  # fmt: skip


_register_builtins()
