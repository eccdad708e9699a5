"""The ``continuation`` analysis: branches of steady motions of a machine with balls (or a
``jeffcott_balls`` rotor) continued in a named parameter, optionally with fold and Hopf curves in a
second one (:mod:`rotorlab.continuation`).

Example::

    [[analysis]]
    type = "continuation"
    param = "drive.speed"
    range = ["600 rpm", "3000 rpm"]
    start_from = "balanced"           # balanced | side | all | a motion's label ("side 01") | hopf | simulation
    param2 = "ball_mass"              # optional: fold and Hopf curves in a second parameter
    range2 = ["10 g", "40 g"]
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PlainValidator, ValidationInfo, WithJsonSchema, field_validator

from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, Unit, _error, _QuantityValidator, flag, quantity

__all__ = ["ContinuationSpec", "continuation_dimension", "CONTINUATION_NAMES"]

#: The parameter names a continuation takes, as patterns, and their dimensions (io/_units.py).
CONTINUATION_NAMES: tuple[tuple[str, str, str], ...] = (
    (r"drive\.speed", "angular_speed", "drive.speed"),
    (r"ball_mass", "mass", "ball_mass (every ball)"),
    (r"ball_mass_scaled_damping", "mass", "ball_mass_scaled_damping (every ball, its damping per unit mass kept)"),
    (r"ball_damping", "torque_damping", "ball_damping (every ball)"),
    (r"races\[\d+\]\.balls\[\d+\]\.mass", "mass", "races[i].balls[j].mass"),
    (r"races\[\d+\]\.balls\[\d+\]\.damping", "torque_damping", "races[i].balls[j].damping"),
    (r"races\[\d+\]\.balls\[\d+\]\.inertia", "inertia", "races[i].balls[j].inertia"),
    (r"races\[\d+\]\.(radius|axial_offset)", "length", "races[i].radius"),
    (r"unbalances\[\d+\]\.magnitude", "unbalance", "unbalances[i].magnitude"),
    (r"unbalances\[\d+\]\.phase", "angle", "unbalances[i].phase"),
    (r"support_anisotropy", "dimensionless", "support_anisotropy ((k_yy - k_xx) / (k_xx + k_yy), against drive.speed)"),
)

#: Any other key path of the model's named parameters (its values then plain SI numbers).
_KEY_PATH = re.compile(r"[a-z_][a-z0-9_]*(\[\d+\])?(\.[a-z_][a-z0-9_]*(\[\d+\])?)*")

#: How a range is said for people, by dimension: (unit, factor from SI).
_PEOPLE = {"angular_speed": ("rpm", 30.0 / math.pi), "mass": ("g", 1e3), "length": ("mm", 1e3),
           "angle": ("deg", 180.0 / math.pi)}

_STARTS = re.compile(r"balanced|side|all|hopf|simulation|main[+-]|main \d+|side [01]+")


def continuation_dimension(name: str) -> str | None:
    """The dimension of parameter ``name``; None for another key path of the model's named
    parameters (checked against the model when it runs; its range then in plain SI numbers).
    ValueError listing the names if ``name`` is not a key path.

    >>> continuation_dimension("drive.speed"), continuation_dimension("races[0].balls[1].mass")
    ('angular_speed', 'mass')
    >>> continuation_dimension("structure.bearings[0].kxx") is None
    True
    """
    for pattern, dimension, _ in CONTINUATION_NAMES:
        if re.fullmatch(pattern, name):
            return dimension
    if _KEY_PATH.fullmatch(name) and "." in name or name in ("disc_mass", "stiffness", "damping", "eccentricity"):
        return None
    raise ValueError(f"{name!r} is not a continuation parameter; use one of "
                     + ", ".join(shown for _, _, shown in CONTINUATION_NAMES) + " or another named parameter of "
                     "the model (its key path)")


class _Name:
    def __call__(self, value: Any) -> str:
        if not isinstance(value, str):
            raise _error("must be a parameter name (a string such as \"drive.speed\")")
        try:
            continuation_dimension(value)
        except ValueError as exc:
            raise _error(str(exc)) from None
        return value


_ParamName = Annotated[str, PlainValidator(_Name()), WithJsonSchema({"type": "string"})]
_Range = Annotated[Any, WithJsonSchema({"type": "array", "minItems": 2, "maxItems": 2}), Unit("SI")]


def _read_range(value: Any, name: str | None) -> tuple[float, float] | None:
    if value is None:
        return None
    if name is None:
        raise _error("needs a valid parameter name (param / param2) to know its unit")
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise _error("must be [start, stop] (numbers in SI or strings with a unit)")
    dimension = continuation_dimension(name)
    read = _QuantityValidator(dimension or "dimensionless")
    ends = []
    for what, raw in zip(("start", "stop"), value):
        if dimension is None and not isinstance(raw, (int, float)):
            raise _error(f"{what}: {name} takes plain numbers in its SI unit (no unit known here)")
        try:
            ends.append(read(raw))
        except Exception as exc:  # the quantity's own message
            detail = getattr(exc, "context", None) or {}
            raise _error(f"{what}: {detail.get('detail', str(exc))}") from None
    if ends[0] == ends[1]:
        raise _error(f"start and stop must differ, got {ends[0]:g} twice")
    lo, hi = _OPEN_RANGES.get(name, (-math.inf, math.inf))
    for what, v in zip(("start", "stop"), ends):
        if not lo < v < hi:
            raise _error(f"{what}: {name} = {v:g} must lie strictly between {lo:g} and {hi:g}")
    return ends[0], ends[1]


#: Parameters whose values lie in an open interval (the relative stiffness difference of the supports).
_OPEN_RANGES = {"support_anisotropy": (-1.0, 1.0)}

#: Parameters taken only as ``param2`` against ``drive.speed``, and what their curves are.
_SECOND_ONLY = {"support_anisotropy": "the balanced state's Floquet stability boundary"}


class ContinuationSpec(AbstractAnalysisSpec):
    """Continue steady motions in a named parameter; fold and Hopf curves in a second one.

    Parameters
    ----------
    param : str
        ``drive.speed``, ``ball_mass``, ``ball_damping`` or a key path of the machine
        (``races[i].balls[j].mass``, ``unbalances[i].magnitude``, ...); a ``jeffcott_balls``
        rotor is continued as the machine it equals (one race, the disc's unbalance).
    range : (float, float)
        ``[start, stop]`` in the parameter's SI unit or with a unit; the starting motions are
        those at ``start``.
    start_from : str
        ``balanced``, ``side``, ``all`` or a motion's label (``main+``, ``side 01``): steady
        motions; ``hopf`` (the orbits born at the Hopf points of all steady motions) or
        ``simulation`` (the whirl a simulation at ``range[0]`` ends in): periodic orbits of a
        ``jeffcott_balls`` rotor in its co-rotating frame, continued in ``drive.speed``.
    param2, range2 : optional
        A second parameter and its range: the fold and Hopf points found are continued in it
        (the case's own value of ``param2`` must lie in ``range2``).
    switch : bool
        Follow the other branch at every branch point.
    speed : float, optional
        The constant speed (rad/s) when ``param`` is not ``drive.speed``; default the model's
        constant speed.
    """

    model_types: ClassVar[tuple[str, ...] | None] = ("machine", "jeffcott_balls")

    type: Literal["continuation"] = "continuation"
    param: _ParamName = Field(description="the continued parameter (drive.speed, ball_mass, ... )")
    range: _Range = Field(description="[start, stop] of the parameter (SI or with a unit)")
    start_from: str = Field("balanced", description="starting motions: balanced, side, all or a motion's label")
    param2: _ParamName | None = Field(None, description="second parameter of fold and Hopf curves")
    range2: _Range = Field(None, description="[start, stop] of the second parameter")
    switch: flag() = Field(True, description="switch branches at branch points")
    speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="constant speed (rad/s) when the speed is not the continued parameter")

    @field_validator("range", mode="plain")
    @classmethod
    def _read_range1(cls, value: Any, info: ValidationInfo) -> tuple[float, float] | None:
        return _read_range(value, info.data.get("param"))

    @field_validator("range2", mode="plain")
    @classmethod
    def _read_range2(cls, value: Any, info: ValidationInfo) -> tuple[float, float] | None:
        return _read_range(value, info.data.get("param2"))

    @field_validator("start_from", mode="plain")
    @classmethod
    def _read_start(cls, value: Any) -> str:
        if not isinstance(value, str) or not _STARTS.fullmatch(value):
            raise _error("must be balanced, side, all, hopf, simulation or a motion's label (main+, main-, side 01, "
                         "...)")
        return value

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model type and that ``param2`` and ``range2`` come together."""
        issues = super().case_issues(model)
        if issues:  # a model this analysis does not take: the parameters are not its to check
            return issues
        if (self.param2 is None) != (self.range2 is None):
            key = "range2" if self.range2 is None else "param2"
            issues.append(Issue((key,), "param2 and range2 come together: give both or neither",
                                self.param2 or self.range2))
        if self.speed is not None and self.param == "drive.speed":
            issues.append(Issue(("speed",), "is the continued parameter: give its range only", self.speed))
        if self.param2 is not None and self.param2 == self.param:
            issues.append(Issue(("param2",), "must differ from param", self.param2))
        if self.param in _SECOND_ONLY:
            issues.append(Issue(("param",), f"is continued as param2 against drive.speed only ({_SECOND_ONLY[self.param]})",
                                self.param))
        if self.param2 in _SECOND_ONLY and self.param != "drive.speed":
            issues.append(Issue(("param2",), f"is continued against drive.speed only ({_SECOND_ONLY[self.param2]}), "
                                f"not against {self.param}", self.param2))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        what = f"the whirl orbits from {self.start_from}" if self.start_from in ("hopf", "simulation") else \
            f"the {self.start_from} steady motions"
        text = f"continuation of {what} in {self.param} {_people(self.param, *self.range)}"
        if self.param2 is not None:
            curves = _SECOND_ONLY.get(self.param2, "fold and Hopf curves")
            text += f"; {curves} in {self.param2} ({_people(self.param2, *self.range2)})"
        return text


def _people(name: str, a: float, b: float) -> str:
    """``from A to B`` in the unit people read for the parameter's dimension (rpm, g, mm, deg), else SI.

    >>> _people("drive.speed", 52.35987755982988, 314.1592653589793)
    'from 500 to 3000 rpm'
    """
    unit, k = _PEOPLE.get(continuation_dimension(name) or "", ("(SI)", 1.0))
    return f"from {a * k:.6g} to {b * k:.6g} {unit}"
