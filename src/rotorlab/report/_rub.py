"""Report section and findings of the ``rub`` analysis: the regime, and every measured number with
its closed-form value beside it (rows of :func:`rotorlab.analyses._rub.rub_rows`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["rub_section", "rub_findings"]

Rows = Sequence[Mapping[str, Any]]


def _fmt(v: Any) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.5g}"
    return str(v)


def rub_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the regime sentence and the measured / closed-form table."""
    from rotorlab.report._table import table

    a = ds.attrs
    head = (f"<p>Simulated regime: <b>{_fmt(rows[0]['measured'])}</b>; the closed forms allow: "
            f"{_fmt(rows[0]['closed_form'])}.</p>")  # fmt: skip
    if a.get("status", 0) < 0:
        head += f"<p>The integration failed: {a.get('status_message', '')}.</p>"
    body = [[r["quantity"], _fmt(r["measured"]), _fmt(r["closed_form"]), r["unit"], r["source"]] for r in rows[1:]]
    return head + table(["quantity", "simulated", "closed form", "unit", "source"], body, numeric={1, 2})


def rub_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The regime with the closed-form prediction, and the whirl radius and speed ratio."""
    numbers = tuple(f"{r['quantity']}: {_fmt(r['measured'])} (closed form {_fmt(r['closed_form'])}) {r['unit']}".rstrip()
                    for r in rows[1:3])  # fmt: skip
    return Findings(f"{rows[0]['measured']}; closed forms allow: {rows[0]['closed_form']}", numbers)
