"""Floquet multipliers of a periodic orbit from its segment Jacobians, and their test functions.

The monodromy matrix of an orbit computed by ``m`` shooting segments is the product of the
segment Jacobians, ``M = G_{m-1} ... G_1 G_0``; its eigenvalues are the Floquet multipliers.
An autonomous orbit always has the trivial multiplier 1 (the flow along the orbit); it is
identified by its eigenvector (the one most nearly parallel to the vector field at the orbit's
first point), checked (its distance from 1 is reported) and left out of the stability label, so
that the label does not hinge on whether round-off puts it at ``1 - 1e-9`` or ``1 + 1e-9``: the
orbit is stable when every other multiplier lies inside the unit circle.

Test functions along a branch (zeros located by :func:`rotorlab.continuation.continue_curve`):

- fold or branch point of cycles: ``prod_i (mu_i - 1)`` over the non-trivial multipliers (zero
  when a second multiplier reaches +1: at a fold of the branch, which the branch's own tangent
  tells apart, or at a branch point where another family of orbits crosses, e.g. one that breaks
  a symmetry of the orbit);
- period doubling: ``prod_i (mu_i + 1)`` over the non-trivial multipliers (real for a real
  matrix; zero when a multiplier crosses -1);
- torus (Neimark–Sacker): ``prod_{i<j} (mu_i mu_j - 1)`` over the non-trivial multipliers (zero
  when a complex pair crosses the unit circle, and at a neutral saddle, two real multipliers
  with product 1, which :func:`is_torus` tells apart).

Both are returned as ``sign * |value|**(1/k)`` (k factors) so that their size neither under- nor
overflows. The fold of cycles is the fold of the branch in its parameter
(:func:`rotorlab.continuation.fold_test`).

References
----------
Kuznetsov Yu.A., Elements of Applied Bifurcation Theory, 3rd ed., Springer 2004, ch. 1.5 and
10.3 (multipliers, test functions for the codimension-one bifurcations of cycles).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["monodromy", "floquet_multipliers", "is_stable", "period_doubling_value", "torus_value",
           "is_torus", "is_period_doubling", "plus_one_value", "is_plus_one"]


def monodromy(segment_jacobians: np.ndarray) -> np.ndarray:
    """The product ``G_{m-1} ... G_0`` of the segment Jacobians, shape (m, n, n) -> (n, n)."""
    g = np.asarray(segment_jacobians, dtype=float)
    out = np.eye(g.shape[1])
    for gi in g:
        out = gi @ out
    return out


def floquet_multipliers(segment_jacobians: np.ndarray, flow: np.ndarray | None = None,
                        weight: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """The Floquet multipliers (largest modulus first) and the index of the trivial one.

    Parameters
    ----------
    segment_jacobians : array_like, shape (m, n, n)
    flow : array_like, shape (n,), optional
        The vector field at the orbit's first point (an autonomous orbit); None for a forced
        (non-autonomous) orbit, which has no trivial multiplier.
    weight : array_like, shape (n,), optional
        Typical size of each state (the eigenvectors are compared in ``x / weight``).

    Returns
    -------
    multipliers : ndarray of complex, shape (n,)
    trivial : int
        Index of the trivial multiplier in ``multipliers``, or -1 for a forced orbit.
    """
    m = monodromy(segment_jacobians)
    mu, vec = np.linalg.eig(m)
    order = np.argsort(-np.abs(mu), kind="stable")
    mu, vec = mu[order], vec[:, order]
    if flow is None:
        return mu, -1
    w = np.ones(mu.size) if weight is None else np.asarray(weight, dtype=float)
    f = np.asarray(flow, dtype=float) / w
    f /= max(np.linalg.norm(f), 1e-300)
    v = vec / w[:, None]
    v /= np.maximum(np.linalg.norm(v, axis=0), 1e-300)
    near = np.abs(mu - 1.0) < 0.1
    align = np.abs(f @ v)
    cand = np.flatnonzero(near) if near.any() else np.arange(mu.size)
    # among the multipliers near 1 the one whose eigenvector is the flow direction
    k = int(cand[np.argmax(align[cand] - np.abs(mu[cand] - 1.0))])
    return mu, k


def _others(mu: np.ndarray, trivial: int) -> np.ndarray:
    mu = np.asarray(mu)
    return mu if trivial < 0 else np.delete(mu, trivial)


def is_stable(mu: np.ndarray, trivial: int) -> bool:
    """True if every non-trivial multiplier lies strictly inside the unit circle."""
    rest = _others(mu, trivial)
    return bool(rest.size == 0 or np.max(np.abs(rest)) < 1.0)


def _root(values: np.ndarray) -> float:
    if values.size == 0:
        return 1.0
    if np.any(values == 0):
        return 0.0
    prod = complex(np.prod(values / np.maximum(np.abs(values), 1e-300)))
    sign = 1.0 if prod.real >= 0 else -1.0
    logs = np.log(np.maximum(np.abs(values), 1e-300))
    return sign * math.exp(float(np.mean(logs)))


def plus_one_value(mu: np.ndarray, trivial: int) -> float:
    """``prod (mu_i - 1)`` over the non-trivial multipliers (zero when one reaches +1)."""
    return _root(_others(mu, trivial) - 1.0)


def is_plus_one(mu: np.ndarray, trivial: int, tol: float = 1e-3) -> bool:
    """True if a non-trivial multiplier lies at +1 (within ``tol``)."""
    return bool((np.abs(_others(mu, trivial) - 1.0) < tol).any())


def period_doubling_value(mu: np.ndarray, trivial: int) -> float:
    """``prod (mu_i + 1)`` over the non-trivial multipliers (zero when one crosses -1)."""
    return _root(_others(mu, trivial) + 1.0)


def torus_value(mu: np.ndarray, trivial: int) -> float:
    """``prod_{i<j} (mu_i mu_j - 1)`` over the non-trivial multipliers (zero when a complex pair
    crosses the unit circle, or at a neutral saddle)."""
    rest = _others(mu, trivial)
    i, j = np.triu_indices(rest.size, 1)
    return _root(rest[i] * rest[j] - 1.0)


def is_torus(mu: np.ndarray, trivial: int, tol: float = 1e-3) -> bool:
    """True if a complex pair of non-trivial multipliers lies on the unit circle (within ``tol``)."""
    rest = _others(mu, trivial)
    pair = (np.abs(rest.imag) > 1e-6) & (np.abs(np.abs(rest) - 1.0) < tol)
    return bool(pair.any())


def is_period_doubling(mu: np.ndarray, trivial: int, tol: float = 1e-3) -> bool:
    """True if a non-trivial multiplier lies at -1 (within ``tol``)."""
    return bool((np.abs(_others(mu, trivial) + 1.0) < tol).any())
