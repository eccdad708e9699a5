"""Steady unbalance response: amplitude and phase of every DOF versus spin speed."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear._system import LinearSystem
from rotorlab.linear._unbalance import Unbalance

__all__ = ["Unbalance", "unbalance_response"]


def unbalance_response(system: LinearSystem, speeds: Sequence[float],
                       unbalances: Sequence[Unbalance]) -> xr.Dataset:
    """Compute the steady response to rotating unbalances over a range of spin speeds.

    Parameters
    ----------
    system : LinearSystem
    speeds : sequence of float
        Spin speeds Omega (rad/s).
    unbalances : sequence of Unbalance

    Returns
    -------
    xarray.Dataset
        Dims ``speed`` and ``dof`` (with ``node``, ``direction`` coordinates) and ``node``:

        * ``amplitude`` (speed, dof): ``|Q|`` (m or rad);
        * ``phase`` (speed, dof): ``arg Q`` (rad), the motion being ``|Q| cos(Omega t +
          phase)``; a lag behind the heavy spot is negative;
        * ``response_real``, ``response_imag`` (speed, dof): Q itself;
        * ``orbit_major``, ``orbit_minor`` (speed, node_index): semi-axes of the translational
          orbit of each node (m); ``orbit_whirl`` (+1 forward, -1 backward);
        * ``peak_orbit``, ``peak_speed`` (node_index): the largest orbit semi-axis of each
          node (m) and its speed (rad/s), located between the grid speeds around the grid's
          maximum (a lightly damped resonance is narrower than the grid). Without damping
          the response is unbounded at the critical speeds: ``peak_orbit`` is inf,
          ``peak_speed`` NaN, and ``attrs["note"]`` says so.

    Notes
    -----
    The unbalance force at its node is ``m e Omega^2 (cos(Omega t + beta), sin(Omega t +
    beta))``, i.e. complex amplitudes ``F_x = m e Omega^2 exp(i beta)``, ``F_y = -i F_x``, and the
    moment on the tilts that of the axial offset and of the couple (:class:`Unbalance`); the
    response solves ``(K - Omega^2 M + i Omega (C + Omega G)) Q = F`` at every speed (one
    batched LAPACK solve). The orbit ``x + i y = a_f exp(i Omega t) + a_b exp(-i Omega t)`` has
    semi-axes ``|a_f| + |a_b|`` and ``||a_f| - |a_b||``.

    References
    ----------
    Friswell et al. (2010), Chapters 3 and 6 (response to out-of-balance forces).

    Examples
    --------
    >>> from rotorlab.linear import Bearing, RigidBody, assemble
    >>> s = assemble([RigidBody(0, 1.0, 1e-2), Bearing(0, kxx=1e4, k_tilt_x=1e2)])
    >>> ds = unbalance_response(s, [1000.0], [Unbalance(0, 1e-3)])
    >>> round(float(ds.orbit_major[0, 0]), 9)  # m e W^2 / |k - m W^2|, far above resonance
    0.001010101
    """
    w = np.atleast_1d(np.asarray(speeds, dtype=float))
    if w.ndim != 1 or not np.all(np.isfinite(w)):
        raise ValueError("speeds must be a finite 1-D sequence (rad/s)")
    n = system.n_dof
    F = _force(system, unbalances)
    Q = _solve(system, F, w)
    X, Y = Q[:, 0::4], Q[:, 1::4]
    af = np.abs(X + 1j * Y) / 2.0
    ab = np.abs(X - 1j * Y) / 2.0
    peak_speed, peak_orbit, note = _peaks(system, F, w, af + ab)
    return xr.Dataset(
        {
            "amplitude": (("speed", "dof"), np.abs(Q), {"units": "m or rad"}),
            "phase": (("speed", "dof"), np.angle(Q), {"units": "rad"}),
            "response_real": (("speed", "dof"), Q.real, {"units": "m or rad"}),
            "response_imag": (("speed", "dof"), Q.imag, {"units": "m or rad"}),
            "orbit_major": (("speed", "node_index"), af + ab, {"units": "m"}),
            "orbit_minor": (("speed", "node_index"), np.abs(af - ab), {"units": "m"}),
            "orbit_whirl": (("speed", "node_index"), np.sign(af - ab).astype(np.int8),
                            {"units": "1", "flag_values": [1, -1, 0],
                             "flag_meanings": "forward backward straight"}),
            "peak_speed": ("node_index", peak_speed, {"units": "rad/s", "long_name":
                           "speed of the largest orbit, refined between grid speeds"}),
            "peak_orbit": ("node_index", peak_orbit, {"units": "m", "long_name":
                           "largest orbit semi-axis (inf: undamped, unbounded)"}),
        },
        coords={
            "speed": ("speed", w, {"units": "rad/s"}),
            "speed_rpm": ("speed", w * RPM_PER_RAD_S, {"units": "rev/min"}),
            "dof": ("dof", np.arange(n), {"units": "1"}),
            "node": ("dof", system.dof_node, {"units": "1"}),
            "direction": ("dof", np.array(system.dof_direction), {"units": "1"}),
            "node_index": ("node_index", np.arange(system.n_nodes), {"units": "1"}),
            "node_position": ("node_index", np.array(system.node_position), {"units": "m"}),
        },
        attrs={"title": "unbalance response",
               "unbalance_nodes": [u.node for u in unbalances],
               "unbalance_magnitudes": [u.magnitude for u in unbalances],
               "unbalance_phases": [u.phase for u in unbalances],
               "unbalance_axial_offsets": [u.axial_offset for u in unbalances],
               "unbalance_couples": [u.couple for u in unbalances],
               "unbalance_couple_phases": [u.couple_phase for u in unbalances],
               **({"note": note} if note else {})},
    )


def _force(system: LinearSystem, unbalances: Sequence[Unbalance]) -> np.ndarray:
    F = np.zeros(system.n_dof, dtype=complex)
    for u in unbalances:
        if u.node >= system.n_nodes:
            raise ValueError(f"Unbalance.node = {u.node} but the system has "
                             f"{system.n_nodes} nodes")
        F[4 * u.node:4 * u.node + 4] += u.node_force()
    return F


def _solve(system: LinearSystem, F: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Complex amplitudes Q (speed, dof) at the speeds ``w``."""
    D = (system.K[None] - (w * w)[:, None, None] * system.M[None]
         + 1j * w[:, None, None] * (system.C[None] + w[:, None, None] * system.G[None]))
    rhs = (w * w)[:, None] * F[None, :]
    with single_threaded_blas():
        return np.linalg.solve(D, rhs[:, :, None])[:, :, 0]


def _orbit(system: LinearSystem, F: np.ndarray, speed: float, node: int) -> float:
    Q = _solve(system, F, np.array([speed]))[0]
    z = Q[4 * node] + 1j * Q[4 * node + 1], Q[4 * node] - 1j * Q[4 * node + 1]
    return (abs(z[0]) + abs(z[1])) / 2.0


def _peaks(system: LinearSystem, F: np.ndarray, w: np.ndarray,
           orbit: np.ndarray) -> tuple[np.ndarray, np.ndarray, str]:
    """Largest orbit of every node and its speed, refined between the grid speeds.

    A lightly damped resonance is narrower than any practical speed grid: the grid maximum is
    only a bracket, and the peak is located in it by a bounded scalar minimisation (Brent's
    method, scipy.optimize.minimize_scalar). Without any damping the response is unbounded at
    the critical speeds: the peak is then inf at no particular speed, and a note says so.
    """
    n_nodes = orbit.shape[1]
    if not np.any(system.C) and F.any():
        from rotorlab.linear._critical import critical_speeds

        crit = critical_speeds(system, harmonics=(1,), max_speed=float(w.max()), damped=False).speed
        inside = np.unique(np.round(crit[(crit >= w.min()) & (crit <= w.max())], 9))
        where = (", ".join(f"{c * RPM_PER_RAD_S:.6g}" for c in inside) + " rpm") if inside.size \
            else "none in this speed range"
        note = ("undamped rotor: the response is unbounded at the critical speeds "
                f"({where}); the orbits on the speed grid depend on how close the grid comes")
        return (np.full(n_nodes, np.nan), np.where(np.any(orbit > 0, axis=0), np.inf, 0.0),
                note)
    from scipy.optimize import minimize_scalar

    speeds, peaks = np.full(n_nodes, np.nan), np.zeros(n_nodes)
    for node in range(n_nodes):
        column = orbit[:, node]
        if not np.isfinite(column).any() or not column.any():
            continue
        k = int(np.nanargmax(column))
        best_w, best = float(w[k]), float(column[k])
        lo, hi = float(w[max(k - 1, 0)]), float(w[min(k + 1, w.size - 1)])
        if hi > lo:
            res = minimize_scalar(lambda s, node=node: -_orbit(system, F, s, node),
                                  bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-10 * hi})
            if -res.fun > best:
                best_w, best = float(res.x), float(-res.fun)
        speeds[node], peaks[node] = best_w, best
    return speeds, peaks, ""
