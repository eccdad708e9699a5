"""Case-file spec of the ``sweep`` analysis: regimes of a rotor with balls over a grid (or a
seeded random sample) of model parameters and initial conditions.

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

import re
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PlainValidator, WithJsonSchema
from pydantic_core import PydanticCustomError

from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, _error, _QuantityValidator, integer, quantity

__all__ = ["SWEEP_PARAMETERS", "SweepSpec", "coordinate_dimension"]

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
_STATE = re.compile(r"^(d?)psi_([1-9][0-9]*)$")


def coordinate_dimension(name: str, kind: str) -> str | None:
    """Return the dimension of a sweep coordinate (``kind`` "param" or "ic"), None if unknown.

    Examples
    --------
    >>> coordinate_dimension("dpsi_2", "ic"), coordinate_dimension("ball_mass", "param")
    ('angular_speed', 'mass')
    """
    if kind == "param":
        return SWEEP_PARAMETERS.get(name, (None,))[0]
    m = _STATE.match(name)
    if m is None:
        return None
    return "angular_speed" if m.group(1) else "angle"


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
                allowed = (", ".join(SWEEP_PARAMETERS) if self.kind == "param"
                           else "psi_<i> (ball angle, rad), dpsi_<i> (ball rate, rad/s)")  # fmt: skip
                raise _error(f"{name}: unknown {self.kind} coordinate (allowed: {allowed})")
            if not isinstance(entry, (list, tuple)) or len(entry) not in (2, 3):
                raise _error(f"{name}: must be [start, stop, count] (or [low, high] with sample)")
            ends = []
            for what, raw in zip(("start", "stop"), entry[:2]):
                try:
                    ends.append(_QuantityValidator(dim)(raw))
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
    return Annotated[dict[str, tuple], PlainValidator(_AxesValidator(kind)), WithJsonSchema(schema)]


class SweepSpec(AbstractAnalysisSpec):
    """Regimes of a rotor with balls at every point of a grid or a random sample.

    Every point is a start-up at a constant speed, classified like
    :class:`rotorlab.explore.BalancerRegimes` (balanced, side motions, non-synchronous, other).

    Parameters
    ----------
    speed_ratio : float, optional
        Base spin speed as a multiple of the critical speed p (-), > 0.
    speed : float, optional
        Base spin speed (rad/s), > 0. Neither: the model's constant ``[model.speed]``.
    param : dict of str to [start, stop, count] or [low, high]
        Model parameters to vary (:data:`SWEEP_PARAMETERS`; SI or with units), one result
        dimension each in the order given.
    ic : dict of str to [start, stop, count] or [low, high]
        Initial conditions to vary: ``psi_<i>`` (angle of ball i from the unbalance, rad),
        ``dpsi_<i>`` (its rate relative to the rotor, rad/s).
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
    window_revolutions : float
        Classification window (revolutions at the base speed), > 0.
    chunk : int
        Points per chunk, >= 1.
    rtol, atol : float
        Integrator tolerances.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratio", "speed", False),
        ("t_end", "revolutions", True),
    )

    type: Literal["sweep"] = "sweep"
    speed_ratio: quantity("dimensionless", gt=0) | None = Field(None, description="base speed / critical speed (-)")
    speed: quantity("angular_speed", gt=0) | None = Field(None, description="base spin speed (rad/s)")
    param: _axes("param") = Field(default_factory=dict, description="model parameters to vary (SI)")
    ic: _axes("ic") = Field(default_factory=dict, description="initial conditions to vary (rad, rad/s)")
    sample: integer(ge=1) | None = Field(None, description="number of random points instead of a grid")
    seed: integer() = Field(0, description="seed of the random sample")
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    revolutions: quantity("dimensionless", gt=0) | None = Field(None, description="simulated revolutions (-)")
    n_horizons: integer(ge=1) = Field(4, description="classification horizons")
    window_revolutions: quantity("dimensionless", gt=0) = Field(10.0, description="classification window (-)")
    chunk: integer(ge=1) = Field(1024, description="points per chunk")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) = Field(1e-10, description="absolute tolerance")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model (a rotor with balls), the ball indices and grid / sample entries."""
        issues = []
        if getattr(model, "type", None) != "jeffcott_balls" or model.n_balls < 1:
            return [Issue(("type",), "needs a jeffcott_balls model with at least one ball", self.type)]
        for name in self.ic:
            i = int(_STATE.match(name).group(2))
            if i > model.n_balls:
                issues.append(Issue(("ic", name), f"the model has {model.n_balls} ball(s)", name))
        for key in ("param", "ic"):
            for name, entry in getattr(self, key).items():
                if self.sample is not None and len(entry) != 2:
                    issues.append(Issue((key, name), "with sample, give a range [low, high]", list(entry)))
                if self.sample is None and len(entry) != 3:
                    issues.append(Issue((key, name), "give [start, stop, count] (or set sample)", list(entry)))
        if not self.param and not self.ic:
            issues.append(Issue(("param",), "give at least one param or ic to vary", None, show_value=False))
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
        if self.speed is not None:
            return self.speed
        if self.speed_ratio is not None:
            return self.speed_ratio * model.critical_speed()
        return model.speed_profile().final_speed

    def describe(self, model: AbstractModelSpec) -> str:
        names = [*self.param, *self.ic]
        what = f"{self.sample} random points" if self.sample else "a grid"
        return f"regimes at {what} over {', '.join(names) or 'nothing'}"
