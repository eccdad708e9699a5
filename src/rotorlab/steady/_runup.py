"""Run-up through the critical speed with a prescribed omega(t): with and without the balancer.

The rotor with its balls and the same disc without balls are integrated in the co-rotating frame
along the same speed profile (:class:`rotorlab.models.LinearRamp` or
:class:`rotorlab.models.HillRunUp`); the result gives the largest shaft deflection of each, and
whether the balls synchronise (come to rest relative to the rotor on a predicted steady motion)
after the passage.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.steady._analysis import analyze_steady
from rotorlab.steady._motions import wrap
from rotorlab.steady._verify import match_state, typical_deflection
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls

__all__ = ["run_up"]


def run_up(model: JeffcottBalls, profile: Any, *, t_end: float, initial_ball_angles: Any = None,
           t_start: float = 0.0, n_save: int = 2000, settle_revolutions: float = 20.0,
           rate_tol: float = 1e-4, angle_tol: float = 0.05, rtol: float = 1e-8, atol: float = 1e-11,
           threads: int | None = None) -> xarray.Dataset:  # fmt: skip
    """Run the rotor up along ``profile`` with and without its balancer.

    Parameters
    ----------
    model : JeffcottBalls
        Rotor and balls without Coulomb friction (its speed profile is replaced).
    profile : LinearRamp or HillRunUp or ConstantSpeed
        Prescribed omega(t).
    t_end : float
        End time (s); the balls' synchronisation is judged over its last revolutions.
    initial_ball_angles : array_like, shape (n_ic, n), optional
        Start angles psi_i (rad); default: the balls spread evenly, ``psi_i = 2 pi i / n + 0.3``.
    t_start : float
        Start time (s) (> 0 for a Hill profile with exponent < 1).
    n_save : int
        Points of the saved time grid on [t_start, t_end].
    settle_revolutions : float
        Final window (revolutions at the final speed) in which the balls must rest relative to the
        rotor to count as synchronised.
    rate_tol : float
        Synchronised: every ``|psi_i'|`` and the rotor's co-rotating velocity / deflection scale below
        ``rate_tol * omega`` over the window.
    angle_tol : float
        Tolerance of the match to a steady motion at the final speed (rad).
    rtol, atol : float
        Integrator tolerances.
    threads : int, optional

    Returns
    -------
    xarray.Dataset
        Dims ``ic``, ``time``, ``ball``. Coordinates ``time`` (s), ``speed`` (time; rad/s),
        ``speed_rpm``. Variables: ``amplitude`` (ic, time; m) and ``amplitude_without`` (time; m,
        the disc alone), ``ball_angle`` (ic, time, ball; rad), ``max_amplitude`` (ic),
        ``max_amplitude_without``, ``speed_at_max`` (ic) and ``speed_at_max_without`` (rad/s),
        ``final_amplitude`` (ic) and ``final_amplitude_without`` (m, mean over the window),
        ``synchronised`` (ic), ``final_motion`` (ic; label of the steady motion reached at the
        final speed, or ``"none"``), ``final_ball_angle`` (ic, ball; rad), ``status`` (ic) and
        ``status_without``. Attributes: the critical speeds with (``critical_speed``) and without
        (``critical_speed_without``) the balls (rad/s), ``final_speed``.

    Notes
    -----
    "Without the balancer" is the same disc, unbalance and shaft with the balls removed (its
    critical speed is sqrt(c / M1), slightly higher than sqrt(c / M)).

    Examples
    --------
    A fast ramp through p: the balls synchronise and balance the rotor.

    >>> from rotorlab.models import LinearRamp
    >>> from rotorlab.steady import steady_case
    >>> case = steady_case("zhakash-k2")
    >>> p = case.critical_speed()
    >>> ds = run_up(case.model("enough"), LinearRamp(0.3 * p, 2.5 * p, 0.22), t_end=12.0,
    ...             initial_ball_angles=[[0.3, 2.0]], n_save=500)
    >>> bool(ds.synchronised[0]), str(ds.final_motion.values[0]), float(ds.final_amplitude[0]) < 1e-5
    (True, 'main-', True)
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
    from rotorlab.models import JeffcottBalls

    if model.has_friction:
        raise ValueError("run_up needs a model without Coulomb friction (set friction=0)")
    n = model.n_balls
    if initial_ball_angles is None:
        angles = (2.0 * np.pi * np.arange(n) / max(n, 1) + 0.3)[None, :]
    else:
        angles = np.asarray(initial_ball_angles, dtype=float).reshape(-1, n)
    if not (math.isfinite(t_end) and t_end > t_start):
        raise ValueError(f"t_end must be finite and > t_start = {t_start} (s), got {t_end!r}")
    rot = model.with_speed(profile).with_frame("rotating")
    bare = JeffcottBalls(model.rotor, (), speed=profile, frame="rotating")
    ts = np.linspace(float(t_start), float(t_end), int(n_save))
    control = StepControl(rtol=float(rtol), atol=float(atol))
    y0 = np.array([rot.initial_state(row, t0=float(t_start)) for row in angles])
    sol = solve_ensemble(rot, y0, (float(t_start), float(t_end)), save_at=SaveAt(ts=ts), control=control,
                         threads=threads)  # fmt: skip
    ref = solve_ensemble(bare, np.zeros(4), (float(t_start), float(t_end)), save_at=SaveAt(ts=ts),
                         control=control, threads=1)  # fmt: skip
    speed = np.asarray(profile.spin_speed(ts), dtype=float)
    om_end = float(speed[-1])
    amp = np.hypot(sol.ys[:, :, 0], sol.ys[:, :, 1])
    amp0 = np.hypot(ref.ys[0, :, 0], ref.ys[0, :, 1])
    window = ts >= t_end - settle_revolutions * 2.0 * math.pi / max(abs(om_end), 1e-300)
    window[-1] = True
    n_ic = angles.shape[0]
    synced = np.zeros(n_ic, dtype=bool)
    final_motion = np.full(n_ic, "none", dtype=object)
    analysis = analyze_steady(model, om_end) if om_end > 0 else None
    scale = typical_deflection(model, om_end) if om_end > 0 else 1.0
    for i in range(n_ic):
        ys = sol.ys[i][window]
        if sol.status[i] < 0 or analysis is None:
            continue
        ball_rate = float(np.max(np.abs(ys[:, 4 + n :]))) if n else 0.0
        rotor_rate = float(np.max(np.hypot(ys[:, 2], ys[:, 3]))) / scale
        if max(ball_rate, rotor_rate) <= rate_tol * om_end:
            synced[i] = True
            final_motion[i] = match_state(analysis, sol.y_final[i], scale, angle_tol=angle_tol) or "none"
    k_max = np.argmax(amp, axis=1)
    k0 = int(np.argmax(amp0))
    p = model.critical_speed
    p0 = math.sqrt(model.rotor.stiffness / model.rotor.disc_mass)
    ic, tm, ib = ("ic",), ("ic", "time"), ("ic", "ball")

    def v(dims, values, units, long_name):
        return dims, values, {"units": units, "long_name": long_name}

    data = {
        "amplitude": v(tm, amp, "m", "shaft deflection with the balancer"),
        "amplitude_without": v(("time",), amp0, "m", "shaft deflection without the balancer"),
        "ball_angle": v(("ic", "time", "ball"), wrap(sol.ys[:, :, 4 : 4 + n]), "rad", "ball angle from the unbalance"),
        "max_amplitude": v(ic, amp.max(axis=1), "m", "largest deflection with the balancer"),
        "max_amplitude_without": v((), float(amp0.max()), "m", "largest deflection without the balancer"),
        "speed_at_max": v(ic, speed[k_max], "rad/s", "speed at the largest deflection"),
        "speed_at_max_without": v((), float(speed[k0]), "rad/s", "speed at the largest deflection, no balancer"),
        "final_amplitude": v(ic, amp[:, window].mean(axis=1), "m", "mean deflection, final window"),
        "final_amplitude_without": v((), float(amp0[window].mean()), "m", "mean deflection, final window, no balancer"),
        "synchronised": v(ic, synced, "1", "balls at rest relative to the rotor at the end"),
        "final_motion": v(ic, final_motion.astype(str), "1", "steady motion reached"),
        "final_ball_angle": v(ib, wrap(sol.y_final[:, 4 : 4 + n]), "rad", "final ball angle"),
        "initial_ball_angle": v(ib, angles, "rad", "start angle"),
        "status": v(ic, sol.status.astype(np.int32), "1", "integrator status"),
        "status_without": v((), int(ref.status[0]), "1", "integrator status, no balancer"),
    }  # fmt: skip
    return xr.Dataset(
        data,
        coords={
            "time": ("time", ts, {"units": "s"}),
            "speed": ("time", speed, {"units": "rad/s", "long_name": "spin speed"}),
            "speed_rpm": ("time", speed * _RPM, {"units": "rpm"}),
            "ic": ("ic", np.arange(n_ic), {"units": "1"}),
            "ball": ("ball", np.arange(1, n + 1), {"units": "1"}),
        },
        attrs={
            "analysis": "run-up", "model": "jeffcott_balls", "integration_frame": "rotating",
            "speed_profile": type(profile).__name__, "critical_speed": p, "critical_speed_without": p0,
            "final_speed": om_end, "settle_revolutions": settle_revolutions, "rate_tol": rate_tol,
        },  # fmt: skip
    )
