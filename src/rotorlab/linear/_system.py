"""The assembled linear rotor: ``M q'' + (C + Omega G) q' + K q = f`` and its DOF convention.

Degrees of freedom
------------------
Every node (a station on the shaft axis, or a rigid body) carries four DOFs, node-major::

    q[4 n + 0] = x_n      translation along x (m)
    q[4 n + 1] = y_n      translation along y (m)
    q[4 n + 2] = phi_x_n  tilt of the cross-section in the x-z plane (rad): rotation about +y,
                          equal to dx/dz for a Euler-Bernoulli shaft
    q[4 n + 3] = phi_y_n  tilt of the cross-section in the y-z plane (rad): rotation about -x,
                          equal to dy/dz for a Euler-Bernoulli shaft

z is the shaft axis and the rotor spins at ``Omega > 0`` about +z. With this choice both
lateral planes, (x, phi_x) and (y, phi_y), have *identical* element matrices, so an isotropic
machine is literally the same matrix twice, and forward whirl (x + i y turning like
exp(+i omega t)) is the sense of spin. Friswell et al. (2010) use (u, v, theta, psi) with
theta about x and psi about y: ``u = x, v = y, psi = phi_x, theta = -phi_y``. The seed paper
000 (Babenko, Lavrenko, Strackeljan) uses (xi, psi) and (eta, theta) per plane, which maps to
(x, phi_x) and (y, phi_y) with the same signs (see :mod:`rotorlab.linear.cases`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["LinearSystem", "DIRECTIONS", "dof_index"]

#: Names of the four DOFs of a node, in storage order.
DIRECTIONS: tuple[str, str, str, str] = ("x", "y", "phi_x", "phi_y")
_UNITS = {"x": "m", "y": "m", "phi_x": "rad", "phi_y": "rad"}


def dof_index(node: int, direction: str) -> int:
    """Return the global index of one DOF.

    Parameters
    ----------
    node : int
        Node number (>= 0).
    direction : {"x", "y", "phi_x", "phi_y"}
        Which of the node's four DOFs.

    Returns
    -------
    int
        ``4 * node + DIRECTIONS.index(direction)``.

    Examples
    --------
    >>> dof_index(2, "phi_x")
    10
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    if int(node) != node or node < 0:
        raise ValueError(f"node must be an integer >= 0, got {node!r}")
    return 4 * int(node) + DIRECTIONS.index(direction)


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float, copy=True)
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class LinearSystem:
    """Matrices of a linear rotor at constant spin speed, with the DOF bookkeeping.

    The equations of motion are ``M q'' + (C + Omega G) q' + K q = f(t)``, with ``Omega``
    the spin speed (rad/s) of the spinning parts.

    Parameters
    ----------
    M : array_like, shape (n, n)
        Mass matrix (kg, kg m, kg m^2), symmetric positive definite.
    C : array_like, shape (n, n)
        Viscous damping matrix (N s/m, ...), any real matrix (bearing cross terms make it
        non-symmetric).
    G : array_like, shape (n, n)
        Gyroscopic matrix per unit spin speed (kg m^2), skew-symmetric.
    K : array_like, shape (n, n)
        Stiffness matrix (N/m, N/rad, N m/rad), real; symmetric unless bearings have
        cross-coupled stiffness.
    node_position : array_like, shape (n // 4,), optional
        Axial position z of each node (m); NaN where unknown. Used for plotting mode shapes and
        as the length scale that weights tilts against translations in whirl classification.
    node_label : tuple of str, optional
        A name per node (e.g. ``"rotor"``); defaults to ``"0", "1", ...``.

    Raises
    ------
    ValueError
        If a matrix has the wrong shape, is not finite, if ``n`` is not a multiple of 4, if M is
        not symmetric positive definite or G not skew-symmetric.

    Examples
    --------
    >>> import numpy as np
    >>> s = LinearSystem(M=np.eye(4), C=np.zeros((4, 4)), G=np.zeros((4, 4)), K=np.eye(4))
    >>> s.n_dof, s.n_nodes, s.is_undamped
    (4, 1, True)
    """

    M: np.ndarray
    C: np.ndarray
    G: np.ndarray
    K: np.ndarray
    node_position: np.ndarray | None = None
    node_label: tuple[str, ...] | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        M = _frozen(self.M)
        n = M.shape[0] if M.ndim == 2 else -1
        if M.ndim != 2 or M.shape != (n, n) or n == 0 or n % 4:
            raise ValueError(f"LinearSystem.M must be square with a size that is a multiple of 4, "
                             f"got shape {np.shape(self.M)}")
        for name in ("M", "C", "G", "K"):
            a = _frozen(getattr(self, name))
            if a.shape != (n, n):
                raise ValueError(f"LinearSystem.{name} must have shape {(n, n)}, got {a.shape}")
            if not np.all(np.isfinite(a)):
                raise ValueError(f"LinearSystem.{name} must be finite")
            object.__setattr__(self, name, a)
        scale = max(np.abs(self.M).max(), 1e-300)
        if np.abs(self.M - self.M.T).max() > 1e-10 * scale:
            raise ValueError("LinearSystem.M must be symmetric")
        try:
            np.linalg.cholesky(self.M)
        except np.linalg.LinAlgError:
            raise ValueError("LinearSystem.M must be positive definite (every DOF needs mass or "
                             "inertia; give massless stations a small inertia or condense them)"
                             ) from None
        gscale = max(np.abs(self.G).max(), 1e-300)
        if np.abs(self.G + self.G.T).max() > 1e-10 * gscale:
            raise ValueError("LinearSystem.G must be skew-symmetric")
        nn = n // 4
        if self.node_position is None:
            pos = np.full(nn, np.nan)
        else:
            pos = np.asarray(self.node_position, dtype=float).reshape(-1)
            if pos.shape != (nn,):
                raise ValueError(f"LinearSystem.node_position must have shape ({nn},), "
                                 f"got {pos.shape}")
        object.__setattr__(self, "node_position", _frozen(pos))
        if self.node_label is None:
            labels = tuple(str(i) for i in range(nn))
        else:
            labels = tuple(str(s) for s in self.node_label)
            if len(labels) != nn:
                raise ValueError(f"LinearSystem.node_label must have {nn} entries, "
                                 f"got {len(labels)}")
        object.__setattr__(self, "node_label", labels)

    # ------------------------------------------------------------------ bookkeeping
    @property
    def n_dof(self) -> int:
        """Number of DOFs ``n``."""
        return self.M.shape[0]

    @property
    def n_nodes(self) -> int:
        """Number of nodes ``n / 4``."""
        return self.M.shape[0] // 4

    @property
    def dof_node(self) -> np.ndarray:
        """Node of each DOF, shape (n,)."""
        return np.repeat(np.arange(self.n_nodes), 4)

    @property
    def dof_direction(self) -> tuple[str, ...]:
        """Direction name of each DOF (``"x"``, ``"y"``, ``"phi_x"``, ``"phi_y"``)."""
        return DIRECTIONS * self.n_nodes

    @property
    def dof_unit(self) -> tuple[str, ...]:
        """Unit of each DOF (``"m"`` or ``"rad"``)."""
        return tuple(_UNITS[d] for d in self.dof_direction)

    @property
    def total_mass(self) -> float:
        """Mass moved by a unit rigid translation along x, ``e^T M e`` (kg)."""
        e = np.zeros(self.n_dof)
        e[0::4] = 1.0
        return float(e @ self.M @ e)

    @property
    def length_scale(self) -> float:
        """Length (m) that makes a tilt comparable to a translation: the node span, or 1 m."""
        pos = self.node_position[np.isfinite(self.node_position)]
        span = float(pos.max() - pos.min()) if pos.size > 1 else 0.0
        return span if span > 0 else 1.0

    # ------------------------------------------------------------------ structure tests
    @property
    def is_undamped(self) -> bool:
        """True when C is exactly zero."""
        return not np.any(self.C)

    @property
    def is_conservative(self) -> bool:
        """True when C = 0 and K is symmetric (no circulatory forces)."""
        key = "conservative"
        if key not in self._cache:
            kscale = max(np.abs(self.K).max(), 1e-300)
            self._cache[key] = self.is_undamped and bool(
                np.abs(self.K - self.K.T).max() <= 1e-12 * kscale)
        return self._cache[key]

    @property
    def is_isotropic(self) -> bool:
        """True when the system is unchanged by turning the x-y plane through 90 degrees.

        Then ``M, C, K`` are ``[[A, B], [-B, A]]`` and ``G`` is ``[[0, R], [-R, 0]]`` in
        (x-plane, y-plane) blocks and the complex coordinate ``x + i y`` decouples the planes.
        """
        key = "isotropic"
        if key not in self._cache:
            xp, yp = self.plane_indices
            ok = True
            for name, a in (("M", self.M), ("C", self.C), ("K", self.K), ("G", self.G)):
                scale = max(np.abs(a).max(), 1e-300)
                tol = 1e-12 * scale
                app, aqq = a[np.ix_(xp, xp)], a[np.ix_(yp, yp)]
                apq, aqp = a[np.ix_(xp, yp)], a[np.ix_(yp, xp)]
                if name == "G":
                    ok &= bool(np.abs(app).max() <= tol and np.abs(aqq).max() <= tol)
                    ok &= bool(np.abs(apq + aqp).max() <= tol)
                else:
                    ok &= bool(np.abs(app - aqq).max() <= tol and np.abs(apq + aqp).max() <= tol)
            self._cache[key] = ok
        return self._cache[key]

    @property
    def plane_indices(self) -> tuple[np.ndarray, np.ndarray]:
        """Indices of the x-plane DOFs (x, phi_x per node) and of the y-plane DOFs."""
        base = 4 * np.arange(self.n_nodes)
        xp = np.stack([base, base + 2], axis=1).reshape(-1)
        yp = np.stack([base + 1, base + 3], axis=1).reshape(-1)
        return xp, yp

    def dynamic_stiffness(self, speed: float, s: complex) -> np.ndarray:
        """Return ``K + s (C + speed G) + s^2 M`` (the Laplace-domain operator).

        Parameters
        ----------
        speed : float
            Spin speed Omega (rad/s).
        s : complex
            Laplace variable (1/s); ``s = i omega`` for harmonic motion.

        Returns
        -------
        ndarray, shape (n, n), complex
        """
        return self.K + s * (self.C + speed * self.G) + s * s * self.M

    def without_damping(self) -> LinearSystem:
        """Return a copy with C = 0."""
        return LinearSystem(M=self.M, C=np.zeros_like(self.C), G=self.G, K=self.K,
                            node_position=self.node_position, node_label=self.node_label)
