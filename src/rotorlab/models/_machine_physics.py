"""Initial states, mass matrix and energy of the composed machine (a part of
:class:`rotorlab.models.Machine`; equations in :mod:`rotorlab.models._machine`), and its
structure with the balls locked (its critical speeds).
"""

from __future__ import annotations

import math

import numpy as np

from rotorlab._kernels import machine_codegen as _cg


class _Physics:
    """Initial states, mass matrix, energy and the energy balance of a :class:`Machine` (mixed in)."""

    def initial_state(self, ball_angles=None, *, ball_rates=None, spin_speed: float | None = None,
                      z=None, dz=None, t0: float = 0.0, housing=None) -> np.ndarray:
        """Build a fixed-frame initial state.

        Parameters
        ----------
        ball_angles : array_like, shape (n_b,), optional
            Angles of the balls from the rotor's +x axis (rad), races in order; default equally
            spaced in each race (balanced balls).
        ball_rates : array_like, shape (n_b,), optional
            Rates relative to the rotor (rad/s); default 0 (co-rotating).
        spin_speed : float, optional
            Initial Omega of a motor-driven machine (rad/s), default 0; ignored otherwise.
        z, dz : array_like, shape (n_z,), optional
            Structure coordinates and rates; default at rest at the origin (at the rest position
            under gravity when the clearance is centred there, ``center = "static"``).
        t0 : float
            Initial time (s).
        housing : array_like, shape (4,), optional
            ``(x_h, y_h, vx_h, vy_h)`` of a moving housing (m, m/s); default at rest at 0.

        Returns
        -------
        ndarray, shape (n_state,)
        """
        lay = self.layout
        y = np.zeros(lay.n_state)
        if self.is_motor:
            th, om = 0.0, 0.0 if spin_speed is None else float(spin_speed)
            y[lay.i_theta], y[lay.i_theta + 1] = th, om
        else:
            th, om = self.spin(t0)
        if ball_angles is None:
            psi = np.concatenate([2 * np.pi * np.arange(len(r.balls)) / len(r.balls)
                                  for r in self.races]) if self.races else np.zeros(0)
        else:
            psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        if psi.size != lay.n_balls:
            raise ValueError(f"ball_angles must have {lay.n_balls} entries, got {psi.size}")
        rates = np.zeros(lay.n_balls) if ball_rates is None else np.asarray(ball_rates, float).reshape(-1)
        if rates.size != lay.n_balls:
            raise ValueError(f"ball_rates must have {lay.n_balls} entries, got {rates.size}")
        nz = lay.n_z
        if z is None and self.clearances and self.clearances[0].center == "static":
            # the stator is centred on the rest position under gravity: start there
            zs, hs = self._rest_position()
            y[:nz] = zs
            if self.clearances[0].kind == "housing":
                y[lay.i_clearance:lay.i_clearance + 2] = hs
        if z is not None:
            y[:nz] = np.asarray(z, dtype=float).reshape(nz)
        if dz is not None:
            y[nz:2 * nz] = np.asarray(dz, dtype=float).reshape(nz)
        y[lay.i_phi:lay.i_phi + lay.n_balls] = th + psi
        y[lay.i_w:lay.i_w + lay.n_balls] = om + rates
        if housing is not None:
            if not self.clearances or self.clearances[0].kind != "housing":
                raise ValueError("initial_state: housing given but the machine has no moving housing")
            y[lay.i_clearance:lay.i_clearance + 4] = np.asarray(housing, dtype=float).reshape(4)
        for part, (_, place) in zip(self.attachments, lay.placed_parts):
            part.initial(self, y, place)
        if self.clearances:
            self._clearance_initial(y, om)
        if self.has_friction:
            y = self.initial_modes(t0, y)
        return y

    def initial_modes(self, t: float, y) -> np.ndarray:
        """Return a copy of state ``y`` with stick/slip modes consistent with it.

        As :meth:`rotorlab.models.JeffcottBalls.initial_modes`: a ball with nonzero relative
        speed slips in that direction; at zero relative speed it sticks if the race can hold it
        (stuck balls first), otherwise it slips with the sign of its driving torque.
        """
        y = np.array(y, dtype=float)
        if not self.has_friction:
            return y
        lay = self.layout
        nb, im = lay.n_balls, lay.i_modes
        om = self.spin(float(t), y)[1]
        rel = y[lay.i_w:lay.i_w + nb] - om
        arm = self.to_array()[lay.offsets["friction"]:lay.offsets["friction"] + nb]
        y[im:im + nb] = np.where(rel > 0, 1.0, np.where(rel < 0, -1.0, 0.0))
        y[im:im + nb][arm == 0.0] = 1.0
        terms = _cg.kernel_module(lay).terms
        buf = np.zeros(max(2 * nb, 1))
        for _ in range(nb + 1):
            terms(float(t), y, self.to_array(), -1, buf)
            tq, bound = buf[0::2], buf[1::2]
            bad = [i for i in np.flatnonzero(y[im:im + nb] == 0.0) if abs(tq[i]) > bound[i]]
            if not bad:
                break
            worst = max(bad, key=lambda i: abs(tq[i]) - bound[i])
            y[im + worst] = 1.0 if tq[worst] <= 0 else -1.0
        return y

    # ------------------------------------------------------------------ physics
    def mass_matrix(self, y) -> np.ndarray:
        """Return the full mass matrix over ``(z, phi_b, (theta))`` at state y (symmetric)."""
        lay = self.layout
        y = np.asarray(y, dtype=float)
        nz, nb = lay.n_z, lay.n_balls
        n = nz + nb + (1 if self.is_motor else 0)
        Mf = np.zeros((n, n))
        Mf[:nz, :nz] = self._m0()
        m, l, J, c, race = self._ball_arrays
        st = self._stations
        phi = y[lay.i_phi:lay.i_phi + nb]
        for b in range(nb):
            t = np.array([-math.sin(phi[b]), math.cos(phi[b])])
            col = m[b] * l[b] * (st[race[b]].T @ t)
            Mf[:nz, nz + b] = col
            Mf[nz + b, :nz] = col
            Mf[nz + b, nz + b] = J[b]
        if lay.tilt:  # rigid ball kinematics on a tilting race (module docstring)
            z = y[:nz]
            for b in range(nb):
                T = self.tilt_matrix(self.races[race[b]].node)
                ph = T @ z
                tau = T.T @ np.array([math.cos(phi[b]), math.sin(phi[b])])
                Mf[:nz, :nz] += m[b] * l[b] ** 2 * np.outer(tau, tau)
                col = 0.5 * J[b] * (T.T @ np.array([ph[1], -ph[0]]))
                Mf[:nz, nz + b] += col
                Mf[nz + b, :nz] += col
        if self.is_motor:  # the rotor's parts (unbalances) couple to theta''
            th = y[lay.i_theta]
            w = np.zeros(nz)
            for col in (part.spin_column(self, th) for part in self.attachments):
                if col is not None:
                    w += col
            Mf[:nz, -1] = w
            Mf[-1, :nz] = w
            Mf[-1, -1] = self.drive.polar_inertia
        return Mf

    def energy(self, y, t: float = 0.0) -> float:
        """Mechanical energy ``T + V`` (J) at fixed-frame state y (see the module docstring)."""
        lay = self.layout
        y = np.asarray(y, dtype=float)
        nz, nb = lay.n_z, lay.n_balls
        z, v = y[:nz], y[nz:2 * nz]
        phi, w = y[lay.i_phi:lay.i_phi + nb], y[lay.i_w:lay.i_w + nb]
        om = self.spin(t, y)[1]
        qd = np.concatenate([v, w] + ([[om]] if self.is_motor else []))
        Mf = self.mass_matrix(y)
        kin = 0.5 * qd @ Mf @ qd
        K = self.reduced["K"]
        gx, gy = self.lateral_gravity
        pot = 0.5 * z @ (0.5 * (K + K.T)) @ z  # the weights' -f_g . z: gravity's part
        m, l, J, c, race = self._ball_arrays
        pot -= float(np.sum(m * l * (gx * np.cos(phi) + gy * np.sin(phi))))
        pot += sum(part.energy(self, y, place, t) for part, (_, place) in zip(self.attachments, lay.placed_parts))
        return float(kin + pot + self._clearance_energy(y))

    def energy_balance(self, ts, ys) -> np.ndarray:
        """Return ``work - (E - E_0) - dissipated`` along a trajectory (J); needs energy states.

        Parameters
        ----------
        ts : array_like, shape (N,)
        ys : array_like, shape (N, n_state)
            Saved states of one trajectory with ``energy_states=True``; the work and dissipation
            states start at zero at ``ts[0]`` (as :meth:`initial_state` sets them).
        """
        if not self.energy_states:
            raise ValueError("energy_balance needs a Machine with energy_states=True")
        ie = self.layout.i_energy
        ys = np.asarray(ys, dtype=float)
        e = np.array([self.energy(y, t) for t, y in zip(np.asarray(ts, float), ys)])
        return ys[:, ie] - (e - e[0]) - ys[:, ie + 1]


def locked_structure(machine, *, tilt_inertia: bool = False):
    """Return the structure with the balls locked at their races (``LinearSystem``).

    Each ball of mass m at race radius l and axial offset a from its node is a point mass on the
    race centre ``(x + a phi_x, y + a phi_y)``: the mass ``m e^T e`` (translation m, coupling
    m a, tilt m a^2), as in the kernel's ``M0``. With ``tilt_inertia`` the ball's inertia about
    its place off the axis is added, as for a ring locked to the rotor: ``m l^2 / 2`` about each
    diametral axis (the mean over the ball's angle of the tilting race's ``m l^2 (e_b . phi')^2``
    term) and the polar ``J_b = m l^2 + J_c`` in the gyroscopic matrix (``G[phi_x, phi_y] =
    J_b``, the convention of :class:`rotorlab.linear.RigidBody`; the race-frame term ``J_b phi_b'
    (phi_y phi_x' - phi_x phi_y') / 2`` with ``phi_b' = Omega``), see :mod:`rotorlab.models._machine`.
    """
    from rotorlab.linear import LinearSystem

    s = machine.structure
    M, G = s.M.copy(), s.G.copy()
    for r in machine.races:
        n = 4 * r.node
        e = np.zeros((2, s.n_dof))
        e[0, n], e[1, n + 1] = 1.0, 1.0
        e[0, n + 2] = e[1, n + 3] = r.axial_offset
        M += sum(b.mass for b in r.balls) * (e.T @ e)
        if tilt_inertia:
            for b in r.balls:
                M[n + 2, n + 2] += 0.5 * b.mass * r.radius**2
                M[n + 3, n + 3] += 0.5 * b.mass * r.radius**2
                G[n + 2, n + 3] += b.mass * r.radius**2 + b.inertia
                G[n + 3, n + 2] -= b.mass * r.radius**2 + b.inertia
    return LinearSystem(M=M, C=s.C, G=G, K=s.K, node_position=s.node_position,
                        node_label=s.node_label)


def structure_critical_speeds(machine, max_speed: float | None = None) -> np.ndarray:
    """Forward-whirl 1x critical speeds of the structure with the balls locked (rad/s), their
    inertia about the tilt axes included (:func:`locked_structure` with ``tilt_inertia``)."""
    from rotorlab.linear import critical_speeds

    cs = critical_speeds(locked_structure(machine, tilt_inertia=True), max_speed=max_speed,
                         damped=False)
    return cs.speed[cs.whirl >= 0]
