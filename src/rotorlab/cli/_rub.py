"""Console table of the ``rub`` analysis for ``rotorlab run``."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from rotorlab.report._rub import _fmt

__all__ = ["rub_tables"]

Rows = Sequence[Mapping[str, Any]]


def rub_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run``: one per ``rub`` result."""
    from rich.table import Table

    tables = []
    for name in results:
        r = rows[name]
        t = Table(title=f"{name}: {r[0]['measured']} (closed forms: {r[0]['closed_form']})", title_justify="left")
        for col in ("quantity", "simulated", "closed form", "unit"):
            t.add_column(col, justify="left" if col in ("quantity", "unit") else "right")
        for row in r[1:]:
            t.add_row(row["quantity"], _fmt(row["measured"]), _fmt(row["closed_form"]), row["unit"])
        tables.append(t)
    return tables
