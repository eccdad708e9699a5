"""The ``steady`` and ``stability-chart`` commands: steady motions of a rotor with balls.

Both take a case file (or built-in case) with a ``jeffcott_balls`` model. ``--regime R`` applies
the ``eccentricity`` / ``support_damping`` overrides that the case's analyses labelled
``regime = "R"`` carry. Speeds are given in rpm (or as multiples of the critical speed p) at this
edge and converted to rad/s at once; JSON output is SI with labelled rpm and degree values.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.cli._app import (CaseArg, JsonOpt, SetOpt, _json_case, _load, _settings, app, find_analysis, own_entry,
                               run_through_entry)
from rotorlab.cli._options import parse_range, parse_speed_range
from rotorlab.cli._output import BadInput, emit_json, handled, info, status, stdout

__all__ = ["steady_command", "stability_chart_command", "run_up_command", "parse_range", "regime_overrides", "steady_tables"]

_METHODS = ("exact", "hamilton", "averaged")

RegimeOpt = Annotated[Optional[str], typer.Option(  # noqa: UP007
    "--regime", metavar="R", help="Use the eccentricity / support damping of the case's analyses labelled "
    "regime = R.")]  # fmt: skip


def regime_overrides(loaded: Any, regime: str | None) -> dict[str, float]:
    """Collect the overrides of the analyses labelled ``regime`` (empty for None).

    Parameters
    ----------
    loaded : rotorlab.io.Case
        The case.
    regime : str or None
        A ``regime`` label of its analyses.

    Returns
    -------
    dict of str to float
        ``eccentricity`` (m) and / or ``support_damping`` (N*s/m), as given by those analyses.

    Raises
    ------
    BadInput
        No analysis carries that label (the known labels are listed), or two analyses give it
        different values.
    """
    if regime is None:
        return {}
    found: dict[str, tuple[float, str]] = {}
    labels = set()
    for a in loaded.analyses:
        label = getattr(a, "regime", None)
        if label is None:
            continue
        labels.add(label)
        if label != regime:
            continue
        for key, value in a.overrides().items():
            if key in found and found[key][0] != value:
                raise BadInput(f"--regime {regime}: analyses {found[key][1]} and {a.name} give different {key} "
                               f"({found[key][0]:g} and {value:g})")  # fmt: skip
            found[key] = (value, a.name)
    if regime not in labels:
        known = ", ".join(sorted(labels)) or "none"
        raise BadInput(f"--regime {regime}: no analysis of case {loaded.name} has that regime (regimes: {known})")
    return {k: v for k, (v, _) in found.items()}


def _model(loaded: Any, overrides: dict[str, float], kind: str) -> Any:
    """The steady-motion model of a case whose model type has no ``kind`` entry of its own: the
    model's own check (``steady_issues``: a jeffcott_balls rotor with balls) decides."""
    from rotorlab.io import ANALYSIS_SPECS

    issues = loaded.model.steady_issues(ANALYSIS_SPECS[kind].model_construct())  # unvalidated: its type only
    if issues:
        raise BadInput(f"case {loaded.name}: {kind} " + "; ".join(i.message for i in issues))
    from rotorlab.analyses import build_model
    from rotorlab.steady import with_parameter

    model = build_model(loaded.model)
    for key, value in overrides.items():
        model = with_parameter(model, key, value)
    return model


def _first(loaded: Any, kind: str, regime: str | None) -> Any:
    for a in loaded.analyses:
        if a.type == kind and (regime is None or getattr(a, "regime", None) == regime):
            return a
    return None


def _positive(option: str, value: float | None) -> None:
    if value is not None and not (math.isfinite(value) and value > 0):
        raise BadInput(f"{option} = {value:g}: must be a finite number > 0")


def _check_plot(option: str, path: Path | None) -> None:
    if path is None:
        return
    if path.is_dir():
        raise BadInput(f"{option} = {path}: is a folder (give a file name)")
    if not path.absolute().parent.is_dir():
        raise BadInput(f"{option} = {path}: folder {path.absolute().parent} does not exist")


def _angles(values: list[float]) -> str:
    return "(" + ", ".join(f"{a:.2f}" for a in values) + ")"


def _fmt(value: float | None, spec: str) -> str:
    return "-" if value is None else format(value, spec)


@app.command("steady")
def steady_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speed_rpm: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Spin speed (rpm).")] = None,
    speed_ratio: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-ratio", metavar="RATIO", help="Spin speed as a multiple of the critical speed p.")] = None,
    regime: RegimeOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """List every steady motion at one speed with its three stability verdicts.

    Verdicts: seed 003 (least H~*, Hessian of f), seed 002 (averaged equations) and the exact
    eigenvalues; every disagreement is listed. Without a speed option the speed of the case's
    first steady analysis (of the regime, if given) is used.
    """
    settings = _settings(ctx)
    with handled(settings):
        _positive("--speed-rpm", speed_rpm)
        _positive("--speed-ratio", speed_ratio)
        if speed_rpm is not None and speed_ratio is not None:
            raise BadInput("--speed-rpm and --speed-ratio exclude each other: give only one")
        loaded = _load(case, sets, settings)
        if own_entry(loaded, "steady"):
            _own_steady(settings, loaded, speed_rpm, speed_ratio, json_out)
            return
        overrides = regime_overrides(loaded, regime)
        spec = _first(loaded, "steady", regime)
        if speed_rpm is None and speed_ratio is None:
            if spec is None:
                raise BadInput(f"case {loaded.name} has no steady analysis: give --speed-rpm or --speed-ratio")
            overrides = overrides or spec.overrides()
        model = _model(loaded, overrides, "steady")
        if speed_rpm is not None:
            omega = speed_rpm / _RPM
        elif speed_ratio is not None:
            omega = speed_ratio * model.critical_speed
        else:
            omega = spec.spin_speed(loaded.model)
        from rotorlab.analyses._steady import steady_document
        from rotorlab.steady import analyze_steady

        samples = spec.family_samples if spec is not None else 12
        doc = steady_document(analyze_steady(model, omega, family_samples=samples))
        doc = {**_json_case(loaded), "regime": regime, "overrides": overrides, **doc}
        if json_out:
            emit_json(doc)
            return
        _print_steady(doc)


def _own_steady(settings: Any, loaded: Any, speed_rpm: float | None, speed_ratio: float | None,
                json_out: bool) -> None:
    """``steady`` on a model with its own implementation (a machine): speed from the options, the
    case's first steady analysis or its constant drive."""
    from rotorlab.io import SteadySpec

    spec = _first(loaded, "steady", None)
    if speed_rpm is not None:
        omega = speed_rpm / _RPM
    elif speed_ratio is not None:
        p = loaded.model.critical_speed()
        if p is None:
            raise BadInput(f"--speed-ratio: model '{loaded.model.type}' has no critical speed; give --speed-rpm")
        omega = speed_ratio * p
    elif spec is not None:
        omega = spec.spin_speed(loaded.model)
    else:
        profile = loaded.model.speed_profile()
        if profile is None or not profile.is_constant:
            raise BadInput(f"case {loaded.name} has no steady analysis and no constant speed: give --speed-rpm "
                           "or --speed-ratio")
        omega = profile.final_speed
    run_through_entry(settings, loaded, SteadySpec(name=spec.name if spec is not None else "steady", speed=omega,
                                                   races=spec.races if spec is not None else None),
                      json_out, extra={"speed": omega, "speed_rpm": omega * _RPM})


def _print_steady(doc: dict[str, Any]) -> None:
    from rich.table import Table

    con = stdout()
    head = f"{doc['case']}" + (f" (regime {doc['regime']})" if doc["regime"] else "")
    title = (f"{head}: steady motions at {doc['speed_rpm']:.6g} rpm, ω/p = {doc['speed_ratio']:.4g} "
             f"(p = {doc['critical_speed_rpm']:.6g} rpm)")  # fmt: skip
    table = Table(title=title, title_justify="left")
    for name in ("motion", "ball angles (deg)", "deflection (mm)", "phase (deg)", "H~* (J)", "seed 003",
                 "seed 002", "exact", "growth (1/s)"):  # fmt: skip
        table.add_column(name, justify="right" if name[0] in "dpHg" else "left")
    for m in doc["motions"]:
        angles = "-" if m["ball_angles_deg"] is None else _angles(m["ball_angles_deg"])
        amp = None if m["amplitude"] is None else m["amplitude"] * 1e3
        table.add_row(m["label"] + ("" if m["exists"] else " (absent)"), angles, _fmt(amp, ".4g"),
                      _fmt(m["phase_deg"], ".1f"), _fmt(m["h_tilde"], ".5g"), m["verdicts"]["hamilton"],
                      m["verdicts"]["averaged"], m["verdicts"]["exact"], _fmt(m["growth_rate"], ".3g"))  # fmt: skip
    con.print(table)
    stable = doc["stable"]["exact"]
    con.print(f"Exactly stable: {', '.join(stable) if stable else 'none'}", markup=False)
    for d in doc["disagreements"]:
        con.print(f"disagreement: {d['message']}", markup=False)
    if doc.get("friction"):
        con.print(f"friction: {doc['friction']}", markup=False)


@app.command("stability-chart")
def stability_chart_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speeds_rpm: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--speeds-rpm", metavar="A:B:N", help="N speeds from A to B rpm.")] = None,
    speed_ratios: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--speed-ratios", metavar="A:B:N", help="N speeds from A p to B p.")] = None,
    param: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--param", metavar="NAME=A:B:N", help="Second parameter (ball_mass, ball_damping, eccentricity, "
        "support_damping) over N values from A to B (SI, or with a unit: eccentricity=0.05mm:2.5mm:25).")] = None,
    regime: RegimeOpt = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Save the chart figure (PNG, PDF or SVG by suffix).")] = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc", help="Write the chart Dataset to this NetCDF file.")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Chart which steady motions exist and which are stable (three methods) over a speed range.

    Without --speeds-rpm/--speed-ratios the speeds of the case's first stability-chart analysis
    are used. Prints the speed intervals in which each motion is stable, by each method.
    """
    settings = _settings(ctx)
    with handled(settings):
        if speeds_rpm is not None and speed_ratios is not None:
            raise BadInput("--speeds-rpm and --speed-ratios exclude each other: give only one")
        rpm = None if speeds_rpm is None else parse_speed_range(speeds_rpm, min_count=1)
        ratios = None if speed_ratios is None else parse_range("--speed-ratios", speed_ratios)
        for option, grid in (("--speeds-rpm", rpm), ("--speed-ratios", ratios)):
            if grid is not None and not grid[0] > 0:
                raise BadInput(f"{option}: speeds must be > 0")
        name, values = _param(param)
        _check_plot("--plot", plot)
        _check_plot("--out", out)
        loaded = _load(case, sets, settings)
        if own_entry(loaded, "stability-chart"):
            _own_chart(settings, loaded, rpm, ratios, name, values, out, json_out)
            return
        overrides = regime_overrides(loaded, regime)
        spec = _first(loaded, "stability-chart", regime)
        if rpm is None and ratios is None:
            if spec is None:
                charts = [f"{a.name} (" + (f"regime {a.regime}" if getattr(a, "regime", None)
                                            else "the model's parameters") + ")"
                          for a in loaded.analyses if a.type == "stability-chart"]
                what = (f"no stability-chart analysis for regime {regime}; it has "
                        + ", ".join(charts)) if charts and regime is not None else (
                    "no stability-chart analysis")
                raise BadInput(f"case {loaded.name} has {what}: give --speeds-rpm or --speed-ratios"
                               + (", or one of those regimes" if charts and regime is not None else ""))
            overrides = overrides or spec.overrides()
            if name is None and spec.param is not None:
                name, values = spec.param, spec.parameter_values()
        model = _model(loaded, overrides, "stability-chart")
        import numpy as np

        if rpm is not None:
            speeds = np.linspace(*rpm[:2], rpm[2]) / _RPM
        elif ratios is not None:
            speeds = np.linspace(*ratios[:2], ratios[2]) * model.critical_speed
        else:
            speeds = spec.spin_speeds(loaded.model)
        from rotorlab.analyses._steady import chart_intervals
        from rotorlab.steady import stability_chart

        count = speeds.size * (1 if values is None else len(values))
        info(settings, f"Charting {loaded.name}: {count} points ...", json_mode=json_out)
        with status(settings, "Computing steady motions ..."):
            ds = stability_chart(model, speeds, param=name, values=values,
                                 family_samples=spec.family_samples if spec is not None else 8)  # fmt: skip
        ds.attrs.update(case=loaded.name, regime=regime or "")
        intervals = chart_intervals(ds)
        written = _write_outputs(ds, plot, out)
        if json_out:
            crit = ds.critical_speed.values
            emit_json({**_json_case(loaded), "regime": regime, "overrides": overrides,
                       "param": name, "values": None if values is None else [float(v) for v in values],
                       "param_units": _param_units(name), "speeds": [float(w) for w in speeds],
                       "speeds_rpm": [float(w * _RPM) for w in speeds],
                       "critical_speed": float(crit) if crit.ndim == 0 else [float(c) for c in crit],
                       "intervals": intervals, "files": written})  # fmt: skip
            return
        _print_intervals(loaded.name, ds, intervals, name)
        for path in written:
            stdout().print(f"Wrote {path}", markup=False)


def _own_chart(settings: Any, loaded: Any, rpm: Any, ratios: Any, name: str | None, values: Any,
               out: Path | None, json_out: bool) -> None:
    """``stability-chart`` on a model with its own implementation (a machine)."""
    from rotorlab.io import StabilityChartSpec

    spec = _first(loaded, "stability-chart", None)
    update: dict[str, Any] = {}
    if rpm is not None:
        update.update(speeds=(rpm[0] / _RPM, rpm[1] / _RPM, rpm[2]), speed_ratios=None)
    elif ratios is not None:
        update.update(speed_ratios=ratios, speeds=None)
    if name is not None:
        update.update(param=name, values=(float(values[0]), float(values[-1]), len(values)))
    if spec is None:
        if not update.get("speeds") and not update.get("speed_ratios"):
            raise BadInput(f"case {loaded.name} has no stability-chart analysis: give --speeds-rpm or --speed-ratios")
        spec = StabilityChartSpec(name="stability-chart", **update)
    else:
        spec = spec.model_copy(update=update)
    run_through_entry(settings, loaded, spec, json_out, out)


@app.command("run-up")
def run_up_command(
    ctx: typer.Context,
    case: CaseArg,
    analysis: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--analysis", metavar="NAME", help="Which run-up analysis of the case (default: the first).")] = None,
    t_end: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--t-end", metavar="SECONDS", help="Simulated time (s) instead of the analysis'.")] = None,
    out: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--out", "-o", metavar="FILE.nc", help="Write the result Dataset to this NetCDF file.")] = None,
    sets: SetOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Run a case's run-up analysis: passage through the critical speeds, residual vibration.

    Any model with run-ups (a rotor with balls along a speed profile; a machine with its drive or
    motor). JSON: {"case", "source", "analysis", "type", "rows": [...]} with the rows of the
    analysis type (``rotorlab run --json`` gives the same rows).
    """
    settings = _settings(ctx)
    with handled(settings):
        _positive("--t-end", t_end)
        _check_plot("--out", out)
        loaded = _load(case, sets, settings)
        spec = find_analysis(loaded, "run-up", analysis)
        if spec is None:
            raise BadInput(f"case {loaded.name} has no run-up analysis ([[analysis]] type \"run-up\")")
        if t_end is not None:
            spec = spec.model_copy(update={"t_end": t_end})
        run_through_entry(settings, loaded, spec, json_out, out)


def _param(text: str | None) -> tuple[str | None, Any]:
    if text is None:
        return None, None
    from rotorlab.io._steady_specs import STEADY_PARAMETERS

    name, sep, grid = text.partition("=")
    if not sep or name not in STEADY_PARAMETERS:
        raise BadInput(f"--param = {text}: must be NAME=A:B:N with NAME one of {', '.join(STEADY_PARAMETERS)}")
    dimension, bound, _ = STEADY_PARAMETERS[name]
    start, stop, count = parse_range("--param", grid, dimension)
    if (bound == "gt" and not start > 0) or start < 0:
        raise BadInput(f"--param = {text}: {name} must be {'> 0' if bound == 'gt' else '>= 0'}")
    import numpy as np

    return name, np.linspace(start, stop, count)


def _param_units(name: str | None) -> str | None:
    if name is None:
        return None
    from rotorlab.io._steady_specs import STEADY_PARAMETERS

    return STEADY_PARAMETERS[name][2]


def _write_outputs(ds: Any, plot: Path | None, out: Path | None) -> list[str]:
    written = []
    if plot is not None:
        from rotorlab.plot import stability_chart_figure

        stability_chart_figure(ds).savefig(plot, dpi=110)
        written.append(str(plot))
    if out is not None:
        from rotorlab.io import save_netcdf

        written.append(str(save_netcdf(ds, out)))
    return written


def _print_intervals(case: str, ds: Any, intervals: dict[str, list[dict[str, Any]]], param: str | None) -> None:
    from rich.table import Table

    con = stdout()
    names = {"exact": "exact eigenvalues", "hamilton": "seed 003 (least H~*)", "averaged": "seed 002 (averaged)"}
    table = Table(title=f"{case}: speeds at which each motion is stable", title_justify="left")
    columns = ["method", "motion"] + ([param] if param else []) + ["from (rpm)", "to (rpm)", "ω/p"]
    for c in columns:
        table.add_column(c, justify="right" if c in ("from (rpm)", "to (rpm)", "ω/p", param) else "left")
    for method in _METHODS:
        for r in intervals[method]:
            row = [names[method], r["motion"]] + ([f"{r[param]:.4g}"] if param else [])
            row += [f"{r['start_rpm']:.0f}", f"{r['stop_rpm']:.0f}", f"{r['start_ratio']:.3g} - {r['stop_ratio']:.3g}"]
            table.add_row(*row)
    con.print(table)
    if not any(intervals.values()):
        con.print("No motion is stable anywhere on this chart.", markup=False)


def _result_text(ds: Any, rows: list[dict[str, Any]]) -> str:
    kind = ds.attrs.get("analysis")
    if kind == "steady":
        stable = [r["motion"] for r in rows if r["verdict_exact"] == "stable"]
        count = len([m for m in str(ds.attrs.get("disagreements", "")).split("\n") if m])
        return (f"ω/p = {float(ds.attrs['speed_ratio']):.3g}: exactly stable {', '.join(stable) or 'none'}; "
                f"{count} disagreement(s)")  # fmt: skip
    if kind == "stability-chart":
        exact = [r for r in rows if r["method"] == "exact"]
        if ds.attrs.get("parameter"):
            return f"{len(exact)} exactly stable interval(s) over {ds.attrs['parameter']}"
        text = "; ".join(f"{r['motion']} {r['start_ratio']:.3g}-{r['stop_ratio']:.3g} p" for r in exact)
        return text or "none stable"
    if kind == "verify":
        parts = []
        for r in rows:
            fr = ", ".join(f"{k} {100 * v:.0f}%" for k, v in r["fractions"].items())
            parts.append(f"{r['speed_ratio']:.3g} p: {fr}" + ("" if r["agrees_exact"] else " (not as predicted)"))
        return "; ".join(parts)
    if kind == "run-up":
        return "; ".join(
            f"peak {r['max_amplitude'] * 1e3:.3g} mm with balls, {r['max_amplitude_without'] * 1e3:.3g} mm without; "
            + (f"synchronised on {r['final_motion']}" if r["synchronised"] else "not synchronised")
            for r in rows
        )
    return ""


def steady_tables(results: dict[str, Any], tables: dict[str, list[dict[str, Any]]]) -> list[Any]:
    """Return the rich table summarising the steady-motion results of a run (empty if none).

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Results of steady-motion analyses by name.
    tables : dict of str to list of dict
        Their rows (:func:`rotorlab.analyses.steady_rows`).
    """
    if not results:
        return []
    from rich.table import Table

    table = Table(title="Steady motions", title_justify="left")
    for name in ("analysis", "type", "regime", "result"):
        table.add_column(name)
    for name, ds in results.items():
        table.add_row(name, str(ds.attrs.get("analysis", "")), str(ds.attrs.get("regime", "")),
                      _result_text(ds, tables[name]))  # fmt: skip
    return [table]
