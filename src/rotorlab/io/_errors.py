"""The one exception of the case-file layer and the helpers that word its messages.

Every problem with a case file (syntax, unknown keys, wrong units, values out of range, keys that
contradict each other) is reported as one :class:`CaseError` whose message lists each problem on a
line of its own, in the form ``key.path = value: what is allowed``.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["CaseError", "Issue", "IssueGroup", "format_path", "format_value", "did_you_mean"]

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


class CaseError(ValueError):
    """A case file (or a value meant for one) is invalid.

    Parameters
    ----------
    message : str
        The complete, user-facing message.
    problems : sequence of str, optional
        One line per problem (``key.path = value: what is allowed``). Defaults to the message.
    origin : str, optional
        The file, built-in case or ``"<string>"`` the problems were found in.

    Attributes
    ----------
    problems : tuple of str
        The individual problems, in the order they were found.
    origin : str
        Where the case came from.

    Examples
    --------
    >>> err = CaseError("model.disc_mass = -1: must be > 0 (kg)")
    >>> isinstance(err, ValueError), err.problems
    (True, ('model.disc_mass = -1: must be > 0 (kg)',))
    """

    def __init__(self, message: str, problems: Sequence[str] = (), origin: str = "") -> None:
        super().__init__(message)
        self.problems: tuple[str, ...] = tuple(problems) if problems else (message,)
        self.origin = origin


CaseError.__module__ = "rotorlab.io"  # tracebacks name the public path


@dataclass(frozen=True, slots=True)
class Issue:
    """One problem found by a cross-field check.

    Parameters
    ----------
    loc : tuple of str or int
        Key path relative to the object that found it, e.g. ``("initial_ball_angles", 2)``.
    message : str
        What is wrong and what is allowed.
    value : Any, optional
        The offending value, shown after the path when ``show_value`` is true. When the case
        came from a file, the value as written in the file is shown instead.
    show_value : bool, optional
        Whether to show ``= value`` after the key path.
    """

    loc: tuple[str | int, ...]
    message: str
    value: Any = None
    show_value: bool = True


class IssueGroup(ValueError):
    """Several :class:`Issue` raised together from inside a pydantic validator.

    pydantic wraps it into a ``value_error``; the case loader unpacks it into one line per
    issue, with the key path extended by each issue's ``loc``.

    Parameters
    ----------
    issues : iterable of Issue
        The problems found.
    """

    def __init__(self, issues: Iterable[Issue]) -> None:
        self.issues: tuple[Issue, ...] = tuple(issues)
        lines = []
        for issue in self.issues:
            path = format_path(issue.loc)
            head = path or "(case)"
            if issue.show_value and issue.loc:
                head = f"{head} = {format_value(issue.value)}"
            lines.append(f"{head}: {issue.message}")
        super().__init__("; ".join(lines))


def format_path(loc: Iterable[str | int]) -> str:
    """Write a key path the way a user would point at it in the TOML file.

    Parameters
    ----------
    loc : iterable of str or int
        Keys (str) and list indices (int).

    Returns
    -------
    str
        e.g. ``model.balls[1].mass``; keys that are not bare TOML keys are quoted.

    Examples
    --------
    >>> format_path(("model", "balls", 1, "mass"))
    'model.balls[1].mass'
    >>> format_path(("analysis", 0, "odd key"))
    'analysis[0]."odd key"'
    """
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            key = part if _BARE_KEY.match(part) else _quote(part)
            out += f".{key}" if out else key
    return out


def format_value(value: Any, limit: int = 80) -> str:
    """Write a value as it would appear in a TOML file, shortened to about ``limit`` characters.

    Parameters
    ----------
    value : Any
        A TOML value (str, int, float, bool, list, dict) or any object.
    limit : int, optional
        Longer renderings are cut and end with ``...``.

    Returns
    -------
    str

    Examples
    --------
    >>> format_value("12 furlongs"), format_value(float("nan")), format_value([True, -0.03])
    ('"12 furlongs"', 'nan', '[true, -0.03]')
    """
    text = _render(value)
    if len(text) > limit:
        text = text[: limit - 3] + "..."
    return text


def did_you_mean(word: str, options: Iterable[str]) -> str:
    """Return ``"did you mean 'x'?"`` for the closest option, or ``""`` if none is close.

    Examples
    --------
    >>> did_you_mean("rtoll", ["atol", "rtol", "n_save"])
    "did you mean 'rtol'?"
    """
    matches = difflib.get_close_matches(str(word), list(options), n=1, cutoff=0.6)
    return f"did you mean '{matches[0]}'?" if matches else ""


def _quote(text: str) -> str:
    out = ['"']
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _render(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return _quote(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return repr(value)
    if isinstance(value, Mapping):
        inner = ", ".join(f"{format_path((str(k),))} = {_render(v)}" for k, v in value.items())
        return "{" + inner + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_render(v) for v in value) + "]"
    return repr(value)
