"""The ``sweep`` command: checkpointed, resumable sweeps (``show`` is in :mod:`rotorlab.cli._show`).

``rotorlab sweep CASE --param NAME=A:B:N --ic NAME=A:B:N --out STORE.zarr`` runs the regimes of a
rotor with balls at every point of the grid (or of a ``--sample N --seed S``), in-process, on a
local Dask cluster (``--workers N``) or on a running one (``--scheduler tcp://HOST:PORT``). Each
finished chunk is in the store at once; ``--resume`` continues an interrupted sweep. ``rotorlab
show STORE.zarr`` prints a summary and writes its figures. Every option is checked before the
store is touched (bad input: exit 2, nothing written).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app, find_analysis
from rotorlab.cli._output import BadInput, console_or_json, exit_if_failed, handled, info
from rotorlab.cli._options import MAX_SEED, count_option, parse_range
from rotorlab.cli._sweep_common import (
    ChunkOpt,
    SchedulerOpt,
    WorkersOpt,
    YesOpt,
    check_store_path,
    executor_from_options,
    regime_fractions,
    run_with_bar,
    stability_line,
)


def _names(known: Any) -> str:
    from rotorlab.io._coordinates import coordinates_text

    return coordinates_text(known)


__all__ = ["sweep_command", "parse_axis"]


def _check_ranges(mapper: Any, options: Any, axes: dict[str, tuple]) -> None:
    """Refuse, before any store exists, a range that leaves a parameter's allowed values (a
    negative mass would fail every chunk of the store, and no --resume could finish it)."""
    import numpy as np

    find = getattr(mapper, "coordinate_parameter", None)
    for option, texts in options:
        for text in texts or ():
            name = text.partition("=")[0].strip()
            par = find(name) if find is not None and name in axes else None
            bad = [] if par is None else [v for v in axes[name][:2] if not par.admits(v)]
            if bad:
                raise BadInput(f"{option} = {text}: {name} = {bad[0]:g} is outside its allowed range: "
                               f"must be {par.allowed}")
            if par is not None:  # each end also passes the model's own checks (a ball inside its tube)
                try:
                    mapper.starts({name: np.asarray(axes[name][:2], dtype=float)})
                except ValueError as exc:
                    raise BadInput(f"{option} = {text}: {exc}") from None

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
    return name, parse_range(option, rest, dimension, sample=sample, head=f"{option} = {text}: ",
                             form=f"must be {form}" + (" (with --sample)" if sample else ""))


def _report(settings: Any, json_out: bool, loaded: Any, out: Path, sweep: Any, where: str, p: Any, seconds: float,
            extra: dict[str, Any], lines: list[str], ds: Any = None) -> None:  # fmt: skip
    """Print what ``rotorlab sweep`` did (or its JSON document, with ``extra``); exit 3 if points
    of ``ds`` failed."""
    _print_report(settings, json_out, loaded, out, sweep, where, p, seconds, extra, lines)
    exit_if_failed({str(out): ds})


def _print_report(settings: Any, json_out: bool, loaded: Any, out: Path, sweep: Any, where: str, p: Any,
                  seconds: float, extra: dict[str, Any], lines: list[str]) -> None:  # fmt: skip
    doc = {**_json_case(loaded), "store": str(out), "dims": list(sweep.dims),
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
    sample: Annotated[Optional[int], count_option(  # noqa: UP007
        "--sample", what="random points", metavar="N", help="Draw N random points from the --param/--ic ranges instead of a grid.")] = None,
    seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--seed", low=0, high=MAX_SEED, metavar="S", help="Seed of --sample (default: the case's, else 0).")] = None,
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
    chunk: ChunkOpt("Points per chunk (default: the case's, else 1024; a resumed store keeps its own).") = None,
    per_point: Annotated[str, typer.Option(
        "--per-point", metavar="ANALYSIS", help="What each point computes: 'regimes' (integrate and classify) or "
        "'stability' (existence and stability of every steady motion; --param over speed_rpm, speed_ratio or "
        "spin_speed and ball_mass, ball_damping, eccentricity, support_damping).")] = "regimes",
    sets: SetOpt = None,
    yes: YesOpt = False,
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
            _stability_sweep(settings, case, sets, out, param or [], sample, seed, speed_rpm, speed_ratio, resume,
                             executor, chunk, json_out, yes)  # fmt: skip
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
        loaded = _load(case, sets, settings)
        from rotorlab.io import SweepSpec
        from rotorlab.io._sweep_specs import sweep_coordinates

        model = loaded.model
        kind = getattr(model, "type", None)
        if not sweep_coordinates(model, "ic"):
            from rotorlab.io._coordinates import mappable_text

            raise BadInput(f"case {loaded.name}: rotorlab sweep needs {mappable_text(model)}")
        for option, texts, what in (("--param", param, "param"), ("--ic", ic, "ic")):
            known = sweep_coordinates(model, what)
            for text in texts or ():
                name = text.partition("=")[0].strip()
                if name in known:
                    continue
                reason = model.missing_coordinate(name)
                if reason is not None:
                    raise BadInput(f"{option} {name}: the model of {loaded.name} {reason}")
                raise BadInput(f"{option} = {text}: {name!r} is not a{' parameter' if what == 'param' else 'n initial'}"
                               f"{'' if what == 'param' else ' condition'} of this {kind} model (allowed: "
                               f"{_names(known)})")  # fmt: skip
        if model.spins_at_own_speed and (speed_rpm is not None or speed_ratio is not None):
            raise BadInput(f"--speed-{'rpm' if speed_rpm is not None else 'ratio'}: a {kind} spins at its "
                           "model's spin_speed; vary it with --param spin_speed=A:B:N")  # fmt: skip
        spec = find_analysis(loaded, "sweep", analysis)

        update: dict[str, Any] = {}
        if speed_rpm is not None:
            update.update(speed=speed_rpm / _RPM, speed_ratio=None)
        if speed_ratio is not None:
            if model.critical_speed() is None:
                raise BadInput("--speed-ratio: the model has no critical speed; give --speed-rpm")
            update.update(speed_ratio=speed_ratio, speed=None)
        if spec is None:
            if not axes:
                raise BadInput(f"case {loaded.name} has no sweep analysis: give --param and/or --ic")
            profile = model.speed_profile()
            if not (model.spins_at_own_speed or update) and (
                    profile is None or not profile.is_constant or profile.final_speed == 0):
                raise BadInput(f"case {loaded.name} has no constant speed: give --speed-rpm or --speed-ratio")
            spec = SweepSpec(name="sweep", revolutions=200.0, t_end=None)
        spec = spec.model_copy(update=update)
        from rotorlab.analyses._sweep import build_sweep

        try:
            sweep = build_sweep(model, spec, axes=axes or None, sample=sample, seed=seed, t_end=t_end)
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        _check_ranges(sweep.analysis.mapper, (("--param", param), ("--ic", ic)), axes)
        from rotorlab.io._coordinates import record_input_units

        # the unit each angle was written in, for figures (``rotorlab show`` draws it in that unit)
        given = [(t.partition("=")[0].strip(), t.partition("=")[2].split(":")[:2]) for t in (*(param or ()), *(ic or ()))]
        shown = {k: v for k, v in record_input_units(sweep.input_units, given).items() if k in sweep.varied}
        sweep = dataclasses.replace(sweep, input_units=shown)
        size = chunk if chunk is not None else (None if resume and out.exists() else spec.chunk)
        where = executor.describe()
        shape = " x ".join(str(s) for s in sweep.shape)
        info(settings, f"Sweeping {loaded.name}: {sweep.n_points} points ({' x '.join(sweep.dims)} = {shape}), "
             f"{sweep.analysis.mapper.t_end:.6g} s each, {where}, into {out} ...", json_mode=json_out)  # fmt: skip
        ds, p, seconds = run_with_bar(settings, loaded.name, sweep, out, resume, size, executor, yes)
        fractions, n = regime_fractions(ds)
        _report(settings, json_out, loaded, out, sweep, where, p, seconds,
                {"fractions": fractions, "n": n, "t_end": float(ds.attrs["t_end"])},
                ["fractions after {:g} s: {}".format(float(ds.attrs["t_end"]), ", ".join(
                    f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0))], ds)  # fmt: skip


def _stability_sweep(settings: Any, case: str, sets: list[str] | None, out: Path, texts: list[str], sample: int | None, seed: int | None,
                     speed_rpm: float | None, speed_ratio: float | None, resume: bool, executor: Any,
                     chunk: int | None, json_out: bool, yes: bool = False) -> None:  # fmt: skip
    from rotorlab.analyses._sweep import SPEED_AXES, STABILITY_AXES, STABILITY_CHUNK, stability_summary, stability_sweep

    axes: dict[str, tuple] = {}
    for text in texts:
        name, entry = parse_axis("--param", text, "param", sample is not None, STABILITY_AXES)
        if name in axes:
            raise BadInput(f"--param = {text}: {name} is given twice")
        if name in SPEED_AXES and set(axes) & set(SPEED_AXES):
            raise BadInput(f"--param = {text}: the speed is already swept by --param {next(iter(set(axes) & set(SPEED_AXES)))}")
        positive = name in SPEED_AXES or name == "ball_mass"
        if not all(v > 0 if positive else v >= 0 for v in entry[:2]):
            raise BadInput(f"--param = {text}: {name} must be {'> 0' if positive else '>= 0'}")
        axes[name] = entry
    if not axes:
        raise BadInput("--per-point stability needs the points: give --param NAME=A:B:N (speed_rpm, speed_ratio, "
                       "spin_speed, ball_mass, ball_damping, eccentricity, support_damping)")  # fmt: skip
    swept_speed = set(axes) & set(SPEED_AXES)
    if swept_speed and (speed_rpm is not None or speed_ratio is not None):
        raise BadInput(f"--speed-{'rpm' if speed_rpm is not None else 'ratio'}: the speed is swept by "
                       f"--param {next(iter(swept_speed))}")  # fmt: skip
    check_store_path(out, resume)
    loaded = _load(case, sets, settings)
    from rotorlab.cli._steady import _model

    model = _model(loaded, {}, "stability-chart")  # per-point stability: the stability chart's check
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
        if name not in SPEED_AXES:
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
    ds, p, seconds = run_with_bar(settings, loaded.name, sweep, out, resume, size, executor, yes)
    summary = stability_summary(ds.stack(point=list(sweep.dims)))
    _report(settings, json_out, loaded, out, sweep, where, p, seconds,
            {"per_point": "stability", "fixed": fixed, "stability": summary}, [stability_line(summary)])


