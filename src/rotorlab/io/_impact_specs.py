"""Case-file specs of the centrifuge rotor striking its housing (seed 001).

The ``impact_rotor`` model (rotor and membranes in ``[model]``, the conical housing in
``[model.housing]``, the stones in ``[model.stones]``) and the analyses ``impacts`` (one run:
regime, impacts, sliding, energy, trajectory of P) and ``impacts-sweep`` (many random stone
sequences at each value of one parameter), registered in :mod:`rotorlab.io._schema`.

Examples
--------
>>> from rotorlab.io import load_case
>>> case = load_case("krasnov-crusher")
>>> round(case.model.housing.gap, 9), round(case.model.housing.cone_angle, 4), case.model.stones.n_guides
(0.0045, 0.9599, 4)
>>> [a.type for a in case.analyses]
['impacts', 'impacts-sweep']
"""

from __future__ import annotations

import math
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, ValidationInfo, WithJsonSchema, field_validator, model_validator

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import (
    Unit,
    AbstractAnalysisSpec,
    AbstractModelSpec,
    _choice,
    _error,
    _QuantityValidator,
    _Spec,
    flag,
    integer,
    quantity,
)

__all__ = [
    "IMPACT_SWEEP_PARAMETERS",
    "HousingSpec",
    "StonesSpec",
    "ImpactRotorSpec",
    "ImpactsSpec",
    "ImpactsSweepSpec",
]

#: Parameters an ``impacts-sweep`` can vary: name -> (dimension, SI unit).
IMPACT_SWEEP_PARAMETERS: dict[str, tuple[str, str]] = {
    "stone_mass": ("mass", "kg"),
    "interval": ("time", "s"),
    "internal_friction": ("dimensionless", ""),
    "restitution": ("dimensionless", ""),
    "friction": ("dimensionless", ""),
}


class HousingSpec(_Spec):
    """The conical housing and the impact laws (see :class:`rotorlab.models.Housing`)."""

    radius: quantity("length", gt=0) = Field(description="radius r_P of the circle of P (m)")
    height: quantity("length") = Field(description="height h_P of P above the centre of mass (m)")
    gap: quantity("length", gt=0) = Field(description="gap Delta along the cone normal (m)")
    cone_angle: quantity("angle", gt=0, le=math.pi / 2) = Field(
        description="angle beta of the cone normal (rad); 90 deg is a cylinder"
    )
    restitution: quantity("dimensionless", ge=0, le=1) = Field(0.5, description="restitution k (-)")
    friction: quantity("dimensionless", ge=0) = Field(0.2, description="friction f at the housing (-)")
    rest_speed: quantity("velocity", gt=0) = Field(1e-4, description="rebound speed turning chatter into sliding (m/s)")
    count_speed: quantity("velocity", ge=0) = Field(
        0.0, description="approach speed from which impacts count (m/s); 0: every located impact"
    )
    whirl_limit: quantity("angular_speed", gt=0) | None = Field(
        None, description="backward whirl speed that stops a run (rad/s); default: the run stops where the "
                          "slip of P over the housing vanishes (without tilt at r_P sin(beta) omega0 / gap)"
    )

    @model_validator(mode="after")
    def _check_speeds(self) -> HousingSpec:
        if 0.0 < self.count_speed <= self.rest_speed:
            raise IssueGroup([Issue(("rest_speed",), f"must be < count_speed ({self.count_speed:g} m/s)", self.rest_speed)])
        return self


class StonesSpec(_Spec):
    """The stones and the accelerator (see :class:`rotorlab.models.StoneFeed`)."""

    mass: quantity("mass", gt=0) = Field(description="mass m_q of a stone (kg)")
    interval: quantity("time", gt=0) = Field(description="time Delta t between stones (s)")
    radius: quantity("length", gt=0) = Field(description="radius R_q of the accelerator (m)")
    height: quantity("length") = Field(description="height h_q of the accelerator above the centre of mass (m)")
    spiral_angle: quantity("angle", gt=0, lt=math.pi / 2) = Field(description="angle a of the guides to the radius (rad)")
    guide_friction: quantity("dimensionless", ge=0) = Field(description="friction f_q between stone and guide (-)")
    start_radius: quantity("length", gt=0) = Field(0.1, description="radius where a stone lands on its guide (m)")
    start_speed: quantity("velocity", ge=0) = Field(0.0, description="speed of a landing stone along its guide (m/s)")
    n_guides: integer(ge=1) = Field(4, description="number N of guides (-)")
    guides: _choice("random", "cyclic") = Field("random", description="guide of each stone: random or in turn")
    first_time: quantity("time", gt=0) | None = Field(None, description="time of the first stone (s); default one interval")
    mass_spread: quantity("dimensionless", ge=0, lt=1) = Field(0.0, description="relative half-width of the stone masses (-)")
    time_jitter: quantity("dimensionless", ge=0, lt=0.5) = Field(0.0, description="relative jitter of the stone times (-)")

    @model_validator(mode="after")
    def _check(self) -> StonesSpec:
        issues = []
        if self.start_radius >= self.radius:
            issues.append(Issue(("start_radius",), f"must be < radius ({self.radius:g} m)", self.start_radius))
        cot = 1.0 / math.tan(self.spiral_angle)
        if self.guide_friction >= cot:
            issues.append(Issue(("guide_friction",), f"must be < cot(spiral_angle) = {cot:.4g} (else a stone stays put)",
                                self.guide_friction))  # fmt: skip
        if issues:
            raise IssueGroup(issues)
        return self


class ImpactRotorSpec(AbstractModelSpec):
    """Centrifuge rotor on two membranes, kicked by stones, striking a conical housing (seed 001).

    Parameters
    ----------
    mass, inertia_transverse, inertia_polar : float
        m (kg), A1 = A2, A3 (kg*m^2).
    spin_speed : float
        omega0 (rad/s).
    stiffness_1, stiffness_2, height_1, height_2 : float
        Membranes: c1, c2 (N/m) at h1, h2 above the centre of mass (m).
    internal_friction : float
        gamma (-).
    translational : bool
        Freeze the tilt.
    housing : HousingSpec
    stones : StonesSpec
    """

    type: Literal["impact_rotor"] = "impact_rotor"
    mass: quantity("mass", gt=0) = Field(description="rotor mass m (kg)")
    inertia_transverse: quantity("inertia", gt=0) = Field(description="transverse moment of inertia A1 (kg*m^2)")
    inertia_polar: quantity("inertia", gt=0) = Field(description="polar moment of inertia A3 (kg*m^2)")
    spin_speed: quantity("angular_speed", gt=0) = Field(description="spin speed omega0 (rad/s)")
    stiffness_1: quantity("stiffness", gt=0) = Field(description="stiffness c1 of membrane 1 (N/m)")
    stiffness_2: quantity("stiffness", gt=0) = Field(description="stiffness c2 of membrane 2 (N/m)")
    height_1: quantity("length") = Field(description="height h1 of membrane 1 (m)")
    height_2: quantity("length") = Field(description="height h2 of membrane 2 (m)")
    internal_friction: quantity("dimensionless", ge=0) = Field(0.2, description="internal friction gamma (-)")
    translational: flag() = Field(False, description="freeze the tilt (translational motion of the axis)")
    housing: HousingSpec = Field(description="the conical housing ([model.housing])")
    stones: StonesSpec = Field(description="the stones ([model.stones])")

    @model_validator(mode="after")
    def _check_heights(self) -> ImpactRotorSpec:
        if self.height_1 == self.height_2:
            raise IssueGroup([Issue(("height_2",), "must differ from height_1", self.height_2)])
        return self

    def describe(self) -> str:
        """Return a one-line description."""
        kind = "translational " if self.translational else ""
        return (f"{kind}centrifuge rotor {self.mass:g} kg at {self.spin_speed * RPM_PER_RAD_S:.5g} rpm, "
                f"gap {self.housing.gap * 1e3:.3g} mm, stones {self.stones.mass:g} kg every {self.stones.interval:g} s")  # fmt: skip


class _ImpactAnalysis(AbstractAnalysisSpec):
    """Common keys of the impact analyses: duration, seed, tolerances and parameter overrides."""

    model_types: ClassVar[tuple[str, ...]] = ("impact_rotor",)
    wrong_model_message: ClassVar[str] = "needs an impact_rotor model (this case has '{kind}')"

    t_end: quantity("time", gt=0) = Field(10.0, description="duration of a run (s)")
    seed: integer(ge=0) = Field(0, description="seed of the (first) stone sequence (-)")
    stone_mass: quantity("mass", gt=0) | None = Field(None, description="stone mass of this analysis (kg)")
    interval: quantity("time", gt=0) | None = Field(None, description="time between stones of this analysis (s)")
    internal_friction: quantity("dimensionless", ge=0) | None = Field(None, description="gamma of this analysis (-)")
    restitution: quantity("dimensionless", ge=0, le=1) | None = Field(None, description="k of this analysis (-)")
    friction: quantity("dimensionless", ge=0) | None = Field(None, description="f of this analysis (-)")
    sliding_fraction: quantity("dimensionless", ge=0, le=1) = Field(
        0.001, description="share of a run in sustained sliding contact from which it is 'sliding' "
        "(-); 0: the paper's convention, any sustained sliding episode"
    )
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance (-)")
    atol: quantity("dimensionless", gt=0) = Field(1e-11, description="absolute tolerance (SI)")

    def overrides(self) -> dict[str, float]:
        """Parameter overrides given, by :data:`rotorlab.analyses.SWEEP_PARAMS` name (SI)."""
        keys = ("stone_mass", "interval", "internal_friction", "restitution", "friction")
        return {k: getattr(self, k) for k in keys if getattr(self, k) is not None}


class ImpactsSpec(_ImpactAnalysis):
    """One run from rest: regime, impacts, sliding, energy and the trajectory of P.

    Parameters
    ----------
    t_end : float
        Duration (s), > 0; default 10 s.
    seed : int
        Seed of the stone sequence, >= 0.
    n_save : int
        Saved states (trajectory of P), >= 2.
    stone_mass, interval, internal_friction, restitution, friction : float, optional
        Overrides of the model's values (kg, s, -, -, -).
    sliding_fraction, rtol, atol : float
        See :func:`rotorlab.analyses.impact_run`.
    """

    type: Literal["impacts"] = "impacts"
    n_save: integer(ge=2) = Field(4000, description="saved states (-)")

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        mass = self.stone_mass if self.stone_mass is not None else model.stones.mass
        return f"impacts over {self.t_end:g} s, stones {mass:g} kg, seed {self.seed}"


class ImpactsSweepSpec(_ImpactAnalysis):
    """Many random stone sequences at each value of one parameter (median and spread).

    Parameters
    ----------
    param : {"stone_mass", "interval", "internal_friction", "restitution", "friction"}
        The swept parameter.
    values : tuple of float
        Its values, SI numbers or strings with a unit (``["0.5 kg", "1 kg"]``).
    n_sequences : int
        Stone sequences per value (seeds ``seed .. seed + n - 1``), >= 1.
    """

    type: Literal["impacts-sweep"] = "impacts-sweep"
    param: _choice(*IMPACT_SWEEP_PARAMETERS) = Field("stone_mass", description="swept parameter")
    values: Annotated[Any, WithJsonSchema({"type": "array"}), Unit("SI")] = Field(description="values of the parameter (SI)")
    n_sequences: integer(ge=1) = Field(16, description="stone sequences per value (-)")

    @field_validator("values", mode="plain")
    @classmethod
    def _read_values(cls, value: Any, info: ValidationInfo) -> tuple[float, ...]:
        param = info.data.get("param", "stone_mass")
        if not isinstance(value, (list, tuple)) or not value:
            raise _error("must be a non-empty list of values")
        dim, _ = IMPACT_SWEEP_PARAMETERS.get(param, ("dimensionless", ""))
        read = _QuantityValidator(dim, gt=0.0 if param in ("stone_mass", "interval") else None,
                                  ge=None if param in ("stone_mass", "interval") else 0.0)  # fmt: skip
        out = []
        for k, item in enumerate(value):
            try:
                out.append(read(item))
            except Exception as exc:  # pydantic's custom error carries the detail
                detail = getattr(exc, "context", None) or {}
                raise _error(f"entry {k}: {detail.get('detail', str(exc))}") from None
        return tuple(out)

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        unit = IMPACT_SWEEP_PARAMETERS[self.param][1]
        vals = ", ".join(f"{v:g}" for v in self.values)
        return f"{self.param} sweep ({vals}{' ' + unit if unit else ''}), {self.n_sequences} sequences x {self.t_end:g} s"
