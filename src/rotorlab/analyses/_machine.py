"""Analyses of the composed machine (:class:`rotorlab.models.Machine`): simulation from many ball
starts, steady balanced states and their exact stability over speed, and run-ups.

All functions are pure: a model in, an :class:`xarray.Dataset` out (SI units in ``attrs``), with
an integer ``status`` per element (0: success) and, where the question has no answer for this
machine (no co-rotating equilibria), a failed status and the reason in ``attrs["message"]``.

The common analysis types run on a ``machine`` case through the machine's own entries
(:func:`machine_analysis_types`, the ``analyses`` of its :class:`~rotorlab.analyses.ModelType`):
``simulate``, ``steady`` (every balanced motion at one speed, :func:`machine_motions`),
``stability-chart`` and ``run-up``; ``basin`` and ``sweep`` through its regime mapper
(:func:`machine_mapper`, :class:`rotorlab.explore.MachineRegimes`); ``campbell``, ``modes`` and
the other structural analyses through the spec's ``linear_structure()``.

This module holds ``simulate`` and the registry entries; the steady analyses are in
``_machine_steady``, the run-ups in ``_machine_run_up`` and their shared helpers in
``_machine_common`` (their public names are re-exported here).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from rotorlab.analyses._machine_common import (  # noqa: F401  (re-exported: the names users import from here)
    CLEARANCE_STATUS,
    NO_STEADY_STATUS,
    NON_SYNCHRONOUS_RATE,
    _annotate,
    _ball_coords,
    _num,
    _outcome,
    _per_race,
    _per_station,
    _variant,
    _wrap,
    add_figure_variables,
    check_saved_states,
    clearance_violation,
    flag_unstable,
    status_detail,
    locked_structure,
    machine_model,
    machine_quantities,
    orbit_amplitude,
    structure_critical_speeds,
    unbalance_amplitudes,
)
from rotorlab.analyses._machine_steady import jeffcott_limit, machine_motions, machine_steady  # noqa: F401
from rotorlab.explore._outcome import BALANCED_FRACTION
from rotorlab.explore._settle import NOT_SETTLED, settle_estimate

__all__ = ["machine_simulate", "machine_steady", "machine_motions", "locked_structure",
           "orbit_amplitude", "machine_model", "machine_quantities", "machine_analysis_types",
           "jeffcott_limit", "structure_critical_speeds", "unbalance_amplitudes", "NO_STEADY_STATUS", "CLEARANCE_STATUS",
           "clearance_violation", "NON_SYNCHRONOUS_RATE"]

#: Samples per revolution in the final window of a simulation.
_SAMPLES_PER_REV = 32
#: The settle estimate of a simulation compares its final window with the windows ending this
#: fraction of the run and twice it earlier.
SETTLE_STEP = 0.1


def machine_simulate(machine, initial_ball_angles, *, t_end: float, rtol: float = 1e-8,
                     atol: float = 1e-10, window_revolutions: float = 2.0,
                     n_save: int | None = None, threads: int | None = None,
                     progress: Callable[[int, int], None] | None = None):
    """Simulate the machine from many ball starts and report where each ends.

    Every trajectory starts with the structure at rest and the balls at rest relative to the
    rotor at the given angles (rad, from the rotor's reference direction, races in order).

    Parameters
    ----------
    machine : Machine
    initial_ball_angles : array_like, shape (n_starts, n_balls)
    t_end : float
        Simulated time (s).
    rtol, atol : float
        Integrator tolerances.
    window_revolutions : float
        Length of the final window (revolutions at the final speed) over which the vibration
        amplitude is taken (its maximum).
    n_save : int, optional
        Also keep ``n_save`` equally spaced states over [0, t_end] as the time history
        ``displacement`` (ic, time, station): each node's distance from the axis (m); under
        gravity also ``displacement_from_rest`` (each node's distance from where it rests, what
        the report plots), with a clearance ``clearance_distance`` (ic, time) and ``attrs["gap"]``
        (:func:`~rotorlab.analyses._machine_common.add_figure_variables`). A history that would not fit in this machine's memory is refused up
        front (:func:`check_saved_states`, :class:`rotorlab._memory.TooLarge`).

    Returns
    -------
    xarray.Dataset
        ``final_ball_angle`` (ic, ball): angle relative to the rotor (rad, wrapped to
        [-pi, pi)); ``amplitude`` (ic, station): vibration amplitude of each node in the final
        window (largest distance from its mean position, m); ``reference_amplitude`` (station): the same without balancing (the
        linear unbalance response at the final speed of each start, first start shown);
        ``final_speed`` (ic) (rad/s); ``max_final_rate`` (ic): largest ball rate relative to
        the rotor in the final window (rad/s); ``outcome`` (ic): "balanced" (every station's
        vibration at most :data:`~rotorlab.analyses.BALANCED_FRACTION` of the largest vibration
        without balancing, above the first critical speed), "below critical speed" (the same at or
        below it, :data:`BELOW_CRITICAL`), "non-synchronous" (balls still moving relative to the rotor faster
        than :data:`NON_SYNCHRONOUS_RATE` times its speed), "not settled" (its vibration still
        falling towards balance at the end, :func:`_settle_estimate`), "not balanced" (settled
        elsewhere), "no balancer" or "failed"; ``settle_estimate`` (ic): the estimated time to
        balance of a start not settled (s, NaN for the others); ``status`` (ic): the integrator's (:class:`rotorlab.integrate.Status`; its
        sanity monitor fails a run beyond the structure's validity,
        :meth:`~rotorlab.models.Machine.impossible_states`), or ``UNSTABLE`` where the structure is
        unstable at the final speed (:func:`flag_unstable`); ``attrs["status_detail"]``: why the
        first failed run failed.
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    ang = np.asarray(initial_ball_angles, dtype=float)
    if ang.ndim == 1:
        ang = ang[None, :]
    if ang.ndim != 2 or ang.shape[1] != machine.n_balls:
        raise ValueError(f"initial_ball_angles must have shape (n_starts, {machine.n_balls}) "
                         f"(rad), got {np.shape(initial_ball_angles)}")
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    y0 = np.array([machine.initial_state(a) for a in ang])
    lay = machine.layout
    if machine.is_motor:
        om_end = float(machine.drive.no_load_speed) if machine.drive.kind == "linear" else \
            float(max(machine.drive.torque[0]))
    else:
        om_end = float(machine.drive.spin_speed(t_end))
    window = min(t_end, window_revolutions * 2 * np.pi / max(abs(om_end), 1e-12))
    n_window = int(max(16, min(2000, window_revolutions * _SAMPLES_PER_REV)))
    ts = np.linspace(t_end - window, t_end, n_window)
    earlier = _earlier_windows(ts, t_end)
    ts_all, hist = np.union1d(ts, earlier.ravel()), None
    if n_save is not None:
        if isinstance(n_save, bool) or int(n_save) != n_save or n_save < 2:
            raise ValueError(f"n_save must be an integer >= 2, got {n_save!r}")
        check_saved_states(machine, n_save, len(ang))  # refused up front, as a run-up's
        hist = np.linspace(0.0, t_end, int(n_save))
        ts_all = np.union1d(hist, ts_all)
    sol = solve_ensemble(machine, y0, (0.0, t_end), save_at=SaveAt(ts=ts_all),
                         control=StepControl(rtol=rtol, atol=atol), threads=threads,
                         progress=progress)
    ys_all = sol.ys
    ys = ys_all[:, np.searchsorted(ts_all, ts)]  # the final window
    amp = orbit_amplitude(machine, ys)
    th = np.array([machine.spin(t_end, y)[0] for y in sol.y_final])
    om = np.array([machine.spin(t_end, y)[1] for y in sol.y_final])
    rel = _wrap(sol.y_final[:, lay.i_phi:lay.i_phi + lay.n_balls] - th[:, None])
    ref = unbalance_amplitudes(machine, float(om[0])) if om.size else np.zeros(machine.structure.n_nodes)
    # ball rates relative to the rotor over the final window (largest |psi'|)
    om_t = np.array([[machine.spin(t, y)[1] for t, y in zip(ts, traj)] for traj in ys])
    rates = ys[:, :, lay.i_w:lay.i_w + lay.n_balls] - om_t[:, :, None]
    max_rate = np.abs(rates).reshape(len(ang), -1).max(axis=1, initial=0.0)
    crit = structure_critical_speeds(machine)
    first = float(crit[0]) if crit.size else 0.0
    status, notes = flag_unstable(machine, sol.status, om, sol.notes)
    outcome = [_outcome(int(st), a, ref, r, w, lay.n_balls, first)
               for st, a, r, w in zip(status, amp, max_rate, om)]
    settle = _settle_estimate(machine, ys_all, ts_all, earlier, amp, ref, t_end)
    for i, text in enumerate(outcome):  # still converging towards balance: not settled, not "not balanced"
        if text not in ("balanced", "failed", "no balancer") and status[i] >= 0 and np.isfinite(settle[i]):
            outcome[i] = NOT_SETTLED
    labels = list(machine.structure.node_label)
    ds = xr.Dataset(
        {
            "final_ball_angle": (("ic", "ball"), rel, {"units": "rad"}),
            "amplitude": (("ic", "station"), amp, {"units": "m"}),
            "reference_amplitude": (("station",), ref, {"units": "m"}),
            "final_speed": (("ic",), om, {"units": "rad/s"}),
            "initial_ball_angle": (("ic", "ball"), ang, {"units": "rad"}),
            "max_final_rate": (("ic",), max_rate, {"units": "rad/s"}),
            "settle_estimate": (("ic",), settle, {"units": "s", "long_name": "estimated time to balance of a start "
                                                                            "not settled (NaN: not converging)"}),
            "outcome": (("ic",), np.asarray(outcome, dtype=str)),
            "status": (("ic",), status),
        },
        coords={"ic": np.arange(ang.shape[0]), "station": labels, **_ball_coords(machine)},
        attrs={"analysis": "simulate", "model": "machine", "t_end": float(t_end),
               "window": float(window), "status_detail": status_detail(notes)},
    )
    if hist is not None:
        ds = ds.assign_coords(time=("time", hist, {"units": "s"}))
        saved = ys_all[:, np.searchsorted(ts_all, hist)]
        ds["displacement"] = (("ic", "time", "station"), machine.station_amplitudes(saved), {"units": "m"})
        ds = add_figure_variables(ds, machine, saved, ("ic", "time"))
    return ds


def _earlier_windows(ts: np.ndarray, t_end: float) -> np.ndarray:
    """The final window's save times shifted back by 20 % and 10 % of the run (shape (2, n)), or
    an empty array when the run is too short for them to start after t = 0."""
    shifts = np.array([[-2.0 * SETTLE_STEP * t_end], [-SETTLE_STEP * t_end]])
    return ts[None, :] + shifts if ts[0] + shifts[0, 0] >= 0.0 else np.empty((0, ts.size))


def _settle_estimate(machine, ys_all, ts_all, earlier, amp, ref, t_end) -> np.ndarray:
    """Estimated time to balance (s) of each start whose vibration still falls towards
    :data:`~rotorlab.analyses.BALANCED_FRACTION` of the locked unbalance response, NaN for the
    others: :func:`rotorlab.explore._settle.settle_estimate` on the vibration amplitude (largest
    over the stations) in the final window and the windows ending 10 % and 20 % of the run
    earlier."""
    n = amp.shape[0]
    if earlier.shape[0] == 0 or n == 0:
        return np.full(n, np.nan)
    worst = [orbit_amplitude(machine, ys_all[:, np.searchsorted(ts_all, w)]).max(axis=1) for w in earlier]
    worst = np.stack([*worst, amp.max(axis=1)], axis=1)
    horizons = t_end * np.array([1.0 - 2.0 * SETTLE_STEP, 1.0 - SETTLE_STEP, 1.0])
    return settle_estimate(worst, np.full(n, BALANCED_FRACTION * float(np.max(ref))), horizons)[:, -1]


def _run_simulate(case_model, analysis, progress=None):
    omega = analysis.spin_speed(case_model)
    m = _variant(case_model, analysis, omega)
    sets = analysis.ball_angle_sets(m.n_balls)
    angles = np.array(sets, dtype=float).reshape(len(sets), m.n_balls)
    ds = machine_simulate(m, angles, t_end=analysis.duration(case_model), rtol=analysis.rtol,
                          atol=analysis.atol, n_save=analysis.n_save, progress=progress)
    return _annotate(ds, case_model, analysis)


def _simulate_task_size(case_model, analysis) -> int:
    return len(analysis.ball_angle_sets(case_model.balls_in(analysis.races)))


def _simulate_rows(ds) -> list[dict[str, Any]]:
    rows = []
    for i in range(ds.sizes["ic"]):
        rows.append({
            "ic": i, "final_speed": _num(ds.final_speed.values[i]),
            "final_speed_rpm": _num(ds.final_speed.values[i] * 30 / np.pi),
            "initial_ball_angles_deg": _per_race(ds, ds.initial_ball_angle.values[i]),
            "final_ball_angles_deg": _per_race(ds, ds.final_ball_angle.values[i]),
            "amplitude": _per_station(ds, ds.amplitude.values[i]),
            "reference_amplitude": _per_station(ds, ds.reference_amplitude.values),
            "outcome": str(ds.outcome.values[i]),
            "status": int(ds.status.values[i]),
            "settle_estimate_s": _num(ds.settle_estimate.values[i]) if "settle_estimate" in ds else None,
        })
    return rows


def machine_analysis_types() -> dict[str, Any]:
    """The machine's own implementations of the common analysis types (its ``ModelType.analyses``)."""
    from rotorlab.analyses._machine_run_up import _run_run_up, _run_up_rows, _run_up_task_size
    from rotorlab.analyses._machine_steady import (_chart_rows, _chart_task_size, _run_chart, _run_steady,
                                                   _steady_rows)
    from rotorlab.analyses._registry import AnalysisType

    return {
        "simulate": AnalysisType("simulate", _run_simulate, _simulate_rows, "machine", _simulate_task_size,
                                 "trajectories"),
        "steady": AnalysisType("steady", _run_steady, _steady_rows, "machine"),
        "stability-chart": AnalysisType("stability-chart", _run_chart, _chart_rows, "machine", _chart_task_size),
        "run-up": AnalysisType("run-up", _run_run_up, _run_up_rows, "machine", _run_up_task_size),
    }


def machine_mapper(case_model, analysis, kw):
    """The regime mapper of a machine's basins and sweeps (:class:`rotorlab.explore.MachineRegimes`
    at the analysis' constant speed; None without balls)."""
    from rotorlab.explore import MachineRegimes
    from rotorlab.integrate import StepControl

    if case_model.n_balls == 0:
        return None
    omega = analysis.spin_speed(case_model)
    if omega is None:  # spin_speed is a coordinate of every start: any base speed will do
        omega = case_model.critical_speed()
    if analysis.rtol is not None or analysis.atol is not None:
        kw["control"] = StepControl(rtol=analysis.rtol or 1e-8, atol=analysis.atol or 1e-10)
    source = machine_model(case_model)
    return MachineRegimes(_variant(case_model, analysis, omega, source=source), source=source,
                          races=getattr(analysis, "races", None), **kw)
