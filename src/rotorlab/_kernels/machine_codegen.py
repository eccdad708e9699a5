r"""Generator of the compiled right-hand side of the composed machine model (``machine``).

The physics is documented in :mod:`rotorlab.models._machine`; this module turns the *sizes* of
one machine (structure coordinates, races and balls per race, unbalances, drive, energy states)
into the source of a module with one ``rhs(t, y, p, out)`` in which every count is a
compile-time constant and every loop is unrolled into straight scalar code. The lane driver
(:mod:`rotorlab.integrate._lanes`, "Lane-friendly kernels") can then vectorise it across its
lanes: sines and cosines come from :func:`rotorlab._kernels._vmath.sincos`, the drive profile is
inlined for its kind (a Hill run-up needs ``exp``/``log`` and runs scalar), and no loop runs over
a count read from ``p``.

The generated file is written once per source hash into the cache directory of the integrator's
drivers (``$ROTORLAB_CACHE_DIR``, see :mod:`rotorlab.integrate._codegen`), imported under a
module name containing that hash and cached by numba like any module-level kernel.

Packed parameters ``p`` (float64; offsets from :class:`Layout`)
---------------------------------------------------------------
=================  ===========================================================================
``speed``          6: the prescribed profile block (:mod:`rotorlab._kernels.speed`); zeros with a
                   motor
``motor``          3 + 2 n_t: polar inertia J (kg m^2), stall torque T_s (N m), no-load speed
                   w_0 (rad/s) [linear]; then n_t speeds (rad/s) and n_t torques (N m) [table]
``gravity``        2: g_x, g_y (m/s^2), the lateral components of gravity
``balls``          4 per ball (races in order): m (kg), m l (kg m), J = m l^2 + J_c (kg m^2),
                   c (N m s/rad)
``unbalances``     3 per unbalance: U = m e (kg m), cos beta, sin beta (beta: phase, rad)
``stations``       per station (races, then unbalances): B (2 x n_z, row-major), then H B^T
                   (n_z x 2, row-major); ``B z`` is the lateral displacement of the station
``L``              per ordered pair of stations (s, s'): B_s H B_s'^T (2 x 2, row-major)
``HK, HC, HG``     n_z x n_z each (row-major): H K, H C, H G; ``HG`` only when the structure is
                   gyroscopic
``Hf``             n_z: H f_g, the weight of the structure and of the balls
``C, Ka``          n_z x n_z each, only with energy states: C and the skew part of K
=================  ===========================================================================

``H = M0^-1`` with ``M0 = M_s + sum_r m_r B_r^T B_r`` (the structure plus the ball masses carried
by the races).

States
------
``[z (n_z), z' (n_z), phi (n_b), phi' (n_b), (theta, Omega) with a motor, (W, D) with energy
states]``: structure coordinates and their rates, absolute ball angles and rates, spin angle and
speed, drive work and dissipated energy.
"""

from __future__ import annotations

import hashlib
import importlib.util
import inspect
import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["Layout", "kernel_module"]

SPEED_KINDS = ("constant", "ramp", "hill")
DRIVE_KINDS = ("profile", "linear", "table")


@dataclass(frozen=True)
class Layout:
    """Sizes of one machine and the offsets of its packed parameters and states.

    Parameters
    ----------
    n_z : int
        Structure coordinates (4 per node, or the number of modes kept).
    races : tuple of int
        Balls per race.
    n_unbalance : int
        Number of unbalances.
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
    clearance : {"", "rigid", "elastic", "housing"}
        The kind of the machine's clearance (rotor-stator contact), "" for none; see
        :mod:`rotorlab._kernels.machine_contact`.
    friction : bool
        The balls have Coulomb or rolling friction (stick-slip modes).
    tilt : tuple of int
        Empty, or (when some race can tilt) per race the number of its node among the races'
        distinct nodes: the balls follow the tilting race plane (rigid ball kinematics, see
        :mod:`rotorlab.models._machine`); adds a tilt station per distinct node and one axial
        unknown per ball to the Schur system.
    """

    n_z: int
    races: tuple[int, ...]
    n_unbalance: int
    drive: str = "profile"
    speed_kind: str = "constant"
    n_table: int = 0
    gyroscopic: bool = False
    energy: bool = False
    clearance: str = ""
    friction: bool = False
    tilt: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "races", tuple(int(n) for n in self.races))
        object.__setattr__(self, "tilt", tuple(int(k) for k in self.tilt))
        if self.tilt and (len(self.tilt) != len(self.races) or sorted(set(self.tilt)) != list(range(self.n_tilt))):
            raise ValueError(f"bad layout tilt={self.tilt!r} for races={self.races!r}")
        if self.drive not in DRIVE_KINDS or self.speed_kind not in SPEED_KINDS:
            raise ValueError(f"bad layout drive={self.drive!r} speed_kind={self.speed_kind!r}")
        if self.clearance not in ("", "rigid", "elastic", "housing"):
            raise ValueError(f"bad layout clearance={self.clearance!r}")
        if self.friction and self.clearance:
            raise ValueError("ball friction and a clearance together are not implemented")

    # ---- counts
    @property
    def n_balls(self) -> int:
        return sum(self.races)

    @property
    def n_races(self) -> int:
        return len(self.races)

    @property
    def n_stations(self) -> int:
        return self.n_races + self.n_unbalance + (1 if self.clearance else 0)

    @property
    def n_all_stations(self) -> int:
        """Stations with packed B, H B^T and pair matrices: the lateral ones, then (with
        ``tilt``) one tilt station per distinct race node, whose ``B`` is that node's tilt ``T``."""
        return self.n_stations + self.n_tilt

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
        return self.i_energy + (2 if self.energy else 0)

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
            ("gravity", 2),
            ("balls", 4 * self.n_balls),
            ("unbalances", 3 * self.n_unbalance),
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
        ]
        out, k = {}, 0
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
                f"{'a' + ''.join(map(str, self.tilt)) if self.tilt else ''}")


def _sum(terms: list[str]) -> str:
    return " + ".join(terms) if terms else "0.0"


def generate(lay: Layout) -> str:
    """Return the source of the kernel module for ``lay`` (see the module docstring)."""
    nz, nb = lay.n_z, lay.n_balls
    L: list[str] = []
    a = L.append
    a(f"    # sizes: n_z={nz}, races={lay.races}, unbalances={lay.n_unbalance}, drive={lay.drive}, "
      f"speed={lay.speed_kind}, energy={lay.energy}, clearance={lay.clearance or None}")
    if lay.friction:
        a("    forced = -1")
    corr = prefix(lay, L)
    if lay.clearance:
        from rotorlab._kernels import machine_contact as _mc

        L += _mc.rhs_contact_lines(lay, corr)
    if lay.friction:
        friction_torques(lay, L, corr)
    _tail(lay, L, corr)
    body = "\n".join(L)
    header = _HEADER.format(key=lay.key)
    if lay.clearance:
        header = header.replace("import profile\n", "import profile\n" + _mc.IMPORTS, 1)
    src = header + body + "\n"
    if lay.clearance:
        src += _mc.extra_functions(lay, corr)
    if lay.friction:
        src += friction_functions(lay)
    return src


def prefix(lay: Layout, L: list[str], *, solve: bool = True) -> list[tuple[int, str, str]]:
    """Append the lines that evaluate the spin, the free structure terms ``h = H R_z``, the Schur
    system of the ball (and spin) accelerations, its LDL^T factors and (``solve``) its solution
    ``x`` and the reaction forces ``(gx_s, gy_s)`` of the balls on their stations; return those
    stations as ``(s, gx name, gy name)``."""
    nz, nb, o = lay.n_z, lay.n_balls, lay.offsets
    races, br = lay.races, lay.ball_race
    nr, nu = lay.n_races, lay.n_unbalance
    a = L.append
    # ---- spin
    if lay.motor:
        a(f"    theta = y[{lay.i_theta}]")
        a(f"    om = y[{lay.i_theta + 1}]")
    elif lay.speed_kind == "constant":
        a(f"    om = p[{o['speed'] + 1}]")
        a("    theta = om * t")
        a("    dom = 0.0")
    elif lay.speed_kind == "ramp":
        k = o["speed"]
        a(f"    w0 = p[{k + 1}]")
        a(f"    w1 = p[{k + 2}]")
        a(f"    dur = p[{k + 3}]")
        a("    slope = (w1 - w0) / dur")
        a("    tc = min(max(t, 0.0), dur)")
        a("    om = w0 + slope * tc")
        a("    theta = w0 * tc + 0.5 * slope * tc * tc + om * (t - tc)")
        a("    dom = slope if (t >= 0.0 and t < dur) else 0.0")
    else:
        a(f"    theta, om, dom = profile(t, p, {o['speed']})")
    # ---- coordinates
    for i in range(nz):
        a(f"    z{i} = y[{i}]")
        a(f"    v{i} = y[{nz + i}]")
    for b in range(nb):
        a(f"    s{b}, c{b} = sincos(y[{lay.i_phi + b}])")
        a(f"    w{b} = y[{lay.i_w + b}]")
    a(f"    gx = p[{o['gravity']}]")
    a(f"    gy = p[{o['gravity'] + 1}]")
    if nu:
        a("    sth, cth = sincos(theta)")
    for u in range(nu):
        k = o["unbalances"] + 3 * u
        a(f"    U{u} = p[{k}]")
        a(f"    eux{u} = cth * p[{k + 1}] - sth * p[{k + 2}]")
        a(f"    euy{u} = sth * p[{k + 1}] + cth * p[{k + 2}]")
    # ---- ball parameters and station forces (centrifugal terms)
    for b in range(nb):
        k = o["balls"] + 4 * b
        a(f"    ml{b} = p[{k + 1}]")
        a(f"    J{b} = p[{k + 2}]")
        a(f"    cb{b} = p[{k + 3}]")
        a(f"    rel{b} = w{b} - om")
    if lay.tilt:
        tilt_lines(lay, L)
    stations_force = []
    for r in range(nr):
        bs = [b for b in range(nb) if br[b] == r]
        a(f"    fx{r} = {_sum([f'ml{b} * w{b} * w{b} * c{b}' for b in bs])}")
        a(f"    fy{r} = {_sum([f'ml{b} * w{b} * w{b} * s{b}' for b in bs])}")
        stations_force.append((r, f"fx{r}", f"fy{r}"))
    for u in range(nu):
        s = nr + u
        if lay.motor:
            a(f"    fx{s} = U{u} * om * om * eux{u}")
            a(f"    fy{s} = U{u} * om * om * euy{u}")
        else:  # U (Omega^2 e_u - Omega' t_u), t_u = (-euy, eux)
            a(f"    fx{s} = U{u} * (om * om * eux{u} + dom * euy{u})")
            a(f"    fy{s} = U{u} * (om * om * euy{u} - dom * eux{u})")
        stations_force.append((s, f"fx{s}", f"fy{s}"))
    if lay.tilt:  # the balls' velocity terms on their tilting races (moments on phi_r)
        for ts in lay.tilt_stations:
            r, bs = ts, lay.tilt_balls(ts)
            a(f"    fx{ts} = -({_sum([f'w{b} * (D{b} * (tp{b} * c{b} - ep{b} * s{b}) + J{b} * tvy{r})' for b in bs])})")
            a(f"    fy{ts} = -({_sum([f'w{b} * (D{b} * (tp{b} * s{b} + ep{b} * c{b}) - J{b} * tvx{r})' for b in bs])})")
            stations_force.append((ts, f"fx{ts}", f"fy{ts}"))
    # ---- h = H R_z
    for i in range(nz):
        terms = [f"p[{o['Hf'] + i}]"]
        terms += [f"p[{o['HK'] + nz * i + j}] * z{j}" for j in range(nz)]
        terms += [f"p[{o['HC'] + nz * i + j}] * v{j}" for j in range(nz)]
        rhs = f"    h{i} = " + terms[0] + "".join(" - " + t for t in terms[1:])
        a(rhs)
        if lay.gyroscopic:
            kg = o["HG"] + nz * i
            a(f"    h{i} -= om * ({_sum([f'p[{kg + j}] * v{j}' for j in range(nz)])})")
        for s, fx, fy in stations_force:
            k = lay.station_HBT(s) + 2 * i
            a(f"    h{i} += p[{k}] * {fx} + p[{k + 1}] * {fy}")
    # ---- a0_s = B_s h for the stations that enter the Schur system
    need = list(range(nr)) + ([nr + u for u in range(nu)] if lay.motor else [])
    need += lay.tilt_stations
    for s in need:
        kb = lay.station_B(s)
        a(f"    ax{s} = {_sum([f'p[{kb + j}] * h{j}' for j in range(nz)])}")
        a(f"    ay{s} = {_sum([f'p[{kb + nz + j}] * h{j}' for j in range(nz)])}")
    # ---- Schur system S x = q in the ball accelerations (and theta'')
    unknowns = [("b", b) for b in range(nb)] + ([("th", 0)] if lay.motor else [])
    unknowns += [("m", b) for b in range(nb)] if lay.tilt else []
    n_s = len(unknowns)

    def t_vec(kind, idx):  # (tx, ty) expressions of the unit tangent of a ball / unbalance
        return (f"(-s{idx})", f"c{idx}") if kind == "b" else (f"(-euy{idx})", f"eux{idx}")

    def station(kind, idx):
        return br[idx] if kind == "b" else nr + idx

    def tLt(k1, i1, k2, i2):
        s1, s2 = station(k1, i1), station(k2, i2)
        kk = lay.pair_L(s1, s2)
        t1, t2 = t_vec(k1, i1), t_vec(k2, i2)
        return (f"({t1[0]} * (p[{kk}] * {t2[0]} + p[{kk + 1}] * {t2[1]}) + "
                f"{t1[1]} * (p[{kk + 2}] * {t2[0]} + p[{kk + 3}] * {t2[1]}))")

    if lay.tilt:
        tilt_schur(lay, L, unknowns)
    for i, (ki, ii) in enumerate([] if lay.tilt else unknowns):
        for j, (kj, ij) in enumerate(unknowns[: i + 1]):
            if ki == "b" and kj == "b":
                diag = f"J{ii} - " if i == j else "-"
                a(f"    S{i}_{j} = {diag}ml{ii} * ml{ij} * {tLt('b', ii, 'b', ij)}")
            else:  # rows/cols of theta: sums over the unbalances
                if ki == "th" and kj == "th":
                    terms = [f"U{u} * U{u2} * {tLt('u', u, 'u', u2)}"
                             for u in range(nu) for u2 in range(nu)]
                    a(f"    S{i}_{j} = p[{o['motor']}] - ({_sum(terms)})")
                else:
                    b = ij if kj == "b" else ii
                    terms = [f"U{u} * {tLt('b', b, 'u', u)}" for u in range(nu)]
                    a(f"    S{i}_{j} = -ml{b} * ({_sum(terms)})")
    # right-hand sides
    for i, (k, idx) in enumerate(unknowns):
        if k == "b":
            r = br[idx]
            extra = ""
            if lay.tilt:  # the ball's moment on its tilting race and the axial motion's term
                ts = lay.tilt_station(r)
                extra = f" + D{idx} * ep{idx} * tp{idx} - (nx{idx} * ax{ts} + ny{idx} * ay{ts})"
            a(f"    q{i} = -cb{idx} * rel{idx} + ml{idx} * (-gx * s{idx} + gy * c{idx})"
              f" - ml{idx} * (-s{idx} * ax{r} + c{idx} * ay{r})" + extra)
        elif k == "m":
            ts = lay.tilt_station(br[idx])
            a(f"    q{i} = -(c{idx} * ax{ts} + s{idx} * ay{ts})")
        else:
            km = o["motor"]
            if lay.drive == "linear":
                a(f"    torque = p[{km + 1}] * (1.0 - om / p[{km + 2}])")
            else:
                nt = lay.n_table
                ks, kt = km + 3, km + 3 + nt
                a(f"    torque = p[{kt}]")
                for q in range(nt - 1):
                    a(f"    fr = min(max((om - p[{ks + q}]) / (p[{ks + q + 1}] - p[{ks + q}]), 0.0), 1.0)")
                    a(f"    torque += fr * (p[{kt + q + 1}] - p[{kt + q}])")
            terms = ["torque"] + [f"cb{b} * rel{b}" for b in range(nb)]
            terms += [f"U{u} * (-gx * euy{u} + gy * eux{u})" for u in range(nu)]
            terms += [f"-U{u} * (-euy{u} * ax{nr + u} + eux{u} * ay{nr + u})" for u in range(nu)]
            a(f"    q{i} = {_sum(terms)}")
    if lay.friction:
        friction_solve(lay, L, unknowns, t_vec, station)
        return reactions(lay, L, "g", "x")
    # LDL^T (S symmetric positive definite: a Schur complement of the mass matrix)
    for j in range(n_s):
        a(f"    D{j} = S{j}_{j}" + "".join(f" - L{j}_{k} * L{j}_{k} * D{k}" for k in range(j)))
        for i in range(j + 1, n_s):
            a(f"    L{i}_{j} = (S{i}_{j}" + "".join(f" - L{i}_{k} * L{j}_{k} * D{k}" for k in range(j))
              + f") / D{j}")
    if not solve:
        return []
    solve_lines(lay, L, "x", "q")
    return reactions(lay, L, "g", "x")


def tilt_lines(lay: Layout, L: list[str]) -> None:
    """Append the tilt ``(tx, ty)`` and its rate ``(tvx, tvy)`` of each race's node and per ball
    ``D = m l^2``, ``ep = e . phi'``, ``tp = t . phi'`` and its moment arm on the race's tilt
    ``(nx, ny) = J_b / 2 (phi_y, -phi_x)`` (rigid ball kinematics, :mod:`rotorlab.models._machine`)."""
    nz, br, o = lay.n_z, lay.ball_race, lay.offsets
    a = L.append
    for r in lay.tilt_stations:  # named by the tilt station
        kb = lay.station_B(r)
        for name, row, src in (("tx", 0, "z"), ("ty", 1, "z"), ("tvx", 0, "v"), ("tvy", 1, "v")):
            a(f"    {name}{r} = {_sum([f'p[{kb + row * nz + j}] * {src}{j}' for j in range(nz)])}")
    for b in range(lay.n_balls):
        r = lay.tilt_station(br[b])
        a(f"    D{b} = p[{o['tilt'] + b}]")
        a(f"    ep{b} = c{b} * tvx{r} + s{b} * tvy{r}")
        a(f"    tp{b} = c{b} * tvy{r} - s{b} * tvx{r}")
        a(f"    nx{b} = 0.5 * J{b} * ty{r}")
        a(f"    ny{b} = -0.5 * J{b} * tx{r}")


def loads(lay: Layout, kind: str, idx: int) -> list[tuple[int, str, str]]:
    """Where a unit of Schur unknown ``(kind, idx)`` acts on the structure: ``(station, vx, vy)``
    with ``X_j = sum B_s^T (vx, vy)`` (its column of the mass matrix's coupling block)."""
    br, nr = lay.ball_race, lay.n_races
    if kind == "b":
        out = [(br[idx], f"mtx{idx}", f"mty{idx}")]
        if lay.tilt:
            out.append((lay.tilt_station(br[idx]), f"nx{idx}", f"ny{idx}"))
        return out
    if kind == "th":
        return [(nr + u, f"(-U{u} * euy{u})", f"(U{u} * eux{u})") for u in range(lay.n_unbalance)]
    return [(lay.tilt_station(br[idx]), f"c{idx}", f"s{idx}")]


def tilt_schur(lay: Layout, L: list[str], unknowns) -> None:
    """Append the Schur matrix ``S = diag(J_b, J, -1 / D_b) - X^T H X`` of a ``tilt`` layout
    (lower triangle ``S{i}_{j}``); ``P{j}_{s} = B_s H X_j`` is formed once per unknown."""
    a = L.append
    for b in range(lay.n_balls):
        a(f"    mtx{b} = -ml{b} * s{b}")
        a(f"    mty{b} = ml{b} * c{b}")
    lds = [loads(lay, k, i) for k, i in unknowns]
    used = sorted({s for ld in lds for s, _, _ in ld})
    # B_s H B_s2^T = B_s (H B_s2^T) from the packed B and H B^T that the kernel reads anyway
    # (for s <= s2; the other half by symmetry): fewer distinct loads of p than reading the
    # packed pairs, which keeps the lane loop within LLVM's runtime alias-check budget
    nz = lay.n_z
    for i1, s1 in enumerate(used):
        for s2 in used[i1:]:
            kb, kh = lay.station_B(s1), lay.station_HBT(s2)
            for k in range(4):
                row, col = divmod(k, 2)
                a(f"    Lv{s1}_{s2}_{k} = " + _sum([f"p[{kb + row * nz + j}] * p[{kh + 2 * j + col}]"
                                                   for j in range(nz)]))

    def lv(s1, s2, k):
        return f"Lv{s1}_{s2}_{k}" if s1 <= s2 else f"Lv{s2}_{s1}_{2 * (k % 2) + k // 2}"

    for j, ld in enumerate(lds):
        for s in used:
            for row, nm in ((0, "Px"), (1, "Py")):
                terms = [f"{lv(s, s2, 2 * row)} * {vx} + {lv(s, s2, 2 * row + 1)} * {vy}"
                         for s2, vx, vy in ld]
                a(f"    {nm}{j}_{s} = {_sum(terms)}")
    km = lay.offsets["motor"]
    for i, (ki, ii) in enumerate(unknowns):
        for j in range(i + 1):
            quad = _sum([f"{vx} * Px{j}_{s} + {vy} * Py{j}_{s}" for s, vx, vy in lds[i]])
            diag = ""
            if i == j:
                diag = {"b": f"J{ii}", "th": f"p[{km}]", "m": f"-1.0 / D{ii}"}[ki] + " "
            a(f"    S{i}_{j} = {diag}- ({quad})")


def unit_rhs(lay: Layout, L: list[str], tag: str, s: int, tq: str, ind: str) -> None:
    """Append ``{tag}q{i} = -X_i^T H B_s^T f`` for a unit force ``f = ({tag}fx, {tag}fy)`` at
    station ``s`` (and the spin torque ``tq`` on theta's row): the right-hand side of the
    Schur system for the response to a force (the clearance's Delassus terms)."""
    br, nr, nb = lay.ball_race, lay.n_races, lay.n_balls
    a = lambda x: L.append(ind + x)  # noqa: E731

    def proj(s2, vx, vy):
        kk = lay.pair_L(s2, s)
        return (f"{vx} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
                f" + {vy} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy)")

    for b in range(nb):
        kk = lay.pair_L(br[b], s)
        extra = ""
        if lay.tilt:
            extra = " + " + proj(lay.tilt_station(br[b]), f"nx{b}", f"ny{b}")
        a(f"{tag}q{b} = -ml{b} * (-s{b} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
          f" + c{b} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy))"
          + (f" - ({extra[3:]})" if extra else ""))
    if lay.motor:
        terms = []
        for u in range(lay.n_unbalance):
            kk = lay.pair_L(nr + u, s)
            terms.append(f"U{u} * (-euy{u} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
                         f" + eux{u} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy))")
        a(f"{tag}q{nb} = {tq} - ({_sum(terms)})")
    if lay.tilt:
        i0 = nb + (1 if lay.motor else 0)
        for b in range(nb):
            a(f"{tag}q{i0 + b} = -({proj(lay.tilt_station(br[b]), f'c{b}', f's{b}')})")


def friction_solve(lay: Layout, L: list[str], unknowns, t_vec, station) -> None:
    """Append the Schur system with the balls' stick/slip modes and its solution ``x``.

    Ball b with friction arm ``kap_b`` (``coulomb l + rolling``, m) and mode ``md_b`` (the state
    after the layout's clearance: -1 / +1 slipping with that sign of ``phi_b' - Omega``, 0 stuck;
    always free when ``kap_b == 0``), exactly the law of :mod:`rotorlab._kernels.jeffcott_balls`:

    - slipping: the race's torque ``-md_b kap_b N_b`` on the ball, with the normal force
      ``N_b = m_b (l w_b^2 + e_b . (g - a_r))`` (``e_b = (cos phi_b, sin phi_b)``, ``a_r`` the
      absolute acceleration of its station, linear in the unknowns: ``a_r = a0_r - sum_j E``),
      which adds ``md kap m e_b . L_(r, s_j) t_j m l_j`` to row b (S is no longer symmetric) and
      its reaction to the motor's row;
    - stuck (``md_b == 0``, or ``forced == b`` in the trial solves of the events): the row becomes
      ``x_b = Omega'`` (prescribed spin) or ``x_b - theta'' = 0`` (motor, whose row then takes the
      ball's row: the holding torque is internal).

    The system is solved by Gaussian elimination without pivoting (its diagonal is that of a
    Schur complement of the mass matrix, or 1 on a stuck row), straight-line code as the LDL^T.
    """
    nb, br, o = lay.n_balls, lay.ball_race, lay.offsets
    n_s = len(unknowns)
    a = L.append
    th = nb if lay.motor else -1

    def S(i, j):
        return f"S{max(i, j)}_{min(i, j)}"

    def E(b, j):  # ml_j e_b . L_(r_b, s_j) t_j (or the unbalances' sum for theta)
        kind, idx = unknowns[j]
        if kind == "b":
            pairs = [(f"ml{idx}", lay.pair_L(br[b], br[idx]), t_vec("b", idx))]
            if lay.tilt:
                pairs.append(("1.0", lay.pair_L(br[b], lay.tilt_station(br[idx])),
                              (f"nx{idx}", f"ny{idx}")))
        elif kind == "m":
            pairs = [("1.0", lay.pair_L(br[b], lay.tilt_station(br[idx])), (f"c{idx}", f"s{idx}"))]
        else:
            pairs = [(f"U{u}", lay.pair_L(br[b], lay.n_races + u), t_vec("u", u))
                     for u in range(lay.n_unbalance)]
        terms = [f"{w} * (c{b} * (p[{k}] * {t[0]} + p[{k + 1}] * {t[1]}) + "
                 f"s{b} * (p[{k + 2}] * {t[0]} + p[{k + 3}] * {t[1]}))" for w, k, t in pairs]
        return f"({_sum(terms)})"

    for b in range(nb):
        r = br[b]
        a(f"    kap{b} = p[{o['friction'] + b}]")
        a(f"    kmd{b} = y[{lay.i_modes + b}]")
        a(f"    kst{b} = 1.0 if ((kap{b} > 0.0 and kmd{b} == 0.0) or forced == {b}) else 0.0")
        a(f"    ksg{b} = (1.0 - kst{b}) * kmd{b} * kap{b}")
        a(f"    kms{b} = ksg{b} * p[{o['balls'] + 4 * b}]")
        a(f"    kN0{b} = ml{b} * w{b} * w{b} + p[{o['balls'] + 4 * b}] * "
          f"(c{b} * (gx - ax{r}) + s{b} * (gy - ay{r}))")
    # rows of the balls: slip adds the friction, stuck replaces the row
    for b in range(nb):
        for j in range(n_s):
            delta = "1.0" if j == b else ("-1.0" if j == th else "0.0")
            a(f"    A{b}_{j} = (1.0 - kst{b}) * ({S(b, j)} + kms{b} * {E(b, j)}) + kst{b} * {delta}")
        stuck_rhs = "0.0" if lay.motor else "dom"
        a(f"    r{b} = (1.0 - kst{b}) * (q{b} - ksg{b} * kN0{b}) + kst{b} * {stuck_rhs}")
    if lay.motor:
        for j in range(n_s):
            terms = [S(th, j)]
            for b in range(nb):
                terms.append(f"kst{b} * {S(b, j)} - kms{b} * {E(b, j)}")
            a(f"    A{th}_{j} = " + " + ".join(terms))
        a(f"    r{th} = q{th}" + "".join(f" + kst{b} * q{b} + ksg{b} * kN0{b}" for b in range(nb)))
    for i in range(nb + (1 if lay.motor else 0), n_s):  # the axial unknowns of the balls
        for j in range(n_s):
            a(f"    A{i}_{j} = {S(i, j)}")
        a(f"    r{i} = q{i}")
    for k in range(n_s):
        for i in range(k + 1, n_s):
            a(f"    fe = A{i}_{k} / A{k}_{k}")
            for j in range(k + 1, n_s):
                a(f"    A{i}_{j} -= fe * A{k}_{j}")
            a(f"    r{i} -= fe * r{k}")
    for i in reversed(range(n_s)):
        a(f"    x{i} = (r{i}" + "".join(f" - A{i}_{j} * x{j}" for j in range(i + 1, n_s)) + f") / A{i}_{i}")


def friction_torques(lay: Layout, L: list[str], corr, zdd: str = "out") -> None:
    """Append ``tq{b}`` (the race's torque on ball b: friction, or the holding torque of a stuck
    ball) and ``bd{b}`` (the friction bound ``kap_b N_b``, with ``w_b = Omega`` when stuck) from
    the solution (the residual of the ball's equation, exact in every mode)."""
    nz, br, o = lay.n_z, lay.ball_race, lay.offsets
    a = L.append
    for r in list(range(lay.n_races)) + lay.tilt_stations:
        # station acceleration a_r = a0_r - sum_s L_(r, s) g_s
        for row, nm in ((0, "fax"), (1, "fay")):
            terms = [f"a{'xy'[row]}{r}"]
            for s, gx, gy in corr:
                k = lay.pair_L(r, s) + 2 * row
                terms.append(f"-(p[{k}] * {gx} + p[{k + 1}] * {gy})")
            a(f"    {nm}{r} = " + " ".join(terms))
    for b in range(lay.n_balls):
        r = br[b]
        m = f"p[{o['balls'] + 4 * b}]"
        tilt = ""
        if lay.tilt:  # + n_b . T_r z'' - D e.phi' t.phi' (rigid kinematics)
            tilt = f" + nx{b} * fax{lay.tilt_station(r)} + ny{b} * fay{lay.tilt_station(r)} - D{b} * ep{b} * tp{b}"
        a(f"    tq{b} = J{b} * x{b} + cb{b} * rel{b} - ml{b} * (-s{b} * (gx - fax{r}) + c{b} * (gy - fay{r}))" + tilt)
        a(f"    wn{b} = kst{b} * om + (1.0 - kst{b}) * w{b}")
        a(f"    bd{b} = kap{b} * (ml{b} * wn{b} * wn{b} + {m} * (c{b} * (gx - fax{r}) + s{b} * (gy - fay{r})))")


def friction_functions(lay: Layout) -> str:
    """Source of ``terms``, ``events`` and ``reset`` of the balls' stick/slip (friction layouts)."""
    nb, im, n = lay.n_balls, lay.i_modes, lay.n_state
    L: list[str] = []
    corr = prefix(lay, L)
    friction_torques(lay, L, corr)
    for b in range(nb):
        L.append(f"    buf[{2 * b}] = tq{b}")
        L.append(f"    buf[{2 * b + 1}] = bd{b}")
    src = (_DECO + "def terms(t, y, p, forced, buf):  # pragma: no cover - compiled\n"
           '    """buf[2 b], buf[2 b + 1]: the race\'s torque on ball b and its friction bound."""\n'
           + "\n".join(L) + "\n")
    ev = [f"    terms(t, y, p, -1, g)"]
    for b in range(nb):
        ev += [f"    md = y[{im + b}]",
               f"    if p[{lay.offsets['friction'] + b}] <= 0.0:",
               f"        g[{2 * b}] = 1.0", f"        g[{2 * b + 1}] = 1.0",
               "    elif md != 0.0:",
               f"        g[{2 * b}] = (y[{lay.i_w + b}] - om) * md", f"        g[{2 * b + 1}] = 1.0",
               "    else:",
               f"        g[{2 * b + 1}] = g[{2 * b + 1}] - abs(g[{2 * b}])", f"        g[{2 * b}] = 1.0"]
    spin = (f"    om = y[{lay.i_theta + 1}]" if lay.motor else
            f"    om = spin_speed(t, p)")
    src += (_DECO + "def events(t, y, p, g):  # pragma: no cover - compiled\n"
            '    """Events per ball b: 2 b stick, 2 b + 1 slip (direction -1), as jeffcott_balls."""\n'
            + spin + "\n" + "\n".join(ev) + "\n")
    src += (_DECO + f'''def reset(k, t, y, p, y_new):  # pragma: no cover - compiled
    """Stick or slip of ball k // 2 (trial solve with the ball stuck), relative speed set to 0."""
    b = k // 2
    terms(t, y, p, b, y_new)
    tq = y_new[2 * b]
    bd = y_new[2 * b + 1]
    for i in range({n}):
        y_new[i] = y[i]
    if k % 2 == 0 and abs(tq) <= bd:
        md = 0.0
    elif tq <= 0.0:
        md = 1.0
    else:
        md = -1.0
    y_new[{im} + b] = md
{spin.replace("    om", "    y_new[" + str(lay.i_w) + " + b]")}
    return 0
''')
    src += (_DECO + f'''def spin_speed(t, p):  # pragma: no cover - compiled
    theta, om, dom = profile(t, p, {lay.offsets['speed']})
    return om
''')
    return src


_DECO = '\n\n@njit(cache=True, nogil=True, error_model="numpy")\n'


def solve_lines(lay: Layout, L: list[str], x: str, q: str, indent: str = "    ") -> None:
    """Append the forward and back substitution ``S x = q`` with the LDL^T factors of :func:`prefix`."""
    n_s = lay.n_schur
    for i in range(n_s):
        L.append(f"{indent}{x}{i} = {q}{i}" + "".join(f" - L{i}_{k} * {x}{k}" for k in range(i)))
    for i in reversed(range(n_s)):
        L.append(f"{indent}{x}{i} = {x}{i} / D{i}" + "".join(f" - L{k}_{i} * {x}{k}" for k in range(i + 1, n_s)))


def reactions(lay: Layout, L: list[str], g: str, x: str, indent: str = "    ") -> list[tuple[int, str, str]]:
    """Append the station forces of the ball (and spin) accelerations ``x``: ``(g}x_s, g}y_s)``."""
    nb, br, nr = lay.n_balls, lay.ball_race, lay.n_races
    corr = []
    for r in range(nr):
        bs = [b for b in range(nb) if br[b] == r]
        L.append(f"{indent}{g}x{r} = {_sum([f'-ml{b} * {x}{b} * s{b}' for b in bs])}")
        L.append(f"{indent}{g}y{r} = {_sum([f'ml{b} * {x}{b} * c{b}' for b in bs])}")
        corr.append((r, f"{g}x{r}", f"{g}y{r}"))
    if lay.motor:
        for u in range(lay.n_unbalance):
            L.append(f"{indent}{g}x{nr + u} = -U{u} * {x}{nb} * euy{u}")
            L.append(f"{indent}{g}y{nr + u} = U{u} * {x}{nb} * eux{u}")
            corr.append((nr + u, f"{g}x{nr + u}", f"{g}y{nr + u}"))
    if lay.tilt:  # the balls' moments on their races' tilt: n_b phi_b'' + e_b mu_b
        i0 = nb + (1 if lay.motor else 0)
        for ts in lay.tilt_stations:
            bs = lay.tilt_balls(ts)
            L.append(f"{indent}{g}x{ts} = {_sum([f'nx{b} * {x}{b} + c{b} * {x}{i0 + b}' for b in bs])}")
            L.append(f"{indent}{g}y{ts} = {_sum([f'ny{b} * {x}{b} + s{b} * {x}{i0 + b}' for b in bs])}")
            corr.append((ts, f"{g}x{ts}", f"{g}y{ts}"))
    return corr


def _tail(lay: Layout, L: list[str], corr: list[tuple[int, str, str]]) -> None:
    """Append the writes of dy/dt (structure, balls, spin, energy states; clearance: its own)."""
    nz, nb, o = lay.n_z, lay.n_balls, lay.offsets
    nr, nu = lay.n_races, lay.n_unbalance
    a = L.append
    cl = bool(lay.clearance)
    for i in range(nz):
        terms = [f"p[{lay.station_HBT(s) + 2 * i}] * {gx} + p[{lay.station_HBT(s) + 2 * i + 1}] * {gy}"
                 for s, gx, gy in corr]
        a(f"    out[{i}] = v{i}")
        a(f"    out[{nz + i}] = h{i}" + "".join(f" - ({t})" for t in terms) + (f" + cz{i}" if cl else ""))
    for b in range(nb):
        a(f"    out[{lay.i_phi + b}] = w{b}")
        a(f"    out[{lay.i_w + b}] = x{b}" + (f" + cx{b}" if cl else ""))
    if lay.motor:
        a(f"    out[{lay.i_theta}] = om")
        a(f"    out[{lay.i_theta + 1}] = x{nb}" + (f" + cx{nb}" if cl else ""))
    if lay.energy:
        ie = lay.i_energy
        if lay.motor:
            a(f"    out[{ie}] = torque * om")
        else:  # drive torque from the spin equation with J = 0
            terms = []
            for u in range(nu):
                kb = lay.station_B(nr + u)
                axu = _sum([f"p[{kb + j}] * out[{nz + j}]" for j in range(nz)])
                ayu = _sum([f"p[{kb + nz + j}] * out[{nz + j}]" for j in range(nz)])
                terms.append(f"U{u} * (-euy{u} * ({axu}) + eux{u} * ({ayu}))")
                terms.append(f"-U{u} * (-gx * euy{u} + gy * eux{u})")
            terms += [f"-cb{b} * rel{b}" for b in range(nb)]
            if lay.friction:  # the reaction of the races' torques on the balls
                terms += [f"tq{b}" for b in range(nb)]
            a(f"    torque = {_sum(terms)}")
            a(f"    out[{ie}] = torque * om")
        diss = [f"cb{b} * rel{b} * rel{b}" for b in range(nb)]
        if lay.friction:
            diss += [f"-tq{b} * rel{b}" for b in range(nb)]
        kc, ka = o["C"], o["Ka"]
        diss += [f"v{i} * (p[{kc + nz * i + j}] * v{j} + p[{ka + nz * i + j}] * z{j})"
                 for i in range(nz) for j in range(nz)]
        a(f"    out[{ie + 1}] = {_sum(diss)}")
    if cl:
        from rotorlab._kernels import machine_contact as _mc

        L += _mc.rhs_tail_lines(lay)
    if lay.friction:
        for b in range(nb):
            a(f"    out[{lay.i_modes + b}] = 0.0")


_HEADER = '''"""Generated by rotorlab._kernels.machine_codegen for sizes {key}; do not edit."""
from numba import njit

from rotorlab._kernels._vmath import sincos
from rotorlab._kernels.speed import profile


@njit(cache=True, nogil=True, error_model="numpy")
def rhs(t, y, p, out):  # pragma: no cover - compiled
    """Right-hand side of the machine (layout in rotorlab._kernels.machine_codegen)."""
'''

_LOADED: dict[str, Any] = {}


def _deps_hash(source: str) -> str:
    import numba

    from rotorlab._kernels import _vmath, speed

    h = hashlib.sha256(numba.__version__.encode())
    h.update(sys.version.encode())
    h.update(source.encode())
    from rotorlab._kernels import contact, machine_contact

    for mod in (_vmath, speed, contact, machine_contact):
        h.update(Path(inspect.getsourcefile(mod)).read_bytes())
    return h.hexdigest()[:20]


def kernel_module(lay: Layout):
    """Return the imported kernel module for ``lay`` (generated and written on first use)."""
    from rotorlab.integrate._codegen import cache_dir as _cache_dir

    source = generate(lay)
    digest = _deps_hash(source)
    if digest in _LOADED:
        return _LOADED[digest]
    name = f"_rotorlab_machine_{lay.key}_{digest}"
    directory = _cache_dir()
    if directory is None:  # pragma: no cover - no writable directory at all
        directory = Path(tempfile.mkdtemp(prefix="rotorlab-machine-"))
    path = directory / f"{name}.py"
    if not path.exists():
        fd, tmp = tempfile.mkstemp(dir=directory, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(source)
        os.replace(tmp, path)
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    _LOADED[digest] = module
    return module
