"""Eigen-solvers of ``M q'' + (C + Omega G) q' + K q = 0`` over many speeds, by structure.

Every solver returns, per speed, one eigenvalue per *mode* (the representative of a complex
conjugate pair, ``Im(lambda) >= 0``), the displacement mode shape and a normalised vector used
to track the mode across speeds. The matrices that do not depend on speed are factorised once;
each speed costs one LAPACK call on a small matrix, and all speeds go to LAPACK in one batched
call (``numpy.linalg.eigh``/``eig`` on a stack).

Methods (``method=`` of :func:`rotorlab.linear.campbell` and :func:`rotorlab.linear.modal`):

``"isotropic-hermitian"``
    Isotropic (axisymmetric) and conservative, K positive definite. In the complex coordinate
    ``w = (x, phi_x) + i (y, phi_y)`` the planes decouple, ``M_p w'' - i Omega G_r w' + K_p w =
    0``, and with ``M_p = L_M L_M^T``, ``K_p = L_K L_K^T``, ``z = (L_M^T w', L_K^T w)`` this is
    ``z' = i H z`` with ``H = [[Omega G~, i B], [-i B^T, 0]]`` Hermitian of size n/2
    (``B = L_M^-1 L_K``, ``G~ = L_M^-1 G_r L_M^-T``). Its real eigenvalues are the whirl
    frequencies, positive for forward and negative for backward whirl: classification is exact.
``"hermitian"``
    Conservative (C = 0, K symmetric positive definite): the same energy coordinates for the
    real system give a real skew-symmetric first-order matrix, i.e. a Hermitian ``H`` of size
    2n whose positive eigenvalues are the natural frequencies.
``"isotropic"``
    Isotropic with damping or circulatory terms: the complex-coordinate first-order system of
    size n (complex), solved with a general eigen-solver.
``"state-space"``
    Anything: ``A = [[0, I], [-M^-1 K, -M^-1 (C + Omega G)]]`` of size 2n.
``"dense"``
    The reference: the generalised problem ``[[0, I], [-K, -(C + Omega G)]] x = lambda [[I, 0],
    [0, M]] x`` solved with ``scipy.linalg.eig`` speed by speed (what peer codes do).

References
----------
Friswell et al. (2010), Chapters 3 and 5 (state-space eigenproblem, forward/backward
whirl); Meirovitch (1974) for the Hermitian form of gyroscopic conservative systems.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import scipy.linalg

from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear._system import LinearSystem

__all__ = ["METHODS", "Spectrum", "Solver", "whirl_of_shapes"]

METHODS = ("auto", "isotropic-hermitian", "hermitian", "isotropic", "state-space", "dense")


class Spectrum(NamedTuple):
    """Raw eigen-solution at S speeds with m modes each.

    eigenvalues : (S, m) complex, Im >= 0 (1/s)
    shapes : (S, m, n) complex displacement shapes (unnormalised)
    track : (S, m, p) complex unit vectors for MAC tracking
    """

    eigenvalues: np.ndarray
    shapes: np.ndarray
    track: np.ndarray


def _chol(a: np.ndarray) -> np.ndarray | None:
    try:
        return np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return None


class Solver:
    """Factorise a system once and solve its eigenproblem at any speeds.

    Parameters
    ----------
    system : LinearSystem
    method : str
        One of :data:`METHODS`; ``"auto"`` picks the cheapest exact method the structure allows
        (isotropic-hermitian > hermitian > isotropic > state-space).
    """

    def __init__(self, system: LinearSystem, method: str = "auto") -> None:
        if method not in METHODS:
            raise ValueError(f"method must be one of {METHODS}, got {method!r}")
        self.system = system
        s = system
        xp, yp = s.plane_indices
        self._xp, self._yp = xp, yp
        if method == "auto":
            method = self._pick()
        self.method = method
        with single_threaded_blas():
            self._setup(method)

    def _setup(self, method: str) -> None:
        s = self.system
        xp, yp = self._xp, self._yp
        if method == "isotropic-hermitian":
            self._setup_hermitian(s.M[np.ix_(xp, xp)], s.K[np.ix_(xp, xp)],
                                  s.G[np.ix_(xp, yp)], complex_coordinate=True)
        elif method == "hermitian":
            self._setup_hermitian(s.M, s.K, s.G, complex_coordinate=False)
        elif method == "isotropic":
            if not s.is_isotropic:
                raise ValueError("method 'isotropic' needs an isotropic system")
            mp = s.M[np.ix_(xp, xp)]
            kc = s.K[np.ix_(xp, xp)] - 1j * s.K[np.ix_(xp, yp)]
            cc = s.C[np.ix_(xp, xp)] - 1j * s.C[np.ix_(xp, yp)]
            self._mik = np.linalg.solve(mp, kc)
            self._mic = np.linalg.solve(mp, cc)
            self._mig = np.linalg.solve(mp, -1j * s.G[np.ix_(xp, yp)])
            self._lm_t = np.linalg.cholesky(mp).T
        elif method == "state-space":
            self._mik = np.linalg.solve(s.M, s.K)
            self._mic = np.linalg.solve(s.M, s.C)
            self._mig = np.linalg.solve(s.M, s.G)
        if method in ("state-space", "dense"):
            self._lm_t = np.linalg.cholesky(s.M).T

    # ----------------------------------------------------------------- set-up
    def _pick(self) -> str:
        s = self.system
        if s.is_conservative:
            if s.is_isotropic:
                xp = self._xp
                if _chol(s.K[np.ix_(xp, xp)]) is not None:
                    return "isotropic-hermitian"
            if _chol(s.K) is not None:
                return "hermitian"
        if s.is_isotropic:
            return "isotropic"
        return "state-space"

    def _setup_hermitian(self, M, K, G, *, complex_coordinate: bool) -> None:
        if not self.system.is_conservative:
            raise ValueError(f"method {self.method!r} needs C = 0 and a symmetric K")
        if complex_coordinate and not self.system.is_isotropic:
            raise ValueError("method 'isotropic-hermitian' needs an isotropic system")
        lm, lk = _chol(M), _chol(K)
        if lk is None:
            raise ValueError(f"method {self.method!r} needs K positive definite (no rigid-body "
                             "modes); use 'state-space'")
        n = M.shape[0]
        B = scipy.linalg.solve_triangular(lm, lk, lower=True)
        gt = scipy.linalg.solve_triangular(lm, G, lower=True)
        gt = scipy.linalg.solve_triangular(lm, gt.T, lower=True).T
        h0 = np.zeros((2 * n, 2 * n), dtype=complex)
        h1 = np.zeros((2 * n, 2 * n), dtype=complex)
        h0[:n, n:] = 1j * B
        h0[n:, :n] = -1j * B.T
        # complex coordinate: H = [[Omega G~, iB], [-iB^T, 0]], G~ real symmetric;
        # real system:        H = [[i Omega G~, iB], [-iB^T, 0]], G~ real skew.
        h1[:n, :n] = gt if complex_coordinate else 1j * gt
        self._h0, self._h1 = h0, h1
        self._lkinv_t = scipy.linalg.solve_triangular(lk.T, np.eye(n), lower=False)
        self._n = n

    # ----------------------------------------------------------------- solving
    def solve(self, speeds) -> Spectrum:
        """Return the :class:`Spectrum` at each speed (rad/s), shape (S,)."""
        w = np.atleast_1d(np.asarray(speeds, dtype=float))
        if w.ndim != 1 or not np.all(np.isfinite(w)):
            raise ValueError("speeds must be a finite 1-D array (rad/s)")
        solve = {"isotropic-hermitian": self._solve_hermitian, "hermitian": self._solve_hermitian,
                 "isotropic": self._solve_isotropic, "state-space": self._solve_state_space,
                 "dense": self._solve_dense}[self.method]
        with single_threaded_blas():
            return solve(w)

    def frequency_slope(self, speed: float, track: np.ndarray) -> np.ndarray | None:
        """Return d|omega|/dOmega of the modes given by their tracking vectors, if available.

        For the Hermitian methods the eigenvalue derivative is ``z^H (dH/dOmega) z``
        (Hellmann-Feynman); other methods return None.

        Parameters
        ----------
        speed : float
            Spin speed (rad/s) at which ``track`` was computed (unused by the formula, kept for
            the contract).
        track : ndarray, shape (k, p)
            Tracking vectors returned by :meth:`solve` at that speed.
        """
        if self.method not in ("isotropic-hermitian", "hermitian"):
            return None
        d = np.einsum("kp,pq,kq->k", track.conj(), self._h1, track).real
        if self.method == "isotropic-hermitian":
            h0h1 = track.conj() @ self._h0 + speed * (track.conj() @ self._h1)
            om = np.einsum("kp,kp->k", h0h1, track).real
            d = np.where(om < 0, -d, d)
        return d

    def _solve_hermitian(self, w: np.ndarray) -> Spectrum:
        n = self._n
        H = self._h0[None, :, :] + w[:, None, None] * self._h1[None, :, :]
        om, Z = np.linalg.eigh(H)  # ascending, orthonormal columns
        if self.method == "hermitian":
            om, Z = om[:, n:], Z[:, :, n:]  # positive half: one per +-omega pair
        W = np.matmul(self._lkinv_t, Z[:, n:, :]).transpose(0, 2, 1)  # q = L_K^-T v; (S, m, n)
        lam = 1j * np.abs(om)
        track = Z.transpose(0, 2, 1)
        if self.method == "hermitian":
            return Spectrum(lam, W, track)
        return Spectrum(lam, self._planes(W, om < 0), track)

    def _planes(self, W: np.ndarray, backward: np.ndarray) -> np.ndarray:
        """Real-system shapes from complex-coordinate ones: (W, -iW), conjugated if backward."""
        S, m, _ = W.shape
        shapes = np.empty((S, m, 2 * W.shape[2]), dtype=complex)
        Wc = np.where(backward[:, :, None], W.conj(), W)
        shapes[:, :, self._xp] = Wc
        shapes[:, :, self._yp] = np.where(backward[:, :, None], 1j, -1j) * Wc
        return shapes

    def _solve_isotropic(self, w: np.ndarray) -> Spectrum:
        npl = self._mik.shape[0]
        A = np.zeros((w.size, 2 * npl, 2 * npl), dtype=complex)
        A[:, :npl, npl:] = np.eye(npl)
        A[:, npl:, :npl] = -self._mik
        A[:, npl:, npl:] = -(self._mic[None] + w[:, None, None] * self._mig[None])
        lam, V = np.linalg.eig(A)
        backward = lam.imag < 0
        lam = np.where(backward, lam.conj(), lam)
        W = V[:, :npl, :].transpose(0, 2, 1)
        return Spectrum(lam, self._planes(W, backward), _mass_weighted(W, self._lm_t))

    def _solve_state_space(self, w: np.ndarray) -> Spectrum:
        n = self.system.n_dof
        A = np.zeros((w.size, 2 * n, 2 * n))
        A[:, :n, n:] = np.eye(n)
        A[:, n:, :n] = -self._mik
        A[:, n:, n:] = -(self._mic[None] + w[:, None, None] * self._mig[None])
        lam, V = np.linalg.eig(A)
        return _select_half(lam, V, n, self._lm_t)

    def _solve_dense(self, w: np.ndarray) -> Spectrum:
        s = self.system
        n = s.n_dof
        Bm = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), s.M]])
        lams, vecs = [], []
        for om in w:
            Am = np.block([[np.zeros((n, n)), np.eye(n)], [-s.K, -(s.C + om * s.G)]])
            lam, V = scipy.linalg.eig(Am, Bm)
            lams.append(lam)
            vecs.append(V)
        return _select_half(np.array(lams), np.array(vecs), n, self._lm_t)


def _mass_weighted(shapes: np.ndarray, lm_t: np.ndarray) -> np.ndarray:
    """Unit vectors ``L_M^T q``: modes are (nearly) orthogonal in this metric, so MAC works."""
    u = np.matmul(shapes, lm_t.T)
    return u / np.linalg.norm(u, axis=2, keepdims=True)


def _select_half(lam: np.ndarray, V: np.ndarray, n: int, lm_t: np.ndarray) -> Spectrum:
    """Keep one eigenvalue per conjugate pair (largest imaginary parts first)."""
    order = np.argsort(-lam.imag, axis=1, kind="stable")[:, :n]
    lam = np.take_along_axis(lam, order, axis=1)
    V = np.take_along_axis(V, order[:, None, :], axis=2)
    shapes = V[:, :n, :].transpose(0, 2, 1)
    return Spectrum(lam, shapes, _mass_weighted(shapes, lm_t))


def whirl_of_shapes(shapes: np.ndarray, length_scale: float = 1.0,
                    tol: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
    """Classify the whirl of complex mode shapes.

    Parameters
    ----------
    shapes : ndarray, shape (..., n)
        Displacement shapes ``Q`` of modes ``Re(Q exp(i omega t))`` with omega > 0.
    length_scale : float
        Tilts are multiplied by this length (m) before translations and tilts are compared.
    tol : float
        Relative size below which an orbit counts as a straight line.

    Returns
    -------
    index : ndarray, shape (...)
        ``sum(a_f^2 - a_b^2) / sum(a_f^2 + a_b^2)`` over the x-y pairs of every node, with
        ``a_f = |X + i Y| / 2`` and ``a_b = |X - i Y| / 2`` the forward and backward circular
        components of each orbit; +1 pure forward, -1 pure backward.
    code : ndarray of int8, shape (...)
        +1 forward, -1 backward, 0 mixed (pairs whirl in opposite senses) or planar.

    References
    ----------
    Friswell et al. (2010), Chapter 3 (forward and backward whirl of an elliptical orbit).
    """
    q = shapes.reshape(shapes.shape[:-1] + (-1, 4))
    X = np.concatenate([q[..., 0], length_scale * q[..., 2]], axis=-1)
    Y = np.concatenate([q[..., 1], length_scale * q[..., 3]], axis=-1)
    af = np.abs(X + 1j * Y) ** 2
    ab = np.abs(X - 1j * Y) ** 2
    tot = af + ab
    total = tot.sum(axis=-1)
    safe = np.where(total > 0, total, 1.0)
    index = (af - ab).sum(axis=-1) / safe
    big = tot > 1e-6 * tot.max(axis=-1, keepdims=True)
    diff = af - ab
    sig = np.abs(diff) > tol * tot
    pos = np.any(big & sig & (diff > 0), axis=-1)
    neg = np.any(big & sig & (diff < 0), axis=-1)
    code = np.where(pos & ~neg, 1, np.where(neg & ~pos, -1, 0)).astype(np.int8)
    return index, code
