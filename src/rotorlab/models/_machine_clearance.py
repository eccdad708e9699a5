"""The clearance of the composed machine (a part of :class:`rotorlab.models.Machine`): gap and
contact helpers, the energy a yielding stator stores, the rub parameters and the sanity checks of
a run with contact. The contact law itself is generated in :mod:`rotorlab._kernels.machine_contact`.
"""

from __future__ import annotations

import math

import numpy as np

from rotorlab._kernels import machine_codegen as _cg
from rotorlab._kernels.contact import circular_gap, contact_velocities
from rotorlab.models._speed import ConstantSpeed


def pressed_contact_mode(gap_vector, gap_rate, surface_speed: float) -> float:
    """Sliding mode of a start pressed into an elastic stator: +1 or -1, the sign of its slip.

    The slip is the contact law's own (:func:`rotorlab._kernels.contact.contact_velocities`):
    ``s = u . t + R_r Omega`` with ``t`` 90 degrees ahead of the normal ``n = w / |w|``, so that
    sliding friction ``F_t = -mu sign(s) N`` opposes it from the first instant and the stick event
    (``sign * s`` falling through 0) can fire. A slip of exactly 0 counts as positive.

    Parameters
    ----------
    gap_vector, gap_rate : array_like, shape (2,)
        ``w`` (m) and ``w'`` (m/s), the gap vector and its rate.
    surface_speed : float
        ``R_r Omega``, the rotor's surface speed at the contact (m/s).
    """
    _, nx, ny = circular_gap.py_func(float(gap_vector[0]), float(gap_vector[1]), 0.0)
    _, s = contact_velocities.py_func(nx, ny, float(gap_rate[0]), float(gap_rate[1]), float(surface_speed))
    return 1.0 if s >= 0.0 else -1.0


class _ClearanceParts:
    """Clearance helpers of a :class:`Machine` (mixed in)."""

    def _clearance_initial(self, y: np.ndarray, om: float) -> None:
        """Contact mode of an initial state: free inside the clearance; pressed into an elastic
        stator, sliding along its slip; beyond a rigid one, an error."""
        c = self.clearances[0]
        w = self.gap_vector(y)
        if c.kind != "elastic" and math.hypot(w[0], w[1]) > c.gap:
            raise ValueError(f"Machine.initial_state: the gap vector {w.tolist()!r} m lies outside the "
                             f"{c.kind} stator (clearance {c.gap:g} m)")
        y[-1] = self._clearance_mode(y, c.gap, c.rotor_radius * om)

    def _clearance_mode(self, y: np.ndarray, gap: float, surface_speed: float) -> float:
        """0 inside the clearance ``gap`` (m) or beyond a rigid stator or housing (the sanity
        check then fails the run), else :func:`pressed_contact_mode` of the gap vector and its rate."""
        c = self.clearances[0]
        w = self.gap_vector(y)
        if c.kind != "elastic" or math.hypot(w[0], w[1]) <= gap:
            return 0.0
        u = self.gap_matrix(c) @ y[self.n_coordinates:2 * self.n_coordinates]
        return pressed_contact_mode(w, u, surface_speed)

    def start_mode(self, y, params, t0: float = 0.0) -> float:
        """Contact mode that the start ``y`` takes under the packed parameters ``params`` (a rub
        map's point: its clearance, rotor radius and, with a prescribed speed, spin at ``t0``);
        see :func:`pressed_contact_mode`."""
        from rotorlab._kernels.speed import profile

        lay = self.layout
        p = np.ascontiguousarray(params, dtype=float)
        kc = lay.offsets["clearance"]
        om = y[lay.i_theta + 1] if self.is_motor else profile(float(t0), p, lay.offsets["speed"])[1]
        return self._clearance_mode(np.asarray(y, dtype=float), float(p[kc]), float(p[kc + 3] * om))

    def _clearance_energy(self, y: np.ndarray) -> float:
        """Energy stored by the clearance: a massless elastic stator's ``k_s p^2 / 2``, a moving
        housing's ``m_s |v_h|^2 / 2 + k_s |x_h|^2 / 2 - m_s g . x_h`` (J)."""
        if not self.clearances:
            return 0.0
        c, lay = self.clearances[0], self.layout
        if c.kind == "rigid":
            return 0.0
        ks = c.stator.stiffness
        if c.kind == "elastic":
            w = self.gap_vector(y)
            pen = max(math.hypot(w[0], w[1]) - c.gap, 0.0)
            return 0.5 * ks * pen * pen
        xh, vh = y[lay.i_clearance:lay.i_clearance + 2], y[lay.i_clearance + 2:lay.i_clearance + 4]
        gx, gy = self.lateral_gravity
        return float(0.5 * c.stator.mass * vh @ vh + 0.5 * ks * xh @ xh
                     - c.stator.mass * (gx * xh[0] + gy * xh[1]))

    def gap_vector(self, y) -> np.ndarray:
        """Return the clearance's gap vector ``w`` (m), shape (..., 2), at states y."""
        if not self.clearances:
            raise ValueError("gap_vector needs a Machine with a clearance")
        y = np.asarray(y, dtype=float)
        w = y[..., :self.n_coordinates] @ self.gap_matrix(self.clearances[0]).T
        if self.clearances[0].kind == "housing":
            i = self.layout.i_clearance
            w = w - y[..., i:i + 2]
        return w - np.asarray(self.clearance_center)

    @property
    def clearance_center(self) -> tuple[float, float]:
        """Centre of the stator's circle (m): the clearance's ``center``, or with ``"static"`` the
        gap vector of the machine at rest under gravity (``B K^-1 f_g`` minus a moving housing's
        own sag ``m_s g / k_s``)."""
        c = self.clearances[0]
        if c.center != "static":
            return c.center
        if "center" not in self._cache:
            zs, hs = self._rest_position()
            w = self.gap_matrix(c) @ zs - hs
            self._cache["center"] = (float(w[0]), float(w[1]))
        return self._cache["center"]

    def _rest_position(self) -> tuple[np.ndarray, np.ndarray]:
        """Structure coordinates ``K^-1 f_g`` and a moving housing's ``m_s g / k_s`` at rest under
        gravity (balls at rest, lumped on their races)."""
        gx, gy = self.lateral_gravity
        try:
            zs = np.linalg.solve(self.reduced["K"], self._weights())
        except np.linalg.LinAlgError:
            raise ValueError('Clearance.center = "static" needs a structure held by its supports '
                             "(its stiffness matrix is singular)") from None
        c = self.clearances[0] if self.clearances else None
        hs = np.zeros(2)
        if c is not None and c.kind == "housing":
            hs = c.stator.mass * np.array([gx, gy]) / c.stator.stiffness
        return zs, hs

    def rest_clearance(self) -> tuple[float, str | None]:
        """Where the clearance station rests under gravity, against the gap.

        At rest (no spin, balls lumped on their races) the structure sits at ``K^-1 f_g``; its gap
        vector from the stator's centre is ``w_s = B K^-1 f_g - c`` (minus a moving housing's own
        sag). The mean of any free motion is this static deflection (gravity is a constant load
        on a linear structure), and the mean of a closed orbit lies inside the orbit's convex
        hull: where ``|w_s|`` exceeds the gap, no motion at any speed stays clear of the stator,
        and from rest the rotor lies on it.

        Returns
        -------
        radius : float
            ``|w_s|`` (m); NaN without a clearance or where the supports do not hold the
            structure (singular stiffness).
        message : str or None
            Names the station, ``|w_s|`` and the gap when ``|w_s|`` exceeds the gap.
        """
        if not self.clearances:
            return math.nan, None
        c = self.clearances[0]
        try:
            zs, hs = self._rest_position()
        except ValueError:
            return math.nan, None
        w = self.gap_matrix(c) @ zs - hs - np.asarray(self.clearance_center)
        radius = float(math.hypot(w[0], w[1]))
        if radius <= c.gap:
            return radius, None
        label = self.structure.node_label[c.node]
        return radius, (f"at rest under gravity the clearance station {label!r} lies {radius * 1e3:.4g} mm from "
                        f"the stator's centre, beyond the gap {c.gap * 1e3:.4g} mm: the rotor rests on the "
                        "stator from the start")

    @property
    def rub_parameters(self) -> dict[str, tuple[int, str]]:
        """Parameters a rub map may vary: name -> (index in :meth:`to_array`, unit).

        ``clearance`` (m), ``restitution``, ``friction``, ``spin_speed`` (rad/s, constant
        prescribed speed), ``unbalance`` (kg m, the first unbalance, without a couple) and ``stator_stiffness``
        (N/m, an elastic stator or housing); empty without a clearance.
        """
        if not self.clearances:
            return {}
        o = self.layout.offsets
        kc = o["clearance"]
        out = {"clearance": (kc, "m"), "restitution": (kc + 1, "1"), "friction": (kc + 2, "1")}
        if isinstance(self.drive, ConstantSpeed):
            out["spin_speed"] = (o["speed"] + 1, "rad/s")
        if self.unbalances and self.unbalances[0].couple == 0.0:  # a couple is two kernel entries
            out["unbalance"] = (self.layout.placed(True)[0][1].param, "kg m")
        if self.clearances[0].kind != "rigid":
            out["stator_stiffness"] = (kc + 5, "N/m")
        return out

    def contact_samples(self, ts, ys, params=None, layout=None):
        """The clearance's contact at saved samples (:class:`rotorlab.contact.ContactSamples`);
        the normal force from the compiled contact law (the generated ``contact_terms`` of
        ``layout``: default this machine's, or a preset's with constants, ``Layout.fixed``)."""
        from rotorlab._kernels.speed import profile
        from rotorlab.models._rub_rotor import ContactSamples, sampled_normal_force

        if not self.clearances:
            raise ValueError("contact_samples needs a Machine with a clearance")
        ys = np.atleast_2d(np.asarray(ys, dtype=float))
        ts = np.broadcast_to(np.asarray(ts, dtype=float), ys.shape[:1])
        p = self.to_array() if params is None else np.ascontiguousarray(params, dtype=float)
        lay, nz = layout or self.layout, self.n_coordinates
        mod = _cg.kernel_module(lay)
        dw = ys[:, nz:2 * nz] @ self.gap_matrix(self.clearances[0]).T
        if self.clearances[0].kind == "housing":
            dw = dw - ys[:, lay.i_clearance + 2:lay.i_clearance + 4]
        mode = ys[:, -1]
        force = sampled_normal_force(ts, ys, mode, lambda t, row: mod.contact_terms(t, row, p, float(row[-1]))[0])
        if self.is_motor:
            spin = ys[:, lay.i_theta + 1]
        else:
            spin = np.array([profile(float(t), p, lay.offsets["speed"])[1] for t in ts])
        return ContactSamples(self.gap_vector(ys), dw, mode, ys[:, -3], ys[:, -2], force, spin)

    def gap_state(self, position=(0.0, 0.0), velocity=(0.0, 0.0)) -> np.ndarray:
        """Initial state with the given gap vector ``w`` (m) and rate ``w'`` (m/s): the structure
        in the mass-weighted shortest shape that has them, balls as in :meth:`initial_state`."""
        if not self.clearances:
            raise ValueError("gap_state needs a Machine with a clearance")
        B = self.gap_matrix(self.clearances[0])
        H = np.linalg.inv(self._m0())
        shape = H @ B.T @ np.linalg.inv(B @ H @ B.T)
        centre = np.asarray(self.clearance_center)
        return self.initial_state(z=shape @ (np.asarray(position, float) + centre),
                                  dz=shape @ np.asarray(velocity, float))

    def whirl_state(self, radius: float, whirl_speed: float) -> np.ndarray:
        """Initial state with the gap vector on a circular whirl: ``w = (radius, 0)``, ``w' =
        (0, whirl_speed radius)`` (see :meth:`gap_state`)."""
        return self.gap_state((radius, 0.0), (0.0, whirl_speed * radius))

    def equivalent_rub_rotor(self):
        """The Jeffcott rotor this machine is at its clearance (:class:`rotorlab.contact.RubRotor`).

        With ``S = H B^T (B H B^T)^-1`` the mass-weighted shortest shape of a unit gap vector
        (``H = M0^-1``): mass ``(B H B^T)^-1``, stiffness ``S^T K S`` and damping ``S^T C S``
        (x entries), eccentricity ``sum U / m``. Exact for one rigid body whose tilt does not
        couple with its translation (the Jeffcott rotor as a machine); a Rayleigh estimate
        otherwise (the closed forms beside a general machine are then approximate).
        """
        from rotorlab.models._rub_rotor import RubRotor

        if not self.clearances:
            raise ValueError("equivalent_rub_rotor needs a Machine with a clearance")
        c = self.clearances[0]
        if c.rotor_radius <= 0.0:
            raise ValueError("the closed forms need the rotor's radius at the contact: set "
                             "Clearance.rotor_radius (> 0 m)")
        B = self.gap_matrix(c)
        H = np.linalg.inv(self._m0())
        Lc = B @ H @ B.T
        S = H @ B.T @ np.linalg.inv(Lc)
        red = self.reduced
        m = 1.0 / Lc[0, 0]
        k = float((S.T @ red["K"] @ S)[0, 0])
        damp = float((S.T @ red["C"] @ S)[0, 0])
        ecc = sum(u.magnitude for u in self.unbalances) / m
        st = c.stator
        kw = {} if st == "rigid" else {"stator_stiffness": st.stiffness, "stator_damping": st.damping,
                                        "stator_mass": st.mass}
        return RubRotor(mass=m, stiffness=k, clearance=c.gap, damping=max(damp, 0.0), eccentricity=ecc,
                        friction=c.friction, rotor_radius=c.rotor_radius, **kw)

    def _clearance_impossible(self, ys, y_final, t_final, params) -> list[str]:
        """The clearance's part of the sanity monitor (:meth:`Machine.impossible_states`): runs
        where the rotor went through a rigid stator (or a moving housing, which it strikes rigidly).

        Beyond ``delta (1 + 1e-6)`` a rebound lower than the integrator resolves was missed
        (raise the clearance's ``rest_speed``): a failed run. The clearance ``delta`` is read from
        ``params`` (one row per run or one for all).
        """
        y_final = np.asarray(y_final, dtype=float)
        n = y_final.shape[0]
        if not self.clearances or self.clearances[0].kind == "elastic":
            return [""] * n
        params = np.atleast_2d(params)
        delta = np.broadcast_to(params[:, self.layout.offsets["clearance"]], (n,))
        ys = np.asarray(ys, dtype=float)
        rad = np.hypot(*np.moveaxis(self.gap_vector(ys), -1, 0)) if ys.size else np.zeros((n, 0))
        r_final = np.hypot(*self.gap_vector(y_final).T)
        out = []
        for i in range(n):
            r = np.concatenate([rad[i][np.isfinite(rad[i])], [r_final[i]]])
            worst = float(r.max())
            if worst <= delta[i] * (1.0 + 1e-6):
                out.append("")
            else:
                out.append(f"the rotor passed through the stator: gap vector {worst:.6g} m, "
                           f"{worst - delta[i]:.3g} m beyond the clearance {delta[i]:g} m (by t = "
                           f"{t_final[i]:.6g} s); a rebound lower than the tolerances resolve was "
                           "missed: raise the clearance's rest_speed")
        return out
