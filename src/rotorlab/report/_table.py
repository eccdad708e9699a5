"""HTML building blocks shared by the report's sections: escaping and tables."""

from __future__ import annotations

import html
import re
from collections.abc import Iterable, Sequence
from typing import Any

__all__ = ["escape", "table", "console_table"]

_NUMBER = re.compile(r"^[±+-]?(\d|\.\d)")


def escape(value: Any) -> str:
    """``str(value)`` escaped for HTML text and attributes."""
    return html.escape(str(value), quote=True)


def table(header: Sequence[str], rows: Iterable[Sequence[Any]], numeric: set[int] = frozenset(),
          raw: set[int] = frozenset()) -> str:  # fmt: skip
    """Return an HTML table.

    Parameters
    ----------
    header : sequence of str
    rows : iterable of sequences
        Cells, escaped unless their column is in ``raw``.
    numeric : set of int
        Columns right-aligned where the cell starts like a number.
    raw : set of int
        Columns whose cells are HTML already.

    Examples
    --------
    >>> table(("a", "b"), [(1, "<x>")], numeric={0})
    '<table><thead><tr><th>a</th><th>b</th></tr></thead><tbody><tr><td class="num">1</td><td>&lt;x&gt;</td></tr></tbody></table>'
    """
    head = "".join(f"<th>{escape(h)}</th>" for h in header)
    body = []
    for row in rows:
        cells = []
        for j, cell in enumerate(row):
            css = ' class="num"' if j in numeric and _NUMBER.match(str(cell)) else ""
            cells.append(f"<td{css}>{cell if j in raw else escape(cell)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def console_table(title: str, header: Sequence[str], rows: Iterable[Sequence[str]], left: str) -> Any:
    """A rich table for the console: ``title`` above, the column ``left`` left-aligned, the others
    right-aligned (numbers)."""
    from rich.table import Table

    t = Table(title=title, title_justify="left")
    for col in header:
        t.add_column(col, justify="left" if col == left else "right")
    for line in rows:
        t.add_row(*line)
    return t
