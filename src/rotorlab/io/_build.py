"""From a validated ``machine`` spec to its :class:`rotorlab.models.Machine`: the one place a
machine is built from a case (the linear structures: :mod:`rotorlab.io._linear_build`), and the
checks of a case that need the built model (``n_modes`` of an isotropic structure, whether the
machine has steady motions, its first critical speed), which the spec's validators call.

The machine carries a :class:`StructureSource`: its structure's own numbers by key path
(``bearings[0].kxx``, ``bodies[1].mass``), so that ``Machine.parameters`` names them
``structure.<key path>`` and ``Machine.with_parameters`` rebuilds the structure from its table
alone, never from the case document.
"""

from __future__ import annotations

from typing import Any

__all__ = ["build_machine", "StructureSource", "n_modes_issues", "why_no_steady_motions", "machine_critical_speed"]


def _leaves(data: Any, path: str = ""):
    """(key path, number) of every number in dumped spec data, key paths as messages write them."""
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _leaves(v, f"{path}.{k}" if path else str(k))
    elif isinstance(data, (list, tuple)):
        for i, v in enumerate(data):
            yield from _leaves(v, f"{path}[{i}]")
    elif isinstance(data, (int, float)) and not isinstance(data, bool):
        yield path, float(data)


def _set_path(data: Any, path: tuple, value: float) -> None:
    for k in path[:-1]:
        data = data[k]
    data[path[-1]] = value


class StructureSource:
    """The linear structure of a machine with its case-file table: named numbers, rebuilt on edit.

    Parameters
    ----------
    spec : rotorlab.io.MultibodySpec or rotorlab.io.FeRotorSpec
        The validated ``[model.structure]`` table.

    Notes
    -----
    A new value is checked against the key's bounds (the caller's :class:`~rotorlab.models.Parameter`)
    and the table is validated alone (its own cross-checks: a compliance matrix's symmetry, a
    body's name), then built by :func:`rotorlab.io.build_linear_system`.
    """

    def __init__(self, spec: Any) -> None:
        self.spec = spec
        self._system = None
        self._parameters = None

    def __repr__(self) -> str:
        # what a sweep store remembers of a machine (rotorlab.sweep.describe_value): the table's
        # content, never the object's address (a resumed run must find the same description)
        import hashlib

        text = self.spec.model_dump_json(warnings=False)
        return f"StructureSource({self.spec.type}, sha256 {hashlib.sha256(text.encode()).hexdigest()[:16]})"

    @property
    def system(self) -> Any:
        """The :class:`rotorlab.linear.LinearSystem` of the table."""
        if self._system is None:
            from rotorlab.io._linear_build import build_linear_system

            self._system = build_linear_system(self.spec)
        return self._system

    @property
    def parameters(self) -> tuple:
        """Every number of the table that has a unit, as :class:`rotorlab.models.Parameter`
        (names without ``structure.``)."""
        if self._parameters is None:
            from rotorlab.io._coordinates import key_quantity
            from rotorlab.io._fields import plain_data
            from rotorlab.io._machine_spec import MachineSpec
            from rotorlab.models import Parameter

            out = []
            for name, value in _leaves(plain_data(self.spec.model_dump(mode="python"))):
                q = key_quantity(f"model.structure.{name}", MachineSpec)
                if q is not None:
                    out.append(Parameter(name, q.dimension.si or "1", value, q.bounds))
            self._parameters = tuple(out)
        return self._parameters

    def with_value(self, name: str, value: float) -> StructureSource:
        """A new source with the number at ``name`` set (SI), its table validated alone.

        Raises
        ------
        ValueError
            The table refuses the value (the message names the key path and the value).
        """
        from pydantic import ValidationError

        from rotorlab.io._fields import plain_data
        from rotorlab.io._overrides import parse_key_path

        data = plain_data(self.spec.model_dump(mode="python"))
        path = tuple(int(k) if str(k).isdigit() else k for k in parse_key_path(name))
        _set_path(data, path, float(value))
        try:
            return StructureSource(type(self.spec).model_validate(data))
        except ValidationError as exc:
            first = exc.errors()[0]
            raise ValueError(f"structure.{name} = {value:g}: {first.get('msg', exc)}") from None


def build_machine(spec: Any) -> Any:
    """Build the :class:`rotorlab.models.Machine` of a validated ``machine`` spec (the run's
    machine when it has built it already, or the one built before from this spec object:
    :mod:`rotorlab.io._built`)."""
    from rotorlab.io._built import built_once
    from rotorlab.models import Machine

    return built_once(spec, _machine, Machine)


def _machine(spec: Any) -> Any:
    from rotorlab.models import (Ball, BallRace, ConstantSpeed, Gravity, HillRunUp, LinearRamp,
                                 Machine, Motor)

    source = StructureSource(spec.structure)
    races = tuple(BallRace(spec.node_of(r), r.radius,
                           tuple(Ball(b.mass, b.inertia, b.damping, b.coulomb, b.rolling) for b in r.balls),
                           r.axial_offset) for r in spec.races)
    d = spec.drive
    drives = {
        "constant": lambda: ConstantSpeed(d.speed),
        "ramp": lambda: LinearRamp(d.start, d.stop, d.duration),
        "hill": lambda: HillRunUp(d.max_speed, d.t_half, d.exponent),
        "motor": lambda: Motor(d.stall_torque if d.speeds is None else (d.speeds, d.torques),
                               d.polar_inertia,
                               float("inf") if d.no_load_speed is None else d.no_load_speed),
        "servo": lambda: d.build(),
    }
    drive = drives[d.profile]()
    gravity = None if spec.gravity is None else Gravity(spec.gravity.vector)
    from rotorlab.io._part_specs import PART_SPECS

    # each registered key's items: a key that is a field of Machine (unbalances) fills that
    # field, the others are its parts
    built = {key: tuple(item.build(spec.node_of(item)) for item in getattr(spec, key)) for key in PART_SPECS}
    held = {key: items for key, items in built.items() if key in Machine.__dataclass_fields__}
    parts = tuple(p for key, items in built.items() if key not in held for p in items)
    return Machine(source.system, races=races, gravity=gravity, drive=drive,
                   n_modes=spec.n_modes, clearances=tuple(_clearance(spec, c) for c in spec.clearances),
                   parts=parts, structure_source=source, **held)


def _clearance(spec: Any, c: Any) -> Any:
    from rotorlab.models import Clearance, ElasticStator

    stator = "rigid" if c.stator is None else ElasticStator(c.stator.stiffness, c.stator.damping,
                                                             c.stator.mass)
    conical = None if c.conical is None else (c.conical.half_angle, c.conical.lever)
    return Clearance(spec.node_of(c), c.gap, stator, restitution=c.restitution, friction=c.friction,
                     rotor_radius=c.rotor_radius, axial_offset=c.axial_offset, conical=conical,
                     rest_speed=c.rest_speed,
                     center="static" if c.center_at_rest else (c.center or (0.0, 0.0)))


def n_modes_issues(spec: Any) -> list:
    """What ``Machine`` requires of ``n_modes`` for the spec's structure, as key-path issues (the
    model would otherwise raise on build: an internal error instead of exit code 2)."""
    from rotorlab.io._errors import Issue
    from rotorlab.io._linear_build import build_linear_system
    from rotorlab.models._machine import MAX_COORDINATES

    n_dof, k = spec.structure.n_dof, spec.n_modes
    if k is None:
        if n_dof > MAX_COORDINATES:
            return [Issue(("n_modes",), f"required: the structure has {n_dof} DOFs and the compiled "
                                        f"kernel takes at most {MAX_COORDINATES} coordinates; keep "
                                        "its lowest modes (e.g. n_modes = 8)", show_value=False)]
        return []
    if k > n_dof:
        return [Issue(("n_modes",), f"must be <= {n_dof} (the structure's DOFs)", k)]
    if k % 2 and build_linear_system(spec.structure).is_isotropic:
        return [Issue(("n_modes",), "must be even for an isotropic structure (its modes come "
                                    "in x/y pairs)", k)]
    return []


def why_no_steady_motions(spec: Any) -> str | None:
    """Why the spec's machine has no steady motions (no co-rotating frame), None if it has."""
    from rotorlab.models import ConstantSpeed

    return build_machine(spec).with_drive(ConstantSpeed(1.0)).why_no_rotating_frame()


def machine_critical_speed(spec: Any) -> float | None:
    """The lowest forward 1x critical speed of the spec's structure with the balls locked (rad/s)."""
    from rotorlab.models._machine_physics import structure_critical_speeds

    crit = structure_critical_speeds(build_machine(spec))
    return float(crit[0]) if crit.size else None
