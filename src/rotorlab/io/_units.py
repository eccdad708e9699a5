"""Conversion of case-file quantities to SI floats.

A quantity in a case file is either a plain number, taken as SI, or a string ``"<number> <unit>"``
read with pint (imported lazily, on the first string with a unit). Only the units an engineer
working on rotors needs are accepted (:data:`ACCEPTED_UNITS`, with any SI prefix); anything else
is reported as an unknown unit rather than silently read as, say, a furlong or a Planck constant.

Angles
------
pint treats the radian as dimensionless, so ``"1200 rpm"`` and ``"125.7 rad/s"`` are the same
quantity. A hertz, however, is one *cycle* per second: for an angular speed ``"20 Hz"`` means
``2*pi*20`` rad/s, and for a frequency ``"1200 rpm"`` means 20 Hz. Whether a unit carries an
angle is read from its definition (a degree, a revolution, an rpm carry one; a second does not),
so a dimensionless field refuses ``"30 deg"`` and an angular speed accepts both ``"1/s"`` and
``"rad/s"``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache
from numbers import Real
from typing import Any

from rotorlab.io._errors import CaseError, did_you_mean, format_value

__all__ = ["Dimension", "DIMENSIONS", "ACCEPTED_UNITS", "to_si", "UnitError", "convert", "input_unit"]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True, slots=True)
class Dimension:
    """A physical dimension a case-file field may have.

    Parameters
    ----------
    name : str
        Identifier used in the schema, e.g. ``"angular_speed"``.
    noun : str
        How to name it in a message: ``"angular speed"``.
    si : str
        The SI unit the value is converted to, as shown to users (``"rad/s"``).
    reference : str
        The same unit without radians, as pint reads it (``"1/s"``).
    angle_powers : tuple of int
        Powers of the radian the input may carry (``(0, 1)`` for an angular speed: both
        ``1/s`` and ``rad/s`` are accepted).
    cyclic : bool
        The SI value counts cycles, not radians (frequency in Hz): an input carrying one
        radian (``rpm``, ``rad/s``) is divided by 2*pi.
    """

    name: str
    noun: str
    si: str
    reference: str
    angle_powers: tuple[int, ...] = (0,)
    cyclic: bool = False

    @property
    def with_article(self) -> str:
        """The noun with its indefinite article (``"an angular speed"``)."""
        return ("an " if self.noun[0] in "aeiou" else "a ") + self.noun

    @property
    def described(self) -> str:
        """The noun with its article and SI unit (``"an angular speed (rad/s)"``)."""
        return f"{self.with_article} ({self.si})" if self.si else self.with_article


_DIMENSION_LIST = (
    Dimension("dimensionless", "dimensionless number", "", "dimensionless"),
    Dimension("mass", "mass", "kg", "kg"),
    Dimension("length", "length", "m", "m"),
    Dimension("time", "time", "s", "s"),
    Dimension("angle", "angle", "rad", "dimensionless", (0, 1)),
    Dimension("angular_speed", "angular speed", "rad/s", "1/s", (0, 1)),
    Dimension("frequency", "frequency", "Hz", "1/s", (0, 1), cyclic=True),
    Dimension("angular_acceleration", "angular acceleration", "rad/s^2", "1/s^2", (0, 1)),
    Dimension("stiffness", "stiffness", "N/m", "N/m"),
    Dimension("damping", "damping coefficient", "N*s/m", "N*s/m"),
    Dimension("compliance", "compliance", "m/N", "m/N"),
    Dimension("inertia", "moment of inertia", "kg*m^2", "kg*m^2"),
    Dimension("torque_damping", "rotational damping", "N*m*s/rad", "N*m*s", (0, -1)),
    Dimension("rotational_stiffness", "rotational stiffness", "N*m/rad", "N*m", (0, -1)),
    Dimension("force", "force", "N", "N"),
    Dimension("torque", "torque", "N*m", "N*m"),
    Dimension("velocity", "velocity", "m/s", "m/s"),
    Dimension("acceleration", "acceleration", "m/s^2", "m/s^2"),
    Dimension("pressure", "pressure", "Pa", "Pa"),
    Dimension("energy", "energy", "J", "J"),
    Dimension("power", "power", "W", "W"),
    Dimension("flexural_rigidity", "flexural rigidity", "N*m^2", "N*m^2"),
    Dimension("density", "density", "kg/m^3", "kg/m^3"),
    Dimension("unbalance", "unbalance", "kg*m", "kg*m"),
    Dimension("couple_unbalance", "couple unbalance", "kg*m^2", "kg*m^2"),
    Dimension("stiffness_coupling", "translation-tilt stiffness", "N/rad", "N", (0, -1)),
    Dimension("damping_coupling", "translation-tilt damping", "N*s/rad", "N*s", (0, -1)),
    Dimension("compliance_coupling", "translation-tilt compliance", "1/N", "1/N", (0, 1)),
    Dimension("rotational_compliance", "rotational compliance", "rad/(N*m)", "1/(N*m)", (0, 1)),
)

#: The dimensions known to :func:`to_si`, by name.
DIMENSIONS: dict[str, Dimension] = {d.name: d for d in _DIMENSION_LIST}

#: Units accepted in case files (pint's canonical names; any SI prefix may be added), with the
#: symbols a user would write.
ACCEPTED_UNITS: dict[str, str] = {
    "meter": "m",
    "inch": "in",
    "foot": "ft",
    "gram": "g",
    "metric_ton": "t",
    "pound": "lb",
    "second": "s",
    "minute": "min",
    "hour": "h",
    "radian": "rad",
    "degree": "deg",
    "arcminute": "arcmin",
    "arcsecond": "arcsec",
    "turn": "rev",
    "revolutions_per_minute": "rpm",
    "revolutions_per_second": "rps",
    "hertz": "Hz",
    "newton": "N",
    "force_pound": "lbf",
    "joule": "J",
    "watt": "W",
    "pascal": "Pa",
    "bar": "bar",
    "percent": "%",
}

_SUGGESTIONS = (
    "m mm um µm km in ft g kg t lb s ms min h rad deg rev turn rpm rps Hz kHz N kN MN lbf "
    "J W Pa kPa MPa GPa bar % meter gram second minute hour radian degree revolution hertz "
    "newton"
).split()

_NUMBER = re.compile(
    r"^\s*(?P<num>[+-]?(?:(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|nan|inf|infinity))"
    r"(?P<unit>.*?)\s*$",
    re.IGNORECASE,
)
_TOKEN = re.compile(r"[^\W\d]\w*|°|%|Ω")
_SUPERSCRIPTS = str.maketrans(
    {"²": "^2", "³": "^3", "¹": "^1", "⁻": "^-", "·": "*", "×": "*", "°": " deg "}
)


class UnitError(ValueError):
    """A single value cannot be converted; the message says why (without the key path)."""


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("@alias turn = rev")
    return ureg


def _base_names(ureg: Any, name: str) -> set[str]:
    try:
        return {unit for _prefix, unit, _suffix in ureg.parse_unit_name(name)}
    except Exception:
        return set()


def _parse(text: str) -> tuple[float, Any, str]:
    """Split ``"<number> <unit>"`` and read the unit; returns (number, pint Unit or None, unit)."""
    match = _NUMBER.match(text)
    if match is None or (match["unit"] and not re.match(r"[\s°%/*]|[^\W\d_]", match["unit"])):
        raise UnitError('cannot read a quantity: write a number then a unit, e.g. "1.5 mm"')
    number = float(match["num"])
    unit_text = match["unit"].translate(_SUPERSCRIPTS).strip()
    if unit_text.startswith("/"):
        unit_text = "1" + unit_text
    if not unit_text:
        return number, None, ""
    ureg = _registry()
    for token in _TOKEN.findall(unit_text):
        if not (_base_names(ureg, token) & ACCEPTED_UNITS.keys()):
            hint = did_you_mean(token, _SUGGESTIONS)
            raise UnitError(f"unknown unit '{token}'" + (f" ({hint})" if hint else ""))
    try:
        unit = ureg.parse_units(unit_text)
    except Exception:  # pint raises assorted types (tokenizer, parser) for malformed expressions
        raise UnitError(f"cannot read the unit '{unit_text}': write units joined by '*', '/' and '^' with "
                        "matched parentheses, e.g. \"kg*m/s^2\" or \"N/(m/s)\"") from None
    for name, _power in ureg.Quantity(1.0, unit).unit_items():
        if not (_base_names(ureg, name) & ACCEPTED_UNITS.keys()):
            raise UnitError(f"unknown unit '{name}' in '{unit_text}'")
    return number, unit, unit_text


def _dimension_noun(ureg: Any, dimensionality: Any, angle_power: int) -> str:
    if not dimensionality:
        return "angle" if angle_power == 1 else "a plain number"
    same = [d for d in _DIMENSION_LIST
            if ureg.parse_units(d.reference).dimensionality == dimensionality]
    for dim in same:
        if angle_power in dim.angle_powers:
            return dim.noun
    return same[0].noun if same else str(dimensionality)


def convert(value: Any, dimension: str | Dimension) -> float:
    """Convert one case-file value to an SI float, or raise :class:`UnitError`.

    Parameters
    ----------
    value : float or int or str
        A plain number (SI) or a string with a unit.
    dimension : str or Dimension
        A key of :data:`DIMENSIONS`.

    Returns
    -------
    float
        The value in the SI unit of ``dimension``; always finite.

    Raises
    ------
    UnitError
        Wrong type, unknown unit, wrong dimension or a value that is not finite; the message
        does not name the key (see :func:`to_si`).
    KeyError
        ``dimension`` is not known (a programming error, not a user error).
    """
    dim = dimension if isinstance(dimension, Dimension) else DIMENSIONS[dimension]
    if isinstance(value, bool):
        raise UnitError(_expected(dim, "a boolean"))
    if isinstance(value, Real):
        try:
            number = float(value)
        except OverflowError:
            raise UnitError("must be a finite number") from None
        if not math.isfinite(number):
            raise UnitError("must be a finite number")
        return number
    if not isinstance(value, str):
        kind = "a table" if isinstance(value, dict) else (
            "a list" if isinstance(value, (list, tuple)) else f"a {type(value).__name__}")
        raise UnitError(_expected(dim, kind))
    number, unit, unit_text = _parse(value)
    if not math.isfinite(number):
        raise UnitError("must be a finite number")
    if unit is None:
        if dim.reference != "dimensionless":
            raise UnitError(
                f"wrong dimension: expected {dim.described}, got a plain number "
                f"(write {value.strip()} without quotes for SI, or add a unit)"
            )
        return number
    ureg = _registry()
    quantity = ureg.Quantity(number, unit)
    hertz_power = 0
    for name, power in quantity.unit_items():
        if "hertz" in _base_names(ureg, name):
            hertz_power += int(power)
    base_units = dict(quantity.to_base_units().unit_items())
    angle_power = int(base_units.get("radian", 0)) + hertz_power
    reference = ureg.parse_units(dim.reference)
    if quantity.dimensionality != reference.dimensionality or angle_power not in dim.angle_powers:
        got = _dimension_noun(ureg, quantity.dimensionality, angle_power)
        raise UnitError(f"wrong dimension: expected {dim.described}, got {got}")
    try:
        result = float(quantity.to(reference).magnitude) * TWO_PI**hertz_power
    except Exception as exc:  # a pint conversion failure despite equal dimensions
        raise UnitError(f"cannot convert '{unit_text}' to {dim.si} ({exc})") from None
    if dim.cyclic and angle_power == 1:
        result /= TWO_PI
    if not math.isfinite(result):
        raise UnitError("must be a finite number")
    return result


def _expected(dim: Dimension, got: str) -> str:
    if dim.name == "dimensionless":
        return f"must be a number, got {got}"
    example = f'"1 {dim.si}"'
    return f"must be a number (SI, {dim.si}) or a string with a unit such as {example}, got {got}"


def to_si(value: Any, dimension: str, where: str) -> float:
    """Convert a number or a string with a unit to an SI float.

    Parameters
    ----------
    value : float or int or str
        A plain number, taken as SI, or a string ``"<number> <unit>"`` such as ``"14800 rpm"``.
    dimension : str
        One of :data:`DIMENSIONS`: ``"mass"``, ``"length"``, ``"time"``, ``"angle"``,
        ``"angular_speed"``, ``"frequency"``, ``"angular_acceleration"``, ``"stiffness"``,
        ``"damping"``, ``"compliance"``, ``"inertia"``, ``"torque_damping"``,
        ``"rotational_stiffness"``, ``"force"``, ``"torque"``, ``"velocity"``,
        ``"acceleration"``, ``"pressure"``, ``"energy"``, ``"power"``, ``"flexural_rigidity"``,
        ``"density"``, ``"unbalance"``, ``"stiffness_coupling"``, ``"compliance_coupling"``,
        ``"rotational_compliance"``, ``"dimensionless"``.
    where : str
        Key path named in the error message, e.g. ``"model.stiffness"``.

    Returns
    -------
    float
        The value in the SI unit of ``dimension`` (kg, m, s, rad, rad/s, Hz, N/m, N*s/m, kg*m^2,
        N*m*s/rad, N*m^2, kg/m^3, kg*m, ...).

    Raises
    ------
    CaseError
        ``where = value: reason``, for an unknown unit, a wrong dimension, a wrong type or a
        value that is not finite.
    ValueError
        ``dimension`` is not one of :data:`DIMENSIONS`.

    Notes
    -----
    For an angular speed a hertz counts cycles: ``"20 Hz"`` is ``2*pi*20`` rad/s, as is
    ``"1200 rpm"``; ``"1/s"`` is read as rad/s.

    Examples
    --------
    >>> round(to_si("14800 rpm", "angular_speed", "speed"), 3)
    1549.852
    >>> round(to_si("20 Hz", "angular_speed", "speed") / (2 * 3.141592653589793), 12)
    20.0
    >>> to_si("882 kg*mm^2", "inertia", "inertia")
    0.000882
    >>> to_si(0.5, "length", "radius")
    0.5
    >>> to_si("211 GPa", "pressure", "youngs_modulus"), to_si("7810 kg/m^3", "density", "rho")
    (211000000000.0, 7810.0)
    >>> to_si("1.07 rad/(kN*m)", "rotational_compliance", "delta")
    0.00107
    >>> to_si("3 m", "mass", "disc_mass")
    Traceback (most recent call last):
    ...
    rotorlab.io.CaseError: disc_mass = "3 m": wrong dimension: expected a mass (kg), got length
    """
    if dimension not in DIMENSIONS:
        raise ValueError(f"unknown dimension {dimension!r} (known: {', '.join(DIMENSIONS)})")
    try:
        return convert(value, dimension)
    except UnitError as exc:
        raise CaseError(f"{where} = {format_value(value)}: {exc}") from None


def input_unit(value: Any) -> str | None:
    """Return ``"deg"`` when an angle was written in degrees, else None (SI, or not an angle).

    What a user wrote is kept apart from the SI value so that results can be shown in the unit
    the input was given in (a basin map over ball angles given in degrees is drawn in degrees)
    without guessing it from the numbers.

    Examples
    --------
    >>> input_unit("350 deg"), input_unit("90°"), input_unit("6.1 rad"), input_unit(6.1), input_unit("20 g")
    ('deg', 'deg', None, None, None)
    """
    if not isinstance(value, str):
        return None
    try:
        _, unit, _ = _parse(value.strip())
    except UnitError:
        return None
    if unit is None:
        return None
    try:
        factor = _registry().Quantity(1.0, unit).to("radian").magnitude
    except Exception:  # pint's DimensionalityError: not an angle
        return None
    return "deg" if math.isclose(factor, math.pi / 180.0, rel_tol=1e-12) else None

