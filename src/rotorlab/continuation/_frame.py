"""The co-rotating right-hand side of one machine, its checks and packed parameters looked up
once (:class:`rotorlab.continuation.MachineEquilibria` evaluates it some ten thousand times per
curve)."""

from __future__ import annotations

import numpy as np

__all__ = ["_Frame"]


class _Frame:
    """:meth:`Machine.rotating_rhs` and the Jacobian of :meth:`Machine.linearize` for one machine,
    with its checks, packed parameters and kernel looked up once (the continuation evaluates them
    some ten thousand times per curve; per call they cost 30 us against the kernel's 2 us).
    ``tests/unit/test_continuation_two_parameter.py`` checks both against the Machine's own."""

    def __init__(self, machine):
        self.om = machine._require_rotating()
        lay = machine.layout
        self.nz, self.nb, self.i_phi, self.i_w = lay.n_z, lay.n_balls, lay.i_phi, lay.i_w
        self.y = np.zeros(lay.n_state)
        self.p = machine.to_array()
        self.kernel = machine.kernels.rhs
        nz, nb = self.nz, self.nb  # Machine._fd_step: one step per block (z, z', psi and psi')
        self.steps = np.repeat([machine._fd_step(j, self.om) for j in (0, nz, 2 * nz)], [nz, nz, 2 * nb])

    def rhs(self, yr: np.ndarray) -> np.ndarray:
        return self.rhs_many(np.asarray(yr, dtype=float)[None, :])[0]

    def rhs_many(self, yr: np.ndarray) -> np.ndarray:
        """:meth:`Machine.rotating_rhs` of each row of ``yr`` (shape (k, 2 (n_z + n_balls)))."""
        nz, nb, om = self.nz, self.nb, self.om
        z, v = yr[:, :nz], yr[:, nz:2 * nz]
        y = np.zeros((yr.shape[0], self.y.size))
        y[:, :nz] = z
        y[:, nz:2 * nz:2] = v[:, 0::2] - om * z[:, 1::2]
        y[:, nz + 1:2 * nz:2] = v[:, 1::2] + om * z[:, 0::2]
        y[:, self.i_phi:self.i_phi + nb] = yr[:, 2 * nz:2 * nz + nb]
        y[:, self.i_w:self.i_w + nb] = yr[:, 2 * nz + nb:] + om
        f = np.empty_like(y)
        for k in range(y.shape[0]):
            self.kernel(0.0, y[k], self.p, f[k])
        out = np.empty_like(yr)
        out[:, :nz] = v
        out[:, nz:2 * nz:2] = f[:, nz:2 * nz:2] + 2.0 * om * v[:, 1::2] + om * om * z[:, 0::2]
        out[:, nz + 1:2 * nz:2] = f[:, nz + 1:2 * nz:2] - 2.0 * om * v[:, 0::2] + om * om * z[:, 1::2]
        out[:, 2 * nz:2 * nz + nb] = yr[:, 2 * nz + nb:]
        out[:, 2 * nz + nb:] = f[:, self.i_w:self.i_w + nb]
        return out

    def matrix(self, yr: np.ndarray) -> np.ndarray:
        """The co-rotating Jacobian, fourth-order central differences as :meth:`Machine.linearize`."""
        n = yr.size
        e = np.diag(self.steps)
        f = self.rhs_many(np.concatenate([yr + e, yr - e, yr + 2 * e, yr - 2 * e]))
        f1, f2 = f[:n] - f[n:2 * n], f[2 * n:3 * n] - f[3 * n:]
        return ((8.0 * f1 - f2) / (12.0 * self.steps[:, None])).T
