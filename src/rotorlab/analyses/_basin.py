"""Run the basin analyses of a case (``basin``, ``working-point``) and tabulate their results.

``basin`` builds the case's mapper (:class:`~rotorlab.explore.TorusRegimes` for a
``toroidal_ball`` model, :class:`~rotorlab.explore.BalancerRegimes` for a ``jeffcott_balls``
model) and calls :func:`rotorlab.explore.basin_map` on a grid, or
:func:`rotorlab.explore.basin_stability` on a seeded random sample; the Dataset gains the basin
fractions at every horizon. ``working-point`` is the working equilibrium of the toroidal ball
with its friction band and the restoring force against the ring angle (seed 004 Fig. 3).
:func:`basin_rows` and :func:`basin_document` turn results into plain data for the command line,
the report and JSON.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray

__all__ = [
    "BASIN_ANALYSES",
    "basin_mapper",
    "run_basin",
    "run_basin_analysis",
    "basin_rows",
    "basin_document",
    "compare_basins",
]

#: Analysis types run by :func:`run_basin_analysis`.
BASIN_ANALYSES = ("basin", "working-point")


def _num(value: Any) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def basin_mapper(case_model: Any, analysis: Any, *, t_end: float | None = None,
                 explain: dict[str, Any] | None = None) -> Any:
    """Build the mapper of a ``basin`` (or ``sweep``) analysis.

    Without a ``t_end`` (here or in the analysis) a mapper of a balancer (one with
    ``balanced_decay_rate()``) runs :func:`rotorlab.explore._settle.default_horizon`: several time
    constants of its balanced state's slowest decaying mode, within stated revolution bounds.

    Parameters
    ----------
    case_model : rotorlab.io.ToroidalBallSpec or rotorlab.io.JeffcottBallsSpec
        ``Case.model``.
    analysis : rotorlab.io.BasinSpec or rotorlab.io.SweepSpec
        Gives ``n_horizons``, ``t_end``, ``window_revolutions``, ``spare_turns``, ``rtol``,
        ``atol`` (None: the mapper's default) and ``spin_speed(case_model)``.
    t_end : float, optional
        Simulated time (s) instead of the analysis' (or the default).
    explain : dict, optional
        Filled with ``horizon_rule`` (how the horizon was chosen, a sentence) and, for a
        balancer, ``slowest_decay_rate`` (1/s; NaN without a stable balanced state).

    Returns
    -------
    rotorlab.explore.TorusRegimes, rotorlab.explore.BalancerRegimes or rotorlab.explore.MachineRegimes

    Raises
    ------
    ValueError
        The model cannot be mapped (see :meth:`rotorlab.io.BasinSpec.case_issues`).
    """
    from rotorlab.analyses._registry import MODEL_TYPES

    kw: dict[str, Any] = {"n_horizons": analysis.n_horizons}
    if t_end is not None or analysis.t_end is not None:
        kw["t_end"] = float(t_end if t_end is not None else analysis.t_end)
    if analysis.window_revolutions is not None:
        kw["window_revolutions"] = analysis.window_revolutions
    kind = getattr(case_model, "type", None)
    entry = MODEL_TYPES.get(kind)
    mapper = None if entry is None or entry.mapper is None else entry.mapper(case_model, analysis, kw)
    if mapper is None:
        raise ValueError(f"analysis {analysis.name}: basins need a toroidal_ball model or a jeffcott_balls or machine "
                         f"model with balls, not {kind!r}")  # fmt: skip
    return _with_horizon(mapper, "t_end" in kw, "the t_end given", explain)


def _with_horizon(mapper: Any, given: bool, source: str, explain: dict[str, Any] | None) -> Any:
    """The mapper with its default horizon from its balanced state's eigenvalues (when it has
    ``balanced_decay_rate`` and no t_end was given); ``explain`` gets how it was chosen."""
    from dataclasses import replace

    from rotorlab.explore._settle import default_horizon

    rate_of = getattr(mapper, "balanced_decay_rate", None)
    rate = rate_of() if rate_of is not None else None
    info: dict[str, Any] = {"slowest_decay_rate": math.nan if rate is None else float(rate)}
    if given or rate_of is None:
        t = float(mapper.horizons()[-1])
        info["horizon_rule"] = f"horizon {t:.3g} s, from {source}" if given else f"horizon {t:.3g} s, the mapper's default"
        if rate is not None:
            info["horizon_rule"] += f" ({t * rate:.3g} time constants of the balanced state's slowest mode, {1 / rate:.3g} s)"
    else:
        speed = mapper.start_value("spin_speed")
        t, info["horizon_rule"] = default_horizon(rate, speed, float(mapper.t_end))
        mapper = replace(mapper, t_end=t)
    if explain is not None:
        explain.update(info)
    return mapper


def torus_mapper(case_model: Any, analysis: Any, kw: dict[str, Any]) -> Any:
    """The regime mapper of a ``toroidal_ball`` model (the ``mapper`` of its model type)."""
    from rotorlab.analyses._case import build_model
    from rotorlab.explore import TorusRegimes
    from rotorlab.integrate import StepControl

    if analysis.rtol is not None or analysis.atol is not None:
        kw["control"] = StepControl(rtol=analysis.rtol or 1e-6, atol=analysis.atol or 1e-8)
    if analysis.spare_turns is not None:
        kw["spare_turns"] = analysis.spare_turns
    return TorusRegimes(build_model(case_model), **kw)


def balancer_mapper(case_model: Any, analysis: Any, kw: dict[str, Any]) -> Any:
    """The regime mapper of a ``jeffcott_balls`` model (None without balls): its ball starts at
    the analysis' constant speed (integrated in the fixed frame, see
    :class:`~rotorlab.explore.BalancerRegimes`)."""
    from rotorlab.analyses._case import build_model
    from rotorlab.explore import BalancerRegimes
    from rotorlab.integrate import StepControl
    from rotorlab.models import ConstantSpeed, JeffcottBalls

    if case_model.n_balls == 0:
        return None
    base = build_model(case_model)
    omega = analysis.spin_speed(case_model)
    if omega is None:  # spin_speed is a coordinate of every start: any base speed will do
        omega = case_model.critical_speed()
    model = JeffcottBalls(base.rotor, base.balls, speed=ConstantSpeed(omega))
    if analysis.rtol is not None or analysis.atol is not None:
        kw["control"] = StepControl(rtol=analysis.rtol or 1e-8, atol=analysis.atol or 1e-10)
    return BalancerRegimes(model, **kw)


def run_basin(
    mapper: Any,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    *,
    fixed: Mapping[str, float] | None = None,
    samples: int | None = None,
    seed: int = 0,
    confidence: float = 0.95,
    threads: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    store: Any = None,
    resume: bool = False,
    executor: Any = None,
) -> xarray.Dataset:
    """Map a grid (or random sample) of two start coordinates to regimes, with fractions.

    Parameters
    ----------
    mapper : rotorlab.explore.AbstractMapper
    x, y : (name, start, stop, count)
        Varied coordinates (SI).
    fixed : mapping of str to float, optional
        Other coordinates (SI).
    samples : int, optional
        Draw this many starts uniformly from the x and y ranges (seeded) instead of the grid.
    seed, confidence : int, float
        Random starts: seed and level of the Wilson intervals.
    threads, chunk_size, progress
        As for :func:`rotorlab.explore.map_starts`; results do not depend on them.
    store : path-like, optional
        Checkpoint: write every chunk to this Zarr store as it finishes; an interrupted run
        continues with ``resume=True``, computing only the missing chunks. The Dataset is the
        same, bit for bit, as without a store.
    resume : bool
        Continue ``store`` (it must hold the same starts and mapper).
    executor : rotorlab.sweep.InProcess, LocalProcesses or DaskExecutor, optional
        Where the chunks run (instead of ``threads``); results do not depend on it.

    Returns
    -------
    xarray.Dataset
        The Dataset of :func:`rotorlab.explore.basin_map` (dims ``y``, ``x``, ``horizon``) or
        of :func:`rotorlab.explore.basin_stability` (dim ``ic``), plus ``fraction`` and
        ``count`` (horizon, regime) and, for random starts, ``ci_low``/``ci_high``; attrs
        ``analysis = "basin"``, ``x``, ``y`` (coordinate names), ``mode`` (``"grid"`` or
        ``"random"``), ``fixed_<name>`` for each fixed coordinate.
    """
    from rotorlab.explore import GridAxis, basin_fractions, basin_map, basin_stability

    fixed = dict(fixed or {})
    if samples is None:
        ds = basin_map(mapper, GridAxis(*x), GridAxis(*y), fixed=fixed, threads=threads, chunk_size=chunk_size,
                       progress=progress, store=store, resume=resume, executor=executor)  # fmt: skip
        fr = basin_fractions(ds)
        ds = ds.assign(fraction=fr["fraction"], count=fr["count"])
        mode = "grid"
    else:
        ds = basin_stability(mapper, {x[0]: (x[1], x[2]), y[0]: (y[1], y[2])}, samples, seed=seed,
                             confidence=confidence, fixed=fixed, threads=threads, chunk_size=chunk_size,
                             progress=progress, store=store, resume=resume, executor=executor)  # fmt: skip
        ds = ds.assign(fraction=ds["probability"])
        mode = "random"
        for name, value in fixed.items():
            ds.attrs[f"fixed_{name}"] = float(value)
    ds["fraction"].attrs.update(units="1", description="fraction of the starts with each label")
    ds["count"].attrs.update(units="1", description="number of starts with each label")
    ds.attrs.update(analysis="basin", x=x[0], y=y[0], mode=mode)
    return ds


def run_basin_analysis(case_model: Any, analysis: Any, *, t_end: float | None = None,
                       threads: int | None = None, chunk_size: int | None = None,
                       progress: Callable[[int, int], None] | None = None, store: Any = None,
                       resume: bool = False, executor: Any = None) -> xarray.Dataset:  # fmt: skip
    """Run one ``basin`` or ``working-point`` analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.ToroidalBallSpec or rotorlab.io.JeffcottBallsSpec
        ``Case.model``.
    analysis : rotorlab.io.BasinSpec or rotorlab.io.WorkingPointSpec
    t_end : float, optional
        Simulated time (s) instead of the analysis' (basin only).
    threads, chunk_size, progress, store, resume, executor
        As for :func:`run_basin` (basin only; a ``working-point`` refuses a store).

    Returns
    -------
    xarray.Dataset
        See :func:`run_basin`; for ``working-point`` the variables of
        :meth:`rotorlab.models.ToroidalBall.working_point` and the restoring force
        (:meth:`rotorlab.models.ToroidalBall.restoring_force`) on a ``ring_angle`` dim (its
        ``alpha`` and ``normal`` renamed ``curve_alpha`` and ``curve_normal``), and one
        trajectory released at ``start`` on a ``time`` dim (``release_psi``, ``release_alpha``,
        ``release_dpsi``, ``release_dalpha``; seed 004 Fig. 5) with attrs ``release_stuck``
        and ``release_settle_time`` (s).
        ``attrs["name"]`` is the analysis name; a basin also has ``value_<name>``, the value
        of every coordinate that is not varied (fixed, or the model's; SI) with its SI unit in
        ``units_<name>`` (none for a dimensionless one), and
        ``input_units_<name>`` (``"deg"``) for every coordinate the case gave in degrees
        (:attr:`rotorlab.io.BasinSpec.input_units`; figures show it in that unit).

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> case = load_case("strautmanis-torus")
    >>> ds = run_basin_analysis(case.model, case.analysis("working-point"))
    >>> round(float(ds.psi), 5), round(float(ds.alpha), 4)  # seed 004: 3.14156, 1.56825
    (3.14159, 1.5685)
    >>> bool(ds.alpha_band[0] <= 1.56825 <= ds.alpha_band[1]), bool(ds.psi_band[0] <= 3.14156 <= ds.psi_band[1])
    (True, True)
    """
    if analysis.type == "working-point":
        if store is not None or executor is not None:
            raise ValueError(f"analysis {analysis.name}: a working-point analysis runs no sweep (no store or executor)")
        ds = _working_point(case_model, analysis, progress)
    else:
        explain: dict[str, Any] = {}
        mapper = basin_mapper(case_model, analysis, t_end=t_end, explain=explain)
        ds = run_basin(mapper, analysis.x, analysis.y, fixed=analysis.fixed, samples=analysis.samples,
                       seed=analysis.seed, confidence=analysis.confidence, threads=threads,
                       chunk_size=chunk_size, progress=progress, store=store, resume=resume,
                       executor=executor)  # fmt: skip
    ds.attrs["name"] = analysis.name
    ds.attrs["model"] = str(case_model.type)
    if analysis.type == "basin":
        ds.attrs.update(explain)
        from rotorlab.io import DIMENSIONS, coordinate_dimensions

        dims = coordinate_dimensions(case_model)
        for key, value in _effective_values(case_model, analysis, mapper).items():
            ds.attrs[f"value_{key}"] = value
            unit = DIMENSIONS[dims[key]].si if dims.get(key) in DIMENSIONS else ""
            if unit:
                ds.attrs[f"units_{key}"] = unit  # the SI unit of that value, for titles
        for key, unit in analysis.input_units.items():  # what the input was written in, for display
            ds.attrs[f"input_units_{key}"] = unit
    return ds


def basin_task_size(case_model: Any, analysis: Any) -> int:
    """Starts of a case's ``basin`` analysis (its progress-bar total)."""
    return analysis.samples if analysis.samples is not None else analysis.x[3] * analysis.y[3]


def _effective_values(case_model: Any, analysis: Any, mapper: Any) -> dict[str, float]:
    """Every start coordinate that is not varied, with the value the starts use (SI): the fixed
    value, or the mapper's (its ``start_value``)."""
    from rotorlab.io import coordinate_dimensions

    varied = {analysis.x[0], analysis.y[0]}
    out: dict[str, float] = {}
    for name in coordinate_dimensions(case_model):
        if name in varied:
            continue
        value = analysis.fixed[name] if name in analysis.fixed else mapper.start_value(name)
        if value is not None:
            out[name] = float(value)
    return out


def _working_point(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None) -> xarray.Dataset:
    from rotorlab.analyses._case import build_model

    if progress is not None:
        progress(0, 1)
    model = build_model(case_model)
    wp = model.working_point()
    psi = math.pi + np.linspace(-analysis.psi_span, analysis.psi_span, analysis.points)
    force = model.restoring_force(psi)
    force = force.rename({"psi": "ring_angle", "alpha": "curve_alpha", "normal": "curve_normal"})
    ds = wp.to_dataset().merge(force, combine_attrs="drop_conflicts")
    release = _release(model, analysis.start, analysis.t_end, float(wp.frequencies.max()))
    ds = ds.merge(release)
    ds.attrs.update(release.attrs)
    ds.attrs.update(analysis="working-point", rolling_friction=model.rolling_friction, form=model.form)
    if progress is not None:
        progress(1, 1)
    return ds


def _release(model: Any, start: Sequence[float], t_end: float, fastest: float) -> xarray.Dataset:
    """One trajectory released at ``start`` (psi, alpha, dpsi, dalpha), saved on ``time`` (Fig. 5),
    with 16 samples per period of the fastest small oscillation (``fastest``, rad/s)."""
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve

    ts = np.linspace(0.0, t_end, min(int(math.ceil(t_end * fastest / (2.0 * math.pi) * 16.0)) + 1, 100001))
    sol = solve(model, model.initial_state(*start), (0.0, t_end), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=1e-8, atol=1e-10))  # fmt: skip
    stuck = bool(sol.y_final[4] == 0.0 and sol.y_final[5] == 0.0)
    units = ("rad", "rad", "rad/s", "rad/s")
    data = {f"release_{n}": ("time", sol.ys[:, j], {"units": u})
            for j, (n, u) in enumerate(zip(("psi", "alpha", "dpsi", "dalpha"), units))}  # fmt: skip
    return xr.Dataset(data, coords={"time": ("time", ts, {"units": "s"})},
                      attrs={"release_start": list(map(float, start)), "release_stuck": int(stuck),
                             "release_settle_time": float(sol.y_final[6]) if stuck else math.nan,
                             "release_status": int(sol.status)})  # fmt: skip


def _fractions(ds: xarray.Dataset) -> tuple[list[str], np.ndarray]:
    names = [str(r) for r in ds["regime"].values]
    return names, np.asarray(ds["fraction"].values, dtype=float)


def basin_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a basin result: one row per regime (or the working point's numbers).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_basin_analysis`.

    Returns
    -------
    list of dict
        ``basin``: keys ``regime``, ``fraction`` (at the last horizon), ``count``, ``n``,
        ``fraction_half`` (at ``horizon_half_s``, the horizon nearest half the simulated time), ``ci_low``,
        ``ci_high`` (random starts, else None), ``settle_time_median_s`` and
        ``settle_time_max_s`` (of the starts with that final label that settled, else None).
        ``working-point``: keys ``quantity``, ``value``, ``unit``.
    """
    if ds.attrs.get("analysis") == "working-point":
        return [
            {"quantity": "psi", "value": float(ds.psi), "unit": "rad"},
            {"quantity": "alpha", "value": float(ds.alpha), "unit": "rad"},
            {"quantity": "normal", "value": float(ds.normal), "unit": "m/s^2"},
            {"quantity": "psi_band_lo", "value": float(ds.psi_band[0]), "unit": "rad"},
            {"quantity": "psi_band_hi", "value": float(ds.psi_band[1]), "unit": "rad"},
            {"quantity": "alpha_band_lo", "value": float(ds.alpha_band[0]), "unit": "rad"},
            {"quantity": "alpha_band_hi", "value": float(ds.alpha_band[1]), "unit": "rad"},
            {"quantity": "ring_frequency", "value": float(ds.frequency[0]), "unit": "rad/s"},
            {"quantity": "cross_section_frequency", "value": float(ds.frequency[1]), "unit": "rad/s"},
            {"quantity": "released_final_psi", "value": float(ds.release_psi[-1]), "unit": "rad"},
            {"quantity": "released_final_alpha", "value": float(ds.release_alpha[-1]), "unit": "rad"},
            {"quantity": "released_settle_time", "value": float(ds.attrs["release_settle_time"]), "unit": "s"},
        ]
    names, frac = _fractions(ds)
    horizons = np.asarray(ds["horizon"].values, dtype=float)
    half = int(np.argmin(np.abs(horizons - horizons[-1] / 2.0)))
    n = int(ds["count"].values[-1].sum())
    outcome = np.asarray(ds["outcome"].values).ravel()
    settle = np.asarray(ds["label_since"].values, dtype=float).ravel()
    has_ci = "ci_low" in ds
    rows = []
    for k, name in enumerate(names):
        t = settle[outcome == k]
        rows.append({
            "regime": name,
            "fraction": float(frac[-1, k]),
            "count": int(ds["count"].values[-1, k]),
            "n": n,
            "fraction_half": float(frac[half, k]),
            "horizon_half_s": float(horizons[half]),
            "ci_low": float(ds["ci_low"].values[-1, k]) if has_ci else None,
            "ci_high": float(ds["ci_high"].values[-1, k]) if has_ci else None,
            "label_since_median_s": _num(np.median(t)) if t.size else None,
            "label_since_max_s": _num(np.max(t)) if t.size else None,
        })  # fmt: skip
    return rows


def basin_document(ds: xarray.Dataset) -> dict[str, Any]:
    """Return a basin result as JSON-ready data (the ``rotorlab basin --json`` document).

    Returns
    -------
    dict
        ``fractions`` (label -> fraction at the last horizon), ``n``, ``t_end_s``, ``x``, ``y``
        (names), ``mode``, ``fixed`` (SI), ``horizons_s`` and ``fractions_by_horizon`` (label ->
        list), ``label_since_s`` (label -> median and max time from which the starts ending with
        that label kept it), and for random starts ``seed``, ``confidence`` and ``ci`` (label ->
        [low, high]); ``verdict`` (:func:`rotorlab.analyses._verdict.basin_verdict`), and where
        the horizon rule is known ``horizon_rule`` and ``slowest_decay_rate_per_s``.
    """
    names, frac = _fractions(ds)
    rows = basin_rows(ds)
    doc: dict[str, Any] = {
        "fractions": {n: float(frac[-1, k]) for k, n in enumerate(names)},
        "n": rows[0]["n"] if rows else 0,
        "t_end_s": float(ds["horizon"].values[-1]),
        "x": ds.attrs.get("x"),
        "y": ds.attrs.get("y"),
        "mode": ds.attrs.get("mode"),
        "fixed": {k[6:]: float(v) for k, v in ds.attrs.items() if k.startswith("fixed_")},
        "horizons_s": [float(h) for h in ds["horizon"].values],
        "fractions_by_horizon": {n: [float(v) for v in frac[:, k]] for k, n in enumerate(names)},
        "label_since_s": {r["regime"]: {"median": r["label_since_median_s"], "max": r["label_since_max_s"]}
                          for r in rows},
    }  # fmt: skip
    if "outcome" in ds:
        from rotorlab.analyses._verdict import basin_verdict

        doc["verdict"] = basin_verdict(ds)
    if ds.attrs.get("horizon_rule"):
        doc["horizon_rule"] = str(ds.attrs["horizon_rule"])
        doc["slowest_decay_rate_per_s"] = _num(ds.attrs.get("slowest_decay_rate", math.nan))
    if ds.attrs.get("mode") == "random":
        doc["seed"] = int(ds.attrs["seed"])
        doc["confidence"] = float(ds.attrs["confidence"])
        doc["ci"] = {r["regime"]: [r["ci_low"], r["ci_high"]] for r in rows}
    return doc


def compare_basins(results: Mapping[str, xarray.Dataset], label: str | None = None) -> dict[str, Any] | None:
    """Compare basin results that differ in one fixed coordinate (e.g. the rolling friction).

    Parameters
    ----------
    results : mapping of str to xarray.Dataset
        Basin results by analysis name (others are ignored).
    label : str, optional
        The regime to compare; default the first label (``working`` / ``balanced``).

    Returns
    -------
    dict or None
        None unless at least two basin results share their grid axes, labels and horizons and
        differ in exactly one fixed coordinate. Otherwise ``parameter`` (its name), ``label``,
        ``horizons_s``, ``entries`` (list of ``{"analysis", "value", "fractions"}`` sorted by the
        parameter value, fractions of ``label`` at every horizon), ``larger_wins`` (per horizon:
        True if the fraction grows with the parameter, False if it shrinks, None if neither
        throughout) and ``verdict`` (one sentence).
    """
    basins = [(n, ds) for n, ds in results.items() if ds.attrs.get("analysis") == "basin"]
    if len(basins) < 2:
        return None
    first = basins[0][1]

    def key(ds: xarray.Dataset) -> tuple[Any, ...]:
        return (ds.attrs.get("x"), ds.attrs.get("y"), ds.attrs.get("mode"), tuple(ds["regime"].values),
                tuple(np.round(ds["horizon"].values, 9)))  # fmt: skip

    basins = [(n, ds) for n, ds in basins if key(ds) == key(first)]
    fixed = [{k[6:]: float(v) for k, v in ds.attrs.items() if k.startswith(("fixed_", "value_"))}
             for _, ds in basins]  # fmt: skip
    names = set().union(*fixed)
    differing = [k for k in sorted(names) if len({f.get(k) for f in fixed}) > 1]
    if len(basins) < 2 or len(differing) != 1 or any(differing[0] not in f for f in fixed):
        return None
    param = differing[0]
    regimes = [str(r) for r in first["regime"].values]
    label = label or regimes[0]
    k = regimes.index(label)
    entries = sorted(({"analysis": n, "value": f[param],
                       "fractions": [float(v) for v in ds["fraction"].values[:, k]]}
                      for (n, ds), f in zip(basins, fixed)), key=lambda e: e["value"])  # fmt: skip
    table = np.array([e["fractions"] for e in entries])
    steps = np.diff(table, axis=0)
    wins = [True if np.all(s > 0) else False if np.all(s < 0) else None for s in steps.T]
    horizons = [float(h) for h in first["horizon"].values]
    lo, hi = entries[0], entries[-1]
    t = horizons[-1]
    change = ("larger" if hi["fractions"][-1] > lo["fractions"][-1] else
              "smaller" if hi["fractions"][-1] < lo["fractions"][-1] else "the same")  # fmt: skip
    verdict = (f"After {t:g} s, {param} = {hi['value']:g} gives a {change} {label} fraction than "
               f"{param} = {lo['value']:g}: {hi['fractions'][-1]:.1%} against {lo['fractions'][-1]:.1%}.")
    if len(set(wins)) > 1:
        parts = [f"{what} at {_spans(horizons, [w is flag for w in wins])} s"
                 for flag, what in ((True, "larger"), (False, "smaller"), (None, "neither larger nor smaller"))
                 if flag in wins]  # fmt: skip
        verdict += f" With larger {param} the {label} fraction is " + " and ".join(parts) + "."
    return {"parameter": param, "label": label, "horizons_s": horizons, "entries": entries,
            "larger_wins": wins, "verdict": verdict}  # fmt: skip


def _spans(values: Sequence[float], mask: Sequence[bool]) -> str:
    """Compress the values where mask holds into runs: ``"10-140, 200"``.

    Examples
    --------
    >>> _spans([10.0, 20.0, 30.0, 40.0, 50.0], [True, True, False, True, False])
    '10-20, 40'
    """
    from rotorlab.explore._outcome import true_runs

    return ", ".join(f"{a:g}" if a == b else f"{a:g}-{b:g}" for a, b in true_runs(values, mask))
