"""The ``shock-margin`` and ``friction-margin`` commands: a case's margin analysis (or a default
one) with speeds and settings from the command line, run through the registries."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _load, _settings, app, find_analysis, run_through_entry
from rotorlab.cli._output import BadInput, handled
from rotorlab.cli._options import count_option
from rotorlab.cli._steady import _check_plot

__all__: list[str] = []

SpeedRpmOpt = Annotated[Optional[list[float]], typer.Option(  # noqa: UP007
    "--speed-rpm", metavar="RPM", help="Spin speed (rpm), > 0; repeatable.", show_default=False)]
SpeedRatioOpt = Annotated[Optional[list[float]], typer.Option(  # noqa: UP007
    "--speed-ratio", metavar="R", help="Spin speed as a multiple of the critical speed, > 0; repeatable.",
    show_default=False)]  # fmt: skip
AnalysisOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--analysis", metavar="NAME", help="The case's analysis of this type to start from (default: the first).",
    show_default=False)]  # fmt: skip
NoSimOpt = Annotated[bool, typer.Option("--no-simulate", help="Closed forms only (no simulation check).")]
OutOpt = Annotated[Optional[Path], typer.Option(  # noqa: UP007
    "--out", "-o", metavar="FILE.nc", help="Also write the result to this NetCDF file.", show_default=False)]


def _speeds(rpm: list[float] | None, ratio: list[float] | None) -> dict[str, Any]:
    if rpm and ratio:
        raise BadInput("--speed-rpm and --speed-ratio exclude each other: give only one")
    for option, values, unit in (("--speed-rpm", rpm, "rpm"), ("--speed-ratio", ratio, "multiple of p")):
        for v in values or ():
            if not (math.isfinite(v) and v > 0):
                raise BadInput(f"{option} = {v:g}: must be a finite number > 0 ({unit})")
    if rpm:
        return {"speed": tuple(v * math.pi / 30.0 for v in rpm), "speed_ratio": None}
    if ratio:
        return {"speed": None, "speed_ratio": tuple(ratio)}
    return {}


def _run(ctx, kind: str, case: str, sets, analysis, speeds: tuple[Any, Any], no_simulate: bool,
         extra: dict[str, Any], out, json_out) -> None:
    """Start from the case's analysis of ``kind`` (or a default one), apply the options, run it."""
    settings = _settings(ctx)
    with handled(settings):
        update = {**_speeds(*speeds), **{k: v for k, v in extra.items() if v is not None}}
        if no_simulate:
            update["simulate"] = False
        _check_plot("--out", out)
        loaded = _load(case, sets)
        from rotorlab.io import ANALYSIS_SPECS

        spec_type = ANALYSIS_SPECS[kind]
        problem = spec_type.wrong_model(loaded.model)
        if problem is not None:
            raise BadInput(f"case {loaded.name}: {kind} {problem}")
        found = find_analysis(loaded, kind, analysis)
        spec = found if found is not None else spec_type(name=kind)
        run_through_entry(settings, loaded, spec.model_copy(update=update), json_out, out)


@app.command("shock-margin")
def shock_margin_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speed_rpm: SpeedRpmOpt = None,
    speed_ratio: SpeedRatioOpt = None,
    directions: Annotated[Optional[int], count_option(  # noqa: UP007
        "--directions", high=720, metavar="N", help="Directions of the knock and the load shift over a turn.",
        show_default=False)] = None,  # fmt: skip
    no_simulate: NoSimOpt = False,
    analysis: AnalysisOpt = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Minimal fatal shock of the balanced state: the smallest knock (N s) and load shift (g mm) that
    throw the balls out of balance, with the worst direction, at each speed."""
    _run(ctx, "shock-margin", case, sets, analysis, (speed_rpm, speed_ratio), no_simulate,
         {"directions": directions}, out, json_out)


@app.command("friction-margin")
def friction_margin_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speed_rpm: SpeedRpmOpt = None,
    speed_ratio: SpeedRatioOpt = None,
    grid: Annotated[Optional[int], count_option(  # noqa: UP007
        "--grid", low=21, high=2001, metavar="N",
        help="Grid points per ball angle of the band search (one or two balls; more are searched by optimisation).",
        show_default=False)] = None,  # fmt: skip
    no_simulate: NoSimOpt = False,
    analysis: AnalysisOpt = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Friction band: where friction holds the balls near the balanced position, and the worst residual
    vibration over it, at each speed (checked by simulation)."""
    _run(ctx, "friction-margin", case, sets, analysis, (speed_rpm, speed_ratio), no_simulate, {"grid": grid}, out,
         json_out)
