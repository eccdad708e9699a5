"""The compiled ensemble integrator: adaptive Dormand–Prince 5(4), dense output, events and
reset maps (impacts, stick–slip), per-trajectory status codes, parallel over trajectories."""

from rotorlab.integrate._backends import BACKENDS, Backend, Lanes, Scalar, register_backend
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
    "BACKENDS",
    "Backend",
    "Lanes",
    "Scalar",
    "register_backend",
    "EnsembleSolution",
    "Event",
    "SaveAt",
    "Solution",
    "Status",
    "StepControl",
    "solve",
    "solve_ensemble",
]
