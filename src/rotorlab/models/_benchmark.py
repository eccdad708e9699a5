"""The project's benchmark problem: a nondimensional Jeffcott rotor with a two-ball balancer.

The rotor (mass M including the balls, stiffness k, damping c) carries an unbalance eps and two
balls (mass m each, race radius R, viscous damping beta relative to the race) and spins at
Omega. In the frame fixed in space (Zhakash et al. 2024, eqs. (1)-(3), with point-mass balls)::

    M x'' + c x' + k x = eps W^2 cos(W t) + m R sum_i (w_i^2 cos phi_i + w_i' sin phi_i)
    M y'' + c y' + k y = eps W^2 sin(W t) + m R sum_i (w_i^2 sin phi_i - w_i' cos phi_i)
    m R^2 w_i'          = -beta (w_i - W) + m R (x'' sin phi_i - y'' cos phi_i)

which is the ``jeffcott_balls`` model with disc mass M - 2 m, eccentricity eps / (M - 2 m) and
two equal balls (:meth:`BenchmarkProblem.model`). Its start-ups from a 256 x 256 grid of ball
angles, 2000 revolutions each at rtol 1e-8 and atol 1e-10, are the workload of ``bench/``: every
start off the diagonal phi_1 = phi_2 balances (final amplitude of about 2e-9), and on the
diagonal (the balls move as one and cannot balance) the amplitude ends at 0.0357191.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rotorlab.models._jeffcott_balls import JeffcottBalls

__all__ = ["BenchmarkProblem", "BENCHMARK"]


@dataclass(frozen=True)
class BenchmarkProblem:
    """The benchmark's parameters (nondimensional), tolerances and grid of start angles.

    Parameters
    ----------
    total_mass, ball_mass, race_radius, unbalance, stiffness, damping, ball_damping, spin_speed : float
        M, m, R, eps (= M1 e), k, c, beta, Omega.
    revolutions : int
        Simulated revolutions at Omega.
    rtol, atol : float
        Integration tolerances.
    n_grid : int
        The start angles form an ``n_grid`` x ``n_grid`` grid over [0, 2 pi)^2.
    balanced_threshold : float
        Final amplitude below which a start counts as balanced.

    Examples
    --------
    >>> BENCHMARK.t_end == 2000 * 2 * math.pi / 2.5
    True
    >>> BENCHMARK.grid_angles([1, 256])
    (array([0.        , 0.02454369]), array([0.02454369, 0.        ]))
    """

    total_mass: float = 1.0
    ball_mass: float = 0.02
    race_radius: float = 1.0
    unbalance: float = 0.01
    stiffness: float = 1.0
    damping: float = 0.02
    ball_damping: float = 0.01
    spin_speed: float = 2.5
    revolutions: int = 2000
    rtol: float = 1e-8
    atol: float = 1e-10
    n_grid: int = 256
    balanced_threshold: float = 1e-3

    @property
    def t_end(self) -> float:
        """Simulated time: ``revolutions`` turns at Omega."""
        return self.revolutions * 2.0 * math.pi / self.spin_speed

    def grid_angles(self, index: np.ndarray | list[int]) -> tuple[np.ndarray, np.ndarray]:
        """Start angles (phi_1, phi_2) = 2 pi (i, j) / n_grid of grid indices n = i n_grid + j."""
        i, j = np.divmod(np.asarray(index), self.n_grid)
        return 2.0 * np.pi * i / self.n_grid, 2.0 * np.pi * j / self.n_grid

    def initial_state(self, index: np.ndarray | list[int]) -> np.ndarray:
        """Start states, shape (n, 8): rotor at rest at the origin, balls turning with the rotor."""
        p1, p2 = self.grid_angles(np.atleast_1d(index))
        y0 = np.zeros((p1.size, 8))
        y0[:, 4], y0[:, 5] = p1, p2
        y0[:, 6:8] = self.spin_speed
        return y0

    def subset_indices(self, n: int | None = None, seed: int = 12345, offdiag: bool = False) -> np.ndarray:
        """A fixed pseudo-random permutation of the grid (its first ``n`` entries).

        Every measurement uses a prefix of this permutation, so subsets are nested and each is a
        uniform sample of the grid; ``offdiag`` skips the invariant diagonal phi_1 = phi_2.
        """
        perm = np.random.default_rng(seed).permutation(self.n_grid * self.n_grid)
        if offdiag:
            perm = perm[perm // self.n_grid != perm % self.n_grid]
        return perm if n is None else perm[:n]

    def model(self) -> JeffcottBalls:
        """The benchmark as a ``jeffcott_balls`` model (fixed frame, constant speed)."""
        from rotorlab.models._jeffcott_balls import JeffcottBalls
        from rotorlab.models._jeffcott_params import BallParams, RotorParams
        from rotorlab.models._speed import ConstantSpeed

        disc = self.total_mass - 2.0 * self.ball_mass
        rotor = RotorParams(disc, self.unbalance / disc, self.stiffness, self.damping)
        ball = BallParams(self.ball_mass, self.race_radius, damping=self.ball_damping)
        return JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(self.spin_speed))


#: The benchmark problem of ``bench/`` and ``tests/validation/test_jeffcott_bench.py``.
BENCHMARK = BenchmarkProblem()
