"""Case-file specs of the margin analyses: ``shock-margin`` (:mod:`rotorlab.analyses._shock_margin`) and
``friction-margin`` (:mod:`rotorlab.analyses._friction_margin`).

Layout::

    [[analysis]]
    type = "shock-margin"
    speed_ratio = [1.5, 2.0, 3.0]     # or speed = ["2400 rpm", ...]; neither: the model's speed
    directions = 24                   # knock and load-shift directions over a turn
    simulate = true                   # bisect the impulse and check the load shift by simulation

    [[analysis]]
    type = "friction-margin"
    speed = ["120 rad/s", "140 rad/s"]

Examples
--------
>>> ShockMarginSpec(speed_ratio=[2, 3]).directions
24
"""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field

from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, flag, integer, quantity

__all__ = ["ShockMarginSpec", "FrictionMarginSpec"]


class _Speeds(AbstractAnalysisSpec):
    """Speeds as multiples of the critical speed or in rad/s (or the model's constant speed)."""

    exclusive = (("speed_ratio", "speed", False),)
    speed_ratio: tuple[quantity("dimensionless", gt=0), ...] | None = Field(
        None, min_length=1, description="spin speeds as multiples of the critical speed p (-)")
    speed: tuple[quantity("angular_speed", gt=0), ...] | None = Field(
        None, min_length=1, description="spin speeds (rad/s)")

    def speed_values(self, model: AbstractModelSpec, critical_speed: float | None = None) -> list[float]:
        """The speeds (rad/s): ``speed``, ``speed_ratio`` times p, else the model's constant speed."""
        if self.speed is not None:
            return list(self.speed)
        if self.speed_ratio is not None:
            p = model.critical_speed() if critical_speed is None else critical_speed
            return [r * p for r in self.speed_ratio]
        profile = model.speed_profile()
        if profile is not None and profile.is_constant:
            return [profile.final_speed]
        spin = getattr(model, "spin_speed", None)  # a body spinning at one speed (toroidal_ball)
        return [] if spin is None else [spin]

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        issues = super().case_issues(model)
        if issues:
            return issues
        if self.speed_ratio is not None and model.critical_speed() is None:
            return [Issue(("speed_ratio",), "the model has no critical speed: give speed", self.speed_ratio)]
        if not self.speed_values(model):
            return [Issue(("speed",), "the model's speed is not constant: give speed or speed_ratio", None,
                          show_value=False)]
        return []


class ShockMarginSpec(_Speeds):
    """Minimal fatal lateral impulse (N s) and step change of unbalance (kg m) of the balanced state,
    over speed and direction."""

    type: Literal["shock-margin"] = "shock-margin"
    model_types: ClassVar[tuple[str, ...]] = ("jeffcott_balls", "machine")
    wrong_model_message: ClassVar[str] = ('needs a rotor with balls ([model] type "jeffcott_balls" or "machine"), '
                                          'but the case\'s model is "{kind}"')
    directions: integer(ge=1, le=720) = Field(24, description="directions of the knock and the load shift over a turn")
    simulate: flag() = Field(True, description="bisect the impulse and check the load shift by simulation")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-7, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) = Field(1e-9, description="absolute tolerance")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        issues = super().case_issues(model)
        if issues:
            return issues
        return _SHOCK_CHECKS[model.type](model)

    def describe(self, model: AbstractModelSpec) -> str:
        n = len(self.speed_values(model))
        return (f"shock margin: {self.directions} directions x {n} speed(s)"
                + (", simulated" if self.simulate else ", linearised only"))


class FrictionMarginSpec(_Speeds):
    """Band of ball positions held by friction and the worst residual vibration over it, over speed."""

    type: Literal["friction-margin"] = "friction-margin"
    model_types: ClassVar[tuple[str, ...]] = ("jeffcott_balls", "toroidal_ball", "machine")
    wrong_model_message: ClassVar[str] = ('needs a balancer with ball friction ([model] type "jeffcott_balls", '
                                          '"toroidal_ball" or "machine"), but the case\'s model is "{kind}"')
    grid: integer(ge=21, le=2001) = Field(241, description="grid points per ball angle over the band search (one "
                                                           "or two balls; more are searched by optimisation)")
    simulate: flag() = Field(True, description="check the band's worst point by simulation")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        issues = super().case_issues(model)
        if issues:
            return issues
        return _FRICTION_CHECKS[model.type](model)

    def describe(self, model: AbstractModelSpec) -> str:
        return f"friction margin: band and worst residual at {len(self.speed_values(model))} speed(s)"


def _rotor_shock_issues(model: AbstractModelSpec) -> list[Issue]:
    """``jeffcott_balls``: balls, without Coulomb friction."""
    if not model.balls:
        return [Issue(("type",), "needs balls on the rotor ([[model.balls]])", "shock-margin")]
    if any(b.friction > 0 for b in model.balls):
        return [Issue(("type",), "needs balls without Coulomb friction (the balanced state is then an "
                                 "isolated equilibrium): set the balls' friction to 0 or use friction-margin",
                      "shock-margin")]  # fmt: skip
    return []


def _machine_shock_issues(model: AbstractModelSpec) -> list[Issue]:
    """``machine``: balls, an unbalance (the knock and the load shift act at the first one's station) and a
    balanced state that is an equilibrium of the co-rotating frame (:meth:`Machine.why_no_rotating_frame`)."""
    from rotorlab.io._build import build_machine
    from rotorlab.models import ConstantSpeed

    if not model.balls:
        return [Issue(("type",), "needs balls on the machine ([[model.races]] with balls)", "shock-margin")]
    if not model.unbalances:
        return [Issue(("type",), "needs an unbalance ([[model.unbalances]]): the knock and the load shift act at "
                                 "the first one's station", "shock-margin")]  # fmt: skip
    why = build_machine(model).with_drive(ConstantSpeed(1.0)).why_no_rotating_frame()
    if why is not None:
        return [Issue(("type",), f"needs the machine's balanced state as a steady equilibrium, but {why}",
                      "shock-margin")]
    return []


#: What ``shock-margin`` needs of each model type it runs on (:attr:`ShockMarginSpec.model_types`).
_SHOCK_CHECKS = {"jeffcott_balls": _rotor_shock_issues, "machine": _machine_shock_issues}


def _rotor_friction_issues(model: AbstractModelSpec) -> list[Issue]:
    """No friction, no band: a rotor's one or two balls need Coulomb friction."""
    if not model.balls:
        return [Issue(("type",), "needs balls on the rotor ([[model.balls]])", "friction-margin")]
    if len(model.balls) > 2:
        return [Issue(("type",), f"maps the band of one or two balls on this rotor, the model has {len(model.balls)} "
                                 "(a machine case, [model] type \"machine\", searches the stuck set of any number)",
                      "friction-margin")]
    if not any(b.friction > 0 for b in model.balls):
        return [Issue(("type",), "needs Coulomb friction on the balls (model.balls[i].friction > 0): "
                                 "without it the band is a point", "friction-margin")]
    return []


def _torus_friction_issues(model: AbstractModelSpec) -> list[Issue]:
    """A torus ball needs rolling friction."""
    if model.rolling_friction <= 0:
        return [Issue(("type",), "needs rolling friction (model.rolling_friction > 0): without it the band is a point",
                      "friction-margin")]
    return []


def _machine_friction_issues(model: AbstractModelSpec) -> list[Issue]:
    """A machine: balls with Coulomb or rolling friction and, without friction, a balanced state in the
    co-rotating frame (isotropic supports, no gravity across the axis, a constant speed); any number of
    balls, on races that tilt or not (:mod:`rotorlab.analyses._friction_machine`)."""
    from dataclasses import replace

    from rotorlab.io._build import build_machine
    from rotorlab.models import ConstantSpeed

    balls = model.balls
    if not balls:
        return [Issue(("type",), "needs balls on the machine ([[model.races]] with balls)", "friction-margin")]
    if not any(b.coulomb > 0 or b.rolling > 0 for b in balls):
        return [Issue(("type",), "needs friction on the balls (model.races[i].balls[j].coulomb or rolling > 0): "
                                 "without it the band is a point", "friction-margin")]  # fmt: skip
    m = build_machine(model).with_drive(ConstantSpeed(1.0))
    smooth = replace(m, races=tuple(replace(r, balls=tuple(replace(b, coulomb=0.0, rolling=0.0) for b in r.balls))
                                    for r in m.races))  # fmt: skip
    why = smooth.why_no_rotating_frame()
    if why is not None:
        return [Issue(("type",), "needs the machine's balanced state without friction as a steady equilibrium "
                                 f"(the stuck balls then ride on a steady response), but {why}",
                      "friction-margin")]  # fmt: skip
    return []


#: What ``friction-margin`` needs of each model type it runs on (:attr:`FrictionMarginSpec.model_types`).
_FRICTION_CHECKS = {"jeffcott_balls": _rotor_friction_issues, "toroidal_ball": _torus_friction_issues,
                    "machine": _machine_friction_issues}
