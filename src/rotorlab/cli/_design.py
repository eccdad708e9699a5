"""The ``rotorlab design`` command: the values of named parameters that minimise an objective while
the rotor balances with confidence (the Wilson lower bound of P(balanced)) over its operating
range; every design from the same random starts, the winner re-simulated from fresh ones. On the
sweep engine (``--store``, ``--resume``, ``--workers``, ``--scheduler``). Every option is checked
before anything is computed or written (bad input: exit 2).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab._limits import MAX_STARTS
from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _load, _settings, app, find_analysis
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._output import BadInput, handled, info, progress_bar
from rotorlab.cli._sweep_common import OutNcOpt, ResumeOpt, SchedulerOpt, WorkersOpt

__all__ = ["design_command"]

_OPTION_OF = {"vary": "--vary", "objectives": "--objective", "param": "--param", "starts": "--starts",
              "seed": "--seed", "budget": "--budget", "optimizer": "--optimizer", "optimizer_seed": "--optimizer-seed",
              "constraints": "--constraint"}


def _vary(texts: list[str] | None, loaded: Any) -> dict[str, list[float]]:
    from rotorlab.cli._sweep import parse_axis
    from rotorlab.io._coordinates import coordinates_text
    from rotorlab.io._sweep_specs import sweep_coordinates

    out: dict[str, list[float]] = {}
    known = sweep_coordinates(loaded.model, "param")
    for text in texts or ():
        name = text.partition("=")[0].strip()
        if name not in known:
            raise BadInput(f"--vary = {text}: {name!r} is not a parameter of this {loaded.model.type} model (allowed: "
                           f"{coordinates_text(known)})")  # fmt: skip
        name, entry = parse_axis("--vary", text, "param", True, {name: known[name]})  # model.<key path> too
        out[name] = list(entry)
    return out


def _store(store: Path | None, resume: bool) -> None:
    if resume and store is None:
        raise BadInput("--resume needs --store DIR (the folder of the evaluations to continue)")
    if store is None:
        return
    if store.exists() and not resume:
        raise BadInput(f"--store = {store}: exists; give --resume to continue that search, or another path")
    if store.exists() and not store.is_dir():
        raise BadInput(f"--store = {store}: not a folder")
    if not store.absolute().parent.is_dir():
        raise BadInput(f"--store = {store}: folder {store.absolute().parent} does not exist")


def _reads_run_ups(data: dict[str, Any]) -> bool:
    """Whether a design's objectives, limits or constraints read run-ups (its ``param`` may be omitted)."""
    from rotorlab.design import DESIGN_CONSTRAINTS, DESIGN_OBJECTIVES

    names = [n for n in (*(data.get("objectives") or ()), *(data.get("limits") or {})) if isinstance(n, str)]
    constraints = [n for n in data.get("constraints") or () if isinstance(n, str)]
    return any(getattr(DESIGN_OBJECTIVES.get(n), "run_ups", False) for n in names) or any(
        getattr(DESIGN_CONSTRAINTS.get(n), "run_ups", False) for n in constraints)


@app.command("design")
def design_command(
    ctx: typer.Context,
    case: CaseArg,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which design analysis of the case gives the defaults.")] = None,
    vary: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--vary", metavar="NAME=LOW:HIGH", help="A named parameter varied between bounds (repeatable; replaces the "
        "case's vary table).")] = None,
    objective: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--objective", metavar="NAME", help="An objective to minimise (repeatable, at most two: a Pareto "
        "front).")] = None,
    constraint: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--constraint", metavar="NAME", help="A named constraint every feasible design meets, e.g. "
        "no-housing-contact (repeatable; replaces the case's constraints).")] = None,
    param: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=A:B:N", help="The operating range (spin_speed=1800rpm:2400rpm:3; a run-up design: "
        "default the drive's operating speed).")] = None,
    starts: Annotated[Optional[int], count_option(  # noqa: UP007
        "--starts", high=MAX_STARTS, what="random starts per design and operating value", metavar="N",
        help="Random starts per design and operating value (the same for every design).")] = None,
    seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--seed", low=0, high=MAX_SEED, metavar="S", help="Seed of the random starts.")] = None,
    budget: Annotated[Optional[int], count_option(  # noqa: UP007
        "--budget", high=10_000, what="designs evaluated", metavar="N", help="Designs evaluated.")] = None,
    optimizer: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--optimizer", metavar="NAME", help="tpe (default) or differential-evolution.")] = None,
    optimizer_seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--optimizer-seed", low=0, high=MAX_SEED, metavar="S", help="Seed of the optimiser.")] = None,
    store: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--store", metavar="DIR", help="Checkpoint: every design's starts go to a Zarr store in this folder; an "
        "interrupted search continues with --resume.")] = None,
    resume: ResumeOpt = False,
    scheduler: SchedulerOpt = None,
    workers: WorkersOpt = None,
    out: OutNcOpt = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the designs figure (PNG, PDF or SVG).")] = None,
    sets: SetOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Design search: the values of the varied parameters that minimise the objective(s) while
    the Wilson lower bound of P(balanced) reaches min_balanced at every operating value.

    Every design is evaluated from the same random starts (common random numbers); the winner
    is re-simulated from fresh starts and both intervals are shown. Results do not depend on
    --workers, --scheduler or interruptions (--store and --resume).
    """
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.cli._basin import checked_outputs, validated_spec, write_and_report

        executor = checked_outputs(plot, out, None, False, scheduler, workers)
        _store(store, resume)
        loaded = _load(case, sets, settings)
        from rotorlab.io._coordinates import mappable_text
        from rotorlab.io._sweep_specs import sweep_coordinates

        base = find_analysis(loaded, "design", analysis)
        data = base.model_dump() if base is not None else {"type": "design", "name": "design"}
        updates: dict[str, Any] = {"starts": starts, "seed": seed, "budget": budget, "optimizer": optimizer,
                                   "optimizer_seed": optimizer_seed, "objectives": objective or None,
                                   "constraints": constraint or None}  # fmt: skip
        wanted = {**data, **{k: v for k, v in updates.items() if v is not None}}
        if not _reads_run_ups(wanted) and not sweep_coordinates(loaded.model, "ic"):  # P(balanced): random starts
            raise BadInput(f"case {loaded.name}: design needs {mappable_text(loaded.model)} (or a run-up objective "
                           "of a machine with a servo drive)")
        if vary:
            updates["vary"] = _vary(vary, loaded)
        if param is not None:
            from rotorlab.cli._basin_stability import _axes

            updates["param"] = _axes(param, None, loaded)["param"]
        data.update({k: v for k, v in updates.items() if v is not None})
        if not data.get("param") and _reads_run_ups(data):  # a run-up design operates at its drive's speed
            speed = getattr(getattr(loaded.model, "drive", None), "operating_speed", None)
            if speed is not None:
                data["param"] = {"model.drive.operating_speed": [float(speed), float(speed), 1]}
        for key, option in (("vary", "--vary NAME=LOW:HIGH"), ("objectives", "--objective NAME"),
                            ("param", "--param NAME=A:B:N")):  # fmt: skip
            if not data.get(key):
                raise BadInput(f"case {loaded.name} has no design analysis: give {option}")
        from rotorlab.io import DesignSpec

        spec = validated_spec(DesignSpec, data, loaded, _OPTION_OF, where=True)
        from rotorlab.analyses._design_case import (design_document, design_problem, design_rows,
                                                    run_design_analysis)  # fmt: skip

        try:  # the bounds against each parameter's range, before anything runs
            design_problem(loaded.model, spec)
        except ValueError as exc:
            raise BadInput(f"case {loaded.name}, analysis {spec.name}: {exc}") from None
        info(settings, f"Design search of {loaded.name}: {spec.describe(loaded.model)}, {executor.describe()} ...",
             json_mode=json_out)  # fmt: skip
        from rotorlab.sweep import ExecutorError, SweepStoreError

        with progress_bar(settings, {spec.name: spec.budget}, {spec.name: "designs"}) as update:
            try:
                ds = run_design_analysis(loaded.model, spec, progress=lambda d, t: update(spec.name, d, t),
                                         store=store, resume=resume, executor=executor)  # fmt: skip
            except (SweepStoreError, ExecutorError) as exc:
                raise BadInput(f"--store = {store}: {exc}") from None
        ds.attrs["case"] = loaded.name
        from rotorlab.plot._design import design_figure
        from rotorlab.report._design import design_tables

        tables = lambda: design_tables({spec.name: ds}, {spec.name: design_rows(ds)})  # noqa: E731
        write_and_report(loaded, spec.name, ds, lambda: design_figure(ds), plot, out, json_out,
                         lambda: design_document(ds), tables)
