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

__all__ = ["PEAK_BAND", "SETTLE_TAIL", "PEAK_ACCURACY", "ramp_end_settle", "settle_from_windows", "critical_peaks",
           "peak_underread", "saves_for_peak", "coarse_saves_note", "run_up_outcome", "run_up_ensemble",
           "jeffcott_run_up_verdicts"]

#: The transient peak at a critical speed w_c is taken while the speed lies in
#: [(1 - PEAK_BAND) w_c, (1 + PEAK_BAND) w_c].
PEAK_BAND = 0.15
#: The settle estimate at the ramp's end compares the vibration over the last SETTLE_TAIL of the
#: run with that over the two SETTLE_TAIL-long windows before it.
SETTLE_TAIL = 0.1
#: A run-up passes a critical speed when its final speed exceeds it by this factor.
PASS_MARGIN = 1.05
#: Accuracy the transient peaks are read to: a coarser save grid is said (:func:`coarse_saves_note`).
PEAK_ACCURACY = 0.01


def ramp_end_settle(machine, ts, ys, threshold: float) -> float:
    """Estimated time (s) at which a run-up's vibration falls below ``threshold`` (m), NaN unless
    it is still falling towards it at the end (over windows of :data:`SETTLE_TAIL` of the run
    ending at 80 %, 90 % and 100 % of it, the largest station's orbit amplitude)."""
    from rotorlab.analyses._machine_common import orbit_amplitude

    return settle_from_windows(ts, lambda sel: float(orbit_amplitude(machine, ys[sel]).max()), threshold)


def settle_from_windows(ts, window_amplitude, threshold: float) -> float:
    """:func:`ramp_end_settle` on any vibration measure: ``window_amplitude(sel)`` gives the
    vibration (m) over the saved times selected by the boolean mask ``sel``."""
    from rotorlab.explore._settle import settle_estimate

    ts = np.asarray(ts, dtype=float)
    t0, t1 = float(ts[0]), float(ts[-1])
    ends = t1 - SETTLE_TAIL * (t1 - t0) * np.array([2.0, 1.0, 0.0])
    amp = []
    for end in ends:
        sel = (ts >= end - SETTLE_TAIL * (t1 - t0) * (1 + 1e-12)) & (ts <= end * (1 + 1e-12))
        if sel.sum() < 2:
            return math.nan
        amp.append(float(window_amplitude(sel)))
    return float(settle_estimate(np.array([amp]), np.array([threshold]), ends)[0, -1])


def _band_saves(speeds, amplitude, critical_speeds, passed: int):
    """The largest station amplitude at each save, and per critical speed passed the indices of
    the saves within :data:`PEAK_BAND` of it (None for those not passed)."""
    w = np.abs(np.asarray(speeds, dtype=float))
    amp = np.asarray(amplitude, dtype=float).reshape(w.size, -1).max(axis=1)
    crit = np.ravel(np.asarray(critical_speeds, dtype=float))
    bands = [np.flatnonzero((w >= (1.0 - PEAK_BAND) * c) & (w <= (1.0 + PEAK_BAND) * c)) if k < int(passed) else None
             for k, c in enumerate(crit)]  # fmt: skip
    return amp, bands


def critical_peaks(speeds, amplitude, critical_speeds, passed: int) -> np.ndarray:
    """Largest displacement of any station from the axis (m) while the speed is within
    :data:`PEAK_BAND` of each critical speed, for the first ``passed`` of them; NaN for the
    others (not passed). Read from the saved states: :func:`peak_underread` estimates by how
    much it falls short of the peak between them."""
    amp, bands = _band_saves(speeds, amplitude, critical_speeds, passed)
    return np.array([amp[i].max() if i is not None and i.size else np.nan for i in bands])


def peak_underread(speeds, amplitude, critical_speeds, passed: int) -> np.ndarray:
    """Estimated relative shortfall of each :func:`critical_peaks` value below the peak between
    the saves (-): ``(a - a2) / a`` with ``a`` the peak of all saves in the band and ``a2`` the
    lower of the peaks of every other save (odd and even ones), the peak a grid of twice the
    interval reads. A peak's shortfall falls at least in proportion to the save interval (as its
    square on a smooth envelope), so the step from ``2 h`` to ``h`` is at least the shortfall
    left at ``h``; with the envelope's fast beats (a whirl passing a resonance) this holds only
    on average, which the tests check against dense re-simulations. NaN where the critical speed
    was not passed; ``inf`` with fewer than 4 saves in the band (not bounded)."""
    amp, bands = _band_saves(speeds, amplitude, critical_speeds, passed)
    out = np.full(len(bands), np.nan)
    for k, idx in enumerate(bands):
        if idx is None:
            continue
        if idx.size < 4:
            out[k] = math.inf
            continue
        top = float(amp[idx].max())
        half = min(float(amp[idx[0::2]].max()), float(amp[idx[1::2]].max()))
        out[k] = (top - half) / top if top > 0 else 0.0
    return out


def saves_for_peak(n_save: int, underread, accuracy: float = PEAK_ACCURACY) -> int:
    """Saved points that would read every transient peak to ``accuracy`` (the shortfall taken
    to fall in proportion to the save interval, with a 10 % margin): ``n_save`` itself when it
    does already, 0 when a peak is not bounded (too few saves near it to tell)."""
    u = np.asarray(underread, dtype=float)
    u = u[~np.isnan(u)]
    if u.size and not np.all(np.isfinite(u)):
        return 0
    worst = float(u.max()) if u.size else 0.0
    return int(n_save) if worst <= accuracy else int(math.ceil(n_save * worst / accuracy * 1.1))


def coarse_saves_note(n_save: int, underread, accuracy: float = PEAK_ACCURACY) -> str:
    """What the findings say when the saves are too coarse for the transient peaks (else "")."""
    u = np.asarray(underread, dtype=float)
    u = u[~np.isnan(u)]
    if not u.size or float(u.max()) <= accuracy:
        return ""
    need = saves_for_peak(n_save, u, accuracy)
    if not need:
        return (f"the {n_save} saves put fewer than 4 within {100 * PEAK_BAND:g} % of a critical speed "
                "passed: its transient peak is not bounded; save more often")
    return (f"the {n_save} saves are too coarse for the transient peaks: they may read up to "
            f"{100 * float(u.max()):.2g} % low; n_save = {need} reads them to {100 * accuracy:g} %")


def run_up_outcome(status: int, n_balls: int, captured_at: float, residual: float, reference: float,
                   final_speed: float, critical_speeds, tail_ball_angles, settle: float) -> str:
    """Where a run-up ended: "failed", "no balancer", "captured" (below a critical speed),
    "balanced" (``residual`` vibration at most BALANCED_FRACTION of the ``reference`` unbalance
    response at the final speed, above the first critical speed; at or below it "below critical
    speed": a machine that did not spin up is never balanced), "not settled" (its vibration still
    falling towards balance at the end, ``settle`` finite, :func:`ramp_end_settle`),
    "non-synchronous" (a ball turns more than half a turn relative to the rotor over
    ``tail_ball_angles``, shape (n_times, n_balls)) or "not balanced"."""
    from rotorlab.analyses._machine_common import BELOW_CRITICAL
    from rotorlab.explore._outcome import BALANCED_FRACTION
    from rotorlab.explore._settle import NOT_SETTLED

    if int(status) < 0:
        return "failed"
    if n_balls == 0:
        return "no balancer"
    if np.isfinite(captured_at):
        return "captured"
    if residual <= BALANCED_FRACTION * reference + 1e-15:
        crit = np.ravel(np.asarray(critical_speeds, dtype=float))
        return "balanced" if not crit.size or abs(float(final_speed)) > crit[0] else BELOW_CRITICAL
    if np.isfinite(settle):
        return NOT_SETTLED  # still converging towards balance at the ramp's end
    turn = np.ptp(np.unwrap(np.asarray(tail_ball_angles, dtype=float), axis=0), axis=0)
    return "non-synchronous" if np.any(turn > np.pi) else "not balanced"


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


def jeffcott_run_up_verdicts(model, ds, confidence: float = 0.95):
    """Give a :func:`rotorlab.steady.run_up` result the machine run-up's verdicts, judged on the
    model's machine (:attr:`rotorlab.models.JeffcottBalls.machine`: its balls-locked critical
    speeds and unbalance response) by the same functions as :func:`machine_run_up`.

    Adds over ``ic``: ``outcome`` (:func:`run_up_outcome`; a synchronised run that is not
    balanced names the steady motion it reached), ``passed`` (critical speeds the final speed
    exceeds by 5 %), ``settle_estimate`` (s), ``residual_amplitude`` (largest deflection over the
    last 10 % of the run, m), ``critical_peak`` and ``critical_peak_underread`` (ic, critical;
    m and -, :func:`critical_peaks`, :func:`peak_underread`); ``reference_amplitude`` (m, the
    locked unbalance response at the final speed); attrs ``critical_speeds`` (rad/s),
    ``n_save``, ``peak_accuracy``, ``peak_saves_note`` (:func:`coarse_saves_note`) and
    ``ensemble`` fields ``balanced_share`` / ``_low`` / ``_high`` (:func:`run_up_ensemble`).
    """
    from rotorlab.analyses._machine_common import structure_critical_speeds, unbalance_amplitudes
    from rotorlab.explore._outcome import BALANCED_FRACTION

    machine = model.machine
    ts, speed = ds.time.values, ds.speed.values
    amp = ds.amplitude.values
    final = float(speed[-1])
    crit = np.unique(np.round(structure_critical_speeds(machine, max_speed=None), 9))
    passed = int(np.sum(abs(final) > PASS_MARGIN * crit))
    reference = float(np.max(unbalance_amplitudes(machine, final)))
    threshold = BALANCED_FRACTION * reference
    tail = ts >= 0.9 * ts[-1]
    n_ic = amp.shape[0]
    settle, residual = np.full(n_ic, np.nan), amp[:, tail].max(axis=1)
    outcome = []
    for i in range(n_ic):
        if int(ds.status.values[i]) >= 0:
            settle[i] = settle_from_windows(ts, lambda sel, a=amp[i]: float(a[sel].max()), threshold)
        text = run_up_outcome(int(ds.status.values[i]), model.n_balls, math.nan, float(residual[i]), reference,
                              final, crit, ds.ball_angle.values[i][tail], float(settle[i]))
        motion = str(ds.final_motion.values[i])
        outcome.append(motion if text == "not balanced" and bool(ds.synchronised.values[i]) and motion != "none"
                       else text)
    peaks = np.array([critical_peaks(speed, amp[i], crit, passed) for i in range(n_ic)]).reshape(n_ic, crit.size)
    under = np.array([peak_underread(speed, amp[i], crit, passed) for i in range(n_ic)]).reshape(n_ic, crit.size)
    ds = ds.assign(
        outcome=(("ic",), np.array(outcome, dtype=str), {"units": "1", "long_name": "where the run-up ended"}),
        passed=(("ic",), np.full(n_ic, passed), {"units": "1", "long_name": "critical speeds passed"}),
        settle_estimate=(("ic",), settle, {"units": "s", "long_name": "estimated time to balance"}),
        residual_amplitude=(("ic",), residual, {"units": "m", "long_name": "largest deflection, last 10 %"}),
        reference_amplitude=((), reference, {"units": "m", "long_name": "locked unbalance response at the end"}),
        critical_peak=(("ic", "critical"), peaks, {"units": "m", "long_name": "transient peak at the critical speed"}),
        critical_peak_underread=(("ic", "critical"), under, {"units": "1", "long_name": "estimated shortfall of the peak"}),
    )  # fmt: skip
    ens = run_up_ensemble(outcome, peaks, crit, confidence)
    ds.attrs.update(critical_speeds=crit, n_save=int(ts.size), peak_accuracy=PEAK_ACCURACY,
                    peak_saves_note=coarse_saves_note(ts.size, under),
                    **{k: (math.nan if ens[k] is None else ens[k])
                       for k in ("balanced_share", "balanced_share_low", "balanced_share_high")})
    return ds
