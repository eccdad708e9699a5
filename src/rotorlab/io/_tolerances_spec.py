"""Case-file spec of the ``tolerances`` analysis: Sobol indices of P(balanced), the residual vibration
and the transient peak of a balancer machine with respect to uncertain inputs with stated
distributions, and Monte-Carlo envelopes of its vibration (:mod:`rotorlab.analyses._tolerances`;
``rotorlab tolerances`` adds a Zarr store, resume and Dask).

Layout::

    [[analysis]]
    type = "tolerances"
    samples = 32        # base samples N (a power of 2): N (D + 2) machines for D inputs
    starts = 4          # ball starts per machine (the same starts at every machine)
    seed = 0
    t_end = "8 s"
    [analysis.inputs]   # named parameters (key paths), ball_mass, ball_damping, support_anisotropy
    "races[0].balls[0].mass" = {distribution = "normal", tolerance = 0.02}   # std 2 % of the case value
    "races[0].radius" = {distribution = "normal", mean = "40 mm", std = "0.05 mm"}
    "races[0].balls[0].rolling" = {distribution = "normal", mean = "1 um", std = "0.5 um", low = "0 m"}
    ball_damping = {distribution = "uniform", low = "1e-4 N*m*s", high = "4e-4 N*m*s"}
    support_anisotropy = {distribution = "uniform", low = -0.05, high = 0.05}

Examples
--------
>>> spec = TolerancesSpec(inputs={"ball_damping": {"distribution": "uniform", "low": 1e-4, "high": 4e-4},
...                               "races[0].radius": {"distribution": "normal", "tolerance": 0.01}})
>>> spec.inputs["races[0].radius"]["tolerance"], spec.samples
(0.01, 32)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PlainValidator, WithJsonSchema

from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, RaceIndices, Unit, _error, integer, quantity

__all__ = ["TolerancesSpec", "ALIASES"]

#: Inputs that are no single key path: every ball's mass or damping at once, and the supports'
#: anisotropy ``(k_yy - k_xx) / (k_xx + k_yy)`` (:func:`rotorlab.continuation.with_anisotropy`).
ALIASES = {"ball_mass": "mass", "ball_damping": "torque_damping", "support_anisotropy": "dimensionless"}
#: How far from the mean (in std) a normal's draws may reach (:func:`rotorlab.explore.sobol_sample`).
_REACH = 6.5
_KEYS = {"normal": ("mean", "std", "tolerance", "low", "high"), "uniform": ("low", "high", "tolerance")}


def _dimension(name: str) -> str | None:
    """The dimension of an input's values (None: no model has that number)."""
    from rotorlab.io._coordinates import KEY_PREFIX, key_quantity

    if name in ALIASES:
        return ALIASES[name]
    found = key_quantity(KEY_PREFIX + name)
    if found is None:
        return None
    from rotorlab.io._units import DIMENSIONS

    return next(k for k, d in DIMENSIONS.items() if d is found.dimension)


def _read_inputs(value: Any) -> dict[str, dict[str, Any]]:
    """Read ``{NAME = {distribution = ..., ...}}`` into SI numbers (no model needed); every problem
    at once, each at its key path (``inputs.<NAME>.<key>``)."""
    from rotorlab.io._errors import IssueGroup
    from rotorlab.io._units import UnitError, convert

    if not isinstance(value, Mapping) or not value:
        raise _error("must be a table NAME = {distribution = \"normal\" | \"uniform\", ...} of two or more inputs")
    out, issues = {}, []
    for name, entry in value.items():
        name = str(name)
        dim = _dimension(name)
        unknown = Issue((name,), f"not a number of any model (give a named parameter's key path such as "
                                 f"races[0].balls[0].mass, or one of {', '.join(ALIASES)})", None,
                        show_value=False)  # fmt: skip
        plain = isinstance(entry, Mapping) and all(isinstance(v, (int, float)) for k, v in entry.items()
                                                   if k != "distribution")  # fmt: skip
        if dim is None and not plain:
            issues.append(unknown)  # plain numbers: the model decides (an integer key is structural)
            continue
        dim = dim or "dimensionless"
        if not isinstance(entry, Mapping) or entry.get("distribution") not in _KEYS:
            got = entry.get("distribution") if isinstance(entry, Mapping) else entry
            issues.append(Issue((name, "distribution"), "give distribution = \"normal\" or \"uniform\"", got))
            continue
        kind = entry["distribution"]
        for key in sorted(set(entry) - {"distribution", *_KEYS[kind]}):
            issues.append(Issue((name, key), f"not allowed for a {kind} distribution (allowed: "
                                             f"{', '.join(_KEYS[kind])})", entry[key]))  # fmt: skip
        item: dict[str, Any] = {"distribution": kind}
        for key in _KEYS[kind]:
            raw = entry.get(key)
            item[key] = None
            if raw is None:
                continue
            try:
                item[key] = convert(raw, "dimensionless" if key == "tolerance" else dim)
            except UnitError as exc:
                issues.append(Issue((name, key), str(exc), raw))
                continue
            if not math.isfinite(item[key]):
                issues.append(Issue((name, key), "must be finite", raw))
        out[name] = item
    if issues:
        raise IssueGroup(issues)
    return out


_InputsField = Annotated[dict[str, dict[str, Any]], PlainValidator(_read_inputs),
                         WithJsonSchema({"type": "object", "additionalProperties": {"type": "object"}}),
                         Unit("SI")]  # fmt: skip


class TolerancesSpec(AbstractAnalysisSpec):
    """Sobol indices of a balancer machine's outcome with respect to uncertain inputs.

    Parameters
    ----------
    inputs : {NAME: {distribution, ...}}
        Two or more uncertain inputs: a named parameter of the machine (the case's key path,
        ``races[0].balls[0].mass``, ``unbalances[0].phase`` ...), ``ball_mass`` or
        ``ball_damping`` (every ball at once) or ``support_anisotropy``. A ``normal`` has ``mean``
        (default the case value) and ``std`` or ``tolerance`` (std relative to the mean), and
        optional truncation bounds ``low``/``high``; a ``uniform`` has ``low`` and ``high``, or
        ``tolerance`` (the case value +- that fraction). Values SI or with units.
    samples : int
        Base samples N, a power of 2: N (D + 2) machines are simulated for D inputs.
    starts : int
        Random ball starts per machine, the same at every machine (common random numbers):
        P(balanced) of a machine is the fraction of them that balance.
    seed : int
        Seed of the design and of the starts.
    t_end : float
        Simulated time of every start (s).
    n_horizons : int
        Windows the run is cut into: the vibration amplitude of each (its envelope over time),
        the last one the residual vibration, the largest the transient peak.
    speed : float, optional
        Constant spin speed (rad/s); default the case's constant drive speed.
    confidence : float
        Level of the bootstrap intervals of the indices and of the envelope band's
        complement (0.9: 5-95 %).
    resamples : int
        Bootstrap resamples of the indices.
    chunk : int, optional
        Machines per chunk of the sweep engine.
    races : list of int, optional
        The ball races that take part (default all); the inputs' ``races[i]`` count the chosen
        races from 0.
    """

    model_types: ClassVar[tuple[str, ...]] = ("machine",)
    wrong_model_message: ClassVar[str] = "needs a machine model with balls, not {kind!r}"

    type: Literal["tolerances"] = "tolerances"
    inputs: _InputsField = Field(description="uncertain inputs {NAME = {distribution = ..., ...}} (SI)")
    samples: integer(ge=2, le=65536) = Field(32, description="base samples N, a power of 2")
    starts: integer(ge=1, le=1024) = Field(4, description="random ball starts per machine")
    seed: integer(ge=0) = Field(0, description="seed of the design and the starts")
    t_end: quantity("time", gt=0) = Field(8.0, description="simulated time of every start (s)")
    n_horizons: integer(ge=2, le=400) = Field(40, description="windows of the vibration envelope")
    speed: quantity("angular_speed", gt=0) | None = Field(None, description="constant spin speed (rad/s)")
    confidence: quantity("dimensionless", gt=0, lt=1) = Field(0.95, description="level of the intervals (-)")
    resamples: integer(ge=10, le=10000) = Field(200, description="bootstrap resamples")
    chunk: integer(ge=1, le=100_000) | None = Field(None, description="machines per chunk")
    races: RaceIndices | None = Field(None, description="ball races that take part (default all)")

    def machine(self, model: AbstractModelSpec) -> Any:
        """The machine the inputs' names refer to: the case's, with the chosen ``races`` only
        (renumbered from 0 in the order given)."""
        from dataclasses import replace

        from rotorlab.io._machine_spec import build_machine

        machine = build_machine(model)
        return machine if self.races is None else replace(machine, races=tuple(machine.races[i] for i in self.races))

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the machine (balls, a constant speed), every input's name, its distribution
        against the parameter's range and the design size."""
        issues = super().case_issues(model)
        if issues:
            return issues
        if self.samples & (self.samples - 1):
            issues.append(Issue(("samples",), "must be a power of 2 (the balance of the Sobol sequence)", self.samples))
        if len(self.inputs) < 2:
            issues.append(Issue(("inputs",), "give two or more uncertain inputs", list(self.inputs)))
        race_issues = model.race_issues(self.races)
        if race_issues:
            return issues + race_issues
        try:
            machine = self.machine(model)
        except (ValueError, TypeError):
            return issues  # the model's own checks report it
        if machine.n_balls == 0:
            return issues + [Issue(("type",), "needs a machine with balls (a balancer)", self.type)]
        from rotorlab.models import ConstantSpeed

        if self.speed is None and (not isinstance(machine.drive, ConstantSpeed) or machine.drive.speed == 0):
            issues.append(Issue(("speed",), "give the constant spin speed (the case's drive is not a constant "
                                            "nonzero speed)", None, show_value=False))  # fmt: skip
        for name in self.inputs:
            try:
                self.distribution(name, machine)
            except ValueError as exc:
                issues.append(Issue(("inputs", name), str(exc), dict(self.inputs[name])))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        d = len(self.inputs)
        return (f"Sobol indices of P(balanced), residual vibration and transient peak over {d} uncertain inputs "
                f"({', '.join(self.inputs)}): {self.samples * (d + 2)} machines x {self.starts} starts of "
                f"{self.t_end:g} s")

    def distribution(self, name: str, machine: Any) -> tuple[Any, Any]:
        """The :class:`~rotorlab.explore.Distribution` of input ``name`` on ``machine`` (a built
        :class:`~rotorlab.models.Machine`) and the :class:`~rotorlab.models.Parameter` whose range
        it must keep (None for an alias); ValueError saying what is wrong."""
        from rotorlab._distributions import Distribution

        entry = self.inputs[name]
        case_value, param = _case_value(name, machine)
        mean = entry.get("mean") if entry.get("mean") is not None else case_value
        tol = entry.get("tolerance")
        if tol is not None and not tol > 0:
            raise ValueError(f"tolerance must be > 0 (a fraction of the value), got {tol:g}")
        if tol is not None and (mean is None or mean == 0):
            raise ValueError("a relative tolerance needs a nonzero value; give mean and std (or low and high)")
        if entry["distribution"] == "normal":
            if (entry.get("std") is None) == (tol is None):
                raise ValueError("give std or tolerance (one of them)")
            std = entry["std"] if entry.get("std") is not None else abs(mean) * tol
            low = entry.get("low") if entry.get("low") is not None else -math.inf
            high = entry.get("high") if entry.get("high") is not None else math.inf
            # truncated at the parameter's range where the design's draws could reach it (they
            # stay within 6.1 std of the mean: the quantiles are taken at u in [5e-10, 1 - 5e-10])
            gt, ge, lt, le = param.bounds
            lower = gt if gt is not None else ge
            upper = lt if lt is not None else le
            if lower is not None and lower > mean - _REACH * std:
                low = max(low, lower)
            if upper is not None and upper < mean + _REACH * std:
                high = min(high, upper)
            dist = Distribution("normal", mean=float(mean), std=float(std), low=float(low), high=float(high))
        else:
            given = entry.get("low") is not None and entry.get("high") is not None
            if given == (tol is not None):
                raise ValueError("give low and high, or tolerance (the case value +- that fraction)")
            low, high = (entry["low"], entry["high"]) if given else (mean - abs(mean) * tol, mean + abs(mean) * tol)
            dist = Distribution("uniform", low=float(low), high=float(high))
        _check_support(dist, param)
        return dist, param


#: The ranges of the aliases (gt, ge, lt, le), those of a ball's keys and of an anisotropy.
_ALIAS_BOUNDS = {"ball_mass": ((0.0, None, None, None), "kg"), "ball_damping": ((None, 0.0, None, None), "N*m*s/rad"),
                 "support_anisotropy": ((-1.0, None, 1.0, None), "1")}


def _case_value(name: str, machine: Any) -> tuple[float | None, Any]:
    """The value input ``name`` has in the case (None where there is none) and its Parameter."""
    from rotorlab.models import Parameter

    if name in _ALIAS_BOUNDS:
        bounds, unit = _ALIAS_BOUNDS[name]
        if name == "support_anisotropy":
            if not machine.structure.is_isotropic:
                raise ValueError("the supports are already anisotropic: support_anisotropy is measured from "
                                 "isotropic ones")  # fmt: skip
            return 0.0, Parameter(name, unit, 0.0, bounds)
        values = {float(getattr(b, name[5:])) for r in machine.races for b in r.balls}
        value = values.pop() if len(values) == 1 else None
        return value, Parameter(name, unit, math.nan if value is None else value, bounds)
    space = machine.parameters
    if name not in space:
        import difflib

        names = [n for n in space.names if not space.structural(n)]
        near = difflib.get_close_matches(name, names, n=4, cutoff=0.6)
        hint = f"did you mean {', '.join(near)}? " if near else ""
        raise ValueError(f"not a named parameter of this machine ({hint}it has {len(names)}: {', '.join(names[:6])}, "
                         f"...; `rotorlab show CASE` lists them; or one of {', '.join(ALIASES)})")
    if space.structural(name):
        raise ValueError("structural (a new value changes the compiled layout): it cannot be uncertain")
    return float(space[name].value), space[name]


def _check_support(dist: Any, param: Any) -> None:
    """ValueError where the distribution's draws reach values outside the parameter's range."""
    import numpy as np

    from rotorlab._distributions import U_CLIP

    lo, hi = (float(v) for v in dist.quantile(np.array([U_CLIP, 1.0 - U_CLIP])))
    gt, ge, lt, le = param.bounds
    bad = []
    if gt is not None and not lo > gt:
        bad.append(f"> {gt:g}")
    if ge is not None and not lo >= ge:
        bad.append(f">= {ge:g}")
    if lt is not None and not hi < lt:
        bad.append(f"< {lt:g}")
    if le is not None and not hi <= le:
        bad.append(f"<= {le:g}")
    if bad:
        raise ValueError(f"{dist.describe()} reaches values the parameter cannot take (it must be "
                         f"{' and '.join(bad)} {param.unit}): give low/high within that range")  # fmt: skip
