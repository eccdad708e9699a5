"""Console tables of the machine analyses (``rotorlab run``)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["machine_tables"]


def machine_tables(results: Mapping[str, Any], tables: Mapping[str, Sequence[Mapping[str, Any]]]) -> list[Any]:
    """One rich table per machine result (the report's table)."""
    from rich.table import Table

    from rotorlab.report._machine import machine_rows_table

    out = []
    for name, ds in results.items():
        header, body = machine_rows_table(ds, tables[name])
        t = Table(title=f"{name} ({ds.attrs['analysis']})", title_justify="left")
        for h in header:
            t.add_column(h)
        for row in body:
            t.add_row(*row)
        out.append(t)
    return out
