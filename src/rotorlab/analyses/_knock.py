"""The ``machine-knock`` analysis: will a machine with a balancer strike its housing while it runs up?

A balancer's balls start wherever they lay when the machine stopped, and until they settle they can
add to the unbalance instead of cancelling it. Over many random initial ball positions (a seeded
sample), each run-up with the model's drive is simulated with the clearance active (impacts located
and resolved, :class:`rotorlab.models.Clearance`), for every value of the balls' damping; the result
is, per damping, the probability that the rotor touches its housing at all (with its Wilson
interval) and the largest normal impulse of any impact, beside the same run-up without balls.

Every run of one damping and one start is independent and deterministic (the same starts for every
damping: common random numbers, so the curves compare dampings, not samples).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["machine_knock", "run_knock_analysis", "knock_rows", "knock_task_size"]

#: Evenly spaced samples over a run-up from which its least margin (gap less the largest
#: excursion of the clearance station) is read.
MARGIN_SAMPLES = 2000

#: Where each run-up ends is judged over windows of this many turns at the final speed ...
WINDOW_REVOLUTIONS = 2.0
#: ... sampled at this many states each. A run whose speed changed by more than STEADY_SPEED
#: (relative) from the first window's end to the last is still spinning up: not settled.
WINDOW_SAMPLES = 33
STEADY_SPEED = 0.01


def machine_knock(machine, *, t_end: float, ball_damping, starts: int = 32, seed: int = 0,
                  rtol: float = 1e-8, atol: float = 1e-10, threads: int | None = None,
                  progress: Callable[[int, int], None] | None = None):
    """Run the machine up from random ball positions for each ball damping; count contacts.

    Parameters
    ----------
    machine : Machine
        With a clearance and at least one ball.
    t_end : float
        Duration of each run-up (s).
    ball_damping : array_like, shape (n_d,)
        Viscous damping of every ball relative to the rotor (N m s/rad), >= 0.
    starts : int
        Random initial ball positions (uniform angles relative to the rotor, balls at rest
        relative to it), the same for every damping.
    seed : int
        Seed of the starts (NumPy ``default_rng``).
    rtol, atol : float
        Integrator tolerances.

    Returns
    -------
    xarray.Dataset
        Over ``(ball_damping, ic)``: ``impacts`` (impacts of the run), ``peak_impulse`` (largest
        normal impulse, N s), ``status``; over ``ball_damping``: ``contact_probability`` (share of
        the successful runs with any impact) with ``probability_low`` / ``probability_high`` (95 %
        Wilson interval), ``largest_impulse`` (N s, over the starts); ``initial_ball_angle`` (ic,
        ball, rad). Attributes: ``no_balls_impacts`` and ``no_balls_peak_impulse`` (the same run-up
        without balls), ``gap`` (m), ``final_speed`` (rad/s, of the run without balls), ``t_end``,
        ``seed``, ``starts``. Where each run-up ended, over ``(ball_damping, ic)``: ``outcome``
        ("balanced", "not balanced", "non-synchronous", "not settled": still converging towards
        balance, "below critical speed" or "failed", :func:`_end_labels`) and ``settle_estimate``
        (s, of those not settled); over ``ball_damping``: ``balanced_share`` with
        ``balanced_low`` / ``balanced_high`` (95 % Wilson interval).
    """
    import xarray as xr

    from rotorlab.explore import wilson_interval
    from rotorlab.integrate import SaveAt, StepControl, solve, solve_ensemble

    if not machine.clearances:
        raise ValueError("machine_knock needs a machine with a clearance")
    nb = machine.n_balls
    if nb == 0:
        raise ValueError("machine_knock needs balls (a race with balls) on the machine")
    damping = np.atleast_1d(np.asarray(ball_damping, dtype=float))
    if damping.ndim != 1 or damping.size == 0 or not np.all(np.isfinite(damping)) or np.any(damping < 0):
        raise ValueError(f"ball_damping must be one or more finite numbers >= 0 (N m s/rad), got {ball_damping!r}")
    if isinstance(starts, bool) or int(starts) != starts or starts < 1:
        raise ValueError(f"starts must be an integer >= 1, got {starts!r}")
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    starts = int(starts)
    from rotorlab._memory import check_memory

    n_runs = damping.size * starts
    from dataclasses import replace

    bare = replace(machine, races=())
    ref = solve(bare, bare.initial_state(), (0.0, float(t_end)), save_at=SaveAt(ts=[float(t_end)]),
                control=StepControl(rtol=rtol, atol=atol), max_events_recorded=0)
    final_bare = float(bare.spin(float(t_end), ref.y_final)[1])
    ts, windows = _margin_times(float(t_end), *_end_windows(float(t_end), final_bare))
    check_memory(8.0 * n_runs * ((4 + ts.size) * machine.kernels.n_state + machine.layout.n_param + nb),
                 f"starts = {starts} for {damping.size} ball damping(s) ({n_runs} run-ups)",
                 "use fewer starts")  # fmt: skip
    angles = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, (starts, nb))
    base = machine.to_array()
    kb = machine.layout.offsets["balls"]
    params = np.repeat(base[None, :], damping.size * starts, axis=0)
    for b in range(nb):
        params[:, kb + 4 * b + 3] = np.repeat(damping, starts)
    y0 = np.array([machine.initial_state(a) for a in angles])
    y0 = np.tile(y0, (damping.size, 1))
    control = StepControl(rtol=rtol, atol=atol)
    sol = solve_ensemble(machine, y0, (0.0, float(t_end)), params=params, save_at=SaveAt(ts=ts),
                         control=control, threads=threads, progress=progress, max_events_recorded=0)  # fmt: skip
    shape = (damping.size, starts)
    status = np.asarray(sol.status, dtype=np.int64).reshape(shape)
    ok = status >= 0
    impacts = np.where(ok, sol.y_final[:, -3].reshape(shape), np.nan)
    peak = np.where(ok, sol.y_final[:, -2].reshape(shape), np.nan)
    n_ok = ok.sum(axis=1)
    hits = np.nansum(impacts > 0, axis=1)
    prob = np.where(n_ok > 0, hits / np.maximum(n_ok, 1), np.nan)
    ci = np.array([wilson_interval(int(h), int(n)) if n > 0 else (np.nan, np.nan) for h, n in zip(hits, n_ok)],
                  dtype=float).reshape(-1, 2)
    lo, hi = ci[:, 0], ci[:, 1]
    largest = np.array([np.nanmax(row) if np.any(np.isfinite(row)) else np.nan for row in peak])
    margin = _least_margins(machine, sol.ys, impacts, ok).reshape(shape)
    outcome, settle = _end_labels(machine, sol, ts, windows, status.ravel())
    outcome, settle = outcome.reshape(shape), settle.reshape(shape)
    n_bal = (outcome == "balanced").sum(axis=1)
    bal_ci = np.array([wilson_interval(int(b), int(n)) if n > 0 else (np.nan, np.nan) for b, n in zip(n_bal, n_ok)],
                      dtype=float).reshape(-1, 2)
    ds = xr.Dataset(
        {
            "impacts": (("ball_damping", "ic"), impacts, {"units": "1"}),
            "peak_impulse": (("ball_damping", "ic"), peak, {"units": "N s"}),
            "status": (("ball_damping", "ic"), status, {"units": "1"}),
            "contact_probability": (("ball_damping",), prob, {"units": "1"}),
            "probability_low": (("ball_damping",), lo, {"units": "1"}),
            "probability_high": (("ball_damping",), hi, {"units": "1"}),
            "largest_impulse": (("ball_damping",), largest, {"units": "N s"}),
            "initial_ball_angle": (("ic", "ball"), angles, {"units": "rad"}),
            "outcome": (("ball_damping", "ic"), outcome),
            "settle_estimate": (("ball_damping", "ic"), settle, {"units": "s"}),
            "balanced_share": (("ball_damping",), np.where(n_ok > 0, n_bal / np.maximum(n_ok, 1), np.nan),
                               {"units": "1"}),
            "least_margin": (("ball_damping", "ic"), margin, {"units": "m"}),
            "balanced_low": (("ball_damping",), bal_ci[:, 0], {"units": "1"}),
            "balanced_high": (("ball_damping",), bal_ci[:, 1], {"units": "1"}),
        },
        coords={"ball_damping": ("ball_damping", damping, {"units": "N m s/rad"}),
                "ic": ("ic", np.arange(starts), {"units": "1"}), "ball": ("ball", np.arange(nb), {"units": "1"})},
        attrs={"analysis": "knock", "model": "machine", "t_end": float(t_end), "seed": int(seed),
               "starts": starts, "gap": float(machine.clearances[0].gap),
               "no_balls_impacts": float(ref.y_final[-3]) if int(ref.status) >= 0 else math.nan,
               "no_balls_peak_impulse": float(ref.y_final[-2]) if int(ref.status) >= 0 else math.nan,
               "no_balls_status": int(ref.status), "final_speed": final_bare,
               "margin_sample_interval": float(t_end) / MARGIN_SAMPLES},
    )
    return ds


def _margin_times(t_end: float, ts: np.ndarray, windows: list[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
    """The end windows' save times merged with :data:`MARGIN_SAMPLES` evenly spaced ones over the
    whole run (for the least margin), and the windows' indices among them."""
    every = np.linspace(0.0, t_end, MARGIN_SAMPLES + 1)[1:]
    merged = np.unique(np.concatenate([every, ts]))
    return merged, [np.searchsorted(merged, ts[w]) for w in windows]


def _least_margins(machine, ys: np.ndarray, impacts: np.ndarray, ok: np.ndarray) -> np.ndarray:
    """Per run: the gap less the largest distance of the clearance station from the stator's
    centre over the saved states (m); 0 for a run that touched; NaN for a failed run.

    Sampled (:data:`MARGIN_SAMPLES` evenly over the run, plus the end windows), so a margin can
    be overstated by the excursion between two samples; a run that touched is exact (0).
    """
    w = machine.gap_vector(ys)
    far = np.hypot(w[..., 0], w[..., 1]).max(axis=-1)
    margin = np.maximum(float(machine.clearances[0].gap) - far, 0.0)
    touched = impacts.ravel() > 0
    return np.where(~ok.ravel(), np.nan, np.where(touched, 0.0, margin))


def _end_windows(t_end: float, speed: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """Save times: windows of :data:`WINDOW_REVOLUTIONS` turns at ``speed`` ending at 80 %, 90 %
    and 100 % of the run (only the last when the run is too short), and their indices."""
    width = min(WINDOW_REVOLUTIONS * 2.0 * math.pi / max(abs(speed), 1e-12), 0.1 * t_end)
    ends = [0.8 * t_end, 0.9 * t_end, t_end]
    ts = np.concatenate([np.linspace(e - width, e, WINDOW_SAMPLES) for e in ends])
    return ts, [np.arange(k * WINDOW_SAMPLES, (k + 1) * WINDOW_SAMPLES) for k in range(3)]


def _end_labels(machine, sol, ts, windows, status) -> tuple[np.ndarray, np.ndarray]:
    """Where each run-up ended (:func:`rotorlab.explore._outcome.machine_outcome` over its last
    window; *not settled* where the vibration still falls towards balance over the three
    windows, :func:`rotorlab.explore._settle.settle_estimate`, or where the speed still changed
    by more than :data:`STEADY_SPEED` over them: the ramp had not ended) and its estimated time to
    balance (s; NaN for the others and while the ramp goes on)."""
    from rotorlab.analyses._machine_common import orbit_amplitude, structure_critical_speeds, unbalance_amplitudes
    from rotorlab.explore._outcome import BALANCED_FRACTION, machine_outcome
    from rotorlab.explore._settle import NOT_SETTLED, settle_estimate

    lay = machine.layout
    nb = lay.n_balls
    ys = sol.ys
    amp = np.stack([orbit_amplitude(machine, ys[:, w]).max(axis=-1) for w in windows], axis=1)
    last = ys[:, windows[-1]]
    spin = np.array([[machine.spin(t, y)[1] for t, y in zip(ts[windows[-1]], run)] for run in last])
    rate = np.abs(last[:, :, lay.i_w:lay.i_w + nb] - spin[:, :, None]).max(axis=(1, 2))
    speed = spin[:, -1]
    crit = structure_critical_speeds(machine)
    first = float(crit[0]) if crit.size else 0.0
    ref = np.array([np.max(unbalance_amplitudes(machine, float(w))) if np.isfinite(w) else np.nan for w in speed])
    horizons = ts[[w[-1] for w in windows]]
    settle = settle_estimate(amp, BALANCED_FRACTION * ref, horizons)[:, -1]
    w0 = np.array([machine.spin(ts[windows[0][-1]], run[-1])[1] for run in ys[:, windows[0]]])
    spinning_up = ~(np.abs(speed - w0) <= STEADY_SPEED * np.abs(speed))
    settle = np.where(spinning_up, np.nan, settle)  # no extrapolation while the drive still accelerates
    out = np.empty(ys.shape[0], dtype=object)
    for i in range(ys.shape[0]):
        text = machine_outcome(int(status[i]), amp[i, -1], ref[i], float(rate[i]), float(speed[i]), nb, first)
        if text not in ("balanced", "failed") and (np.isfinite(settle[i]) or spinning_up[i]):
            text = NOT_SETTLED
        out[i] = text
    settle = np.where(out == NOT_SETTLED, settle, np.nan)
    return out.astype(str), settle


def knock_task_size(case_model: Any, analysis: Any) -> int:
    """Run-ups of a ``machine-knock`` analysis (its progress-bar total)."""
    return len(analysis.ball_damping) * analysis.starts


def run_knock_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None):
    """Run a case's ``machine-knock`` analysis."""
    from rotorlab.analyses._machine import _variant

    m = _variant(case_model, analysis)
    ds = machine_knock(m, t_end=analysis.t_end, ball_damping=analysis.ball_damping, starts=analysis.starts,
                       seed=analysis.seed, rtol=analysis.rtol, atol=analysis.atol, progress=progress)  # fmt: skip
    ds.attrs["name"] = analysis.name
    return ds


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def knock_rows(ds) -> list[dict[str, Any]]:
    """One row per ball damping: contact probability (with its interval), largest impulse, impacts."""
    rows = []
    for i, d in enumerate(ds.ball_damping.values):
        imp = ds.impacts.values[i]
        rows.append({
            "ball_damping": float(d),
            "contact_probability": _num(ds.contact_probability.values[i]),
            "probability_low": _num(ds.probability_low.values[i]),
            "probability_high": _num(ds.probability_high.values[i]),
            "largest_impulse": _num(ds.largest_impulse.values[i]),
            "mean_impacts": _num(np.nanmean(imp)) if np.any(np.isfinite(imp)) else None,
            "failed": int(np.sum(ds.status.values[i] < 0)),
            "runs": int(ds.sizes["ic"]),
            **({"least_margin": _num(np.nanmin(ds.least_margin.values[i]))}
               if "least_margin" in ds and np.any(np.isfinite(ds.least_margin.values[i])) else {}),
            **(_end_row(ds, i) if "outcome" in ds else {}),
        })
    return rows


def _end_row(ds, i: int) -> dict[str, Any]:
    """Where the run-ups of one damping ended: the count of each outcome, the share balanced with
    its Wilson interval, and the latest estimated settle time of those not settled."""
    out = [str(o) for o in ds.outcome.values[i]]
    est = ds.settle_estimate.values[i]
    return {"outcomes": {o: out.count(o) for o in sorted(set(out))},
            "balanced_share": _num(ds.balanced_share.values[i]), "balanced_low": _num(ds.balanced_low.values[i]),
            "balanced_high": _num(ds.balanced_high.values[i]), "not_settled": out.count("not settled"),
            "settle_by_s": _num(np.nanmax(est)) if np.any(np.isfinite(est)) else None}
