"""rotorlab: dynamics of centrifuge rotors and automatic (passive) balancers.

Subpackages are imported lazily (``rotorlab.integrate`` is loaded on first access), so that
``import rotorlab`` and ``rotorlab --version`` stay fast: nothing compiles at import.
"""

from __future__ import annotations

import importlib
from typing import Any

from rotorlab._version import __version__

_SUBMODULES = {"contact", "integrate", "models", "io", "plot", "report", "analyses", "linear", "steady", "explore"}

__all__ = ["__version__", *sorted(_SUBMODULES)]


def __getattr__(name: str) -> Any:
    if name in _SUBMODULES:
        return importlib.import_module(f"rotorlab.{name}")
    raise AttributeError(f"module 'rotorlab' has no attribute {name!r}")
