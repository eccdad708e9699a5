"""Case-file specs of the linear analyses: Campbell diagram, modes, critical speeds, unbalance
response, identification of stiffnesses from measured frequencies, and the data audit.

They run on a linear rotor model (``multibody`` or ``fe_rotor``; see
:class:`~rotorlab.io._linear_common.AbstractLinearModelSpec`) and are computed by
:mod:`rotorlab.analyses` with :mod:`rotorlab.linear`.
"""

from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import Field, model_validator

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import (
    AbstractAnalysisSpec,
    AbstractModelSpec,
    _choice,
    _Spec,
    integer,
    quantity,
)
from rotorlab.io._linear_common import AbstractLinearModelSpec, label, parse_path
from rotorlab.io._multibody_spec import ElasticSpec, MultibodySpec, elastic_issues

__all__ = [
    "LINEAR_MODELS",
    "CampbellSpec",
    "ModesSpec",
    "CriticalSpeedsSpec",
    "UnbalanceSpec",
    "UnbalanceResponseSpec",
    "MeasurementSpec",
    "IdentifySpec",
    "DataAuditSpec",
    "linear_model_issues",
]

#: Model types the linear analyses run on.
LINEAR_MODELS = ("multibody", "fe_rotor")

#: Data sets :class:`DataAuditSpec` can audit (see :data:`rotorlab.analyses.DATA_AUDITS`).
AUDITED_DATA = ("pico21",)


def linear_model_issues(model: AbstractModelSpec) -> list[Issue]:
    """Return an issue unless ``model`` is a linear rotor model (``loc`` empty)."""
    if isinstance(model, AbstractLinearModelSpec):
        return []
    allowed = " or ".join(f'"{t}"' for t in LINEAR_MODELS)
    return [Issue((), f"needs a linear rotor model ([model] type {allowed}), but the case's "
                      f'model is "{model.type}"', show_value=False)]


def structure_issues(model: AbstractModelSpec) -> tuple[Any, list[Issue]]:
    """The linear structure of ``model`` (:meth:`~AbstractModelSpec.linear_structure`: itself for a
    linear rotor, the structure of a machine) and, if it has none, the issue saying so."""
    structure = model.linear_structure()
    if structure is None:
        allowed = " or ".join(f'"{t}"' for t in LINEAR_MODELS)
        return None, [Issue((), f"needs a linear rotor model ([model] type {allowed}) or a model built "
                                f'on one (machine), but the case\'s model is "{model.type}"',
                            show_value=False)]
    return structure, []


def _harmonics_issues(harmonics: tuple[int, ...]) -> list[Issue]:
    if len(set(harmonics)) != len(harmonics):
        return [Issue(("harmonics",), "lists a harmonic twice", list(harmonics))]
    return []


def _n_modes_issues(n_modes: int | None, model: AbstractModelSpec) -> list[Issue]:
    if n_modes is not None and isinstance(model, AbstractLinearModelSpec) \
            and n_modes > model.n_dof:
        return [Issue(("n_modes",), f"must be <= {model.n_dof} (the model's number of modes)",
                      n_modes)]
    return []


class _SpeedRange(AbstractAnalysisSpec):
    """An analysis over ``n_speeds`` equally spaced spin speeds from ``start`` to ``stop``."""

    start: quantity("angular_speed", ge=0) = Field(0.0, description="lowest spin speed (rad/s)")
    stop: quantity("angular_speed", gt=0) = Field(description="highest spin speed (rad/s)")
    n_speeds: integer(ge=2) = Field(101, description="number of equally spaced speeds")

    @model_validator(mode="after")
    def _check_range(self) -> _SpeedRange:
        if not self.stop > self.start:
            raise IssueGroup([Issue(("stop",), f"must be > start = {self.start:.6g} rad/s "
                                               f"({self.start * _RPM:.6g} rpm)", self.stop)])
        return self

    def speeds(self) -> tuple[float, ...]:
        """Return the spin speeds (rad/s), ``start`` and ``stop`` included."""
        n = self.n_speeds
        step = (self.stop - self.start) / (n - 1)
        return tuple(self.start + k * step for k in range(n - 1)) + (self.stop,)

    def _range_text(self) -> str:
        return (f"{self.n_speeds} speeds from {self.start * _RPM:.6g} to "
                f"{self.stop * _RPM:.6g} rpm")


class CampbellSpec(_SpeedRange):
    """Campbell diagram: tracked natural frequencies versus spin speed, and critical speeds.

    Parameters
    ----------
    name : str, optional
    start, stop : float
        Speed range (rad/s), 0 <= start < stop.
    n_speeds : int
        Number of equally spaced speeds, >= 2.
    n_modes : int
        Number of branches (the lowest at ``start``), >= 1.
    harmonics : tuple of int
        Excitation lines n x whose crossings are reported as critical speeds.
    """

    type: Literal["campbell"] = "campbell"
    n_modes: integer(ge=1) = Field(6, description="number of mode branches")
    harmonics: tuple[integer(ge=1), ...] = Field(
        (1,), min_length=1, description="excitation orders n of the n x lines")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check that the model has a linear structure with ``n_modes`` modes."""
        structure, issues = structure_issues(model)
        return issues + _n_modes_issues(self.n_modes, structure) + _harmonics_issues(self.harmonics)

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        lines = ", ".join(f"{h}x" for h in self.harmonics)
        return f"Campbell diagram, {self.n_modes} modes, {self._range_text()}, lines {lines}"


class ModesSpec(AbstractAnalysisSpec):
    """Complex modes at one spin speed.

    Parameters
    ----------
    name : str, optional
    speed : float
        Spin speed (rad/s), >= 0.
    n_modes : int, optional
        Keep the lowest ``n_modes``; default all.
    """

    type: Literal["modes"] = "modes"
    speed: quantity("angular_speed", ge=0) = Field(0.0, description="spin speed (rad/s)")
    n_modes: integer(ge=1) | None = Field(None, description="number of modes, default all")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check that the model has a linear structure with ``n_modes`` modes."""
        structure, issues = structure_issues(model)
        return issues + _n_modes_issues(self.n_modes, structure)

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        count = "all" if self.n_modes is None else str(self.n_modes)
        return f"{count} modes at {self.speed * _RPM:.6g} rpm"


class CriticalSpeedsSpec(AbstractAnalysisSpec):
    """Critical speeds of the undamped rotor, exactly (no speed grid).

    Parameters
    ----------
    name : str, optional
    harmonics : tuple of int
        Excitation orders (1: synchronous unbalance).
    max_speed : float, optional
        Report critical speeds up to this speed (rad/s).
    """

    type: Literal["critical_speeds"] = "critical_speeds"
    harmonics: tuple[integer(ge=1), ...] = Field(
        (1,), min_length=1, description="excitation orders n of the n x lines")
    max_speed: quantity("angular_speed", gt=0) | None = Field(
        None, description="highest critical speed reported (rad/s)")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check that the model has a linear structure."""
        return structure_issues(model)[1] + _harmonics_issues(self.harmonics)

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        upto = "" if self.max_speed is None else f" up to {self.max_speed * _RPM:.6g} rpm"
        return f"critical speeds of lines {', '.join(f'{h}x' for h in self.harmonics)}{upto}"


class UnbalanceSpec(_Spec):
    """An unbalance at a node, turning with the rotor: static, couple or both (the case-file form
    of :class:`rotorlab.linear.Unbalance`, in ``[[analysis.unbalances]]`` of an
    ``unbalance_response`` and in ``[[model.unbalances]]`` of a ``machine``).

    Parameters
    ----------
    at : str, optional
        Name of the node (a body, disc or bearing name, or a node number as text).
    node : int, optional
        Node index.
    position : float, optional
        Axial position of a node (m).
    axial_offset : float
        Plane of the static unbalance from the node along +z (m).
    magnitude : float
        Static unbalance m e (kg*m), >= 0.
    phase : float
        Angle of its heavy spot from +x at t = 0, in the sense of rotation (rad).
    couple : float
        Couple unbalance U_c (kg*m^2), >= 0 (two opposite unbalances U at axial distance d, U d
        = U_c).
    couple_phase : float
        Angle of the couple's heavy spot on the +z side (rad).

    At least one of ``magnitude`` and ``couple`` is given.
    """

    description: ClassVar[str] = "unbalances"  # as a machine's part (rotorlab.io._part_specs)
    at: label() | None = Field(None, description="name of the node")
    node: integer(ge=0) | None = Field(None, description="node index")
    position: quantity("length") | None = Field(None, description="axial position (m)")
    axial_offset: quantity("length") = Field(0.0, description="offset of the static unbalance along +z (m)")
    magnitude: quantity("unbalance", ge=0) = Field(0.0, description="static unbalance m e (kg*m)")
    phase: quantity("angle") = Field(0.0, description="angle of the heavy spot (rad)")
    couple: quantity("couple_unbalance", ge=0) = Field(0.0, description="couple unbalance (kg*m^2)")
    couple_phase: quantity("angle") = Field(0.0, description="angle of the couple's +z heavy spot (rad)")

    @model_validator(mode="after")
    def _check_place(self) -> UnbalanceSpec:
        given = [k for k in ("at", "node", "position") if getattr(self, k) is not None]
        if len(given) != 1:
            what = "give one of at, node or position" if not given else (
                f"{' and '.join(given)} exclude each other: give only one")
            raise IssueGroup([Issue((), what, show_value=False)])
        if not {"magnitude", "couple"} & self.model_fields_set:
            raise IssueGroup([Issue((), "give magnitude (static unbalance, kg*m) or couple (couple "
                                        "unbalance, kg*m^2), or both", show_value=False)])
        return self

    def unbalance(self, node: int) -> Any:
        """The :class:`rotorlab.linear.Unbalance` (SI) at ``node`` (the located place)."""
        from rotorlab.linear._unbalance import Unbalance

        return Unbalance(node, self.magnitude, self.phase, self.axial_offset, self.couple, self.couple_phase)

    def build(self, node: int) -> Any:
        """The machine's unbalance at ``node`` (a plain :class:`rotorlab.linear.Unbalance`, which
        :class:`rotorlab.models.Machine` holds in ``unbalances`` and makes its part of)."""
        return self.unbalance(node)


class UnbalanceResponseSpec(_SpeedRange):
    """Steady response to rotating unbalances over a speed range.

    Parameters
    ----------
    name : str, optional
    start, stop : float
        Speed range (rad/s).
    n_speeds : int
        Number of speeds, >= 2.
    unbalances : tuple of UnbalanceSpec
        At least one.
    outputs : tuple of str
        Names of the nodes shown in tables and figures; default every named node (all nodes
        of a multibody model).
    """

    type: Literal["unbalance_response"] = "unbalance_response"
    n_speeds: integer(ge=2) = Field(201, description="number of equally spaced speeds")
    unbalances: tuple[UnbalanceSpec, ...] = Field(min_length=1, description="unbalances")
    outputs: tuple[label(), ...] = Field((), description="nodes to show, by name")

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check that the model has a linear structure and every unbalance and output is at one
        of its nodes."""
        model, issues = structure_issues(model)
        if issues:
            return issues
        for i, u in enumerate(self.unbalances):
            node, key, message = model.locate(u.node, u.at, u.position)
            if node is None:
                issues.append(Issue(("unbalances", i, key), message, getattr(u, key)))
        names = model.component_nodes()
        for i, name in enumerate(self.outputs):
            if name not in names:
                issues.append(Issue(("outputs", i), f"no node of that name (names: "
                                                    f"{', '.join(names)})", name))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        total = sum(u.magnitude for u in self.unbalances)
        couples = sum(u.couple for u in self.unbalances)
        return (f"unbalance response to {len(self.unbalances)} unbalance(s) "
                f"(total {total:.6g} kg*m" + (f", couples {couples:.6g} kg*m^2" if couples else "")
                + f"), {self._range_text()}")


class MeasurementSpec(_Spec):
    """One measured natural frequency.

    Parameters
    ----------
    speed : float
        Spin speed of the measurement (rad/s), >= 0.
    mode : int
        Rank of the natural frequency at that speed (0 = lowest), >= 0.
    frequency : float
        Measured frequency (Hz), > 0.
    weight : float
        Weight of its relative residual, > 0.
    """

    speed: quantity("angular_speed", ge=0) = Field(0.0, description="spin speed (rad/s)")
    mode: integer(ge=0) = Field(description="rank of the frequency, 0 = lowest")
    frequency: quantity("frequency", gt=0) = Field(description="measured frequency (Hz)")
    weight: quantity("dimensionless", gt=0) = Field(1.0, description="weight (-)")


class IdentifySpec(AbstractAnalysisSpec):
    """Fit model values (e.g. support stiffnesses) to measured natural frequencies.

    Parameters
    ----------
    name : str, optional
    parameters : tuple of str
        Key paths of positive numbers in ``[model]`` to fit, e.g.
        ``"elastic.geometry.housing.translational_stiffness"`` or ``"bearings[0].kxx"``; the
        model's values are the starting point.
    measurements : tuple of MeasurementSpec
        At least as many as parameters.
    elastic : ElasticSpec, optional
        Multibody models only: replaces ``[model.elastic]`` for this analysis, to fit a
        parametric (geometry) form of a structure the model gives as a matrix.
    """

    type: Literal["identify"] = "identify"
    parameters: tuple[str, ...] = Field(min_length=1, description="key paths in [model]")
    measurements: tuple[MeasurementSpec, ...] = Field(
        min_length=1, description="measured natural frequencies")
    elastic: ElasticSpec | None = Field(None, description="replaces [model.elastic]")

    def fit_model(self, model: AbstractLinearModelSpec) -> AbstractLinearModelSpec:
        """Return the model whose values are fitted (``elastic`` replaced if given)."""
        if self.elastic is None:
            return model
        return model.model_copy(update={"elastic": self.elastic})

    def paths(self) -> tuple[tuple[str | int, ...], ...]:
        """Return the parsed ``parameters``."""
        return tuple(parse_path(p) or () for p in self.parameters)

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the paths, the modes and the number of measurements against the model."""
        issues = linear_model_issues(model)
        if issues:
            return issues
        if self.elastic is not None:
            if not isinstance(model, MultibodySpec):
                return [Issue(("elastic",), "replaces [model.elastic]: only for a multibody "
                                            "model", show_value=False)]
            issues += [Issue(("elastic", *x.loc), x.message, x.value, x.show_value)
                       for x in elastic_issues(self.elastic, model.bodies)]
        base = self.fit_model(model)
        for k, text in enumerate(self.parameters):
            path = parse_path(text)
            if path is None:
                issues.append(Issue(("parameters", k), 'is not a key path (e.g. '
                                                       '"bearings[0].kxx")', text))
                continue
            value, message = base.value_at(path)
            if message:
                issues.append(Issue(("parameters", k), message, text))
            elif isinstance(value, bool) or not isinstance(value, float):
                issues.append(Issue(("parameters", k), "is not a number of the model" + (
                    " (not set: give it a starting value)" if value is None else ""), text))
            elif not value > 0:
                issues.append(Issue(("parameters", k), f"has the value {value:.6g}: a fitted "
                                                       "value must be > 0", text))
            elif text in self.parameters[:k]:
                issues.append(Issue(("parameters", k), "is listed twice", text))
        for j, m in enumerate(self.measurements):
            if m.mode >= model.n_dof:
                issues.append(Issue(("measurements", j, "mode"), f"must be < {model.n_dof} "
                                                                 "(the model's number of modes)",
                                    m.mode))
        if len(self.measurements) < len(self.parameters):
            issues.append(Issue(("measurements",), f"{len(self.measurements)} measurement(s) "
                                                   f"cannot determine {len(self.parameters)} "
                                                   "parameters", show_value=False))
        return issues

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        return (f"fit {', '.join(self.parameters)} to {len(self.measurements)} measured "
                f"frequencies")


class DataAuditSpec(AbstractAnalysisSpec):
    """Cross-check of a published data set against its own redundancies (findings table).

    Parameters
    ----------
    name : str, optional
    data : {"pico21"}
        Which data set: ``"pico21"`` is seed 000's printed tables
        (:func:`rotorlab.linear.cases.audit_pico21`).
    """

    type: Literal["data_audit"] = "data_audit"
    data: _choice(*AUDITED_DATA) = Field(description="the data set to audit")

    def describe(self, model: AbstractModelSpec) -> str:
        """Return a one-line description."""
        return f"audit of the printed data of {self.data}"
