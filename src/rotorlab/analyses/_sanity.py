"""Sanity checks of a case before it runs: warnings with numbers, each naming the fix.

A case can be valid and still not be the machine its author meant: a bare number read in SI (an
unbalance of ``50`` is 50 kg*m), balls that cannot cancel the unbalance, a balancer run below
its first critical speed, a rotor resting on its stator, a motor too weak to lift the
unbalance, a simulated time shorter than the slowest mode. ``rotorlab validate`` prints these
warnings (``--json`` lists them) and ``rotorlab run`` prints them before it runs; a warning never
stops a run nor changes an exit code (errors stay errors).

For implementers
----------------
1. Write ``check(case, facts) -> list[SanityWarning]``: ``case`` is the loaded case,
   ``facts`` its :class:`~rotorlab.analyses._facts.MachineFacts` (None for a model type without
   them); cheap (no simulation).
2. Each warning says what was found, with the numbers (rounded by :mod:`rotorlab._people`), and
   the one change that fixes it, naming the key path.
3. ``register_sanity_check("my-check", check)``; test the message it prints.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

from rotorlab import _people as people
from rotorlab._registry import Registry
from rotorlab.analyses._facts import MachineFacts, machine_facts

__all__ = ["SanityWarning", "SANITY_CHECKS", "register_sanity_check", "sanity_warnings", "SIZE_LIMITS",
           "MAX_ECCENTRICITY", "MAX_BALL_SHARE"]


@dataclass(frozen=True)
class SanityWarning:
    """One warning: ``check`` (its key in :data:`SANITY_CHECKS`), what was found (``message``,
    with numbers), the one change that fixes it (``fix``) and the numbers in SI (``numbers``)."""

    check: str
    message: str
    fix: str
    numbers: dict[str, float] = field(default_factory=dict)

    @property
    def text(self) -> str:
        """The line printed: ``message; fix``."""
        return f"{self.message}; {self.fix}"

    def to_dict(self) -> dict[str, Any]:
        return {"check": self.check, "message": self.message, "fix": self.fix, "numbers": dict(self.numbers)}


Check = Callable[[Any, "MachineFacts | None"], list[SanityWarning]]

#: Checks by name, run in this order (see the module's "For implementers" list).
SANITY_CHECKS: Registry[Check] = Registry("sanity check")


def register_sanity_check(name: str, check: Check, *, replace: bool = False) -> None:
    """Add a check to :data:`SANITY_CHECKS`."""
    SANITY_CHECKS.register(name, check, replace=replace)


def sanity_warnings(case: Any) -> list[SanityWarning]:
    """Run every check of :data:`SANITY_CHECKS` on a loaded case.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> [w.check for w in sanity_warnings(load_case("autobalancer"))]
    ['below-critical']
    """
    try:
        facts = machine_facts(case)
    except (ValueError, ArithmeticError):  # a structure these cheap facts cannot read: no machine checks
        facts = None
    return [w for check in SANITY_CHECKS.values() for w in check(case, facts)]


# --------------------------------------------------------------------------- unit slips

#: The sizes of the machines rotorlab models (centrifuges, washers, ball balancers, lab rigs),
#: by SI unit: (smallest, largest) nonzero value; a value outside is most likely a bare number
#: read in SI or a unit slip.
SIZE_LIMITS = {"m": (None, 5.0), "kg": (1e-5, 1e4)}
#: Largest plausible distance of the rotor's mass centre from the axis, unbalance / mass (m).
MAX_ECCENTRICITY = 0.05
#: Largest plausible mass of all balls as a share of the rotor's mass.
MAX_BALL_SHARE = 0.5

_EXAMPLE_UNIT = {"m": "mm", "kg": "g"}


def _values(spec: Any, prefix: str) -> Iterator[tuple[str, float, str]]:
    """``(key path, value, SI unit)`` of every number of a case table with a unit."""
    from pydantic import BaseModel

    from rotorlab.io import field_unit

    for name, info in type(spec).model_fields.items():
        value = getattr(spec, name, None)
        key = f"{prefix}.{info.alias or name}"
        items = value if isinstance(value, tuple) else (value,)
        for i, item in enumerate(items):
            where = f"{key}[{i}]" if isinstance(value, tuple) else key
            if isinstance(item, BaseModel):
                yield from _values(item, where)
            elif isinstance(item, (int, float)) and not isinstance(item, bool):
                unit = field_unit(info)
                if unit in SIZE_LIMITS:
                    yield where, float(item), unit


def _sizes(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    out = []
    for key, value, unit in _values(case.model, "model"):
        low, high = SIZE_LIMITS[unit]
        a = abs(value)
        if a == 0 or ((low is None or a >= low) and (high is None or a <= high)):
            continue
        bound = f"up to {people.quantity(high, unit)}" if high is not None and a > high else \
            f"from {people.quantity(low, unit)}"
        out.append(SanityWarning(
            "unit-slip", f"{key} = {people.number(value)} {unit} is far outside the sizes of the machines rotorlab "
            f"models ({bound}): a number without a unit is read in SI",
            f'write its unit, e.g. "{people.number(value)} {_EXAMPLE_UNIT[unit]}"', {"value": value}))
    return out


def _unbalance_slip(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or not facts.rotor_mass > 0:
        return []
    e = facts.unbalance / facts.rotor_mass
    if e <= MAX_ECCENTRICITY:
        return []
    return [SanityWarning(
        "unit-slip-unbalance", f"the unbalance {people.unbalance(facts.unbalance)} on a {people.mass(facts.rotor_mass)} "
        f"rotor puts its mass centre {people.length(e)} off the axis (more than {people.length(MAX_ECCENTRICITY)} "
        "is no machine's): a number without a unit is read as kg*m (or m)",
        f"check {facts.unbalance_key} and write its unit, e.g. \"{people.number(facts.unbalance)} g*mm\"",
        {"unbalance": facts.unbalance, "rotor_mass": facts.rotor_mass, "eccentricity": e})]


def _ball_slip(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or not facts.balls or not facts.rotor_mass > 0:
        return []
    total = sum(m for _, m in facts.balls)
    if total <= MAX_BALL_SHARE * facts.rotor_mass:
        return []
    key, heaviest = max(facts.balls, key=lambda kv: kv[1])
    return [SanityWarning(
        "unit-slip-balls", f"the balls weigh {people.mass(total)} together on a {people.mass(facts.rotor_mass)} rotor "
        f"(more than {people.number(100 * MAX_BALL_SHARE)} % of it): balancer balls are a small part of the rotor",
        f'check {key} = {people.mass(heaviest)} (a mass in grams needs its unit, e.g. "{people.number(heaviest)} g")',
        {"ball_mass_total": total, "rotor_mass": facts.rotor_mass})]


# --------------------------------------------------------------------------- the balancer


def _capacity(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or not facts.balls or facts.capacity >= facts.unbalance:
        return []
    need = facts.unbalance / facts.capacity
    return [SanityWarning(
        "ball-capacity", f"the balls can cancel at most {people.unbalance(facts.capacity)} (sum of ball mass x race "
        f"radius); the unbalance is {people.unbalance(facts.unbalance)}: they cannot balance it",
        f"make the balls at least {people.number(need)} times heavier (or their race radius larger), or the "
        f"unbalance smaller", {"capacity": facts.capacity, "unbalance": facts.unbalance})]


def _below_critical(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or not facts.balls or facts.first_forward is None:
        return []
    p = facts.first_forward
    out = []
    for where, w in facts.operating:
        if w < p:
            out.append(SanityWarning(
                "below-critical", f"{where} is {people.speed(w)}, below the first forward critical speed "
                f"{people.speed(p)} (undamped, balls locked): a balancer works only above {people.speed(p)}, "
                "below it the balls add to the unbalance",
                f"run above {people.speed(p)}, or soften the mounts (lower support stiffness) until the critical "
                f"speed falls below {people.speed(w)}", {"speed": w, "critical_speed": p}))
    return out


def _sag(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or facts.rest_offset is None or facts.gap is None:
        return []
    r, gap = facts.rest_offset, facts.gap
    if r <= 0.5 * gap:
        return []
    fix = (f"give {facts.gap_key}.center_at_rest = true (the stator centred where the rotor rests)"
           if not facts.center_at_rest else "") or f"give {facts.gap_key}.gap > {people.length(2 * r)}"
    if r > gap:
        what = "the rotor rests on its stator and knocks in every run-up, with or without balls"
    else:
        what = f"{people.number(100 * r / gap)} % of the gap is gone before the rotor turns"
    return [SanityWarning(
        "sag-gap", f"at rest under gravity the clearance station lies {people.length(r)} from the stator's centre, "
        f"against a gap of {people.length(gap)}: {what}", fix, {"rest_offset": r, "gap": gap})]


def _motor(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    if facts is None or facts.stall_torque is None or not facts.lateral_gravity > 0:
        return []
    lift = facts.unbalance * facts.lateral_gravity
    if facts.stall_torque >= lift:
        return []
    return [SanityWarning(
        "motor-torque", f"the motor's stall torque {people.torque(facts.stall_torque)} is below the unbalance's "
        f"gravity torque U g = {people.torque(lift)}: from rest it cannot lift the unbalance over the top",
        f"give {facts.stall_key} > {people.torque(lift)}", {"stall_torque": facts.stall_torque, "gravity_torque": lift})]


def _horizons(case: Any, facts: MachineFacts | None) -> list[SanityWarning]:
    from rotorlab.analyses._verdict import MIN_TIME_CONSTANTS, round_up_horizon
    from rotorlab.explore._settle import TIME_CONSTANTS

    if facts is None or facts.time_constant is None:
        return []
    tau = facts.time_constant
    return [SanityWarning(
        "horizon", f"{key} = {people.duration(t)} is shorter than {MIN_TIME_CONSTANTS:g} time constants of the "
        f"slowest mode ({people.duration(tau)}, structure with the balls locked): its start-up transient has not "
        "died out", f"give t_end >= {people.duration(round_up_horizon(TIME_CONSTANTS * tau))} ({TIME_CONSTANTS:g} "
        "time constants)", {"t_end": t, "time_constant": tau})
        for key, t in facts.horizons if t < MIN_TIME_CONSTANTS * tau]


for _name, _check in (("unit-slip", _sizes), ("unit-slip-unbalance", _unbalance_slip), ("unit-slip-balls", _ball_slip),
                      ("ball-capacity", _capacity), ("below-critical", _below_critical), ("sag-gap", _sag),
                      ("motor-torque", _motor), ("horizon", _horizons)):
    register_sanity_check(_name, _check)
