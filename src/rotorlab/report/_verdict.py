"""The verdict block of the report: ``<section id="verdict">`` at the top of the page, one
element per line with class ``verdict-line`` and ``data-verdict`` (yes, no, not-settled, info)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rotorlab.report._table import escape as _e

__all__ = ["verdict_section", "VERDICT_CSS"]

_MARK = {"yes": "yes", "no": "no", "not-settled": "not settled", "info": "–"}

VERDICT_CSS = """
#verdict{border:2px solid #556;border-radius:6px;padding:.2em 1em .6em;margin:1em 0 1.5em;background:#fbfbfd}
#verdict h2{margin-top:.4em;border:none}
#verdict .verdict-line{margin:.35em 0;display:grid;grid-template-columns:7em 1fr;column-gap:.4em}
#verdict .mark{font-weight:700}
#verdict [data-verdict=yes] .mark{color:#1a7f37}#verdict [data-verdict=no] .mark{color:#b3261e}
#verdict [data-verdict=not-settled] .mark{color:#b35900}#verdict [data-verdict=info] .mark{color:#666}
#verdict .topic{font-weight:600}#verdict .fix{display:block;color:#333}
"""


def verdict_section(lines: Sequence[Any]) -> str:
    """HTML of the verdict (lines of :func:`rotorlab.analyses.machine_verdict`); "" without lines.

    >>> from rotorlab.analyses import VerdictLine
    >>> html = verdict_section([VerdictLine("balances", "no", "Does not balance.", "heavier balls")])
    >>> 'class="verdict-line" data-verdict="no" data-topic="balances"' in html, "Fix: heavier balls" in html
    (True, True)
    """
    if not lines:
        return ""
    items = []
    for line in lines:
        fix = f'<span class="fix">Fix: {_e(line.fix)}</span>' if line.fix else ""
        items.append(f'<p class="verdict-line" data-verdict="{_e(line.status)}" data-topic="{_e(line.topic)}">'
                     f'<span class="mark">{_e(_MARK[line.status])}</span><span class="body"><span class="topic">'
                     f"{_e(line.topic)}</span>: {_e(line.sentence)}{fix}</span></p>")
    return '<section id="verdict"><h2>Verdict</h2>' + "".join(items) + "</section>"
