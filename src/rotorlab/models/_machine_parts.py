"""Attachments of the composed machine model: balls and races, unbalances, gravity, a motor, a
clearance (rotor-stator contact).

See :mod:`rotorlab.models._machine` for the model and its equations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from rotorlab.linear._unbalance import Unbalance  # the one unbalance type, static and couple
from rotorlab.models._parameters import _FREE, _GE0, _GT0  # bounds (gt, ge, lt, le) of named parameters

__all__ = ["Ball", "BallRace", "Unbalance", "Gravity", "Motor", "Clearance", "ElasticStator"]


def _num(owner: str, name: str, value, unit: str, *, low: float | None = 0.0,
         strict: bool = False) -> float:
    """Return ``value`` as a finite float, or raise ValueError naming field, value and range."""
    if low is None:
        allowed = f"a finite number ({unit})"
    else:
        allowed = f"a finite number {'>' if strict else '>='} {low:g} ({unit})"
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be {allowed}, got {value!r}") from None
    if not math.isfinite(v) or (low is not None and (v < low or (strict and v == low))):
        raise ValueError(f"{owner}.{name} must be {allowed}, got {value!r}")
    return v


def _node(owner: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise ValueError(f"{owner}.node must be an integer >= 0, got {value!r}")
    return int(value)


@dataclass(frozen=True, slots=True)
class Ball:
    """One ball (or pendulum) of an automatic balancer.

    Parameters
    ----------
    mass : float
        m (kg), > 0.
    inertia : float
        Own moment of inertia about its centre, about an axis parallel to the shaft (kg m^2),
        >= 0; the ball's inertia about the shaft axis is ``m l^2 + inertia`` (l: race radius).
    damping : float
        Viscous damping c of its motion relative to the rotor: torque ``-c (phi' - Omega)``
        (N m s/rad), >= 0.
    coulomb : float
        Coulomb friction coefficient (1), >= 0. With ``rolling`` it bounds the race's torque on
        the ball by ``(coulomb l + rolling) N`` (N: the normal force of the race, l: its radius),
        with stick-slip as in ``jeffcott_balls`` (whose ``friction`` f is ``coulomb`` here).
    rolling : float
        Rolling-friction arm (m), >= 0 (see ``coulomb``).
    """

    #: Named parameters (field, unit, bounds (gt, ge, lt, le)): ``races[i].balls[j].<field>``
    fields: ClassVar[tuple] = (("mass", "kg", _GT0), ("inertia", "kg*m^2", _GE0),
                               ("damping", "N*m*s/rad", _GE0), ("coulomb", "1", _GE0),
                               ("rolling", "m", _GE0))

    mass: float
    inertia: float = 0.0
    damping: float = 0.0
    coulomb: float = 0.0
    rolling: float = 0.0

    def rotating_refusal(self) -> str | None:
        """Why the co-rotating frame has no equilibria with this ball, None if it has."""
        if self.coulomb > 0 or self.rolling > 0:
            return ("the balls have Coulomb or rolling friction (stick-slip): steady motions are "
                    "not equilibria of a smooth system; simulate instead")
        return None

    def __post_init__(self) -> None:
        o = "Ball"
        object.__setattr__(self, "mass", _num(o, "mass", self.mass, "kg", strict=True))
        for name, unit in (("inertia", "kg m^2"), ("damping", "N m s/rad"), ("coulomb", "1"),
                           ("rolling", "m")):
            object.__setattr__(self, name, _num(o, name, getattr(self, name), unit))


@dataclass(frozen=True, slots=True)
class BallRace:
    """A race (or a set of pendulums) at a station of the structure.

    Parameters
    ----------
    node : int
        Node of the structure that carries the race.
    radius : float
        l, distance of the balls' centres from the shaft axis (m), > 0.
    balls : tuple of Ball
        The balls in this race (at least one).
    axial_offset : float
        Axial distance a of the race plane from the node along +z (m): the race centre moves by
        ``(x + a phi_x, y + a phi_y)``, so an offset race couples to the tilt.
    """

    #: Named parameters of its own: ``races[i].<field>`` (its balls' are theirs)
    fields: ClassVar[tuple] = (("radius", "m", _GT0), ("axial_offset", "m", _FREE))

    node: int
    radius: float
    balls: tuple[Ball, ...] = ()
    axial_offset: float = 0.0

    def __post_init__(self) -> None:
        o = "BallRace"
        object.__setattr__(self, "node", _node(o, self.node))
        object.__setattr__(self, "radius", _num(o, "radius", self.radius, "m", strict=True))
        object.__setattr__(self, "axial_offset",
                           _num(o, "axial_offset", self.axial_offset, "m", low=None))
        balls = tuple(self.balls)
        if not balls:
            raise ValueError("BallRace.balls must hold at least one Ball, got none")
        for i, b in enumerate(balls):
            if not isinstance(b, Ball):
                raise ValueError(f"BallRace.balls[{i}] must be a Ball, got {type(b).__name__}")
        object.__setattr__(self, "balls", balls)

    @property
    def capacity(self) -> float:
        """Balancing capacity ``sum m l`` (kg m)."""
        return sum(b.mass for b in self.balls) * self.radius


@dataclass(frozen=True, slots=True)
class Gravity:
    """Gravity: the acceleration vector ``(g_x, g_y, g_z)`` in the fixed frame (m/s^2).

    z is the shaft axis: a vertical machine has ``(0, 0, -9.81)`` (no lateral load), a
    horizontal one e.g. ``(0, -9.81, 0)``. Only the lateral components act in the model.
    """

    vector: tuple[float, float, float] = (0.0, 0.0, -9.81)

    def __post_init__(self) -> None:
        v = tuple(self.vector)
        if len(v) != 3:
            raise ValueError(f"Gravity.vector must have 3 components (m/s^2), got {self.vector!r}")
        object.__setattr__(self, "vector",
                           tuple(_num("Gravity", f"vector[{i}]", x, "m/s^2", low=None)
                                 for i, x in enumerate(v)))

    @property
    def lateral(self) -> tuple[float, float]:
        """``(g_x, g_y)`` (m/s^2)."""
        return self.vector[0], self.vector[1]

    def rotating_refusal(self) -> str | None:
        """Why the co-rotating frame has no equilibria under this gravity, None if it has."""
        if self.lateral == (0.0, 0.0):
            return None
        return ("gravity acts across the axis: the balls are pulled down once per "
                "revolution, so there is no steady motion; simulate instead")


@dataclass(frozen=True, slots=True)
class Motor:
    """A motor with a torque characteristic; spin angle and speed become states.

    Parameters
    ----------
    torque : float or (array_like, array_like)
        Either the stall torque T_s (N m) of the linear characteristic
        ``T = T_s (1 - Omega / Omega_0)``, or a table ``(speeds, torques)`` (rad/s, N m) with
        increasing speeds, interpolated linearly and held constant outside.
    polar_inertia : float
        Polar moment of inertia of everything that spins with the rotor (rotor, armature,
        coupling, the unbalance's ``m e^2``; the balls are separate states) (kg m^2), > 0.
    no_load_speed : float
        Omega_0 of the linear characteristic (rad/s), > 0; unused with a table.
    """

    torque: object
    polar_inertia: float
    no_load_speed: float = math.inf

    def __post_init__(self) -> None:
        o = "Motor"
        object.__setattr__(self, "polar_inertia",
                           _num(o, "polar_inertia", self.polar_inertia, "kg m^2", strict=True))
        if isinstance(self.torque, (tuple, list)) and len(self.torque) == 2 and np.ndim(self.torque[0]) == 1:
            w = np.asarray(self.torque[0], dtype=float)
            tq = np.asarray(self.torque[1], dtype=float)
            if w.shape != tq.shape or w.size < 2 or not np.all(np.isfinite(w)) \
                    or not np.all(np.isfinite(tq)) or np.any(np.diff(w) <= 0):
                raise ValueError("Motor.torque table must be two finite arrays of equal length "
                                 ">= 2 with strictly increasing speeds (rad/s, N m), got "
                                 f"{self.torque!r}")
            object.__setattr__(self, "torque", (tuple(w.tolist()), tuple(tq.tolist())))
        else:
            object.__setattr__(self, "torque", _num(o, "torque", self.torque, "N m", low=None))
            if not (self.no_load_speed > 0 and math.isfinite(self.no_load_speed)):
                raise ValueError("Motor.no_load_speed must be a finite number > 0 (rad/s) for a "
                                 f"linear characteristic, got {self.no_load_speed!r}")
        object.__setattr__(self, "no_load_speed", float(self.no_load_speed))

    def rotating_refusal(self) -> str:
        """A motor's speed follows its torque balance: no co-rotating equilibria."""
        return "the spin speed is not constant (steady motions need a ConstantSpeed drive)"

    @property
    def kind(self) -> str:
        """``"linear"`` or ``"table"``."""
        return "table" if isinstance(self.torque, tuple) else "linear"

    @property
    def drive_kind(self) -> str:
        """The layout's drive kind (``rotorlab._kernels.machine_drive.DRIVES``): the characteristic's."""
        return self.kind

    def speed_block(self) -> np.ndarray:
        """The machine's speed block with this drive: unused (zeros); a commanded drive fills it."""
        return np.zeros(6)

    @property
    def n_table(self) -> int:
        return len(self.torque[0]) if self.kind == "table" else 0

    def torque_at(self, speed):
        """Return the torque T(Omega) (N m) at speeds ``speed`` (rad/s)."""
        w = np.asarray(speed, dtype=float)
        if self.kind == "linear":
            return self.torque * (1.0 - w / self.no_load_speed)
        return np.interp(w, self.torque[0], self.torque[1])

    @property
    def stall_torque(self) -> float:
        """The torque at rest T(0) (N m): T_s of the linear characteristic, the table's at 0."""
        return float(self.torque_at(0.0))

    def scaled(self, factor: float) -> Motor:
        """Return this motor with its torque characteristic times ``factor`` (> 0): T_s of the
        linear characteristic, every torque of a table; the speeds are kept."""
        f = float(factor)
        if not (f > 0 and math.isfinite(f)):
            raise ValueError(f"Motor.scaled: factor must be a finite number > 0, got {factor!r}")
        if self.kind == "linear":
            return Motor(self.torque * f, self.polar_inertia, self.no_load_speed)
        return Motor((self.torque[0], tuple(f * t for t in self.torque[1])), self.polar_inertia,
                     self.no_load_speed)

    def to_array(self) -> np.ndarray:
        """``[J, T_s, Omega_0, speeds..., torques...]`` (see the kernel layout)."""
        if self.kind == "linear":
            return np.array([self.polar_inertia, self.torque, self.no_load_speed])
        return np.concatenate([[self.polar_inertia, 0.0, 0.0], self.torque[0], self.torque[1]])


@dataclass(frozen=True, slots=True)
class ElasticStator:
    """A stator that yields: radial stiffness and damping, and optionally a mass of its own.

    Parameters
    ----------
    stiffness : float
        k_s (N/m), > 0. Massless stator: the contact stiffness, ``N = max(0, k_s p + c_s p')``
        with the penetration ``p = |w| - delta``. With a mass: the stiffness of the housing's
        mounting to the ground, isotropic; the rotor then strikes the housing rigidly.
    damping : float
        c_s (N s/m), >= 0, in the contact (massless) or in the mounting (with a mass).
    mass : float
        m_s (kg), >= 0: 0 is a massless stator; > 0 a moving housing (four states: its lateral
        position and velocity).
    """

    #: Named parameters: ``clearances[i].stator.<field>``; a housing mass from or to 0 changes
    #: the compiled layout (housing states)
    fields: ClassVar[tuple] = (("stiffness", "N/m", _GT0), ("damping", "N*s/m", _GE0), ("mass", "kg", _GE0))

    stiffness: float
    damping: float = 0.0
    mass: float = 0.0

    def __post_init__(self) -> None:
        o = "ElasticStator"
        object.__setattr__(self, "stiffness", _num(o, "stiffness", self.stiffness, "N/m", strict=True))
        object.__setattr__(self, "damping", _num(o, "damping", self.damping, "N s/m"))
        object.__setattr__(self, "mass", _num(o, "mass", self.mass, "kg"))


CLEARANCE_KINDS = ("rigid", "elastic", "housing")
#: the generated kernel's contact form of each stator kind (:attr:`Clearance.kernel_kind`)
KERNEL_CLEARANCE = {"rigid": "massless", "elastic": "massless", "housing": "housing"}


@dataclass(frozen=True, slots=True)
class Clearance:
    """A clearance between the rotor and a stator at one station (rotor-stator contact).

    The *gap vector* is ``w = B z`` (minus the housing's position with a moving housing): the
    lateral displacement ``(x + a phi_x, y + a phi_y)`` of the station (a: ``axial_offset``) or,
    for a conical gap (seed 001), ``w = sin(beta) (x, y) + l_P (phi_x, phi_y)``; contact when
    ``|w| >= gap``. The contact law (:mod:`rotorlab._kernels.contact`): located impacts with
    Newton restitution and a Coulomb impulse (stick within the friction cone, slip otherwise,
    the rotor's surface speed ``R_r Omega`` in the slip), chatter turned into sustained contact,
    sustained sliding (full rub) or rolling (backward whirl) contact, lift-off.

    Parameters
    ----------
    node : int
        Node (station) of the structure.
    gap : float
        delta, radial clearance (m), > 0.
    stator : "rigid" or ElasticStator
        A rigid stator (impacts), a massless elastic one (penalty contact, no impulses), or a
        housing with mass on an elastic mounting (impacts on the moving housing).
    restitution : float
        e, Newton's restitution coefficient in [0, 1] (impacts only).
    friction : float
        mu, Coulomb friction coefficient (1), >= 0.
    rotor_radius : float
        R_r, radius of the rotor's surface at the contact (m), >= 0.
    axial_offset : float
        Axial distance of the contact plane from the node (m).
    conical : (float, float), optional
        ``(beta, l_P)``: half angle of a conical gap (rad, in (0, pi/2]) and lever of the tilt
        (m); replaces ``axial_offset``.
    rest_speed : float
        Rebound speed (m/s), > 0, below which a pressed rotor's impacts count as accumulated
        (chatter): one plastic impulse, then sustained contact (see :class:`rotorlab.contact.JeffcottRub`).
    center : (float, float) or "static"
        Centre of the stator's circle in the fixed frame (m), the gap vector being measured from
        it; ``"static"``: where the station rests under gravity (the housing built around the
        sagging rotor), see :meth:`rotorlab.models.Machine.clearance_center`.
    stabilisation : float, optional
        Rate ``a`` (1/s) of the Baumgarte stabilisation of a rigid sustained contact
        (:mod:`rotorlab._kernels.machine_contact`); None: the structure's highest natural
        frequency; 0: none (the rub rotor's law, :attr:`rotorlab.contact.JeffcottRub.machine`).
    """

    #: Named parameters of its own numbers: ``clearances[i].<field>`` (its stator's, cone's and
    #: centre's: see :func:`rotorlab.models._parameters.machine_slots`)
    fields: ClassVar[tuple] = (("gap", "m", _GT0), ("restitution", "1", (None, 0.0, None, 1.0)),
                               ("friction", "1", _GE0), ("rotor_radius", "m", _GE0),
                               ("axial_offset", "m", _FREE), ("rest_speed", "m/s", _GT0))

    node: int
    gap: float
    stator: object = "rigid"
    restitution: float = 0.5
    friction: float = 0.0
    rotor_radius: float = 0.0
    axial_offset: float = 0.0
    conical: tuple[float, float] | None = None
    rest_speed: float = 1e-5
    center: tuple[float, float] | str = (0.0, 0.0)
    stabilisation: float | None = None

    def __post_init__(self) -> None:
        o = "Clearance"
        if self.stabilisation is not None:
            object.__setattr__(self, "stabilisation", _num(o, "stabilisation", self.stabilisation, "1/s"))
        if isinstance(self.center, str):
            if self.center != "static":
                raise ValueError(f'{o}.center must be (x, y) (m) or "static", got {self.center!r}')
        else:
            c = tuple(self.center)
            if len(c) != 2:
                raise ValueError(f'{o}.center must be (x, y) (m) or "static", got {self.center!r}')
            object.__setattr__(self, "center", tuple(_num(o, f"center[{i}]", v, "m", low=None)
                                                     for i, v in enumerate(c)))
        object.__setattr__(self, "node", _node(o, self.node))
        object.__setattr__(self, "gap", _num(o, "gap", self.gap, "m", strict=True))
        if not (self.stator == "rigid" or isinstance(self.stator, ElasticStator)):
            raise ValueError(f"{o}.stator must be 'rigid' or an ElasticStator, got {self.stator!r}")
        e = _num(o, "restitution", self.restitution, "1")
        if e > 1.0:
            raise ValueError(f"{o}.restitution must be in [0, 1], got {self.restitution!r}")
        object.__setattr__(self, "restitution", e)
        object.__setattr__(self, "friction", _num(o, "friction", self.friction, "1"))
        object.__setattr__(self, "rotor_radius", _num(o, "rotor_radius", self.rotor_radius, "m"))
        object.__setattr__(self, "axial_offset", _num(o, "axial_offset", self.axial_offset, "m", low=None))
        object.__setattr__(self, "rest_speed", _num(o, "rest_speed", self.rest_speed, "m/s", strict=True))
        if self.conical is not None:
            c = tuple(self.conical)
            if len(c) != 2:
                raise ValueError(f"{o}.conical must be (half_angle, lever), got {self.conical!r}")
            beta = _num(o, "conical[0]", c[0], "rad", strict=True)
            if beta > math.pi / 2:
                raise ValueError(f"{o}.conical[0] must be in (0, pi/2] (rad), got {c[0]!r}")
            object.__setattr__(self, "conical", (beta, _num(o, "conical[1]", c[1], "m", low=None)))

    @property
    def kind(self) -> str:
        """``"rigid"``, ``"elastic"`` (massless) or ``"housing"`` (with mass)."""
        if self.stator == "rigid":
            return "rigid"
        return "housing" if self.stator.mass > 0.0 else "elastic"

    @property
    def kernel_kind(self) -> str:
        """The form of the generated kernel's contact code (:data:`KERNEL_CLEARANCE` of
        :attr:`kind`): a stator with mass has states of its own, ``"housing"``; a rigid and a
        massless elastic stator share one, ``"massless"`` (their numbers are run-time data)."""
        return KERNEL_CLEARANCE[self.kind]

    def to_array(self) -> np.ndarray:
        """``[delta, e, mu, R_r, v_rest, k_s, c_s, m_s]`` (SI; zeros for a rigid stator)."""
        s = self.stator
        ks, cs, ms = (0.0, 0.0, 0.0) if s == "rigid" else (s.stiffness, s.damping, s.mass)
        return np.array([self.gap, self.restitution, self.friction, self.rotor_radius,
                         self.rest_speed, ks, cs, ms])
