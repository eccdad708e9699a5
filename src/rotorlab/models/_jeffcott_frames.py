"""Fixed and co-rotating coordinates of the Jeffcott rotor with balls (model ``jeffcott_balls``).

The rotating frame turns with the spin angle theta(t): x + i y = e^{i theta} (u + i v) for the
disc centre and phi_i = theta + psi_i for ball i (see :mod:`rotorlab.models._jeffcott_balls`).
Extra entries after the balls (friction modes) are copied unchanged.

Examples
--------
>>> import numpy as np
>>> y = np.array([1e-3, 0.0, 0.0, 0.0, 0.5, 0.0])
>>> back = fixed_to_rotating(0.3, 10.0, rotating_to_fixed(0.3, 10.0, y, 1), 1)
>>> bool(np.allclose(back, y))
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["fixed_to_rotating", "rotating_to_fixed"]


def rotating_to_fixed(theta, omega, y, n_balls: int) -> np.ndarray:
    """Convert rotating-frame states to the fixed frame.

    Parameters
    ----------
    theta, omega : float or array_like, shape (...)
        Spin angle (rad) and speed (rad/s) at the states' times.
    y : array_like, shape (..., n_state)
        ``[u, v, du, dv, psi_i, dpsi_i, (modes)]`` (m, m/s, rad, rad/s).
    n_balls : int

    Returns
    -------
    ndarray, shape (..., n_state)
        ``[x, y, vx, vy, phi_i, w_i, (modes)]``.
    """
    y = np.asarray(y, dtype=float)
    th = np.asarray(theta, dtype=float)
    om = np.asarray(omega, dtype=float)
    c, s = np.cos(th), np.sin(th)
    u, v, du, dv = (y[..., k] for k in range(4))
    a = du - om * v
    b = dv + om * u
    out = np.array(y, copy=True)
    out[..., 0] = c * u - s * v
    out[..., 1] = s * u + c * v
    out[..., 2] = c * a - s * b
    out[..., 3] = s * a + c * b
    n = n_balls
    out[..., 4 : 4 + n] = y[..., 4 : 4 + n] + th[..., None]
    out[..., 4 + n : 4 + 2 * n] = y[..., 4 + n : 4 + 2 * n] + om[..., None]
    return out


def fixed_to_rotating(theta, omega, y, n_balls: int) -> np.ndarray:
    """Convert fixed-frame states to the co-rotating frame (inverse of :func:`rotating_to_fixed`).

    Parameters
    ----------
    theta, omega : float or array_like, shape (...)
        Spin angle (rad) and speed (rad/s) at the states' times.
    y : array_like, shape (..., n_state)
        ``[x, y, vx, vy, phi_i, w_i, (modes)]``.
    n_balls : int

    Returns
    -------
    ndarray, shape (..., n_state)
        ``[u, v, du, dv, psi_i, dpsi_i, (modes)]``; the angles psi_i = phi_i - theta are not
        wrapped.
    """
    y = np.asarray(y, dtype=float)
    th = np.asarray(theta, dtype=float)
    om = np.asarray(omega, dtype=float)
    c, s = np.cos(th), np.sin(th)
    x, yy, vx, vy = (y[..., k] for k in range(4))
    out = np.array(y, copy=True)
    u = c * x + s * yy
    v = -s * x + c * yy
    out[..., 0] = u
    out[..., 1] = v
    out[..., 2] = c * vx + s * vy + om * v
    out[..., 3] = -s * vx + c * vy - om * u
    n = n_balls
    out[..., 4 : 4 + n] = y[..., 4 : 4 + n] - th[..., None]
    out[..., 4 + n : 4 + 2 * n] = y[..., 4 + n : 4 + 2 * n] - om[..., None]
    return out
