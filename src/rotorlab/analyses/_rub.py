"""The ``rub`` analysis: simulate a rotor in its clearance, name its regime and put the closed-form
prediction beside every measured number (:mod:`rotorlab.contact`).

It runs on any model with a clearance (a ``rub_rotor``, or a ``machine`` with a clearance and a
constant speed), built through the model registry; the closed forms are those of the model's
``equivalent_rub_rotor()`` (exact for the Jeffcott rotor, see
:meth:`rotorlab.models.Machine.equivalent_rub_rotor` for a machine)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray

    from rotorlab.contact import JeffcottRub, RubRotor

__all__ = ["rub_model", "rub_quantities", "run_rub_analysis", "rub_rows", "rub_prediction", "run_rub_map",
           "rub_map_rows", "rub_map_task_size"]

#: The ``mode`` of a saved sample after a failed run's end (its state is NaN).
NO_STATE = -128


def _rotor(case_model: Any) -> RubRotor:
    from rotorlab.contact import RubRotor

    ks = case_model.stator_stiffness
    return RubRotor(
        mass=case_model.mass, stiffness=case_model.stiffness, clearance=case_model.clearance,
        damping=case_model.damping, eccentricity=case_model.eccentricity,
        stator_stiffness=math.inf if ks is None else ks, stator_damping=case_model.stator_damping,
        friction=case_model.friction, rotor_radius=case_model.rotor_radius,
    )  # fmt: skip


def rub_model(case_model: Any) -> JeffcottRub:
    """Build the :class:`~rotorlab.contact.JeffcottRub` of a validated ``rub_rotor`` case model."""
    from rotorlab.contact import JeffcottRub
    from rotorlab.io._rub_specs import JeffcottRubSpec

    if not isinstance(case_model, JeffcottRubSpec):
        raise ValueError(f"needs a rub_rotor model, got {getattr(case_model, 'type', None)!r}")
    return JeffcottRub(_rotor(case_model), case_model.spin_speed, restitution=case_model.restitution,
                       rest_speed=case_model.rest_speed)  # fmt: skip


def rub_quantities(case_model: Any) -> list[dict[str, Any]]:
    """Natural frequency, grazing speeds and the no-rub orbit at the spin speed."""
    from rotorlab.contact import grazing_speeds, no_rub_radius

    rotor = _rotor(case_model)
    out = [{"quantity": "natural frequency sqrt(k/m)", "value": rotor.natural_frequency, "unit": "rad/s", "sign": ""}]
    for i, w in enumerate(grazing_speeds(rotor)):
        out.append({"quantity": f"grazing speed {i + 1} (no-rub orbit reaches the clearance)", "value": w,
                    "unit": "rad/s", "sign": ""})  # fmt: skip
    out.append({"quantity": "no-rub orbit radius at the spin speed", "value": no_rub_radius(rotor, case_model.spin_speed),
                "unit": "m", "sign": ""})  # fmt: skip
    return out


def rub_prediction(rotor: RubRotor, speed: float) -> dict[str, Any]:
    """What the closed forms say at one speed: every regime they allow, with its numbers.

    Returns a dict with ``no_rub_radius`` (m) and ``no_rub_fits`` (inside the clearance), the
    full-rub ``branches`` (radius m, normal force N, stable or not, largest first; stability for
    an elastic stator only), ``critical_friction`` (elastic stator, where a frictionless branch
    exists), the ``rolling`` backward whirl (whirl speed rad/s, radius m, normal force N,
    friction needed) or None, and ``regimes``: the labels of the regimes allowed.
    """
    from dataclasses import replace

    from rotorlab.contact import (
        critical_friction,
        full_rub,
        full_rub_characteristic,
        hurwitz_stable,
        no_rub_radius,
        rolling_whirl,
    )

    r0 = no_rub_radius(rotor, speed)
    branches = []
    for b in full_rub(rotor, speed):
        stable = None if rotor.rigid_stator else hurwitz_stable(full_rub_characteristic(rotor, speed, b.radius))
        branches.append({"radius": b.radius, "normal_force": b.normal_force, "stable": stable})
    mu_c = None
    if not rotor.rigid_stator and full_rub(replace(rotor, friction=0.0), speed):
        mu_c = critical_friction(rotor, speed)
    roll = rolling_whirl(rotor, speed) if rotor.stator_mass == 0.0 else None
    rolling = None
    if roll is not None:
        rolling = {"whirl_speed": roll.whirl_speed, "radius": roll.radius, "normal_force": roll.normal_force,
                   "friction_needed": roll.friction_needed}  # fmt: skip
    regimes = []
    if r0 < rotor.clearance:
        regimes.append("no contact")
    if any(b["stable"] is not False for b in branches):
        regimes.append("full rub (forward)")
    if rolling is not None and rotor.friction >= rolling["friction_needed"]:
        regimes.append("backward whirl, rolling")
    return {"no_rub_radius": r0, "no_rub_fits": r0 < rotor.clearance, "branches": branches,
            "critical_friction": mu_c, "rolling": rolling, "regimes": regimes}  # fmt: skip


def run_rub_analysis(case_model: Any, analysis: Any,
                     progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Simulate, classify the last window and store measured features beside the closed forms."""
    import xarray as xr

    from rotorlab.analyses._registry import MODEL_TYPES
    from rotorlab.contact import RubRegime, rub_features
    from rotorlab.integrate import SaveAt, StepControl, solve

    model = MODEL_TYPES[case_model.type].build(case_model)
    rotor = model.equivalent_rub_rotor()
    r, w = analysis.initial_radius, analysis.initial_whirl
    y0 = model.whirl_state(r, w)
    ts = np.linspace(analysis.t_end - analysis.window, analysis.t_end, analysis.samples)
    sol = solve(model, y0, (0.0, analysis.t_end), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-9, atol=1e-12 * rotor.clearance / 1e-3),
                max_events_recorded=0)  # fmt: skip
    if progress is not None:
        progress(1, 1)
    cs = model.contact_samples(ts, sol.ys)
    spin_speed = float(cs.spin_speed[-1])
    pred = rub_prediction(rotor, spin_speed)
    ys = sol.ys
    wx, wy = cs.w[:, 0], cs.w[:, 1]
    radius = np.hypot(wx, wy)
    # the model's sanity monitor (a rotor beyond a rigid stator) marks the run IMPOSSIBLE with a note
    status, message = int(sol.status), (sol.note or sol.status.message)
    if status < 0:
        regime, feats = RubRegime.FAILED, None
    else:
        feats = rub_features(model, ts, ys)
        regime = feats.regime
    ds = xr.Dataset(
        {
            "x": (("time",), wx, {"units": "m"}),
            "y": (("time",), wy, {"units": "m"}),
            "radius": (("time",), radius, {"units": "m"}),
            # samples after a failed run's end hold no state (NaN): marked NO_STATE, not a mode
            "mode": (("time",), np.where(np.isfinite(cs.mode), cs.mode, NO_STATE).astype(np.int8),
                     {"units": "1", "no_state": NO_STATE}),
        },
        coords={"time": ("time", ts, {"units": "s"})},
    )
    ds.attrs.update({
        "name": analysis.name, "status": status, "status_message": message, "t_final": float(sol.t_final),
        "regime": int(regime), "regime_label": regime.label, "spin_speed": spin_speed,
        "clearance": rotor.clearance, "rigid_stator": int(rotor.rigid_stator), "friction": rotor.friction,
        "predicted_regimes": "; ".join(pred["regimes"]) or "none of the closed forms",
        "no_rub_radius": pred["no_rub_radius"],
        "branch_radius": [b["radius"] for b in pred["branches"]],
        "branch_normal_force": [b["normal_force"] for b in pred["branches"]],
        "branch_stable": [(-1 if b["stable"] is None else int(b["stable"])) for b in pred["branches"]],
        "critical_friction": np.nan if pred["critical_friction"] is None else pred["critical_friction"],
    })  # fmt: skip
    if pred["rolling"] is not None:
        ds.attrs.update({f"rolling_{k}": v for k, v in pred["rolling"].items()})
    if feats is not None:
        ds.attrs.update({"impact_rate": feats.impact_rate, "contact_fraction": feats.contact_fraction,
                         "rolling_fraction": feats.rolling_fraction, "whirl_ratio": feats.whirl_ratio,
                         "peak_force": feats.peak_force, "peak_impulse": feats.peak_impulse,
                         "mean_radius": float(radius.mean())})  # fmt: skip
    return ds


def _closed_form_for(ds: xarray.Dataset) -> tuple[float | None, float | None, float | None, str]:
    """(radius m, whirl ratio, normal force N, source) the closed forms give for the measured regime."""
    from rotorlab.contact import RubRegime

    a = ds.attrs
    regime = RubRegime(a["regime"])
    if regime == RubRegime.NO_CONTACT:
        return a["no_rub_radius"], 1.0, 0.0, "Jeffcott unbalance response"
    # np.atleast_1d: a one-branch list comes back from NetCDF as a scalar attribute
    if regime == RubRegime.FULL_RUB and np.atleast_1d(a["branch_radius"]).size:
        radii = list(np.atleast_1d(a["branch_radius"]))
        i = int(np.argmin([abs(r - a["mean_radius"]) for r in radii]))
        return radii[i], 1.0, list(np.atleast_1d(a["branch_normal_force"]))[i], "Black (1968), Choy & Padovan (1987)"
    if regime == RubRegime.BACKWARD_ROLLING and "rolling_radius" in a:
        return a["rolling_radius"], a["rolling_whirl_speed"] / a["spin_speed"], a["rolling_normal_force"], "Crandall (1990)"
    return None, None, None, "no closed form for this regime"


def rub_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Summary rows: the regime, then each measured quantity with its closed-form value."""
    a = ds.attrs
    radius, whirl, force, source = _closed_form_for(ds)
    rows: list[dict[str, Any]] = [{"quantity": "regime", "measured": a["regime_label"],
                                   "closed_form": a["predicted_regimes"], "unit": "", "source": source}]  # fmt: skip
    if "mean_radius" not in a:
        return rows
    for name, measured, closed, unit in (
        ("whirl radius (mean)", a["mean_radius"], radius, "m"),
        ("whirl speed / spin speed", a["whirl_ratio"], whirl, ""),
        ("contact normal force (peak)", a["peak_force"], force, "N"),
        ("contact fraction", a["contact_fraction"], None, ""),
        ("contacts begun per second", a["impact_rate"], None, "1/s"),
        ("largest impact impulse", a["peak_impulse"], None, "N*s"),
    ):
        rows.append({"quantity": name, "measured": float(measured), "closed_form": None if closed is None else float(closed),
                     "unit": unit, "source": source if closed is not None else ""})  # fmt: skip
    mu_c = a.get("critical_friction")
    if mu_c is not None and np.isfinite(mu_c):
        rows.append({"quantity": "critical friction of the full rub", "measured": float(a["friction"]),
                     "closed_form": float(mu_c), "unit": "", "source": "Hurwitz criterion of the rub orbit"})  # fmt: skip
    return rows


def run_rub_map(case_model: Any, analysis: Any,
                progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Map the rub regimes over spin speed x the second axis on the sweep engine.

    Every point is simulated from the same whirl (``initial_radius``, ``initial_whirl``) and its
    last ``window`` classified (:class:`rotorlab.contact.RubRegimes`); the Dataset is the sweep's
    (``regime`` and the features over ``spin_speed`` and the second axis) with
    ``grazing_boundary`` (second-axis value at which the closed-form no-rub orbit just reaches the
    clearance, at every speed) beside it, and the same line ``grazing_curve`` on a fine grid
    ``curve_speed`` across the map; ``attrs["closed_form_decided"]`` counts the finished
    points where the closed forms (:func:`rub_prediction`) allow a single regime and
    ``attrs["closed_form_agree"]`` those of them where the map shows that regime.
    """
    from dataclasses import replace

    from rotorlab.analyses._registry import MODEL_TYPES
    from rotorlab.contact import RubRegime, RubRegimes, no_rub_radius
    from rotorlab.sweep import GridAxis, Sweep, run_sweep

    model = MODEL_TYPES[case_model.type].build(case_model)
    axis = analysis.second_axis
    r, w = analysis.initial_radius, analysis.initial_whirl
    regimes = RubRegimes(model, t_end=analysis.t_end, window=analysis.window, position=(r, 0.0),
                         velocity=(0.0, w * r), n_samples=analysis.samples)  # fmt: skip
    axes = (GridAxis("spin_speed", *analysis.spin_speed), GridAxis(axis, *getattr(analysis, axis)))
    total = analysis.spin_speed[2] * getattr(analysis, axis)[2]
    report = None if progress is None else (lambda p: progress(p.done, p.total))
    ds = run_sweep(Sweep(regimes, axes=axes), progress=report)
    rotor = model.equivalent_rub_rotor()
    speeds = ds.spin_speed.values

    def grazing(at: np.ndarray) -> np.ndarray:
        if axis == "clearance":  # the clearance the no-rub orbit just reaches
            return np.array([no_rub_radius(rotor, float(s)) for s in at])
        # the orbit radius is linear in the eccentricity: the one (or m e) that just reaches it
        per_unit = np.array([no_rub_radius(replace(rotor, eccentricity=1.0), float(s)) for s in at])
        return rotor.clearance / per_unit * (rotor.mass if axis == "unbalance" else 1.0)

    unit = {"units": ds[axis].attrs["units"]}  # the second axis' own (the model's rub_parameters)
    ds["grazing_boundary"] = (("spin_speed",), grazing(speeds), unit)
    # the same line on a fine grid over the map's cells (a figure draws it; the grid is coarse)
    half = 0.5 * (speeds[-1] - speeds[0]) / max(speeds.size - 1, 1)
    fine = np.unique(np.concatenate([np.linspace(max(speeds[0] - half, 1e-9 * speeds[0]), speeds[-1] + half, 201),
                                     speeds]))  # fmt: skip
    ds = ds.assign_coords(curve_speed=("curve_speed", fine, {"units": "rad/s"}))
    ds["grazing_curve"] = (("curve_speed",), grazing(fine), unit)
    # where the closed forms allow a single regime, does the map show it?
    decided = agree = 0
    for i, s in enumerate(speeds):
        for j, v in enumerate(ds[axis].values):
            v = float(v)
            at = {"clearance": {"clearance": v}, "eccentricity": {"eccentricity": v},
                  "unbalance": {"eccentricity": v / rotor.mass}}[axis]  # fmt: skip
            allowed = rub_prediction(replace(rotor, **at), float(s))["regimes"]
            if len(allowed) == 1 and int(ds.status.values[i, j]) >= 0:
                decided += 1
                agree += RubRegime(int(ds.regime.values[i, j])).label == allowed[0]
    ds.attrs.update({"name": analysis.name, "second_axis": axis, "points": int(total),
                     "closed_form_decided": decided, "closed_form_agree": agree})  # fmt: skip
    return ds


def rub_map_task_size(case_model: Any, analysis: Any) -> int:
    """Points of a ``rub-map`` analysis (its progress-bar total)."""
    return int(analysis.spin_speed[2] * getattr(analysis, analysis.second_axis)[2])


def rub_map_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """One row per regime: how many points of the map are in it and where."""
    from rotorlab.contact import RubRegime

    codes = ds.regime.values.ravel()
    axis = ds.attrs["second_axis"]
    sp = np.broadcast_to(ds.spin_speed.values[:, None], ds.regime.shape).ravel()
    sec = np.broadcast_to(ds[axis].values[None, :], ds.regime.shape).ravel()
    rows = []
    for r in RubRegime:
        k = codes == int(r)
        if not k.any():
            continue
        rows.append({"regime": r.label, "points": int(k.sum()), "share": float(k.mean()),
                     "spin_speed_min": float(sp[k].min()), "spin_speed_max": float(sp[k].max()),
                     f"{axis}_min": float(sec[k].min()), f"{axis}_max": float(sec[k].max())})
    return rows
