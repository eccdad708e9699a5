"""Console output of the command line: messages, errors and exit codes, progress, tables, JSON.

Everything meant for a person goes through rich consoles created per call (so that test runners
that swap ``sys.stdout``/``sys.stderr`` see it); progress bars and messages go to stderr, results
to stdout. With ``--json`` stdout carries only the JSON document. rich is imported inside the
functions to keep ``rotorlab --version`` fast.
"""

from __future__ import annotations

import contextlib
import errno
import json
import logging
import math
import os
import sys
import traceback
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import typer

from rotorlab._people import length, relative

__all__ = [
    "Settings",
    "BadInput",
    "OptionError",
    "clean_click_errors",
    "say",
    "EXIT_BAD_INPUT",
    "EXIT_INTERNAL",
    "EXIT_FAILED_RESULTS",
    "exit_if_failed",
    "handled",
    "stdout",
    "stderr",
    "info",
    "emit_json",
    "progress_bar",
    "status",
    "summary_table",
    "outcome_table",
    "clean_text",
    "TEXT_LIMIT",
]

EXIT_INTERNAL = 1
EXIT_BAD_INPUT = 2
#: The command ran and wrote its results, but some of them failed (an integrator gave up, or a
#: sanity check found a physically impossible state): never reported as a success.
EXIT_FAILED_RESULTS = 3

#: errno codes of a system that refuses a write (not a bug of rotorlab): the message names the path
_SYSTEM_REFUSALS = frozenset(getattr(errno, n) for n in ("ENOSPC", "EDQUOT", "EACCES", "EPERM", "EROFS", "EIO",
                                                         "EFBIG", "EMFILE", "ENFILE") if hasattr(errno, n))


#: Longest text from a user or a file (a case's description, a store's attribute) printed on one
#: line of a table or message; error messages get :data:`LINE_LIMIT` per line.
TEXT_LIMIT = 200
LINE_LIMIT = 1000

# ANSI/VT escape sequences: CSI (ESC [ ... final), OSC (ESC ] ... BEL or ESC \), two-byte ESC x, C1 CSI
_ESCAPES = r"\x1b\[[0-?]*[ -/]*[@-~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)?|\x1b[@-_]?|\x9b[0-?]*[ -/]*[@-~]"


def clean_text(value: Any, limit: int | None = TEXT_LIMIT, *, lines: bool = False) -> str:
    """``value`` as text safe for a terminal: escape sequences removed, other control characters
    shown as ``?``, cut to ``limit`` characters (the length of the rest said).

    Every echo of text that came from a user or a file goes through this (the consoles of
    :func:`stdout` and :func:`stderr`, error messages, warnings, progress lines), so that a case
    file, a ``--set`` value or a store's attributes cannot move the cursor, retitle the window
    or hide text.

    Parameters
    ----------
    value : Any
        Shown with ``str``.
    limit : int or None
        Longest text kept (per line with ``lines``); None: no limit.
    lines : bool
        Keep line breaks (each line cleaned and cut on its own).

    Examples
    --------
    >>> clean_text("disc\x1b[2J\x1b]0;pwned\x07 mass\x08")
    'disc mass?'
    >>> clean_text("x" * 300, limit=5)
    'xxxxx... (300 characters)'
    """
    import re
    import unicodedata

    text = str(value)
    if lines:
        return "\n".join(clean_text(line, limit) for line in text.split("\n"))
    cut = 0
    if limit is not None and len(text) > 4 * limit:  # never scan megabytes of a hostile text
        text, cut = text[: 4 * limit], len(text)
    text = re.sub(_ESCAPES, "", text)
    text = "".join(c if c == " " or unicodedata.category(c) not in ("Cc", "Cf", "Co", "Cs") else "?" for c in text)
    total = cut or len(text)
    if limit is not None and len(text) > limit:
        return text[:limit] + f"... ({total} characters)"
    return text if not cut else text + f"... ({total} characters)"


class BadInput(ValueError):
    """A command-line option has a value that is not allowed (message names option and value)."""


class OptionError(typer.BadParameter):
    """An option's value refused while the command line is read (before the command runs):
    ``error: <message>`` on stderr, cleaned, exit code 2, like :class:`BadInput`."""

    exit_code = EXIT_BAD_INPUT

    def show(self, file: Any = None) -> None:
        say(f"error: {self.message}")


@contextlib.contextmanager
def clean_click_errors() -> Iterator[None]:
    """Clean the message of a click error raised in the block (click's usage errors repeat what
    was typed: an unknown option, a value it cannot read) before click prints it."""
    try:
        yield
    except typer.TyperException as exc:  # click's errors (typer bundles its own click)
        if isinstance(getattr(exc, "message", None), str):
            exc.message = clean_text(exc.message, LINE_LIMIT, lines=True)
        raise


@dataclass(frozen=True, slots=True)
class Settings:
    """Global options: how much to print.

    Parameters
    ----------
    quiet : bool
        No progress and no messages: only the results (or the requested JSON) and errors.
    verbose : bool
        Print more detail, and tracebacks of internal errors.
    """

    quiet: bool = False
    verbose: bool = False


def _clean_console_class() -> Any:
    """A rich ``Console`` whose every printed string (messages, table cells, titles) is cleaned
    by :func:`clean_text` first (created once, on first use: rich is imported late)."""
    global _CleanConsole
    if _CleanConsole is None:
        from rich.console import Console

        class CleanConsole(Console):
            def render_str(self, text: str, **kwargs: Any) -> Any:
                return super().render_str(clean_text(text, None, lines=True), **kwargs)

            def print(self, *objects: Any, **kwargs: Any) -> None:
                super().print(*(compact(o) for o in objects), **kwargs)

        _CleanConsole = CleanConsole
    return _CleanConsole


_CleanConsole: Any = None


#: Width of the printed tables when stdout is not a terminal (a file, a pipe, a CI log).
TABLE_WIDTH = 100


def compact(table: Any) -> Any:
    """Make a rich table compact (``table`` itself; anything else is returned as it is).

    No vertical rules and one space between columns; a column is never narrower than the
    longest word of its cells, so that a word is wrapped onto the next line as a whole and
    never cut ("balanc..."), while the headers wrap at their spaces.
    """
    from rich import box
    from rich.table import Table

    if not isinstance(table, Table):
        return table
    table.box = box.SIMPLE_HEAD
    table.padding = (0, 1)
    table.pad_edge = False
    table.collapse_padding = True
    for col in table.columns:
        words = [len(w) for cell in col._cells for w in str(getattr(cell, "plain", cell)).split()]
        col.min_width = max(col.min_width or 0, max(words, default=1))
        col.overflow = "fold"
    return table


def stdout() -> Any:
    """Return a rich console on the current ``sys.stdout`` (:data:`TABLE_WIDTH` columns when not a
    terminal, unless ``COLUMNS`` says otherwise); every string it prints is cleaned of escape sequences (:func:`clean_text`) and
    every table is made :func:`compact`."""
    console = _clean_console_class()(file=sys.stdout, highlight=False, soft_wrap=True)
    if not console.is_terminal and not os.environ.get("COLUMNS", "").isdigit():
        console.width = TABLE_WIDTH
    return console


def stderr() -> Any:
    """Return a rich console on the current ``sys.stderr`` (strings cleaned as by :func:`stdout`)."""
    return _clean_console_class()(file=sys.stderr, highlight=False, soft_wrap=True)


def say(message: Any, *, limit: int | None = LINE_LIMIT) -> None:
    """Write ``message`` and a line break to stderr, cleaned (:func:`clean_text`, line breaks
    kept, each line cut to ``limit``): the one way plain messages reach the terminal."""
    sys.stderr.write(clean_text(message, limit, lines=True) + "\n")


def info(settings: Settings, message: str, *, json_mode: bool = False) -> None:
    """Print a progress/status message (stderr in JSON mode, else stdout) unless quiet."""
    if settings.quiet:
        return
    (stderr() if json_mode else stdout()).print(message, markup=False)


def emit_json(document: Any) -> None:
    """Write ``document`` as JSON to stdout (the only stdout output in ``--json`` mode)."""
    sys.stdout.write(json.dumps(document, indent=2, allow_nan=False) + "\n")
    sys.stdout.flush()


def console_or_json(settings: Settings, json_out: bool, document: Any) -> Any:
    """Finish a command's output: in ``--json`` mode write ``document`` and return None; else
    return the stdout console for the human-readable results (printed also when quiet: ``-q``
    hides progress and messages, not results)."""
    if json_out:
        emit_json(document)
        return None
    return stdout()


@contextlib.contextmanager
def handled(settings: Settings) -> Iterator[None]:
    """Turn exceptions into one clear message on stderr and the documented exit code.

    Bad input (:class:`rotorlab.io.CaseError`, :class:`BadInput`, a size that would not fit in
    memory, :class:`rotorlab._memory.TooLarge`): the message, exit code 2. A write the system
    refuses (disk full, permissions): the message with the path, exit code 1.
    Anything unexpected: a short message (traceback with ``-v``), exit code 1.
    """
    import warnings

    global _interrupt_reported
    try:
        with warnings.catch_warnings():
            # rotorlab's own warnings (a case without schema_version, lost chunks recomputed) as
            # one line each on stderr, every time
            warnings.filterwarnings("always", category=UserWarning, module="rotorlab")
            warnings.showwarning = _warning_line
            yield
    except (typer.Exit, typer.Abort):
        raise
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        _interrupt_reported = True
        raise typer.Exit(130) from None
    except Exception as exc:  # noqa: BLE001 - the last line of defence of the CLI
        # imported here, not before the try: a Ctrl-C during these (heavy) imports is handled too
        from rotorlab._memory import TooLarge
        from rotorlab.io import CaseError

        if isinstance(exc, (CaseError, BadInput, TooLarge)):
            say(f"error: {exc}")
            raise typer.Exit(EXIT_BAD_INPUT) from None
        if isinstance(exc, OSError) and exc.errno in _SYSTEM_REFUSALS:
            text = str(exc) if type(exc).__str__ is not OSError.__str__ else (
                f"cannot write {exc.filename}: {exc.strerror}" if exc.filename else f"{exc.strerror or exc}")
            say(f"error: {text}")
            raise typer.Exit(EXIT_INTERNAL) from None
        _internal(settings, exc)


#: Set when :func:`handled` has said "interrupted" (the entry point says it otherwise).
_interrupt_reported = False


def _warning_line(message: Any, category: Any, filename: str, lineno: int, file: Any = None,
                  line: Any = None) -> None:  # fmt: skip
    say(f"warning: {message}")


def _internal(settings: Settings, exc: BaseException) -> None:
    """Report an unexpected exception (traceback with ``-v``) and exit 1."""
    if settings.verbose:
        say("".join(traceback.format_exception(exc)).rstrip("\n"), limit=None)
    say(f"internal error: {type(exc).__name__}: {exc}")
    if not settings.verbose:
        sys.stderr.write("(run with -v for the traceback)\n")
    raise typer.Exit(EXIT_INTERNAL) from None


def exit_if_failed(datasets: Mapping[str, Any]) -> None:
    """Exit with :data:`EXIT_FAILED_RESULTS` (3) after the results are out when any trajectory or
    run of ``datasets`` (name -> Dataset with an integer ``status`` variable, or attribute for a
    single run) failed, naming how many and why; nothing happens when every status is usable
    (>= 0).

    Every command that integrates calls this last, so that no command exits 0 with a result it
    knows is impossible.
    """
    import numpy as np

    from rotorlab.integrate import Status

    lines = []
    for name, ds in datasets.items():
        if ds is None:
            continue
        if "status" in ds.variables:
            codes = np.asarray(ds["status"].values).ravel()
        elif isinstance(ds.attrs.get("status"), (int, np.integer)):  # a single run's status attribute
            codes = np.array([int(ds.attrs["status"])])
        else:
            continue
        bad = codes[codes < 0]
        if bad.size == 0:
            continue
        kinds = []
        for code in np.unique(bad):
            try:
                text = Status(int(code)).message
            except ValueError:
                text = f"status {int(code)}"
            kinds.append(f"{int(np.count_nonzero(bad == code))} {text}")
        detail = ds.attrs.get("status_detail", "") or (ds.attrs.get("status_message", "") if "status" not in
                                                        ds.variables else "")  # fmt: skip
        lines.append(f"{name}: {bad.size} of {codes.size} failed ({'; '.join(kinds)})"
                     + (f"; first: {detail}" if detail else ""))  # fmt: skip
    if lines:
        say("failed results: " + "\n  ".join(["", *lines]).lstrip("\n "))
        raise typer.Exit(EXIT_FAILED_RESULTS)


@contextlib.contextmanager
def progress_bar(settings: Settings, tasks: Mapping[str, int],
                 units: Mapping[str, str] | None = None) -> Iterator[Any]:
    """Show a progress bar on stderr with one line per task; yield ``update(name, done, total)``.

    The bar is drawn only when stderr is a terminal (nothing is written otherwise).

    Parameters
    ----------
    settings : Settings
        No bar when quiet.
    tasks : mapping of str to int
        Task name to its number of steps (trajectories).
    units : mapping of str to str, optional
        Task name to the word shown after its count (default ``"trajectories"``).
    """
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        SpinnerColumn,
        TextColumn,
        TimeElapsedColumn,
    )

    console = stderr()
    if not settings.quiet and not console.is_terminal:  # piped: plain lines, not a bar
        with compile_notices(settings), _plain_progress(tasks, units) as update:
            yield update
        return
    bar = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("{task.fields[unit]}"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=settings.quiet or not console.is_terminal,
    )
    words = dict(units or {})
    def add(name: str, total: int) -> Any:  # the description is rich markup: cleaned and escaped
        from rich.markup import escape

        return bar.add_task(escape(clean_text(name)), total=total, unit=clean_text(words.get(name, "trajectories")))

    ids = {name: add(name, total) for name, total in tasks.items()}

    def update(name: str, done: int, total: int) -> None:
        if name not in ids:
            ids[name] = add(name, total)
        bar.update(ids[name], completed=done, total=total)

    with bar, compile_notices(settings):
        yield update


@contextlib.contextmanager
def _plain_progress(tasks: Mapping[str, int],
                    units: Mapping[str, str] | None) -> Iterator[Any]:
    """Progress as plain lines on stderr (for a pipe or a log file): ``name: done/total unit``
    at the start, then every 10 % or 10 s, and at the end of each task."""
    import time

    words = dict(units or {})
    last: dict[str, tuple[float, float]] = {}  # name -> (time, fraction) of the last line

    def line(name: str, done: int, total: int) -> None:
        say(f"{name}: {done}/{total} {words.get(name, 'trajectories')}", limit=TEXT_LIMIT)
        sys.stderr.flush()

    def update(name: str, done: int, total: int) -> None:
        now, fraction = time.monotonic(), done / total if total else 1.0
        then, shown = last.get(name, (-1e9, -1.0))
        if done >= total or fraction - shown >= 0.1 or now - then >= 10.0:
            if (then, shown) != (now, fraction):
                line(name, done, total)
            last[name] = (now, fraction)

    for name, total in tasks.items():
        update(name, 0, total)
    yield update


class _StderrHandler(logging.Handler):
    """logging handler writing each record as one line on the current ``sys.stderr`` (looked
    up at each record: test runners swap it)."""

    def emit(self, record: logging.LogRecord) -> None:
        say(self.format(record))
        sys.stderr.flush()


@contextlib.contextmanager
def compile_notices(settings: Settings) -> Iterator[None]:
    """Show on stderr, unless quiet, that the integrator is being compiled (first run only)."""
    if settings.quiet:
        yield
        return
    logger = logging.getLogger("rotorlab.compile")
    handler = _StderrHandler(logging.INFO)
    logger.addHandler(handler)
    level = logger.level
    logger.setLevel(logging.INFO)
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(level)


@contextlib.contextmanager
def status(settings: Settings, text: str) -> Iterator[None]:
    """Show ``text`` on stderr while the block runs: a spinner on a terminal, one plain line
    otherwise (nothing when quiet)."""
    console = stderr()
    if settings.quiet:
        yield
        return
    if not console.is_terminal:
        say(text)
        sys.stderr.flush()
        with compile_notices(settings):
            yield
        return
    from rich.markup import escape

    with console.status(escape(clean_text(text, LINE_LIMIT))), compile_notices(settings):
        yield


def _fmt_angles(values: Sequence[float | None]) -> str:
    return "(" + ", ".join("-" if v is None else f"{v:.1f}" for v in values) + ")"


def _fmt_mm(value: float | None) -> str:
    return "-" if value is None else length(value)


def outcome_table(title: str, rows: Sequence[Mapping[str, Any]]) -> Any:
    """Return a rich table with one line per (speed, start configuration)."""
    from rich.table import Table

    table = Table(title=title, title_justify="left")
    for name, justify in (("speed (rpm)", "right"), ("ω/p", "right"), ("start (deg)", "left"),
                          ("deflection", "right"), ("of unbalance alone", "right"),
                          ("final angles (deg)", "left"), ("outcome", "left")):  # fmt: skip
        table.add_column(name, justify=justify)
    for r in rows:
        ratio = r["amplitude_ratio"]
        table.add_row(
            f"{r['speed_rpm']:.0f}", f"{r['speed_ratio']:.3g}", _fmt_angles(r["initial_ball_angles_deg"]),
            _fmt_mm(r["final_amplitude"]), "-" if ratio is None else relative(ratio),
            _fmt_angles(r["final_ball_angles_deg"]), r["outcome"],
        )  # fmt: skip
    return table


def summary_table(results: Mapping[str, Sequence[Mapping[str, Any]]]) -> Any:
    """Return a short rich table: per analysis and speed, how many starts ended how."""
    from rich.table import Table

    table = Table(title="Outcomes", title_justify="left")
    for name, justify in (("analysis", "left"), ("speed (rpm)", "right"), ("ω/p", "right"),
                          ("outcomes", "left"), ("deflection", "right")):  # fmt: skip
        table.add_column(name, justify=justify)
    for name, rows in results.items():
        by_speed: dict[float, list[Mapping[str, Any]]] = {}
        for r in rows:
            by_speed.setdefault(r["speed"], []).append(r)
        for group in by_speed.values():
            counts: dict[str, int] = {}
            for r in group:
                counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
            amps = [r["final_amplitude"] for r in group if r["final_amplitude"] is not None]
            low, high = (_fmt_mm(min(amps)), _fmt_mm(max(amps))) if amps else ("-", "-")
            span = low if low == high else f"{low} … {high}"
            text = ", ".join(f"{k} ×{v}" for k, v in counts.items())
            first = group[0]
            table.add_row(name, f"{first['speed_rpm']:.0f}", f"{first['speed_ratio']:.3g}", text, span)
    return table


def finite_or_none(value: float | None) -> float | None:
    """Return ``value`` if it is a finite float, else None (for JSON)."""
    return value if value is not None and math.isfinite(value) else None


def simulation_tables(results: Mapping[str, Any], rows: Mapping[str, Sequence[Mapping[str, Any]]]) -> list[Any]:
    """The console tables of simulations in ``rotorlab run``: one :func:`summary_table` of all."""
    return [summary_table({name: rows[name] for name in results})] if results else []


def simulation_detail_tables(results: Mapping[str, Any],
                             rows: Mapping[str, Sequence[Mapping[str, Any]]]) -> list[Any]:  # fmt: skip
    """The ``-v`` tables of simulations: one :func:`outcome_table` per analysis."""
    return [outcome_table(name, rows[name]) for name in results]
