"""The ``machine-knock`` analysis (washer-knock): does a balancer machine strike its housing during a
run-up, over random ball starts, against ball damping.

What is checked: the bounds (a clearance smaller than the no-balls run-up's own vibration is struck
in every run, one far larger never), the 95 % interval is SciPy's Wilson interval of the counts,
the same seeded starts serve every damping, and the result does not depend on the number of threads.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.stats import binomtest

from rotorlab.analyses._knock import knock_rows, machine_knock
from rotorlab.io import load_case
from rotorlab.io._machine_spec import build_machine


@pytest.fixture(scope="module")
def washer():
    return build_machine(load_case("washer-knock").model)


def test_a_tight_clearance_is_always_struck_and_a_wide_one_never(washer):
    kw = dict(t_end=4.0, ball_damping=[0.005, 0.05], starts=4, seed=3)
    tight = machine_knock(replace(washer, clearances=(replace(washer.clearances[0], gap=1e-3),)), **kw)
    wide = machine_knock(replace(washer, clearances=(replace(washer.clearances[0], gap=0.1),)), **kw)
    assert np.all(tight.status.values == 0) and np.all(wide.status.values == 0)
    # without balls the tub passes its critical speed (25 rad/s at ~2 s) with more than 1 mm of
    # vibration: it strikes a 1 mm clearance; 100 mm is far beyond anything it reaches
    assert tight.attrs["no_balls_impacts"] > 0 and wide.attrs["no_balls_impacts"] == 0
    assert tight.contact_probability.values.tolist() == [1.0, 1.0]
    assert wide.contact_probability.values.tolist() == [0.0, 0.0] and np.all(wide.largest_impulse.values == 0.0)
    assert np.all(tight.largest_impulse.values > 0.0)
    # the least margin: 0 where a run touched; else the gap less the largest excursion, read from
    # 2000 samples and checked against an independent run of one start saved 20 times more densely
    assert np.all(tight.least_margin.values == 0.0)
    assert all(row["least_margin"] == 0.0 for row in knock_rows(tight))
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    wide_machine = replace(washer, clearances=(replace(washer.clearances[0], gap=0.1),))
    angles = np.random.default_rng(3).uniform(0.0, 2.0 * np.pi, (4, wide_machine.n_balls))
    params = wide_machine.to_array()
    kb = wide_machine.layout.offsets["balls"]
    for b in range(wide_machine.n_balls):
        params[kb + 4 * b + 3] = 0.05
    dense = solve_ensemble(wide_machine, wide_machine.initial_state(angles[2])[None], (0.0, 4.0),
                           params=params[None], save_at=SaveAt(ts=np.linspace(0.0, 4.0, 40001)),
                           control=StepControl(rtol=1e-8, atol=1e-10), max_events_recorded=0)
    w = wide_machine.gap_vector(dense.ys[0])
    exact = 0.1 - np.hypot(w[:, 0], w[:, 1]).max()
    sampled = float(wide.least_margin.values[1, 2])
    assert 0.0 < exact <= sampled <= exact + 1e-3 * (0.1 - exact)
    assert knock_rows(wide)[1]["least_margin"] == pytest.approx(float(np.min(wide.least_margin.values[1])))
    for ds in (tight, wide):
        for i, row in enumerate(knock_rows(ds)):
            hits = int(round(row["contact_probability"] * row["runs"]))
            lo, hi = binomtest(hits, row["runs"]).proportion_ci(0.95, method="wilson")
            assert (row["probability_low"], row["probability_high"]) == pytest.approx((lo, hi), abs=1e-12)
    # the report's verdict leads with the choice and the confidence 4 starts give (Wilson, 0 of 4:
    # below 3.84 / 7.84 = 49 %), and says when no damping keeps the run-up clear
    from rotorlab.report._knock import knock_findings

    verdict = knock_findings(wide, knock_rows(wide)).verdict
    assert verdict == ("Choose a ball damping of 0.005, 0.05 N m s/rad: no run-up touched the housing there (0 of 4 "
                       "random ball starts; contact probability below 49 % with 95 % confidence, more starts narrow "
                       "this). Without balls the run-up stays clear.")
    verdict = knock_findings(tight, knock_rows(tight)).verdict
    assert verdict.startswith("Every ball damping tried lets some run-ups touch the housing; the fewest at ")
    assert "touched in 100 % of the run-ups, hardest at " in verdict
    assert verdict.endswith(f"Without balls it strikes {int(tight.attrs['no_balls_impacts'])} times (largest impulse "
                            f"{tight.attrs['no_balls_peak_impulse']:.3g} N s).")


def test_knock_runs_are_seeded_and_independent_of_threads(washer):
    kw = dict(t_end=3.0, ball_damping=[0.02, 0.2], starts=3, seed=7)
    a = machine_knock(washer, threads=1, **kw)
    b = machine_knock(washer, threads=2, **kw)
    for name in ("impacts", "peak_impulse", "status", "initial_ball_angle"):
        assert np.array_equal(a[name].values, b[name].values), name
    rng = np.random.default_rng(7)
    assert np.array_equal(a.initial_ball_angle.values, rng.uniform(0.0, 2.0 * np.pi, (3, 2)))


def test_bad_knock_arguments_are_refused(washer):
    with pytest.raises(ValueError, match=r"ball_damping must be one or more finite numbers >= 0"):
        machine_knock(washer, t_end=1.0, ball_damping=[-1.0])
    with pytest.raises(ValueError, match="needs a machine with a clearance"):
        machine_knock(replace(washer, clearances=()), t_end=1.0, ball_damping=[0.1])
    with pytest.raises(ValueError, match="needs balls"):
        machine_knock(replace(washer, races=()), t_end=1.0, ball_damping=[0.1])


def test_knock_run_ups_say_where_they_end_and_a_longer_run_up_settles_the_unsettled(washer):
    """Each knock run-up is labelled where it ends: at 4 s the tub is still spinning up (41 rad/s,
    its motor's no-load speed is far above), so no run is judged, every one is *not settled* and
    the findings say the run-up is too short; a run-up of 40 s (an independent re-simulation of the
    same seeded starts) ends balanced from every start at 0.05 N m s/rad, the share 4 of 4 with
    SciPy's Wilson interval."""
    from rotorlab.report._knock import knock_findings

    wide = replace(washer, clearances=(replace(washer.clearances[0], gap=0.1),))
    kw = dict(ball_damping=[0.005, 0.05], starts=4, seed=3)
    short = machine_knock(wide, t_end=4.0, **kw)
    assert np.all(short.outcome.values == "not settled")  # the ramp goes on: no verdict yet
    assert short.attrs["final_speed"] == pytest.approx(41.05, rel=1e-3)
    numbers = knock_findings(short, knock_rows(short)).numbers
    assert any("were still spinning up at 4 s: too short for their verdict" in n for n in numbers)
    long = machine_knock(wide, t_end=40.0, **kw)
    assert np.all(long.outcome.values[1] == "balanced")
    row = knock_rows(long)[1]
    assert row["outcomes"] == {"balanced": 4} and row["balanced_share"] == 1.0
    lo, hi = binomtest(4, 4).proportion_ci(0.95, method="wilson")
    assert (row["balanced_low"], row["balanced_high"]) == pytest.approx((lo, hi), abs=1e-12)
    assert np.all(long.impacts.values == 0)  # the wide clearance is never struck
