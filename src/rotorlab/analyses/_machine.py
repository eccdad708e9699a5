"""Analyses of the composed machine (:class:`rotorlab.models.Machine`): simulation from many ball
starts, steady balanced states and their exact stability over speed, and run-ups.

All functions are pure: a model in, an :class:`xarray.Dataset` out (SI units in ``attrs``), with
an integer ``status`` per element (0: success) and, where the question has no answer for this
machine (no co-rotating equilibria), a failed status and the reason in ``attrs["message"]``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["machine_simulate", "machine_steady", "machine_run_up", "locked_structure", "orbit_amplitude",
           "run_machine_analysis", "machine_rows", "machine_model", "machine_quantities",
           "MACHINE_ANALYSES",
           "structure_critical_speeds", "unbalance_amplitudes", "NO_STEADY_STATUS"]

#: Status of a steady analysis on a machine without co-rotating equilibria.
NO_STEADY_STATUS = 3
#: Samples per revolution in the final window of a simulation.
_SAMPLES_PER_REV = 32


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def locked_structure(machine):
    """Return the structure with the ball masses added at their races (``LinearSystem``)."""
    from rotorlab.linear import LinearSystem

    s = machine.structure
    M = s.M.copy()
    for r in machine.races:
        e = np.zeros((2, s.n_dof))
        e[0, 4 * r.node], e[1, 4 * r.node + 1] = 1.0, 1.0
        e[0, 4 * r.node + 2] = e[1, 4 * r.node + 3] = r.axial_offset
        M += sum(b.mass for b in r.balls) * (e.T @ e)
    return LinearSystem(M=M, C=s.C, G=s.G, K=s.K, node_position=s.node_position,
                        node_label=s.node_label)


def structure_critical_speeds(machine, max_speed: float | None = None) -> np.ndarray:
    """Forward-whirl 1x critical speeds of the structure with the balls locked (rad/s)."""
    from rotorlab.linear import critical_speeds

    cs = critical_speeds(locked_structure(machine), max_speed=max_speed)
    return cs.speed[cs.whirl >= 0]


def unbalance_amplitudes(machine, spin_speed: float) -> np.ndarray:
    """Steady radial amplitude per node (m) of the unbalance response without balls.

    The largest radius of each node's (elliptical) orbit, ``sqrt((|X|^2 + |Y|^2)/2 +
    |X^2 + Y^2|/2)``, from the full structure with the balls locked but not acting as balancers.
    """
    s = locked_structure(machine)
    om = float(spin_speed)
    D = s.K + 1j * om * (s.C + om * s.G) - om * om * s.M
    f = np.zeros(s.n_dof, dtype=complex)
    for u in machine.unbalances:
        ph = u.mass_eccentricity * om * om * np.exp(1j * u.phase)
        f[4 * u.node] += ph
        f[4 * u.node + 1] += -1j * ph
        f[4 * u.node + 2] += u.axial_offset * ph
        f[4 * u.node + 3] += -1j * u.axial_offset * ph
    q = np.linalg.solve(D, f)
    X, Y = q[0::4], q[1::4]
    return np.sqrt(0.5 * (np.abs(X) ** 2 + np.abs(Y) ** 2) + 0.5 * np.abs(X * X + Y * Y))


def orbit_amplitude(machine, ys) -> np.ndarray:
    """Largest distance of each node from its mean position over the saved states (m).

    Parameters
    ----------
    ys : array_like, shape (..., n_times, n_state)

    Returns
    -------
    ndarray, shape (..., n_nodes)
        The vibration amplitude, without the static deflection (e.g. under gravity).
    """
    q = machine.displacements(np.asarray(ys, dtype=float))
    x, y = q[..., 0::4], q[..., 1::4]
    dx = x - x.mean(axis=-2, keepdims=True)
    dy = y - y.mean(axis=-2, keepdims=True)
    return np.hypot(dx, dy).max(axis=-2)


def _with_units(ds):
    """Give every variable and coordinate without a unit the unit "1" (counts, flags, labels)."""
    for name in (*ds.data_vars, *ds.coords):
        ds[name].attrs.setdefault("units", "1")
    return ds


def _ball_coords(machine) -> dict[str, Any]:
    race = [i for i, r in enumerate(machine.races) for _ in r.balls]
    return {"ball": np.arange(machine.n_balls), "race": ("ball", np.asarray(race, dtype=int))}


def machine_simulate(machine, initial_ball_angles, *, t_end: float, rtol: float = 1e-8,
                     atol: float = 1e-10, window_revolutions: float = 2.0,
                     threads: int | None = None,
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

    Returns
    -------
    xarray.Dataset
        ``final_ball_angle`` (ic, ball): angle relative to the rotor (rad, wrapped to
        [-pi, pi)); ``amplitude`` (ic, station): vibration amplitude of each node in the final
        window (largest distance from its mean position, m); ``reference_amplitude`` (station): the same without balancing (the
        linear unbalance response at the final speed of each start, first start shown);
        ``final_speed`` (ic) (rad/s); ``status`` (ic).
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
    n_save = int(max(16, min(2000, window_revolutions * _SAMPLES_PER_REV)))
    ts = np.linspace(t_end - window, t_end, n_save)
    sol = solve_ensemble(machine, y0, (0.0, t_end), save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=rtol, atol=atol), threads=threads,
                         progress=progress)
    amp = orbit_amplitude(machine, sol.ys)
    th = np.array([machine.spin(t_end, y)[0] for y in sol.y_final])
    om = np.array([machine.spin(t_end, y)[1] for y in sol.y_final])
    rel = _wrap(sol.y_final[:, lay.i_phi:lay.i_phi + lay.n_balls] - th[:, None])
    ref = unbalance_amplitudes(machine, float(om[0])) if om.size else np.zeros(machine.structure.n_nodes)
    labels = list(machine.structure.node_label)
    ds = xr.Dataset(
        {
            "final_ball_angle": (("ic", "ball"), rel, {"units": "rad"}),
            "amplitude": (("ic", "station"), amp, {"units": "m"}),
            "reference_amplitude": (("station",), ref, {"units": "m"}),
            "final_speed": (("ic",), om, {"units": "rad/s"}),
            "initial_ball_angle": (("ic", "ball"), ang, {"units": "rad"}),
            "status": (("ic",), np.asarray(sol.status, dtype=np.int64)),
        },
        coords={"ic": np.arange(ang.shape[0]), "station": labels, **_ball_coords(machine)},
        attrs={"analysis": "simulate", "model": "machine", "t_end": float(t_end),
               "window": float(window)},
    )
    return ds


def machine_steady(machine, speeds, *, ball_angles=None):
    """Balanced steady states over speed and their exact stability (co-rotating frame).

    Parameters
    ----------
    machine : Machine
        Its drive is replaced by each constant speed.
    speeds : array_like
        Spin speeds (rad/s), > 0.
    ball_angles : array_like, optional
        A guess of the balanced ball angles (rad).

    Returns
    -------
    xarray.Dataset
        ``exists`` (speed): a steady motion was found (the balanced one when the balls can
        cancel the unbalance, else the one that starts from the best partial balance);
        ``balanced`` (speed): it has no vibration; ``amplitude`` (speed, station): its whirl
        radius per node (m); ``ball_angle`` (speed, ball) (rad); ``max_real_eigenvalue`` (speed) (1/s) of the linearised co-rotating equations;
        ``stable`` (speed); ``status`` (speed): 0, or ``NO_STEADY_STATUS`` with
        ``attrs["message"]`` when the machine has no co-rotating equilibria (anisotropic
        structure, gravity across the axis) - simulate it instead.
    """
    import xarray as xr

    from rotorlab.models import ConstantSpeed

    om = np.atleast_1d(np.asarray(speeds, dtype=float))
    if om.ndim != 1 or om.size == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
        raise ValueError(f"speeds must be finite numbers > 0 (rad/s), got {speeds!r}")
    nb = machine.n_balls
    exists = np.zeros(om.size, bool)
    angles = np.full((om.size, nb), np.nan)
    lam_max = np.full(om.size, np.nan)
    stable = np.zeros(om.size, bool)
    balanced = np.zeros(om.size, bool)
    amplitude = np.full((om.size, machine.structure.n_nodes), np.nan)
    status = np.zeros(om.size, np.int64)
    probe = machine.with_drive(ConstantSpeed(float(om[0])))
    message = probe.why_no_rotating_frame()
    if message is not None:
        status[:] = NO_STEADY_STATUS
    else:
        guess, near = ball_angles, None
        for i, w in enumerate(om):
            m = machine.with_drive(ConstantSpeed(float(w)))
            y = m.steady_state(guess, near=near)
            if y is None:
                continue
            nz = m.n_coordinates
            psi = y[2 * nz:2 * nz + nb]
            guess, near = psi, y
            lin = m.linearize(y)
            exists[i] = True
            balanced[i] = bool(np.all(y[:nz] == 0.0))
            angles[i] = _wrap(psi)
            lam_max[i] = float(lin.eigenvalues.real.max())
            stable[i] = lin.is_stable
            amp = m.station_amplitudes(m.rotating_to_fixed(y))
            amplitude[i] = amp
        if not exists.any():
            message = "no steady motion found at any speed (the equilibrium solver did not converge)"
    ds = xr.Dataset(
        {
            "exists": (("speed",), exists),
            "ball_angle": (("speed", "ball"), angles, {"units": "rad"}),
            "max_real_eigenvalue": (("speed",), lam_max, {"units": "1/s"}),
            "stable": (("speed",), stable),
            "balanced": (("speed",), balanced),
            "amplitude": (("speed", "station"), amplitude, {"units": "m"}),
            "status": (("speed",), status),
        },
        coords={"speed": ("speed", om, {"units": "rad/s"}), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "steady", "model": "machine",
               **({"message": message} if message else {})},
    )
    return ds


def machine_run_up(machine, *, t_end: float, n_save: int = 2000, ball_angles=None,
                   rtol: float = 1e-8, atol: float = 1e-10, initial_speed: float = 0.0):
    """Run the machine up (motor or prescribed profile) and say whether it passes its criticals.

    Returns
    -------
    xarray.Dataset
        Over ``time``: ``speed`` (rad/s), ``amplitude`` (time, station) radial displacement of
        each node (m), ``ball_angle`` (time, ball) relative to the rotor (rad). Attributes:
        ``critical_speeds`` (rad/s, forward 1x, balls locked), ``final_speed``,
        ``passed`` (number of critical speeds passed, the final speed above 1.05 times each),
        ``captured_at`` (the critical speed just above a final speed within 15 % below it, or
        NaN), ``residual_amplitude`` per station (vibration amplitude about the mean position
        over the last 10 % of the run, m).
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve

    if isinstance(n_save, bool) or int(n_save) != n_save or n_save < 10:
        raise ValueError(f"n_save must be an integer >= 10, got {n_save!r}")
    from rotorlab._memory import check_memory

    check_memory(8.0 * int(n_save) * (2 * machine.kernels.n_state + 8),
                 f"n_save = {int(n_save)} saved states of {machine.kernels.n_state} entries",
                 "save fewer states (n_save)")  # fmt: skip
    y0 = machine.initial_state(ball_angles, spin_speed=initial_speed)
    ts = np.linspace(0.0, float(t_end), int(n_save))
    sol = solve(machine, y0, (0.0, float(t_end)), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=rtol, atol=atol))
    lay = machine.layout
    spin = np.array([machine.spin(t, y) for t, y in zip(ts, sol.ys)])
    amp = machine.station_amplitudes(sol.ys)
    rel = _wrap(sol.ys[:, lay.i_phi:lay.i_phi + lay.n_balls] - spin[:, :1])
    final = float(spin[-1, 1])
    crit = structure_critical_speeds(machine, max_speed=None)
    crit = np.unique(np.round(crit, 9))
    passed = int(np.sum(final > 1.05 * crit))
    above = crit[crit >= final]
    captured = float(above[0]) if above.size and final >= 0.85 * above[0] and machine.is_motor \
        and final < 0.95 * _motor_top(machine) else math.nan
    tail = ts >= 0.9 * ts[-1]
    ds = xr.Dataset(
        {
            "speed": (("time",), spin[:, 1], {"units": "rad/s"}),
            "amplitude": (("time", "station"), amp, {"units": "m"}),
            "ball_angle": (("time", "ball"), rel, {"units": "rad"}),
            "residual_amplitude": (("station",), orbit_amplitude(machine, sol.ys[tail]),
                                   {"units": "m"}),
        },
        coords={"time": ("time", ts, {"units": "s"}), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "run-up", "model": "machine", "critical_speeds": crit,
               "final_speed": final, "passed": passed, "captured_at": captured,
               "status": int(sol.status)},
    )
    return ds


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



# --------------------------------------------------------------------------- case files


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def _deg(values) -> list[float | None]:
    return [None if not np.isfinite(v) else round(float(np.degrees(v)), 3) for v in np.ravel(values)]


def machine_model(case_model):
    """Build the :class:`~rotorlab.models.Machine` of a ``machine`` spec."""
    from rotorlab.io._machine_spec import build_machine

    return build_machine(case_model)


def machine_quantities(case_model) -> list[dict[str, Any]]:
    """Derived quantities: critical speeds (balls locked), unbalance, capacity per race."""
    m = machine_model(case_model)
    rows = [{"quantity": "critical speeds (forward 1x, balls locked)",
             "value": ", ".join(f"{w:.4g}" for w in structure_critical_speeds(m)[:6]),
             "unit": "rad/s", "sign": ""},
            {"quantity": "unbalance sum m e", "value": sum(u.mass_eccentricity for u in m.unbalances),
             "unit": "kg*m", "sign": ""}]
    for i, r in enumerate(m.races):
        rows.append({"quantity": f"capacity of race {i} (sum m l)", "value": r.capacity,
                     "unit": "kg*m", "sign": ""})
    return rows


def _variant(case_model, analysis):
    """The case's machine with only the analysis' races (all when it names none)."""
    from dataclasses import replace

    m = machine_model(case_model)
    if analysis.races is not None:
        m = replace(m, races=tuple(m.races[i] for i in analysis.races))
    return m


def _run_steady(case_model, analysis, progress):
    m = _variant(case_model, analysis)
    return machine_steady(m, np.linspace(analysis.start, analysis.stop, analysis.n_speeds))


def _run_simulate(case_model, analysis, progress):
    from rotorlab.models import ConstantSpeed

    m = _variant(case_model, analysis)
    if analysis.speed is not None:
        m = m.with_drive(ConstantSpeed(analysis.speed))
    if analysis.initial_ball_angles is None or m.n_balls == 0:
        angles = np.zeros((1, m.n_balls))
    else:
        angles = np.array([a[: m.n_balls] for a in analysis.initial_ball_angles], dtype=float)
    return machine_simulate(m, angles, t_end=analysis.t_end, rtol=analysis.rtol, atol=analysis.atol,
                            progress=progress)


def _run_run_up(case_model, analysis, progress):
    m = _variant(case_model, analysis)
    angles = None if analysis.initial_ball_angles is None else list(analysis.initial_ball_angles)[: m.n_balls]
    d = case_model.drive
    start = getattr(d, "initial_speed", 0.0)
    return machine_run_up(m, t_end=analysis.t_end, n_save=analysis.n_save, ball_angles=angles,
                          rtol=analysis.rtol, atol=analysis.atol, initial_speed=start)


_RUNNERS = {"machine-steady": _run_steady, "machine-simulate": _run_simulate,
            "machine-run-up": _run_run_up}
MACHINE_ANALYSES = tuple(_RUNNERS)


def run_machine_analysis(case_model, analysis, progress=None):
    """Run one machine analysis of a case (``machine-steady``, ``-simulate``, ``-run-up``)."""
    ds = _with_units(_RUNNERS[analysis.type](case_model, analysis, progress))
    if analysis.races is not None:
        ds.attrs["races"] = list(analysis.races)
    ds.attrs["n_races"] = len(case_model.races) if analysis.races is None else len(analysis.races)
    ds.attrs["name"] = analysis.name
    if progress is not None:
        progress(1, 1)
    return ds


def _steady_rows(ds) -> list[dict[str, Any]]:
    msg = ds.attrs.get("message")
    return [{"speed": _num(w), "speed_rpm": _num(w * 30 / np.pi), "exists": bool(e),
             "balanced": bool(b), "stable": bool(s), "max_real_eigenvalue": _num(l),
             "ball_angles_deg": _deg(a),
             "amplitude": {str(k): _num(v) for k, v in zip(ds.station.values, amp)},
             "status": int(st), **({"message": msg} if msg and int(st) != 0 else {})}
            for w, e, b, s, l, a, amp, st in zip(ds.speed.values, ds.exists.values, ds.balanced.values,
                                                 ds.stable.values, ds.max_real_eigenvalue.values,
                                                 ds.ball_angle.values, ds.amplitude.values,
                                                 ds.status.values)]


def _simulate_rows(ds) -> list[dict[str, Any]]:
    race = ds.race.values
    rows = []
    for i in range(ds.sizes["ic"]):
        ang = ds.final_ball_angle.values[i]
        rows.append({
            "ic": i, "final_speed": _num(ds.final_speed.values[i]),
            "final_ball_angles_deg": {f"race {r}": _deg(ang[race == r]) for r in np.unique(race)},
            "amplitude": {str(s): _num(a) for s, a in zip(ds.station.values, ds.amplitude.values[i])},
            "reference_amplitude": {str(s): _num(a) for s, a in
                                    zip(ds.station.values, ds.reference_amplitude.values)},
            "status": int(ds.status.values[i]),
        })
    return rows


def _run_up_rows(ds) -> list[dict[str, Any]]:
    a = ds.attrs
    return [{"final_speed": _num(a["final_speed"]), "final_speed_rpm": _num(a["final_speed"] * 30 / np.pi),
             "critical_speeds": [_num(w) for w in np.ravel(a["critical_speeds"])],
             "passed": int(a["passed"]), "captured_at": _num(a["captured_at"]),
             "residual_amplitude": {str(s): _num(v) for s, v in
                                    zip(ds.station.values, ds.residual_amplitude.values)},
             "status": int(a["status"])}]


_ROWS = {"machine-steady": _steady_rows, "machine-simulate": _simulate_rows, "machine-run-up": _run_up_rows}


def machine_rows(ds) -> list[dict[str, Any]]:
    """Summary rows of a machine analysis (JSON-ready, SI; angles in degrees)."""
    return _ROWS[ds.attrs["analysis"]](ds)
