"""A machine simulated in its co-rotating frame (:meth:`rotorlab.models.Machine.in_rotating_frame`).

The same machine, its states seen from the frame that turns with the spin angle theta
(:mod:`rotorlab._kernels.machine_corotating`): structure coordinate pairs ``z_r = R^T z`` with
rates ``z_r' = R^T z' - Omega J z_r``, ball angles ``psi = phi - theta`` and rates
``psi' = phi' - Omega``; every other state as in the fixed frame. :func:`rotorlab.integrate.solve`
and :func:`~rotorlab.integrate.solve_ensemble` take it like any model (``kernels``,
``to_array()``); its packed parameters are the machine's.

Examples
--------
>>> import numpy as np
>>> from rotorlab.linear import LinearSystem
>>> from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance
>>> s = LinearSystem(M=np.eye(4), C=np.diag([0.02, 0.02, 0, 0]), G=np.zeros((4, 4)),
...                  K=np.diag([1.0, 1.0, 5.0, 5.0]))
>>> mac = Machine(s, races=(BallRace(0, 1.0, (Ball(0.02), Ball(0.02))),),
...               unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(2.0), n_modes=2)
>>> rot = mac.in_rotating_frame()
>>> rot.state_names[:4], rot.n_state == mac.n_state
(('u_1', 'u_2', 'du_1', 'du_2'), True)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab.models._base import Kernels

__all__ = ["CoRotatingMachine"]


@dataclass(frozen=True)
class CoRotatingMachine:
    """``machine`` with its states in the co-rotating frame (see the module docstring).

    Parameters
    ----------
    machine : Machine
        One with a co-rotating kernel (:meth:`Machine.why_no_rotating_kernel` is None).
    """

    machine: Any

    def __post_init__(self) -> None:
        why = self.machine.why_no_rotating_kernel()
        if why is not None:
            raise ValueError(f"no co-rotating kernel: {why}")

    @property
    def kernels(self) -> Kernels:
        """The machine's :attr:`Machine.rotating_kernels`."""
        return self.machine.rotating_kernels

    @property
    def n_state(self) -> int:
        return self.machine.n_state

    @property
    def state_names(self) -> tuple[str, ...]:
        """The machine's names, ``u``/``psi`` for the turned coordinates and ball angles."""
        m, lay = self.machine, self.machine.layout
        names = list(m.state_names)
        for i in range(lay.n_z):
            names[i] = f"u_{i + 1}"
            names[lay.n_z + i] = f"du_{i + 1}"
        for b, label in enumerate(m._ball_labels):
            names[lay.i_phi + b], names[lay.i_w + b] = f"psi_{label}", f"dpsi_{label}"
        return tuple(names)

    def to_array(self) -> np.ndarray:
        """The machine's packed parameters."""
        return self.machine.to_array()

    def initial_state(self, *args, t0: float = 0.0, **kw) -> np.ndarray:
        """:meth:`Machine.initial_state` (same arguments) turned into this frame at ``t0``."""
        return self.machine.to_frame(t0, self.machine.initial_state(*args, t0=t0, **kw), "rotating")

    def to_fixed(self, t, y) -> np.ndarray:
        """States ``y`` of this frame at times ``t`` in the fixed frame (:meth:`Machine.to_frame`)."""
        return self.machine.to_frame(t, y, "fixed")

    def rhs(self, t: float, y) -> np.ndarray:
        """dy/dt from the compiled co-rotating kernel (allocates; for SciPy and tests)."""
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty_like(y)
        self.kernels.rhs(float(t), y, self.to_array(), out)
        return out
