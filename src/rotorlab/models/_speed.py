"""Prescribed spin-speed profiles of a rotor: constant, linear ramp, Hill run-up.

Each profile is a frozen dataclass that packs itself into the 6-entry block read by the compiled
kernel :func:`rotorlab._kernels.speed.profile` (layout documented there) and evaluates the spin
angle, speed and acceleration at given times. Nothing compiles at import; the first evaluation
compiles (and caches) the kernel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

__all__ = [
    "ConstantSpeed",
    "LinearRamp",
    "HillRunUp",
    "SpeedProfile",
    "speed_from_array",
]


def _finite(owner: str, name: str, value: float, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be a real number ({unit}), got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{owner}.{name} must be finite ({unit}), got {value!r}")
    return v


def _positive(owner: str, name: str, value: float, unit: str) -> float:
    v = _finite(owner, name, value, unit)
    if v <= 0.0:
        raise ValueError(f"{owner}.{name} must be > 0 ({unit}), got {value!r}")
    return v


class _ProfileMixin:
    """Evaluation helpers shared by the profiles (they only need ``to_array``)."""

    __slots__ = ()

    def rotating_refusal(self) -> str | None:
        """Why a machine driven by this profile has no co-rotating equilibria (a constant speed
        has them: None)."""
        return None if isinstance(self, ConstantSpeed) else (
            "the spin speed is not constant (steady motions need a ConstantSpeed drive)")

    def _evaluate(self, t) -> np.ndarray:
        from rotorlab._kernels.speed import evaluate

        ts = np.asarray(t, dtype=float)
        flat = np.ascontiguousarray(ts.ravel())
        out = np.empty((flat.size, 3))
        evaluate(flat, self.to_array(), 0, out)
        return out.reshape(ts.shape + (3,))

    def spin_angle(self, t):
        """Return the spin angle theta(t) (rad), theta(0) = 0.

        Parameters
        ----------
        t : float or array_like
            Time (s).

        Returns
        -------
        float or ndarray
            Same shape as ``t``.
        """
        return self._evaluate(t)[..., 0]

    def spin_speed(self, t):
        """Return the spin speed omega(t) = d theta / dt (rad/s); ``t`` in s, any shape."""
        return self._evaluate(t)[..., 1]

    def spin_acceleration(self, t):
        """Return the spin acceleration d omega / dt (rad/s^2); ``t`` in s, any shape."""
        return self._evaluate(t)[..., 2]

    def revolution_times(self, t0: float, t1: float) -> np.ndarray:
        """Return the times in (t0, t1] at which the rotor has turned a whole number of times.

        Parameters
        ----------
        t0, t1 : float
            Time span (s).

        Returns
        -------
        ndarray
            Times ``t_k`` with ``|theta(t_k) - theta(t0)| = 2 pi k``, k = 1, 2, ... (s).

        Raises
        ------
        ValueError
            If the speed changes sign within the span (the angle is then not monotonic).
        """
        grid = np.linspace(t0, t1, 257)
        th = self.spin_angle(grid)
        dth = np.diff(th)
        if np.any(dth > 0) and np.any(dth < 0):
            raise ValueError("revolution_times needs a spin speed of one sign over the span")
        sign = -1.0 if np.sum(dth) < 0 else 1.0
        total = sign * (th[-1] - th[0])
        n_rev = int(math.floor(total / (2.0 * math.pi) * (1.0 + 1e-15)))
        if n_rev < 1:
            return np.empty(0)
        targets = th[0] + sign * 2.0 * math.pi * np.arange(1, n_rev + 1)
        idx = np.searchsorted(sign * th, sign * targets)  # bracket each target on the grid
        lo = grid[np.clip(idx - 1, 0, grid.size - 1)]
        hi = grid[np.clip(idx, 0, grid.size - 1)]
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            above = sign * (self.spin_angle(mid) - targets) >= 0.0
            hi = np.where(above, mid, hi)
            lo = np.where(above, lo, mid)
            if np.all(hi - lo <= 4.0 * np.spacing(np.maximum(np.abs(hi), 1.0))):
                break
        return hi


@dataclass(frozen=True, slots=True)
class ConstantSpeed(_ProfileMixin):
    """Spin at a constant speed: theta(t) = omega t.

    Parameters
    ----------
    speed : float
        Spin speed omega (rad/s); counter-clockwise positive.
    """

    speed: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", _finite("ConstantSpeed", "speed", self.speed, "rad/s"))

    def to_array(self) -> np.ndarray:
        """Return the packed 6-entry block ``[0, omega, 0, 0, 0, 0]``."""
        return np.array([0.0, self.speed, 0.0, 0.0, 0.0, 0.0])


@dataclass(frozen=True, slots=True)
class LinearRamp(_ProfileMixin):
    """Change the speed linearly from ``start`` to ``stop`` in ``duration``, then hold ``stop``.

    Parameters
    ----------
    start : float
        Speed at t <= 0 (rad/s).
    stop : float
        Speed at t >= duration (rad/s).
    duration : float
        Length of the ramp (s), > 0.

    Notes
    -----
    For 0 <= t < T: omega = w0 + (w1 - w0) t / T and theta = w0 t + (w1 - w0) t^2 / (2 T);
    afterwards theta = (w0 + w1) T / 2 + w1 (t - T).
    """

    start: float
    stop: float
    duration: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _finite("LinearRamp", "start", self.start, "rad/s"))
        object.__setattr__(self, "stop", _finite("LinearRamp", "stop", self.stop, "rad/s"))
        object.__setattr__(
            self, "duration", _positive("LinearRamp", "duration", self.duration, "s")
        )

    def to_array(self) -> np.ndarray:
        """Return the packed 6-entry block ``[1, start, stop, duration, 0, 0]``."""
        return np.array([1.0, self.start, self.stop, self.duration, 0.0, 0.0])


@dataclass(frozen=True, slots=True)
class HillRunUp(_ProfileMixin):
    """Run up along the Hill curve omega(t) = omega_max t^n / (t_half^n + t^n).

    Parameters
    ----------
    max_speed : float
        Final speed omega_max (rad/s).
    t_half : float
        Time at which half the final speed is reached (s), > 0.
    exponent : float
        Hill exponent n (1), 0.01 <= n <= 1000. For n < 1 the acceleration is unbounded at t = 0
        (start the integration at t > 0).

    Notes
    -----
    theta(t) = omega_max (t - t_half F(t / t_half)) with F(z) = int_0^z du / (1 + u^n); the
    kernel evaluates the equivalent ``omega_max t_half G(t / t_half)``,
    ``G(z) = int_0^z u^n / (1 + u^n) du``, to about 1e-15 relative (see
    :mod:`rotorlab._kernels.speed`). For n > 1, F(inf) = (pi / n) / sin(pi / n).
    """

    max_speed: float
    t_half: float
    exponent: float

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "max_speed", _finite("HillRunUp", "max_speed", self.max_speed, "rad/s")
        )
        object.__setattr__(self, "t_half", _positive("HillRunUp", "t_half", self.t_half, "s"))
        n = _positive("HillRunUp", "exponent", self.exponent, "1")
        if not 0.01 <= n <= 1000.0:
            raise ValueError(
                f"HillRunUp.exponent must be in [0.01, 1000] (1), got {self.exponent!r}; "
                "outside that range the profile is numerically a step or a constant"
            )
        object.__setattr__(self, "exponent", n)

    def to_array(self) -> np.ndarray:
        """Return ``[2, omega_max, t_half, n, G(2^(-1/n)), G(2^(1/n))]`` (last two derived)."""
        from rotorlab._kernels.speed import hill_integrals

        n = self.exponent
        g_a = hill_integrals(2.0 ** (-1.0 / n), n)[1]
        g_b = hill_integrals(2.0 ** (1.0 / n), n)[1]
        return np.array([2.0, self.max_speed, self.t_half, n, g_a, g_b])

    def integrals(self, z):
        """Return ``(F(z), G(z))``, the integrals of 1/(1+u^n) and u^n/(1+u^n) over [0, z].

        Parameters
        ----------
        z : float or array_like
            Upper limit (1), >= 0.

        Returns
        -------
        F, G : ndarray
            Same shape as ``z``.
        """
        from rotorlab._kernels.speed import hill_integrals

        zs = np.asarray(z, dtype=float)
        f = np.empty(zs.shape)
        g = np.empty(zs.shape)
        for idx, zi in np.ndenumerate(zs):
            f[idx], g[idx] = hill_integrals(float(zi), self.exponent)
        return f, g


SpeedProfile = Union[ConstantSpeed, LinearRamp, HillRunUp]


def speed_from_array(block) -> SpeedProfile:
    """Rebuild a speed profile from its packed 6-entry block (inverse of ``to_array``).

    Parameters
    ----------
    block : array_like, shape (6,)

    Returns
    -------
    ConstantSpeed or LinearRamp or HillRunUp

    Raises
    ------
    ValueError
        If the kind code ``block[0]`` is not 0, 1 or 2.
    """
    b = np.asarray(block, dtype=float)
    if b.shape != (6,):
        raise ValueError(f"a speed block has 6 entries, got shape {b.shape}")
    kind = b[0]
    if kind == 0.0:
        return ConstantSpeed(b[1])
    if kind == 1.0:
        return LinearRamp(b[1], b[2], b[3])
    if kind == 2.0:
        return HillRunUp(b[1], b[2], b[3])
    raise ValueError(f"unknown speed-profile kind {kind!r} (0 constant, 1 ramp, 2 Hill)")
