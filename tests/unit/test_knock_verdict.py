"""The machine-knock verdict counts the starts behind each damping it recommends.

Review of the session-5 diff: the verdict said "0 of N random ball starts" with N the finished runs
of the first clear damping only; where a run failed at another clear damping, fewer starts stand
behind it (and its Wilson bound is the wider one the verdict quotes). Rows as
:func:`rotorlab.analyses._knock.knock_rows` makes them.
"""

from __future__ import annotations

from types import SimpleNamespace

from rotorlab.report._knock import _verdict

Z2 = 1.959963984540054**2  # Wilson interval, 95 %: 0 of n -> upper bound z^2 / (n + z^2)


def _row(damping: float, runs: int, failed: int) -> dict:
    n = runs - failed
    return {"ball_damping": damping, "runs": runs, "failed": failed, "contact_probability": 0.0,
            "probability_low": 0.0, "probability_high": Z2 / (n + Z2), "largest_impulse": None}


def test_the_verdict_counts_the_finished_starts_of_every_clear_damping():
    ds = SimpleNamespace(attrs={"no_balls_impacts": 0.0})
    same = _verdict(ds, [_row(0.01, 4, 0), _row(0.1, 4, 0)])
    assert "(0 of 4 random ball starts; contact probability below 49 % with 95 % confidence" in same
    # one run failed at 0.1: 3 starts stand behind it, and its bound (56 %) is the one quoted
    mixed = _verdict(ds, [_row(0.01, 4, 0), _row(0.1, 4, 1)])
    assert "(0 of 3 to 4 random ball starts; contact probability below 56 % with 95 % confidence" in mixed
    assert mixed.endswith("Without balls the run-up stays clear.")
