"""The sanity monitor of ``impact_rotor`` (kernel contract item 6): penetration beyond the
clearance and energy created, read from the energy ledger the kernel keeps
(:mod:`rotorlab._kernels.impact_rotor`). :meth:`rotorlab.models.ImpactRotor.impossible_states`
calls :func:`impossible_states`."""

from __future__ import annotations

import numpy as np

from rotorlab._kernels import impact_rotor as _k

__all__ = ["ENERGY_TOLERANCE", "impossible_states"]

#: Energy created beyond the ledger's bound that fails a run, relative to the energy that went
#: through the ledger (see :func:`impossible_states`).
ENERGY_TOLERANCE = 1e-3


def impossible_states(ys, y_final, t_final, params) -> list[str]:
    """Return, per run of ``impact_rotor``, why its result is physically impossible (empty if not).

    Two checks, on the records the kernel keeps (the same on the scalar and the lane driver):

    - **penetration beyond the clearance.** The housing is rigid and every approach of P is
      caught by the impact event, so P can exceed the gap only by the event-location
      tolerance. ``|w| - Delta > Delta`` (at an impact or projection, or in a saved state)
      means the impacts no longer hold the rotor (issue 14: 1.4 million "impacts" in 2 s,
      penetration 2e6 m, with seed 001's own impulse arithmetic).
    - **energy created.** The energy ledger of :mod:`rotorlab._kernels.impact_rotor`: the
      fixed-frame vibration energy ``E`` changes by ``W_NC + W_DRIVE - E_REST - E_FRIC``
      (work between impulses; the drive's work through the friction impulses, less what
      restitution and friction took). The sources are the stones (``W_ST``) and the drive
      (``W_DRIVE``, and ``f r_P omega0 int N dt`` in sliding); the membranes' friction and
      the friction heat in sliding (``W_ST + f r_P omega0 int N dt - W_NC``), restitution
      and the friction heat of the impulses only take energy away. A run whose energy rose
      above the ledger, or in which one of those losses is negative, created energy (a
      missed impact, a law pushing P along its slip). Tolerance: ``ENERGY_TOLERANCE`` times
      the energy that went through the ledger (``E_0 + |W_ST| + W_DRIVE + f r_P omega0 int
      N dt``). Why: the ledger closes to the integration error, first order in ``rtol``
      (3e-8 of that at the case files' ``rtol = 1e-8``, ``tests/unit/test_impact_ledger.py``);
      the check is for energy created at the scale of the budget (issue 14's run: 1.4e6
      times it), not for integration error, and 1e-3 leaves that room up to ``rtol`` of
      about 1e-5.

    An accumulation of impacts in finite time that the chatter rule (``rest_speed``) does
    not turn into sliding contact ends the run with the integrator's own failed status
    ``EVENT_LOOP`` (events firing without time advancing).

    Parameters
    ----------
    ys : ndarray, shape (N, n_save, 28)
    y_final : ndarray, shape (N, 28)
    t_final : ndarray, shape (N,)
    params : ndarray, shape (N or 1, n_param)
        Packed parameters (:meth:`ImpactRotor.to_array`) of each run.

    Returns
    -------
    list of str
        Per run, empty or the message naming the check and its numbers.
    """
    ys, y_final, params = np.asarray(ys, float), np.asarray(y_final, float), np.atleast_2d(params)
    n = y_final.shape[0]

    def col(i):
        return np.broadcast_to(params[:, i], (n,))

    gap, sb, lp = col(_k.P_GAP), col(_k.P_SB), col(_k.P_LP)
    pen = y_final[:, _k.PEN_MAX]
    if ys.shape[1]:
        w1 = sb[:, None] * ys[:, :, _k.U1] + lp[:, None] * ys[:, :, _k.T1]
        w2 = sb[:, None] * ys[:, :, _k.U2] + lp[:, None] * ys[:, :, _k.T2]
        with np.errstate(invalid="ignore"):
            pen = np.fmax(pen, np.nanmax(np.hypot(w1, w2), axis=1, initial=0.0) - gap)
    energy = np.array([_k.fixed_energy(y_final[i], params[i if params.shape[0] > 1 else 0]) for i in range(n)])
    yf = y_final
    slide_drive = col(_k.P_F) * col(_k.P_RP) * col(_k.P_W0) * yf[:, _k.INT_N]
    gain = energy - yf[:, _k.E_0]
    allowed = yf[:, _k.W_NC] + yf[:, _k.W_DRIVE] - yf[:, _k.E_REST] - yf[:, _k.E_FRIC]
    between = yf[:, _k.W_ST] + slide_drive - yf[:, _k.W_NC]  # membranes' friction + sliding heat
    created = np.max(np.stack([gain - allowed, -between, -yf[:, _k.E_REST], -yf[:, _k.E_FRIC]]), axis=0)
    scale = np.abs(yf[:, _k.E_0]) + np.abs(yf[:, _k.W_ST]) + np.abs(yf[:, _k.W_DRIVE]) + np.abs(slide_drive)
    tol = ENERGY_TOLERANCE * scale + 1e-12
    out = []
    for i in range(n):
        after = f"by t = {t_final[i]:.6g} s after {int(yf[i, _k.N_ALL])} impacts"
        if pen[i] > gap[i]:
            out.append(f"the gap point P went {pen[i]:.3g} m through the housing (gap {gap[i]:.3g} m) {after}: "
                       "the impacts no longer hold the rotor (restitution near 1 with heavy stones?)")  # fmt: skip
        elif created[i] > tol[i]:
            out.append(f"energy created: the vibration energy rose by {gain[i]:.4g} J {after}; the stones "
                       f"supplied {yf[i, _k.W_ST]:.4g} J and the drive {yf[i, _k.W_DRIVE] + slide_drive[i]:.4g} J, "
                       f"and the ledger allows {allowed[i]:.4g} J (lost by restitution {yf[i, _k.E_REST]:.4g} J, "
                       f"by friction at the impacts {yf[i, _k.E_FRIC]:.4g} J, by the membranes and in sliding "
                       f"{between[i]:.4g} J): {created[i]:.3g} J created (tolerance {tol[i]:.3g} J; "
                       "tolerances too loose?)")  # fmt: skip
        else:
            out.append("")
    return out
