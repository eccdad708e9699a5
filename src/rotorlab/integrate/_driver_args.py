"""The grouped arguments of the compiled drivers (scalar :mod:`._core` and lanes :mod:`._lanes`).

Every driver entry point takes ``(inputs, settings, events, outputs, n_threads)``. The groups are
named tuples, which numba passes by value and reads by attribute (``inputs.Y0``) without cost.
They live in this module, not in the templates, so that every generated copy of a template uses
the same classes (numba's cache keys on them).

Inputs whose first dimension is 1 are shared by all trajectories (``Y0``, ``P``, ``T1``, ``TS``).
"""

from typing import NamedTuple

import numpy as np

__all__ = ["Inputs", "Settings", "EventTable", "Outputs"]


class Inputs(NamedTuple):
    """What each trajectory starts from."""

    Y0: np.ndarray  # (1 or N, n) initial states
    P: np.ndarray  # (1 or N, n_param) packed parameters
    T1: np.ndarray  # (1 or N,) end times (s)
    TS: np.ndarray  # (1 or N, n_save) save times (s), inf-padded
    atol: np.ndarray  # (n,) absolute tolerance per state


class Settings(NamedTuple):
    """Scalars of the step-size control."""

    t0: float  # start time (s)
    rtol: float
    n_cont: int  # leading continuous states (the rest are discrete modes)
    first_step: float  # <= 0: automatic
    max_step: float
    max_steps: int  # step attempts per trajectory


class EventTable(NamedTuple):
    """The model's event functions and what each does (``_core.ACT_*``)."""

    n_ev: int
    ev_dir: np.ndarray  # int64 (max(n_ev, 1),): -1, 0, +1
    ev_act: np.ndarray  # int64 (max(n_ev, 1),): ACT_RESET, ACT_STOP, ACT_COUNT, ACT_OFF


class Outputs(NamedTuple):
    """Buffers the driver writes, one row per trajectory."""

    YS: np.ndarray  # (N, n_save, n) saved states
    YF: np.ndarray  # (N, n) final states
    STATUS: np.ndarray  # int64 (N,)
    TEND: np.ndarray  # (N,) end times (s)
    EVC: np.ndarray  # int64 (N, max(n_ev, 1)) event counts
    RECT: np.ndarray  # (N, max_rec) event times (s)
    RECK: np.ndarray  # int64 (N, max_rec) which event
    STATS: np.ndarray  # int64 (N, 4) nfev, naccept, nreject, nevents
