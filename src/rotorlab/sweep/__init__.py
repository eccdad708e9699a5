"""Sweeps at scale: one description for every analysis that maps over many points, run in chunks
in-process, on local processes or on a Dask cluster, checkpointed to a Zarr store and resumable.

Layers: a :class:`Sweep` says which points (grid :class:`GridAxis`/:class:`ListAxis`, a seeded
:class:`Sample`, or :class:`Points`) and which per-point analysis (any
:class:`AbstractPointAnalysis`, e.g. :class:`rotorlab.explore.MapperAnalysis`);
:func:`run_sweep` cuts it into chunks and runs :func:`compute_chunk` on an executor
(:class:`InProcess`, :class:`LocalProcesses`, :class:`DaskExecutor`); the results go to memory or
to a Zarr store (:func:`open_sweep` reads it back). Results are bit-identical whatever the
executor, the chunk size and the number of workers, and however often the run was interrupted
and resumed.
"""

from rotorlab.sweep._axes import GridAxis, ListAxis, Points, Sample
from rotorlab.sweep._eta import PILOT_ABOVE, Estimate, LongRunDeclined, human_duration, long_run_guard
from rotorlab.sweep._executors import DaskExecutor, ExecutorError, InProcess, LocalProcesses
from rotorlab.sweep._run import SweepProgress, run_sweep
from rotorlab.sweep._spec import DEFAULT_CHUNK, AbstractPointAnalysis, ChunkVar, Sweep, compute_chunk, describe_value
from rotorlab.sweep._store_read import SweepStoreError, open_sweep, store_info

__all__ = [
    "AbstractPointAnalysis",
    "ChunkVar",
    "DEFAULT_CHUNK",
    "DaskExecutor",
    "Estimate",
    "ExecutorError",
    "GridAxis",
    "InProcess",
    "ListAxis",
    "LocalProcesses",
    "LongRunDeclined",
    "PILOT_ABOVE",
    "Points",
    "Sample",
    "Sweep",
    "SweepProgress",
    "SweepStoreError",
    "compute_chunk",
    "describe_value",
    "human_duration",
    "long_run_guard",
    "open_sweep",
    "run_sweep",
    "store_info",
]
