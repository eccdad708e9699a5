"""Run a sweep: cut it into chunks, run the chunk function on an executor, keep every result."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from rotorlab.sweep._spec import DEFAULT_CHUNK, Sweep, compute_chunk
from rotorlab.sweep._store import MemorySink, ZarrSink

__all__ = ["run_sweep", "SweepProgress"]


@dataclass(frozen=True, slots=True)
class SweepProgress:
    """Where a sweep stands, passed to the ``progress`` callback after each chunk.

    Parameters
    ----------
    done : int
        Points finished (including those of a resumed store).
    total : int
        Points of the sweep.
    chunks_done, n_chunks : int
        The same in chunks.
    computed : int
        Chunks computed by this run so far.
    skipped : int
        Chunks already in the store when this run started.
    """

    done: int
    total: int
    chunks_done: int
    n_chunks: int
    computed: int
    skipped: int


def run_sweep(
    sweep: Sweep,
    *,
    store: Any = None,
    resume: bool = False,
    chunk_size: int | None = None,
    executor: Any = None,
    progress: Callable[[SweepProgress], None] | None = None,
    only: Any = None,
):
    """Run a sweep chunk by chunk and return its results as a Dataset.

    Parameters
    ----------
    sweep : Sweep
        What to compute.
    store : path-like or MemorySink, optional
        A Zarr store (folder) to write each chunk to as it finishes, with a completion mark; the
        result is then read back from it. Without it, results are collected in memory (in the
        given ``MemorySink`` of this sweep, which keeps them for the next run).
    resume : bool
        Continue the store: compute only its missing chunks. The store must hold the same sweep
        (same :meth:`Sweep.describe`) written by the same rotorlab version; a store that does not
        exist yet is created.
    chunk_size : int, optional
        Points per chunk (default :data:`DEFAULT_CHUNK`, or the store's when resuming). Results
        do not depend on it.
    executor : InProcess, LocalProcesses or DaskExecutor, optional
        Where chunks run (default :class:`InProcess`). Results do not depend on it.
    progress : callable, optional
        ``progress(SweepProgress)`` once at the start and after each finished chunk.
    only : iterable of int, optional
        Compute only these chunks (those not yet done); the others stay missing and the Dataset
        holds fill values there (NaN / 0 / False, as :func:`~rotorlab.sweep.open_sweep` with
        ``partial=True``). For sweeps that choose their next points from the results so far
        (adaptive basin stability, :func:`rotorlab.explore.basin_stability_over`).

    Returns
    -------
    xarray.Dataset
        Dims: the sweep's dims (one per axis, or the sample / point-list dim) then the
        analysis's trailing dims; see :func:`rotorlab.sweep.open_sweep`.

    Raises
    ------
    SweepStoreError
        The store exists without ``resume``, or cannot be resumed (another sweep, damaged).
    LongRunDeclined
        Run inside :func:`rotorlab.sweep.long_run_guard`, the sweep had
        :data:`~rotorlab.sweep.PILOT_ABOVE` points or more, and the guard declined its
        estimate (timed on a pilot before anything is written).
    KeyboardInterrupt
        Re-raised after the running tasks are cancelled; every finished chunk is in the store.

    Examples
    --------
    >>> from rotorlab.explore import MapperAnalysis, TorusRegimes
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> from rotorlab.sweep import GridAxis, Sweep
    >>> sw = Sweep(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=1.0, n_horizons=1)),
    ...            axes=(GridAxis("psi", 1.0, 5.0, 3),))
    >>> ds = run_sweep(sw, chunk_size=2)
    >>> ds.outcome.dims, ds.outcome.sizes["psi"]
    (('psi',), 3)
    """
    from rotorlab.sweep._eta import check_long_run
    from rotorlab.sweep._executors import InProcess

    if not isinstance(sweep, Sweep):
        raise TypeError(f"sweep must be a Sweep, got {type(sweep).__name__}")
    threads = getattr(executor, "threads", None)
    fresh = store is not None and not isinstance(store, MemorySink) and not resume and only is None
    if fresh:  # a new store: asked before it is created (a declined sweep writes nothing)
        check_long_run(sweep, sweep.n_points, threads)
    if isinstance(store, MemorySink):  # chunks kept in memory between runs of this sweep
        if store.sweep is not sweep or (chunk_size is not None and chunk_size != store.chunk_size):
            raise ValueError("a MemorySink store continues only the sweep (and chunk size) it was made for")
        sink: Any = store
        size = store.chunk_size
    elif store is None:
        if resume:
            raise ValueError("resume needs a store")
        sink = MemorySink(sweep, chunk_size)
        size = DEFAULT_CHUNK if chunk_size is None else chunk_size
    else:
        sink = ZarrSink(store, sweep, chunk_size, resume=resume)
        size = sink.chunk_size
    ranges = sweep.chunks(size)
    considered = range(len(ranges)) if only is None else sorted({int(k) for k in only})
    if considered and not 0 <= considered[0] <= considered[-1] < len(ranges):
        sink.close()
        raise ValueError(f"only: chunk numbers must be in [0, {len(ranges) - 1}], got {considered[0]}..{considered[-1]}")
    missing = set(sink.missing(len(ranges)))
    todo = [k for k in considered if k in missing]
    total = sum(ranges[k][1] - ranges[k][0] for k in considered)
    done = total - sum(ranges[k][1] - ranges[k][0] for k in todo)
    skipped = len(considered) - len(todo)
    if not fresh:  # in memory, resumed, or some chunks only (a round of an adaptive sweep, asked once
        # for all its missing points: the most it may compute): asked for the points left
        left = total - done if only is None else sum(ranges[k][1] - ranges[k][0] for k in missing)
        try:
            check_long_run(sweep, left, threads)
        except BaseException:
            sink.close()
            raise
    coords = sweep.coordinates()

    def tasks():
        for k in todo:
            lo, hi = ranges[k]
            yield k, {name: values[lo:hi] for name, values in coords.items()}

    def report(computed: int) -> None:
        if progress is not None:
            progress(SweepProgress(done, total, skipped + computed, len(considered), computed, skipped))

    report(0)
    results = (executor or InProcess()).imap(compute_chunk, sweep.analysis, tasks())
    computed = 0
    try:
        for k, result in results:
            lo, hi = ranges[k]
            sink.write(k, lo, hi, result)
            computed += 1
            done += hi - lo
            report(computed)
    finally:
        results.close()
        sink.close()
    return sink.dataset(partial=only is not None)
