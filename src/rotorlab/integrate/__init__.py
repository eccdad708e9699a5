"""The compiled ensemble integrator: adaptive Dormand–Prince 5(4), dense output, events and
reset maps (impacts, stick–slip), per-trajectory status codes, parallel over trajectories."""

from rotorlab.integrate._api import (
    EnsembleSolution,
    Event,
    SaveAt,
    Solution,
    Status,
    StepControl,
    solve,
    solve_ensemble,
)

__all__ = [
    "EnsembleSolution",
    "Event",
    "SaveAt",
    "Solution",
    "Status",
    "StepControl",
    "solve",
    "solve_ensemble",
]
