"""Run-up verdicts over an ensemble of ball starts (issue 26 items 1 and 5): the share balanced
at the end of the ramp with its Wilson interval, *not settled* where the balls still converge
(with the estimated time to balance), and the transient peak at each critical speed passed with
an order-statistic interval of its median.

The machine is the motor-driven planar machine of ``test_machine_analyses`` (the same layout and
drive, so the same compiled driver) with balls heavy enough to balance (2 m l = 0.06 > U = 0.05
kg m) and a motor strong enough to pass the first critical speed (0.945 rad/s) to its no-load
speed 3 rad/s, where the balanced state's slowest mode decays at 0.0219 1/s (a 46 s time
constant): 200 s of ramp are too short for most starts.
"""

import math

import numpy as np
import pytest
from scipy import stats

from rotorlab._order_stats import median_interval
from rotorlab.analyses._machine_common import unbalance_amplitudes
from rotorlab.analyses._machine_run_up import _run_up_rows, run_up_starts
from rotorlab.analyses._verdict import MARGIN, round_up_horizon
from rotorlab.explore._outcome import BALANCED_FRACTION
from rotorlab.explore._settle import slowest_decay_rate
from rotorlab.linear import LinearSystem
from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Motor, Unbalance
from rotorlab.report._machine import _run_up_findings, machine_rows_table

S = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.05, 0.05, 0.0, 0.0]), G=np.zeros((4, 4)),
                 K=np.diag([1.0, 1.0, 5.0, 5.0]))
MACHINE = Machine(S, races=(BallRace(0, 0.5, (Ball(0.06, damping=0.005),) * 2),), unbalances=(Unbalance(0, 0.05),),
                  drive=Motor(0.02, polar_inertia=0.05, no_load_speed=3.0), n_modes=2)  # fmt: skip
STARTS = [list(a) for a in np.random.default_rng(1).uniform(-np.pi, np.pi, (16, 2))]
DT = 0.1  # both runs save every 0.1 s, so their peaks are read at the same instants


def test_run_up_shares_not_settled_and_peaks_against_a_longer_re_simulation():
    short = run_up_starts(MACHINE, STARTS, t_end=200.0, n_save=2001)
    rows = _run_up_rows(short)
    ens = rows[0]["ensemble"]
    out = [r["outcome"] for r in rows]
    runs = sum(o != "failed" for o in out)
    assert ens["runs"] == runs >= 12 and ens["balanced"] == out.count("balanced")
    assert ens["not_settled"] == out.count("not settled") >= 3 and ens["balanced"] >= 1
    # the share's interval is the Wilson interval of balanced / runs
    ci = stats.binomtest(ens["balanced"], runs).proportion_ci(0.95, method="wilson")
    np.testing.assert_allclose([ens["balanced_share_low"], ens["balanced_share_high"]], [ci.low, ci.high], rtol=1e-9)
    # a run not settled decays at the rate of the balanced state's slowest mode at its final speed
    late = [r for r in rows if r["outcome"] == "not settled"]
    w = late[0]["final_speed"]
    fixed = MACHINE.with_drive(ConstantSpeed(w))
    rate = slowest_decay_rate(fixed.linearize(fixed.balanced_state()).eigenvalues)
    np.testing.assert_allclose(rate, 0.0219, rtol=0.01)
    threshold = BALANCED_FRACTION * float(unbalance_amplitudes(MACHINE, w).max())
    for r in late:
        amp = max(r["residual_amplitude"].values())
        assert 200.0 < r["settle_estimate_s"] and amp > threshold
        assert math.log(amp / threshold) / (r["settle_estimate_s"] - 200.0) == pytest.approx(rate, rel=0.15)
    # an independent longer run-up to the horizon the findings name: every start not settled
    # balances there, every balanced one stays balanced
    need = round_up_horizon(MARGIN * max(r["settle_estimate_s"] for r in late))
    text = _run_up_findings(short, rows)
    assert "would do" in text.verdict and f"{need:g} s" in text.verdict
    assert f"{ens['balanced']} of {runs} run-ups" in text.verdict
    longer = run_up_starts(MACHINE, STARTS, t_end=need, n_save=int(round(need / DT)) + 1)
    long_rows = _run_up_rows(longer)
    for r, q in zip(rows, long_rows):
        assert q["outcome"] == ("failed" if r["outcome"] == "failed" else "balanced"), (r["ic"], r["outcome"])
    assert long_rows[0]["ensemble"]["balanced"] == ens["balanced"] + ens["not_settled"]
    # the transient peak at the critical speed is over by 200 s: the longer run gives the same one
    np.testing.assert_allclose(longer.critical_peak.values, short.critical_peak.values, rtol=1e-6)
    peaks = short.critical_peak.values[:, 0]
    peaks = np.sort(peaks[np.isfinite(peaks)])
    (first, second) = ens["critical_peaks"]
    assert first["runs_passed"] == peaks.size == runs and second["runs_passed"] == 0 and second["median"] is None
    # the order statistics x_(j), x_(n+1-j) with 1 - 2 P(B <= j - 1) >= 0.95 > 1 - 2 P(B <= j)
    j = next(j for j in range(peaks.size // 2, 0, -1) if 1 - 2 * stats.binom.cdf(j - 1, peaks.size, 0.5) >= 0.95)
    assert (first["low"], first["high"]) == (peaks[j - 1], peaks[peaks.size - j])
    assert first["coverage"] == pytest.approx(1 - 2 * stats.binom.cdf(j - 1, peaks.size, 0.5), rel=1e-12)
    assert first["median"] == pytest.approx(float(np.median(peaks)), rel=1e-12)
    header, body = machine_rows_table(short, rows)
    assert header[-2:] == ("settles by (s)", "transient peak at each critical speed passed (mm)")


@pytest.mark.parametrize("n", [7, 14, 40])
def test_the_median_interval_covers_the_median_as_often_as_it_says(n):
    # exponential draws (median ln 2): the interval holds it in a share of 20000 samples that
    # agrees with its stated coverage within 4 standard errors
    rng = np.random.default_rng(7)
    reps = 20000
    draws = rng.exponential(size=(reps, n))
    _, _, _, coverage = median_interval(draws[0])
    hits = sum(lo <= math.log(2.0) <= hi for lo, hi in (median_interval(d)[1:3] for d in draws))
    assert coverage >= 0.95
    assert abs(hits / reps - coverage) < 4 * math.sqrt(coverage * (1 - coverage) / reps)


def test_too_few_runs_for_the_interval_give_the_range_and_its_lower_coverage():
    med, lo, hi, cov = median_interval([5.0, 1.0, 3.0, np.nan, 2.0])
    assert (med, lo, hi) == (2.5, 1.0, 5.0) and cov == pytest.approx(1 - 2 * 0.5**4)
    assert all(math.isnan(v) for v in median_interval([]))
