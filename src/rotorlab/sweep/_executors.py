"""Where the chunk function runs: in this process, in local worker processes, or on Dask (whose
local cluster runs its workers as threads of this process).

An executor is a frozen value; :meth:`imap` yields the results of the chunk tasks as they
finish (in any order) and cancels what is left when it is closed early (Ctrl-C, an error). The
chunk function (:func:`rotorlab.sweep.compute_chunk`) gives the same bits wherever it runs, so
the executor changes only the wall time.
"""

from __future__ import annotations

import contextlib
import os
import uuid
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

__all__ = ["InProcess", "LocalProcesses", "DaskExecutor", "ExecutorError"]

Task = tuple[int, dict]


class ExecutorError(ValueError):
    """An executor cannot start (e.g. no scheduler at the given address)."""


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _check_count(owner: str, name: str, value: Any) -> None:
    if value is not None and (isinstance(value, bool) or int(value) != value or value < 1):
        raise ValueError(f"{owner}.{name} must be an integer >= 1 or None, got {value!r}")


#: The chunk thread of :class:`InProcess` still running (abandoned by an interrupt), if any.
_chunk_thread: list[Any] = []

#: How often the waiting thread wakes up to let signal handlers run (s).
_WAKE = 0.05


def _interruptible(fn: Callable, *args: Any) -> Any:
    """``fn(*args)`` in a daemon thread, waited for in :data:`_WAKE` steps (signals act between
    them). A chunk abandoned by an earlier interrupt is waited for first: two parallel regions
    at once would abort numba's default threading layer."""
    import threading

    while _chunk_thread and _chunk_thread[0].is_alive():
        _chunk_thread[0].join(_WAKE)
    box: dict[str, Any] = {}

    def target() -> None:
        try:
            box["value"] = fn(*args)
        except BaseException as exc:  # noqa: BLE001 - handed to the waiting thread
            box["error"] = exc

    thread = threading.Thread(target=target, name="rotorlab-chunk", daemon=True)
    _chunk_thread[:] = [thread]
    thread.start()
    while thread.is_alive():
        thread.join(_WAKE)
    if "error" in box:
        raise box["error"]
    return box["value"]


@dataclass(frozen=True, slots=True)
class InProcess:
    """Run the chunks one after the other in this process (the integrator uses its threads).

    Parameters
    ----------
    threads : int, optional
        Integrator threads (default: numba's). Results do not depend on it.
    """

    threads: int | None = None

    def __post_init__(self) -> None:
        _check_count("InProcess", "threads", self.threads)

    def imap(self, fn: Callable, analysis: Any, tasks: Iterable[Task]) -> Iterator[Any]:
        """Yield ``fn(analysis, k, coords, threads)`` for every task ``(k, coords)``.

        Each chunk runs in a worker thread while this thread waits in short steps, so that a
        signal (Ctrl-C, SIGTERM) acts within a fraction of a second: Python runs signal
        handlers in the main thread only, and a chunk is one compiled call of many seconds that
        would hold it. An interrupted chunk is abandoned (its thread finishes in the background
        and its result is dropped); the chunks finished before it are kept.
        """
        for k, coords in tasks:
            yield _interruptible(fn, analysis, k, coords, self.threads)

    def describe(self) -> str:
        return "in-process"


@dataclass(frozen=True, slots=True)
class LocalProcesses:
    """Run the chunks in ``workers`` local processes (``concurrent.futures``, spawned).

    Parameters
    ----------
    workers : int
        Number of worker processes, >= 1.
    threads : int, optional
        Integrator threads per worker (default: cores // workers, at least 1).
    """

    workers: int = 2
    threads: int | None = None

    def __post_init__(self) -> None:
        _check_count("LocalProcesses", "workers", self.workers)
        _check_count("LocalProcesses", "threads", self.threads)

    def imap(self, fn: Callable, analysis: Any, tasks: Iterable[Task]) -> Iterator[Any]:
        """Yield the chunk results in the order they finish."""
        import multiprocessing
        from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

        threads = self.threads or max(1, _cores() // self.workers)
        pool = ProcessPoolExecutor(max_workers=self.workers, mp_context=multiprocessing.get_context("spawn"))
        pending: set = set()
        try:
            queue = iter(tasks)
            # keep a few tasks per worker in flight, not the whole sweep in memory
            for k, coords in queue:
                pending.add(pool.submit(fn, analysis, k, coords, threads))
                if len(pending) >= 2 * self.workers:
                    break
            while pending:
                finished, pending = wait(pending, return_when=FIRST_COMPLETED)
                for fut in finished:
                    yield fut.result()
                    nxt = next(queue, None)
                    if nxt is not None:
                        pending.add(pool.submit(fn, analysis, nxt[0], nxt[1], threads))
        finally:
            for fut in pending:
                fut.cancel()
            pool.shutdown(wait=True, cancel_futures=True)

    def describe(self) -> str:
        return f"{self.workers} local processes"


# Dask settings of the LocalCluster that --workers starts: its diagnostics poll several times a
# second in every process (the statistical profiler samples each worker's stack every 10 ms, the
# event-loop "tick" monitor runs every 20 ms, the system monitor every 0.5 s), which an idle
# 2-worker cluster measured as ~0.1 CPU-s per wall-second (bench/README.md). Nobody looks at them
# here (no dashboard), so they are slowed down or off. The memory monitor (pausing and restarting
# a worker process that runs out of memory) keeps its default; thread workers have none
# (local_cluster).
_QUIET = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.tick.limit": "10s",
    "distributed.admin.system-monitor.interval": "5s",
}


def local_cluster(workers: int, processes: bool = False):
    """The ``LocalCluster`` of :class:`DaskExecutor` (and of ``bench/sweep.py --idle-cluster``):
    ``workers`` single-threaded workers, no dashboard, quiet diagnostics (``_QUIET``).

    By default the workers are threads of this process: the compiled integrator releases the GIL
    (``nogil=True``), so they integrate in parallel, and nothing has to start. Worker processes
    (``processes=True``, each with its nanny) import rotorlab and load the compiled integrator
    again: ``rotorlab sweep --workers 2`` cost 4.3-4.6 CPU-s more than in-process with worker
    processes, 0.1-0.65 CPU-s more with thread workers (bench/README.md, issue 11 session 8).

    Thread workers have no memory limit: Dask measures a worker's memory as its process's, which
    for a thread is the whole command with the results it holds, and it pauses a worker above
    80 % of its share of the RAM: the sweep would wait as long as the command holds that much
    (seen: a 300 MB limit and a 320 MB array in the process, the task never ran). Worker processes
    keep Dask's default.
    """
    import logging

    import dask
    from distributed import LocalCluster

    with dask.config.set(_QUIET):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=processes, dashboard_address=None,
                            memory_limit="auto" if processes else 0, silence_logs=logging.ERROR)  # fmt: skip


def _parallel_regions_threadsafe() -> bool:
    """Whether numba's threading layer runs parallel regions launched from several threads at once
    (``tbb`` and ``omp`` do; ``workqueue``, the only one numba guarantees, aborts the process)."""
    import numba

    numba.get_num_threads()  # starts the threading layer, so that it can be asked for its name
    return numba.threading_layer() != "workqueue"


@dataclass(frozen=True)
class DaskExecutor:
    """Run the chunks as tasks on a Dask cluster (``dask.distributed``).

    Parameters
    ----------
    scheduler : str, optional
        Address of a running scheduler (``tcp://HOST:PORT``).
    workers : int, optional
        Without ``scheduler``: start a ``LocalCluster`` of this many single-threaded workers for
        the sweep (default 2) and close it afterwards. They are threads of this process
        (:func:`local_cluster`), or processes where each task runs a parallel region
        (``threads`` > 1) and numba's threading layer cannot run two at once (``workqueue``).
    threads : int, optional
        Integrator threads per task (default: cores // workers on a local cluster, numba's
        default on a remote one). Results do not depend on it.
    client : distributed.Client, optional
        Use this client instead (it is not closed afterwards).

    Notes
    -----
    Dask reschedules the tasks of a worker that dies on the remaining workers (up to its
    ``distributed.scheduler.allowed-failures`` retries), so the sweep completes with the same
    results; the driver writes every result to the store itself, so workers need no shared file
    system.
    """

    scheduler: str | None = None
    workers: int | None = None
    threads: int | None = None
    client: Any = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        _check_count("DaskExecutor", "workers", self.workers)
        _check_count("DaskExecutor", "threads", self.threads)
        if self.scheduler is not None and self.workers is not None:
            raise ValueError("DaskExecutor: give scheduler (a running cluster) or workers (a local one), not both")
        if self.scheduler is not None and (not isinstance(self.scheduler, str) or "://" not in self.scheduler):
            raise ValueError(f"DaskExecutor.scheduler must be an address like tcp://HOST:PORT, got {self.scheduler!r}")

    def imap(self, fn: Callable, analysis: Any, tasks: Iterable[Task]) -> Iterator[Any]:
        """Submit every task, then yield results as they finish."""
        from distributed import as_completed

        client, threads, owned = self._connect()
        run = uuid.uuid4().hex[:12]
        futures = []
        try:
            for k, coords in tasks:
                futures.append(client.submit(fn, analysis, k, coords, threads, key=f"rotorlab-chunk-{run}-{k}"))
            for fut in as_completed(futures):
                result = fut.result()
                fut.release()
                yield result
        finally:
            pending = [f for f in futures if not f.done()]
            if pending:
                client.cancel(pending)
            for obj in owned:
                try:
                    obj.close()
                except Exception:  # noqa: BLE001, S110 - closing is best effort
                    pass

    def _connect(self) -> tuple[Any, int | None, list[Any]]:
        """The client, the integrator threads per task and what to close afterwards."""
        from distributed import Client

        if self.client is not None:
            return self.client, self.threads, []
        if self.scheduler is not None:
            try:
                client = Client(self.scheduler, timeout="10s")
            except (OSError, TimeoutError) as exc:
                raise ExecutorError(f"--scheduler = {self.scheduler}: cannot connect ({exc})") from None
            return client, self.threads, [client]
        n = self.workers or 2
        threads = self.threads or max(1, _cores() // n)
        cluster = local_cluster(n, processes=threads > 1 and not _parallel_regions_threadsafe())
        client = Client(cluster)
        return client, threads, [client, cluster]

    @contextlib.contextmanager
    def session(self) -> Iterator[DaskExecutor]:
        """This executor bound to one client for several runs (a local cluster starts once), e.g.
        the rounds of an adaptive basin stability."""
        client, threads, owned = self._connect()
        try:
            yield DaskExecutor(threads=threads, client=client)
        finally:
            for obj in owned:
                try:
                    obj.close()
                except Exception:  # noqa: BLE001, S110 - closing is best effort
                    pass

    def describe(self) -> str:
        if self.client is not None:
            return "Dask (given client)"
        return f"Dask at {self.scheduler}" if self.scheduler else f"Dask LocalCluster of {self.workers or 2} workers"
