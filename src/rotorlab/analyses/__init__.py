"""Analyses: pure functions from models (or validated cases) to labelled xarray Datasets.

Model types and analysis types are registered values (:data:`MODEL_TYPES`,
:data:`ANALYSIS_TYPES`; see the "For implementers" list of :mod:`rotorlab.analyses._registry`).
Nothing here plots or writes files; see :mod:`rotorlab.plot`, :mod:`rotorlab.report` and the
command line (:mod:`rotorlab.cli`) for that.
"""

from rotorlab.analyses._basin import (
    BASIN_ANALYSES,
    basin_document,
    basin_mapper,
    basin_rows,
    compare_basins,
    run_basin,
    run_basin_analysis,
)
from rotorlab.analyses._case import (
    RUNNABLE_ANALYSES,
    build_model,
    model_quantities,
    run_analysis,
    run_case,
    summarize,
)
from rotorlab.analyses._registry import (
    ANALYSIS_TYPES,
    MODEL_TYPES,
    AnalysisType,
    ModelType,
    analysis_entry,
    register_analysis_type,
    register_model_type,
)
from rotorlab.analyses import _impact_sweep, _impacts
from rotorlab.analyses._impact_sweep import ImpactAnalysis, impact_sweep, impact_sweep_definition, summarize_impact_sweep
from rotorlab.analyses._impacts import (
    IMPACT_ANALYSES,
    REGIMES,
    SEED001_TABLE,
    SLIDING_CONVENTIONS,
    SLIDING_FRACTION,
    SWEEP_PARAMS,
    classify_impacts,
    impact_model,
    impact_run,
    impact_summary,
    paper_counts,
    run_impact_analysis,
    stacked_params,
    sweep_summary,
)
from rotorlab.analyses._linear import (
    DATA_AUDITS,
    LINEAR_ANALYSES,
    campbell_summary,
    critical_summary,
    critical_entry,
    modes_summary,
    run_linear_analysis,
    summarize_linear,
)
from rotorlab.io._linear_build import build_linear_system
from rotorlab.explore._outcome import (
    BALANCED_FRACTION,
    SETTLE_RATE,
    SIDE_TOLERANCE,
    classify,
    reference_amplitude,
    wrap_angle,
)
from rotorlab.analyses._simulate import SETTLE_REVOLUTIONS, simulate
from rotorlab.analyses._facts import MACHINE_FACTS, MachineFacts, machine_facts, register_machine_facts
from rotorlab.analyses._page_verdict import VERDICT_EVIDENCE, VerdictLine, explain_regime, machine_verdict, register_evidence
from rotorlab.analyses._sanity import SANITY_CHECKS, SanityWarning, register_sanity_check, sanity_warnings
from rotorlab.analyses._machine import machine_simulate, machine_steady
from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search
from rotorlab.analyses._machine_run_up import PassingTorque, machine_run_up, passing_torque
from rotorlab.analyses._steady import (
    STEADY_ANALYSES,
    chart_intervals,
    run_steady_analysis,
    steady_document,
    steady_model,
    steady_rows,
)

__all__ = [
    "DesignProblem",
    "DesignVariable",
    "design_search",
    "MACHINE_FACTS",
    "MachineFacts",
    "machine_facts",
    "register_machine_facts",
    "VERDICT_EVIDENCE",
    "VerdictLine",
    "explain_regime",
    "machine_verdict",
    "register_evidence",
    "SANITY_CHECKS",
    "SanityWarning",
    "register_sanity_check",
    "sanity_warnings",
    "PassingTorque",
    "passing_torque",
    "machine_run_up",
    "machine_simulate",
    "machine_steady",
    *_impacts.__all__,
    *_impact_sweep.__all__,
    "ANALYSIS_TYPES",
    "AnalysisType",
    "BALANCED_FRACTION",
    "MODEL_TYPES",
    "ModelType",
    "analysis_entry",
    "model_quantities",
    "register_analysis_type",
    "register_model_type",
    "BASIN_ANALYSES",
    "DATA_AUDITS",
    "LINEAR_ANALYSES",
    "RUNNABLE_ANALYSES",
    "SETTLE_RATE",
    "SETTLE_REVOLUTIONS",
    "SIDE_TOLERANCE",
    "STEADY_ANALYSES",
    "basin_document",
    "basin_mapper",
    "basin_rows",
    "build_linear_system",
    "build_model",
    "chart_intervals",
    "campbell_summary",
    "critical_entry",
    "critical_summary",
    "classify",
    "compare_basins",
    "modes_summary",
    "reference_amplitude",
    "run_analysis",
    "run_basin",
    "run_basin_analysis",
    "run_case",
    "run_linear_analysis",
    "run_steady_analysis",
    "simulate",
    "steady_document",
    "steady_model",
    "steady_rows",
    "summarize",
    "summarize_linear",
    "wrap_angle",
]
