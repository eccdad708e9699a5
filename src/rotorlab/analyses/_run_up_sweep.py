"""A design's run-ups on the sweep engine: one point per ball start, so that a run-up design's
evaluations have what every sweep has (a Zarr store per design, resume, local processes or Dask
workers) and give the same numbers wherever they run.

Each point is one run-up from rest (:func:`rotorlab.analyses._machine_run_up.run_up_starts`) from
the start's ball angles, summarised by what the run-up objectives and constraints read: the time
to reach :data:`~rotorlab.analyses._design_run_up.REACHED` of the operating speed, the critical
speed it was captured at, the transient peak at each critical speed, its outcome and, with a
clearance, the largest distance of the clearance station from the stator's centre and the
contacts it made.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["RunUpStarts", "run_up_ensemble", "start_angles"]

#: Run-ups per chunk at most (a design's starts spread over the workers).
_CHUNK = 16


def start_angles(n_balls: int, starts: int, seed: int) -> np.ndarray:
    """The ball angles of a design's starts (rad), shape (starts, n_balls): uniform, from ``seed``
    (the same for every design: common random numbers); one start of no angles without balls."""
    if not n_balls:
        return np.zeros((1, 0))
    rng = np.random.default_rng(seed)
    return np.array([rng.uniform(0.0, 2 * np.pi, n_balls) for _ in range(starts)])


@dataclass(frozen=True, eq=False)
class RunUpStarts:
    """Per-point analysis (:class:`rotorlab.sweep.AbstractPointAnalysis`): the run-up of
    ``machine`` from start ``start`` (a coordinate: its row of ``angles``).

    Parameters
    ----------
    machine : Machine
        With a servo drive (:class:`rotorlab.models.ServoDrive`).
    angles : numpy.ndarray, shape (starts, n_balls)
        Ball angles of each start (rad).
    t_end : float
        Length of each run-up (s).
    n_save : int
        Saved states per run-up.
    """

    machine: Any
    angles: np.ndarray
    t_end: float
    n_save: int

    @property
    def coordinate_units(self) -> dict[str, str]:
        return {"start": "1"}

    def _critical(self) -> np.ndarray:
        from rotorlab.analyses._machine_run_up import _critical_speeds

        return _critical_speeds(self.machine)

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return {"critical": (self._critical(), {"units": "rad/s", "description": "forward 1x critical speeds, balls "
                                                "locked"})}  # fmt: skip

    def result_attrs(self) -> dict[str, Any]:
        c = self.machine.clearances
        return {"gap": float(c[0].gap) if c else math.nan, "t_end": float(self.t_end), "n_save": int(self.n_save)}

    def run_chunk(self, coords: dict[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        from rotorlab.analyses._design_run_up import reach_times
        from rotorlab.analyses._machine_run_up import run_up_starts
        from rotorlab.sweep import ChunkVar

        m = self.machine
        rows = [int(round(k)) for k in np.asarray(coords["start"], dtype=float)]
        starts = [tuple(self.angles[k]) for k in rows] if m.n_balls else [None] * len(rows)
        ds = run_up_starts(m, starts, t_end=self.t_end, n_save=self.n_save, initial_speed=m.drive.initial_speed)
        n = len(rows)
        outcome = np.array([str(o) for o in ds["outcome"].values])
        far = np.full(n, math.nan)
        impacts = np.zeros(n)
        if m.clearances:
            far = np.nanmax(np.asarray(ds["clearance_distance"].values, dtype=float).reshape(n, -1), axis=1)
            impacts = np.asarray(ds["impacts"].values, dtype=float).reshape(n)
        peaks = np.asarray(ds["critical_peak"].values, dtype=float).reshape(n, -1)
        return {
            "reach_time": ChunkVar((), reach_times(m, ds), {"units": "s", "description": "time to reach 99 % of the "
                                   "operating speed (inf: never)"}),
            "captured_at": ChunkVar((), np.asarray(ds["captured_at"].values, dtype=float).reshape(n),
                                    {"units": "rad/s", "description": "critical speed captured at (NaN: none)"}),
            "status": ChunkVar((), np.asarray(ds["status"].values).reshape(n).astype(np.int32), {"units": "1"}),
            "balanced": ChunkVar((), outcome == "balanced", {"units": "1"}),
            "failed": ChunkVar((), outcome == "failed", {"units": "1"}),
            "critical_peak": ChunkVar(("critical",), peaks, {"units": "m"}),
            "clearance_far": ChunkVar((), far, {"units": "m", "description": "largest distance of the clearance "
                                      "station from the stator's centre (NaN: no clearance)"}),
            "impacts": ChunkVar((), impacts, {"units": "1", "description": "contacts (impacts or onsets)"}),
        }  # fmt: skip


def run_up_ensemble(model, settings, *, store=None, resume: bool = False, executor=None):
    """The run-ups of a design (``settings`` a :class:`~rotorlab.design.RunUpSettings`) on the sweep
    engine: a Dataset over ``start`` (:class:`RunUpStarts`' variables)."""
    from rotorlab.analyses._design_run_up import run_up_t_end
    from rotorlab.sweep import GridAxis, Sweep, run_sweep

    angles = start_angles(model.n_balls, settings.starts, settings.seed)
    n = angles.shape[0]
    analysis = RunUpStarts(model, angles, run_up_t_end(model, settings), int(settings.n_save))
    sweep = Sweep(analysis, axes=(GridAxis("start", 0.0, float(n - 1), n),))
    return run_sweep(sweep, store=store, resume=resume, executor=executor,
                     chunk_size=None if resume and store is not None else max(1, min(_CHUNK, -(-n // 4))))
