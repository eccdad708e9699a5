"""Compiled kernels of the planar Jeffcott rotor with n balls or pendulums (``jeffcott_balls``).

Physics and conventions are documented in :mod:`rotorlab.models._jeffcott_balls`; this module is
the allocation-free numerics. The model simulates in both frames on its preset machine's
generated kernels (:mod:`rotorlab.models._jeffcott_machine`); of this module the package runs only
:func:`stick_torques` (the friction helpers of the model). The kernels stay as the tests' oracle
(``tests/unit/test_jeffcott_machine.py``) and the baseline of ``bench/machine.py`` and
``bench/corotating.py``.

Packed parameters ``p`` (float64, length ``12 + 6 n``)
------------------------------------------------------
======================  =========================================================================
``p[0]``                n, number of balls (stored as float)
``p[1]``                1.0 if the state carries n stick/slip modes (any f_i > 0), else 0.0
``p[2]``                M1, disc mass (kg)
``p[3]``                e, eccentricity of the disc's mass centre (m)
``p[4]``                c, lateral shaft stiffness (N/m)
``p[5]``                d, external viscous damping on the disc centre (N s/m)
``p[6:12]``             speed profile block (:mod:`rotorlab._kernels.speed`)
``p[12 + 6 i + 0..4]``  ball i: m_i (kg), l_i (m), J_i (kg m^2), b_i (N m s/rad), f_i (1)
``p[12 + 6 i + 5]``     1 / J_i (1/(kg m^2)), derived: the kernels multiply by it (a division
                        per use measured 7 % of the lane driver's time on the two-ball sweep)
======================  =========================================================================

States
------
fixed frame     ``[x, y, vx, vy, phi_1..phi_n, w_1..w_n, (mode_1..mode_n)]``
rotating frame  ``[u, v, du, dv, psi_1..psi_n, dpsi_1..dpsi_n, (mode_1..mode_n)]``, with
                ``x + i y = e^(i theta) (u + i v)`` and ``phi_i = theta + psi_i``.

Solution of the (2+n)x(2+n) mass-matrix system (O(n), no allocation)
--------------------------------------------------------------------
All dynamics are written in "working axes" (the fixed axes, or the co-rotating axes U, V, in
which the absolute acceleration of O1 has components ``a = (ax, ay)``; the equations are
covariant under the rotation, with ball angles ``alpha_i = phi_i`` or ``psi_i`` and the
unbalance along ``(cos theta, sin theta)`` or ``(1, 0)``). A free ball obeys

    J_i alpha_i'' = g0_i + A_i ax + B_i ay,
    A_i = m_i l_i s_i + kap_i c_i,  B_i = -m_i l_i c_i + kap_i s_i,

with ``g0_i = -b_i (w_i - Omega) - sigma_i f_i m_i l_i^2 w_i^2`` and ``kap_i = sigma_i f_i m_i l_i``
(``sigma_i`` = slip mode; the friction terms come from the normal force
``N_i = m_i (l_i w_i^2 - ax c_i - ay s_i)``, linear in ``a``). A stuck ball has
``alpha_i'' = Omega'`` and ``w_i = Omega``. Substituting into the rotor equations
``M a = F + sum_i m_i l_i (alpha_i'' (s_i, -c_i) + w_i^2 (c_i, s_i))`` gives the 2x2 system

    [M - sum q_i s_i A_i     -sum q_i s_i B_i ] [ax]   [Fx + sum m_i l_i w_i^2 c_i + sum q_i s_i g0_i]
    [  sum q_i c_i A_i     M + sum q_i c_i B_i] [ay] = [Fy + sum m_i l_i w_i^2 s_i - sum q_i c_i g0_i]

(sums over free balls, ``q_i = m_i l_i / J_i``; stuck balls add ``m_i l_i Omega' (s_i, -c_i)`` to
the right side), solved by Cramer's rule; then each ``alpha_i''`` follows. The sines and cosines
of the first pass are parked in the output array (scratch) so the second pass reuses them.
Without modes (``p[1] == 0``) a lean path with the same equations (kap_i = 0, symmetric 2x2)
runs, within about 1.25x of the hand-written two-ball benchmark RHS. Helpers are inlined
(``inline="always"``) so that no array crosses a call boundary inside a kernel.

Stick/slip (when ``p[1] == 1``)
-------------------------------
``mode_i``: -1 / +1 slipping with negative / positive relative velocity, 0 stuck. Balls with
``f_i == 0`` are always free (their mode is ignored). For a stuck ball the *driving torque*
``D_i = m_i l_i (ax s_i - ay c_i) - J_i Omega'`` is what the race must hold (the holding torque on
the ball is ``-D_i``), and the bound is ``f_i l_i N_i``. Event functions (``2 i``: ``stick_i``,
``2 i + 1``: ``slip_i``, direction -1): slipping: ``g = (w_i - Omega) mode_i`` and 1.0; stuck: 1.0
and ``g = f_i l_i N_i - |D_i|``. The reset sticks when ``|D_i| <= f_i l_i N_i`` (computed with the
ball stuck), else slips with ``mode_i = sign(D_i)``; leaving stick slips with ``sign(D_i)``; the
relative velocity is set exactly to zero in both cases.
"""


from numba import njit

from rotorlab._kernels._vmath import sincos
from rotorlab._kernels.speed import profile, profile_arithmetic, profile_constant

__all__ = [
    "P_N",
    "P_MODES",
    "P_M1",
    "P_E",
    "P_C",
    "P_D",
    "P_SPEED",
    "P_BALLS",
    "BALL_STRIDE",
    "rhs_fixed",
    "rhs_rotating",
    "rhs_fixed_free",
    "rhs_rotating_free",
    "rhs_fixed_constant",
    "rhs_rotating_constant",
    "events_fixed",
    "events_rotating",
    "reset_fixed",
    "reset_rotating",
    "stick_torques",
]

P_N = 0
P_MODES = 1
P_M1 = 2
P_E = 3
P_C = 4
P_D = 5
P_SPEED = 6
P_BALLS = 12
BALL_STRIDE = 6
B_M = 0
B_L = 1
B_J = 2
B_B = 3
B_F = 4
B_IJ = 5  # 1 / J, derived by the model's to_array

# the speed profiles a lane-friendly kernel computes (_rhs_free's literal ``speed``)
SPEED_ANY = 0
SPEED_ARITHMETIC = 1
SPEED_CONSTANT = 2

# state layout
I_X = 0
I_Y = 1
I_VX = 2
I_VY = 3
I_ANGLE = 4


@njit(cache=True, nogil=True, inline="always")
def _free_coefficients(k, rel, w, s, c, mode, p, has_modes):
    """Return ``(g0, A, B)`` of a free ball whose parameter block starts at ``p[k]``."""
    m = p[k + B_M]
    ml = m * p[k + B_L]
    g0 = -p[k + B_B] * rel
    kap = 0.0
    f = p[k + B_F]
    if has_modes and f > 0.0:
        # slip: torque -mode f l N with N = m (l w^2 - ax c - ay s)
        sig = mode
        g0 -= sig * f * ml * p[k + B_L] * w * w
        kap = sig * f * ml
    return g0, ml * s + kap * c, -ml * c + kap * s


@njit(cache=True, nogil=True, inline="always")
def _is_stuck(k, mode, has_modes, p):
    return has_modes and p[k + B_F] > 0.0 and mode == 0.0


@njit(cache=True, nogil=True, inline="always")
def _solve(t, y, p, rotating, forced, scr, ks, kc, stride):
    """Solve for the absolute acceleration of O1 in working axes.

    ``forced`` is a ball index treated as stuck regardless of its mode (-1: none). ``sin`` and
    ``cos`` of ball i are written to ``scr[ks + stride i]`` and ``scr[kc + stride i]``.

    Returns ``(ax, ay, theta, omega, domega)``.
    """
    n = int(p[P_N])
    has_modes = p[P_MODES] != 0.0
    theta, om, dom = profile(t, p, P_SPEED)
    m1e = p[P_M1] * p[P_E]
    cst = p[P_C]
    dmp = p[P_D]
    if rotating:
        X = y[I_X]
        Y = y[I_Y]
        VX = y[I_VX] - om * Y
        VY = y[I_VY] + om * X
        cu = 1.0
        su = 0.0
    else:
        X = y[I_X]
        Y = y[I_Y]
        VX = y[I_VX]
        VY = y[I_VY]
        su, cu = sincos(theta)
    rx = m1e * (om * om * cu + dom * su) - cst * X - dmp * VX
    ry = m1e * (om * om * su - dom * cu) - cst * Y - dmp * VY
    mass = p[P_M1]
    for i in range(n):
        mass += p[P_BALLS + BALL_STRIDE * i + B_M]
    a11 = mass
    a12 = 0.0
    a21 = 0.0
    a22 = mass
    for i in range(n):
        k = P_BALLS + BALL_STRIDE * i
        ang = y[I_ANGLE + i]
        rate = y[I_ANGLE + n + i]
        s, c = sincos(ang)
        scr[ks + stride * i] = s
        scr[kc + stride * i] = c
        mode = y[I_ANGLE + 2 * n + i] if has_modes else 1.0
        ml = p[k + B_M] * p[k + B_L]
        if i == forced or _is_stuck(k, mode, has_modes, p):
            rx += ml * (om * om * c + dom * s)
            ry += ml * (om * om * s - dom * c)
            continue
        w = rate + om if rotating else rate
        rel = rate if rotating else rate - om
        g0, A, B = _free_coefficients(k, rel, w, s, c, mode, p, has_modes)
        q = ml * p[k + B_IJ]
        a11 -= q * s * A
        a12 -= q * s * B
        a21 += q * c * A
        a22 += q * c * B
        rx += ml * w * w * c + q * s * g0
        ry += ml * w * w * s - q * c * g0
    inv_det = 1.0 / (a11 * a22 - a12 * a21)
    ax = (a22 * rx - a12 * ry) * inv_det
    ay = (a11 * ry - a21 * rx) * inv_det
    return ax, ay, theta, om, dom


@njit(cache=True, nogil=True, inline="always")
def _drive_and_bound(k, s, c, ax, ay, om, dom, p):
    """Driving torque D (N m) on a stuck ball and the friction bound f l N (N m)."""
    m = p[k + B_M]
    l = p[k + B_L]
    drive = m * l * (ax * s - ay * c) - p[k + B_J] * dom
    bound = p[k + B_F] * l * m * (l * om * om - ax * c - ay * s)
    return drive, bound


@njit(cache=True, nogil=True, inline="always")
def _rhs(t, y, p, out, rotating):
    n = int(p[P_N])
    has_modes = p[P_MODES] != 0.0
    ax, ay, theta, om, dom = _solve(t, y, p, rotating, -1, out, I_ANGLE, I_ANGLE + n, 1)
    out[I_X] = y[I_VX]
    out[I_Y] = y[I_VY]
    if rotating:
        out[I_VX] = ax + 2.0 * om * y[I_VY] + dom * y[I_Y] + om * om * y[I_X]
        out[I_VY] = ay - 2.0 * om * y[I_VX] - dom * y[I_X] + om * om * y[I_Y]
    else:
        out[I_VX] = ax
        out[I_VY] = ay
    for i in range(n):
        k = P_BALLS + BALL_STRIDE * i
        s = out[I_ANGLE + i]
        c = out[I_ANGLE + n + i]
        rate = y[I_ANGLE + n + i]
        mode = 1.0
        if has_modes:
            mode = y[I_ANGLE + 2 * n + i]
            out[I_ANGLE + 2 * n + i] = 0.0
        if _is_stuck(k, mode, has_modes, p):
            if rotating:
                out[I_ANGLE + i] = 0.0
                out[I_ANGLE + n + i] = 0.0
            else:
                out[I_ANGLE + i] = om
                out[I_ANGLE + n + i] = dom
            continue
        w = rate + om if rotating else rate
        rel = rate if rotating else rate - om
        g0, A, B = _free_coefficients(k, rel, w, s, c, mode, p, has_modes)
        acc = (g0 + A * ax + B * ay) * p[k + B_IJ]
        out[I_ANGLE + i] = rate
        out[I_ANGLE + n + i] = acc - dom if rotating else acc


@njit(cache=True, nogil=True, inline="always")
def _rhs_free(t, y, p, out, rotating, speed):
    """Right-hand side without stick/slip modes (the common, fast path; same equations).

    The ball count is taken from the state's length (``4 + 2 n``), which the lane driver makes a
    compile-time constant: its loops over the balls then unroll and the loop over lanes
    vectorises. ``speed`` (a literal) is the speed profiles the kernel computes: ``SPEED_ANY``
    (:func:`profile`), ``SPEED_ARITHMETIC`` (constant or ramp, no library call,
    :func:`profile_arithmetic`) or ``SPEED_CONSTANT`` (:func:`profile_constant`); a kind
    outside them gives NaN.
    """
    n = (y.shape[0] - 4) // 2
    if speed == SPEED_CONSTANT:
        theta, om, dom = profile_constant(t, p, P_SPEED)
    elif speed == SPEED_ARITHMETIC:
        theta, om, dom = profile_arithmetic(t, p, P_SPEED)
    else:
        theta, om, dom = profile(t, p, P_SPEED)
    m1e = p[P_M1] * p[P_E]
    X = y[I_X]
    Y = y[I_Y]
    if rotating:
        VX = y[I_VX] - om * Y
        VY = y[I_VY] + om * X
        cu = 1.0
        su = 0.0
    else:
        VX = y[I_VX]
        VY = y[I_VY]
        su, cu = sincos(theta)
    rx = m1e * (om * om * cu + dom * su) - p[P_C] * X - p[P_D] * VX
    ry = m1e * (om * om * su - dom * cu) - p[P_C] * Y - p[P_D] * VY
    mass = p[P_M1]
    sss = 0.0  # sums of q_i m_i l_i s_i^2, ... (the 2x2 system of the module docstring)
    ssc = 0.0
    scc = 0.0
    for i in range(n):
        k = P_BALLS + BALL_STRIDE * i
        m = p[k + B_M]
        ml = m * p[k + B_L]
        mass += m
        rate = y[I_ANGLE + n + i]
        s, c = sincos(y[I_ANGLE + i])
        out[I_ANGLE + i] = s
        out[I_ANGLE + n + i] = c
        w = rate + om if rotating else rate
        g0 = -p[k + B_B] * (rate if rotating else rate - om)
        q = ml * p[k + B_IJ]
        qs = q * s
        qc = q * c
        sss += qs * ml * s
        ssc += qs * ml * c
        scc += qc * ml * c
        mw2 = ml * w * w
        rx += mw2 * c + qs * g0
        ry += mw2 * s - qc * g0
    a11 = mass - sss
    a22 = mass - scc
    inv_det = 1.0 / (a11 * a22 - ssc * ssc)
    ax = (a22 * rx - ssc * ry) * inv_det
    ay = (a11 * ry - ssc * rx) * inv_det
    out[I_X] = y[I_VX]
    out[I_Y] = y[I_VY]
    if rotating:
        out[I_VX] = ax + 2.0 * om * y[I_VY] + dom * y[I_Y] + om * om * y[I_X]
        out[I_VY] = ay - 2.0 * om * y[I_VX] - dom * y[I_X] + om * om * y[I_Y]
    else:
        out[I_VX] = ax
        out[I_VY] = ay
    for i in range(n):
        k = P_BALLS + BALL_STRIDE * i
        s = out[I_ANGLE + i]
        c = out[I_ANGLE + n + i]
        rate = y[I_ANGLE + n + i]
        ml = p[k + B_M] * p[k + B_L]
        g0 = -p[k + B_B] * (rate if rotating else rate - om)
        acc = (g0 + ml * (ax * s - ay * c)) * p[k + B_IJ]
        out[I_ANGLE + i] = rate
        out[I_ANGLE + n + i] = acc - dom if rotating else acc


@njit(cache=True, nogil=True, fastmath=False)
def rhs_fixed(t, y, p, out):
    """Right-hand side in the fixed frame (see the module docstring for y and p)."""
    if p[P_MODES] != 0.0:
        _rhs(t, y, p, out, False)
    else:
        _rhs_free(t, y, p, out, False, SPEED_ANY)


@njit(cache=True, nogil=True, fastmath=False)
def rhs_rotating(t, y, p, out):
    """Right-hand side in the co-rotating frame (see the module docstring for y and p)."""
    if p[P_MODES] != 0.0:
        _rhs(t, y, p, out, True)
    else:
        _rhs_free(t, y, p, out, True, SPEED_ANY)


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_fixed_free(t, y, p, out):
    """Lane-friendly right-hand side in the fixed frame: no stick/slip modes, constant or ramp
    speed (a Hill run-up gives NaN: use :func:`rhs_fixed`). Same equations and numbers as
    :func:`rhs_fixed` for those models."""
    _rhs_free(t, y, p, out, False, SPEED_ARITHMETIC)


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_rotating_free(t, y, p, out):
    """Lane-friendly right-hand side in the co-rotating frame (see :func:`rhs_fixed_free`)."""
    _rhs_free(t, y, p, out, True, SPEED_ARITHMETIC)


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_fixed_constant(t, y, p, out):
    """:func:`rhs_fixed_free` for a constant speed only (another kind gives NaN): no select
    between profile kinds. Same numbers as :func:`rhs_fixed` for those models."""
    _rhs_free(t, y, p, out, False, SPEED_CONSTANT)


@njit(cache=True, nogil=True, error_model="numpy")
def rhs_rotating_constant(t, y, p, out):
    """Lane-friendly right-hand side in the co-rotating frame (see :func:`rhs_fixed_constant`)."""
    _rhs_free(t, y, p, out, True, SPEED_CONSTANT)


@njit(cache=True, nogil=True, inline="always")
def _events(t, y, p, g, rotating):
    n = int(p[P_N])
    ax, ay, theta, om, dom = _solve(t, y, p, rotating, -1, g, 0, 1, 2)
    for i in range(n):
        k = P_BALLS + BALL_STRIDE * i
        s = g[2 * i]
        c = g[2 * i + 1]
        mode = y[I_ANGLE + 2 * n + i]
        if p[k + B_F] <= 0.0:
            g[2 * i] = 1.0
            g[2 * i + 1] = 1.0
        elif mode != 0.0:
            rate = y[I_ANGLE + n + i]
            rel = rate if rotating else rate - om
            g[2 * i] = rel * mode
            g[2 * i + 1] = 1.0
        else:
            drive, bound = _drive_and_bound(k, s, c, ax, ay, om, dom, p)
            g[2 * i] = 1.0
            g[2 * i + 1] = bound - abs(drive)


@njit(cache=True, nogil=True)
def events_fixed(t, y, p, g):
    """Stick/slip event functions in the fixed frame: ``stick_i``, ``slip_i`` per ball."""
    _events(t, y, p, g, False)


@njit(cache=True, nogil=True)
def events_rotating(t, y, p, g):
    """Stick/slip event functions in the co-rotating frame: ``stick_i``, ``slip_i`` per ball."""
    _events(t, y, p, g, True)


@njit(cache=True, nogil=True, inline="always")
def _reset(k_event, t, y, p, y_new, rotating):
    n = int(p[P_N])
    i = k_event // 2
    k = P_BALLS + BALL_STRIDE * i
    # the trial solve treats ball i as stuck in both cases (reaching zero relative speed, or
    # currently stuck and about to break away); y_new is scratch here, filled below
    ax, ay, theta, om, dom = _solve(t, y, p, rotating, i, y_new, 0, 1, 2)
    s = y_new[2 * i]
    c = y_new[2 * i + 1]
    drive, bound = _drive_and_bound(k, s, c, ax, ay, om, dom, p)
    for j in range(y.shape[0]):
        y_new[j] = y[j]
    if k_event % 2 == 0 and abs(drive) <= bound:
        mode = 0.0
    elif drive >= 0.0:
        mode = 1.0
    else:
        mode = -1.0
    y_new[I_ANGLE + 2 * n + i] = mode
    y_new[I_ANGLE + n + i] = 0.0 if rotating else om
    return 0


@njit(cache=True, nogil=True)
def reset_fixed(k, t, y, p, y_new):
    """Stick/slip reset map in the fixed frame (event ``k``: ball ``k // 2``)."""
    return _reset(k, t, y, p, y_new, False)


@njit(cache=True, nogil=True)
def reset_rotating(k, t, y, p, y_new):
    """Stick/slip reset map in the co-rotating frame (event ``k``: ball ``k // 2``)."""
    return _reset(k, t, y, p, y_new, True)


@njit(cache=True, nogil=True)
def stick_torques(t, y, p, rotating, forced, drive, bound, acc):
    """Driving torques and friction bounds of the balls as if ``forced`` (>= 0) were stuck.

    Parameters
    ----------
    t : float
        Time (s).
    y, p : ndarray
        State (in the frame given by ``rotating``) and packed parameters.
    rotating : bool
        Frame of ``y``.
    forced : int
        Ball treated as stuck in addition to the stuck modes (-1: none).
    drive, bound : ndarray, shape (n,)
        Filled with ``D_i = m_i l_i (ax s_i - ay c_i) - J_i Omega'`` (N m) and
        ``f_i l_i N_i`` (N m); both are meaningful for stuck balls.
    acc : ndarray, shape (2 + n,)
        Filled with ``(ax, ay)`` (absolute acceleration of O1 in working axes, m/s^2) and the
        normal forces ``N_i`` (N).
    """
    n = int(p[P_N])
    has_modes = p[P_MODES] != 0.0
    # bound[] is scratch during the solve (sin and cos both land there and are recomputed)
    ax, ay, theta, om, dom = _solve(t, y, p, rotating, forced, bound, 0, 0, 1)
    for i in range(n):
        ang = y[I_ANGLE + i]
        s, c = sincos(ang)
        k = P_BALLS + BALL_STRIDE * i
        d_i, b_i = _drive_and_bound(k, s, c, ax, ay, om, dom, p)
        drive[i] = d_i
        bound[i] = b_i
        mode = y[I_ANGLE + 2 * n + i] if has_modes else 1.0
        rate = y[I_ANGLE + n + i]
        w = rate + om if rotating else rate
        if i == forced or _is_stuck(k, mode, has_modes, p):
            w = om
        acc[2 + i] = p[k + B_M] * (p[k + B_L] * w * w - ax * c - ay * s)
    acc[0] = ax
    acc[1] = ay
