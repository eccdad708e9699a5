"""Periodic orbits by orthogonal collocation (Gauss points on a uniform mesh), for comparison.

The method of AUTO and COCO (Doedel, Keller & Kernevez 1991; Ascher, Mattheij & Russell 1995,
ch. 5): the orbit ``x(s)``, ``s = t / T`` in ``[0, 1]``, is a continuous piecewise polynomial of
degree ``m`` on ``N`` equal intervals, given by its values at ``m + 1`` equally spaced nodes per
interval (shared at the interval ends); on each interval the equation ``x' = T f(x)`` holds at
the ``m`` Gauss-Legendre points (superconvergent at the mesh points: error ``O(h^{2m})``). The
orbit closes on itself up to whole turns of its angles (``winding``), and an integral phase
condition ``int (x - x_ref) . x_ref' ds = 0`` against the starting guess fixes the phase. Newton's
method on the ``N m n + 1`` unknowns (node values and ``T``) with the Jacobian assembled from
``f``'s Jacobian at the collocation points (central differences).

Measured against :func:`rotorlab.continuation.find_periodic_orbit` (multiple shooting on the
compiled integrator) in ``bench/collocation.py``; the choice and its numbers are in
docs/architecture.md. Only the single orbit is solved here (no continuation, no Floquet
multipliers): multiple shooting stays the method of :func:`continue_periodic`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["CollocationOrbit", "collocate_orbit"]


@dataclass(frozen=True)
class CollocationOrbit:
    """A periodic orbit by collocation: ``times`` (the mesh nodes, s), ``states`` there (shape
    (N m + 1, n), the last one the first plus the winding), ``period`` (s), Newton ``iterations``
    and the largest collocation residual ``residual`` (of ``x' - T f``, per unit s)."""

    times: np.ndarray
    states: np.ndarray
    period: float
    iterations: int
    residual: float


def _basis(m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Nodes ``k / m``, Gauss points and weights on [0, 1], and the Lagrange basis values ``L`` and
    derivatives ``D`` at the Gauss points (shape (m, m + 1))."""
    nodes = np.linspace(0.0, 1.0, m + 1)
    g, w = np.polynomial.legendre.leggauss(m)
    c, w = 0.5 * (g + 1.0), 0.5 * w
    L = np.ones((m, m + 1))
    D = np.zeros((m, m + 1))
    for k in range(m + 1):
        others = np.delete(nodes, k)
        den = np.prod(nodes[k] - others)
        L[:, k] = np.prod(c[:, None] - others[None, :], axis=1) / den
        for j in range(m):
            rest = np.delete(others, j)
            D[:, k] += np.prod(c[:, None] - rest[None, :], axis=1) / den
    return nodes, c, w, L, D


def collocate_orbit(f: Callable[[np.ndarray], np.ndarray], times: np.ndarray, states: np.ndarray, period: float, *,
                    intervals: int = 40, degree: int = 4, winding: np.ndarray | None = None, tol: float = 1e-11,
                    max_iterations: int = 20, jacobian_step: np.ndarray | float = 1e-7) -> CollocationOrbit:
    """Solve for the periodic orbit near a guess by orthogonal collocation.

    Parameters
    ----------
    f : callable
        The autonomous vector field ``f(x) -> dx/dt`` (n,).
    times, states : array_like
        The guess: states (k, n) at increasing times over one period from ``times[0]`` (they are
        interpolated onto the mesh; angles unwrapped, as an integrator gives them).
    period : float
        The guess of the period (s).
    intervals, degree : int
        ``N`` mesh intervals, ``m`` Gauss points (polynomial degree) per interval.
    winding : array_like of float, optional
        ``x(T) - x(0)`` (whole turns of angles: ``2 pi k``); default zeros.
    tol : float
        Newton stops when the largest update, relative to the largest |state| (and T), is below.
    jacobian_step : float or array_like
        Central-difference step of each state for ``f``'s Jacobian.

    Returns
    -------
    CollocationOrbit

    Raises
    ------
    ValueError
        Newton does not converge in ``max_iterations``.
    """
    times = np.asarray(times, dtype=float)
    states = np.asarray(states, dtype=float)
    n = states.shape[1]
    N, m = int(intervals), int(degree)
    nodes, c, w, L, D = _basis(m)
    jump = np.zeros(n) if winding is None else np.asarray(winding, dtype=float)
    s_nodes = (np.arange(N)[:, None] + nodes[None, :]).ravel()[: N * m] / N  # distinct nodes
    s_guess = (times - times[0]) / (times[-1] - times[0])
    x = np.array([np.interp(s_nodes, s_guess, states[:, i]) for i in range(n)]).T  # (N m, n)
    T = float(period)
    step = np.broadcast_to(np.asarray(jacobian_step, dtype=float), (n,))
    h = 1.0 / N

    def interval_values(x):
        """(N, m + 1, n): each interval's node values, the last interval closing with the winding."""
        ext = np.vstack([x, x[:1] + jump])
        idx = np.arange(N)[:, None] * m + np.arange(m + 1)[None, :]
        return ext[idx]

    def colloc(xv):
        """States and derivatives (d/ds) at the Gauss points, shape (N, m, n)."""
        return np.einsum("ik,jkn->jin", L, xv), np.einsum("ik,jkn->jin", D, xv) / h

    xv0 = interval_values(x)
    ref_c, ref_d = colloc(xv0)
    weights = np.broadcast_to(w[None, :] * h, (N, m))
    nu = N * m * n
    for it in range(1, max_iterations + 1):
        xv = interval_values(x)
        xc, dc = colloc(xv)
        pts = xc.reshape(-1, n)
        fc = np.array([f(p) for p in pts])
        res = np.concatenate([(dc.reshape(-1, n) - T * fc).ravel(),
                              [np.sum(weights[..., None] * (xc - ref_c) * ref_d)]])
        jf = np.empty((pts.shape[0], n, n))
        for q in range(n):
            e = np.zeros(n)
            e[q] = step[q]
            jf[:, :, q] = (np.array([f(p + e) for p in pts]) - np.array([f(p - e) for p in pts])) / (2 * step[q])
        A = np.zeros((nu + 1, nu + 1))
        for j in range(N):
            cols = [((j * m + k) % (N * m)) for k in range(m + 1)]
            for i in range(m):
                row = (j * m + i) * n
                p = j * m + i
                for k, col in enumerate(cols):
                    A[row:row + n, col * n:col * n + n] += D[i, k] / h * np.eye(n) - T * L[i, k] * jf[p]
                    A[nu, col * n:col * n + n] += weights[j, i] * L[i, k] * ref_d[j, i]
                A[row:row + n, nu] = -fc[p]
        dz = np.linalg.solve(A, -res)
        x = x + dz[:nu].reshape(-1, n)
        T += dz[nu]
        size = max(np.max(np.abs(x)), abs(T), 1.0)
        if np.max(np.abs(dz)) <= tol * size:
            xv = interval_values(x)
            xc, dc = colloc(xv)
            fc = np.array([f(p) for p in xc.reshape(-1, n)])
            worst = float(np.max(np.abs(dc.reshape(-1, n) - T * fc)))
            s_all = np.append(s_nodes, 1.0)
            return CollocationOrbit(times=s_all * T, states=np.vstack([x, x[:1] + jump]), period=T,
                                    iterations=it, residual=worst)
    raise ValueError(f"collocation: Newton did not converge in {max_iterations} iterations "
                     f"(last update {np.max(np.abs(dz)):.3g}); give a better guess or more intervals")
