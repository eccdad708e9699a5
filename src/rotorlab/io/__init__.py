"""Case files (TOML, validated, converted to SI) and result files (NetCDF).

A case file describes one model and the analyses to run on it. Plain numbers are SI; strings
carry units (``"14800 rpm"``, ``"882 kg*mm^2"``, ``"30 deg"``, ``"3 MN/m"``, ``"211 GPa"``) and are converted
with pint, which is imported only when a unit has to be read. Every problem in a case is
reported in one :class:`CaseError` naming the key path, the value and what is allowed.

Examples
--------
>>> from rotorlab.io import load_case
>>> case = load_case("autobalancer")
>>> round(case.model.critical_speed() / (2 * 3.141592653589793), 2)
20.0
"""

from rotorlab.io._basin_specs import BasinSpec, ToroidalBallSpec, WorkingPointSpec
from rotorlab.io._continuation_spec import ContinuationSpec
from rotorlab.io._coordinates import BALANCER_COORDINATES, TORUS_COORDINATES, coordinate_dimensions
from rotorlab.io._case import builtin_cases, dump_case, load_case, parse_case, validate_case
from rotorlab.io._errors import CaseError, Issue
from rotorlab.io._overrides import apply_overrides, parse_key_path, parse_override
from rotorlab.io._results import load_netcdf, missing_units, save_netcdf
from rotorlab.io._ross import ROSS_ELEMENTS, import_ross
from rotorlab.io._templates import TEMPLATES, ross_case_text, template_text, write_case_text
from rotorlab.io._linear_common import AbstractLinearModelSpec
from rotorlab.io._fields import Unit, field_unit
from rotorlab.io._schema import (
    ANALYSIS_SPECS,
    MODEL_SPECS,
    SCHEMA_VERSION,
    SPEED_PROFILES,
    AbstractAnalysisSpec,
    AbstractModelSpec,
    AbstractSpeedProfile,
    Ball,
    CampbellSpec,
    Case,
    ConstantSpeed,
    CriticalSpeedsSpec,
    DataAuditSpec,
    FeRotorSpec,
    HillSpeed,
    IdentifySpec,
    JeffcottBallsSpec,
    ModesSpec,
    MultibodySpec,
    RampSpeed,
    SimulateSpec,
    UnbalanceResponseSpec,
    analysis_union,
    integer,
    model_union,
    quantity,
    register_analysis_spec,
    register_model_spec,
)
from rotorlab.io._impact_specs import (
    IMPACT_SWEEP_PARAMETERS,
    HousingSpec,
    ImpactRotorSpec,
    ImpactsSpec,
    ImpactsSweepSpec,
    StonesSpec,
)
from rotorlab.io._steady_specs import (
    STEADY_PARAMETERS,
    RunUpSpec,
    StabilityChartSpec,
    SteadyAnalysisSpec,
    SteadySpec,
    VerifySpec,
)
from rotorlab.io._sweep_specs import SweepSpec
from rotorlab.io._basin_stability_spec import BasinStabilitySpec
from rotorlab.io._design_spec import DesignSpec
from rotorlab.io._tolerances_spec import TolerancesSpec
from rotorlab.io._units import ACCEPTED_UNITS, DIMENSIONS, Dimension, to_si

__all__ = [
    "apply_overrides",
    "parse_key_path",
    "parse_override",
    "IMPACT_SWEEP_PARAMETERS",
    "HousingSpec",
    "ImpactRotorSpec",
    "ImpactsSpec",
    "ImpactsSweepSpec",
    "StonesSpec",
    "ACCEPTED_UNITS",
    "ANALYSIS_SPECS",
    "Unit",
    "analysis_union",
    "field_unit",
    "model_union",
    "register_analysis_spec",
    "register_model_spec",
    "BALANCER_COORDINATES",
    "DIMENSIONS",
    "MODEL_SPECS",
    "SCHEMA_VERSION",
    "SPEED_PROFILES",
    "STEADY_PARAMETERS",
    "TORUS_COORDINATES",
    "AbstractAnalysisSpec",
    "AbstractLinearModelSpec",
    "AbstractModelSpec",
    "AbstractSpeedProfile",
    "Ball",
    "BasinSpec",
    "CampbellSpec",
    "ContinuationSpec",
    "Case",
    "CaseError",
    "ConstantSpeed",
    "CriticalSpeedsSpec",
    "DataAuditSpec",
    "Dimension",
    "FeRotorSpec",
    "HillSpeed",
    "IdentifySpec",
    "Issue",
    "JeffcottBallsSpec",
    "ModesSpec",
    "MultibodySpec",
    "RampSpeed",
    "RunUpSpec",
    "SimulateSpec",
    "StabilityChartSpec",
    "SteadyAnalysisSpec",
    "SteadySpec",
    "ToroidalBallSpec",
    "SweepSpec",
    "BasinStabilitySpec",
    "DesignSpec",
    "TolerancesSpec",
    "UnbalanceResponseSpec",
    "VerifySpec",
    "WorkingPointSpec",
    "builtin_cases",
    "import_ross",
    "ROSS_ELEMENTS",
    "TEMPLATES",
    "template_text",
    "write_case_text",
    "ross_case_text",
    "coordinate_dimensions",
    "dump_case",
    "integer",
    "load_case",
    "load_netcdf",
    "missing_units",
    "parse_case",
    "quantity",
    "save_netcdf",
    "to_si",
    "validate_case",
]
