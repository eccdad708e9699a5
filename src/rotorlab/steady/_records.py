"""The records of the steady-motion analysis: a steady motion and its stability verdicts.

Kept apart from the modules that compute them (:mod:`rotorlab.steady._motions` finds the motions,
:mod:`rotorlab.steady._stability` judges them) so that neither imports the other.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

__all__ = ["SteadyMotion", "Stability"]


@dataclass(frozen=True)
class Stability:
    """Stability of one steady motion by the three methods.

    Attributes
    ----------
    hamilton : {"stable", "unstable"}
        Seed 003's verdict: H~* least among the (undamped) steady motions and f of eq. (18) a
        minimum above / maximum below omega_cr = sqrt(c / M).
    hamilton_minimal : bool
        H~* is least among the steady motions at d = 0 (eqs. (14), (15)).
    hessian : {"minimum", "maximum", "saddle", "degenerate"}
        Type of the critical point of f (eq. (19)); a family's n - 2 neutral directions are left
        out.
    hessian_eigenvalues : ndarray, shape (n,)
        Eigenvalues of the matrix a of eq. (19) (kg^2 m^2).
    averaged : {"stable", "unstable", "undefined"}
        Seed 002's verdict from the averaged equations (undefined when a ball has no damping).
    averaged_eigenvalues : ndarray, shape (n,)
        Eigenvalues of dP_s / dpsi_j (1/s), real.
    averaged_a, averaged_b : float
        A and B of eq. (19) (corrected), for n = 2 (1/s, 1/s^2); NaN otherwise.
    exact : {"stable", "unstable", "marginal", "partly stable", "absent"}
        From the eigenvalues of the full linearization; "partly stable" for a family whose
        members differ; "absent" when the motion does not exist with the support damping.
    eigenvalues : ndarray, shape (4 + 2 n,)
        Eigenvalues of the representative member (1/s, complex); NaN when absent.
    growth_rate : float
        Largest real part of the eigenvalues, neutral family directions left out, over all
        members (1/s); NaN when absent.
    stable_fraction : float
        Fraction of the family's members that are exactly stable (1 or 0 for isolated motions).
    """

    hamilton: str
    hamilton_minimal: bool
    hessian: str
    hessian_eigenvalues: np.ndarray
    averaged: str
    averaged_eigenvalues: np.ndarray
    averaged_a: float
    averaged_b: float
    exact: str
    eigenvalues: np.ndarray
    growth_rate: float
    stable_fraction: float

    def is_stable(self, method: str) -> bool:
        """Return the verdict of ``method`` ("hamilton", "averaged" or "exact") as a bool."""
        if method not in ("hamilton", "averaged", "exact"):
            raise ValueError(f"method must be 'hamilton', 'averaged' or 'exact', got {method!r}")
        return getattr(self, method) == "stable"



@dataclass(frozen=True)
class SteadyMotion:
    """One steady motion (or family of steady motions) at a constant speed.

    Attributes
    ----------
    label : str
        ``"main+"``, ``"main-"``, ``"main"`` (family, n >= 3) or ``"side 0110"``.
    kind : {"main", "side"}
    bits : tuple of int
        Seed 003's k_i of a side motion (0: ball towards the heavy side of the disc when d = 0);
        empty for a main motion.
    exists : bool
        Whether the motion exists in the model (with its support damping).
    ball_angles : ndarray, shape (n,)
        Angles psi_i from the unbalance, in (-pi, pi] (rad); for a family, one representative
        member (the first of ``samples``); NaN when the motion does not exist.
    deflection : complex
        Steady shaft deflection ``u + i v`` in the co-rotating axes (m) (U along the unbalance).
    h_tilde : float
        H~* = Pi - T0 on the motion (J), Filimonikhin & Filimonikhina eqs. (10), (14), (15) (with
        the disc's ``M1 e^2`` in T0, see :func:`rotorlab.models.JeffcottBalls.reduced_hamiltonian`).
    dimension : int
        0 for an isolated motion, n - 2 for the family of main motions (n >= 3).
    samples : ndarray, shape (n_samples, n)
        Ball angles of members of the motion (one row for an isolated motion) (rad).
    spin_speed : float
        Omega (rad/s).
    stability : Stability or None
        The three stability verdicts (set by :func:`rotorlab.steady.analyze_steady`).
    """

    label: str
    kind: Literal["main", "side"]
    bits: tuple[int, ...]
    exists: bool
    ball_angles: np.ndarray
    deflection: complex
    h_tilde: float
    dimension: int
    samples: np.ndarray
    spin_speed: float
    stability: Stability | None = field(default=None)

    @property
    def amplitude(self) -> float:
        """Shaft deflection ``|z|`` (m)."""
        return abs(self.deflection)

    @property
    def phase(self) -> float:
        """Angle of the deflection from the unbalance, in the sense of rotation (rad)."""
        return math.atan2(self.deflection.imag, self.deflection.real) if self.amplitude > 0 else 0.0

    def states(self) -> np.ndarray:
        """Return co-rotating states ``[u, v, 0, 0, psi_i, 0]`` of every sample, shape (k, 4 + 2n)."""
        k, n = self.samples.shape
        y = np.zeros((k, 4 + 2 * n))
        y[:, 0], y[:, 1] = self.deflection.real, self.deflection.imag
        y[:, 4 : 4 + n] = self.samples
        return y
