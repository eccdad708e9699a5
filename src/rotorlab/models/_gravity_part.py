r"""Gravity as a part of the composed machine (:mod:`rotorlab.models._parts`): the acceleration
``g = (g_x, g_y, g_z)`` in the fixed frame, z the shaft axis; only its lateral components act.

It has no states and no stations; its packed block is ``(g_x, g_y)`` (m/s^2), which its kernel
lines read into the generated variables ``gx``, ``gy`` (every part that has weight reads them:
the balls' ``m l g . t_b``, an unbalance's ``U g . t_u``, a tuned mass absorber, a moving
housing). The weight of the structure and of the balls on the races, ``f_g`` (structure
coordinates, :meth:`GravityPart.weights`), is a constant load: the machine packs ``H f_g``
with its structure, and the part's energy is its potential ``-f_g . z``. A machine without
gravity has the part with ``g = 0`` (one compiled kernel for both). Across the axis it pulls the
balls down once per revolution: no co-rotating equilibria (:meth:`Gravity.rotating_refusal`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from rotorlab.models._machine_parts import Gravity
from rotorlab.models._parts import AbstractKernelPart, AbstractPart

__all__ = ["GravityPart"]


@dataclass(frozen=True)
class _GravityLines(AbstractKernelPart):
    """Kernel lines of gravity: ``gx``, ``gy`` from its block of 2."""

    key: ClassVar[str] = ""
    n_param: ClassVar[int] = 2

    def variable_lines(self, lay, place):
        return [f"    gx = p[{place.param}]", f"    gy = p[{place.param + 1}]"]

    def force_lines(self, lay, L, place):
        return []


@dataclass(frozen=True)
class GravityPart(Gravity, AbstractPart):
    """A machine's :class:`~rotorlab.models.Gravity` as its part (``Machine.gravity``; None: zero)."""

    key: ClassVar[str] = "gravity"
    node: ClassVar[int] = 0  # it acts everywhere

    @classmethod
    def of(cls, g: Gravity | None) -> GravityPart:
        """The part of gravity ``g`` (None: no gravity, ``g = 0``)."""
        return cls((0.0, 0.0, 0.0) if g is None else g.vector)

    def kernel(self) -> _GravityLines:
        return _GravityLines()

    def stations(self, machine) -> list[np.ndarray]:
        return []

    def pack(self, machine) -> np.ndarray:
        return np.array(self.lateral)

    def state_names(self, index: int) -> list[str]:
        return []

    def initial(self, machine, y, place) -> None:
        """No states."""

    def weights(self, machine) -> np.ndarray:
        """``f_g`` in the structure coordinates (N): the structure's weight ``Phi^T M_s e_g`` and
        the balls' on their races."""
        gx, gy = self.lateral
        s = machine.structure
        eg = np.zeros(s.n_dof)
        eg[0::4], eg[1::4] = gx, gy
        f = machine.basis.T @ (s.M @ eg)
        for r, B in zip(machine.races, machine._stations):
            f += sum(b.mass for b in r.balls) * (B.T @ np.array([gx, gy]))
        return f

    @staticmethod
    def slots(machine) -> list:
        """Its named parameters ``gravity.vector[k]`` (m/s^2), when the machine has gravity."""
        from dataclasses import replace

        from rotorlab.models._parameters import _FREE, _slot

        if machine.gravity is None:
            return []
        out = []
        for k in range(3):
            def set_g(mm, v, k=k):
                vec = list(mm.gravity.vector)
                vec[k] = v
                return replace(mm, gravity=replace(mm.gravity, vector=tuple(vec)))

            out.append(_slot(f"gravity.vector[{k}]", "m/s^2", machine.gravity.vector[k], _FREE, set_g))
        return out

    def energy(self, machine, y, place, t: float = 0.0) -> float:
        """The potential of the weights ``-f_g . z`` (J); the balls', unbalances' and other
        parts' own terms ``-m g . r`` are theirs."""
        return float(-self.weights(machine) @ np.asarray(y, dtype=float)[:machine.n_coordinates])
