r"""Built-in steady-motion cases of seeds 002 and 003, with documented parameter choices.

The seeds give equations, not numbers, so the parameters below are chosen as a realistic
laboratory rotor with an automatic balancer, and each case comes in *regimes* (same rotor and
balls, different eccentricity or support damping) that cover what the seeds discuss: enough
balancing capacity (``M1 e < sum m_i l_i``) and too little (``M1 e > sum m_i l_i``), one ball
dominating (``m_2 l_2 > M1 e + m_1 l_1``, seed 003 second side motion, case ii), and undamped
supports (seed 003's assumption 1). The verification speeds are ratios omega / p (p = sqrt(c / M),
M = M1 + sum m_i) below, just above and well above the critical speed: 0.6, 1.2 (inside the
window above p where nothing is stable), 2 and 3. Between the end of that window and about
1.7-1.8 p a non-synchronous whirl near p coexists with the stable motions and captures part of
the starts (see :mod:`rotorlab.steady._corrections`); a verification there shows it.

``zhakash-k2`` (Zhakash et al. 2024, seed 002)
    Two equal steel balls in an oil-filled race (eqs. (1)-(3), point masses J = m R^2):
    M1 = 2.0 kg, c = 2.0e4 N/m (p = 98.5 rad/s, 941 rpm), m = 0.030 kg (a 19 mm steel ball),
    R = 0.060 m, beta0 = b / (m R^2) = 20 1/s (b = 2.16e-3 N m s), shaft damping beta = d =
    8.12 N s/m (2 % of critical). Regimes: ``enough`` eta = M1 r / (m R) = 1.2 (r = 1.08 mm,
    condition (17) eta/2 < 1 holds); ``short`` eta = 2.6 (r = 2.34 mm, (17) fails).
``filimonikhin-n2`` (Filimonikhin & Filimonikhina, seed 003)
    Two unequal pendulums on the shaft (fig. 1a): M1 = 3.0 kg, c = 5.0e4 N/m (p = 127 rad/s,
    1213 rpm); m1 = 0.040 kg, m2 = 0.060 kg, l1 = l2 = 0.050 m (m1 l1 = 2.0e-3, m2 l2 = 3.0e-3
    kg m), J_Oi = 1.3 m_i l_i^2 (arm and bob), pivot damping b_i = (20 1/s) m_i l_i^2
    (2.0e-3 and 3.0e-3 N m s), support damping d = 23.6 N s/m (3 % of critical). Regimes: ``enough`` e = 1.0 mm (Me = 3.0e-3 kg m, main motions exist);
    ``short`` e = 2.0 mm (Me = 6.0e-3 > 5.0e-3); ``dominant`` e = 0.2 mm (Me = 0.6e-3 <
    m2 l2 - m1 l1 = 1.0e-3: no main motion although Me < sum m_i l_i); ``undamped`` e = 1.0 mm
    with d = 0 as the seed assumes (its main motions are then exactly unstable at every
    supercritical speed, see :mod:`rotorlab.steady._corrections`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams

__all__ = ["SteadyCase", "Regime", "steady_case", "steady_case_names"]


@dataclass(frozen=True)
class Regime:
    """One parameter variant of a case.

    Attributes
    ----------
    name : str
    eccentricity : float
        e (m).
    support_damping : float
        d (N s/m).
    description : str
    """

    name: str
    eccentricity: float
    support_damping: float
    description: str


@dataclass(frozen=True)
class SteadyCase:
    """A built-in rotor with balls, its regimes and the speeds at which it is checked.

    Attributes
    ----------
    name : str
        ``"zhakash-k2"`` or ``"filimonikhin-n2"``.
    title : str
    reference : str
        The seed paper.
    rotor : RotorParams
        Disc and shaft (eccentricity and damping are set per regime).
    balls : tuple of BallParams
    regimes : tuple of Regime
    speed_ratios : tuple of float
        Verification speeds omega / p.
    chart_speed_ratios : tuple of float
        ``(start, stop, count)`` of the stability chart's speed axis, as omega / p.
    """

    name: str
    title: str
    reference: str
    rotor: RotorParams
    balls: tuple[BallParams, ...]
    regimes: tuple[Regime, ...]
    speed_ratios: tuple[float, ...]
    chart_speed_ratios: tuple[float, float, int]

    @property
    def regime_names(self) -> tuple[str, ...]:
        """Names of the regimes."""
        return tuple(r.name for r in self.regimes)

    def regime(self, name: str) -> Regime:
        """Return the regime called ``name`` (ValueError lists the valid names)."""
        for r in self.regimes:
            if r.name == name:
                return r
        raise ValueError(f"case {self.name!r} has no regime {name!r}; regimes: {', '.join(self.regime_names)}")

    def model(self, regime: str, spin_speed: float = 1.0) -> JeffcottBalls:
        """Return the model of ``regime`` at a constant speed (rad/s), fixed frame."""
        r = self.regime(regime)
        rotor = replace(self.rotor, eccentricity=r.eccentricity, damping=r.support_damping)
        return JeffcottBalls(rotor, self.balls, speed=ConstantSpeed(spin_speed))

    def critical_speed(self) -> float:
        """p = sqrt(c / M) (rad/s), the same in every regime."""
        return math.sqrt(self.rotor.stiffness / (self.rotor.disc_mass + sum(b.mass for b in self.balls)))

    def speeds(self) -> tuple[float, ...]:
        """Verification speeds (rad/s)."""
        p = self.critical_speed()
        return tuple(r * p for r in self.speed_ratios)


def _zhakash() -> SteadyCase:
    m1, c, m, big_r, beta0 = 2.0, 2.0e4, 0.030, 0.060, 20.0
    big_m = m1 + 2 * m
    d = 2.0 * 0.02 * math.sqrt(c * big_m)
    ball = BallParams(m, big_r, damping=beta0 * m * big_r**2)
    regimes = (
        Regime("enough", 1.2 * m * big_r / m1, d, "eta = 1.2: capacity suffices, (17) holds"),
        Regime("short", 2.6 * m * big_r / m1, d, "eta = 2.6 > 2: capacity too small, (17) fails"),
    )
    return SteadyCase(
        name="zhakash-k2",
        title="Two equal balls in a race (seed 002, k = 2)",
        reference="Zhakash A.T., Dzhakashova E.A., Yesilkhankyzy A. Mechanics and Technologies 3(85), 2024",
        rotor=RotorParams(m1, regimes[0].eccentricity, c, d),
        balls=(ball, ball),
        regimes=regimes,
        speed_ratios=(0.6, 1.2, 2.0, 3.0),
        chart_speed_ratios=(0.2, 4.0, 191),
    )


def _filimonikhin() -> SteadyCase:
    m1, c = 3.0, 5.0e4
    pend = tuple(BallParams(m, 0.05, inertia=1.3 * m * 0.05**2, damping=20.0 * m * 0.05**2) for m in (0.04, 0.06))
    big_m = m1 + sum(b.mass for b in pend)
    d = 2.0 * 0.03 * math.sqrt(c * big_m)
    regimes = (
        Regime("enough", 1.0e-3, d, "Me = 3.0e-3 kg m: main motions exist"),
        Regime("short", 2.0e-3, d, "Me = 6.0e-3 > m1 l1 + m2 l2 = 5.0e-3 kg m: capacity too small"),
        Regime("dominant", 0.2e-3, d, "Me = 0.6e-3 < m2 l2 - m1 l1 = 1.0e-3 kg m: pendulum 2 dominates"),
        Regime("undamped", 1.0e-3, 0.0, "Me = 3.0e-3 kg m with undamped supports, as seed 003 assumes"),
    )
    return SteadyCase(
        name="filimonikhin-n2",
        title="Two unequal pendulums (seed 003, n = 2)",
        reference="Filimonikhin G.B., Filimonikhina I.I. Application of the Hamilton function to the "
        "conditions of auto-balancing (Kirovohrad National Technical University)",
        rotor=RotorParams(m1, regimes[0].eccentricity, c, d),
        balls=pend,
        regimes=regimes,
        speed_ratios=(0.6, 1.2, 2.0, 3.0),
        chart_speed_ratios=(0.2, 4.0, 191),
    )


_CASES = {"zhakash-k2": _zhakash, "filimonikhin-n2": _filimonikhin}


def steady_case_names() -> tuple[str, ...]:
    """Return the names of the built-in steady-motion cases.

    Examples
    --------
    >>> steady_case_names()
    ('zhakash-k2', 'filimonikhin-n2')
    """
    return tuple(_CASES)


def steady_case(name: str) -> SteadyCase:
    """Return the built-in case ``name``.

    Raises
    ------
    ValueError
        Unknown name (the message lists the valid ones).

    Examples
    --------
    >>> case = steady_case("filimonikhin-n2")
    >>> case.regime_names, round(case.critical_speed(), 1)
    (('enough', 'short', 'dominant', 'undamped'), 127.0)
    """
    if name not in _CASES:
        raise ValueError(f"unknown steady case {name!r}; built-in cases: {', '.join(_CASES)}")
    return _CASES[name]()
