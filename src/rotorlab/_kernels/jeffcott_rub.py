"""Compiled kernels of the Jeffcott rotor in a circular clearance (model ``jeffcott_rub``): the
tests' oracle only.

The model (:class:`rotorlab.contact.JeffcottRub`) runs its preset machine's generated kernel
(:mod:`rotorlab.models._rub_machine`); this hand-written one stays as the reference that kernel is
checked against to 1e-12 (``tests/unit/test_rub_machine.py``), and for its constants: the state
indices and the model's own 15 packed entries, which lead the preset's packed vector.

Physics and conventions: :mod:`rotorlab.models._jeffcott_rub`; the contact law itself is
:mod:`rotorlab._kernels.contact`.

State ``y`` (length ``N_STATE`` = 9, the last ``N_DISCRETE`` = 3 discrete)
-------------------------------------------------------------------------
``0, 1`` x, y (m), fixed frame; ``2, 3`` their rates (m/s); ``4`` DISS: energy dissipated by the
contact (restitution, friction, stator damping) (J); ``5`` DRIVE: work the drive does through the
contact friction torque (J); ``6`` N_IMP: impacts (rigid stator) or contact onsets (elastic);
``7`` P_MAX: largest normal impulse (N s); ``8`` MODE: 0 free, +1 / -1 in contact sliding with
positive / negative slip, 2 in contact rolling (stick).

Packed parameters ``p``
-----------------------
``m, k, c, eps, Omega, delta, k_s, c_s, mu, R_r, e, v_rest, g_x, g_y, rigid`` (SI; ``rigid`` 1.0
for a rigid stator, then ``k_s, c_s`` are unused).

Events (all direction -1)
-------------------------
``0 contact`` (free: ``g = delta - |w|``); ``1 lift_off`` (in contact: rigid ``g = N``,
elastic ``g = |w| - delta``); ``2 stick`` (sliding: ``g = sign * s``, the slip reaching zero);
``3 slip`` (rolling: ``g = mu N - |F_t|``, the friction cone reached).
"""

import math

from numba import njit

from rotorlab._kernels._vmath import sincos
from rotorlab._kernels.contact import (
    circular_gap,
    contact_velocities,
    impulse_energy,
    newton_coulomb_impulse,
    penalty_normal_force,
    sustained_forces,
)

N_STATE = 9
N_DISCRETE = 3
X, Y, VX, VY, DISS, DRIVE, N_IMP, P_MAX, MODE = 0, 1, 2, 3, 4, 5, 6, 7, 8
P_M, P_K, P_C, P_EPS, P_W, P_D, P_KS, P_CS, P_MU, P_R, P_E, P_VREST, P_GX, P_GY, P_RIGID = range(15)
N_PARAM = 15
EV_CONTACT, EV_LIFT, EV_STICK, EV_SLIP = 0, 1, 2, 3


@njit(cache=True, nogil=True, inline="always")
def free_accel(t, y, p):
    """Acceleration of the centre without contact: spring, damping, unbalance, gravity (m/s^2)."""
    m = p[P_M]
    w = p[P_W]
    s, c = sincos(w * t)
    fu = p[P_EPS] * w * w
    ax = (-p[P_K] * y[X] - p[P_C] * y[VX]) / m + fu * c + p[P_GX]
    ay = (-p[P_K] * y[Y] - p[P_C] * y[VY]) / m + fu * s + p[P_GY]
    return ax, ay


@njit(cache=True, nogil=True, inline="always")
def contact_forces(t, y, p):
    """Contact force in the contact frame: N, F_t (N), the normal, and the slip speed (m/s)."""
    g, nx, ny = circular_gap(y[X], y[Y], p[P_D])
    r = p[P_D] - g
    vn, s = contact_velocities(nx, ny, y[VX], y[VY], p[P_R] * p[P_W])
    vt = s - p[P_R] * p[P_W]
    ax, ay = free_accel(t, y, p)
    an = ax * nx + ay * ny
    at = -ax * ny + ay * nx
    mode = y[MODE]
    rigid = p[P_RIGID] != 0.0
    stick = mode == 2.0
    n, ft = sustained_forces(an, at, vt, vn, r, p[P_M], rigid, stick)
    if not rigid:
        n = penalty_normal_force(-g, vn, p[P_KS], p[P_CS])
    if not stick:
        ft = -p[P_MU] * mode * n
    return n, ft, nx, ny, s, vn


@njit(cache=True, nogil=True)
def rhs(t, y, p, out):
    ax, ay = free_accel(t, y, p)
    out[X] = y[VX]
    out[Y] = y[VY]
    out[DISS] = 0.0
    out[DRIVE] = 0.0
    if y[MODE] != 0.0:
        n, ft, nx, ny, s, vn = contact_forces(t, y, p)
        m = p[P_M]
        ax += (-n * nx - ft * ny) / m
        ay += (-n * ny + ft * nx) / m
        # friction dissipates -F_t s, the drive supplies -F_t R Omega; the stator damper c_s vn^2
        d = -ft * s
        if p[P_RIGID] == 0.0 and n > 0.0:
            d += p[P_CS] * vn * vn
        out[DISS] = d
        out[DRIVE] = -ft * p[P_R] * p[P_W]
    out[VX] = ax
    out[VY] = ay
    out[N_IMP] = 0.0
    out[P_MAX] = 0.0
    out[MODE] = 0.0


@njit(cache=True, nogil=True)
def events(t, y, p, g):
    mode = y[MODE]
    if mode == 0.0:
        gap, _, _ = circular_gap(y[X], y[Y], p[P_D])
        # right after an impact the centre is on the circle to round-off: exactly 0 there, so that
        # the integrator probes the step for a tiny rebound instead of starting just inside
        g[EV_CONTACT] = gap if abs(gap) > 8.0 * 2.220446049250313e-16 * p[P_D] else 0.0
        g[EV_LIFT] = 1.0
        g[EV_STICK] = 1.0
        g[EV_SLIP] = 1.0
        return
    g[EV_CONTACT] = 1.0
    n, ft, nx, ny, s, vn = contact_forces(t, y, p)
    if p[P_RIGID] != 0.0:
        g[EV_LIFT] = n
    else:
        gap, _, _ = circular_gap(y[X], y[Y], p[P_D])
        g[EV_LIFT] = -gap
    if mode == 2.0:
        g[EV_STICK] = 1.0
        g[EV_SLIP] = p[P_MU] * n - abs(ft)
    else:
        g[EV_STICK] = mode * s if p[P_MU] > 0.0 else 1.0
        g[EV_SLIP] = 1.0


@njit(cache=True, nogil=True, inline="always")
def _project(y_new, p):
    """Put the centre back on the clearance circle (rigid stator)."""
    g, nx, ny = circular_gap(y_new[X], y_new[Y], p[P_D])
    y_new[X] += g * nx
    y_new[Y] += g * ny


@njit(cache=True, nogil=True, inline="always")
def _enter_contact_mode(t, y_new, p, s):
    """Rolling if the friction cone holds the rolling force, else sliding along the slip."""
    if p[P_MU] > 0.0 and s == 0.0:
        y_new[MODE] = 2.0
        n, ft, _, _, _, _ = contact_forces(t, y_new, p)
        if abs(ft) <= p[P_MU] * n:
            return
        y_new[MODE] = -1.0 if ft > 0.0 else 1.0
        return
    y_new[MODE] = 1.0 if s > 0.0 else -1.0


@njit(cache=True, nogil=True)
def reset(k, t, y, p, y_new):
    for i in range(N_STATE):
        y_new[i] = y[i]
    m = p[P_M]
    rigid = p[P_RIGID] != 0.0
    if k == EV_CONTACT:
        y_new[N_IMP] += 1.0
        if not rigid:
            _, nx, ny = circular_gap(y[X], y[Y], p[P_D])
            _, s = contact_velocities(nx, ny, y[VX], y[VY], p[P_R] * p[P_W])
            _enter_contact_mode(t, y_new, p, s)
            return 0
        _project(y_new, p)
        _, nx, ny = circular_gap(y_new[X], y_new[Y], p[P_D])
        ss = p[P_R] * p[P_W]
        vn, s = contact_velocities(nx, ny, y_new[VX], y_new[VY], ss)
        e = p[P_E]
        ax, ay = free_accel(t, y_new, p)
        vt = s - ss
        pressing = ax * nx + ay * ny + vt * vt / p[P_D] > 0.0
        # an approach speed below rest_speed is the end of an accumulation (or integration noise
        # at a grazing touch): sustained contact if the stator has to push, else nothing happens
        settle = e * vn < p[P_VREST] and pressing
        if vn <= 0.0 and not settle:
            return 0
        if settle:
            e = 0.0  # the rest of the accumulation (chatter) as one plastic impulse
        w = 1.0 / m
        pn, pt, stuck = newton_coulomb_impulse(vn, s, w, 0.0, w, e, p[P_MU])
        ln, lt, dr = impulse_energy(vn, s, pn, pt, w, 0.0, w, ss)
        y_new[VX] += (-pn * nx - pt * ny) * w
        y_new[VY] += (-pn * ny + pt * nx) * w
        y_new[DISS] += ln + lt
        y_new[DRIVE] += dr
        if pn > y_new[P_MAX]:
            y_new[P_MAX] = pn
        if settle:
            _, s2 = contact_velocities(nx, ny, y_new[VX], y_new[VY], ss)
            _enter_contact_mode(t, y_new, p, 0.0 if stuck else s2)
        return 0
    if k == EV_LIFT:
        if rigid:
            _project(y_new, p)
        y_new[MODE] = 0.0
        return 0
    if k == EV_STICK:
        _enter_contact_mode(t, y_new, p, 0.0)
        return 0
    # EV_SLIP: the rolling force reached the cone; slide against it
    n, ft, _, _, _, _ = contact_forces(t, y, p)
    y_new[MODE] = -1.0 if ft > 0.0 else 1.0
    return 0
