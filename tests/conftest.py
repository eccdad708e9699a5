"""Test-suite settings shared by every test module.

Hypothesis' per-example deadline (200 ms by default) measures wall time, which on a shared
2-core CI machine depends on what else runs (the first example also pays for imports): a
deadline failure there says nothing about rotorlab. Speed targets live in ``bench/``; here
every property test runs without a deadline.

Under CI (``CI`` set, as ``.ci/run`` is run) the examples are derandomised: a landing is judged on
the same examples every time, and exploring new ones is the job of local runs (which keep
Hypothesis' random search and its database of failing examples).
"""

import os

from hypothesis import settings

settings.register_profile("rotorlab", deadline=None)
settings.register_profile("rotorlab-ci", deadline=None, derandomize=True, database=None)
settings.load_profile("rotorlab-ci" if os.environ.get("CI") else "rotorlab")
