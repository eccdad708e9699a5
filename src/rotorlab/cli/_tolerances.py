"""The ``rotorlab tolerances`` command: Sobol indices of P(balanced), the residual vibration and the
transient peak of a balancer machine with respect to uncertain inputs with stated distributions,
and the Monte-Carlo envelope of its vibration; on the sweep engine (``--store``, ``--resume``,
``--workers``, ``--scheduler``). Every option is checked before anything is computed or written
(bad input: exit 2).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _load, _settings, app, find_analysis
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._output import BadInput, handled, info, progress_bar
from rotorlab.cli._sweep_common import ChunkOpt, OutNcOpt, ResumeOpt, SchedulerOpt, StoreOpt, WorkersOpt, YesOpt

__all__ = ["tolerances_command"]

# the options that set each key of the analysis, for messages
_OPTION_OF = {"samples": "--samples", "starts": "--starts", "seed": "--seed", "t_end": "--t-end",
              "inputs": "analysis inputs"}  # fmt: skip


@app.command("tolerances")
def tolerances_command(
    ctx: typer.Context,
    case: CaseArg,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which tolerances analysis of the case to run (default its only one).")] = None,
    samples: Annotated[Optional[int], count_option(  # noqa: UP007
        "--samples", low=2, high=65536, what="base samples", metavar="N",
        help="Base samples N, a power of 2: N (D + 2) machines for D inputs.")] = None,
    starts: Annotated[Optional[int], count_option(  # noqa: UP007
        "--starts", low=1, high=1024, what="ball starts per machine", metavar="K",
        help="Random ball starts per machine (the same at every machine).")] = None,
    seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--seed", low=0, high=MAX_SEED, metavar="S", help="Seed of the design and of the starts.")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="S", help="Simulated time of every start (s).")] = None,
    chunk: ChunkOpt("Machines per chunk (default 16).") = None,
    store: StoreOpt("machines") = None,
    resume: ResumeOpt = False,
    scheduler: SchedulerOpt = None,
    workers: WorkersOpt = None,
    out: OutNcOpt = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the Sobol indices as bars with their intervals (PNG, PDF or SVG).")] = None,
    envelope: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--envelope", metavar="FILE", help="Save the Monte-Carlo envelope of the vibration (PNG, PDF or SVG).")] = None,
    sets: SetOpt = None,
    yes: YesOpt = False,
    json_out: JsonOpt = False,
) -> None:
    """Tolerances: which uncertain input P(balanced), the residual vibration and the transient peak
    are most sensitive to (Sobol first- and total-order indices with bootstrap intervals), and the
    spread of the vibration over the machines (median and 5-95 % band over time).

    The inputs and their distributions are the case's [[analysis]] type = "tolerances" table.
    Results do not depend on --workers, --scheduler or interruptions (--store and --resume).
    """
    import math

    settings = _settings(ctx)
    with handled(settings):
        if t_end is not None and not (math.isfinite(t_end) and t_end > 0):
            raise BadInput(f"--t-end = {t_end:g}: must be a finite number > 0 (s)")
        from rotorlab.cli._basin import checked_outputs, validated_spec
        from rotorlab.cli._steady import _check_plot

        executor = checked_outputs(plot, out, store, resume, scheduler, workers)
        _check_plot("--envelope", envelope)
        loaded = _load(case, sets, settings)
        base = find_analysis(loaded, "tolerances", analysis)
        if base is None:
            raise BadInput(f"case {loaded.name} has no tolerances analysis: add [[analysis]] type = \"tolerances\" "
                           "with its [analysis.inputs]")  # fmt: skip
        from rotorlab.io import TolerancesSpec

        data = base.model_dump()
        data.update({k: v for k, v in {"samples": samples, "starts": starts, "seed": seed, "t_end": t_end}.items()
                     if v is not None})  # fmt: skip
        spec = validated_spec(TolerancesSpec, data, loaded, _OPTION_OF, where=True)
        from rotorlab.analyses._tolerances import (run_tolerances_analysis, tolerances_document, tolerances_rows,
                                                   tolerances_task_size)  # fmt: skip
        from rotorlab.cli._sweep_common import run_into_store

        total = tolerances_task_size(loaded.model, spec)
        info(settings, f"Tolerances of {loaded.name}: {total} machines x {spec.starts} starts of {spec.t_end:.3g} s, "
             f"{executor.describe()} ...", json_mode=json_out)  # fmt: skip
        with progress_bar(settings, {spec.name: total}) as update:
            ds = run_into_store(lambda: run_tolerances_analysis(
                loaded.model, spec, progress=lambda done, n: update(spec.name, done, n), store=store, resume=resume,
                executor=executor), store, "--store", yes=yes, settings=settings, what="machines")  # fmt: skip
        ds.attrs["case"] = loaded.name
        from rotorlab.cli._basin import _save_plot, write_and_report
        from rotorlab.plot._tolerances import envelope_figure, sensitivity_figure
        from rotorlab.report._tolerances import tolerances_tables

        if envelope is not None:
            info(settings, f"Wrote {_save_plot(envelope_figure(ds), envelope)}", json_mode=json_out)
        write_and_report(loaded, spec.name, ds, lambda: sensitivity_figure(ds), plot, out, json_out,
                         lambda: tolerances_document(ds),
                         lambda: tolerances_tables({spec.name: ds}, {spec.name: tolerances_rows(ds)}))
