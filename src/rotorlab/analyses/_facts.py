"""What an engineer checks first about a balancer machine, in SI: its masses and unbalance, the
balls' capacity, its critical speeds, the speeds it runs at, its sag against its gap, its motor
and the time constant of its slowest mode.

The sanity checks (:mod:`rotorlab.analyses._sanity`) and the verdict
(:mod:`rotorlab.analyses._page_verdict`) read these facts; each model type that has them
registers one function in :data:`MACHINE_FACTS` (a model type without an entry gets neither
the machine checks nor the machine lines of the verdict).

For implementers
----------------
1. Write ``facts(spec) -> MachineFacts`` for your model spec (cheap: no simulation; a linear
   eigenvalue problem is fine).
2. ``register_machine_facts("my_model", facts)``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab._registry import Registry

__all__ = ["MachineFacts", "MACHINE_FACTS", "register_machine_facts", "machine_facts", "slowest_time_constant"]


@dataclass(frozen=True)
class MachineFacts:
    """The facts of one machine (SI).

    Parameters
    ----------
    rotor_mass : float
        Mass of the structure without the balls (kg).
    rotor_key : str
        The key path of that mass (for messages).
    unbalance : float
        The static unbalance the balls must cancel, ``|sum m e exp(i phase)|`` (kg*m).
    unbalance_key : str
    balls : sequence of (key, mass)
        Every ball's key path and mass (kg).
    capacity : float
        What the balls can cancel at most, ``sum m l`` over every race (kg*m).
    critical_speeds : list of dict
        Entries of :func:`rotorlab.analyses.critical_entry` (undamped, balls locked), those
        unbalance excites first.
    operating : sequence of (where, speed)
        The speeds (rad/s) the machine runs at: the drive's final speed and every analysis'
        constant speed, each with what sets it.
    lateral_gravity : float
        Gravity across the spin axis (m/s^2).
    stall_torque : float or None
        The motor's torque at rest (N*m); None without a motor.
    rest_offset, gap : float or None
        The clearance station's distance at rest from the stator's centre, and the gap (m).
    center_at_rest : bool
    time_constant : float or None
        ``1 / min(-Re lambda)`` over the damped modes of the structure with the balls locked,
        at rest, up to twice the highest running speed (s).
    horizons : sequence of (key, seconds)
        The simulated time of every analysis that has one.
    """

    rotor_mass: float
    rotor_key: str
    unbalance: float
    unbalance_key: str
    balls: Sequence[tuple[str, float]] = ()
    capacity: float = 0.0
    critical_speeds: list[dict[str, Any]] = field(default_factory=list)
    operating: Sequence[tuple[str, float]] = ()
    lateral_gravity: float = 0.0
    stall_torque: float | None = None
    stall_key: str = "model.drive.stall_torque"
    rest_offset: float | None = None
    gap: float | None = None
    gap_key: str = "model.clearances[0]"
    center_at_rest: bool = False
    time_constant: float | None = None
    horizons: Sequence[tuple[str, float]] = ()

    @property
    def first_forward(self) -> float | None:
        """The lowest undamped critical speed that unbalance excites (rad/s)."""
        found = [e["speed_rpm"] for e in self.critical_speeds if e["excited_by_unbalance"] and e["whirl"] != "B"]
        return min(found) / RPM_PER_RAD_S if found else None


#: Fact functions by model type (see the module's "For implementers" list).
MACHINE_FACTS: Registry[Callable[[Any], MachineFacts]] = Registry("model type with machine facts")


def register_machine_facts(model_type: str, facts: Callable[[Any], MachineFacts], *, replace: bool = False) -> None:
    """Add the fact function of a model type to :data:`MACHINE_FACTS`."""
    MACHINE_FACTS.register(model_type, facts, replace=replace)


def machine_facts(case: Any) -> MachineFacts | None:
    """The facts of a loaded case's machine, or None when its model type has none."""
    facts = MACHINE_FACTS.get(case.model.type)
    return None if facts is None else facts(case)


def slowest_time_constant(eigenvalues, max_frequency: float | None = None) -> float | None:
    """``1 / min(-Re lambda)`` over the decaying eigenvalues (s): the slowest damped mode, of
    those with ``|Im lambda|`` up to ``max_frequency`` (rad/s) if given (modes far above every
    running speed respond quasi-statically and do not hold a transient up); None when none decays.

    >>> slowest_time_constant([-2.0 + 5j, -2.0 - 5j, -0.5 + 1j, -0.5 - 1j, 1e-14 + 3j])
    2.0
    >>> slowest_time_constant([-2.0 + 5j, -0.1 + 900j], max_frequency=100.0)
    0.5
    """
    ev = np.asarray(eigenvalues, dtype=complex).reshape(-1)
    if max_frequency is not None:
        ev = ev[np.abs(ev.imag) <= max_frequency]
    rates = -ev.real[ev.real < -1e-9 * max(1.0, float(np.abs(ev).max(initial=0.0)))]
    return float(1.0 / rates.min()) if rates.size else None


def _horizons(case: Any) -> list[tuple[str, float]]:
    out = []
    for i, a in enumerate(case.analyses):
        try:
            t = a.duration(case.model) if hasattr(a, "duration") else getattr(a, "t_end", None)
        except ValueError:
            t = None
        if isinstance(t, (int, float)) and math.isfinite(t):
            out.append((f"analysis[{i}] ({a.name}).t_end", float(t)))
    return out


def _operating(case: Any) -> list[tuple[str, float]]:
    out = []
    profile = case.model.speed_profile()
    if profile is not None:
        out.append(("the drive's final speed", float(profile.final_speed)))
    for a in case.analyses:
        if hasattr(a, "spin_speed"):
            w = a.spin_speed(case.model)
            if w is not None and all(abs(w - v) > 1e-9 * w for _, v in out):
                out.append((f"analysis {a.name}", float(w)))
    return out


def _machine(case: Any) -> MachineFacts:
    from rotorlab.analyses._linear import critical_entries
    from rotorlab.io._machine_spec import build_machine
    from rotorlab.linear import modal
    from rotorlab.models._machine_physics import locked_structure

    spec = case.model
    m = build_machine(spec)
    M = np.asarray(m.structure.M, dtype=float)
    ux = np.zeros(M.shape[0])
    ux[0::4] = 1.0
    locked = locked_structure(m, tilt_inertia=True)
    balls = [(f"model.races[{i}].balls[{j}].mass", float(b.mass)) for i, r in enumerate(spec.races)
             for j, b in enumerate(r.balls)]
    offset, gap, at_rest = None, None, False
    if m.clearances:
        radius, _ = m.rest_clearance()
        offset = radius if math.isfinite(radius) else None
        gap, at_rest = float(m.clearances[0].gap), bool(spec.clearances[0].center_at_rest)
    operating = _operating(case)
    top = 2.0 * max((w for _, w in operating), default=math.inf)
    try:
        tau = slowest_time_constant(modal(locked, 0.0).eigenvalues, top)
    except (np.linalg.LinAlgError, ValueError):
        tau = None
    return MachineFacts(
        rotor_mass=float(ux @ M @ ux), rotor_key="model.structure", balls=balls,
        unbalance=float(abs(sum(u.magnitude * np.exp(1j * u.phase) for u in m.unbalances))),
        unbalance_key="model.unbalances", capacity=float(sum(r.capacity for r in m.races)),
        critical_speeds=critical_entries(locked), operating=operating,
        lateral_gravity=float(math.hypot(*m.lateral_gravity)),
        stall_torque=float(m.drive.stall_torque) if hasattr(m.drive, "stall_torque") else None,
        rest_offset=offset, gap=gap, center_at_rest=at_rest, time_constant=tau, horizons=_horizons(case))


def _jeffcott(case: Any) -> MachineFacts:
    spec = case.model
    p = spec.critical_speed()
    entry = {"speed_rpm": p * RPM_PER_RAD_S, "definition": "undamped", "damped_crossing_rpm": None,
             "undamped_rpm": p * RPM_PER_RAD_S, "damping_ratio": None, "whirl": "F", "harmonic": 1,
             "excited_by_unbalance": True, "note": ""}
    rate = spec.damping / (2.0 * spec.total_mass)
    g = getattr(spec, "gravity", 0.0)
    return MachineFacts(
        rotor_mass=float(spec.disc_mass), rotor_key="model.disc_mass",
        unbalance=float(spec.disc_mass * spec.eccentricity), unbalance_key="model.eccentricity",
        balls=[(f"model.balls[{i}].mass", float(b.mass)) for i, b in enumerate(spec.balls)],
        capacity=float(sum(b.mass * b.radius for b in spec.balls)), critical_speeds=[entry],
        operating=_operating(case), lateral_gravity=float(g) if isinstance(g, (int, float)) else 0.0,
        time_constant=1.0 / rate if rate > 0 else None, horizons=_horizons(case))


def _register_builtins(entries: Mapping[str, Callable[[Any], MachineFacts]]) -> None:
    for name, facts in entries.items():
        register_machine_facts(name, facts)


_register_builtins({"machine": _machine, "jeffcott_balls": _jeffcott})
