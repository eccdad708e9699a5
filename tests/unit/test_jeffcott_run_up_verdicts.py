"""Run-up verdicts of the Jeffcott rotor with balls (issue 26 item 5), judged by the machine
run-up's functions on ``model.machine``: the share balanced at the end of the ramp with its
Wilson interval, *not settled* starts with their estimated time to balance, the transient peak at
the critical speed with the order-statistic interval of its median, all checked against a longer
independent re-simulation; and the shortfall of peaks read from coarse saves, said in the output.

The case is ``zhakash-k2`` (regime "enough", the doctest of :func:`rotorlab.steady.run_up`, the
same compiled driver) on a 1 s ramp from 0.3 p to 2.5 p: at 2 s five of the twelve starts still
converge to balance, the others' balls are left circling (non-synchronous).
"""

import math

import numpy as np
import pytest
from scipy import stats

from rotorlab.analyses._run_up_verdicts import PEAK_ACCURACY, jeffcott_run_up_verdicts
from rotorlab.analyses._steady import _run_up_rows
from rotorlab.explore._outcome import BALANCED_FRACTION
from rotorlab.models import LinearRamp
from rotorlab.report._findings import _run_up as run_up_findings
from rotorlab.steady import run_up, steady_case

CASE = steady_case("zhakash-k2")
MODEL = CASE.model("enough")
P = CASE.critical_speed()
RAMP = LinearRamp(0.3 * P, 2.5 * P, 1.0)
DT = 2e-4  # short and long runs save at the same instants


def _run(t_end, starts, n_save=None):
    n = int(round(t_end / DT)) + 1 if n_save is None else n_save
    return jeffcott_run_up_verdicts(MODEL, run_up(MODEL, RAMP, t_end=t_end, initial_ball_angles=starts, n_save=n))


def test_jeffcott_run_up_shares_not_settled_and_peaks_against_a_longer_re_simulation():
    starts = np.random.default_rng(1).uniform(-np.pi, np.pi, (12, 2))
    short = _run(2.0, starts)
    rows = _run_up_rows(short)
    ens = rows[0]["ensemble"]
    out = [r["outcome"] for r in rows]
    assert ens["runs"] == 12 and ens["balanced"] == out.count("balanced")
    assert ens["not_settled"] == out.count("not settled") >= 3
    assert out.count("non-synchronous") >= 3
    ci = stats.binomtest(ens["balanced"], 12).proportion_ci(0.95, method="wilson")
    np.testing.assert_allclose([ens["balanced_share_low"], ens["balanced_share_high"]], [ci.low, ci.high],
                               rtol=1e-9, atol=1e-12)
    assert short.attrs["critical_speeds"][0] == pytest.approx(MODEL.critical_speed, rel=1e-9)
    # the independent longer run-up: every start not settled balances, the others keep their verdict
    longer = _run(6.0, starts)
    long_rows = _run_up_rows(longer)
    for r, q in zip(rows, long_rows):
        assert q["outcome"] == ("balanced" if r["outcome"] in ("not settled", "balanced") else r["outcome"]), r["ic"]
    assert long_rows[0]["ensemble"]["balanced"] == ens["balanced"] + ens["not_settled"]
    # ... and falls below the balanced threshold near the estimated time
    threshold = BALANCED_FRACTION * float(longer.reference_amplitude)
    ts = longer.time.values
    for r in rows:
        if r["outcome"] == "not settled":
            amp = longer.amplitude.values[r["ic"]]
            crossed = ts[np.flatnonzero(amp > threshold)[-1] + 1]
            assert 2.0 < r["settle_estimate_s"] and crossed == pytest.approx(r["settle_estimate_s"], rel=0.35)
    # the transient peak at p is over by 2 s: the longer run reads the same one at the same saves
    np.testing.assert_allclose(longer.critical_peak.values, short.critical_peak.values, rtol=1e-6)
    assert short.attrs["peak_saves_note"] == "" and float(short.critical_peak_underread.max()) <= PEAK_ACCURACY
    peaks = np.sort(short.critical_peak.values[:, 0])
    first = ens["critical_peaks"][0]
    j = next(j for j in range(peaks.size // 2, 0, -1) if 1 - 2 * stats.binom.cdf(j - 1, peaks.size, 0.5) >= 0.95)
    assert first["runs_passed"] == 12 and (first["low"], first["high"]) == (peaks[j - 1], peaks[peaks.size - j])
    assert first["median"] == pytest.approx(float(np.median(peaks)), rel=1e-12)
    said = run_up_findings(short, rows).numbers
    assert f"balanced at the end of the ramp in {ens['balanced']} of 12 run-ups" in said[2], said
    assert f"{ens['not_settled']} not settled" in said[2] and said[3].startswith("transient peak at")


def test_coarse_saves_under_read_the_transient_peak_and_say_so():
    starts = np.random.default_rng(2).uniform(-np.pi, np.pi, (6, 2))
    dense = _run(3.0, starts, n_save=40001)
    coarse = _run(3.0, starts, n_save=200)
    true = 1.0 - coarse.critical_peak.values[:, 0] / dense.critical_peak.values[:, 0]
    assert true.max() > 0.02  # the coarse saves read a peak more than 2 % low ...
    assert np.all(coarse.critical_peak_underread.values[:, 0] >= true)  # ... the estimate covers each shortfall
    note = coarse.attrs["peak_saves_note"]
    assert "200 saves are too coarse" in note, note
    assert note in run_up_findings(coarse, _run_up_rows(coarse)).numbers
    need = int(note.split("n_save = ")[1].split()[0])
    fine = _run(3.0, starts, n_save=need)  # the save count the note names reads every peak to 1 %
    shortfall = 1.0 - fine.critical_peak.values[:, 0] / dense.critical_peak.values[:, 0]
    assert shortfall.max() <= PEAK_ACCURACY and fine.attrs["peak_saves_note"] == ""
    assert not math.isnan(float(dense.critical_peak_underread.max()))
