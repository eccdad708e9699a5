"""Case-file specs of the rotor with balls: spin-speed profiles, balls, the
``jeffcott_balls`` model and the ``simulate`` analysis (registered in :mod:`rotorlab.io._schema`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Annotated, Any, ClassVar, Literal, Union

from pydantic import Field, field_validator, model_validator

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import (
    AbstractAnalysisSpec,
    AbstractModelSpec,
    RaceIndices,
    _choice,
    _Spec,
    integer,
    quantity,
    speed_text,
)

__all__ = [
    "AbstractSpeedProfile",
    "ConstantSpeed",
    "RampSpeed",
    "HillSpeed",
    "SPEED_PROFILES",
    "Ball",
    "JeffcottBallsSpec",
    "SimulateSpec",
]

# --------------------------------------------------------------------------- speed profiles


class AbstractSpeedProfile(_Spec):
    """A prescribed spin speed omega(t) of the rotor (rad/s)."""

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        raise NotImplementedError

    @property
    def is_constant(self) -> bool:
        """Whether the speed does not change with time."""
        return False

    @property
    def final_speed(self) -> float:
        """The speed approached for large times (rad/s)."""
        raise NotImplementedError


class ConstantSpeed(AbstractSpeedProfile):
    """Constant spin speed.

    Parameters
    ----------
    speed : float
        Spin speed omega (rad/s), > 0.
    """

    profile: Literal["constant"] = "constant"
    speed: quantity("angular_speed", gt=0) = Field(description="spin speed (rad/s)")

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        return self.speed

    @property
    def is_constant(self) -> bool:
        """True: the speed does not change."""
        return True

    @property
    def final_speed(self) -> float:
        """The constant speed (rad/s)."""
        return self.speed


class RampSpeed(AbstractSpeedProfile):
    """Linear run-up (or run-down) from ``start`` to ``stop`` in ``duration``, then constant.

    Parameters
    ----------
    start : float
        Speed at t = 0 (rad/s), >= 0.
    stop : float
        Speed reached at t = duration and kept afterwards (rad/s), >= 0.
    duration : float
        Length of the ramp (s), > 0.

    Notes
    -----
    omega(t) = start + (stop - start) * min(t / duration, 1) for t >= 0.
    """

    profile: Literal["ramp"] = "ramp"
    start: quantity("angular_speed", ge=0) = Field(description="speed at t = 0 (rad/s)")
    stop: quantity("angular_speed", ge=0) = Field(description="speed after the ramp (rad/s)")
    duration: quantity("time", gt=0) = Field(description="duration of the ramp (s)")

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        fraction = min(max(t / self.duration, 0.0), 1.0)
        return self.start + (self.stop - self.start) * fraction

    @property
    def final_speed(self) -> float:
        """The speed after the ramp (rad/s)."""
        return self.stop


class HillSpeed(AbstractSpeedProfile):
    """Smooth run-up following a Hill function.

    Parameters
    ----------
    max_speed : float
        Speed approached for t -> infinity (rad/s), > 0.
    t_half : float
        Time at which half of ``max_speed`` is reached (s), > 0.
    exponent : float
        Steepness n of the run-up (dimensionless), 0.01 <= n <= 1000.

    Notes
    -----
    omega(t) = max_speed * t**n / (t_half**n + t**n) for t >= 0.
    """

    profile: Literal["hill"] = "hill"
    max_speed: quantity("angular_speed", gt=0) = Field(description="final speed (rad/s)")
    t_half: quantity("time", gt=0) = Field(description="time to reach half speed (s)")
    exponent: quantity("dimensionless", ge=0.01, le=1000) = Field(
        description="steepness n (-), 0.01 to 1000"
    )

    def speed_at(self, t: float) -> float:
        """Return the spin speed at time ``t`` (s), in rad/s."""
        if t <= 0.0:
            return 0.0
        ratio = (self.t_half / t) ** self.exponent
        return self.max_speed / (1.0 + ratio)

    @property
    def final_speed(self) -> float:
        """The speed approached for large times (rad/s)."""
        return self.max_speed


#: Spin-speed profiles by the value of their ``profile`` key.
SPEED_PROFILES: Mapping[str, type[AbstractSpeedProfile]] = MappingProxyType(
    {
        "constant": ConstantSpeed,
        "ramp": RampSpeed,
        "hill": HillSpeed,
    }
)

_SpeedProfile = Annotated[
    Union[tuple(SPEED_PROFILES.values())],  # noqa: UP007 - built from the registry
    Field(discriminator="profile"),
]


# --------------------------------------------------------------------------- models


class Ball(_Spec):
    """One balancing ball (or roller) running in a circular race of the disc.

    Parameters
    ----------
    mass : float
        Ball mass m (kg), > 0.
    radius : float
        Radius R of the ball's centre path, measured from the disc centre (m), > 0.
    inertia : float, optional
        Moment of inertia of the ball about the rotor axis (kg*m^2), >= mass * radius**2.
        Omitted: a point mass, ``mass * radius**2`` (filled in by the model spec).
    damping : float
        Viscous damping of the ball's motion relative to the disc (N*m*s/rad), >= 0.
    friction : float
        Coulomb friction coefficient of the ball in its race (-), >= 0.
    count : int
        Input only: repeat this ball ``count`` times (the model spec expands it). >= 1.
    """

    mass: quantity("mass", gt=0) = Field(description="ball mass (kg)")
    radius: quantity("length", gt=0) = Field(description="radius of the ball's path (m)")
    inertia: quantity("inertia", ge=0) | None = Field(
        None, description="inertia about the rotor axis (kg*m^2)"
    )
    damping: quantity("torque_damping", ge=0) = Field(
        0.0, description="viscous damping relative to the disc (N*m*s/rad)"
    )
    friction: quantity("dimensionless", ge=0) = Field(
        0.0, description="Coulomb friction coefficient (-)"
    )
    count: integer(ge=1) = Field(1, exclude=True, description="number of identical balls")

    @model_validator(mode="after")
    def _check_inertia(self) -> Ball:
        if self.count > MAX_BALLS:
            raise IssueGroup([Issue(("count",), _too_many_balls(self.count), self.count)])
        point = self.mass * self.radius**2
        if self.inertia is not None and self.inertia < point * (1.0 - 1e-12):
            raise IssueGroup(
                [
                    Issue(
                        ("inertia",),
                        f"must be >= mass * radius^2 = {point:.6g} kg*m^2 (a point mass)",
                        self.inertia,
                    )
                ]
            )
        return self



#: Most balls a model may have: far beyond any balancer, and small enough that a simulation's
#: state (2 n + 4 entries) and saved trajectories stay in memory.
MAX_BALLS = 1000


def _too_many_balls(n: int) -> str:
    from rotorlab._memory import format_bytes

    return (f"{n} balls: the state would have {2 * n + 4} entries and one start saved at 2000 times alone "
            f"{format_bytes(8.0 * 2000 * (2 * n + 4))}; at most {MAX_BALLS} balls")


class JeffcottBallsSpec(AbstractModelSpec):
    """Jeffcott rotor (disc on a massless elastic shaft) with an automatic ball balancer.

    Parameters
    ----------
    frame : {"fixed", "rotating"}
        Coordinates of the disc centre: fixed (x, y) or co-rotating (u, v).
    disc_mass : float
        Disc mass M1 (kg), > 0.
    eccentricity : float
        Distance e between the disc's centre of mass and the shaft axis (m), >= 0.
    stiffness : float
        Lateral shaft stiffness c (N/m), > 0.
    damping : float
        External viscous damping of the disc centre beta (N*s/m), >= 0.
    speed : ConstantSpeed or RampSpeed or HillSpeed, optional
        The spin-speed profile; analyses may set their own constant speed instead.
    balls : tuple of Ball
        The balls, with ``count`` expanded and ``inertia`` filled in.

    Notes
    -----
    The critical speed is p = sqrt(c / M), with M = M1 + sum of the ball masses (seed 002,
    eq. (10)).
    """

    type: Literal["jeffcott_balls"] = "jeffcott_balls"
    frame: _choice("fixed", "rotating") = Field("fixed", description="fixed or rotating")
    disc_mass: quantity("mass", gt=0) = Field(description="disc mass M1 (kg)")
    eccentricity: quantity("length", ge=0) = Field(description="disc eccentricity e (m)")
    stiffness: quantity("stiffness", gt=0) = Field(description="shaft stiffness c (N/m)")
    damping: quantity("damping", ge=0) = Field(
        0.0, description="external viscous damping of the disc centre (N*s/m)"
    )
    speed: _SpeedProfile | None = Field(None, description="spin-speed profile")
    balls: tuple[Ball, ...] = Field((), description="balancing balls")
    sweeps_keys: ClassVar[bool] = True  # basins and sweeps vary model.<key path> (its named parameters)

    @field_validator("balls", mode="after")
    @classmethod
    def _expand_balls(cls, balls: tuple[Ball, ...]) -> tuple[Ball, ...]:
        total = sum(ball.count for ball in balls)
        if total > MAX_BALLS:
            raise IssueGroup([Issue((), _too_many_balls(total), total)])
        out = []
        for ball in balls:
            inertia = ball.inertia if ball.inertia is not None else ball.mass * ball.radius**2
            single = ball.model_copy(update={"count": 1, "inertia": inertia})
            out.extend([single] * ball.count)
        return tuple(out)

    @property
    def n_balls(self) -> int:
        """Number of balls."""
        return len(self.balls)

    @property
    def total_mass(self) -> float:
        """M = M1 + sum of ball masses (kg)."""
        return self.disc_mass + sum(b.mass for b in self.balls)

    def critical_speed(self) -> float:
        """Return p = sqrt(c / M) (rad/s), M = disc plus balls (seed 002, eq. (10))."""
        return math.sqrt(self.stiffness / self.total_mass)

    def speed_profile(self) -> AbstractSpeedProfile | None:
        """Return the ``[model.speed]`` profile, or None."""
        return self.speed

    def start_coordinates(self) -> dict[str, str]:
        """``psi_<i>``, ``dpsi_<i>``, the rotor's start position ``rotor_u``, ``rotor_v`` and the
        rotor's and balls' parameters (none without balls)."""
        from rotorlab.io._coordinates import BALANCER_COORDINATES, ROTOR_STATE_COORDINATES, ball_coordinates

        return ball_coordinates(self.n_balls, {**ROTOR_STATE_COORDINATES, **BALANCER_COORDINATES})

    def missing_coordinate(self, name: str) -> str | None:
        """``has <n> ball(s)`` for the angle or rate of a ball the model does not have."""
        from rotorlab.io._coordinates import BALL_COORDINATE

        return f"has {self.n_balls} ball(s)" if BALL_COORDINATE.match(name) else None

    def without_regimes(self) -> str:
        """A rotor with balls has a regime mapper; this one has no balls."""
        return "a jeffcott_balls model without balls"

    def steady_issues(self, analysis: AbstractAnalysisSpec) -> list[Issue]:
        """Check a steady-motion analysis: at least one ball, no Coulomb friction if it simulates."""
        if self.n_balls < 1:
            return super().steady_issues(analysis)
        if getattr(analysis, "simulates", False) and any(b.friction > 0 for b in self.balls):
            return [Issue(("type",), "integrates without Coulomb friction: set the balls' friction to 0",
                          analysis.type)]
        return []

    def describe(self) -> str:
        """Return ``jeffcott_balls, <n> ball(s), critical speed p = ...`` (``rotorlab validate``)."""
        return f"{self.type}, {self.n_balls} ball(s), critical speed p = {speed_text(self.critical_speed())}"


#: Model specifications by the value of their ``type`` key.

def constant_spin_speed(speed: float | None, speed_ratio: float | None, model: AbstractModelSpec) -> float | None:
    """Return an analysis' constant spin speed (rad/s): ``speed``, else ``speed_ratio * p``, else the
    model's profile speed if that profile is constant, else None."""
    if speed is not None:
        return speed
    if speed_ratio is not None:
        p = model.critical_speed()
        return None if p is None else speed_ratio * p
    profile = model.speed_profile()
    if profile is not None and profile.is_constant:
        return profile.final_speed
    return None


class SimulateSpec(AbstractAnalysisSpec):
    """Time simulation of an ensemble of start-ups (one per initial ball configuration).

    Parameters
    ----------
    name : str, optional
        Unique name; default ``"simulate-<index>"``.
    speed_ratio : float, optional
        Constant spin speed as a multiple of the model's critical speed p (-), > 0.
    speed : float, optional
        Constant spin speed (rad/s), > 0. Neither ``speed_ratio`` nor ``speed``: the model's
        ``[model.speed]`` profile is followed.
    initial_ball_angles : tuple of tuple of float, optional
        Initial ball configurations, each with one angle per ball, measured from the unbalance
        (rad). Excludes ``ball_angle_grid``.
    ball_angle_grid : int, optional
        N >= 1: every ball takes the angles 2*pi*k/N, k = 0..N-1, giving N**n_balls
        configurations. Excludes ``initial_ball_angles``.
    t_end : float, optional
        Simulated time (s), > 0. Excludes ``revolutions``.
    revolutions : float, optional
        Simulated time as a number of revolutions at the (constant) analysis speed, > 0.
    n_save : int
        Number of points of the saved, uniform time grid, >= 2.
    rtol, atol : float
        Relative (0 < rtol < 1) and absolute (> 0) error tolerances of the integrator.
    races : tuple of int, optional
        A machine model: the indices of the ball races that take part (a variant of the
        machine; ``[]``: no balancer), default all.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratio", "speed", False),
        ("initial_ball_angles", "ball_angle_grid", True),
        ("t_end", "revolutions", True),
    )

    type: Literal["simulate"] = "simulate"
    #: A rotor with balls: the jeffcott_balls start-ups, or the machine's own simulate.
    model_types: ClassVar[tuple[str, ...]] = ("jeffcott_balls", "machine")
    speed_ratio: quantity("dimensionless", gt=0) | None = Field(
        None, description="speed as a multiple of the critical speed (-)"
    )
    speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="constant spin speed (rad/s)"
    )
    initial_ball_angles: tuple[tuple[quantity("angle"), ...], ...] | None = Field(
        None, description="ball configurations, one angle per ball (rad)"
    )
    ball_angle_grid: integer(ge=1) | None = Field(
        None, description="N angles per ball, N**n_balls configurations"
    )
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    revolutions: quantity("dimensionless", gt=0) | None = Field(
        None, description="simulated revolutions at the analysis speed (-)"
    )
    n_save: integer(ge=2) = Field(2000, description="points of the saved time grid")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) = Field(1e-10, description="absolute tolerance")
    races: RaceIndices | None = Field(None, description="ball races that take part (machine; default all)")

    def spin_speed(self, model: AbstractModelSpec) -> float | None:
        """Return the constant spin speed of this analysis (rad/s), or None to follow a profile.

        ``speed`` if given, else ``speed_ratio * p``, else the model's profile speed if that
        profile is constant, else None.
        """
        return constant_spin_speed(self.speed, self.speed_ratio, model)

    def duration(self, model: AbstractModelSpec) -> float:
        """Return the simulated time (s): ``t_end``, or ``revolutions`` at the spin speed."""
        if self.t_end is not None:
            return self.t_end
        omega = self.spin_speed(model)
        if omega is None or self.revolutions is None:
            raise ValueError("revolutions need a constant spin speed")
        return self.revolutions * 2.0 * math.pi / omega

    def describe(self, model: AbstractModelSpec) -> str:
        """Return ``<n> start configuration(s), <t> s at <speed>`` (``rotorlab validate``)."""
        return (f"{len(self.ball_angle_sets(model.balls_in(self.races)))} start configuration(s), "
                f"{self.duration(model):.6g} s "
                f"at {speed_text(self.spin_speed(model), model.critical_speed())}")  # fmt: skip

    def summary(self, model: AbstractModelSpec) -> dict[str, Any]:
        """Return ``speed`` (rad/s or None), ``speed_rpm``, ``configurations`` and ``t_end`` (s)."""
        omega = self.spin_speed(model)
        return {"speed": omega, "speed_rpm": None if omega is None else omega * RPM_PER_RAD_S,
                "configurations": len(self.ball_angle_sets(model.balls_in(self.races))),
                "t_end": self.duration(model)}  # fmt: skip

    def ball_angle_sets(self, n_balls: int) -> tuple[tuple[float, ...], ...]:
        """Return the initial ball configurations, shape (n_configurations, n_balls), in rad.

        Examples
        --------
        >>> spec = SimulateSpec(ball_angle_grid=2, t_end=1.0)
        >>> [[round(a, 4) for a in row] for row in spec.ball_angle_sets(2)]
        [[0.0, 0.0], [0.0, 3.1416], [3.1416, 0.0], [3.1416, 3.1416]]
        """
        if self.initial_ball_angles is not None:
            return self.initial_ball_angles
        n = self.ball_angle_grid or 1
        angles = [2.0 * math.pi * k / n for k in range(n)]
        return tuple(itertools.product(angles, repeat=n_balls))

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model type, ball-angle rows against the number of balls and that a spin
        speed exists."""
        issues = super().case_issues(model) or model.race_issues(self.races)
        if issues:
            return issues
        n = model.balls_in(self.races)
        if self.initial_ball_angles is not None and len(self.initial_ball_angles) == 0:
            issues.append(Issue(("initial_ball_angles",), "is empty: give at least one configuration (one angle "
                                "per ball), or leave it out and give ball_angle_grid", []))  # fmt: skip
        for k, row in enumerate(self.initial_ball_angles or ()):
            if len(row) != n:
                issues.append(
                    Issue(
                        ("initial_ball_angles", k),
                        f"has {len(row)} angle(s) but the model has {n} ball(s): "
                        "give one angle per ball",
                        list(row),
                    )
                )
        profile = model.speed_profile()
        if self.speed_ratio is None and self.speed is None and profile is None:
            issues.append(
                Issue(
                    (),
                    "no spin speed: give speed_ratio or speed, or a [model.speed] profile",
                    show_value=False,
                )
            )
        if self.speed_ratio is not None and model.critical_speed() is None:
            issues.append(
                Issue(
                    ("speed_ratio",),
                    f"model '{model.type}' has no critical speed to scale: give speed instead",
                    self.speed_ratio,
                )
            )
        elif (
            self.revolutions is not None
            and (self.speed_ratio is not None or self.speed is not None or profile is not None)
            and self.spin_speed(model) is None
        ):
            issues.append(
                Issue(
                    ("revolutions",),
                    f"needs a constant spin speed, but the {profile.profile} profile changes: "
                    "give t_end instead",
                    self.revolutions,
                )
            )
        return issues
