"""Option values shared by several commands, parsed without heavy imports.

Every parser raises :class:`~rotorlab.cli._output.BadInput` with a message that names the
option, the value given and what is allowed, so that a bad option ends the command with exit
code 2 before anything is computed or written.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from rotorlab.cli._output import BadInput

__all__ = ["MAX_SPEEDS", "PLOT_SUFFIXES", "parse_speed_range", "check_speed", "check_plot_path"]

#: Upper limit of N in ``START:STOP:N`` (a typo such as 1e9 speeds would never finish).
MAX_SPEEDS = 100_000

#: File types ``--plot`` writes.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def parse_speed_range(text: str, option: str = "--speeds-rpm") -> tuple[float, float, int]:
    """Read ``START:STOP:N``: N equally spaced speeds from START to STOP (rpm).

    Parameters
    ----------
    text : str
        The option value.
    option : str
        The option's name, for messages.

    Returns
    -------
    (float, float, int)
        START and STOP (rpm) and N.

    Raises
    ------
    BadInput
        Not three fields, a field that is not a number, START < 0, STOP <= START, N not an
        integer in [2, MAX_SPEEDS]; every problem is listed.

    Examples
    --------
    >>> parse_speed_range("0:4000:81")
    (0.0, 4000.0, 81)
    >>> parse_speed_range("5:1:0")
    Traceback (most recent call last):
    ...
    rotorlab.cli._output.BadInput: --speeds-rpm = 5:1:0: STOP must be > START (5 rpm); N must be an integer >= 2
    """
    head = f"{option} = {text}: "
    fields = text.split(":")
    if len(fields) != 3:
        raise BadInput(head + "give START:STOP:N (rpm, rpm, number of speeds), e.g. 0:4000:81")
    values = []
    for name, field in zip(("START", "STOP", "N"), fields):
        try:
            values.append(float(field))
        except ValueError:
            raise BadInput(head + f"{name} = {field!r} is not a number") from None
    start, stop, n = values
    problems = []
    if not (math.isfinite(start) and start >= 0):
        problems.append("START must be a finite number >= 0 (rpm)")
    if not math.isfinite(stop):
        problems.append("STOP must be a finite number (rpm)")
    elif math.isfinite(start) and not stop > start:
        problems.append(f"STOP must be > START ({start:g} rpm)")
    if not (math.isfinite(n) and n.is_integer() and n >= 2):
        problems.append("N must be an integer >= 2")
    elif n > MAX_SPEEDS:
        problems.append(f"N must be <= {MAX_SPEEDS}")
    if problems:
        raise BadInput(head + "; ".join(problems))
    return start, stop, int(n)


def check_speed(value: float, option: str = "--speed-rpm") -> float:
    """Return ``value`` if it is a finite speed >= 0 (rpm), else raise :class:`BadInput`."""
    if not (math.isfinite(value) and value >= 0):
        raise BadInput(f"{option} = {value:g}: must be a finite number >= 0 (rpm)")
    return float(value)


def check_plot_path(path: Path, option: str = "--plot") -> Path:
    """Check that a figure can be written to ``path`` (without creating anything).

    Raises
    ------
    BadInput
        Unsupported suffix, an existing folder, a missing parent folder, or no write access.
    """
    suffix = path.suffix.lower()
    if suffix not in PLOT_SUFFIXES:
        kinds = ", ".join(PLOT_SUFFIXES)
        raise BadInput(f"{option} = {path}: unsupported file type '{suffix or '(none)'}' "
                       f"(use {kinds})")
    if path.is_dir():
        raise BadInput(f"{option} = {path}: is a folder (give a file name)")
    parent = path.absolute().parent
    if not parent.is_dir():
        raise BadInput(f"{option} = {path}: folder {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise BadInput(f"{option} = {path}: folder {parent} is not writable")
    return path
