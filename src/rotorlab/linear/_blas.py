"""Run small dense LAPACK problems on one OpenBLAS thread.

The linear analyses solve many small eigenproblems (tens of unknowns). OpenBLAS splits even
these over all its threads, and on a busy machine the threads wait for each other: a 28 x 28
Hermitian eigenproblem then takes 20 ms instead of 0.2 ms. :func:`single_threaded_blas` sets
every loaded OpenBLAS (NumPy's and SciPy's) to one thread for the duration of a ``with`` block
and restores the previous counts afterwards; with other BLAS libraries, or if none is found, it
does nothing. Nested and concurrent uses share one saved state (the first to enter saves it, the
last to leave restores it).

Why not threadpoolctl: ``threadpool_limits`` rescans the loaded libraries on every call (3 ms
here, against 0.2 ms for the eigenproblem it guards), and a reused ``ThreadpoolController``
(threadpoolctl 3.8) stopped applying its limit once one limit had been restored and another was
set from a second thread (tests/unit/test_linear_blas.py is the contract both must meet). The
two OpenBLAS calls below are all this needs.
"""

from __future__ import annotations

import contextlib
import ctypes
import threading
from collections.abc import Iterator

__all__ = ["single_threaded_blas"]

_NAMES = ("openblas_{}_num_threads", "scipy_openblas_{}_num_threads",
          "scipy_openblas_{}_num_threads64_", "openblas_{}_num_threads64_")
_lock = threading.Lock()
_state = {"depth": 0, "saved": [], "handles": None}


def _find_handles() -> list:
    handles = []
    try:
        with open("/proc/self/maps") as f:
            paths = {line.split()[-1] for line in f if "openblas" in line.lower()}
    except OSError:
        return handles
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for pattern in _NAMES:
            get = getattr(lib, pattern.format("get"), None)
            put = getattr(lib, pattern.format("set"), None)
            if get is not None and put is not None:
                get.restype = ctypes.c_int
                put.argtypes = [ctypes.c_int]
                handles.append((get, put))
                break
    return handles


@contextlib.contextmanager
def single_threaded_blas() -> Iterator[None]:
    """Limit OpenBLAS to one thread inside the ``with`` block (see module docstring)."""
    with _lock:
        if _state["handles"] is None:
            _state["handles"] = _find_handles()
        if _state["depth"] == 0:
            _state["saved"] = [get() for get, _ in _state["handles"]]
            for _, put in _state["handles"]:
                put(1)
        _state["depth"] += 1
    try:
        yield
    finally:
        with _lock:
            _state["depth"] -= 1
            if _state["depth"] == 0:
                for (_, put), n in zip(_state["handles"], _state["saved"]):
                    put(max(int(n), 1))
