"""Sizes and offsets of a machine's generated kernel (:class:`Layout`), and the small pieces
the generators share (:mod:`rotorlab._kernels.machine_codegen` and its parts
:mod:`~rotorlab._kernels.machine_tilt`, :mod:`~rotorlab._kernels.machine_friction`,
:mod:`~rotorlab._kernels.machine_contact`).

Packed parameters ``p`` (float64; offsets from :class:`Layout`, after ``param_base`` entries
the kernel does not read)
---------------------------------------------------------------------------------------------
=================  ===========================================================================
``speed``          6: the prescribed profile block (:mod:`rotorlab._kernels.speed`); zeros with a
                   motor
``motor``          3 + 2 n_t: polar inertia J (kg m^2), stall torque T_s (N m), no-load speed
                   w_0 (rad/s) [linear]; then n_t speeds (rad/s) and n_t torques (N m) [table]
``balls``          4 per ball (races in order): m (kg), m l (kg m), J = m l^2 + J_c (kg m^2),
                   c (N m s/rad)
``part<k>``        the block of each part fixed to the rotor (``rotor``: an unbalance, 3 per
                   point unbalance: U = m e (kg m), cos beta, sin beta), its size and contents its
                   own; ``offsets["unbalances"]`` is where the first one starts
``stations``       per station (races, then the rotor parts' (the point unbalances), then the
                   clearance's, then with ``tilt`` one per distinct race node, then the other
                   parts'): B (2 x n_z, row-major), then H B^T (n_z x 2, row-major); ``B z`` is
                   the lateral displacement of the station (a tilt station's ``B`` is its node's
                   tilt ``T``)
``L``              per ordered pair of stations (s, s'): B_s H B_s'^T (2 x 2, row-major)
``HK, HC, HG``     n_z x n_z each (row-major): H K, H C, H G; ``HG`` only when the structure is
                   gyroscopic
``Hf``             n_z: H f_g, the weight of the structure and of the balls
``C, Ka``          n_z x n_z each, only with energy states: C and the skew part of K
``clearance``      11, only with a clearance (:mod:`rotorlab._kernels.machine_contact`)
``friction``       n_b, only with ball friction: each ball's friction arm ``coulomb l + rolling``
                   (m)
``tilt``           n_b, only with ``tilt``: each ball's ``D = m l^2`` (kg m^2), its inertia
                   about its race's diameters
``part<k>``        the block of each other attachment part ``k`` (:mod:`rotorlab.models._parts`),
                   its size and contents its own: gravity's (every machine has it) is g_x, g_y
                   (m/s^2), the lateral components of gravity
=================  ===========================================================================

``H = M0^-1`` with ``M0 = M_s + sum_r m_r B_r^T B_r`` (the structure plus the ball masses carried
by the races).

States
------
``[z (n_z), z' (n_z), phi (n_b), phi' (n_b), (theta, Omega) with a motor, (W, D) with energy
states, (the parts' states), (clearance states), (n_b stick/slip modes) with ball friction]``: structure coordinates
and their rates, absolute ball angles and rates, spin angle and speed, drive work and dissipated
energy; the clearance's states are listed in :mod:`rotorlab._kernels.machine_contact`, and a
ball's mode is -1 / +1 slipping with that sign of ``phi' - Omega``, 0 stuck.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

__all__ = ["Layout", "PartPlace", "SpinLoad", "SPEED_KINDS", "DRIVE_KINDS"]

# the prescribed speed kinds, each with whether its generated profile is plain arithmetic (the
# kernel then vectorises in the lane driver); a Hill run-up needs exp, log and series with branches
SPEED_KINDS = {"constant": True, "ramp": True, "hill": False}
DRIVE_KINDS = ("profile", "linear", "table", "servo_linear", "servo_table")


class PartPlace(NamedTuple):
    """Where an attachment part's block sits: its first state, first packed parameter and first
    station (the index for :meth:`Layout.station_B`)."""

    state: int
    param: int
    station: int


class SpinLoad(NamedTuple):
    """How a part fixed to the rotor (an unbalance) couples to the spin at one of its stations:
    a unit ``theta''`` moves the station by ``coef * (tx, ty)`` (its column of the mass matrix's
    coupling block is ``coef B_s^T (tx, ty)``), and ``torque`` is the generalised force of its
    own loads on theta (gravity); each entry is an expression of generated variables."""

    station: int
    coef: str
    tx: str
    ty: str
    torque: str


@dataclass(frozen=True)
class Layout:
    """Sizes of one machine and the offsets of its packed parameters and states.

    Parameters
    ----------
    n_z : int
        Structure coordinates (4 per node, or the number of modes kept).
    races : tuple of int
        Balls per race.
    drive : {"profile", "linear", "table"}
        Prescribed spin, or a motor with a linear or tabulated characteristic.
    speed_kind : {"constant", "ramp", "hill"}
        Kind of the prescribed profile (``"constant"`` with a motor, unused).
    n_table : int
        Points of the tabulated characteristic (0 otherwise).
    gyroscopic : bool
        The structure has a nonzero G.
    energy : bool
        The state carries the drive work and the dissipated energy.
    clearance : {"", "massless", "housing"}
        The kind of the machine's clearance (rotor-stator contact), "" for none: a massless
        stator (rigid or elastic, told apart at run time by its stiffness: one compiled kernel
        for both) or a moving housing; see :mod:`rotorlab._kernels.machine_contact`.
    friction : bool
        The balls have Coulomb or rolling friction (stick-slip modes).
    tilt : tuple of int
        Empty, or (when some race can tilt) per race the number of its node among the races'
        distinct nodes: the balls follow the tilting race plane (rigid ball kinematics, see
        :mod:`rotorlab.models._machine`); adds a tilt station per distinct node and one axial
        unknown per ball to the Schur system.
    param_base : int
        Packed entries in front of the machine's own that the kernel leaves alone (a preset's
        own parameters, e.g. those of ``jeffcott_balls``); every offset starts after them.
    parts : tuple
        The kernel parts of the machine's attachments (:class:`rotorlab.models._parts.AbstractKernelPart`:
        frozen objects with ``key``, ``n_states``, ``n_param``, ``n_stations``, ``rotor`` and the
        lines they add to the kernel), in order; those fixed to the rotor (``rotor``: the
        unbalances) have their stations right after the races' and their blocks after the balls'.
    fixed : tuple of (int, float)
        Packed entries (absolute index, value) that the kernel takes as compile-time constants:
        a preset that keeps them for every value of its named parameters gives them
        (:mod:`rotorlab.models._rub_machine`); the generator folds them into the source
        (:mod:`rotorlab._kernels.machine_fold`). The packed vector still carries them.
    """

    n_z: int
    races: tuple[int, ...]
    drive: str = "profile"
    speed_kind: str = "constant"
    n_table: int = 0
    gyroscopic: bool = False
    energy: bool = False
    clearance: str = ""
    friction: bool = False
    tilt: tuple[int, ...] = ()
    parts: tuple[Any, ...] = ()
    param_base: int = 0
    fixed: tuple[tuple[int, float], ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "fixed", tuple(sorted((int(k), float(v)) for k, v in self.fixed)))
        object.__setattr__(self, "races", tuple(int(n) for n in self.races))
        object.__setattr__(self, "tilt", tuple(int(k) for k in self.tilt))
        if self.tilt and (len(self.tilt) != len(self.races) or sorted(set(self.tilt)) != list(range(self.n_tilt))):
            raise ValueError(f"bad layout tilt={self.tilt!r} for races={self.races!r}")
        if self.drive not in DRIVE_KINDS or self.speed_kind not in SPEED_KINDS:
            raise ValueError(f"bad layout drive={self.drive!r} speed_kind={self.speed_kind!r}")
        if self.clearance not in ("", "massless", "housing"):
            raise ValueError(f"bad layout clearance={self.clearance!r}")
        if self.friction and self.clearance:
            raise ValueError("ball friction and a clearance together are not implemented")

    @property
    def vectorises(self) -> bool:
        """Whether the generated kernel vectorises in the lane driver (``Kernels.vectorises``):
        every part is straight arithmetic with :func:`rotorlab._kernels._vmath.sincos`; the speed
        profile says so in :data:`SPEED_KINDS` (a motor's layout has kind ``"constant"``).
        ``tests/unit/test_vectorise.py`` checks machines of every part."""
        return SPEED_KINDS[self.speed_kind]

    # ---- counts
    @property
    def n_balls(self) -> int:
        return sum(self.races)

    @property
    def n_races(self) -> int:
        return len(self.races)

    @property
    def n_unbalance(self) -> int:
        """Stations of the parts fixed to the rotor (the point unbalances), after the races'."""
        return sum(part.n_stations for part in self.parts if part.rotor)

    @property
    def n_stations(self) -> int:
        return self.n_races + self.n_unbalance + (1 if self.clearance else 0)

    @property
    def n_all_stations(self) -> int:
        """Stations with packed B, H B^T and pair matrices: the lateral ones, then (with
        ``tilt``) one tilt station per distinct race node, whose ``B`` is that node's tilt ``T``,
        then the other parts' stations."""
        return self.n_stations + self.n_tilt + sum(part.n_stations for part in self.parts if not part.rotor)

    @property
    def placed_parts(self) -> list[tuple[Any, PartPlace]]:
        """Each part with its :class:`PartPlace`, in order (the rotor parts' stations after the
        races', the others' after the tilt stations)."""
        o = self.offsets
        out, i = [], self.i_parts
        s = {True: self.n_races, False: self.n_stations + self.n_tilt}
        for k, part in enumerate(self.parts):
            out.append((part, PartPlace(i, o[f"part{k}"], s[part.rotor])))
            i += part.n_states
            s[part.rotor] += part.n_stations
        return out

    def placed(self, rotor: bool) -> list[tuple[Any, PartPlace]]:
        """The placed parts fixed to the rotor (``rotor``) or not."""
        return [(part, place) for part, place in self.placed_parts if part.rotor == rotor]

    def places(self, key: str) -> list[PartPlace]:
        """The places of the parts whose kernel key is ``key`` (``"ta"``: the absorbers), in order."""
        return [place for part, place in self.placed_parts if part.key == key]

    @property
    def spin_loads(self) -> list[SpinLoad]:
        """The :class:`SpinLoad` of every part fixed to the rotor, in order."""
        return [ld for part, place in self.placed(True) for ld in part.spin_loads(self, place)]

    @property
    def i_parts(self) -> int:
        """First state of the parts (after the energy states)."""
        return self.i_energy + (2 if self.energy else 0)

    @property
    def n_tilt(self) -> int:
        """Distinct nodes of the races (tilt stations), 0 without ``tilt``."""
        return max(self.tilt) + 1 if self.tilt else 0

    def tilt_station(self, r: int) -> int:
        """Index of the tilt station of race ``r`` (``tilt`` layouts)."""
        return self.n_stations + self.tilt[r]

    @property
    def tilt_stations(self) -> list[int]:
        """The tilt stations, in order."""
        return [self.n_stations + k for k in range(self.n_tilt)]

    def tilt_balls(self, ts: int) -> list[int]:
        """The balls whose race sits on tilt station ``ts``."""
        return [b for b in range(self.n_balls) if self.tilt_station(self.ball_race[b]) == ts]

    @property
    def n_schur(self) -> int:
        """Unknowns of the Schur system: ball accelerations, theta'' with a motor, and with
        ``tilt`` one axial unknown per ball (``mu_b = m_b l_b^2 e_b . T_r z''``)."""
        return self.n_balls + (1 if self.motor else 0) + (self.n_balls if self.tilt else 0)

    @property
    def motor(self) -> bool:
        return self.drive != "profile"

    @property
    def ball_race(self) -> tuple[int, ...]:
        """Race of each ball."""
        return tuple(r for r, n in enumerate(self.races) for _ in range(n))

    # ---- state offsets
    @property
    def i_phi(self) -> int:
        return 2 * self.n_z

    @property
    def i_w(self) -> int:
        return 2 * self.n_z + self.n_balls

    @property
    def i_theta(self) -> int:
        return 2 * self.n_z + 2 * self.n_balls

    @property
    def i_energy(self) -> int:
        return self.i_theta + (2 if self.motor else 0)

    @property
    def i_clearance(self) -> int:
        """First state of the clearance: the housing's (x, y, vx, vy) if it moves, then the
        contact's dissipated energy and drive work, then its three discrete states (impacts,
        largest normal impulse, mode) at the very end."""
        return self.i_parts + sum(part.n_states for part in self.parts)

    @property
    def n_clearance_states(self) -> int:
        if not self.clearance:
            return 0
        return 5 + (4 if self.clearance == "housing" else 0)

    @property
    def i_modes(self) -> int:
        """First stick/slip mode of the balls (one per ball, at the end, with friction)."""
        return self.i_clearance + self.n_clearance_states

    @property
    def n_discrete(self) -> int:
        return (3 if self.clearance else 0) + (self.n_balls if self.friction else 0)

    @property
    def n_state(self) -> int:
        return self.i_modes + (self.n_balls if self.friction else 0)

    # ---- parameter offsets
    @property
    def offsets(self) -> dict[str, int]:
        nz, ns = self.n_z, self.n_all_stations
        sizes = [
            ("speed", 6),
            ("motor", 3 + 2 * self.n_table),
            ("balls", 4 * self.n_balls),
            ("unbalances", 0),  # where the rotor parts' blocks start: the first unbalance's U, cos, sin
        ] + [(f"part{k}", part.n_param) for k, part in enumerate(self.parts) if part.rotor] + [
            ("stations", 4 * nz * ns),
            ("L", 4 * ns * ns),
            ("HK", nz * nz),
            ("HC", nz * nz),
            ("HG", nz * nz if self.gyroscopic else 0),
            ("Hf", nz),
            ("C", nz * nz if self.energy else 0),
            ("Ka", nz * nz if self.energy else 0),
            ("clearance", 11 if self.clearance else 0),
            ("friction", self.n_balls if self.friction else 0),
            ("tilt", self.n_balls if self.tilt else 0),
        ] + [(f"part{k}", part.n_param) for k, part in enumerate(self.parts) if not part.rotor]
        out, k = {}, self.param_base
        for name, size in sizes:
            out[name] = k
            k += size
        out["size"] = k
        return out

    @property
    def n_param(self) -> int:
        return self.offsets["size"]

    def station_B(self, s: int) -> int:
        """Offset of B (2 x n_z) of station ``s``."""
        return self.offsets["stations"] + 4 * self.n_z * s

    def station_HBT(self, s: int) -> int:
        """Offset of H B^T (n_z x 2) of station ``s``."""
        return self.station_B(s) + 2 * self.n_z

    def pair_L(self, s: int, s2: int) -> int:
        """Offset of B_s H B_s2^T (2 x 2)."""
        return self.offsets["L"] + 4 * (s * self.n_all_stations + s2)

    @property
    def key(self) -> str:
        """Short identifier of the sizes (used in the generated module's name)."""
        races = "x".join(str(n) for n in self.races) or "0"
        return (f"z{self.n_z}r{races}u{self.n_unbalance}{self.drive[0]}{self.speed_kind[0]}"
                f"t{self.n_table}{'g' if self.gyroscopic else ''}{'e' if self.energy else ''}"
                f"{'c' + self.clearance[0] if self.clearance else ''}{'f' if self.friction else ''}"
                f"{'a' + ''.join(map(str, self.tilt)) if self.tilt else ''}"
                + "".join(f"p{part.key}" for part in self.parts if part.key and not part.rotor)
                + (f"b{self.param_base}" if self.param_base else "") + (f"k{len(self.fixed)}" if self.fixed else ""))
