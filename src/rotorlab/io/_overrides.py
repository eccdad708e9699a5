"""Overrides: set any key of a case before it is validated (the command line's ``--set KEY=VALUE``).

A key path is written the way validation errors write it (copy it from an error message):
``model.disc_mass``, ``model.balls[0].mass``, ``analysis[1].t_end``, ``analysis[0]."odd key"``.
A plain number as a path segment indexes a list too (``model.races.0.radius``). The value
replaces (or adds) that key in the raw case mapping, which is then validated exactly like the
file: a unit string (``"20 g"``) is read where the file takes a unit, a bad value or an unknown
key is reported with its key path and what is allowed.

Examples
--------
>>> parse_override("model.balls[0].mass=20 g")
('model.balls[0].mass', '20 g')
>>> parse_override("analysis[1].initial_ball_angles=[[0, 1.5]]")
('analysis[1].initial_ball_angles', [[0, 1.5]])
>>> apply_overrides({"model": {"balls": [{"mass": 0.03}]}}, {"model.balls.0.mass": "20 g"})
{'model': {'balls': [{'mass': '20 g'}]}}
"""

from __future__ import annotations

import copy
import re
import tomllib
from collections.abc import Iterable, Mapping
from typing import Any

from rotorlab.io._errors import CaseError, did_you_mean, format_path, format_value
from rotorlab.io._toml import check_key_depth, read_toml

__all__ = ["parse_key_path", "parse_override", "parse_value", "apply_overrides", "describe_overrides"]

_BARE = re.compile(r"[A-Za-z0-9_-]+")
_INDEX = re.compile(r"\[(\d+)\]")
_DIGITS = re.compile(r"\d+")


class _Digits(str):
    """A bare all-digit segment (``races.0``): a list index under a list, a key under a table."""


def parse_key_path(text: str) -> tuple[str | int, ...]:
    """Read a key path such as ``model.balls[1].mass`` into its keys (str) and indices (int).

    Parameters
    ----------
    text : str
        Dotted TOML keys (bare or quoted), each optionally followed by ``[N]`` list indices.

    Returns
    -------
    tuple of str or int
        A bare all-digit key (``races.0``) is returned as a str subclass that indexes a list
        when it meets one (see :func:`apply_overrides`).

    Raises
    ------
    ValueError
        Not a key path; the message says where it stops being one.

    Examples
    --------
    >>> parse_key_path('analysis[0]."odd key"')
    ('analysis', 0, 'odd key')
    >>> format_path(parse_key_path("model.races.0.balls[0].mass"))
    'model.races.0.balls[0].mass'
    """
    parts: list[str | int] = []
    pos, n = 0, len(text)
    while True:
        if pos < n and text[pos] in "\"'":
            end, key = _quoted(text, pos)
            parts.append(key)
            pos = end
        else:
            match = _BARE.match(text, pos)
            if match is None:
                what = f"at {text[pos:]!r}" if pos < n else "at the end"
                raise ValueError(f"not a key path {what}: expected a key (letters, digits, _ or -, "
                                 'or a quoted "key"), e.g. model.balls[0].mass')
            key = match.group()
            parts.append(_Digits(key) if _DIGITS.fullmatch(key) else key)
            pos = match.end()
        while (match := _INDEX.match(text, pos)) is not None:
            parts.append(int(match.group(1)))
            pos = match.end()
        if pos == n:
            check_key_depth(parts)
            return tuple(parts)
        if text[pos] != ".":
            raise ValueError(f"not a key path at {text[pos:]!r}: keys are separated by '.', list "
                             "entries are written [N], e.g. model.balls[0].mass")
        pos += 1


def _quoted(text: str, pos: int) -> tuple[int, str]:
    quote = text[pos]
    i = pos + 1
    while i < len(text) and text[i] != quote:
        i += 2 if quote == '"' and text[i] == "\\" else 1
    if i >= len(text):
        raise ValueError(f"not a key path at {text[pos:]!r}: the quoted key is not closed")
    try:
        key = tomllib.loads(f"k = {text[pos:i + 1]}")["k"]
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"not a key path at {text[pos:i + 1]!r}: {exc}") from None
    return i + 1, key


def parse_value(text: str) -> Any:
    """Read a value as a TOML value; a bare word or a number with a unit stays a string.

    ``0.02``, ``3``, ``true``, ``[1, 2]``, ``"20 g"`` and ``{profile = "constant"}`` are TOML
    values; ``20 g``, ``2400rpm`` and ``fixed`` are not, and are read as the strings they are
    (the case file's unit syntax then applies).

    Raises
    ------
    ValueError
        Empty, or it starts like a TOML string, array or table but is not a valid one.

    Examples
    --------
    >>> parse_value("1e-3"), parse_value("2400 rpm"), parse_value('"30 deg"'), parse_value("[0, 90]")
    (0.001, '2400 rpm', '30 deg', [0, 90])
    """
    stripped = text.strip()
    if not stripped:
        raise ValueError("no value after '=' (give a number, a string such as 20 g, true/false or a [list])")
    try:
        return read_toml(f"v = {stripped}")["v"]
    except tomllib.TOMLDecodeError as exc:
        if stripped[0] in "[{\"'":
            reason = re.sub(r"\s*\((at line \d+, column \d+|at end of document)\)\s*$", "", str(exc))
            raise ValueError(f"not a TOML value ({reason.lower()})") from None
        return stripped


def parse_override(text: str, option: str = "--set") -> tuple[str, Any]:
    """Split ``KEY=VALUE`` into the key path (as written) and the value (see :func:`parse_value`).

    Raises
    ------
    CaseError
        No ``=``, a key that is not a key path, or a value that is not readable; the message
        names the option and the text.
    """
    key, sep, value = _split(text)
    shown = text if len(text) <= 120 else f"{text[:120]}... ({len(text)} characters)"
    head = f"{option} {shown}: "
    if not sep:
        raise CaseError(head + "give KEY=VALUE, with KEY a key path of the case file as in its error "
                        "messages, e.g. model.balls[0].mass=20g")  # fmt: skip
    try:
        parse_key_path(key.strip())
        return key.strip(), parse_value(value)
    except ValueError as exc:
        raise CaseError(head + str(exc)) from None


def _split(text: str) -> tuple[str, str, str]:
    """Split at the first '=' outside a quoted key."""
    quote = ""
    for i, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = ""
        elif ch in "\"'":
            quote = ch
        elif ch == "=":
            return text[:i], "=", text[i + 1:]
    return text, "", ""


def describe_overrides(overrides: Mapping[Any, Any]) -> list[str]:
    """One ``key.path = value`` line per override (value as TOML would write it)."""
    return [f"{format_path(_path(k))} = {format_value(v)}" for k, v in overrides.items()]


def _path(key: str | Iterable[str | int]) -> tuple[str | int, ...]:
    if isinstance(key, str):
        return parse_key_path(key)
    check_key_depth(tuple(key))
    return tuple(key)


def apply_overrides(data: Mapping[str, Any], overrides: Mapping[Any, Any], origin: str = "<case>") -> dict[str, Any]:
    """Return a copy of a raw case mapping with the overrides set, before any validation.

    Parameters
    ----------
    data : mapping
        The parsed TOML document (not modified).
    overrides : mapping
        Key path (str such as ``"model.balls[0].mass"``, or a tuple of keys and indices) to its
        new value (a Python value as TOML would give it: number, str with or without a unit,
        bool, list, dict). Applied in order; a missing table on the way is created.
    origin : str, optional
        For messages.

    Returns
    -------
    dict

    Raises
    ------
    CaseError
        A key path that is not one, or that runs into a value or past the end of a list (every
        such problem, one line each, naming the key path, the value and what is allowed).
    """
    doc: dict[str, Any] = copy.deepcopy(dict(data))
    problems = []
    for key, value in overrides.items():
        try:
            path = _path(key)
        except ValueError as exc:
            problems.append(f"{key} = {format_value(value)}: {exc}")
            continue
        if not path:
            problems.append(f"(empty key path) = {format_value(value)}: give a key path, e.g. model.disc_mass")
            continue
        problem = _set(doc, path, copy.deepcopy(value))
        if problem:
            problems.append(f"{format_path(path)} = {format_value(value)}: {problem}")
    if problems:
        count = f"{len(problems)} problem" + ("s" if len(problems) != 1 else "")
        message = f"cannot set keys of {origin} ({count}):\n" + "\n".join(f"  {p}" for p in problems)
        raise CaseError(message, problems, origin)
    return doc


def _set(doc: dict[str, Any], path: tuple[str | int, ...], value: Any) -> str:
    """Set ``value`` at ``path``; return what is wrong ("" if it was set)."""
    node: Any = doc
    for depth, part in enumerate(path):
        where = format_path(path[:depth]) or "the case"
        last = depth == len(path) - 1
        if isinstance(node, list) and isinstance(part, (int, _Digits)):
            index = int(part)
            if index >= len(node):
                return (f"{where} has {len(node)} entr{'y' if len(node) == 1 else 'ies'}: give an index from 0 "
                        f"to {len(node) - 1}" if node else f"{where} is an empty list: nothing to set")  # fmt: skip
            if last:
                node[index] = value
                return ""
            node = node[index]
        elif isinstance(node, list):
            return f"{where} is a list: give an entry's index, e.g. {where}[0].{part}"
        elif isinstance(node, dict) and not isinstance(part, int):
            key = str(part)
            if last:
                node[key] = value
                return ""
            if key not in node:
                if isinstance(path[depth + 1], int):
                    hint = did_you_mean(key, [str(k) for k in node])
                    keys = ", ".join(str(k) for k in node) or "none"
                    return (f"{format_path(path[:depth + 1])} is not in the case, so it has no entry "
                            f"[{path[depth + 1]}]" + (f"; {hint}" if hint else "") + f" (keys of {where}: {keys})")
                node[key] = {}
            node = node[key]
        elif isinstance(node, dict):
            return f"{where} is a table, not a list: give a key instead of [{part}]"
        else:
            return f"{where} = {format_value(node)} is a single value, not a table or list: cannot set a key inside it"
    return ""  # pragma: no cover - the loop returns on the last part
