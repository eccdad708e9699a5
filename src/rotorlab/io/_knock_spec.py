"""Case-file spec of the ``machine-knock`` analysis (:mod:`rotorlab.analyses._knock`): will a machine
with a balancer strike its housing during a run-up, from random ball positions, against ball damping.

Layout::

    [[analysis]]
    type = "machine-knock"
    name = "knock"
    t_end = "20 s"                                   # each run-up
    ball_damping = ["0.01 N*m*s/rad", "0.05 N*m*s/rad", "0.2 N*m*s/rad"]
    starts = 32                                      # random initial ball positions (seeded)
    seed = 0
"""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field

from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, integer, quantity

__all__ = ["MachineKnockSpec"]


class MachineKnockSpec(AbstractAnalysisSpec):
    """Probability of any contact with the housing and the largest impact impulse during a run-up,
    over random initial ball positions, for each ball damping."""

    type: Literal["machine-knock"] = "machine-knock"
    model_types: ClassVar[tuple[str, ...]] = ("machine",)
    wrong_model_message: ClassVar[str] = ('needs a machine model ([model] type "machine"), but the case\'s model '
                                          'is "{kind}"')
    races: tuple[integer(ge=0), ...] | None = Field(
        None, description="indices of the races that take part (default: all)")
    t_end: quantity("time", gt=0) = Field(description="duration of each run-up (s)")
    ball_damping: tuple[quantity("torque_damping", ge=0), ...] = Field(
        min_length=1, description="viscous damping of every ball relative to the rotor (N*m*s/rad)")
    starts: integer(ge=1) = Field(32, description="random initial ball positions")
    seed: integer(ge=0) = Field(0, description="seed of the random starts")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) = Field(1e-10, description="absolute tolerance")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        issues = super().case_issues(model)
        if issues:
            return issues
        n = len(model.races)
        issues = [Issue(("races", i), f"must be < {n} (the model has {n} race(s))", r)
                  for i, r in enumerate(self.races or ()) if r >= n]
        if issues:
            return issues
        if not model.clearances:
            issues.append(Issue(("type",), "needs a clearance on the machine ([[model.clearances]]): "
                                           "without one nothing can knock", self.type))
        races = model.races if self.races is None else [model.races[i] for i in self.races]
        if not any(r.balls for r in races):
            issues.append(Issue(("type",), "needs balls on the machine (a race with balls)", self.type))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        return (f"run-up knock: {self.starts} random ball starts x {len(self.ball_damping)} ball "
                f"damping(s), {self.t_end:g} s each")
