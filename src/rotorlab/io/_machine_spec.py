"""Case-file spec of the ``machine`` model: a linear structure with balancers, unbalances,
gravity and a drive (see :mod:`rotorlab.models._machine`).

Layout::

    [model]
    type = "machine"
    n_modes = 6                      # optional: keep the lowest modes of the structure
    [model.structure]                # the same tables as a multibody or fe_rotor model
    type = "multibody"
    [[model.structure.bodies]]
    ...
    [[model.races]]                  # any number of races
    at = "rotor"                     # node: its name (or node = index, or position = z)
    radius = "40 mm"
    axial_offset = "0 mm"            # race plane from the node along +z
    balls = [{ mass = "5 g", damping = "2e-4 N*m*s/rad", count = 2 }]
                                     # optional per ball: coulomb = 0.01 (friction coefficient)
                                     # and rolling = "0.1 mm" (arm): stick-slip, torque bound
                                     # (coulomb radius + rolling) N
    [[model.unbalances]]             # static (magnitude, phase, axial_offset) and/or couple
    at = "rotor"
    magnitude = "50 g*mm"
    phase = "0 deg"
    couple = "2 g*mm^2"              # optional: couple unbalance, heavy spot on the +z side at
    couple_phase = "90 deg"          # couple_phase
    [model.gravity]
    vector = ["0 m/s^2", "-9.81 m/s^2", "0 m/s^2"]   # z is the shaft axis
    [[model.clearances]]             # at most one: rotor-stator contact at a station
    at = "rotor"
    gap = "1 mm"
    restitution = 0.5                # Newton's coefficient (impacts on a rigid or moving stator)
    friction = 0.2
    rotor_radius = "50 mm"           # its surface speed R_r Omega enters the slip
    rest_speed = "1e-5 m/s"          # optional: chatter below it becomes sustained contact
    conical = { half_angle = "30 deg", lever = "50 mm" }   # optional: a conical gap (seed 001)
    center_at_rest = true            # optional: centre the stator where the station rests under
                                     # gravity (or center = ["0 mm", "-16 mm"]; default: the axis)
    stator = { stiffness = "1e6 N/m", damping = "100 N*s/m", mass = "10 kg" }
                                     # optional (omitted: rigid); mass 0: massless elastic stator
    [model.drive]                    # a speed profile (constant, ramp, hill) or a motor
    profile = "motor"
    stall_torque = "2 N*m"
    no_load_speed = "1500 rpm"
    polar_inertia = "0.05 kg*m^2"
"""

from __future__ import annotations

import math

from typing import Annotated, ClassVar, Literal, Union

from pydantic import Field, field_validator, model_validator

from rotorlab.io._build import build_machine
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fe_rotor_spec import FeRotorSpec
from rotorlab.io._fields import AbstractAnalysisSpec, AbstractModelSpec, _Spec, integer, quantity
from rotorlab.io._jeffcott_specs import MAX_BALLS, SPEED_PROFILES, AbstractSpeedProfile, _too_many_balls
from rotorlab.io._linear_analyses import UnbalanceSpec
from rotorlab.io._multibody_spec import MultibodySpec
from rotorlab.io._part_specs import PART_SPECS
from rotorlab.io._station import _Station

__all__ = ["MachineBallSpec", "RaceSpec", "MachineUnbalanceSpec", "GravitySpec", "MotorSpec", "ServoSpec",
           "StatorSpec", "ConicalGapSpec", "ClearanceSpec",
           "MachineSpec", "build_machine", "MACHINE_STEADY_PARAMETERS"]

#: Second parameters of a machine's stability chart (every ball of the chosen races takes the
#: value); the other parameters of :data:`rotorlab.io._steady_specs.STEADY_PARAMETERS` belong to
#: the single-mass rotor.
MACHINE_STEADY_PARAMETERS = ("ball_mass", "ball_damping")
#: Steady-motion analysis types that run on a machine.
_STEADY_TYPES = ("steady", "stability-chart", "run-up")


class MachineBallSpec(_Spec):
    """One ball (or pendulum) of a race.

    Parameters
    ----------
    mass : float
        m (kg), > 0.
    inertia : float
        Own moment of inertia about its centre (kg*m^2), >= 0.
    damping : float
        Viscous damping relative to the rotor (N*m*s/rad), >= 0.
    coulomb, rolling : float
        Coulomb friction coefficient (-) and rolling-friction arm (m), >= 0: stick-slip with the
        race's torque bounded by ``(coulomb radius + rolling) N`` (see
        :func:`rotorlab._kernels.machine_friction.friction_solve`); 0 with a clearance.
    count : int
        Repeat this ball ``count`` times.
    """

    mass: quantity("mass", gt=0) = Field(description="ball mass (kg)")
    inertia: quantity("inertia", ge=0) = Field(0.0, description="own central inertia (kg*m^2)")
    damping: quantity("torque_damping", ge=0) = Field(
        0.0, description="viscous damping relative to the rotor (N*m*s/rad)")
    coulomb: quantity("dimensionless", ge=0) = Field(0.0, description="Coulomb friction (-)")
    rolling: quantity("length", ge=0) = Field(0.0, description="rolling-friction arm (m)")
    count: integer(ge=1) = Field(1, exclude=True, description="number of identical balls")

    @model_validator(mode="after")
    def _count(self):
        if self.count > MAX_BALLS:
            raise IssueGroup([Issue(("count",), _too_many_balls(self.count), self.count)])
        return self


class RaceSpec(_Station):
    """A ball race at a station of the structure.

    Parameters
    ----------
    node, at, position : int, str, float
        Where (one of them).
    axial_offset : float
        Race plane from the node along +z (m).
    radius : float
        Radius of the balls' centre path (m), > 0.
    balls : tuple of MachineBallSpec
        Its balls (``count`` expanded).
    """

    radius: quantity("length", gt=0) = Field(description="radius of the balls' path (m)")
    balls: tuple[MachineBallSpec, ...] = Field(min_length=1, description="balls of the race")

    @field_validator("balls", mode="after")
    @classmethod
    def _expand(cls, balls):
        total = sum(b.count for b in balls)
        if total > MAX_BALLS:
            raise IssueGroup([Issue((), _too_many_balls(total), total)])
        out = []
        for b in balls:  # one copy per entry, repeated: written_balls() finds the entries again
            out.extend([b.model_copy(update={"count": 1})] * b.count)
        return tuple(out)

    def written_balls(self) -> list[tuple[int, MachineBallSpec]]:
        """The ball entries as written, each with its index in the race's ``balls`` before
        ``count`` was expanded (for key paths in messages): the expansion repeats one object per
        entry."""
        out: list[tuple[int, MachineBallSpec]] = []
        for b in self.balls:
            if not out or out[-1][1] is not b:
                out.append((len(out), b))
        return out


#: The machine's unbalances are the one unbalance spec of the case files (static and couple).
MachineUnbalanceSpec = UnbalanceSpec


class StatorSpec(_Spec):
    """An elastic stator: massless (contact stiffness and damping) or a housing with mass on an
    elastic mounting (see :class:`rotorlab.models.ElasticStator`)."""

    stiffness: quantity("stiffness", gt=0) = Field(description="stator stiffness k_s (N/m)")
    damping: quantity("damping", ge=0) = Field(0.0, description="stator damping c_s (N*s/m)")
    mass: quantity("mass", ge=0) = Field(0.0, description="housing mass m_s (kg); 0: massless stator")


class ConicalGapSpec(_Spec):
    """A conical gap: ``w = sin(half_angle) (x, y) + lever (phi_x, phi_y)``."""

    half_angle: quantity("angle", gt=0, le=1.5707963267948966) = Field(
        description="half angle of the cone (rad)")
    lever: quantity("length") = Field(description="lever of the tilt at the contact (m)")


class ClearanceSpec(_Station):
    """A clearance between the rotor and a stator at a station (see :class:`rotorlab.models.Clearance`).

    Parameters
    ----------
    node, at, position : int, str, float
        Where (one of them); ``axial_offset`` moves the contact plane along +z.
    gap : float
        Radial clearance delta (m), > 0.
    stator : StatorSpec, optional
        Omitted: a rigid stator.
    restitution, friction : float
        Newton's restitution e in [0, 1]; Coulomb friction mu >= 0.
    rotor_radius : float
        Radius of the rotor's surface at the contact (m).
    rest_speed : float
        Rebound speed below which chatter becomes sustained contact (m/s).
    conical : ConicalGapSpec, optional
    center : (float, float), optional
        Centre of the stator's circle (m); default the axis.
    center_at_rest : bool
        Centre it where the station rests under gravity instead.
    """

    gap: quantity("length", gt=0) = Field(description="radial clearance delta (m)")
    stator: StatorSpec | None = Field(None, description="elastic stator (omitted: rigid)")
    restitution: quantity("dimensionless", ge=0, le=1) = Field(0.5, description="restitution e (-)")
    friction: quantity("dimensionless", ge=0) = Field(0.0, description="Coulomb friction mu (-)")
    rotor_radius: quantity("length", ge=0) = Field(0.0, description="rotor radius R_r at the contact (m)")
    rest_speed: quantity("velocity", gt=0) = Field(
        1e-5, description="rebound speed below which chatter becomes sustained contact (m/s)")
    conical: ConicalGapSpec | None = Field(None, description="conical gap (seed 001)")
    center: tuple[quantity("length"), quantity("length")] | None = Field(
        None, description="centre of the stator circle (m); default: the axis")
    center_at_rest: bool = Field(False, description="centre the stator where the station rests "
                                                    "under gravity")

    @model_validator(mode="after")
    def _one_center(self):
        if self.center is not None and self.center_at_rest:
            raise IssueGroup([Issue(("center_at_rest",), "give either center or center_at_rest = true, "
                                                         "not both", self.center_at_rest)])
        off = math.hypot(*self.center) if self.center is not None else 0.0
        if off > self.gap and (self.stator is None or self.stator.mass > 0):
            # the structure starts at rest on the axis: it would start beyond the stator it strikes
            kind = "rigid stator" if self.stator is None else "housing"
            raise IssueGroup([Issue(("center",), f"lies {off * 1e3:.6g} mm from the axis, where the rotor "
                                                 f"starts at rest: outside the gap of the {kind}; allowed: "
                                                 f"at most the gap, {self.gap * 1e3:.6g} mm, from the axis "
                                                 "(or center_at_rest = true)", self.center)])
        return self


class GravitySpec(_Spec):
    """Gravity in the fixed frame, z along the shaft axis (m/s^2)."""

    vector: tuple[quantity("acceleration"), quantity("acceleration"), quantity("acceleration")] = \
        Field(description="gravity (g_x, g_y, g_z) with z the shaft axis (m/s^2)")


class MotorSpec(AbstractSpeedProfile):
    """A motor: linear torque characteristic, or a table of torque over speed.

    Parameters
    ----------
    stall_torque, no_load_speed : float, optional
        ``T = stall_torque (1 - Omega / no_load_speed)`` (N*m, rad/s), both > 0.
    speeds, torques : tuple of float, optional
        A table instead (rad/s increasing, N*m), interpolated linearly; its torque at the initial
        speed > 0.
    polar_inertia : float
        Of everything that spins with the rotor (kg*m^2), > 0.
    initial_speed : float
        Speed at t = 0 (rad/s), >= 0.
    """

    profile: Literal["motor"] = "motor"
    stall_torque: quantity("torque") | None = Field(None, description="stall torque (N*m)")
    no_load_speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="no-load speed (rad/s)")
    speeds: tuple[quantity("angular_speed", ge=0), ...] | None = Field(
        None, description="speeds of the torque table (rad/s)")
    torques: tuple[quantity("torque"), ...] | None = Field(
        None, description="torques of the torque table (N*m)")
    polar_inertia: quantity("inertia", gt=0) = Field(description="spinning inertia (kg*m^2)")
    initial_speed: quantity("angular_speed", ge=0) = Field(0.0, description="speed at t = 0 (rad/s)")

    @model_validator(mode="after")
    def _one_characteristic(self):
        lin = self.stall_torque is not None or self.no_load_speed is not None
        tab = self.speeds is not None or self.torques is not None
        issues = []
        if lin == tab:
            issues.append(Issue((), "give either stall_torque and no_load_speed, or speeds and "
                                    "torques", show_value=False))
        elif lin and (self.stall_torque is None or self.no_load_speed is None):
            k = "stall_torque" if self.stall_torque is None else "no_load_speed"
            issues.append(Issue((k,), "required with a linear characteristic", show_value=False))
        elif tab:
            if self.speeds is None or self.torques is None or len(self.speeds) != len(self.torques) \
                    or len(self.speeds) < 2:
                issues.append(Issue(("torques",), "speeds and torques must both be given, of "
                                                  "equal length >= 2", show_value=False))
            elif any(b <= a for a, b in zip(self.speeds[:-1], self.speeds[1:])):
                issues.append(Issue(("speeds",), "must increase strictly", list(self.speeds)))
            elif not self._table_torque(self.initial_speed) > 0:
                issues.append(Issue(("torques",), f"the torque at the initial speed "
                                                  f"({self.initial_speed:g} rad/s), "
                                                  f"{self._table_torque(self.initial_speed):g} N*m, must be > 0 "
                                                  "N*m: else the motor never spins the machine up",
                                    list(self.torques)))
        if lin and self.stall_torque is not None and not self.stall_torque > 0:
            issues.append(Issue(("stall_torque",), "must be > 0 N*m (the torque at rest): with 0 the motor never "
                                                   "spins the machine up, with less it drives it backwards",
                                self.stall_torque))
        if issues:
            raise IssueGroup(issues)
        return self

    def _table_torque(self, speed: float) -> float:
        """The table's torque at ``speed`` (N*m): interpolated linearly, held constant outside
        (as :class:`rotorlab.models.Motor`)."""
        import numpy as np

        return float(np.interp(speed, self.speeds, self.torques))

    def speed_at(self, t: float) -> float:
        """The initial speed (the motor's speed is a state, not a profile)."""
        return self.initial_speed

    @property
    def final_speed(self) -> float:
        """No-load speed, or the table's zero-torque speed if any, else its last speed (rad/s)."""
        if self.no_load_speed is not None:
            return self.no_load_speed
        for (w0, t0), (w1, t1) in zip(zip(self.speeds, self.torques),
                                      zip(self.speeds[1:], self.torques[1:])):
            if t0 > 0 >= t1:
                return w0 + (w1 - w0) * t0 / (t0 - t1)
        return self.speeds[-1]


class ServoSpec(MotorSpec):
    """A speed-commanded drive whose torque the motor's characteristic limits
    (:class:`rotorlab.models.ServoDrive`)::

        [model.drive]
        profile = "servo"
        stall_torque = "2 N*m"           # the torque limit: the motor's characteristic (or speeds/torques)
        no_load_speed = "3000 rpm"       # optional with a servo: omitted, the limit is constant
        polar_inertia = "0.05 kg*m^2"
        operating_speed = "1200 rpm"     # the command: ramp at ramp_rate, dwell, on to operating_speed
        ramp_rate = "20 rad/s^2"
        dwell_speed = "300 rpm"          # optional, with dwell_time (default: no dwell)
        dwell_time = "2 s"
        gain = "1 N*m*s/rad"             # speed-loop gain K: T = min(T_max, max(-T_max, K (W_cmd - W)))
    """

    profile: Literal["servo"] = "servo"  # type: ignore[assignment]
    operating_speed: quantity("angular_speed", gt=0) = Field(description="the command's final speed (rad/s)")
    ramp_rate: quantity("angular_acceleration", gt=0) = Field(description="the command's acceleration (rad/s^2)")
    dwell_speed: quantity("angular_speed", ge=0) = Field(0.0, description="dwell speed (rad/s)")
    dwell_time: quantity("time", ge=0) = Field(0.0, description="dwell time (s)")
    gain: quantity("torque_damping", gt=0) = Field(1.0, description="speed-loop gain (N*m*s/rad)")

    @model_validator(mode="before")
    @classmethod
    def _constant_limit(cls, data):
        if isinstance(data, dict) and "stall_torque" in data and "no_load_speed" not in data:
            data = dict(data, no_load_speed=1e300)  # a constant limit
        return data

    @model_validator(mode="after")
    def _command(self):
        if self.initial_speed > self.operating_speed:
            raise IssueGroup([Issue(("initial_speed",), f"must be <= operating_speed ({self.operating_speed:g} "
                                                        "rad/s)", self.initial_speed)])
        return self

    @property
    def final_speed(self) -> float:
        return self.operating_speed

    def build(self):
        """The :class:`rotorlab.models.ServoDrive`."""
        from rotorlab.models import ServoDrive

        return ServoDrive(self.stall_torque if self.speeds is None else (self.speeds, self.torques),
                          self.polar_inertia, self.no_load_speed if self.speeds is None else float("inf"),
                          operating_speed=self.operating_speed, ramp_rate=self.ramp_rate,
                          dwell_speed=self.dwell_speed, dwell_time=self.dwell_time, gain=self.gain,
                          initial_speed=self.initial_speed)


_Drive = Annotated[Union[tuple(SPEED_PROFILES.values()) + (MotorSpec, ServoSpec)],  # noqa: UP007
                   Field(discriminator="profile")]
_Structure = Annotated[Union[MultibodySpec, FeRotorSpec], Field(discriminator="type")]  # noqa: UP007


class MachineSpec(AbstractModelSpec):
    """A linear structure with ball races, unbalances, gravity and a drive.

    Parameters
    ----------
    structure : MultibodySpec or FeRotorSpec
        The rotor and its supports, with the tables of those models.
    races : tuple of RaceSpec
    unbalances : tuple of MachineUnbalanceSpec
    gravity : GravitySpec, optional
    drive : a speed profile or MotorSpec
    n_modes : int, optional
        Keep the lowest modes of the structure.
    """

    type: Literal["machine"] = "machine"
    structure: _Structure = Field(description="the linear structure (multibody or fe_rotor)")
    races: tuple[RaceSpec, ...] = Field((), description="ball races")
    # the attachment parts (rotorlab.models._parts): one key each, ``[[model.<key>]]``
    __annotations__.update({key: tuple[spec, ...] for key, spec in PART_SPECS.items()})
    locals().update({key: Field((), description=spec.description) for key, spec in PART_SPECS.items()})
    gravity: GravitySpec | None = Field(None, description="gravity")
    drive: _Drive = Field(description="spin-speed profile or motor")
    n_modes: integer(ge=1) | None = Field(None, description="modes of the structure kept")
    clearances: tuple[ClearanceSpec, ...] = Field(
        (), max_length=1, description="rotor-stator clearances (at most one)")

    @model_validator(mode="after")
    def _check_places(self):
        issues = []
        for key, items in (("races", self.races), ("clearances", self.clearances),
                           *((k, getattr(self, k)) for k in PART_SPECS)):
            for i, it in enumerate(items):
                node, bad, msg = self.structure.locate(it.node, it.at, it.position)
                if node is None:
                    issues.append(Issue((key, i, bad), msg, getattr(it, bad)))
        if self.clearances:
            for i, r in enumerate(self.races):
                for j, b in r.written_balls():  # key paths as written (count = n repeats an entry)
                    for k in ("coulomb", "rolling"):
                        if getattr(b, k) != 0.0:
                            issues.append(Issue(("races", i, "balls", j, k), "must be 0 with a "
                                                "clearance: ball friction (stick-slip) together with "
                                                "rotor-stator contact is not implemented", getattr(b, k)))
        issues += self._n_modes_issues()
        if issues:
            raise IssueGroup(issues)
        return self

    def _n_modes_issues(self) -> list[Issue]:
        """What ``Machine`` requires of ``n_modes`` (:func:`rotorlab.io._build.n_modes_issues`)."""
        from rotorlab.io._build import n_modes_issues

        return n_modes_issues(self)

    def node_of(self, item) -> int:
        """Node index of a race or unbalance spec."""
        return self.structure.locate(item.node, item.at, item.position)[0]

    @property
    def n_balls(self) -> int:
        return sum(len(r.balls) for r in self.races)

    def speed_profile(self) -> AbstractSpeedProfile | None:
        return self.drive

    def critical_speed(self) -> float | None:
        """The lowest forward 1x critical speed of the structure with the balls locked (rad/s)."""
        from rotorlab.io._build import machine_critical_speed

        return machine_critical_speed(self)

    sweeps_keys: ClassVar[bool] = True
    rub_map_axis: ClassVar[str] = "unbalance"  # what a rub-map varies besides speed and clearance

    def rub_issues(self, spec: AbstractAnalysisSpec) -> list[Issue]:
        """What the rub analyses need of a machine: a clearance, a constant speed, the rotor radius."""
        from rotorlab.io._rub_specs import _machine_rub_issues

        return _machine_rub_issues(spec, self)

    @property
    def balls(self) -> tuple[MachineBallSpec, ...]:
        """Every ball, races in order."""
        return tuple(b for r in self.races for b in r.balls)

    def start_coordinates(self) -> dict[str, str]:
        """``psi_<i>``, ``dpsi_<i>`` (every ball, races in order), ``spin_speed``, ``ball_mass``,
        ``ball_damping`` (none without balls)."""
        from rotorlab.io._coordinates import MACHINE_COORDINATES, ball_coordinates

        return ball_coordinates(self.n_balls, MACHINE_COORDINATES)

    def linear_structure(self) -> MultibodySpec | FeRotorSpec:
        """The structure (campbell, modes and the other linear analyses run on it)."""
        return self.structure

    def race_issues(self, races: tuple[int, ...] | None) -> list[Issue]:
        """Each chosen race index must name one of the races."""
        n = len(self.races)
        return [Issue(("races", i), f"must be < {n} (the model has {n} race(s))", r)
                for i, r in enumerate(races or ()) if r >= n]

    def balls_in(self, races: tuple[int, ...] | None) -> int:
        chosen = self.races if races is None else [self.races[i] for i in races if i < len(self.races)]
        return sum(len(r.balls) for r in chosen)

    def steady_issues(self, analysis) -> list[Issue]:
        """``steady``, ``stability-chart`` (over speed and ``ball_mass`` or ``ball_damping``) and
        ``run-up`` run on a machine; the single-mass regime overrides do not apply."""
        if analysis.type not in _STEADY_TYPES:
            return [Issue(("type",), "does not run on a machine model (it runs "
                                     f"{', '.join(_STEADY_TYPES)}, simulate, basin and sweep)", analysis.type)]
        if analysis.type != "run-up":
            from rotorlab.io._build import why_no_steady_motions

            why = why_no_steady_motions(self)
            if why is not None:
                return [Issue(("type",), f"this machine has no steady motions: {why} (analysis type "
                                         "simulate or run-up)", analysis.type)]
        issues = [Issue((key,), "belongs to the single-mass jeffcott_balls model: a machine's "
                                "unbalances and damping are set in [model]", getattr(analysis, key))
                  for key in ("eccentricity", "support_damping") if getattr(analysis, key, None) is not None]
        param = getattr(analysis, "param", None)
        if param is not None and param not in MACHINE_STEADY_PARAMETERS:
            issues.append(Issue(("param",), "a machine's stability chart varies "
                                            f"{' or '.join(MACHINE_STEADY_PARAMETERS)}", param))
        if analysis.type != "run-up" and self.balls_in(getattr(analysis, "races", None)) == 0:
            issues.append(Issue(("races",) if getattr(analysis, "races", None) is not None else ("type",),
                                "steady motions of a balancer need at least one ball",
                                getattr(analysis, "races", None) or analysis.type))
        return issues

    def passing_torque_issues(self, analysis) -> list[Issue]:
        """``passing_torque = true`` scales the motor's torque: a motor drive, a stall torque
        T(0) > 0, and no prescribed ``speed`` profile in the analysis."""
        d = self.drive
        if d.profile != "motor":
            return [Issue(("passing_torque",), "needs [model.drive] profile = \"motor\" (its torque is what is "
                                               f"scaled); this machine's drive is {d.profile!r}", True)]
        issues = []
        if getattr(analysis, "speed", None) is not None:
            issues.append(Issue(("speed",), "replaces the motor by a prescribed speed: leave it out with "
                                            "passing_torque = true", show_value=False))
        t0 = d.stall_torque if d.speeds is None else d.torques[0]
        if t0 is not None and not t0 > 0:
            key = "stall_torque" if d.speeds is None else "torques"
            issues.append(Issue(("passing_torque",), f"scales the motor's torque, whose value at rest ({key}) "
                                                     f"must then be > 0 N*m, got {t0:g} N*m", True))
        target = getattr(analysis, "passing_target_speed", None)
        if target is not None and not target < d.final_speed:
            issues.append(Issue(("passing_target_speed",), f"must be below the motor's no-load speed "
                                                           f"{d.final_speed:g} rad/s (no torque of its "
                                                           "characteristic runs faster)", target))
        return issues

    def describe(self) -> str:
        drive = self.drive.profile
        gap = ""
        if self.clearances:
            c = self.clearances[0]
            kind = "rigid" if c.stator is None else ("housing" if c.stator.mass > 0 else "elastic")
            gap = f"{c.gap * 1e3:.3g} mm clearance ({kind} stator), "
        return (f"machine: {self.structure.describe()}; {len(self.races)} race(s) with "
                f"{self.n_balls} ball(s), {len(self.unbalances)} unbalance(s), "
                f"{'gravity, ' if self.gravity else ''}{gap}drive {drive}")
