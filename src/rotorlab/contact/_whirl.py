"""Dry-friction backward whirl and dry whip: closed forms of the whirl in permanent contact.

Conventions and parameters as in :mod:`rotorlab.contact._theory` (:class:`RubRotor`).

Dry-friction backward whirl (Black 1968; Crandall 1990)
    Rolling without slip, the rotor's contact point is at rest on the stator:
    ``r omega_w + R_r Omega = v_stator``. Rigid, fixed stator: ``omega_w = -(R_r / delta) Omega``.
    With a contact compliance ``k_s`` the whirl radius grows to ``r = delta + N / k_s`` and
    ``omega_w = -R_r Omega / r`` (:func:`rolling_whirl`); the radial balance
    ``N = r (m omega_w^2 - k)`` then gives ``(k + k_s) r^2 - k_s delta r - m R_r^2 Omega^2 = 0``.
    A whirl exists when ``N > 0``, i.e. ``R_r Omega / delta > sqrt(k / m)``; the tangential balance
    needs the friction ``c r |omega_w|``, so rolling needs ``mu >= c r |omega_w| / N``
    (:func:`friction_to_roll`); below it the whirl slips. A housing with mass ``m_s`` on
    ``k_s`` (rigid contact, undamped) moving with the rotor whirls at exactly
    ``-(R_r / delta) Omega`` with radius ``delta (k_s - m_s w^2) / (k + k_s - (m + m_s) w^2)``,
    which diverges at the coupled backward natural frequency ``sqrt((k + k_s) / (m + m_s))``:
    past it the whirl cannot roll any more and locks at that frequency, *dry whip*
    (:func:`dry_whip_frequency`; rotorlab's machine with a moving housing does, tested).

Slipping whip of a massless stator
    With ``m_s = 0`` no whirl locks at ``sqrt((k + k_s) / m)``. The backward whirl that slips
    (friction ``mu N`` driving it) has the closed form :func:`slipping_whip`: in units of
    ``p = sqrt(k / m)``, ``omega = -(zeta + sqrt(zeta^2 + mu^2)) / mu``, with ``zeta = c / (2 sqrt(k m))``;
    it exists below the coupled frequency and is a saddle (one real positive eigenvalue), so a
    simulation leaves it (and here loses contact).

References
----------
H. F. Black (1968); S. H. Crandall (1990): see :mod:`rotorlab.contact._theory`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorlab.contact._theory import RubRotor, _speed, full_rub_jacobian

__all__ = ["RollingWhirl", "SlippingWhip", "rolling_whirl", "friction_to_roll", "dry_whip_frequency",
           "slipping_whip"]


@dataclass(frozen=True, slots=True)
class RollingWhirl:
    """Backward whirl rolling without slip on the stator.

    Parameters
    ----------
    whirl_speed : float
        omega_w, whirl angular speed (rad/s), < 0 (backward) for a positive spin.
    radius : float
        r, whirl radius of the rotor centre (m).
    normal_force : float
        N, contact normal force (N), > 0.
    friction_needed : float
        The smallest friction coefficient that sustains rolling, tangential force over N.
    """

    whirl_speed: float
    radius: float
    normal_force: float
    friction_needed: float


def rolling_whirl(p: RubRotor, speed: float) -> RollingWhirl | None:
    """Return the backward whirl rolling without slip at spin ``speed``, or None if none exists.

    Fixed stator (``stator_mass = 0``) with contact compliance ``k_s`` (rigid if infinite):
    ``r = (k_s delta + sqrt(k_s^2 delta^2 + 4 (k + k_s) m R_r^2 Omega^2)) / (2 (k + k_s))``,
    ``omega_w = -R_r Omega / r`` (``r = delta``, ``omega_w = -(R_r / delta) Omega`` when rigid),
    ``N = r (m omega_w^2 - k)``. Moving housing (``stator_mass > 0``, rigid contact, no
    damping): ``omega_w = -(R_r / delta) Omega``,
    ``r = delta (k_s - m_s omega_w^2) / (k + k_s - (m + m_s) omega_w^2)``.
    None where ``N <= 0`` (too slow to press the stator) or the radius is not finite and beyond
    the clearance (past the dry-whip frequency).

    References
    ----------
    Black (1968); Crandall (1990), dry friction whirl.

    Examples
    --------
    >>> wh = rolling_whirl(RubRotor(1.0, 1.0, 0.01, rotor_radius=0.1), 1.0)
    >>> round(wh.whirl_speed, 9), round(wh.normal_force, 9)
    (-10.0, 0.99)
    """
    w = _speed(speed)
    m, k, d, ks, rr = p.mass, p.stiffness, p.clearance, p.stator_stiffness, p.rotor_radius
    if p.stator_mass > 0.0:
        if p.damping > 0.0 or p.stator_damping > 0.0:
            raise ValueError(
                "rolling_whirl with a moving housing (stator_mass > 0) is the undamped closed form: "
                f"got damping={p.damping:g}, stator_damping={p.stator_damping:g} N s/m"
            )
        om = -rr * w / d
        kss = math.inf if p.rigid_stator else ks
        if math.isinf(kss):
            r = d
        else:
            den = k + kss - (m + p.stator_mass) * om * om
            if den <= 0.0:
                return None
            r = d * (kss - p.stator_mass * om * om) / den
    elif p.rigid_stator:
        r, om = d, -rr * w / d
    else:
        r = (ks * d + math.sqrt((ks * d) ** 2 + 4.0 * (k + ks) * m * (rr * w) ** 2)) / (2.0 * (k + ks))
        om = -rr * w / r
    n = r * (m * om * om - k)
    if not (n > 0.0 and r >= d):
        return None
    return RollingWhirl(om, r, n, p.damping * r * abs(om) / n)


def friction_to_roll(p: RubRotor, speed: float) -> float:
    """Return the smallest friction coefficient that sustains the rolling backward whirl.

    Tangential balance of the rotor whirling at constant radius: friction must supply its
    damping force, ``mu N >= c r |omega_w|``. ``math.inf`` where no rolling whirl exists.
    """
    wh = rolling_whirl(p, speed)
    return math.inf if wh is None else wh.friction_needed


def dry_whip_frequency(p: RubRotor) -> float:
    """Return the coupled backward natural frequency ``sqrt((k + k_s) / (m + m_s))`` (rad/s).

    With a moving housing (``stator_mass > 0``) it is the frequency of dry whip: the rolling
    whirl's radius diverges there (:func:`rolling_whirl`), and a whirl driven past it stays in
    permanent contact at this frequency (rotor and housing move as one; tested in simulation).
    With a massless stator it is only the bound of the slipping whip (:func:`slipping_whip`,
    whose radius diverges there): that state is a saddle, and a whirl does not lock onto it or near
    this frequency. Elastic stator only.

    References
    ----------
    Crandall (1990), dry whip.
    """
    if p.rigid_stator:
        raise ValueError("dry_whip_frequency needs an elastic stator: RubRotor.stator_stiffness is inf")
    return math.sqrt((p.stiffness + p.stator_stiffness) / (p.mass + p.stator_mass))


@dataclass(frozen=True)
class SlippingWhip:
    """The slipping backward whip of a rotor in a massless elastic stator (a saddle).

    Parameters
    ----------
    whirl_speed : float
        omega_w, whirl angular speed (rad/s), < 0: ``p omega`` with the nondimensional ``omega``
        of :func:`slipping_whip`.
    radius : float
        r, whirl radius of the rotor centre (m), ``k_s delta / (k + k_s - m omega_w^2)``.
    normal_force : float
        N = ``k_s (r - delta)`` = ``r (m omega_w^2 - k)`` (N), > 0.
    min_spin_speed : float
        The slip ``r omega_w + R_r Omega`` is positive (friction drives the backward whirl) only
        for a spin speed above ``r |omega_w| / R_r`` (rad/s).
    eigenvalues : ndarray, shape (4,)
        Of the linearisation in the frame whirling with it (:func:`full_rub_jacobian` at
        ``omega_w``): a zero (the phase), a damped pair and a real positive one, ``growth_rate``.
    growth_rate : float
        The largest real part (1/s), > 0: the state is a saddle.
    """

    whirl_speed: float
    radius: float
    normal_force: float
    min_spin_speed: float
    eigenvalues: np.ndarray
    growth_rate: float


def slipping_whip(p: RubRotor) -> SlippingWhip | None:
    """Return the slipping backward whip of a massless elastic stator, or None where none exists.

    A circular whirl ``z = r e^{i omega_w t}`` in permanent contact, sliding with a positive slip
    ``s = r omega_w + R_r Omega > 0`` (friction ``F_t = -mu N`` drives it backwards). The radial and
    tangential balances ``N = r (m omega_w^2 - k)`` and ``c omega_w r = F_t = -mu N`` give, with
    ``p = sqrt(k / m)``, ``zeta = c / (2 sqrt(k m))`` and ``omega = omega_w / p``::

        mu omega^2 + 2 zeta omega - mu = 0,   omega = -(zeta + sqrt(zeta^2 + mu^2)) / mu

    (the other root is a forward whirl with ``N < 0``; a negative slip has no root with
    ``N > 0`` and ``Omega >= 0``), independent of the spin speed and of the stator. The stator
    sets the radius ``r = k_s delta / (k + k_s - m omega_w^2)``.

    Existence: ``mu > 0`` and ``zeta > 0`` (then ``|omega| > 1`` and ``N > 0``; with ``zeta = 0``
    ``omega = -1`` and ``N = 0``), ``|omega_w|`` below the coupled frequency
    ``sqrt((k + k_s) / m)`` (:func:`dry_whip_frequency`; the radius diverges there), and a spin
    speed above ``min_spin_speed`` (checked by the caller).

    Stability: in the whirling frame the characteristic polynomial is
    ``s (m^2 s^3 + a1 s^2 + a2 s + a3)`` with
    ``a3 = mu (k + m omega_w^2)(k + k_s - m omega_w^2) / omega_w < 0`` wherever the state exists,
    so a real eigenvalue is positive: the state is a saddle (rotorlab's simulation stays on it
    for as long as round-off allows, then leaves it at ``growth_rate``). Massless elastic stator
    only: a moving housing locks at :func:`dry_whip_frequency`.

    References
    ----------
    Black (1968); Crandall (1990), dry whip (the whirl and the stability derived here; checked
    with sympy in ``tests/validation/test_contact_theory.py``).

    Examples
    --------
    >>> w = slipping_whip(RubRotor(1.0, 1.0, 0.01, damping=0.1, stator_stiffness=100.0, friction=0.3))
    >>> round(w.whirl_speed, 6), w.growth_rate > 0.0
    (-1.18046, True)
    """
    if p.rigid_stator or p.stator_mass != 0.0:
        raise ValueError("slipping_whip needs a massless elastic stator: got stator_stiffness="
                         f"{p.stator_stiffness:g} N/m, stator_mass={p.stator_mass:g} kg")
    m, k, ks, mu = p.mass, p.stiffness, p.stator_stiffness, p.friction
    zeta = p.damping / (2.0 * math.sqrt(k * m))
    if mu == 0.0 or zeta == 0.0:
        return None
    om = -p.natural_frequency * (zeta + math.hypot(zeta, mu)) / mu
    den = k + ks - m * om * om
    if den <= 0.0:
        return None
    r = ks * p.clearance / den
    lam = np.linalg.eigvals(full_rub_jacobian(p, om, r))
    return SlippingWhip(om, r, ks * (r - p.clearance), r * abs(om) / p.rotor_radius, lam, float(lam.real.max()))
