"""Case-file specs of the toroidal ball balancer (seed 004) and of the basin analyses.

The start coordinates a basin may vary (names, dimensions, ``model.<key path>``) are in
:mod:`rotorlab.io._coordinates`.

``[model] type = "toroidal_ball"`` is one ball rolling in a torus offset from the rotation axis
(:class:`rotorlab.models.ToroidalBall`). ``[[analysis]] type = "basin"`` maps a 2-D grid (or a
seeded random sample) of start coordinates to regimes with :mod:`rotorlab.explore`, for the
toroidal ball (working / spare / other) and for a rotor with balls (balanced / side motions /
non-synchronous / other). ``type = "working-point"`` gives the working equilibrium of the
toroidal ball, its friction band and the restoring force against the ring angle (seed 004
Fig. 3).

A grid axis is written ``[name, start, stop, count]``; start and stop take the unit of the
named coordinate (``["psi", "0 deg", "360 deg", 64]``, ``["dpsi", -280, 140, 64]`` in rad/s).

Examples
--------
>>> spec = BasinSpec(x=["psi", "0 deg", "180 deg", 3], y=["dpsi", -10, 10, 2],
...                  fixed={"rolling_friction": "0.1 mm"})
>>> spec.x, spec.fixed
(('psi', 0.0, 3.141592653589793, 3), {'rolling_friction': 0.0001})
"""

from __future__ import annotations

import math
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PlainValidator, WithJsonSchema, model_validator
from pydantic_core import PydanticCustomError

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.io._coordinates import (
    BALANCER_COORDINATES,
    TORUS_COORDINATES,
    RecordsInputUnits,
    _any_dimension,
    _bound_kw,
    _known_names,
    coordinate_dimensions,
    coordinates_text,
    key_quantity,
    mappable_text,
)
from rotorlab.io._errors import Issue, IssueGroup, did_you_mean
from rotorlab.io._fields import (
    AbstractAnalysisSpec,
    AbstractModelSpec,
    RaceIndices,
    _choice,
    _error,
    _QuantityValidator,
    chosen_race_issues,
    integer,
    quantity,
)
from rotorlab.io._jeffcott_specs import constant_spin_speed

__all__ = [
    "ToroidalBallSpec",
    "BasinSpec",
    "WorkingPointSpec",
]


def _detail(exc: PydanticCustomError) -> str:
    return str((exc.context or {}).get("detail", exc.message()))


class _AxisValidator:
    """Read ``[name, start, stop, count]``; start and stop in the unit of the named coordinate."""

    def __call__(self, value: Any) -> tuple[str, float, float, int]:
        if not isinstance(value, (list, tuple)) or len(value) != 4:
            raise _error('must be [name, start, stop, count], e.g. ["psi", "0 deg", "360 deg", 64]')
        name, start, stop, count = value
        if not isinstance(name, str):
            raise _error(f"the name (first entry) must be a string, got {name!r}")
        dim = _any_dimension(name)
        if dim is None:
            hint = did_you_mean(name, [*TORUS_COORDINATES, *BALANCER_COORDINATES])
            raise _error(f"unknown coordinate {name!r}" + (f"; {hint}" if hint else "")
                         + f" (coordinates: {_known_names()})")  # fmt: skip
        ends = []
        for what, raw in (("start", start), ("stop", stop)):
            try:
                ends.append((key_quantity(name) or _QuantityValidator(dim, **_bound_kw(name)))(raw))
            except PydanticCustomError as exc:
                raise _error(f"{what}: {_detail(exc)}") from None
        if isinstance(count, bool) or not isinstance(count, (int, float)) or not float(count).is_integer() or count < 1:
            raise _error("count (the fourth entry) must be an integer >= 1")
        count = int(count)
        if count == 1 and ends[0] != ends[1]:
            raise _error("count = 1 needs start = stop")
        if count > 1 and not ends[1] > ends[0]:
            raise _error("stop must be > start")
        return name, ends[0], ends[1], count


_Axis = Annotated[tuple[str, float, float, int], PlainValidator(_AxisValidator()),
                  WithJsonSchema({"type": "array", "minItems": 4, "maxItems": 4,
                                  "description": "[name, start, stop, count]"})]  # fmt: skip


class _FixedValidator:
    """Read a table of coordinate values, each converted with its coordinate's unit."""

    def __call__(self, value: Any) -> dict[str, float]:
        if not isinstance(value, dict):
            raise _error("must be a table of coordinate = value (e.g. {alpha = 0, rolling_friction = \"0.1 mm\"})")
        out = {}
        for name, raw in value.items():
            dim = _any_dimension(str(name))
            if dim is None:
                hint = did_you_mean(str(name), [*TORUS_COORDINATES, *BALANCER_COORDINATES])
                raise _error(f"unknown coordinate {name!r}" + (f"; {hint}" if hint else "")
                             + f" (coordinates: {_known_names()})")  # fmt: skip
            try:
                out[str(name)] = (key_quantity(str(name)) or _QuantityValidator(dim, **_bound_kw(str(name))))(raw)
            except PydanticCustomError as exc:
                raise _error(f"{name}: {_detail(exc)}") from None
        return out


_Fixed = Annotated[dict[str, float], PlainValidator(_FixedValidator()),
                   WithJsonSchema({"type": "object", "description": "coordinate = value"})]  # fmt: skip


# --------------------------------------------------------------------------- the model


class ToroidalBallSpec(AbstractModelSpec):
    """One ball rolling in a spinning torus offset from the rotation axis (seed 004).

    Parameters
    ----------
    ring_radius : float
        R, radius of the torus' centre line (m), > tube_radius.
    tube_radius : float
        R1, radius of the tube's cross-section (m), > ball_radius.
    ball_radius : float
        r (m), > 0.
    spin_speed : float
        omega, constant speed of the body (rad/s), > 0.
    offset : float
        e, distance of the torus axis from the rotation axis (m), >= 0.
    rolling_friction : float
        k, lever arm of the rolling resistance (m), >= 0.
    gravity : float
        g (m/s^2), >= 0.
    form : {"rolling", "paper"}
        Equations of a ball rolling without slip, or seed 004 eqs. (4)-(6) as printed (see
        :mod:`rotorlab.models._toroidal_ball`).
    """

    type: Literal["toroidal_ball"] = "toroidal_ball"
    ring_radius: quantity("length", gt=0) = Field(description="ring (centre-line) radius R (m)")
    tube_radius: quantity("length", gt=0) = Field(description="tube radius R1 (m)")
    ball_radius: quantity("length", gt=0) = Field(description="ball radius r (m)")
    spin_speed: quantity("angular_speed", gt=0) = Field(description="spin speed of the body omega (rad/s)")
    offset: quantity("length", ge=0) = Field(description="offset e of the torus axis (m)")
    rolling_friction: quantity("length", ge=0) = Field(0.0, description="rolling friction k (m)")
    gravity: quantity("acceleration", ge=0) = Field(9.81, description="gravity g (m/s^2)")
    form: _choice("rolling", "paper") = Field("rolling", description="rolling or paper")
    sweeps_keys: ClassVar[bool] = True  # basins and sweeps vary model.<key path> (its named parameters)

    @model_validator(mode="after")
    def _check_sizes(self) -> ToroidalBallSpec:
        issues = []
        if self.ball_radius >= self.tube_radius:
            issues.append(Issue(("ball_radius",), f"must be < tube_radius = {self.tube_radius:g} m",
                                self.ball_radius))  # fmt: skip
        if self.tube_radius >= self.ring_radius:
            issues.append(Issue(("tube_radius",), f"must be < ring_radius = {self.ring_radius:g} m",
                                self.tube_radius))  # fmt: skip
        if issues:
            raise IssueGroup(issues)
        return self

    def start_coordinates(self) -> dict[str, str]:
        """Its state entries and parameters (:data:`TORUS_COORDINATES`)."""
        return dict(TORUS_COORDINATES)

    spins_at_own_speed: ClassVar[bool] = True

    def basin_issues(self, spec: AbstractAnalysisSpec) -> list[Issue]:
        """ball_radius < tube_radius < ring_radius at every start of the basin ``spec``."""
        issues = []
        for small, large in (("ball_radius", "tube_radius"), ("tube_radius", "ring_radius")):
            lo_s, hi_s, loc_s = spec.value_range(self, small)
            lo_l, hi_l, loc_l = spec.value_range(self, large)
            if hi_s >= lo_l and (loc_s or loc_l):
                loc = loc_s or loc_l
                issues.append(Issue(loc, f"{small} must stay < {large} at every start (largest {small} "
                                         f"{hi_s:g} m, smallest {large} {lo_l:g} m)", show_value=False))  # fmt: skip
        return issues

    def describe(self) -> str:
        """One line: geometry, speed and friction."""
        rpm = self.spin_speed * RPM_PER_RAD_S
        return (f"toroidal_ball (R = {self.ring_radius * 1e3:g} mm, R1 = {self.tube_radius * 1e3:g} mm, "
                f"r = {self.ball_radius * 1e3:g} mm, e = {self.offset * 1e3:g} mm, "
                f"k = {self.rolling_friction:g} m, {rpm:.0f} rpm, {self.form} form)")  # fmt: skip


# --------------------------------------------------------------------------- analyses


class BasinSpec(RecordsInputUnits):
    """Regimes reached from a 2-D grid (or a seeded random sample) of start coordinates.

    Parameters
    ----------
    x, y : (str, float, float, int)
        ``[name, start, stop, count]``: the varied coordinates (state entries or parameters of
        the model; SI or with units). With ``samples`` the starts are drawn uniformly from the
        two ranges instead and the counts are not used.
    fixed : dict of str to float
        Values of other coordinates (SI or with units), e.g. ``{alpha = 0, rolling_friction =
        "0.1 mm"}``; the rest take the model's values (state entries: 0, ball angles: equally
        spaced).
    samples : int, optional
        Number of random starts (basin stability with Wilson intervals), >= 1.
    seed : int
        Seed of the random starts, >= 0.
    confidence : float
        Level of the Wilson intervals, in (0, 1).
    t_end : float, optional
        Simulated time (s), > 0; default 60 s (toroidal ball) or 20 s (rotor with balls).
    n_horizons : int
        Horizons at which every start is classified (the fractions against time show whether a
        fraction has converged), >= 1.
    window_revolutions : float, optional
        Classification window before each horizon in body revolutions, > 0 (default 20 for the
        toroidal ball, 10 for a rotor with balls).
    spare_turns : float, optional
        Toroidal ball: turns round the ring within the window that make the regime *spare*.
    speed_ratio, speed : float, optional
        Rotor with balls: constant spin speed as omega / p or in rad/s (one is needed unless
        the model's speed profile is constant).
    rtol, atol : float, optional
        Integrator tolerances (default 1e-6 / 1e-8 for the toroidal ball, 1e-8 / 1e-10 for a
        rotor with balls).
    races : tuple of int, optional
        A machine model: the indices of the ball races that take part (a variant of the
        machine; ``psi_<i>`` counts the balls of these races in order); default all.
    """

    exclusive = (("speed_ratio", "speed", False),)

    type: Literal["basin"] = "basin"
    x: _Axis = Field(description="first varied coordinate [name, start, stop, count]")
    y: _Axis = Field(description="second varied coordinate [name, start, stop, count]")
    fixed: _Fixed = Field(default_factory=dict, description="fixed coordinates")
    samples: integer(ge=1) | None = Field(None, description="number of random starts")
    seed: integer(ge=0) = Field(0, description="seed of the random starts")
    confidence: quantity("dimensionless", gt=0, lt=1) = Field(0.95, description="confidence level (-)")
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    n_horizons: integer(ge=1) = Field(10, description="number of horizons")
    window_revolutions: quantity("dimensionless", gt=0) | None = Field(
        None, description="classification window (revolutions)")
    spare_turns: quantity("dimensionless", gt=0) | None = Field(
        None, description="turns in the window that make a moving ball spare (toroidal ball)")
    speed_ratio: quantity("dimensionless", gt=0) | None = Field(None, description="omega / p (-)")
    speed: quantity("angular_speed", gt=0) | None = Field(None, description="spin speed (rad/s)")
    rtol: quantity("dimensionless", gt=0, lt=1) | None = Field(None, description="relative tolerance (-)")
    atol: quantity("dimensionless", gt=0) | None = Field(None, description="absolute tolerance (-)")
    races: RaceIndices | None = Field(None, description="ball races that take part (machine; default all)")

    @classmethod
    def _written(cls, data: dict[str, Any]) -> list[tuple[str, list[Any]]]:
        """The angles of x, y and fixed as written (see :attr:`input_units`)."""
        given = [(raw[0], raw[1:3]) for raw in (data.get("x"), data.get("y"))
                 if isinstance(raw, (list, tuple)) and len(raw) == 4 and isinstance(raw[0], str)]
        fixed = data.get("fixed")
        return given + [(str(name), [raw]) for name, raw in (fixed.items() if isinstance(fixed, dict) else ())]

    @model_validator(mode="after")
    def _check_axes(self) -> BasinSpec:
        issues = []
        if self.x[0] == self.y[0]:
            issues.append(Issue(("y",), f"must vary another coordinate than x ({self.x[0]})", self.y[0]))
        for name in sorted({self.x[0], self.y[0]} & set(self.fixed)):
            issues.append(Issue(("fixed", name), "is varied by x or y; it cannot also be fixed",
                                self.fixed[name]))  # fmt: skip
        if issues:
            raise IssueGroup(issues)
        return self

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the coordinates and options against the model."""
        kind = getattr(model, "type", None)
        known = coordinate_dimensions(model)
        if not known:
            return [Issue(("type",), f"basins need {mappable_text(model)}", self.type)]
        issues = []
        for key, axis in (("x", self.x), ("y", self.y)):
            if axis[0] not in known:
                issues.append(Issue((key,), f"{axis[0]!r} is not a coordinate of this {kind} model "
                                            f"(coordinates: {coordinates_text(known)})", list(axis)))  # fmt: skip
        for name, value in self.fixed.items():
            if name not in known:
                issues.append(Issue(("fixed", name), f"not a coordinate of this {kind} model "
                                                     f"(coordinates: {coordinates_text(known)})", value))  # fmt: skip
        issues += model.basin_issues(self)
        issues += chosen_race_issues(model, self.races, [(("x",), self.x[0]), (("y",), self.y[0])]
                                     + [(("fixed", k), k) for k in self.fixed])
        if model.spins_at_own_speed:
            for key in ("speed_ratio", "speed"):
                if getattr(self, key) is not None:
                    issues.append(Issue((key,), f"applies to a rotor with balls only; a {kind} "
                                                "spins at its model's spin_speed (vary or fix spin_speed)",
                                        getattr(self, key)))  # fmt: skip
        else:
            if self.spare_turns is not None:
                issues.append(Issue(("spare_turns",), "applies to a toroidal_ball model only", self.spare_turns))
            if self.spin_speed(model) is None and "spin_speed" not in (self.x[0], self.y[0], *self.fixed):
                issues.append(Issue((), "a basin of a rotor with balls needs a constant spin speed: give "
                                        "speed or speed_ratio (or vary spin_speed)", show_value=False))  # fmt: skip
        return issues

    def value_range(self, model: AbstractModelSpec, name: str) -> tuple[float, float, tuple[str, ...]]:
        """Smallest and largest value of a model parameter over the starts, and where it is set
        (the key path of ``x``, ``y`` or ``fixed``; empty when the model's own value is used)."""
        for key, axis in (("x", self.x), ("y", self.y)):
            if axis[0] == name:
                return axis[1], axis[2], (key,)
        if name in self.fixed:
            return self.fixed[name], self.fixed[name], ("fixed", name)
        value = float(getattr(model, name))
        return value, value, ()

    def spin_speed(self, model: AbstractModelSpec) -> float | None:
        """Constant spin speed of a rotor with balls (rad/s): ``speed``, ``speed_ratio * p``, the
        model's constant profile, or None."""
        return constant_spin_speed(self.speed, self.speed_ratio, model)

    def describe(self, model: AbstractModelSpec) -> str:
        """One line: the grid or sample and the horizon."""
        if self.samples is not None:
            where = f"{self.samples} random starts over {self.x[0]} x {self.y[0]} (seed {self.seed})"
        else:
            where = f"{self.x[3]} x {self.y[3]} grid of {self.x[0]} x {self.y[0]}"
        t = f", {self.t_end:g} s" if self.t_end is not None else ""
        return f"{where}{t}"


class WorkingPointSpec(AbstractAnalysisSpec):
    """The working equilibrium of a toroidal ball, its friction band and restoring force (Fig. 3).

    Parameters
    ----------
    psi_span : float
        Half-width of the ring-angle range of the restoring-force curve around psi = pi (rad),
        in (0, pi].
    points : int
        Points of the curve, >= 3.
    start : (float, float, float, float)
        ``[psi, alpha, dpsi, dalpha]`` of one trajectory released towards the working point,
        whose phase portrait is drawn (seed 004 Fig. 5) (rad, rad/s).
    t_end : float
        Simulated time of that trajectory (s), > 0.
    """

    type: Literal["working-point"] = "working-point"
    model_types: ClassVar[tuple[str, ...]] = ("toroidal_ball",)
    psi_span: quantity("angle", gt=0, le=math.pi) = Field(math.pi, description="half-width of the psi range (rad)")
    points: integer(ge=3) = Field(361, description="points of the restoring-force curve")
    start: tuple[quantity("angle"), quantity("angle"), quantity("angular_speed"), quantity("angular_speed")] = Field(
        (2.0, 0.0, 0.0, 0.0), description="[psi, alpha, dpsi, dalpha] of the phase-portrait trajectory (rad, rad/s)")
    t_end: quantity("time", gt=0) = Field(10.0, description="simulated time of the trajectory (s)")

    def describe(self, model: AbstractModelSpec) -> str:
        """One line."""
        return "working point, friction band and restoring force of the toroidal ball"
