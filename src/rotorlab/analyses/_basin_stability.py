"""Run a case's ``basin-stability`` analysis and tabulate it: the probability of balancing (and of
every other motion, and of not having settled) from random starts at each value of a parameter.

The mapper is the case model's (:func:`rotorlab.analyses.basin_mapper`, as for ``basin`` and
``sweep``); the starts and rounds are :func:`rotorlab.explore.basin_stability_over`'s. Without a
``t_end`` the horizon is the longest of the default horizons
(:func:`rotorlab.explore._settle.default_horizon`) of the balanced state at every parameter
value, each from that value's slowest decaying mode; each value's verdict ("the fractions no
longer change", or the horizon that would do) is :func:`rotorlab.analyses._verdict.basin_verdict`'s.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray

__all__ = ["run_basin_stability_analysis", "basin_stability_rows", "basin_stability_document",
           "basin_stability_task_size", "stability_mapper"]  # fmt: skip


def _num(value: Any) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def _at(mapper: Any, name: str, value: float) -> Any:
    """The mapper of the model at ``name = value`` (None where the mapper cannot make it)."""
    try:
        model = mapper.starts({name: np.array([float(value)])})[0]
        return replace(mapper, model=model)
    except (ValueError, TypeError, KeyError):
        return None


def stability_mapper(case_model: Any, spec: Any, *, t_end: float | None = None) -> tuple[Any, np.ndarray, str]:
    """The mapper of a ``basin-stability`` analysis, the balanced state's slowest decay rate at
    every parameter value (1/s, NaN where none is stable) and how the horizon was chosen.

    Without a ``t_end`` (here or in ``spec``) the horizon is the longest default horizon over the
    values: several time constants of each value's slowest mode, within revolution bounds.
    """
    from rotorlab.analyses._basin import basin_mapper

    explain: dict[str, Any] = {}
    given = t_end is not None or spec.t_end is not None
    mapper = basin_mapper(case_model, spec, t_end=t_end, explain=explain)
    name, a, b, n = spec.param_axis
    return horizon_over(mapper, name, np.linspace(a, b, n), given, str(explain.get("horizon_rule", "")))


def horizon_over(mapper: Any, name: str, values: np.ndarray, given: bool, rule: str) -> tuple[Any, np.ndarray, str]:
    """The mapper with the longest default horizon over ``name = values`` (unless ``given``: the
    horizon was set), the balanced state's slowest decay rate at each value (1/s, NaN where none
    is stable) and how the horizon was chosen (``rule`` when it was given)."""
    from rotorlab.explore._settle import default_horizon

    variants = [_at(mapper, name, v) for v in values]
    rate_of = [getattr(m, "balanced_decay_rate", None) for m in variants]
    rates = np.array([np.nan if f is None or f() is None else float(f()) for f in rate_of])
    if not given and getattr(mapper, "balanced_decay_rate", None) is not None:
        choices = [default_horizon(None if not np.isfinite(r) else r, m.start_value("spin_speed") if m else
                                   mapper.start_value("spin_speed"), float(mapper.t_end))
                   for r, m in zip(rates, variants)]  # fmt: skip
        k = int(np.argmax([c[0] for c in choices]))
        mapper = replace(mapper, t_end=float(choices[k][0]))
        rule = (f"horizon {choices[k][0]:.3g} s, the longest default horizon over {name} (at {name} = {values[k]:.4g}: "
                f"{choices[k][1].removeprefix('horizon ')})")  # fmt: skip
    return mapper, rates, rule


def run_basin_stability_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None,
                                 *, t_end: float | None = None, chunk_size: int | None = None, store: Any = None,
                                 resume: bool = False, executor: Any = None) -> xarray.Dataset:  # fmt: skip
    """Run one ``basin-stability`` analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.AbstractModelSpec
        ``Case.model`` (a model with a regime mapper).
    analysis : rotorlab.io.BasinStabilitySpec
    progress : callable, optional
        ``progress(done, planned)`` in starts.
    t_end : float, optional
        Simulated time (s) instead of the analysis' (or the default).
    chunk_size, store, resume, executor
        As for :func:`rotorlab.explore.basin_stability_over`; results do not depend on them
        (except ``chunk_size``, the step of the adaptive rounds).

    Returns
    -------
    xarray.Dataset
        :func:`rotorlab.explore.basin_stability_over`'s, plus ``decay_rate`` (value; the
        balanced state's slowest decay rate, 1/s); attrs ``analysis``, ``name``, ``model``,
        ``horizon_rule``, ``param_units``.
    """
    from rotorlab.explore import basin_stability_over
    from rotorlab.sweep import GridAxis

    mapper, rates, rule = stability_mapper(case_model, analysis, t_end=t_end)
    name, a, b, n = analysis.param_axis
    units = dict(mapper.coordinate_units)
    shown = {k: v for k, v in analysis.input_units.items() if k == name}  # the drawn starts are no sweep axis
    ds = basin_stability_over(mapper, GridAxis(name, a, b, n), analysis.start_ranges(case_model), seed=analysis.seed,
                              starts=analysis.starts, ci_width=analysis.ci_width, confidence=analysis.confidence,
                              chunk_size=chunk_size if chunk_size is not None else analysis.chunk, store=store,
                              resume=resume, executor=executor, progress=progress, input_units=shown)  # fmt: skip
    ds["decay_rate"] = ((name,), rates, {"units": "1/s", "description": "slowest decay rate of the balanced state"})
    ds.attrs.update(analysis="basin-stability", name=analysis.name, model=str(case_model.type), horizon_rule=rule,
                    param_units=units.get(name, ""))  # fmt: skip
    return ds


def basin_stability_task_size(case_model: Any, analysis: Any) -> int:
    """The most starts a case's ``basin-stability`` analysis may run (its progress-bar total)."""
    from rotorlab._wilson import starts_for_half_width

    per = analysis.starts if analysis.starts is not None else starts_for_half_width(analysis.ci_width or 0.05,
                                                                                   analysis.confidence)
    return int(per) * int(analysis.param_axis[3])


def _verdict_at(ds: xarray.Dataset, i: int) -> dict[str, Any]:
    """:func:`~rotorlab.analyses._verdict.basin_verdict` of the starts at the i-th value."""
    from rotorlab.analyses._verdict import basin_verdict

    dim = ds.attrs["param"]
    one = ds.isel({dim: i})
    keep = np.asarray(one["computed"].values, dtype=bool)
    part = one.isel(start=np.flatnonzero(keep))[[v for v in ("count", "outcome") if v in one]]
    if "settle_estimate" in one:  # at the last horizon (the only one kept)
        part["settle_estimate"] = one["settle_estimate"].isel(start=np.flatnonzero(keep)).expand_dims(
            horizon=[float(ds.horizon[-1])], axis=-1)  # fmt: skip
    part.attrs["slowest_decay_rate"] = float(ds["decay_rate"].values[i]) if "decay_rate" in ds else math.nan
    return basin_verdict(part, float(ds.attrs.get("confidence", 0.95)))


def basin_stability_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a basin-stability result: one row per parameter value.

    Returns
    -------
    list of dict
        ``param``, ``value`` (SI), ``n`` (starts), ``fractions`` and ``ci`` (label -> fraction and
        [low, high] of its Wilson interval), ``balanced`` (the first label's fraction) and
        ``balanced_ci``, ``not_settled``, ``half_width``, ``settle_time_median_s`` and
        ``settle_time_max_s`` (the horizon from which the balanced starts stayed balanced),
        ``time_constant_s`` (1 / the balanced state's slowest decay rate, None if none is
        stable), ``failed`` (integrations), ``settled`` and ``verdict`` (:func:`basin_verdict`).
    """
    from rotorlab.explore._settle import NOT_SETTLED

    dim = ds.attrs["param"]
    labels = [str(r) for r in ds["regime"].values]
    rows = []
    for i, value in enumerate(ds[dim].values):
        n = int(ds["n"].values[i])
        p = ds["probability"].values[i]
        lo, hi = ds["ci_low"].values[i], ds["ci_high"].values[i]
        outcome = np.asarray(ds["outcome"].values[i])
        since = np.asarray(ds["label_since"].values[i], dtype=float)[outcome == 0]
        rate = float(ds["decay_rate"].values[i]) if "decay_rate" in ds else math.nan
        verdict = _verdict_at(ds, i)
        status = np.asarray(ds["status"].values[i])[np.asarray(ds["computed"].values[i], dtype=bool)]
        rows.append({
            "param": dim, "value": float(value), "n": n,
            "fractions": {lab: float(p[k]) for k, lab in enumerate(labels)},
            "ci": {lab: [float(lo[k]), float(hi[k])] for k, lab in enumerate(labels)},
            "balanced": float(p[0]), "balanced_ci": [float(lo[0]), float(hi[0])],
            "not_settled": float(p[labels.index(NOT_SETTLED)]) if NOT_SETTLED in labels else 0.0,
            "half_width": float(ds["half_width"].values[i]),
            "settle_time_median_s": _num(np.median(since)) if since.size else None,
            "settle_time_max_s": _num(np.max(since)) if since.size else None,
            "time_constant_s": 1.0 / rate if math.isfinite(rate) and rate > 0 else None,
            "failed": int(np.count_nonzero(status < 0)),
            "settled": bool(verdict["settled"]), "verdict": verdict["sentence"],
        })  # fmt: skip
    return rows


def basin_stability_document(ds: xarray.Dataset) -> dict[str, Any]:
    """A basin-stability result as JSON-ready data (the ``rotorlab basin-stability --json`` document)."""
    rows = basin_stability_rows(ds)
    return {
        "param": ds.attrs["param"], "param_units": ds.attrs.get("param_units", ""),
        "values": [r["value"] for r in rows], "labels": [str(r) for r in ds["regime"].values],
        "mode": ds.attrs["mode"], "target_half_width": _num(ds.attrs.get("target_half_width", math.nan)),
        "confidence": float(ds.attrs["confidence"]), "seed": int(ds.attrs["seed"]),
        "starts_total": int(ds["n"].values.sum()), "rounds": int(ds.attrs["rounds"]),
        "t_end_s": float(ds["horizon"].values[-1]), "horizon_rule": str(ds.attrs.get("horizon_rule", "")),
        "ranges": json.loads(ds.attrs.get("ranges", "{}")), "rows": rows,
    }  # fmt: skip
