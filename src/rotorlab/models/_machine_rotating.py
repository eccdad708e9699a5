"""The composed machine in its co-rotating frame (a part of :class:`rotorlab.models.Machine`):
where the structure is isotropic, without lateral gravity and at a constant speed, steady motions
are equilibria; their linearization, the balanced ball angles and the steady states. See the
equations in :mod:`rotorlab.models._machine`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from rotorlab.models._base import Kernels
from rotorlab.models._jeffcott_physics import Linearization

__all__ = ["EXACT_RTOL", "MachineLinearization", "spectrum_is_stable", "spectrum_verdict"]


#: Real parts within this fraction of the spectral scale count as zero ("marginal").
EXACT_RTOL = 1e-10


def _drop_neutral(values: np.ndarray, count: int) -> np.ndarray:
    """``values`` without the ``count`` of least magnitude (a family's neutral directions)."""
    if count <= 0:
        return values
    order = np.argsort(np.abs(values))
    return values[np.sort(order[count:])]


def spectrum_verdict(eigenvalues, neutral: int = 0, *, scale: float = 0.0,
                     rtol: float = EXACT_RTOL) -> tuple[str, float]:
    """Classify an equilibrium by the eigenvalues of its linearization.

    Parameters
    ----------
    eigenvalues : array_like of complex
        Of the first-order Jacobian (1/s).
    neutral : int
        Eigenvalues of least magnitude left out: the directions along a family of equilibria.
    scale : float
        A rate (1/s) below which the spectral radius is not taken as the scale of zero (the spin
        speed for a steady motion).
    rtol : float
        Real parts within ``rtol * max(spectral radius, scale)`` of zero count as zero.

    Returns
    -------
    (str, float)
        ``"stable"`` (every real part below the tolerance), ``"unstable"`` (one above it) or
        ``"marginal"``, and the largest real part of the eigenvalues kept (1/s).

    Examples
    --------
    >>> spectrum_verdict([-1 + 2j, -1 - 2j, -0.5])
    ('stable', -0.5)
    >>> spectrum_verdict([1e-15 + 1j, 1e-15 - 1j, -3.0])[0]
    'marginal'
    >>> spectrum_verdict([1e-14, -2.0], neutral=1)
    ('stable', -2.0)
    """
    lam = np.asarray(eigenvalues, dtype=complex).reshape(-1)
    rest = _drop_neutral(lam, int(neutral))
    growth = float(np.max(rest.real))
    tol = rtol * max(float(np.max(np.abs(lam))), float(scale))
    return ("stable" if growth < -tol else "unstable" if growth > tol else "marginal"), growth


@dataclass(frozen=True)
class MachineLinearization(Linearization):
    """Linearized co-rotating-frame motion about an equilibrium (constant speed).

    The fields of :class:`rotorlab.models.Linearization`, here for ``q = (z_rotating, psi)``:
    ``A`` (shape (2 n, 2 n)) the first-order Jacobian ``dy'/dy`` of ``[q, q']``; ``M``, ``C``,
    ``G``, ``K`` (shape (n, n)) with ``M q'' + (C + G) q' + K q = 0`` (mass, damping as the
    symmetric part of the velocity matrix, gyroscopic as its skew part, stiffness);
    ``spin_speed`` Omega (rad/s); ``residual`` the rotating-frame dy/dt at the state (zero at an
    equilibrium). Adds :attr:`is_stable`; :func:`spectrum_verdict` classifies its eigenvalues.
    """

    @property
    def is_stable(self) -> bool:
        """All eigenvalues in the open left half-plane, up to round-off (zero modes excluded)."""
        return spectrum_is_stable(self.eigenvalues)


def spectrum_is_stable(eigenvalues) -> bool:
    """No real part above ``1e-9`` of ``max(spectral radius, 1 / s)``: stable, marginal modes (an
    undamped tilt, a family's neutral direction) counted as stable (:attr:`MachineLinearization.is_stable`)."""
    return spectrum_verdict(eigenvalues, scale=1.0, rtol=1e-9)[0] != "unstable"


class _RotatingFrame:
    """Co-rotating frame, linearization and steady states of a :class:`Machine` (mixed in)."""

    # ------------------------------------------------------------------ co-rotating frame
    @property
    def has_rotating_frame(self) -> bool:
        """True where steady motions are equilibria of the co-rotating frame.

        Needs an isotropic structure, no lateral gravity and a constant prescribed speed.
        """
        return self.why_no_rotating_frame() is None

    def why_no_rotating_frame(self) -> str | None:
        """The reason the co-rotating frame has no equilibria, or None if it has."""
        # each attachment says why it has none (balls with friction, gravity across the axis, a
        # drive without a constant speed, a part whose states the frame does not carry)
        reasons = [b.rotating_refusal() for r in self.races for b in r.balls]
        if not self.structure.is_isotropic:
            reasons.append("the structure is anisotropic (its supports differ in x and y): the balls "
                           "and the rotor never reach a steady motion; simulate instead")
        held = self.attachments[:len(self.attachments) - len(self.parts)]  # unbalances, gravity
        reasons += [part.rotating_refusal() for part in held] + [self.drive.rotating_refusal()]
        reasons += [part.rotating_refusal() for part in self.parts]
        return next((why for why in reasons if why), None)

    def why_no_rotating_kernel(self) -> str | None:
        """Why the machine has no compiled co-rotating kernel (:attr:`rotating_kernels`), or None.

        The structure coordinates must come in lateral pairs that turn with the frame (an
        unreduced structure's x/y translations and tilts, or an isotropic structure's x/y mode
        pairs); the frame does not carry a clearance's or a part's own states yet.
        """
        if self.n_modes is not None and not self.structure.is_isotropic:
            return ("the structure is anisotropic and reduced to modes, which do not come in x/y "
                    "pairs: set n_modes = None or simulate in the fixed frame")
        if self.clearances:
            return "the co-rotating kernel does not carry a clearance's states: simulate in the fixed frame"
        with_states = [part.key for part in self.parts if part.kernel().n_states]
        if with_states:
            return (f"the co-rotating kernel does not carry the states of the machine's {with_states[0]}: "
                    "simulate in the fixed frame")
        return None

    @property
    def rotating_kernels(self) -> Kernels:
        """Compiled kernels of the co-rotating frame (:mod:`rotorlab._kernels.machine_corotating`):
        states ``[z_r, z_r', psi, psi', ...]`` (the fixed frame's otherwise,
        :meth:`to_frame`); the fixed frame's equations, turned with the spin.

        Raises
        ------
        ValueError
            With :meth:`why_no_rotating_kernel`'s reason.
        """
        if "rotating_kernels" not in self._cache:
            why = self.why_no_rotating_kernel()
            if why is not None:
                raise ValueError(f"no co-rotating kernel: {why}")
            from rotorlab._kernels.machine_corotating import rotating_kernel_module

            mod = rotating_kernel_module(self.layout)
            kw = dict(rhs=mod.rhs_rotating)
            if self.has_friction:
                kw.update(events=mod.events_rotating, reset=mod.reset_rotating)
            self._cache["rotating_kernels"] = replace(self.kernels, **kw)
        return self._cache["rotating_kernels"]

    def in_rotating_frame(self):
        """This machine with its states in the co-rotating frame, a model that
        :func:`rotorlab.integrate.solve` takes (:class:`rotorlab.models.CoRotatingMachine`).

        Raises
        ------
        ValueError
            With :meth:`why_no_rotating_kernel`'s reason.
        """
        from rotorlab.models._machine_corotating import CoRotatingMachine

        return CoRotatingMachine(self)

    def to_frame(self, t, y, frame: str) -> np.ndarray:
        """Turn full states ``y`` (shape (..., n_state)) at times ``t`` from the other frame into
        ``frame`` (``"fixed"`` or ``"rotating"``): the pairs of structure coordinates by the spin
        angle, their rates with the frame's rate, ball angles and rates by theta and Omega
        (:mod:`rotorlab._kernels.machine_corotating`); every other state is copied."""
        if frame not in ("fixed", "rotating"):
            raise ValueError(f"frame must be 'fixed' or 'rotating', got {frame!r}")
        lay = self.layout
        nz, nb = lay.n_z, lay.n_balls
        y = np.array(y, dtype=float)
        t = np.broadcast_to(np.asarray(t, dtype=float), y.shape[:-1])
        if self.is_motor:
            th, om = y[..., lay.i_theta], y[..., lay.i_theta + 1]
        else:
            th, om = self.drive.spin_angle(t), self.drive.spin_speed(t)
        sg = 1.0 if frame == "fixed" else -1.0
        c, s = np.cos(th)[..., None], sg * np.sin(th)[..., None]
        out = y.copy()
        z, v = y[..., :nz], y[..., nz:2 * nz]
        if frame == "fixed":
            v = v + self._rot_pairs(z, 1.0) * om[..., None]
        for blk, src in ((slice(0, nz), z), (slice(nz, 2 * nz), v)):
            out[..., blk][..., 0::2] = c * src[..., 0::2] - s * src[..., 1::2]
            out[..., blk][..., 1::2] = s * src[..., 0::2] + c * src[..., 1::2]
        if frame == "rotating":
            out[..., nz:2 * nz] -= self._rot_pairs(out[..., :nz], 1.0) * om[..., None]
        out[..., lay.i_phi:lay.i_phi + nb] += sg * th[..., None]
        out[..., lay.i_w:lay.i_w + nb] += sg * om[..., None]
        return out

    def _require_rotating(self) -> float:
        if "why_no_rotating" not in self._cache:  # the machine is frozen: its answer is too
            self._cache["why_no_rotating"] = self.why_no_rotating_frame()
        why = self._cache["why_no_rotating"]
        if why is not None:
            raise ValueError(f"no co-rotating equilibria: {why}")
        return float(self.drive.speed)

    def _rot_pairs(self, a: np.ndarray, om: float) -> np.ndarray:
        """Apply ``Omega J`` (J = [[0, -1], [1, 0]]) to each (even, odd) coordinate pair."""
        out = np.empty_like(a)
        out[..., 0::2] = -om * a[..., 1::2]
        out[..., 1::2] = om * a[..., 0::2]
        return out

    def rotating_to_fixed(self, yr) -> np.ndarray:
        """Convert a co-rotating state ``[z_r, z_r', psi, psi']`` to the fixed frame at t = 0."""
        om = self._require_rotating()
        lay = self.layout
        nz, nb = lay.n_z, lay.n_balls
        yr = np.asarray(yr, dtype=float)
        y = np.zeros(lay.n_state)
        y[:nz] = yr[:nz]
        y[nz:2 * nz] = yr[nz:2 * nz] + self._rot_pairs(yr[:nz], om)
        y[lay.i_phi:lay.i_phi + nb] = yr[2 * nz:2 * nz + nb]
        y[lay.i_w:lay.i_w + nb] = yr[2 * nz + nb:2 * nz + 2 * nb] + om
        return y

    def rotating_rhs(self, yr) -> np.ndarray:
        """Return d/dt of a co-rotating state ``[z_r, z_r', psi, psi']`` (autonomous).

        Evaluated through the compiled fixed-frame kernel at t = 0 (theta = 0), where the frames
        coincide: ``u'' = x'' - 2 Omega J u' + Omega^2 u``, ``psi'' = phi''``.
        """
        return self.rotating_rhs_many(np.asarray(yr, dtype=float)[None, :])[0]

    def rotating_rhs_many(self, yr) -> np.ndarray:
        """:meth:`rotating_rhs` of each row of ``yr`` (shape (k, 2 (n_z + n_balls))), the checks,
        the packed parameters and the kernel looked up once."""
        om = self._require_rotating()
        lay = self.layout
        nz, nb = lay.n_z, lay.n_balls
        yr = np.asarray(yr, dtype=float)
        z, v = yr[:, :nz], yr[:, nz:2 * nz]
        y = np.zeros((yr.shape[0], lay.n_state))
        y[:, :nz] = z
        y[:, nz:2 * nz] = v + self._rot_pairs(z, om)
        y[:, lay.i_phi:lay.i_phi + nb] = yr[:, 2 * nz:2 * nz + nb]
        y[:, lay.i_w:lay.i_w + nb] = yr[:, 2 * nz + nb:2 * nz + 2 * nb] + om
        kernel, p = self.kernels.rhs, self.to_array()
        f = np.empty_like(y)
        for k in range(y.shape[0]):
            kernel(0.0, y[k], p, f[k])
        out = np.empty_like(yr)
        out[:, :nz] = v
        out[:, nz:2 * nz] = f[:, nz:2 * nz] - 2.0 * self._rot_pairs(v, om) + om * om * z
        out[:, 2 * nz:2 * nz + nb] = yr[:, 2 * nz + nb:2 * nz + 2 * nb]
        out[:, 2 * nz + nb:] = f[:, lay.i_w:lay.i_w + nb]
        return out

    def linearize(self, yr) -> MachineLinearization:
        """Linearize the co-rotating equations about ``yr`` (velocities taken as given).

        The Jacobian is a fourth-order central difference of :meth:`rotating_rhs` (relative
        accuracy about 1e-10 on the scale of the entries).
        """
        om = self._require_rotating()
        yr = np.asarray(yr, dtype=float)
        n = yr.size
        nz, nb = self.n_coordinates, self.n_balls  # one step per block: z, z', psi and psi'
        e = np.diag(np.repeat([self._fd_step(j, om) for j in (0, nz, 2 * nz)], [nz, nz, 2 * nb]))
        f = self.rotating_rhs_many(np.concatenate([yr[None, :], yr + e, yr - e, yr + 2 * e, yr - 2 * e]))
        f1, f2 = f[1:n + 1] - f[n + 1:2 * n + 1], f[2 * n + 1:3 * n + 1] - f[3 * n + 1:]
        A = ((8.0 * f1 - f2) / (12.0 * np.diag(e)[:, None])).T
        half = n // 2
        Mf = self.mass_matrix(self.rotating_to_fixed(yr))[: half, : half]
        K = -Mf @ A[half:, :half]
        D = -Mf @ A[half:, half:]
        return MachineLinearization(A=A, M=Mf, C=0.5 * (D + D.T), G=0.5 * (D - D.T), K=K,
                                    spin_speed=om, residual=f[0])

    @property
    def _unbalance_scale(self) -> float:
        """Size of the unbalances (kg m): the sum of the kernel's point unbalances ``m e``."""
        return sum(me for _, _, me, _ in self._point_unbalances)

    def _fd_step(self, j: int, om: float) -> float:
        """Finite-difference step of co-rotating state entry j (m, m/s, rad or rad/s)."""
        nz = self.n_coordinates
        if j >= 2 * nz:
            return 1e-3  # ball angles (rad) and rates (rad/s)
        u = self._unbalance_scale + sum(r.capacity for r in self.races)
        zs = max(u / max(self.structure.total_mass, 1e-300), 1e-12)
        return 1e-3 * zs * (1.0 if j < nz else max(abs(om), 1.0))

    def balance_residual(self, ball_angles) -> np.ndarray:
        """Return the generalised force of the locked balls and unbalances per Omega^2 (kg m).

        ``sum_b m_b l_b B_r^T e_b + sum_u U B_u^T e_u`` at theta = 0: zero in a balanced state.
        """
        psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        m, l, J, c, race = self._ball_arrays
        st = self._stations
        f = np.zeros(self.n_coordinates)
        for b in range(psi.size):
            f += m[b] * l[b] * (st[race[b]].T @ np.array([math.cos(psi[b]), math.sin(psi[b])]))
        for u, (_, _, me, beta) in enumerate(self._point_unbalances):
            f += me * (st[len(self.races) + u].T @ np.array([math.cos(beta), math.sin(beta)]))
        return f

    def balanced_angles(self, guess=None, *, starts: int = 16, seed: int = 0) -> np.ndarray | None:
        """Return ball angles that cancel the unbalance exactly, or None if the balls cannot.

        Solves ``balance_residual(psi) = 0`` (least squares from ``guess`` and ``starts`` random
        starts; accepted below 1e-10 of the unbalance scale).
        """
        from scipy.optimize import least_squares

        nb = self.n_balls
        if nb == 0:
            return None
        scale = max(self._unbalance_scale, 1e-300)
        rng = np.random.default_rng(seed)
        tries = ([np.asarray(guess, float)] if guess is not None else []) + \
            [rng.uniform(0, 2 * np.pi, nb) for _ in range(starts)]
        for x0 in tries:
            res = least_squares(lambda a: self.balance_residual(a) / scale, x0, xtol=1e-15,
                                ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(res.fun)) < 1e-10:
                return np.mod(res.x, 2 * np.pi)
        return None

    def balanced_state(self, ball_angles=None) -> np.ndarray:
        """Return the co-rotating state of the balanced machine: z = 0, balls at rest at their angles.

        Raises
        ------
        ValueError
            If the balls cannot cancel the unbalance or there is no co-rotating frame.
        """
        self._require_rotating()
        psi = self.balanced_angles() if ball_angles is None else np.asarray(ball_angles, float)
        if psi is None:
            raise ValueError("the balls cannot cancel the unbalance (capacity too small or "
                             "races in the wrong planes)")
        return self.rotating_state(ball_angles=psi)

    def steady_state(self, ball_angles=None, *, starts: int = 16, seed: int = 0,
                     near=None) -> np.ndarray | None:
        """Return a co-rotating equilibrium (a steady motion), balanced or not, or None.

        Starts from the balanced state when the balls can cancel the unbalance, else from the
        ball angles that cancel most of it (least squares) with the structure on its locked
        response, and solves ``rotating_rhs(y) = 0`` for the positions (velocities zero) with
        SciPy's hybrid Powell method (Levenberg-Marquardt where it stalls), from each of the
        distinct best partial balances (mirror images); ``near`` (a co-rotating state, e.g. the
        steady motion at a neighbouring speed) is tried first as the start.
        """
        from scipy.optimize import least_squares

        om = self._require_rotating()
        nb = self.n_balls
        psi = self.balanced_angles(ball_angles, starts=starts, seed=seed)
        if psi is not None:
            return self.balanced_state(psi)
        scale = max(self._unbalance_scale, 1e-300)
        rng = np.random.default_rng(seed)
        guesses = ([np.asarray(ball_angles, float)] if ball_angles is not None else []) + \
            [rng.uniform(0, 2 * np.pi, nb) for _ in range(starts)]
        fits = sorted((least_squares(lambda a: self.balance_residual(a) / scale, g) for g in guesses),
                      key=lambda r: r.cost) if nb else []
        # the best partial balances (distinct ball layouts of the least cost; mirror images of
        # each other): the equilibrium solver may converge from one and not from the other
        layouts = [np.zeros(0)] if not fits else []
        for fit in fits:
            if fit.cost > fits[0].cost + 1e-10 * max(fits[0].cost, 1e-300) + 1e-20:
                break
            if all(np.max(np.abs(np.angle(np.exp(1j * (fit.x - q))))) > 1e-6 for q in layouts):
                layouts.append(fit.x)
        K0 = self.reduced["K"] - om * om * self._m0()
        starts_y = [self.rotating_state(ball_angles=q, coordinates=np.linalg.lstsq(
            K0, om * om * self.balance_residual(q), rcond=None)[0]) for q in layouts[:4]]
        if near is not None:
            starts_y.insert(0, np.asarray(near, dtype=float))
        for y0 in starts_y:
            y = self.equilibrium_near(y0)
            if y is not None:
                return y
        return None

    def rotating_state(self, displacements=None, ball_angles=(), *, coordinates=None) -> np.ndarray:
        """Return the co-rotating state at rest ``[z, 0, psi, 0]``.

        Parameters
        ----------
        displacements : array_like, optional
            The structure's nodal coordinates (m, rad), mapped to the reduced coordinates ``z``
            by least squares on :attr:`basis`; zero if neither this nor ``coordinates`` is given.
        ball_angles : array_like
            psi of every ball (rad).
        coordinates : array_like, optional
            ``z`` itself (the reduced coordinates).
        """
        nz, nb = self.n_coordinates, self.n_balls
        y = np.zeros(2 * nz + 2 * nb)
        if coordinates is not None:
            y[:nz] = coordinates
        elif displacements is not None:
            if "basis_pinv" not in self._cache:
                self._cache["basis_pinv"] = np.linalg.pinv(self.basis)
            y[:nz] = self._cache["basis_pinv"] @ np.asarray(displacements, dtype=float)
        y[2 * nz:2 * nz + nb] = ball_angles
        return y

    def equilibrium_near(self, y0) -> np.ndarray | None:
        """Return the co-rotating equilibrium nearest the positions of state ``y0``, or None.

        Solves ``rotating_rhs(y) = 0`` for the positions ``(z, psi)`` (velocities zero) with
        SciPy's hybrid Powell method, Levenberg-Marquardt where it stalls; accepted where every
        acceleration is below ``1e-9`` of the unbalance over the structure's mass times
        ``max(1, Omega^2)``; a start that meets this already is returned as it is (at rest).
        """
        from scipy.optimize import root

        om = self._require_rotating()
        nz, nb = self.n_coordinates, self.n_balls
        y0 = np.asarray(y0, dtype=float)

        def residual(x):
            f = self.rotating_rhs(self.rotating_state(ball_angles=x[nz:], coordinates=x[:nz]))
            return np.concatenate([f[nz:2 * nz], f[2 * nz + nb:]])

        zs = max(self._unbalance_scale / max(self.structure.total_mass, 1e-300), 1e-300)
        tol = 1e-9 * zs * max(1.0, om * om)
        x0 = np.concatenate([y0[:nz], y0[2 * nz:2 * nz + nb]])
        if np.max(np.abs(residual(x0)), initial=0.0) <= tol:
            return self.rotating_state(ball_angles=x0[nz:], coordinates=x0[:nz])
        sol = root(residual, x0, method="hybr", options={"xtol": 1e-13})
        if np.max(np.abs(residual(sol.x))) > tol:
            sol = root(residual, x0, method="lm", options={"xtol": 1e-15, "ftol": 1e-15})
        if np.max(np.abs(residual(sol.x))) > tol:
            return None
        return self.rotating_state(ball_angles=sol.x[nz:], coordinates=sol.x[:nz])

    def reduction_change(self, spin_speed: float) -> float:
        """Relative change of the locked-ball unbalance response when ``n_modes`` doubles.

        Returns ``max |q_2n - q_n| / max |q_2n|`` over the node translations of the steady
        response to the unbalances (balls at rest in their races, treated as point masses on
        the structure) at ``spin_speed``; 0 for an unreduced structure.
        """
        if self.n_modes is None:
            return 0.0
        big = replace(self, n_modes=min(2 * self.n_modes, self.structure.n_dof))
        a = self._locked_response(spin_speed)
        b = big._locked_response(spin_speed)
        return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))

    def _locked_response(self, om: float) -> np.ndarray:
        red = self.reduced
        D = red["K"] + 1j * om * (red["C"] + om * red["G"]) - om * om * self._m0()
        f = np.zeros(self.n_coordinates, dtype=complex)
        st = self._stations
        for u, (_, _, me, beta) in enumerate(self._point_unbalances):
            f += me * om * om * np.exp(1j * beta) * (st[len(self.races) + u].T @ np.array([1.0, -1j]))
        q = self.basis @ np.linalg.solve(D, f)
        return np.concatenate([q[0::4], q[1::4]])
