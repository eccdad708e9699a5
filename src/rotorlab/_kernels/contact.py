"""The rotor-stator contact law as small inlinable kernels, shared by every model with a clearance.

Everything is written in the contact frame of one contact point: ``n`` the unit normal pointing
from the clearance's centre towards the stator (the direction of the gap vector ``w``), ``t = k x n``
the tangent (90 degrees ahead of ``n``, the direction of forward whirl). The contact force on the
rotor is ``-N n + F_t t`` (``N >= 0`` presses the rotor back); an impulse likewise ``-P_n n + P_t t``.

Velocities at the contact point: ``v_n`` (> 0: approaching the stator) and the *slip* speed
``s = u_t + R_r Omega`` (the rotor's surface speed included: a spinning rotor in contact slides even
when its centre stands still). How an impulse changes them is the contact point's *Delassus*
matrix ``W`` (inverse effective mass, symmetric, in the (n, t) basis): for a point mass with
prescribed spin ``W = I / m``; a free spin adds ``R_r^2 / J`` to ``w_tt``; a generalised structure
gives ``W = B H B^T`` (``H`` the inverse mass matrix, ``B`` the map to the contact point).

Laws
----
- :func:`circular_gap`: ``g = delta - |w|`` and the normal; a conical gap is the same law on the
  gap vector ``w = sin(beta) u + l_P theta`` (seed 001): only the map ``B`` differs.
- :func:`newton_coulomb_impulse`: Newton restitution ``v_n+ = -e v_n`` with a Coulomb impulse:
  sticking (``s+ = 0``) when the impulse that stops the slip lies inside the friction cone
  ``|P_t| <= mu P_n``, otherwise sliding with ``P_t = -mu sign(s-) P_n``.
- :func:`impulse_energy`: the exact split of an impulse's energy change into the restitution
  loss, the friction loss (``-P_t (s- + s+) / 2 >= 0``) and the work of the drive that holds the
  spin (``-P_t R_r Omega``): ``Delta T = -loss_n - loss_t + drive``, because the kinetic energy of a
  body with a constant mass matrix changes by ``P . (v- + v+) / 2`` under an impulse ``P``.
- :func:`sustained_forces`: in sustained contact the normal force that keeps the rotor on the
  stator (rigid) and the tangential force that keeps it rolling (stick), from the accelerations
  it would have without them; sliding uses ``F_t = -mu sign(s) N``.
- :func:`penalty_normal_force`: an elastic (massless) stator, ``N = max(0, k_s p + c_s dp/dt)``.

References
----------
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 2-5 (Newton restitution,
Coulomb impulse, energy of an impulse). F. Pfeiffer, C. Glocker, *Multibody Dynamics with
Unilateral Contacts*, Wiley (1996) (Delassus matrix, stick and slip in sustained contact).
"""

import math

from numba import njit


@njit(cache=True, nogil=True, inline="always")
def circular_gap(wx, wy, delta):
    """Gap ``delta - |w|`` (m) and the unit normal ``(n_x, n_y)`` along ``w``.

    At ``w = 0`` the normal is taken along x (the gap is then ``delta`` and no contact is near).
    """
    r = math.sqrt(wx * wx + wy * wy)
    if r > 0.0:
        return delta - r, wx / r, wy / r
    return delta, 1.0, 0.0


@njit(cache=True, nogil=True, inline="always")
def contact_velocities(nx, ny, ux, uy, surface_speed):
    """Normal speed ``v_n = u . n`` (> 0 approaching) and slip ``s = u . t + surface_speed``."""
    return ux * nx + uy * ny, -ux * ny + uy * nx + surface_speed


@njit(cache=True, nogil=True, inline="always")
def newton_coulomb_impulse(vn, s, wnn, wnt, wtt, e, mu):
    """Impulse of an impact with restitution ``e`` and Coulomb friction ``mu``.

    Parameters
    ----------
    vn : float
        Approach speed (m/s), > 0.
    s : float
        Slip speed of the contact point before the impact (m/s).
    wnn, wnt, wtt : float
        Delassus matrix of the contact point in the (n, t) basis (1/kg); the velocity change of
        an impulse ``-P_n n + P_t t`` is ``dv_n = -wnn P_n + wnt P_t``, ``ds = -wnt P_n + wtt P_t``.
    e, mu : float
        Restitution in [0, 1] and friction coefficient >= 0.

    Returns
    -------
    P_n, P_t : float
        Normal impulse (N s, > 0) and tangential impulse (N s).
    stick : bool
        Whether the impulse stops the slip (inside the friction cone).
    """
    # stick: v_n+ = -e v_n and s+ = 0
    det = wnn * wtt - wnt * wnt
    pn = ((1.0 + e) * vn * wtt - wnt * s) / det
    pt = ((1.0 + e) * vn * wnt - wnn * s) / det
    if abs(pt) <= mu * pn:
        return pn, pt, True
    sig = 1.0 if s > 0.0 else -1.0
    pn = (1.0 + e) * vn / (wnn + mu * sig * wnt)
    return pn, -mu * sig * pn, False


@njit(cache=True, nogil=True, inline="always")
def impulse_energy(vn, s, pn, pt, wnn, wnt, wtt, surface_speed):
    """Energy split of an impulse: (restitution loss, friction loss, drive work) (J).

    ``loss_n = P_n (v_n- + v_n+) / 2`` (the normal impulse opposes the approach), ``loss_t =
    -P_t (s- + s+) / 2``, ``drive = -P_t surface_speed``; the kinetic energy of the body changes by
    ``drive - loss_n - loss_t``.
    """
    vn2 = vn - wnn * pn + wnt * pt
    s2 = s - wnt * pn + wtt * pt
    return 0.5 * pn * (vn + vn2), -0.5 * pt * (s + s2), -pt * surface_speed


@njit(cache=True, nogil=True, inline="always")
def sustained_forces(an, at, vt, vn, r, m_eff, rigid, stick):
    """Constraint forces of sustained contact of a point mass ``m_eff`` (N).

    Parameters
    ----------
    an, at : float
        Normal and tangential acceleration of the centre without the contact force (m/s^2).
    vt, vn : float
        Tangential and normal velocity of the centre (m/s); r: its distance from the clearance
        centre (m).
    rigid : bool
        Rigid stator: ``N`` keeps ``|w| = delta`` (``N = m (a_n + v_t^2 / r)``); otherwise ``N``
        is given elsewhere (penalty) and 0 is returned for it.
    stick : bool
        Rolling: ``F_t`` keeps the slip at zero with a constant surface speed,
        ``F_t = m (v_t v_n / r - a_t)``; otherwise 0 (the caller applies ``-mu sign(s) N``).

    Returns
    -------
    N, F_t : float
    """
    n = m_eff * (an + vt * vt / r) if rigid else 0.0
    ft = m_eff * (vt * vn / r - at) if stick else 0.0
    return n, ft


@njit(cache=True, nogil=True, inline="always")
def penalty_normal_force(penetration, penetration_rate, k_s, c_s):
    """Normal force of an elastic massless stator, ``max(0, k_s p + c_s dp/dt)`` (N)."""
    f = k_s * penetration + c_s * penetration_rate
    return f if f > 0.0 else 0.0


@njit(cache=True, nogil=True, inline="always")
def delassus_forces(bn, bs, wnn, wnt, wtt, mu, mode, rigid, n_given):
    """Constraint forces ``N, F_t`` (N) of sustained contact of a general structure.

    The contact point's radial acceleration ``r''`` and slip rate ``s'`` are affine in the
    contact force ``-N n + F_t t`` through the Delassus matrix ``W`` (see
    :func:`newton_coulomb_impulse`): ``r'' = b_n - w_nn N + w_nt F_t``, ``s' = b_s - w_nt N +
    w_tt F_t``, with ``b_n, b_s`` their values without contact force
    (``b_n = a_n + v_t^2 / r``, ``b_s = a_t - v_t v_n / r + R_r Omega'``). A rigid stator holds
    ``r'' = 0`` (``N`` unknown), an elastic one gives ``N = n_given``; rolling (``mode == 2``)
    holds ``s' = 0`` (``F_t`` unknown), sliding with slip sign ``mode = +-1`` has ``F_t = -mu
    mode N``. For a point mass (``W = I / m``) this is :func:`sustained_forces`.
    """
    if mode == 2.0:
        if rigid:
            det = wnn * wtt - wnt * wnt
            return (bn * wtt - wnt * bs) / det, (wnt * bn - wnn * bs) / det
        return n_given, (wnt * n_given - bs) / wtt
    n = bn / (wnn + mu * mode * wnt) if rigid else n_given
    return n, -mu * mode * n
