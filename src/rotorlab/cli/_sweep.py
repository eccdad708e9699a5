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
from rotorlab.cli._output import BadInput, console_or_json, handled, info, stderr

__all__ = ["sweep_command", "show_command", "parse_axis", "check_store_path", "executor_from_options",
           "run_into_store", "stability_sweep", "stability_summary", "impact_summary", "STABILITY_AXES"]

_RPM = 60.0 / (2.0 * math.pi)

# options shared by the commands that run on the sweep engine (sweep, basin)
SchedulerOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--scheduler", metavar="ADDR", help="Run the chunks on the Dask cluster at ADDR (tcp://HOST:PORT).")]
WorkersOpt = Annotated[Optional[int], typer.Option(  # noqa: UP007
    "--workers", metavar="N", help="Run the chunks on a local Dask cluster of N worker processes.")]


def parse_axis(option: str, text: str, kind: str, sample: bool,
               dimensions: dict[str, str] | None = None) -> tuple[str, tuple]:  # fmt: skip
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
    dimensions : dict of str to str, optional
        The allowed names and their dimensions (default: every coordinate of a regime sweep).

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
    dimension = coordinate_dimension(name, kind) if dimensions is None else dimensions.get(name)
    if dimension is None:
        allowed = _allowed(kind) if dimensions is None else ", ".join(dimensions)
        raise BadInput(f"{option} = {text}: unknown {'parameter' if kind == 'param' else 'initial condition'} "
                       f"{name!r} (allowed: {allowed})")  # fmt: skip
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


def _run_with_bar(settings: Any, title: str, sweep: Any, out: Path, resume: bool, size: int | None,
                  executor: Any) -> tuple[Any, Any, float]:  # fmt: skip
    """Run ``sweep`` into ``out`` under a progress bar: the Dataset, the last progress, seconds."""
    from rotorlab.sweep import run_sweep

    started = time.perf_counter()
    last: list[Any] = []
    with _Bar(settings, title) as bar:

        def progress(p: Any) -> None:
            last[:] = [p]
            bar(p)

        ds = run_into_store(lambda: run_sweep(sweep, store=out, resume=resume, chunk_size=size,
                                              executor=executor, progress=progress), out)  # fmt: skip
    return ds, last[-1], time.perf_counter() - started


def _report(settings: Any, json_out: bool, loaded: Any, out: Path, sweep: Any, where: str, p: Any, seconds: float,
            extra: dict[str, Any], lines: list[str]) -> None:  # fmt: skip
    """Print what ``rotorlab sweep`` did (or its JSON document, with ``extra``)."""
    doc = {"case": loaded.name, "source": loaded.source, "store": str(out), "dims": list(sweep.dims),
           "shape": list(sweep.shape), "n_points": sweep.n_points, "executor": where,
           "chunks": {"total": p.n_chunks, "computed": p.computed, "skipped": p.skipped}, **extra,
           "seconds": round(seconds, 3)}  # fmt: skip
    con = console_or_json(settings, json_out, doc)
    if con is None:
        return
    con.print(f"{loaded.name}: {sweep.n_points} points, {p.computed} chunk(s) computed, {p.skipped} already "
              f"in the store, {seconds:.1f} s", markup=False)  # fmt: skip
    for line in lines:
        con.print(line, markup=False)
    con.print(f"Wrote {out} (rotorlab show {out})", markup=False)


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
    per_point: Annotated[str, typer.Option(
        "--per-point", metavar="ANALYSIS", help="What each point computes: 'regimes' (integrate and classify) or "
        "'stability' (existence and stability of every steady motion; --param over speed_rpm, speed_ratio or "
        "spin_speed and ball_mass, ball_damping, eccentricity, support_damping).")] = "regimes",
    json_out: JsonOpt = False,
) -> None:
    """Run the regimes (or, with --per-point stability, the steady-motion stability) of a rotor with
    balls over a grid or sample of parameters and initial conditions.

    Results go to a Zarr store as each chunk finishes; an interrupted sweep (Ctrl-C, a killed
    process, a lost worker) continues with --resume, computing only what is missing. Results
    are identical, bit for bit, whatever --workers, --scheduler or --chunk.
    """
    settings = _settings(ctx)
    with handled(settings):
        if per_point not in ("regimes", "stability"):
            raise BadInput(f"--per-point = {per_point}: must be 'regimes' or 'stability'")
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
        if per_point == "stability":
            for option, value in (("--ic", ic), ("--t-end", t_end), ("--analysis", analysis)):
                if value is not None:
                    raise BadInput(f"{option}: not with --per-point stability (steady motions have no initial "
                                   "conditions, simulated time or case sweep analysis)")  # fmt: skip
            _stability_sweep(settings, case, out, param or [], sample, seed, speed_rpm, speed_ratio, resume,
                             executor, chunk, json_out)  # fmt: skip
            return
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

        try:
            sweep = build_sweep(loaded.model, spec, axes=axes or None, sample=sample, seed=seed, t_end=t_end)
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        size = chunk if chunk is not None else (None if resume and out.exists() else spec.chunk)
        where = executor.describe()
        shape = " x ".join(str(s) for s in sweep.shape)
        info(settings, f"Sweeping {loaded.name}: {sweep.n_points} points ({' x '.join(sweep.dims)} = {shape}), "
             f"{sweep.analysis.mapper.t_end:.6g} s each, {where}, into {out} ...", json_mode=json_out)  # fmt: skip
        ds, p, seconds = _run_with_bar(settings, loaded.name, sweep, out, resume, size, executor)
        fractions, n = _fractions(ds)
        _report(settings, json_out, loaded, out, sweep, where, p, seconds,
                {"fractions": fractions, "n": n, "t_end": float(ds.attrs["t_end"])},
                ["fractions after {:g} s: {}".format(float(ds.attrs["t_end"]), ", ".join(
                    f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0))])  # fmt: skip


#: Coordinates of ``rotorlab sweep --per-point stability`` and their dimensions: the speed (one of
#: three spellings; ``speed_rpm`` is stored as the ``spin_speed`` axis in rad/s) and the steady
#: parameters of :data:`rotorlab.steady.PARAMETERS`.
STABILITY_AXES = {"speed_rpm": "dimensionless", "speed_ratio": "dimensionless", "spin_speed": "angular_speed",
                  "ball_mass": "mass", "ball_damping": "torque_damping", "eccentricity": "length",
                  "support_damping": "damping"}  # fmt: skip
_SPEEDS = ("speed_rpm", "speed_ratio", "spin_speed")
#: Points per chunk of a stability sweep when none is given (a point takes milliseconds).
STABILITY_CHUNK = 64


def stability_sweep(model: Any, axes: dict[str, tuple], *, sample: int | None = None, seed: int | None = None,
                    fixed: dict[str, float] | None = None) -> Any:  # fmt: skip
    """The :class:`rotorlab.sweep.Sweep` of ``rotorlab sweep --per-point stability``.

    Parameters
    ----------
    model : JeffcottBalls
    axes : dict of str to tuple
        Name (a key of :data:`STABILITY_AXES`) to ``(start, stop, n)``, or ``(low, high)`` with
        ``sample``; ``speed_rpm`` becomes the ``spin_speed`` axis (rad/s).
    sample, seed : int, optional
        A seeded random sample of ``sample`` points instead of a grid.
    fixed : dict of str to float, optional
        The speed when it is not swept (``spin_speed`` in rad/s or ``speed_ratio``).

    Returns
    -------
    rotorlab.sweep.Sweep
        Points evaluated by :class:`rotorlab.steady.SteadyStability`.
    """
    from rotorlab.steady import SteadyStability
    from rotorlab.sweep import GridAxis, Sample, Sweep

    conv = {name: (("spin_speed", 1.0 / _RPM) if name == "speed_rpm" else (name, 1.0)) for name in axes}
    ranges = {conv[k][0]: tuple(v * conv[k][1] for v in entry[:2]) + tuple(entry[2:]) for k, entry in axes.items()}
    analysis = SteadyStability(model)
    if sample is not None:
        return Sweep(analysis, sample=Sample({k: v[:2] for k, v in ranges.items()}, sample, 0 if seed is None else seed),
                     fixed=fixed or {})  # fmt: skip
    return Sweep(analysis, axes=tuple(GridAxis(k, *v) for k, v in ranges.items()), fixed=fixed or {})


def _stability_sweep(settings: Any, case: str, out: Path, texts: list[str], sample: int | None, seed: int | None,
                     speed_rpm: float | None, speed_ratio: float | None, resume: bool, executor: Any,
                     chunk: int | None, json_out: bool) -> None:  # fmt: skip
    axes: dict[str, tuple] = {}
    for text in texts:
        name, entry = parse_axis("--param", text, "param", sample is not None, STABILITY_AXES)
        if name in axes:
            raise BadInput(f"--param = {text}: {name} is given twice")
        if name in _SPEEDS and set(axes) & set(_SPEEDS):
            raise BadInput(f"--param = {text}: the speed is already swept by --param {next(iter(set(axes) & set(_SPEEDS)))}")
        positive = name in _SPEEDS or name == "ball_mass"
        if not all(v > 0 if positive else v >= 0 for v in entry[:2]):
            raise BadInput(f"--param = {text}: {name} must be {'> 0' if positive else '>= 0'}")
        axes[name] = entry
    if not axes:
        raise BadInput("--per-point stability needs the points: give --param NAME=A:B:N (speed_rpm, speed_ratio, "
                       "spin_speed, ball_mass, ball_damping, eccentricity, support_damping)")  # fmt: skip
    swept_speed = set(axes) & set(_SPEEDS)
    if swept_speed and (speed_rpm is not None or speed_ratio is not None):
        raise BadInput(f"--speed-{'rpm' if speed_rpm is not None else 'ratio'}: the speed is swept by "
                       f"--param {next(iter(swept_speed))}")  # fmt: skip
    check_store_path(out, resume)
    loaded = _load(case)
    from rotorlab.cli._steady import _model

    model = _model(loaded, {})
    fixed: dict[str, float] = {}
    if speed_rpm is not None:
        fixed["spin_speed"] = speed_rpm / _RPM
    elif speed_ratio is not None:
        fixed["speed_ratio"] = speed_ratio
    elif not swept_speed:
        profile = loaded.model.speed_profile()
        if profile is None or not profile.is_constant or profile.final_speed == 0:
            raise BadInput(f"case {loaded.name} has no constant speed: give --speed-rpm, --speed-ratio or "
                           "--param speed_rpm=A:B:N")  # fmt: skip
        fixed["spin_speed"] = float(profile.final_speed)
    from rotorlab.steady import with_parameter

    for name, entry in axes.items():  # a bad value fails here, before the store exists
        if name not in _SPEEDS:
            for v in entry[:2]:
                try:
                    with_parameter(model, name, v)
                except ValueError as exc:
                    raise BadInput(f"--param {name}: {exc}") from None
    sweep = stability_sweep(model, axes, sample=sample, seed=seed, fixed=fixed)
    size = chunk if chunk is not None else (None if resume and out.exists() else STABILITY_CHUNK)
    where = executor.describe()
    shape = " x ".join(str(s) for s in sweep.shape)
    info(settings, f"Sweeping the steady motions of {loaded.name}: {sweep.n_points} points "
         f"({' x '.join(sweep.dims)} = {shape}), {where}, into {out} ...", json_mode=json_out)  # fmt: skip
    ds, p, seconds = _run_with_bar(settings, loaded.name, sweep, out, resume, size, executor)
    summary = stability_summary(ds.stack(point=list(sweep.dims)))
    _report(settings, json_out, loaded, out, sweep, where, p, seconds,
            {"per_point": "stability", "fixed": fixed, "stability": summary}, [_stability_line(summary)])


def stability_summary(flat: Any) -> dict[str, Any]:
    """Fractions of the points of a steady-stability sweep (``point`` x ``motion``) where a main
    (balanced) motion, any motion, and each motion is stable by the exact eigenvalues."""
    import numpy as np

    stable = np.asarray(flat["stable_exact"].transpose("point", "motion").values, dtype=bool)
    labels = list(flat["motion"].attrs.get("labels", [str(m) for m in flat["motion"].values]))
    main = np.array([str(lab).startswith("main") for lab in labels])
    n = stable.shape[0]

    def frac(x: Any) -> float:
        return float(np.count_nonzero(x)) / n if n else float("nan")

    return {"n": n, "balanced": frac(stable[:, main].any(axis=1)), "any_stable": frac(stable.any(axis=1)),
            "motions": {str(lab): frac(stable[:, i]) for i, lab in enumerate(labels)}}  # fmt: skip


def _stability_line(summary: dict[str, Any]) -> str:
    return (f"exactly stable over {summary['n']} finished points: a main (balanced) motion "
              f"{100 * summary['balanced']:.1f}%, any motion {100 * summary['any_stable']:.1f}%; " + ", ".join(
                  f"{k} {100 * v:.1f}%" for k, v in summary["motions"].items() if v > 0))  # fmt: skip


def impact_summary(flat: Any) -> dict[str, Any]:
    """Regime fractions and impact counts of the runs of an impact store (``point``)."""
    import numpy as np

    names = list(flat.attrs.get("regimes", []))
    codes = np.asarray(flat["regime"].values) if "regime" in flat else np.zeros(0, int)
    impacts = np.asarray(flat["impacts"].values)
    n = impacts.size
    regimes = {str(name): float(np.count_nonzero(codes == i)) / n for i, name in enumerate(names)} if n else {}
    return {"n": n, "regimes": regimes, "impacts_mean": float(impacts.mean()) if n else float("nan"),
            "impacts_max": int(impacts.max()) if n else 0}  # fmt: skip


def _analysis_name(meta: dict[str, Any]) -> str:
    res = meta["result_attrs"]
    if res.get("mapper") or res.get("analysis"):
        return str(res.get("mapper") or res.get("analysis"))
    import json

    desc = meta.get("sweep")
    try:
        desc = json.loads(desc) if isinstance(desc, str) else desc
        return str(desc["analysis"]["type"]).rsplit(".", 1)[-1]
    except (TypeError, KeyError, ValueError):
        return "?"


@app.command("show")
def show_command(
    ctx: typer.Context,
    store: Annotated[Path, typer.Argument(metavar="STORE.zarr", help="A store written by 'rotorlab sweep'.")],
    figures: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--figures", metavar="DIR", help="Folder for the figures (default: STORE without .zarr, plus "
        "'-figures').")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Print a summary of a sweep store and write its figures (basin map of a 2-D sweep, fractions).

    Regime stores get regime fractions and figures; steady-stability stores the fractions of
    points where a motion is exactly stable; impact stores the impact counts and regimes.
    """
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
        fractions, n, stability, impacts = None, 0, None, None
        mask = done.repeat(meta["chunk_size"])[: meta["n_points"]]  # the finished points only
        flat = ds.stack(point=list(meta["dims"])).isel(point=mask).reset_index("point", drop=True) \
            if mask.any() else None  # fmt: skip
        if "label" in ds:
            if flat is not None:
                fractions, n = _fractions(ds if meta["complete"] else flat)
            if meta["complete"]:
                written = _figures(ds, folder)
        elif "stable_exact" in ds and flat is not None:
            stability = stability_summary(flat)
            n = stability["n"]
        elif "impacts" in ds and flat is not None:
            impacts = impact_summary(flat)
            n = impacts["n"]
        name = _analysis_name(meta)
        doc = {"store": str(store), "analysis": name, "dims": meta["dims"], "shape": meta["shape"],
               "n_points": meta["n_points"], "chunks": {"total": meta["n_chunks"], "done": meta["chunks_done"]},
               "complete": meta["complete"], "runs": meta["runs"], "versions": meta["versions"],
               "fixed": meta["fixed"], "result": dict(meta["result_attrs"]), "variables": sorted(ds.data_vars),
               "fractions": fractions, "stability": stability, "impacts": impacts, "n": n,
               "figures": written}  # fmt: skip
        con = console_or_json(settings, json_out, doc)
        if con is None:
            return
        shape = " x ".join(f"{d} {s}" for d, s in zip(meta["dims"], meta["shape"]))
        con.print(f"{store}: {meta['n_points']} points ({shape}); {meta['chunks_done']} of {meta['n_chunks']} "
                  f"chunks done" + ("" if meta["complete"] else " (unfinished: continue with rotorlab sweep "
                                    "... --resume)"), markup=False)  # fmt: skip
        res = meta["result_attrs"]
        per = f", {float(res['t_end']):.6g} s per point" if "t_end" in res else ""
        con.print(f"analysis: {name}{per}; written in {meta['runs']} run(s) by rotorlab "
                  f"{meta['versions'].get('rotorlab')}", markup=False)  # fmt: skip
        for name in meta["dims"]:
            c = ds[name]
            con.print(f"  {name}: {float(c.min()):.6g} .. {float(c.max()):.6g} {c.attrs.get('units', '')}",
                      markup=False)  # fmt: skip
        if fractions is not None:
            con.print(f"fractions of {n} finished points: " + ", ".join(
                f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0), markup=False)  # fmt: skip
        if stability is not None:
            con.print(_stability_line(stability), markup=False)
        if impacts is not None:
            con.print(f"{n} finished runs: {impacts['impacts_mean']:.3g} impacts per run on average (at most "
                      f"{impacts['impacts_max']}); regimes: " + (", ".join(
                          f"{k} {100 * v:.1f}%" for k, v in impacts["regimes"].items() if v > 0) or "none"),
                      markup=False)  # fmt: skip
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
