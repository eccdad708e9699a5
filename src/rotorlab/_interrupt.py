"""Ctrl-C that Python swallowed: remembered, so that the command line still stops.

Python turns SIGINT into ``KeyboardInterrupt`` in whatever code runs at that moment. When that is
a callback Python calls from C (a weak-reference callback of the import system's module locks,
for example), the exception is printed as "Exception ignored in ..." and the program goes on: a
``rotorlab run`` interrupted 0.02 s after start then wrote its whole output and exited 0 (seen in
``tests/robustness/test_signals.py``). The command line's handler (:func:`handler`, installed by
:func:`rotorlab.cli.main`) raises as Python's own does and also records the interrupt;
:func:`check` raises it again at the points where a command would commit work (after its
imports, before an output folder is put in place).
"""

from __future__ import annotations

from typing import Any

__all__ = ["check", "handler"]

_pending = False


def handler(signum: int, frame: Any) -> None:
    """SIGINT handler: record the interrupt and raise ``KeyboardInterrupt`` (as Python's own)."""
    global _pending
    _pending = True
    raise KeyboardInterrupt


def check() -> None:
    """Raise ``KeyboardInterrupt`` if a Ctrl-C was recorded and then swallowed."""
    if _pending:
        raise KeyboardInterrupt
