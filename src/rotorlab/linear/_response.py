"""Steady unbalance response: amplitude and phase of every DOF versus spin speed."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear._system import LinearSystem

__all__ = ["Unbalance", "unbalance_response"]


@dataclass(frozen=True, slots=True)
class Unbalance:
    """A static unbalance m e turning with the rotor.

    Parameters
    ----------
    node : int
        Node where it acts (>= 0).
    magnitude : float
        m e (kg m), >= 0.
    phase : float
        Angle of the heavy spot from +x at t = 0, in the sense of rotation (rad).

    Examples
    --------
    >>> Unbalance(node=2, magnitude=1e-4).phase
    0.0
    """

    node: int
    magnitude: float
    phase: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.node, bool) or not isinstance(self.node, (int, np.integer)) \
                or self.node < 0:
            raise ValueError(f"Unbalance.node must be an integer >= 0, got {self.node!r}")
        object.__setattr__(self, "node", int(self.node))
        for name, unit, low in (("magnitude", "kg m", 0.0), ("phase", "rad", None)):
            try:
                v = float(getattr(self, name))
            except (TypeError, ValueError):
                v = math.nan
            if not math.isfinite(v) or (low is not None and v < low):
                rule = "a finite number" + ("" if low is None else " >= 0")
                raise ValueError(f"Unbalance.{name} must be {rule} ({unit}), "
                                 f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)


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
          orbit of each node (m); ``orbit_whirl`` (+1 forward, -1 backward).

    Notes
    -----
    The unbalance force at its node is ``m e Omega^2 (cos(Omega t + beta), sin(Omega t +
    beta))``, i.e. complex amplitudes ``F_x = m e Omega^2 exp(i beta)``, ``F_y = -i F_x``; the
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
    F = np.zeros(n, dtype=complex)
    for u in unbalances:
        if u.node >= system.n_nodes:
            raise ValueError(f"Unbalance.node = {u.node} but the system has "
                             f"{system.n_nodes} nodes")
        f = u.magnitude * np.exp(1j * u.phase)
        F[4 * u.node] += f
        F[4 * u.node + 1] += -1j * f
    D = (system.K[None] - (w * w)[:, None, None] * system.M[None]
         + 1j * w[:, None, None] * (system.C[None] + w[:, None, None] * system.G[None]))
    rhs = (w * w)[:, None] * F[None, :]
    with single_threaded_blas():
        Q = np.linalg.solve(D, rhs[:, :, None])[:, :, 0]
    X, Y = Q[:, 0::4], Q[:, 1::4]
    af = np.abs(X + 1j * Y) / 2.0
    ab = np.abs(X - 1j * Y) / 2.0
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
        },
        coords={
            "speed": ("speed", w, {"units": "rad/s"}),
            "speed_rpm": ("speed", w * 30.0 / np.pi, {"units": "rev/min"}),
            "dof": ("dof", np.arange(n), {"units": "1"}),
            "node": ("dof", system.dof_node, {"units": "1"}),
            "direction": ("dof", np.array(system.dof_direction), {"units": "1"}),
            "node_index": ("node_index", np.arange(system.n_nodes), {"units": "1"}),
            "node_position": ("node_index", np.array(system.node_position), {"units": "m"}),
        },
        attrs={"title": "unbalance response",
               "unbalance_nodes": [u.node for u in unbalances],
               "unbalance_magnitudes": [u.magnitude for u in unbalances],
               "unbalance_phases": [u.phase for u in unbalances]},
    )
