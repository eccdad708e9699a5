"""The one place TOML text is read (case files, ``--set`` values and keys): nesting bounded.

Python's TOML reader, pydantic and the error messages walk a document recursively, so an
absurdly nested file (``x = [[[[...]]]]``, a table header of thousands of dotted keys) or key
path would end in ``RecursionError``; every reader goes through :func:`read_toml` and every key
path through :func:`check_key_depth`, which refuse more than :data:`MAX_DEPTH` levels.
"""

from __future__ import annotations

import tomllib
from typing import Any

__all__ = ["MAX_DEPTH", "read_toml", "toml_depth_problem", "check_key_depth"]

#: Most levels of tables and lists a case may nest (its deepest key path, e.g.
#: ``model.races[0].balls[0].mass``, has 5).
MAX_DEPTH = 32


def read_toml(text: str) -> dict[str, Any]:
    """Parse TOML ``text``; raise ``tomllib.TOMLDecodeError`` for bad syntax and ValueError for
    nesting beyond :data:`MAX_DEPTH` levels.

    Examples
    --------
    >>> read_toml("a = [[1]]")
    {'a': [[1]]}
    >>> read_toml("a = " + "[" * 40 + "]" * 40)
    Traceback (most recent call last):
    ...
    ValueError: a[0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0]: nested deeper than 32 levels of tables and lists (at most 32)
    """
    try:
        doc = tomllib.loads(text)
    except RecursionError:
        raise ValueError(f"tables and lists nested far deeper than {MAX_DEPTH} levels (at most "
                         f"{MAX_DEPTH})") from None
    problem = toml_depth_problem(doc)
    if problem:
        raise ValueError(problem)
    return doc


def toml_depth_problem(doc: Any) -> str:
    """What is wrong with the nesting of a parsed document ("" if it is at most :data:`MAX_DEPTH`
    levels deep), naming the first key path that goes deeper (walked without recursion)."""
    from rotorlab.io._errors import format_path

    stack: list[tuple[Any, tuple[str | int, ...]]] = [(doc, ())]
    while stack:
        node, path = stack.pop()
        if len(path) > MAX_DEPTH:
            return (f"{format_path(path)}: nested deeper than {MAX_DEPTH} levels of tables and lists "
                    f"(at most {MAX_DEPTH})")
        if isinstance(node, dict):
            stack.extend((v, (*path, str(k))) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((v, (*path, i)) for i, v in enumerate(node))
    return ""


def check_key_depth(parts: tuple[Any, ...]) -> None:
    """Raise ValueError for a key path of more than :data:`MAX_DEPTH` keys and indices."""
    if len(parts) > MAX_DEPTH:
        raise ValueError(f"not a key path of a case: {len(parts)} keys and indices, at most {MAX_DEPTH}")
