"""The ``rotorlab basin`` command: regimes reached from a grid (or random sample) of starts.

Registered on :data:`rotorlab.cli._app.app`; see :mod:`rotorlab.analyses._basin` for the
computation and :func:`rotorlab.analyses.basin_document` for the ``--json`` document.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app, find_analysis
from rotorlab.cli._output import BadInput, emit_json, exit_if_failed, handled, info, progress_bar, stdout
from rotorlab.cli._steady import _check_plot, parse_range
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._sweep_common import ChunkOpt, SchedulerOpt, WorkersOpt, YesOpt


def _names(known: Any) -> str:
    from rotorlab.io._coordinates import coordinates_text

    return coordinates_text(known)


__all__ = ["basin_command", "basin_tables"]

# options that set each key of a basin analysis, for messages
_OPTION_OF = {"x": "--x", "y": "--y", "fixed": "--fix", "samples": "--random", "seed": "--seed",
              "t_end": "--t-end"}  # fmt: skip


def _axis(option: str, text: str | None, known: dict[str, str]) -> tuple[str, float, float, int] | None:
    """Read ``NAME=A:B:N``; A and B in SI or with a unit of the coordinate's dimension."""
    if text is None:
        return None
    name, sep, grid = text.partition("=")
    name = name.strip()
    if not sep or not name:
        raise BadInput(f"{option} = {text}: must be NAME=A:B:N (coordinates: {_names(known)})")
    if name not in known:
        raise BadInput(f"{option} = {text}: {name!r} is not a coordinate of this case's model "
                       f"(coordinates: {_names(known)})")  # fmt: skip
    start, stop, count = parse_range(option, grid, known[name])
    return name, start, stop, count


def _fixed(values: list[str] | None, known: dict[str, str]) -> dict[str, float]:
    from rotorlab.io import to_si

    out = {}
    for text in values or ():
        name, sep, raw = text.partition("=")
        name = name.strip()
        if not sep or name not in known:
            raise BadInput(f"--fix = {text}: must be NAME=VALUE with NAME one of {_names(known)}")
        try:
            out[name] = float(raw)
        except ValueError:
            out[name] = to_si(raw.strip(), known[name], f"--fix {name}")
    return out


def _input_units(base: Any, x: str | None, y: str | None, fix: list[str] | None) -> dict[str, str]:
    """The units the coordinates were written in: the case's, then those of --x, --y and --fix."""
    from rotorlab.io._coordinates import record_input_units

    given = [(t.partition("=")[0].strip(), t.partition("=")[2].split(":")[:2]) for t in (x, y) if t]
    given += [(t.partition("=")[0].strip(), [t.partition("=")[2].strip()]) for t in fix or ()]
    return record_input_units(base.input_units if base is not None else {}, given)


def _effective_spec(loaded: Any, base: Any, updates: dict[str, Any]) -> Any:
    """The basin analysis with the command-line options applied, validated against the model."""
    from rotorlab.io import BasinSpec

    data = base.model_dump() if base is not None else {"type": "basin", "name": "basin"}
    data.update({k: v for k, v in updates.items() if v is not None})
    if base is not None and "fixed" in updates:
        data["fixed"] = {**base.fixed, **updates["fixed"]}
    for axis in ("x", "y"):  # a coordinate varied now is no longer fixed
        if axis in updates and updates[axis] is not None:
            data.get("fixed", {}).pop(updates[axis][0], None)
    missing = [opt for key, opt in (("x", "--x"), ("y", "--y")) if data.get(key) is None]
    if missing:
        raise BadInput(f"case {loaded.name} has no basin analysis: give {' and '.join(missing)} "
                       "(NAME=A:B:N)")  # fmt: skip
    return validated_spec(BasinSpec, data, loaded, _OPTION_OF)


def validated_spec(kind: Any, data: dict[str, Any], loaded: Any, option_of: dict[str, str],
                   where: bool = False) -> Any:  # fmt: skip
    """The analysis spec ``kind`` of ``data`` (a case's analysis with command-line options applied),
    checked against the case's model: the first problem is BadInput naming the option that sets
    its key (``option_of``; with ``where`` also the rest of its key path)."""
    from pydantic import ValidationError

    try:
        spec = kind.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        key = str(err["loc"][0]) if err["loc"] else ""
        msg = err["msg"].removeprefix("Value error, ")
        raise BadInput(f"{option_of.get(key, key)}: {msg}" if key else msg) from None
    issues = spec.case_issues(loaded.model)
    if issues:
        first = issues[0]
        key = str(first.loc[0]) if first.loc else ""
        rest = " ".join(str(k) for k in first.loc[1:]) if where else ""
        raise BadInput(f"{option_of.get(key, 'case ' + loaded.name)}{' ' + rest if rest else ''}: {first.message}")
    return spec


def _save_plot(fig: Any, path: Path) -> str:
    """Save a figure atomically (a temporary file renamed into place)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.absolute().parent)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return str(path)


@app.command("basin")
def basin_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    x: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--x", metavar="NAME=A:B:N", help="First varied start coordinate or parameter: N values from A to B "
        "(SI, or with a unit: psi=0:360deg:64).")] = None,
    y: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--y", metavar="NAME=A:B:N", help="Second varied start coordinate or parameter.")] = None,
    fix: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--fix", metavar="NAME=VALUE", help="Fix another coordinate (repeatable): --fix rolling_friction=1e-4.")] = None,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which basin analysis of the case to start from (default: the first).")] = None,
    random: Annotated[Optional[int], count_option(  # noqa: UP007
        "--random", what="random starts", metavar="N", help="N random starts over the x and y ranges (basin stability) instead of the grid.")] = None,
    seed: Annotated[Optional[int], count_option(  # noqa: UP007
        "--seed", low=0, high=MAX_SEED, metavar="S", help="Seed of the random starts.")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="S", help="Simulated time (s).")] = None,
    chunk: ChunkOpt("Trajectories integrated together (results do not depend on it).") = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc", help="Write the basin Dataset to this NetCDF file.")] = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the basin map (PNG, PDF or SVG by suffix).")] = None,
    store: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--store", metavar="STORE.zarr", help="Checkpoint: write every finished chunk to this Zarr store, so that "
        "an interrupted basin continues with --resume (results are the same).")] = None,
    resume: Annotated[bool, typer.Option("--resume", help="Continue the basin in --store: compute only its "
                                         "missing chunks.")] = False,  # fmt: skip
    scheduler: SchedulerOpt = None,
    workers: WorkersOpt = None,
    yes: YesOpt = False,
    json_out: JsonOpt = False,
) -> None:
    """Map starts to regimes: basin map, basin fractions against the simulated time, settling times.

    Without --x/--y the grid of the case's (first, or --analysis) basin analysis is used. The
    toroidal ball's regimes are working, spare and other; a rotor with balls has balanced, one
    per side motion, non-synchronous and other. With --store every finished chunk is kept in a
    Zarr store: Ctrl-C (or a killed run) loses nothing, and the same command with --resume
    computes only the missing chunks.
    """
    settings = _settings(ctx)
    with handled(settings):
        if t_end is not None and not (t_end > 0 and t_end < float("inf")):
            raise BadInput(f"--t-end = {t_end:g}: must be a finite number > 0 (s)")
        from rotorlab.cli._sweep_common import run_into_store

        executor = checked_outputs(plot, out, store, resume, scheduler, workers)
        loaded = _load(case, sets, settings)
        from rotorlab.io import coordinate_dimensions

        known = coordinate_dimensions(loaded.model)
        if not known:
            from rotorlab.io._coordinates import mappable_text

            raise BadInput(f"case {loaded.name}: basins need {mappable_text(loaded.model)}")
        base = find_analysis(loaded, "basin", analysis)
        updates: dict[str, Any] = {"x": _axis("--x", x, known), "y": _axis("--y", y, known),
                                   "samples": random, "seed": seed, "t_end": t_end}  # fmt: skip
        if fix:
            updates["fixed"] = _fixed(fix, known)
        if updates["x"] is not None and updates["y"] is not None and updates["x"][0] == updates["y"][0]:
            raise BadInput(f"--y = {y}: must vary another coordinate than --x ({updates['x'][0]})")
        spec = _effective_spec(loaded, base, updates)
        spec = spec.with_input_units(_input_units(base, x, y, fix))
        from rotorlab.analyses._basin import basin_document, run_basin_analysis

        n = spec.samples if spec.samples is not None else spec.x[3] * spec.y[3]
        info(settings, f"Mapping {loaded.name}: {n} starts ...", json_mode=json_out)
        with progress_bar(settings, {spec.name: n}) as update:
            ds = run_into_store(lambda: run_basin_analysis(
                loaded.model, spec, chunk_size=chunk, progress=lambda done, total: update(spec.name, done, total),
                store=store, resume=resume, executor=executor), store, "--store", yes=yes, settings=settings,
                what="starts")  # fmt: skip
        ds.attrs["case"] = loaded.name
        from rotorlab.analyses._basin import basin_rows
        from rotorlab.plot import basin_figure

        write_and_report(loaded, spec.name, ds, lambda: basin_figure(
            ds, title=f"{loaded.name}: regimes after {float(ds.horizon[-1]):g} s"), plot, out, json_out,
            lambda: basin_document(ds), lambda: basin_tables({spec.name: ds}, {spec.name: basin_rows(ds)}))  # fmt: skip


def checked_outputs(plot: Path | None, out: Path | None, store: Path | None, resume: bool, scheduler: str | None,
                    workers: int | None) -> Any:  # fmt: skip
    """Check ``--plot``, ``--out``, ``--store``/``--resume`` and ``--scheduler``/``--workers`` before
    anything runs (BadInput naming the option); return the executor."""
    from rotorlab.cli._sweep_common import check_store_path, executor_from_options

    _check_plot("--plot", plot)
    _check_plot("--out", out)
    executor = executor_from_options(scheduler, workers)
    if resume and store is None:
        raise BadInput("--resume needs --store STORE.zarr (the store to continue)")
    if store is not None:
        check_store_path(store, resume, "--store")
    return executor


def write_and_report(loaded: Any, name: str, ds: Any, figure: Any, plot: Path | None, out: Path | None,
                     json_out: bool, document: Any, tables: Any) -> None:  # fmt: skip
    """Save ``figure()`` to ``--plot`` and ``ds`` to ``--out``, then print ``document()`` (``--json``)
    or ``tables()`` and the files written; exit 3 if some result of ``ds`` failed."""
    written = []
    if plot is not None:
        written.append(_save_plot(figure(), plot))
    if out is not None:
        from rotorlab.io import save_netcdf

        written.append(str(save_netcdf(ds, out)))
    if json_out:
        emit_json({**_json_case(loaded), "analysis": name, **document(), "files": written})
    else:
        for table in tables():
            stdout().print(table)
        for path in written:
            stdout().print(f"Wrote {path}", markup=False)
    exit_if_failed({name: ds})


def _verdict_caption(ds: Any) -> str | None:
    """How the horizon was chosen and whether the fractions stopped changing (its stated test)."""
    from rotorlab.analyses._verdict import basin_verdict

    if "count" not in ds or "outcome" not in ds:
        return None
    rule = ds.attrs.get("horizon_rule")
    return ((f"{str(rule)[0].upper()}{str(rule)[1:]}. " if rule else "") + basin_verdict(ds)["sentence"])


def basin_tables(results: dict[str, Any], tables: dict[str, list[dict[str, Any]]]) -> list[Any]:
    """Return rich tables of basin and working-point results (one per analysis, empty if none).

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Results of basin analyses by name.
    tables : dict of str to list of dict
        Their rows (:func:`rotorlab.analyses.basin_rows`).
    """
    from rich.table import Table

    from rotorlab.analyses._basin import compare_basins
    from rotorlab.report._basin import basin_table_rows

    out = []
    for name, ds in results.items():
        rows = tables[name]
        if ds.attrs.get("analysis") == "working-point":
            table = Table(title=f"{name}: working point and friction band", title_justify="left")
            table.add_column("quantity")
            table.add_column("value", justify="right")
            table.add_column("unit")
            for r in rows:
                table.add_row(r["quantity"], f"{r['value']:.6g}", r["unit"])
            out.append(table)
            continue
        horizons = ds["horizon"].values
        n = rows[0]["n"] if rows else 0
        fixed = ", ".join(f"{k[6:]} = {float(v):g}" for k, v in ds.attrs.items() if k.startswith("fixed_"))
        over = (f"{ds.attrs.get('x')} x {ds.attrs.get('y')}" if "x" in ds.attrs else
                " x ".join(d for d in ds["label"].dims if d != "horizon"))  # fmt: skip
        table = Table(title=f"{name}: {n} starts, {over}"
                            + (f" ({fixed})" if fixed else "") + f", after {float(horizons[-1]):g} s",
                      title_justify="left", caption=_verdict_caption(ds), caption_justify="left")  # fmt: skip
        half = rows[0]["horizon_half_s"] if rows else float(horizons[-1])
        for col in ("regime", "%", "starts", "CI (%)", f"% at {half:g} s",
                    "label kept since, median / max (s)"):  # fmt: skip
            table.add_column(col, justify="left" if col == "regime" else "right")
        for r in basin_table_rows(rows):
            table.add_row(*r)
        out.append(table)
    cmp = compare_basins(results)
    if cmp is not None:
        table = Table(title=cmp["verdict"], title_justify="left")
        table.add_column("simulated time (s)", justify="right")
        for e in cmp["entries"]:
            table.add_column(f"{cmp['label']} % ({cmp['parameter']} = {e['value']:g})", justify="right")
        for j, t in enumerate(cmp["horizons_s"]):
            table.add_row(f"{t:g}", *(f"{100.0 * e['fractions'][j]:.1f}" for e in cmp["entries"]))
        out.append(table)
    return out
