"""Compiled kernels of one ball rolling in a toroidal balancer body (model ``toroidal_ball``).

Physics, conventions and the comparison with the printed equations are documented in
:mod:`rotorlab.models._toroidal_ball`; this module is the allocation-free numerics.

Packed parameters ``p`` (float64, length ``P_SIZE`` = 14)
---------------------------------------------------------
=========  ======================================================================================
``p[0]``   R, radius of the torus' centre line (m)
``p[1]``   R1, radius of the tube's cross-section (m)
``p[2]``   r, ball radius (m)
``p[3]``   omega, spin speed of the body (rad/s)
``p[4]``   e, offset of the torus axis from the rotation axis, towards psi = pi (m)
``p[5]``   k, rolling-friction coefficient (lever arm of the rolling resistance, m)
``p[6]``   g, gravitational acceleration along -z (m/s^2)
``p[7]``   c_rho: 1 -> ring radius of the ball centre rho = R + a sin(alpha); 0 -> rho = R
``p[8]``   c_rel: coefficient of the relative (psi', alpha') inertial terms
``p[9]``   c_cor: coefficient of the Coriolis-type terms omega psi', omega alpha'
``p[10]``  c_nrm: 1 -> the offset term -e omega^2 sin(alpha) cos(psi) is in N; 0 -> it is not
``p[11]``  f_alpha: factor on the cross-section rolling resistance (1 derived, R1 / a printed)
``p[12]``  1 / a (derived, 1/m)
``p[13]``  5/7 k / r (derived, 1)
=========  ======================================================================================

``a = R1 - r`` is the radius of the circle the ball centre describes in the cross-section.
The two forms of the model differ only in ``p[7:12]`` (see the model module):
``rolling`` = (1, 1, 12/7, 1, 1), ``paper`` = (0, 5/7, 10/7, 0, R1/a).

State ``y`` (length 7, the last three discrete)
-----------------------------------------------
``[psi, alpha, dpsi, dalpha, mode_psi, mode_alpha, t_switch]``: ring angle and cross-section
angle of the ball centre relative to the body (rad), their rates (rad/s), the rolling modes
(+1 / -1 rolling with positive / negative rate, 0 stuck: no rolling relative to the body in that
direction) and the time of the last stick/slip transition (s, set by the reset map).

Equations (per unit mass, s = sign)
-----------------------------------
::

    rho    = R + c_rho a sin(alpha)
    N      = g cos(alpha) + rho (omega + psi')^2 sin(alpha) + a alpha'^2
             - c_nrm e omega^2 sin(alpha) cos(psi)                                  (m/s^2)
    F_psi  = -(a cos(alpha) / rho) alpha' (2 c_rel psi' + c_cor omega)
             + (5/7) (e omega^2 / rho) sin(psi)
    F_alp  = (rho cos(alpha) / a) (c_rel psi'^2 + c_cor omega psi' + (5/7) omega^2)
             - (5/7) (e omega^2 / a) cos(alpha) cos(psi) - (5/7) (g / a) sin(alpha)
    B_psi  = (5/7) k max(N, 0) / (rho r)
    B_alp  = (5/7) k max(N, 0) f_alpha / (a r)
    psi''  = F_psi - B_psi mode_psi      (rolling)     psi'' = 0, psi' = 0      (stuck)
    alpha''= F_alp - B_alp mode_alpha    (rolling)     alpha''= 0, alpha' = 0   (stuck)

Stick/slip
----------
Events (direction -1): ``0 stick_psi`` g = psi' mode_psi while rolling (1.0 while stuck);
``1 slip_psi`` g = B_psi - |F_psi| while stuck (1.0 while rolling); ``2 stick_alpha`` and
``3 slip_alpha`` likewise; ``4 lift_off`` g = N (counted only: the model assumes contact).
Sines and cosines come from :func:`rotorlab._kernels._vmath.sincos` and there is no loop, so the
right-hand side is lane-friendly (it vectorises in the lane driver, see
``tests/unit/test_vectorise.py``; the stuck/rolling choices are selects). ``sincos`` uses no fused
multiply-add, so the scalar and the lane driver and any thread count give the same bits
(``tests/unit/test_lanes_events.py``).
The reset sets the rate exactly to zero and sticks when ``|F| <= B`` (evaluated at zero rate),
else rolls with ``mode = sign(F)``; leaving stick (``slip_*``) always rolls with ``sign(F)``. It
writes the event time into ``t_switch``. Because the mass matrix is diagonal, the holding force
of one direction does not depend on the acceleration of the other.
"""

from numba import njit

from rotorlab._kernels._vmath import sincos


__all__ = [
    "P_R", "P_R1", "P_RB", "P_OMEGA", "P_E", "P_K", "P_G", "P_CRHO", "P_CREL", "P_CCOR",
    "P_CNRM", "P_FALPHA", "P_INV_A", "P_KR", "P_SIZE", "N_STATE", "N_DISCRETE", "I_PSI", "I_ALPHA", "I_DPSI",
    "I_DALPHA", "I_MPSI", "I_MALPHA", "I_TSWITCH", "rhs", "events", "reset", "forces",
]  # fmt: skip

P_R = 0
P_R1 = 1
P_RB = 2
P_OMEGA = 3
P_E = 4
P_K = 5
P_G = 6
P_CRHO = 7
P_CREL = 8
P_CCOR = 9
P_CNRM = 10
P_FALPHA = 11
P_INV_A = 12
P_KR = 13
P_SIZE = 14

I_PSI = 0
I_ALPHA = 1
I_DPSI = 2
I_DALPHA = 3
I_MPSI = 4
I_MALPHA = 5
I_TSWITCH = 6
N_STATE = 7
N_DISCRETE = 3

_FIVE_SEVENTHS = 5.0 / 7.0


@njit(cache=True, nogil=True, inline="always")
def _terms(psi, alpha, dpsi, dalpha, p):
    """Return ``(F_psi, F_alpha, B_psi, B_alpha, N)`` at one state (see the module docstring)."""
    om = p[P_OMEGA]
    a = p[P_R1] - p[P_RB]
    inv_a = p[P_INV_A]
    sa, ca = sincos(alpha)
    sp, cp = sincos(psi)
    rho = p[P_R] + p[P_CRHO] * a * sa
    inv_rho = 1.0 / rho
    w = om + dpsi
    eo2 = p[P_E] * om * om
    normal = p[P_G] * ca + rho * w * w * sa + a * dalpha * dalpha - p[P_CNRM] * eo2 * sa * cp
    f_psi = (_FIVE_SEVENTHS * eo2 * sp - a * ca * dalpha * (2.0 * p[P_CREL] * dpsi + p[P_CCOR] * om)) * inv_rho
    f_alpha = (rho * ca * (p[P_CREL] * dpsi * dpsi + p[P_CCOR] * om * dpsi + _FIVE_SEVENTHS * om * om)
               - _FIVE_SEVENTHS * (eo2 * ca * cp + p[P_G] * sa)) * inv_a  # fmt: skip
    nk = p[P_KR] * (0.0 if normal <= 0.0 else normal)  # max(normal, 0), NaN kept, as a select
    return f_psi, f_alpha, nk * inv_rho, nk * p[P_FALPHA] * inv_a, normal


@njit(cache=True, nogil=True)
def forces(y, p, out):
    """Write ``[F_psi, F_alpha, B_psi, B_alpha, N]`` at state ``y`` into ``out`` (shape (5,)).

    The rates of stuck directions are taken as zero whatever ``y`` holds.
    """
    dpsi = 0.0 if y[I_MPSI] == 0.0 else y[I_DPSI]
    dalpha = 0.0 if y[I_MALPHA] == 0.0 else y[I_DALPHA]
    f_psi, f_alpha, b_psi, b_alpha, normal = _terms(y[I_PSI], y[I_ALPHA], dpsi, dalpha, p)
    out[0] = f_psi
    out[1] = f_alpha
    out[2] = b_psi
    out[3] = b_alpha
    out[4] = normal


@njit(cache=True, nogil=True)
def rhs(t, y, p, out):
    """dy/dt of the toroidal ball (rolling resistance as stick/slip modes)."""
    m_psi = y[I_MPSI]
    m_alpha = y[I_MALPHA]
    dpsi = 0.0 if m_psi == 0.0 else y[I_DPSI]
    dalpha = 0.0 if m_alpha == 0.0 else y[I_DALPHA]
    f_psi, f_alpha, b_psi, b_alpha, _ = _terms(y[I_PSI], y[I_ALPHA], dpsi, dalpha, p)
    out[I_PSI] = dpsi
    out[I_ALPHA] = dalpha
    out[I_DPSI] = 0.0 if m_psi == 0.0 else f_psi - b_psi * m_psi
    out[I_DALPHA] = 0.0 if m_alpha == 0.0 else f_alpha - b_alpha * m_alpha
    out[I_MPSI] = 0.0
    out[I_MALPHA] = 0.0
    out[I_TSWITCH] = 0.0


@njit(cache=True, nogil=True)
def events(t, y, p, g):
    """Event functions: stick_psi, slip_psi, stick_alpha, slip_alpha, lift_off."""
    m_psi = y[I_MPSI]
    m_alpha = y[I_MALPHA]
    dpsi = 0.0 if m_psi == 0.0 else y[I_DPSI]
    dalpha = 0.0 if m_alpha == 0.0 else y[I_DALPHA]
    f_psi, f_alpha, b_psi, b_alpha, normal = _terms(y[I_PSI], y[I_ALPHA], dpsi, dalpha, p)
    # selects, not branches: the lane driver evaluates this for all lanes in one vector loop
    g[0] = 1.0 if m_psi == 0.0 else dpsi * m_psi
    g[1] = b_psi - abs(f_psi) if m_psi == 0.0 else 1.0
    g[2] = 1.0 if m_alpha == 0.0 else dalpha * m_alpha
    g[3] = b_alpha - abs(f_alpha) if m_alpha == 0.0 else 1.0
    g[4] = normal


@njit(cache=True, nogil=True)
def reset(k, t, y, p, y_new):
    """Stick/slip switch of one direction (``k`` = 0..3); ``lift_off`` (4) changes nothing."""
    for i in range(y.shape[0]):
        y_new[i] = y[i]
    if k >= 4:
        return 0
    if k < 2:
        i_rate = I_DPSI
        i_mode = I_MPSI
    else:
        i_rate = I_DALPHA
        i_mode = I_MALPHA
    y_new[i_rate] = 0.0
    y_new[i_mode] = 0.0
    dpsi = 0.0 if y_new[I_MPSI] == 0.0 else y_new[I_DPSI]
    dalpha = 0.0 if y_new[I_MALPHA] == 0.0 else y_new[I_DALPHA]
    f_psi, f_alpha, b_psi, b_alpha, _ = _terms(y_new[I_PSI], y_new[I_ALPHA], dpsi, dalpha, p)
    drive = f_psi if k < 2 else f_alpha
    bound = b_psi if k < 2 else b_alpha
    if k % 2 == 1 or abs(drive) > bound:
        # break-away (k odd): the drive is reaching the bound and will exceed it, so roll
        # whatever round-off says at the located zero; a stop with |drive| > bound reverses
        y_new[i_mode] = 1.0 if drive > 0.0 else -1.0
    y_new[I_TSWITCH] = t
    return 0
