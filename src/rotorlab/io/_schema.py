"""The case-file schema, version 1: pydantic models whose fields hold SI floats after validation.

Layout of a case file::

    schema_version = 1           # optional
    name = "autobalancer"         # optional, defaults to the file name
    description = "one line"      # optional
    [model]                       # one model, chosen by `type` (see MODEL_SPECS)
    [model.speed]                 # optional spin-speed profile, chosen by `profile`
    [[model.balls]]               # zero or more balls
    [[analysis]]                  # zero or more analyses, chosen by `type` (see ANALYSIS_SPECS)

Every quantity accepts a plain number (SI) or a string with a unit (see :func:`to_si`).

For implementers
----------------
1. A new model type is one class deriving from :class:`AbstractModelSpec` with a field
   ``type: Literal["<name>"] = "<name>"``, plus one line in :data:`MODEL_SPECS`. Override
   :attr:`~AbstractModelSpec.n_balls`, :meth:`~AbstractModelSpec.critical_speed` and
   :meth:`~AbstractModelSpec.speed_profile` where the model has them.
2. A new analysis type is one class deriving from :class:`AbstractAnalysisSpec` with a field
   ``type: Literal["<name>"] = "<name>"``, plus one line in :data:`ANALYSIS_SPECS`. Declare
   pairs of mutually exclusive keys in ``exclusive``; put checks that need the model in
   :meth:`~AbstractAnalysisSpec.case_issues`.
3. Declare quantities with :func:`quantity` (dimension and bounds), integers with
   :func:`integer`; give every field a ``description`` with its SI unit in parentheses, it is
   quoted when the key is missing.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping
from types import MappingProxyType
from typing import Annotated, Any, ClassVar, Literal, Union

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PlainValidator,
    PrivateAttr,
    WithJsonSchema,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from rotorlab.io._errors import Issue, IssueGroup, did_you_mean
from rotorlab.io._units import DIMENSIONS, UnitError, convert

__all__ = [
    "SCHEMA_VERSION",
    "quantity",
    "integer",
    "AbstractSpeedProfile",
    "ConstantSpeed",
    "RampSpeed",
    "HillSpeed",
    "SPEED_PROFILES",
    "Ball",
    "AbstractModelSpec",
    "JeffcottBallsSpec",
    "MODEL_SPECS",
    "AbstractAnalysisSpec",
    "SimulateSpec",
    "ANALYSIS_SPECS",
    "Case",
    "exclusive_issues",
    "duplicate_name_issues",
]

#: The case-file schema version this module reads and writes.
SCHEMA_VERSION = 1

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
    }
    return Annotated[
        float, PlainValidator(_QuantityValidator(dimension, gt, ge, lt, le)), WithJsonSchema(schema)
    ]


class _IntegerValidator:
    def __init__(self, ge: int | None) -> None:
        self.ge = ge

    def __call__(self, value: Any) -> int:
        allowed = "an integer" + (f" >= {self.ge}" if self.ge is not None else "")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _error(f"must be {allowed}")
        if isinstance(value, float):
            if not (math.isfinite(value) and value.is_integer()):
                raise _error(f"must be {allowed}")
            value = int(value)
        if self.ge is not None and value < self.ge:
            raise _error(f"must be {allowed}")
        return int(value)


def integer(*, ge: int | None = None) -> Any:
    """Return the annotated type of an integer field (an integral float such as 2e3 is accepted).

    Parameters
    ----------
    ge : int, optional
        Lower bound.
    """
    return Annotated[
        int, PlainValidator(_IntegerValidator(ge)), WithJsonSchema({"type": "integer"})
    ]


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
            "1 to 64 letters, digits, '_', '-' or '.', starting with a letter or digit",
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


# --------------------------------------------------------------------------- speed profiles


class AbstractSpeedProfile(_Spec):
    """A prescribed spin speed omega(t) of the rotor (rad/s)."""

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        raise NotImplementedError

    @property
    def is_constant(self) -> bool:
        """Whether the speed does not change with time."""
        return False

    @property
    def final_speed(self) -> float:
        """The speed approached for large times (rad/s)."""
        raise NotImplementedError


class ConstantSpeed(AbstractSpeedProfile):
    """Constant spin speed.

    Parameters
    ----------
    speed : float
        Spin speed omega (rad/s), > 0.
    """

    profile: Literal["constant"] = "constant"
    speed: quantity("angular_speed", gt=0) = Field(description="spin speed (rad/s)")

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        return self.speed

    @property
    def is_constant(self) -> bool:
        """True: the speed does not change."""
        return True

    @property
    def final_speed(self) -> float:
        """The constant speed (rad/s)."""
        return self.speed


class RampSpeed(AbstractSpeedProfile):
    """Linear run-up (or run-down) from ``start`` to ``stop`` in ``duration``, then constant.

    Parameters
    ----------
    start : float
        Speed at t = 0 (rad/s), >= 0.
    stop : float
        Speed reached at t = duration and kept afterwards (rad/s), >= 0.
    duration : float
        Length of the ramp (s), > 0.

    Notes
    -----
    omega(t) = start + (stop - start) * min(t / duration, 1) for t >= 0.
    """

    profile: Literal["ramp"] = "ramp"
    start: quantity("angular_speed", ge=0) = Field(description="speed at t = 0 (rad/s)")
    stop: quantity("angular_speed", ge=0) = Field(description="speed after the ramp (rad/s)")
    duration: quantity("time", gt=0) = Field(description="duration of the ramp (s)")

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        fraction = min(max(t / self.duration, 0.0), 1.0)
        return self.start + (self.stop - self.start) * fraction

    @property
    def final_speed(self) -> float:
        """The speed after the ramp (rad/s)."""
        return self.stop


class HillSpeed(AbstractSpeedProfile):
    """Smooth run-up following a Hill function.

    Parameters
    ----------
    max_speed : float
        Speed approached for t -> infinity (rad/s), > 0.
    t_half : float
        Time at which half of ``max_speed`` is reached (s), > 0.
    exponent : float
        Steepness n of the run-up (dimensionless), 0.01 <= n <= 1000.

    Notes
    -----
    omega(t) = max_speed * t**n / (t_half**n + t**n) for t >= 0.
    """

    profile: Literal["hill"] = "hill"
    max_speed: quantity("angular_speed", gt=0) = Field(description="final speed (rad/s)")
    t_half: quantity("time", gt=0) = Field(description="time to reach half speed (s)")
    exponent: quantity("dimensionless", ge=0.01, le=1000) = Field(
        description="steepness n (-), 0.01 to 1000"
    )

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        if t <= 0.0:
            return 0.0
        ratio = (self.t_half / t) ** self.exponent
        return self.max_speed / (1.0 + ratio)

    @property
    def final_speed(self) -> float:
        """The speed approached for large times (rad/s)."""
        return self.max_speed


#: Spin-speed profiles by the value of their ``profile`` key.
SPEED_PROFILES: Mapping[str, type[AbstractSpeedProfile]] = MappingProxyType(
    {
        "constant": ConstantSpeed,
        "ramp": RampSpeed,
        "hill": HillSpeed,
    }
)

_SpeedProfile = Annotated[
    Union[tuple(SPEED_PROFILES.values())],  # noqa: UP007 - built from the registry
    Field(discriminator="profile"),
]


# --------------------------------------------------------------------------- models


class Ball(_Spec):
    """One balancing ball (or roller) running in a circular race of the disc.

    Parameters
    ----------
    mass : float
        Ball mass m (kg), > 0.
    radius : float
        Radius R of the ball's centre path, measured from the disc centre (m), > 0.
    inertia : float, optional
        Moment of inertia of the ball about the rotor axis (kg*m^2), >= mass * radius**2.
        Omitted: a point mass, ``mass * radius**2`` (filled in by the model spec).
    damping : float
        Viscous damping of the ball's motion relative to the disc (N*m*s/rad), >= 0.
    friction : float
        Coulomb friction coefficient of the ball in its race (-), >= 0.
    count : int
        Input only: repeat this ball ``count`` times (the model spec expands it). >= 1.
    """

    mass: quantity("mass", gt=0) = Field(description="ball mass (kg)")
    radius: quantity("length", gt=0) = Field(description="radius of the ball's path (m)")
    inertia: quantity("inertia", ge=0) | None = Field(
        None, description="inertia about the rotor axis (kg*m^2)"
    )
    damping: quantity("torque_damping", ge=0) = Field(
        0.0, description="viscous damping relative to the disc (N*m*s/rad)"
    )
    friction: quantity("dimensionless", ge=0) = Field(
        0.0, description="Coulomb friction coefficient (-)"
    )
    count: integer(ge=1) = Field(1, exclude=True, description="number of identical balls")

    @model_validator(mode="after")
    def _check_inertia(self) -> Ball:
        point = self.mass * self.radius**2
        if self.inertia is not None and self.inertia < point * (1.0 - 1e-12):
            raise IssueGroup(
                [
                    Issue(
                        ("inertia",),
                        f"must be >= mass * radius^2 = {point:.6g} kg*m^2 (a point mass)",
                        self.inertia,
                    )
                ]
            )
        return self


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


class JeffcottBallsSpec(AbstractModelSpec):
    """Jeffcott rotor (disc on a massless elastic shaft) with an automatic ball balancer.

    Parameters
    ----------
    frame : {"fixed", "rotating"}
        Coordinates of the disc centre: fixed (x, y) or co-rotating (u, v).
    disc_mass : float
        Disc mass M1 (kg), > 0.
    eccentricity : float
        Distance e between the disc's centre of mass and the shaft axis (m), >= 0.
    stiffness : float
        Lateral shaft stiffness c (N/m), > 0.
    damping : float
        External viscous damping of the disc centre beta (N*s/m), >= 0.
    speed : ConstantSpeed or RampSpeed or HillSpeed, optional
        The spin-speed profile; analyses may set their own constant speed instead.
    balls : tuple of Ball
        The balls, with ``count`` expanded and ``inertia`` filled in.

    Notes
    -----
    The critical speed is p = sqrt(c / M), with M = M1 + sum of the ball masses (seed 002,
    eq. (10)).
    """

    type: Literal["jeffcott_balls"] = "jeffcott_balls"
    frame: _choice("fixed", "rotating") = Field("fixed", description="fixed or rotating")
    disc_mass: quantity("mass", gt=0) = Field(description="disc mass M1 (kg)")
    eccentricity: quantity("length", ge=0) = Field(description="disc eccentricity e (m)")
    stiffness: quantity("stiffness", gt=0) = Field(description="shaft stiffness c (N/m)")
    damping: quantity("damping", ge=0) = Field(
        0.0, description="external viscous damping of the disc centre (N*s/m)"
    )
    speed: _SpeedProfile | None = Field(None, description="spin-speed profile")
    balls: tuple[Ball, ...] = Field((), description="balancing balls")

    @field_validator("balls", mode="after")
    @classmethod
    def _expand_balls(cls, balls: tuple[Ball, ...]) -> tuple[Ball, ...]:
        out = []
        for ball in balls:
            inertia = ball.inertia if ball.inertia is not None else ball.mass * ball.radius**2
            single = ball.model_copy(update={"count": 1, "inertia": inertia})
            out.extend([single] * ball.count)
        return tuple(out)

    @property
    def n_balls(self) -> int:
        """Number of balls."""
        return len(self.balls)

    @property
    def total_mass(self) -> float:
        """M = M1 + sum of ball masses (kg)."""
        return self.disc_mass + sum(b.mass for b in self.balls)

    def critical_speed(self) -> float:
        """Return p = sqrt(c / M) (rad/s), M = disc plus balls (seed 002, eq. (10))."""
        return math.sqrt(self.stiffness / self.total_mass)

    def speed_profile(self) -> AbstractSpeedProfile | None:
        """Return the ``[model.speed]`` profile, or None."""
        return self.speed


#: Model specifications by the value of their ``type`` key.
MODEL_SPECS: Mapping[str, type[AbstractModelSpec]] = MappingProxyType(
    {
        "jeffcott_balls": JeffcottBallsSpec,
    }
)

_ModelSpec = Annotated[
    Union[tuple(MODEL_SPECS.values())],  # noqa: UP007 - built from the registry
    Field(discriminator="type"),
]


# --------------------------------------------------------------------------- analyses


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

    type: str
    name: _Name | None = Field(None, description="unique name of the analysis")

    @model_validator(mode="after")
    def _check_exclusive(self) -> AbstractAnalysisSpec:
        present = {key for key in type(self).model_fields if getattr(self, key) is not None}
        issues = exclusive_issues(self.exclusive, present)
        if issues:
            raise IssueGroup(issues)
        return self

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Return the problems of this analysis that depend on the model (``loc`` relative)."""
        return []


class SimulateSpec(AbstractAnalysisSpec):
    """Time simulation of an ensemble of start-ups (one per initial ball configuration).

    Parameters
    ----------
    name : str, optional
        Unique name; default ``"simulate-<index>"``.
    speed_ratio : float, optional
        Constant spin speed as a multiple of the model's critical speed p (-), > 0.
    speed : float, optional
        Constant spin speed (rad/s), > 0. Neither ``speed_ratio`` nor ``speed``: the model's
        ``[model.speed]`` profile is followed.
    initial_ball_angles : tuple of tuple of float, optional
        Initial ball configurations, each with one angle per ball, measured from the unbalance
        (rad). Excludes ``ball_angle_grid``.
    ball_angle_grid : int, optional
        N >= 1: every ball takes the angles 2*pi*k/N, k = 0..N-1, giving N**n_balls
        configurations. Excludes ``initial_ball_angles``.
    t_end : float, optional
        Simulated time (s), > 0. Excludes ``revolutions``.
    revolutions : float, optional
        Simulated time as a number of revolutions at the (constant) analysis speed, > 0.
    n_save : int
        Number of points of the saved, uniform time grid, >= 2.
    rtol, atol : float
        Relative (0 < rtol < 1) and absolute (> 0) error tolerances of the integrator.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratio", "speed", False),
        ("initial_ball_angles", "ball_angle_grid", True),
        ("t_end", "revolutions", True),
    )

    type: Literal["simulate"] = "simulate"
    speed_ratio: quantity("dimensionless", gt=0) | None = Field(
        None, description="speed as a multiple of the critical speed (-)"
    )
    speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="constant spin speed (rad/s)"
    )
    initial_ball_angles: tuple[tuple[quantity("angle"), ...], ...] | None = Field(
        None, description="ball configurations, one angle per ball (rad)"
    )
    ball_angle_grid: integer(ge=1) | None = Field(
        None, description="N angles per ball, N**n_balls configurations"
    )
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    revolutions: quantity("dimensionless", gt=0) | None = Field(
        None, description="simulated revolutions at the analysis speed (-)"
    )
    n_save: integer(ge=2) = Field(2000, description="points of the saved time grid")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) = Field(1e-10, description="absolute tolerance")

    def spin_speed(self, model: AbstractModelSpec) -> float | None:
        """Return the constant spin speed of this analysis (rad/s), or None to follow a profile.

        ``speed`` if given, else ``speed_ratio * p``, else the model's profile speed if that
        profile is constant, else None.
        """
        if self.speed is not None:
            return self.speed
        if self.speed_ratio is not None:
            p = model.critical_speed()
            return None if p is None else self.speed_ratio * p
        profile = model.speed_profile()
        if profile is not None and profile.is_constant:
            return profile.final_speed
        return None

    def duration(self, model: AbstractModelSpec) -> float:
        """Return the simulated time (s): ``t_end``, or ``revolutions`` at the spin speed."""
        if self.t_end is not None:
            return self.t_end
        omega = self.spin_speed(model)
        if omega is None or self.revolutions is None:
            raise ValueError("revolutions need a constant spin speed")
        return self.revolutions * 2.0 * math.pi / omega

    def ball_angle_sets(self, n_balls: int) -> tuple[tuple[float, ...], ...]:
        """Return the initial ball configurations, shape (n_configurations, n_balls), in rad.

        Examples
        --------
        >>> spec = SimulateSpec(ball_angle_grid=2, t_end=1.0)
        >>> [[round(a, 4) for a in row] for row in spec.ball_angle_sets(2)]
        [[0.0, 0.0], [0.0, 3.1416], [3.1416, 0.0], [3.1416, 3.1416]]
        """
        if self.initial_ball_angles is not None:
            return self.initial_ball_angles
        n = self.ball_angle_grid or 1
        angles = [2.0 * math.pi * k / n for k in range(n)]
        return tuple(itertools.product(angles, repeat=n_balls))

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check ball-angle rows against the number of balls and that a spin speed exists."""
        issues = []
        n = model.n_balls
        for k, row in enumerate(self.initial_ball_angles or ()):
            if len(row) != n:
                issues.append(
                    Issue(
                        ("initial_ball_angles", k),
                        f"has {len(row)} angle(s) but the model has {n} ball(s): "
                        "give one angle per ball",
                        list(row),
                    )
                )
        profile = model.speed_profile()
        if self.speed_ratio is None and self.speed is None and profile is None:
            issues.append(
                Issue(
                    (),
                    "no spin speed: give speed_ratio or speed, or a [model.speed] profile",
                    show_value=False,
                )
            )
        if self.speed_ratio is not None and model.critical_speed() is None:
            issues.append(
                Issue(
                    ("speed_ratio",),
                    f"model '{model.type}' has no critical speed to scale: give speed instead",
                    self.speed_ratio,
                )
            )
        elif (
            self.revolutions is not None
            and (self.speed_ratio is not None or self.speed is not None or profile is not None)
            and self.spin_speed(model) is None
        ):
            issues.append(
                Issue(
                    ("revolutions",),
                    f"needs a constant spin speed, but the {profile.profile} profile changes: "
                    "give t_end instead",
                    self.revolutions,
                )
            )
        return issues


#: Analysis specifications by the value of their ``type`` key.
ANALYSIS_SPECS: Mapping[str, type[AbstractAnalysisSpec]] = MappingProxyType(
    {
        "simulate": SimulateSpec,
    }
)

_AnalysisSpec = Annotated[
    Union[tuple(ANALYSIS_SPECS.values())],  # noqa: UP007 - built from the registry
    Field(discriminator="type"),
]


# --------------------------------------------------------------------------- the case


class _SchemaVersionValidator:
    def __call__(self, value: Any) -> int:
        if isinstance(value, bool) or value != SCHEMA_VERSION:
            raise _error(f"unsupported schema version (this rotorlab reads {SCHEMA_VERSION})")
        return SCHEMA_VERSION


class Case(BaseModel):
    """A validated case: one model and the analyses to run on it, all values in SI.

    Build it with :func:`rotorlab.io.load_case`, :func:`rotorlab.io.parse_case` or
    :func:`rotorlab.io.validate_case`, which turn every problem into a
    :class:`~rotorlab.io.CaseError`; constructing it directly raises pydantic's
    ``ValidationError``.

    Parameters
    ----------
    schema_version : int
        Always 1.
    name : str
        Case name (letters, digits, '_', '-', '.').
    description : str
        One line shown by ``rotorlab cases``.
    model : JeffcottBallsSpec
        The model (any of :data:`MODEL_SPECS`).
    analyses : tuple of SimulateSpec
        The analyses in file order (key ``analysis`` in the file), with default names filled
        in (``"<type>-<index>"``).

    Attributes
    ----------
    source : str
        Path of the case file, ``"builtin:<name>"``, or the origin given to the parser.
    text : str
        The TOML text the case was read from ("" if built from Python objects).
    """

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    schema_version: Annotated[
        int, PlainValidator(_SchemaVersionValidator()), WithJsonSchema({"const": 1})
    ] = Field(SCHEMA_VERSION, description="case-file schema version")
    name: _Name = Field(description="case name")
    description: _Text = Field("", description="one-line description")
    model: _ModelSpec = Field(description="the model ([model] table)")
    analyses: tuple[_AnalysisSpec, ...] = Field(
        (), alias="analysis", description="analyses ([[analysis]] entries)"
    )

    _source: str = PrivateAttr("<python>")
    _text: str = PrivateAttr("")

    @field_validator("analyses", mode="after")
    @classmethod
    def _name_analyses(cls, analyses: tuple[Any, ...]) -> tuple[Any, ...]:
        issues = duplicate_name_issues([(a.name, a.type) for a in analyses])
        if issues:
            raise IssueGroup(issues)
        return tuple(
            a if a.name is not None else a.model_copy(update={"name": f"{a.type}-{i}"})
            for i, a in enumerate(analyses)
        )

    @model_validator(mode="after")
    def _check_against_model(self) -> Case:
        issues = []
        for i, analysis in enumerate(self.analyses):
            for issue in analysis.case_issues(self.model):
                issues.append(
                    Issue(("analysis", i, *issue.loc), issue.message, issue.value, issue.show_value)
                )
        if issues:
            raise IssueGroup(issues)
        return self

    @property
    def source(self) -> str:
        """Path of the case file, ``"builtin:<name>"``, or the parser's origin."""
        return self._source

    @property
    def text(self) -> str:
        """The TOML text the case was read from."""
        return self._text

    def analysis(self, name: str) -> Any:
        """Return the analysis called ``name``.

        Raises
        ------
        KeyError
            No analysis has that name; the message lists the names.
        """
        for a in self.analyses:
            if a.name == name:
                return a
        names = ", ".join(a.name for a in self.analyses) or "none"
        raise KeyError(f"no analysis named {name!r} (analyses: {names})")

    def model_dump_si(self) -> dict[str, Any]:
        """Return the case as plain Python data (dicts, lists, str, int, float, None), in SI.

        Keys follow the attribute names (``analyses``, not ``analysis``); ``source`` and
        ``text`` are not included.
        """
        return _plain(self.model_dump(mode="python"))


def _plain(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    return obj
