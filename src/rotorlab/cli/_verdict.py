"""The verdict on the terminal: the first screen of ``rotorlab run`` (fits 100 columns)."""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from typing import Any

__all__ = ["verdict_text", "WIDTH"]

#: Columns the verdict fits in.
WIDTH = 100
_MARK = {"yes": "YES", "no": "NO", "not-settled": "NOT SETTLED", "info": "-"}


def verdict_text(lines: Sequence[Any], width: int = WIDTH) -> str:
    """The verdict as plain text, each line wrapped to ``width`` columns under its mark.

    >>> from rotorlab.analyses import VerdictLine
    >>> print(verdict_text([VerdictLine("run-up", "no", "0 of 1 starts pass.", "more torque")]))
    Verdict
      NO           run-up: 0 of 1 starts pass.
                   fix: more torque
    """
    if not lines:
        return ""
    indent = " " * 15
    out = ["Verdict"]
    for line in lines:
        first = f"  {_MARK[line.status]:<12} "
        out += textwrap.wrap(f"{line.topic}: {line.sentence}", width, initial_indent=first,
                             subsequent_indent=indent, break_on_hyphens=False)
        if line.fix:
            out += textwrap.wrap(f"fix: {line.fix}", width, initial_indent=indent, subsequent_indent=indent + "  ",
                                 break_on_hyphens=False)
    return "\n".join(out)
