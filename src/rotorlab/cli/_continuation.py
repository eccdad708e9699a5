"""The ``continue`` command: branches of steady motions in a named parameter (``rotorlab.continuation``).

``rotorlab continue CASE --param NAME=START:STOP [--param2 NAME=A:B] [--from K] [--plot F]
[--out F.nc] [--json]``: START and STOP are SI numbers or carry a unit (``1000rpm:3000rpm``,
``10g:40g``); without ``--param`` the case's first ``continuation`` analysis is run. JSON is SI:
``{"case", ..., "branches": [...], "units": {...}, "curves": [...]}`` (the issue's document).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app
from rotorlab.cli._output import BadInput, emit_json, handled, info, status, stdout
from rotorlab.cli._steady import _check_plot

__all__ = ["continue_command", "parse_named_range", "continuation_tables"]


def parse_named_range(option: str, text: str) -> tuple[str, tuple[float, float]]:
    """Read ``NAME=START:STOP`` (START, STOP in SI or with a unit of the parameter's dimension).

    Raises
    ------
    BadInput
        Malformed text, an unknown name (the known ones are listed), a unit of the wrong
        dimension, or START = STOP.

    Examples
    --------
    >>> parse_named_range("--param", "drive.speed=0:30rpm")
    ('drive.speed', (0.0, 3.141592653589793))
    """
    from rotorlab.io import CaseError, to_si
    from rotorlab.io._continuation_spec import continuation_dimension

    name, sep, rest = text.partition("=")
    parts = rest.split(":")
    if not sep or len(parts) != 2:
        raise BadInput(f"{option} = {text}: must be NAME=START:STOP (e.g. drive.speed=1000rpm:3000rpm)")
    try:
        dimension = continuation_dimension(name.strip())
    except ValueError as exc:
        raise BadInput(f"{option} = {text}: {exc}") from None
    ends = []
    for part in parts:
        try:
            ends.append(float(part))
        except ValueError:
            if dimension is None:
                raise BadInput(f"{option} = {text}: {name.strip()} takes plain numbers in its SI unit") from None
            try:
                ends.append(to_si(part.strip(), dimension, option))
            except CaseError as exc:
                raise BadInput(f"{option} = {text}: {exc}") from None
    if ends[0] == ends[1] or not all(abs(e) < float("inf") for e in ends):
        raise BadInput(f"{option} = {text}: START and STOP must be finite and differ")
    return name.strip(), (ends[0], ends[1])


@app.command("continue")
def continue_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    param: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=START:STOP", help="The continued parameter and its range (drive.speed, ball_mass, "
        "ball_mass_scaled_damping, "
        "ball_damping, races[i].balls[j].mass, unbalances[i].magnitude ...; SI or with a unit: "
        "drive.speed=1000rpm:3000rpm).")] = None,
    param2: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param2", metavar="NAME=A:B", help="Continue the fold and Hopf points found in a second parameter; support_anisotropy=A:B "
        "((k_yy - k_xx) / (k_xx + k_yy)) against drive.speed: the balanced state's Floquet stability boundary.")] = None,
    start_from: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--from", metavar="K", help="Starting motions: balanced, side, all or a motion's label (side 01); hopf or "
        "simulation: whirl orbits (periodic branches) from the Hopf points or from a simulation at the range's "
        "start.")] = None,
    speed_rpm: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Constant speed when the speed is not the continued parameter.")] = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the bifurcation diagram (PNG, PDF or SVG by suffix); with --param2 "
        "also the curves over the grid chart as FILE-curves.")] = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc", help="Write the result Dataset to this NetCDF file.")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Continue steady motions of a machine with balls (or a jeffcott_balls rotor) in a named parameter.

    Locates folds, Hopf points (with their frequency) and branch points, switches branches at
    branch points, and says in words where stability changes ("balancing becomes stable above
    1371 rpm"). Without --param the case's first continuation analysis is run.
    """
    settings = _settings(ctx)
    with handled(settings):
        first = None if param is None else parse_named_range("--param", param)
        second = None if param2 is None else parse_named_range("--param2", param2)
        _check_plot("--plot", plot)
        _check_plot("--out", out)
        loaded = _load(case, sets, settings)
        spec = _spec(loaded, first, second, start_from, speed_rpm)
        from rotorlab.analyses import run_analysis, summarize
        from rotorlab.analyses._continuation import continuation_machine
        try:
            continuation_machine(loaded.model, spec)
        except ValueError as exc:
            raise BadInput(f"--param = {param or spec.param}: {exc}") from None
        info(settings, f"{loaded.name}: continuation ({spec.describe(loaded.model)}) ...", json_mode=json_out)
        with status(settings, "Continuing ..."):
            try:
                ds = run_analysis(loaded.model, spec)
            except ValueError as exc:  # no motion of that kind at START, a refused value ...
                raise BadInput(f"--from {spec.start_from} / --param {spec.param}: {exc}") from None
        ds.attrs["case"] = loaded.name
        rows = summarize(ds)
        written = _write(ds, plot, out)
        if json_out:
            import json

            emit_json({**_json_case(loaded), "analysis": spec.name, "type": "continuation",
                       **json.loads(ds.attrs["result"]), "files": written})
            return
        con = stdout()
        for table in continuation_tables({spec.name: ds}, {spec.name: rows}):
            con.print(table, markup=False)
        for path in written:
            con.print(f"Wrote {path}", markup=False)


def _spec(loaded: Any, first: Any, second: Any, start_from: str | None, speed_rpm: float | None) -> Any:
    from pydantic import ValidationError

    from rotorlab.io import ContinuationSpec

    base = next((a for a in loaded.analyses if a.type == "continuation"), None)
    if first is None and base is None:
        raise BadInput(f"case {loaded.name} has no continuation analysis: give --param NAME=START:STOP")
    data: dict[str, Any] = {} if base is None else base.model_dump(exclude_none=True)
    data.setdefault("name", "continuation")
    if first is not None:
        data.update(param=first[0], range=list(first[1]))
    if second is not None:
        data.update(param2=second[0], range2=list(second[1]))
    if start_from is not None:
        data["start_from"] = start_from
    if speed_rpm is not None:
        data["speed"] = f"{speed_rpm!r} rpm"
    data["type"] = "continuation"
    try:
        spec = ContinuationSpec(**data)
    except ValidationError as exc:
        err = exc.errors()[0]
        key = str(err["loc"][0]) if err["loc"] else ""
        option = _OPTIONS.get(key, "--param")
        raise BadInput(f"{option} = {err.get('input')!r}: {err['msg'].removeprefix('Value error, ')}") from None
    issues = spec.case_issues(loaded.model)
    if issues:
        raise BadInput("; ".join(f"{_OPTIONS.get(str(i.loc[0]), 'continuation.' + str(i.loc[0]))}: {i.message}"
                                 for i in issues))
    return spec


_OPTIONS = {"start_from": "--from", "param2": "--param2", "range2": "--param2", "speed": "--speed-rpm",
            "param": "--param", "range": "--param"}


def _write(ds: Any, plot: Path | None, out: Path | None) -> list[str]:
    written = []
    if plot is not None:
        from rotorlab.plot import continuation_figures

        for stem, fig in continuation_figures(ds, "x").items():
            path = plot if stem.endswith("-bifurcation") else plot.with_name(f"{plot.stem}-curves{plot.suffix}")
            fig.savefig(path, dpi=110)
            written.append(str(path))
    if out is not None:
        from rotorlab.io import save_netcdf

        written.append(str(save_netcdf(ds, out)))
    return written


def continuation_tables(results: Mapping[str, Any], rows: Mapping[str, Sequence[Mapping[str, Any]]]) -> list[Any]:
    """One rich table per continuation result: its special points in words, then its branches."""
    from rich.table import Table

    from rotorlab._constants import shown_unit
    from rotorlab.report._continuation import _orbit_sentences, _period, _points

    out = []
    for name, ds in results.items():
        t = Table(title=f"{name}: special points of the steady motions in {ds.attrs.get('parameter', '')}",
                  title_justify="left")
        f, unit = shown_unit(ds.attrs.get("units", ""))
        for col in ("type", "branch", f"value ({unit})", "what happens"):
            t.add_column(col, justify="right" if col.startswith("value") else "left")
        for r in _points(rows[name]):
            t.add_row(r["type"], r["branch"], f"{f * r['value']:.6g}", r["description"])
        out.append(t)
        b = Table(title=f"{name}: branches", title_justify="left")
        for col in ("branch", f"from ({unit})", f"to ({unit})", "points", "stable points", "period (s)", "ended"):
            b.add_column(col)
        for r in rows[name]:
            if r["type"] == "branch-summary":
                b.add_row(r["branch"], f"{f * r['from']:.4g}", f"{f * r['to']:.4g}", str(r["points"]),
                          str(r["stable_points"]), _period(r), r["end"])
        out.append(b)
        out.extend(_orbit_sentences(rows[name]))
    return out
