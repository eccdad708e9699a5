"""Parameter objects of the ``jeffcott_balls`` model: the rotor and one ball (or pendulum).

See :mod:`rotorlab.models._jeffcott_balls` for the model, its equations and conventions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["RotorParams", "BallParams"]


def _number(owner: str, name: str, value, unit: str, *, low: float, strict: bool) -> float:
    """Return ``value`` as float, or raise ValueError naming field, value and allowed range."""
    allowed = f"a finite number {'>' if strict else '>='} {low:g} ({unit})"
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be {allowed}, got {value!r}") from None
    if not math.isfinite(v) or v < low or (strict and v == low):
        raise ValueError(f"{owner}.{name} must be {allowed}, got {value!r}")
    return v


@dataclass(frozen=True, slots=True)
class RotorParams:
    """Disc on an elastic shaft (Jeffcott rotor).

    Parameters
    ----------
    disc_mass : float
        Mass M1 of the disc without balls (kg), > 0.
    eccentricity : float
        Distance e from the disc centre O1 (on the shaft) to the disc's mass centre (m), >= 0.
        The unbalance points along +x at t = 0 and turns with the rotor.
    stiffness : float
        Lateral stiffness c of the shaft at the disc (N/m), >= 0.
    damping : float
        External viscous damping d acting on the absolute velocity of O1 (N s/m), >= 0.

    Examples
    --------
    >>> RotorParams(disc_mass=1.0, eccentricity=1e-3, stiffness=1e4).damping
    0.0
    >>> RotorParams(disc_mass=-1.0, eccentricity=0.0, stiffness=1.0)
    Traceback (most recent call last):
    ...
    ValueError: RotorParams.disc_mass must be a finite number > 0 (kg), got -1.0
    """

    disc_mass: float
    eccentricity: float
    stiffness: float
    damping: float = 0.0

    def __post_init__(self) -> None:
        owner = "RotorParams"
        for name, unit, strict in (
            ("disc_mass", "kg", True),
            ("eccentricity", "m", False),
            ("stiffness", "N/m", False),
            ("damping", "N s/m", False),
        ):
            value = _number(owner, name, getattr(self, name), unit, low=0.0, strict=strict)
            object.__setattr__(self, name, value)

    @property
    def imbalance(self) -> float:
        """Static unbalance M1 e (kg m)."""
        return self.disc_mass * self.eccentricity


@dataclass(frozen=True, slots=True)
class BallParams:
    """One ball running in a race, or one pendulum pivoted on the shaft axis.

    Parameters
    ----------
    mass : float
        Mass m_i (kg), > 0.
    radius : float
        Distance l_i from the shaft axis O1 to the ball's (pendulum's) mass centre (m), > 0.
    inertia : float or None
        Moment of inertia J_i about the shaft axis O1 (kg m^2), >= m_i l_i^2; ``None`` means
        m_i l_i^2 (point mass). Following Filimonikhin & Filimonikhina this is the axial moment
        of inertia of the corrective mass *about the shaft axis*: a pendulum's J_O, or for a ball
        of own central inertia J_c, J_i = m_i l_i^2 + J_c (see the model's Notes for rolling).
    damping : float
        Viscous damping b_i of the motion relative to the rotor: torque -b_i (phi_i' - theta')
        on the ball (N m s/rad), >= 0.
    friction : float
        Coulomb friction coefficient f_i (1), >= 0: the race holds the ball up to a torque
        f_i N_i l_i (N_i: normal force); > 0 switches the model to stick-slip.

    Examples
    --------
    >>> BallParams(mass=0.1, radius=0.05).inertia
    0.00025000000000000006
    >>> BallParams(mass=0.1, radius=0.05, inertia=1e-4)
    Traceback (most recent call last):
    ...
    ValueError: BallParams.inertia must be >= mass * radius**2 = 0.00025 (kg m^2), got 0.0001
    """

    mass: float
    radius: float
    inertia: float | None = None
    damping: float = 0.0
    friction: float = 0.0

    def __post_init__(self) -> None:
        owner = "BallParams"
        m = _number(owner, "mass", self.mass, "kg", low=0.0, strict=True)
        l = _number(owner, "radius", self.radius, "m", low=0.0, strict=True)
        point = m * l * l
        if self.inertia is None:
            inertia = point
        else:
            inertia = _number(owner, "inertia", self.inertia, "kg m^2", low=0.0, strict=True)
            if inertia < point * (1.0 - 1e-12):
                raise ValueError(
                    f"{owner}.inertia must be >= mass * radius**2 = {point:g} (kg m^2), "
                    f"got {self.inertia!r}"
                )
        object.__setattr__(self, "mass", m)
        object.__setattr__(self, "radius", l)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(
            self, "damping", _number(owner, "damping", self.damping, "N m s/rad", low=0.0, strict=False)
        )
        object.__setattr__(
            self, "friction", _number(owner, "friction", self.friction, "1", low=0.0, strict=False)
        )

    @property
    def static_moment(self) -> float:
        """Balancing capacity m_i l_i of this ball (kg m)."""
        return self.mass * self.radius
