"""Closed forms of rotor-stator contact that every rub code is checked against.

The rotor is the Jeffcott rotor (mass ``m``, isotropic stiffness ``k``, viscous damping ``c``,
unbalance eccentricity ``eps``) spinning at ``Omega`` inside a circular clearance ``delta``; the
stator is rigid or elastic (radial stiffness ``k_s``, damping ``c_s``, mass ``m_s``); contact
carries Coulomb friction ``mu``. Positions are complex, ``z = x + i y`` in the fixed frame. Every
function returns SI values (rad/s, m, N) and is pure.

Synchronous full annular rub (Black 1968; Choy & Padovan 1987)
    The rotor whirls forward at ``Omega`` with radius ``r > delta``, pressing the stator with
    ``N = k_s (r - delta)``; its contact point slides forward over the stator (surface speed
    ``(r + R_r) Omega > 0``), so friction ``mu N`` acts backwards along the tangent. In the frame
    rotating at ``Omega``, with ``w0 = r e^{-i phi}`` (phase lag ``phi`` behind the unbalance)::

        (k - m Omega^2 + i c Omega) r + k_s (r - delta) (1 + i mu) = m eps Omega^2 e^{i phi}

    and its modulus squared is a quadratic in ``r``::

        ((k - m Omega^2 + k_s) r - k_s delta)^2 + ((c Omega + mu k_s) r - mu k_s delta)^2
            = (m eps Omega^2)^2 ,

    whose roots beyond the clearance are the two rub branches; they meet at the fold where the
    discriminant vanishes. The contact force ``-k_s (|w| - delta)(1 + i mu) w/|w|`` is a
    *follower* force (the friction part is not the gradient of a potential), so friction feeds a
    flutter instability: the characteristic quartic of the linearisation in the rotating frame
    (:func:`full_rub_characteristic`) loses Hurwitz stability above a critical friction
    coefficient (:func:`critical_friction`). With ``mu = 0`` the contact is a conservative radial
    spring and the upper branch decays at ``-c / (2 m)`` like the free Jeffcott rotor.

Dry-friction backward whirl and dry whip (Black 1968; Crandall 1990)
    The rolling backward whirl, the moving housing's dry whip at the coupled frequency and the
    slipping whip of a massless stator (a saddle): :mod:`rotorlab.contact._whirl`.

Chatter (Nordmark & Piiroinen 2009)
    A body pressed against a wall by a constant acceleration ``a`` and striking it at ``v0`` with
    restitution ``e < 1`` makes infinitely many impacts in the finite time
    ``sum_{j>=1} 2 e^j v0 / a = 2 e v0 / (a (1 - e))`` (:func:`chatter_time`), after which it
    rests on the wall (sustained contact).

References
----------
H. F. Black, "Interaction of a whirling rotor with a vibrating stator across a clearance
annulus", J. Mech. Eng. Sci. 10 (1968) 1-12.
F. K. Choy, J. Padovan, "Non-linear transient analysis of rotor-casing rub events", J. Sound
Vib. 113 (1987) 529-545.
S. H. Crandall, "From whirl to whip in rotordynamics", Proc. 3rd IFToMM Int. Conf. on Rotordynamics,
Lyon (1990) 19-26.
A. B. Nordmark, P. T. Piiroinen, "Simulation and stability analysis of impacting systems with
complete chattering", Nonlinear Dyn. 58 (2009) 85-106.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from rotorlab.models._checks import check_number as _num
from rotorlab.models._rub_rotor import RubRotor

__all__ = [
    "RubRotor",
    "RubBranch",
        "no_rub_radius",
    "grazing_speeds",
    "full_rub",
    "full_rub_fold_speeds",
    "full_rub_jacobian",
    "full_rub_characteristic",
    "hurwitz_stable",
    "critical_friction",
    "chatter_time",
    "chatter_impact_times",
]


@dataclass(frozen=True, slots=True)
class RubBranch:
    """One synchronous full-rub orbit.

    Parameters
    ----------
    radius : float
        r, whirl radius of the rotor centre (m), > clearance for an elastic stator.
    normal_force : float
        N, contact normal force (N), > 0.
    phase : float
        phi, lag of the rotor displacement behind the unbalance (rad), in (-pi, pi].
    """

    radius: float
    normal_force: float
    phase: float


def _speed(speed) -> float:
    return _num("speed", "Omega", speed, lo=None, unit="rad/s")


def no_rub_radius(p: RubRotor, speed: float) -> float:
    """Return the radius of the synchronous unbalance orbit without contact (m).

    ``r0 = m eps Omega^2 / |k - m Omega^2 + i c Omega|`` (the Jeffcott rotor's response).

    Examples
    --------
    >>> round(no_rub_radius(RubRotor(1.0, 1.0, 1.0, damping=0.1, eccentricity=0.3), 1.0), 12)
    3.0
    """
    w = _speed(speed)
    return p.mass * p.eccentricity * w * w / abs(complex(p.stiffness - p.mass * w * w, p.damping * w))


def grazing_speeds(p: RubRotor) -> tuple[float, ...]:
    """Return the spin speeds where the no-rub orbit just reaches the clearance (rad/s), ascending.

    Solves ``no_rub_radius(Omega) = delta``: with ``s = Omega^2``,
    ``m^2 (eps^2 - delta^2) s^2 + delta^2 (2 k m - c^2) s - delta^2 k^2 = 0``. With
    ``eps < delta`` the orbit touches the stator only in a band around the critical speed (two
    speeds, or none if damping keeps the resonance peak inside); with ``eps > delta`` it touches
    from one speed on.

    Examples
    --------
    >>> [round(w, 6) for w in grazing_speeds(RubRotor(1.0, 1.0, 1.0, eccentricity=2.0))]
    [0.57735]
    """
    m, k, c, e, d = p.mass, p.stiffness, p.damping, p.eccentricity, p.clearance
    if e == 0.0:
        return ()
    coeffs = [m * m * (e * e - d * d), d * d * (2.0 * k * m - c * c), -d * d * k * k]
    if coeffs[0] == 0.0:
        roots = np.array([-coeffs[2] / coeffs[1]]) if coeffs[1] != 0.0 else np.array([])
    else:
        roots = np.roots(coeffs)
    s = sorted(float(r.real) for r in np.atleast_1d(roots) if abs(r.imag) <= 1e-12 * abs(r) and r.real > 0.0)
    return tuple(math.sqrt(x) for x in s)


def _full_rub_coefficients(p: RubRotor, w: float) -> tuple[float, float, float]:
    m, k, c, ks, d, mu = p.mass, p.stiffness, p.damping, p.stator_stiffness, p.clearance, p.friction
    f = m * p.eccentricity * w * w
    a_ = k - m * w * w + ks
    b_ = c * w + mu * ks
    dd = ks * d
    return a_ * a_ + b_ * b_, -2.0 * dd * (a_ + mu * b_), dd * dd * (1.0 + mu * mu) - f * f


def full_rub(p: RubRotor, speed: float) -> tuple[RubBranch, ...]:
    """Return the synchronous full annular rub orbits at one spin speed, largest radius first.

    Elastic stator: the roots ``r > delta`` of the quadratic in the module docstring. Rigid
    stator: ``r = delta`` and the roots ``N > 0`` of
    ``((k - m Omega^2) delta + N)^2 + (c Omega delta + mu N)^2 = (m eps Omega^2)^2``.
    Zero, one or two orbits; two meet at a fold (:func:`full_rub_fold_speeds`).

    References
    ----------
    Black (1968) section 3; Choy & Padovan (1987), synchronous rub.

    Examples
    --------
    >>> p = RubRotor(1.0, 1.0, 1.0, damping=0.1, eccentricity=0.3, stator_stiffness=10.0)
    >>> [round(b.radius, 4) for b in full_rub(p, 1.5)]
    [1.2171, 1.0679]
    """
    w = _speed(speed)
    m, k, c, ks, d, mu = p.mass, p.stiffness, p.damping, p.stator_stiffness, p.clearance, p.friction
    f = m * p.eccentricity * w * w
    out = []
    if p.rigid_stator:
        # (a + N)^2 + (b + mu N)^2 = f^2 with a = (k - m w^2) d, b = c w d
        a_, b_ = (k - m * w * w) * d, c * w * d
        qa, qb, qc = 1.0 + mu * mu, 2.0 * (a_ + mu * b_), a_ * a_ + b_ * b_ - f * f
        disc = qb * qb - 4.0 * qa * qc
        if disc < 0.0:
            return ()
        for sgn in (-1.0, 1.0):  # larger N (larger force, same radius) first
            n = (-qb - sgn * math.sqrt(disc)) / (2.0 * qa)
            if n > 0.0:
                phase = math.atan2(b_ + mu * n, a_ + n)
                out.append(RubBranch(d, n, phase))
        return tuple(out)
    qa, qb, qc = _full_rub_coefficients(p, w)
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return ()
    for sgn in (1.0, -1.0):
        r = (-qb + sgn * math.sqrt(disc)) / (2.0 * qa)
        if r > d:
            n = ks * (r - d)
            lhs = complex(k - m * w * w, c * w) * r + n * complex(1.0, mu)
            out.append(RubBranch(r, n, math.atan2(lhs.imag, lhs.real)))
    return tuple(out)


def full_rub_fold_speeds(p: RubRotor, speed_max: float, n_scan: int = 2001) -> tuple[float, ...]:
    """Return the speeds in ``(0, speed_max]`` where the two full-rub branches are born or merge.

    The discriminant of the radius quadratic changes sign there (located by a scan of
    ``n_scan`` speeds and :func:`scipy.optimize.brentq`); a fold counts only where the merging
    radius lies beyond the clearance. Elastic stator only.
    """
    if p.rigid_stator:
        raise ValueError("full_rub_fold_speeds needs an elastic stator: RubRotor.stator_stiffness is inf")
    w_max = _num("full_rub_fold_speeds", "speed_max", speed_max, unit="rad/s")

    def disc(w):
        a_, b_, c_ = _full_rub_coefficients(p, w)
        return (b_ * b_ - 4.0 * a_ * c_) / (a_ * a_)

    ws = np.linspace(w_max / n_scan, w_max, n_scan)
    vals = np.array([disc(w) for w in ws])
    folds = []
    for i in np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0):
        wf = brentq(disc, ws[i], ws[i + 1], xtol=1e-14 * w_max)
        a_, b_, _ = _full_rub_coefficients(p, wf)
        if -b_ / (2.0 * a_) > p.clearance:
            folds.append(float(wf))
    return tuple(folds)


def _contact_matrices(p: RubRotor, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and damping of the contact force linearised at ``w0 = radius`` (real axis).

    The force ``-(1 + i mu)(k_s (|w| - delta) + c_s d|w|/dt) w/|w|``: radial stiffness ``k_s``,
    tangential ``N / r``, the friction rotation ``[[1, -mu], [mu, 1]]`` in front.
    """
    ks, d, mu = p.stator_stiffness, p.clearance, p.friction
    rot = np.array([[1.0, -mu], [mu, 1.0]])
    kc = rot @ np.diag([ks, ks * (1.0 - d / radius)])
    cc = rot @ np.diag([p.stator_damping, 0.0])
    return kc, cc


def full_rub_jacobian(p: RubRotor, speed: float, radius: float) -> np.ndarray:
    """Return the Jacobian of the rub dynamics in the frame rotating at ``speed``, shape (4, 4).

    State ``[u, v, du/dt, dv/dt]``: radial and tangential displacement from the orbit
    ``w0 = radius`` (the phase is a rotation that leaves the linearisation unchanged), for a
    massless elastic stator in permanent contact.
    """
    if p.rigid_stator:
        raise ValueError("full_rub_jacobian needs an elastic stator: RubRotor.stator_stiffness is inf")
    w = _speed(speed)
    m, k, c = p.mass, p.stiffness, p.damping
    j = np.array([[0.0, -1.0], [1.0, 0.0]])  # multiplication by i
    kc, cc = _contact_matrices(p, radius)
    kr = (k - m * w * w) * np.eye(2) + c * w * j + kc
    cr = c * np.eye(2) + 2.0 * m * w * j + cc
    a = np.zeros((4, 4))
    a[:2, 2:] = np.eye(2)
    a[2:, :2] = -kr / m
    a[2:, 2:] = -cr / m
    return a


def full_rub_characteristic(p: RubRotor, speed: float, radius: float) -> np.ndarray:
    """Return the characteristic quartic of a full-rub orbit, coefficients highest power first.

    ``det(m s^2 I + s C_r + K_r)`` with, in the local radial/tangential axes,
    ``K_r = (k - m Omega^2) I + c Omega J + R(mu) diag(k_s, N/r)`` and
    ``C_r = c I + 2 m Omega J + R(mu) diag(c_s, 0)``, ``J`` the rotation by 90 degrees and
    ``R(mu) = [[1, -mu], [mu, 1]]``. Expanded by hand as the product of two quadratics in ``s``
    minus the product of the off-diagonal ones; the roots equal the eigenvalues of
    :func:`full_rub_jacobian` (tested).
    """
    if p.rigid_stator:
        raise ValueError("full_rub_characteristic needs an elastic stator: RubRotor.stator_stiffness is inf")
    w = _speed(speed)
    m, k, c, mu = p.mass, p.stiffness, p.damping, p.friction
    kc, cc = _contact_matrices(p, radius)
    kp = k - m * w * w
    # entries as polynomials in s (highest power first): a11 a22 - a12 a21
    a11 = np.array([m, c + cc[0, 0], kp + kc[0, 0]])
    a22 = np.array([m, c + cc[1, 1], kp + kc[1, 1]])
    a12 = np.array([0.0, -2.0 * m * w + cc[0, 1], -c * w + kc[0, 1]])
    a21 = np.array([0.0, 2.0 * m * w + cc[1, 0], c * w + kc[1, 0]])
    return np.polysub(np.polymul(a11, a22), np.polymul(a12, a21))


def hurwitz_stable(coeffs) -> bool:
    """Return whether a real polynomial (highest power first, leading > 0) is Hurwitz stable.

    Routh-Hurwitz for degree <= 4: all coefficients positive, and for the quartic
    ``a1 a2 a3 - a0 a3^2 - a1^2 a4 > 0`` (for the cubic ``a1 a2 > a0 a3``).

    Examples
    --------
    >>> hurwitz_stable([1.0, 3.0, 3.0, 1.0])  # (s + 1)^3
    True
    >>> hurwitz_stable([1.0, 0.0, 2.0, 0.0, 1.0])  # (s^2 + 1)^2
    False
    """
    a = np.asarray(coeffs, dtype=float)
    a = a / a[0]
    if np.any(a <= 0.0):
        return False
    if a.size == 5:
        return bool(a[1] * a[2] * a[3] - a[3] ** 2 - a[1] ** 2 * a[4] > 0.0)
    if a.size == 4:
        return bool(a[1] * a[2] > a[3])
    if a.size <= 3:
        return True
    raise ValueError(f"hurwitz_stable handles degree <= 4, got degree {a.size - 1}")


def _hurwitz_margin(p: RubRotor, w: float, branch: int) -> float | None:
    b = full_rub(p, w)
    if len(b) <= branch:
        return None
    a = full_rub_characteristic(p, w, b[branch].radius)
    a = a / a[0]
    return float(a[1] * a[2] * a[3] - a[3] ** 2 - a[1] ** 2 * a[4])


def critical_friction(p: RubRotor, speed: float, mu_max: float = 2.0, n_scan: int = 200) -> float:
    """Return the friction coefficient above which the upper full-rub orbit is unstable.

    The smallest ``mu`` in ``[0, mu_max]`` at which the Hurwitz determinant of
    :func:`full_rub_characteristic` on the larger-radius branch changes sign (scan of ``n_scan``
    values, then :func:`scipy.optimize.brentq`). ``0.0`` if the orbit is unstable already without
    friction, ``math.inf`` if it stays stable up to ``mu_max``.

    Raises
    ------
    ValueError
        No full-rub orbit at ``mu = 0`` at this speed.
    """
    from dataclasses import replace

    w = _speed(speed)
    if not full_rub(replace(p, friction=0.0), w):
        raise ValueError(f"no synchronous full-rub orbit at speed {w:g} rad/s without friction")

    def margin(mu):  # Hurwitz determinant of the upper branch; -1 where the branch has gone
        v = _hurwitz_margin(replace(p, friction=mu), w, 0)
        return -1.0 if v is None else v

    def stable(mu):
        q = replace(p, friction=mu)
        b = full_rub(q, w)
        return bool(b) and hurwitz_stable(full_rub_characteristic(q, w, b[0].radius))

    if not stable(0.0):
        return 0.0
    mus = np.linspace(0.0, mu_max, n_scan + 1)
    for a, b in zip(mus[:-1], mus[1:]):
        if not stable(b):
            return float(brentq(margin, a, b, xtol=1e-13))
    return math.inf


def chatter_time(impact_speed: float, acceleration: float, restitution: float) -> float:
    """Return the duration of complete chatter, ``2 e v0 / (a (1 - e))`` (s).

    A body pressed towards a wall by ``acceleration`` (m/s^2, > 0) that strikes it at
    ``impact_speed`` (m/s, > 0) with restitution ``e`` in [0, 1) comes to rest on it after the sum
    of its flight times ``2 e^j v0 / a``, j >= 1.

    References
    ----------
    Nordmark & Piiroinen (2009), complete chattering.

    Examples
    --------
    >>> chatter_time(1.0, 9.81, 0.5) * 9.81
    2.0
    """
    v0 = _num("chatter_time", "impact_speed", impact_speed, unit="m/s")
    a = _num("chatter_time", "acceleration", acceleration, unit="m/s^2")
    e = _num("chatter_time", "restitution", restitution, lo_open=False, hi=1.0, hi_open=True)
    return 2.0 * e * v0 / (a * (1.0 - e))


def chatter_impact_times(impact_speed: float, acceleration: float, restitution: float, n: int) -> np.ndarray:
    """Return the times of the first ``n`` impacts after the one at t = 0 (s), shape (n,).

    ``t_j = 2 e v0 (1 - e^j) / (a (1 - e))``: partial sums of the flight times.
    """
    t_inf = chatter_time(impact_speed, acceleration, restitution)
    e = float(restitution)
    return t_inf * (1.0 - e ** np.arange(1, int(n) + 1))
