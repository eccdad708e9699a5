"""From a validated case to results: build the model, run every analysis, summarize outcomes.

Each step looks the case's ``type`` strings up in the registries of
:mod:`rotorlab.analyses._registry` (:data:`MODEL_TYPES`, :data:`ANALYSIS_TYPES`; see its
"For implementers" list to add a type): simulations of the ``jeffcott_balls`` model
(:mod:`rotorlab.analyses._simulate`), basins and sweeps of it and of the ``toroidal_ball`` model
(:mod:`rotorlab.analyses._basin`), the linear analyses of the ``multibody`` and ``fe_rotor``
models (:mod:`rotorlab.analyses._linear`), the steady motions (:mod:`rotorlab.analyses._steady`)
and the impacts of the ``impact_rotor`` model (:mod:`rotorlab.analyses._impacts`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from rotorlab._compile_cache import compile_label
from rotorlab.analyses._registry import ANALYSIS_TYPES, MODEL_TYPES, analysis_entry
from rotorlab.io._built import built_model

if TYPE_CHECKING:
    import xarray

    from rotorlab.io import Case

__all__ = ["RUNNABLE_ANALYSES", "build_model", "run_analysis", "run_case", "summarize"]

#: Analysis types (the ``type`` of a case's ``[[analysis]]``) that :func:`run_case` can run: a
#: live view of the keys of :data:`ANALYSIS_TYPES`.
RUNNABLE_ANALYSES = ANALYSIS_TYPES.keys()


def _not_runnable(analysis: Any) -> str:
    return (f"analysis {analysis.name}: type {analysis.type!r} cannot be run here "
            f"(runnable: {', '.join(ANALYSIS_TYPES)})")  # fmt: skip


def build_model(case_model: Any) -> Any:
    """Build the model object of a validated case's ``[model]`` table: the one way from a spec
    to its model (inside :func:`rotorlab.io._built.built_model`, the model built already).

    Parameters
    ----------
    case_model : rotorlab.io.AbstractModelSpec
        ``Case.model`` (SI values, balls expanded).

    Returns
    -------
    object
        What the model type's entry in :data:`MODEL_TYPES` builds: for ``jeffcott_balls`` a
        :class:`~rotorlab.models.JeffcottBalls` whose speed profile is the case's
        ``[model.speed]``, or a rotor at rest (``ConstantSpeed(0)``) when the case gives none
        (analyses set their own speed); for a linear rotor model its
        :class:`~rotorlab.linear.LinearSystem`; for a toroidal ball the
        :class:`~rotorlab.models.ToroidalBall`; for an ``impact_rotor`` the
        :class:`~rotorlab.models.ImpactRotor`.

    Raises
    ------
    ValueError
        The model type is not registered.

    Examples
    --------
    >>> import math
    >>> from rotorlab.io import load_case
    >>> model = build_model(load_case("autobalancer").model)
    >>> model.n_balls, round(model.critical_speed / (2 * math.pi), 3)
    (2, 20.001)
    """
    kind = getattr(case_model, "type", None)
    if kind not in MODEL_TYPES:
        raise ValueError(f"cannot build a model of type {kind!r} (registered: {', '.join(MODEL_TYPES)})")
    return MODEL_TYPES[kind].build(case_model)


def model_quantities(case_model: Any) -> list[dict[str, Any]]:
    """The derived quantities of a case's model (its entry's ``quantities``; [] if unregistered)."""
    kind = getattr(case_model, "type", None)
    return MODEL_TYPES[kind].quantities(case_model) if kind in MODEL_TYPES else []


def run_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None,
                 model: Any = None) -> xarray.Dataset:  # fmt: skip
    """Run one analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.AbstractModelSpec
        ``Case.model``.
    analysis : rotorlab.io.AbstractAnalysisSpec
        One entry of ``Case.analyses``.
    progress : callable, optional
        ``progress(done, total)``, in the unit of the analysis type (trajectories of a
        simulation or basin; a linear analysis reports 0 of 1, then 1 of 1).
    model : object, optional
        The model built from ``case_model`` (:func:`build_model`) when the caller has it; built
        here otherwise. The analysis runs inside :func:`rotorlab.io._built.built_model`: every
        build of ``case_model`` below it gives this model (variants derive from it).

    Returns
    -------
    xarray.Dataset
        What the analysis type's entry in :data:`ANALYSIS_TYPES` returns (see
        :func:`rotorlab.analyses.simulate`, :func:`rotorlab.analyses.run_linear_analysis`, ...);
        ``attrs["name"]`` is the analysis name, ``attrs["analysis"]`` its type,
        ``attrs["model_type"]`` the model's type and ``attrs["model_quantities"]`` the model's
        derived quantities (JSON text).

    Raises
    ------
    ValueError
        The analysis type is not registered.
    """
    if analysis.type not in ANALYSIS_TYPES:
        raise ValueError(_not_runnable(analysis))
    kind = getattr(case_model, "type", None)
    with built_model(case_model, build_model(case_model) if model is None else model):
        ds = analysis_entry(kind, analysis.type).run(case_model, analysis, progress=progress)
        quantities = model_quantities(case_model)
    ds.attrs["name"] = analysis.name
    ds.attrs["analysis"] = analysis.type
    ds.attrs["model_type"] = str(kind)
    ds.attrs["model_quantities"] = json.dumps(quantities)
    return ds


def run_case(case: Case, progress: Callable[[str, int, int], None] | None = None,
             model: Any = None) -> dict[str, xarray.Dataset]:  # fmt: skip
    """Run every analysis of a case, in file order, on its model built once.

    Parameters
    ----------
    case : rotorlab.io.Case
        A validated case (:func:`rotorlab.io.load_case`).
    progress : callable, optional
        Called as ``progress(analysis_name, done, total)`` as trajectories finish.
    model : object, optional
        ``build_model(case.model)`` when the caller has built it (``rotorlab run`` does, for the
        sanity checks, the verdict and the report too); built here otherwise, once, and handed
        to every analysis (:func:`run_analysis`).

    Returns
    -------
    dict of str to xarray.Dataset
        Results by analysis name, in the case's order.

    Raises
    ------
    ValueError
        An analysis type is not in :data:`RUNNABLE_ANALYSES` (checked before anything runs).
    """
    for analysis in case.analyses:
        if analysis.type not in ANALYSIS_TYPES:
            raise ValueError(_not_runnable(analysis))
    if model is None:
        model = build_model(case.model)
    results = {}
    for analysis in case.analyses:
        report = None
        if progress is not None:

            def report(done: int, total: int, name: str = analysis.name) -> None:
                progress(name, done, total)

        with compile_label(f"case '{case.name}', analysis '{analysis.name}'"):
            ds = run_analysis(case.model, analysis, progress=report, model=model)
        ds.attrs["case"] = case.name
        results[analysis.name] = ds
    return results


def summarize(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a result: the rows of its analysis type (``attrs["analysis"]``).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_analysis` (or any analysis function that sets ``attrs["analysis"]``;
        a Dataset of :func:`rotorlab.analyses.simulate` without it is a simulation).

    Returns
    -------
    list of dict
        Plain Python values (JSON-ready; NaN becomes None). A simulation: one row per (speed,
        initial configuration), keys ``speed`` (rad/s), ``speed_rpm``, ``speed_hz``,
        ``speed_ratio`` (omega / p), ``ic``, ``initial_ball_angles_deg``, ``final_amplitude``
        (m), ``reference_amplitude`` (m), ``amplitude_ratio`` (final / reference),
        ``final_ball_angles_deg``, ``outcome``, ``status``; other types: see the ``rows`` of
        their entry (:func:`rotorlab.analyses.analysis_entry` of ``attrs["model_type"]``)
        (:func:`rotorlab.analyses.summarize_linear`, :func:`~rotorlab.analyses.steady_rows`,
        :func:`~rotorlab.analyses.basin_rows`, ...).
    """
    return analysis_entry(ds.attrs.get("model_type"), ds.attrs.get("analysis", "simulate")).rows(ds)
