"""The verdict on the terminal: the first screen of ``rotorlab run`` (fits 100 columns)."""

from __future__ import annotations

import re
import textwrap
from collections.abc import Sequence
from typing import Any

__all__ = ["verdict_text", "WIDTH"]

#: Columns the verdict fits in.
WIDTH = 100
_MARK = {"yes": "YES", "no": "NO", "not-settled": "NOT SETTLED", "info": "-"}
# a number and its unit stay on one line (a no-break space while wrapping)
_UNIT = re.compile(r"(\d) (?=(?:rpm|mm|µm|nm|m|ms|s|min|h|%|×|kg|g|N\*m|kg\*m|g\*mm|p)\b|[%×])")


def _wrap(text: str, width: int, first: str, rest: str) -> list[str]:
    lines = textwrap.wrap(_UNIT.sub("\\1\u00a0", text), width, initial_indent=first, subsequent_indent=rest,
                          break_on_hyphens=False)
    return [line.replace("\u00a0", " ") for line in lines]


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
        out += _wrap(f"{line.topic}: {line.sentence}", width, first, indent)
        if line.fix:
            out += _wrap(f"fix: {line.fix}", width, indent, indent + "  ")
    return "\n".join(out)
