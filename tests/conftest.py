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
