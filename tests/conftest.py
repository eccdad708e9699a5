"""Test-suite settings shared by every test module.

Hypothesis' per-example deadline (200 ms by default) measures wall time, which on a shared
2-core CI machine depends on what else runs (the first example also pays for imports): a
deadline failure there says nothing about rotorlab. Speed targets live in ``bench/``; here
every property test runs without a deadline.
"""

from hypothesis import settings

settings.register_profile("rotorlab", deadline=None)
settings.load_profile("rotorlab")
