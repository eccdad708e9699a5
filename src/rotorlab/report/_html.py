"""Render the HTML page of a run: one self-contained file (inline CSS, images as data URIs)."""

from __future__ import annotations

import base64
import datetime as _dt
import json
import math
import platform
import re
from collections.abc import Mapping, Sequence
from typing import Any

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.io import field_unit
from rotorlab.report._presentations import PRESENTATIONS, presentation_of
from rotorlab.report._table import escape as _e
from rotorlab.report._table import table as _table
from rotorlab.report._verdict import VERDICT_CSS, verdict_section

__all__ = ["render_report", "parameter_rows", "versions"]

_MAX_NUMBERS = 5  # key numbers shown in a findings box

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
.rl-plotly{max-width:100%;overflow-x:auto}
figcaption{font-size:.85em;color:#555}.muted{color:#666;font-size:.9em}
.finding{border:1px solid #b8c7d9;background:#f4f8fc;border-radius:4px;padding:.3em 1em;margin:.6em 0}
.finding h3{margin:.4em 0 .2em}.finding ul{margin:.2em 0 .5em;padding-left:1.4em}
.verdict{font-weight:600;margin:.2em 0}
.outcome-balanced{color:#1a7f37;font-weight:600}.outcome-bad{color:#b35900;font-weight:600}
"""


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
        if all(isinstance(a, (int, float)) for a in value):  # one list of angles
            return ", ".join(f"{math.degrees(a):.4g}°" for a in value)
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
        Speeds are also given in rpm and Hz, angles in degrees; a dimensionless value has no
        unit (not SI's "1").

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
            unit = field_unit(info)
            rows.append((key, _fmt(value), _shown_unit(unit), _other_units(value, unit)))
    return rows


def _shown_unit(unit: str) -> str:
    """The unit as shown to people: none for a dimensionless value (SI's "1")."""
    return "" if unit == "1" else unit


def _quantity_row(q: Mapping[str, Any]) -> tuple[str, str, str, str]:
    also = _other_units(q["value"], q["unit"])
    return q["quantity"], q["sign"] + _fmt(q["value"]), _shown_unit(q["unit"]), q["sign"] + also if also else ""


def _quantity_rows(results: Mapping[str, Any]) -> list[tuple[str, str, str, str]]:
    """The model's derived quantities, as carried by its results (``attrs["model_quantities"]``)."""
    for ds in results.values():
        text = ds.attrs.get("model_quantities")
        if text:
            return [_quantity_row(q) for q in json.loads(text)]
    return []


def _findings_box(analysis: Any, ds: Any, rows: Sequence[Mapping[str, Any]]) -> str:
    found = presentation_of(analysis.type, ds.attrs.get("model_type")).findings(ds, rows)
    shown = found.numbers[:_MAX_NUMBERS]
    more = len(found.numbers) - len(shown)
    numbers = "".join(f"<li>{_e(n)}</li>" for n in shown) + (
        f'<li class="muted">{more} more in the section below</li>' if more > 0 else "")
    return (f'<div class="finding"><h3><a href="#{_e(_anchor(analysis.name))}">{_e(analysis.name)}</a> '
            f'<span class="muted">({_e(analysis.type)})</span></h3>'
            f'<p class="verdict">{_e(found.verdict)}</p>' + (f"<ul>{numbers}</ul>" if numbers else "") + "</div>")


def _anchor(name: str) -> str:
    return "analysis-" + re.sub(r"[^A-Za-z0-9_.-]", "-", name)


def _figure(key: str, png: bytes, interactive: Mapping[str, Any] | None = None) -> str:
    """A figure: the PNG inline, or its interactive Plotly twin (data as JSON, drawn on load)."""
    if interactive is not None:
        data = json.dumps(interactive, separators=(",", ":")).replace("</", "<\\/")
        return (f'<figure class="interactive" data-stem="{_e(key)}"><div class="rl-plotly"></div>'
                f'<script type="application/json" class="rl-plotly-data">{data}</script>'
                f'<figcaption>{_e(key)}: interactive (drag to zoom, double-click to reset, click a legend '
                f'entry to hide it); for papers: <a href="{_e(key)}.png">{_e(key)}.png</a></figcaption></figure>')
    data = base64.b64encode(png).decode("ascii")
    return (f'<figure><img alt="{_e(key)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{_e(key)}.png</figcaption></figure>")  # fmt: skip


# Draws every interactive figure once plotly.js (inlined above it) is loaded.
_DRAW = """<script>
document.querySelectorAll("figure.interactive").forEach(function (f) {
  var spec = JSON.parse(f.querySelector(".rl-plotly-data").textContent);
  Plotly.newPlot(f.querySelector(".rl-plotly"), spec.data, spec.layout,
                 {displaylogo: false, responsive: true});
});
</script>"""


def _plotly_parts(interactive: Mapping[str, Mapping[str, Any]]) -> list[str]:
    """plotly.js (once) and the script that draws the interactive figures, if there are any."""
    if not any(interactive.values()):
        return []
    from rotorlab.plot import plotly_script

    return [f"<script>{plotly_script()}</script>", _DRAW]


def render_report(case: Any, results: Mapping[str, Any], pngs: Mapping[str, Mapping[str, bytes]],
                  summary_tables: Mapping[str, Sequence[Mapping[str, Any]]],
                  files: Sequence[str], case_text: str, *,
                  interactive: Mapping[str, Mapping[str, Any]] | None = None) -> str:  # fmt: skip
    """Return the HTML text of the report (see :func:`rotorlab.report.write_report`).

    The page opens with the findings of every analysis (the verdict in words and the key numbers
    with units), then one section per analysis (its figures, its result tables, its parameters),
    the notes of the analysis families, the model's parameters and derived quantities, the files,
    the case file and, last, the software versions. Each analysis is presented by the entry of
    its family in :data:`rotorlab.report.PRESENTATIONS`.

    Parameters
    ----------
    case : rotorlab.io.Case
    results : mapping of str to xarray.Dataset
        By analysis name.
    pngs : mapping of str to mapping of str to bytes
        Rendered figures by analysis name, then by file stem; an analysis shows its own figures
        only (figures under a name that is no analysis of the case go to "Other figures").
    summary_tables : mapping of str to list of dict
        Rows of :func:`rotorlab.analyses.summarize` by analysis name.
    files : sequence of str
        Names of the files written next to the report (linked relatively).
    case_text : str
        The case file text to show.
    interactive : mapping of str to mapping of str to dict, optional
        Plotly twins (:func:`rotorlab.plot.to_plotly`) by analysis name, then by file stem: shown
        in place of the PNG of the same stem (which the page links to); plotly.js is inlined
        once, so the page works offline.

    Returns
    -------
    str
    """
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    interactive = interactive or {}
    ran = [a for a in case.analyses if a.name in results]
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>rotorlab report: {_e(case.name)}</title>",
        f"<style>{_CSS}{VERDICT_CSS}</style></head><body>",
        f"<h1>rotorlab report: {_e(case.name)}</h1>",
        f"<p>{_e(case.description)}</p>" if case.description else "",
        f'<p class="muted">Case source: {_e(case.source)} · generated {now}</p>',
    ]
    from rotorlab.analyses import machine_verdict

    parts.append(verdict_section(machine_verdict(case, results, summary_tables)))  # the verdict first
    if case.overrides:
        from rotorlab.io._overrides import describe_overrides

        parts.append(f'<p class="muted">Keys set on top of the case file (--set): '
                     f"{_e('; '.join(describe_overrides(case.overrides)))}</p>")
    if ran:
        parts.append("<h2>Findings</h2>")
        parts += [_findings_box(a, results[a.name], summary_tables.get(a.name, [])) for a in ran]
    for analysis in case.analyses:
        name = analysis.name
        ds = results.get(name)
        parts.append(f'<h2 id="{_e(_anchor(name))}">Analysis: {_e(name)} ({_e(analysis.type)})</h2>')
        twins = interactive.get(name, {})
        parts += [_figure(key, png, twins.get(key)) for key, png in pngs.get(name, {}).items()]
        if ds is not None:
            parts.append(presentation_of(analysis.type, case.model.type).section(ds, summary_tables.get(name, [])))
        parts += ["<h3>Parameters</h3>", _table(("key", "value", "unit", "also"),
                                                parameter_rows(analysis, f"analysis.{name}"), numeric={1})]  # fmt: skip
    for family, presentation in PRESENTATIONS.items():
        chosen = {a.name: results[a.name] for a in ran if presentation_of(a.type, case.model.type).family == family}
        if chosen and presentation.notes is not None:
            parts.append(presentation.notes(chosen))
    known = {a.name for a in case.analyses}
    rest = [(k, png) for name, stems in pngs.items() if name not in known for k, png in stems.items()]
    if rest:
        parts.append("<h2>Other figures</h2>")
        parts += [_figure(k, png) for k, png in rest]
    parts += [
        "<h2>Model parameters</h2>",
        '<p class="muted">All values in SI units as used in the computation; speeds also in rpm '
        "and Hz, angles also in degrees.</p>",
        _table(("key", "value", "unit", "also"), parameter_rows(case.model, "model"), numeric={1}),
    ]
    derived = _quantity_rows(results)
    if derived:
        parts += ["<h3>Derived quantities</h3>", _table(("quantity", "value", "unit", "also"), derived,
                                                        numeric={1})]  # fmt: skip
    parts += [
        "<h2>Files</h2>",
        "<ul>" + "".join(f'<li><a href="{_e(f)}">{_e(f)}</a></li>' for f in files) + "</ul>",
        "<h2>Case file</h2>",
        f"<pre>{_e(case_text)}</pre>",
        "<h2>Software</h2>",
        _table(("package", "version"), versions().items()),
        *_plotly_parts(interactive),
        "</body></html>",
    ]
    return "\n".join(p for p in parts if p) + "\n"
