"""Case-file spec of the ``sweep`` analysis: regimes of a rotor with balls or of a toroidal ball
over a grid (or a seeded random sample) of model parameters and initial conditions.

Run by :func:`rotorlab.analyses.run_analysis` (in-process) and by ``rotorlab sweep`` (which adds
a Zarr store, resume and Dask); registered in :mod:`rotorlab.io._schema`.

Examples
--------
>>> spec = SweepSpec(speed="2400 rpm", param={"ball_mass": ["10 g", "50 g", 3]},
...                  ic={"psi_1": ["0 deg", "180 deg", 2]}, t_end="2 s")
>>> spec.param["ball_mass"], round(spec.ic["psi_1"][1], 4)
((0.01, 0.05, 3), 3.1416)
"""

from __future__ import annotations

from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PlainValidator, WithJsonSchema
from pydantic_core import PydanticCustomError

from rotorlab._limits import MAX_CHUNK
from rotorlab.io._coordinates import (BALL_COORDINATE, ROTOR_STATE_COORDINATES, TORUS_COORDINATES, RecordsInputUnits, _any_dimension,
                                     coordinate_dimensions, coordinates_text, key_quantity, mappable_text)
from rotorlab.io._errors import Issue
from rotorlab.io._fields import (AbstractAnalysisSpec, AbstractModelSpec, RaceIndices, Unit, _error, _QuantityValidator,
                                 chosen_race_issues, integer, quantity)  # fmt: skip

__all__ = ["BaseSpeedSpec", "SWEEP_PARAMETERS", "TORUS_STATES", "SweepSpec", "coordinate_dimension", "sweep_coordinates"]

#: Model parameters a sweep of a rotor with balls can vary: name -> (dimension, SI unit).
SWEEP_PARAMETERS: dict[str, tuple[str, str]] = {
    "spin_speed": ("angular_speed", "rad/s"),
    "disc_mass": ("mass", "kg"),
    "eccentricity": ("length", "m"),
    "stiffness": ("stiffness", "N/m"),
    "damping": ("damping", "N*s/m"),
    "ball_mass": ("mass", "kg"),
    "ball_radius": ("length", "m"),
    "ball_damping": ("torque_damping", "N*m*s/rad"),
    "ball_friction": ("dimensionless", "1"),
}

#: Initial conditions of a toroidal ball (its state entries; the rest of
#: :data:`rotorlab.io.TORUS_COORDINATES` are parameters).
TORUS_STATES = ("psi", "alpha", "dpsi", "dalpha")


def _is_state(name: str) -> bool:
    return name in TORUS_STATES or name in ROTOR_STATE_COORDINATES or BALL_COORDINATE.match(name) is not None


def coordinate_dimension(name: str, kind: str) -> str | None:
    """Return the dimension of a sweep coordinate of any model (``kind`` "param" or "ic"), None
    if no model has it.

    Examples
    --------
    >>> coordinate_dimension("dpsi_2", "ic"), coordinate_dimension("ball_mass", "param")
    ('angular_speed', 'mass')
    >>> coordinate_dimension("rolling_friction", "param"), coordinate_dimension("psi", "ic")
    ('length', 'angle')
    >>> coordinate_dimension("psi", "param") is None
    True
    """
    if _is_state(name) != (kind == "ic"):
        return None
    return _any_dimension(name)


def sweep_coordinates(model: Any, kind: str) -> dict[str, str]:
    """Return the coordinates of kind ``kind`` ("param" or "ic") a sweep of ``model`` can vary.

    Parameters
    ----------
    model : rotorlab.io.JeffcottBallsSpec or rotorlab.io.ToroidalBallSpec
        A validated ``[model]`` table.
    kind : {"param", "ic"}

    Returns
    -------
    dict of str to str
        Name to dimension; empty for a model rotorlab has no regime mapper for (the
        coordinates are those of :func:`rotorlab.io.coordinate_dimensions`).

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> list(sweep_coordinates(load_case("strautmanis-torus").model, "ic"))
    ['psi', 'alpha', 'dpsi', 'dalpha']
    """
    from rotorlab.io._coordinates import Coordinates

    named = {n: d for n, d in coordinate_dimensions(model).items() if _is_state(n) == (kind == "ic")}
    return Coordinates(named, model) if kind == "param" else named


def _allowed(kind: str) -> str:
    if kind == "param":
        params = [*SWEEP_PARAMETERS, *(k for k in TORUS_COORDINATES if k not in SWEEP_PARAMETERS and not _is_state(k))]
        return ", ".join(params)
    return ("psi_<i> (ball angle), dpsi_<i> (ball rate), rotor_u, rotor_v (rotor position); toroidal ball: "
            + ", ".join(TORUS_STATES))


class _AxesValidator:
    """Read ``{NAME = [start, stop, count]}`` (a grid) or ``{NAME = [low, high]}`` (a sample range)."""

    def __init__(self, kind: str) -> None:
        self.kind = kind

    def __call__(self, value: Any) -> dict[str, tuple]:
        if not isinstance(value, dict):
            raise _error("must be a table NAME = [start, stop, count] (or [low, high] with sample)")
        out = {}
        for name, entry in value.items():
            dim = coordinate_dimension(str(name), self.kind)
            if dim is None:
                raise _error(f"{name}: unknown {self.kind} coordinate (allowed: {_allowed(self.kind)})")
            if not isinstance(entry, (list, tuple)) or len(entry) not in (2, 3):
                raise _error(f"{name}: must be [start, stop, count] (or [low, high] with sample)")
            ends = []
            for what, raw in zip(("start", "stop"), entry[:2]):
                try:
                    ends.append((key_quantity(str(name)) or _QuantityValidator(dim))(raw))
                except PydanticCustomError as exc:
                    raise _error(f"{name} {what}: {(exc.context or {}).get('detail', exc.message())}") from None
            if len(entry) == 2:
                if not ends[1] >= ends[0]:
                    raise _error(f"{name}: high must be >= low")
                out[str(name)] = (ends[0], ends[1])
                continue
            count = entry[2]
            if isinstance(count, bool) or not isinstance(count, (int, float)) or not float(count).is_integer() or count < 1:
                raise _error(f"{name}: count (the third entry) must be an integer >= 1")
            out[str(name)] = (ends[0], ends[1], int(count))
        return out


def _axes(kind: str) -> Any:
    schema = {"type": "object", "additionalProperties": {"type": "array", "minItems": 2, "maxItems": 3}}
    unit = {"param": "SI", "ic": "rad, rad/s"}[kind]
    return Annotated[dict[str, tuple], PlainValidator(_AxesValidator(kind)), WithJsonSchema(schema), Unit(unit)]


class BaseSpeedSpec(AbstractAnalysisSpec):
    """The base spin speed of an analysis whose starts are integrated at a constant speed
    (``sweep``, ``basin-stability``): ``speed_ratio`` or ``speed``, else the model's own."""

    speed_ratio: quantity("dimensionless", gt=0) | None = Field(None, description="base speed / critical speed (-)")
    speed: quantity("angular_speed", gt=0) | None = Field(None, description="base spin speed (rad/s)")

    def speed_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the base speed (and ``spare_turns``, a toroidal ball's) against the model."""
        issues = []
        kind = getattr(model, "type", None)
        if model.spins_at_own_speed:
            for key in ("speed_ratio", "speed"):
                if getattr(self, key) is not None:
                    issues.append(Issue((key,), f"applies to a rotor with balls only; a {kind} spins at its "
                                                "model's spin_speed (vary it with param)", getattr(self, key)))
            return issues
        if getattr(self, "spare_turns", None) is not None:
            issues.append(Issue(("spare_turns",), "applies to a toroidal_ball model only", self.spare_turns))
        if self.speed is None and self.speed_ratio is None:
            profile = model.speed_profile()
            if profile is None or not profile.is_constant or profile.final_speed == 0:
                issues.append(Issue(("speed",), "give speed or speed_ratio (the model has no constant speed)",
                                    None, show_value=False))  # fmt: skip
        if self.speed_ratio is not None and model.critical_speed() is None:
            issues.append(Issue(("speed_ratio",), "the model has no critical speed: give speed", self.speed_ratio))
        return issues

    def spin_speed(self, model: AbstractModelSpec) -> float:
        """Return the base spin speed (rad/s)."""
        if model.spins_at_own_speed:
            return model.spin_speed
        if self.speed is not None:
            return self.speed
        if self.speed_ratio is not None:
            return self.speed_ratio * model.critical_speed()
        return model.speed_profile().final_speed


class SweepSpec(BaseSpeedSpec, RecordsInputUnits):
    """Regimes of a rotor with balls or of a toroidal ball at every point of a grid or a sample.

    Every point is a start-up at a constant speed, classified by the model's mapper (built like
    a ``basin`` analysis', :func:`rotorlab.analyses.basin_mapper`):
    :class:`rotorlab.explore.BalancerRegimes` (balanced, side motions, non-synchronous, other)
    or :class:`rotorlab.explore.TorusRegimes` (working, spare, other).

    Parameters
    ----------
    speed_ratio : float, optional
        Rotor with balls: base spin speed as a multiple of the critical speed p (-), > 0.
    speed : float, optional
        Rotor with balls: base spin speed (rad/s), > 0. Neither: the model's constant
        ``[model.speed]`` (a toroidal ball always spins at its model's ``spin_speed``).
    param : dict of str to [start, stop, count] or [low, high]
        Model parameters to vary (SI or with units; a rotor with balls:
        :data:`SWEEP_PARAMETERS`, a toroidal ball: its geometry, ``spin_speed``, ``offset``,
        ``rolling_friction``, ``gravity``), one result dimension each in the order given.
    ic : dict of str to [start, stop, count] or [low, high]
        Initial conditions to vary: ``psi_<i>`` (angle of ball i from the unbalance, rad),
        ``dpsi_<i>`` (its rate relative to the rotor, rad/s); toroidal ball: ``psi``,
        ``alpha`` (rad), ``dpsi``, ``dalpha`` (rad/s).
    sample : int, optional
        Draw this many random points (entries are then [low, high] ranges) instead of a grid.
    seed : int
        Seed of the random sample.
    t_end : float, optional
        Simulated time (s), > 0. Excludes ``revolutions``.
    revolutions : float, optional
        Simulated time in revolutions at the base speed, > 0.
    n_horizons : int
        Horizons at which trajectories are classified, >= 1.
    window_revolutions : float, optional
        Classification window (revolutions at the base speed), > 0 (default: the mapper's, 10
        for a rotor with balls, 20 for a toroidal ball).
    spare_turns : float, optional
        Toroidal ball: turns round the ring within the window that make the regime *spare*.
    chunk : int
        Points per chunk, >= 1.
    rtol, atol : float, optional
        Integrator tolerances (default: the mapper's, 1e-8 / 1e-10 for a rotor with balls,
        1e-6 / 1e-8 for a toroidal ball).
    races : tuple of int, optional
        A machine model: the indices of the ball races that take part (a variant of the
        machine; ``psi_<i>`` counts the balls of these races in order); default all.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratio", "speed", False),
        ("t_end", "revolutions", True),
    )

    type: Literal["sweep"] = "sweep"
    param: _axes("param") = Field(default_factory=dict, description="model parameters to vary (SI)")
    ic: _axes("ic") = Field(default_factory=dict, description="initial conditions to vary (rad, rad/s)")
    sample: integer(ge=1) | None = Field(None, description="number of random points instead of a grid")
    seed: integer() = Field(0, description="seed of the random sample")
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    revolutions: quantity("dimensionless", gt=0) | None = Field(None, description="simulated revolutions (-)")
    n_horizons: integer(ge=1) = Field(4, description="classification horizons")
    window_revolutions: quantity("dimensionless", gt=0) | None = Field(None, description="classification window (-)")
    spare_turns: quantity("dimensionless", gt=0) | None = Field(
        None, description="turns in the window that make a moving ball spare (toroidal ball)")
    chunk: integer(ge=1, le=MAX_CHUNK) = Field(1024, description="points per chunk")
    rtol: quantity("dimensionless", gt=0, lt=1) | None = Field(None, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) | None = Field(None, description="absolute tolerance")
    races: RaceIndices | None = Field(None, description="ball races that take part (machine; default all)")

    @classmethod
    def _written(cls, data: dict[str, Any]) -> list[tuple[str, list[Any]]]:
        """The angles of ``param`` and ``ic`` as written (see :attr:`input_units`).

        Examples
        --------
        >>> SweepSpec(ic={"psi_1": ["0 deg", "90 deg", 3], "dpsi_1": [-1, 1, 2]}, t_end=1.0).input_units
        {'psi_1': 'deg'}
        """
        return [(str(name), list(raw[:2])) for key in ("param", "ic") if isinstance(data.get(key), dict)
                for name, raw in data[key].items() if isinstance(raw, (list, tuple))]  # fmt: skip

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model (one with a regime mapper), the coordinates and grid / sample entries."""
        issues = []
        kind = getattr(model, "type", None)
        if not coordinate_dimensions(model):
            return [Issue(("type",), f"needs {mappable_text(model)}", self.type)]
        for key in ("param", "ic"):
            known = sweep_coordinates(model, key)
            for name in getattr(self, key):
                if name in known:
                    continue
                reason = model.missing_coordinate(name)
                if reason is not None:
                    issues.append(Issue((key, name), f"the model {reason}", name))
                else:
                    issues.append(Issue((key, name), f"not a{'n initial condition' if key == 'ic' else ' parameter'}"
                                                     f" of this {kind} model (allowed: {coordinates_text(known)})", name))
        for key in ("param", "ic"):
            for name, entry in getattr(self, key).items():
                if self.sample is not None and len(entry) != 2:
                    issues.append(Issue((key, name), "with sample, give a range [low, high]", list(entry)))
                if self.sample is None and len(entry) != 3:
                    issues.append(Issue((key, name), "give [start, stop, count] (or set sample)", list(entry)))
        issues += chosen_race_issues(model, self.races, [(("ic", k), k) for k in self.ic])
        if not self.param and not self.ic:
            issues.append(Issue(("param",), "give at least one param or ic to vary", None, show_value=False))
        return issues + self.speed_issues(model)

    def describe(self, model: AbstractModelSpec) -> str:
        names = [*self.param, *self.ic]
        what = f"{self.sample} random points" if self.sample else "a grid"
        return f"regimes at {what} over {', '.join(names) or 'nothing'}"
