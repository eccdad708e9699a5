r"""The composed machine (model ``machine``): a linear structure plus what is attached to it.

A *structure* is any :class:`rotorlab.linear.LinearSystem` (rigid bodies, a housing on supports,
Timoshenko FE shafts, anisotropic bearings with cross terms): ``M_s z'' + (C + Omega G) z' + K z =
f`` over the DOFs ``x, y, phi_x, phi_y`` of every node, optionally reduced to its lowest
``n_modes`` undamped, non-spinning modes (``z = Phi eta``, ``Phi^T M Phi = I``). Attached to it:

- **ball races** (:class:`BallRace`): balls of mass m_b at radius l about the race centre, which
  moves with the node as ``r_c = B z = (x + a phi_x, y + a phi_y)`` (a: axial offset of the race);
  the race plane tilts with its node (``phi = T z``) and a ball follows it, axially too (rigid
  ball kinematics, as Rodrigues, Champneys, Friswell & Wilson 2008);
- **unbalances** (:class:`Unbalance`): ``U = m e`` at ``theta + beta`` at a station, and couples
  (in the kernel two opposite point unbalances, whose forces and couplings are the couple's);
- **gravity** (:class:`Gravity`): its lateral part loads the structure, the balls and, through
  the unbalances, the drive;
- **a drive**: a prescribed spin (:class:`ConstantSpeed`, :class:`LinearRamp`,
  :class:`HillRunUp`) or a :class:`Motor` (spin angle and speed become states);
- **a clearance** (:class:`Clearance`): rotor-stator contact at a station against a rigid stator,
  a massless elastic one or a moving housing, with located impacts, Newton restitution, Coulomb
  friction with the rotor's surface speed, chatter, sustained sliding or rolling contact and
  lift-off (generated over the shared contact law, :mod:`rotorlab._kernels.machine_contact`);
- **ball friction** (a :class:`Ball`'s ``coulomb`` and ``rolling``): stick-slip with the law of
  ``jeffcott_balls``; one mode state per ball at the end of the state, events ``stick_<r>_<b>``,
  ``slip_<r>_<b>`` and their reset maps (:func:`rotorlab._kernels.machine_codegen.friction_solve`);
  the friction power ``-tau_b (phi_b' - Omega)`` counts as dissipated. Not with a clearance.
- **parts** (:mod:`rotorlab.models._parts`): attachments that own their states, packed block,
  kernel lines, energy and named parameters: the unbalances and gravity (made from the fields
  above) and ``parts``, e.g. a :class:`rotorlab.models.TunedMassAbsorber` (states after the energy states).

Equations (fixed frame, always)
-------------------------------
With ``e_b = (cos phi_b, sin phi_b)``, ``t_b = (-sin phi_b, cos phi_b)`` for ball b (absolute
angle phi_b, race r) and ``e_u, t_u`` likewise at ``theta + beta_u``, the kinetic energy is ::

    T = 1/2 z'^T M_s z' + sum_b [1/2 m_b |B_r z'|^2 + m_b l_b phi_b' t_b . B_r z'
        + 1/2 J_b phi_b'^2] + 1/2 J theta'^2 + sum_u U_u theta' t_u . B_u z'

(``J_b = m_b l_b^2 + J_c``; J the polar inertia of a motor-driven rotor; the unbalance masses are
part of ``M_s``), plus the terms of a ball on a *tilting* race (below). Lagrange's equations give ::

    M0 z'' + sum_b m_b l_b B_r^T t_b phi_b'' + sum_u U B_u^T t_u theta''
        = -K z - (C + Omega G) z' + f_g + sum_b m_b l_b phi_b'^2 B_r^T e_b + sum_u U theta'^2 B_u^T e_u
    J_b phi_b'' + m_b l_b t_b . B_r z'' = -c_b (phi_b' - Omega) + m_b l_b g . t_b
    J theta'' + sum_u U t_u . B_u z'' = T(Omega) + sum_b c_b (phi_b' - Omega) + sum_u U g . t_u

with ``M0 = M_s + sum_r m_r B_r^T B_r`` (m_r: ball mass of race r) and ``f_g`` the weights of the
structure (``M_s`` times the rigid translation along g) and of the balls. With a prescribed spin
the last equation is not solved: theta'' is known and the torque it needs is the drive torque.

Rigid ball kinematics on a tilting race: the ball sits at the body point ``(l e(phi_b), a)`` of
the race, turned with its node by the rotation vector ``(-phi_y, phi_x, 0)`` (``phi = T_r z``, the
node's tilt); ``phi_b`` is measured in the tilted race plane. To second order in the small
motions (the truncation of Rodrigues et al. 2008, Section 2.3.2) this moves the ball axially by
``-l e_b . phi`` and turns the race plane about its normal at the rate ``(phi_y phi_x' - phi_x
phi_y') / 2``, which adds to T ::

    sum_b [1/2 m_b l_b^2 (e_b . phi')^2 + 1/2 J_b phi_b' (phi_y phi_x' - phi_x phi_y')]

(the ball's own inertia J_c turns with the race normal too). Its terms in the equations: the
structure gains the mass ``m_b l_b^2 T^T e_b e_b^T T`` and the force ``-T^T [m_b l_b^2 phi_b'
((t_b . phi') e_b + (e_b . phi') t_b) + J_b phi_b' (phi_y', -phi_x')]``, the ball its coupling
``J_b / 2 (phi_y, -phi_x) . T z''`` and the force ``m_b l_b^2 (e_b . phi') (t_b . phi')``. The
structure's equilibria and the balanced state are unchanged (the terms vanish at rest); they
change the stability of the balanced state (its primary region's onset, Fig. 5(a) of the paper)
and the motion. The rank-one mass terms enter the elimination below as one extra unknown per
ball, ``mu_b = m_b l_b^2 e_b . T z''`` (its row ``e_b . T z'' - mu_b / (m_b l_b^2) = 0``), so
that ``M0`` stays constant; the Schur complement is then symmetric quasi-definite (positive
block of the ball and spin accelerations, negative block of the mu_b) and the unrolled LDL^T
needs no pivoting.

Solution of the mass-matrix system: with ``H = M0^-1`` (constant, precomputed) the structure
accelerations are eliminated, leaving the Schur complement ``S = diag(J_b, J) - X^T H X``
(symmetric positive definite, size n_b or n_b + 1) for the ball (and spin) accelerations, solved by
an unrolled LDL^T; then ``z'' = H (R_z - X s)``. All constant products (``H K``, ``H C``, ``H G``,
``H B^T``, ``B H B^T``) are packed in ``p`` (layout: :mod:`rotorlab._kernels.machine_codegen`).

Energy (:meth:`Machine.energy`): ``E = T + 1/2 z^T K_sym z - f_g . z - sum_b m_b l_b g . e_b -
sum_u U g . e_u`` (with a prescribed spin the rotor's own spin energy is left out, J = 0). The
drive power is ``T(Omega) Omega`` (motor) or the torque the prescribed spin needs times Omega; the
dissipated power is ``z'^T C z' + z'^T K_skew z + sum_b c_b (phi_b' - Omega)^2``. With
``energy_states=True`` both are integrated as two extra states (``work``, ``dissipated``), so the
balance ``work = E - E(0) + dissipated`` holds to the integrator's tolerance
(:meth:`Machine.energy_balance`); this is the documented choice over quadrature of saved samples.

Co-rotating frame: where the structure is isotropic (:attr:`LinearSystem.is_isotropic`), there is
no lateral gravity and the spin is constant, ``u = R(-theta) x`` per coordinate pair and
``psi_b = phi_b - theta`` make the equations autonomous; steady motions are equilibria there
(:meth:`Machine.rotating_rhs`, :meth:`Machine.linearize`, :meth:`Machine.balanced_state`).

Where the code lives: this module holds the machine's sizes, structure reduction, packing and
kernels; its initial states, mass matrix and energy are in ``_machine_physics``, its clearance
helpers in ``_machine_clearance``, its co-rotating frame (linearization, steady states) in
``_machine_rotating`` and its validity limits and sanity monitor in ``_machine_validity`` (mixed
into :class:`Machine`); the attachments in ``_machine_parts``, the parts' protocol in ``_parts``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rotorlab._kernels import machine_codegen as _cg
from rotorlab.linear._system import LinearSystem
from rotorlab.models._base import EventSpec, Kernels
from rotorlab.models._machine_parts import Ball, BallRace, Clearance, ElasticStator, Gravity, Motor, Unbalance
from rotorlab.models._machine_clearance import _ClearanceParts
from rotorlab.models._machine_physics import _Physics
from rotorlab.models._machine_rotating import MachineLinearization, _RotatingFrame
from rotorlab.models._parameters import machine_slots
from rotorlab.models._parts import AbstractPart, part_indices
from rotorlab.models._protocol import ParametrisedMixin
from rotorlab.models._gravity_part import GravityPart
from rotorlab.models._unbalance_part import UnbalancePart
from rotorlab.models._machine_validity import _Validity
from rotorlab.models._speed import ConstantSpeed, HillRunUp, LinearRamp

__all__ = ["Machine", "MachineLinearization", "Ball", "BallRace", "Unbalance", "Gravity", "Motor",
           "Clearance", "ElasticStator"]

MAX_COORDINATES = 40
CLEARANCE_EVENTS = ("contact", "lift_off", "stick", "slip")
CLEARANCE_MODES = {0: "free", 1: "sliding (positive slip)", -1: "sliding (negative slip)", 2: "rolling"}
_SPEED_KIND = {ConstantSpeed: "constant", LinearRamp: "ramp", HillRunUp: "hill"}


def _tuple_of(owner: str, items, cls) -> tuple:
    if items is None:
        return ()
    if isinstance(items, cls):
        items = (items,)
    out = tuple(items)
    for i, it in enumerate(out):
        if not isinstance(it, cls):
            raise ValueError(f"{owner}[{i}] must be a {cls.__name__}, got {type(it).__name__}")
    return out


@dataclass(frozen=True)
class Machine(_Physics, _ClearanceParts, _RotatingFrame, _Validity, ParametrisedMixin):
    """A linear structure with ball races, unbalances, gravity and a drive (model ``machine``).

    Parameters
    ----------
    structure : LinearSystem
        The rotor and its supports (M, C, G, K over x, y, phi_x, phi_y per node).
    races : tuple of BallRace
        Automatic-balancer races, any number, at any node.
    unbalances : tuple of Unbalance
    gravity : Gravity, optional
        None: no lateral gravity.
    drive : ConstantSpeed, LinearRamp, HillRunUp or Motor
        Prescribed spin or a motor.
    n_modes : int, optional
        Keep the lowest ``n_modes`` modes of the structure (even when the structure is isotropic:
        modes come in x/y pairs); None keeps every DOF (at most 40 coordinates).
    energy_states : bool
        Append the drive work and the dissipated energy as two states.
    clearances : tuple of Clearance
        Rotor-stator contact; at most one clearance per machine for now. It adds its states
        (see :mod:`rotorlab._kernels.machine_contact`), its events ``contact``, ``lift_off``,
        ``stick``, ``slip`` and their reset maps.
    parts : tuple of AbstractPart
        Further attachments, each owning its states, parameters and kernel lines
        (:mod:`rotorlab.models._parts`), e.g. :class:`rotorlab.models.TunedMassAbsorber`.
    unit_modes : bool
        With ``n_modes``: scale each kept mode so that its largest DOF entry is 1 (then a mode
        that moves one DOF only has that DOF as its coordinate) instead of unit modal mass.
    param_base : int
        Entries in front of the packed parameters that the kernel leaves to a preset which owns
        them (:meth:`rotorlab.models.JeffcottBalls.machine`); zeros here.
    structure_source : optional
        Where ``structure`` came from, when it has named parameters of its own (a machine built
        from a case: :class:`rotorlab.io.StructureSource`): ``parameters`` lists them as
        ``structure.<key path>`` and ``with_parameters`` rebuilds the structure from it. It has
        ``parameters`` (:class:`rotorlab.models.Parameter` objects), ``with_value(name, value)``
        (a new source) and ``system`` (its :class:`~rotorlab.linear.LinearSystem`).

    Notes
    -----
    Named parameters (:mod:`rotorlab.models._protocol`): ``races[i].balls[j].mass``,
    ``unbalances[i].magnitude``, ``drive.speed``, ``clearances[0].gap``, ``n_modes``
    (structural) ..., as the case file's ``[model]`` keys.

    Examples
    --------
    >>> import numpy as np
    >>> from rotorlab.linear import LinearSystem
    >>> s = LinearSystem(M=np.diag([1.0, 1.0, 0.1, 0.1]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
    ...                  G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 1.0, 1.0]))
    >>> m = Machine(s, races=(BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * 2),),
    ...             unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(2.5))
    >>> m.n_state, m.state_names[8]
    (12, 'phi_1_1')
    """

    structure: LinearSystem
    races: tuple[BallRace, ...] = ()
    unbalances: tuple[Unbalance, ...] = ()
    gravity: Gravity | None = None
    drive: Any = field(default=None, kw_only=True)
    n_modes: int | None = field(default=None, kw_only=True)
    energy_states: bool = field(default=False, kw_only=True)
    clearances: tuple[Clearance, ...] = field(default=(), kw_only=True)
    parts: tuple[AbstractPart, ...] = field(default=(), kw_only=True)
    unit_modes: bool = field(default=False, kw_only=True)
    param_base: int = field(default=0, kw_only=True, repr=False)
    structure_source: Any = field(default=None, kw_only=True, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.structure, LinearSystem):
            raise ValueError("Machine.structure must be a rotorlab.linear.LinearSystem, got "
                             f"{type(self.structure).__name__}")
        object.__setattr__(self, "races", _tuple_of("Machine.races", self.races, BallRace))
        object.__setattr__(self, "unbalances",
                           _tuple_of("Machine.unbalances", self.unbalances, Unbalance))
        if self.gravity is not None and not isinstance(self.gravity, Gravity):
            raise ValueError(f"Machine.gravity must be a Gravity or None, got {self.gravity!r}")
        if not isinstance(self.drive, (Motor, ConstantSpeed, LinearRamp, HillRunUp)):
            raise ValueError("Machine.drive must be ConstantSpeed, LinearRamp, HillRunUp or Motor, "
                             f"got {type(self.drive).__name__}")
        object.__setattr__(self, "clearances",
                           _tuple_of("Machine.clearances", self.clearances, Clearance))
        if len(self.clearances) > 1:
            raise ValueError(f"Machine.clearances: at most one clearance per machine is implemented, "
                             f"got {len(self.clearances)}")
        object.__setattr__(self, "parts", _tuple_of("Machine.parts", self.parts, AbstractPart))
        nn = self.structure.n_nodes
        for what, items in (("races", self.races), ("unbalances", self.unbalances),
                            ("clearances", self.clearances), ("parts", self.parts)):
            for i, it in enumerate(items):
                if it.node >= nn:
                    raise ValueError(f"Machine.{what}[{i}].node must be < {nn} (the structure's "
                                     f"nodes), got {it.node}")
        if self.has_friction and self.clearances:
            raise ValueError("Machine: ball friction (a Ball's coulomb or rolling > 0) together with a "
                             "clearance is not implemented; set coulomb = 0 and rolling = 0, or "
                             "remove the clearance")
        if self.n_modes is not None:
            k = self.n_modes
            if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k <= self.structure.n_dof:
                raise ValueError(f"Machine.n_modes must be an integer in [1, {self.structure.n_dof}] "
                                 f"or None, got {k!r}")
            if self.structure.is_isotropic and k % 2:
                raise ValueError(f"Machine.n_modes must be even for an isotropic structure "
                                 f"(x/y mode pairs), got {k}")
        elif self.structure.n_dof > MAX_COORDINATES:
            raise ValueError(f"Machine: the structure has {self.structure.n_dof} DOFs; the compiled "
                             f"kernel takes at most {MAX_COORDINATES} coordinates: set n_modes "
                             "(e.g. 8) to keep its lowest modes")
        object.__setattr__(self, "energy_states", bool(self.energy_states))

    # ------------------------------------------------------------------ sizes and names
    @property
    def is_motor(self) -> bool:
        """True when the drive is a motor (spin angle and speed are states)."""
        return isinstance(self.drive, Motor)

    @property
    def has_friction(self) -> bool:
        """True when some ball has Coulomb or rolling friction (the state then carries one
        stick/slip mode per ball, and the kernel its events ``stick_<race>_<ball>``,
        ``slip_<race>_<ball>``)."""
        return any(b.coulomb > 0 or b.rolling > 0 for r in self.races for b in r.balls)

    @property
    def _point_unbalances(self) -> tuple[tuple[int, float, float, float], ...]:
        """The unbalances as the kernel's point unbalances ``(node, axial_offset, m e, phase)``
        (a couple is two opposite ones, :meth:`Unbalance.point_unbalances`)."""
        return tuple((u.node, a, me, beta) for u in self.unbalances for a, me, beta in u.point_unbalances())

    @property
    def attachments(self) -> tuple[AbstractPart, ...]:
        """Every attachment part in the kernel's order: an UnbalancePart of each unbalance, the
        GravityPart (zero without gravity), then ``parts`` (:mod:`rotorlab.models._parts`)."""
        if "attachments" not in self._cache:
            self._cache["attachments"] = (tuple(UnbalancePart.of(u) for u in self.unbalances)
                                          + (GravityPart.of(self.gravity),) + self.parts)
        return self._cache["attachments"]

    @property
    def layout(self) -> _cg.Layout:
        """Sizes and offsets of the states and parameters (a machine_codegen Layout)."""
        if "layout" not in self._cache:
            d = self.drive
            self._cache["layout"] = _cg.Layout(
                n_z=self.n_coordinates, races=tuple(len(r.balls) for r in self.races),
                drive=d.drive_kind if self.is_motor else "profile",
                speed_kind="constant" if self.is_motor else _SPEED_KIND[type(d)],
                n_table=d.n_table if self.is_motor else 0,
                gyroscopic=bool(np.any(self.reduced["G"])), energy=self.energy_states,
                clearance=self.clearances[0].kernel_kind if self.clearances else "",
                friction=self.has_friction,
                tilt=self._tilt_numbers(), parts=tuple(part.kernel() for part in self.attachments),
                param_base=self.param_base)
        return self._cache["layout"]

    @property
    def n_coordinates(self) -> int:
        """Structure coordinates n_z (DOFs, or modes kept)."""
        return self.structure.n_dof if self.n_modes is None else int(self.n_modes)

    @property
    def n_balls(self) -> int:
        return sum(len(r.balls) for r in self.races)

    @property
    def n_state(self) -> int:
        return self.layout.n_state

    @property
    def kernels(self) -> Kernels:
        """Compiled kernels, generated for this machine's sizes (shared between equal sizes)."""
        if "kernels" not in self._cache:
            self._cache["kernels"] = self.kernels_for(self.layout)
        return self._cache["kernels"]

    def kernels_for(self, layout: _cg.Layout) -> Kernels:
        """This machine's kernels generated for ``layout``: its own, or one with compile-time
        constants a preset gives (``Layout.fixed``, :mod:`rotorlab.models._rub_machine`)."""
        mod = _cg.kernel_module(layout)
        common = dict(rhs=mod.rhs, n_state=self.n_state, vectorises=layout.vectorises, inline_lanes=self._inline_lanes)
        if self.clearances:
            return Kernels(**common, n_discrete=layout.n_discrete, events=mod.events, reset=mod.reset,
                           event_specs=tuple(EventSpec(n, -1, "reset") for n in CLEARANCE_EVENTS))
        if self.has_friction:
            specs = [EventSpec(f"{what}_{name}", -1, "reset")
                     for name in self._ball_labels for what in ("stick", "slip")]
            return Kernels(**common, n_discrete=layout.n_discrete, events=mod.events, reset=mod.reset,
                           event_specs=tuple(specs))
        return Kernels(**common)

    @property
    def _inline_lanes(self) -> bool:
        """Whether the lane driver inlines this machine's kernel (``Kernels.inline_lanes``).

        Measured with :func:`rotorlab.integrate._drivers.is_vectorised`: every generated kernel
        vectorises as a call; inlined, those of up to 16 states do (the 16-state two-plane rotor
        with two balls a race ran at the same speed inlined or called: 1306-1333 trajectories per
        CPU-s either way), the 28-state Pico 21 does not. ``tests/unit/test_vectorise.py`` checks
        machines on both sides of 12.
        """
        return self.n_state <= 12

    @property
    def coordinate_names(self) -> tuple[str, ...]:
        """Names of the structure coordinates (``x_<node>`` ..., or ``q_1`` ... when reduced)."""
        if self.n_modes is not None:
            return tuple(f"q_{i + 1}" for i in range(self.n_coordinates))
        lab = self.structure.node_label
        return tuple(f"{d}_{lab[n]}" for n in range(self.structure.n_nodes)
                     for d in ("x", "y", "phi_x", "phi_y"))

    @property
    def state_names(self) -> tuple[str, ...]:
        """Name of each state entry, in order."""
        zc = self.coordinate_names
        balls = self._ball_labels
        names = list(zc) + [f"d{n}" for n in zc] + [f"phi_{b}" for b in balls] + [f"w_{b}" for b in balls]
        if self.is_motor:
            names += ["theta", "omega"]
        if self.energy_states:
            names += ["work", "dissipated"]
        for part, i in zip(self.attachments, part_indices(self.attachments)):
            names += part.state_names(i)
        if self.clearances:
            if self.clearances[0].kind == "housing":
                names += ["x_housing", "y_housing", "vx_housing", "vy_housing"]
            names += ["contact_dissipated", "contact_drive_work", "impacts", "peak_impulse", "contact_mode"]
        if self.has_friction:
            names += [f"mode_{b}" for b in balls]
        return tuple(names)

    @property
    def _ball_labels(self) -> list[str]:
        return [f"{r + 1}_{b + 1}" for r, race in enumerate(self.races) for b in range(len(race.balls))]

    # ------------------------------------------------------------------ structure reduction
    @property
    def basis(self) -> np.ndarray:
        """The basis Phi (shape n_dof by n_z) from structure coordinates to DOFs.

        The identity, or the kept modes (mass-normalised, or with ``unit_modes`` a largest entry 1).

        For an isotropic structure the modes of the x plane are used for both planes, ordered as
        x/y pairs (so that the co-rotating frame rotates each pair).
        """
        if "basis" in self._cache:
            return self._cache["basis"]
        s = self.structure
        if self.n_modes is None:
            phi = np.eye(s.n_dof)
        else:
            import scipy.linalg as sla

            ks = 0.5 * (s.K + s.K.T)
            if s.is_isotropic:
                xp, yp = s.plane_indices
                k = self.n_modes // 2
                _, vx = sla.eigh(ks[np.ix_(xp, xp)], s.M[np.ix_(xp, xp)], subset_by_index=(0, k - 1))
                phi = np.zeros((s.n_dof, 2 * k))
                phi[xp, 0::2] = vx
                phi[yp, 1::2] = vx
            else:
                _, phi = sla.eigh(ks, s.M, subset_by_index=(0, self.n_modes - 1))
            if self.unit_modes:
                phi = phi / phi[np.argmax(np.abs(phi), axis=0), range(phi.shape[1])]
        self._cache["basis"] = phi
        return phi

    @property
    def reduced(self) -> dict[str, np.ndarray]:
        """``M, C, G, K`` of the structure in its coordinates (``Phi^T A Phi``)."""
        if "reduced" not in self._cache:
            phi, s = self.basis, self.structure
            self._cache["reduced"] = {n: phi.T @ getattr(s, n) @ phi for n in ("M", "C", "G", "K")}
        return self._cache["reduced"]

    def station_matrix(self, node: int, axial_offset: float = 0.0, *, dofs: bool = False) -> np.ndarray:
        """B, shape (2, n_z): the lateral displacement ``(x + a phi_x, y + a phi_y)`` of a station
        (with ``dofs``: over the structure's DOFs, shape (2, n_dof))."""
        e = np.zeros((2, self.structure.n_dof))
        e[0, 4 * node] = 1.0
        e[1, 4 * node + 1] = 1.0
        e[0, 4 * node + 2] = axial_offset
        e[1, 4 * node + 3] = axial_offset
        return e if dofs else e @ self.basis

    def _tilt_numbers(self) -> tuple[int, ...]:
        """Per race the number of its node among the races' distinct nodes, or () when no race
        can tilt (the layout's ``tilt``)."""
        if not any(np.any(self.tilt_matrix(r.node) != 0.0) for r in self.races):
            return ()
        nodes = list(dict.fromkeys(r.node for r in self.races))
        return tuple(nodes.index(r.node) for r in self.races)

    def tilt_matrix(self, node: int) -> np.ndarray:
        """T, shape (2, n_z): the tilt ``(phi_x, phi_y)`` of a node (where its races tilt)."""
        return self.basis[4 * node + 2:4 * node + 4, :]

    @property
    def _packed_stations(self) -> list[np.ndarray]:
        """The stations packed in ``p``: :attr:`_stations`, then with a tilting race (layout
        ``tilt``) the tilt ``T_r`` of each race's node."""
        nodes = list(dict.fromkeys(r.node for r in self.races)) if self.layout.tilt else []
        extra = [self.tilt_matrix(n) for n in nodes]
        return self._stations + extra + [B for part in self.attachments if not part.kernel().rotor
                                         for B in part.stations(self)]

    @property
    def _stations(self) -> list[np.ndarray]:
        """The lateral stations: the races', the rotor parts' (unbalances'), the clearance's."""
        return [self.station_matrix(r.node, r.axial_offset) for r in self.races] + \
               [B for part in self.attachments if part.kernel().rotor for B in part.stations(self)] + \
               [self.gap_matrix(c) for c in self.clearances]

    def gap_matrix(self, clearance: Clearance) -> np.ndarray:
        """B, shape (2, n_z), of a clearance: its gap vector is ``w = B z`` (minus the housing).

        ``(x + a phi_x, y + a phi_y)`` at the station, or ``sin(beta) (x, y) + l_P (phi_x,
        phi_y)`` for a conical gap ``(beta, l_P)``.
        """
        if clearance.conical is None:
            return self.station_matrix(clearance.node, clearance.axial_offset)
        beta, lever = clearance.conical
        e = np.zeros((2, self.structure.n_dof))
        k = 4 * clearance.node
        e[0, k], e[1, k + 1] = math.sin(beta), math.sin(beta)
        e[0, k + 2], e[1, k + 3] = lever, lever
        return e @ self.basis

    @property
    def _ball_arrays(self):
        """Per ball: m, l, J_b, c, race index."""
        rows = [(b.mass, r.radius, b.mass * r.radius ** 2 + b.inertia, b.damping, i)
                for i, r in enumerate(self.races) for b in r.balls]
        a = np.array(rows, dtype=float).reshape(-1, 5)
        return a[:, 0], a[:, 1], a[:, 2], a[:, 3], a[:, 4].astype(int)

    @property
    def lateral_gravity(self) -> tuple[float, float]:
        return (0.0, 0.0) if self.gravity is None else self.gravity.lateral

    def _weights(self) -> np.ndarray:
        """f_g in the structure coordinates: structure and ball weights (N), gravity's
        (:meth:`rotorlab.models._gravity_part.GravityPart.weights`)."""
        return GravityPart.of(self.gravity).weights(self)

    def _m0(self) -> np.ndarray:
        m0 = self.reduced["M"].copy()
        for r, B in zip(self.races, self._stations):
            m0 += sum(b.mass for b in r.balls) * (B.T @ B)
        return m0

    # ------------------------------------------------------------------ packing
    def to_array(self) -> np.ndarray:
        """Return the packed parameters (layout in :mod:`rotorlab._kernels.machine_codegen`)."""
        if "p" in self._cache:
            return self._cache["p"].copy()
        lay = self.layout
        o = lay.offsets
        p = np.zeros(lay.n_param)
        d = self.drive
        if self.is_motor:
            blk = d.to_array()
            p[o["motor"]:o["motor"] + blk.size] = blk
            p[o["speed"]:o["speed"] + 6] = d.speed_block()
        else:
            p[o["speed"]:o["speed"] + 6] = d.to_array()
        if lay.friction:  # friction arm of each ball: coulomb l + rolling (m)
            p[o["friction"]:o["friction"] + lay.n_balls] = [
                b.coulomb * r.radius + b.rolling for r in self.races for b in r.balls]
        m, l, J, c, _ = self._ball_arrays
        for b in range(lay.n_balls):
            p[o["balls"] + 4 * b: o["balls"] + 4 * b + 4] = (m[b], m[b] * l[b], J[b], c[b])
        red = self.reduced
        H = np.linalg.inv(self._m0())
        H = 0.5 * (H + H.T)
        st = self._packed_stations
        nz = lay.n_z
        if lay.tilt:  # D_b = m_b l_b^2: the ball's inertia about its race's diameters
            p[o["tilt"]:o["tilt"] + lay.n_balls] = m * l * l
        for s, B in enumerate(st):
            k = lay.station_B(s)
            p[k:k + 2 * nz] = B.ravel()
            p[k + 2 * nz:k + 4 * nz] = (H @ B.T).ravel()
        for s, B in enumerate(st):
            for s2, B2 in enumerate(st):
                k = lay.pair_L(s, s2)
                p[k:k + 4] = (B @ H @ B2.T).ravel()
        p[o["HK"]:o["HK"] + nz * nz] = (H @ red["K"]).ravel()
        p[o["HC"]:o["HC"] + nz * nz] = (H @ red["C"]).ravel()
        if lay.gyroscopic:
            p[o["HG"]:o["HG"] + nz * nz] = (H @ red["G"]).ravel()
        p[o["Hf"]:o["Hf"] + nz] = H @ self._weights()
        if lay.energy:
            p[o["C"]:o["C"] + nz * nz] = red["C"].ravel()
            p[o["Ka"]:o["Ka"] + nz * nz] = (0.5 * (red["K"] - red["K"].T)).ravel()
        if self.clearances:
            p[o["clearance"]:o["clearance"] + 8] = self.clearances[0].to_array()
            p[o["clearance"] + 8:o["clearance"] + 10] = self.clearance_center
            # rate of the contact's constraint stabilisation: the highest natural frequency
            p[o["clearance"] + 10] = self._stabilisation_rate()
        for part, place in zip(self.attachments, (pl for _, pl in lay.placed_parts)):
            blk = part.pack(self)
            p[place.param:place.param + blk.size] = blk
        self._cache["p"] = p
        return p.copy()

    def _stabilisation_rate(self) -> float:
        """The clearance's Baumgarte rate (1/s): its own, or the highest natural frequency."""
        a = self.clearances[0].stabilisation
        if a is not None:
            return a
        import scipy.linalg as sla

        lam = sla.eigvals(self.reduced["K"], self._m0())
        return math.sqrt(max(float(np.max(np.abs(lam))), 1e-300))

    # ------------------------------------------------------------------ variants
    def with_drive(self, drive) -> Machine:
        """Return a copy with another drive."""
        return replace(self, drive=drive)

    def _parameter_slots(self):
        return machine_slots(self)

    def _compiled_layout(self):
        return self.layout

    # ------------------------------------------------------------------ evaluation helpers
    def rhs(self, t: float, y, p=None) -> np.ndarray:
        """Return dy/dt from the compiled kernel (allocates; for SciPy and tests)."""
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty_like(y)
        self.kernels.rhs(float(t), y, self.to_array() if p is None else np.asarray(p, float), out)
        return out

    def spin(self, t: float, y=None) -> tuple[float, float]:
        """Return ``(theta, Omega)`` at time t (from the state with a motor)."""
        if self.is_motor:
            if y is None:
                raise ValueError("a motor-driven machine needs the state y for its spin")
            return float(y[self.layout.i_theta]), float(y[self.layout.i_theta + 1])
        return float(self.drive.spin_angle(t)), float(self.drive.spin_speed(t))

    def displacements(self, y) -> np.ndarray:
        """Return the node DOFs ``Phi z`` (shape (..., n_dof)) of fixed-frame states y."""
        y = np.asarray(y, dtype=float)
        return y[..., :self.n_coordinates] @ self.basis.T

    def station_amplitudes(self, y) -> np.ndarray:
        """Return ``sqrt(x^2 + y^2)`` of every node (m) at states y (shape (..., n_nodes))."""
        q = self.displacements(y)
        return np.hypot(q[..., 0::4], q[..., 1::4])
