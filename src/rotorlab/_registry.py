"""A named table of registered values, read like a read-only mapping and extended by ``register``.

rotorlab keeps one table per kind of extension point: the case-file specs of model and analysis
types (:data:`rotorlab.io.MODEL_SPECS`, :data:`rotorlab.io.ANALYSIS_SPECS`), how each model type
is built and each analysis type runs (:data:`rotorlab.analyses.MODEL_TYPES`,
:data:`rotorlab.analyses.ANALYSIS_TYPES`) and how each analysis family is presented
(:data:`rotorlab.report.PRESENTATIONS`). Code that handles "any model" or "any analysis" looks
its entry up in these tables and never branches on a type string.

Nothing heavy is imported here (the command line imports it at start-up).
"""

from __future__ import annotations

import contextlib
import importlib
from collections.abc import Callable, Iterator, Mapping
from typing import Any, Generic, TypeVar

__all__ = ["Registry", "lazy"]

V = TypeVar("V")


class Registry(Mapping[str, V], Generic[V]):
    """A table of values by key: a read-only mapping plus :meth:`register`.

    Parameters
    ----------
    what : str
        What a key names, for messages (``"analysis type"``).
    on_change : callable, optional
        Called with no arguments after every registration or removal (e.g. to rebuild a
        schema that enumerates the entries).

    Examples
    --------
    >>> colours = Registry("colour")
    >>> colours.register("red", 0xFF0000)
    >>> colours["red"], list(colours)
    (16711680, ['red'])
    >>> colours["blue"]
    Traceback (most recent call last):
    ...
    KeyError: "no colour 'blue' (registered: red)"
    """

    def __init__(self, what: str, on_change: Callable[[], None] | None = None) -> None:
        self._what = what
        self._entries: dict[str, V] = {}
        self._on_change = on_change

    def __getitem__(self, key: str) -> V:
        try:
            return self._entries[key]
        except KeyError:
            known = ", ".join(self._entries) or "none"
            raise KeyError(f"no {self._what} {key!r} (registered: {known})") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)

    def __repr__(self) -> str:
        return f"Registry({self._what!r}: {', '.join(self._entries)})"

    def register(self, key: str, value: V, *, replace: bool = False) -> None:
        """Add ``value`` under ``key``.

        Raises
        ------
        ValueError
            ``key`` is taken and ``replace`` is false.
        """
        if key in self._entries and not replace:
            raise ValueError(f"{self._what} {key!r} is already registered")
        self._entries[key] = value
        if self._on_change is not None:
            self._on_change()

    def unregister(self, key: str) -> V:
        """Remove and return the value under ``key`` (KeyError if there is none)."""
        value = self[key]
        del self._entries[key]
        if self._on_change is not None:
            self._on_change()
        return value

    @contextlib.contextmanager
    def registered(self, key: str, value: V) -> Iterator[V]:
        """Register ``value`` for the duration of a ``with`` block (tests, plug-ins tried out)."""
        self.register(key, value)
        try:
            yield value
        finally:
            self.unregister(key)


class lazy:  # noqa: N801 - used like a function
    """A function named by ``"module:attribute"``, imported on its first call.

    Registry entries of the presentation layer name plotting and console functions this way,
    so that registering them imports neither matplotlib nor the command line.

    Examples
    --------
    >>> sqrt = lazy("math:sqrt")
    >>> sqrt(16.0), sqrt.target
    (4.0, 'math:sqrt')
    """

    def __init__(self, target: str) -> None:
        module, _, attribute = target.partition(":")
        if not module or not attribute:
            raise ValueError(f"lazy({target!r}): give 'module:attribute'")
        self.target = target
        self._function: Callable[..., Any] | None = None

    def resolve(self) -> Callable[..., Any]:
        """Import and return the function."""
        if self._function is None:
            module, _, attribute = self.target.partition(":")
            self._function = getattr(importlib.import_module(module), attribute)
        return self._function

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.resolve()(*args, **kwargs)

    def __repr__(self) -> str:
        return f"lazy({self.target!r})"
