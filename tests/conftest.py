"""Test-suite settings shared by every test module.

Hypothesis' per-example deadline (200 ms by default) measures wall time, which on a shared
2-core CI machine depends on what else runs (the first example also pays for imports): a
deadline failure there says nothing about rotorlab. Speed targets live in ``bench/``; here
every property test runs without a deadline.

Under CI (``CI`` set, as ``.ci/run`` is run) the examples are derandomised: a landing is judged on
the same examples every time, and exploring new ones is the job of local runs (which keep
Hypothesis' random search and its database of failing examples).

The compiled driver copies (``$ROTORLAB_CACHE_DIR``, by default the user's
``~/.cache/rotorlab``) go to a folder made for this run and removed at its end: a test run never
reads nor writes the user's cache, and every run is judged from a cold cache as CI judges it.
The test processes of ``pytest-xdist`` share the controller's folder (they inherit its
environment). A developer who wants to keep the compiled copies between local runs names a folder
of their own in ``ROTORLAB_TEST_CACHE_DIR`` (never removed by the tests).
"""

import os
import shutil
import tempfile

from hypothesis import settings

_RUN_CACHE = "_ROTORLAB_TEST_RUN_CACHE"  # set by the process that made the folder (the controller)


def pytest_configure(config):
    if os.environ.get("PYTEST_XDIST_WORKER"):
        return  # a test process: the controller's environment already names the folder
    keep = os.environ.get("ROTORLAB_TEST_CACHE_DIR")
    if keep:
        os.environ["ROTORLAB_CACHE_DIR"] = keep
        return
    folder = tempfile.mkdtemp(prefix="rotorlab-test-cache-")
    os.environ["ROTORLAB_CACHE_DIR"] = folder
    os.environ[_RUN_CACHE] = folder


def pytest_unconfigure(config):
    if os.environ.get("PYTEST_XDIST_WORKER"):
        return
    folder = os.environ.pop(_RUN_CACHE, None)
    if folder:
        shutil.rmtree(folder, ignore_errors=True)

settings.register_profile("rotorlab", deadline=None)
settings.register_profile("rotorlab-ci", deadline=None, derandomize=True, database=None)
settings.load_profile("rotorlab-ci" if os.environ.get("CI") else "rotorlab")


# The compile budget: most of the suite's time is numba compiling driver copies (one per model
# kernel set and driver kind, 15-70 CPU-s each), so a test that builds a model layout of its own
# costs more than its assertions. A run that builds more copies than this fails at its end,
# naming the copies; a new layout should reuse one of the canonical test models instead (or the
# budget is raised in the same commit, with the reason). The whole suite built 72 at 2026-11-28
# (session 10, fresh clone, CI=true).
DRIVER_COPY_BUDGET = 80


def _driver_copies(folder):
    drivers = os.path.join(folder, "drivers")
    if not os.path.isdir(drivers):
        return []
    return sorted(f for f in os.listdir(drivers) if f.endswith(".py") and f.startswith(("core_", "lanes")))


def pytest_sessionfinish(session, exitstatus):
    folder = os.environ.get(_RUN_CACHE)
    if os.environ.get("PYTEST_XDIST_WORKER") or not folder:
        return
    copies = _driver_copies(folder)
    session.config._rotorlab_copies = copies
    if len(copies) > DRIVER_COPY_BUDGET and session.exitstatus == 0:
        session.exitstatus = 1


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    copies = getattr(config, "_rotorlab_copies", None)
    if copies is None:
        return
    over = len(copies) > DRIVER_COPY_BUDGET
    terminalreporter.write_line(
        f"rotorlab compile budget: {len(copies)} driver copies built (budget {DRIVER_COPY_BUDGET})"
        + (": OVER BUDGET, this run fails; the copies: " + ", ".join(copies) if over else ""),
        red=over,
    )
