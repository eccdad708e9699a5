"""What the commands that run on the sweep engine share (``sweep``, ``show``, ``basin``,
``impacts-sweep``): the ``--scheduler``/``--workers`` options, checks of a store path and of the
executor options, running into a store (store and executor errors are bad input, Ctrl-C keeps the
finished chunks) and the progress bar of a sweep.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._options import MAX_CHUNK, MAX_WORKERS, count_option
from rotorlab.cli._output import BadInput, clean_text, say, stderr

__all__ = ["SchedulerOpt", "WorkersOpt", "ChunkOpt", "YesOpt", "OutNcOpt", "ResumeOpt", "StoreOpt", "LONG_RUN_S",
           "scheduler_is_safe", "check_store_path",
           "executor_from_options", "run_into_store",
           "SweepBar", "run_with_bar", "stability_line", "regime_fractions"]

# options shared by the commands that run on the sweep engine (sweep, basin)
SchedulerOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--scheduler", metavar="ADDR", help="Run the chunks on the Dask cluster at ADDR (tcp://HOST:PORT).")]
WorkersOpt = Annotated[Optional[int], count_option(  # noqa: UP007
    "--workers", high=MAX_WORKERS, what="threads of a local Dask cluster", metavar="N",
    help="Run the chunks on a local Dask cluster of N workers (threads of this command).")]


# the result file and --resume of the commands that write one Dataset (basin-stability, design)
OutNcOpt = Annotated[Optional[Path], typer.Option(  # noqa: UP007
    "--out", "-o", metavar="FILE.nc", help="Write the result Dataset to this NetCDF file.")]
ResumeOpt = Annotated[bool, typer.Option("--resume", help="Continue the run in --store.")]

#: Above this estimated time (s) a sweep asks for --yes before it starts (rotorlab.sweep.long_run_guard).
LONG_RUN_S = 600.0

YesOpt = Annotated[bool, typer.Option(
    "--yes", "-y", help=f"Run even when the estimate (timed on a pilot) exceeds {LONG_RUN_S / 60:g} min.")]


def StoreOpt(what: str) -> Any:  # noqa: N802 - an option type, named like the others
    """The ``--store STORE.zarr`` checkpoint of a command whose chunks hold ``what``."""
    return Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--store", metavar="STORE.zarr", help=f"Checkpoint: every finished chunk of {what} goes to this Zarr store; "
        "an interrupted run continues with --resume.")]


def ChunkOpt(what: str) -> Any:  # noqa: N802 - an option type, named like the others
    """The ``--chunk N`` option (``what`` is its help), bounded to [1, MAX_CHUNK]: a chunk is
    allocated whole in a store."""
    return Annotated[Optional[int], count_option(  # noqa: UP007
        "--chunk", high=MAX_CHUNK, what="points per chunk", metavar="N", help=what)]


def check_store_path(out: Path, resume: bool, option: str = "--out") -> None:
    """Refuse (BadInput) a store path that exists without ``--resume``, is not a sweep store, or
    lies in a missing folder."""
    if out.exists() and not resume:
        raise BadInput(f"{option} = {out}: exists; give --resume to continue that sweep, or another path")
    if not out.absolute().parent.is_dir():
        raise BadInput(f"{option} = {out}: folder {out.absolute().parent} does not exist")
    if out.exists():
        from rotorlab.sweep import SweepStoreError, store_info

        try:
            store_info(out)
        except SweepStoreError as exc:
            raise BadInput(f"{option} = {out}: {exc}") from None


def executor_from_options(scheduler: str | None, workers: int | None) -> Any:
    """The executor of ``--scheduler ADDR`` / ``--workers N`` (None: in this process), checked."""
    if scheduler is not None and workers is not None:
        raise BadInput("--scheduler and --workers exclude each other: give only one")
    if scheduler is not None and "://" not in scheduler:
        raise BadInput(f"--scheduler = {scheduler}: must be an address like tcp://HOST:PORT")
    if scheduler is not None and not scheduler_is_safe(scheduler):
        stderr().print(f"warning: --scheduler = {scheduler}: not a local address and not TLS (tls://). Dask moves "
                       "work and results as pickles: whoever runs or intercepts that cluster can run code in this "
                       "process. Use tls:// with certificates, or only a cluster you trust on a private network.",
                       markup=False)  # fmt: skip
    from rotorlab.sweep import DaskExecutor, InProcess

    return (DaskExecutor(scheduler=scheduler) if scheduler else DaskExecutor(workers=workers) if workers
            else InProcess())  # fmt: skip


def scheduler_is_safe(address: str) -> bool:
    """True for a TLS address or one on this machine (loopback, a local socket, in-process)."""
    import ipaddress
    from urllib.parse import urlsplit

    parts = urlsplit(address)
    if parts.scheme in ("tls", "inproc", "ucx+tls"):
        return True
    try:
        host = parts.hostname or ""
    except ValueError:
        return False
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def run_into_store(run: Callable[[], Any], store: Path | None, option: str = "--out", *,
                   yes: bool = True, settings: Any = None, what: str = "points") -> Any:
    """Return ``run()``, a sweep into ``store``: store and executor errors become BadInput (an
    unreachable scheduler leaves no store behind), and Ctrl-C says what is kept and exits 130.

    A large sweep is first estimated on a pilot (:func:`rotorlab.sweep.long_run_guard`): the
    estimate is printed (unless quiet), and one above :data:`LONG_RUN_S` without ``yes`` (the
    ``--yes`` option) stops before anything is written (BadInput, exit code 2).
    """
    from rotorlab.sweep import ExecutorError, LongRunDeclined, SweepStoreError, long_run_guard, store_info

    def decide(estimate: Any) -> bool:
        if estimate.seconds > LONG_RUN_S and not yes:
            return False
        if settings is None or not settings.quiet:
            say(estimate.describe(what))
        return True

    existed = store is not None and store.exists()
    try:
        with long_run_guard(decide):
            return run()
    except LongRunDeclined as exc:
        raise BadInput(f"{exc.estimate.describe(what)}: longer than {LONG_RUN_S / 60:g} min. Give --yes to run it, "
                       "or fewer points, a shorter --t-end, or more workers (--workers, --scheduler)") from None
    except SweepStoreError as exc:
        raise BadInput(f"{option} = {store}: {exc}") from None
    except ExecutorError as exc:
        if store is not None and not existed and store.exists() and store_info(store)["chunks_done"] == 0:
            import shutil

            shutil.rmtree(store)  # nothing computed: leave nothing behind
        raise BadInput(str(exc)) from None
    except KeyboardInterrupt:
        if store is None:
            stderr().print("interrupted", markup=False)
            raise typer.Exit(130) from None
        meta = store_info(store) if store.exists() else {"chunks_done": 0, "n_chunks": "?"}
        stderr().print(f"interrupted: {meta['chunks_done']} of {meta['n_chunks']} chunks are kept in {store}; "
                       "continue with the same command and --resume", markup=False)  # fmt: skip
        raise typer.Exit(130) from None


class SweepBar:
    """Rich progress bar of a sweep on stderr: points done, rate, time left (terminals only)."""

    def __init__(self, settings: Any, title: str) -> None:
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, \
            TimeRemainingColumn  # fmt: skip

        console = stderr()
        self.progress = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                                 TextColumn("points"), TextColumn("{task.fields[rate]}"), TimeElapsedColumn(),
                                 TextColumn("left"), TimeRemainingColumn(), console=console, transient=True,
                                 disable=settings.quiet or not console.is_terminal)  # fmt: skip
        self.title = title
        self.task = None
        self.start = time.perf_counter()
        self.first = 0

        # not a terminal (a pipe, a log file): plain lines every 10 % or 10 s instead of a bar
        self.plain = not settings.quiet and not console.is_terminal
        self.shown = (-1e9, -1.0)
        from rotorlab.cli._output import compile_notices

        self.notices = compile_notices(settings)

    def __enter__(self) -> SweepBar:
        self.progress.__enter__()
        self.notices.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.notices.__exit__(*exc)
        self.progress.__exit__(*exc)

    def __call__(self, p: Any) -> None:
        elapsed = time.perf_counter() - self.start
        if self.task is None:
            from rich.markup import escape

            self.first = p.done
            self.task = self.progress.add_task(escape(clean_text(self.title)), total=p.total, completed=p.done,
                                               rate="")  # fmt: skip
        rate = (p.done - self.first) / elapsed if elapsed > 0 else 0.0
        self.progress.update(self.task, completed=p.done, rate=f"{rate:.3g}/s")
        if self.plain:
            fraction = p.done / p.total if p.total else 1.0
            if p.done >= p.total or fraction - self.shown[1] >= 0.1 or elapsed - self.shown[0] >= 10.0:
                say(f"{self.title}: {p.done}/{p.total} points")
                sys.stderr.flush()
                self.shown = (elapsed, fraction)


def run_with_bar(settings: Any, title: str, sweep: Any, out: Path, resume: bool, size: int | None,
                  executor: Any, yes: bool = True) -> tuple[Any, Any, float]:  # fmt: skip
    """Run ``sweep`` into ``out`` under a progress bar: the Dataset, the last progress, seconds
    (a long sweep without ``yes`` is refused first, :func:`run_into_store`)."""
    from rotorlab.sweep import run_sweep

    started = time.perf_counter()
    last: list[Any] = []
    with SweepBar(settings, title) as bar:

        def progress(p: Any) -> None:
            last[:] = [p]
            bar(p)

        ds = run_into_store(lambda: run_sweep(sweep, store=out, resume=resume, chunk_size=size,
                                              executor=executor, progress=progress), out,
                            yes=yes, settings=settings)  # fmt: skip
    return ds, last[-1], time.perf_counter() - started


def stability_line(summary: dict[str, Any]) -> str:
    """One line: where a main (balanced) motion, any motion and each motion is exactly stable."""
    return (f"exactly stable over {summary['n']} finished points: a main (balanced) motion "
              f"{100 * summary['balanced']:.1f}%, any motion {100 * summary['any_stable']:.1f}%; " + ", ".join(
                  f"{k} {100 * v:.1f}%" for k, v in summary["motions"].items() if v > 0))  # fmt: skip


def regime_fractions(ds: Any) -> tuple[dict[str, float], int]:
    """Final regime fractions of a regime sweep and the number of its points."""
    from rotorlab.explore import basin_fractions

    fr = basin_fractions(ds).isel(horizon=-1)
    return {str(r): float(v) for r, v in zip(fr.regime.values, fr.fraction.values)}, int(fr.attrs["n"])
