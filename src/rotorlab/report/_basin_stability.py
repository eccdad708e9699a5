"""Presentation of the ``basin-stability`` analysis: over the parameter range, from what share of
start-ups the balancer balances (with its Wilson interval), which other motions take the rest,
which starts had not settled, and how fast the balanced ones settled (rows of
:func:`rotorlab.analyses._basin_stability.basin_stability_rows`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["basin_stability_section", "basin_stability_findings", "basin_stability_tables", "stability_verdict"]

Rows = Sequence[Mapping[str, Any]]


def _pct(v: float) -> str:
    return f"{100.0 * v:.1f} %"


def _ci(pair: Sequence[float]) -> str:
    return f"{100.0 * pair[0]:.1f}–{100.0 * pair[1]:.1f} %"


def _value(ds: xarray.Dataset, row: Mapping[str, Any]) -> str:
    from rotorlab.plot._basin_stability import param_display

    shown, label = param_display(ds)
    unit = label[label.find("(") + 1 : -1] if "(" in label else ""
    i = [float(v) for v in ds[ds.attrs["param"]].values].index(row["value"])
    return f"{shown[i]:.4g}" + (f" {unit}" if unit else "")


def _others(rows: Rows, first: str) -> dict[str, Mapping[str, Any]]:
    """Every motion besides the first label (and not settled) seen at some value: its row of largest share."""
    out: dict[str, Mapping[str, Any]] = {}
    for r in rows:
        for lab, p in r["fractions"].items():
            if lab not in (first, "not settled") and p > 0 and (lab not in out or p > out[lab]["fractions"][lab]):
                out[lab] = r
    return out


def stability_verdict(ds: xarray.Dataset, rows: Rows) -> str:
    """In words: the range of the balanced share with its intervals, each other motion at its
    largest, starts not settled, and the horizon rule."""
    if not rows:
        return "No parameter value was run."
    first = str(ds["regime"].values[0])
    name = ds.attrs["param"]
    lo = min(rows, key=lambda r: r["balanced"])
    hi = max(rows, key=lambda r: r["balanced"])
    conf = f"{100.0 * float(ds.attrs.get('confidence', 0.95)):g} %"
    if lo is hi or lo["balanced"] == hi["balanced"]:
        out = (f"Over {name} {_value(ds, rows[0])} to {_value(ds, rows[-1])} the share of random start-ups that end "
               f"{first} is {_pct(lo['balanced'])} everywhere (Wilson {conf}: {_ci(lo['balanced_ci'])} or narrower).")
    else:
        out = (f"Over {name} {_value(ds, rows[0])} to {_value(ds, rows[-1])} the share of random start-ups that end "
               f"{first} ranges from {_pct(lo['balanced'])} ({_ci(lo['balanced_ci'])}, Wilson {conf}) at "
               f"{_value(ds, lo)} to {_pct(hi['balanced'])} ({_ci(hi['balanced_ci'])}) at {_value(ds, hi)}.")
    for lab, r in _others(rows, first).items():
        what = f"a {lab} whirl" if lab == "non-synchronous" else lab
        out += f" {what[0].upper()}{what[1:]} takes up to {_pct(r['fractions'][lab])} ({_ci(r['ci'][lab])}) at {_value(ds, r)}."
    waiting = [r for r in rows if r["not_settled"] > 0]
    if waiting:
        worst = max(waiting, key=lambda r: r["not_settled"])
        out += (f" {len(waiting)} of {len(rows)} values have starts not settled (up to {_pct(worst['not_settled'])} at "
                f"{_value(ds, worst)}): {worst['verdict']}")
    unsure = [r for r in rows if not r["settled"] and r["not_settled"] == 0]
    if unsure:
        out += f" At {len(unsure)} value(s) the stated test does not yet show that the fractions stopped changing."
    failed = sum(r["failed"] for r in rows)
    if failed:
        out += f" {failed} integration(s) failed (counted as 'other')."
    return out


def _numbers(ds: xarray.Dataset, rows: Rows) -> tuple[str, ...]:
    n = [r["n"] for r in rows]
    mode = ds.attrs.get("mode")
    how = (f"{min(n)} starts per value" if mode == "starts" else
           f"{min(n)} to {max(n)} starts per value, until every Wilson interval is within "
           f"±{100.0 * float(ds.attrs['target_half_width']):g} %")  # fmt: skip
    out = [how + f" (seed {ds.attrs.get('seed')}, {sum(n)} in all)", str(ds.attrs.get("horizon_rule", ""))]
    settled = [r for r in rows if r["settle_time_max_s"] is not None]
    if settled:
        slow = max(settled, key=lambda r: r["settle_time_max_s"])
        tau = slow["time_constant_s"]
        out.append(f"balanced starts settled by {slow['settle_time_max_s']:.3g} s at the latest ({_value(ds, slow)}; "
                   f"median {slow['settle_time_median_s']:.3g} s" + (f", slowest mode's time constant {tau:.3g} s)"
                                                                     if tau else ")"))  # fmt: skip
    return tuple(s for s in out if s)


def basin_stability_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The verdict and the key numbers (starts, horizon, settle times)."""
    return Findings(stability_verdict(ds, rows), _numbers(ds, rows))


def _table_rows(ds: xarray.Dataset, rows: Rows) -> tuple[list[str], list[list[str]]]:
    first = str(ds["regime"].values[0])
    others = list(_others(rows, first))
    head = ["value", "starts", f"{first} (95 % interval)", *others, "not settled", "settled by (median / max, s)",
            "time constant (s)"]
    body = []
    for r in rows:
        settle = ("–" if r["settle_time_max_s"] is None else
                  f"{r['settle_time_median_s']:.3g} / {r['settle_time_max_s']:.3g}")  # fmt: skip
        body.append([_value(ds, r), str(r["n"]), f"{_pct(r['balanced'])} ({_ci(r['balanced_ci'])})",
                     *(f"{_pct(r['fractions'][lab])} ({_ci(r['ci'][lab])})" for lab in others),
                     _pct(r["not_settled"]), settle,
                     "–" if r["time_constant_s"] is None else f"{r['time_constant_s']:.3g}"])  # fmt: skip
    return head, body


def basin_stability_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the verdict, then one table row per parameter value."""
    from html import escape

    from rotorlab.report._table import table

    head, body = _table_rows(ds, rows)
    return f"<p>{escape(stability_verdict(ds, rows))}</p>" + table(head, body, numeric={1})


def basin_stability_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run`` and ``rotorlab basin-stability``: one per result."""
    from rotorlab.report._table import console_table

    return [console_table(f"{name}: {stability_verdict(ds, rows[name])}", *_table_rows(ds, rows[name]), left="value")
            for name, ds in results.items()]  # fmt: skip
