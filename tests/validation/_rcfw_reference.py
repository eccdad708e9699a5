"""Independent reference for the two-plane ball balancer of Rodrigues et al. (2008).

The equations come from the Lagrangian in ``dev/derive_rcfw.py`` (sympy, truncated after second
order in the small rotor motions as in the paper's Section 2.3.2), lambdified here for numbers.
Nothing in this module uses rotorlab: it is the yardstick that ``rotorlab.models.Machine`` is
measured against, and it holds the paper's closed forms and printed numbers.

Units: the paper's nondimensional set is read as SI with M = 1 kg, R = 1 m and k11 = 1 N/m, so
that Omega_1 = sqrt(k11 / M) = 1 rad/s and the nondimensional time is seconds. The paper scales
the ball damping with the ball mass, ``c_b = b / (m Omega_1 R^2)`` (Section 2.3.3), so a ball of
mass m has the dimensional damping ``b = c_b m`` (N m s).

References
----------
Rodrigues, Champneys, Friswell & Wilson, "Automatic two-plane balancing for rigid rotors",
Int. J. Non-Linear Mech. 43 (2008) 527-541 (author preprint, University of Bristol, hdl 1983/946;
equation and figure numbers below are the preprint's): eqs. (14)-(16) balanced state, (18)-(21)
long rotor and critical ball mass, Fig. 5 stability chart, Fig. 11 simulations.
Rodrigues, Champneys, Friswell & Wilson, "Two-plane automatic balancing: a symmetry breaking
analysis", Int. J. Non-Linear Mech. 46 (2011) 1139-1154: eq. (2) the model without the balls'
tilt inertia, eq. (32) the critical speeds with the balls, Section 5 / Fig. 13(b) the disc rotor.
"""

from __future__ import annotations

import functools
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[2]

# -- The paper's long rotor (Rodrigues et al. 2008, eqs. (18) and (20)) -------------------------
JT, JP = 3.25, 0.5  # transverse and polar moments of inertia (eq. (18))
SUPPORT_Z, SUPPORT_K, SUPPORT_C = 3.0, 0.5, 0.01  # l = 3, k11 = 1 -> k = 0.5 each, c = 0.01 (20)
RACE_Z, RACE_R = 2.0, 1.0  # z = 2 (eq. (20)), race radius R = 1 (the length scale)
CB = 0.01  # ball damping in the paper's scaling c_b = b / (m Omega_1 R^2) (eq. (20))
EPS = 0.01  # static imbalance eps / R (eq. (20))
M_CRIT = 0.0025  # critical ball mass m_c = eps / 4 (eq. (21))
OMEGA_CON = 1.81  # "Omega_2 = sqrt(k22 / (Jt - Jp)) ~= 1.81" (eq. (19))


@dataclass(frozen=True)
class TwoPlane:
    """Parameters of the rigid rotor with ball races (SI; see the module docstring).

    ``balls`` holds one ``(mass, race_radius, race_z, damping)`` per ball; ``supports`` one
    ``(stiffness, damping, z)`` per isotropic support.
    """

    mass: float = 1.0
    jt: float = JT
    jp: float = JP
    eps: float = EPS
    supports: tuple = ((SUPPORT_K, SUPPORT_C, SUPPORT_Z), (SUPPORT_K, SUPPORT_C, -SUPPORT_Z))
    balls: tuple = field(default_factory=tuple)
    kinematics: str = "rigid"

    @classmethod
    def long_rotor(cls, ball_mass: float, eps: float = EPS, *, cb: float = CB,
                   kinematics: str = "rigid", jt: float = JT, jp: float = JP) -> TwoPlane:
        """The paper's long rotor with two races of two balls at z = +-2 (eqs. (18), (20))."""
        ball_top = (ball_mass, RACE_R, RACE_Z, cb * ball_mass)
        ball_bottom = (ball_mass, RACE_R, -RACE_Z, cb * ball_mass)
        return cls(eps=eps, balls=(ball_top, ball_top, ball_bottom, ball_bottom),
                   kinematics=kinematics, jt=jt, jp=jp)

    @property
    def n(self) -> int:
        return len(self.balls)

    @property
    def k11(self) -> float:
        return sum(s[0] for s in self.supports)

    @property
    def k22(self) -> float:
        return sum(s[0] * s[2] ** 2 for s in self.supports)

    def with_balls(self, ball_mass: float) -> TwoPlane:
        return replace(self, balls=tuple((ball_mass, r, z, b / m * ball_mass)
                                         for (m, r, z, b) in self.balls))


@functools.lru_cache(maxsize=None)
def _lambdified(n_balls: tuple[int, ...], n_supports: int, kinematics: str):
    sys.path.insert(0, str(ROOT / "dev"))
    try:
        from derive_rcfw import derive
    finally:
        sys.path.pop(0)
    Mm, f, q, qd, par = derive(n_balls, n_supports, kinematics)
    args = [q, qd, par["th"], par["Om"], par["dOm"], par["Mr"], par["Jt"], par["Jp"], par["eps"],
            par["k"], par["c"], par["zs"], par["m"], par["R"], par["z"], par["b"]]
    return (sp.lambdify(args, Mm, "numpy", cse=True), sp.lambdify(args, f, "numpy", cse=True))


def fixed_rhs(sys_: TwoPlane, y, theta: float, omega: float, domega: float = 0.0) -> np.ndarray:
    """dy/dt in the fixed frame, ``y = (x, y, phi_x, phi_y, psi_i, rates...)`` (q then q').

    Works on complex ``y`` too (complex-step derivatives).
    """
    n = sys_.n
    races = (n,) if n else ()
    m_fun, f_fun = _lambdified(races, len(sys_.supports), sys_.kinematics)
    q, qd = y[: 4 + n], y[4 + n :]
    k, c, zs = (tuple(s[j] for s in sys_.supports) for j in range(3))
    m, r, z, b = (tuple(bl[j] for bl in sys_.balls) for j in range(4))
    args = (list(q), list(qd), theta, omega, domega, sys_.mass, sys_.jt, sys_.jp, sys_.eps,
            k, c, zs, m, r, z, b)
    dtype = complex if np.iscomplexobj(y) else float
    Mm = np.array(m_fun(*args), dtype=dtype)
    f = np.array(f_fun(*args), dtype=dtype).ravel()
    return np.concatenate([qd, np.linalg.solve(Mm, f)])


def rotating_rhs(sys_: TwoPlane, s, omega: float) -> np.ndarray:
    """dy/dt in the frame turning at the constant speed omega (autonomous).

    ``s = (u, v, a_x, a_y, alpha_i, rates...)``: the fixed-frame state at spin angle 0 is
    ``x + i y = u + i v`` (the same for the tilts), ``psi_i = alpha_i``, with the rates
    ``x' + i y' = (u' + i v') + i omega (u + i v)`` and ``psi_i' = omega + alpha_i'``; then
    ``(u + i v)'' = (x + i y)'' - 2 i omega (u + i v)' + omega^2 (u + i v)`` and
    ``alpha_i'' = psi_i''``.
    """
    n = sys_.n
    s = np.asarray(s)
    u, v, ax, ay = s[0], s[1], s[2], s[3]
    ud, vd, axd, ayd = s[4 + n], s[5 + n], s[6 + n], s[7 + n]
    rates = np.array([ud - omega * v, vd + omega * u, axd - omega * ay, ayd + omega * ax])
    fixed = np.concatenate([s[: 4 + n], rates, omega + s[8 + n :]])
    acc = fixed_rhs(sys_, fixed, 0.0, omega)[4 + n :]
    rel = np.array([acc[0] + 2 * omega * vd + omega**2 * u, acc[1] - 2 * omega * ud + omega**2 * v,
                    acc[2] + 2 * omega * ayd + omega**2 * ax, acc[3] - 2 * omega * axd + omega**2 * ay])
    return np.concatenate([s[4 + n :], rel, acc[4:]])


def jacobian(fun, s, h: float = 1e-30) -> np.ndarray:
    """Jacobian of ``fun`` at ``s`` by complex steps (exact to round-off)."""
    s = np.asarray(s, dtype=float)
    cols = []
    for j in range(s.size):
        e = s.astype(complex)
        e[j] += 1j * h
        cols.append(np.imag(fun(e)) / h)
    return np.array(cols).T


# -- Closed forms ---------------------------------------------------------------------------
def balanced_angles(eps: float, ball_mass: float, mass: float = 1.0, race_r: float = RACE_R):
    """Ball angles (body frame) of the balanced state for a static imbalance at phase 0.

    Eq. (16) with s_x = -M eps / (m R), s_y = c_x = c_y = 0: both races centre on the side
    opposite the imbalance, ``alpha_bar = pi``, and split by ``alpha_hat = arccos(M eps / (4 m R))``.
    Returns ``(alpha_1, alpha_2, alpha_3, alpha_4)`` or None when ``m < m_c`` (no balanced state).
    """
    arg = mass * eps / (4.0 * ball_mass * race_r)
    if arg > 1.0:
        return None
    hat = np.arccos(arg)
    return np.array([np.pi + hat, np.pi - hat, np.pi + hat, np.pi - hat])


def critical_mass(eps: float, mass: float = 1.0, race_r: float = RACE_R) -> float:
    """m_c = M eps / (4 R) (eq. (21)): the four balls in line opposite the imbalance."""
    return mass * eps / (4.0 * race_r)


def whirl_frequencies(omega: float, mass: float, jt: float, jp: float, k11: float, k22: float):
    """Undamped whirl frequencies of the bare rotor (k12 = 0) at spin speed omega.

    Cylindrical: ``sqrt(k11 / M)`` forward and backward. Conical: ``Jt w^2 -+ Jp omega w - k22 = 0``
    gives forward ``(Jp omega + sqrt(Jp^2 omega^2 + 4 Jt k22)) / (2 Jt)`` and backward
    ``(-Jp omega + sqrt(...)) / (2 Jt)`` (the gyroscopic split). Returns ``(cyl, con_fw, con_bw)``.
    """
    root = np.sqrt(jp**2 * omega**2 + 4.0 * jt * k22)
    return np.sqrt(k11 / mass), (jp * omega + root) / (2 * jt), (-jp * omega + root) / (2 * jt)


def critical_speeds(mass: float, jt: float, jp: float, k11: float, k22: float):
    """The rigid-body critical speeds (forward synchronous whirl, eq. (19)).

    ``Omega_1 = sqrt(k11 / M)``; ``Omega_2 = sqrt(k22 / (Jt - Jp))`` where the forward conical
    whirl frequency equals the spin speed, which happens only for a long rotor (Jt > Jp); for
    Jp >= Jt there is no conical critical speed (None). Also returns the backward conical
    critical speed ``sqrt(k22 / (Jt + Jp))``.
    """
    con = np.sqrt(k22 / (jt - jp)) if jt > jp else None
    return np.sqrt(k11 / mass), con, np.sqrt(k22 / (jt + jp))


def balanced_state(sys_: TwoPlane) -> np.ndarray | None:
    """The balanced state B in the co-rotating frame (rotor at rest on the axis, balls fixed)."""
    masses = {bl[0] for bl in sys_.balls}
    if len(masses) != 1 or sys_.n != 4:
        raise ValueError("balanced_state: four equal balls expected")
    ang = balanced_angles(sys_.eps, masses.pop(), sys_.mass, sys_.balls[0][1])
    if ang is None:
        return None
    s = np.zeros(2 * (4 + sys_.n))
    s[4:8] = ang
    return s


def spectral_abscissa(sys_: TwoPlane, omega: float) -> float:
    """Largest real part of the eigenvalues of the linearisation about B (co-rotating frame)."""
    s = balanced_state(sys_)
    if s is None:
        return np.nan
    J = jacobian(lambda v: rotating_rhs(sys_, v, omega), s)
    return float(np.max(np.linalg.eigvals(J).real))


def vibration(x, y, phi_x, phi_y):
    """The paper's vibration measure A-bar (eq. (23)): mean deflection at unit distance
    either side of the rotor centre, ``(|(x, y) + (phi_x, phi_y)| + |(x, y) - (phi_x, phi_y)|) / 2``
    (invariant under the frame rotation, so the same in the fixed and co-rotating frames)."""
    return 0.5 * (np.hypot(x + phi_x, y + phi_y) + np.hypot(x - phi_x, y - phi_y))
