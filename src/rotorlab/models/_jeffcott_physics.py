r"""Energy, Hamilton function, dissipation, drive torque and linearization of ``jeffcott_balls``.

Pure NumPy functions of a :class:`~rotorlab.models.JeffcottBalls` model and states in the
model's frame (arrays of shape (..., n_state), converted internally); the model's methods of the
same names call them. Notation as in :mod:`rotorlab.models._jeffcott_balls`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "Linearization",
    "energy",
    "hamiltonian",
    "reduced_hamiltonian",
    "dissipation",
    "hamiltonian_rate",
    "drive_torque",
    "linearize",
]


def _ball_arrays(model):
    b = model.balls
    return (
        np.array([x.mass for x in b]),
        np.array([x.radius for x in b]),
        np.array([x.inertia for x in b]),
        np.array([x.damping for x in b]),
        np.array([x.friction for x in b]),
    )


def _in_frame(model, y, t, frame):
    """States in ``frame`` and the spin (theta, omega) at ``t``, broadcast to y.shape[:-1]."""
    y = np.asarray(y, dtype=float)
    if y.shape[-1] != model.n_state:
        raise ValueError(f"y must have n_state = {model.n_state} entries last, got {y.shape}")
    t = np.broadcast_to(np.asarray(t, dtype=float), y.shape[:-1])
    th, om, dom = model.spin(t)
    return model.to_frame(t, y, frame), t, th, om, dom


def _stuck_mask(model, y):
    n = model.n_balls
    if not model.has_friction:
        return np.zeros(y.shape[:-1] + (n,), dtype=bool)
    f = np.array([b.friction for b in model.balls])
    return (y[..., 4 + 2 * n :] == 0.0) & (f > 0.0)


def energy(model, t, y):
    """Return the total mechanical energy T + Pi in the fixed frame.

    Parameters
    ----------
    model : JeffcottBalls
    t : float or array_like, shape (...)
        Times (s).
    y : array_like, shape (..., n_state)
        States in the model's frame.

    Returns
    -------
    ndarray, shape (...)
        ``1/2 M1 |v_C|^2 + sum_i [1/2 m_i |v_O1|^2 + m_i l_i w_i (-vx sin phi_i + vy cos phi_i)
        + 1/2 J_i w_i^2] + 1/2 c (x^2 + y^2)`` (J); the disc's own spin energy is left out.

    Notes
    -----
    With the prescribed spin the drive does work: ``dE/dt = omega tau_drive - sum q' Q`` with
    :func:`drive_torque` (tested), not zero.
    """
    yf, t, th, om, _ = _in_frame(model, y, t, "fixed")
    n = model.n_balls
    r = model.rotor
    m, l, J, _, _ = _ball_arrays(model)
    x, yy, vx, vy = (yf[..., k] for k in range(4))
    phi = yf[..., 4 : 4 + n]
    w = np.where(_stuck_mask(model, yf), om[..., None], yf[..., 4 + n : 4 + 2 * n])
    vcx = vx - r.eccentricity * om * np.sin(th)
    vcy = vy + r.eccentricity * om * np.cos(th)
    t_disc = 0.5 * r.disc_mass * (vcx**2 + vcy**2)
    t_balls = np.sum(
        0.5 * m * (vx**2 + vy**2)[..., None]
        + m * l * w * (-vx[..., None] * np.sin(phi) + vy[..., None] * np.cos(phi))
        + 0.5 * J * w**2,
        axis=-1,
    )
    return t_disc + t_balls + 0.5 * r.stiffness * (x**2 + yy**2)


def _rotating_parts(model, y, t):
    yr, t, th, om, dom = _in_frame(model, y, t, "rotating")
    n = model.n_balls
    m, l, J, b, f = _ball_arrays(model)
    u, v, du, dv = (yr[..., k] for k in range(4))
    psi = yr[..., 4 : 4 + n]
    dpsi = np.where(_stuck_mask(model, yr), 0.0, yr[..., 4 + n : 4 + 2 * n])
    return yr, om, u, v, du, dv, psi, dpsi, (m, l, J, b, f)


def _pi_minus_t0(model, om, u, v, psi, m, l, J):
    r = model.rotor
    big_m = model.total_mass
    ml = m * l
    t0 = 0.5 * om**2 * (
        big_m * (u**2 + v**2)
        + 2.0 * r.imbalance * u
        + r.imbalance * r.eccentricity
        + 2.0 * np.sum(ml * (u[..., None] * np.cos(psi) + v[..., None] * np.sin(psi)), axis=-1)
        + np.sum(J)
    )
    return 0.5 * r.stiffness * (u**2 + v**2) - t0


def hamiltonian(model, y, t=0.0):
    """Return H* = T2 + Pi - T0 in the co-rotating frame (Jacobi integral).

    Parameters
    ----------
    model : JeffcottBalls
    y : array_like, shape (..., n_state)
        States in the model's frame.
    t : float or array_like, shape (...)
        Times (s): they set the spin speed Omega(t) and, for fixed-frame states, the rotation.

    Returns
    -------
    ndarray, shape (...)
        H* (J), with T2, T0 as in :mod:`rotorlab.models._jeffcott_balls`.

    Notes
    -----
    At constant speed dH*/dt = sum q_i' Q_i (:func:`hamiltonian_rate`), = -2 Phi when d = 0.

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (4), (5), (8), (9).
    """
    yr, om, u, v, du, dv, psi, dpsi, (m, l, J, _, _) = _rotating_parts(model, y, t)
    big_m = model.total_mass
    ml = m * l
    t2 = 0.5 * big_m * (du**2 + dv**2) + np.sum(
        ml * dpsi * (-du[..., None] * np.sin(psi) + dv[..., None] * np.cos(psi)) + 0.5 * J * dpsi**2,
        axis=-1,
    )
    return t2 + _pi_minus_t0(model, om, u, v, psi, m, l, J)


def reduced_hamiltonian(model, y, t=0.0):
    """Return H~* = Pi - T0, the Hamilton function at zero generalized velocities.

    Parameters and Returns as in :func:`hamiltonian` (velocities in ``y`` are ignored).

    Notes
    -----
    ``2 H~* = (c - M Omega^2)(u^2 + v^2) - Omega^2 (M1 e^2 + sum J_i) - 2 u Omega^2 (sum m_i l_i
    cos psi_i + M1 e) - 2 v Omega^2 sum m_i l_i sin psi_i``; its stationary points are the
    steady motions (eq. (11)).

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (6), (10).
    """
    yr, om, u, v, du, dv, psi, dpsi, (m, l, J, _, _) = _rotating_parts(model, y, t)
    return _pi_minus_t0(model, om, u, v, psi, m, l, J)


def dissipation(model, y, t=0.0):
    """Return the Rayleigh function of the viscous forces.

    Returns
    -------
    ndarray, shape (...)
        ``Phi = 1/2 d |v_O1|^2 + 1/2 sum_i b_i (phi_i' - theta')^2`` (W), absolute velocity of
        O1; Coulomb friction is not included (see :func:`hamiltonian_rate`).

    References
    ----------
    Filimonikhin & Filimonikhina eq. (7) (there d = 0).
    """
    yr, om, u, v, du, dv, psi, dpsi, (_, _, _, b, _) = _rotating_parts(model, y, t)
    d = model.rotor.damping
    return 0.5 * d * ((du - om * v) ** 2 + (dv + om * u) ** 2) + 0.5 * np.sum(b * dpsi**2, axis=-1)


def _friction_torques(model, yr, t):
    """Coulomb torques on the balls (holding torque -D_i if stuck) and the acceleration of O1 in
    the co-rotating axes, for rotating-frame states ``yr`` at times ``t``."""
    from rotorlab._kernels.jeffcott_balls import stick_torques

    n = model.n_balls
    flat = np.ascontiguousarray(yr.reshape(-1, yr.shape[-1]))
    tt = np.broadcast_to(t, yr.shape[:-1]).reshape(-1)
    p = model.to_array()
    torque = np.zeros((flat.shape[0], n))
    acc = np.zeros((flat.shape[0], 2))
    f_l = np.array([b.friction * b.radius for b in model.balls])
    drive, bound, out = np.empty(n), np.empty(n), np.empty(2 + n)
    for j in range(flat.shape[0]):
        stick_torques(float(tt[j]), flat[j], p, True, -1, drive, bound, out)
        acc[j] = out[:2]
        if model.has_friction:
            mode = flat[j, 4 + 2 * n :]
            stuck = (mode == 0.0) & (f_l > 0.0)
            torque[j] = np.where(stuck, -drive, -mode * f_l * out[2:])
    shape = yr.shape[:-1]
    return torque.reshape(shape + (n,)), acc.reshape(shape + (2,))


def hamiltonian_rate(model, y, t=0.0):
    """Return sum_i q_i' Q_i, the power of the non-conservative forces in the rotating frame.

    At constant speed this is dH*/dt along trajectories:
    ``-d [u'(u' - Omega v) + v'(v' + Omega u)] - sum_i b_i psi_i'^2 + sum_i T_i psi_i'`` (W),
    equal to -2 Phi when d = 0 and there is no Coulomb friction.

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (2), (5) (corrected, see the model's docstring).
    """
    yr, om, u, v, du, dv, psi, dpsi, (_, _, _, b, _) = _rotating_parts(model, y, t)
    d = model.rotor.damping
    power = -d * (du * (du - om * v) + dv * (dv + om * u)) - np.sum(b * dpsi**2, axis=-1)
    if model.has_friction:
        torque, _ = _friction_torques(model, yr, np.broadcast_to(np.asarray(t, float), yr.shape[:-1]))
        power = power + np.sum(torque * dpsi, axis=-1)
    return power


def drive_torque(model, t, y):
    """Return the torque the drive must apply to the disc to keep the prescribed spin.

    Parameters
    ----------
    model : JeffcottBalls
    t : float or array_like, shape (...)
        Times (s).
    y : array_like, shape (..., n_state)
        States in the model's frame.

    Returns
    -------
    ndarray, shape (...)
        ``tau = M1 e (-x'' sin theta + y'' cos theta) + M1 e^2 theta'' - sum_i b_i (phi_i' -
        theta') + sum_i T_i`` (N m), T_i the Coulomb torque on ball i (for a stuck ball the
        holding torque -D_i). The disc's own ``J_C theta''`` is left out, as in :func:`energy`.
        Power balance: ``dE/dt = theta' tau - 2 Phi + sum_i T_i psi_i'``.
    """
    yr, t, th, om, dom = _in_frame(model, y, t, "rotating")
    n = model.n_balls
    r = model.rotor
    m, l, J, b, f = _ball_arrays(model)
    dpsi = np.where(_stuck_mask(model, yr), 0.0, yr[..., 4 + n : 4 + 2 * n])
    torque, acc = _friction_torques(model, yr, t)
    # acc is the absolute acceleration of O1 in the co-rotating axes: (a . e_V) = ay
    viscous = -np.sum(b * dpsi, axis=-1)  # minus the generalized viscous force on theta
    return r.imbalance * (acc[..., 1] + r.eccentricity * dom) + viscous + np.sum(torque, axis=-1)


@dataclass(frozen=True)
class Linearization:
    """Linearized motion about a steady motion, co-rotating frame, constant speed.

    Attributes
    ----------
    A : ndarray, shape (n_state, n_state)
        First-order Jacobian: ``dy'/dy``.
    M, C, G, K : ndarray, shape (2 + n, 2 + n)
        ``M q'' + (C + G) q' + K q = 0`` for ``q = (u, v, psi_1..psi_n)``: mass matrix (kg, kg m,
        kg m^2), damping (symmetric), gyroscopic (skew), stiffness (Hessian of H~* plus the
        circulatory part ``d Omega [[0, -1], [1, 0]]`` of the external damping).
    spin_speed : float
        Omega (rad/s).
    residual : ndarray, shape (n_state,)
        dy/dt at the given state with zero velocities (zero at an equilibrium).
    """

    A: np.ndarray
    M: np.ndarray
    C: np.ndarray
    G: np.ndarray
    K: np.ndarray
    spin_speed: float
    residual: np.ndarray

    @property
    def eigenvalues(self) -> np.ndarray:
        """Eigenvalues of A (1/s)."""
        return np.linalg.eigvals(self.A)


def linearize(model, y_eq, spin_speed=None) -> Linearization:
    """Linearize the co-rotating-frame equations about a state with zero velocities.

    Parameters
    ----------
    model : JeffcottBalls
        Without Coulomb friction.
    y_eq : array_like, shape (n_state,)
        Co-rotating-frame state ``[u, v, 0, 0, psi_i, 0]`` (whatever ``model.frame``); its velocity
        entries are taken as zero.
    spin_speed : float, optional
        Constant Omega (rad/s); required unless the speed profile is constant.

    Returns
    -------
    Linearization

    Notes
    -----
    ``M = [[M, 0, -m_i l_i s_i], [0, M, m_i l_i c_i], [., ., diag J_i]]``;
    ``G[v,u] = 2 M Omega``, ``G[psi_i,u] = 2 Omega m_i l_i c_i``, ``G[psi_i,v] = 2 Omega m_i l_i
    s_i`` (skew); ``C = diag(d, d, b_i)``; ``K`` = Hessian of H~* (``c - M Omega^2`` on u, v;
    ``Omega^2 m_i l_i s_i``, ``-Omega^2 m_i l_i c_i`` on (u, psi_i), (v, psi_i);
    ``Omega^2 m_i l_i (u c_i + v s_i)`` on psi_i) + circulatory part, + ``(dM/dq_k) q''`` when
    the state is not an equilibrium. ``A = [[0, I], [-M^-1 K, -M^-1 (C + G)]]``.

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (9)-(11).
    """
    from rotorlab.models._speed import ConstantSpeed

    if model.has_friction:
        raise ValueError("linearize needs a model without Coulomb friction (set friction=0)")
    if spin_speed is None:
        if not isinstance(model.speed, ConstantSpeed):
            raise ValueError("spin_speed must be given when the speed profile is not constant")
        spin_speed = model.speed.speed
    om = float(spin_speed)
    n = model.n_balls
    rot = model.with_frame("rotating").with_speed(ConstantSpeed(om))
    y = np.array(y_eq, dtype=float).reshape(-1)
    if y.size != rot.n_state:
        raise ValueError(f"y_eq must have {rot.n_state} entries, got {y.size}")
    y[2:4] = 0.0
    y[4 + n :] = 0.0
    acc = rot.rhs(0.0, y)
    m, l, J, b, _ = _ball_arrays(model)
    ml = m * l
    u, v = y[0], y[1]
    s, c = np.sin(y[4 : 4 + n]), np.cos(y[4 : 4 + n])
    big_m = model.total_mass
    d = model.rotor.damping
    k = 2 + n
    M = np.zeros((k, k))
    M[0, 0] = M[1, 1] = big_m
    M[0, 2:] = M[2:, 0] = -ml * s
    M[1, 2:] = M[2:, 1] = ml * c
    M[2:, 2:] = np.diag(J)
    G = np.zeros((k, k))
    G[1, 0], G[0, 1] = 2.0 * big_m * om, -2.0 * big_m * om
    G[2:, 0], G[0, 2:] = 2.0 * om * ml * c, -2.0 * om * ml * c
    G[2:, 1], G[1, 2:] = 2.0 * om * ml * s, -2.0 * om * ml * s
    C = np.diag(np.concatenate([[d, d], b]))
    K = np.zeros((k, k))
    K[0, 0] = K[1, 1] = model.rotor.stiffness - big_m * om * om
    K[0, 2:] = K[2:, 0] = om * om * ml * s
    K[1, 2:] = K[2:, 1] = -om * om * ml * c
    K[2:, 2:] = np.diag(om * om * ml * (u * c + v * s))
    K[0, 1] -= d * om
    K[1, 0] += d * om
    qdd = np.concatenate([acc[2:4], acc[4 + n :]])
    K[0, 2:] += -ml * c * qdd[2:]
    K[1, 2:] += -ml * s * qdd[2:]
    K[2:, 2:] += np.diag(-ml * (c * qdd[0] + s * qdd[1]))
    Minv = np.linalg.inv(M)
    iq = np.concatenate([[0, 1], 4 + np.arange(n)])  # state indices of q = (u, v, psi_i)
    iv = np.concatenate([[2, 3], 4 + n + np.arange(n)])  # and of q'
    A = np.zeros((2 * k, 2 * k))
    A[np.ix_(iq, iv)] = np.eye(k)
    A[np.ix_(iv, iq)] = -Minv @ K
    A[np.ix_(iv, iv)] = -Minv @ (C + G)
    return Linearization(A=A, M=M, C=C, G=G, K=K, spin_speed=om, residual=acc)
