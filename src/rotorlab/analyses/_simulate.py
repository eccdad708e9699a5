"""Time simulation of a ball balancer from many start configurations, with outcome labels."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.explore._outcome import (
    BALANCED_FRACTION,
    SETTLE_RATE,
    SIDE_TOLERANCE,
    classify,
    reference_amplitude,
    wrap_angle,
)
from rotorlab.explore._settle import NOT_SETTLED, settle_estimate
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls

__all__ = ["simulate", "SETTLE_REVOLUTIONS", "run_simulate_analysis", "simulation_rows", "simulation_task_size"]

#: Length of the final window (revolutions at the final speed) over which the final amplitude is
#: averaged and the balls must stay at rest relative to the rotor to count as settled.
SETTLE_REVOLUTIONS = 10.0


def _check_inputs(model: Any, speeds: Any, initial_ball_angles: Any, t_end: float,
                  n_save: int) -> tuple[np.ndarray | None, np.ndarray]:  # fmt: skip
    if not hasattr(model, "with_speed") or not hasattr(model, "balls"):
        raise TypeError(f"model must be a JeffcottBalls model, got {type(model).__name__}")
    if not (isinstance(t_end, (int, float)) and math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    if isinstance(n_save, bool) or int(n_save) != n_save or n_save < 2:
        raise ValueError(f"n_save must be an integer >= 2, got {n_save!r}")
    om = None
    if speeds is not None:
        om = np.atleast_1d(np.asarray(speeds, dtype=float))
        if om.ndim != 1 or om.size == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
            raise ValueError(f"speeds must be finite numbers > 0 (rad/s), got {speeds!r}")
    angles = np.asarray(initial_ball_angles, dtype=float)
    if angles.ndim == 1 and model.n_balls == 1:
        angles = angles[:, None]
    if angles.ndim != 2 or angles.shape[0] == 0 or angles.shape[1] != model.n_balls:
        raise ValueError(
            f"initial_ball_angles must have shape (n_configurations, {model.n_balls}) "
            f"(one angle per ball, rad), got shape {angles.shape}"
        )
    if not np.all(np.isfinite(angles)):
        raise ValueError("initial_ball_angles must be finite (rad)")
    return om, angles


def simulate(
    model: JeffcottBalls,
    *,
    speeds: Any,
    initial_ball_angles: Any,
    t_end: float,
    n_save: int = 2000,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    progress: Callable[[int, int], None] | None = None,
    threads: int | None = None,
    frame: str = "auto",
) -> xarray.Dataset:
    """Simulate start-ups of a ball balancer at constant speeds and label where each one ends.

    Every trajectory starts with the disc centre at rest on the shaft axis and the balls at
    rest relative to the rotor at the given angles from the unbalance. All trajectories of one
    speed are integrated in one parallel :func:`rotorlab.integrate.solve_ensemble` call, in the
    frame where they are cheapest (``frame``); results are reported in both frames.

    Parameters
    ----------
    model : JeffcottBalls
        The rotor and its balls (any frame; its speed profile is replaced unless ``speeds`` is
        None).
    speeds : array_like, shape (n_speed,), or None
        Constant spin speeds omega (rad/s), > 0. None: follow the model's own speed profile
        (one entry on the ``speed`` dim, valued at its speed at ``t_end``).
    initial_ball_angles : array_like, shape (n_ic, n_balls)
        Start configurations: angle of each ball from the unbalance (rad).
    t_end : float
        Simulated time (s), > 0.
    n_save : int
        Points of the saved uniform time grid on [0, t_end], >= 2.
    rtol, atol : float
        Integrator tolerances (relative; absolute, in SI units of each state).
    progress : callable, optional
        Called as ``progress(done, total)`` with trajectories finished so far, over all speeds.
    threads : int, optional
        Number of threads (default: numba's). Results do not depend on it.
    frame : {"auto", "fixed", "rotating"}
        Frame the states are integrated in. ``"auto"`` (default): per speed, the cheaper one
        (:meth:`~rotorlab.models.JeffcottBalls.cheapest_frame`: fixed from 1.8 times the
        critical speed with the capacity to balance, where a balanced start takes about a third
        of the right-hand-side evaluations of the co-rotating frame; co-rotating below, where
        steady motions are equilibria); a speed profile is judged by its speed at ``t_end``.
        The results agree to the integrator tolerance; ``attrs["integration_frame"]`` names the
        frame of each speed.

    Returns
    -------
    xarray.Dataset
        Dims ``speed``, ``ic``, ``time``, ``ball``; coordinates ``speed`` (rad/s),
        ``speed_rpm``, ``speed_ratio`` (omega / p), ``time`` (s), ``ic``, ``ball`` (1..n).
        Variables: ``amplitude`` (shaft deflection, m), ``x``, ``y`` (disc centre in the fixed
        frame, m), ``ball_angle`` (from the unbalance, wrapped to (-pi, pi], rad),
        ``ball_rate`` (relative to the rotor, rad/s), ``status``, ``n_steps``,
        ``initial_ball_angle`` (ic, ball), ``final_amplitude`` (m, mean over the last
        :data:`SETTLE_REVOLUTIONS` revolutions), ``final_ball_angle`` (rad),
        ``max_final_rate`` (largest ``|relative rate|`` over that window, rad/s), ``outcome`` (str,
        see :func:`rotorlab.analyses.classify`), ``reference_amplitude`` (speed; deflection
        caused by the unbalance alone, m) and ``critical_speed`` (p, rad/s).

    Raises
    ------
    ValueError
        Bad speeds, angles, times, tolerances or frame (nothing is integrated).

    Notes
    -----
    Frames: x + i y = e^{i theta} (u + i v), phi_i = theta + psi_i (see
    :mod:`rotorlab.models._jeffcott_balls`). The saved states of either frame give the other's
    at the same times: ``x``, ``y`` are rotated from (u, v), or the amplitude and the ball angles
    and rates taken from (x, y) and phi_i - theta, phi_i' - Omega. Seed 002 predicts, for two balls with
    eta = M1 e / (m R) < 2, the balanced state psi = +-(pi - arccos(eta / 2)) stable only for
    omega > p, and both balls on the unbalance side stable for omega < p.

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> rotor = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
    >>> ball = BallParams(mass=0.03, radius=0.05, damping=2e-3)
    >>> model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0))
    >>> ds = simulate(model, speeds=[2 * model.critical_speed], t_end=5.0, n_save=200,
    ...               initial_ball_angles=[[0.5, 2.5]])
    >>> import numpy as np
    >>> str(ds.outcome.item()), np.round(np.degrees(ds.final_ball_angle.values[0, 0]), 1) + 0.0
    ('balanced', array([-120.,  120.]))
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, Status, StepControl, solve_ensemble
    from rotorlab.models import ConstantSpeed

    om_list, angles = _check_inputs(model, speeds, initial_ball_angles, t_end, n_save)
    if frame not in ("auto", "fixed", "rotating"):
        raise ValueError(f"frame must be 'auto', 'fixed' or 'rotating', got {frame!r}")
    control = StepControl(rtol=float(rtol), atol=float(atol))
    n_ic, n = angles.shape
    t_end = float(t_end)
    from rotorlab._memory import check_memory

    n_speeds = 1 if om_list is None else len(om_list)
    n_state = model.kernels.n_state
    check_memory(8.0 * n_speeds * n_ic * int(n_save) * (2 * n_state + 3 * n + 3),
                 f"{n_speeds} speed(s) x {n_ic} start(s) x n_save = {int(n_save)} saved states of {n_state} entries",
                 "save fewer states (n_save) or simulate fewer starts")  # fmt: skip
    ts = np.linspace(0.0, t_end, int(n_save))
    models = [model] if om_list is None else [model.with_speed(ConstantSpeed(float(om))) for om in om_list]
    models = [m.with_frame(m.cheapest_frame(float(m.speed.spin_speed(t_end))) if frame == "auto" else frame)
              for m in models]  # fmt: skip
    total = n_ic * len(models)
    chunk = None
    if progress is not None:
        import numba

        chunk = max(int(threads or numba.get_num_threads()), math.ceil(n_ic / 20))
    shape = (len(models), n_ic)
    out = {
        "amplitude": np.empty((*shape, ts.size)),
        "x": np.empty((*shape, ts.size)),
        "y": np.empty((*shape, ts.size)),
        "ball_angle": np.empty((*shape, ts.size, n)),
        "ball_rate": np.empty((*shape, ts.size, n)),
        "status": np.empty(shape, dtype=np.int32),
        "n_steps": np.empty(shape, dtype=np.int64),
        "final_amplitude": np.empty(shape),
        "final_ball_angle": np.empty((*shape, n)),
        "max_final_rate": np.empty(shape),
        "outcome": np.empty(shape, dtype=object),
        "settle_estimate": np.empty(shape),
    }
    speed_end = np.empty(len(models))
    reference = np.empty(len(models))
    r = model.rotor
    for k, rot in enumerate(models):
        if rot.has_friction:  # each start's stick/slip modes settled one at a time
            y0 = np.array([rot.initial_state(row) for row in angles])
        else:  # rot.initial_state of every start at once (0.2 ms a start one at a time)
            yr = np.zeros((n_ic, rot.n_state))
            yr[:, 4 : 4 + n] = angles
            y0 = rot.with_frame("rotating").to_frame(0.0, yr, rot.frame)

        def report(done: int, _total: int, offset: int = k * n_ic) -> None:
            progress(offset + done, total)  # type: ignore[misc]

        sol = solve_ensemble(
            rot, y0, (0.0, t_end), save_at=SaveAt(ts=ts), control=control, threads=threads,
            chunk_size=chunk, progress=None if progress is None else report,
        )  # fmt: skip
        om_end = float(rot.speed.spin_speed(t_end))
        speed_end[k] = om_end
        reference[k] = reference_amplitude(r.imbalance, r.stiffness, rot.total_mass, r.damping, om_end)
        _saved_states(rot, ts, sol.ys, out, k)
        out["status"][k] = sol.status
        out["n_steps"][k] = sol.stats[:, 1] + sol.stats[:, 2]
        window = ts >= t_end - SETTLE_REVOLUTIONS * 2.0 * math.pi / max(abs(om_end), 1e-300)
        window[-1] = True
        ok = sol.status >= 0
        amp_win = out["amplitude"][k][:, window]
        rate_win = np.abs(out["ball_rate"][k][:, window, :]).reshape(n_ic, -1)
        out["final_amplitude"][k] = np.where(ok, amp_win.mean(axis=1), np.nan)
        out["max_final_rate"][k] = np.where(ok, rate_win.max(axis=1, initial=0.0), np.nan)
        psi_end = sol.y_final[:, 4 : 4 + n] - (float(rot.speed.spin_angle(t_end)) if rot.frame == "fixed" else 0.0)
        out["final_ball_angle"][k] = np.where(ok[:, None], wrap_angle(psi_end), np.nan)
        distance = np.maximum(out["amplitude"][k] / (BALANCED_FRACTION * reference[k]),
                              np.abs(out["ball_rate"][k]).max(axis=2, initial=0.0) / (SETTLE_RATE * abs(om_end)))
        out["settle_estimate"][k] = _settle_estimate(ts, distance, window)
        for i in range(n_ic):
            code = int(sol.status[i])
            note = sol.notes[i] if sol.notes else ""
            out["outcome"][k, i] = classify(
                code, note or Status(code).message, float(out["final_amplitude"][k, i]),
                float(reference[k]), out["final_ball_angle"][k, i],
                float(out["max_final_rate"][k, i]), om_end,
            )  # fmt: skip
            if out["outcome"][k, i] != "balanced" and code >= 0 and np.isfinite(out["settle_estimate"][k, i]):
                out["outcome"][k, i] = NOT_SETTLED

    p = model.critical_speed
    dims2 = ("speed", "ic")
    flags = " ".join(f"{int(st)}:{st.name.lower()}" for st in Status)
    ds = xr.Dataset(
        {
            "amplitude": (("speed", "ic", "time"), out["amplitude"],
                          {"units": "m", "long_name": "shaft deflection at the disc"}),
            "x": (("speed", "ic", "time"), out["x"],
                  {"units": "m", "long_name": "disc centre x (fixed frame)"}),
            "y": (("speed", "ic", "time"), out["y"],
                  {"units": "m", "long_name": "disc centre y (fixed frame)"}),
            "ball_angle": (("speed", "ic", "time", "ball"), out["ball_angle"],
                           {"units": "rad", "long_name": "ball angle from the unbalance"}),
            "ball_rate": (("speed", "ic", "time", "ball"), out["ball_rate"],
                          {"units": "rad/s", "long_name": "ball rate relative to the rotor"}),
            "status": (dims2, out["status"], {"units": "1", "flag_meanings": flags}),
            "n_steps": (dims2, out["n_steps"], {"units": "1", "long_name": "integrator steps"}),
            "initial_ball_angle": (("ic", "ball"), angles,
                                   {"units": "rad", "long_name": "initial ball angle"}),
            "final_amplitude": (dims2, out["final_amplitude"],
                                {"units": "m", "long_name": "mean deflection, final window"}),
            "final_ball_angle": (("speed", "ic", "ball"), out["final_ball_angle"],
                                 {"units": "rad", "long_name": "final ball angle"}),
            "max_final_rate": (dims2, out["max_final_rate"],
                               {"units": "rad/s", "long_name": "largest |ball rate|, final window"}),
            "outcome": (dims2, out["outcome"].astype(str), {"long_name": "outcome"}),
            "settle_estimate": (dims2, out["settle_estimate"],
                                {"units": "s", "long_name": "estimated time to balance of a start not settled"}),
            "reference_amplitude": (("speed",), reference,
                                    {"units": "m", "long_name": "deflection, unbalance alone"}),
            "critical_speed": ((), p, {"units": "rad/s", "long_name": "critical speed p"}),
        },  # fmt: skip
        coords={
            "speed": ("speed", speed_end, {"units": "rad/s", "long_name": "spin speed"}),
            "speed_rpm": ("speed", speed_end * _RPM, {"units": "rpm"}),
            "speed_ratio": ("speed", speed_end / p, {"units": "1", "long_name": "omega / p"}),
            "time": ("time", ts, {"units": "s"}),
            "ic": ("ic", np.arange(n_ic), {"units": "1", "long_name": "initial configuration"}),
            "ball": ("ball", np.arange(1, n + 1), {"units": "1"}),
        },
        attrs={
            "analysis": "simulate",
            "model": "jeffcott_balls",
            "integration_frame": ", ".join(m.frame for m in models),
            "speed_profile": "constant" if om_list is not None else type(model.speed).__name__,
            "t_end": t_end,
            "rtol": float(rtol),
            "atol": float(atol),
            "settle_revolutions": SETTLE_REVOLUTIONS,
            "balanced_fraction": BALANCED_FRACTION,
            "settle_rate": SETTLE_RATE,
            "side_tolerance": SIDE_TOLERANCE,
        },
    )
    return ds


def _saved_states(rot: Any, ts: np.ndarray, ys: np.ndarray, out: dict, k: int) -> None:
    """Fill ``out[...][k]`` (amplitude, x, y, ball angle and rate) from the states ``ys`` (ic,
    time, state) saved at ``ts`` in ``rot``'s frame: the states of that frame are copied, the
    other frame's computed from them at the same times."""
    n = rot.n_balls
    theta = np.broadcast_to(np.asarray(rot.speed.spin_angle(ts), dtype=float), ts.shape)
    a, b = ys[:, :, 0], ys[:, :, 1]
    if rot.frame == "fixed":  # x, y saved; psi_i = phi_i - theta, psi_i' = phi_i' - Omega
        out["x"][k], out["y"][k] = a, b
        out["ball_angle"][k] = wrap_angle(ys[:, :, 4 : 4 + n] - theta[:, None])
        omega = np.broadcast_to(np.asarray(rot.speed.spin_speed(ts), dtype=float), ts.shape)
        out["ball_rate"][k] = ys[:, :, 4 + n : 4 + 2 * n] - omega[:, None]
    else:  # u, v saved: x + i y = e^{i theta} (u + i v)
        c, s = np.cos(theta), np.sin(theta)
        out["x"][k] = c * a - s * b
        out["y"][k] = s * a + c * b
        out["ball_angle"][k] = wrap_angle(ys[:, :, 4 : 4 + n])
        out["ball_rate"][k] = ys[:, :, 4 + n : 4 + 2 * n]
    out["amplitude"][k] = np.hypot(a, b)


def _settle_estimate(ts: np.ndarray, distance: np.ndarray, window: np.ndarray) -> np.ndarray:
    """Estimated time to balance (s) of every start whose distance to the balanced state (in units
    of its thresholds, balanced below 1) still falls towards it at the end, NaN for the others:
    :func:`rotorlab.explore._settle.settle_estimate` on the largest distance over the final
    window and the windows ending 10 % and 20 % of the run earlier."""
    width = int(window.sum())
    step = max(ts.size // 10, 1)
    ends = [ts.size - 1 - 2 * step, ts.size - 1 - step, ts.size - 1]
    if ends[0] - width + 1 < 0:
        return np.full(distance.shape[0], np.nan)
    worst = np.stack([distance[:, e - width + 1:e + 1].max(axis=1) for e in ends], axis=1)
    return settle_estimate(worst, np.ones(distance.shape[0]), ts[ends])[:, -1]


def run_simulate_analysis(case_model: Any, analysis: Any,
                          progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Run a case's ``simulate`` analysis (see :func:`simulate`); ``attrs["name"]`` is its name."""
    from rotorlab.analyses._case import build_model

    model = build_model(case_model)
    omega = analysis.spin_speed(case_model)
    sets = analysis.ball_angle_sets(model.n_balls)
    angles = np.array(sets, dtype=float).reshape(len(sets), model.n_balls)
    ds = simulate(model, speeds=None if omega is None else [omega], initial_ball_angles=angles,
                  t_end=analysis.duration(case_model), n_save=analysis.n_save, rtol=analysis.rtol,
                  atol=analysis.atol, progress=progress)  # fmt: skip
    ds.attrs["name"] = analysis.name
    return ds


def simulation_task_size(case_model: Any, analysis: Any) -> int:
    """Trajectories of a case's ``simulate`` analysis (its progress-bar total)."""
    return len(analysis.ball_angle_sets(case_model.n_balls))


def _degrees(values: np.ndarray) -> list[float | None]:
    return [None if not np.isfinite(v) else round(float(np.degrees(v)), 2) for v in values]


def _number(value: float) -> float | None:
    return float(value) if np.isfinite(value) else None


def simulation_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a simulation: one row per (speed, initial configuration).

    Returns
    -------
    list of dict
        Keys ``speed`` (rad/s), ``speed_rpm``, ``speed_hz``, ``speed_ratio`` (omega / p), ``ic``,
        ``initial_ball_angles_deg``, ``final_amplitude`` (m), ``reference_amplitude`` (m),
        ``amplitude_ratio`` (final / reference), ``final_ball_angles_deg``, ``outcome``,
        ``settle_estimate_s`` (estimated time to balance of a start ``not settled``, else None),
        ``status``. Plain Python values (JSON-ready; NaN becomes None).
    """
    rows = []
    for k in range(ds.sizes["speed"]):
        om = float(ds.speed.values[k])
        ref = float(ds.reference_amplitude.values[k])
        for i in range(ds.sizes["ic"]):
            amp = float(ds.final_amplitude.values[k, i])
            rows.append({
                "speed": om,
                "speed_rpm": om * _RPM,
                "speed_hz": om / (2.0 * math.pi),
                "speed_ratio": float(ds.speed_ratio.values[k]),
                "ic": int(ds.ic.values[i]),
                "initial_ball_angles_deg": _degrees(ds.initial_ball_angle.values[i]),
                "final_amplitude": _number(amp),
                "reference_amplitude": ref,
                "amplitude_ratio": _number(amp / ref) if ref > 0 else None,
                "final_ball_angles_deg": _degrees(ds.final_ball_angle.values[k, i]),
                "outcome": str(ds.outcome.values[k, i]),
                "settle_estimate_s": _number(float(ds.settle_estimate.values[k, i])) if "settle_estimate" in ds
                else None,
                "status": int(ds.status.values[k, i]),
            })  # fmt: skip
    return rows
