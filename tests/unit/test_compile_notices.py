"""The compile notices (issue 24): a compile started by a case names the case and the analysis,
not an internal module, and says how long it took when it is done."""

import logging
import re

import numpy as np
import xarray
from numba import njit

from rotorlab._compile_cache import compile_label, compiling_for
from rotorlab.analyses import _case
from rotorlab.integrate._drivers import compiled
from rotorlab.io import load_case


def test_a_case_names_its_compiles(monkeypatch):
    seen, models = [], []

    def spy(case_model, analysis, progress=None, model=None):
        seen.append(compiling_for())
        models.append(model)
        return xarray.Dataset()

    monkeypatch.setattr(_case, "run_analysis", spy)
    case = load_case("autobalancer")
    _case.run_case(case)
    assert seen == [f"case '{case.name}', analysis '{a.name}'" for a in case.analyses]
    assert models[0].n_balls == 2 and all(m is models[0] for m in models)  # built once, handed down
    assert compiling_for() is None  # only while the case runs
    with compile_label("case 'x'"):
        assert compiling_for() == "case 'x'"
    assert compiling_for() is None


def test_an_announced_compile_says_its_elapsed_time_once(caplog):
    @njit(nogil=True)
    def worker(counter):
        counter[0] += 1

    ns = {"_ANNOUNCED": "8-lane integrator for case 'x', analysis 'y'"}
    args = (np.zeros(1, dtype=np.int64),)
    with caplog.at_level(logging.INFO, logger="rotorlab.compile"):
        compiled(ns, worker, args)
        compiled(ns, worker, args)  # compiled already: nothing more to say
    assert len(caplog.messages) == 1
    assert re.fullmatch(r"compiled the 8-lane integrator for case 'x', analysis 'y' in \d+ s", caplog.messages[0])
    assert "_ANNOUNCED" not in ns and len(worker.signatures) == 1
    caplog.clear()

    @njit(nogil=True)
    def other(counter):
        counter[0] += 2

    with caplog.at_level(logging.INFO, logger="rotorlab.compile"):
        compiled({}, other, args)  # loaded from numba's cache or not announced: silent
    assert caplog.messages == [] and len(other.signatures) == 1
