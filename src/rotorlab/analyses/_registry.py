"""The registries of model types and analysis types: one value per type, looked up, never branched on.

A case names its model and analyses by ``type`` strings. Everything that handles "any model" or
"any analysis" (:func:`rotorlab.analyses.build_model`, :func:`~rotorlab.analyses.run_analysis`,
:func:`~rotorlab.analyses.summarize`, ``rotorlab run``, the report, the sweep engine) looks the
type up here (and its presentation in :data:`rotorlab.report.PRESENTATIONS`) instead of testing
the string.

For implementers
----------------
A new model type or analysis type touches its spec, one entry here and (for a new family) one
presentation; no other module changes.

1. Write the case-file spec (:mod:`rotorlab.io`, see the "For implementers" list of
   :mod:`rotorlab.io._schema`) and register it: ``rotorlab.io.register_model_spec(MySpec)`` or
   ``rotorlab.io.register_analysis_spec(MySpec)``.
2. A model type: register a :class:`ModelType` whose ``build(spec)`` returns the model object
   the analyses use, whose ``quantities(spec)`` returns the derived quantities shown with the
   model's parameters (physics belongs here, not in the report) and, if its start-ups can be
   classified into regimes, whose ``mapper`` builds the regime mapper of basins and sweeps:
   ``register_model_type(ModelType("my_model", build=..., quantities=..., mapper=...))``.
   Where a common analysis type (``simulate``, ``steady``, ...) needs its own code for this
   model, give it in ``analyses`` as an :class:`AnalysisType` of the same name (same case-file
   spec; its own run, rows and presentation); :func:`analysis_entry` picks it.
3. An analysis type: register an :class:`AnalysisType` with

   - ``run(case_model, analysis, progress)``: a Dataset with ``attrs["name"]`` (the analysis
     name); ``attrs["analysis"]`` is set to the type by :func:`rotorlab.analyses.run_analysis`;
     call ``progress(done, total)`` as work finishes (``None`` allowed);
   - ``rows(ds)``: its summary rows, plain JSON-ready values, SI (or labelled ``_rpm``,
     ``_deg`` keys);
   - ``family``: the key of its presentation in :data:`rotorlab.report.PRESENTATIONS` (reuse one
     or register a new :class:`rotorlab.report.Presentation`: figures, report section, findings,
     console tables);
   - ``task_size(case_model, analysis)`` and ``progress_unit``: the total the progress bar of
     ``rotorlab run`` counts to and what it counts (default: one task, "done").

4. ``tests/unit/test_registries.py`` checks that every registered spec has an entry, every
   entry a presentation, and runs a toy analysis through :func:`~rotorlab.analyses.run_case`,
   ``rotorlab run`` and the report: copy it for yours.
"""

from __future__ import annotations

from collections.abc import Callable
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from rotorlab._registry import Registry

if TYPE_CHECKING:
    import xarray

__all__ = ["ModelType", "AnalysisType", "MODEL_TYPES", "ANALYSIS_TYPES", "register_model_type",
           "register_analysis_type", "analysis_entry"]  # fmt: skip

Progress = Callable[[int, int], None]


def one_task(case_model: Any, analysis: Any) -> int:
    """The task size of an analysis that reports only "started" and "done"."""
    return 1


def no_quantities(case_model: Any) -> list[dict[str, Any]]:
    """A model type without derived quantities."""
    return []


@dataclass(frozen=True)
class ModelType:
    """How a model spec becomes a model.

    Parameters
    ----------
    name : str
        The ``type`` of ``[model]`` in a case file (the key of its spec in
        :data:`rotorlab.io.MODEL_SPECS`).
    build : callable
        ``build(spec) -> model``: the model object the analyses use.
    quantities : callable
        ``quantities(spec) -> list of dict``: derived quantities (keys ``quantity``, ``value``
        (SI), ``unit``, ``sign`` ("" or "±")), carried in ``attrs["model_quantities"]`` of
        every result.
    mapper : callable, optional
        ``mapper(spec, analysis, options) -> rotorlab.explore.AbstractMapper or None``: the
        regime mapper (with ``start_value``, item 8 of its list) of ``basin`` and ``sweep`` analyses (``options``: keyword arguments of
        the mapper from the analysis, to complete); None (or a mapper returning None): the model
        has no basins.
    analyses : mapping of str to AnalysisType
        The model's own implementations of common analysis types, by analysis type: they read
        the same case-file spec as the common entry in :data:`ANALYSIS_TYPES` and replace its
        ``run``, ``rows`` and presentation for this model (see :func:`analysis_entry`).
    """

    name: str
    build: Callable[[Any], Any]
    quantities: Callable[[Any], list[dict[str, Any]]] = no_quantities
    mapper: Callable[[Any, Any, dict[str, Any]], Any] | None = None
    analyses: Mapping[str, AnalysisType] = field(default_factory=dict)

    def __post_init__(self) -> None:
        # within a run, building the run's spec gives the model the run built, and a spec object is
        # built once (rotorlab.io._built)
        object.__setattr__(self, "build", _handing_down(self.build))


def _handing_down(build: Callable[[Any], Any]) -> Callable[[Any], Any]:
    if getattr(build, "hands_down", False):
        return build

    def build_once(spec: Any) -> Any:
        from rotorlab.io._built import built_once

        return built_once(spec, build)

    build_once.hands_down = True  # type: ignore[attr-defined]
    build_once.__wrapped__ = build  # type: ignore[attr-defined]
    build_once.__doc__ = build.__doc__
    return build_once


@dataclass(frozen=True)
class AnalysisType:
    """How an analysis runs, what it reports and how its progress is counted.

    Parameters
    ----------
    name : str
        The ``type`` of an ``[[analysis]]`` (the key of its spec in
        :data:`rotorlab.io.ANALYSIS_SPECS`).
    run : callable
        ``run(case_model, analysis, progress=None) -> xarray.Dataset`` (``progress`` is passed
        by keyword).
    rows : callable
        ``rows(ds) -> list of dict``: summary rows (:func:`rotorlab.analyses.summarize`).
    family : str
        Its presentation (a key of :data:`rotorlab.report.PRESENTATIONS`).
    task_size : callable
        ``task_size(case_model, analysis) -> int``: the total of its progress.
    progress_unit : str
        What the progress counts ("trajectories", "done").
    """

    name: str
    run: Callable[..., xarray.Dataset]
    rows: Callable[[xarray.Dataset], list[dict[str, Any]]]
    family: str
    task_size: Callable[[Any, Any], int] = one_task
    progress_unit: str = "done"


#: Model types by the ``type`` of ``[model]``.
MODEL_TYPES: Registry[ModelType] = Registry("model type")

#: Analysis types by the ``type`` of ``[[analysis]]``.
ANALYSIS_TYPES: Registry[AnalysisType] = Registry("analysis type")


def register_model_type(entry: ModelType, *, replace: bool = False) -> None:
    """Add a :class:`ModelType` to :data:`MODEL_TYPES` (ValueError if its name is taken)."""
    MODEL_TYPES.register(entry.name, entry, replace=replace)


def register_analysis_type(entry: AnalysisType, *, replace: bool = False) -> None:
    """Add an :class:`AnalysisType` to :data:`ANALYSIS_TYPES` (ValueError if its name is taken)."""
    ANALYSIS_TYPES.register(entry.name, entry, replace=replace)


def analysis_entry(model_type: str | None, analysis_type: str) -> AnalysisType:
    """The entry that runs, tabulates and presents ``analysis_type`` on a ``model_type`` model.

    The model type's own implementation (:attr:`ModelType.analyses`) if it has one, else the
    common entry of :data:`ANALYSIS_TYPES` (KeyError naming the registered types if neither).
    """
    model = MODEL_TYPES.get(model_type) if model_type is not None else None
    if model is not None and analysis_type in model.analyses:
        return model.analyses[analysis_type]
    return ANALYSIS_TYPES[analysis_type]


# --------------------------------------------------------------------------- the built-in types


def _register_builtins() -> None:
    from rotorlab.analyses import _basin, _builders, _impacts, _linear, _machine, _rub, _simulate, _steady, _sweep
    from rotorlab.io._linear_build import build_linear_system

    machine = {"analyses": _machine.machine_analysis_types()}
    for name, build, quantities, mapper, *own in (
        ("jeffcott_balls", _builders.jeffcott_balls_model, _builders.jeffcott_quantities, _basin.balancer_mapper),
        ("multibody", build_linear_system, _builders.linear_quantities, None),
        ("fe_rotor", build_linear_system, _builders.linear_quantities, None),
        ("toroidal_ball", _builders.toroidal_ball_model, _builders.reference_speed_quantities, _basin.torus_mapper),
        ("impact_rotor", _impacts.impact_model, _builders.reference_speed_quantities, None),
        ("machine", _machine.machine_model, _machine.machine_quantities, _machine.machine_mapper, machine),
        ("rub_rotor", _rub.rub_model, _rub.rub_quantities, None),
    ):
        register_model_type(ModelType(name, build, quantities, mapper, **(own[0] if own else {})))

    trajectories = {"progress_unit": "trajectories"}
    register_analysis_type(AnalysisType("simulate", _simulate.run_simulate_analysis, _simulate.simulation_rows,
                                        "simulate", _simulate.simulation_task_size, **trajectories))  # fmt: skip
    for name in _linear.LINEAR_ANALYSES:
        register_analysis_type(AnalysisType(name, _linear.run_linear_case_analysis, _linear.summarize_linear,
                                            "linear"))  # fmt: skip
    for name in _steady.STEADY_ANALYSES:
        register_analysis_type(AnalysisType(name, _steady.run_steady_analysis, _steady.steady_rows, "steady"))
    register_analysis_type(AnalysisType("basin", _basin.run_basin_analysis, _basin.basin_rows, "basin",
                                        _basin.basin_task_size, **trajectories))  # fmt: skip
    register_analysis_type(AnalysisType("working-point", _basin.run_basin_analysis, _basin.basin_rows, "basin"))
    register_analysis_type(AnalysisType("sweep", _sweep.run_sweep_analysis, _basin.basin_rows, "basin",
                                        _sweep.sweep_task_size, **trajectories))  # fmt: skip
    from rotorlab.analyses import _basin_stability as _bs

    register_analysis_type(AnalysisType("basin-stability", _bs.run_basin_stability_analysis, _bs.basin_stability_rows,
                                        "basin-stability", _bs.basin_stability_task_size, **trajectories))  # fmt: skip
    register_analysis_type(AnalysisType("impacts", _impacts.run_impact_analysis, _impacts.impact_rows, "impacts"))
    register_analysis_type(AnalysisType("impacts-sweep", _impacts.run_impact_analysis, _impacts.sweep_rows,
                                        "impacts"))  # fmt: skip
    register_analysis_type(AnalysisType("rub", _rub.run_rub_analysis, _rub.rub_rows, "rub"))
    from rotorlab.analyses import _knock

    register_analysis_type(AnalysisType("machine-knock", _knock.run_knock_analysis, _knock.knock_rows, "knock",
                                        _knock.knock_task_size, **trajectories))  # fmt: skip
    register_analysis_type(AnalysisType("rub-map", _rub.run_rub_map, _rub.rub_map_rows, "rub-map",
                                        _rub.rub_map_task_size, progress_unit="points"))
    from rotorlab.analyses import _continuation, _friction_margin, _shock_margin

    register_analysis_type(AnalysisType("continuation", _continuation.run_continuation_analysis,
                                        _continuation.continuation_rows, "continuation"))
    register_analysis_type(AnalysisType("shock-margin", _shock_margin.run_shock_margin_analysis,
                                        _shock_margin.shock_margin_rows, "shock-margin",
                                        _shock_margin.shock_margin_task_size, progress_unit="ensembles"))
    register_analysis_type(AnalysisType("friction-margin", _friction_margin.run_friction_margin_analysis,
                                        _friction_margin.friction_margin_rows, "friction-margin"))
    from rotorlab.analyses import _design_case

    register_analysis_type(AnalysisType("design", _design_case.run_design_analysis, _design_case.design_rows, "design",
                                        _design_case.design_task_size, progress_unit="designs"))
    from rotorlab.analyses import _tolerances

    register_analysis_type(AnalysisType("tolerances", _tolerances.run_tolerances_analysis, _tolerances.tolerances_rows,
                                        "tolerances", _tolerances.tolerances_task_size, progress_unit="machines"))


_register_builtins()
