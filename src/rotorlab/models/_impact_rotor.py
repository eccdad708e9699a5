r"""Centrifuge rotor kicked by stones and striking its conical housing (``impact_rotor``, seed 001).

The rotor of a stone-crusher centrifuge (Krasnov, Tovstik & Tovstik 2003) is a dynamically
symmetric rigid body (mass m, transverse and polar moments of inertia A1 = A2, A3) spinning at
the constant speed omega0 about the vertical k. Two ring membranes at the heights h1, h2 (from
the centre of mass) hold it upright; every stone its accelerator throws pushes it sideways; when
the pushes are strong enough the circle of the gap point P (radius r_P, height h_P) strikes the
conical housing (gap Delta along the cone normal, half-angle measured by beta).

Small motions in the frame rotating at omega0 are the displacement u = u1 i + u2 j of the centre
of mass and the tilt t = t1 i + t2 j of the axis (t1, t2: small rotations of the axis in the
planes XZ, YZ; a point at height z moves by u + z t horizontally). The state, the packed
parameters and the kernels are in :mod:`rotorlab._kernels.impact_rotor`.

Equations (seed 001, numbers as printed)
----------------------------------------
::

    (2.2)  m (u'' + 2 w0 x u' - w0^2 u)               = F_m + F_q + F_c
           A1 t'' - (A3 - 2 A1) w0 x t' - (A1 - A3) w0^2 t = M_m + M_q + M_c
    (4.1)  F_m = -c L(u + n_m t),   M_m = n_m F_m - c_* L(t),   L(x) = x + (gamma/w0)(x' + w0 x x)
           c = c1 + c2, n_m = (c1 h1 + c2 h2)/c, c_* = c1 c2 (h1 - h2)^2 / c
    (4.2)  F_q = sum_n m_n w0^2 R_q P(alpha_n k) J(w0 (t - t_n)),   M_q = h_q F_q
    (3.2)  w = u sin(beta) + l_P t,  l_P = r_P cos(beta) + h_P sin(beta);  impact when |w| = Delta,
           at the angle phi of w
    (3.9)  S_n = (1 + k) m* v_P,  1/m* = sin^2(beta)/m + l_P^2/A1
           u'+ = u'- - (S_n/m)(sin(beta) e + f e_perp),  t'+ = t'- - (S_n/A1)(l_P e + f h_P e_perp)

with ``w0 = omega0 k``, moments written as the plane vectors ``M = M_y i - M_x j`` of (2.3),
``e = (cos phi, sin phi)`` the direction of w and ``e_perp = k x e`` the direction in which the
material point P slides over the housing (its speed omega0 r_P dwarfs the vibration). In the
translational variant the tilt is frozen (t = 0, ``1/m* = sin^2(beta)/m``).

Reconstructions of garbled formulas
-----------------------------------
The OCR of the paper garbles four formulas; each is rebuilt from mechanics and checked:

1. **(3.9), impact map.** Printed: ``Sn = (1 + k)m* vp``, ``sin^ ll_ m* m Ai'`` and four lines
   ``«+ = «p Sn m``, ``t+ = t1- Sn``. Reconstructed: integrating (2.2) over the impact with the
   impulse ``S = -S_n n - f S_n e_perp`` (3.6)-(3.7) at R_P gives the plane impulse
   ``-S_n (sin(beta) e + f e_perp)`` and the plane moment ``R_P x S = -S_n (l_P e + f h_P e_perp)``
   (in the (2.3) convention); the normal speed ``v_P = e . w'`` then changes by ``-S_n/m*`` with
   ``1/m* = sin^2(beta)/m + l_P^2/A1`` (friction acts along e_perp and does not change it), so
   (3.5) ``v+ = -k v-`` gives ``S_n = (1 + k) m* v-``. Checked: the normal speed after the map is
   exactly ``-k v-``; with k = 1, f = 0 the Jacobi energy (:meth:`ImpactRotor.jacobi_energy`) is
   unchanged by any impact and conserved over thousands of impacts; with k < 1 its loss equals the
   sum of ``1/2 m* (1 - k^2) v^2`` (``tests/validation/test_impact_energy.py``).
2. **(4.1), membrane forces with Sorokin's internal friction.** Printed (OCR):
   ``Fm = -c I ит + — {ит + x ит) ), ^о``, ``м = -сЛ t + ^-(t + c¿¿0 xt) )+hmF``, ``—c(u + nmt)``.
   Reconstructed: ``F_m = -c (u_m + (gamma/w0)(u_m' + w0 x u_m))``, ``u_m = u + n_m t``, and
   ``M_m = -c_* (t + (gamma/w0)(t' + w0 x t)) + n_m F_m``. Mechanics: each membrane at height
   h_i acts with ``-c_i L(u + h_i t)`` at that height, and ``u' + w0 x u`` is the velocity
   relative to the fixed membrane seen in the rotating frame, so the friction is a viscous force
   ``c gamma / w0`` of the *non-rotating* membranes (Sorokin's loss factor gamma at the frequency
   w0). Summing the membranes gives exactly the printed c, n_m and c_* (checked symbolically by
   ``c_* + c n_m^2 = c1 h1^2 + c2 h2^2`` in ``test_impact_frames.py``). Checked: the rotating-
   frame solution equals the inertial-frame equations (fixed viscous damping, gyroscopic
   ``A1 tau'' - i A3 w0 tau' = M``) integrated by scipy and rotated
   (``tests/validation/test_impact_frames.py``).
3. **(4.3), the stone on its guide.** Printed: ``dv/dT = r cos a - Ft, dr/dT = v cos a`` with
   ``tg a = r dphi/dr, Ft = fq Fn, Fn = Kv +2v + r sin a``. Reconstructed: ``F_n = kappa v^2 +
   2 v + r sin a`` (the OCR lost the square of the centripetal term ``kappa v^2``), in units of
   R_q, tau = w0 t, per unit stone mass: guide reaction normal to the guide = curvature term +
   Coriolis ``2 v`` + the component ``r sin a`` of the centrifugal force. For the logarithmic
   spiral ``r = r0 exp(phi cot a)`` the curvature is ``kappa = sin(a) / r``. Checked: the motor
   work on one stone equals its kinetic-energy gain in the fixed frame plus the heat of guide
   friction (``tests/validation/test_impact_stones.py``).
4. **J(tau), push of one stone on the rotor.** Printed (OCR): ``J_x = F_n sin(phi + a) -
   [..] cos(phi + a), J_y = -F_n cos(phi + a) - [..] sin(phi + a)`` with the friction term
   dropped. Reconstructed: by Newton's third law the rotor receives ``-F_n e_n + F_t e_t`` with
   ``e_t = (cos(phi + a), sin(phi + a))`` along the guide and ``e_n = k x e_t``:
   ``J_x = F_n sin(phi + a) + F_t cos(phi + a)``, ``J_y = -F_n cos(phi + a) + F_t sin(phi + a)``
   (friction drags the guide *outwards*, the way the stone slides). Checked by the same energy
   balance (the printed sign of F_t adds ``2 int r F_t sin(a) dtau``, 81 % too much), see
   :func:`stone_push` and ``test_impact_stones.py``.

Parameters the paper does not give are explicit, with defaults documented on
:class:`StoneFeed` (start radius and speed of a stone on its guide, number N of guides, the guide
sequence, the first stone time, spreads of mass and time) and :class:`Housing` (the speed
thresholds of chatter and of impact counting, the backward-whirl limit).

Sliding contact
---------------
When an impact would rebound slower than ``rest_speed`` (an accumulation of impacts, k^n -> 0),
the rotor is put in sustained contact: P stays on the housing (|w| = Delta), the normal force is
``N = m* (e . w''_free + (|w'|^2 - (e . w')^2) / Delta)`` with friction ``f N`` along
``-e_perp``, and the rotor leaves the housing when N would pull (N = 0). The contact force and
moment are those of (3.9) with S_n -> N. The friction force ``-f N e_perp`` assumes that the
contact point slides forwards over the housing (the surface speed ``r_P omega0`` dwarfs the
vibration). When a sliding contact whirls backwards, friction drives it further backwards; the
faster it whirls, the larger N (centripetal term) and the friction, and nothing in the sliding
law limits it (the whirl speed grows to ~1e12 rad/s within a second). The theory says where that
law ends: where the slip of P over the housing (:func:`rotorlab._kernels.impact_rotor.slip_speed`,
the surface speed ``r_P omega0`` plus the vibration of the material point P) vanishes, the rotor
rolls on the housing, the dry-friction backward whirl ``-(R / delta) Omega`` (Black 1968, Crandall
1990; see :func:`rotorlab.contact.rolling_whirl`), which this sliding model cannot carry. The run
is stopped exactly there (the event ``backward_whirl`` is the slip itself) and flagged. Without
tilt (the translational model, ``w = sin(beta) u``) this is the whirl speed
``r_P sin(beta) omega0 / Delta`` (:meth:`Housing.rolling_whirl_speed`); with tilt the material
point P also moves with ``h_P t'``, which is not along ``w``, so the whirl speed at which P rolls
differs from it (over the 6 stopped runs of 16 (2 and 3 kg, seed 0, 10 s) the slip vanishes
0.36 ms after the whirl passes that speed, with the same impact counts). A ``whirl_limit`` replaces the criterion by a threshold on the backward whirl
speed of the contact point. The impacts counted are the same whichever stop ends the slide,
since a sliding contact makes no impacts: over 16 runs (2 and 3 kg, seed 0, 10 s) the former
empirical limit 2 omega0, the slip criterion and no limit at all flag the same runs with the same
counts (``tests/validation/test_impact_whirl.py``).

Impacts are the shared contact law (:mod:`rotorlab._kernels.contact`), which is (3.9) while P
slides forwards. Its friction impulse sticks when the slip of P vanishes: the rotor then rolls
on the housing, the same dry-friction backward whirl reached through impacts instead of
sliding (with restitution 1 and heavy stones, where no accumulation turns into sliding), and
the run is stopped and flagged there too. Seed 001's own map, friction always along
``-e_perp``, pushed such a run past rolling (friction along the slip, energy from nowhere) until
P went through the housing (issue 14: 1.4 million impacts, 2e6 m); the energy ledger
(:mod:`rotorlab._kernels.impact_rotor`) and :meth:`ImpactRotor.impossible_states` fail any run
that creates energy or passes the housing.

Energy
------
The motor keeps omega0 constant; it spends ``m_n w0^2 R_q^2 W`` on each stone (W from
:func:`stone_push`) and ``f r_P w0 (sum S_n + int N dt)`` on friction at the housing. Their ratio
is the paper's eta (Fig. 5).

References
----------
Krasnov A. A., Tovstik P. E., Tovstik T. P. Dynamics of a centrifuge with impacts. Vestnik
St. Petersburg Univ., Ser. 1, 2003, no. 3 (17), eqs. (2.1)-(4.3), section 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from rotorlab._kernels import impact_rotor as _k
from rotorlab.models._base import EventSpec, Kernels
from rotorlab.models._impact_ledger import impossible_states
from rotorlab.models._impact_params import CentrifugeRotor, Housing
from rotorlab.models._impact_reconstructions import RECONSTRUCTIONS, Reconstruction
from rotorlab.models._impact_stones import StoneFeed, StonePush, StoneSequence, stone_push
from rotorlab.models._parameters import impact_slots
from rotorlab.models._protocol import ParametrisedMixin

__all__ = [
    "CentrifugeRotor",
    "Housing",
    "StoneFeed",
    "StoneSequence",
    "StonePush",
    "ImpactRotor",
    "stone_push",
    "krasnov_crusher",
    "EVENT_NAMES",
    "STATE_NAMES",
    "RECONSTRUCTIONS",
    "Reconstruction",
]

#: Event functions of the model, in kernel order.
EVENT_NAMES = ("impact", "lift_off", "stone", "backward_whirl", "whirl_reverse")

#: Names of the state entries, in kernel order.
STATE_NAMES = (
    "u1", "u2", "t1", "t2", "du1", "du2", "dt1", "dt2", "int_contact_force", "work_stones",
    "work_nonconservative", "mode", "i_breakpoint", "t_reset", "n_impacts", "n_impacts_all", "n_slides",
    "t_slide_start", "t_sliding", "impulse_sum", "e_restitution", "v_max", "penetration_max", "whirl",
    "energy_start", "work_drive", "e_friction", "e_projection", "t_before_runaway",
    "n_impacts_before_runaway", "n_impacts_all_before_runaway", "work_drive_before_runaway",
    "int_contact_force_before_runaway",
)  # fmt: skip

_KERNELS = Kernels(
    rhs=_k.rhs,
    n_state=_k.N_STATE,
    n_discrete=_k.N_DISCRETE,
    events=_k.events,
    reset=_k.reset,
    event_specs=tuple(EventSpec(name, -1, "reset") for name in EVENT_NAMES),
)


# ----------------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class ImpactRotor(ParametrisedMixin):
    """The centrifuge rotor with stones and housing: the model object the integrator runs.

    Parameters
    ----------
    rotor : CentrifugeRotor
    housing : Housing
    stones : StoneFeed
    sequence : StoneSequence
        The stones of this run (default none: :meth:`with_stones` draws them).

    Notes
    -----
    State and packed parameters: :mod:`rotorlab._kernels.impact_rotor`. Events
    ``impact, lift_off, stone, backward_whirl, whirl_reverse`` (all resets; ``backward_whirl``
    stops the run).

    Examples
    --------
    >>> model = krasnov_crusher().with_stones(t_end=0.2, seed=3)
    >>> model.n_state, len(model.sequence), round(model.equivalent_mass, 2)
    (33, 5, 627.3)
    """

    rotor: CentrifugeRotor
    housing: Housing
    stones: StoneFeed
    sequence: StoneSequence = field(default_factory=StoneSequence)

    def __post_init__(self) -> None:
        for name, cls in (("rotor", CentrifugeRotor), ("housing", Housing), ("stones", StoneFeed),
                          ("sequence", StoneSequence)):  # fmt: skip
            if not isinstance(getattr(self, name), cls):
                raise ValueError(f"ImpactRotor.{name} must be a {cls.__name__}, got {type(getattr(self, name)).__name__}")
        if self.sequence.n_guides != self.stones.n_guides and len(self.sequence):
            raise ValueError("ImpactRotor.sequence must use the feed's n_guides")

    # ---- contract -----------------------------------------------------------------------------
    @property
    def kernels(self) -> Kernels:
        """Compiled kernels (shared by all instances)."""
        return _KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_NAMES

    @property
    def n_state(self) -> int:
        return _k.N_STATE

    @property
    def translational(self) -> bool:
        return self.rotor.translational

    @property
    def equivalent_mass(self) -> float:
        """m*, eq. (3.9) (kg): ``1/m* = sin^2(beta)/m + l_P^2/A1`` (no tilt term if translational)."""
        return 1.0 / self._inv_mstar()

    def _inv_mstar(self) -> float:
        sb = math.sin(self.housing.cone_angle)
        inv = sb * sb / self.rotor.mass
        if not self.translational:
            inv += self.housing.lever() ** 2 / self.rotor.inertia_transverse
        return inv

    def with_stones(self, t_end: float, seed: int | None = 0, **changes) -> ImpactRotor:
        """This model with the stones of a run to ``t_end`` drawn from ``seed``.

        Keyword arguments replace fields of the :class:`StoneFeed` first (e.g. ``mass=3.0``).
        """
        feed = replace(self.stones, **changes) if changes else self.stones
        return replace(self, stones=feed, sequence=feed.sequence(t_end, seed))

    def push(self) -> StonePush:
        """J(tau) of one stone (see :func:`stone_push`)."""
        return self.stones.push(self.rotor.spin_speed)

    def _parameter_slots(self):
        return impact_slots(self)

    def to_array(self) -> np.ndarray:
        """Packed parameters (layout in :mod:`rotorlab._kernels.impact_rotor`)."""
        r, h, s, seq = self.rotor, self.housing, self.stones, self.sequence
        w0 = r.spin_speed
        push = self.push()
        head = np.zeros(_k.P_HEADER)
        head[[_k.P_M, _k.P_A1, _k.P_A3, _k.P_W0, _k.P_C, _k.P_NM, _k.P_CS, _k.P_GAM]] = (
            r.mass, r.inertia_transverse, r.inertia_polar, w0, r.stiffness, r.membrane_offset,
            r.tilt_stiffness, r.internal_friction,
        )  # fmt: skip
        head[[_k.P_SB, _k.P_CB, _k.P_LP, _k.P_HP, _k.P_RP, _k.P_GAP, _k.P_K, _k.P_F]] = (
            math.sin(h.cone_angle), math.cos(h.cone_angle), h.lever(), h.height, h.radius, h.gap,
            h.restitution, h.friction,
        )  # fmt: skip
        head[_k.P_IMS] = self._inv_mstar()
        head[_k.P_HQ] = s.height
        head[_k.P_TRANS] = 1.0 if r.translational else 0.0
        head[_k.P_VREST] = h.rest_speed
        head[_k.P_VCOUNT] = h.count_speed
        head[_k.P_WHIRL] = h.rolling_whirl_speed(w0) if h.whirl_limit is None else h.whirl_limit
        head[_k.P_SLIPSTOP] = 1.0 if h.whirl_limit is None else 0.0
        head[_k.P_TAUEND] = push.tau_end
        # stones: t_n, m_n w0^2 R_q, cos(alpha_n), sin(alpha_n)
        n = len(seq)
        ang = seq.angles()
        stones = np.column_stack([seq.times, seq.masses * w0 * w0 * s.radius, np.cos(ang), np.sin(ang)])
        bp, active = _breakpoints(seq.times, push.tau_end / w0)
        n_act = active.shape[1]
        tab = np.column_stack([push.jx, push.jy, push.djx, push.djy])
        o_st = _k.P_HEADER
        o_bp = o_st + 4 * n
        o_act = o_bp + bp.size
        o_tab = o_act + active.size
        head[[_k.P_NST, _k.P_OST, _k.P_NBP, _k.P_OBP, _k.P_OACT, _k.P_NACT, _k.P_NTAB, _k.P_OTAB, _k.P_DTAU]] = (
            n, o_st, bp.size, o_bp, o_act, n_act, push.tau.size, o_tab, push.tau[1] - push.tau[0],
        )  # fmt: skip
        return np.concatenate([head, stones.ravel(), bp, active.ravel().astype(float), tab.ravel()])

    def impossible_states(self, ys, y_final, t_final, params) -> list[str]:
        """Sanity monitor (kernel contract item 6): runs whose result is physically impossible.

        The gap point P deeper in the housing than the clearance, or energy created beyond the
        ledger's bound; the checks, their tolerance and the parameters are those of
        :func:`rotorlab.models._impact_ledger.impossible_states`.
        """
        return impossible_states(ys, y_final, t_final, params)

    def initial_state(self, u=(0.0, 0.0), tilt=(0.0, 0.0), du=(0.0, 0.0), dtilt=(0.0, 0.0)) -> np.ndarray:
        """State at rest (default) or with the given displacement, tilt and rates (SI).

        The rotor must start clear of the housing (``|w| < Delta``).
        """
        y = np.zeros(_k.N_STATE)
        y[_k.U1:_k.U2 + 1] = u
        y[_k.DU1:_k.DU2 + 1] = du
        if not self.translational:
            y[_k.T1:_k.T2 + 1] = tilt
            y[_k.DT1:_k.DT2 + 1] = dtilt
        y[_k.T_RESET] = -1.0
        y[_k.E_0] = self.fixed_energy(y)
        w = self.gap_vector(y)
        if np.hypot(*w) >= self.housing.gap:
            raise ValueError(f"initial state must be clear of the housing: |w| = {np.hypot(*w):.4g} m >= gap {self.housing.gap:g} m")
        return y

    # ---- physics helpers (numpy, for analyses and tests) ---------------------------------------
    def gap_vector(self, y) -> np.ndarray:
        """w = u sin(beta) + l_P t at states ``y`` (..., 28) -> (..., 2) (m)."""
        y = np.asarray(y, dtype=float)
        sb = math.sin(self.housing.cone_angle)
        lp = self.housing.lever()
        return sb * y[..., 0:2] + lp * y[..., 2:4]

    def jacobi_energy(self, y) -> np.ndarray:
        """Energy of the small motions in the rotating frame (J), conserved without gamma, f, stones.

        ``1/2 m |u'|^2 + 1/2 A1 |t'|^2 + 1/2 c |u + n_m t|^2 + 1/2 c_* |t|^2 - 1/2 m w0^2 |u|^2
        + 1/2 (A3 - A1) w0^2 |t|^2``.
        """
        y = np.asarray(y, dtype=float)
        r = self.rotor
        w0 = r.spin_speed
        u, t, du, dt = y[..., 0:2], y[..., 2:4], y[..., 4:6], y[..., 6:8]
        um = u + r.membrane_offset * t

        def sq(v):
            return np.sum(v * v, axis=-1)

        return (0.5 * r.mass * sq(du) + 0.5 * r.inertia_transverse * sq(dt) + 0.5 * r.stiffness * sq(um)
                + 0.5 * r.tilt_stiffness * sq(t) - 0.5 * r.mass * w0 * w0 * sq(u)
                + 0.5 * (r.inertia_polar - r.inertia_transverse) * w0 * w0 * sq(t))  # fmt: skip

    def fixed_energy(self, y) -> np.ndarray:
        """Vibration energy in the fixed frame at states ``y`` (..., 28) (J).

        ``1/2 m |X'|^2 + 1/2 A1 |T'|^2 + 1/2 c |u + n_m t|^2 + 1/2 c_* |t|^2`` with the
        fixed-frame velocities ``X' = u' + omega0 k x u``, ``T' = t' + omega0 k x t`` (the
        membranes are fixed, the gyroscopic moment does no work); the energy ledger of
        :mod:`rotorlab._kernels.impact_rotor` balances it. Conserved without stones, membrane
        friction and contact.
        """
        y = np.asarray(y, dtype=float)
        r = self.rotor
        w0 = r.spin_speed
        u, t, du, dt = y[..., 0:2], y[..., 2:4], y[..., 4:6], y[..., 6:8]
        x = du + w0 * np.stack([-u[..., 1], u[..., 0]], axis=-1)
        um = u + r.membrane_offset * t

        def sq(v):
            return np.sum(v * v, axis=-1)

        e = 0.5 * r.mass * sq(x) + 0.5 * r.stiffness * sq(um)
        if not self.translational:
            s = dt + w0 * np.stack([-t[..., 1], t[..., 0]], axis=-1)
            e = e + 0.5 * r.inertia_transverse * sq(s) + 0.5 * r.tilt_stiffness * sq(t)
        return e

    def stone_energy(self, t_end: float) -> float:
        """Energy the motor spends on the stones landed before ``t_end`` (J), partial last ones."""
        push = self.push()
        w0 = self.rotor.spin_speed
        seq = self.sequence
        tau = np.clip(w0 * (t_end - seq.times), 0.0, push.tau_end)
        frac = np.interp(tau, push.tau, push.work)
        return float(np.sum(seq.masses * (self.stones.radius * w0) ** 2 * frac))

    def state_matrix(self) -> np.ndarray:
        """A of the free small motions ``x' = A x``, x = (u, t, u', t') in the rotating frame.

        Without stones and contact; exact (the equations are linear), from the compiled kernel.

        Returns
        -------
        ndarray, shape (8, 8)

        Examples
        --------
        >>> a = krasnov_crusher().state_matrix()
        >>> bool(np.all(np.linalg.eigvals(a).real < 0))
        True
        """
        base = replace(self, sequence=StoneSequence(n_guides=self.stones.n_guides))
        p = base.to_array()
        out = np.empty(_k.N_STATE)
        a = np.zeros((8, 8))
        for j in range(8):
            y = base.initial_state()
            y[j] = 1.0
            _k.rhs(0.0, y, p, out)
            a[:, j] = out[:8]
        if self.translational:  # the tilt is frozen
            a[:, [2, 3, 6, 7]] = 0.0
            a[[2, 3, 6, 7], :] = 0.0
        return a

    def linearize(self):
        """M, C, G, K of the free small motions in the rotating frame (no stones, no contact).

        ``M q'' + (C + G) q' + K q = 0`` for ``q = (u1, u2, t1, t2)`` (translational model:
        ``q = (u1, u2)``); the equations are linear, so this is exact.

        Returns
        -------
        rotorlab.models.Linearization
            ``M = diag(m, m, A1, A1)`` (kg, kg m^2); ``C = (gamma / omega0) S`` (Sorokin's internal
            friction, symmetric); ``G`` skew: ``2 m omega0`` between u1, u2 (Coriolis) and
            ``(A3 - 2 A1) omega0`` between t1, t2 (gyroscopic, rotating frame); ``K = S - diag(m
            omega0^2, m omega0^2, (A1 - A3) omega0^2, ...) + gamma J S``: membrane stiffness ``S``
            (c on u, ``c n_m`` coupling, ``c n_m^2 + c_*`` on t), the centrifugal softening and
            the circulatory part of the internal friction (``J`` turns axis 1 into axis 2);
            ``A = [[0, I], [-M^-1 K, -M^-1 (C + G)]]`` equals :meth:`state_matrix`.

        References
        ----------
        Krasnov, Tovstik & Tovstik (2003), eqs (2.2), (4.1) as reconstructed in this module.

        Examples
        --------
        >>> lin = krasnov_crusher().linearize()
        >>> lin.M.shape, bool(np.allclose(lin.G, -lin.G.T)), bool(np.allclose(lin.A, krasnov_crusher().state_matrix()))
        ((4, 4), True, True)
        """
        from rotorlab.models._jeffcott_physics import Linearization

        r = self.rotor
        m, a1, a3, w0, gam = r.mass, r.inertia_transverse, r.inertia_polar, r.spin_speed, r.internal_friction
        c, nm, cs = r.stiffness, r.membrane_offset, r.tilt_stiffness
        n = 2 if r.translational else 4
        s2 = np.array([[c, c * nm], [c * nm, c * nm * nm + cs]])[: n // 2, : n // 2]  # one axis: (u, t)
        S = np.zeros((n, n))
        circ = np.zeros((n, n))
        for a in range(2):
            dofs = [a, 2 + a][: n // 2]
            S[np.ix_(dofs, dofs)] = s2
            other = [1 - a, 3 - a][: n // 2]
            circ[np.ix_(dofs, other)] = (-1.0 if a == 0 else 1.0) * s2
        M = np.diag([m, m, a1, a1][:n])
        G = np.zeros((n, n))
        G[1, 0], G[0, 1] = 2.0 * m * w0, -2.0 * m * w0
        if n == 4:
            g = (a3 - 2.0 * a1) * w0
            G[2, 3], G[3, 2] = g, -g
        K = S - np.diag([m * w0**2, m * w0**2, (a1 - a3) * w0**2, (a1 - a3) * w0**2][:n]) + gam * circ
        C = (gam / w0) * S
        minv = np.diag(1.0 / np.diag(M))
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ K, -minv @ (C + G)]])
        return Linearization(A=A, M=M, C=C, G=G, K=K, spin_speed=w0, residual=np.zeros(2 * n))

    def rhs(self, t: float, y) -> np.ndarray:
        """dy/dt at one state (calls the compiled kernel)."""
        out = np.empty(_k.N_STATE)
        _k.rhs(float(t), np.asarray(y, dtype=float), self.to_array(), out)
        return out


def _breakpoints(times: np.ndarray, duration: float) -> tuple[np.ndarray, np.ndarray]:
    """Sorted distinct arrival/departure times and the stones active after each of them.

    Returns ``bp`` (n_bp,) and ``active`` (n_bp + 1, n_act) with -1 padding; row i lists the
    stones on their guides after i breakpoints have passed.
    """
    n = times.size
    if n == 0:
        return np.empty(0), np.full((1, 1), -1.0)
    ends = times + duration
    bp = np.unique(np.concatenate([times, ends]))
    rows: list[list[int]] = [[]]
    for tb in bp:
        act = np.nonzero((times <= tb) & (ends > tb))[0]
        rows.append(act.tolist())
    n_act = max(1, max(len(r) for r in rows))
    active = np.full((len(rows), n_act), -1.0)
    for i, r in enumerate(rows):
        active[i, : len(r)] = r
    return bp, active


def krasnov_crusher(*, translational: bool = False, stone_mass: float = 0.7, interval: float = 0.035,
                    internal_friction: float = 0.2, restitution: float = 0.5, friction: float = 0.2,
                    **feed) -> ImpactRotor:  # fmt: skip
    """The stone-crusher rotor of seed 001, section 5 (its translational variant on request).

    Parameters
    ----------
    translational : bool
        The paper's variant with the axis translating: h1 = -h2 = 0.15 m, h_q = 0, beta = 90 deg
        and the tilt frozen.
    stone_mass, interval, internal_friction, restitution, friction : float
        m_q (kg), Delta t (s), gamma, k, f; defaults the section-5 values.
    **feed
        Other :class:`StoneFeed` fields (``n_guides``, ``start_radius``, ...).

    Returns
    -------
    ImpactRotor
        Without stones; draw them with :meth:`ImpactRotor.with_stones`.

    Examples
    --------
    >>> m = krasnov_crusher()
    >>> round(m.housing.lever(), 4), m.rotor.spin_speed, m.stones.mass
    (0.1947, 160.0, 0.7)
    >>> round(krasnov_crusher(translational=True).equivalent_mass, 1)
    635.7
    """
    h1, h2, hq, beta = (0.15, -0.15, 0.0, 90.0) if translational else (-0.05, 0.2, 0.28, 55.0)
    rotor = CentrifugeRotor(635.7, 70.35, 115.68, 160.0, 3.22e6, 3.22e6, h1, h2, internal_friction,
                            translational)  # fmt: skip
    housing = Housing(0.625, -0.2, 4.5e-3, math.radians(beta), restitution, friction)
    stones = StoneFeed(stone_mass, interval, 0.6, hq, math.radians(30.0), 0.5, **feed)
    return ImpactRotor(rotor, housing, stones)
