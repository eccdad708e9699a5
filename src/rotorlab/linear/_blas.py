"""Run small dense LAPACK problems on one BLAS thread.

The linear analyses solve many small eigenproblems (tens of unknowns). OpenBLAS splits even
these over all its threads, and on a busy machine the threads wait for each other: a 28 x 28
Hermitian eigenproblem then takes 20 ms instead of 0.2 ms. :func:`single_threaded_blas` limits
every loaded BLAS (NumPy's and SciPy's) to one thread for the duration of a ``with`` block and
restores the previous counts afterwards, through ``threadpoolctl``. Nested and concurrent uses
share one limit (the first to enter sets it, the last to leave restores it): threadpoolctl's own
contexts restore on exit, which would lift the limit while another thread is still inside.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["single_threaded_blas"]

_lock = threading.Lock()
_state: dict[str, Any] = {"depth": 0, "controller": None, "limiter": None}


@contextlib.contextmanager
def single_threaded_blas() -> Iterator[None]:
    """Limit BLAS to one thread inside the ``with`` block (see module docstring)."""
    with _lock:
        if _state["controller"] is None:
            from threadpoolctl import ThreadpoolController

            _state["controller"] = ThreadpoolController()  # finds the loaded libraries once
        if _state["depth"] == 0:
            _state["limiter"] = _state["controller"].limit(limits=1, user_api="blas")
        _state["depth"] += 1
    try:
        yield
    finally:
        with _lock:
            _state["depth"] -= 1
            if _state["depth"] == 0:
                _state["limiter"].restore_original_limits()
                _state["limiter"] = None
