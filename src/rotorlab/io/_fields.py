"""Building blocks of the case-file schema: field types with units, and the abstract specs.

:func:`quantity`, :func:`integer` and :func:`flag` declare fields whose values are checked and
converted to SI when a case is read; :class:`AbstractModelSpec` and
:class:`AbstractAnalysisSpec` are the bases of every ``[model]`` type and ``[[analysis]]``
type (see the "For implementers" list in :mod:`rotorlab.io._schema`). Model and analysis
modules import from here, and :mod:`rotorlab.io._schema` assembles them into the registries.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any, ClassVar, get_args

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, WithJsonSchema, model_validator
from pydantic_core import PydanticCustomError

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.io._errors import Issue, IssueGroup, did_you_mean
from rotorlab.io._units import DIMENSIONS, UnitError, convert

if TYPE_CHECKING:
    from rotorlab.io._jeffcott_specs import AbstractSpeedProfile

__all__ = [
    "Unit",
    "field_unit",
    "quantity",
    "integer",
    "flag",
    "AbstractModelSpec",
    "AbstractAnalysisSpec",
    "exclusive_issues",
    "duplicate_name_issues",
    "plain_data",
    "speed_text",
    "RaceIndices",
    "chosen_race_issues",
]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$")


def _error(detail: str) -> PydanticCustomError:
    return PydanticCustomError("rotorlab", "{detail}", {"detail": detail})


def _bounds_text(gt: float | None, ge: float | None, lt: float | None, le: float | None) -> str:
    parts = []
    if gt is not None:
        parts.append(f"> {gt:g}")
    if ge is not None:
        parts.append(f">= {ge:g}")
    if lt is not None:
        parts.append(f"< {lt:g}")
    if le is not None:
        parts.append(f"<= {le:g}")
    return " and ".join(parts)


class _QuantityValidator:
    """Convert a case-file value to SI (see :func:`convert`) and check its bounds."""

    def __init__(self, dimension: str, gt=None, ge=None, lt=None, le=None) -> None:
        self.dimension = DIMENSIONS[dimension]
        self.bounds = (gt, ge, lt, le)

    def __call__(self, value: Any) -> float:
        try:
            x = convert(value, self.dimension)
        except UnitError as exc:
            raise _error(str(exc)) from None
        gt, ge, lt, le = self.bounds
        if (
            (gt is not None and not x > gt)
            or (ge is not None and not x >= ge)
            or (lt is not None and not x < lt)
            or (le is not None and not x <= le)
        ):
            si = self.dimension.si
            detail = f"must be {_bounds_text(gt, ge, lt, le)}" + (f" ({si})" if si else "")
            if isinstance(value, str):
                detail += f", got {x:.6g}" + (f" {si}" if si else "")
            raise _error(detail)
        return x


@dataclass(frozen=True)
class Unit:
    """The SI unit of a field's values, as metadata of its annotated type (``"1"``: dimensionless).

    :func:`quantity` adds it; a field whose validator is its own declares it with
    ``Annotated[..., Unit("rad/s")]``. :func:`field_unit` reads it back (the report's parameter
    tables show it).
    """

    si: str


def _units_in(tp: Any) -> list[str]:
    found = [m.si for m in getattr(tp, "__metadata__", ()) if isinstance(m, Unit)]
    for arg in get_args(tp):
        found += [u for u in _units_in(arg) if u not in found]
    return found


def field_unit(info: Any) -> str:
    """Return the SI unit of a pydantic field from its metadata ("" if it has none).

    Parameters
    ----------
    info : pydantic.fields.FieldInfo

    Returns
    -------
    str
        The :class:`Unit` of the field's type, looked up through ``Optional``, tuples and
        nested ``Annotated`` types; several distinct units are joined by ``", "`` (a tuple of an
        angle and a speed gives ``"rad, rad/s"``).

    Examples
    --------
    >>> from pydantic import BaseModel
    >>> class Spec(BaseModel):
    ...     speed: quantity("angular_speed") | None = None
    ...     start: tuple[quantity("angle"), quantity("angular_speed")] = (0.0, 0.0)
    ...     ratio: quantity("dimensionless") = 1.0
    >>> [field_unit(f) for f in Spec.model_fields.values()]
    ['rad/s', 'rad, rad/s', '1']
    """
    found = [m.si for m in info.metadata if isinstance(m, Unit)]
    found += [u for u in _units_in(info.annotation) if u not in found]
    return ", ".join(found)


def quantity(
    dimension: str,
    *,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
) -> Any:
    """Return the annotated type of a quantity field (a float in SI after validation).

    Parameters
    ----------
    dimension : str
        A key of :data:`rotorlab.io.DIMENSIONS`.
    gt, ge, lt, le : float, optional
        Bounds on the SI value.

    Returns
    -------
    typing.Annotated
        ``Annotated[float, ...]`` accepting a number (SI) or a string with a unit.
    """
    dim = DIMENSIONS[dimension]
    schema = {
        "anyOf": [{"type": "number"}, {"type": "string"}],
        "description": f"{dim.noun}: a number in {dim.si or 'SI'} or a string with a unit",
        "unit": dim.si or "1",  # the SI unit of the value after reading (as Unit below)
    }
    return Annotated[
        float, PlainValidator(_QuantityValidator(dimension, gt, ge, lt, le)), WithJsonSchema(schema),
        Unit(dim.si or "1"),
    ]


class _IntegerValidator:
    def __init__(self, ge: int | None, le: int | None = None) -> None:
        self.ge, self.le = ge, le

    def __call__(self, value: Any) -> int:
        allowed = ("an integer" + (f" >= {self.ge}" if self.ge is not None else "")
                   + (f" and <= {self.le}" if self.le is not None else ""))
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _error(f"must be {allowed}")
        if isinstance(value, float):
            if not (math.isfinite(value) and value.is_integer()):
                raise _error(f"must be {allowed}")
            value = int(value)
        if (self.ge is not None and value < self.ge) or (self.le is not None and value > self.le):
            raise _error(f"must be {allowed}")
        return int(value)


def integer(*, ge: int | None = None, le: int | None = None) -> Any:
    """Return the annotated type of an integer field (an integral float such as 2e3 is accepted).

    Parameters
    ----------
    ge, le : int, optional
        Lower and upper bounds.
    """
    return Annotated[
        int, PlainValidator(_IntegerValidator(ge, le)), WithJsonSchema({"type": "integer"})
    ]


class _FlagValidator:
    def __call__(self, value: Any) -> bool:
        if not isinstance(value, bool):
            raise _error("must be true or false")
        return value


def flag() -> Any:
    """Return the annotated type of a boolean field (only TOML ``true``/``false`` accepted)."""
    return Annotated[bool, PlainValidator(_FlagValidator()), WithJsonSchema({"type": "boolean"})]


class _TextValidator:
    def __init__(self, pattern: re.Pattern[str] | None, what: str) -> None:
        self.pattern = pattern
        self.what = what

    def __call__(self, value: Any) -> str:
        if not isinstance(value, str):
            raise _error(f"must be a string ({self.what})")
        if self.pattern is not None and not self.pattern.match(value):
            raise _error(f"must be {self.what}")
        return value


_Name = Annotated[
    str,
    PlainValidator(
        _TextValidator(
            _NAME,
            "1 to 64 ASCII letters (a-z, A-Z), digits, '_', '-' or '.', starting with a letter or digit",
        )
    ),
    WithJsonSchema({"type": "string", "pattern": _NAME.pattern}),
]
_Text = Annotated[
    str, PlainValidator(_TextValidator(None, "free text")), WithJsonSchema({"type": "string"})
]


class _ChoiceValidator:
    def __init__(self, options: tuple[str, ...]) -> None:
        self.options = options

    def __call__(self, value: Any) -> str:
        if value in self.options:
            return value
        quoted = ", ".join(f'"{o}"' for o in self.options)
        hint = did_you_mean(value, self.options) if isinstance(value, str) else ""
        raise _error(f"must be one of {quoted}" + (f"; {hint}" if hint else ""))


def _choice(*options: str) -> Any:
    return Annotated[
        str, PlainValidator(_ChoiceValidator(options)), WithJsonSchema({"enum": list(options)})
    ]


class _Spec(BaseModel):
    """Base of all schema models: frozen, and unknown keys are errors."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class AbstractModelSpec(_Spec):
    """Base of the model specifications (the ``[model]`` table).

    Subclasses add ``type: Literal["<name>"]`` and their parameters; see the module docstring.
    """

    @property
    def n_balls(self) -> int:
        """Number of balancing bodies (balls, pendulums) after expanding ``count``."""
        return 0

    def critical_speed(self) -> float | None:
        """Return the reference (critical) speed p used by ``speed_ratio`` (rad/s), if any."""
        return None

    def speed_profile(self) -> AbstractSpeedProfile | None:
        """Return the model's own spin-speed profile, if it has one."""
        return None

    def describe(self) -> str:
        """Return a one-line description of the model (shown by ``rotorlab validate``)."""
        return str(getattr(self, "type", type(self).__name__))

    #: Whether basins and sweeps of this model may vary any number of its ``[model]`` table by
    #: key path (``model.<key path>``; see :data:`rotorlab.io._coordinates.KEY_PREFIX`).
    sweeps_keys: ClassVar[bool] = False

    def start_coordinates(self) -> dict[str, str]:
        """The coordinates (state entries and parameters) a basin or sweep of this model varies,
        name -> dimension; empty for a model without a regime mapper."""
        return {}

    #: Whether the model always spins at its own ``spin_speed`` (a toroidal ball): its basins and
    #: sweeps take no ``speed`` or ``speed_ratio`` (they vary or fix ``spin_speed`` instead).
    spins_at_own_speed: ClassVar[bool] = False

    def missing_coordinate(self, name: str) -> str | None:
        """Why this model has no start coordinate ``name``, where it can say so better than by
        listing the coordinates it has (``"has 2 ball(s)"`` for ``psi_3``); None otherwise."""
        return None

    def without_regimes(self) -> str:
        """What this model is, for a message saying that basins and sweeps cannot map it."""
        return f"model type {getattr(self, 'type', None)!r}"

    def basin_issues(self, spec: AbstractAnalysisSpec) -> list[Issue]:
        """Check a ``basin`` analysis' starts against this model, beyond the names of its
        coordinates (a toroidal ball: its sizes stay ordered at every start)."""
        return []

    def linear_structure(self) -> AbstractModelSpec | None:
        """The linear rotor spec the linear analyses (``campbell``, ``modes``, ...) run on, or None.

        A linear rotor model is its own structure; a composed model returns the structure it is
        built from.
        """
        return None

    def race_issues(self, races: tuple[int, ...] | None) -> list[Issue]:
        """Check an analysis' choice of ball races (``races = [...]``; None: all of them)."""
        if races is None:
            return []
        return [Issue(("races",), f"model '{getattr(self, 'type', '?')}' has no ball races to choose "
                                  "from: leave races out", list(races))]

    def balls_in(self, races: tuple[int, ...] | None) -> int:
        """Number of balls of the chosen races (None: all balls)."""
        return self.n_balls

    def steady_issues(self, analysis: AbstractAnalysisSpec) -> list[Issue]:
        """Check that a steady-motion analysis (``steady``, ``stability-chart``, ``verify``,
        ``run-up``) can run on this model; the model types that can override this."""
        what = f"model '{getattr(self, 'type', '?')}' with {self.n_balls} ball(s)"
        return [Issue(("type",), "needs a rotor with balls (a jeffcott_balls model with at least one "
                                 f"ball, or a machine model; this case has a {what})", analysis.type)]


    def passing_torque_issues(self, analysis: AbstractAnalysisSpec) -> list[Issue]:
        """Check a ``run-up`` with ``passing_torque = true``: the model must be driven by a motor
        whose torque can be scaled; the model types that have one override this."""
        return [Issue(("passing_torque",), "needs a machine model driven by a motor ([model.drive] profile = "
                                           f"\"motor\"); model '{getattr(self, 'type', '?')}' has none", True)]


#: Type of the ``races`` key of analyses that run on a machine's ball races (indices, >= 0).
RaceIndices = tuple[integer(ge=0), ...]


def chosen_race_issues(model: AbstractModelSpec, races: tuple[int, ...] | None,
                       named: list[tuple[tuple, str]]) -> list[Issue]:
    """Check a basin's or sweep's choice of races and its ball coordinates against it.

    ``named`` holds ``(key path, coordinate name)``; a ``psi_<i>`` or ``dpsi_<i>`` beyond the
    balls of the chosen races is an issue at its key path.
    """
    issues = model.race_issues(races)
    if races is None or issues:
        return issues
    n = model.balls_in(races)
    for key, name in named:
        hit = re.fullmatch(r"d?psi_(\d+)", str(name))
        if hit and int(hit.group(1)) > n:
            issues.append(Issue(key, f"{name!r} names ball {hit.group(1)}, but the races "
                                     f"{list(races)} have {n} ball(s)", name))
    return issues


def speed_text(omega: float | None, p: float | None = None) -> str:
    """A spin speed in rad/s, rpm and Hz (and as omega / p when ``p`` is given), for messages.

    Examples
    --------
    >>> speed_text(251.32741228718345, 125.66370614359172)
    '251.327 rad/s = 2400 rpm = 40 Hz (ω/p = 2)'
    """
    if omega is None:
        return "follows the model's speed profile"
    text = f"{omega:.6g} rad/s = {omega * RPM_PER_RAD_S:.6g} rpm = {omega / (2 * math.pi):.6g} Hz"
    return text + (f" (ω/p = {omega / p:.3g})" if p else "")


def exclusive_issues(
    pairs: tuple[tuple[str, str, bool], ...], present: set[str]
) -> list[Issue]:
    """Check pairs of mutually exclusive keys.

    Parameters
    ----------
    pairs : tuple of (str, str, bool)
        ``(a, b, required)``: ``a`` and ``b`` exclude each other; if ``required``, one of them
        must be given.
    present : set of str
        The keys given.

    Returns
    -------
    list of Issue
        With an empty ``loc`` (the analysis itself).
    """
    issues = []
    for a, b, required in pairs:
        if a in present and b in present:
            issues.append(
                Issue((), f"{a} and {b} exclude each other: give only one", show_value=False)
            )
        elif required and a not in present and b not in present:
            issues.append(Issue((), f"give one of {a} or {b}", show_value=False))
    return issues


def duplicate_name_issues(entries: list[tuple[str | None, str]]) -> list[Issue]:
    """Find analyses whose names (given, or defaulted to ``<type>-<index>``) collide.

    Parameters
    ----------
    entries : list of (str or None, str)
        For each analysis, its given name (None if omitted) and its type.

    Returns
    -------
    list of Issue
        ``loc`` is ``(index, "name")`` for a given name, ``(index,)`` for a default one.
    """
    first: dict[str, int] = {}
    issues = []
    for index, (given, kind) in enumerate(entries):
        name = given if given is not None else f"{kind}-{index}"
        if name in first:
            message = f"duplicate analysis name '{name}' (also used by analysis[{first[name]}])"
            if given is not None:
                issues.append(Issue((index, "name"), message, given))
            else:
                issues.append(Issue((index,), message + "; give a name", show_value=False))
        else:
            first[name] = index
    return issues


class AbstractAnalysisSpec(_Spec):
    """Base of the analysis specifications (the ``[[analysis]]`` entries).

    Parameters
    ----------
    name : str, optional
        Unique name of the analysis; defaults to ``"<type>-<index>"`` (0-based index in the
        file). Names become file names of results.
    """

    #: Pairs ``(a, b, required)`` of mutually exclusive keys.
    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = ()

    #: The ``[model]`` types this analysis runs on; None: any (the model's own hooks, such as
    #: ``steady_issues``, say what it cannot run). Read by :meth:`case_issues` and, through
    #: :meth:`wrong_model`, by the command line: one list, no test of the type elsewhere.
    model_types: ClassVar[tuple[str, ...] | None] = None
    #: What a case with a model of another type is told (``{kind}``: its type; ``{types}``: the
    #: accepted ones, joined by "or").
    wrong_model_message: ClassVar[str] = "needs a {types} model, not {kind!r}"

    type: str
    name: _Name | None = Field(None, description="unique name of the analysis")

    @model_validator(mode="after")
    def _check_exclusive(self) -> AbstractAnalysisSpec:
        present = {key for key in type(self).model_fields if getattr(self, key) is not None}
        issues = exclusive_issues(self.exclusive, present)
        if issues:
            raise IssueGroup(issues)
        return self

    @classmethod
    def wrong_model(cls, model: AbstractModelSpec) -> str | None:
        """Why this analysis type cannot run on ``model``'s type (:attr:`model_types`), or None.

        Examples
        --------
        >>> from rotorlab.io import WorkingPointSpec, load_case
        >>> WorkingPointSpec.wrong_model(load_case("autobalancer").model)
        "needs a toroidal_ball model, not 'jeffcott_balls'"
        >>> WorkingPointSpec.wrong_model(load_case("strautmanis-torus").model) is None
        True
        """
        kind = getattr(model, "type", None)
        if cls.model_types is None or kind in cls.model_types:
            return None
        return cls.wrong_model_message.format(kind=kind, types=" or ".join(cls.model_types))

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Return the problems of this analysis that depend on the model (``loc`` relative).

        Here: a model type outside :attr:`model_types`; a subclass adds its own checks after
        ``super().case_issues(model)`` comes back empty.
        """
        problem = self.wrong_model(model)
        return [] if problem is None else [Issue(("type",), problem, self.type)]

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description of what the analysis computes on ``model``."""
        return f"{self.type} analysis"

    def summary(self, model: AbstractModelSpec) -> dict[str, Any]:
        """Return plain data describing the analysis on ``model`` (``rotorlab validate --json``)."""
        return {"description": self.describe(model)}


def plain_data(obj: Any) -> Any:
    """Turn dumped pydantic data into plain data: tuples become lists, recursively."""
    if isinstance(obj, dict):
        return {k: plain_data(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain_data(v) for v in obj]
    return obj
