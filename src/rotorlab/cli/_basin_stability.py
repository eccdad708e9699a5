"""The ``rotorlab basin-stability`` command: the probability of balancing (and of every other motion,
and of not having settled) from seeded random starts at each value of a parameter, with Wilson
intervals, sampled until they are as narrow as asked; on the sweep engine (``--store``,
``--resume``, ``--workers``, ``--scheduler``). Every option is checked before anything is
computed or written (bad input: exit 2).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app, find_analysis
from rotorlab._limits import MAX_STARTS
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._output import BadInput, handled, info, progress_bar
from rotorlab.cli._sweep_common import ChunkOpt, OutNcOpt, ResumeOpt, SchedulerOpt, StoreOpt, WorkersOpt, YesOpt

__all__ = ["basin_stability_command"]

# the options that set each key of the analysis, for messages
_OPTION_OF = {"param": "--param", "starts": "--starts", "ci_width": "--ci-width", "seed": "--seed",
              "ranges": "--range", "t_end": "--t-end", "speed": "--speed-rpm", "speed_ratio": "--speed-ratio"}


def _check_width(ci_width: float | None) -> None:
    from rotorlab._wilson import min_half_width

    if ci_width is None:
        return
    low = min_half_width()
    if not (math.isfinite(ci_width) and low <= ci_width < 0.5):
        raise BadInput(f"--ci-width = {ci_width:g}: must be a number in [{low:.3g}, 0.5) (the target half-width of "
                       f"the Wilson 95 % intervals; {low:.3g} needs the most starts allowed, {MAX_STARTS} per value)")


def _spec(loaded: Any, base: Any, updates: dict[str, Any]) -> Any:
    """The analysis with the options applied, validated against the model (BadInput naming the option)."""
    from rotorlab.io import BasinStabilitySpec

    data = base.model_dump() if base is not None else {"type": "basin-stability", "name": "basin-stability"}
    if updates.get("starts") is not None:
        data["ci_width"] = None
    if updates.get("ci_width") is not None:
        data["starts"] = None
    if updates.get("speed") is not None:
        data["speed_ratio"] = None
    if updates.get("speed_ratio") is not None:
        data["speed"] = None
    data.update({k: v for k, v in updates.items() if v is not None})
    if not data.get("param"):
        raise BadInput(f"case {loaded.name} has no basin-stability analysis: give --param NAME=A:B:N")
    from rotorlab.cli._basin import validated_spec

    return validated_spec(BasinStabilitySpec, data, loaded, _OPTION_OF, where=True)


def _axes(param: str | None, ranges: list[str] | None, loaded: Any) -> dict[str, Any]:
    """--param and --range read against the model's names (SI values)."""
    from rotorlab.cli._sweep import parse_axis
    from rotorlab.io._sweep_specs import sweep_coordinates

    out: dict[str, Any] = {}
    if param is not None:
        known = sweep_coordinates(loaded.model, "param")
        name = param.partition("=")[0].strip()
        if name not in known and "=" in param:
            reason = loaded.model.missing_coordinate(name)
            from rotorlab.io._coordinates import coordinates_text

            raise BadInput(f"--param = {param}: " + (f"the model of {loaded.name} {reason}" if reason is not None else
                           f"{name!r} is not a parameter of this {loaded.model.type} model (allowed: "
                           f"{coordinates_text(known)})"))  # fmt: skip
        dims = dict(known)
        if name in known:  # a machine's model.<key path> is known only when asked for
            dims[name] = known[name]
        name, entry = parse_axis("--param", param, "param", False, dims)
        out["param"] = {name: list(entry)}
    if ranges:
        known = sweep_coordinates(loaded.model, "ic")
        table = {}
        for text in ranges:
            name, entry = parse_axis("--range", text, "ic", True, dict(known))
            if name in table:
                raise BadInput(f"--range = {text}: {name} is given twice")
            if not entry[1] > entry[0]:
                raise BadInput(f"--range = {text}: HIGH must be > LOW (to hold {name} at one value use --set)")
            table[name] = list(entry)
        out["ranges"] = table
    return out


@app.command("basin-stability")
def basin_stability_command(
    ctx: typer.Context,
    case: CaseArg,
    param: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=A:B:N", help="The parameter and its N values from A to B (SI or with a unit: "
        "spin_speed=1500rpm:3000rpm:16), one of the names of rotorlab sweep --param.")] = None,
    starts: Annotated[Optional[int], count_option(  # noqa: UP007
        "--starts", high=MAX_STARTS, what="random starts per value", metavar="N",
        help="N random starts at every value (instead of --ci-width).")] = None,
    ci_width: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--ci-width", metavar="W", help="Add random starts at each value until every Wilson 95 % interval is within "
        "+-W (default 0.05).")] = None,
    seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--seed", low=0, high=MAX_SEED, metavar="S", help="Seed of the random starts (the same at every value).")] = None,
    ranges: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--range", metavar="NAME=LOW:HIGH", help="A start coordinate drawn uniformly (repeatable; default every "
        "ball angle over 0:360deg).")] = None,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which basin-stability analysis of the case gives the defaults.")] = None,
    speed_rpm: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Base spin speed (rpm) when the parameter is not the speed.")] = None,
    speed_ratio: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-ratio", metavar="RATIO", help="Base spin speed as a multiple of the critical speed p.")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="S", help="Simulated time (s); default from the balanced state's slowest mode.")] = None,
    chunk: ChunkOpt("Starts per chunk (with --ci-width: the step in which a value grows, default 128).") = None,
    store: StoreOpt("starts") = None,
    resume: ResumeOpt = False,
    scheduler: SchedulerOpt = None,
    workers: WorkersOpt = None,
    out: OutNcOpt = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the fractions against the parameter (PNG, PDF or SVG).")] = None,
    sets: SetOpt = None,
    yes: YesOpt = False,
    json_out: JsonOpt = False,
) -> None:
    """Basin stability over a parameter: P(balanced), P(each other motion) and P(not settled) from
    seeded random starts at every value, with Wilson 95 % intervals.

    With --ci-width W (the default, 0.05) starts are added at each value in rounds until every
    interval is within +-W; with --starts N every value gets N. Results do not depend on
    --workers, --scheduler or interruptions (--store and --resume).
    """
    settings = _settings(ctx)
    with handled(settings):
        if starts is not None and ci_width is not None:
            raise BadInput("--starts and --ci-width exclude each other: give only one")
        _check_width(ci_width)
        for option, value in (("--speed-rpm", speed_rpm), ("--speed-ratio", speed_ratio), ("--t-end", t_end)):
            if value is not None and not (math.isfinite(value) and value > 0):
                raise BadInput(f"{option} = {value:g}: must be a finite number > 0")
        if speed_rpm is not None and speed_ratio is not None:
            raise BadInput("--speed-rpm and --speed-ratio exclude each other: give only one")
        from rotorlab.cli._basin import checked_outputs
        from rotorlab.cli._sweep_common import run_into_store

        executor = checked_outputs(plot, out, store, resume, scheduler, workers)
        loaded = _load(case, sets, settings)
        from rotorlab._constants import RPM_PER_RAD_S
        from rotorlab.io._coordinates import mappable_text, record_input_units
        from rotorlab.io._sweep_specs import sweep_coordinates

        if not sweep_coordinates(loaded.model, "ic"):
            raise BadInput(f"case {loaded.name}: basin-stability needs {mappable_text(loaded.model)}")
        base = find_analysis(loaded, "basin-stability", analysis)
        updates = {"starts": starts, "ci_width": ci_width, "seed": seed, "t_end": t_end, "speed_ratio": speed_ratio,
                   "speed": None if speed_rpm is None else speed_rpm / RPM_PER_RAD_S, **_axes(param, ranges, loaded)}
        spec = _spec(loaded, base, updates)
        given = [(t.partition("=")[0].strip(), t.partition("=")[2].split(":")[:2]) for t in (param, *(ranges or ()))
                 if t]  # fmt: skip
        spec = spec.with_input_units(record_input_units(base.input_units if base is not None else {}, given))
        from rotorlab.analyses._basin_stability import (basin_stability_document, basin_stability_rows,
                                                        basin_stability_task_size, run_basin_stability_analysis,
                                                        stability_mapper)  # fmt: skip
        from rotorlab.cli._sweep import _check_ranges

        name = spec.param_axis[0]
        try:
            mapper = stability_mapper(loaded.model, spec)[0]
        except ValueError as exc:
            raise BadInput(f"--param {name}: {exc}") from None
        _check_ranges(mapper, (("--param", [param] if param else []),), {name: spec.param_axis[1:]})
        most = basin_stability_task_size(loaded.model, spec)
        # ETA hook: a pilot chunk's timing times ``most`` starts (at most) gives the estimate to show here
        info(settings, f"Basin stability of {loaded.name} over {name} ({spec.param_axis[3]} values): at most {most} "
             f"starts of {float(mapper.t_end):.3g} s, {executor.describe()} ...", json_mode=json_out)  # fmt: skip
        with progress_bar(settings, {spec.name: most}) as update:
            ds = run_into_store(lambda: run_basin_stability_analysis(
                loaded.model, spec, progress=lambda done, total: update(spec.name, done, total), store=store,
                resume=resume, executor=executor), store, "--store", yes=yes, settings=settings,
                what="starts")  # fmt: skip
        ds.attrs["case"] = loaded.name
        from rotorlab.cli._basin import write_and_report
        from rotorlab.plot._basin_stability import basin_stability_figure
        from rotorlab.report._basin_stability import basin_stability_tables

        write_and_report(loaded, spec.name, ds, lambda: basin_stability_figure(ds), plot, out, json_out,
                         lambda: basin_stability_document(ds),
                         lambda: basin_stability_tables({spec.name: ds}, {spec.name: basin_stability_rows(ds)}))
