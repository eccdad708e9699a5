"""The ``impacts`` and ``impacts-sweep`` commands: the rotor striking its housing (seed 001).

Both take a case file (or built-in case) with an ``impact_rotor`` model. Defaults come from the
case's first ``impacts`` / ``impacts-sweep`` analysis (or the one named by ``--analysis``);
options override them. Values are SI at this edge already (kg, s); JSON output is SI with the
unit in each key. ``impacts-sweep`` is this issue's sweep over stone mass with many random stone
sequences (named apart from the general ``sweep`` command).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app, find_analysis
from rotorlab.cli._output import BadInput, console_or_json, exit_if_failed, handled, info, status
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._sweep_common import ChunkOpt, SchedulerOpt, WorkersOpt

__all__ = ["impacts_command", "impacts_sweep_command", "impact_tables"]

AnalysisOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--analysis", metavar="NAME", help="Which analysis of the case supplies the defaults (default: the first).")]
PlotOpt = Annotated[Optional[Path], typer.Option(  # noqa: UP007
    "--plot", metavar="FILE", help="Save the figure (PNG, PDF or SVG by suffix).")]
OutOpt = Annotated[Optional[Path], typer.Option(  # noqa: UP007
    "--out", "-o", metavar="FILE.nc", help="Write the result Dataset to this NetCDF file.")]
TEndOpt = Annotated[Optional[float], typer.Option(  # noqa: UP007
    "--t-end", metavar="SECONDS", help="Duration of a run (s).")]
SeedOpt = Annotated[Optional[int], count_option(  # noqa: UP007
    "--seed", low=0, high=MAX_SEED, metavar="N", help="Seed of the (first) stone sequence, >= 0.")]


def _check(stone_mass: float | None, t_end: float | None, seed: int | None, plot: Path | None,
           out: Path | None) -> None:
    """Check the options both commands share (bad input: BadInput naming the option)."""
    from rotorlab.cli._app import _positive
    from rotorlab.cli._steady import _check_plot

    for option, value, unit in (("--stone-mass", stone_mass, "kg"), ("--t-end", t_end, "s")):
        _positive(option, None if value is None else [value], unit)
    _check_plot("--plot", plot)
    _check_plot("--out", out)


def _impact_case(case: str, sets: list[str] | None = None, settings: Any = None) -> Any:
    from rotorlab.io import ImpactsSpec

    loaded = _load(case, sets, settings)
    problem = ImpactsSpec.wrong_model(loaded.model)
    if problem is not None:
        raise BadInput(f"case {loaded.name}: {problem}")
    return loaded


def _spec(loaded: Any, kind: str, name: str | None) -> Any:
    from rotorlab.io import ImpactsSpec, ImpactsSweepSpec

    found = find_analysis(loaded, kind, name)
    if found is not None:
        return found
    if kind == "impacts":
        return ImpactsSpec(name="impacts")
    return ImpactsSweepSpec(name="impacts-sweep", values=[0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 3.0])


def _finish(settings: Any, loaded: Any, spec: Any, ds: Any, summary: dict[str, Any], plot: Path | None,
            out: Path | None, json_out: bool, files: tuple[str, ...] = ()) -> None:
    """Write the figure and NetCDF file, then print the JSON document or the tables."""
    ds.attrs["case"] = loaded.name
    written = [*files]
    if plot is not None:
        from rotorlab.plot import impact_figures

        for fig in impact_figures(ds, "x").values():
            fig.savefig(plot, dpi=110)
        written.append(str(plot))
    if out is not None:
        from rotorlab.io import save_netcdf

        written.append(str(save_netcdf(ds, out)))
    doc = {**_json_case(loaded), **summary, "files": written}
    if ds.attrs.get("analysis") == "impacts-sweep":
        from rotorlab.analyses import paper_counts

        for row, p in zip(doc["rows"], paper_counts(ds)):
            row["paper_impacts"] = p
    con = console_or_json(settings, json_out, doc)
    if con is not None:
        for table in impact_tables({spec.name: ds}):
            con.print(table)
        for path in written:
            con.print(f"Wrote {path}", markup=False)
    exit_if_failed({spec.name: ds})


@app.command("impacts")
def impacts_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    stone_mass: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--stone-mass", metavar="KG", help="Mass of every stone (kg).")] = None,
    t_end: TEndOpt = None,
    seed: SeedOpt = None,
    analysis: AnalysisOpt = None,
    plot: PlotOpt = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Simulate one run from rest: regime, impacts, sliding time, energy ratio eta.

    Regimes: none, rebounds, sliding (sustained sliding contact for >= 0.1 % of the run; the
    analysis key sliding_fraction, 0 for the paper's any sliding episode), backward_whirl (the
    run was stopped: a self-feeding dry-friction backward whirl). --plot draws the trajectory of the gap point P in the rotating frame (seed 001, Figs. 3, 4).
    """
    settings = _settings(ctx)
    with handled(settings):
        _check(stone_mass, t_end, seed, plot, out)
        loaded = _impact_case(case, sets, settings)
        spec = _spec(loaded, "impacts", analysis)
        from rotorlab.analyses import impact_model, impact_run, impact_summary

        overrides = spec.overrides()
        if stone_mass is not None:
            overrides["stone_mass"] = stone_mass
        model = impact_model(loaded.model, **overrides)
        duration = spec.t_end if t_end is None else t_end
        run_seed = spec.seed if seed is None else seed
        info(settings, f"Simulating {loaded.name}: {duration:g} s, stones {model.stones.mass:g} kg, seed {run_seed} ...",
             json_mode=json_out)  # fmt: skip
        with status(settings, "Integrating ..."):
            ds = impact_run(model, duration, seed=run_seed, n_save=spec.n_save, rtol=spec.rtol, atol=spec.atol,
                            sliding_fraction=spec.sliding_fraction)  # fmt: skip
        _finish(settings, loaded, spec, ds, impact_summary(ds), plot, out, json_out)


def _param(stone_mass: str | None, param: str | None) -> tuple[str | None, Any]:
    import numpy as np

    from rotorlab.cli._steady import parse_range
    from rotorlab.io import IMPACT_SWEEP_PARAMETERS

    if stone_mass is not None and param is not None:
        raise BadInput("--stone-mass and --param exclude each other: give only one")
    if stone_mass is not None:
        lo, hi, n = parse_range("--stone-mass", stone_mass, "mass")
        if not lo > 0:
            raise BadInput(f"--stone-mass = {stone_mass}: masses must be > 0 (kg)")
        return "stone_mass", np.linspace(lo, hi, n)
    if param is None:
        return None, None
    name, sep, grid = param.partition("=")
    if not sep or name not in IMPACT_SWEEP_PARAMETERS:
        raise BadInput(f"--param = {param}: must be NAME=A:B:N with NAME one of {', '.join(IMPACT_SWEEP_PARAMETERS)}")
    dim, unit = IMPACT_SWEEP_PARAMETERS[name]
    lo, hi, n = parse_range("--param", grid, dim)
    if lo < 0 or (name in ("stone_mass", "interval") and lo == 0) or (name == "restitution" and hi > 1):
        raise BadInput(f"--param = {param}: values out of range for {name}")
    return name, np.linspace(lo, hi, n)


def _executor(workers: int | None, scheduler: str | None, chunk: int | None, store: Path | None,
              resume: bool) -> Any:
    """The executor of ``--workers`` / ``--scheduler`` (None: in-process), after checking the options."""
    from rotorlab.cli._sweep_common import check_store_path, executor_from_options

    executor = executor_from_options(scheduler, workers)
    if resume and store is None:
        raise BadInput("--resume needs --out STORE.zarr (the store of the sweep to continue)")
    if store is not None:
        check_store_path(store, resume)
    return None if scheduler is None and workers is None else executor


def _run_stored(settings: Any, sweep: Any, *, store: Path | None, resume: bool, chunk: int | None,
                executor: Any, title: str) -> tuple[Any, Any]:
    """Run the sweep (into ``store`` if given) with a progress bar; BadInput / exit 130 on failure
    (:func:`rotorlab.cli._sweep_common.run_into_store`).

    Returns the per-run Dataset and the last :class:`rotorlab.sweep.SweepProgress`.
    """
    from rotorlab.analyses._impact_sweep import default_chunk
    from rotorlab.cli._sweep_common import SweepBar, run_into_store
    from rotorlab.sweep import InProcess, run_sweep

    last: list[Any] = []
    split = store is not None or executor is not None
    size = chunk if chunk is not None or (resume and store is not None and store.exists()) else (
        default_chunk(sweep, split=split))

    def run() -> Any:
        with SweepBar(settings, title) as bar:

            def progress(p: Any) -> None:
                last[:] = [p]
                bar(p)

            return run_sweep(sweep, store=store, resume=resume, chunk_size=size, executor=executor or InProcess(),
                             progress=progress)  # fmt: skip

    if store is None and executor is None:
        runs = run()  # in memory: a plain Ctrl-C, nothing to keep
    else:
        runs = run_into_store(run, store)
    return runs, last[-1]


@app.command("impacts-sweep")
def impacts_sweep_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    stone_mass: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--stone-mass", metavar="A:B:N", help="N stone masses from A to B (kg, or with a unit: 500g:3kg:6).")] = None,
    param: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=A:B:N", help="Sweep another parameter: interval, internal_friction, "
        "restitution or friction (SI, or with a unit).")] = None,
    sequences: Annotated[Optional[int], count_option(  # noqa: UP007
        "--sequences", what="stone sequences per value", metavar="N", help="Random stone sequences per value (>= 1).")] = None,
    t_end: TEndOpt = None,
    seed: SeedOpt = None,
    analysis: AnalysisOpt = None,
    plot: PlotOpt = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc|STORE.zarr", help="Write the result Dataset to this NetCDF file; or, "
        "with the suffix .zarr, every run to this sweep store chunk by chunk (resumable with --resume).")] = None,
    resume: Annotated[bool, typer.Option("--resume", help="Continue the sweep in --out STORE.zarr: run only its "
                                         "missing chunks.")] = False,  # fmt: skip
    workers: WorkersOpt = None,
    scheduler: SchedulerOpt = None,
    chunk: ChunkOpt("Runs per chunk (default: one value's sequences; a resumed store keeps its own).") = None,
    json_out: JsonOpt = False,
) -> None:
    """Impact counts over many random stone sequences per stone mass (seed 001's table, Fig. 5).

    Prints per value the median and quartiles of the impacts, the regimes of the runs and the
    median energy ratio eta; for the seed's own parameters also the paper's count. With --out
    STORE.zarr every finished chunk of runs is kept at once and an interrupted sweep continues
    with --resume; results are identical, bit for bit, whatever --workers, --scheduler or --chunk.
    """
    settings = _settings(ctx)
    with handled(settings):
        name, values = _param(stone_mass, param)
        store = out if out is not None and out.suffix == ".zarr" else None
        _check(None, t_end, seed, plot, None if store is not None else out)
        executor = _executor(workers, scheduler, chunk, store, resume)
        loaded = _impact_case(case, sets, settings)
        spec = _spec(loaded, "impacts-sweep", analysis)
        if name is None:
            name, values = spec.param, list(spec.values)
        from rotorlab.analyses import impact_model, impact_sweep_definition, summarize_impact_sweep, sweep_summary

        overrides = {k: v for k, v in spec.overrides().items() if k != name}
        model = impact_model(loaded.model, **overrides)
        n_seq = spec.n_sequences if sequences is None else sequences
        duration = spec.t_end if t_end is None else t_end
        first = spec.seed if seed is None else seed
        sweep = impact_sweep_definition(model, values, param=name, n_sequences=n_seq, t_end=duration, seed=first,
                                        rtol=spec.rtol, atol=spec.atol, sliding_fraction=spec.sliding_fraction)  # fmt: skip
        where = "" if executor is None else f", {executor.describe()}"
        into = "" if store is None else f", into {store}"
        info(settings, f"Sweeping {name} of {loaded.name}: {len(values)} values x {n_seq} sequences x {duration:g} s"
             f"{where}{into} ...", json_mode=json_out)  # fmt: skip
        runs, p = _run_stored(settings, sweep, store=store, resume=resume, chunk=chunk, executor=executor,
                              title=loaded.name)  # fmt: skip
        ds = summarize_impact_sweep(runs, model, param=name, seed=first)
        summary = sweep_summary(ds)
        if store is not None or executor is not None:
            summary["sweep"] = {"store": None if store is None else str(store),
                                "executor": "in-process" if executor is None else executor.describe(),
                                "chunks": {"total": p.n_chunks, "computed": p.computed, "skipped": p.skipped}}  # fmt: skip
        _finish(settings, loaded, spec, ds, summary, plot, None if store is not None else out, json_out,
                files=() if store is None else (str(store),))  # fmt: skip


def impact_tables(results: dict[str, Any], rows: dict[str, Any] | None = None) -> list[Any]:
    """Rich tables of impact results (``impacts`` and ``impacts-sweep`` Datasets), by name
    (``rows``, the summary rows by name, is accepted for the presentation registry and unused)."""
    from rich.table import Table

    from rotorlab.analyses import impact_summary, paper_counts, sweep_summary
    from rotorlab.report._impacts import SWEEP_COLUMNS, sweep_cells

    tables = []
    for name, ds in results.items():
        kind = ds.attrs.get("analysis")
        if kind == "impacts":
            s = impact_summary(ds)
            t = Table(title=f"{name}: {s['t_end_s']:g} s, stones {s['stone_mass_kg']:g} kg, seed {s['seed']}",
                      title_justify="left")  # fmt: skip
            for col in ("regime", "impacts", "all impacts", "slides", "sliding (s)", "eta", "max approach (m/s)",
                        "max penetration (m)"):  # fmt: skip
                t.add_column(col, justify="left" if col == "regime" else "right")
            eta = "-" if s["energy_ratio"] is None else f"{s['energy_ratio']:.3g}"
            if s["runaway_start_s"] is not None and s["energy_ratio_before_runaway"] is not None:
                eta = f"{s['energy_ratio_before_runaway']:.3g} before runaway, {eta} at stop"
            t.add_row(s["regime"] + (" (stopped)" if s["backward_whirl"] else ""), str(s["impacts"]),
                      str(s["impacts_all"]), str(s["slides"]), f"{s['sliding_time_s']:.4g}", eta,
                      f"{s['max_approach_speed_m_s']:.3g}", f"{s['max_penetration_m']:.2g}")  # fmt: skip
            tables.append(t)
        elif kind == "impacts-sweep":
            doc = sweep_summary(ds)
            paper = paper_counts(ds)
            unit = f" ({doc['units']})" if doc["units"] not in ("", "1") else ""
            t = Table(title=f"{name}: impacts in {doc['t_end_s']:g} s over {doc['n_sequences']} stone sequences",
                      title_justify="left")  # fmt: skip
            with_paper = any(p is not None for p in paper)
            for col in [doc["param"] + unit, *SWEEP_COLUMNS] + (["seed 001"] if with_paper else []):
                t.add_column(col, justify="right")
            for row, p in zip(doc["rows"], paper):
                t.add_row(*sweep_cells(row), *(["-" if p is None else str(p)] if with_paper else []))
            tables.append(t)
    return tables
