"""The ``rotorlab`` command line: a thin typer layer over :mod:`rotorlab.io`,
:mod:`rotorlab.analyses`, :mod:`rotorlab.plot` and :mod:`rotorlab.report`.

The linear-rotordynamics commands (``campbell``, ``modes``) live in :mod:`rotorlab.cli._linear`
and are registered on the same :data:`app`.

Exit codes: 0 success, 1 internal error, 2 bad input (case file, case name, option value).
Nothing heavy (numpy, numba, xarray, matplotlib, pydantic) is imported at module import, so that
``rotorlab --version`` answers at once.
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path
from typing import Annotated, Any, Optional

import typer
from typer.core import TyperGroup

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab._version import __version__
from rotorlab.cli._output import (
    BadInput,
    Settings,
    clean_click_errors,
    emit_json,
    exit_if_failed,
    handled,
    info,
    outcome_table,
    progress_bar,
    say,
    status,
    stdout,
)

__all__ = ["app", "main"]

DEFAULT_CASE = "autobalancer"
DEFAULT_OUT = "rotorlab-out"

class _Group(TyperGroup):
    """The app's command group: click's own usage errors (an unknown option, a value it cannot
    read) are cleaned like every other echo (:func:`~rotorlab.cli._output.clean_text`)."""

    def make_context(self, *args: Any, **kwargs: Any) -> Any:
        with clean_click_errors():
            return super().make_context(*args, **kwargs)

    def invoke(self, ctx: Any) -> Any:
        with clean_click_errors():
            return super().invoke(ctx)


app = typer.Typer(
    cls=_Group,
    name="rotorlab",
    help="Dynamics of centrifuge rotors and automatic ball balancers.",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
)

CaseArg = Annotated[str, typer.Argument(help="TOML case file or built-in case name (see 'rotorlab cases').",
                                        metavar="CASE", show_default=False)]  # fmt: skip
JsonOpt = Annotated[bool, typer.Option("--json", help="Print a machine-readable summary on stdout only.")]
SetOpt = Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
    "--set", metavar="KEY=VALUE", help="Set a key of the case before it is validated, e.g. --set model.disc_mass=2kg "
    "or --set 'model.balls[0].mass=20 g' (KEY as in the error messages; VALUE a TOML value or a number with a "
    "unit); repeatable.", show_default=False)]  # fmt: skip


def _version(value: bool) -> None:
    if value:
        typer.echo(f"rotorlab {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    ctx: typer.Context,
    version: Annotated[bool, typer.Option("--version", callback=_version, is_eager=True,
                                          help="Show the version and exit.")] = False,  # fmt: skip
    quiet: Annotated[bool, typer.Option("-q", "--quiet", help="No progress or messages: print only results (or --json) and errors.")] = False,
    verbose: Annotated[bool, typer.Option("-v", "--verbose", help="Print more; tracebacks of internal errors.")] = False,
) -> None:
    """Dynamics of centrifuge rotors and automatic ball balancers.

    CASE arguments take a TOML case file or the name of a built-in case.
    """
    if quiet and verbose:
        typer.echo("error: -q/--quiet and -v/--verbose exclude each other", err=True)
        raise typer.Exit(2)
    ctx.obj = Settings(quiet=quiet, verbose=verbose)


def _settings(ctx: typer.Context) -> Settings:
    obj = ctx.find_root().obj
    return obj if isinstance(obj, Settings) else Settings()


def _load(source: str, sets: list[str] | None = None, settings: Settings | None = None) -> Any:
    """Load a case with the command's ``--set KEY=VALUE`` options applied (the one place that does).

    Given the command's ``settings`` (every command but ``validate`` and ``run``, which print
    them in their own place) the case's sanity warnings
    (:func:`rotorlab.analyses.sanity_warnings`) go to stderr before the command runs, unless
    ``-q``; they never stop it.
    """
    from rotorlab.io import load_case, parse_override

    overrides = dict(parse_override(text) for text in sets or ())
    loaded = load_case(source, overrides=overrides)
    if settings is not None and not settings.quiet:
        from rotorlab.analyses import sanity_warnings
        from rotorlab.io._built import built_model

        with built_model(loaded.model, model_of(loaded)):
            warnings = sanity_warnings(loaded)
        for w in warnings:
            say(f"warning ({w.check}): {w.text}")
    return loaded


_MODELS: dict[int, tuple[Any, Any]] = {}


def model_of(loaded: Any) -> Any:
    """The model of a loaded case, built once per command (:func:`rotorlab.analyses.build_model`)."""
    spec, model = _MODELS.get(id(loaded.model), (None, None))
    if spec is not loaded.model:
        from rotorlab.analyses import build_model

        model = build_model(loaded.model)
        _MODELS.clear()
        _MODELS[id(loaded.model)] = (loaded.model, model)
    return model


def _json_case(case: Any) -> dict[str, Any]:
    out = {"case": case.name, "source": case.source}
    if case.overrides:
        out["set"] = case.overrides
    return out


# --------------------------------------------------------------------------- cases / validate


@app.command("cases")
def cases_command(ctx: typer.Context, json_out: JsonOpt = False) -> None:
    """List the built-in cases with their one-line descriptions."""
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.io import builtin_cases

        found = builtin_cases()
        if json_out:
            emit_json({"cases": found})
            return
        from rich.table import Table

        table = Table(title="Built-in cases (use the name as CASE)", title_justify="left")
        table.add_column("name")
        table.add_column("description")
        for name, description in found.items():
            table.add_row(name, description)
        stdout().print(table)


def _analysis_summary(case: Any) -> list[dict[str, Any]]:
    return [{"name": a.name, "type": a.type, **a.summary(case.model)} for a in case.analyses]


@app.command("validate")
def validate_command(ctx: typer.Context, case: CaseArg, sets: SetOpt = None, json_out: JsonOpt = False) -> None:
    """Check a case file and print a summary of it (exit code 2 and the problems if invalid)."""
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.io import CaseError

        try:
            loaded = _load(case, sets)
        except CaseError as exc:
            if json_out:
                emit_json({"ok": False, "source": case, "problems": list(exc.problems)})
            raise
        p = loaded.model.critical_speed()
        analyses = _analysis_summary(loaded)
        from rotorlab.analyses import sanity_warnings

        warnings = sanity_warnings(loaded)
        if json_out:
            extra = {"n_dof": loaded.model.n_dof} if hasattr(loaded.model, "n_dof") else {}
            from rotorlab.analyses import critical_summary

            crit = {"critical_speed_rpm": None if p is None else p * _RPM,
                    "critical_speed_definition": None if p is None else "undamped",
                    **critical_summary(loaded.model)}
            emit_json({"ok": True, **_json_case(loaded), "description": loaded.description,
                       "critical_speed": p, **crit, "n_balls": loaded.model.n_balls, **extra,
                       "model": loaded.model_dump_si()["model"], "analyses": analyses,
                       "warnings": [w.to_dict() for w in warnings]})  # fmt: skip
            return
        con = stdout()
        con.print(f"OK: {loaded.name} ({loaded.source})", markup=False)
        if loaded.description:
            con.print(f"  {loaded.description}", markup=False)
        con.print(f"  model: {loaded.model.describe()}", markup=False)
        for a in loaded.analyses:
            con.print(f"  analysis {a.name} ({a.type}): {a.describe(loaded.model)}", markup=False)
        for w in warnings:
            con.print(f"warning ({w.check}): {w.text}", markup=False)


# --------------------------------------------------------------------------- run


@app.command("run")
def run_command(
    ctx: typer.Context,
    case: Annotated[str, typer.Argument(
        help="TOML case file or built-in case name.", metavar="CASE")] = DEFAULT_CASE,
    sets: SetOpt = None,
    out: Annotated[Path, typer.Option("--out", "-o", metavar="DIR", help="Output folder.")] = Path(DEFAULT_OUT),
    json_out: JsonOpt = False,
) -> None:
    """Run every analysis of a case; write report.html, NetCDF results and PNG figures to --out."""
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.report import check_output_dir

        loaded = _load(case, sets)
        try:
            check_output_dir(out)
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        if not loaded.analyses:
            raise BadInput(f"case {loaded.name}: lists no [[analysis]] to run")
        from rotorlab.analyses import ANALYSIS_TYPES

        for i, a in enumerate(loaded.analyses):
            if a.type not in ANALYSIS_TYPES:
                raise BadInput(f'analysis[{i}].type = "{a.type}": rotorlab run cannot run this '
                               f"analysis type yet (runnable: {', '.join(ANALYSIS_TYPES)})")  # fmt: skip
        from rotorlab.analyses import sanity_warnings
        from rotorlab.io._built import built_model

        model = model_of(loaded)  # built once: the analyses, checks, verdict and report share it
        with built_model(loaded.model, model):
            warnings = sanity_warnings(loaded)
            for w in () if settings.quiet else warnings:  # before the run, never stopping it (errors stay errors)
                say(f"warning ({w.check}): {w.text}")
            count = len(loaded.analyses)
            info(settings, f"Running {loaded.name} ({count} {'analysis' if count == 1 else 'analyses'}) ...",
                 json_mode=json_out)  # fmt: skip
            start = time.perf_counter()
            from rotorlab.analyses import run_case, summarize

            from rotorlab.analyses import analysis_entry

            entries = {a.name: analysis_entry(loaded.model.type, a.type) for a in loaded.analyses}
            tasks = {a.name: entries[a.name].task_size(loaded.model, a) for a in loaded.analyses}
            units = {name: entry.progress_unit for name, entry in entries.items()}
            with progress_bar(settings, tasks, units) as update:
                results = run_case(loaded, progress=update, model=model)
            computed = time.perf_counter() - start
            from rotorlab.report import PRESENTATIONS, write_report

            shown = {name: PRESENTATIONS[entry.family] for name, entry in entries.items()}
            tables = {name: summarize(ds) for name, ds in results.items()}
            with status(settings, "Drawing figures and writing the report ..."):
                figures = {name: shown[name].figures(ds, name) for name, ds in results.items()}
                report = write_report(out, loaded, results, figures, tables)
            from rotorlab.analyses import machine_verdict

            verdict = machine_verdict(loaded, results, tables)
        files = sorted([report.name, *(f"{n}.nc" for n in results),
                        *(f"{k}.png" for stems in figures.values() for k in stems)])
        total = time.perf_counter() - start
        if json_out:
            emit_json({**_json_case(loaded), "out_dir": str(report.parent), "report": str(report),
                       "files": files, "seconds": round(total, 3), "warnings": [w.to_dict() for w in warnings],
                       "verdict": [line.to_dict() for line in verdict],
                       "analyses": {name: {"type": ds.attrs.get("analysis", ""), "rows": tables[name]}
                                    for name, ds in results.items()}})  # fmt: skip
            exit_if_failed(results)
            return
        con = stdout()
        from rotorlab.cli._verdict import verdict_text

        con.print(verdict_text(verdict), markup=False, highlight=False)
        for family, presentation in PRESENTATIONS.items():
            chosen = {n: ds for n, ds in results.items() if entries[n].family == family}
            if not chosen:
                continue
            for table in presentation.console(chosen, tables):
                con.print(table)
            if settings.verbose:
                for table in presentation.console_detail(chosen, tables):
                    con.print(table)
        if settings.verbose:
            con.print(f"computed in {computed:.1f} s, total {total:.1f} s", markup=False)
        con.print(f"Report: {report}", markup=False)
        exit_if_failed(results)


# --------------------------------------------------------------------------- simulate


def own_entry(loaded: Any, kind: str) -> bool:
    """Whether the case's model type runs analysis type ``kind`` with its own implementation
    (:attr:`rotorlab.analyses.ModelType.analyses`); the command then runs it through
    :func:`run_through_entry`."""
    from rotorlab.analyses import MODEL_TYPES

    entry = MODEL_TYPES.get(loaded.model.type)
    return entry is not None and kind in entry.analyses


def run_through_entry(settings: Any, loaded: Any, spec: Any, json_out: bool, out: Path | None = None,
                      extra: dict[str, Any] | None = None) -> None:
    """Check ``spec`` against the case's model, run it through the registries and print its
    presentation's tables (or ``{case, source, analysis, type, ..., rows}`` as JSON).

    Raises BadInput (exit 2, nothing run) when the analysis cannot run on the model, naming why.
    """
    issues = spec.case_issues(loaded.model)
    if issues:
        raise BadInput("; ".join(
            f"{spec.type}" + "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in i.loc)
            + (f" = {i.value!r}" if i.show_value and i.value is not None else "") + f": {i.message}"
            for i in issues))
    from rotorlab.analyses import analysis_entry, run_analysis, summarize

    entry = analysis_entry(loaded.model.type, spec.type)
    info(settings, f"{loaded.name}: {spec.type} ({spec.describe(loaded.model)}) ...", json_mode=json_out)
    with progress_bar(settings, {spec.name: entry.task_size(loaded.model, spec)},
                      {spec.name: entry.progress_unit}) as update:
        ds = run_analysis(loaded.model, spec, progress=lambda done, n: update(spec.name, done, n),
                          model=model_of(loaded))
    ds.attrs["case"] = loaded.name
    rows = summarize(ds)
    written = None
    if out is not None:
        from rotorlab.io import save_netcdf

        written = str(save_netcdf(ds, out))
    if json_out:
        emit_json({**_json_case(loaded), "analysis": spec.name, "type": spec.type, **(extra or {}),
                   "out": written, "rows": rows})
        exit_if_failed({spec.name: ds})
        return
    from rotorlab.report import PRESENTATIONS

    con = stdout()
    for table in PRESENTATIONS[entry.family].console({spec.name: ds}, {spec.name: rows}):
        con.print(table)
    if ds.attrs.get("message"):
        con.print(str(ds.attrs["message"]), markup=False)
    if written:
        con.print(f"Wrote {written}", markup=False)
    exit_if_failed({spec.name: ds})


def _positive(option: str, values: list[float] | None, unit: str) -> list[float]:
    out = []
    for v in values or ():
        if not (math.isfinite(v) and v > 0):
            raise BadInput(f"{option} = {v:g}: must be a finite number > 0 ({unit})")
        out.append(float(v))
    return out


def find_analysis(loaded: Any, kind: str, name: str | None) -> Any:
    """The analysis of type ``kind`` called ``name`` (BadInput if none), or the first one (or None)."""
    found = [a for a in loaded.analyses if a.type == kind]
    if name is not None:
        for a in found:
            if a.name == name:
                return a
        names = ", ".join(a.name for a in found) or "none"
        raise BadInput(f"--analysis = {name}: no {kind} analysis of that name ({kind} analyses: {names})")
    return found[0] if found else None


def _pick_analysis(loaded: Any, name: str | None) -> Any:
    from rotorlab.io import SimulateSpec

    found = find_analysis(loaded, "simulate", name)
    if found is not None:
        return found
    return SimulateSpec(name="simulate", ball_angle_grid=4 if loaded.model.n_balls <= 2 else 2,
                        revolutions=200.0)  # fmt: skip


@app.command("simulate")
def simulate_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speed_rpm: Annotated[Optional[list[float]], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Constant spin speed (rpm); repeat for several speeds.")] = None,
    speed_ratio: Annotated[Optional[list[float]], typer.Option(  # noqa: UP007
        "--speed-ratio", metavar="RATIO", help="Spin speed as a multiple of the critical speed p; repeatable.")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="SECONDS", help="Simulated time (s).")] = None,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which simulate analysis of the case supplies the start configurations "
        "and tolerances (default: the first).")] = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc", help="Write the result Dataset to this NetCDF file.")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Simulate start-ups of a case's model from its start configurations and label the outcomes.

    Without --speed-rpm/--speed-ratio the speed of the case's (first) simulate analysis is used;
    without --t-end its simulated time. A case without simulate analyses uses a 4 x 4 grid of
    ball angles and 200 revolutions.
    """
    settings = _settings(ctx)
    with handled(settings):
        rpm = _positive("--speed-rpm", speed_rpm, "rpm")
        ratio = _positive("--speed-ratio", speed_ratio, "multiples of the critical speed")
        if rpm and ratio:
            raise BadInput("--speed-rpm and --speed-ratio exclude each other: give only one")
        t_end_given = t_end is not None
        if t_end_given:
            _positive("--t-end", [t_end], "s")
        if out is not None:
            if out.is_dir():
                raise BadInput(f"--out = {out}: is a folder (give a .nc file name)")
            if not out.absolute().parent.is_dir():
                raise BadInput(f"--out = {out}: folder {out.absolute().parent} does not exist")
        loaded = _load(case, sets, settings)
        if own_entry(loaded, "simulate"):
            spec = _pick_analysis(loaded, analysis)
            if len(rpm) + len(ratio) > 1:
                raise BadInput(f"case {loaded.name}: a {loaded.model.type} model simulates one speed at a time: "
                               "give one --speed-rpm or --speed-ratio")
            update: dict[str, Any] = {}
            if rpm or ratio:
                update.update(speed=rpm[0] / _RPM if rpm else None, speed_ratio=ratio[0] if ratio else None)
            if t_end_given:
                update.update(t_end=t_end, revolutions=None)
            run_through_entry(settings, loaded, spec.model_copy(update=update), json_out, out)
            return
        from rotorlab.io import SimulateSpec

        # the model types simulate accepts (those with their own simulate ran above)
        if SimulateSpec.wrong_model(loaded.model) is not None:
            raise BadInput(f"case {loaded.name}: its model is '{loaded.model.type}'; simulate needs a rotor with "
                           f"balls ([model] type {' or '.join(SimulateSpec.model_types)}); for a linear rotor use "
                           "'rotorlab campbell' or 'rotorlab modes'")  # fmt: skip
        spec = _pick_analysis(loaded, analysis)
        model_spec = loaded.model
        p = model_spec.critical_speed()
        if ratio and p is None:
            raise BadInput(f"--speed-ratio: model '{model_spec.type}' has no critical speed; give --speed-rpm")
        speeds = [r / _RPM for r in rpm] or [r * p for r in ratio] or None
        if speeds is None:
            omega = spec.spin_speed(model_spec)
            speeds = None if omega is None else [omega]
        if speeds is None and spec.revolutions is not None and t_end is None:
            raise BadInput("the model's speed profile changes: give --t-end or a constant speed")
        if t_end is None:
            t_end = spec.t_end if spec.t_end is not None else spec.revolutions * 2 * math.pi / min(speeds)
        from rotorlab.analyses import build_model, simulate, summarize

        model = model_of(loaded) if model_spec is loaded.model else build_model(model_spec)
        angles = spec.ball_angle_sets(model.n_balls)
        info(settings, f"Simulating {loaded.name}: {len(angles)} start(s) x "
             f"{1 if speeds is None else len(speeds)} speed(s), {t_end:.6g} s ...", json_mode=json_out)  # fmt: skip
        total = len(angles) * (1 if speeds is None else len(speeds))
        with progress_bar(settings, {spec.name: total}) as update:
            ds = simulate(model, speeds=speeds, initial_ball_angles=angles, t_end=t_end,
                          n_save=spec.n_save, rtol=spec.rtol, atol=spec.atol,
                          progress=lambda done, n: update(spec.name, done, n))  # fmt: skip
        ds.attrs["name"] = spec.name
        ds.attrs["case"] = loaded.name
        rows = summarize(ds)
        written = None
        if out is not None:
            from rotorlab.io import save_netcdf

            written = str(save_netcdf(ds, out))
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(written, 0o666 & ~umask)
        if json_out:
            emit_json({**_json_case(loaded), "analysis": spec.name, "t_end": t_end,
                       "out": written, "rows": rows})  # fmt: skip
            exit_if_failed({spec.name: ds})
            return
        con = stdout()
        title = f"{loaded.name}: {spec.name}" if not (rpm or ratio or t_end_given) else (
            f"{loaded.name}: start configurations and tolerances of {spec.name}")
        con.print(outcome_table(title, rows))
        if written:
            con.print(f"Wrote {written}", markup=False)
        exit_if_failed({spec.name: ds})


def main() -> None:
    """Run the ``rotorlab`` command line (see :func:`rotorlab.cli.main`, the entry point)."""
    from rotorlab.cli import main as guarded_main

    guarded_main()


