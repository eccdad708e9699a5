"""Report section and findings of the ``continuation`` analysis: the special points in words, the
branches, and the two-parameter curves (figures from :mod:`rotorlab.plot._continuation`)."""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

from rotorlab._constants import shown_unit
from rotorlab.report._findings import Findings

__all__ = ["continuation_section", "continuation_findings"]

Rows = Sequence[Mapping[str, Any]]


def _points(rows: Rows) -> list[Mapping[str, Any]]:
    """Special points, a mirror image (same type and value on main+ / main-) once."""
    out: list[Mapping[str, Any]] = []
    for r in rows:
        if r["type"] == "branch-summary":
            continue
        if not any(o["type"] == r["type"] and abs(o["value"] - r["value"]) <= 1e-7 * max(1.0, abs(r["value"]))
                   for o in out):
            out.append(r)
    return out


def _period(row: Mapping[str, Any]) -> str:
    """A periodic branch's period range (s); a dash for equilibria."""
    if "period_from_s" not in row:
        return "-"
    return f"{row['period_from_s']:.5g} to {row['period_to_s']:.5g}"


def _orbit_sentences(rows: Rows) -> list[str]:
    """Per periodic branch: where its orbit exists and is stable, and how it was started."""
    out = []
    for r in rows:
        if r.get("sentence"):
            text = r["sentence"][0].upper() + r["sentence"][1:]
            out.append(text + (f" (started by {r['started']})" if r.get("started") else "") + ".")
    return out


def continuation_section(ds: Any, rows: Rows) -> str:
    """HTML: every special point with its sentence, the branches, and the curves' extent."""
    from rotorlab.report._table import table

    pts = _points(rows)
    html = "<p>" + ("<br>".join(f"<b>{r['type']}</b> ({r['branch']}): {r['description']}" for r in pts)
                    or "No fold, Hopf or branch point in this range.") + "</p>"
    summary = [r for r in rows if r["type"] == "branch-summary"]
    orbits = _orbit_sentences(rows)
    if orbits:
        html += "<p>" + "<br>".join(orbits) + "</p>"
    f, unit = shown_unit(ds.attrs.get("units", ""))
    html += table(["branch", f"from ({unit})", f"to ({unit})", "points", "stable points", "period (s)", "ended"],
                  [[r["branch"], f"{f * r['from']:.4g}", f"{f * r['to']:.4g}", r["points"], r["stable_points"],
                    _period(r), r["end"]] for r in summary], numeric={1, 2, 3, 4})
    doc = json.loads(ds.attrs.get("result", "{}"))
    curves = doc.get("curves", [])
    if curves:
        body = []
        for c in curves:
            p1, p2 = c["parameters"]
            v1 = [p[p1] for p in c["points"]]
            v2 = [p[p2] for p in c["points"]]
            body.append([f"{c['type']} ({c['label']})", f"{min(v1):.6g} to {max(v1):.6g}",
                         f"{min(v2):.6g} to {max(v2):.6g}", "yes" if c.get("stability_boundary", True) else "no",
                         c["end"]])
        html += table(["curve", f"{curves[0]['parameters'][0]} (SI)", f"{curves[0]['parameters'][1]} (SI)",
                       "stability boundary", "ended"], body)
    return html


def continuation_findings(ds: Any, rows: Rows) -> Findings:
    """The sentences of the special points that change stability first, then the others; the
    curves' own findings (speed x support anisotropy: up to which anisotropy balancing is stable)
    first where there are any."""
    pts = _points(rows)
    curve_findings = json.loads(ds.attrs.get("result", "{}")).get("findings", [])
    if curve_findings:
        said = [f[0].upper() + f[1:] + "." for f in curve_findings]
        return Findings(said[0], tuple(said[1:]) + tuple(f"{r['type']} ({r['branch']}): {r['description']}"
                                                         for r in pts[:6]))
    orbits = _orbit_sentences(rows)
    if orbits:
        return Findings(orbits[0], tuple(orbits[1:]) + tuple(f"{r['type']} ({r['branch']}): {r['description']}"
                                                             for r in pts[:6]))
    if not pts:
        return Findings("No fold, Hopf or branch point of the continued steady motions in this range.")
    first = [r for r in pts if "becomes stable" in r["description"] or "stable only below" in r["description"]]
    verdict = (first or pts)[0]["description"]
    verdict = verdict[0].upper() + verdict[1:] + "."
    return Findings(verdict, tuple(f"{r['type']} ({r['branch']}): {r['description']}" for r in pts[:6]))
