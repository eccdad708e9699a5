"""Impacts of the centrifuge rotor on its housing: runs, regimes, energy, sweeps (seed 001).

Every function here integrates :class:`rotorlab.models.ImpactRotor` with the compiled ensemble
integrator and returns an ``xarray.Dataset`` (SI, ``attrs["units"]`` on every variable).

Regimes (per run)
-----------------
``none``: no impact with an approach speed >= ``Housing.count_speed``; ``rebounds``: impacts,
sliding contact for less than ``sliding_fraction`` of the run; ``sliding``: the rotor in
sustained contact with the housing, slipping, for at least that share of the run (default
:data:`SLIDING_FRACTION`, 0.1 %; the conventions are :data:`SLIDING_CONVENTIONS`, see below);
``backward_whirl``: a sliding contact whirled backwards until the slip of P vanished (the
theory's criterion; without tilt the rolling speed
:meth:`rotorlab.models.Housing.rolling_whirl_speed`), where the sliding law ends in the
dry-friction backward whirl, or an impact's friction impulse stuck (the slip of P stopped: P
rolls on the housing, reached through impacts, e.g. with restitution 1), and the run was
stopped there (its impact counts are those of the whole run: a sliding contact makes no
impacts, so they do not depend on the speed at which the stop is detected);
``failed``: the integrator gave up (status < 0).

These are the general rub regimes of :mod:`rotorlab.contact` (:class:`~rotorlab.contact.RubRegime`,
same codes): ``none`` is no contact, ``rebounds`` intermittent impacts, ``sliding`` sustained
contact (full rub), ``backward_whirl`` the rolling backward whirl; the decision is the shared
:func:`rotorlab.contact.regime_codes` under :data:`SEED001_RULE`. Where the seed's rule differs
from the window rule of a rub map (:data:`rotorlab.contact.WINDOW_RULE`): it judges a whole run
with stones, not a window in a steady state, so

- ``sliding`` is not a full annular rub in permanent contact: a run is ``sliding`` once
  ``sliding_fraction`` of it was spent in sustained contact, impacts between the episodes
  included; and the seed's
  sliding law assumes the contact point slides forwards (friction along ``-e_perp``), so its
  whirl ratio is not measured (NaN: the run is never labelled backward from it);
- contacts slower than ``count_speed`` (uncounted chatter) do not make a run ``rebounds``;
- ``backward_whirl`` is the run stopped at the onset of rolling (whirl ratio -whirl speed /
  omega0 < 0, rolling fraction 1), whatever fraction of it was in contact.

The ``sliding`` convention (:data:`SLIDING_CONVENTIONS`, the option ``sliding_fraction``)
-----------------------------------------------------------------------------------------
The paper calls sliding "a regime in which the rotor slides on the housing for some interval of
time" and has it begin at 3 kg in Fig. 4 (one run per mass); which share of a run makes it
``sliding`` is a convention, named here: ``"paper"`` (0: any sustained sliding episode),
``"default"`` (0.1 % of the run: 2 ms of Fig. 4's 2 s, 10 ms of the table's 10 s) and
``"noticeable"`` (2 %, the former default). Over 16 seeded sequences of Fig. 4 (translational,
2 s) the first stone mass where most runs are ``sliding`` is 3 kg under ``"paper"`` and
``"default"`` and 5 kg under ``"noticeable"`` (at 4 kg 15 of 16 runs touch, for at most 31 ms);
sustained contacts there whirl forwards and last only while a stone pushes, so their share of a
run is small (median 0.2 % at 3 kg, 0.9 % at 4 kg, 4 % at 5 kg). In the table's 10 s runs (tilt)
the default puts the onset at 0.9-1 kg (half the runs at 0.9 kg), where the printed count jumps
from 43 to 400 (``dev/crusher_choices.py``).

Energy (seed 001, Fig. 5)
-------------------------
``energy_stones``: what the motor spends on accelerating the stones (``m_n omega0^2 R_q^2 W``,
partial for a stone still on its guide); ``energy_friction``: what it spends against the
friction at the housing, ``f r_P omega0 (sum S_n + int N dt)``; ``eta`` their ratio. A run
stopped at the backward whirl ends in a runaway (the contact point whirling backwards, friction
feeding it) that can hold nearly all of its friction work in the last milliseconds: its values
before the runaway (``*_before_runaway``, up to ``runaway_start``, the last time P touched the
housing whirling forwards) and the runaway's own (``*_runaway``) are reported apart.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab._kernels import impact_rotor as _k
from rotorlab.contact._regimes import RegimeRule, regime_codes

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import ImpactRotor

__all__ = [
    "IMPACT_ANALYSES",
    "REGIMES",
    "SEED001_TABLE",
    "SLIDING_FRACTION",
    "SLIDING_CONVENTIONS",
    "SEED001_RULE",
    "impact_features",
    "SWEEP_PARAMS",
    "classify_impacts",
    "impact_model",
    "impact_run",
    "run_impact_analysis",
    "impact_summary",
    "paper_counts",
    "sweep_summary",
    "stacked_params",
]

#: Regime labels by code (``failed`` is -1).
REGIMES = ("none", "rebounds", "sliding", "backward_whirl")

#: Named conventions for the ``sliding`` label: share of the run in sustained sliding contact
#: from which a run is ``sliding`` (the option ``sliding_fraction``; module docstring). ``paper``:
#: any sustained sliding episode ("the rotor slides on the housing for some interval of time").
SLIDING_CONVENTIONS = {"paper": 0.0, "default": 0.001, "noticeable": 0.02}

#: Default fraction of the run in sliding contact from which a run is in the sliding regime.
SLIDING_FRACTION = SLIDING_CONVENTIONS["default"]

#: Seed 001's table: impacts in 10 s at Delta t = 0.035 s by stone mass (kg), general case (one
#: random sequence each; at 3 kg "sliding, a series of very frequent impacts").
SEED001_TABLE = {0.5: 0, 0.6: 2, 0.7: 12, 0.8: 23, 0.9: 43, 1.0: 400, 3.0: 34000}

#: Parameters a sweep can vary: name -> (part of the model, field, unit).
SWEEP_PARAMS = {
    "stone_mass": ("stones", "mass", "kg"),
    "interval": ("stones", "interval", "s"),
    "internal_friction": ("rotor", "internal_friction", "1"),
    "restitution": ("housing", "restitution", "1"),
    "friction": ("housing", "friction", "1"),
}


def stacked_params(models: Sequence[ImpactRotor]) -> np.ndarray:
    """Packed parameter vectors of several models, zero-padded to one length, shape (N, n_p)."""
    ps = [m.to_array() for m in models]
    width = max(p.size for p in ps)
    out = np.zeros((len(ps), width))
    for i, p in enumerate(ps):
        out[i, : p.size] = p
    return out


#: The shared regime rule (:func:`rotorlab.contact.regime_codes`) for a whole seed-001 run.
SEED001_RULE = RegimeRule(sustained_fraction=SLIDING_FRACTION, impacts_in_sustained=True,
                          uncounted_contact_is_impact=False, backward_at_stop=True)  # fmt: skip


def impact_features(impacts, sliding_time, duration, whirl) -> dict[str, np.ndarray]:
    """The rub features (:mod:`rotorlab.contact._regimes`) of seed-001 runs from their records.

    ``impact_rate`` = counted impacts / duration (1/s); ``contact_fraction`` = time in sliding
    contact / duration; ``whirl_ratio`` = -1 (backward, its sign: the run was stopped at the
    onset of the rolling backward whirl) where ``whirl``, else NaN (the seed's sliding law
    assumes forward sliding and the whirl is not measured); ``rolling_fraction`` = 1 where
    stopped at rolling, else 0 (the seed has no rolling contact).
    """
    impacts, sliding_time, duration, whirl = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (impacts, sliding_time, duration, whirl))
    )
    stopped = whirl > 0
    return {
        "impact_rate": impacts / duration,
        "contact_fraction": sliding_time / duration,
        "whirl_ratio": np.where(stopped, -1.0, np.nan),
        "rolling_fraction": np.where(stopped, 1.0, 0.0),
    }


def classify_impacts(impacts, sliding_time, duration, whirl, status,
                     sliding_fraction: float = SLIDING_FRACTION) -> np.ndarray:  # fmt: skip
    """Regime codes (0 none, 1 rebounds, 2 sliding, 3 backward_whirl, -1 failed) of runs.

    The features of :func:`impact_features` classified by :func:`rotorlab.contact.regime_codes`
    under :data:`SEED001_RULE` (with ``sliding_fraction``); the codes are those of
    :class:`rotorlab.contact.RubRegime` (see the module docstring for the mapping).

    Parameters
    ----------
    impacts : array_like
        Counted impacts.
    sliding_time, duration : array_like
        Time in sliding contact and length of the run (s).
    whirl : array_like
        1 where the run was stopped by the backward whirl.
    status : array_like of int
        Integrator status (< 0: failed).
    sliding_fraction : float
        Fraction of the run in sliding contact from which it is ``sliding``, in [0, 1]; 0 (the
        paper's convention): any sustained sliding episode. See :data:`SLIDING_CONVENTIONS`.

    Returns
    -------
    ndarray of int

    Examples
    --------
    >>> classify_impacts([0, 5, 50, 9, 3], [0, 0, 1.0, 0.1, 0], 10.0, [0, 0, 0, 1, 0], [0, 0, 0, 1, -2])
    array([ 0,  1,  2,  3, -1])

    5 ms of sliding in 10 s is 0.05 % of the run: ``rebounds`` by default, ``sliding`` under the
    paper's convention (any sustained sliding episode):

    >>> classify_impacts([5, 5], [0.005, 0.0], 10.0, 0, 0).tolist()
    [1, 1]
    >>> classify_impacts([5, 5], [0.005, 0.0], 10.0, 0, 0, SLIDING_CONVENTIONS["paper"]).tolist()
    [2, 1]
    """
    if not 0.0 <= float(sliding_fraction) <= 1.0:
        raise ValueError(f"sliding_fraction must be in [0, 1] (share of the run), got {sliding_fraction!r}")
    f = impact_features(impacts, sliding_time, duration, whirl)
    rule = SEED001_RULE if sliding_fraction == SLIDING_FRACTION else replace(SEED001_RULE, sustained_fraction=float(sliding_fraction))
    return regime_codes(np.asarray(impacts, dtype=float), f["contact_fraction"], f["whirl_ratio"],
                        f["rolling_fraction"], status, rule)  # fmt: skip


def _label(code: int) -> str:
    return "failed" if code < 0 else REGIMES[code]


def _scalars(models: Sequence[ImpactRotor], sol: Any) -> dict[str, np.ndarray]:
    yf = sol.y_final
    tf = sol.t_final
    sliding = yf[:, _k.T_SLIDE] + np.where(yf[:, _k.MODE] != 0.0, tf - yf[:, _k.T_START], 0.0)
    e_st = np.array([m.stone_energy(t) for m, t in zip(models, tf)])
    # the drive's work against friction at the housing: at the impulses (W_DRIVE, -P_t r_P omega0)
    # and in sliding (f N r_P omega0); f r_P omega0 (sum S_n + int N dt) while P slides forwards
    slide = np.array([m.housing.friction * m.housing.radius * m.rotor.spin_speed for m in models])
    e_fr = yf[:, _k.W_DRIVE] + slide * yf[:, _k.INT_N]
    e_vib = np.array([m.fixed_energy(y) for m, y in zip(models, yf)])
    # a run stopped at the backward whirl: its records before the runaway (issue 28, item 5)
    stopped = yf[:, _k.WHIRL] != 0.0
    t_run = np.where(stopped, yf[:, _k.R_T], tf)
    e_st_pre = np.array([m.stone_energy(t) for m, t in zip(models, t_run)])
    e_fr_pre = np.where(stopped, yf[:, _k.R_WDRIVE] + slide * yf[:, _k.R_INTN], e_fr)
    imp_pre = np.where(stopped, yf[:, _k.R_NIMP], yf[:, _k.N_IMP]).astype(np.int64)
    with np.errstate(divide="ignore", invalid="ignore"):
        eta = np.where(e_st > 0, e_fr / e_st, np.nan)
        eta_pre = np.where(e_st_pre > 0, e_fr_pre / e_st_pre, np.nan)
    return {
        "impacts": yf[:, _k.N_IMP].astype(np.int64),
        "impacts_all": yf[:, _k.N_ALL].astype(np.int64),
        "slides": yf[:, _k.N_SLIDE].astype(np.int64),
        "sliding_time": sliding,
        "max_penetration": np.maximum(yf[:, _k.PEN_MAX], 0.0),
        "max_approach_speed": yf[:, _k.V_MAX],
        "energy_stones": e_st,
        "energy_friction": e_fr,
        "energy_restitution": yf[:, _k.E_REST],
        "energy_vibration": e_vib - yf[:, _k.E_0],
        "work_stones": yf[:, _k.W_ST],
        "eta": eta,
        "runaway_start": np.where(stopped, t_run, np.nan),
        "impacts_before_runaway": imp_pre,
        "energy_friction_before_runaway": e_fr_pre,
        "eta_before_runaway": eta_pre,
        "impacts_runaway": yf[:, _k.N_IMP].astype(np.int64) - imp_pre,
        "energy_friction_runaway": e_fr - e_fr_pre,
        "whirl": yf[:, _k.WHIRL].astype(np.int64),
        "t_final": tf,
        "status": sol.status.astype(np.int64),
        "n_steps": sol.stats[:, 1].astype(np.int64),
    }


_UNITS = {
    "impacts": "1", "impacts_all": "1", "slides": "1", "sliding_time": "s", "max_penetration": "m",
    "max_approach_speed": "m/s", "energy_stones": "J", "energy_friction": "J",
    "energy_restitution": "J", "energy_vibration": "J", "work_stones": "J", "eta": "1", "whirl": "1", "t_final": "s", "status": "1",
    "runaway_start": "s", "impacts_before_runaway": "1", "energy_friction_before_runaway": "J",
    "eta_before_runaway": "1", "impacts_runaway": "1", "energy_friction_runaway": "J",
    "n_steps": "1", "regime": "1",
}  # fmt: skip
_DESCRIPTIONS = {
    "impacts": "located impacts with approach speed >= count_speed (default 0: every one)",
    "runaway_start": "run stopped at the backward whirl: last time P touched the housing whirling forwards (NaN: not stopped)",
    "impacts_before_runaway": "impacts up to runaway_start (every impact of a run not stopped)",
    "energy_friction_before_runaway": "energy_friction up to runaway_start",
    "eta_before_runaway": "eta up to runaway_start (eta of a run not stopped)",
    "impacts_runaway": "impacts from runaway_start to the backward-whirl stop",
    "energy_friction_runaway": "energy_friction from runaway_start to the backward-whirl stop",
    "impacts_all": "every impact, chatter included",
    "slides": "number of sliding-contact episodes",
    "sliding_time": "total time in sliding contact",
    "max_penetration": "largest excess of |w| over the gap seen at impacts and projections",
    "max_approach_speed": "largest normal approach speed of P",
    "energy_stones": "motor energy spent on accelerating stones",
    "energy_friction": "motor energy spent against friction at the housing",
    "energy_restitution": "energy lost in the normal direction by restitution",
    "energy_vibration": "vibration energy gained in the fixed frame (end minus start)",
    "work_stones": "work of the stone forces on the rotor's vibration",
    "eta": "energy_friction / energy_stones (seed 001, Fig. 5)",
    "whirl": "1: stopped by a self-feeding dry-friction backward whirl",
    "t_final": "time the run ended",
    "status": "integrator status (>= 0 usable)",
    "n_steps": "accepted integrator steps",
    "regime": "0 none, 1 rebounds, 2 sliding, 3 backward_whirl, -1 failed",
}


def _control(rtol: float, atol: float):
    from rotorlab.integrate import StepControl

    scale = np.ones(_k.N_STATE)
    scale[[_k.INT_N, _k.W_ST, _k.W_NC]] = 1e30  # the integrals of the ledger do not steer the step size
    return StepControl(rtol=rtol, atol=tuple(atol * scale))


def _model_attrs(model: ImpactRotor, t_end: float, sliding_fraction: float) -> dict[str, Any]:
    r, h, s = model.rotor, model.housing, model.stones
    return {
        "model": "impact_rotor",
        "translational": int(r.translational),
        "t_end": float(t_end),
        "sliding_fraction": float(sliding_fraction),
        "count_speed": h.count_speed,
        "rest_speed": h.rest_speed,
        "spin_speed": r.spin_speed,
        "stone_mass": s.mass,
        "interval": s.interval,
        "internal_friction": r.internal_friction,
        "restitution": h.restitution,
        "friction": h.friction,
        "gap": h.gap,
        "n_guides": s.n_guides,
        "guides": s.guides,
        "start_radius": s.start_radius,
        "mass_spread": s.mass_spread,
        "time_jitter": s.time_jitter,
        "stone_generator": "numpy.random.default_rng(seed)",
    }


def impact_run(model: ImpactRotor, t_end: float = 10.0, *, seed: int | None = 0, n_save: int = 4000,
               rtol: float = 1e-8, atol: float = 1e-11,
               sliding_fraction: float = SLIDING_FRACTION) -> xarray.Dataset:  # fmt: skip
    """Simulate one run from rest with a seeded stone sequence; trajectory of P and bookkeeping.

    Parameters
    ----------
    model : ImpactRotor
        Its stone feed is used; any sequence it carries is replaced by one drawn from ``seed``.
    t_end : float
        Duration (s), > 0.
    seed : int or None
        Seed of the stone sequence (:meth:`rotorlab.models.StoneFeed.sequence`).
    n_save : int
        Number of saved states (trajectory of P), >= 2.
    rtol, atol : float
        Integrator tolerances (atol in m, m/s, rad, rad/s).
    sliding_fraction : float
        See :func:`classify_impacts`.

    Returns
    -------
    xarray.Dataset
        Scalars (``impacts``, ``impacts_all``, ``slides``, ``sliding_time``, ``max_penetration``,
        ``max_approach_speed``, ``energy_*``, ``eta``, ``whirl``, ``regime``, ``status``), the
        trajectory of P in the rotating frame ``p_x, p_y`` (dim ``time``, in units of the gap),
        ``mode``, and the stone sequence ``stone_time``, ``stone_mass``, ``stone_guide`` (dim
        ``stone``); ``attrs["regime"]`` is the label and ``attrs["seed"]`` the seed.

    Examples
    --------
    >>> from rotorlab.models import krasnov_crusher
    >>> ds = impact_run(krasnov_crusher(), t_end=1.0, seed=0, n_save=200)
    >>> ds.attrs["regime"], int(ds.impacts), ds.sizes["stone"]
    ('none', 0, 28)
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, solve_ensemble

    if not (t_end > 0 and math.isfinite(t_end)):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    if int(n_save) < 2:
        raise ValueError(f"n_save must be >= 2, got {n_save!r}")
    from rotorlab._memory import check_memory

    check_memory(8.0 * int(n_save) * (2 * _k.N_STATE + 8), f"n_save = {int(n_save)} saved states of {_k.N_STATE} entries",
                 "save fewer states (n_save)")  # fmt: skip
    run = model.with_stones(t_end, seed)
    ts = np.linspace(0.0, t_end, int(n_save))
    sol = solve_ensemble(run, run.initial_state(), (0.0, t_end), save_at=SaveAt(ts=ts),
                         control=_control(rtol, atol), max_events_recorded=0, threads=1)  # fmt: skip
    sc = {k: v[0] for k, v in _scalars([run], sol).items()}
    ys = sol.ys[0]
    w = run.gap_vector(ys) / run.housing.gap
    # penetration also from the saved states (sliding drift included)
    sc["max_penetration"] = max(float(sc["max_penetration"]),
                                float(np.nanmax(np.hypot(w[:, 0], w[:, 1]), initial=0.0) - 1.0) * run.housing.gap, 0.0)  # fmt: skip
    code = int(classify_impacts(sc["impacts"], sc["sliding_time"], sc["t_final"], sc["whirl"],
                                sc["status"], sliding_fraction))  # fmt: skip
    sc["regime"] = code
    data = {k: ((), v, {"units": _UNITS[k], "description": _DESCRIPTIONS[k]}) for k, v in sc.items()}
    data["p_x"] = (("time",), w[:, 0], {"units": "1", "description": "w_x / gap, rotating frame"})
    data["p_y"] = (("time",), w[:, 1], {"units": "1", "description": "w_y / gap, rotating frame"})
    data["mode"] = (("time",), ys[:, _k.MODE], {"units": "1", "description": "0 free, 1 sliding"})
    data["displacement"] = (("time", "axis"), ys[:, 0:2], {"units": "m"})
    data["tilt"] = (("time", "axis"), ys[:, 2:4], {"units": "rad"})
    seq = run.sequence
    data["stone_time"] = (("stone",), seq.times, {"units": "s"})
    data["stone_mass"] = (("stone",), seq.masses, {"units": "kg"})
    data["stone_guide"] = (("stone",), seq.guides, {"units": "1", "description": "guide j at 2 pi j / N"})
    ds = xr.Dataset(data, coords={"time": ("time", ts, {"units": "s"}), "axis": ["x", "y"],
                                  "stone": ("stone", np.arange(len(seq)), {"units": "1"})})  # fmt: skip
    ds.attrs.update(_model_attrs(run, t_end, sliding_fraction))
    ds.attrs.update({"analysis": "impacts", "regime": _label(code), "seed": -1 if seed is None else int(seed)})
    if sol.notes and sol.notes[0]:
        ds.attrs["status_detail"] = sol.notes[0]
    elif int(sc["status"]) < 0:
        from rotorlab.integrate import Status

        ds.attrs["status_detail"] = Status(int(sc["status"])).message
    elif int(sc["whirl"]):
        ds.attrs["status_detail"] = (f"stopped at t = {float(sc['t_final']):.6g} s at the onset of the dry-friction backward "
                                     "whirl (P rolls on the housing); the model cannot carry it beyond")  # fmt: skip
    return ds


def _num(x: Any) -> float | int | None:
    v = float(x)
    if not math.isfinite(v):
        return None
    return int(v) if float(v).is_integer() and abs(v) < 2**53 and isinstance(x, (int, np.integer)) else v


def impact_summary(ds: xarray.Dataset) -> dict[str, Any]:
    """JSON-ready summary of :func:`impact_run` (SI; keys named with their unit).

    Examples
    --------
    >>> from rotorlab.models import krasnov_crusher
    >>> s = impact_summary(impact_run(krasnov_crusher(), t_end=0.5, n_save=50))
    >>> s["regime"], s["impacts"], s["sliding_time_s"]
    ('none', 0, 0.0)
    """
    return {
        "regime": ds.attrs["regime"],
        "impacts": int(ds.impacts),
        "impacts_all": int(ds.impacts_all),
        "slides": int(ds.slides),
        "sliding_time_s": float(ds.sliding_time),
        "energy_ratio": _num(ds.eta.values),
        "energy_ratio_before_runaway": _num(ds.eta_before_runaway.values),
        "runaway_start_s": _num(ds.runaway_start.values),
        "impacts_before_runaway": int(ds.impacts_before_runaway),
        "impacts_runaway": int(ds.impacts_runaway),
        "energy_friction_runaway_J": float(ds.energy_friction_runaway),
        "energy_stones_J": float(ds.energy_stones),
        "energy_friction_J": float(ds.energy_friction),
        "energy_vibration_J": float(ds.energy_vibration),
        "work_stones_J": float(ds.work_stones),
        "max_penetration_m": float(ds.max_penetration),
        "max_approach_speed_m_s": float(ds.max_approach_speed),
        "backward_whirl": bool(int(ds.whirl)),
        "t_final_s": float(ds.t_final),
        "status": int(ds.status),
        "status_detail": str(ds.attrs.get("status_detail", "")),
        "seed": int(ds.attrs["seed"]),
        "stone_mass_kg": float(ds.attrs["stone_mass"]),
        "n_stones": int(ds.sizes["stone"]),
        "t_end_s": float(ds.attrs["t_end"]),
    }


def sweep_summary(ds: xarray.Dataset) -> dict[str, Any]:
    """JSON-ready summary of :func:`impact_sweep`: per value the median, quartiles, regimes.

    Impact statistics (median, quartiles, range) are over the runs that did not fail, None where
    every run failed; ``regimes`` counts the runs per regime and ``failed``; ``regime`` is the most
    frequent of those (the first of equals, in that order).
    """
    rows = []
    for i, v in enumerate(ds.value.values):
        counts = {lab: int(round(float(ds.regime_fraction.values[i, c]) * ds.sizes["sequence"]))
                  for c, lab in enumerate(REGIMES)}  # fmt: skip
        counts["failed"] = int(round(float(ds.failed_fraction.values[i]) * ds.sizes["sequence"]))
        done = ds.impacts.values[i][ds.regime.values[i] >= 0]  # a failed run's count is no result
        rows.append({
            "value": float(v),
            "impacts_median": _num(ds.impacts_median.values[i]),
            "impacts_q25": _num(ds.impacts_q25.values[i]),
            "impacts_q75": _num(ds.impacts_q75.values[i]),
            "impacts_min": int(done.min()) if done.size else None,
            "impacts_max": int(done.max()) if done.size else None,
            "sliding_time_median_s": _num(ds.sliding_time_median.values[i]),
            "energy_ratio_median": _num(ds.eta_median.values[i]),
            "energy_ratio_before_runaway_median": (_num(ds.eta_before_runaway_median.values[i])
                                                   if "eta_before_runaway_median" in ds else None),
            "regimes": counts,
            "regime": max(counts, key=counts.get),  # the most frequent outcome, "failed" included
        })  # fmt: skip
    return {"param": ds.attrs["param"], "units": ds.attrs["param_units"], "t_end_s": ds.attrs["t_end"],
            "n_sequences": int(ds.sizes["sequence"]), "seed": int(ds.attrs["seed"]), "rows": rows}  # fmt: skip


#: Analysis types of case files run by :func:`run_impact_analysis`.
IMPACT_ANALYSES = ("impacts", "impacts-sweep")


def impact_model(case_model: Any, **overrides: float) -> ImpactRotor:
    """Build the :class:`~rotorlab.models.ImpactRotor` of a validated ``impact_rotor`` case model.

    Parameters
    ----------
    case_model : rotorlab.io.ImpactRotorSpec
        ``Case.model`` (SI).
    **overrides : float
        Values of :data:`SWEEP_PARAMS` names (``stone_mass=3.0``) replacing the case's.

    Returns
    -------
    ImpactRotor
        Without stones (runs draw their own sequences).

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> m = impact_model(load_case("krasnov-crusher").model, stone_mass=3.0)
    >>> m.stones.mass, m.rotor.spin_speed, m.translational
    (3.0, 160.0, False)
    """
    from rotorlab.io import ImpactRotorSpec
    from rotorlab.models import ImpactRotor

    if not isinstance(case_model, ImpactRotorSpec):
        raise ValueError(f"needs an impact_rotor model, got {getattr(case_model, 'type', None)!r}")
    from rotorlab.io._built import handed_down

    model = handed_down(case_model, ImpactRotor)  # the run's model; the overrides derive from it
    model = _impact_rotor(case_model) if model is None else model
    for name, value in overrides.items():
        if name not in SWEEP_PARAMS:
            raise ValueError(f"unknown override {name!r} (known: {', '.join(SWEEP_PARAMS)})")
        part, fld, _ = SWEEP_PARAMS[name]
        model = replace(model, **{part: replace(getattr(model, part), **{fld: float(value)})})
    return model


def _impact_rotor(case_model: Any) -> Any:
    from rotorlab.models import CentrifugeRotor, Housing, ImpactRotor, StoneFeed

    cm, h, s = case_model, case_model.housing, case_model.stones
    rotor = CentrifugeRotor(cm.mass, cm.inertia_transverse, cm.inertia_polar, cm.spin_speed, cm.stiffness_1,
                            cm.stiffness_2, cm.height_1, cm.height_2, cm.internal_friction, cm.translational)  # fmt: skip
    housing = Housing(h.radius, h.height, h.gap, h.cone_angle, h.restitution, h.friction, h.rest_speed,
                      h.count_speed, h.whirl_limit)  # fmt: skip
    feed = StoneFeed(s.mass, s.interval, s.radius, s.height, s.spiral_angle, s.guide_friction, s.start_radius,
                     s.start_speed, s.n_guides, s.guides, s.first_time, s.mass_spread, s.time_jitter)  # fmt: skip
    return ImpactRotor(rotor, housing, feed)


def _one_run(model: ImpactRotor, analysis: Any, progress: Callable[[int, int], None] | None) -> xarray.Dataset:
    if progress is not None:
        progress(0, 1)
    ds = impact_run(model, analysis.t_end, seed=analysis.seed, n_save=analysis.n_save, rtol=analysis.rtol,
                    atol=analysis.atol, sliding_fraction=analysis.sliding_fraction)  # fmt: skip
    if progress is not None:
        progress(1, 1)
    return ds


def _many_runs(model: ImpactRotor, analysis: Any, progress: Callable[[int, int], None] | None) -> xarray.Dataset:
    from rotorlab.analyses._impact_sweep import impact_sweep

    return impact_sweep(model, analysis.values, param=analysis.param, n_sequences=analysis.n_sequences,
                        t_end=analysis.t_end, seed=analysis.seed, rtol=analysis.rtol, atol=analysis.atol,
                        sliding_fraction=analysis.sliding_fraction, progress=progress)  # fmt: skip


_RUNNERS = {"impacts": _one_run, "impacts-sweep": _many_runs}


def run_impact_analysis(case_model: Any, analysis: Any,
                        progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Run an ``impacts`` or ``impacts-sweep`` analysis of a case (see :func:`impact_run`,
    :func:`impact_sweep`); ``attrs["name"]`` is the analysis name."""
    if analysis.type not in _RUNNERS:
        raise ValueError(f"not an impact analysis: {analysis.type!r}")
    ds = _RUNNERS[analysis.type](impact_model(case_model, **analysis.overrides()), analysis, progress)
    ds.attrs["name"] = analysis.name
    return ds


def impact_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """The summary rows of an ``impacts`` run: one row, :func:`impact_summary`."""
    return [impact_summary(ds)]


def sweep_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """The summary rows of an ``impacts-sweep``: one per swept value (:func:`sweep_summary`)."""
    return sweep_summary(ds)["rows"]


def paper_counts(ds: xarray.Dataset) -> list[int | None]:
    """Seed 001's printed count for each swept stone mass, where the sweep matches the table.

    The table applies to the general (tilting) rotor, stone-mass sweeps, Delta t = 0.035 s and
    10 s runs; other entries are None.
    """
    a = ds.attrs
    applies = (a.get("param") == "stone_mass" and not a.get("translational")
               and abs(float(a.get("interval", 0)) - 0.035) < 1e-12 and abs(float(a.get("t_end", 0)) - 10.0) < 1e-12)  # fmt: skip
    out: list[int | None] = []
    for v in ds.value.values:
        hit = [n for m, n in SEED001_TABLE.items() if abs(m - float(v)) < 1e-9]
        out.append(hit[0] if applies and hit else None)
    return out
