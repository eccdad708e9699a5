r"""The friction band of a ``machine`` whose balls have Coulomb or rolling friction (``friction-margin``).

The machine's law (:mod:`rotorlab._kernels.machine_friction`): ball b sticks while the race's
holding torque stays within ``kap_b N_b``, ``kap_b = coulomb l_b + rolling_b`` (m). With every ball
stuck at psi_b the balls ride with the rotor as point masses, and at a constant speed the
structure stands still in the co-rotating frame at the locked response

    (K + i Omega (C + Omega G) - Omega^2 M0) Z
        = Omega^2 (sum_u U_u e^{i beta_u} B_u^T + sum_b m_b l_b e^{i psi_b} B_r^T) (1, -i)

(M0 the structure with the balls' masses at their races, B a station's lateral displacement; the
complex station deflection in the co-rotating frame is ``w_r = (B_r Z)_x``). The station turns
with the rotor, its acceleration ``-Omega^2 w_r``, so ball b needs the holding torque
``D_b = m_b l_b Omega^2 Im(w_r e^{-i psi_b})`` and is pressed with ``N_b = m_b Omega^2 (l_b +
Re(w_r e^{-i psi_b}))``: it sticks while ``|Im(w_r e^{-i psi_b})| <= (kap_b / l_b) (l_b +
Re(w_r e^{-i psi_b}))`` - for one race on a planar rotor the condition of ``jeffcott_balls``
(kap = f l).

Races that tilt with their node (rigid ball kinematics, :mod:`rotorlab.models._machine`: ball b
turns with the race plane, ``phi = T_r z`` its node's tilt). With every ball stuck at
``phi_b = Omega t + psi_b`` and the structure standing still in the co-rotating frame, at t = 0
``z = u``, ``z' = Omega J u``, ``z'' = -Omega^2 u`` (J turns every coordinate pair by 90 deg), so
``phi' = Omega (-phi_y, phi_x)``, ``e_b . phi' = -Omega t_b . phi`` and ``t_b . phi' = Omega e_b .
phi``. The tilting terms of the structure (its mass ``m_b l_b^2 T^T e_b e_b^T T``, the force
``-T^T [m_b l_b^2 Omega ((t_b . phi') e_b + (e_b . phi') t_b) + J_b Omega (phi_y', -phi_x')]``)
then add ``Omega^2 T^T (m_b l_b^2 e_b e_b^T + J_c I) phi`` (``J_b = m_b l_b^2 + J_c``): the
steady response solves the real system

    (K - Omega^2 M0 + Omega (C + Omega G) J + Omega^2 sum_b T_r^T (m_b l_b^2 e_b e_b^T + J_c I) T_r) u
        = Omega^2 (sum_b m_b l_b B_r^T e_b + sum_u U_u B_u^T e_u),

one solve per arrangement (without tilt it is the complex solve above). The ball's equation
(``J_b phi_b'' + m_b l_b t_b . B_r z'' + J_b / 2 (phi_y phi_x'' - phi_x phi_y'') - m_b l_b^2
(e_b . phi') (t_b . phi') = torque of the race``) gives, with ``w_b = B_r u`` and ``phi = T_r u``,
the holding torque ``D_b = m_b l_b Omega^2 (-t_b . w_b + l_b (e_b . phi) (t_b . phi))`` (the
gyroscopic coupling vanishes: ``phi'' = -Omega^2 phi``), and the race presses the ball with the
kernel's in-plane ``N_b = m_b Omega^2 (l_b + e_b . w_b)``; the ball sticks while ``|D_b| <= kap_b
N_b`` (:meth:`MachineStick.holding`; checked against the kernel's ``terms`` in
``tests/validation/test_friction_machines.py``).

One or two balls: the band is searched as for that rotor (:func:`rotorlab.analyses._friction_margin.stuck_band`)
around the balanced angles of the machine without friction. Three or more: the stuck set is
every arrangement where all balls stick, the part of it joined to the balanced family is searched by
constrained optimisation (:mod:`rotorlab.analyses._friction_search`; ``search`` in the result says
how). The residual is the largest node deflection ``max |X|`` (m). Needs, without friction, a
steady balanced state: an isotropic structure and no gravity across the axis (the analysis sets a
constant speed).

The simulated check releases the balls stuck (mode 0) at the worst point just inside and at the
next grid point outside, the structure on its locked response, and follows them for
``CHECK_REVOLUTIONS`` revolutions in the fixed frame.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

__all__ = ["machine_band", "MachineStick", "balanced_family"]

#: Seeded least-squares solves for distinct balanced arrangements (the optimiser's starts).
BALANCED_STARTS = 8


class MachineStick:
    """The stuck-ball terms of a machine at one speed (module docstring), vectorised over ball angles."""

    def __init__(self, machine, om: float):
        nz = machine.n_coordinates
        red = machine.reduced
        st = machine._stations
        m, l, J, c, race = machine._ball_arrays
        nr = len(machine.races)
        self.om, self.l, self.m = om, l, m
        self.kap = np.array([b.coulomb * r.radius + b.rolling for r in machine.races for b in r.balls])
        self.tilting = bool(machine.layout.tilt)
        self.B = np.array([st[race[b]] for b in range(m.size)]).reshape(m.size, 2, nz)
        self.T = np.array([machine.tilt_matrix(machine.races[race[b]].node) for b in range(m.size)]).reshape(
            m.size, 2, nz)
        self.nodes = np.stack([machine.basis[0::4, :], machine.basis[1::4, :]])  # (2, n_nodes, nz)
        if self.tilting:  # the real co-rotating system (module docstring), one solve per arrangement
            pairs = np.zeros((nz, nz))
            pairs[0::2, 1::2] = -np.eye(nz // 2)
            pairs[1::2, 0::2] = np.eye(nz // 2)
            jc = J - m * l * l
            self.A0 = (red["K"] - om * om * machine._m0() + om * (red["C"] + om * red["G"]) @ pairs
                       + om * om * sum(jc[b] * self.T[b].T @ self.T[b] for b in range(m.size)))
            self.fu = om * om * sum((me * (st[nr + u].T @ np.array([math.cos(beta), math.sin(beta)]))
                                     for u, (_, _, me, beta) in enumerate(machine._point_unbalances)), np.zeros(nz))
            self.D = m * l * l
            return
        D = red["K"] + 1j * om * (red["C"] + om * red["G"]) - om * om * machine._m0()
        proj = np.array([1.0, -1j])
        fu = np.zeros(nz, dtype=complex)
        for u, (_, _, me, beta) in enumerate(machine._point_unbalances):
            fu += me * np.exp(1j * beta) * (st[nr + u].T @ proj)
        fb = np.array([m[b] * l[b] * (st[race[b]].T @ proj) for b in range(m.size)]).reshape(m.size, nz)
        self.zu = np.linalg.solve(D, om * om * fu)
        self.zb = np.linalg.solve(D, om * om * fb.T).T  # (n_b, nz)

    def coordinates(self, psi) -> np.ndarray:
        """The structure's co-rotating coordinates z_r (real, shape (..., n_z)) with the balls stuck at psi."""
        psi = np.asarray(psi, dtype=float)
        if not self.tilting:
            return (self.zu + np.exp(1j * psi) @ self.zb).real
        cs = np.stack([np.cos(psi), np.sin(psi)], axis=-1)  # (..., n_b, 2): e_b
        f = self.fu + self.om ** 2 * np.einsum("...bk,bkz->...z", cs * (self.m * self.l)[:, None], self.B)
        te = np.einsum("...bk,bkz->...bz", cs, self.T)  # e_b . T_r
        A = self.A0 + self.om ** 2 * np.einsum("b,...bi,...bj->...ij", self.D, te, te)
        flat_a, flat_f = A.reshape(-1, *self.A0.shape), f.reshape(-1, self.A0.shape[0])
        out = np.empty_like(flat_f)
        for k in range(0, flat_f.shape[0], 4096):  # batches of a bounded size
            out[k:k + 4096] = np.linalg.solve(flat_a[k:k + 4096], flat_f[k:k + 4096, :, None])[..., 0]
        return out.reshape(f.shape)

    def holding(self, psi):
        """``(amplitude, hold, allow)`` at stuck angles psi (..., n_b): the largest node deflection (m), the
        race's holding torque on each ball and what friction allows, both per ``m_b l_b Omega^2`` (m)."""
        psi = np.asarray(psi, dtype=float)
        z = self.coordinates(psi)
        e = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
        t = np.stack([-e[..., 1], e[..., 0]], axis=-1)
        w = np.einsum("bkz,...z->...bk", self.B, z)  # the race station of each ball
        hold = -np.sum(t * w, axis=-1)
        if self.tilting:
            phi = np.einsum("bkz,...z->...bk", self.T, z)
            hold = hold + self.l * np.sum(e * phi, axis=-1) * np.sum(t * phi, axis=-1)
        allow = self.kap / self.l * (self.l + np.sum(e * w, axis=-1))
        amp = np.hypot(*np.einsum("knz,...z->k...n", self.nodes, z)).max(axis=-1)
        return amp, hold, allow

    def terms(self, psi):
        """``(largest node deflection (m), holding-torque margin per ball)`` at stuck angles psi (..., n_b)."""
        amp, hold, allow = self.holding(psi)
        return amp, np.abs(hold) - allow


def _frictionless(machine):
    races = tuple(replace(r, balls=tuple(replace(b, coulomb=0.0, rolling=0.0) for b in r.balls))
                  for r in machine.races)
    return replace(machine, races=races)


def machine_band(machine, speeds, *, grid: int = 241, simulate: bool = True, threads: int | None = None):
    """Friction band and worst residual deflection of a machine (module docstring): on a grid for one or two
    balls, by constrained optimisation from the balanced family for more (:mod:`._friction_search`)."""
    from rotorlab.analyses._friction_margin import stuck_band
    from rotorlab.models import ConstantSpeed

    smooth = _frictionless(machine).with_drive(ConstantSpeed(1.0))
    why = smooth.why_no_rotating_frame()
    if why is not None or machine.n_balls == 0:
        raise ValueError("friction_margin of a machine needs balls and a balanced state of the machine without "
                         f"friction as a steady equilibrium: {why or 'the machine has no balls'}")
    cache: dict[float, MachineStick] = {}

    def stick(om):
        if om not in cache:
            cache[om] = MachineStick(machine.with_drive(ConstantSpeed(om)), om)
        return cache[om]

    def check(om, centre, offset, beyond):
        return _check(machine, stick(om), om, centre, offset, beyond, threads)

    if machine.n_balls > 2:
        return _searched_band(machine, smooth, speeds, stick, (lambda om, pair: _release(
            machine, stick(om), om, pair, threads)) if simulate else None)
    out = stuck_band(machine.n_balls, speeds, grid=grid, simulate=simulate,
                     terms=lambda om, psi: stick(float(om)).terms(psi), check=check,
                     centre=lambda om: smooth.with_drive(ConstantSpeed(om)).balanced_angles())
    out["search"] = f"a grid of {grid} points per ball angle"
    return out


def balanced_family(smooth, starts: int = BALANCED_STARTS) -> list[np.ndarray]:
    """Distinct balanced arrangements of the machine without friction (seeded least-squares solves)."""
    found: list[np.ndarray] = []
    for seed in range(starts):
        psi = smooth.balanced_angles(starts=16, seed=seed)
        if psi is not None and all(np.abs(np.angle(np.exp(1j * (psi - q)))).max() > 1e-6 for q in found):
            found.append(psi)
    return found


def _either_side(stick, res):
    """Arrangements just inside the stuck set at the worst one and just outside, or None: from the worst
    arrangement in the least-norm direction that lowers every margin holding it on the edge at the same
    rate (a step of CHECK_STEP of its offset from the balanced start, less until every ball sticks), and
    as far the other way."""
    from rotorlab.analyses._friction_margin import CHECK_STEP

    x, centre = res["worst_at"], res["centre"]
    margin = stick.terms(x)[1]
    active = margin > -1e-6 * stick.kap
    h = 1e-7
    grads = np.array([(stick.terms(x + h * e)[1] - stick.terms(x - h * e)[1]) / (2 * h) for e in np.eye(x.size)]).T
    if not active.any():
        return None
    d = -np.linalg.lstsq(grads[active], np.ones(int(active.sum())), rcond=None)[0]  # every held margin grows
    d = d / np.linalg.norm(d) * CHECK_STEP * np.linalg.norm(x - centre)
    for _ in range(20):
        inside, outside = x + d, x - d
        if np.all(stick.terms(inside)[1] < 0.0) and not np.all(stick.terms(outside)[1] <= 0.0):
            return inside, outside
        d = 0.5 * d
    return None


def _searched_band(machine, smooth, speeds, stick, release) -> dict:
    """The band of three or more balls, per speed, by :func:`._friction_search.worst_stuck`."""
    from rotorlab.analyses._friction_search import worst_stuck
    from rotorlab.models import ConstantSpeed

    n, ns = machine.n_balls, len(speeds)
    low, high, worst_at = (np.full((ns, n), np.nan) for _ in range(3))
    worst = np.full(ns, np.nan)
    inside, outside = np.full(ns, -1, dtype=np.int64), np.full(ns, -1, dtype=np.int64)
    runs, kept = [], []
    for i, om in enumerate(speeds):
        st = stick(float(om))
        starts = balanced_family(smooth.with_drive(ConstantSpeed(float(om))))
        if not starts:
            continue
        res = worst_stuck(st.holding, starts, scale=float(st.kap.max()))
        runs.append(res["runs"])
        kept.append(res["kept"])
        if not np.isfinite(res["worst"]):
            continue
        worst[i], low[i], high[i] = res["worst"], res["low"], res["high"]
        worst_at[i] = res["worst_at"] - res["centre"]
        pair = _either_side(st, res)
        if release is not None and pair is not None:
            inside[i], outside[i] = release(float(om), pair)
    return {"band_low": low, "band_high": high, "worst_residual": worst, "worst_angles": worst_at,
            "check_inside": inside, "check_outside": outside,
            "coordinates": [f"psi_{k + 1}" for k in range(n)], "residual": "largest node deflection", "units": "m",
            "search": f"SLSQP: {min(runs, default=0)}+ climbs from the balanced family per speed, "
                      f"{min(kept, default=0)}+ ended stuck"}  # fmt: skip


def _check(machine, stick, om, centre, offset, beyond, threads):
    """Release the balls stuck at (1 - CHECK_STEP) times the worst ``offset`` (must stay) and at ``beyond``
    (must move), the structure on its locked response; 1 agrees, 0 not, -1 failed."""
    from rotorlab.analyses._friction_margin import CHECK_STEP

    outside = (1.0 + CHECK_STEP) * offset if beyond is None else beyond
    return _release(machine, stick, om, (centre + (1.0 - CHECK_STEP) * offset, centre + outside), threads)


def _release(machine, stick, om, pair, threads):
    """Release the balls stuck at the two arrangements of ``pair`` (inside: must stay; outside: must move),
    the structure on its steady response; per arrangement 1 agrees, 0 not, -1 failed."""
    from rotorlab.analyses._friction_margin import CHECK_REVOLUTIONS
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
    from rotorlab.models import ConstantSpeed

    m = machine.with_drive(ConstantSpeed(om))
    lay = m.layout
    nz, nb = lay.n_z, lay.n_balls
    starts = []
    for psi in pair:
        y = np.zeros(lay.n_state)
        z = stick.coordinates(psi)
        y[:nz] = z
        y[nz:2 * nz] = m._rot_pairs(z, om)  # standing still in the co-rotating frame
        y[lay.i_phi:lay.i_phi + nb] = psi
        y[lay.i_w:lay.i_w + nb] = om
        starts.append(m.initial_modes(0.0, y))  # the kernel's own stick test: stuck inside, slipping outside
    t_end = CHECK_REVOLUTIONS * 2.0 * math.pi / om
    # the scalar driver (two trajectories): the copy `solve` and the machine tests build for this layout
    sol = solve_ensemble(m, np.array(starts), (0.0, t_end), save_at=SaveAt(ts=[t_end]),
                         control=StepControl(rtol=1e-9, atol=1e-12), threads=threads, lanes=None)  # fmt: skip
    ok = np.asarray(sol.status) >= 0
    yf = np.asarray(sol.y_final)
    balls = slice(lay.i_phi, lay.i_phi + nb)
    moved = np.abs(yf[:, balls] - om * t_end - np.array(starts)[:, balls]).max(axis=1)
    return (int(moved[0] < 1e-9) if ok[0] else -1), (int(moved[1] > 1e-6) if ok[1] else -1)
