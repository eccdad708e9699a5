"""Stones of the centrifuge of seed 001: the push of one stone on its guide (eq. (4.3), J(tau)) and
the stream of stones its accelerator throws (masses, times, guides; fixed or seeded random).

The reconstructions of the garbled (4.3) and J(tau) and how they are checked are documented in
:mod:`rotorlab.models._impact_rotor`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Literal

import numpy as np

from rotorlab.models._checks import check_number as _num

__all__ = ["StonePush", "stone_push", "StoneFeed", "StoneSequence"]


@dataclass(frozen=True, slots=True)
class StonePush:
    """The push of one stone on its guide, from eq. (4.3) (dimensionless, tau = omega0 t).

    Attributes
    ----------
    tau : ndarray, shape (n,)
        Uniform grid on [0, tau_end].
    jx, jy, djx, djy : ndarray, shape (n,)
        J(tau) in the guide's frame (the guide starts at angle 0) and its derivative.
    work : ndarray, shape (n,)
        Motor work on the stone up to tau, in units of m_q R_q^2 omega0^2.
    radius, angle : ndarray, shape (n,)
        Position of the stone: radius in units of R_q and polar angle in the guide's frame (rad).
    tau_end : float
        Time on the guide (rad of rotor turn).
    exit_speed : float
        Speed along the guide at the rim, in units of R_q omega0.
    friction_heat : float
        Heat of guide friction, in units of m_q R_q^2 omega0^2.
    kinetic_gain : float
        Kinetic energy gained in the fixed frame, same units.
    """

    tau: np.ndarray
    jx: np.ndarray
    jy: np.ndarray
    djx: np.ndarray
    djy: np.ndarray
    work: np.ndarray
    radius: np.ndarray
    angle: np.ndarray
    tau_end: float
    exit_speed: float
    friction_heat: float
    kinetic_gain: float


@lru_cache(maxsize=32)
def _push_cached(r0: float, v0: float, a: float, fq: float, n: int) -> StonePush:
    from scipy.integrate import solve_ivp

    sa, ca, ta = math.sin(a), math.cos(a), math.tan(a)

    def f(tau, y):
        r, v = y[0], y[1]
        fn = sa * v * v / r + 2.0 * v + r * sa
        ft = fq * fn
        dv = r * ca - ft
        return [v * ca, dv, r * (fn * ca - ft * sa), ft * v]

    def rim(tau, y):
        return y[0] - 1.0

    rim.terminal = True
    rim.direction = 1
    sol = solve_ivp(f, (0.0, 1e3), [r0, v0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=rim, dense_output=True)  # fmt: skip
    if sol.status != 1:
        raise ValueError("the stone does not reach the rim of the accelerator (check guide_friction)")
    tau_end = float(sol.t_events[0][0])
    tau = np.linspace(0.0, tau_end, n)
    r, v, work, heat = sol.sol(tau)
    r[-1] = 1.0
    dr = v * ca
    fn = sa * v * v / r + 2.0 * v + r * sa
    ft = fq * fn
    dv = r * ca - ft
    dfn = sa * (2.0 * v * dv / r - v * v * dr / (r * r)) + 2.0 * dv + dr * sa
    psi = ta * np.log(r / r0) + a  # polar angle of the stone + angle of the guide to the radius
    dpsi = v * sa / r
    sp, cp = np.sin(psi), np.cos(psi)
    jx = fn * (sp + fq * cp)
    jy = fn * (-cp + fq * sp)
    djx = dfn * (sp + fq * cp) + fn * dpsi * (cp - fq * sp)
    djy = dfn * (-cp + fq * sp) + fn * dpsi * (sp + fq * cp)
    ve = float(v[-1])
    kin = 0.5 * (ve * ve + 1.0 + 2.0 * ve * sa) - 0.5 * (v0 * v0 + r0 * r0 + 2.0 * v0 * r0 * sa)
    return StonePush(tau, jx, jy, djx, djy, work, r, psi - a, tau_end, ve, float(heat[-1]), kin)


def stone_push(start_radius: float, spiral_angle: float, guide_friction: float,
               start_speed: float = 0.0, n_table: int = 2049) -> StonePush:  # fmt: skip
    """Integrate eq. (4.3) for one stone on a logarithmic-spiral guide and tabulate J(tau).

    Parameters
    ----------
    start_radius : float
        r0, radius where the stone lands on its guide, in units of R_q, in (0, 1).
    spiral_angle : float
        a, angle between the guide and the radius (rad), in (0, pi/2).
    guide_friction : float
        f_q, friction between stone and guide, >= 0 and < cot(a) (else the stone stays put).
    start_speed : float
        Initial speed along the guide, units of R_q omega0, >= 0.
    n_table : int
        Points of the table.

    Returns
    -------
    StonePush

    Examples
    --------
    >>> import math
    >>> sp = stone_push(0.25, math.radians(30), 0.5)
    >>> round(sp.tau_end, 4), bool(abs(sp.work[-1] - sp.kinetic_gain - sp.friction_heat) < 1e-10)
    (4.4063, True)
    """
    r0 = _num("stone_push", "start_radius", start_radius, hi=1.0, hi_open=True)
    a = _num("stone_push", "spiral_angle", spiral_angle, hi=math.pi / 2, hi_open=True, unit="rad")
    fq = _num("stone_push", "guide_friction", guide_friction, lo_open=False)
    v0 = _num("stone_push", "start_speed", start_speed, lo_open=False)
    if fq >= 1.0 / math.tan(a):
        raise ValueError(
            f"stone_push.guide_friction must be < cot(spiral_angle) = {1 / math.tan(a):.4g} "
            f"(else a stone at rest stays on its guide), got {guide_friction!r}"
        )
    return _push_cached(r0, v0, a, fq, int(n_table))


@dataclass(frozen=True, slots=True)
class StoneFeed:
    """The stones and the accelerator that throws them.

    Parameters
    ----------
    mass : float
        m_q, nominal mass of a stone (kg), > 0.
    interval : float
        Delta t, nominal time between two stones (s), > 0.
    radius : float
        R_q, radius of the accelerator: a stone leaves its guide there (m), > 0.
    height : float
        h_q, height of the accelerator above the centre of mass (m).
    spiral_angle : float
        a, angle of the logarithmic-spiral guides to the radius (rad), in (0, pi/2).
    guide_friction : float
        f_q, friction between stone and guide, >= 0.
    start_radius : float
        Radius where a stone lands on its guide (m), in (0, R_q). Not given in the paper;
        default 0.1 m (the feed tube's radius). It decides Fig. 4 (issue 30): sustained contact
        whirls forwards and lasts only while a stone pushes, and a stone landing at 0.1 m pushes
        for 34.5 ms of the 70 ms between stones (27.5 ms from 0.15 m, the former default, with
        which no run slides at 5 kg); see ``dev/crusher_choices.py``.
    start_speed : float
        Speed of a landing stone along its guide (m/s), >= 0; default 0 (not given).
    n_guides : int
        N, number of guides at the angles 2 pi j / N; default 4 (not given).
    guides : {"random", "cyclic"}
        Which guide each stone takes: uniformly at random (default) or in turn.
    first_time : float or None
        Time of the first stone (s), > 0; ``None`` (default) is one interval.
    mass_spread : float
        Stone masses are uniform in ``mass * (1 +- mass_spread)``; default 0 (all equal, as in
        the paper's examples). In [0, 1).
    time_jitter : float
        Stone times are ``first_time + (n + U(-j, j)) interval``; default 0 (regular). In
        [0, 0.5).

    Examples
    --------
    >>> import math
    >>> feed = StoneFeed(0.7, 0.035, 0.6, 0.28, math.radians(30), 0.5)
    >>> seq = feed.sequence(1.0, seed=1)
    >>> len(seq), seq.times[:2].round(3).tolist(), float(seq.masses[0])
    (28, [0.035, 0.07], 0.7)
    """

    mass: float
    interval: float
    radius: float
    height: float
    spiral_angle: float
    guide_friction: float
    start_radius: float = 0.1
    start_speed: float = 0.0
    n_guides: int = 4
    guides: Literal["random", "cyclic"] = "random"
    first_time: float | None = None
    mass_spread: float = 0.0
    time_jitter: float = 0.0

    def __post_init__(self) -> None:
        o = "StoneFeed"
        object.__setattr__(self, "mass", _num(o, "mass", self.mass, unit="kg"))
        object.__setattr__(self, "interval", _num(o, "interval", self.interval, unit="s"))
        object.__setattr__(self, "radius", _num(o, "radius", self.radius, unit="m"))
        object.__setattr__(self, "height", _num(o, "height", self.height, lo=None, unit="m"))
        object.__setattr__(self, "spiral_angle",
                           _num(o, "spiral_angle", self.spiral_angle, hi=math.pi / 2, hi_open=True, unit="rad"))
        object.__setattr__(self, "guide_friction", _num(o, "guide_friction", self.guide_friction, lo_open=False))
        object.__setattr__(self, "start_radius",
                           _num(o, "start_radius", self.start_radius, hi=self.radius, hi_open=True, unit="m"))
        object.__setattr__(self, "start_speed", _num(o, "start_speed", self.start_speed, lo_open=False, unit="m/s"))
        if isinstance(self.n_guides, bool) or not isinstance(self.n_guides, (int, np.integer)) or self.n_guides < 1:
            raise ValueError(f"{o}.n_guides must be an integer >= 1, got {self.n_guides!r}")
        if self.guides not in ("random", "cyclic"):
            raise ValueError(f"{o}.guides must be 'random' or 'cyclic', got {self.guides!r}")
        if self.first_time is not None:
            object.__setattr__(self, "first_time", _num(o, "first_time", self.first_time, unit="s"))
        object.__setattr__(self, "mass_spread", _num(o, "mass_spread", self.mass_spread, lo_open=False, hi=1.0, hi_open=True))
        object.__setattr__(self, "time_jitter", _num(o, "time_jitter", self.time_jitter, lo_open=False, hi=0.5, hi_open=True))
        if self.guide_friction >= 1.0 / math.tan(self.spiral_angle):
            raise ValueError(
                f"{o}.guide_friction must be < cot(spiral_angle) = {1 / math.tan(self.spiral_angle):.4g}"
                f" (else a stone stays on its guide), got {self.guide_friction!r}"
            )

    def push(self, spin_speed: float) -> StonePush:
        """The tabulated push J(tau) of one stone (see :func:`stone_push`)."""
        return stone_push(self.start_radius / self.radius, self.spiral_angle, self.guide_friction,
                          self.start_speed / (self.radius * spin_speed))  # fmt: skip

    def sequence(self, t_end: float, seed: int | None = 0) -> StoneSequence:
        """Draw the stones that land before ``t_end`` (s) with a seeded generator.

        Parameters
        ----------
        t_end : float
            End of the run (s).
        seed : int or None
            Seed of ``numpy.random.default_rng``; the same seed gives the same stones.

        Returns
        -------
        StoneSequence
        """
        t_end = _num("StoneFeed.sequence", "t_end", t_end, unit="s")
        rng = np.random.default_rng(seed)
        t1 = self.interval if self.first_time is None else self.first_time
        n = max(0, int(math.floor((t_end - t1) / self.interval)) + 1)
        idx = np.arange(n, dtype=float)
        if self.time_jitter > 0.0:
            idx = idx + rng.uniform(-self.time_jitter, self.time_jitter, n)
        times = t1 + idx * self.interval
        if self.guides == "random":
            guides = rng.integers(0, self.n_guides, n)
        else:
            guides = np.arange(n) % self.n_guides
        masses = np.full(n, self.mass)
        if self.mass_spread > 0.0:
            masses = self.mass * (1.0 + rng.uniform(-self.mass_spread, self.mass_spread, n))
        keep = (times > 0.0) & (times < t_end)
        return StoneSequence(times[keep], masses[keep], guides[keep].astype(np.int64), self.n_guides,
                             -1 if seed is None else int(seed))  # fmt: skip


@dataclass(frozen=True)
class StoneSequence:
    """The stones of one run: landing times (s), masses (kg) and guide numbers 0 .. N-1.

    Parameters
    ----------
    times : ndarray, shape (n,)
        Strictly increasing, > 0 (s).
    masses : ndarray, shape (n,)
        > 0 (kg).
    guides : ndarray of int, shape (n,)
        Guide j sits at the angle 2 pi j / n_guides.
    n_guides : int
    seed : int
        Seed it was drawn with (-1: not drawn / unseeded).
    """

    times: np.ndarray = field(default_factory=lambda: np.empty(0))
    masses: np.ndarray = field(default_factory=lambda: np.empty(0))
    guides: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64))
    n_guides: int = 4
    seed: int = -1

    def __post_init__(self) -> None:
        t = np.asarray(self.times, dtype=float).ravel()
        m = np.asarray(self.masses, dtype=float).ravel()
        g = np.asarray(self.guides).ravel().astype(np.int64)
        if not (t.size == m.size == g.size):
            raise ValueError(f"StoneSequence.times, masses and guides must have the same length, got {t.size}, {m.size}, {g.size}")
        if t.size and (not np.all(np.isfinite(t)) or t[0] <= 0.0 or np.any(np.diff(t) <= 0.0)):
            raise ValueError("StoneSequence.times must be finite, > 0 and strictly increasing (s)")
        if np.any(~(m > 0.0)) or not np.all(np.isfinite(m)):
            raise ValueError("StoneSequence.masses must be finite and > 0 (kg)")
        if np.any((g < 0) | (g >= self.n_guides)):
            raise ValueError(f"StoneSequence.guides must be in 0 .. {self.n_guides - 1}")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "masses", m)
        object.__setattr__(self, "guides", g)

    def __len__(self) -> int:
        return int(self.times.size)

    def angles(self) -> np.ndarray:
        """Angles alpha_n of the guides (rad)."""
        return 2.0 * math.pi * self.guides / self.n_guides
