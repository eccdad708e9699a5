"""Small models with closed-form answers: they show how to write a model and test the integrator.

- :class:`HarmonicOscillator`: smooth, for convergence-order and accuracy checks.
- :class:`BouncingBall`: impacts with restitution whose accumulation (chatter) turns into
  sustained contact, and lift-off when the contact force would pull.
- :class:`FrictionBlock`: Coulomb (dry) friction as stick–slip, not as a smoothed sign.
- :class:`PlanarOscillator`: one smooth planar polynomial field (one compiled kernel) that is the
  Van der Pol oscillator, the Hopf (Stuart–Landau) and Bautin normal forms or the damped Mathieu
  equation, for the periodic-orbit checks of :mod:`rotorlab.continuation`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorlab._kernels import examples as _k
from rotorlab.models._base import EventSpec, Kernels

__all__ = ["HarmonicOscillator", "BouncingBall", "FrictionBlock", "PlanarOscillator"]

_OSC_KERNELS = Kernels(rhs=_k.oscillator_rhs, n_state=2)
_PLANAR_KERNELS = Kernels(rhs=_k.planar_rhs, n_state=2)
_BALL_KERNELS = Kernels(
    rhs=_k.ball_rhs,
    n_state=3,
    n_discrete=1,
    events=_k.ball_events,
    reset=_k.ball_reset,
    event_specs=(EventSpec("impact", -1, "reset"), EventSpec("lift_off", -1, "reset")),
)
_BLOCK_KERNELS = Kernels(
    rhs=_k.block_rhs,
    n_state=3,
    n_discrete=1,
    events=_k.block_events,
    reset=_k.block_reset,
    event_specs=(EventSpec("stop", -1, "reset"), EventSpec("break_away", -1, "reset")),
)


def _check_positive(name: str, value: float, allow_zero: bool = False) -> None:
    ok = math.isfinite(value) and (value >= 0 if allow_zero else value > 0)
    if not ok:
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be finite and {bound}, got {value!r}")


@dataclass(frozen=True, slots=True)
class HarmonicOscillator:
    """Undamped oscillator x'' = -omega^2 x.

    Parameters
    ----------
    frequency : float
        Angular frequency omega (rad/s).

    Notes
    -----
    State ``[x, v]`` (m, m/s); packed parameters ``[omega]``.
    """

    frequency: float = 1.0

    def __post_init__(self) -> None:
        _check_positive("frequency", self.frequency)

    @property
    def kernels(self) -> Kernels:
        return _OSC_KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("x", "v")

    def to_array(self) -> np.ndarray:
        return np.array([self.frequency])

    def exact(self, t: np.ndarray, y0: np.ndarray) -> np.ndarray:
        """Closed-form solution, shape (len(t), 2)."""
        w = self.frequency
        t = np.asarray(t, dtype=float)[:, None]
        x0, v0 = y0
        return np.hstack(
            [x0 * np.cos(w * t) + v0 / w * np.sin(w * t), -x0 * w * np.sin(w * t) + v0 * np.cos(w * t)]
        )


@dataclass(frozen=True, slots=True)
class BouncingBall:
    """A ball falling on a rigid floor: Newton restitution, chatter, sustained contact, lift-off.

    Parameters
    ----------
    gravity : float
        Downward acceleration a (m/s^2).
    restitution : float
        Newton's coefficient e in [0, 1): rebound speed = e * approach speed.
    rest_speed : float
        Rebound speed (m/s) below which the impacts are treated as accumulated: the ball is put
        in sustained contact (mode 1) instead of computing the remaining infinitely many,
        geometrically shrinking bounces. The time this skips is ``2 e v / (a (1 - e))`` for the
        last rebound speed v, so it is below ``2 rest_speed / (a (1 - e))``.
    push_amplitude, push_frequency : float
        Optional upward acceleration ``push_amplitude * sin(push_frequency * t)`` (m/s^2, rad/s)
        that can lift the ball off the floor again.

    Notes
    -----
    State ``[h, v, mode]``: height (m), upward velocity (m/s), mode 0 = flight, 1 = contact.
    Packed parameters ``[gravity, restitution, rest_speed, push_amplitude, push_frequency]``.
    Events: ``impact`` (h reaches 0 in flight) and ``lift_off`` (contact force per unit mass
    ``a - push`` reaches 0 in contact).

    After the first impact with speed v0 the bounce times form a geometric series that
    accumulates at ``T_inf = 2 e v0 / (a (1 - e))``; the ball then rests.
    """

    gravity: float = 9.81
    restitution: float = 0.8
    rest_speed: float = 1e-9
    push_amplitude: float = 0.0
    push_frequency: float = 0.0

    def __post_init__(self) -> None:
        _check_positive("gravity", self.gravity)
        if not 0.0 <= self.restitution < 1.0:
            raise ValueError(f"restitution must be in [0, 1), got {self.restitution!r}")
        _check_positive("rest_speed", self.rest_speed)
        _check_positive("push_amplitude", self.push_amplitude, allow_zero=True)
        _check_positive("push_frequency", self.push_frequency, allow_zero=True)

    @property
    def kernels(self) -> Kernels:
        return _BALL_KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("h", "v", "mode")

    def to_array(self) -> np.ndarray:
        return np.array(
            [self.gravity, self.restitution, self.rest_speed, self.push_amplitude, self.push_frequency]
        )

    def accumulation_time(self, impact_speed: float) -> float:
        """Time from the first impact (speed ``impact_speed``) to the accumulation point (s)."""
        e = self.restitution
        return 2.0 * e * impact_speed / (self.gravity * (1.0 - e))

    def impacts_until_rest(self, impact_speed: float) -> int:
        """Number of impacts until the rebound speed falls below ``rest_speed``."""
        e = self.restitution
        if e == 0.0:
            return 1
        k = 1
        v = e * impact_speed
        while v >= self.rest_speed:
            v *= e
            k += 1
        return k


@dataclass(frozen=True, slots=True)
class FrictionBlock:
    """A block on a rough floor with Coulomb friction, an optional spring and a harmonic push.

    Parameters
    ----------
    friction_accel : float
        mu * g, the friction force per unit mass (m/s^2); static and kinetic are equal.
    spring_rate : float
        k / m, the squared natural frequency of the spring (1/s^2), >= 0.
    push_amplitude, push_frequency : float
        External force per unit mass ``push_amplitude * sin(push_frequency * t)``.

    Notes
    -----
    State ``[x, v, mode]``: position (m), velocity (m/s), mode +1/-1 sliding in the positive /
    negative direction, 0 stuck. Packed parameters
    ``[friction_accel, spring_rate, push_amplitude, push_frequency]``.

    Sliding, ``v' = -k/m x + push - mu g sign(v)``; stuck, ``x' = v' = 0`` while
    ``|-k/m x + push| <= mu g``. Without spring and push a block launched at v0 stops at
    ``t = v0 / (mu g)`` after ``x = v0^2 / (2 mu g)`` and stays there.
    """

    friction_accel: float = 1.0
    spring_rate: float = 0.0
    push_amplitude: float = 0.0
    push_frequency: float = 0.0

    def __post_init__(self) -> None:
        _check_positive("friction_accel", self.friction_accel)
        _check_positive("spring_rate", self.spring_rate, allow_zero=True)
        _check_positive("push_amplitude", self.push_amplitude, allow_zero=True)
        _check_positive("push_frequency", self.push_frequency, allow_zero=True)

    @property
    def kernels(self) -> Kernels:
        return _BLOCK_KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("x", "v", "mode")

    def to_array(self) -> np.ndarray:
        return np.array(
            [self.friction_accel, self.spring_rate, self.push_amplitude, self.push_frequency]
        )

    def initial_state(self, x0: float, v0: float) -> np.ndarray:
        """State with the right sliding/stuck mode for position ``x0`` and velocity ``v0``."""
        if v0 != 0.0:
            mode = math.copysign(1.0, v0)
        else:
            drive = -self.spring_rate * x0
            mode = 0.0 if abs(drive) <= self.friction_accel else math.copysign(1.0, drive)
        return np.array([x0, v0, mode])


_PLANAR_FIELDS = ("a11", "a12", "a21", "a22", "c1", "c2", "c3", "c4", "q1", "q2", "q3", "q4", "d", "e", "w")


@dataclass(frozen=True, slots=True)
class PlanarOscillator:
    """A smooth planar field with linear, cubic, quintic, Van der Pol and parametric terms.

    With ``r2 = x^2 + y^2``::

        x' = a11 x + a12 y + (c1 x + c2 y) r2 + (q1 x + q2 y) r2^2
        y' = (a21 + e cos(w t)) x + a22 y + (c3 x + c4 y) r2 + (q3 x + q4 y) r2^2 + d x^2 y

    The constructors give the textbook cases: :meth:`van_der_pol`, :meth:`stuart_landau` (the
    Hopf normal form, and with a quintic term the Bautin normal form, whose orbits fold) and
    :meth:`mathieu` (a linear time-periodic system). All share one compiled kernel.

    Parameters
    ----------
    a11, a12, a21, a22, c1, c2, c3, c4, q1, q2, q3, q4, d, e, w : float
        The coefficients above (units of the state per second; ``w`` in rad/s).

    Notes
    -----
    State ``[x, y]``; packed parameters in the order of the fields.
    """

    a11: float = 0.0
    a12: float = 1.0
    a21: float = -1.0
    a22: float = 0.0
    c1: float = 0.0
    c2: float = 0.0
    c3: float = 0.0
    c4: float = 0.0
    q1: float = 0.0
    q2: float = 0.0
    q3: float = 0.0
    q4: float = 0.0
    d: float = 0.0
    e: float = 0.0
    w: float = 0.0

    def __post_init__(self) -> None:
        for name in _PLANAR_FIELDS:
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"PlanarOscillator.{name} must be finite, got {getattr(self, name)!r}")

    @classmethod
    def van_der_pol(cls, mu: float) -> PlanarOscillator:
        """``x'' - mu (1 - x^2) x' + x = 0`` as ``x' = y``, ``y' = -x + mu (1 - x^2) y``."""
        return cls(a22=mu, d=-mu)

    @classmethod
    def stuart_landau(cls, mu: float, omega: float = 1.0, cubic: float = -1.0, twist: float = 0.0,
                      quintic: float = 0.0) -> PlanarOscillator:
        """``z' = (mu + i omega) z + (cubic + i twist) |z|^2 z + quintic |z|^4 z``, ``z = x + i y``.

        With ``cubic < 0`` (supercritical Hopf at ``mu = 0``) the orbit has radius
        ``sqrt(-mu / cubic)``; with ``cubic > 0`` and ``quintic < 0`` (Bautin) the orbits of radius
        ``r^2 = (cubic + sqrt(cubic^2 + 4 mu |quintic|)) / (2 |quintic|)`` fold at
        ``mu = -cubic^2 / (4 |quintic|)``.
        """
        return cls(a11=mu, a12=-omega, a21=omega, a22=mu, c1=cubic, c2=-twist, c3=twist, c4=cubic,
                   q1=quintic, q4=quintic)

    @classmethod
    def mathieu(cls, delta: float, eps: float, damping: float = 0.0, frequency: float = 1.0) -> PlanarOscillator:
        """The damped Mathieu equation ``x'' + damping x' + (delta + eps cos(frequency t)) x = 0``."""
        return cls(a12=1.0, a21=-delta, a22=-damping, e=-eps, w=frequency)

    @property
    def kernels(self) -> Kernels:
        return _PLANAR_KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("x", "y")

    def to_array(self) -> np.ndarray:
        return np.array([getattr(self, name) for name in _PLANAR_FIELDS], dtype=float)
