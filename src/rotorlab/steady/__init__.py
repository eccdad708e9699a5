"""Steady motions of rotors with automatic-balancer balls or pendulums, and their stability.

At constant speed the steady motions of :class:`rotorlab.models.JeffcottBalls` are equilibria of
its co-rotating frame. This package lists them (:func:`find_steady_motions`: main motions, their
family for n >= 3, the 2^n side motions, with the support damping), assesses their stability
three ways (:func:`analyze_steady`: seed 003's Hamilton function, seed 002's averaged equations,
exact eigenvalues) and reports where those disagree; :func:`stability_chart` sweeps speed and a
parameter, :func:`verify` checks the predictions by simulation (basin fractions), :func:`run_up`
passes the critical speed with a prescribed omega(t). The seeds' typos and contradicted
conclusions are in :mod:`rotorlab.steady._corrections` (:data:`SEED_NOTES`); the built-in cases
``zhakash-k2`` and ``filimonikhin-n2`` in :func:`steady_case`.
"""

from rotorlab.steady._analysis import Disagreement, SteadyAnalysis, analyze_steady
from rotorlab.steady._cases import Regime, SteadyCase, steady_case, steady_case_names
from rotorlab.steady._chart import EXACT_VERDICTS, PARAMETERS, SteadyStability, stability_chart, stable_intervals, with_parameter
from rotorlab.steady._corrections import SEED_NOTES, SeedNote
from rotorlab.steady._motions import (
    SteadyMotion,
    find_steady_motions,
    main_family_angles,
    main_motions_exist,
    motion_labels,
    side_deflection,
)
from rotorlab.steady._runup import run_up
from rotorlab.steady._stability import Stability, assess_stability, averaged_jacobian, hessian_f
from rotorlab.steady._verify import OTHER_OUTCOMES, ball_grid, match_state, verify

__all__ = [
    "Disagreement",
    "EXACT_VERDICTS",
    "OTHER_OUTCOMES",
    "PARAMETERS",
    "Regime",
    "SEED_NOTES",
    "SeedNote",
    "Stability",
    "SteadyAnalysis",
    "SteadyCase",
    "SteadyMotion",
    "SteadyStability",
    "analyze_steady",
    "assess_stability",
    "averaged_jacobian",
    "ball_grid",
    "find_steady_motions",
    "hessian_f",
    "main_family_angles",
    "main_motions_exist",
    "match_state",
    "motion_labels",
    "run_up",
    "side_deflection",
    "stability_chart",
    "stable_intervals",
    "steady_case",
    "steady_case_names",
    "verify",
    "with_parameter",
]
