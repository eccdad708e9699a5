r"""The composed machine (model ``machine``): a linear structure plus what is attached to it.

A *structure* is any :class:`rotorlab.linear.LinearSystem` (rigid bodies, a housing on supports,
Timoshenko FE shafts, anisotropic bearings with cross terms): ``M_s z'' + (C + Omega G) z' + K z =
f`` over the DOFs ``x, y, phi_x, phi_y`` of every node, optionally reduced to its lowest
``n_modes`` undamped, non-spinning modes (``z = Phi eta``, ``Phi^T M Phi = I``). Attached to it:

- **ball races** (:class:`BallRace`): balls of mass m_b at radius l about the race centre, which
  moves with the node as ``r_c = B z = (x + a phi_x, y + a phi_y)`` (a: axial offset of the race);
  the race plane tilts with its node (``phi = T z``) and a ball follows it, axially too (rigid
  ball kinematics, as Rodrigues, Champneys, Friswell & Wilson 2008);
- **unbalances** (:class:`Unbalance`): ``U = m e`` at ``theta + beta`` at a station;
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
from rotorlab.models._jeffcott_physics import Linearization
from rotorlab.models._speed import ConstantSpeed, HillRunUp, LinearRamp

__all__ = ["Machine", "MachineLinearization", "Ball", "BallRace", "Unbalance", "Gravity", "Motor",
           "Clearance", "ElasticStator"]

MAX_COORDINATES = 40
CLEARANCE_EVENTS = ("contact", "lift_off", "stick", "slip")
CLEARANCE_MODES = {0: "free", 1: "sliding (positive slip)", -1: "sliding (negative slip)", 2: "rolling"}
_SPEED_KIND = {ConstantSpeed: "constant", LinearRamp: "ramp", HillRunUp: "hill"}


@dataclass(frozen=True)
class MachineLinearization(Linearization):
    """Linearized co-rotating-frame motion about an equilibrium (constant speed).

    The fields of :class:`rotorlab.models.Linearization`, here for ``q = (z_rotating, psi)``:
    ``A`` (shape (2 n, 2 n)) the first-order Jacobian ``dy'/dy`` of ``[q, q']``; ``M``, ``C``,
    ``G``, ``K`` (shape (n, n)) with ``M q'' + (C + G) q' + K q = 0`` (mass, damping as the
    symmetric part of the velocity matrix, gyroscopic as its skew part, stiffness);
    ``spin_speed`` Omega (rad/s); ``residual`` the rotating-frame dy/dt at the state (zero at an
    equilibrium). Adds :attr:`is_stable`.
    """

    @property
    def is_stable(self) -> bool:
        """All eigenvalues in the open left half-plane, up to round-off (zero modes excluded)."""
        lam = self.eigenvalues
        scale = max(np.abs(lam).max(), 1.0)
        return bool(np.all(lam.real < 1e-9 * scale))


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
class Machine:
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
        nn = self.structure.n_nodes
        for what, items in (("races", self.races), ("unbalances", self.unbalances),
                            ("clearances", self.clearances)):
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
    def layout(self) -> _cg.Layout:
        """Sizes and offsets of the states and parameters (a machine_codegen Layout)."""
        if "layout" not in self._cache:
            d = self.drive
            self._cache["layout"] = _cg.Layout(
                n_z=self.n_coordinates, races=tuple(len(r.balls) for r in self.races),
                n_unbalance=len(self.unbalances),
                drive=d.kind if self.is_motor else "profile",
                speed_kind="constant" if self.is_motor else _SPEED_KIND[type(d)],
                n_table=d.n_table if self.is_motor else 0,
                gyroscopic=bool(np.any(self.reduced["G"])), energy=self.energy_states,
                clearance=self.clearances[0].kind if self.clearances else "",
                friction=self.has_friction,
                tilt=self._tilt_numbers())
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
            mod = _cg.kernel_module(self.layout)
            if self.clearances:
                self._cache["kernels"] = Kernels(
                    rhs=mod.rhs, n_state=self.n_state, n_discrete=self.layout.n_discrete,
                    events=mod.events, reset=mod.reset, vectorises=True,
                    event_specs=tuple(EventSpec(n, -1, "reset") for n in CLEARANCE_EVENTS))
            elif self.has_friction:
                specs = []
                for name in self._ball_labels:
                    specs += [EventSpec(f"stick_{name}", -1, "reset"), EventSpec(f"slip_{name}", -1, "reset")]
                self._cache["kernels"] = Kernels(
                    rhs=mod.rhs, n_state=self.n_state, n_discrete=self.layout.n_discrete,
                    events=mod.events, reset=mod.reset, vectorises=True, event_specs=tuple(specs))
            else:
                self._cache["kernels"] = Kernels(rhs=mod.rhs, n_state=self.n_state, vectorises=True)
        return self._cache["kernels"]

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

        The identity, or the kept mass-normalised modes.

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
        self._cache["basis"] = phi
        return phi

    @property
    def reduced(self) -> dict[str, np.ndarray]:
        """``M, C, G, K`` of the structure in its coordinates (``Phi^T A Phi``)."""
        if "reduced" not in self._cache:
            phi, s = self.basis, self.structure
            self._cache["reduced"] = {n: phi.T @ getattr(s, n) @ phi for n in ("M", "C", "G", "K")}
        return self._cache["reduced"]

    def station_matrix(self, node: int, axial_offset: float = 0.0) -> np.ndarray:
        """B, shape (2, n_z): the lateral displacement ``(x + a phi_x, y + a phi_y)`` of a station."""
        e = np.zeros((2, self.structure.n_dof))
        e[0, 4 * node] = 1.0
        e[1, 4 * node + 1] = 1.0
        e[0, 4 * node + 2] = axial_offset
        e[1, 4 * node + 3] = axial_offset
        return e @ self.basis

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
        return self._stations + extra

    @property
    def _stations(self) -> list[np.ndarray]:
        return [self.station_matrix(r.node, r.axial_offset) for r in self.races] + \
               [self.station_matrix(u.node, u.axial_offset) for u in self.unbalances] + \
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
        """f_g in the structure coordinates: structure and ball weights (N)."""
        gx, gy = self.lateral_gravity
        s = self.structure
        eg = np.zeros(s.n_dof)
        eg[0::4], eg[1::4] = gx, gy
        f = self.basis.T @ (s.M @ eg)
        for r, B in zip(self.races, self._stations):
            f += sum(b.mass for b in r.balls) * (B.T @ np.array([gx, gy]))
        return f

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
        else:
            p[o["speed"]:o["speed"] + 6] = d.to_array()
        p[o["gravity"]:o["gravity"] + 2] = self.lateral_gravity
        if lay.friction:  # friction arm of each ball: coulomb l + rolling (m)
            p[o["friction"]:o["friction"] + lay.n_balls] = [
                b.coulomb * r.radius + b.rolling for r in self.races for b in r.balls]
        m, l, J, c, _ = self._ball_arrays
        for b in range(lay.n_balls):
            p[o["balls"] + 4 * b: o["balls"] + 4 * b + 4] = (m[b], m[b] * l[b], J[b], c[b])
        for u, un in enumerate(self.unbalances):
            p[o["unbalances"] + 3 * u: o["unbalances"] + 3 * u + 3] = (
                un.mass_eccentricity, math.cos(un.phase), math.sin(un.phase))
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
            import scipy.linalg as sla

            lam = sla.eigvals(red["K"], self._m0())
            p[o["clearance"] + 10] = math.sqrt(max(float(np.max(np.abs(lam))), 1e-300))
        self._cache["p"] = p
        return p.copy()

    # ------------------------------------------------------------------ variants
    def with_drive(self, drive) -> Machine:
        """Return a copy with another drive."""
        return replace(self, drive=drive)

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

    def initial_state(self, ball_angles=None, *, ball_rates=None, spin_speed: float | None = None,
                      z=None, dz=None, t0: float = 0.0, housing=None) -> np.ndarray:
        """Build a fixed-frame initial state.

        Parameters
        ----------
        ball_angles : array_like, shape (n_b,), optional
            Angles of the balls from the rotor's +x axis (rad), races in order; default equally
            spaced in each race (balanced balls).
        ball_rates : array_like, shape (n_b,), optional
            Rates relative to the rotor (rad/s); default 0 (co-rotating).
        spin_speed : float, optional
            Initial Omega of a motor-driven machine (rad/s), default 0; ignored otherwise.
        z, dz : array_like, shape (n_z,), optional
            Structure coordinates and rates; default at rest at the origin (at the rest position
            under gravity when the clearance is centred there, ``center = "static"``).
        t0 : float
            Initial time (s).
        housing : array_like, shape (4,), optional
            ``(x_h, y_h, vx_h, vy_h)`` of a moving housing (m, m/s); default at rest at 0.

        Returns
        -------
        ndarray, shape (n_state,)
        """
        lay = self.layout
        y = np.zeros(lay.n_state)
        if self.is_motor:
            th, om = 0.0, 0.0 if spin_speed is None else float(spin_speed)
            y[lay.i_theta], y[lay.i_theta + 1] = th, om
        else:
            th, om = self.spin(t0)
        if ball_angles is None:
            psi = np.concatenate([2 * np.pi * np.arange(len(r.balls)) / len(r.balls)
                                  for r in self.races]) if self.races else np.zeros(0)
        else:
            psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        if psi.size != lay.n_balls:
            raise ValueError(f"ball_angles must have {lay.n_balls} entries, got {psi.size}")
        rates = np.zeros(lay.n_balls) if ball_rates is None else np.asarray(ball_rates, float).reshape(-1)
        if rates.size != lay.n_balls:
            raise ValueError(f"ball_rates must have {lay.n_balls} entries, got {rates.size}")
        nz = lay.n_z
        if z is None and self.clearances and self.clearances[0].center == "static":
            # the stator is centred on the rest position under gravity: start there
            zs, hs = self._rest_position()
            y[:nz] = zs
            if self.clearances[0].kind == "housing":
                y[lay.i_clearance:lay.i_clearance + 2] = hs
        if z is not None:
            y[:nz] = np.asarray(z, dtype=float).reshape(nz)
        if dz is not None:
            y[nz:2 * nz] = np.asarray(dz, dtype=float).reshape(nz)
        y[lay.i_phi:lay.i_phi + lay.n_balls] = th + psi
        y[lay.i_w:lay.i_w + lay.n_balls] = om + rates
        if housing is not None:
            if not self.clearances or self.clearances[0].kind != "housing":
                raise ValueError("initial_state: housing given but the machine has no moving housing")
            y[lay.i_clearance:lay.i_clearance + 4] = np.asarray(housing, dtype=float).reshape(4)
        if self.clearances:
            self._clearance_initial(y, om)
        if self.has_friction:
            y = self.initial_modes(t0, y)
        return y

    def initial_modes(self, t: float, y) -> np.ndarray:
        """Return a copy of state ``y`` with stick/slip modes consistent with it.

        As :meth:`rotorlab.models.JeffcottBalls.initial_modes`: a ball with nonzero relative
        speed slips in that direction; at zero relative speed it sticks if the race can hold it
        (stuck balls first), otherwise it slips with the sign of its driving torque.
        """
        y = np.array(y, dtype=float)
        if not self.has_friction:
            return y
        lay = self.layout
        nb, im = lay.n_balls, lay.i_modes
        om = self.spin(float(t), y)[1]
        rel = y[lay.i_w:lay.i_w + nb] - om
        arm = self.to_array()[lay.offsets["friction"]:lay.offsets["friction"] + nb]
        y[im:im + nb] = np.where(rel > 0, 1.0, np.where(rel < 0, -1.0, 0.0))
        y[im:im + nb][arm == 0.0] = 1.0
        terms = _cg.kernel_module(lay).terms
        buf = np.zeros(max(2 * nb, 1))
        for _ in range(nb + 1):
            terms(float(t), y, self.to_array(), -1, buf)
            tq, bound = buf[0::2], buf[1::2]
            bad = [i for i in np.flatnonzero(y[im:im + nb] == 0.0) if abs(tq[i]) > bound[i]]
            if not bad:
                break
            worst = max(bad, key=lambda i: abs(tq[i]) - bound[i])
            y[im + worst] = 1.0 if tq[worst] <= 0 else -1.0
        return y

    def _clearance_initial(self, y: np.ndarray, om: float) -> None:
        """Contact mode of an initial state: free inside the clearance; pressed into an elastic
        stator, sliding along its slip; beyond a rigid one, an error."""
        c = self.clearances[0]
        w = self.gap_vector(y)
        rad = math.hypot(w[0], w[1])
        if rad <= c.gap:
            return
        if c.kind != "elastic":
            raise ValueError(f"Machine.initial_state: the gap vector {w.tolist()!r} m lies outside the "
                             f"{c.kind} stator (clearance {c.gap:g} m)")
        u = self.gap_matrix(c) @ y[self.n_coordinates:2 * self.n_coordinates]
        if c.kind == "housing":
            u = u - y[self.layout.i_clearance + 2:self.layout.i_clearance + 4]
        slip = (-w[1] * u[0] + w[0] * u[1]) / rad + c.rotor_radius * om
        y[-1] = 1.0 if slip >= 0.0 else -1.0

    # ------------------------------------------------------------------ physics
    def mass_matrix(self, y) -> np.ndarray:
        """Return the full mass matrix over ``(z, phi_b, (theta))`` at state y (symmetric)."""
        lay = self.layout
        y = np.asarray(y, dtype=float)
        nz, nb = lay.n_z, lay.n_balls
        n = nz + nb + (1 if self.is_motor else 0)
        Mf = np.zeros((n, n))
        Mf[:nz, :nz] = self._m0()
        m, l, J, c, race = self._ball_arrays
        st = self._stations
        phi = y[lay.i_phi:lay.i_phi + nb]
        for b in range(nb):
            t = np.array([-math.sin(phi[b]), math.cos(phi[b])])
            col = m[b] * l[b] * (st[race[b]].T @ t)
            Mf[:nz, nz + b] = col
            Mf[nz + b, :nz] = col
            Mf[nz + b, nz + b] = J[b]
        if lay.tilt:  # rigid ball kinematics on a tilting race (module docstring)
            z = y[:nz]
            for b in range(nb):
                T = self.tilt_matrix(self.races[race[b]].node)
                ph = T @ z
                tau = T.T @ np.array([math.cos(phi[b]), math.sin(phi[b])])
                Mf[:nz, :nz] += m[b] * l[b] ** 2 * np.outer(tau, tau)
                col = 0.5 * J[b] * (T.T @ np.array([ph[1], -ph[0]]))
                Mf[:nz, nz + b] += col
                Mf[nz + b, :nz] += col
        if self.is_motor:
            th = y[lay.i_theta]
            w = np.zeros(nz)
            for u, un in enumerate(self.unbalances):
                a = th + un.phase
                w += un.mass_eccentricity * (st[len(self.races) + u].T @ np.array([-math.sin(a), math.cos(a)]))
            Mf[:nz, -1] = w
            Mf[-1, :nz] = w
            Mf[-1, -1] = self.drive.polar_inertia
        return Mf

    def energy(self, y, t: float = 0.0) -> float:
        """Mechanical energy ``T + V`` (J) at fixed-frame state y (see the module docstring)."""
        lay = self.layout
        y = np.asarray(y, dtype=float)
        nz, nb = lay.n_z, lay.n_balls
        z, v = y[:nz], y[nz:2 * nz]
        phi, w = y[lay.i_phi:lay.i_phi + nb], y[lay.i_w:lay.i_w + nb]
        th, om = self.spin(t, y)
        qd = np.concatenate([v, w] + ([[om]] if self.is_motor else []))
        Mf = self.mass_matrix(y)
        kin = 0.5 * qd @ Mf @ qd
        st = self._stations
        if not self.is_motor:  # the unbalance-structure coupling with the prescribed spin
            for u, un in enumerate(self.unbalances):
                a = th + un.phase
                kin += un.mass_eccentricity * om * (np.array([-math.sin(a), math.cos(a)]) @ (st[len(self.races) + u] @ v))
        K = self.reduced["K"]
        gx, gy = self.lateral_gravity
        pot = 0.5 * z @ (0.5 * (K + K.T)) @ z - self._weights() @ z
        m, l, J, c, race = self._ball_arrays
        pot -= float(np.sum(m * l * (gx * np.cos(phi) + gy * np.sin(phi))))
        for un in self.unbalances:
            a = th + un.phase
            pot -= un.mass_eccentricity * (gx * math.cos(a) + gy * math.sin(a))
        return float(kin + pot + self._clearance_energy(y))

    def _clearance_energy(self, y: np.ndarray) -> float:
        """Energy stored by the clearance: a massless elastic stator's ``k_s p^2 / 2``, a moving
        housing's ``m_s |v_h|^2 / 2 + k_s |x_h|^2 / 2 - m_s g . x_h`` (J)."""
        if not self.clearances:
            return 0.0
        c, lay = self.clearances[0], self.layout
        if c.kind == "rigid":
            return 0.0
        ks = c.stator.stiffness
        if c.kind == "elastic":
            w = self.gap_vector(y)
            pen = max(math.hypot(w[0], w[1]) - c.gap, 0.0)
            return 0.5 * ks * pen * pen
        xh, vh = y[lay.i_clearance:lay.i_clearance + 2], y[lay.i_clearance + 2:lay.i_clearance + 4]
        gx, gy = self.lateral_gravity
        return float(0.5 * c.stator.mass * vh @ vh + 0.5 * ks * xh @ xh
                     - c.stator.mass * (gx * xh[0] + gy * xh[1]))

    def gap_vector(self, y) -> np.ndarray:
        """Return the clearance's gap vector ``w`` (m), shape (..., 2), at states y."""
        if not self.clearances:
            raise ValueError("gap_vector needs a Machine with a clearance")
        y = np.asarray(y, dtype=float)
        w = y[..., :self.n_coordinates] @ self.gap_matrix(self.clearances[0]).T
        if self.clearances[0].kind == "housing":
            i = self.layout.i_clearance
            w = w - y[..., i:i + 2]
        return w - np.asarray(self.clearance_center)

    @property
    def clearance_center(self) -> tuple[float, float]:
        """Centre of the stator's circle (m): the clearance's ``center``, or with ``"static"`` the
        gap vector of the machine at rest under gravity (``B K^-1 f_g`` minus a moving housing's
        own sag ``m_s g / k_s``)."""
        c = self.clearances[0]
        if c.center != "static":
            return c.center
        if "center" not in self._cache:
            zs, hs = self._rest_position()
            w = self.gap_matrix(c) @ zs - hs
            self._cache["center"] = (float(w[0]), float(w[1]))
        return self._cache["center"]

    def _rest_position(self) -> tuple[np.ndarray, np.ndarray]:
        """Structure coordinates ``K^-1 f_g`` and a moving housing's ``m_s g / k_s`` at rest under
        gravity (balls at rest, lumped on their races)."""
        gx, gy = self.lateral_gravity
        try:
            zs = np.linalg.solve(self.reduced["K"], self._weights())
        except np.linalg.LinAlgError:
            raise ValueError('Clearance.center = "static" needs a structure held by its supports '
                             "(its stiffness matrix is singular)") from None
        c = self.clearances[0] if self.clearances else None
        hs = np.zeros(2)
        if c is not None and c.kind == "housing":
            hs = c.stator.mass * np.array([gx, gy]) / c.stator.stiffness
        return zs, hs

    @property
    def rub_parameters(self) -> dict[str, tuple[int, str]]:
        """Parameters a rub map may vary: name -> (index in :meth:`to_array`, unit).

        ``clearance`` (m), ``restitution``, ``friction``, ``spin_speed`` (rad/s, constant
        prescribed speed), ``unbalance`` (kg m, the first unbalance) and ``stator_stiffness``
        (N/m, an elastic stator or housing); empty without a clearance.
        """
        if not self.clearances:
            return {}
        o = self.layout.offsets
        kc = o["clearance"]
        out = {"clearance": (kc, "m"), "restitution": (kc + 1, "1"), "friction": (kc + 2, "1")}
        if isinstance(self.drive, ConstantSpeed):
            out["spin_speed"] = (o["speed"] + 1, "rad/s")
        if self.unbalances:
            out["unbalance"] = (o["unbalances"], "kg m")
        if self.clearances[0].kind != "rigid":
            out["stator_stiffness"] = (kc + 5, "N/m")
        return out

    def contact_samples(self, ts, ys, params=None):
        """The clearance's contact at saved samples (:class:`rotorlab.contact.ContactSamples`);
        the normal force from the compiled contact law (the generated ``contact_terms``)."""
        from rotorlab._kernels.speed import profile
        from rotorlab.contact._regimes import ContactSamples

        if not self.clearances:
            raise ValueError("contact_samples needs a Machine with a clearance")
        ys = np.atleast_2d(np.asarray(ys, dtype=float))
        ts = np.broadcast_to(np.asarray(ts, dtype=float), ys.shape[:1])
        p = self.to_array() if params is None else np.ascontiguousarray(params, dtype=float)
        lay, nz = self.layout, self.n_coordinates
        mod = _cg.kernel_module(lay)
        dw = ys[:, nz:2 * nz] @ self.gap_matrix(self.clearances[0]).T
        if self.clearances[0].kind == "housing":
            dw = dw - ys[:, lay.i_clearance + 2:lay.i_clearance + 4]
        mode = ys[:, -1]
        force = np.array([mod.contact_terms(float(t), np.ascontiguousarray(row), p, float(row[-1]))[0]
                          if row[-1] != 0.0 else 0.0 for t, row in zip(ts, ys)])
        if self.is_motor:
            spin = ys[:, lay.i_theta + 1]
        else:
            spin = np.array([profile(float(t), p, lay.offsets["speed"])[1] for t in ts])
        return ContactSamples(self.gap_vector(ys), dw, mode, ys[:, -3], ys[:, -2], force, spin)

    def gap_state(self, position=(0.0, 0.0), velocity=(0.0, 0.0)) -> np.ndarray:
        """Initial state with the given gap vector ``w`` (m) and rate ``w'`` (m/s): the structure
        in the mass-weighted shortest shape that has them, balls as in :meth:`initial_state`."""
        if not self.clearances:
            raise ValueError("gap_state needs a Machine with a clearance")
        B = self.gap_matrix(self.clearances[0])
        H = np.linalg.inv(self._m0())
        shape = H @ B.T @ np.linalg.inv(B @ H @ B.T)
        centre = np.asarray(self.clearance_center)
        return self.initial_state(z=shape @ (np.asarray(position, float) + centre),
                                  dz=shape @ np.asarray(velocity, float))

    def whirl_state(self, radius: float, whirl_speed: float) -> np.ndarray:
        """Initial state with the gap vector on a circular whirl: ``w = (radius, 0)``, ``w' =
        (0, whirl_speed radius)`` (see :meth:`gap_state`)."""
        return self.gap_state((radius, 0.0), (0.0, whirl_speed * radius))

    def equivalent_rub_rotor(self):
        """The Jeffcott rotor this machine is at its clearance (:class:`rotorlab.contact.RubRotor`).

        With ``S = H B^T (B H B^T)^-1`` the mass-weighted shortest shape of a unit gap vector
        (``H = M0^-1``): mass ``(B H B^T)^-1``, stiffness ``S^T K S`` and damping ``S^T C S``
        (x entries), eccentricity ``sum U / m``. Exact for one rigid body whose tilt does not
        couple with its translation (the Jeffcott rotor as a machine); a Rayleigh estimate
        otherwise (the closed forms beside a general machine are then approximate).
        """
        from rotorlab.contact import RubRotor

        if not self.clearances:
            raise ValueError("equivalent_rub_rotor needs a Machine with a clearance")
        c = self.clearances[0]
        if c.rotor_radius <= 0.0:
            raise ValueError("the closed forms need the rotor's radius at the contact: set "
                             "Clearance.rotor_radius (> 0 m)")
        B = self.gap_matrix(c)
        H = np.linalg.inv(self._m0())
        Lc = B @ H @ B.T
        S = H @ B.T @ np.linalg.inv(Lc)
        red = self.reduced
        m = 1.0 / Lc[0, 0]
        k = float((S.T @ red["K"] @ S)[0, 0])
        damp = float((S.T @ red["C"] @ S)[0, 0])
        ecc = sum(u.mass_eccentricity for u in self.unbalances) / m
        st = c.stator
        kw = {} if st == "rigid" else {"stator_stiffness": st.stiffness, "stator_damping": st.damping,
                                        "stator_mass": st.mass}
        return RubRotor(mass=m, stiffness=k, clearance=c.gap, damping=max(damp, 0.0), eccentricity=ecc,
                        friction=c.friction, rotor_radius=c.rotor_radius, **kw)

    def impossible_states(self, ys, y_final, t_final, params) -> list[str]:
        """Sanity monitor (kernel contract item 6): runs where the rotor went through a rigid
        stator (or a moving housing, which it strikes rigidly).

        Beyond ``delta (1 + 1e-6)`` a rebound lower than the integrator resolves was missed
        (raise the clearance's ``rest_speed``): a failed run. The clearance ``delta`` is read from
        ``params`` (one row per run or one for all).
        """
        y_final = np.asarray(y_final, dtype=float)
        n = y_final.shape[0]
        if not self.clearances or self.clearances[0].kind == "elastic":
            return [""] * n
        params = np.atleast_2d(params)
        delta = np.broadcast_to(params[:, self.layout.offsets["clearance"]], (n,))
        ys = np.asarray(ys, dtype=float)
        rad = np.hypot(*np.moveaxis(self.gap_vector(ys), -1, 0)) if ys.size else np.zeros((n, 0))
        r_final = np.hypot(*self.gap_vector(y_final).T)
        out = []
        for i in range(n):
            r = np.concatenate([rad[i][np.isfinite(rad[i])], [r_final[i]]])
            worst = float(r.max())
            if worst <= delta[i] * (1.0 + 1e-6):
                out.append("")
            else:
                out.append(f"the rotor passed through the stator: gap vector {worst:.6g} m, "
                           f"{worst - delta[i]:.3g} m beyond the clearance {delta[i]:g} m (by t = "
                           f"{t_final[i]:.6g} s); a rebound lower than the tolerances resolve was "
                           "missed: raise the clearance's rest_speed")
        return out

    def energy_balance(self, ts, ys) -> np.ndarray:
        """Return ``work - (E - E_0) - dissipated`` along a trajectory (J); needs energy states.

        Parameters
        ----------
        ts : array_like, shape (N,)
        ys : array_like, shape (N, n_state)
            Saved states of one trajectory with ``energy_states=True``; the work and dissipation
            states start at zero at ``ts[0]`` (as :meth:`initial_state` sets them).
        """
        if not self.energy_states:
            raise ValueError("energy_balance needs a Machine with energy_states=True")
        ie = self.layout.i_energy
        ys = np.asarray(ys, dtype=float)
        e = np.array([self.energy(y, t) for t, y in zip(np.asarray(ts, float), ys)])
        return ys[:, ie] - (e - e[0]) - ys[:, ie + 1]

    def displacements(self, y) -> np.ndarray:
        """Return the node DOFs ``Phi z`` (shape (..., n_dof)) of fixed-frame states y."""
        y = np.asarray(y, dtype=float)
        return y[..., :self.n_coordinates] @ self.basis.T

    def station_amplitudes(self, y) -> np.ndarray:
        """Return ``sqrt(x^2 + y^2)`` of every node (m) at states y (shape (..., n_nodes))."""
        q = self.displacements(y)
        return np.hypot(q[..., 0::4], q[..., 1::4])

    # ------------------------------------------------------------------ co-rotating frame
    @property
    def has_rotating_frame(self) -> bool:
        """True where steady motions are equilibria of the co-rotating frame.

        Needs an isotropic structure, no lateral gravity and a constant prescribed speed.
        """
        return (self.structure.is_isotropic and not self.is_motor and not self.has_friction
                and isinstance(self.drive, ConstantSpeed) and self.lateral_gravity == (0.0, 0.0))

    def why_no_rotating_frame(self) -> str | None:
        """The reason the co-rotating frame has no equilibria, or None if it has."""
        if self.has_friction:
            return ("the balls have Coulomb or rolling friction (stick-slip): steady motions are "
                    "not equilibria of a smooth system; simulate instead")
        if not self.structure.is_isotropic:
            return ("the structure is anisotropic (its supports differ in x and y): the balls "
                    "and the rotor never reach a steady motion; simulate instead")
        if self.lateral_gravity != (0.0, 0.0):
            return ("gravity acts across the axis: the balls are pulled down once per "
                    "revolution, so there is no steady motion; simulate instead")
        if self.is_motor or not isinstance(self.drive, ConstantSpeed):
            return "the spin speed is not constant (steady motions need a ConstantSpeed drive)"
        return None

    def _require_rotating(self) -> float:
        why = self.why_no_rotating_frame()
        if why is not None:
            raise ValueError(f"no co-rotating equilibria: {why}")
        return float(self.drive.speed)

    def _rot_pairs(self, a: np.ndarray, om: float) -> np.ndarray:
        """Apply ``Omega J`` (J = [[0, -1], [1, 0]]) to each (even, odd) coordinate pair."""
        out = np.empty_like(a)
        out[..., 0::2] = -om * a[..., 1::2]
        out[..., 1::2] = om * a[..., 0::2]
        return out

    def rotating_to_fixed(self, yr) -> np.ndarray:
        """Convert a co-rotating state ``[z_r, z_r', psi, psi']`` to the fixed frame at t = 0."""
        om = self._require_rotating()
        lay = self.layout
        nz, nb = lay.n_z, lay.n_balls
        yr = np.asarray(yr, dtype=float)
        y = np.zeros(lay.n_state)
        y[:nz] = yr[:nz]
        y[nz:2 * nz] = yr[nz:2 * nz] + self._rot_pairs(yr[:nz], om)
        y[lay.i_phi:lay.i_phi + nb] = yr[2 * nz:2 * nz + nb]
        y[lay.i_w:lay.i_w + nb] = yr[2 * nz + nb:2 * nz + 2 * nb] + om
        return y

    def rotating_rhs(self, yr) -> np.ndarray:
        """Return d/dt of a co-rotating state ``[z_r, z_r', psi, psi']`` (autonomous).

        Evaluated through the compiled fixed-frame kernel at t = 0 (theta = 0), where the frames
        coincide: ``u'' = x'' - 2 Omega J u' + Omega^2 u``, ``psi'' = phi''``.
        """
        om = self._require_rotating()
        lay = self.layout
        nz, nb = lay.n_z, lay.n_balls
        yr = np.asarray(yr, dtype=float)
        f = self.rhs(0.0, self.rotating_to_fixed(yr))
        out = np.empty(2 * nz + 2 * nb)
        out[:nz] = yr[nz:2 * nz]
        out[nz:2 * nz] = f[nz:2 * nz] - 2.0 * self._rot_pairs(yr[nz:2 * nz], om) + om * om * yr[:nz]
        out[2 * nz:2 * nz + nb] = yr[2 * nz + nb:2 * nz + 2 * nb]
        out[2 * nz + nb:] = f[lay.i_w:lay.i_w + nb]
        return out

    def linearize(self, yr) -> MachineLinearization:
        """Linearize the co-rotating equations about ``yr`` (velocities taken as given).

        The Jacobian is a fourth-order central difference of :meth:`rotating_rhs` (relative
        accuracy about 1e-10 on the scale of the entries).
        """
        om = self._require_rotating()
        yr = np.asarray(yr, dtype=float)
        n = yr.size
        A = np.empty((n, n))
        for j in range(n):
            h = self._fd_step(j, om)
            e = np.zeros(n)
            e[j] = h
            f1 = self.rotating_rhs(yr + e) - self.rotating_rhs(yr - e)
            f2 = self.rotating_rhs(yr + 2 * e) - self.rotating_rhs(yr - 2 * e)
            A[:, j] = (8.0 * f1 - f2) / (12.0 * h)
        half = n // 2
        Mf = self.mass_matrix(self.rotating_to_fixed(yr))[: half, : half]
        K = -Mf @ A[half:, :half]
        D = -Mf @ A[half:, half:]
        return MachineLinearization(A=A, M=Mf, C=0.5 * (D + D.T), G=0.5 * (D - D.T), K=K,
                                    spin_speed=om, residual=self.rotating_rhs(yr))

    def _fd_step(self, j: int, om: float) -> float:
        """Finite-difference step of co-rotating state entry j (m, m/s, rad or rad/s)."""
        nz = self.n_coordinates
        if j >= 2 * nz:
            return 1e-3  # ball angles (rad) and rates (rad/s)
        u = sum(x.mass_eccentricity for x in self.unbalances) + sum(r.capacity for r in self.races)
        zs = max(u / max(self.structure.total_mass, 1e-300), 1e-12)
        return 1e-3 * zs * (1.0 if j < nz else max(abs(om), 1.0))

    def balance_residual(self, ball_angles) -> np.ndarray:
        """Return the generalised force of the locked balls and unbalances per Omega^2 (kg m).

        ``sum_b m_b l_b B_r^T e_b + sum_u U B_u^T e_u`` at theta = 0: zero in a balanced state.
        """
        psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        m, l, J, c, race = self._ball_arrays
        st = self._stations
        f = np.zeros(self.n_coordinates)
        for b in range(psi.size):
            f += m[b] * l[b] * (st[race[b]].T @ np.array([math.cos(psi[b]), math.sin(psi[b])]))
        for u, un in enumerate(self.unbalances):
            f += un.mass_eccentricity * (st[len(self.races) + u].T @ np.array([math.cos(un.phase), math.sin(un.phase)]))
        return f

    def balanced_angles(self, guess=None, *, starts: int = 16, seed: int = 0) -> np.ndarray | None:
        """Return ball angles that cancel the unbalance exactly, or None if the balls cannot.

        Solves ``balance_residual(psi) = 0`` (least squares from ``guess`` and ``starts`` random
        starts; accepted below 1e-10 of the unbalance scale).
        """
        from scipy.optimize import least_squares

        nb = self.n_balls
        if nb == 0:
            return None
        scale = max(sum(u.mass_eccentricity for u in self.unbalances), 1e-300)
        rng = np.random.default_rng(seed)
        tries = ([np.asarray(guess, float)] if guess is not None else []) + \
            [rng.uniform(0, 2 * np.pi, nb) for _ in range(starts)]
        for x0 in tries:
            res = least_squares(lambda a: self.balance_residual(a) / scale, x0, xtol=1e-15,
                                ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(res.fun)) < 1e-10:
                return np.mod(res.x, 2 * np.pi)
        return None

    def balanced_state(self, ball_angles=None) -> np.ndarray:
        """Return the co-rotating state of the balanced machine: z = 0, balls at rest at their angles.

        Raises
        ------
        ValueError
            If the balls cannot cancel the unbalance or there is no co-rotating frame.
        """
        self._require_rotating()
        psi = self.balanced_angles() if ball_angles is None else np.asarray(ball_angles, float)
        if psi is None:
            raise ValueError("the balls cannot cancel the unbalance (capacity too small or "
                             "races in the wrong planes)")
        nz, nb = self.n_coordinates, self.n_balls
        y = np.zeros(2 * nz + 2 * nb)
        y[2 * nz:2 * nz + nb] = psi
        return y

    def steady_state(self, ball_angles=None, *, starts: int = 16, seed: int = 0,
                     near=None) -> np.ndarray | None:
        """Return a co-rotating equilibrium (a steady motion), balanced or not, or None.

        Starts from the balanced state when the balls can cancel the unbalance, else from the
        ball angles that cancel most of it (least squares) with the structure on its locked
        response, and solves ``rotating_rhs(y) = 0`` for the positions (velocities zero) with
        SciPy's hybrid Powell method (Levenberg-Marquardt where it stalls), from each of the
        distinct best partial balances (mirror images); ``near`` (a co-rotating state, e.g. the
        steady motion at a neighbouring speed) is tried first as the start.
        """
        from scipy.optimize import least_squares, root

        om = self._require_rotating()
        nz, nb = self.n_coordinates, self.n_balls
        psi = self.balanced_angles(ball_angles, starts=starts, seed=seed)
        if psi is not None:
            return self.balanced_state(psi)
        scale = max(sum(u.mass_eccentricity for u in self.unbalances), 1e-300)
        rng = np.random.default_rng(seed)
        guesses = ([np.asarray(ball_angles, float)] if ball_angles is not None else []) + \
            [rng.uniform(0, 2 * np.pi, nb) for _ in range(starts)]
        fits = sorted((least_squares(lambda a: self.balance_residual(a) / scale, g) for g in guesses),
                      key=lambda r: r.cost) if nb else []
        # the best partial balances (distinct ball layouts of the least cost; mirror images of
        # each other): the equilibrium solver may converge from one and not from the other
        layouts = [np.zeros(0)] if not fits else []
        for fit in fits:
            if fit.cost > fits[0].cost + 1e-10 * max(fits[0].cost, 1e-300) + 1e-20:
                break
            if all(np.max(np.abs(np.angle(np.exp(1j * (fit.x - q))))) > 1e-6 for q in layouts):
                layouts.append(fit.x)
        K0 = self.reduced["K"] - om * om * self._m0()

        def residual(x):
            y = np.zeros(2 * nz + 2 * nb)
            y[:nz], y[2 * nz:2 * nz + nb] = x[:nz], x[nz:]
            f = self.rotating_rhs(y)
            return np.concatenate([f[nz:2 * nz], f[2 * nz + nb:]])

        starts_x = [np.concatenate([np.linalg.lstsq(K0, om * om * self.balance_residual(q), rcond=None)[0], q])
                    for q in layouts[:4]]
        if near is not None:
            near = np.asarray(near, dtype=float)
            starts_x.insert(0, np.concatenate([near[:nz], near[2 * nz:2 * nz + nb]]))
        zs = max(scale / max(self.structure.total_mass, 1e-300), 1e-300)
        for x0 in starts_x:
            sol = root(residual, x0, method="hybr", options={"xtol": 1e-13})
            if np.max(np.abs(residual(sol.x))) > 1e-9 * zs * max(1.0, om * om):
                sol = root(residual, x0, method="lm", options={"xtol": 1e-15, "ftol": 1e-15})
            if np.max(np.abs(residual(sol.x))) <= 1e-9 * zs * max(1.0, om * om):
                y = np.zeros(2 * nz + 2 * nb)
                y[:nz], y[2 * nz:2 * nz + nb] = sol.x[:nz], sol.x[nz:]
                return y
        return None

    def reduction_change(self, spin_speed: float) -> float:
        """Relative change of the locked-ball unbalance response when ``n_modes`` doubles.

        Returns ``max |q_2n - q_n| / max |q_2n|`` over the node translations of the steady
        response to the unbalances (balls at rest in their races, treated as point masses on
        the structure) at ``spin_speed``; 0 for an unreduced structure.
        """
        if self.n_modes is None:
            return 0.0
        big = replace(self, n_modes=min(2 * self.n_modes, self.structure.n_dof))
        a = self._locked_response(spin_speed)
        b = big._locked_response(spin_speed)
        return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))

    def _locked_response(self, om: float) -> np.ndarray:
        red = self.reduced
        D = red["K"] + 1j * om * (red["C"] + om * red["G"]) - om * om * self._m0()
        f = np.zeros(self.n_coordinates, dtype=complex)
        st = self._stations
        for u, un in enumerate(self.unbalances):
            f += un.mass_eccentricity * om * om * np.exp(1j * un.phase) * (st[len(self.races) + u].T @ np.array([1.0, -1j]))
        q = self.basis @ np.linalg.solve(D, f)
        return np.concatenate([q[0::4], q[1::4]])
