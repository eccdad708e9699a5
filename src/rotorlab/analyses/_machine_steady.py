"""Steady motions of the composed machine: balanced states over speed and their exact stability
(``stability-chart``), every balanced motion at one speed with the seeds' verdicts where they
apply (``steady``), and their case-file entries and rows.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorlab.analyses._machine_common import (
    CLEARANCE_STATUS,
    NO_STEADY_STATUS,
    _annotate,
    _ball_coords,
    _num,
    _per_race,
    _per_station,
    _variant,
    _wrap,
    clearance_violation,
)

__all__ = ["machine_steady", "machine_motions", "jeffcott_limit", "SEED_VERDICTS_NOTE"]


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
        cancel the unbalance, else the one that starts from the best partial balance at that
        speed, or, where that does not converge, from the motion at the previous speed);
        ``balanced`` (speed): it has no vibration; ``amplitude`` (speed, station): its whirl
        radius per node (m); ``ball_angle`` (speed, ball) (rad); ``max_real_eigenvalue`` (speed) (1/s) of the linearised co-rotating equations;
        ``stable`` (speed); ``status`` (speed): 0, or ``NO_STEADY_STATUS`` with
        ``attrs["message"]`` when the machine has no co-rotating equilibria (anisotropic
        structure, gravity across the axis) - simulate it instead; ``CLEARANCE_STATUS`` (and
        ``exists`` false) where the orbit at the machine's clearance exceeds the gap
        (:func:`clearance_violation`, named in ``attrs["message"]``).
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
    hits: list[str] = []
    if message is not None:
        status[:] = NO_STEADY_STATUS
    else:
        guess, near = ball_angles, None
        for i, w in enumerate(om):
            m = machine.with_drive(ConstantSpeed(float(w)))
            # each speed on its own first (from the best partial balance), so that a verdict does
            # not depend on the speeds before it: several partly balanced motions may coexist and
            # continuing one from the previous speed can stay on an unstable branch where the
            # steady_state of that speed alone is stable (Pico 21, one race, 2300 rpm); the
            # previous speed's motion is the fallback start where the solver does not converge
            y = m.steady_state(guess)
            if y is None and near is not None:
                y = m.steady_state(guess, near=near)
            if y is None:
                continue
            nz = m.n_coordinates
            guess, near = y[2 * nz:2 * nz + nb], y
            exists[i] = True
            balanced[i] = bool(np.all(y[:nz] == 0.0))
            angles[i], amplitude[i], lam_max[i], stable[i] = _judge(m, y)
            _, hit = clearance_violation(m, y)
            if hit is not None:
                exists[i], stable[i], status[i] = False, False, CLEARANCE_STATUS
                hits.append(f"at {w:.6g} rad/s {hit}")
        if not exists.any() and not hits:
            message = "no steady motion found at any speed (the equilibrium solver did not converge)"
        elif hits:
            message = "; ".join(hits)
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


# --------------------------------------------------------------------------- steady motions at one speed


def jeffcott_limit(machine):
    """The :class:`~rotorlab.models.JeffcottBalls` model this machine is, or None.

    The seeds' Hamilton-function (seed 003) and averaged (seed 002) stability verdicts are
    derived for a planar disc on an isotropic shaft with one race of balls in the disc's plane.
    A machine is that model when its structure is one node whose translation does not couple to
    its tilt (no cross terms in M, C, G, K), isotropic, with one race and every unbalance at that
    node's plane (no couple), no gravity across the axis and a constant speed. Then M1 = M_xx, c = K_xx,
    d = C_xx, e = (sum of the unbalances) / M1 (their resultant), and the ball angles of that
    model are measured from the unbalance (shifted by its phase).
    """
    from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams

    s = machine.structure
    if (machine.why_no_rotating_frame() is not None or s.n_dof != 4 or len(machine.races) != 1
            or machine.races[0].axial_offset != 0.0 or any(u.axial_offset != 0.0 or u.couple != 0.0 for u in machine.unbalances)):
        return None
    for name in ("M", "C", "K", "G"):
        a = getattr(s, name)
        if np.any(a[:2, 2:] != 0.0) or np.any(a[2:, :2] != 0.0) or (name == "G" and np.any(a[:2, :2] != 0.0)):
            return None
    race = machine.races[0]
    u = sum(x.magnitude * np.exp(1j * x.phase) for x in machine.unbalances)
    m1 = float(s.M[0, 0])
    rotor = RotorParams(disc_mass=m1, eccentricity=abs(u) / m1, stiffness=float(s.K[0, 0]),
                        damping=float(s.C[0, 0]))
    balls = tuple(BallParams(mass=b.mass, radius=race.radius, inertia=b.mass * race.radius ** 2 + b.inertia,
                             damping=b.damping) for b in race.balls)
    return JeffcottBalls(rotor, balls, speed=ConstantSpeed(float(machine.drive.speed)), frame="rotating"), \
        float(np.angle(u)) if abs(u) > 0 else 0.0


#: Why the seeds' verdicts are not given for a machine that is not the planar single-mass rotor.
SEED_VERDICTS_NOTE = ("the seeds' Hamilton (seed 003) and averaged (seed 002) verdicts assume a planar "
                      "disc on an isotropic shaft with one race in its plane; this machine is not that "
                      "rotor, so only the exact eigenvalues judge stability")


def machine_motions(machine, *, starts: int = 24, seed: int = 0, angle_tol: float = 1e-6):
    """Every balanced steady motion at the machine's constant speed (or the best partial one).

    Balanced motions are the ball angles that cancel the unbalance (:meth:`Machine.balance_residual`
    = 0, from ``starts`` seeded random starts, distinct ones kept); when the balls cannot cancel
    it, the steady motion that starts from the best partial balance. Each is judged by the exact
    eigenvalues of the co-rotating linearization; where the machine is the planar single-mass
    rotor (:func:`jeffcott_limit`) the seeds' Hamilton and averaged verdicts of the same motion
    are added, elsewhere they are "n/a" with the reason in ``attrs["seed_verdicts"]``.

    Returns
    -------
    xarray.Dataset
        Dim ``motion``: ``label``, ``kind`` ("balanced" or "partly balanced"; "side" too where
        the seeds' verdicts are given), ``exists``, ``ball_angle``
        (motion, ball) (rad, from the rotor's reference direction), ``amplitude`` (motion,
        station) whirl radius (m), ``max_real_eigenvalue`` (1/s), ``stable``,
        ``verdict_exact``, ``verdict_hamilton``, ``verdict_averaged``; ``status`` (0, or
        :data:`NO_STEADY_STATUS` with ``attrs["message"]`` when there is no co-rotating frame,
        or :data:`CLEARANCE_STATUS` when every motion's orbit at the clearance exceeds the gap).
        A motion whose orbit exceeds the gap (:func:`clearance_violation`) has ``exists`` false,
        verdict "absent (exceeds the clearance)", and ``attrs["message"]`` names the station, the
        radius and the gap.
    """
    import xarray as xr
    from scipy.optimize import least_squares

    nb = machine.n_balls
    message = machine.why_no_rotating_frame()
    limit = jeffcott_limit(machine) if message is None and nb else None
    note = SEED_VERDICTS_NOTE
    if limit is not None:
        note = "the machine is the planar single-mass rotor of seeds 002/003: their verdicts are given"
        motions, machine = _seed_motions(machine, *limit)
    elif message is None and nb:
        found: list[np.ndarray] = []
        scale = max(machine._unbalance_scale, 1e-300)
        rng = np.random.default_rng(seed)
        for _ in range(starts):
            res = least_squares(lambda a: machine.balance_residual(a) / scale, rng.uniform(0, 2 * np.pi, nb),
                                xtol=1e-15, ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(res.fun)) < 1e-10:
                psi = _wrap(res.x)
                if not any(np.max(np.abs(_wrap(psi - f))) < angle_tol for f in found):
                    found.append(psi)
        ys = [machine.balanced_state(p) for p in sorted(found, key=lambda p: tuple(np.round(p, 6)))]
        kinds = ["balanced"] * len(ys)
        if not ys:
            y = machine.steady_state()
            ys, kinds = ([y], ["partly balanced"]) if y is not None else ([], [])
        if not ys:
            message = "no steady motion found (the equilibrium solver did not converge); simulate instead"
        motions = [(f"{k} {j}", k, y, *_judge(machine, y), "n/a", "n/a") for j, (k, y) in enumerate(zip(kinds, ys))]
    else:
        motions = []
        if message is None:
            message = "the machine has no balls"
    nst = machine.structure.n_nodes
    if not motions:  # one row that says there is none
        motions = [("none", "none", None, np.full(nb, np.nan), np.full(nst, np.nan), math.nan, False, "n/a", "n/a")]
    labels, kinds, states, angles, amp, lam, stable, hamilton, averaged = (list(c) for c in zip(*motions))
    exists_arr = np.array([y is not None for y in states])
    angles, amp, lam, stable = np.array(angles).reshape(-1, nb), np.array(amp), np.array(lam, float), np.array(stable)
    exact = [("stable" if st else "unstable") if y is not None else "absent" for y, st in zip(states, stable)]
    # a motion computed without contact whose orbit reaches past the clearance does not exist
    hits: list[str] = []
    for j, y in enumerate(states):
        hit = None if y is None else clearance_violation(machine, y)[1]
        if hit is not None:
            exists_arr[j], stable[j], exact[j] = False, False, "absent (exceeds the clearance)"
            hits.append(f"motion {labels[j] if j < len(labels) else j}: {hit}")
    if hits:
        message = "; ".join(hits) if message is None else message + "; " + "; ".join(hits)
    ds = xr.Dataset(
        {
            "kind": (("motion",), np.asarray(kinds, dtype=str)),
            "label": (("motion",), np.asarray(labels, dtype=str)),
            "exists": (("motion",), exists_arr),
            "ball_angle": (("motion", "ball"), angles, {"units": "rad"}),
            "amplitude": (("motion", "station"), amp, {"units": "m"}),
            "max_real_eigenvalue": (("motion",), lam, {"units": "1/s"}),
            "stable": (("motion",), stable),
            "verdict_exact": (("motion",), np.asarray(exact, dtype=str)),
            "verdict_hamilton": (("motion",), np.asarray(hamilton, dtype=str)),
            "verdict_averaged": (("motion",), np.asarray(averaged, dtype=str)),
            "status": ((), np.int64(0 if exists_arr.any() else CLEARANCE_STATUS if hits else NO_STEADY_STATUS)),
        },
        coords={"motion": np.arange(len(labels)), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "steady", "model": "machine", "seed_verdicts": note,
               "speed": float(machine.drive.speed) if hasattr(machine.drive, "speed") else math.nan,
               **({"message": message} if message else {})},
    )
    return ds


def _judge(machine, y):
    """Ball angles (rad, wrapped), whirl radius per node (m), largest real part of the eigenvalues
    (1/s) and stability (:attr:`MachineLinearization.is_stable`) of the co-rotating state ``y``."""
    nz, nb = machine.n_coordinates, machine.n_balls
    lin = machine.linearize(y)
    return (_wrap(y[2 * nz:2 * nz + nb]), machine.station_amplitudes(machine.rotating_to_fixed(y)),
            float(lin.eigenvalues.real.max()), lin.is_stable)


def _seed_motions(machine, rotor, phase: float):
    """Every steady motion of seeds 002/003 (balanced and side motions) of a machine that is the
    planar rotor ``rotor`` (:func:`jeffcott_limit`), solved and judged by the machine itself
    (:func:`rotorlab.steady.analyze_steady` on it, its unbalance turned to angle 0), with the seeds'
    two verdicts: rows for :func:`machine_motions` and that turned machine."""
    from dataclasses import replace

    from rotorlab.models._machine_rotating import spectrum_is_stable
    from rotorlab.steady import analyze_steady
    from rotorlab.steady._motions import motion_state

    turned = replace(machine, unbalances=tuple(replace(u, phase=u.phase - phase) for u in machine.unbalances))
    nb, nst = machine.n_balls, machine.structure.n_nodes
    rows = []
    for mo in analyze_steady(rotor, machine=turned).motions:
        st, kind = mo.stability, "balanced" if mo.kind == "main" else mo.kind
        if not mo.exists:
            rows.append((mo.label, kind, None, np.full(nb, np.nan), np.full(nst, np.nan), math.nan, False,
                         "absent", "absent"))
            continue
        y = motion_state(turned, mo.deflection, mo.ball_angles)
        rows.append((mo.label, kind, y, _wrap(mo.ball_angles + phase),
                     turned.station_amplitudes(turned.rotating_to_fixed(y)), float(st.eigenvalues.real.max()),
                     spectrum_is_stable(st.eigenvalues), st.hamilton, st.averaged))
    return rows, turned


def _run_steady(case_model, analysis, progress=None):
    m = _variant(case_model, analysis, analysis.spin_speed(case_model))
    ds = machine_motions(m)
    if progress is not None:
        progress(1, 1)
    return _annotate(ds, case_model, analysis)


def _run_chart(case_model, analysis, progress=None):
    import xarray as xr

    from rotorlab.continuation import with_value  # every ball's mass or damping (ball_mass, ball_damping)

    speeds = analysis.spin_speeds(case_model)
    m = _variant(case_model, analysis, float(speeds[0]))
    values = analysis.parameter_values()
    if values is None:
        ds = machine_steady(m, speeds)
    else:
        parts = []
        for k, v in enumerate(values):
            parts.append(machine_steady(with_value(m, analysis.param, v), speeds))
            if progress is not None:
                progress(k + 1, len(values))
        ds = xr.concat(parts, dim="parameter", combine_attrs="drop_conflicts")
        from rotorlab.io._steady_specs import STEADY_PARAMETERS

        ds = ds.assign_coords(parameter=("parameter", np.asarray(values, float),
                                         {"units": STEADY_PARAMETERS[analysis.param][2]}))
        ds.attrs["parameter"] = analysis.param
    ds.attrs["analysis"] = "stability-chart"
    from rotorlab.models._machine_physics import structure_critical_speeds

    crit = structure_critical_speeds(m)  # the reason and remedy of a chart unstable everywhere
    if crit.size:
        ds.attrs["first_critical_speed"] = float(crit[0])
    return _annotate(ds, case_model, analysis)


def _chart_task_size(case_model, analysis) -> int:
    values = analysis.parameter_values()
    return 1 if values is None else len(values)


def _steady_rows(ds) -> list[dict[str, Any]]:
    msg = ds.attrs.get("message")
    rows = []
    for j in range(ds.sizes["motion"]):
        exists = bool(ds.exists.values[j])
        rows.append({
            "motion": int(j), "label": str(ds.label.values[j]), "kind": str(ds.kind.values[j]), "exists": exists,
            "speed": _num(ds.attrs.get("speed", math.nan)),
            "ball_angles_deg": _per_race(ds, ds.ball_angle.values[j]) if exists else None,
            "amplitude": _per_station(ds, ds.amplitude.values[j]) if exists else None,
            "stable": bool(ds.stable.values[j]), "max_real_eigenvalue": _num(ds.max_real_eigenvalue.values[j]),
            **{f"verdict_{k}": str(ds[f"verdict_{k}"].values[j]) for k in ("exact", "hamilton", "averaged")},
            "seed_verdicts": ds.attrs.get("seed_verdicts", ""),
            "status": int(ds.status.values),
            **({"message": msg} if msg else {}),
        })
    return rows


def _chart_rows(ds) -> list[dict[str, Any]]:
    """One row per (parameter value and) speed: exists, balanced, exact stability."""
    msg = ds.attrs.get("message")
    param = ds.attrs.get("parameter")
    values = ds.parameter.values if param else [None]
    rows = []
    for k, v in enumerate(values):
        sub = ds.isel(parameter=k) if param else ds
        for w, e, b, st, lam, a, amp, code in zip(sub.speed.values, sub.exists.values, sub.balanced.values,
                                                  sub.stable.values, sub.max_real_eigenvalue.values,
                                                  sub.ball_angle.values, sub.amplitude.values, sub.status.values):
            rows.append({**({param: float(v)} if param else {}),
                         "speed": _num(w), "speed_rpm": _num(w * 30 / np.pi), "exists": bool(e),
                         "balanced": bool(b), "stable": bool(st), "max_real_eigenvalue": _num(lam),
                         "ball_angles_deg": _per_race(ds, a), "amplitude": _per_station(ds, amp),
                         "status": int(code), **({"message": msg} if msg and int(code) != 0 else {})})
    return rows
