"""Option values shared by several commands, parsed without heavy imports.

Every parser raises :class:`~rotorlab.cli._output.BadInput` with a message that names the
option, the value given and what is allowed, so that a bad option ends the command with exit
code 2 before anything is computed or written.
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path
from typing import Any

from rotorlab._limits import MAX_CHUNK, MAX_COUNT, MAX_SEED, MAX_SPEED_RPM, MAX_WORKERS
from rotorlab.cli._output import BadInput

__all__ = ["MAX_SPEEDS", "MAX_RANGE_POINTS", "MAX_SPEED_RPM", "MAX_WORKERS", "MAX_CHUNK", "MAX_COUNT", "MAX_SEED",
           "PLOT_SUFFIXES", "Count", "count_option", "parse_range", "parse_speed_range", "check_speed",
           "check_plot_path"]  # fmt: skip

#: Upper limit of N in a speed range ``START:STOP:N`` (a typo such as 1e9 speeds would never finish).
MAX_SPEEDS = 100_000

#: Upper limit of N in any other range ``START:STOP:N`` (a grid axis; whole grids are checked
#: against the memory too).
MAX_RANGE_POINTS = 1_000_000

#: File types ``--plot`` writes.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def _integer(text: str) -> int | None:
    """``text`` as an integer (an integral number such as ``1e3`` too), else None."""
    text = text.strip()
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        return None
    return int(value) if math.isfinite(value) and value.is_integer() else None


class Count:
    """Read a count option's value: an integer from ``low`` to ``high`` (the one place count
    options are read; an integral number such as ``2e3`` is taken too, like the case file's
    counts). Refused: :class:`~rotorlab.cli._output.OptionError` (exit code 2) naming the option,
    the value and the range.

    Examples
    --------
    >>> Count("--workers", 1, 256)("2e1")
    20
    >>> Count("--workers", 1, 256, "threads")("1e30")
    Traceback (most recent call last):
    ...
    rotorlab.cli._output.OptionError: --workers = 1e30: must be an integer >= 1 and <= 256 (threads)
    """

    def __init__(self, option: str, low: int, high: int, what: str = "") -> None:
        self.option, self.low, self.high, self.what = option, low, high, what

    def __call__(self, value: Any) -> int:
        n = value if isinstance(value, int) and not isinstance(value, bool) else _integer(str(value))
        if n is None or not self.low <= n <= self.high:
            from rotorlab.cli._output import OptionError, clean_text

            raise OptionError(f"{self.option} = {clean_text(value, 80)}: must be an integer >= {self.low} and "
                              f"<= {self.high}" + (f" ({self.what})" if self.what else ""))  # fmt: skip
        return n


def count_option(option: str, *, high: int = MAX_COUNT, low: int = 1, what: str = "", **kwargs: Any) -> Any:
    """A ``typer.Option`` for a count (``--chunk``, ``--workers``, ...) read by :class:`Count`."""
    import typer

    return typer.Option(option, parser=Count(option, low, high, what), **kwargs)


def parse_range(option: str, text: str, dimension: str | None = None, *, sample: bool = False,
                min_count: int = 1, max_count: int = MAX_RANGE_POINTS, low: float | None = None,
                high: float | None = None, unit: str = "", head: str | None = None,
                form: str = "must be START:STOP:N") -> tuple:  # fmt: skip
    """Read ``START:STOP:N`` (N evenly spaced values) or, with ``sample``, ``LOW:HIGH``: the one
    place every range option is read and bounded.

    Parameters
    ----------
    option : str
        Option name for messages.
    text : str
        The value; START and STOP are plain numbers, or with ``dimension`` numbers in SI or
        with a unit (``0.05mm``); a unit written on one end only is that of both
        (``10:170deg`` is 10 deg to 170 deg).
    dimension : str, optional
        A key of :data:`rotorlab.io.DIMENSIONS` to convert START and STOP to SI.
    sample : bool
        ``LOW:HIGH`` (a range to draw from), no N.
    min_count, max_count : int
        Bounds of N (START < STOP unless N = 1).
    low, high : float, optional
        Bounds of START and STOP (in ``unit``).
    unit : str
        Unit of the values, for messages (``" rpm"``).
    head, form : str, optional
        Start of every message (default ``"{option} = {text}: "``) and the form asked for when
        the fields do not fit.

    Returns
    -------
    (float, float, int) or, with ``sample``, (float, float)

    Raises
    ------
    BadInput
        Wrong number of fields, a field that is not a number (or a unit of the wrong dimension),
        values out of bounds, N not an integer in [min_count, max_count]; every problem is listed.

    Examples
    --------
    >>> parse_range("--speeds-rpm", "300:3000:10")
    (300.0, 3000.0, 10)
    >>> parse_range("--param", "0:2.5mm:3", "length")
    (0.0, 0.0025, 3)
    >>> [round(v, 4) for v in parse_range("--x", "10:170deg:3", "angle")[:2]]  # the unit of both ends
    [0.1745, 2.9671]
    >>> parse_range("--speeds-rpm", "0:1e300:5", high=1e7, unit=" rpm")
    Traceback (most recent call last):
    ...
    rotorlab.cli._output.BadInput: --speeds-rpm = 0:1e300:5: STOP must be a finite number <= 1e+07 rpm
    """
    head = f"{option} = {text}: " if head is None else head
    fields = text.split(":")
    if len(fields) != (2 if sample else 3):
        raise BadInput(head + form)
    ends = []
    # one unit written on either end is the unit of both: 10:170deg is 10 deg to 170 deg
    shared = _written_units(fields[:2]) if dimension is not None else None
    for name, field in zip(("LOW", "HIGH") if sample else ("START", "STOP"), fields):
        try:
            ends.append(float(field))
            if shared is None:
                continue
            field = f"{field.strip()} {shared}"
            ends.pop()
        except ValueError:
            if dimension is None:
                raise BadInput(head + f"{name} = {field!r} is not a number") from None
        from rotorlab.io import CaseError, to_si

        try:
            ends.append(to_si(field.strip(), dimension, option))
        except (CaseError, ValueError) as exc:
            raise BadInput(head + str(exc)) from None
    start, stop = ends
    first, last = ("LOW", "HIGH") if sample else ("START", "STOP")
    problems = []
    for name, value in ((first, start), (last, stop)):
        if not math.isfinite(value):
            problems.append(f"{name} must be a finite number")
        elif low is not None and value < low:
            problems.append(f"{name} must be a finite number >= {low:g}{unit}")
        elif high is not None and value > high:
            problems.append(f"{name} must be a finite number <= {high:g}{unit}")
    if sample:
        if math.isfinite(start) and math.isfinite(stop) and not stop >= start:
            problems.append(f"HIGH must be >= LOW ({start:g}{unit})")
        if problems:
            raise BadInput(head + "; ".join(problems))
        return start, stop
    n = _integer(fields[2])
    if math.isfinite(start) and math.isfinite(stop) and not (stop > start or (n == 1 and stop == start)):
        problems.append(f"STOP must be > START ({start:g}{unit})" + (" (or equal with N = 1)" if min_count < 2 else ""))
    if n is None or n < min_count:
        problems.append(f"N must be an integer >= {min_count}")
    elif n > max_count:
        problems.append(f"N must be <= {max_count}")
    if problems:
        raise BadInput(head + "; ".join(problems))
    return start, stop, n


_NUMBER = re.compile(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*")


def _written_units(fields: list[str]) -> str | None:
    """The unit written after the number of the range ends, when exactly one unit is written
    (on one end, or the same on both); None when neither end has one or they differ.

    Examples
    --------
    >>> _written_units(["10", "170deg"]), _written_units(["1", "2"]), _written_units(["1 g", "2 kg"]) is None
    ('deg', None, True)
    """
    units = set()
    for field in fields:
        m = _NUMBER.match(field)
        rest = field[m.end():].strip() if m else field.strip()
        if rest:
            units.add(rest)
    return units.pop() if len(units) == 1 else None


def parse_speed_range(text: str, option: str = "--speeds-rpm", min_count: int = 2) -> tuple[float, float, int]:
    """Read ``START:STOP:N``: N equally spaced speeds from START to STOP (rpm), in [0, MAX_SPEED_RPM].

    Raises
    ------
    BadInput
        See :func:`parse_range`; N in [min_count, MAX_SPEEDS].

    Examples
    --------
    >>> parse_speed_range("0:4000:81")
    (0.0, 4000.0, 81)
    >>> parse_speed_range("5:1:0")
    Traceback (most recent call last):
    ...
    rotorlab.cli._output.BadInput: --speeds-rpm = 5:1:0: STOP must be > START (5 rpm); N must be an integer >= 2
    """
    return parse_range(option, text, min_count=min_count, max_count=MAX_SPEEDS, low=0.0, high=MAX_SPEED_RPM,
                       unit=" rpm", form="give START:STOP:N (rpm, rpm, number of speeds), e.g. 0:4000:81")


def check_speed(value: float, option: str = "--speed-rpm", *, positive: bool = False) -> float:
    """Return ``value`` if it is a finite speed >= 0 (> 0 with ``positive``) and at most
    :data:`MAX_SPEED_RPM` (rpm), else raise :class:`BadInput`."""
    if not (math.isfinite(value) and (value > 0 if positive else value >= 0) and value <= MAX_SPEED_RPM):
        raise BadInput(f"{option} = {value:g}: must be a finite number {'>' if positive else '>='} 0 (rpm), "
                       f"at most {MAX_SPEED_RPM:g} rpm")
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
