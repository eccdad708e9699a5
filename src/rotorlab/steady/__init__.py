"""Steady motions of rotors with automatic-balancer balls or pendulums, and their stability.

At constant speed the steady motions of :class:`rotorlab.models.JeffcottBalls` are equilibria of
its co-rotating frame. This package lists them (main motions, the family for n >= 3, and the
2^n side motions), assesses their stability three ways (seed 003's Hamilton function, seed 002's
averaged equations, exact eigenvalues) and reports where those disagree.
"""

from rotorlab.steady._analysis import Disagreement, SteadyAnalysis, analyze_steady
from rotorlab.steady._motions import (
    SteadyMotion,
    find_steady_motions,
    main_family_angles,
    main_motions_exist,
    motion_labels,
    side_deflection,
)
from rotorlab.steady._stability import Stability, assess_stability, averaged_jacobian, hessian_f

__all__ = [
    "Disagreement",
    "Stability",
    "SteadyAnalysis",
    "SteadyMotion",
    "analyze_steady",
    "assess_stability",
    "averaged_jacobian",
    "find_steady_motions",
    "hessian_f",
    "main_family_angles",
    "main_motions_exist",
    "motion_labels",
    "side_deflection",
]
