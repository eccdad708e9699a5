"""Where generated kernel and driver modules are cached, and the lock their builders share.

Below every package (the machine's kernel writer, :mod:`rotorlab._kernels.machine_codegen`, and
the driver writer, :mod:`rotorlab.integrate._codegen`, both take it), so that neither imports
the other's package.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import threading
from collections.abc import Iterator
from pathlib import Path

__all__ = ["BUILD_LOCK", "cache_dir", "compiling_for", "compile_label"]

_FOR: contextvars.ContextVar[str | None] = contextvars.ContextVar("rotorlab_compiling_for", default=None)


def compiling_for() -> str | None:
    """What a compile started now is for, as people name it (``case 'pico21-balancer', analysis
    'vibration-one-race'``), or None outside :func:`compile_label`."""
    return _FOR.get()


@contextlib.contextmanager
def compile_label(text: str) -> Iterator[None]:
    """Name what the compiles started in this block are for (the compile notices show it)."""
    token = _FOR.set(text)
    try:
        yield
    finally:
        _FOR.reset(token)

# Generating and importing a copy is done by one thread at a time (threads of one process, e.g.
# the thread workers of rotorlab.sweep's local Dask cluster, may ask for the same driver at once):
# unlocked, a second thread was handed the module half-executed from sys.modules (KeyError
# 'integrate_lanes_serial') or ast.parse raised SystemError on Python 3.11 (4 thread workers of a
# fresh process: 6 failures in 6 runs). Reentrant: importing a copy may build another.
BUILD_LOCK = threading.RLock()


def cache_dir() -> Path | None:
    """The directory of the generated drivers, created if needed; None if it is not writable."""
    base = os.environ.get("ROTORLAB_CACHE_DIR")
    if base:
        cand = Path(base)
    else:
        xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        cand = Path(xdg) / "rotorlab"
    d = cand / "drivers"
    try:
        d.mkdir(parents=True, exist_ok=True)
        probe = d / f".write-test-{os.getpid()}"
        probe.write_text("ok")
        probe.unlink()
    except OSError:
        return None
    return d
