r"""The unbalance as a part of the composed machine (:mod:`rotorlab.models._parts`): a mass
``m e`` off the axis that turns with the rotor, at ``theta + beta`` (and a couple, as two opposite
point unbalances, :meth:`rotorlab.linear.Unbalance.point_unbalances`).

Per point unbalance ``U = m e`` at the station ``u = B z`` with ``e_u = (cos, sin)(theta +
beta)``, ``t_u = (-sin, cos)(theta + beta)``, its terms of the machine's Lagrangian
(:mod:`rotorlab.models._machine`) are the coupling ``U theta' t_u . B z'`` and the potential
``-U g . e_u``; they put on the station ::

    F = U Omega^2 e_u - U theta'' t_u          (prescribed spin: theta'' = Omega', known)

and on the spin the generalised force ``U g . t_u - U t_u . B z''``. With a motor theta'' is an
unknown of the machine's Schur system: the part hands the generator its column of the coupling
block (:class:`~rotorlab._kernels.machine_layout.SpinLoad`: ``U B^T t_u``, and its gravity torque
``U g . t_u``), and the generator, the tilting races, the ball friction and the clearance read
the spin's coupling from those loads only. It has no states; its energy terms are the coupling
with a prescribed spin (with a motor it is in the mass matrix, :meth:`UnbalancePart.spin_column`)
and the potential.

Packed block (3 per point unbalance): ``U`` (kg m), ``cos beta``, ``sin beta``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np

from rotorlab._kernels.machine_layout import SpinLoad
from rotorlab.linear._unbalance import Unbalance
from rotorlab.models._parts import AbstractKernelPart, AbstractPart

__all__ = ["UnbalancePart"]


@dataclass(frozen=True)
class _UnbalanceLines(AbstractKernelPart):
    """Kernel lines of ``n`` point unbalances (no states; 3 packed numbers and one station each)."""

    key: ClassVar[str] = "u"
    rotor: ClassVar[bool] = True
    n: int = 1

    @property
    def n_param(self) -> int:
        return 3 * self.n

    @property
    def n_stations(self) -> int:
        return self.n

    def _points(self, lay, place):
        """(name index u, packed offset, station) of each point unbalance."""
        u0 = place.station - lay.n_races
        return [(u0 + j, place.param + 3 * j, place.station + j) for j in range(self.n)]

    def variable_lines(self, lay, place):
        """The first part fixed to the rotor writes ``sth, cth``, the sine and cosine of theta."""
        return ["    sth, cth = sincos(theta)"] if place.station == lay.n_races else []

    def force_lines(self, lay, L, place):
        out = []
        for u, k, s in self._points(lay, place):
            L += [f"    U{u} = p[{k}]", f"    eux{u} = cth * p[{k + 1}] - sth * p[{k + 2}]",
                  f"    euy{u} = sth * p[{k + 1}] + cth * p[{k + 2}]"]
            if lay.motor:  # theta'' is an unknown of the Schur system (spin_loads)
                L += [f"    fx{s} = U{u} * om * om * eux{u}", f"    fy{s} = U{u} * om * om * euy{u}"]
            else:  # U (Omega^2 e_u - Omega' t_u), t_u = (-euy, eux)
                L += [f"    fx{s} = U{u} * (om * om * eux{u} + dom * euy{u})",
                      f"    fy{s} = U{u} * (om * om * euy{u} - dom * eux{u})"]
            out.append((s, f"fx{s}", f"fy{s}"))
        return out

    def spin_loads(self, lay, place):
        return [SpinLoad(s, f"U{u}", f"(-euy{u})", f"eux{u}", f"U{u} * (-gx * euy{u} + gy * eux{u})")
                for u, _, s in self._points(lay, place)]


@dataclass(frozen=True)
class UnbalancePart(Unbalance, AbstractPart):
    """An :class:`rotorlab.linear.Unbalance` as a part of a machine (case key ``unbalances``).

    A machine holds its unbalances as given (``Machine.unbalances``, plain
    :class:`~rotorlab.linear.Unbalance` objects) and makes each one of these for its kernel,
    packing, energy and named parameters (``unbalances[i].magnitude``, ``.phase``,
    ``.axial_offset``, ``.couple``, ``.couple_phase``: :attr:`rotorlab.linear.Unbalance.fields`;
    a couple from or to 0 changes the compiled layout).
    """

    key: ClassVar[str] = "unbalances"

    @classmethod
    def of(cls, u: Unbalance) -> UnbalancePart:
        """The part of unbalance ``u``."""
        return u if isinstance(u, cls) else cls(**{f.name: getattr(u, f.name) for f in fields(u)})

    def kernel(self) -> _UnbalanceLines:
        return _UnbalanceLines(len(self.point_unbalances()))

    def stations(self, machine) -> list[np.ndarray]:
        return [machine.station_matrix(self.node, a) for a, _, _ in self.point_unbalances()]

    def pack(self, machine) -> np.ndarray:
        return np.array([(me, math.cos(beta), math.sin(beta)) for _, me, beta in self.point_unbalances()]).ravel()

    def state_names(self, index: int) -> list[str]:
        return []

    def initial(self, machine, y, place) -> None:
        """No states."""

    def spin_column(self, machine, theta: float) -> np.ndarray:
        """``sum U B^T t_u`` (kg m): its column of the mass matrix's coupling block on theta."""
        w = np.zeros(machine.n_coordinates)
        for B, (_, me, beta) in zip(self.stations(machine), self.point_unbalances()):
            a = theta + beta
            w += me * (B.T @ np.array([-math.sin(a), math.cos(a)]))
        return w

    def energy(self, machine, y, place, t: float = 0.0) -> float:
        """``Omega t_u . B z'`` with a prescribed spin (a motor's is in the mass matrix) and the
        potential ``-U g . e_u``, summed over its point unbalances (J)."""
        nz = machine.n_coordinates
        th, om = machine.spin(t, y)
        gx, gy = machine.lateral_gravity
        out = 0.0
        for B, (_, me, beta) in zip(self.stations(machine), self.point_unbalances()):
            a = th + beta
            if not machine.is_motor:
                out += me * om * (np.array([-math.sin(a), math.cos(a)]) @ (B @ y[nz:2 * nz]))
            out -= me * (gx * math.cos(a) + gy * math.sin(a))
        return float(out)

    def rotating_refusal(self) -> str | None:
        return None
