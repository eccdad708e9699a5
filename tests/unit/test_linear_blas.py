"""``single_threaded_blas`` limits every loaded BLAS to one thread and restores the counts, also
when nested or entered from several threads at once (the last to leave restores)."""

from __future__ import annotations

import threading

import numpy as np
import scipy.linalg  # noqa: F401 - loaded, as by rotorlab.linear, before the first use
from threadpoolctl import threadpool_info  # reads the thread counts back

from rotorlab.linear._blas import single_threaded_blas


def _counts() -> list[int]:
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_limit_and_restore():
    np.linalg.eigh(np.eye(3))  # BLAS loaded
    before = _counts()
    with single_threaded_blas():
        assert set(_counts()) <= {1}
        with single_threaded_blas():
            assert set(_counts()) <= {1}
        assert set(_counts()) <= {1}  # the inner exit keeps the outer limit
    assert _counts() == before


def test_concurrent_users_share_one_limit():
    before = _counts()
    inside, leave = threading.Event(), threading.Event()

    def other():
        with single_threaded_blas():
            inside.set()
            leave.wait(10)

    worker = threading.Thread(target=other)
    worker.start()
    inside.wait(10)
    with single_threaded_blas():
        pass
    assert set(_counts()) <= {1}  # still limited: the other thread is inside
    leave.set()
    worker.join()
    assert _counts() == before
