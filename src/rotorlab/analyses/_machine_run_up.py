"""Run-ups of the composed machine: the passage through its critical speeds, and the smallest
motor torque that passes the first one (the Sommerfeld effect), with and without the balls.

:func:`machine_run_up` integrates one run-up and judges it with :func:`run_up_verdict`;
:func:`passing_torque` finds, by bracketing and bisection on the motor's torque scale, the
smallest torque whose run-up reaches a target speed (by default 1.05 times the first critical
speed) with the balls turning with the rotor, each round of probes one ensemble on the lane
driver, and says which mechanism sets it: the rotor captured below the target (Sommerfeld) or the
balls left behind (desynchronised). The ``run-up`` analysis of a machine case
(``passing_torque = true``) reports it with and without the races.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab.analyses._machine_common import (
    _annotate,
    _ball_coords,
    _num,
    _per_station,
    _variant,
    _wrap,
    add_figure_variables,
    check_saved_states,
    flag_unstable,
    orbit_amplitude,
    status_detail,
    structure_critical_speeds,
    unbalance_amplitudes,
)
from rotorlab.analyses._run_up_verdicts import (
    PASS_MARGIN,
    PEAK_BAND,
    coarse_saves_note,
    critical_peaks,
    peak_underread,
    ramp_end_settle,
    run_up_ensemble,
    run_up_outcome,
)
from rotorlab.explore._outcome import BALANCED_FRACTION

__all__ = ["machine_run_up", "run_up_verdict", "passing_torque", "PassingTorque", "NO_PASSING_TORQUE"]

#: Status of a :class:`PassingTorque` whose threshold was not bracketed (the message says why).
NO_PASSING_TORQUE = 5
#: Capture band: a motor captured at a critical speed w_c holds a speed in
#: [CAPTURE_BAND w_c, PASS_MARGIN w_c) for the rest of the run ...
CAPTURE_BAND = 0.85
#: ... judged over this last fraction of the run ...
CAPTURE_TAIL = 0.2
#: ... while its mean acceleration there is at most this fraction of what the motor's torque at
#: that speed would give the spinning inertia alone (the whirl takes the rest).
CAPTURE_ACCELERATION = 0.05
#: The balls of a passing run-up turn with the rotor: each one's rate relative to it at the end
#: at most this fraction of the spin speed (default of ``passing_torque``'s ``sync_tol``).
SYNC_TOL = 0.01
#: What limits a passing torque: the failing probe just below it fell short of the target speed
#: (the rotor was captured), or reached it with a ball left behind.
LIMITS = ("rotor capture", "ball desynchronisation")


def _critical_speeds(machine) -> np.ndarray:
    return np.unique(np.round(structure_critical_speeds(machine, max_speed=None), 9))


def run_up_verdict(machine, times, speeds, critical_speeds) -> tuple[int, float]:
    """Judge where a run-up ended: the critical speeds passed, or the one it is captured at.

    Parameters
    ----------
    machine : Machine
    times, speeds : array_like, shape (n,)
        The run-up's spin speed (rad/s) at increasing times (s); the last is the final speed.
    critical_speeds : array_like
        Forward 1x critical speeds, balls locked, increasing (rad/s).

    Returns
    -------
    passed : int
        Number of critical speeds passed: those the final speed exceeds by the factor
        :data:`PASS_MARGIN` (1.05).
    captured_at : float
        With a motor, the critical speed ``w_c`` the run-up is captured at (the Sommerfeld
        effect), else NaN (rad/s). Captured: over the last :data:`CAPTURE_TAIL` (20 %) of the run
        every speed lies in the band ``[0.85 w_c, 1.05 w_c)`` around it (on either side: with
        damping the whirl's drag peaks above the undamped critical speed, so a capture can sit
        just above it), the motor could still accelerate (its torque ``T(w) > 0`` at the final
        speed) and yet the mean acceleration over that tail is at most
        :data:`CAPTURE_ACCELERATION` (5 %) of ``T(w) / J`` (``J`` the motor's polar inertia, all
        that spins): the whirl absorbs the motor's torque. A run-up still crossing the band at
        the end is neither passed nor captured.
    """
    crit = np.asarray(critical_speeds, dtype=float)
    t, w = np.asarray(times, dtype=float), np.asarray(speeds, dtype=float)
    final = float(w[-1])
    passed = int(np.sum(final > PASS_MARGIN * crit))
    if not machine.is_motor:
        return passed, math.nan
    tail = t >= t[-1] - CAPTURE_TAIL * (t[-1] - t[0])
    lo, hi = float(w[tail].min()), float(w[tail].max())
    band = crit[(CAPTURE_BAND * crit <= lo) & (hi < PASS_MARGIN * crit)]
    torque = float(machine.drive.torque_at(final))
    if band.size == 0 or not torque > 0.0 or tail.sum() < 2:
        return passed, math.nan
    tt = t[tail]
    accel = (w[tail][-1] - w[tail][0]) / (tt[-1] - tt[0])
    if accel > CAPTURE_ACCELERATION * torque / machine.drive.polar_inertia:
        return passed, math.nan
    return passed, float(band[np.argmin(np.abs(band - final))])


def machine_run_up(machine, *, t_end: float, n_save: int = 2000, ball_angles=None,
                   rtol: float = 1e-8, atol: float = 1e-10, initial_speed: float = 0.0):
    """Run the machine up (motor or prescribed profile) and say whether it passes its criticals.

    Returns
    -------
    xarray.Dataset
        Over ``time``: ``speed`` (rad/s), ``amplitude`` (time, station) radial displacement of
        each node (m), ``ball_angle`` (time, ball) relative to the rotor (rad); under gravity
        ``displacement_from_rest`` (time, station), with a clearance ``clearance_distance``
        (time), ``impacts`` (the contact ledger's count at the end) and ``attrs`` ``gap``,
        ``clearance_station``
        (:func:`~rotorlab.analyses._machine_common.add_figure_variables`). Attributes:
        ``critical_speeds`` (rad/s, forward 1x, balls locked), ``final_speed``,
        ``passed`` and ``captured_at`` (:func:`run_up_verdict`), ``residual_amplitude`` per
        station (vibration amplitude about the mean position over the last 10 % of the run, m);
        ``critical_peak`` (critical): the transient peak at each critical speed passed (m, NaN
        for those not passed, :func:`~rotorlab.analyses._run_up_verdicts.critical_peaks`) and
        ``critical_peak_underread`` (critical): its estimated shortfall between the saves (-,
        :func:`~rotorlab.analyses._run_up_verdicts.peak_underread`);
        ``settle_estimate``: with balls, the estimated time to balance (s) where the vibration
        still falls towards balance at the end, else NaN
        (:func:`~rotorlab.analyses._run_up_verdicts.ramp_end_settle`);
        ``status``: the integrator's (its sanity monitor fails a run beyond the structure's
        validity, :meth:`~rotorlab.models.Machine.impossible_states`), or ``UNSTABLE`` where the
        structure is unstable at the final speed (:func:`~rotorlab.analyses._machine_common.flag_unstable`),
        and ``status_detail``, why it failed.
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve

    if isinstance(n_save, bool) or int(n_save) != n_save or n_save < 10:
        raise ValueError(f"n_save must be an integer >= 10, got {n_save!r}")
    check_saved_states(machine, n_save)
    y0 = machine.initial_state(ball_angles, spin_speed=initial_speed)
    ts = np.linspace(0.0, float(t_end), int(n_save))
    sol = solve(machine, y0, (0.0, float(t_end)), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=rtol, atol=atol))
    lay = machine.layout
    spin = np.array([machine.spin(t, y) for t, y in zip(ts, sol.ys)])
    amp = machine.station_amplitudes(sol.ys)
    rel = _wrap(sol.ys[:, lay.i_phi:lay.i_phi + lay.n_balls] - spin[:, :1])
    final = float(spin[-1, 1])
    crit = _critical_speeds(machine)
    passed, captured = run_up_verdict(machine, ts, spin[:, 1], crit)
    status, notes = flag_unstable(machine, [int(sol.status)], [final], [sol.note])
    threshold = BALANCED_FRACTION * float(np.max(unbalance_amplitudes(machine, final))) if machine.n_balls else 0.0
    settle = ramp_end_settle(machine, ts, sol.ys, threshold) if machine.n_balls and status[0] >= 0 else math.nan
    tail = ts >= 0.9 * ts[-1]
    ds = xr.Dataset(
        {
            "speed": (("time",), spin[:, 1], {"units": "rad/s"}),
            "amplitude": (("time", "station"), amp, {"units": "m"}),
            "ball_angle": (("time", "ball"), rel, {"units": "rad"}),
            "residual_amplitude": (("station",), orbit_amplitude(machine, sol.ys[tail]),
                                   {"units": "m"}),
            "critical_peak": (("critical",), critical_peaks(spin[:, 1], amp, crit, passed), {"units": "m"}),
            "critical_peak_underread": (("critical",), peak_underread(spin[:, 1], amp, crit, passed), {"units": "1"}),
        },
        coords={"time": ("time", ts, {"units": "s"}), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "run-up", "model": "machine", "critical_speeds": crit,
               "final_speed": final, "passed": passed, "captured_at": captured,
               "settle_estimate": settle, "status": int(status[0]), "status_detail": notes[0]},
    )
    if machine.clearances:  # the contact ledger's impact count at the end (sustained contact counts one)
        ds["impacts"] = ((), float(sol.ys[-1, machine.state_names.index("impacts")]), {"units": "1"})
    return add_figure_variables(ds, machine, sol.ys, ("time",))



def _motor_top(machine) -> float:
    d = machine.drive
    if d.kind == "linear":
        return float(d.no_load_speed)
    w, t = np.asarray(d.torque[0]), np.asarray(d.torque[1])
    idx = np.flatnonzero((t[:-1] > 0) & (t[1:] <= 0))
    if idx.size:
        k = idx[0]
        return float(w[k] + (w[k + 1] - w[k]) * t[k] / (t[k] - t[k + 1]))
    return float(w[-1])


# --------------------------------------------------------------------------- the passing torque


@dataclass(frozen=True, slots=True)
class PassingTorque:
    """The smallest motor torque whose run-up passes the first critical speed.

    Torques are the motor's stall torque T(0) (N m) after scaling its whole characteristic
    (:meth:`rotorlab.models.Motor.scaled`); ``factor`` is the scale itself.

    Attributes
    ----------
    torque : float
        The smallest probed stall torque that passes (N m): the upper end of the bracket; NaN
        when none was bracketed.
    lower : float
        The largest probed stall torque below it that does not pass (N m); the threshold lies in
        ``(lower, torque]``, ``torque - lower <= rel_tol * torque``.
    factor, lower_factor : float
        The same as multiples of the machine's own motor torque (-).
    critical_speed : float
        The first critical speed (forward 1x, balls locked) (rad/s).
    target_speed : float
        The final speed a passing run-up exceeds (rad/s).
    limited_by : str
        What the probe at ``lower`` failed by (:data:`LIMITS`): ``"rotor capture"`` (it ended
        below ``target_speed``) or ``"ball desynchronisation"`` (it reached it, a ball did not
        turn with the rotor). When no probe passes, what the strongest one failed by; ``""``
        when every probe passes or a run-up failed.
    probes : int
        Run-ups integrated.
    monotone : bool
        Every probed torque at or above ``torque`` passed and every one at or below ``lower``
        did not (False: the verdict is not monotone in the torque, the threshold is the lowest
        crossing found).
    status : int
        0, or :data:`NO_PASSING_TORQUE` (not bracketed, ``message`` says why), or < 0 (a probe's
        integration failed, :class:`rotorlab.integrate.Status`).
    message : str
    """

    torque: float
    lower: float
    factor: float
    lower_factor: float
    critical_speed: float
    probes: int
    monotone: bool
    status: int
    message: str = ""
    target_speed: float = math.nan
    limited_by: str = ""


def passing_torque(machine, *, t_end: float, rel_tol: float = 1e-3, ball_angles=None,
                   initial_speed: float = 0.0, probes: int = 8, rtol: float = 1e-8,
                   atol: float = 1e-10, max_factor: float = 2.0**20, min_factor: float = 2.0**-20,
                   threads: int | None = None, target_speed: float | None = None, synchronise: bool = True,
                   sync_tol: float = SYNC_TOL) -> PassingTorque:
    """Find the smallest motor torque that runs the machine up past its first critical speed.

    Each probe is a run-up from the same start (:meth:`Machine.initial_state` with
    ``ball_angles`` and ``initial_speed``) over ``t_end`` with the motor's characteristic scaled
    by a factor (:meth:`Motor.scaled`); it *passes* when its final speed exceeds
    ``target_speed`` (by default 1.05 times the first critical speed, the pass of
    :func:`run_up_verdict`) and, with ``synchronise`` and balls, every ball turns with the rotor
    at the end (its rate relative to the rotor at most ``sync_tol`` times the spin speed): a rotor
    past its critical speed whose balls lag near the resonance has not run up, it is not
    balancing. :attr:`PassingTorque.limited_by` says which of the two the probe just below the
    threshold failed. The factors are first bracketed
    on a geometric grid (ratio 4, from 4^-5 to 4^2 times the motor's torque, extended up or down
    while no probe or every probe passes), then the bracket is cut by ``probes`` equally spaced
    interior probes per round until its width is at most ``rel_tol`` times its upper end. All
    probes of a round are one ensemble (:func:`rotorlab.integrate.solve_ensemble`, the lane driver).

    Parameters
    ----------
    machine : Machine
        Driven by a :class:`~rotorlab.models.Motor`.
    t_end : float
        Duration of each run-up (s). Just above the threshold the passage takes longer and longer
        (the speed lingers where the motor's torque nearly equals the whirl's drag), so the result
        is the smallest torque that passes *within* ``t_end``.
    rel_tol : float
        Relative width of the final bracket (-), in (0, 1).
    ball_angles : array_like, shape (n_balls,), optional
        Start of the balls relative to the rotor (rad).
    initial_speed : float
        Spin speed at t = 0 (rad/s).
    probes : int
        Run-ups per refinement round (>= 1; 8 fills the lanes of one thread).
    rtol, atol : float
        Integrator tolerances.
    max_factor, min_factor : float
        Give up (status :data:`NO_PASSING_TORQUE`) when no probe up to ``max_factor`` times the
        motor's torque passes, or every one down to ``min_factor`` times it does.
    target_speed : float, optional
        Final speed a passing run-up exceeds (rad/s); default 1.05 times the first critical
        speed. Above the motor's no-load speed no torque passes (status :data:`NO_PASSING_TORQUE`).
    synchronise : bool
        Also require the balls to turn with the rotor at the end (no effect without balls).
    sync_tol : float
        Largest ball rate relative to the rotor, as a fraction of the spin speed (-), in (0, 1).

    Returns
    -------
    PassingTorque

    Raises
    ------
    ValueError
        Without a motor, or on a bad setting.

    Notes
    -----
    Without balls and for a slow run-up (large polar inertia), the threshold approaches the
    quasi-static one of the Sommerfeld effect (Blekhman, "Vibrational Mechanics", 2000, ch. 8):
    the smallest ``T_s`` for which ``T_s (1 - w / w_0)`` stays above the torque the steady whirl
    takes, ``d w |z(w)|^2``, up to past the resonance peak (tested in
    ``tests/unit/test_machine_passing_torque.py``).
    """
    return _passing_torques(machine, [ball_angles], t_end=t_end, rel_tol=rel_tol,
                            initial_speed=initial_speed, probes=probes, rtol=rtol, atol=atol,
                            max_factor=max_factor, min_factor=min_factor, threads=threads,
                            target_speed=target_speed, synchronise=synchronise, sync_tol=sync_tol)[0]


def _check_passing_settings(machine, t_end, rel_tol, probes, max_factor, min_factor, target_speed,
                            sync_tol) -> None:
    if not machine.is_motor:
        raise ValueError("passing_torque needs a machine driven by a Motor (its torque is what is "
                         f"scaled), got drive {type(machine.drive).__name__}")
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    if not 0 < rel_tol < 1:
        raise ValueError(f"rel_tol must be in (0, 1), got {rel_tol!r}")
    if isinstance(probes, bool) or int(probes) != probes or probes < 1:
        raise ValueError(f"probes must be an integer >= 1, got {probes!r}")
    if not 0 < min_factor < 1 < max_factor < math.inf:
        raise ValueError(f"need 0 < min_factor < 1 < max_factor < inf, got {min_factor!r}, {max_factor!r}")
    if target_speed is not None and not (math.isfinite(target_speed) and target_speed > 0):
        raise ValueError(f"target_speed must be a finite number > 0 (rad/s), got {target_speed!r}")
    if not 0 < sync_tol < 1:
        raise ValueError(f"sync_tol must be in (0, 1), got {sync_tol!r}")
    if not machine.drive.stall_torque > 0:
        raise ValueError(f"passing_torque scales the motor's torque: its stall torque T(0) must be > 0 "
                         f"(N m), got {machine.drive.stall_torque!r}")


def _probe_verdict(machine, y, target: float, synchronise: bool, sync_tol: float) -> tuple[bool, bool]:
    """(reached the target speed, balls turning with the rotor) at a probe's final state."""
    lay = machine.layout
    om = float(y[lay.i_theta + 1])
    rel = np.abs(y[lay.i_w:lay.i_w + lay.n_balls] - om)
    return om > target, not synchronise or bool(np.all(rel <= sync_tol * abs(om)))


def _passing_torques(machine, starts, *, t_end, rel_tol=1e-3, initial_speed=0.0, probes=8, rtol=1e-8,
                     atol=1e-10, max_factor=2.0**20, min_factor=2.0**-20, threads=None, target_speed=None,
                     synchronise=True, sync_tol=SYNC_TOL) -> list[PassingTorque]:
    """:func:`passing_torque` from each of several ball starts (None: the default start), the
    probes of every unfinished start in one ensemble per round."""
    from rotorlab.integrate import StepControl, solve_ensemble

    _check_passing_settings(machine, t_end, rel_tol, probes, max_factor, min_factor, target_speed, sync_tol)
    crit = _critical_speeds(machine)
    t0 = machine.drive.stall_torque
    n = len(starts)
    target = (PASS_MARGIN * float(crit[0]) if crit.size else math.nan) if target_speed is None else float(target_speed)
    if crit.size == 0 or _motor_top(machine) <= target:
        why = ("the structure has no forward critical speed" if crit.size == 0 else
               f"the motor's no-load speed {_motor_top(machine):.6g} rad/s is not above the target speed "
               f"{target:.6g} rad/s ({target / crit[0]:.4g} times the first critical speed {crit[0]:.6g} rad/s): "
               "no torque of this characteristic reaches it")
        return [PassingTorque(math.nan, math.nan, math.nan, math.nan, float(crit[0]) if crit.size else math.nan,
                              0, True, NO_PASSING_TORQUE, why, target)] * n
    y0 = [machine.initial_state(None if a is None or machine.n_balls == 0 else list(a), spin_speed=initial_speed)
          for a in starts]
    control = StepControl(rtol=rtol, atol=atol)
    seen: list[list[tuple[float, bool]]] = [[] for _ in range(n)]
    why_not: list[dict[float, str]] = [{} for _ in range(n)]
    in_step = " with the balls in step" if machine.n_balls and synchronise else ""
    lo, hi = [0.0] * n, [math.inf] * n
    grid = [4.0 ** np.arange(-5, 3) for _ in range(n)]
    status, message = [0] * n, [""] * n
    count = [0] * n
    while any(g is not None for g in grid):
        # no probe beyond the limits: give up there rather than integrate an absurd torque
        grid = [None if g is None else np.unique(np.clip(g, min_factor, max_factor)) for g in grid]
        rows = [(k, f) for k in range(n) if grid[k] is not None for f in grid[k]]
        P = np.array([machine.with_drive(machine.drive.scaled(f)).to_array() for _, f in rows])
        sol = solve_ensemble(machine, np.array([y0[k] for k, _ in rows]), (0.0, float(t_end)), params=P,
                             control=control, threads=threads)
        for (k, f), st, y in zip(rows, sol.status, sol.y_final):
            if st < 0 and status[k] == 0:
                status[k], message[k] = int(st), f"the run-up at {f * t0:.6g} N m failed (status {int(st)})"
            count[k] += 1
            fast, sync = _probe_verdict(machine, y, target, synchronise and machine.n_balls > 0, sync_tol)
            seen[k].append((float(f), fast and sync))
            if not (fast and sync):
                why_not[k][float(f)] = LIMITS[0] if not fast else LIMITS[1]
        for k in range(n):
            if grid[k] is None:
                continue
            if status[k] != 0:
                grid[k] = None
                continue
            passing = sorted(f for f, ok in seen[k] if ok)
            if passing:
                hi[k] = passing[0]
                below = [f for f, ok in seen[k] if not ok and f < hi[k]]
                lo[k] = max(below) if below else 0.0
            else:
                lo[k] = max(f for f, _ in seen[k])
            if math.isinf(hi[k]):
                if lo[k] >= max_factor:
                    status[k], grid[k] = NO_PASSING_TORQUE, None
                    message[k] = (f"no run-up up to {lo[k] * t0:.6g} N m ({lo[k]:.6g} times the motor's torque) "
                                  f"passes {target:.6g} rad/s{in_step} "
                                  f"within {t_end:g} s")
                else:
                    grid[k] = lo[k] * 4.0 ** np.arange(1, 9)
            elif lo[k] == 0.0:
                if hi[k] <= min_factor:
                    status[k], grid[k] = NO_PASSING_TORQUE, None
                    message[k] = (f"every run-up down to {hi[k] * t0:.6g} N m ({hi[k]:.6g} times the motor's "
                                  f"torque) passes {target:.6g} rad/s")
                else:
                    grid[k] = hi[k] * 4.0 ** np.arange(-8, 0)
            elif hi[k] - lo[k] > rel_tol * hi[k]:
                grid[k] = np.linspace(lo[k], hi[k], int(probes) + 2)[1:-1]
            else:
                grid[k] = None
    out = []
    for k in range(n):
        ok = status[k] == 0
        unreached = status[k] == NO_PASSING_TORQUE and math.isinf(hi[k])  # no probe passed: say why
        mono = all(p for f, p in seen[k] if f >= hi[k]) and not any(p for f, p in seen[k] if f <= lo[k])
        out.append(PassingTorque(hi[k] * t0 if ok else math.nan, lo[k] * t0 if ok else math.nan,
                                 hi[k] if ok else math.nan, lo[k] if ok else math.nan, float(crit[0]),
                                 count[k], mono, status[k], message[k], target,
                                 why_not[k].get(lo[k], "") if ok or unreached else ""))
    return out


# --------------------------------------------------------------------------- the run-up analysis


def _run_run_up(case_model, analysis, progress=None):
    from rotorlab.analyses._builders import speed_profile

    m = _variant(case_model, analysis)
    if analysis.speed is not None:
        m = m.with_drive(speed_profile(analysis.speed))
    starts = analysis.initial_ball_angles or (None,)
    start_speed = getattr(case_model.drive, "initial_speed", 0.0) if analysis.speed is None else 0.0
    total = _run_up_task_size(case_model, analysis)
    ds = run_up_starts(m, starts, t_end=analysis.t_end, n_save=analysis.n_save, rtol=analysis.rtol,
                       atol=analysis.atol, initial_speed=start_speed, progress=progress, total=total)
    if getattr(analysis, "passing_torque", False):
        _add_passing_torque(ds, m, starts, analysis, start_speed)
        if progress is not None:
            progress(total, total)
    return _annotate(ds, case_model, analysis)


def run_up_starts(m, starts, *, t_end: float, n_save: int = 2000, rtol: float = 1e-8, atol: float = 1e-10,
                  initial_speed: float = 0.0, progress=None, total: int | None = None):
    """:func:`machine_run_up` from each ball start (a sequence of angle lists, or ``(None,)`` for
    the machine's own), concatenated over ``ic``, with each run's ``outcome``
    (:func:`_run_up_outcome`) and ``reference_amplitude`` (the locked unbalance response at its
    final speed)."""
    import xarray as xr

    parts, details = [], []
    for k, angles in enumerate(starts):
        one = machine_run_up(m, t_end=t_end, n_save=n_save,
                             ball_angles=None if angles is None or m.n_balls == 0 else list(angles),
                             rtol=rtol, atol=atol, initial_speed=initial_speed)
        for key in ("final_speed", "passed", "captured_at", "status", "settle_estimate"):
            one[key] = ((), one.attrs.pop(key))
        details.append(one.attrs.pop("status_detail"))
        ref = unbalance_amplitudes(m, float(one["final_speed"]))
        one["reference_amplitude"] = (("station",), ref, {"units": "m"})
        one["outcome"] = ((), _run_up_outcome(m, one, ref))
        parts.append(one)
        if progress is not None:
            progress(k + 1, total or len(starts))
    ds = xr.concat(parts, dim="ic", combine_attrs="override")
    ds = ds.assign_coords(ic=np.arange(len(starts)))
    ds.attrs["status_detail"] = status_detail(details)
    ds["final_speed"].attrs["units"] = "rad/s"
    ds["captured_at"].attrs["units"] = "rad/s"
    ds["settle_estimate"].attrs["units"] = "s"
    ds.attrs["peak_band"] = PEAK_BAND
    ds.attrs["peak_saves_note"] = coarse_saves_note(n_save, ds.critical_peak_underread.values)
    return ds


def _add_passing_torque(ds, machine, starts, analysis, start_speed) -> None:
    """Add the smallest passing stall torque per start with the analysis' races
    (``passing_torque``, ``passing_torque_lower``), without any race
    (``passing_torque_without_balls``, ``..._lower``), their ratio (``passing_torque_ratio``), the
    target speeds and what limits each (``passing_torque_limited_by``, :data:`LIMITS`)."""
    from dataclasses import replace

    kw = dict(t_end=analysis.t_end, rel_tol=analysis.passing_torque_rtol, initial_speed=start_speed,
              rtol=analysis.rtol, atol=analysis.atol, target_speed=getattr(analysis, "passing_target_speed", None),
              synchronise=getattr(analysis, "passing_synchronise", True))
    bare = _passing_torques(replace(machine, races=()), [None], **kw)[0]
    with_balls = _passing_torques(machine, starts, **kw) if machine.n_balls else [bare] * len(starts)
    nm = {"units": "N*m"}
    ds["passing_torque"] = (("ic",), np.array([r.torque for r in with_balls]), nm)
    ds["passing_torque_lower"] = (("ic",), np.array([r.lower for r in with_balls]), nm)
    ds["passing_torque_without_balls"] = ((), bare.torque, nm)
    ds["passing_torque_without_balls_lower"] = ((), bare.lower, nm)
    ratio = np.array([r.torque for r in with_balls]) / bare.torque if machine.n_balls else np.full(len(starts), np.nan)
    ds["passing_torque_ratio"] = (("ic",), ratio, {"units": "1"})
    ds["passing_torque_status"] = (("ic",), np.array([r.status or bare.status for r in with_balls], dtype=np.int64))
    ds["passing_torque_target_speed"] = (("ic",), np.array([r.target_speed for r in with_balls]), {"units": "rad/s"})
    ds["passing_torque_without_balls_target_speed"] = ((), bare.target_speed, {"units": "rad/s"})
    ds["passing_torque_limited_by"] = (("ic",), np.array([r.limited_by for r in with_balls], dtype=object))
    ds["passing_torque_without_balls_limited_by"] = ((), np.array(bare.limited_by, dtype=object))
    ds.attrs["passing_torque_rtol"] = float(analysis.passing_torque_rtol)
    ds.attrs["motor_stall_torque"] = float(machine.drive.stall_torque)
    ds.attrs["passing_synchronise"] = int(bool(kw["synchronise"]))
    ds.attrs["passing_torque_probes"] = int(bare.probes + (sum(r.probes for r in with_balls) if machine.n_balls else 0))
    notes = sorted({r.message for r in (bare, *with_balls) if r.message})
    if notes:
        ds.attrs["passing_torque_message"] = "; ".join(notes)


def _run_up_outcome(machine, ds, reference) -> str:
    """Where a run-up ended (:func:`~rotorlab.analyses._run_up_verdicts.run_up_outcome`)."""
    tail = ds.time.values >= 0.9 * ds.time.values[-1]
    settle = float(ds["settle_estimate"]) if "settle_estimate" in ds else float(ds.attrs.get("settle_estimate", math.nan))
    return run_up_outcome(int(ds["status"]), machine.n_balls, float(ds["captured_at"]),
                          float(np.max(ds.residual_amplitude.values)), float(np.max(reference)),
                          float(ds["final_speed"]), ds.attrs["critical_speeds"], ds.ball_angle.values[tail],
                          settle)


def _run_up_task_size(case_model, analysis) -> int:
    return len(analysis.initial_ball_angles or (None,)) + bool(getattr(analysis, "passing_torque", False))


def _run_up_rows(ds) -> list[dict[str, Any]]:
    crit = [_num(w) for w in np.ravel(ds.attrs["critical_speeds"])]
    has_passing = "passing_torque" in ds
    ensemble = (run_up_ensemble([str(o) for o in ds.outcome.values], ds.critical_peak.values,
                                ds.attrs["critical_speeds"]) if "critical_peak" in ds else None)
    rows = []
    for i in range(ds.sizes["ic"]):
        r = ds.isel(ic=i)
        row = {"ic": i, "final_speed": _num(r.final_speed), "final_speed_rpm": _num(r.final_speed * 30 / np.pi),
               "critical_speeds": crit, "passed": int(r.passed), "captured_at": _num(r.captured_at),
               "residual_amplitude": _per_station(ds, r.residual_amplitude.values),
               "reference_amplitude": _per_station(ds, r.reference_amplitude.values),
               "outcome": str(r.outcome.values), "status": int(r.status),
               "settle_estimate_s": _num(r.settle_estimate) if "settle_estimate" in r else None,
               "critical_peaks": ([_num(v) for v in r.critical_peak.values] if "critical_peak" in r else None),
               "ensemble": ensemble}
        if has_passing:
            row.update({
                "passing_torque": _num(r.passing_torque), "passing_torque_lower": _num(r.passing_torque_lower),
                "passing_torque_without_balls": _num(r.passing_torque_without_balls),
                "passing_torque_without_balls_lower": _num(r.passing_torque_without_balls_lower),
                "passing_torque_ratio": _num(r.passing_torque_ratio),
                "passing_torque_rtol": float(ds.attrs["passing_torque_rtol"]),
                "motor_stall_torque": float(ds.attrs["motor_stall_torque"]),
                "passing_synchronise": bool(ds.attrs.get("passing_synchronise", 1)),
                "passing_torque_status": int(r.passing_torque_status),
                "passing_torque_target_speed": _num(r.passing_torque_target_speed),
                "passing_torque_without_balls_target_speed": _num(r.passing_torque_without_balls_target_speed),
                "passing_torque_limited_by": str(r.passing_torque_limited_by.values) or None,
                "passing_torque_without_balls_limited_by": str(r.passing_torque_without_balls_limited_by.values) or None,
                **({"passing_torque_message": ds.attrs["passing_torque_message"]}
                   if "passing_torque_message" in ds.attrs else {})})
        rows.append(row)
    return rows
