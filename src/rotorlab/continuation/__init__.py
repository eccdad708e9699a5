"""Continuation of steady motions and periodic orbits in any named parameter.

The numerical core (:mod:`rotorlab.continuation._core`) follows solution curves of
``F(x, lam) = 0`` by pseudo-arclength continuation and locates the zeros of test functions along
them (folds, branch points, Hopf points); the model-specific residuals (equilibria of a machine in
its co-rotating frame, periodic orbits by shooting) are built on it. Periodic orbits:
:func:`find_periodic_orbit` (one orbit by multiple shooting on the compiled integrator, Floquet
multipliers with the trivial one checked), :func:`continue_periodic` (a branch, with folds of
cycles, period doublings and torus points), starts :func:`orbit_from_hopf` and
:func:`orbit_from_simulation`; models with events are refused with a message saying why. On anisotropic supports the balanced
state's stability is a Floquet problem: :func:`floquet_boundary` continues its boundary in speed x
``support_anisotropy``.
"""

from rotorlab.continuation._anisotropic import ANISOTROPY, BalancedFloquet, floquet_boundary, with_anisotropy
from rotorlab.continuation._core import (
    ContinuationSettings,
    Crossing,
    Curve,
    CurvePoint,
    branch_point_test,
    continue_curve,
    fold_test,
    numerical_jacobian,
    switch_branch,
)
from rotorlab.continuation._equilibria import continue_equilibria, equilibrium_settings
from rotorlab.continuation._machine_problem import (
    NAMED_PARAMETERS,
    START_KINDS,
    MachineEquilibria,
    as_machine,
    current_value,
    format_value,
    parameter_unit,
    smooth_part_note,
    starting_motions,
    with_value,
)
from rotorlab.continuation._periodic import PeriodicOrbit, continue_periodic, find_periodic_orbit
from rotorlab.continuation._result import SPECIAL_POINT_TYPES, Branch, ContinuationResult, SpecialPoint
from rotorlab.continuation._starts import orbit_from_hopf, orbit_from_simulation
from rotorlab.continuation._two_parameter import TwoParameterCurve, continue_special_point, two_parameter_curves

__all__ = [
    "ANISOTROPY",
    "BalancedFloquet",
    "floquet_boundary",
    "with_anisotropy",
    "NAMED_PARAMETERS",
    "START_KINDS",
    "MachineEquilibria",
    "TwoParameterCurve",
    "as_machine",
    "continue_equilibria",
    "continue_special_point",
    "current_value",
    "two_parameter_curves",
    "equilibrium_settings",
    "format_value",
    "parameter_unit",
    "smooth_part_note",
    "starting_motions",
    "with_value",
    "SPECIAL_POINT_TYPES",
    "Branch",
    "ContinuationResult",
    "SpecialPoint",
    "ContinuationSettings",
    "Crossing",
    "Curve",
    "CurvePoint",
    "branch_point_test",
    "continue_curve",
    "fold_test",
    "numerical_jacobian",
    "switch_branch",
    "PeriodicOrbit",
    "continue_periodic",
    "find_periodic_orbit",
    "orbit_from_hopf",
    "orbit_from_simulation",
]
