"""Case-file spec of the ``design`` analysis: the values of named parameters that minimise an
objective while the rotor balances with confidence over its operating range
(:func:`rotorlab.analyses.design_search`; ``rotorlab design`` adds a store, resume and Dask).

Layout::

    [[analysis]]
    type = "design"
    name = "balls"
    vary = {ball_mass = ["10 g", "60 g"], ball_damping = ["0.5e-3 N*m*s", "5e-3 N*m*s"]}
    objectives = ["residual-vibration"]        # one, or two for a Pareto front
    param = {spin_speed = ["1800 rpm", "2400 rpm", 3]}   # the operating range
    min_balanced = 0.99       # Wilson lower bound of P(balanced) at every operating value
    limits = {residual-vibration = "0.05 mm"}
    constraints = ["no-housing-contact"]   # named constraints (a run-up design of a machine with a clearance)
    starts = 1000             # random starts per design and operating value (the same for all)
    budget = 30               # evaluations
    optimizer = "tpe"         # or "differential-evolution"
    # optional: Sobol indices of the winner (a machine): a ``tolerances`` table without type/name;
    # seed, t_end, races and the speed default to the design's (the speed: its first operating value)
    sensitivity = {inputs = {ball_damping = {distribution = "uniform", tolerance = 0.5}, ...}, samples = 16, starts = 4}

Examples
--------
>>> spec = DesignSpec(vary={"ball_mass": ["10 g", "60 g"]}, param={"spin_speed": ["2000 rpm", "2000 rpm", 1]},
...                   objectives=["ball-mass"], limits={"residual-vibration": "0.05 mm"})
>>> spec.vary, spec.limits, spec.min_balanced
({'ball_mass': (0.01, 0.06)}, {'residual-vibration': 5e-05}, 0.99)
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, field_validator

from rotorlab.io._basin_stability_spec import BasinStabilitySpec
from rotorlab.io._coordinates import coordinates_text
from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractModelSpec, _error, integer, quantity
from rotorlab.io._sweep_specs import _axes, sweep_coordinates
from rotorlab.io._tolerances_spec import TolerancesSpec

__all__ = ["DesignSpec", "DEFAULT_DESIGN_STARTS"]

#: Random starts per design and operating value when a design analysis gives none.
DEFAULT_DESIGN_STARTS = 1000


def _dimension_of(unit: str) -> str:
    """The case-file dimension whose SI unit is ``unit`` (a limit's value is read in it)."""
    from rotorlab.io._units import DIMENSIONS

    return next((k for k, d in DIMENSIONS.items() if d.si == unit), "dimensionless")


def _bound_issues(model: AbstractModelSpec, name: str, entry: tuple) -> list[Issue]:
    """Either bound outside the range of the case key the name varies (``ball_<field>``: every
    ball's ``balls[].<field>``; ``model.<key path>`` and the rotor's names: that key)."""
    from pydantic_core import PydanticCustomError

    from rotorlab.io._coordinates import key_quantity

    path = name if name.startswith("model.") else (
        f"model.balls[0].{name[5:]}" if name.startswith("ball_") else f"model.{name}")  # fmt: skip
    check = key_quantity(path, type(model))
    if check is None:  # the speed and other names without a key of their own: checked when built
        return []
    for value in entry:
        try:
            check(value)
        except PydanticCustomError as exc:
            detail = (exc.context or {}).get("detail", exc.message())
            return [Issue(("vary", name), f"{value:g} is outside the parameter's range: {detail}", list(entry))]
    return []


class DesignSpec(BasinStabilitySpec):
    """Design search: named parameters varied within bounds to minimise one or two objectives,
    with P(balanced) from the same random starts for every design.

    Parameters
    ----------
    vary : {NAME: [low, high]}
        The named parameters varied (SI or with units): names of ``rotorlab sweep --param``
        (``ball_mass``, ``ball_damping``, ``model.<key path>``). A name that changes the compiled
        layout (a ball count) is refused.
    objectives : list of str
        One or two of :data:`rotorlab.design.DESIGN_OBJECTIVES` (``ball-mass``,
        ``residual-vibration``, ``receptance-peak``); two give a Pareto front.
    param : {NAME: [start, stop, count]}
        The operating range: P(balanced) must hold at every value.
    min_balanced : float
        The Wilson lower bound of P(balanced) at every operating value must reach it (default
        0.99, at ``confidence``).
    limits : {OBJECTIVE: value}
        Upper limits on objectives (in the objective's unit, or with a unit).
    constraints : list of str
        Names of :data:`rotorlab.design.DESIGN_CONSTRAINTS` every feasible design meets
        (``no-housing-contact``).

    With a run-up objective, limit or constraint (``run-up-time``, ...) the search runs each
    design's run-ups with the machine's servo drive (``starts`` run-ups from random ball starts,
    ``seed``) instead of random starts at constant speed, ``vary`` names the machine's named
    parameters (``model.drive.ramp_rate``, ``model.clearances[0].gap``), and ``min_balanced``
    (with balls) is the Wilson lower bound of P(balanced) at the run-ups' end
    (``run-up-unbalanced`` <= 1 - min_balanced).
    optimizer : str
        A name of :data:`rotorlab.design.DESIGN_OPTIMIZERS` (default ``tpe``).
    budget : int
        Designs evaluated (default 30).
    optimizer_seed : int
        Seed of the optimiser.
    verify : bool
        Re-simulate the winner from fresh random starts (default true).
    sensitivity : table, optional
        Sobol indices of the winner's P(balanced), residual vibration and transient peak (a
        machine): the keys of a ``tolerances`` analysis (``inputs``, ``samples``, ``starts``, ...);
        ``seed``, ``t_end``, ``races`` and ``speed`` not given are the design's (the speed: the first
        operating value when the operating range is the speed).
    starts, seed, confidence, ranges, t_end, ...
        As for ``basin-stability`` (``starts`` default 1000; ``ci_width`` is not taken: every
        design gets the same starts).
    """

    type: Literal["design"] = "design"  # type: ignore[assignment]
    vary: _axes("param") = Field(description="named parameters varied {NAME = [low, high]} (SI)")
    objectives: list[str] = Field(description="one or two objectives to minimise")
    min_balanced: quantity("dimensionless", gt=0, lt=1) | None = Field(
        0.99, description="least Wilson lower bound of P(balanced) over the operating range (-)")
    limits: dict[str, Any] = Field(default_factory=dict, description="upper limits on objectives (SI)")
    constraints: list[str] = Field(default_factory=list, description="named constraints every feasible design meets")
    optimizer: str = Field("tpe", description="the optimiser")
    budget: integer(ge=1, le=10_000) = Field(30, description="designs evaluated")
    optimizer_seed: integer(ge=0) = Field(0, description="seed of the optimiser")
    verify: bool = Field(True, description="re-simulate the winner from fresh random starts")
    sensitivity: TolerancesSpec | None = Field(None, description="Sobol indices of the winner (a tolerances table)")

    @field_validator("objectives", mode="after")
    @classmethod
    def _known_objectives(cls, value: list[str]) -> list[str]:
        from rotorlab.design import DESIGN_OBJECTIVES

        if not 1 <= len(value) <= 2:
            raise _error(f"give one or two objectives, not {len(value)}")
        for name in value:
            if name not in DESIGN_OBJECTIVES:
                raise _error(f"{name!r} is not an objective (allowed: {', '.join(DESIGN_OBJECTIVES)})")
        if len(set(value)) != len(value):
            raise _error("the objectives must differ")
        return value

    @field_validator("constraints", mode="after")
    @classmethod
    def _known_constraints(cls, value: list[str]) -> list[str]:
        from rotorlab.design import DESIGN_CONSTRAINTS

        for name in value:
            if name not in DESIGN_CONSTRAINTS:
                raise _error(f"{name!r} is not a constraint (allowed: {', '.join(DESIGN_CONSTRAINTS)})")
        return list(dict.fromkeys(value))

    @property
    def reads_run_ups(self) -> bool:
        """Whether an objective, limit or constraint reads the designs' run-ups."""
        from rotorlab.design import DESIGN_CONSTRAINTS, DESIGN_OBJECTIVES

        return any(DESIGN_OBJECTIVES[n].run_ups for n in (*self.objectives, *self.limits) if n in DESIGN_OBJECTIVES) \
            or any(DESIGN_CONSTRAINTS[n].run_ups for n in self.constraints)

    @field_validator("limits", mode="after")
    @classmethod
    def _limits_in_si(cls, value: dict[str, Any]) -> dict[str, float]:
        from rotorlab.design import DESIGN_OBJECTIVES
        from rotorlab.io._units import UnitError, convert

        out = {}
        for name, raw in value.items():
            if name not in DESIGN_OBJECTIVES:
                raise _error(f"{name}: not an objective (allowed: {', '.join(DESIGN_OBJECTIVES)})")
            try:
                out[name] = convert(raw, _dimension_of(DESIGN_OBJECTIVES[name].unit))
            except UnitError as exc:
                raise _error(f"{name}: {exc}") from None
            if not out[name] > 0:
                raise _error(f"{name}: must be > 0, got {out[name]:g}")
        return out

    @field_validator("optimizer", mode="after")
    @classmethod
    def _known_optimizer(cls, value: str) -> str:
        from rotorlab.design import DESIGN_OPTIMIZERS

        if value not in DESIGN_OPTIMIZERS:
            raise _error(f"{value!r} is not an optimiser (allowed: {', '.join(DESIGN_OPTIMIZERS)})")
        return value

    @classmethod
    def _written(cls, data: dict[str, Any]) -> list[tuple[str, list[Any]]]:
        return [*super()._written(data), *((str(n), list(raw[:2])) for n, raw in (data.get("vary") or {}).items()
                                           if isinstance(raw, (list, tuple)))]  # fmt: skip

    @property
    def design_starts(self) -> int:
        """Random starts per design and operating value."""
        return DEFAULT_DESIGN_STARTS if self.starts is None else int(self.starts)

    def _speed_from_range(self, model: AbstractModelSpec) -> bool:
        return (self.speed is None and self.speed_ratio is None and not model.spins_at_own_speed
                and self.param_axis[0] == "spin_speed")  # fmt: skip

    def spin_speed(self, model: AbstractModelSpec) -> float:
        """The base spin speed (rad/s): the first operating speed when the operating range is
        the speed and none is given, else as for ``basin-stability``."""
        return self.param_axis[1] if self._speed_from_range(model) else super().spin_speed(model)

    def speed_issues(self, model: AbstractModelSpec) -> list[Issue]:
        return [] if self._speed_from_range(model) else super().speed_issues(model)

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """The basin-stability checks, plus: every varied name a parameter of the model given
        as [low, high] with low < high, no ``ci_width``, at most as many objectives as the
        optimiser takes."""
        issues = [i for i in super().case_issues(model) if i.loc != ("ci_width",)]
        if self.reads_run_ups and any(i.loc == ("type",) for i in issues):  # run-ups need no regime mapper
            issues = [i for i in issues if i.loc != ("type",)]
            known = sweep_coordinates(model, "param")
            issues += [Issue(("param", n), f"not a parameter of this {model.type} model (allowed: "
                                           f"{coordinates_text(known)})", n) for n in self.param if n not in known]
        if self.ci_width is not None:
            issues.append(Issue(("ci_width",), "not taken by a design search: give starts (every design gets the "
                                               "same random starts)", self.ci_width))  # fmt: skip
        known = sweep_coordinates(model, "param")
        if not self.vary:
            issues.append(Issue(("vary",), "give one or more parameters {NAME = [low, high]}", None, show_value=False))
        for name, entry in self.vary.items():
            if name not in known:
                reason = model.missing_coordinate(name)
                issues.append(Issue(("vary", name), f"the model {reason}" if reason is not None else
                                    f"not a parameter of this {model.type} model (allowed: {coordinates_text(known)})",
                                    name))  # fmt: skip
            elif len(entry) != 2 or not entry[1] > entry[0]:
                issues.append(Issue(("vary", name), "give [low, high] with high > low", list(entry)))
            else:
                issues += _bound_issues(model, name, entry)
        if sweep_coordinates(model, "ic") or not self.reads_run_ups:  # a run-up design without balls: no P(balanced)
            issues += self._starts_issues()
        if self.sensitivity is not None:
            for i in self.sensitivity_spec(model).case_issues(model):  # its "type": the sensitivity table's
                loc = ("sensitivity",) if i.loc == ("type",) else ("sensitivity", *i.loc)
                issues.append(Issue(loc, i.message, i.value, i.show_value and i.loc != ("type",)))
        from rotorlab.design import DESIGN_OPTIMIZERS

        most = DESIGN_OPTIMIZERS[self.optimizer].objectives
        if len(self.objectives) > most:
            issues.append(Issue(("objectives",), f"the optimiser {self.optimizer!r} takes {most} objective(s); "
                                                 "tpe takes two (a Pareto front)", list(self.objectives)))  # fmt: skip
        return issues

    def sensitivity_spec(self, model: AbstractModelSpec) -> TolerancesSpec | None:
        """The ``tolerances`` analysis run at the winner: the ``sensitivity`` table, with the
        design's seed, t_end, races and speed where the table gives none (None: no table)."""
        if self.sensitivity is None:
            return None
        given = self.sensitivity.model_fields_set
        update: dict[str, Any] = {"name": self.name}
        if "seed" not in given:
            update["seed"] = self.seed
        if "t_end" not in given and self.t_end is not None:
            update["t_end"] = self.t_end
        if "races" not in given and self.races is not None:
            update["races"] = self.races
        if "speed" not in given and self._speed_from_range(model):
            update["speed"] = self.param_axis[1]
        return self.sensitivity.model_copy(update=update)

    def _starts_issues(self) -> list[Issue]:
        """Too few starts for ``min_balanced``: even with every start balanced the Wilson lower
        bound stays below it, so no design could pass."""
        import math

        from rotorlab._wilson import wilson_interval

        if self.min_balanced is None:
            return []
        n = self.design_starts
        best = float(wilson_interval(n, n, self.confidence)[0])
        if best >= self.min_balanced:
            return []
        need = n
        while float(wilson_interval(need, need, self.confidence)[0]) < self.min_balanced:
            need = math.ceil(need * 1.05) + 1
        lo = n
        while lo < need:  # the least count that reaches it
            mid = (lo + need) // 2
            lo, need = (mid + 1, need) if float(wilson_interval(mid, mid, self.confidence)[0]) < self.min_balanced \
                else (lo, mid)  # fmt: skip
        return [Issue(("starts",), f"even if every start balances, the {self.confidence * 100:g} % Wilson lower "
                                   f"bound of {n} starts is {best:.4f} < min_balanced = {self.min_balanced:g}: "
                                   f"give starts >= {need}", n)]  # fmt: skip

    def describe(self, model: AbstractModelSpec) -> str:
        names = ", ".join(self.vary)
        each = (f"{self.design_starts} run-up(s) each from random ball starts" if self.reads_run_ups else
                f"{self.design_starts} random starts each at {self.param_axis[3]} operating value(s)")
        return f"design search over {names} for least {' and '.join(self.objectives)} ({self.budget} designs, {each})"
