"""Attachment parts of the composed machine: one object per attachment that owns its states,
packed parameters, kernel lines, energy terms and named parameters.

A :class:`rotorlab.models.Machine` holds its parts in ``parts`` (a tuple of
:class:`AbstractPart`), and makes a part of each of its unbalances
(:class:`~rotorlab.models._unbalance_part.UnbalancePart`, from ``Machine.unbalances``) and of its
gravity (:class:`~rotorlab.models._gravity_part.GravityPart`, from ``Machine.gravity``, zero
without): ``Machine.attachments``, in that order. The machine loops over them wherever it lays
out, packs, names, starts or sums something, and the kernel generator
(:mod:`rotorlab._kernels.machine_codegen`) loops over their kernel parts
(:class:`AbstractKernelPart`) through the common operations of
:mod:`rotorlab._kernels.machine_emit`. A case file lists a part under its own key
(``[[model.<key>]]``); its spec registers there (:data:`rotorlab.io._part_specs.PART_SPECS`;
the unbalances' too, ``[[model.unbalances]]``). The races, the drive, the clearance and ball
friction are not parts yet (fields and flags of ``Machine`` and ``Layout``).

A part whose attachment is *soft* (a spring, a damper: no rigid constraint on the structure)
needs nothing else: it reads the displacement and rate of its stations (``B_s z``, ``B_s z'``),
writes the forces it puts on them (they enter ``h = H R_z`` with the other station forces, so
the Schur system of the balls sees them) and the rates of its own states.

For implementers
----------------
1. Subclass :class:`AbstractPart` as a frozen dataclass whose fields are SI numbers (and a
   ``node``, ``axial_offset`` for where it sits); set :attr:`AbstractPart.key` (the case key, e.g.
   ``"absorbers"``) and :attr:`AbstractPart.fields` (``(field, unit, bounds)`` of its named
   parameters, the case file's key paths ``<key>[i].<field>``); raise ``ValueError`` in
   ``__post_init__`` on bad values.
2. :meth:`AbstractPart.kernel` returns its kernel part: a frozen, hashable object (equal for
   equal sizes) with ``key`` (short tag in the generated module's name), ``n_states``,
   ``n_param``, ``n_stations`` and three line writers, each given the
   :class:`~rotorlab._kernels.machine_layout.Layout` and its
   :class:`~rotorlab._kernels.machine_layout.PartPlace`: ``force_lines(lay, L, place)`` appends
   lines that define the forces on its stations and returns them as ``[(station, fx name, fy
   name)]``; ``rate_lines(lay, place)`` returns the lines writing ``out[...]`` of its states;
   ``dissipation_terms(lay, place)`` returns the terms of its dissipated power (energy states);
   the last two default to none (a part without states, without damping).
   Generated variables: ``z{i}``, ``v{i}`` (structure coordinates and rates), ``gx``, ``gy``
   (lateral gravity), ``om``, ``theta`` (spin), ``dom`` (its rate, prescribed spin), ``sth``,
   ``cth`` (sine and cosine of theta, written by the first ``rotor`` part); name yours with a prefix of your own.
   ``variable_lines(lay, place)`` (optional) defines variables every other part may read
   (gravity's ``gx``, ``gy``), written before all other part lines.
3. :meth:`AbstractPart.stations` returns the ``B`` (2 x n_z) of its stations
   (:meth:`Machine.station_matrix`), :meth:`AbstractPart.pack` its ``n_param`` numbers.
4. :meth:`AbstractPart.state_names`, :meth:`AbstractPart.initial` (its states in a new initial
   state), :meth:`AbstractPart.energy` (its kinetic and potential energy: the machine's energy
   ledger adds it) and :meth:`AbstractPart.rotating_refusal` (why the co-rotating frame has no
   equilibria with it, or None); a linear part also gives its
   :meth:`AbstractPart.dynamic_stiffness` (the reference "without balancing" of a simulation
   then includes it).
5. Register its spec (one line in :mod:`rotorlab.io._part_specs`), add a figure in ``plot/``
   and tests against a closed form.
6. A part fixed to the rotor (it turns with theta: an unbalance) sets ``rotor = True`` on its
   kernel part: its stations come right after the races' and its block after the balls'. With a
   motor, theta'' is an unknown of the Schur system: ``spin_loads(lay, place)`` returns per
   station a :class:`~rotorlab._kernels.machine_layout.SpinLoad` (its column of the mass
   matrix's coupling block on theta, ``coef B_s^T (tx, ty)``, and its generalised force on
   theta); the generator, the tilting races, ball friction and the clearance read the spin's
   coupling from these only. On the model side :meth:`AbstractPart.spin_column` gives the same
   column for the mass matrix.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import replace
from typing import Any, ClassVar

import numpy as np

__all__ = ["AbstractPart", "AbstractKernelPart", "part_slots"]


class AbstractKernelPart(ABC):
    """The sizes and kernel lines of a part (see the module docstring, item 2)."""

    key: ClassVar[str] = ""
    n_states: ClassVar[int] = 0
    n_param: ClassVar[int] = 0
    n_stations: ClassVar[int] = 0
    #: fixed to the rotor (it turns with theta: an unbalance); see the module docstring, item 6
    rotor: ClassVar[bool] = False

    def variable_lines(self, lay, place) -> list[str]:
        """Lines defining variables that other parts read, written before every other line of
        the parts (gravity's ``gx``, ``gy``)."""
        return []

    def spin_loads(self, lay, place) -> list:
        """Its :class:`~rotorlab._kernels.machine_layout.SpinLoad` per station (``rotor`` parts)."""
        return []

    @abstractmethod
    def force_lines(self, lay, L: list[str], place) -> list[tuple[int, str, str]]:
        ...

    def rate_lines(self, lay, place) -> list[str]:
        """The lines writing ``out[...]`` of its states (none by default)."""
        return []

    def dissipation_terms(self, lay, place) -> list[str]:
        """The terms of its dissipated power (none by default)."""
        return []


class AbstractPart(ABC):
    """An attachment of a machine (see the module docstring's "For implementers" list)."""

    key: ClassVar[str] = ""
    #: (field, unit, bounds) of the named parameters; bounds are (gt, ge, lt, le), None: open
    fields: ClassVar[tuple[tuple[str, str, tuple], ...]] = ()
    node: int

    @abstractmethod
    def kernel(self) -> AbstractKernelPart:
        ...

    @abstractmethod
    def stations(self, machine) -> list[np.ndarray]:
        ...

    @abstractmethod
    def pack(self, machine) -> np.ndarray:
        ...

    @abstractmethod
    def state_names(self, index: int) -> list[str]:
        """Names of its states; ``index`` counts the parts of its key (0, 1, ...)."""

    @abstractmethod
    def initial(self, machine, y: np.ndarray, place) -> None:
        """Set its states in the new initial state ``y`` (structure coordinates already set)."""

    @abstractmethod
    def energy(self, machine, y: np.ndarray, place, t: float = 0.0) -> float:
        """Its kinetic and potential energy (J) at the fixed-frame state ``y`` at time ``t``."""

    @abstractmethod
    def rotating_refusal(self) -> str | None:
        """Why the co-rotating frame has no equilibria with this part, None if it has."""

    def spin_column(self, machine, theta: float) -> np.ndarray | None:
        """Its column of the mass matrix's coupling block on theta (a part fixed to the rotor,
        with a motor: shape (n_z,)); None: it does not turn with the rotor."""
        return None

    def dynamic_stiffness(self, machine, omega: float) -> np.ndarray | None:
        """What it adds to the structure's dynamic stiffness ``K + i w C - w^2 M`` over the DOFs
        (shape (n_dof, n_dof), complex) under a harmonic motion at ``omega`` (rad/s), for the
        locked-ball unbalance responses; None: nothing."""
        return None


def part_slots(m, field: str = "parts") -> list[Any]:
    """The named parameters of the parts a machine holds in its field ``field`` (``"parts"``, or
    ``"unbalances"``: each unbalance's :class:`~rotorlab.models._unbalance_part.UnbalancePart`):
    ``<key>[i].<field>`` (i counts the parts of one key), each set by replacing that item."""
    from rotorlab.models._parameters import owned_slots

    parts = m.parts if field == "parts" else m.attachments[:len(m.unbalances)]  # gravity's: GravityPart.slots
    out = []
    for k, (part, i) in enumerate(zip(parts, part_indices(parts))):
        def set_(mm, name, v, k=k):
            held = getattr(mm, field)
            return replace(mm, **{field: held[:k] + (replace(held[k], **{name: v}),) + held[k + 1:]})

        out += owned_slots(f"{part.key}[{i}]", part, set_)
    return out


def part_indices(parts) -> list[int]:
    """Each part's index among the parts of its key."""
    seen: dict[str, int] = {}
    out = []
    for part in parts:
        seen[part.key] = seen.get(part.key, -1) + 1
        out.append(seen[part.key])
    return out
