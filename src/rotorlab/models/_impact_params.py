"""Parameters of the centrifuge rotor of seed 001 and of the housing it strikes (SI); the model
that combines them with the stones is :class:`rotorlab.models.ImpactRotor`."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rotorlab.models._checks import check_number as _num

__all__ = ["CentrifugeRotor", "Housing"]


@dataclass(frozen=True, slots=True)
class CentrifugeRotor:
    """The rigid rotor and its two membranes.

    Parameters
    ----------
    mass : float
        m, mass of the rotor (kg), > 0.
    inertia_transverse : float
        A1 = A2, central moment of inertia about a transverse axis (kg m^2), > 0.
    inertia_polar : float
        A3, moment of inertia about the axis of symmetry (kg m^2), > 0.
    spin_speed : float
        omega0, constant spin speed (rad/s), > 0.
    stiffness_1, stiffness_2 : float
        c1, c2, lateral stiffness of the two membranes (N/m), > 0.
    height_1, height_2 : float
        h1, h2, heights of the membranes above the centre of mass (m), distinct.
    internal_friction : float
        gamma, Sorokin's dimensionless coefficient of internal friction of the membranes, >= 0.
    translational : bool
        Freeze the tilt (the paper's "translational motion of the axis").

    Examples
    --------
    >>> r = CentrifugeRotor(635.7, 70.35, 115.68, 160.0, 3.22e6, 3.22e6, -0.05, 0.2, 0.2)
    >>> round(r.stiffness, 0), round(r.membrane_offset, 4), round(r.tilt_stiffness, 1)
    (6440000.0, 0.075, 100625.0)
    >>> CentrifugeRotor(635.7, 70.35, 115.68, -1.0, 3.22e6, 3.22e6, -0.05, 0.2, 0.2)
    Traceback (most recent call last):
    ...
    ValueError: CentrifugeRotor.spin_speed must be a finite number > 0 (rad/s), got -1.0
    """

    mass: float
    inertia_transverse: float
    inertia_polar: float
    spin_speed: float
    stiffness_1: float
    stiffness_2: float
    height_1: float
    height_2: float
    internal_friction: float = 0.2
    translational: bool = False

    def __post_init__(self) -> None:
        o = "CentrifugeRotor"
        for name, unit in (("mass", "kg"), ("inertia_transverse", "kg m^2"),
                           ("inertia_polar", "kg m^2"), ("spin_speed", "rad/s"),
                           ("stiffness_1", "N/m"), ("stiffness_2", "N/m")):  # fmt: skip
            object.__setattr__(self, name, _num(o, name, getattr(self, name), unit=unit))
        for name in ("height_1", "height_2"):
            object.__setattr__(self, name, _num(o, name, getattr(self, name), lo=None, unit="m"))
        object.__setattr__(
            self, "internal_friction", _num(o, "internal_friction", self.internal_friction, lo_open=False)
        )
        if self.height_1 == self.height_2:
            raise ValueError(f"{o}.height_2 must differ from height_1 ({self.height_1:g} m), got {self.height_2!r}")
        if not isinstance(self.translational, bool):
            raise ValueError(f"{o}.translational must be True or False, got {self.translational!r}")

    @property
    def stiffness(self) -> float:
        """c = c1 + c2 (N/m)."""
        return self.stiffness_1 + self.stiffness_2

    @property
    def membrane_offset(self) -> float:
        """n_m = (c1 h1 + c2 h2) / c (m)."""
        return (self.stiffness_1 * self.height_1 + self.stiffness_2 * self.height_2) / self.stiffness

    @property
    def tilt_stiffness(self) -> float:
        """c_* = c1 c2 (h1 - h2)^2 / c (N m/rad)."""
        return self.stiffness_1 * self.stiffness_2 * (self.height_1 - self.height_2) ** 2 / self.stiffness


@dataclass(frozen=True, slots=True)
class Housing:
    """The conical housing, the gap point P and the impact laws.

    Parameters
    ----------
    radius : float
        r_P, radius of the circle of P (m), > 0.
    height : float
        h_P, height of P above the centre of mass (m).
    gap : float
        Delta, gap along the cone normal (m), > 0.
    cone_angle : float
        beta, angle of the cone normal ``n = sin(beta) e_r - cos(beta) k`` (rad), in (0, pi/2];
        pi/2 is a cylinder.
    restitution : float
        k, Newton's coefficient of restitution, in [0, 1].
    friction : float
        f, Coulomb friction coefficient between rotor and housing, >= 0.
    rest_speed : float
        Rebound speed (m/s) below which a run of impacts is taken as accumulated and the rotor
        slides on the housing; default 1e-4 m/s. Must be < count_speed when that is > 0.
    count_speed : float
        Approach speed (m/s) from which an impact is counted, >= 0; default 0: every located
        impact counts, the chatter before a sliding contact included (issue 30; a positive
        value leaves slow chatter out of the count, e.g. 1e-3 m/s, the former default).
    whirl_limit : float or None
        Backward angular speed (rad/s) of the contact point in the fixed frame during sliding
        above which the run is stopped and flagged as dry-friction backward whirl; ``None``
        (default) takes the theory's criterion: the slip of P over the housing, which the
        sliding law assumes forwards, vanishes (P rolls; without tilt that is the whirl speed
        :meth:`rolling_whirl_speed`; see the module docstring of
        :mod:`rotorlab.models._impact_rotor`).

    Examples
    --------
    >>> import math
    >>> h = Housing(0.625, -0.2, 4.5e-3, math.radians(55), 0.5, 0.2)
    >>> round(h.lever(), 4)
    0.1947
    """

    radius: float
    height: float
    gap: float
    cone_angle: float
    restitution: float = 0.5
    friction: float = 0.2
    rest_speed: float = 1e-4
    count_speed: float = 0.0
    whirl_limit: float | None = None

    def __post_init__(self) -> None:
        o = "Housing"
        object.__setattr__(self, "radius", _num(o, "radius", self.radius, unit="m"))
        object.__setattr__(self, "height", _num(o, "height", self.height, lo=None, unit="m"))
        object.__setattr__(self, "gap", _num(o, "gap", self.gap, unit="m"))
        object.__setattr__(self, "cone_angle", _num(o, "cone_angle", self.cone_angle, hi=math.pi / 2, unit="rad"))
        object.__setattr__(self, "restitution", _num(o, "restitution", self.restitution, lo_open=False, hi=1.0))
        object.__setattr__(self, "friction", _num(o, "friction", self.friction, lo_open=False))
        object.__setattr__(self, "rest_speed", _num(o, "rest_speed", self.rest_speed, unit="m/s"))
        object.__setattr__(self, "count_speed", _num(o, "count_speed", self.count_speed, lo_open=False, unit="m/s"))
        if 0.0 < self.count_speed <= self.rest_speed:
            raise ValueError(
                f"Housing.rest_speed must be < count_speed ({self.count_speed:g} m/s), got {self.rest_speed!r}"
            )
        if self.whirl_limit is not None:
            object.__setattr__(self, "whirl_limit", _num(o, "whirl_limit", self.whirl_limit, unit="rad/s"))

    def rolling_whirl_speed(self, spin_speed: float) -> float:
        """Backward whirl speed (rad/s) at which the rotor rolls on the housing without slip.

        The contact point's lateral displacement whirls on a circle of radius ``Delta / sin(beta)``
        (its gap component ``w`` on ``|w| = Delta``); rolling without slip needs its speed to
        cancel the surface speed ``r_P omega0``: ``|omega_w| = r_P sin(beta) omega0 / Delta``,
        the dry-friction backward whirl ``-(R / delta) Omega`` of Black (1968) and Crandall (1990)
        on the cone (exact in the translational model, where ``w = sin(beta) u``; with tilt the
        run's stop is the slip of P itself, :func:`rotorlab._kernels.impact_rotor.whirl_stop`).

        Examples
        --------
        >>> import math
        >>> h = Housing(0.625, -0.2, 4.5e-3, math.radians(90), 0.5, 0.2)
        >>> round(h.rolling_whirl_speed(160.0), 6)
        22222.222222
        """
        return self.radius * math.sin(self.cone_angle) * float(spin_speed) / self.gap

    def lever(self) -> float:
        """l_P = r_P cos(beta) + h_P sin(beta) (m), eq. (3.2)."""
        return self.radius * math.cos(self.cone_angle) + self.height * math.sin(self.cone_angle)
