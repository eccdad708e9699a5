"""The ``sweep`` and ``show`` commands: checkpointed, resumable sweeps and what their stores hold.

``rotorlab sweep CASE --param NAME=A:B:N --ic NAME=A:B:N --out STORE.zarr`` runs the regimes of a
rotor with balls at every point of the grid (or of a ``--sample N --seed S``), in-process, on a
local Dask cluster (``--workers N``) or on a running one (``--scheduler tcp://HOST:PORT``). Each
finished chunk is in the store at once; ``--resume`` continues an interrupted sweep. ``rotorlab
show STORE.zarr`` prints a summary and writes its figures. Every option is checked before the
store is touched (bad input: exit 2, nothing written).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, _load, _settings, app
from rotorlab.cli._output import BadInput, emit_json, handled, info, stderr, stdout

__all__ = ["sweep_command", "show_command", "parse_axis", "check_store_path", "executor_from_options",
           "run_into_store"]

_RPM = 60.0 / (2.0 * math.pi)

# options shared by the commands that run on the sweep engine (sweep, basin)
SchedulerOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--scheduler", metavar="ADDR", help="Run the chunks on the Dask cluster at ADDR (tcp://HOST:PORT).")]
WorkersOpt = Annotated[Optional[int], typer.Option(  # noqa: UP007
    "--workers", metavar="N", help="Run the chunks on a local Dask cluster of N worker processes.")]


def parse_axis(option: str, text: str, kind: str, sample: bool) -> tuple[str, tuple]:
    """Read ``NAME=START:STOP:N`` (a grid) or, for a sample, ``NAME=LOW:HIGH``.

    Parameters
    ----------
    option : str
        ``--param`` or ``--ic`` (for messages).
    text : str
        The value; numbers are SI, or carry a unit (``ball_mass=10g:50g:5``, ``psi_1=0deg:350deg:36``).
    kind : {"param", "ic"}
    sample : bool
        Whether the sweep is a random sample (ranges) rather than a grid.

    Returns
    -------
    (str, tuple)
        The name and ``(start, stop, n)`` or ``(low, high)`` in SI.

    Raises
    ------
    BadInput
        Unknown name, malformed value, wrong unit.

    Examples
    --------
    >>> parse_axis("--param", "ball_mass=10g:50g:5", "param", False)
    ('ball_mass', (0.01, 0.05, 5))
    >>> parse_axis("--ic", "dpsi_1=-5:5", "ic", True)
    ('dpsi_1', (-5.0, 5.0))
    """
    from rotorlab.io._sweep_specs import _allowed, coordinate_dimension

    name, sep, rest = text.partition("=")
    name = name.strip()
    form = "NAME=LOW:HIGH" if sample else "NAME=START:STOP:N"
    if not sep:
        raise BadInput(f"{option} = {text}: must be {form}")
    dimension = coordinate_dimension(name, kind)
    if dimension is None:
        raise BadInput(f"{option} = {text}: unknown {'parameter' if kind == 'param' else 'initial condition'} "
                       f"{name!r} (allowed: {_allowed(kind)})")  # fmt: skip
    parts = rest.split(":")
    if len(parts) != (2 if sample else 3):
        raise BadInput(f"{option} = {text}: must be {form}" + (" (with --sample)" if sample else ""))
    ends = []
    for part in parts[:2]:
        try:
            ends.append(float(part))
        except ValueError:
            from rotorlab.io import CaseError, to_si

            try:
                ends.append(to_si(part.strip(), dimension, option))
            except (CaseError, ValueError) as exc:
                raise BadInput(f"{option} = {text}: {exc}") from None
    if not all(math.isfinite(v) for v in ends):
        raise BadInput(f"{option} = {text}: START and STOP must be finite")
    if sample:
        if not ends[1] >= ends[0]:
            raise BadInput(f"{option} = {text}: HIGH must be >= LOW")
        return name, (ends[0], ends[1])
    try:
        count = int(parts[2])
    except ValueError:
        count = 0
    if count < 1:
        raise BadInput(f"{option} = {text}: N must be an integer >= 1")
    return name, (ends[0], ends[1], count)


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
    if workers is not None and workers < 1:
        raise BadInput(f"--workers = {workers}: must be an integer >= 1")
    from rotorlab.sweep import DaskExecutor, InProcess

    return (DaskExecutor(scheduler=scheduler) if scheduler else DaskExecutor(workers=workers) if workers
            else InProcess())  # fmt: skip


def run_into_store(run: Callable[[], Any], store: Path | None, option: str = "--out") -> Any:
    """Return ``run()``, a sweep into ``store``: store and executor errors become BadInput (an
    unreachable scheduler leaves no store behind), and Ctrl-C says what is kept and exits 130."""
    from rotorlab.sweep import ExecutorError, SweepStoreError, store_info

    existed = store is not None and store.exists()
    try:
        return run()
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


def _pick(loaded: Any, name: str | None) -> Any:
    sweeps = [a for a in loaded.analyses if a.type == "sweep"]
    if name is not None:
        for a in sweeps:
            if a.name == name:
                return a
        names = ", ".join(a.name for a in sweeps) or "none"
        raise BadInput(f"--analysis = {name}: no sweep analysis of that name (sweep analyses: {names})")
    return sweeps[0] if sweeps else None


def _fractions(ds: Any) -> tuple[dict[str, float], int]:
    from rotorlab.explore import basin_fractions

    fr = basin_fractions(ds).isel(horizon=-1)
    return {str(r): float(v) for r, v in zip(fr.regime.values, fr.fraction.values)}, int(fr.attrs["n"])


class _Bar:
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

    def __enter__(self) -> _Bar:
        self.progress.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.progress.__exit__(*exc)

    def __call__(self, p: Any) -> None:
        if self.task is None:
            self.first = p.done
            self.task = self.progress.add_task(self.title, total=p.total, completed=p.done, rate="")
            return
        elapsed = time.perf_counter() - self.start
        rate = (p.done - self.first) / elapsed if elapsed > 0 else 0.0
        self.progress.update(self.task, completed=p.done, rate=f"{rate:.3g}/s")


@app.command("sweep")
def sweep_command(
    ctx: typer.Context,
    case: CaseArg,
    out: Annotated[Path, typer.Option("--out", "-o", metavar="STORE.zarr",
                                      help="Zarr store the results go to, chunk by chunk.")],  # fmt: skip
    param: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=A:B:N", help="Model parameter over N values from A to B (SI or with a unit: "
        "ball_mass=10g:50g:5); repeatable, one result dimension each. With --sample: NAME=LOW:HIGH.")] = None,
    ic: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--ic", metavar="NAME=A:B:N", help="Initial condition psi_<i> (ball angle) or dpsi_<i> (ball rate) over N "
        "values; repeatable. With --sample: NAME=LOW:HIGH.")] = None,
    sample: Annotated[Optional[int], typer.Option(  # noqa: UP007
        "--sample", metavar="N", help="Draw N random points from the --param/--ic ranges instead of a grid.")] = None,
    seed: Annotated[Optional[int], typer.Option(  # noqa: UP007
        "--seed", metavar="S", help="Seed of --sample (default: the case's, else 0).")] = None,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which sweep analysis of the case gives the defaults (default: the "
        "first).")] = None,
    speed_rpm: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Base spin speed (rpm).")] = None,
    speed_ratio: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-ratio", metavar="RATIO", help="Base spin speed as a multiple of the critical speed p.")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="SECONDS", help="Simulated time (s).")] = None,
    resume: Annotated[bool, typer.Option("--resume", help="Continue the sweep in --out: compute only its "
                                         "missing chunks.")] = False,  # fmt: skip
    scheduler: SchedulerOpt = None,
    workers: WorkersOpt = None,
    chunk: Annotated[Optional[int], typer.Option(  # noqa: UP007
        "--chunk", metavar="N", help="Points per chunk (default: the case's, else 1024; a resumed store keeps "
        "its own).")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Run the regimes of a rotor with balls over a grid or sample of parameters and initial conditions.

    Results go to a Zarr store as each chunk finishes; an interrupted sweep (Ctrl-C, a killed
    process, a lost worker) continues with --resume, computing only what is missing. Results
    are identical, bit for bit, whatever --workers, --scheduler or --chunk.
    """
    settings = _settings(ctx)
    with handled(settings):
        executor = executor_from_options(scheduler, workers)
        for option, value in (("--chunk", chunk), ("--sample", sample)):
            if value is not None and value < 1:
                raise BadInput(f"{option} = {value}: must be an integer >= 1")
        for option, value in (("--speed-rpm", speed_rpm), ("--speed-ratio", speed_ratio), ("--t-end", t_end)):
            if value is not None and not (math.isfinite(value) and value > 0):
                raise BadInput(f"{option} = {value:g}: must be a finite number > 0")
        if speed_rpm is not None and speed_ratio is not None:
            raise BadInput("--speed-rpm and --speed-ratio exclude each other: give only one")
        if seed is not None and sample is None:
            raise BadInput("--seed needs --sample")
        axes: dict[str, tuple] = {}
        for option, texts, kind in (("--param", param, "param"), ("--ic", ic, "ic")):
            for text in texts or ():
                name, entry = parse_axis(option, text, kind, sample is not None)
                if name in axes:
                    raise BadInput(f"{option} = {text}: {name} is given twice")
                axes[name] = entry
        if sample is not None and not axes:
            raise BadInput("--sample needs the ranges to draw from: give --param and/or --ic NAME=LOW:HIGH")
        check_store_path(out, resume)
        loaded = _load(case)
        from rotorlab.io import SweepSpec
        from rotorlab.io._sweep_specs import sweep_coordinates

        kind = getattr(loaded.model, "type", None)
        if not sweep_coordinates(loaded.model, "ic"):
            raise BadInput(f"case {loaded.name}: rotorlab sweep runs models with a regime mapper (a jeffcott_balls "
                           f"model with balls, or a toroidal_ball model), this case's model is '{kind}'")  # fmt: skip
        for option, texts, what in (("--param", param, "param"), ("--ic", ic, "ic")):
            known = sweep_coordinates(loaded.model, what)
            for text in texts or ():
                name = text.partition("=")[0].strip()
                if name in known:
                    continue
                if kind == "jeffcott_balls" and what == "ic":
                    raise BadInput(f"--ic {name}: the model of {loaded.name} has {loaded.model.n_balls} ball(s)")
                raise BadInput(f"{option} = {text}: {name!r} is not a{' parameter' if what == 'param' else 'n initial'}"
                               f"{'' if what == 'param' else ' condition'} of this {kind} model (allowed: "
                               f"{', '.join(known)})")  # fmt: skip
        if kind == "toroidal_ball" and (speed_rpm is not None or speed_ratio is not None):
            raise BadInput(f"--speed-{'rpm' if speed_rpm is not None else 'ratio'}: a toroidal_ball spins at its "
                           "model's spin_speed; vary it with --param spin_speed=A:B:N")  # fmt: skip
        spec = _pick(loaded, analysis)

        update: dict[str, Any] = {}
        if speed_rpm is not None:
            update.update(speed=speed_rpm / _RPM, speed_ratio=None)
        if speed_ratio is not None:
            if loaded.model.critical_speed() is None:
                raise BadInput("--speed-ratio: the model has no critical speed; give --speed-rpm")
            update.update(speed_ratio=speed_ratio, speed=None)
        if spec is None:
            if not axes:
                raise BadInput(f"case {loaded.name} has no sweep analysis: give --param and/or --ic")
            profile = loaded.model.speed_profile() if kind == "jeffcott_balls" else None
            if kind == "jeffcott_balls" and not update and (
                    profile is None or not profile.is_constant or profile.final_speed == 0):
                raise BadInput(f"case {loaded.name} has no constant speed: give --speed-rpm or --speed-ratio")
            spec = SweepSpec(name="sweep", revolutions=200.0, t_end=None)
        spec = spec.model_copy(update=update)
        from rotorlab.analyses._sweep import build_sweep
        from rotorlab.sweep import run_sweep

        try:
            sweep = build_sweep(loaded.model, spec, axes=axes or None, sample=sample, seed=seed, t_end=t_end)
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        size = chunk if chunk is not None else (None if resume and out.exists() else spec.chunk)
        where = executor.describe()
        shape = " x ".join(str(s) for s in sweep.shape)
        info(settings, f"Sweeping {loaded.name}: {sweep.n_points} points ({' x '.join(sweep.dims)} = {shape}), "
             f"{sweep.analysis.mapper.t_end:.6g} s each, {where}, into {out} ...", json_mode=json_out)  # fmt: skip
        started = time.perf_counter()
        last: list[Any] = []
        with _Bar(settings, loaded.name) as bar:

            def progress(p: Any) -> None:
                last[:] = [p]
                bar(p)

            ds = run_into_store(lambda: run_sweep(sweep, store=out, resume=resume, chunk_size=size,
                                                  executor=executor, progress=progress), out)  # fmt: skip
        seconds = time.perf_counter() - started
        p = last[-1]
        fractions, n = _fractions(ds)
        doc = {"case": loaded.name, "source": loaded.source, "store": str(out), "dims": list(sweep.dims),
               "shape": list(sweep.shape), "n_points": sweep.n_points, "executor": where,
               "chunks": {"total": p.n_chunks, "computed": p.computed, "skipped": p.skipped},
               "fractions": fractions, "n": n, "t_end": float(ds.attrs["t_end"]),
               "seconds": round(seconds, 3)}  # fmt: skip
        if json_out:
            emit_json(doc)
            return
        if settings.quiet:
            return
        con = stdout()
        con.print(f"{loaded.name}: {sweep.n_points} points, {p.computed} chunk(s) computed, {p.skipped} already "
                  f"in the store, {seconds:.1f} s", markup=False)  # fmt: skip
        con.print("fractions after {:g} s: {}".format(float(ds.attrs["t_end"]), ", ".join(
            f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0)), markup=False)  # fmt: skip
        con.print(f"Wrote {out} (rotorlab show {out})", markup=False)


@app.command("show")
def show_command(
    ctx: typer.Context,
    store: Annotated[Path, typer.Argument(metavar="STORE.zarr", help="A store written by 'rotorlab sweep'.")],
    figures: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--figures", metavar="DIR", help="Folder for the figures (default: STORE without .zarr, plus "
        "'-figures').")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Print a summary of a sweep store and write its figures (basin map of a 2-D sweep, fractions)."""
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.sweep import SweepStoreError, open_sweep, store_info

        if not store.exists():
            raise BadInput(f"STORE = {store}: does not exist")
        try:
            meta = store_info(store)
            ds = open_sweep(store, partial=True)
        except SweepStoreError as exc:
            raise BadInput(f"STORE = {store}: {exc}") from None
        folder = figures if figures is not None else store.with_name(store.name.removesuffix(".zarr") + "-figures")
        if folder.exists() and not folder.is_dir():
            raise BadInput(f"--figures = {folder}: is a file")
        if not folder.absolute().parent.is_dir():
            raise BadInput(f"--figures = {folder}: folder {folder.absolute().parent} does not exist")
        done = meta["done"] > 0
        written = []
        fractions, n = None, 0
        if "label" in ds:
            sub = ds
            if not meta["complete"]:  # count the finished points only
                flat = ds.stack(point=list(meta["dims"]))
                mask = (done.repeat(meta["chunk_size"])[: meta["n_points"]])
                sub = flat.isel(point=mask).reset_index("point", drop=True) if mask.any() else None
            if sub is not None:
                fractions, n = _fractions(sub)
            if meta["complete"]:
                written = _figures(ds, folder)
        doc = {"store": str(store), "dims": meta["dims"], "shape": meta["shape"], "n_points": meta["n_points"],
               "chunks": {"total": meta["n_chunks"], "done": meta["chunks_done"]}, "complete": meta["complete"],
               "runs": meta["runs"], "versions": meta["versions"], "fixed": meta["fixed"],
               "result": dict(meta["result_attrs"]), "variables": sorted(ds.data_vars),
               "fractions": fractions, "n": n, "figures": written}  # fmt: skip
        if json_out:
            emit_json(doc)
            return
        if settings.quiet:
            return
        con = stdout()
        shape = " x ".join(f"{d} {s}" for d, s in zip(meta["dims"], meta["shape"]))
        con.print(f"{store}: {meta['n_points']} points ({shape}); {meta['chunks_done']} of {meta['n_chunks']} "
                  f"chunks done" + ("" if meta["complete"] else " (unfinished: continue with rotorlab sweep "
                                    "... --resume)"), markup=False)  # fmt: skip
        res = meta["result_attrs"]
        con.print(f"analysis: {res.get('mapper', '?')}, {res.get('t_end', float('nan')):.6g} s per point; "
                  f"written in {meta['runs']} run(s) by rotorlab {meta['versions'].get('rotorlab')}", markup=False)
        for name in meta["dims"]:
            c = ds[name]
            con.print(f"  {name}: {float(c.min()):.6g} .. {float(c.max()):.6g} {c.attrs.get('units', '')}",
                      markup=False)  # fmt: skip
        if fractions is not None:
            con.print(f"fractions of {n} finished points: " + ", ".join(
                f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0), markup=False)  # fmt: skip
        for path in written:
            con.print(f"Wrote {path}", markup=False)


def _figures(ds: Any, folder: Path) -> list[str]:
    from rotorlab.plot import sweep_figures

    folder.mkdir(exist_ok=True)
    out = []
    for stem, fig in sweep_figures(ds).items():
        path = folder / f"{stem}.png"
        fig.savefig(path, dpi=110)
        out.append(str(path))
    return out
