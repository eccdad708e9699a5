"""Case-file specs of a Jeffcott rotor in a circular clearance (rub, impacts, backward whirl).

The ``rub_rotor`` model (:class:`rotorlab.contact.JeffcottRub`: rotor, clearance, rigid or
elastic stator, restitution and friction in ``[model]``) and the analysis ``rub`` (simulate,
classify the regime of the last window and put the closed-form predictions beside it),
registered in :mod:`rotorlab.io._schema`.

Examples
--------
>>> from rotorlab.io import load_case
>>> case = load_case("rub-jeffcott")
>>> case.model.type, round(case.model.clearance, 6), [a.type for a in case.analyses]
('rub_rotor', 0.001, ['rub', 'rub-map'])
"""

from __future__ import annotations

import math
from typing import ClassVar, Literal

from pydantic import Field, model_validator

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, integer, quantity

__all__ = ["JeffcottRubSpec", "RubSpec", "RubMapSpec"]


class JeffcottRubSpec(AbstractModelSpec):
    """A Jeffcott rotor at constant spin in a circular clearance (see :class:`rotorlab.contact.RubRotor`)."""

    type: Literal["rub_rotor"] = "rub_rotor"
    mass: quantity("mass", gt=0) = Field(description="rotor mass m (kg)")
    stiffness: quantity("stiffness", gt=0) = Field(description="shaft and support stiffness k (N/m)")
    damping: quantity("damping", ge=0) = Field(0.0, description="viscous damping c of the rotor (N*s/m)")
    eccentricity: quantity("length", ge=0) = Field(0.0, description="unbalance eccentricity eps (m)")
    clearance: quantity("length", gt=0) = Field(description="radial clearance delta (m)")
    stator_stiffness: quantity("stiffness", gt=0) | None = Field(
        None, description="radial stiffness k_s of the stator (N/m); omit for a rigid stator"
    )
    stator_damping: quantity("damping", ge=0) = Field(0.0, description="radial damping c_s of the stator (N*s/m)")
    friction: quantity("dimensionless", ge=0) = Field(0.0, description="Coulomb friction mu at the stator (-)")
    rotor_radius: quantity("length", gt=0) = Field(description="rotor radius R_r at the contact (m)")
    restitution: quantity("dimensionless", ge=0, le=1) = Field(0.5, description="restitution e of a rigid stator (-)")
    rest_speed: quantity("velocity", gt=0) = Field(
        1e-5, description="rebound speed below which chatter becomes sustained contact (m/s)"
    )
    spin_speed: quantity("angular_speed", ge=0) = Field(description="spin speed Omega (rad/s)")
    rub_map_axis: ClassVar[str] = "eccentricity"  # what a rub-map varies besides speed and clearance

    def rub_issues(self, spec: AbstractAnalysisSpec) -> list[Issue]:
        """What the rub analyses need of this model: a rigid stator's rotor starts inside the clearance."""
        if self.stator_stiffness is None and spec.initial_radius > self.clearance:
            return [Issue(("initial_radius",), f"must be <= the clearance ({self.clearance:g} m) with a rigid "
                          "stator", spec.initial_radius)]  # fmt: skip
        return []

    @model_validator(mode="after")
    def _check_stator(self) -> JeffcottRubSpec:
        if self.stator_stiffness is None and self.stator_damping > 0.0:
            raise IssueGroup([Issue(("stator_damping",), "needs an elastic stator (give stator_stiffness)",
                                    self.stator_damping)])  # fmt: skip
        return self

    def critical_speed(self) -> float | None:
        """sqrt(k / m) (rad/s)."""
        return math.sqrt(self.stiffness / self.mass)

    def describe(self) -> str:
        """Return a one-line description."""
        stator = "rigid stator" if self.stator_stiffness is None else f"stator {self.stator_stiffness:g} N/m"
        return (f"Jeffcott rotor {self.mass:g} kg at {self.spin_speed * RPM_PER_RAD_S:.5g} rpm in a "
                f"{self.clearance * 1e3:.3g} mm clearance, {stator}, friction {self.friction:g}")  # fmt: skip


def _machine_rub_issues(spec: AbstractAnalysisSpec, model: AbstractModelSpec) -> list[Issue]:
    """A machine runs the rub analyses with a clearance, a constant speed and the rotor radius."""
    if not model.clearances:
        return [Issue(("type",), "needs a clearance on the machine ([[model.clearances]])", spec.type)]
    issues = []
    if model.drive.profile != "constant":
        issues.append(Issue(("type",), "needs a constant speed on the machine ([model.drive] "
                                       f'profile = "constant"), got "{model.drive.profile}"', spec.type))
    c = model.clearances[0]
    if c.rotor_radius <= 0.0:
        issues.append(Issue(("type",), "needs the rotor radius at the contact "
                                       "(model.clearances[0].rotor_radius > 0)", spec.type))
    if c.stator is None and spec.initial_radius > c.gap:
        issues.append(Issue(("initial_radius",), f"must be <= the clearance ({c.gap:g} m) with a rigid stator",
                            spec.initial_radius))  # fmt: skip
    return issues


def _model_rub_issues(spec: AbstractAnalysisSpec, model: AbstractModelSpec) -> list[Issue]:
    """The model's own ``rub_issues`` hook; a model without one has no clearance to rub in."""
    hook = getattr(model, "rub_issues", None)
    if hook is None:
        return [Issue(("type",), "needs a rub_rotor model, or a machine with a clearance", spec.type)]
    return list(hook(spec))


class _RubRunSpec(AbstractAnalysisSpec):
    """What the rub analyses share: the run, its classified window and the starting whirl.

    Every run starts on a circular whirl of radius ``initial_radius`` at ``initial_whirl`` (rad/s,
    < 0 backward); the last ``window`` seconds of ``t_end`` are classified from ``samples``
    samples. The model must have a clearance to rub in (its ``rub_issues`` hook).
    """

    t_end: quantity("time", gt=0) = Field(description="simulated time (s)")
    window: quantity("time", gt=0) = Field(description="classified window at the end of the run (s)")
    initial_radius: quantity("length", ge=0) = Field(0.0, description="radius of the starting whirl (m)")
    initial_whirl: quantity("angular_speed") = Field(0.0, description="angular speed of the starting whirl (rad/s)")

    def _window_issues(self) -> list[Issue]:
        if self.window >= self.t_end:
            return [Issue(("window",), f"must be < t_end ({self.t_end:g} s)", self.window)]
        return []

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """A rub_rotor, or a machine with a clearance, a constant speed and the rotor radius; a
        rigid stator's rotor must start inside the clearance."""
        return _model_rub_issues(self, model)


class RubSpec(_RubRunSpec):
    """Simulate the rotor in its clearance and classify what it does (:class:`rotorlab.contact.RubRegime`).

    The start is a circular whirl of radius ``initial_radius`` at ``initial_whirl`` (rad/s, < 0
    backward); the last ``window`` seconds of ``t_end`` are classified, with the closed-form
    predictions (no-rub orbit, full-rub branch and its stability, rolling backward whirl) beside.
    """

    type: Literal["rub"] = "rub"
    samples: integer(ge=2) = Field(400, description="samples in the window (-)")

    @model_validator(mode="after")
    def _check_window(self) -> RubSpec:
        issues = self._window_issues()
        if issues:
            raise IssueGroup(issues)
        return self

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        return f"rub regime over the last {self.window:g} s of {self.t_end:g} s"


_AXIS_UNITS = {"clearance": "length", "eccentricity": "length", "unbalance": "unbalance"}


class RubMapSpec(_RubRunSpec):
    """A map of rub regimes over spin speed and a second parameter, on the sweep engine.

    ``spin_speed = [start, stop, n]`` and exactly one of ``clearance``, ``eccentricity``
    (``rub_rotor``) or ``unbalance`` (a ``machine`` with a clearance) as ``[start, stop, n]``;
    every point is simulated from the same start and its last ``window`` classified
    (:class:`rotorlab.contact.RubRegimes`), with the grazing boundary of the closed forms beside.
    """

    type: Literal["rub-map"] = "rub-map"
    spin_speed: tuple[quantity("angular_speed", gt=0), quantity("angular_speed", gt=0), integer(ge=1)] = Field(
        description="spin speeds [start, stop, count] (rad/s)")
    clearance: tuple[quantity("length", gt=0), quantity("length", gt=0), integer(ge=1)] | None = Field(
        None, description="clearances [start, stop, count] (m)")
    eccentricity: tuple[quantity("length", ge=0), quantity("length", ge=0), integer(ge=1)] | None = Field(
        None, description="unbalance eccentricities [start, stop, count] (m), rub_rotor")
    unbalance: tuple[quantity("unbalance", ge=0), quantity("unbalance", ge=0), integer(ge=1)] | None = Field(
        None, description="first unbalance m e [start, stop, count] (kg*m), machine")
    samples: integer(ge=2) = Field(200, description="samples in the window (-)")

    @model_validator(mode="after")
    def _check(self) -> RubMapSpec:
        given = [k for k in _AXIS_UNITS if getattr(self, k) is not None]
        issues = []
        if len(given) != 1:
            issues.append(Issue((), "give exactly one of clearance, eccentricity or unbalance as the second axis"
                                + (f" (got {', '.join(given)})" if given else ""), show_value=False))
        issues += self._window_issues()
        if issues:
            raise IssueGroup(issues)
        return self

    @property
    def second_axis(self) -> str:
        """The name of the second axis."""
        return next(k for k in _AXIS_UNITS if getattr(self, k) is not None)

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """A rub_rotor (eccentricity or clearance), or a machine with a clearance and a constant
        speed (unbalance or clearance)."""
        issues = super().case_issues(model)
        axis, own = self.second_axis, getattr(model, "rub_map_axis", None)
        if own is not None and axis != "clearance" and axis != own:
            issues.append(Issue((axis,), f"does not apply: a {model.type} model varies its {own}",
                                getattr(self, axis)))
        elif axis == "unbalance" and own == axis and not model.unbalances:
            issues.append(Issue(("unbalance",), "needs an unbalance on the machine ([[model.unbalances]])",
                                self.unbalance))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        n = self.spin_speed[2] * getattr(self, self.second_axis)[2]
        return f"rub-regime map over spin speed x {self.second_axis}: {n} points, {self.t_end:g} s each"
