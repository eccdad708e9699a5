"""The case-file schema, version 1: pydantic models whose fields hold SI floats after validation.

Layout of a case file::

    schema_version = 1           # optional
    name = "autobalancer"         # optional, defaults to the file name
    description = "one line"      # optional
    [model]                       # one model, chosen by `type` (see MODEL_SPECS)
    [model.speed]                 # tables and lists of the model (here: jeffcott_balls)
    [[model.balls]]
    [[analysis]]                  # zero or more analyses, chosen by `type` (see ANALYSIS_SPECS)

Every quantity accepts a plain number (SI) or a string with a unit (see :func:`to_si`).

The specs live in their own modules: field types and the abstract bases in
:mod:`rotorlab.io._fields`, the rotor with balls in :mod:`rotorlab.io._jeffcott_specs`, the
linear rotor models in :mod:`rotorlab.io._multibody_spec` and :mod:`rotorlab.io._fe_rotor_spec`,
the linear analyses in :mod:`rotorlab.io._linear_analyses`. This module registers them and
defines the :class:`Case`.

For implementers
----------------
1. A new model type is one class deriving from :class:`AbstractModelSpec` (a linear rotor:
   from :class:`~rotorlab.io._linear_common.AbstractLinearModelSpec`) with a field
   ``type: Literal["<name>"] = "<name>"``, registered with :func:`register_model_spec` (the
   built-in ones are listed in ``_BUILTIN_MODELS``). Override
   :attr:`~AbstractModelSpec.n_balls`, :meth:`~AbstractModelSpec.critical_speed` and
   :meth:`~AbstractModelSpec.speed_profile` where the model has them.
2. A new analysis type is one class deriving from :class:`AbstractAnalysisSpec` with a field
   ``type: Literal["<name>"] = "<name>"``, registered with :func:`register_analysis_spec`
   (built-in: ``_BUILTIN_ANALYSES``). Declare
   pairs of mutually exclusive keys in ``exclusive`` and the model types it runs on in
   ``model_types`` (None: any; the message for another type in ``wrong_model_message``); put
   other checks that need the model in :meth:`~AbstractAnalysisSpec.case_issues`, after
   ``super().case_issues(model)``. A model type with its own implementation of a common
   analysis type belongs to that type's ``model_types``.
3. Declare quantities with :func:`quantity` (dimension and bounds), integers with
   :func:`integer`, booleans with :func:`~rotorlab.io._fields.flag`; give every field a
   ``description`` (quoted when the key is missing). The unit shown in reports is data: the
   :class:`~rotorlab.io._fields.Unit` that :func:`quantity` puts in the field's type (a field
   with its own validator adds ``Unit("...")`` to its ``Annotated`` type).
4. Then give the type its behaviour: an entry in :data:`rotorlab.analyses.MODEL_TYPES` or
   :data:`rotorlab.analyses.ANALYSIS_TYPES` (see :mod:`rotorlab.analyses._registry`).
"""

from __future__ import annotations

from typing import Annotated, Any, Union

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PlainValidator,
    PrivateAttr,
    WithJsonSchema,
    field_validator,
    model_validator,
)

from rotorlab._registry import Registry
from rotorlab.io._basin_specs import BasinSpec, ToroidalBallSpec, WorkingPointSpec
from rotorlab.io._basin_stability_spec import BasinStabilitySpec
from rotorlab.io._design_spec import DesignSpec
from rotorlab.io._tolerances_spec import TolerancesSpec
from rotorlab.io._continuation_spec import ContinuationSpec
from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fe_rotor_spec import FeRotorSpec
from rotorlab.io._fields import (
    AbstractAnalysisSpec,
    AbstractModelSpec,
    _error,
    _Name,
    _Text,
    duplicate_name_issues,
    exclusive_issues,
    integer,
    plain_data,
    quantity,
)
from rotorlab.io._impact_specs import ImpactRotorSpec, ImpactsSpec, ImpactsSweepSpec
from rotorlab.io._jeffcott_specs import (
    SPEED_PROFILES,
    AbstractSpeedProfile,
    Ball,
    ConstantSpeed,
    HillSpeed,
    JeffcottBallsSpec,
    RampSpeed,
    SimulateSpec,
)
from rotorlab.io._linear_analyses import (
    CampbellSpec,
    CriticalSpeedsSpec,
    DataAuditSpec,
    IdentifySpec,
    ModesSpec,
    UnbalanceResponseSpec,
)
from rotorlab.io._knock_spec import MachineKnockSpec
from rotorlab.io._margin_specs import FrictionMarginSpec, ShockMarginSpec
from rotorlab.io._machine_spec import MachineSpec
from rotorlab.io._multibody_spec import MultibodySpec
from rotorlab.io._rub_specs import JeffcottRubSpec, RubMapSpec, RubSpec
from rotorlab.io._steady_specs import RunUpSpec, StabilityChartSpec, SteadySpec, VerifySpec
from rotorlab.io._sweep_specs import SweepSpec

__all__ = [
    "SCHEMA_VERSION",
    "quantity",
    "integer",
    "AbstractSpeedProfile",
    "ConstantSpeed",
    "RampSpeed",
    "HillSpeed",
    "SPEED_PROFILES",
    "Ball",
    "AbstractModelSpec",
    "JeffcottBallsSpec",
    "MultibodySpec",
    "FeRotorSpec",
    "ToroidalBallSpec",
    "ImpactRotorSpec",
    "ImpactsSpec",
    "ImpactsSweepSpec",
    "MODEL_SPECS",
    "register_model_spec",
    "model_union",
    "AbstractAnalysisSpec",
    "SimulateSpec",
    "CampbellSpec",
    "ModesSpec",
    "CriticalSpeedsSpec",
    "UnbalanceResponseSpec",
    "IdentifySpec",
    "DataAuditSpec",
    "BasinSpec",
    "WorkingPointSpec",
    "ANALYSIS_SPECS",
    "register_analysis_spec",
    "analysis_union",
    "Case",
    "exclusive_issues",
    "duplicate_name_issues",
]

#: The case-file schema version this module reads and writes.
SCHEMA_VERSION = 1

#: Model specifications by the value of their ``type`` key (a read-only mapping; add one with
#: :func:`register_model_spec`).
MODEL_SPECS: Registry[type[AbstractModelSpec]] = Registry("model type", on_change=lambda: _rebuild_case())

#: Analysis specifications by the value of their ``type`` key (a read-only mapping; add one with
#: :func:`register_analysis_spec`).
ANALYSIS_SPECS: Registry[type[AbstractAnalysisSpec]] = Registry("analysis type", on_change=lambda: _rebuild_case())

_BUILTIN_MODELS = (JeffcottBallsSpec, MultibodySpec, FeRotorSpec, ToroidalBallSpec, ImpactRotorSpec, MachineSpec,
                   JeffcottRubSpec)
_BUILTIN_ANALYSES = (SimulateSpec, CampbellSpec, ModesSpec, CriticalSpeedsSpec, UnbalanceResponseSpec, IdentifySpec,
                     DataAuditSpec, SteadySpec, StabilityChartSpec, VerifySpec, RunUpSpec, BasinSpec,
                     WorkingPointSpec, SweepSpec, BasinStabilitySpec, ImpactsSpec, ImpactsSweepSpec, RubSpec, MachineKnockSpec,
                     RubMapSpec, ContinuationSpec, ShockMarginSpec, FrictionMarginSpec, DesignSpec, TolerancesSpec)  # fmt: skip


def _type_key(spec: type[BaseModel]) -> str:
    info = spec.model_fields.get("type")
    if info is None or not isinstance(info.default, str):
        raise TypeError(f"{spec.__name__} has no field type: Literal[\"<name>\"] = \"<name>\"")
    return info.default


def model_union() -> Any:
    """The annotated union of every registered model spec, discriminated by ``type``."""
    return Annotated[Union[tuple(MODEL_SPECS.values())], Field(discriminator="type")]  # noqa: UP007


def analysis_union() -> Any:
    """The annotated union of every registered analysis spec, discriminated by ``type``."""
    return Annotated[Union[tuple(ANALYSIS_SPECS.values())], Field(discriminator="type")]  # noqa: UP007


def register_model_spec(spec: type[AbstractModelSpec], *, replace: bool = False) -> None:
    """Make a model type readable from case files (its key is its ``type`` field's default).

    Parameters
    ----------
    spec : type
        A subclass of :class:`AbstractModelSpec` with ``type: Literal["<name>"] = "<name>"``.
    replace : bool
        Replace a spec registered under the same name.
    """
    MODEL_SPECS.register(_type_key(spec), spec, replace=replace)


def register_analysis_spec(spec: type[AbstractAnalysisSpec], *, replace: bool = False) -> None:
    """Make an analysis type readable from case files (its key is its ``type`` field's default).

    See :func:`register_model_spec`; ``ANALYSIS_SPECS.registered(key, spec)`` registers one
    for the duration of a ``with`` block.
    """
    ANALYSIS_SPECS.register(_type_key(spec), spec, replace=replace)


# --------------------------------------------------------------------------- the case


class _SchemaVersionValidator:
    def __call__(self, value: Any) -> int:
        if isinstance(value, bool) or value != SCHEMA_VERSION:
            raise _error(f"unsupported schema version (this rotorlab reads {SCHEMA_VERSION})")
        return SCHEMA_VERSION


class Case(BaseModel):
    """A validated case: one model and the analyses to run on it, all values in SI.

    Build it with :func:`rotorlab.io.load_case`, :func:`rotorlab.io.parse_case` or
    :func:`rotorlab.io.validate_case`, which turn every problem into a
    :class:`~rotorlab.io.CaseError`; constructing it directly raises pydantic's
    ``ValidationError``.

    Parameters
    ----------
    schema_version : int
        Always 1.
    name : str
        Case name (ASCII letters, digits, '_', '-', '.').
    description : str
        One line shown by ``rotorlab cases``.
    model : JeffcottBallsSpec, MultibodySpec, FeRotorSpec, ToroidalBallSpec or ImpactRotorSpec
        The model (any of :data:`MODEL_SPECS`).
    analyses : tuple of SimulateSpec, CampbellSpec, ...
        The analyses in file order (key ``analysis`` in the file), with default names filled
        in (``"<type>-<index>"``).

    Attributes
    ----------
    source : str
        Path of the case file, ``"builtin:<name>"``, or the origin given to the parser.
    text : str
        The TOML text the case was read from ("" if built from Python objects).
    """

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    schema_version: Annotated[
        int, PlainValidator(_SchemaVersionValidator()), WithJsonSchema({"const": 1})
    ] = Field(SCHEMA_VERSION, description="case-file schema version")
    name: _Name = Field(description="case name")
    description: _Text = Field("", description="one-line description")
    model: Any = Field(description="the model ([model] table)")  # the union is set by _rebuild_case
    analyses: tuple[Any, ...] = Field(
        (), alias="analysis", description="analyses ([[analysis]] entries)"
    )

    _source: str = PrivateAttr("<python>")
    _text: str = PrivateAttr("")
    _overrides: dict[Any, Any] = PrivateAttr(default_factory=dict)

    @field_validator("analyses", mode="after")
    @classmethod
    def _name_analyses(cls, analyses: tuple[Any, ...]) -> tuple[Any, ...]:
        issues = duplicate_name_issues([(a.name, a.type) for a in analyses])
        if issues:
            raise IssueGroup(issues)
        return tuple(
            a if a.name is not None else a.model_copy(update={"name": f"{a.type}-{i}"})
            for i, a in enumerate(analyses)
        )

    @model_validator(mode="after")
    def _check_against_model(self) -> Case:
        issues = []
        for i, analysis in enumerate(self.analyses):
            for issue in analysis.case_issues(self.model):
                issues.append(
                    Issue(("analysis", i, *issue.loc), issue.message, issue.value, issue.show_value)
                )
        if issues:
            raise IssueGroup(issues)
        return self

    @property
    def source(self) -> str:
        """Path of the case file, ``"builtin:<name>"``, or the parser's origin."""
        return self._source

    @property
    def text(self) -> str:
        """The TOML text the case was read from."""
        return self._text

    @property
    def overrides(self) -> dict[Any, Any]:
        """The keys set on top of the file (``load_case(..., overrides=...)``, ``--set``); {} if none."""
        return dict(self._overrides)

    def analysis(self, name: str) -> Any:
        """Return the analysis called ``name``.

        Raises
        ------
        KeyError
            No analysis has that name; the message lists the names.
        """
        for a in self.analyses:
            if a.name == name:
                return a
        names = ", ".join(a.name for a in self.analyses) or "none"
        raise KeyError(f"no analysis named {name!r} (analyses: {names})")

    def model_dump_si(self) -> dict[str, Any]:
        """Return the case as plain Python data (dicts, lists, str, int, float, None), in SI.

        Keys follow the attribute names (``analyses``, not ``analysis``); ``source`` and
        ``text`` are not included.
        """
        return plain_data(self.model_dump(mode="python"))



def _rebuild_case() -> None:
    """Point ``Case.model`` and ``Case.analyses`` at the unions of the registered specs."""
    if not _READY:
        return  # still registering the built-in specs
    Case.model_fields["model"].annotation = model_union()
    Case.model_fields["analyses"].annotation = tuple[analysis_union(), ...]
    Case.model_rebuild(force=True)


_READY = False
for _spec in _BUILTIN_MODELS:
    register_model_spec(_spec)
for _spec in _BUILTIN_ANALYSES:
    register_analysis_spec(_spec)
_READY = True
_rebuild_case()
