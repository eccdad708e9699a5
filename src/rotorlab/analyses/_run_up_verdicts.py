"""Verdicts over an ensemble of machine run-ups: who balances by the end of the ramp, who is still
settling, and how hard each critical speed shook the machine on the way.

* :func:`ramp_end_settle`: a run-up whose vibration still falls towards balance at the end of the
  ramp is *not settled*, with its estimated time to balance
  (:func:`rotorlab.explore._settle.settle_estimate` on the vibration over the last three tenths
  of the run).
* :func:`critical_peaks`: the transient peak at each critical speed passed: the largest
  displacement of any station from the axis while the speed is within :data:`PEAK_BAND` of it.
* :func:`run_up_ensemble`: the share of run-ups balanced at the end with its Wilson interval
  (:mod:`rotorlab._wilson`), and per critical speed the median transient peak over the run-ups
  that passed it with its distribution-free order-statistic interval
  (:mod:`rotorlab._order_stats`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["PEAK_BAND", "SETTLE_TAIL", "ramp_end_settle", "critical_peaks", "run_up_ensemble"]

#: The transient peak at a critical speed w_c is taken while the speed lies in
#: [(1 - PEAK_BAND) w_c, (1 + PEAK_BAND) w_c].
PEAK_BAND = 0.15
#: The settle estimate at the ramp's end compares the vibration over the last SETTLE_TAIL of the
#: run with that over the two SETTLE_TAIL-long windows before it.
SETTLE_TAIL = 0.1


def ramp_end_settle(machine, ts, ys, threshold: float) -> float:
    """Estimated time (s) at which a run-up's vibration falls below ``threshold`` (m), NaN unless
    it is still falling towards it at the end (over windows of :data:`SETTLE_TAIL` of the run
    ending at 80 %, 90 % and 100 % of it, the largest station's orbit amplitude)."""
    from rotorlab.analyses._machine_common import orbit_amplitude
    from rotorlab.explore._settle import settle_estimate

    ts = np.asarray(ts, dtype=float)
    t0, t1 = float(ts[0]), float(ts[-1])
    ends = t1 - SETTLE_TAIL * (t1 - t0) * np.array([2.0, 1.0, 0.0])
    amp = []
    for end in ends:
        sel = (ts >= end - SETTLE_TAIL * (t1 - t0) * (1 + 1e-12)) & (ts <= end * (1 + 1e-12))
        if sel.sum() < 2:
            return math.nan
        amp.append(float(orbit_amplitude(machine, ys[sel]).max()))
    return float(settle_estimate(np.array([amp]), np.array([threshold]), ends)[0, -1])


def critical_peaks(speeds, amplitude, critical_speeds, passed: int) -> np.ndarray:
    """Largest displacement of any station from the axis (m) while the speed is within
    :data:`PEAK_BAND` of each critical speed, for the first ``passed`` of them; NaN for the
    others (not passed)."""
    w = np.abs(np.asarray(speeds, dtype=float))
    amp = np.asarray(amplitude, dtype=float).reshape(w.size, -1).max(axis=1)
    crit = np.ravel(np.asarray(critical_speeds, dtype=float))
    out = np.full(crit.size, np.nan)
    for k in range(min(int(passed), crit.size)):
        sel = (w >= (1.0 - PEAK_BAND) * crit[k]) & (w <= (1.0 + PEAK_BAND) * crit[k])
        if sel.any():
            out[k] = float(amp[sel].max())
    return out


def run_up_ensemble(outcomes, peaks, critical_speeds, confidence: float = 0.95) -> dict[str, Any]:
    """Summarise run-ups from many ball starts.

    Parameters
    ----------
    outcomes : sequence of str
        Each run-up's outcome (``"failed"`` runs are left out of the share).
    peaks : array_like, shape (n_runs, n_critical)
        :func:`critical_peaks` of each run-up (NaN: not passed).
    critical_speeds : array_like, shape (n_critical,)
        rad/s.

    Returns
    -------
    dict
        ``runs`` (run-ups that did not fail), ``balanced``, ``not_settled``, ``balanced_share`` with
        ``balanced_share_low`` / ``balanced_share_high`` (Wilson interval at ``confidence``; None
        without runs), ``confidence`` and ``critical_peaks``: per critical speed ``speed``
        (rad/s), ``runs_passed``, ``median``, ``low``, ``high`` (m; the order-statistic interval
        of the median) and ``coverage`` (its exact coverage, below ``confidence`` only with fewer
        than 6 runs at 95 %), None values where no run passed it.
    """
    from rotorlab._order_stats import median_interval
    from rotorlab._wilson import wilson_interval

    out = [str(o) for o in outcomes]
    runs = sum(o != "failed" for o in out)
    bal = sum(o == "balanced" for o in out)
    doc: dict[str, Any] = {"runs": runs, "balanced": bal, "not_settled": sum(o == "not settled" for o in out),
                           "confidence": confidence, "balanced_share": None, "balanced_share_low": None,
                           "balanced_share_high": None}  # fmt: skip
    if runs:
        lo, hi = wilson_interval(bal, runs, confidence)
        doc.update(balanced_share=bal / runs, balanced_share_low=float(lo), balanced_share_high=float(hi))
    table = np.asarray(peaks, dtype=float).reshape(len(out), -1)
    rows = []
    for k, w in enumerate(np.ravel(np.asarray(critical_speeds, dtype=float))):
        col = table[:, k] if k < table.shape[1] else np.empty(0)
        col = col[np.isfinite(col)]
        med, lo, hi, cov = median_interval(col, confidence) if col.size else (math.nan,) * 4
        rows.append({"speed": float(w), "runs_passed": int(col.size),
                     **{key: (float(v) if math.isfinite(v) else None)
                        for key, v in (("median", med), ("low", lo), ("high", hi), ("coverage", cov))}})
    doc["critical_peaks"] = rows
    return doc
