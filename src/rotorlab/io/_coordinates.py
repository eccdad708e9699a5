"""Start coordinates of the regime mappers: which names a basin or sweep of a model may vary.

A coordinate is a state entry (a toroidal ball's ``psi``, ``alpha``, ``dpsi``, ``dalpha``; a
balancer's ball angle ``psi_<i>`` and rate ``dpsi_<i>``), a model parameter (:data:`TORUS_COORDINATES`,
:data:`BALANCER_COORDINATES`, :data:`MACHINE_COORDINATES`) or, for a model whose spec sets
``sweeps_keys``, any number of its ``[model]`` table as ``model.<key path>``. Each has a
dimension (a key of :data:`rotorlab.io.DIMENSIONS`), which converts the values written in a case
file or on the command line to SI. Used by the ``basin`` and ``sweep`` specs
(:mod:`rotorlab.io._basin_specs`, :mod:`rotorlab.io._sweep_specs`) and by the model specs'
``start_coordinates``.

Examples
--------
>>> ball_coordinates(2, {"spin_speed": "angular_speed"})
{'psi_1': 'angle', 'psi_2': 'angle', 'dpsi_1': 'angular_speed', 'dpsi_2': 'angular_speed', 'spin_speed': 'angular_speed'}
"""

from __future__ import annotations

import re
from typing import Annotated, Any

from pydantic import PrivateAttr, model_validator

from rotorlab.io._fields import AbstractAnalysisSpec, _QuantityValidator
from rotorlab.io._units import DIMENSIONS, input_unit

__all__ = [
    "TORUS_COORDINATES",
    "BALANCER_COORDINATES",
    "MACHINE_COORDINATES",
    "ROTOR_STATE_COORDINATES",
    "BALL_COORDINATE",
    "COORDINATE_BOUNDS",
    "KEY_PREFIX",
    "Coordinates",
    "ball_coordinates",
    "coordinate_dimensions",
    "coordinates_text",
    "key_quantity",
    "mappable_text",
    "record_input_units",
    "RecordsInputUnits",
]

#: Start coordinates of a toroidal-ball basin (state entries and parameters): name -> dimension.
#: The names and units are those of :class:`rotorlab.explore.TorusRegimes`.
TORUS_COORDINATES: dict[str, str] = {
    "psi": "angle",
    "alpha": "angle",
    "dpsi": "angular_speed",
    "dalpha": "angular_speed",
    "ring_radius": "length",
    "tube_radius": "length",
    "ball_radius": "length",
    "spin_speed": "angular_speed",
    "offset": "length",
    "rolling_friction": "length",
    "gravity": "acceleration",
}

#: Start coordinates of a balancer basin besides the ball angles ``psi_<i>`` and rates
#: ``dpsi_<i>`` (i = 1..n): name -> dimension (:class:`rotorlab.explore.BalancerRegimes`).
BALANCER_COORDINATES: dict[str, str] = {
    "spin_speed": "angular_speed",
    "disc_mass": "mass",
    "eccentricity": "length",
    "stiffness": "stiffness",
    "damping": "damping",
    "ball_mass": "mass",
    "ball_radius": "length",
    "ball_damping": "torque_damping",
    "ball_friction": "dimensionless",
}

#: Start state of the rotor of a balancer (:class:`rotorlab.explore.BalancerRegimes`): the disc
#: centre's position in the co-rotating frame (u along the unbalance, v ahead of it), at rest
#: relative to that frame; name -> dimension. Unlike the parameters they are initial conditions.
ROTOR_STATE_COORDINATES: dict[str, str] = {"rotor_u": "length", "rotor_v": "length"}

#: Start coordinates of a machine's balancer besides ``psi_<i>`` and ``dpsi_<i>`` (every ball of
#: every race; :class:`rotorlab.explore.MachineRegimes`).
MACHINE_COORDINATES: dict[str, str] = {
    "spin_speed": "angular_speed",
    "ball_mass": "mass",
    "ball_damping": "torque_damping",
}

#: The angle ``psi_<i>`` or rate ``dpsi_<i>`` of ball i (i = 1, 2, ...) among start coordinates.
BALL_COORDINATE = re.compile(r"^(d?)psi_([1-9][0-9]*)$")

#: Lower bounds of the parameters among the coordinates: name -> ("gt" or "ge", 0).
COORDINATE_BOUNDS: dict[str, str] = {
    "ring_radius": "gt", "tube_radius": "gt", "ball_radius": "gt", "spin_speed": "gt", "offset": "ge",
    "rolling_friction": "ge", "gravity": "ge", "disc_mass": "gt", "eccentricity": "ge", "stiffness": "gt",
    "damping": "ge", "ball_mass": "gt", "ball_damping": "ge", "ball_friction": "ge",
}  # fmt: skip


def _bound_kw(name: str) -> dict[str, float]:
    kind = COORDINATE_BOUNDS.get(name)
    return {} if kind is None else {kind: 0.0}


#: Prefix of a coordinate that is a key path of the case's ``[model]`` table: a model whose spec
#: sets ``sweeps_keys`` (a machine, ``jeffcott_balls``, a toroidal ball) varies any number of its
#: model this way in basins and sweeps,
#: e.g. ``model.unbalances[0].magnitude`` or ``model.structure.bearings[0].kxx``.
KEY_PREFIX = "model."


def _quantity_in(tp: Any, path: tuple[Any, ...], meta: tuple[Any, ...] = ()) -> _QuantityValidator | None:
    """The quantity validator at ``path`` below the annotation ``tp`` (None if no number is there)."""
    import types
    import typing

    from pydantic import BaseModel

    if not path:
        for m in meta:
            if isinstance(getattr(m, "func", None), _QuantityValidator):
                return m.func
    origin = typing.get_origin(tp)
    if origin is Annotated:
        base, *more = typing.get_args(tp)
        return _quantity_in(base, path, tuple(more) + tuple(meta))
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(tp):
            found = _quantity_in(arg, path)
            if found is not None:
                return found
        return None
    if not path:
        return None
    head, rest = path[0], path[1:]
    if origin is tuple and isinstance(head, int):
        args = typing.get_args(tp)
        item = args[0] if len(args) == 2 and args[1] is Ellipsis else (args[head] if head < len(args) else None)
        return None if item is None else _quantity_in(item, rest)
    if isinstance(tp, type) and issubclass(tp, BaseModel) and isinstance(head, str) and head in tp.model_fields:
        info = tp.model_fields[head]
        return _quantity_in(info.annotation, rest, tuple(info.metadata))
    return None


def key_quantity(name: str, spec: Any = None) -> _QuantityValidator | None:
    """The quantity (unit, bounds) of the number a coordinate ``model.<key path>`` names.

    Parameters
    ----------
    name : str
        ``"model."`` and a key path as the error messages write it (``model.races[0].radius``).
    spec : type, optional
        A model spec class; default any registered model type that has that key.

    Returns
    -------
    _QuantityValidator or None
        None when the name is not such a key path or names no number.
    """
    if not name.startswith(KEY_PREFIX):
        return None
    from rotorlab.io._overrides import parse_key_path

    try:
        path = tuple(int(k) if str(k).isdigit() else k for k in parse_key_path(name[len(KEY_PREFIX):]))
    except ValueError:
        return None
    if spec is None:
        from rotorlab.io._schema import MODEL_SPECS

        specs = list(MODEL_SPECS.values())
    else:
        specs = [spec]
    for cls in specs:
        found = _quantity_in(cls, path)
        if found is not None:
            return found
    return None


def _dimension_name(validator: _QuantityValidator) -> str:
    return next(k for k, d in DIMENSIONS.items() if d is validator.dimension)


class Coordinates(dict):
    """The start coordinates of a model (name -> dimension) and, for a model whose spec sets
    ``sweeps_keys``, every number of its ``[model]`` table as ``model.<key path>`` (looked up
    when asked for; not listed)."""

    def __init__(self, named: dict[str, str], model: Any) -> None:
        super().__init__(named)
        self._model = model

    def _key(self, name: Any) -> str | None:
        if not (isinstance(name, str) and getattr(self._model, "sweeps_keys", False)):
            return None
        found = key_quantity(name, type(self._model))
        if found is None:
            return None
        from rotorlab.io._overrides import parse_key_path

        value: Any = self._model.model_dump(mode="python")
        for k in parse_key_path(name[len(KEY_PREFIX):]):  # the key must exist in this model
            k = int(k) if str(k).isdigit() and isinstance(value, (list, tuple)) else k
            if isinstance(k, int) and isinstance(value, (list, tuple)) and k < len(value):
                value = value[k]
            elif isinstance(k, str) and isinstance(value, dict) and k in value:
                value = value[k]
            else:
                return None
        return _dimension_name(found) if isinstance(value, (int, float)) and not isinstance(value, bool) else None

    def __contains__(self, name: Any) -> bool:
        return super().__contains__(name) or self._key(name) is not None

    def __missing__(self, name: Any) -> str:
        dim = self._key(name)
        if dim is None:
            raise KeyError(name)
        return dim


def coordinates_text(known: Any) -> str:
    """The names of ``known`` for messages, with the key paths a ``sweeps_keys`` model also takes."""
    text = ", ".join(known)
    if isinstance(known, Coordinates) and getattr(known._model, "sweeps_keys", False):
        text += (", or any number of [model] as model.<key path> (e.g. model.unbalances[0].magnitude)"
                 if text else "any number of [model] as model.<key path>")
    return text


def _any_dimension(name: str) -> str | None:
    """Dimension of a coordinate name of any model, or None if no model has it."""
    found = key_quantity(name)
    if found is not None:
        return _dimension_name(found)
    if name in TORUS_COORDINATES:
        return TORUS_COORDINATES[name]
    if name in BALANCER_COORDINATES:
        return BALANCER_COORDINATES[name]
    if name in ROTOR_STATE_COORDINATES:
        return ROTOR_STATE_COORDINATES[name]
    m = BALL_COORDINATE.match(name)
    if m:
        return "angular_speed" if m.group(1) else "angle"
    return None


def coordinate_dimensions(model: Any) -> dict[str, str]:
    """Return the start coordinates a basin of ``model`` accepts, with their dimensions.

    Parameters
    ----------
    model : rotorlab.io.AbstractModelSpec
        A validated ``[model]`` table.

    Returns
    -------
    dict of str to str
        Coordinate name to a key of :data:`rotorlab.io.DIMENSIONS` (the model spec's
        ``start_coordinates()``); empty for a model whose basins rotorlab cannot map.

    Examples
    --------
    >>> from rotorlab.io import ToroidalBallSpec
    >>> sorted(coordinate_dimensions(ToroidalBallSpec(ring_radius=0.2, tube_radius=0.015,
    ...        ball_radius=0.0125, spin_speed=140, offset=0.02)))[:4]
    ['alpha', 'ball_radius', 'dalpha', 'dpsi']
    """
    return Coordinates(model.start_coordinates(), model)


def mappable_text(model: Any) -> str:
    """What basins and sweeps need, for the message refusing ``model``: the model types with a
    regime mapper (those whose spec names start coordinates, as registered), and what ``model``
    is instead (its :meth:`~rotorlab.io.AbstractModelSpec.without_regimes`).

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> mappable_text(load_case("friswell-rotor").model)
    "a jeffcott_balls, toroidal_ball or machine model (a rotor with at least one ball), not model type 'fe_rotor'"
    """
    from rotorlab.io._fields import AbstractModelSpec
    from rotorlab.io._schema import MODEL_SPECS

    kinds = [k for k, cls in MODEL_SPECS.items() if cls.start_coordinates is not AbstractModelSpec.start_coordinates]
    listed = ", ".join(kinds[:-1]) + f" or {kinds[-1]}" if len(kinds) > 1 else "".join(kinds)
    return f"a {listed} model (a rotor with at least one ball), not {model.without_regimes()}"


def ball_coordinates(n_balls: int, parameters: dict[str, str]) -> dict[str, str]:
    """The start coordinates of a balancer with ``n_balls`` balls: ``psi_<i>``, ``dpsi_<i>`` and
    ``parameters`` (none without balls)."""
    if n_balls == 0:
        return {}
    out = {f"psi_{i}": "angle" for i in range(1, n_balls + 1)}
    out.update({f"dpsi_{i}": "angular_speed" for i in range(1, n_balls + 1)})
    out.update(parameters)
    return out


def record_input_units(units: dict[str, str], given: list[tuple[str, list[Any]]]) -> dict[str, str]:
    """Return ``units`` updated with the unit each given angle coordinate was written in.

    Parameters
    ----------
    units : dict of str to str
        Units recorded so far (a copy is returned).
    given : list of (name, raw values)
        Coordinates as written (numbers or strings with units); an angle given with a degree
        unit in any of its values is recorded as ``"deg"``, otherwise as ``"rad"``; other
        coordinates are not recorded.
    """
    out = dict(units)
    for name, raws in given:
        out.pop(name, None)
        if _any_dimension(name) == "angle":
            out[name] = next((u for u in map(input_unit, raws) if u), "rad")
    return out


class RecordsInputUnits(AbstractAnalysisSpec):
    """An analysis that varies start coordinates and keeps the unit each angle was written in.

    The values are SI (radians); results and figures show these coordinates in the unit the case
    file or command line gave them in (``attrs["input_units_<name>"]``). A subclass says where
    its angles are written (:meth:`_written`); ``basin`` and ``sweep`` derive from it.
    """

    _input_units: dict[str, str] = PrivateAttr(default_factory=dict)

    @classmethod
    def _written(cls, data: dict[str, Any]) -> list[tuple[str, list[Any]]]:
        """The coordinates in the raw ``data`` with their values as written (for
        :func:`record_input_units`)."""
        return []

    @model_validator(mode="wrap")
    @classmethod
    def _record_input_units(cls, data: Any, handler: Any) -> RecordsInputUnits:
        spec = handler(data)
        if isinstance(data, dict):
            spec._input_units = record_input_units({}, cls._written(data))
        return spec

    @property
    def input_units(self) -> dict[str, str]:
        """Angle coordinate given to the unit it was written in: ``"deg"`` or ``"rad"`` (SI)."""
        return dict(self._input_units)

    def with_input_units(self, units: dict[str, str]) -> RecordsInputUnits:
        """Return a copy whose :attr:`input_units` are ``units`` (for options given apart)."""
        out = self.model_copy()
        out._input_units = dict(units)
        return out


def _known_names() -> str:
    return ", ".join([*TORUS_COORDINATES, *(k for k in BALANCER_COORDINATES if k not in TORUS_COORDINATES),
                      "psi_<i>", "dpsi_<i>"])  # fmt: skip
