"""Case-file specs of the steady-motion analyses of a rotor with balls (seeds 002, 003).

``steady`` (every steady motion at one speed with three stability verdicts),
``stability-chart`` (which motions exist and are stable over a speed range, optionally over a
second parameter), ``verify`` (basin fractions by simulation from a grid of ball starts) and
``run-up`` (passage through the critical speed with and without the balancer), computed by
:mod:`rotorlab.steady` and registered in :mod:`rotorlab.io._schema`. Each accepts the regime
overrides ``eccentricity`` and ``support_damping`` (and a ``regime`` label), so that one case
file covers several regimes of the same rotor.

Examples
--------
>>> spec = StabilityChartSpec(speeds=["300 rpm", "3000 rpm", 10], param="eccentricity",
...                           values=["0.5 mm", "2 mm", 4])
>>> spec.speeds[2], (spec.parameter_values() * 1e3).round(3).tolist()
(10, [0.5, 1.0, 1.5, 2.0])
"""

from __future__ import annotations

from typing import Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field, PlainValidator, ValidationInfo, WithJsonSchema, field_validator
from pydantic_core import PydanticCustomError

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.io._errors import Issue
from rotorlab.io._fields import (
    Unit,
    AbstractAnalysisSpec,
    AbstractModelSpec,
    RaceIndices,
    _choice,
    _error,
    _Name,
    _QuantityValidator,
    integer,
    quantity,
)
from rotorlab.io._jeffcott_specs import _SpeedProfile
from rotorlab.io._units import DIMENSIONS

__all__ = [
    "STEADY_PARAMETERS",
    "SteadyAnalysisSpec",
    "SteadySpec",
    "StabilityChartSpec",
    "VerifySpec",
    "RunUpSpec",
]

#: Second parameters of a stability chart: name to (dimension, lower bound kind, SI unit); the
#: names and units are those of :data:`rotorlab.steady.PARAMETERS`.
STEADY_PARAMETERS: dict[str, tuple[str, str, str]] = {
    "ball_mass": ("mass", "gt", "kg"),
    "ball_damping": ("torque_damping", "ge", "N*m*s/rad"),
    "eccentricity": ("length", "ge", "m"),
    "support_damping": ("damping", "ge", "N*s/m"),
}


class _GridValidator:
    """Read ``[start, stop, count]``: two quantities and a number of evenly spaced points."""

    def __init__(self, dimension: str | None, gt: float | None = None, ge: float | None = None) -> None:
        self.dimension = dimension
        self.gt, self.ge = gt, ge

    def __call__(self, value: Any, dimension: str | None = None) -> tuple[float, float, int]:
        dim = dimension or self.dimension
        if not isinstance(value, (list, tuple)) or len(value) != 3:
            raise _error("must be [start, stop, count] (count evenly spaced points from start to stop)")
        ends = []
        for what, raw in zip(("start", "stop"), value[:2]):
            if dim is None:
                if isinstance(raw, str):
                    raise _error(f"{what}: a value with a unit needs a valid param to know its dimension")
                dim = "dimensionless"
            try:
                ends.append(_QuantityValidator(dim, gt=self.gt, ge=self.ge)(raw))
            except PydanticCustomError as exc:
                raise _error(f"{what}: {(exc.context or {}).get('detail', exc.message())}") from None
        count = value[2]
        if isinstance(count, bool) or not isinstance(count, (int, float)) or not float(count).is_integer() or count < 1:
            raise _error("count (the third entry) must be an integer >= 1")
        start, stop, count = ends[0], ends[1], int(count)
        if count == 1 and start != stop:
            raise _error("count = 1 needs start = stop")
        if count > 1 and not stop > start:
            raise _error("stop must be > start")
        return start, stop, count


def _grid(dimension: str, *, gt: float | None = None, ge: float | None = None) -> Any:
    schema = {"type": "array", "minItems": 3, "maxItems": 3,
              "description": "[start, stop, count]: numbers in SI or strings with a unit, then an integer"}  # fmt: skip
    unit = (DIMENSIONS[dimension].si or "1") if dimension is not None else ""
    return Annotated[tuple[float, float, int], PlainValidator(_GridValidator(dimension, gt, ge)),
                     WithJsonSchema(schema), Unit(unit)]  # fmt: skip


class _TimesValidator:
    """Read one time (s) or one time per speed."""

    def __call__(self, value: Any) -> float | tuple[float, ...]:
        one = _QuantityValidator("time", gt=0)
        if isinstance(value, (list, tuple)):
            if not value:
                raise _error("must be a time > 0 (s) or a non-empty list of them (one per speed)")
            out = []
            for k, item in enumerate(value):
                try:
                    out.append(one(item))
                except PydanticCustomError as exc:
                    raise _error(f"entry {k}: {(exc.context or {}).get('detail', exc.message())}") from None
            return tuple(out)
        return one(value)


_Times = Annotated[Any, PlainValidator(_TimesValidator()), Unit("s"),
                   WithJsonSchema({"anyOf": [{"type": "number"}, {"type": "string"}, {"type": "array"}]})]  # fmt: skip
_Angles = tuple[tuple[quantity("angle"), ...], ...]


def grid_values(grid: tuple[float, float, int]) -> np.ndarray:
    """Return the ``count`` evenly spaced values of a ``(start, stop, count)`` grid."""
    start, stop, count = grid
    return np.linspace(start, stop, int(count))


class SteadyAnalysisSpec(AbstractAnalysisSpec):
    """Base of the steady-motion analyses: a rotor with balls, with optional regime overrides.

    Parameters
    ----------
    regime : str, optional
        Label of the regime (shown in reports; ``rotorlab steady --regime`` looks it up).
    eccentricity : float, optional
        Disc eccentricity e of this analysis (m), >= 0, instead of the model's.
    support_damping : float, optional
        External damping d of the disc centre of this analysis (N*s/m), >= 0, instead of the
        model's ``damping``.
    races : tuple of int, optional
        A machine model: the indices of the ball races that take part (default all).
    """

    regime: _Name | None = Field(None, description="regime label")
    eccentricity: quantity("length", ge=0) | None = Field(None, description="eccentricity e of this regime (m)")
    support_damping: quantity("damping", ge=0) | None = Field(
        None, description="support damping d of this regime (N*s/m)"
    )
    races: RaceIndices | None = Field(None, description="ball races that take part (machine; default all)")

    #: Whether the analysis integrates in time (then Coulomb friction of the balls is not allowed).
    simulates: ClassVar[bool] = False

    def overrides(self) -> dict[str, float]:
        """Return the regime overrides given, by :data:`rotorlab.steady.PARAMETERS` name (SI)."""
        return {k: getattr(self, k) for k in ("eccentricity", "support_damping") if getattr(self, k) is not None}

    def regime_text(self) -> str:
        """Return the regime label with its overrides, e.g. ``"short: e = 2.34 mm"`` ("" if none)."""
        parts = []
        if self.eccentricity is not None:
            parts.append(f"e = {self.eccentricity * 1e3:.4g} mm")
        if self.support_damping is not None:
            parts.append(f"d = {self.support_damping:.4g} N*s/m")
        label = self.regime or ""
        if parts:
            label = f"{label}: " if label else ""
            label += ", ".join(parts)
        return label

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check that the model runs steady-motion analyses (its ``steady_issues``: a rotor with
        balls, without friction when it simulates) and the choice of races."""
        return model.race_issues(self.races) or model.steady_issues(self)


def _speed_issue(spec: Any, key: str, model: AbstractModelSpec) -> list[Issue]:
    if getattr(spec, key) is not None and model.critical_speed() is None:
        return [Issue((key,), f"model '{model.type}' has no critical speed to scale: give speeds instead",
                      getattr(spec, key))]  # fmt: skip
    return []


def _angle_issues(rows: Any, key: str, n: int) -> list[Issue]:
    return [Issue((key, k), f"has {len(row)} angle(s) but the model has {n} ball(s): give one angle per ball",
                  list(row)) for k, row in enumerate(rows or ()) if len(row) != n]  # fmt: skip


def _ratio_text(omega: float, model: AbstractModelSpec) -> str:
    p = model.critical_speed()
    return f"{omega * _RPM:.5g} rpm" + (f" ({omega / p:.3g} p)" if p else "")


class SteadySpec(SteadyAnalysisSpec):
    """Every steady motion at one constant speed, with the three stability verdicts.

    Parameters
    ----------
    speed_ratio : float, optional
        Spin speed as a multiple of the critical speed p = sqrt(c / M) (-), > 0.
    speed : float, optional
        Spin speed (rad/s), > 0. Exactly one of ``speed_ratio`` and ``speed``.
    family_samples : int
        Sample points per free angle of a family of main motions (n >= 3 balls), >= 1.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (("speed_ratio", "speed", True),)

    type: Literal["steady"] = "steady"
    speed_ratio: quantity("dimensionless", gt=0) | None = Field(
        None, description="speed as a multiple of the critical speed (-)"
    )
    speed: quantity("angular_speed", gt=0) | None = Field(None, description="spin speed (rad/s)")
    family_samples: integer(ge=1) = Field(12, description="samples per free angle of a family (-)")

    def spin_speed(self, model: AbstractModelSpec) -> float:
        """Return the spin speed (rad/s)."""
        return self.speed if self.speed is not None else self.speed_ratio * model.critical_speed()

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model (see :class:`SteadyAnalysisSpec`) and that a speed ratio can be scaled."""
        return super().case_issues(model) + _speed_issue(self, "speed_ratio", model)

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        regime = self.regime_text()
        return f"steady motions at {_ratio_text(self.spin_speed(model), model)}" + (f", {regime}" if regime else "")


class StabilityChartSpec(SteadyAnalysisSpec):
    """Which steady motions exist and which are stable over a speed range (and a parameter).

    Parameters
    ----------
    speed_ratios : (float, float, int), optional
        ``[start, stop, count]`` of the speed axis as multiples of p (-), > 0.
    speeds : (float, float, int), optional
        ``[start, stop, count]`` of the speed axis (rad/s; e.g. ``["300 rpm", "3000 rpm", 91]``).
        Exactly one of ``speed_ratios`` and ``speeds``.
    param : {"ball_mass", "ball_damping", "eccentricity", "support_damping"}, optional
        A second parameter (see :func:`rotorlab.steady.with_parameter`).
    values : (float, float, int), optional
        ``[start, stop, count]`` of its values, in its SI unit (kg, N*m*s/rad, m, N*s/m) or as
        strings with a unit. Given with ``param`` only.
    family_samples : int
        Sample points per free angle of a family of main motions, >= 1.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (("speed_ratios", "speeds", True),)

    type: Literal["stability-chart"] = "stability-chart"
    speed_ratios: _grid("dimensionless", gt=0) | None = Field(
        None, description="[start, stop, count] of omega / p (-)"
    )
    speeds: _grid("angular_speed", gt=0) | None = Field(None, description="[start, stop, count] of speeds (rad/s)")
    param: _choice(*STEADY_PARAMETERS) | None = Field(None, description="second parameter")
    values: Annotated[Any, WithJsonSchema({"type": "array"}), Unit("SI")] = Field(
        None, description="[start, stop, count] of the parameter (SI)"
    )
    family_samples: integer(ge=1) = Field(8, description="samples per free angle of a family (-)")

    @field_validator("values", mode="plain")
    @classmethod
    def _read_values(cls, value: Any, info: ValidationInfo) -> tuple[float, float, int] | None:
        if value is None:
            return None
        param = info.data.get("param")
        if param is None:
            raise _error("needs param (the parameter these values belong to)")
        dimension, bound, _ = STEADY_PARAMETERS[param]
        return _GridValidator(dimension, **{bound: 0.0})(value)

    def spin_speeds(self, model: AbstractModelSpec) -> np.ndarray:
        """Return the speeds of the chart (rad/s), shape (count,)."""
        if self.speeds is not None:
            return grid_values(self.speeds)
        return grid_values(self.speed_ratios) * model.critical_speed()

    def parameter_values(self) -> np.ndarray | None:
        """Return the values of ``param`` (SI), or None."""
        return None if self.values is None else grid_values(self.values)

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model, that ``values`` come with ``param`` and a speed ratio can be scaled."""
        issues = super().case_issues(model) + _speed_issue(self, "speed_ratios", model)
        if self.param is not None and self.values is None:
            issues.append(Issue(("param",), "needs values = [start, stop, count]", self.param))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        om = self.spin_speeds(model)
        text = f"stability chart over {om.size} speeds, {_ratio_text(om[0], model)} to {_ratio_text(om[-1], model)}"
        if self.param is not None:
            unit = STEADY_PARAMETERS[self.param][2]
            text += f" x {self.values[2]} values of {self.param} ({self.values[0]:.4g} to {self.values[1]:.4g} {unit})"
        regime = self.regime_text()
        return text + (f", {regime}" if regime else "")


class VerifySpec(SteadyAnalysisSpec):
    """Check the predicted steady motions by simulation: basin fractions from a grid of starts.

    Parameters
    ----------
    speed_ratios : tuple of float, optional
        Spin speeds as multiples of p (-), > 0.
    speeds : tuple of float, optional
        Spin speeds (rad/s), > 0. Exactly one of ``speed_ratios`` and ``speeds``.
    ball_angle_points : int, optional
        Grid points per ball (:func:`rotorlab.steady.ball_grid`, offset so that no start lies on
        an invariant set), points**n_balls starts; default 8 when ``initial_ball_angles`` is not
        given. Excludes ``initial_ball_angles``.
    initial_ball_angles : tuple of tuple of float, optional
        Start configurations, one angle per ball from the unbalance (rad).
    t_end : float or tuple of float, optional
        Simulated time (s), one for all speeds or one per speed; default: 40 e-folding times of
        the slowest stable motion, within 300-6000 revolutions.
    settle_revolutions : float
        Final window in which a start must be at rest in the co-rotating frame (-), > 0.
    rate_tol : float
        At rest: every ball rate below ``rate_tol * omega`` (-), > 0.
    angle_tol : float
        Ball-angle tolerance of the match to a predicted motion (rad), > 0.
    rtol, atol : float
        Integrator tolerances (-).
    family_samples : int
        Sample points per free angle of a family of main motions, >= 1.
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratios", "speeds", True),
        ("ball_angle_points", "initial_ball_angles", False),
    )
    simulates: ClassVar[bool] = True

    type: Literal["verify"] = "verify"
    speed_ratios: tuple[quantity("dimensionless", gt=0), ...] | None = Field(
        None, min_length=1, description="speeds as multiples of the critical speed (-)"
    )
    speeds: tuple[quantity("angular_speed", gt=0), ...] | None = Field(
        None, min_length=1, description="spin speeds (rad/s)"
    )
    ball_angle_points: integer(ge=1) | None = Field(None, description="grid points per ball (-)")
    initial_ball_angles: _Angles | None = Field(None, description="ball configurations, one angle per ball (rad)")
    t_end: _Times | None = Field(None, description="simulated time, one or one per speed (s)")
    settle_revolutions: quantity("dimensionless", gt=0) = Field(20.0, description="final window (revolutions)")
    rate_tol: quantity("dimensionless", gt=0) = Field(1e-5, description="at-rest tolerance on rates / omega (-)")
    angle_tol: quantity("angle", gt=0) = Field(0.05, description="ball-angle tolerance of the match (rad)")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance (-)")
    atol: quantity("dimensionless", gt=0) = Field(1e-11, description="absolute tolerance (-)")
    family_samples: integer(ge=1) = Field(12, description="samples per free angle of a family (-)")

    def spin_speeds(self, model: AbstractModelSpec) -> np.ndarray:
        """Return the speeds (rad/s), shape (n_speed,)."""
        if self.speeds is not None:
            return np.array(self.speeds, dtype=float)
        return np.array(self.speed_ratios, dtype=float) * model.critical_speed()

    def start_count(self, n_balls: int) -> int:
        """Return the number of starts per speed."""
        if self.initial_ball_angles is not None:
            return len(self.initial_ball_angles)
        return (self.ball_angle_points or 8) ** n_balls

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model, angle rows against the balls and per-speed times against the speeds."""
        issues = super().case_issues(model) + _speed_issue(self, "speed_ratios", model)
        issues += _angle_issues(self.initial_ball_angles, "initial_ball_angles", model.balls_in(self.races))
        given = self.speeds if self.speeds is not None else self.speed_ratios
        if isinstance(self.t_end, tuple) and given is not None and len(self.t_end) != len(given):
            issues.append(Issue(("t_end",), f"has {len(self.t_end)} time(s) for {len(given)} speed(s): give one time "
                                "or one per speed", list(self.t_end)))  # fmt: skip
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        om = self.spin_speeds(model)
        text = (f"verification by simulation at {', '.join(_ratio_text(w, model) for w in om)}: "
                f"{self.start_count(model.n_balls)} start(s) per speed")  # fmt: skip
        regime = self.regime_text()
        return text + (f", {regime}" if regime else "")


class RunUpSpec(SteadyAnalysisSpec):
    """Run-up through the critical speed along a prescribed omega(t), with and without balls.

    Parameters
    ----------
    speed : ConstantSpeed or RampSpeed or HillSpeed, optional
        The speed profile (an ``[analysis.speed]`` table with ``profile = "ramp"`` or
        ``"hill"``); default the model's ``[model.speed]``.
    t_start : float
        Start time (s), >= 0 (> 0 for a Hill profile with exponent < 1).
    t_end : float
        End time (s), > t_start; synchronisation is judged over its last revolutions.
    initial_ball_angles : tuple of tuple of float, optional
        Start configurations, one angle per ball (rad); default the balls spread evenly,
        ``2 pi i / n + 0.3``.
    n_save : int
        Points of the saved time grid, >= 2.
    settle_revolutions : float
        Final window (revolutions at the final speed) in which the balls must rest relative to
        the rotor to count as synchronised (-), > 0.
    rate_tol : float
        Synchronised: every ball rate below ``rate_tol * omega`` (-), > 0.
    angle_tol : float
        Tolerance of the match to a steady motion at the final speed (rad), > 0.
    rtol, atol : float
        Integrator tolerances (-).
    passing_torque : bool
        A machine driven by a motor: also find the smallest motor torque whose run-up (over
        ``t_end``, from each start) passes the first critical speed, with the analysis' races and
        without any (:func:`rotorlab.analyses.passing_torque`), and what limits it (the rotor
        captured, or the balls desynchronised).
    passing_torque_rtol : float
        Relative width of that torque's final bracket (-), in (0, 1).
    passing_target_speed : float, optional
        The final speed a passing run-up exceeds (rad/s); default 1.05 times the first critical
        speed (of the machine with the races, and of the one without).
    passing_synchronise : bool
        A passing run-up also ends with every ball turning with the rotor (default true).
    """

    simulates: ClassVar[bool] = True

    type: Literal["run-up"] = "run-up"
    speed: _SpeedProfile | None = Field(None, description="speed profile omega(t)")
    t_start: quantity("time", ge=0) = Field(0.0, description="start time (s)")
    t_end: quantity("time", gt=0) = Field(description="end time (s)")
    initial_ball_angles: _Angles | None = Field(None, description="ball configurations, one angle per ball (rad)")
    n_save: integer(ge=2) = Field(2000, description="points of the saved time grid (-)")
    settle_revolutions: quantity("dimensionless", gt=0) = Field(20.0, description="final window (revolutions)")
    rate_tol: quantity("dimensionless", gt=0) = Field(1e-4, description="synchronised tolerance on rates / omega (-)")
    angle_tol: quantity("angle", gt=0) = Field(0.05, description="ball-angle tolerance of the match (rad)")
    rtol: quantity("dimensionless", gt=0, lt=1) = Field(1e-8, description="relative tolerance (-)")
    atol: quantity("dimensionless", gt=0) = Field(1e-11, description="absolute tolerance (-)")
    passing_torque: bool = Field(False, description="find the smallest motor torque that passes the first "
                                                    "critical speed, with and without the balls (machine with a motor)")
    passing_torque_rtol: quantity("dimensionless", gt=0, lt=1) = Field(
        1e-3, description="relative width of the passing-torque bracket (-)")
    passing_target_speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="final speed a passing run-up exceeds (rad/s); default 1.05 x the first critical speed")
    passing_synchronise: bool = Field(True, description="a passing run-up ends with the balls turning with the rotor")

    def profile(self, model: AbstractModelSpec) -> Any:
        """Return the speed profile spec: this analysis' ``speed``, else the model's."""
        return self.speed if self.speed is not None else model.speed_profile()

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model, the profile, the times and the angle rows."""
        issues = super().case_issues(model)
        profile = self.profile(model)
        if profile is None:
            issues.append(Issue((), "no speed profile: give an [analysis.speed] table or a [model.speed] profile",
                                show_value=False))  # fmt: skip
        elif profile.profile == "hill" and profile.exponent < 1 and self.t_start <= 0:
            issues.append(Issue(("t_start",), "must be > 0 (s) for a hill profile with exponent < 1 (the "
                                "acceleration is unbounded at t = 0)", self.t_start))  # fmt: skip
        if not self.t_end > self.t_start:
            issues.append(Issue(("t_end",), f"must be > t_start = {self.t_start:g} (s)", self.t_end))
        if self.initial_ball_angles is not None and len(self.initial_ball_angles) == 0:
            issues.append(Issue(("initial_ball_angles",), "is empty: give at least one configuration (one angle "
                                "per ball), or leave it out", []))
        issues += _angle_issues(self.initial_ball_angles, "initial_ball_angles", model.balls_in(self.races))
        if self.passing_torque:
            issues += model.passing_torque_issues(self)
        elif self.passing_target_speed is not None:
            issues.append(Issue(("passing_target_speed",), "applies to passing_torque = true only",
                                self.passing_target_speed))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        profile = self.profile(model)
        if profile is None:
            what = "no speed profile"
        elif profile.profile == "ramp":
            ends = f"{_ratio_text(profile.start, model)} to {_ratio_text(profile.stop, model)}"
            what = f"ramp {ends} in {profile.duration:g} s"
        else:
            what = f"{profile.profile} profile to {_ratio_text(profile.final_speed, model)}"
        starts = 1 if self.initial_ball_angles is None else len(self.initial_ball_angles)
        text = f"run-up ({what}) from {self.t_start:g} s to {self.t_end:g} s, {starts} start(s)"
        if self.passing_torque:
            text += f", smallest passing motor torque (to {self.passing_torque_rtol:g})"
        regime = self.regime_text()
        return text + (f", {regime}" if regime else "")
