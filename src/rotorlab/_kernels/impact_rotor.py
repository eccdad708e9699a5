"""Compiled kernels of the centrifuge rotor striking its housing (model ``impact_rotor``).

Physics, conventions and every correction to the printed equations are documented in
:mod:`rotorlab.models._impact_rotor`; this module is the allocation-free numerics.

State ``y`` (length ``N_STATE`` = 33, the last ``N_DISCRETE`` = 22 discrete)
-----------------------------------------------------------------------------
==========  ===================================================================================
``0, 1``    u1, u2: displacement of the centre of mass in the frame rotating at omega0 (m)
``2, 3``    t1, t2: small tilt angles of the axis in the planes XZ, YZ (rad)
``4 .. 7``  their rates (m/s, rad/s)
``8``       INT_N: integral of the sliding contact force, int N dt (N s)
``9``       W_ST: work of the stone forces on the rotor's vibration, fixed frame (J)
``10``      W_NC: work of every non-conservative force between impulses (stones, membrane
            friction, sliding contact) on the vibration, fixed frame (J)
``11``      MODE: 0 free, 1 sliding contact with the housing
``12``      I_BP: number of stone breakpoints (arrivals and departures) passed
``13``      T_RESET: time of the last reset that left P on the housing (s; -1 if none)
``14``      N_IMP: impacts with approach speed >= the counting threshold
``15``      N_ALL: every impact reset (chatter included)
``16``      N_SLIDE: number of sliding episodes
``17``      T_START: start of the current sliding episode (s)
``18``      T_SLIDE: total time in sliding contact, closed episodes (s)
``19``      S_SUM: sum of the normal impact impulses (N s)
``20``      E_REST: energy lost by restitution, sum of P_n (1 - k) v / 2 (J)
``21``      V_MAX: largest approach speed (m/s)
``22``      PEN_MAX: largest excess |w| - Delta seen at an impact or a projection (m)
``23``      WHIRL: 1 if the run was stopped by the dry-friction backward whirl
``24``      E_0: fixed-frame vibration energy of the start (J; set by ``initial_state``)
``25``      W_DRIVE: work of the drive through the impulses' friction, sum of -P_t r_P omega0 (J)
``26``      E_FRIC: heat of friction at the impulses, sum of -P_t (s- + s+) / 2 (J)
``27``      E_PROJ: energy changed by projections of P back onto the housing (J, numerical)
``28``      R_T: last time P touched the housing whirling forwards (s; 0 if never): the run's
            state before a backward-whirl runaway (see "Runaway" below)
``29 .. 32`` R_NIMP, R_NALL, R_WDRIVE, R_INTN: N_IMP, N_ALL, W_DRIVE and INT_N at R_T
==========  ===================================================================================

Runaway: a run stopped at the backward whirl gets there through a runaway (the contact point
whirls backwards on the housing, friction feeds the whirl, N grows with its square), where
nearly all its friction work can come in the last milliseconds. ``R_*`` are the run's records
at the last moment P touched the housing whirling forwards (after an impact, a slide's start or
a lift-off with a forward whirl, or where a slide's whirl turns backwards: ``whirl_reverse``).

Energy ledger
-------------
The vibration energy in the fixed frame (:func:`fixed_energy`, membranes fixed, spin held by the
drive) changes only by the work of the non-smooth and non-conservative forces:
``E(t) - E_0 = W_NC + W_DRIVE - E_REST - E_FRIC + E_PROJ``. The sources are the stones (``W_ST``)
and the drive (``W_DRIVE`` at the impulses, ``f r_P omega0 INT_N`` in sliding contact); the
membranes' friction, restitution and the friction at the housing only take energy away.
:meth:`rotorlab.models.ImpactRotor.impossible_states` fails a run whose ledger does not close or
whose energy exceeds what the sources supplied.

Packed parameters ``p`` (header of ``P_HEADER`` entries, then tables)
--------------------------------------------------------------------
``p[0..22]``: m, A1, A3, omega0, c, n_m, c_*, gamma, sin(beta), cos(beta), l_P, h_P, r_P,
Delta, k, f, 1/m*, h_q, translational (0/1), v_rest, v_count, whirl_limit, tau_end.
``p[23..31]``: n_stones, offset of the stone table (rows ``t_n, m_n omega0^2 R_q, cos a_n,
sin a_n``), n_bp, offset of the sorted breakpoint times, offset of the active-stone table
(``n_bp + 1`` rows of ``n_act`` stone indices, -1 where empty), n_act, n_tab, offset of the
push table (``n_tab`` rows ``J_x, J_y, dJ_x/dtau, dJ_y/dtau`` on the uniform grid
``tau_j = j dtau``), dtau.
``p[32]``: slip stop (1: sliding stops where the slip of P vanishes, the default; 0: at
``whirl_limit``, see :func:`whirl_stop`).

Events (all direction -1)
-------------------------
``0 impact``: free, ``g = Delta - |w|`` (exactly 0 at the time of the last reset that left P on
the housing); ``1 lift_off``: sliding, ``g = N``; ``2 stone``: ``g = t_bp - t`` for the next
stone arrival or departure (the active stones change only there, so the forcing is smooth inside
every step); ``3 backward_whirl``: sliding, ``g`` = the slip of P (:func:`slip_speed`; or, with a
``whirl_limit``, ``whirl_limit + dphi/dt + omega0``, the inertial angular speed of the contact
point; :func:`whirl_stop`), stops the run. An impact whose impulse sticks (the slip of
P stops: P rolls on the housing, the dry-friction backward whirl) also stops the run.
``4 whirl_reverse``: sliding, ``g`` = the inertial whirl speed of the contact point
(:func:`whirl_speed`): where it turns backwards the ``R_*`` records are taken. A stone leaving
its guide while P slides may leave the housing pulling (``N < 0`` right after the breakpoint):
the rotor lifts off there.

Impacts and sliding are the shared contact law of :mod:`rotorlab._kernels.contact` at P
(:func:`delassus`, :func:`slip_speed`); see the note before :func:`delassus`.
"""

import math

from numba import njit

from rotorlab._kernels.contact import delassus_forces, impulse_energy, newton_coulomb_impulse

N_STATE = 33
N_DISCRETE = 22
N_CONT = N_STATE - N_DISCRETE

U1, U2, T1, T2, DU1, DU2, DT1, DT2, INT_N, W_ST, W_NC = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10
MODE, I_BP, T_RESET, N_IMP, N_ALL, N_SLIDE, T_START, T_SLIDE = 11, 12, 13, 14, 15, 16, 17, 18
S_SUM, E_REST, V_MAX, PEN_MAX, WHIRL = 19, 20, 21, 22, 23
E_0, W_DRIVE, E_FRIC, E_PROJ = 24, 25, 26, 27
R_T, R_NIMP, R_NALL, R_WDRIVE, R_INTN = 28, 29, 30, 31, 32

P_M, P_A1, P_A3, P_W0, P_C, P_NM, P_CS, P_GAM = 0, 1, 2, 3, 4, 5, 6, 7
P_SB, P_CB, P_LP, P_HP, P_RP, P_GAP, P_K, P_F = 8, 9, 10, 11, 12, 13, 14, 15
P_IMS, P_HQ, P_TRANS, P_VREST, P_VCOUNT, P_WHIRL, P_TAUEND = 16, 17, 18, 19, 20, 21, 22
P_NST, P_OST, P_NBP, P_OBP, P_OACT, P_NACT, P_NTAB, P_OTAB, P_DTAU = (
    23, 24, 25, 26, 27, 28, 29, 30, 31,
)  # fmt: skip
P_SLIPSTOP = 32
P_HEADER = 33

EV_IMPACT, EV_LIFT, EV_STONE, EV_WHIRL, EV_REVERSE = 0, 1, 2, 3, 4


@njit(cache=True, nogil=True)
def push(tau, p):
    """Dimensionless push ``J(tau)`` of one stone on its guide, (J_x, J_y) in the guide's frame.

    Cubic Hermite interpolation of the tabulated push; continued linearly outside
    ``[0, tau_end]`` (used only inside a step that is truncated at the breakpoint).
    """
    n = int(p[P_NTAB])
    o = int(p[P_OTAB])
    dtau = p[P_DTAU]
    if tau <= 0.0:
        return p[o] + p[o + 2] * tau, p[o + 1] + p[o + 3] * tau
    x = tau / dtau
    if x >= n - 1:
        r = o + 4 * (n - 1)
        d = tau - (n - 1) * dtau
        return p[r] + p[r + 2] * d, p[r + 1] + p[r + 3] * d
    j = int(x)
    s = x - j
    r = o + 4 * j
    s2 = s * s
    s3 = s2 * s
    h00 = 2.0 * s3 - 3.0 * s2 + 1.0
    h10 = (s3 - 2.0 * s2 + s) * dtau
    h01 = -2.0 * s3 + 3.0 * s2
    h11 = (s3 - s2) * dtau
    jx = h00 * p[r] + h10 * p[r + 2] + h01 * p[r + 4] + h11 * p[r + 6]
    jy = h00 * p[r + 1] + h10 * p[r + 3] + h01 * p[r + 5] + h11 * p[r + 7]
    return jx, jy


@njit(cache=True, nogil=True)
def stone_force(t, y, p):
    """Total force of the stones on the rotor, rotating frame (N): sum of m_n w0^2 R_q P(a_n) J."""
    n_act = int(p[P_NACT])
    if n_act == 0:
        return 0.0, 0.0
    i_bp = int(y[I_BP])
    row = int(p[P_OACT]) + i_bp * n_act
    ost = int(p[P_OST])
    w0 = p[P_W0]
    fx = 0.0
    fy = 0.0
    for a in range(n_act):
        idx = int(p[row + a])
        if idx < 0:
            break
        r = ost + 4 * idx
        jx, jy = push(w0 * (t - p[r]), p)
        s = p[r + 1]
        ca = p[r + 2]
        sa = p[r + 3]
        fx += s * (ca * jx - sa * jy)
        fy += s * (sa * jx + ca * jy)
    return fx, fy


@njit(cache=True, nogil=True)
def _free(t, y, p):
    """Accelerations without contact force and the stone force (rotating frame, N)."""
    m = p[P_M]
    a1 = p[P_A1]
    a3 = p[P_A3]
    w0 = p[P_W0]
    c = p[P_C]
    nm = p[P_NM]
    cs = p[P_CS]
    gw = p[P_GAM] / w0
    gam = p[P_GAM]
    u1 = y[U1]
    u2 = y[U2]
    t1 = y[T1]
    t2 = y[T2]
    du1 = y[DU1]
    du2 = y[DU2]
    dt1 = y[DT1]
    dt2 = y[DT2]
    # membranes (4.1): F = -c L(u + n_m t), M~ = n_m F - c_* L(t), L(x) = x + (g/w0)(x' + w0 k x x)
    um1 = u1 + nm * t1
    um2 = u2 + nm * t2
    vm1 = du1 + nm * dt1
    vm2 = du2 + nm * dt2
    fm1 = -c * (um1 + gw * vm1 - gam * um2)
    fm2 = -c * (um2 + gw * vm2 + gam * um1)
    fq1, fq2 = stone_force(t, y, p)
    f1 = fm1 + fq1
    f2 = fm2 + fq2
    ddu1 = 2.0 * w0 * du2 + w0 * w0 * u1 + f1 / m
    ddu2 = -2.0 * w0 * du1 + w0 * w0 * u2 + f2 / m
    if p[P_TRANS] != 0.0:
        return ddu1, ddu2, 0.0, 0.0, fq1, fq2
    hq = p[P_HQ]
    mm1 = nm * fm1 - cs * (t1 + gw * dt1 - gam * t2) + hq * fq1
    mm2 = nm * fm2 - cs * (t2 + gw * dt2 + gam * t1) + hq * fq2
    g = (a3 - 2.0 * a1) * w0
    kk = (a1 - a3) * w0 * w0
    ddt1 = (-g * dt2 + kk * t1 + mm1) / a1
    ddt2 = (g * dt1 + kk * t2 + mm2) / a1
    return ddu1, ddu2, ddt1, ddt2, fq1, fq2


@njit(cache=True, nogil=True)
def free_accel(t, y, p):
    """Accelerations (u1'', u2'', t1'', t2'') without any contact force, eqs (2.2), (4.1), (4.2)."""
    a1, a2, b1, b2, _, _ = _free(t, y, p)
    return a1, a2, b1, b2


@njit(cache=True, nogil=True)
def fixed_velocities(y, p):
    """Velocities in the fixed frame, in rotating axes: ``X' = u' + omega0 k x u``, ``T' = t' +
    omega0 k x t`` (m/s, rad/s); the tilt's are 0 in the translational variant."""
    w0 = p[P_W0]
    x1 = y[DU1] - w0 * y[U2]
    x2 = y[DU2] + w0 * y[U1]
    if p[P_TRANS] != 0.0:
        return x1, x2, 0.0, 0.0
    return x1, x2, y[DT1] - w0 * y[T2], y[DT2] + w0 * y[T1]


@njit(cache=True, nogil=True)
def fixed_energy(y, p):
    """Vibration energy in the fixed frame (J): ``1/2 m |X'|^2 + 1/2 A1 |T'|^2 + 1/2 c |u + n_m
    t|^2 + 1/2 c_* |t|^2`` (the membranes are fixed; the gyroscopic moment does no work).

    Without stones, membrane friction (gamma) and contact it is conserved; it is the Jacobi
    energy of :meth:`rotorlab.models.ImpactRotor.jacobi_energy` plus ``omega0`` times the angular
    momentum of the vibration about the axis.
    """
    x1, x2, s1, s2 = fixed_velocities(y, p)
    um1 = y[U1] + p[P_NM] * y[T1]
    um2 = y[U2] + p[P_NM] * y[T2]
    e = 0.5 * p[P_M] * (x1 * x1 + x2 * x2) + 0.5 * p[P_C] * (um1 * um1 + um2 * um2)
    if p[P_TRANS] == 0.0:
        e += 0.5 * p[P_A1] * (s1 * s1 + s2 * s2) + 0.5 * p[P_CS] * (y[T1] * y[T1] + y[T2] * y[T2])
    return e


@njit(cache=True, nogil=True)
def gap_vector(y, p):
    """w = u sin(beta) + l_P t: |w| is the largest normal displacement of the circle of P (m)."""
    sb = p[P_SB]
    lp = p[P_LP]
    return sb * y[U1] + lp * y[T1], sb * y[U2] + lp * y[T2]


@njit(cache=True, nogil=True)
def gap_rate(y, p):
    """dw/dt (m/s)."""
    sb = p[P_SB]
    lp = p[P_LP]
    return sb * y[DU1] + lp * y[DT1], sb * y[DU2] + lp * y[DT2]


@njit(cache=True, nogil=True)
def contact_force(t, y, p):
    """Normal force N (N) that keeps P on the housing (|w| = Delta), and the unit vector of w.

    The shared sustained-contact law :func:`rotorlab._kernels.contact.delassus_forces` (rigid
    housing, sliding forwards: ``mode = +1``) with the entries of :func:`delassus`:
    ``N = b_n / w_nn = m* (e.w''_free + (|w'|^2 - (e.w')^2) / |w|)``, the normal acceleration the
    free motion would have plus the centripetal term of w turning, times the equivalent mass m*.
    """
    w1, w2 = gap_vector(y, p)
    r = math.sqrt(w1 * w1 + w2 * w2)
    e1 = w1 / r
    e2 = w2 / r
    dw1, dw2 = gap_rate(y, p)
    a1, a2, b1, b2 = free_accel(t, y, p)
    sb = p[P_SB]
    lp = p[P_LP]
    an = e1 * (sb * a1 + lp * b1) + e2 * (sb * a2 + lp * b2)
    vn = e1 * dw1 + e2 * dw2
    cen = (dw1 * dw1 + dw2 * dw2 - vn * vn) / r
    wnn, wnt, wtt = delassus(p)
    n, _ = delassus_forces(an + cen, 0.0, wnn, wnt, wtt, p[P_F], 1.0, True, 0.0)
    return n, e1, e2


@njit(cache=True, nogil=True)
def rhs(t, y, p, out):
    a1, a2, b1, b2, fq1, fq2 = _free(t, y, p)
    out[U1] = y[DU1]
    out[U2] = y[DU2]
    out[T1] = y[DT1]
    out[T2] = y[DT2]
    out[INT_N] = 0.0
    x1, x2, s1, s2 = fixed_velocities(y, p)
    # power of the stones (force F_q at the height h_q) and of the membranes' friction, fixed frame
    p_st = fq1 * (x1 + p[P_HQ] * s1) + fq2 * (x2 + p[P_HQ] * s2)
    gw = p[P_GAM] / p[P_W0]
    xm1 = x1 + p[P_NM] * s1
    xm2 = x2 + p[P_NM] * s2
    p_nc = p_st - gw * (p[P_C] * (xm1 * xm1 + xm2 * xm2) + p[P_CS] * (s1 * s1 + s2 * s2))
    if y[MODE] != 0.0:
        n, e1, e2 = contact_force(t, y, p)
        f = p[P_F]
        # contact force -N (sin(beta) e + f e_perp), moment -N (l_P e + f h_P e_perp), e_perp = k x e
        inv_m = n / p[P_M]
        a1 -= inv_m * (p[P_SB] * e1 - f * e2)
        a2 -= inv_m * (p[P_SB] * e2 + f * e1)
        p_nc -= n * (p[P_SB] * (e1 * x1 + e2 * x2) + f * (e1 * x2 - e2 * x1))
        if p[P_TRANS] == 0.0:
            inv_a = n / p[P_A1]
            hp = p[P_HP]
            b1 -= inv_a * (p[P_LP] * e1 - f * hp * e2)
            b2 -= inv_a * (p[P_LP] * e2 + f * hp * e1)
            p_nc -= n * (p[P_LP] * (e1 * s1 + e2 * s2) + f * hp * (e1 * s2 - e2 * s1))
        out[INT_N] = n
    out[DU1] = a1
    out[DU2] = a2
    out[DT1] = b1
    out[DT2] = b2
    out[W_ST] = p_st
    out[W_NC] = p_nc
    for i in range(N_CONT, N_STATE):
        out[i] = 0.0


@njit(cache=True, nogil=True)
def whirl_speed(y, p):
    """Angular speed of the direction of w (of the contact point) in the fixed frame (rad/s)."""
    w1, w2 = gap_vector(y, p)
    dw1, dw2 = gap_rate(y, p)
    return (w1 * dw2 - w2 * dw1) / (w1 * w1 + w2 * w2) + p[P_W0]


@njit(cache=True, nogil=True)
def whirl_stop(y, p, e1, e2):
    """Sliding contact's stop function (``< 0``: the dry-friction backward whirl is reached).

    With ``p[P_SLIPSTOP] = 1`` (the default) the slip of P over the housing, :func:`slip_speed`:
    the sliding law (friction ``-f N e_perp``) holds while P slides forwards and ends exactly where
    the slip vanishes and P would roll. Otherwise ``whirl_limit + dphi/dt + omega0``: the contact
    point whirling backwards faster than ``whirl_limit`` (a user's override).
    """
    if p[P_SLIPSTOP] != 0.0:
        return slip_speed(y, p, e1, e2)
    return p[P_WHIRL] + whirl_speed(y, p)


@njit(cache=True, nogil=True)
def events(t, y, p, g):
    free = y[MODE] == 0.0
    if free:
        if t == y[T_RESET]:
            g[EV_IMPACT] = 0.0
        else:
            w1, w2 = gap_vector(y, p)
            g[EV_IMPACT] = p[P_GAP] - math.sqrt(w1 * w1 + w2 * w2)
        g[EV_LIFT] = 1.0
        g[EV_WHIRL] = 1.0
        g[EV_REVERSE] = 1.0
    else:
        g[EV_IMPACT] = 1.0
        n, e1, e2 = contact_force(t, y, p)
        g[EV_LIFT] = n
        g[EV_WHIRL] = whirl_stop(y, p, e1, e2)
        g[EV_REVERSE] = whirl_speed(y, p)
    i_bp = int(y[I_BP])
    if i_bp < int(p[P_NBP]):
        g[EV_STONE] = p[int(p[P_OBP]) + i_bp] - t
    else:
        g[EV_STONE] = 1.0


@njit(cache=True, nogil=True)
def _shift(y_new, p, e1, e2, dn, dv):
    """Move w by ``dn`` and dw/dt by ``dv`` along e, mass-weighted as a normal impulse would."""
    ims = p[P_IMS]
    k_u = p[P_SB] / p[P_M] / ims
    y_new[U1] += dn * k_u * e1
    y_new[U2] += dn * k_u * e2
    y_new[DU1] += dv * k_u * e1
    y_new[DU2] += dv * k_u * e2
    if p[P_TRANS] == 0.0:
        k_t = p[P_LP] / p[P_A1] / ims
        y_new[T1] += dn * k_t * e1
        y_new[T2] += dn * k_t * e2
        y_new[DT1] += dv * k_t * e1
        y_new[DT2] += dv * k_t * e2


@njit(cache=True, nogil=True)
def _project(y_new, p, velocity):
    """Put P back on the housing (|w| = Delta) and, if ``velocity``, cancel its normal speed.

    The energy this changes (a numerical correction, round-off after a located event) goes to
    ``E_PROJ``.
    """
    e_before = fixed_energy(y_new, p)
    w1, w2 = gap_vector(y_new, p)
    r = math.sqrt(w1 * w1 + w2 * w2)
    e1 = w1 / r
    e2 = w2 / r
    if r - p[P_GAP] > y_new[PEN_MAX]:
        y_new[PEN_MAX] = r - p[P_GAP]
    dv = 0.0
    if velocity:
        dw1, dw2 = gap_rate(y_new, p)
        dv = -(e1 * dw1 + e2 * dw2)
    _shift(y_new, p, e1, e2, p[P_GAP] - r, dv)
    y_new[E_PROJ] += fixed_energy(y_new, p) - e_before
    return e1, e2


@njit(cache=True, nogil=True)
def _impact(y_new, p, e1, e2, v, e):
    """Impact of P with approach speed ``v`` > 0 and restitution ``e``: the shared law.

    The impulse is :func:`rotorlab._kernels.contact.newton_coulomb_impulse` with the Delassus
    entries of :func:`delassus` and the slip of :func:`slip_speed`; it is applied as the force
    ``-P_n sin(beta) e + P_t e_perp`` on u and the moment ``-P_n l_P e + P_t h_P e_perp`` on t,
    eqs (3.6)-(3.9). While P slides forwards (``s > 0``: ``r_P omega0`` = 100 m/s against
    vibration speeds below about 1 m/s in seed 001's runs) this is exactly (3.9): ``P_n = (1 + k)
    m* v``, ``P_t = -f P_n``. The energy split of :func:`rotorlab._kernels.contact.impulse_energy`
    (surface speed ``r_P omega0``, the fixed-frame kinetic energy) goes to the ledger: ``E_REST``
    (``P_n (1 - e) v / 2``, with Newton's ``v+ = -e v`` exactly), ``E_FRIC``, ``W_DRIVE``.

    Returns
    -------
    bool
        Whether the impulse sticks: the slip of P stops, P rolls on the housing.
    """
    wnn, wnt, wtt = delassus(p)
    s = slip_speed(y_new, p, e1, e2)
    pn, pt, stick = newton_coulomb_impulse(v, s, wnn, wnt, wtt, e, p[P_F])
    m = p[P_M]
    sb = p[P_SB]
    # e_perp = (-e2, e1)
    y_new[DU1] -= (pn * sb * e1 + pt * e2) / m
    y_new[DU2] -= (pn * sb * e2 - pt * e1) / m
    if p[P_TRANS] == 0.0:
        a1 = p[P_A1]
        lp = p[P_LP]
        hp = p[P_HP]
        y_new[DT1] -= (pn * lp * e1 + pt * hp * e2) / a1
        y_new[DT2] -= (pn * lp * e2 - pt * hp * e1) / a1
    y_new[S_SUM] += pn
    _, loss_t, drive = impulse_energy(v, s, pn, pt, wnn, wnt, wtt, p[P_RP] * p[P_W0])
    y_new[E_REST] += 0.5 * pn * (1.0 - e) * v
    y_new[E_FRIC] += loss_t
    y_new[W_DRIVE] += drive
    return stick


@njit(cache=True, nogil=True)
def _count(y_new, p, v):
    y_new[N_ALL] += 1.0
    if v >= p[P_VCOUNT]:
        y_new[N_IMP] += 1.0
    if v > y_new[V_MAX]:
        y_new[V_MAX] = v


@njit(cache=True, nogil=True)
def _record(y_new, t):
    """Take the ``R_*`` records: the state of the run before a backward-whirl runaway."""
    y_new[R_T] = t
    y_new[R_NIMP] = y_new[N_IMP]
    y_new[R_NALL] = y_new[N_ALL]
    y_new[R_WDRIVE] = y_new[W_DRIVE]
    y_new[R_INTN] = y_new[INT_N]


@njit(cache=True, nogil=True)
def _lift_off(t, y, y_new):
    y_new[MODE] = 0.0
    y_new[T_RESET] = t
    y_new[T_SLIDE] += t - y[T_START]


@njit(cache=True, nogil=True)
def reset(k, t, y, p, y_new):
    for i in range(N_STATE):
        y_new[i] = y[i]
    if k == EV_STONE:
        y_new[I_BP] = y[I_BP] + 1.0
        if y[MODE] != 0.0:
            _project(y_new, p, True)
            n, _, _ = contact_force(t, y_new, p)
            if n <= 0.0:
                # the stone that left (or arrived) took the normal force with it: the housing
                # would pull, the rotor lifts off here
                _lift_off(t, y, y_new)
                if whirl_speed(y_new, p) >= 0.0:
                    _record(y_new, t)
        return 0
    if k == EV_REVERSE:
        _record(y_new, t)
        return 0
    if k == EV_IMPACT:
        e1, e2 = _project(y_new, p, False)
        y_new[T_RESET] = t
        dw1, dw2 = gap_rate(y_new, p)
        v = e1 * dw1 + e2 * dw2  # approach speed (> 0 towards the housing)
        if v <= 0.0:
            return 0
        _count(y_new, p, v)
        kr = p[P_K]
        if kr * v < p[P_VREST]:
            # accumulation of impacts: sustained contact if the housing has to push
            y_new[MODE] = 1.0
            stick = _impact(y_new, p, e1, e2, v, 0.0)
            _project(y_new, p, True)
            n, _, _ = contact_force(t, y_new, p)
            if n > 0.0:
                y_new[N_SLIDE] += 1.0
                y_new[T_START] = t
                w1, w2 = gap_vector(y_new, p)
                r = math.sqrt(w1 * w1 + w2 * w2)
                if stick or whirl_stop(y_new, p, w1 / r, w2 / r) < 0.0:
                    # it starts in the dry-friction backward whirl (rolling, or faster than the
                    # rolling speed): the sliding law ends here, stop
                    y_new[WHIRL] = 1.0
                    y_new[MODE] = 0.0
                    return 1
                if whirl_speed(y_new, p) >= 0.0:
                    _record(y_new, t)
                return 0
            for i in range(N_STATE):  # it would pull: an ordinary rebound instead
                y_new[i] = y[i]
            e1, e2 = _project(y_new, p, False)
            y_new[T_RESET] = t
            _count(y_new, p, v)
        if _impact(y_new, p, e1, e2, v, kr):
            # the impulse stops the slip: P rolls on the housing, the dry-friction backward whirl
            # (Black 1968, Crandall 1990) that the sliding law cannot carry: stop, as in sliding
            y_new[WHIRL] = 1.0
            return 1
        if whirl_speed(y_new, p) >= 0.0:
            _record(y_new, t)
        return 0
    if k == EV_LIFT:
        _project(y_new, p, True)
        _lift_off(t, y, y_new)
        if whirl_speed(y_new, p) >= 0.0:
            _record(y_new, t)
        return 0
    # EV_WHIRL: self-feeding backward whirl, stop
    y_new[WHIRL] = 1.0
    y_new[T_SLIDE] += t - y[T_START]
    y_new[MODE] = 0.0
    return 1


# --------------------------------------------------------------- the shared contact law at P
# The impact map (3.9) and the sliding force above are the shared law of rotorlab._kernels.contact
# at the Delassus entries below (tests/unit/test_impact_shared_law.py: equal to the printed (3.9)
# on random states). P slides forwards (r_P omega0 = 100 m/s against vibration speeds below about
# 1 m/s) until a backward whirl brings its slip to zero, where a run is stopped (issue 16).


@njit(cache=True, nogil=True)
def delassus(p):
    """Delassus entries ``w_nn, w_nt, w_tt`` (1/kg) of the gap point P in the (n, t) basis.

    The normal speed of P along the cone normal is ``v_n = e . w'`` (``w = sin(beta) u + l_P
    t``), the tangential speed of the material point P along ``e_perp = k x e`` is
    ``e_perp . (u' + h_P t')``; with the impulse map of (3.9) (force ``sin(beta) e`` and
    ``e_perp`` on u, moment ``l_P e`` and ``h_P e_perp`` on t):
    ``w_nn = sin^2(beta)/m + l_P^2/A1 = 1/m*``, ``w_tt = 1/m + h_P^2/A1``, ``w_nt = 0`` (a
    friction impulse does not change the normal speed, as (3.9) says). Translational: no A1 terms.
    """
    wtt = 1.0 / p[P_M]
    if p[P_TRANS] == 0.0:
        wtt += p[P_HP] * p[P_HP] / p[P_A1]
    return p[P_IMS], 0.0, wtt


@njit(cache=True, nogil=True)
def slip_speed(y, p, e1, e2):
    """Slip ``s`` (m/s) of the material point P over the housing along ``e_perp = k x e``.

    The spin's ``r_P omega0`` plus the vibration: ``e_perp . (u' + h_P t' + omega0 k x (u + h_P
    t))`` (rotating-frame velocity of P plus the frame's). Seed 001 neglects the vibration (its
    friction always acts along ``-e_perp``).
    """
    hp = p[P_HP]
    w0 = p[P_W0]
    x1 = y[U1] + hp * y[T1]
    x2 = y[U2] + hp * y[T2]
    v1 = y[DU1] + hp * y[DT1] - w0 * x2
    v2 = y[DU2] + hp * y[DT2] + w0 * x1
    return p[P_RP] * w0 - e2 * v1 + e1 * v2
