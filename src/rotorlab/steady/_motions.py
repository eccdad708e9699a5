r"""Steady motions of a rotor with n balls or pendulums at constant speed (``jeffcott_balls``).

A steady motion is an equilibrium of the co-rotating frame: the disc centre stands at
``z = u + i v`` and every ball at a fixed angle psi_i from the unbalance. With the unbalance
vector ``U = M1 e + sum_i m_i l_i e^{i psi_i}`` (kg m) and ``D = c - M Omega^2 + i d Omega`` the
equilibrium equations (Filimonikhin & Filimonikhina eq. (11), with the support damping d added)
are ``D z = Omega^2 U`` and ``m_i l_i Omega^2 Im(z e^{-i psi_i}) = 0``, so either z = 0 and U = 0
(main motions, eq. (12)) or every ball lies on the line through z (side motions, eq. (13)).

Main motions
------------
``U = 0``: the n vectors m_i l_i e^{i psi_i} close the polygon with M1 e. They exist iff the
polygon inequality holds strictly: ``M1 e < sum_i m_i l_i`` *and* ``m_j l_j < M1 e + sum_{i != j}
m_i l_i`` for every j (seed 003 case 2a gives only the first). For n = 2 they are the two mirror
images psi -> -psi (seed 002 solution 1, ``psi = +-(pi - gamma)`` for equal balls); for n >= 3 a
continuous family of dimension n - 2, parametrised by the free angles psi_3..psi_n and a branch
sign (the first two balls close the triangle with the rest, see :func:`main_family_angles`).

Side motions
------------
Ball i at ``psi_i = theta + pi k_i`` (k_i = 0: towards the heavy side when d = 0, 1: light side;
2^n of them). With ``s = sum_i m_i l_i (-1)^{k_i}`` and ``z = rho e^{i theta}`` (rho real):
``(rho D - Omega^2 s) e^{i theta} = Omega^2 M1 e``, so

    rho = Omega^2 [s Re D + sgn(Re D) sqrt(Me^2 |D|^2 - s^2 d^2 Omega^2)] / |D|^2,

the root that continues seed 003's eq. (13) (``theta = 0``, ``rho = Omega^2 (Me + s) / (c - M
Omega^2)``) from d = 0; the other root is motion k with all bits flipped. The support damping
turns the line of the balls by theta, and a pair k, k' (all bits flipped) with ``|s| > M1 e``
disappears where ``d Omega |s| > M1 e |D|``.

References
----------
Filimonikhin & Filimonikhina, eqs. (10)-(15). Zhakash et al. 2024, eqs. (9), (12), (16)-(17).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from rotorlab.steady._records import SteadyMotion

if TYPE_CHECKING:
    from rotorlab.models import JeffcottBalls

__all__ = [
    "SteadyMotion",
    "find_steady_motions",
    "main_family_angles",
    "main_motions_exist",
    "motion_labels",
    "motion_state",
    "resolve_speed",
    "steady_machine",
    "side_deflection",
    "wrap",
]

#: Relative margin by which the polygon inequality must hold for main motions to be counted as
#: existing (below it the main motions merge into a side motion with zero deflection).
POLYGON_MARGIN = 1e-9


def wrap(angle):
    """Wrap angles to (-pi, pi] (rad); NaN stays NaN."""
    return np.pi - np.mod(np.pi - np.asarray(angle, dtype=float), 2.0 * np.pi)


def resolve_speed(model: JeffcottBalls, spin_speed: float | None) -> float:
    """Return the constant spin speed Omega (rad/s) to analyse, > 0.

    Raises
    ------
    ValueError
        If ``spin_speed`` is None and the model's speed profile is not constant, or if it is not
        a finite number > 0.
    """
    from rotorlab.models import ConstantSpeed

    if spin_speed is None:
        if not isinstance(model.speed, ConstantSpeed):
            raise ValueError("spin_speed must be given when the model's speed profile is not constant")
        spin_speed = model.speed.speed
    om = float(spin_speed)
    if not (math.isfinite(om) and om > 0.0):
        raise ValueError(f"spin_speed must be a finite number > 0 (rad/s), got {spin_speed!r}")
    return om


def steady_machine(model: JeffcottBalls, spin_speed: float):
    """The :class:`rotorlab.models.Machine` the rotor is, at the constant speed ``spin_speed``.

    :func:`rotorlab.continuation.as_machine`: one node, one race of the balls (one race per ball
    where their radii differ), the disc's unbalance at angle 0 (ball angles psi are measured from
    it), ball friction left out (its smooth part: see :func:`find_steady_motions`). Its
    co-rotating frame solves and judges every steady motion this package lists.
    """
    from rotorlab.continuation import as_machine
    from rotorlab.models import BallParams, ConstantSpeed

    # a point mass's inertia m l^2 computed another way may fall below as_machine's m l^2 by
    # round-off (its own inertia then -1e-19 kg m^2, refused): snap those to as_machine's value
    model = replace(model, balls=tuple(
        replace(b, inertia=b.mass * b.radius ** 2) if abs(b.inertia - b.mass * b.radius ** 2) <= 1e-12 * b.inertia
        else b for b in model.balls))
    model = replace(model, speed=ConstantSpeed(float(spin_speed)))
    if len({b.radius for b in model.balls}) == 1:
        machine = as_machine(model)
    else:  # balls on several radii (or none): one race per ball at the disc, in the model's order
        parts = [as_machine(replace(model, balls=(b,))) for b in model.balls]
        base = parts[0] if parts else as_machine(replace(model, balls=(BallParams(1.0, 1.0),)))
        machine = replace(base, races=tuple(m.races[0] for m in parts))
    # a chart builds one machine per point, all of one layout: its compiled kernel looked up once
    lay = machine.layout
    kernels = next((k for known, k in _KERNELS if known == lay), None)
    if kernels is None:
        _KERNELS.insert(0, (lay, machine.kernels))
        del _KERNELS[4:]
    else:
        machine._cache.setdefault("kernels", kernels)
    return machine


#: The kernels of the last few machine layouts of :func:`steady_machine` (layout, kernels).
_KERNELS: list = []


def motion_state(machine, deflection: complex, angles) -> np.ndarray:
    """The machine's co-rotating state at rest with the disc at ``deflection`` (m) and the balls at
    ``angles`` (rad)."""
    q = np.zeros(machine.structure.n_dof)
    q[0], q[1] = deflection.real, deflection.imag
    return machine.rotating_state(q, angles)


def _on_machine(machine, motion: SteadyMotion) -> SteadyMotion:
    """The motion as an equilibrium of the machine's co-rotating frame: the closed form where the
    machine confirms it (its accelerations vanish to round-off), else the machine's root near it."""
    if not motion.exists:
        return motion
    rows = [machine.equilibrium_near(motion_state(machine, motion.deflection, a)) for a in motion.samples]
    if any(y is None for y in rows):
        raise RuntimeError(f"steady motion {motion.label} at {motion.spin_speed:.6g} rad/s: the closed form is "
                           "not an equilibrium of the machine's co-rotating frame and no root was found near it")
    nz, nb = machine.n_coordinates, machine.n_balls
    q = machine.basis @ rows[0][:nz]
    samples = np.array([y[2 * nz:2 * nz + nb] for y in rows])
    if np.array_equal(samples, motion.samples) and complex(q[0], q[1]) == motion.deflection:
        return motion
    return replace(motion, deflection=complex(q[0], q[1]), ball_angles=wrap(samples[0]), samples=wrap(samples))


def _moments(model: JeffcottBalls) -> np.ndarray:
    return np.array([b.static_moment for b in model.balls], dtype=float)


def main_motions_exist(imbalance: float, moments) -> bool:
    """Return True when main motions (U = 0, seed 003 eq. (12)) exist.

    Parameters
    ----------
    imbalance : float
        M1 e (kg m).
    moments : array_like, shape (n,)
        Static moments m_i l_i (kg m).

    Returns
    -------
    bool
        Strict polygon inequality: the largest of M1 e, m_1 l_1, ..., m_n l_n is less than the sum
        of the others (by the relative margin :data:`POLYGON_MARGIN`); needs n >= 2.

    Examples
    --------
    >>> main_motions_exist(1.0, [0.8, 0.8]), main_motions_exist(2.0, [0.8, 0.8])
    (True, False)
    >>> main_motions_exist(0.2, [0.5, 1.0])  # one ball dominates: 1.0 > 0.2 + 0.5
    False
    """
    sides = np.concatenate([[float(imbalance)], np.asarray(moments, dtype=float).reshape(-1)])
    if sides.size < 3:
        return False
    total = sides.sum()
    return bool(2.0 * sides.max() < total * (1.0 - POLYGON_MARGIN))


def main_family_angles(imbalance: float, moments, free_angles, branch: int) -> np.ndarray | None:
    """Return the ball angles of the main motion with given free angles, or None.

    Parameters
    ----------
    imbalance : float
        M1 e (kg m).
    moments : array_like, shape (n,)
        m_i l_i (kg m), n >= 2.
    free_angles : array_like, shape (n - 2,)
        psi_3..psi_n (rad).
    branch : {+1, -1}
        Which of the two triangles closes the polygon; for n = 2, +1 gives psi_1 in (0, pi).

    Returns
    -------
    ndarray, shape (n,) or None
        Angles psi_i in (-pi, pi] with ``M1 e + sum m_i l_i e^{i psi_i} = 0``; None when
        ``M1 e + sum_{i >= 3} m_i l_i e^{i psi_i}`` cannot be closed by the first two balls.

    Examples
    --------
    >>> import numpy as np
    >>> np.degrees(main_family_angles(1.0, [1.0, 1.0], [], +1)).round(6)  # gamma = 60 degrees
    array([ 120., -120.])
    """
    s = np.asarray(moments, dtype=float).reshape(-1)
    free = np.asarray(free_angles, dtype=float).reshape(-1)
    if s.size < 2 or free.size != s.size - 2:
        raise ValueError(f"free_angles must have n - 2 = {s.size - 2} entries, got {free.size}")
    rest = float(imbalance) + np.sum(s[2:] * np.exp(1j * free))
    r = abs(rest)
    s1, s2 = s[0], s[1]
    if not (abs(s1 - s2) < r < s1 + s2) or r == 0.0:
        return None
    a1 = math.acos(min(1.0, max(-1.0, (s1 * s1 + r * r - s2 * s2) / (2.0 * s1 * r))))
    a2 = math.acos(min(1.0, max(-1.0, (s2 * s2 + r * r - s1 * s1) / (2.0 * s2 * r))))
    base = math.atan2(-rest.imag, -rest.real)  # direction of -rest, where the pair must point
    sign = 1.0 if branch >= 0 else -1.0
    # for rest along +U (base = pi) branch +1 puts ball 1 at pi - a1 in (0, pi)
    out = np.concatenate([[base - sign * a1, base + sign * a2], free])
    return wrap(out)


def side_deflection(imbalance: float, moments, bits, spin_speed: float, stiffness: float,
                    total_mass: float, damping: float) -> tuple[complex, float] | None:  # fmt: skip
    """Return the deflection z and the angle theta of the ball line of side motion ``bits``.

    Parameters
    ----------
    imbalance : float
        M1 e (kg m).
    moments : array_like, shape (n,)
        m_i l_i (kg m).
    bits : sequence of {0, 1}, length n
        k_i of seed 003 eq. (13).
    spin_speed, stiffness, total_mass, damping : float
        Omega (rad/s), c (N/m), M = M1 + sum m_i (kg), d (N s/m).

    Returns
    -------
    (complex, float) or None
        ``z = u + i v`` (m) and theta (rad), the balls being at ``theta + pi k_i``; None when the
        motion does not exist (at resonance, or removed by the support damping).

    Examples
    --------
    Undamped, eq. (13): ``x = Omega^2 (Me + s) / (c - M Omega^2)``, theta = 0.

    >>> z, th = side_deflection(1e-3, [2e-3, 1e-3], (0, 1), 10.0, 200.0, 1.0, 0.0)
    >>> round(z.real, 12), round(z.imag, 12), th
    (0.002, 0.0, 0.0)
    """
    om = float(spin_speed)
    me = float(imbalance)
    s = float(np.sum(np.asarray(moments, dtype=float) * (-1.0) ** np.asarray(bits, dtype=float)))
    dre = float(stiffness) - float(total_mass) * om * om
    dim = float(damping) * om
    dd = complex(dre, dim)
    mod2 = dre * dre + dim * dim
    if math.sqrt(mod2) <= 1e-12 * (float(stiffness) + float(total_mass) * om * om):
        return None  # at resonance without support damping (to round-off): no steady motion
    if me == 0.0:
        if dim != 0.0 and s != 0.0:
            return None  # a balanced disc has no side motion off the axis when d > 0
        return complex(om * om * s / dd), 0.0
    disc = me * me * mod2 - s * s * dim * dim
    if disc < 0.0:
        return None
    sgn = 1.0 if dre >= 0.0 else -1.0
    rho = om * om * (s * dre + sgn * math.sqrt(disc)) / mod2
    rot = om * om * me / (rho * dd - om * om * s)
    theta = math.atan2(rot.imag, rot.real)
    return complex(rho * complex(math.cos(theta), math.sin(theta))), theta


def motion_labels(n_balls: int) -> tuple[str, ...]:
    """Return the labels of all steady motions of a model with ``n_balls`` balls, in order.

    ``"main+"``, ``"main-"`` (n = 2) or ``"main"`` (n >= 3, the family), then ``"side b_1..b_n"``
    for the 2^n side motions in the order of seed 003's number k (b_i = k_i).

    Examples
    --------
    >>> motion_labels(2)
    ('main+', 'main-', 'side 00', 'side 01', 'side 10', 'side 11')
    """
    main = ("main+", "main-") if n_balls == 2 else (("main",) if n_balls >= 3 else ())
    bits = itertools.product((0, 1), repeat=n_balls)
    return main + tuple("side " + "".join(str(b) for b in k) for k in bits)


def _family_samples(imbalance: float, s: np.ndarray, per_dim: int, cap: int) -> np.ndarray:
    """Members of the main family: the two largest balls close the polygon (widest feasible set)."""
    n = s.size
    if n == 2:
        rows = [main_family_angles(imbalance, s, [], b) for b in (+1, -1)]
        return np.array([r for r in rows if r is not None]).reshape(-1, 2)
    order = np.argsort(-s, kind="stable")  # closing pair first
    inverse = np.argsort(order)
    sp = s[order]
    grid = (np.arange(per_dim) + 0.5) * (2.0 * np.pi / per_dim) - np.pi
    candidates = list(itertools.product(grid, repeat=n - 2))
    rng = np.random.default_rng(0)
    rows: list[np.ndarray] = []
    for _ in range(2):
        for free in candidates:
            for b in (+1, -1):
                r = main_family_angles(imbalance, sp, free, b)
                if r is not None:
                    rows.append(r[inverse])
        if rows:
            break
        candidates = list(rng.uniform(-np.pi, np.pi, (4096, n - 2)))  # a thin family: search
    out = np.array(rows).reshape(-1, n)
    if out.shape[0] > cap:
        out = out[np.linspace(0, out.shape[0] - 1, cap).round().astype(int)]
    return out


def _h_tilde(model: JeffcottBalls, om: float, z: complex, angles) -> float:
    """H~* = Pi - T0 at the co-rotating position (z, psi), as the model's ``reduced_hamiltonian``."""
    r = model.rotor
    s = _moments(model)
    psi = np.asarray(angles, dtype=float)
    u, v = z.real, z.imag
    inertia = sum(b.inertia for b in model.balls)
    work = r.imbalance * u + float(np.sum(s * (u * np.cos(psi) + v * np.sin(psi))))
    return float(0.5 * (r.stiffness - model.total_mass * om * om) * (u * u + v * v) - om * om * work
                 - 0.5 * om * om * (r.imbalance * r.eccentricity + inertia))  # fmt: skip


def find_steady_motions(model: JeffcottBalls, spin_speed: float | None = None, *,
                        family_samples: int = 12, max_family_samples: int = 256,
                        machine=None) -> tuple[SteadyMotion, ...]:  # fmt: skip
    """Find all steady motions of the rotor and its balls at a constant speed.

    Parameters
    ----------
    model : JeffcottBalls
        Any frame. Ball friction is left out (the machine's smooth part,
        :func:`rotorlab.continuation.smooth_part_note`): every motion listed is also a steady
        motion with friction, its balls stuck with no friction torque needed; friction adds a
        continuum of stuck positions around them that is not enumerated.
    spin_speed : float, optional
        Omega (rad/s), > 0; default the model's constant speed.
    family_samples : int
        Sample points per free angle of the family of main motions (n >= 3).
    max_family_samples : int
        Cap on the number of family samples kept (evenly strided).
    machine : Machine, optional
        :func:`steady_machine` of the model at the speed (built when not given).

    Returns
    -------
    tuple of SteadyMotion
        In the order of :func:`motion_labels`; motions that do not exist are included with
        ``exists=False`` (NaN angles and deflection) so that labels stay aligned across speeds.

    Notes
    -----
    See the module docstring for the equations. Their closed forms (which hold for this planar
    rotor only) list and label the motions; each is then an equilibrium of the machine's
    co-rotating frame (:meth:`rotorlab.models.Machine.equilibrium_near`: kept where the machine's
    accelerations vanish there to round-off, else its root nearby; RuntimeError if none). For n = 1 no main motion is listed: when
    ``m_1 l_1 = M1 e`` the side motion "side 1" has zero deflection.

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (11)-(15); Zhakash et al. 2024 eqs. (9), (16)-(17).

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> ball = BallParams(mass=0.02, radius=0.1)
    >>> model = JeffcottBalls(RotorParams(1.0, 2e-3, 400.0), (ball, ball), speed=ConstantSpeed(40.0))
    >>> [(m.label, m.exists) for m in find_steady_motions(model)][:3]
    [('main+', True), ('main-', True), ('side 00', True)]
    """
    om = resolve_speed(model, spin_speed)
    n = model.n_balls
    s = _moments(model)
    me = model.imbalance
    r = model.rotor
    big_m = model.total_mass
    nan_angles = np.full(n, np.nan)
    out: list[SteadyMotion] = []
    if n >= 2:
        exists = main_motions_exist(me, s)
        samples = _family_samples(me, s, int(family_samples), int(max_family_samples)) if exists else np.empty((0, n))
        h0 = _h_tilde(model, om, 0j, np.zeros(n)) if n else 0.0  # H~* does not depend on psi at z = 0
        if n == 2:
            for label, row in (("main+", 0), ("main-", 1)):
                ok = exists and samples.shape[0] == 2
                ang = samples[row] if ok else nan_angles
                members = ang[None, :] if ok else np.empty((0, 2))
                z = 0j if ok else complex(np.nan, np.nan)
                out.append(SteadyMotion(label, "main", (), ok, ang, z, h0 if ok else np.nan, 0, members, om))
        else:
            ok = exists and samples.shape[0] > 0
            out.append(SteadyMotion("main", "main", (), ok, samples[0] if ok else nan_angles,
                                    0j if ok else complex(np.nan, np.nan), h0 if ok else np.nan,
                                    n - 2, samples, om))  # fmt: skip
    for bits in itertools.product((0, 1), repeat=n):
        label = "side " + "".join(str(b) for b in bits)
        res = side_deflection(me, s, bits, om, r.stiffness, big_m, r.damping)
        if res is None:
            out.append(SteadyMotion(label, "side", bits, False, nan_angles, complex(np.nan, np.nan),
                                    np.nan, 0, np.empty((0, n)), om))  # fmt: skip
            continue
        z, theta = res
        ang = wrap(theta + np.pi * np.asarray(bits, dtype=float))
        out.append(SteadyMotion(label, "side", bits, True, ang, z, _h_tilde(model, om, z, ang), 0,
                                ang[None, :], om))  # fmt: skip
    machine = steady_machine(model, om) if machine is None else machine
    return tuple(_on_machine(machine, m) for m in out)
