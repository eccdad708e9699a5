"""The named parameters of the machine, ``jeffcott_balls``, the toroidal ball, the impact rotor and
the rub rotor (:mod:`rotorlab.models._protocol`).

Each function lists a model's numbers as :class:`Slot` objects: the name is the key path of the
model's ``[model]`` table (balls as the case expands ``count``: one index per ball), the bounds
are the case file's (``tests/unit/test_parameters.py`` compares them with the schema), and the
setter replaces the part that holds the number.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from rotorlab.models._protocol import Parameter, Slot
from rotorlab.models._speed import ConstantSpeed, HillRunUp, LinearRamp

__all__ = ["machine_slots", "jeffcott_slots", "toroidal_slots", "impact_slots", "rub_slots"]

_GT0 = (0.0, None, None, None)
_GE0 = (None, 0.0, None, None)
_FREE = (None, None, None, None)

#: Fields of a prescribed speed profile: (field, unit, bounds), as the case file's ``[model.drive]``
#: / ``[model.speed]`` tables.
_PROFILE_FIELDS = {
    ConstantSpeed: (("speed", "rad/s", _GT0),),
    LinearRamp: (("start", "rad/s", _GE0), ("stop", "rad/s", _GE0), ("duration", "s", _GT0)),
    HillRunUp: (("max_speed", "rad/s", _GT0), ("t_half", "s", _GT0), ("exponent", "1", (None, 0.01, None, 1000.0))),
}


def _slot(name: str, unit: str, value: float, bounds, set_, structural: bool = False) -> Slot:
    return Slot(Parameter(name, unit, float(value), bounds, structural), set_)


def _profile_slots(prefix: str, profile: Any, attr: str) -> list[Slot]:
    """The fields of a prescribed speed profile held in the model's field ``attr``."""
    out = []
    for name, unit, bounds in _PROFILE_FIELDS.get(type(profile), ()):
        def set_(m, v, name=name):
            return replace(m, **{attr: replace(getattr(m, attr), **{name: v})})

        out.append(_slot(f"{prefix}.{name}", unit, getattr(profile, name), bounds, set_))
    return out


def _set_item(items: tuple, i: int, **kw) -> tuple:
    return items[:i] + (replace(items[i], **kw),) + items[i + 1:]


# ---------------------------------------------------------------------------------------- machine
def owned_slots(prefix: str, item: Any, set_item: Any) -> list[Slot]:
    """The slots of the numbers an attachment owns (its class's ``fields``: ``(field, unit,
    bounds)``), named ``<prefix>.<field>``; ``set_item(model, field, value)`` returns the model
    with that field of the attachment replaced."""
    return [_slot(f"{prefix}.{name}", unit, getattr(item, name), bounds,
                  lambda mm, v, name=name: set_item(mm, name, v))
            for name, unit, bounds in type(item).fields]


def _item_setter(attr: str, i: int):
    """A setter of a field of item ``i`` of the model's tuple ``attr`` (a race, an unbalance ...)."""
    return lambda mm, name, v: replace(mm, **{attr: _set_item(getattr(mm, attr), i, **{name: v})})


def _race_slots(m) -> list[Slot]:
    out = []
    for i, race in enumerate(m.races):
        out += owned_slots(f"races[{i}]", race, _item_setter("races", i))
        for j, ball in enumerate(race.balls):
            def set_ball(mm, name, v, i=i, j=j):
                return replace(mm, races=_set_item(mm.races, i, balls=_set_item(mm.races[i].balls, j, **{name: v})))

            out += owned_slots(f"races[{i}].balls[{j}]", ball, set_ball)
    return out


def _drive_slots(m) -> list[Slot]:
    d = m.drive
    if not m.is_motor:
        return _profile_slots("drive", d, "drive")
    out = [_slot("drive.polar_inertia", "kg*m^2", d.polar_inertia, _GT0,
                 lambda mm, v: replace(mm, drive=replace(mm.drive, polar_inertia=v)))]
    if isinstance(d.torque, tuple):
        speeds, torques = d.torque
        for k in range(len(speeds)):
            def set_row(mm, v, k=k, col=0):
                table = [list(c) for c in mm.drive.torque]
                table[col][k] = v
                return replace(mm, drive=replace(mm.drive, torque=(tuple(table[0]), tuple(table[1]))))

            out.append(_slot(f"drive.speeds[{k}]", "rad/s", speeds[k], _GE0, set_row))
            out.append(_slot(f"drive.torques[{k}]", "N*m", torques[k], _FREE,
                             lambda mm, v, k=k: set_row(mm, v, k, 1)))
    else:
        out.append(_slot("drive.stall_torque", "N*m", d.torque, _FREE,
                         lambda mm, v: replace(mm, drive=replace(mm.drive, torque=v))))
        out.append(_slot("drive.no_load_speed", "rad/s", d.no_load_speed, _GT0,
                         lambda mm, v: replace(mm, drive=replace(mm.drive, no_load_speed=v))))
    if hasattr(type(d), "fields"):  # a commanded drive's own numbers (rotorlab.models._servo)
        out += owned_slots("drive", d, lambda mm, name, v: replace(mm, drive=replace(mm.drive, **{name: v})))
    return out


def _clearance_slots(m) -> list[Slot]:
    out = []
    for i, c in enumerate(m.clearances):
        p = f"clearances[{i}]"
        out += owned_slots(p, c, _item_setter("clearances", i))
        if not isinstance(c.stator, str):
            def set_stator(mm, name, v, i=i):
                cl = mm.clearances[i]
                return replace(mm, clearances=_set_item(mm.clearances, i, stator=replace(cl.stator, **{name: v})))

            # a housing mass from or to 0 changes the compiled layout (housing states): refused by pack
            out += owned_slots(f"{p}.stator", c.stator, set_stator)
        if c.conical is not None:
            for k, (key, unit, bounds) in enumerate((("half_angle", "rad", (0.0, None, None, math.pi / 2)),
                                                     ("lever", "m", _FREE))):
                def set_cone(mm, v, i=i, k=k):
                    cone = list(mm.clearances[i].conical)
                    cone[k] = v
                    return replace(mm, clearances=_set_item(mm.clearances, i, conical=tuple(cone)))

                out.append(_slot(f"{p}.conical.{key}", unit, c.conical[k], bounds, set_cone))
        if not isinstance(c.center, str) and any(c.center):
            for k in range(2):
                def set_center(mm, v, i=i, k=k):
                    ctr = list(mm.clearances[i].center)
                    ctr[k] = v
                    return replace(mm, clearances=_set_item(mm.clearances, i, center=tuple(ctr)))

                out.append(_slot(f"{p}.center[{k}]", "m", c.center[k], _FREE, set_center))
    return out


def machine_slots(m) -> list[Slot]:
    """The named parameters of a :class:`rotorlab.models.Machine` (then those of its structure's
    source, when it was built from a case: ``structure.<key path>``)."""
    from rotorlab.models._gravity_part import GravityPart
    from rotorlab.models._parts import part_slots

    # a couple from or to 0 changes the compiled layout (two more point unbalances): refused by pack
    out = _race_slots(m) + part_slots(m, "unbalances") + _drive_slots(m) + _clearance_slots(m) + GravityPart.slots(m)
    out += part_slots(m)
    if m.n_modes is not None:
        out.append(_slot("n_modes", "1", m.n_modes, (None, 1.0, None, float(m.structure.n_dof)),
                         lambda mm, v: replace(mm, n_modes=_integer("n_modes", v)), structural=True))
    source = m.structure_source
    if source is not None:
        for p in source.parameters:
            def set_s(mm, v, name=p.name):
                src = mm.structure_source.with_value(name, v)
                return replace(mm, structure=src.system, structure_source=src)

            out.append(Slot(Parameter(f"structure.{p.name}", p.unit, p.value, p.bounds, p.structural), set_s))
    return out


def _integer(name: str, v: float) -> int:
    if not float(v).is_integer():
        raise ValueError(f"{name} = {v:g}: must be an integer")
    return int(v)


# ---------------------------------------------------------------------------------- jeffcott_balls
def jeffcott_slots(m) -> list[Slot]:
    """The named parameters of a :class:`rotorlab.models.JeffcottBalls` (the ``jeffcott_balls``
    table's keys: ``disc_mass`` ... ``balls[i].mass`` ... ``speed.speed``)."""
    out = []
    for key, unit, bounds in (("disc_mass", "kg", _GT0), ("eccentricity", "m", _GE0),
                              ("stiffness", "N/m", _GT0), ("damping", "N*s/m", _GE0)):
        out.append(_slot(key, unit, getattr(m.rotor, key), bounds,
                         lambda mm, v, key=key: replace(mm, rotor=replace(mm.rotor, **{key: v}))))
    for i, b in enumerate(m.balls):
        for key, unit, bounds in (("mass", "kg", _GT0), ("radius", "m", _GT0), ("inertia", "kg*m^2", _GE0),
                                  ("damping", "N*m*s/rad", _GE0), ("friction", "1", _GE0)):
            out.append(_slot(f"balls[{i}].{key}", unit, getattr(b, key), bounds,
                             lambda mm, v, i=i, key=key: _set_ball(mm, i, key, v)))
    return out + _profile_slots("speed", m.speed, "speed")


def _set_ball(m, i: int, key: str, v: float):
    """``balls[i].<key>`` set; a point-mass ball (``inertia == mass * radius**2``: the case wrote
    no inertia) stays one when its mass or radius changes, as the case edited at that key would
    fill it (the spec's ``mass * radius**2``)."""
    b = m.balls[i]
    kw = {key: v}
    if key in ("mass", "radius") and b.inertia == b.mass * b.radius**2:
        mass, radius = (v, b.radius) if key == "mass" else (b.mass, v)
        kw["inertia"] = mass * radius**2
    return replace(m, balls=_set_item(m.balls, i, **kw))


# ----------------------------------------------------------------------------------- toroidal_ball
def toroidal_slots(m) -> list[Slot]:
    """The named parameters of a :class:`rotorlab.models.ToroidalBall` (the ``toroidal_ball``
    table's keys; ``form`` is a choice, not a number)."""
    return [_slot(key, unit, getattr(m, key), bounds, lambda mm, v, key=key: replace(mm, **{key: v}))
            for key, unit, bounds in (("ring_radius", "m", _GT0), ("tube_radius", "m", _GT0),
                                      ("ball_radius", "m", _GT0), ("spin_speed", "rad/s", _GT0),
                                      ("offset", "m", _GE0), ("rolling_friction", "m", _GE0),
                                      ("gravity", "m/s^2", _GE0))]


# ------------------------------------------------------------------------------------ impact_rotor
_ANGLE_BELOW_RIGHT = (0.0, None, math.pi / 2, None)
#: (part, prefix of the key path, field, unit, bounds) of the impact rotor's numbers: the rotor's
#: keys are at the top of its table, the housing's and the stone feed's in their own tables.
_IMPACT_FIELDS = (
    *(("rotor", "", f, u, b) for f, u, b in (
        ("mass", "kg", _GT0), ("inertia_transverse", "kg*m^2", _GT0), ("inertia_polar", "kg*m^2", _GT0),
        ("spin_speed", "rad/s", _GT0), ("stiffness_1", "N/m", _GT0), ("stiffness_2", "N/m", _GT0),
        ("height_1", "m", _FREE), ("height_2", "m", _FREE), ("internal_friction", "1", _GE0))),
    *(("housing", "housing.", f, u, b) for f, u, b in (
        ("radius", "m", _GT0), ("height", "m", _FREE), ("gap", "m", _GT0),
        ("cone_angle", "rad", (0.0, None, None, math.pi / 2)), ("restitution", "1", (None, 0.0, None, 1.0)),
        ("friction", "1", _GE0), ("rest_speed", "m/s", _GT0), ("count_speed", "m/s", _GE0),
        ("whirl_limit", "rad/s", _GT0))),
    *(("stones", "stones.", f, u, b) for f, u, b in (
        ("mass", "kg", _GT0), ("interval", "s", _GT0), ("radius", "m", _GT0), ("height", "m", _FREE),
        ("spiral_angle", "rad", _ANGLE_BELOW_RIGHT), ("guide_friction", "1", _GE0), ("start_radius", "m", _GT0),
        ("start_speed", "m/s", _GE0), ("first_time", "s", _GT0), ("mass_spread", "1", (None, 0.0, 1.0, None)),
        ("time_jitter", "1", (None, 0.0, 0.5, None)))),
)


def impact_slots(m) -> list[Slot]:
    """The named parameters of a :class:`rotorlab.models.ImpactRotor` (the ``impact_rotor``
    table's numbers; a key left at None, e.g. ``housing.whirl_limit``, is not one)."""
    out = []
    for part, prefix, key, unit, bounds in _IMPACT_FIELDS:
        value = getattr(getattr(m, part), key)
        if value is None:
            continue

        def set_(mm, v, part=part, key=key):
            return replace(mm, **{part: replace(getattr(mm, part), **{key: v})})

        out.append(_slot(prefix + key, unit, value, bounds, set_))
    return out


# -------------------------------------------------------------------------------------- rub_rotor
#: The rotor's numbers of a ``rub_rotor`` table (:class:`rotorlab.contact.RubRotor`): (key, unit,
#: bounds); ``stator_stiffness`` and ``stator_damping`` only with an elastic stator (a rigid one
#: has neither: the case refuses a stator damping without a stator stiffness).
_RUB_ROTOR_FIELDS = (("mass", "kg", _GT0), ("stiffness", "N/m", _GT0), ("damping", "N*s/m", _GE0),
                     ("eccentricity", "m", _GE0), ("clearance", "m", _GT0))
_RUB_STATOR_FIELDS = (("stator_stiffness", "N/m", _GT0), ("stator_damping", "N*s/m", _GE0))
_RUB_CONTACT_FIELDS = (("friction", "1", _GE0), ("rotor_radius", "m", _GT0))
#: The model's own numbers (:class:`rotorlab.contact.JeffcottRub`).
_RUB_MODEL_FIELDS = (("restitution", "1", (None, 0.0, None, 1.0)), ("rest_speed", "m/s", _GT0),
                     ("spin_speed", "rad/s", _GE0))


def rub_slots(m) -> list[Slot]:
    """The named parameters of a :class:`rotorlab.contact.JeffcottRub` (the ``rub_rotor``
    table's keys: ``mass`` ... ``clearance``, the stator's, ``friction``, ``rotor_radius``,
    ``restitution``, ``rest_speed``, ``spin_speed``)."""
    fields = _RUB_ROTOR_FIELDS + (() if m.rotor.rigid_stator else _RUB_STATOR_FIELDS) + _RUB_CONTACT_FIELDS
    out = [_slot(key, unit, getattr(m.rotor, key), bounds,
                 lambda mm, v, key=key: replace(mm, rotor=replace(mm.rotor, **{key: v})))
           for key, unit, bounds in fields]
    return out + [_slot(key, unit, getattr(m, key), bounds, lambda mm, v, key=key: replace(mm, **{key: v}))
                  for key, unit, bounds in _RUB_MODEL_FIELDS]
