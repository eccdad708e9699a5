"""What a design search minimises and how it searches: the registries of objectives
(:data:`DESIGN_OBJECTIVES`), optimisers (:data:`DESIGN_OPTIMIZERS`) and named constraints
(:data:`DESIGN_CONSTRAINTS`). The search itself, which
runs the evaluations on the basin-stability sweep, is :func:`rotorlab.analyses.design_search`.

This package sits below ``io`` (the case-file spec checks names against it) and ``analyses``; it
imports only ``models`` (and them only inside functions).
"""

from rotorlab.design._constraints import DESIGN_CONSTRAINTS, Constraint, register_constraint
from rotorlab.design._registry import (DESIGN_OBJECTIVES, DESIGN_OPTIMIZERS, DesignPoint, Objective, Optimizer,
                                       RunUpSettings, register_objective, register_optimizer)

__all__ = ["DESIGN_OBJECTIVES", "DESIGN_OPTIMIZERS", "DESIGN_CONSTRAINTS", "DesignPoint", "RunUpSettings", "Objective",
           "Optimizer", "Constraint", "register_objective", "register_optimizer", "register_constraint"]
