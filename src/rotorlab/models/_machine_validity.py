"""Where the composed machine's linear structure stops meaning anything (a part of
:class:`rotorlab.models.Machine`): its sanity monitor (kernel contract item 6), which fails a run
whose structure moved further than a linear, small-deflection model describes, or through a rigid
stator (:mod:`rotorlab.models._machine_clearance`).

The structure is linear (``M z'' + (C + Omega G) z' + K z = f``) and the balls ride on it with
small-motion kinematics (:mod:`rotorlab.models._machine`). Its supports, shafts and tilts are
small-deflection idealisations: a station that moves as far from the axis as the machine is
large, or a node that tilts by a large angle, is far beyond them, whatever the equations still
give. A self-excited structure (cross-coupled bearing stiffness, internal damping above the
threshold speed) grows without bound and reaches such states; nothing of the run is then a motion
of the machine.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["DEFLECTION_FRACTION", "CLEARANCE_REACH", "TILT_LIMIT"]

#: A station whose lateral displacement exceeds this fraction of the machine's size
#: (:meth:`_Validity.size_scale`) is beyond the linear structure's validity.
DEFLECTION_FRACTION = 1.0
#: With a clearance, the machine's size is at least this many times the gap plus the stator
#: centre's distance from the axis: a station that far out has crushed its stator many times over
#: (a yielding stator lets the rotor beyond the gap; the contact law is linear in the penetration).
CLEARANCE_REACH = 10.0
#: A node tilted by more than this (rad, about 29 degrees; ``sin`` is then 4 % below the angle)
#: is beyond the small-angle kinematics of the races and the structure.
TILT_LIMIT = 0.5


class _Validity:
    """The machine's validity limits and sanity monitor (mixed into :class:`Machine`)."""

    def size_scale(self, params=None) -> np.ndarray:
        """The machine's own size (m), per parameter row: the largest of its structure's axial
        span, the radii of gyration of its nodes (``sqrt(I / m)``, diametral and polar, from the
        diagonal of M and G), its race radii and, with a clearance, the rotor's radius there and
        :data:`CLEARANCE_REACH` times the gap plus the stator centre's distance from the axis.

        Parameters
        ----------
        params : array_like, shape (n_param,) or (N, n_param), optional
            Packed parameters (the race radii and rotor radius are read from them: an ensemble
            may stack variants); default this machine's.

        Returns
        -------
        ndarray, shape (N,)
        """
        p = np.atleast_2d(self.to_array() if params is None else np.asarray(params, dtype=float))
        s = self.structure
        pos = np.asarray(s.node_position, dtype=float)
        pos = pos[np.isfinite(pos)]
        m = np.diag(s.M)[0::4]
        inertia = np.maximum(np.diag(s.M)[2::4], np.abs(np.diag(s.G, 1)[2::4]))  # diametral, polar
        gyration = np.sqrt(np.divide(inertia, m, out=np.zeros_like(m), where=m > 0))
        size = np.full(p.shape[0], max(float(np.ptp(pos)) if pos.size > 1 else 0.0, float(gyration.max())))
        o = self.layout.offsets
        for b in range(self.layout.n_balls):
            mb, ml = p[:, o["balls"] + 4 * b], p[:, o["balls"] + 4 * b + 1]  # m_b, m_b l_b
            size = np.maximum(size, np.where(mb > 0, ml / np.where(mb > 0, mb, 1.0), 0.0))
        if self.clearances:  # rotor radius R_r; CLEARANCE_REACH times the gap's reach from the axis
            k = o["clearance"]  # [delta, e, mu, R_r, ..., centre x, centre y, ...]
            reach = p[:, k] + np.hypot(p[:, k + 8], p[:, k + 9])
            size = np.maximum(size, np.maximum(p[:, k + 3], CLEARANCE_REACH * reach))
        return size

    def impossible_states(self, ys, y_final, t_final, params) -> list[str]:
        """Sanity monitor (kernel contract item 6, :mod:`rotorlab.models._base`).

        A run fails when

        - the rotor went through a rigid stator or a moving housing (see
          :meth:`_clearance_impossible`);
        - a station moved further from the axis than :data:`DEFLECTION_FRACTION` times the
          machine's size (:meth:`size_scale`), or a node tilted by more than :data:`TILT_LIMIT`:
          beyond the small deflections the linear structure describes (a self-excited structure
          grows there; the message names the station, the value, the limit and the time).
        """
        y_final = np.asarray(y_final, dtype=float)
        n = y_final.shape[0]
        out = self._clearance_impossible(ys, y_final, t_final, params)
        limit = np.broadcast_to(DEFLECTION_FRACTION * self.size_scale(params), (n,))
        ys = np.asarray(ys, dtype=float)
        r, tilt = _largest(self.displacements(y_final)[:, None, :])
        if ys.size:
            rs, ts = _largest(self.displacements(ys))
            r, tilt = np.maximum(r, rs), np.maximum(tilt, ts)
        labels = self.structure.node_label
        far = (limit[:, None] > 0) & (r > limit[:, None])
        bent = tilt > TILT_LIMIT
        for i in np.flatnonzero(far.any(axis=1) | bent.any(axis=1)):
            if out[i]:
                continue
            if far[i].any():
                node = int(np.argmax(r[i]))
                out[i] = (f"station {labels[node]!r} moved {r[i, node]:.3g} m from the axis (by t = "
                          f"{t_final[i]:.6g} s), more than {DEFLECTION_FRACTION:g} times the machine's size "
                          f"{limit[i]:.3g} m (the largest of its axial span, radii of gyration, race and rotor "
                          "radii, reach of the clearance): far beyond the small deflections its linear "
                          "structure describes (a self-excited, unstable structure grows without bound)")
            else:
                node = int(np.argmax(tilt[i]))
                out[i] = (f"node {labels[node]!r} tilted by {tilt[i, node]:.3g} rad (by t = {t_final[i]:.6g} s), "
                          f"more than {TILT_LIMIT:g} rad ({math.degrees(TILT_LIMIT):.3g} deg): far beyond the "
                          "small angles its linear structure describes (a self-excited, unstable structure "
                          "grows without bound)")
        return out


def _largest(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Largest lateral displacement and tilt of every node over the saved states (NaN rows, after
    a trajectory ended, ignored): ``q`` shape (N, n_times, n_dof) -> two arrays (N, n_nodes)."""
    r = np.hypot(q[..., 0::4], q[..., 1::4])
    t = np.hypot(q[..., 2::4], q[..., 3::4])
    return np.where(np.isfinite(r), r, 0.0).max(axis=1), np.where(np.isfinite(t), t, 0.0).max(axis=1)
