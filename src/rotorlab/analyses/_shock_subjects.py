r"""What :func:`rotorlab.analyses.shock_margin` needs of a model, one class per model type.

The shock margin is the same computation for every balancer whose balanced state is an
equilibrium of the co-rotating frame; what differs between model types is registered here
(:func:`register_shock_subject`, looked up by the model's class):

* the balanced state at a speed: the state the simulations start from, its linearization in the
  co-rotating frame, the balanced ball angles and the jump of both states per N s of a lateral
  impulse on the rotor (``M dq' = (B^T e_beta, 0)``, B the station's lateral displacement);
* the packed parameters at a speed, with the load-shifted unbalance;
* where a simulation ended: ball angles from the rotor (co-rotating), the rotor's deflection
  and the balls' largest rate relative to it, and its label;
* the load-shift bound ``S(beta)`` (kg m).

``jeffcott_balls`` runs in its co-rotating frame (the disc centre is the station; beta from the
unbalance). A ``machine`` runs in the fixed frame from the co-rotating balanced state at t = 0
(where the frames coincide); the knock and the load shift act at the station of its first
unbalance, beta from that unbalance's direction. Where the machine's races and unbalances are all
in that one plane (one race) the load-shift bound is the closed form of
:func:`rotorlab.analyses._shock_margin.load_shift_bound` on the resultant unbalance, else the
smallest shift for which :meth:`Machine.balanced_angles` finds no balance (bisection).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

__all__ = ["Balanced", "register_shock_subject", "shock_subject", "JeffcottSubject", "MachineSubject"]

_SUBJECTS: dict[type, type] = {}


def register_shock_subject(model_type: type, subject: type) -> None:
    """Make ``subject(model)`` the shock-margin view of models of ``model_type`` (and subclasses)."""
    _SUBJECTS[model_type] = subject


def shock_subject(model):
    """The registered shock-margin view of ``model`` (ValueError naming the type if there is none)."""
    for cls in type(model).__mro__:
        if cls in _SUBJECTS:
            return _SUBJECTS[cls](model)
    raise ValueError(f"shock_margin needs a jeffcott_balls rotor or a machine with balls, got {type(model).__name__}")


@dataclass(frozen=True)
class Balanced:
    """The balanced state at one speed (see the module docstring).

    ``y`` the simulated model's start state; ``lin`` its co-rotating linearization; ``angles``
    (rad) the balanced ball angles; ``psi`` the ball angles' slice of ``lin``'s state; ``unit``
    (2, n_lin) and ``kick`` (2, n_state) the jumps of ``lin``'s and of the simulated state per
    N s of impulse along the co-rotating axes (x: the unbalance direction); ``rate`` (1/s) the
    slowest decay.
    """

    y: np.ndarray
    lin: Any
    angles: np.ndarray
    psi: slice
    unit: np.ndarray
    kick: np.ndarray
    rate: float


def _axes(phase: float) -> np.ndarray:
    """Unit vectors along and across a direction: the co-rotating axes of beta = 0 and 90 deg."""
    return np.array([[math.cos(phase), math.sin(phase)], [-math.sin(phase), math.cos(phase)]])


class JeffcottSubject:
    """``jeffcott_balls`` without friction, simulated in its co-rotating frame."""

    def __init__(self, model):
        from rotorlab.models import ConstantSpeed

        if model.n_balls == 0 or model.has_friction:
            raise ValueError("shock_margin needs balls without Coulomb friction (friction = 0)")
        self.model = model
        self.sim = model.with_frame("rotating").with_speed(ConstantSpeed(model.critical_speed))
        self.n_balls = model.n_balls
        self.imbalance = float(model.imbalance)
        self.moments = np.array([b.static_moment for b in model.balls])
        self.capacity = float(self.moments.sum())
        self.critical_speed = float(model.critical_speed)
        self.station = "the disc centre"
        self.races = np.zeros(self.n_balls, dtype=int)

    def balanced(self, om: float, unbalance: complex | None = None) -> Balanced | None:
        from rotorlab.analyses._shock_margin import balanced_angles
        from rotorlab.explore._settle import slowest_decay_rate

        rot = self.sim if unbalance is None else self._shifted(abs(unbalance))
        angles = balanced_angles(rot, om)
        if angles is None:
            return None
        y = rot.initial_state(angles)
        lin = rot.linearize(y, om)
        rate = slowest_decay_rate(lin.eigenvalues)
        if rate is None:
            return None
        n = self.n_balls
        dq = np.linalg.solve(lin.M, np.vstack([np.eye(2), np.zeros((n, 2))])).T  # (2, 2 + n)
        kick = np.zeros((2, y.size))
        kick[:, 2:4], kick[:, 4 + n : 4 + 2 * n] = dq[:, :2], dq[:, 2:]
        return Balanced(y, lin, angles, slice(4, 4 + n), kick, kick, rate)

    def _shifted(self, imbalance: float):
        r = self.sim.rotor
        return replace(self.sim, rotor=replace(r, eccentricity=imbalance / r.disc_mass))

    def params(self, om: float, unbalance: complex | None = None) -> np.ndarray:
        extra = {} if unbalance is None else {"eccentricity": abs(unbalance) / self.sim.rotor.disc_mass}
        return self.sim.pack({"speed.speed": float(om), **extra})

    def shift_start(self, y: np.ndarray, unbalance: complex) -> np.ndarray:
        """The old balanced state with its ball angles measured from the new unbalance."""
        y = np.array(y, dtype=float)
        y[4 : 4 + self.n_balls] -= np.angle(unbalance)
        return y

    def unbalance(self, shift: complex) -> complex:
        """The unbalance (kg m, co-rotating, x along the old one) after a shift ``shift``."""
        return self.imbalance + shift

    def ends(self, yf: np.ndarray, t_end: np.ndarray, om: np.ndarray):
        n = self.n_balls
        return yf[:, 4 : 4 + n], np.hypot(yf[:, 0], yf[:, 1]), np.abs(yf[:, 4 + n : 4 + 2 * n]).max(axis=1)

    def reference(self, unbalances, om) -> np.ndarray:
        from rotorlab.explore._outcome import reference_amplitude

        r = self.sim.rotor
        return reference_amplitude(np.abs(unbalances), r.stiffness, self.sim.total_mass, r.damping, om)

    def label(self, status: int, amp: float, ref: float, angles, rate: float, om: float) -> str:
        from rotorlab.explore._outcome import classify

        return classify(status, "", amp, ref, angles, rate, om)

    def load_shift_bound(self, directions) -> np.ndarray:
        from rotorlab.analyses._shock_margin import load_shift_bound

        return load_shift_bound(self.imbalance, self.moments, directions)


class MachineSubject:
    """A ``machine`` with balls and a co-rotating balanced state, simulated in the fixed frame."""

    def __init__(self, model):
        from rotorlab.models import ConstantSpeed

        if model.n_balls == 0 or not model.unbalances:
            raise ValueError("shock_margin needs a machine with balls (a race with balls) and an unbalance")
        probe = model.with_drive(ConstantSpeed(1.0)) if not isinstance(model.drive, ConstantSpeed) else model
        why = probe.why_no_rotating_frame()
        if why is not None:
            raise ValueError(f"shock_margin needs the machine's balanced state as an equilibrium: {why}")
        from rotorlab.models._machine_physics import structure_critical_speeds

        self.model = probe
        self.sim = probe.with_drive(ConstantSpeed(1.0))
        self.n_balls = model.n_balls
        u0 = model.unbalances[0]
        self.first = u0
        self.phase = float(u0.phase)
        self.axes = _axes(self.phase)
        res = sum(me * np.exp(1j * b) for _, _, me, b in probe._point_unbalances)
        self.imbalance = float(abs(res))
        self.resultant = complex(res)
        self.capacity = float(sum(r.capacity for r in model.races))
        crit = structure_critical_speeds(probe)
        self.critical_speed = float(crit[0]) if crit.size else math.nan
        self.B = probe.station_matrix(u0.node, u0.axial_offset)
        self.station = f"node {probe.structure.node_label[u0.node]}"
        self._nz = probe.n_coordinates
        self.races = probe._ball_arrays[4]
        n_u = len(probe._point_unbalances)
        planar = len(probe.races) == 1 and all(np.allclose(B, probe._stations[0]) for B in probe._stations[1 : 1 + n_u])
        self.moments = np.array([b.mass * probe.races[0].radius for b in probe.races[0].balls]) if planar else None

    def _machine(self, om: float, unbalance: complex | None = None):
        from rotorlab.models import ConstantSpeed

        m = self.sim if unbalance is None else self._shifted(unbalance)
        return m.with_drive(ConstantSpeed(float(om)))

    def _shifted(self, unbalance: complex):
        """The machine with its first unbalance ``unbalance`` (kg m, complex: magnitude and phase)."""
        first = replace(self.first, magnitude=float(abs(unbalance)), phase=float(np.angle(unbalance)))
        return replace(self.sim, unbalances=(first, *self.sim.unbalances[1:]))

    def unbalance(self, shift: complex) -> complex:
        """The first unbalance (kg m, fixed = co-rotating axes at t = 0) after a shift along beta from it."""
        return self.first.magnitude * np.exp(1j * self.phase) + shift * np.exp(1j * self.phase)

    def balanced(self, om: float, unbalance: complex | None = None) -> Balanced | None:
        from rotorlab.explore._settle import slowest_decay_rate

        m = self._machine(om, unbalance)
        angles = m.balanced_angles()
        if angles is None:
            return None
        yr = m.balanced_state(angles)
        lin = m.linearize(yr)
        rate = slowest_decay_rate(lin.eigenvalues)
        if rate is None:
            return None
        nz, nb = self._nz, self.n_balls
        rhs = np.zeros((nz + nb, 2))
        rhs[:nz] = (self.axes @ self.B).T
        dq = np.linalg.solve(lin.M, rhs).T  # (2, nz + nb): per N s along the two axes
        unit = np.zeros((2, yr.size))
        unit[:, nz : 2 * nz], unit[:, 2 * nz + nb :] = dq[:, :nz], dq[:, nz:]
        lay = m.layout
        kick = np.zeros((2, lay.n_state))
        kick[:, nz : 2 * nz], kick[:, lay.i_w : lay.i_w + nb] = dq[:, :nz], dq[:, nz:]
        return Balanced(m.rotating_to_fixed(yr), lin, angles, slice(2 * nz, 2 * nz + nb), unit, kick, rate)

    def params(self, om: float, unbalance: complex | None = None) -> np.ndarray:
        return self._machine(om, unbalance).to_array()

    def shift_start(self, y: np.ndarray, unbalance: complex) -> np.ndarray:
        return np.array(y, dtype=float)

    def ends(self, yf: np.ndarray, t_end: np.ndarray, om: np.ndarray):
        lay = self.sim.layout
        nb = self.n_balls
        psi = yf[:, lay.i_phi : lay.i_phi + nb] - (om * t_end)[:, None]
        amp = self.sim.station_amplitudes(yf).max(axis=1)
        rate = np.abs(yf[:, lay.i_w : lay.i_w + nb] - om[:, None]).max(axis=1)
        return psi, amp, rate

    def reference(self, unbalances, om) -> np.ndarray:
        """The largest node deflection with the balls locked (m), per (unbalance, speed)."""
        out = []
        for u, w in zip(np.atleast_1d(unbalances), np.atleast_1d(om)):
            m = self._machine(float(w), complex(u))
            out.append(float(np.abs(m._locked_response(float(w))).max()))
        return np.array(out)

    def label(self, status: int, amp: float, ref: float, angles, rate: float, om: float) -> str:
        from rotorlab.explore._outcome import machine_outcome

        return machine_outcome(status, amp, ref, rate, om, self.n_balls, self.critical_speed)

    def load_shift_bound(self, directions) -> np.ndarray:
        from rotorlab.analyses._shock_margin import load_shift_bound

        beta = np.asarray(directions, dtype=float)
        if self.moments is not None:
            return load_shift_bound(self.imbalance, self.moments, self.phase + beta - np.angle(self.resultant))
        return np.array([self._searched_shift(b) for b in beta])

    def _searched_shift(self, beta: float, steps: int = 40) -> float:
        """The smallest shift (kg m) along beta the balls cannot cancel: a scan, then bisection."""
        top = 2.0 * (self.capacity + self.imbalance)
        grid = np.linspace(0.0, top, 17)[1:]
        guess, lo = None, 0.0
        for s in grid:
            psi = self._shifted(self.unbalance(s * np.exp(1j * beta))).balanced_angles(guess, starts=6)
            if psi is None:
                hi = s
                break
            guess, lo = psi, s
        else:
            return math.inf
        for _ in range(steps):
            mid = 0.5 * (lo + hi)
            psi = self._shifted(self.unbalance(mid * np.exp(1j * beta))).balanced_angles(guess, starts=6)
            if psi is None:
                hi = mid
            else:
                guess, lo = psi, mid
        return 0.5 * (lo + hi)


def _register() -> None:
    from rotorlab.models import JeffcottBalls, Machine

    register_shock_subject(JeffcottBalls, JeffcottSubject)
    register_shock_subject(Machine, MachineSubject)


_register()
