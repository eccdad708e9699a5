"""Render the HTML page of a run: one self-contained file (inline CSS, images as data URIs)."""

from __future__ import annotations

import base64
import datetime as _dt
import html
import math
import platform
import re
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from rotorlab.report._basin import basin_comparison_section, basin_section
from rotorlab.report._linear import linear_model_rows, linear_section
from rotorlab.report._steady import STEADY_ANALYSES, seed_notes_section, steady_section

__all__ = ["render_report", "parameter_rows", "versions"]

_UNIT = re.compile(r"\(([^()]*)\)\s*$")
_RPM = 60.0 / (2.0 * math.pi)
_NUMBER = re.compile(r"^[±+-]?(\d|\.\d)")

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif;
 margin:2em auto;max-width:72em;padding:0 1em;color:#1b1b1b;line-height:1.4}
h1{font-size:1.6em;margin-bottom:.2em}h2{font-size:1.3em;border-bottom:1px solid #ccc;
 padding-bottom:.2em;margin-top:1.8em}h3{font-size:1.1em}
table{border-collapse:collapse;margin:.6em 0 1.2em;font-size:.9em}
th,td{border:1px solid #d0d0d0;padding:.25em .6em;text-align:left;vertical-align:top}
th{background:#f0f0f0}td.num{text-align:right;font-variant-numeric:tabular-nums}
pre{background:#f7f7f7;border:1px solid #ddd;padding:.8em;overflow-x:auto;font-size:.85em}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #eee}
figcaption{font-size:.85em;color:#555}.muted{color:#666;font-size:.9em}
.outcome-balanced{color:#1a7f37;font-weight:600}.outcome-bad{color:#b35900;font-weight:600}
"""


def _e(value: Any) -> str:
    return html.escape(str(value), quote=True)


def versions() -> dict[str, str]:
    """Return the versions of rotorlab, Python and the numerical libraries.

    Examples
    --------
    >>> sorted(versions())
    ['numba', 'numpy', 'python', 'rotorlab', 'scipy', 'xarray']
    """
    from importlib import metadata

    from rotorlab import __version__

    out = {"rotorlab": __version__, "python": platform.python_version()}
    for name in ("numpy", "scipy", "numba", "xarray"):
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def _unit_of(description: str | None) -> str:
    match = _UNIT.search(description or "")
    if not match:
        return ""
    unit = match[1].strip()
    return "1" if unit == "-" else unit


def _fmt(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return str(value)


def _other_units(value: Any, unit: str) -> str:
    if unit == "rad/s" and isinstance(value, (int, float)):
        return f"{value * _RPM:.6g} rpm = {value / (2 * math.pi):.6g} Hz"
    if unit == "rad" and isinstance(value, (int, float)):
        return f"{math.degrees(value):.6g}°"
    if unit == "rad" and isinstance(value, (list, tuple)):
        rows = ["(" + ", ".join(f"{math.degrees(a):.4g}°" for a in row) + ")" for row in value]
        return ", ".join(rows)
    return ""


def parameter_rows(spec: Any, prefix: str = "") -> list[tuple[str, str, str, str]]:
    """Flatten a validated case table (model or analysis) into display rows.

    Parameters
    ----------
    spec : pydantic model
        ``Case.model`` or one of ``Case.analyses`` (SI values).
    prefix : str
        Key path prefix, e.g. ``"model"``.

    Returns
    -------
    list of (key path, SI value, SI unit, the value in other units)
        Speeds are also given in rpm and Hz, angles in degrees.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> rows = parameter_rows(load_case("autobalancer").model, "model")
    >>> [r for r in rows if r[0] == "model.speed.speed"]
    [('model.speed.speed', '251.327', 'rad/s', '2400 rpm = 40 Hz')]
    """
    from pydantic import BaseModel

    rows = []
    for name, info in type(spec).model_fields.items():
        if info.exclude:
            continue
        key = f"{prefix}.{info.alias or name}" if prefix else (info.alias or name)
        value = getattr(spec, name)
        if value is None:
            continue
        if isinstance(value, BaseModel):
            rows += parameter_rows(value, key)
        elif isinstance(value, tuple) and value and all(isinstance(v, BaseModel) for v in value):
            for i, item in enumerate(value):
                rows += parameter_rows(item, f"{key}[{i}]")
        else:
            unit = _unit_of(info.description)
            rows.append((key, _fmt(value), unit, _other_units(value, unit)))
    return rows


def _table(header: Sequence[str], rows: Iterable[Sequence[Any]], numeric: set[int] = frozenset(),
           raw: set[int] = frozenset()) -> str:  # fmt: skip
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = []
    for row in rows:
        cells = []
        for j, cell in enumerate(row):
            css = ' class="num"' if j in numeric and _NUMBER.match(str(cell)) else ""
            cells.append(f"<td{css}>{cell if j in raw else _e(cell)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _angles(values: Sequence[float | None]) -> str:
    return "(" + ", ".join("–" if v is None else f"{v:.1f}°" for v in values) + ")"


def _outcome_cell(outcome: str) -> str:
    css = "outcome-balanced" if outcome == "balanced" else "outcome-bad"
    return f'<span class="{css}">{_e(outcome)}</span>'


def _summary_table(rows: Sequence[Mapping[str, Any]]) -> str:
    def amp(v: float | None) -> str:
        return "–" if v is None else f"{v * 1e3:.4g}"

    def ratio(v: float | None) -> str:
        return "–" if v is None else f"{v:.3g}"

    header = ("speed (rpm)", "omega/p", "start angles", "final deflection (mm)",
              "× unbalance alone", "final ball angles", "outcome")  # fmt: skip
    body = [
        (f"{r['speed_rpm']:.0f}", f"{r['speed_ratio']:.3g}", _angles(r["initial_ball_angles_deg"]),
         amp(r["final_amplitude"]), ratio(r["amplitude_ratio"]),
         _angles(r["final_ball_angles_deg"]), _outcome_cell(r["outcome"]))  # fmt: skip
        for r in rows
    ]
    return _table(header, body, numeric={0, 1, 3, 4}, raw={6})


def _derived_rows(case: Any) -> list[tuple[str, str, str, str]]:
    model = case.model
    rows = []
    if hasattr(model, "node_labels"):
        return linear_model_rows(model)
    p = model.critical_speed()
    if p is not None:
        rows.append(("critical speed p = sqrt(c / M)", f"{p:.6g}", "rad/s", _other_units(p, "rad/s")))
    balls = getattr(model, "balls", ())
    if getattr(model, "type", "") == "jeffcott_balls":
        rows.append(("total mass M = M1 + sum m_i", f"{model.total_mass:.6g}", "kg", ""))
        imbalance = model.disc_mass * model.eccentricity
        rows.append(("unbalance M1 e", f"{imbalance:.6g}", "kg*m", ""))
        if balls:
            capacity = sum(b.mass * b.radius for b in balls)
            rows.append(("balancing capacity sum m_i R_i", f"{capacity:.6g}", "kg*m", ""))
        if len(balls) == 2 and balls[0] == balls[1]:
            eta = imbalance / (balls[0].mass * balls[0].radius)
            rows.append(("eta = M1 e / (m R) (seed 002 eq. (10))", f"{eta:.6g}", "1", ""))
            if eta < 2:
                alpha = 180.0 - math.degrees(math.acos(eta / 2))
                rows.append(("balanced ball angles ±(pi - arccos(eta/2))", f"±{math.radians(alpha):.6g}",
                             "rad", f"±{alpha:.4g}°"))  # fmt: skip
    return rows


def _figure(key: str, png: bytes) -> str:
    data = base64.b64encode(png).decode("ascii")
    return (f'<figure><img alt="{_e(key)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{_e(key)}.png</figcaption></figure>")  # fmt: skip


def render_report(case: Any, results: Mapping[str, Any], pngs: Mapping[str, bytes],
                  summary_tables: Mapping[str, Sequence[Mapping[str, Any]]],
                  files: Sequence[str], case_text: str) -> str:  # fmt: skip
    """Return the HTML text of the report (see :func:`rotorlab.report.write_report`).

    Parameters
    ----------
    case : rotorlab.io.Case
    results : mapping of str to xarray.Dataset
        By analysis name.
    pngs : mapping of str to bytes
        Rendered figures by file stem; a figure whose stem starts with ``<analysis name>_`` is
        shown in that analysis' section, others under "Other figures".
    summary_tables : mapping of str to list of dict
        Rows of :func:`rotorlab.analyses.summarize` by analysis name (outcomes of a simulation;
        critical speeds, modes, fitted parameters or findings of a linear analysis).
    files : sequence of str
        Names of the files written next to the report (linked relatively).
    case_text : str
        The case file text to show.

    Returns
    -------
    str
    """
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>rotorlab report: {_e(case.name)}</title>",
        f"<style>{_CSS}</style></head><body>",
        f"<h1>rotorlab report: {_e(case.name)}</h1>",
        f"<p>{_e(case.description)}</p>" if case.description else "",
        f'<p class="muted">Case source: {_e(case.source)} · generated {now}</p>',
        "<h2>Software</h2>",
        _table(("package", "version"), versions().items()),
        "<h2>Model parameters</h2>",
        '<p class="muted">All values in SI units as used in the computation; speeds also in rpm '
        "and Hz, angles also in degrees.</p>",
        _table(("key", "value", "unit", "also"), parameter_rows(case.model, "model"),
               numeric={1}),  # fmt: skip
    ]
    derived = _derived_rows(case)
    if derived:
        parts += ["<h3>Derived quantities</h3>", _table(("quantity", "value", "unit", "also"),
                                                        derived, numeric={1})]  # fmt: skip
    shown: set[str] = set()
    for analysis in case.analyses:
        name = analysis.name
        parts.append(f"<h2>Analysis: {_e(name)} ({_e(analysis.type)})</h2>")
        rows = parameter_rows(analysis, f"analysis.{name}")
        ds = results.get(name)
        if analysis.type in STEADY_ANALYSES and ds is not None:  # tables in rotorlab.report._steady
            parts += [_table(("key", "value", "unit", "also"), rows, numeric={1}),
                      steady_section(ds, summary_tables.get(name))]
            parts += [_figure(key, png) for key, png in pngs.items() if key.startswith(f"{name}_")]
            shown.update(key for key in pngs if key.startswith(f"{name}_"))
            continue
        if analysis.type in ("basin", "working-point", "sweep", "impacts", "impacts-sweep") and ds is not None:
            if analysis.type in ("impacts", "impacts-sweep"):  # rotorlab.report._impacts
                from rotorlab.report._impacts import impact_section

                body = impact_section(ds)
            else:  # rotorlab.report._basin
                body = basin_section(ds, summary_tables.get(name), _table)
            parts += [_table(("key", "value", "unit", "also"), rows, numeric={1}), body]
            parts += [_figure(key, png) for key, png in pngs.items() if key.startswith(f"{name}_")]
            shown.update(key for key in pngs if key.startswith(f"{name}_"))
            continue
        if ds is not None and "speed_ratio" in ds.coords:
            for k, om in enumerate(ds.speed.values):
                rows.append(("spin speed used", f"{float(om):.6g}", "rad/s",
                             f"{_other_units(float(om), 'rad/s')}; "
                             f"omega/p = {float(ds.speed_ratio.values[k]):.4g}"))  # fmt: skip
        parts.append(_table(("key", "value", "unit", "also"), rows, numeric={1}))
        if name in summary_tables and analysis.type == "simulate":
            parts += ["<h3>Outcomes</h3>", _summary_table(summary_tables[name])]
        elif name in summary_tables and ds is not None:
            parts.append(linear_section(analysis.type, ds, summary_tables[name], _table))
        for key, png in pngs.items():
            if key.startswith(f"{name}_"):
                parts.append(_figure(key, png))
                shown.add(key)
    parts.append(basin_comparison_section(results, _table))
    if any(a.type in STEADY_ANALYSES for a in case.analyses):
        parts.append(seed_notes_section())
    if any(a.type in ("impacts", "impacts-sweep") for a in case.analyses):
        from rotorlab.report._impacts import reconstructions_section

        parts.append(reconstructions_section())
    rest = [k for k in pngs if k not in shown]
    if rest:
        parts.append("<h2>Other figures</h2>")
        parts += [_figure(k, pngs[k]) for k in rest]
    parts += [
        "<h2>Files</h2>",
        "<ul>" + "".join(f'<li><a href="{_e(f)}">{_e(f)}</a></li>' for f in files) + "</ul>",
        "<h2>Case file</h2>",
        f"<pre>{_e(case_text)}</pre>",
        "</body></html>",
    ]
    return "\n".join(p for p in parts if p) + "\n"
