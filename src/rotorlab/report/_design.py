"""Presentation of the ``design`` analysis: the recommendation in one sentence, its margins (how
far each constraint is from its limit), the winner's independent check from fresh random starts
next to the search's interval, the trade-off, the winner's sensitivity (the input P(balanced)
depends on most) and what was not explored (rows of
:func:`rotorlab.analyses._design_case.design_rows`)."""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rotorlab import _people as people
from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["design_section", "design_findings", "design_tables", "not_explored", "margin_lines"]

Rows = Sequence[Mapping[str, Any]]


def _operating(ds: xarray.Dataset) -> list[str]:
    dim = str(ds.attrs["operating"])
    return [people.quantity(float(v), str(ds[dim].attrs.get("units", ""))) for v in ds[dim].values]


def margin_lines(ds: xarray.Dataset) -> list[str]:
    """How far the winner is from each constraint's limit, in words."""
    best = int(ds.attrs["best"])
    if best < 0:
        return []
    out = []
    limits = json.loads(ds.attrs.get("limits", "{}"))
    units = json.loads(ds.attrs.get("objective_units", "{}"))
    for k, name in enumerate(ds["constraint"].values):
        m = float(ds["margin"].values[best, k])
        if name == "min_balanced":
            level = float(ds.attrs["min_balanced"])
            out.append(f"P(balanced) lower bound {people.number(level + m, 4)} against {people.number(level, 4)} "
                       f"required (margin {people.number(m, 2)})")  # fmt: skip
        else:
            obj = str(name).removeprefix("limits.")
            limit = float(limits[obj])
            out.append(f"{obj} {people.quantity(limit * (1 - m), units.get(obj, ''))} against the limit "
                       f"{people.quantity(limit, units.get(obj, ''))} ({people.number(100 * m, 2)} % below)")
    return out


def _check_line(ds: xarray.Dataset) -> str:
    from rotorlab.analyses._design_case import check_agrees

    best = int(ds.attrs["best"])
    agrees = check_agrees(ds)
    if agrees is None:
        return "The winner was not re-simulated (no random starts, or no feasible design)."
    search = ", ".join(f"{people.number(float(lo), 4)}–{people.number(float(hi), 4)}" for lo, hi in
                       zip(ds["balanced_low"].values[best], ds["balanced_high"].values[best]))  # fmt: skip
    fresh = ", ".join(people.number(float(v), 4) for v in ds["verify_balanced"].values)
    return (f"Re-simulated from {int(ds.attrs['starts'])} fresh random starts (seed {ds.attrs['verify_seed']}): "
            f"P(balanced) {fresh} against the search's interval(s) {search} at {', '.join(_operating(ds))}: "
            + ("inside." if agrees else "OUTSIDE: the search's estimate of its winner is optimistic."))


def not_explored(ds: xarray.Dataset) -> str:
    """What the search did not look at, in one sentence."""
    bounds = json.loads(ds.attrs.get("bounds", "{}"))
    units = json.loads(ds.attrs.get("units", "{}"))
    ranges = ", ".join(f"{n} outside {people.quantity(a, units.get(n, ''))}–{people.quantity(b, units.get(n, ''))}"
                       for n, (a, b) in bounds.items())  # fmt: skip
    if int(ds.attrs.get("run_ups", 0)):
        where = (f"the run-ups from rest under the drive's command only, {int(ds.attrs['run_up_starts'])} per design "
                 f"(random ball starts, seed {int(ds.attrs['run_up_seed'])})")
    else:
        where = (f"P(balanced) only at {', '.join(_operating(ds))} ({ds.attrs['operating']}), from "
                 f"{int(ds.attrs['starts'])} starts per design; run-up transients not checked")
    contact = "no-housing-contact" in json.loads(ds.attrs.get("constraints", "[]"))
    contact_text = "housing contact checked only on those run-ups" if contact else "housing contact not checked"
    return (f"Not explored: {ranges}; every other parameter held at the case's value; {where}; "
            f"{int(ds.attrs['evaluations'])} designs evaluated ({ds.attrs['optimizer']}, budget {ds.attrs['budget']}), "
            f"so a better design between them may exist; {contact_text}"
            + ("." if "ST" in ds else "; sensitivity not computed (give the analysis a sensitivity table)."))


def design_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The recommendation, then its margins, the check and what was not explored."""
    from rotorlab.analyses._design_case import recommendation, sensitivity_sentence

    sens = sensitivity_sentence(ds)
    return Findings(recommendation(ds), (*margin_lines(ds), _check_line(ds), *([sens] if sens else []),
                                         not_explored(ds)))  # fmt: skip


def _table(ds: xarray.Dataset, rows: Rows, only_front: bool) -> tuple[list[str], list[list[str]]]:
    units = json.loads(ds.attrs.get("units", "{}"))
    ounits = json.loads(ds.attrs.get("objective_units", "{}"))
    names = [str(v) for v in ds["variable"].values]
    objs = [str(o) for o in ds["objective"].values]
    head = ["#", *names, *objs, "P(balanced) low", "feasible", ""]
    body = []
    if only_front and len(objs) == 1:  # the winner and the next best feasible designs
        shown = sorted((r for r in rows if r["feasible"]), key=lambda r: r["objectives"][objs[0]])[:5]
    else:
        shown = [r for r in rows if r["pareto"] or r["best"] or not only_front]
    for r in shown:
        low = r["balanced_low"]
        body.append([str(r["trial"]), *(people.quantity(r["values"][n], units.get(n, "")) for n in names),
                     *(people.quantity(r["objectives"][o], ounits.get(o, "")) for o in objs),
                     "–" if low is None else people.number(low, 4), "yes" if r["feasible"] else "no",
                     "winner" if r["best"] else ("Pareto" if r["pareto"] and len(objs) > 1 else "")])  # fmt: skip
    return head, body


def design_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the recommendation, margins, check, what was not explored, the Pareto front (one
    objective: the five best feasible designs) as a table."""
    from html import escape

    from rotorlab.report._table import table

    found = design_findings(ds, rows)
    items = "".join(f"<li>{escape(s)}</li>" for s in found.numbers)
    head, body = _table(ds, rows, only_front=True)
    return f"<p><b>{escape(found.verdict)}</b></p><ul>{items}</ul>" + table(head, body, numeric={0})


def design_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run`` and ``rotorlab design``: the Pareto designs and the winner,
    titled with the recommendation, captioned with margins and the check."""
    from rich.table import Table

    out = []
    for name, ds in results.items():
        found = design_findings(ds, rows[name])
        head, body = _table(ds, rows[name], only_front=True)
        t = Table(title=f"{name}: {found.verdict}", title_justify="left", caption="\n".join(found.numbers),
                  caption_justify="left")  # fmt: skip
        for col in head:
            t.add_column(col, justify="right")
        for line in body:
            t.add_row(*line)
        out.append(t)
    return out

