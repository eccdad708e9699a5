"""Run the steady-motion analyses of a case and tabulate their results.

The analyses ``steady``, ``stability-chart``, ``verify`` and ``run-up`` of a case file
(:mod:`rotorlab.io._steady_specs`) call :mod:`rotorlab.steady` on the case's rotor with balls,
with the analysis' regime overrides applied; :func:`steady_rows` turns each result into plain
rows (JSON-ready, SI plus labelled rpm and degree columns) for the command line and the report.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls
    from rotorlab.steady import SteadyAnalysis

__all__ = [
    "STEADY_ANALYSES",
    "steady_model",
    "run_steady_analysis",
    "steady_document",
    "steady_rows",
    "chart_intervals",
]

#: Analysis types run by :func:`run_steady_analysis`.
STEADY_ANALYSES = ("steady", "stability-chart", "verify", "run-up")

_METHODS = ("exact", "hamilton", "averaged")


def _num(value: Any) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def _deg(values: Any) -> list[float | None]:
    return [_num(np.degrees(v)) for v in np.atleast_1d(np.asarray(values, dtype=float))]


def steady_model(case_model: Any, analysis: Any) -> JeffcottBalls:
    """Build the model of a case with an analysis' regime overrides applied.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec
        ``Case.model``.
    analysis : rotorlab.io.SteadyAnalysisSpec or None
        Its ``eccentricity`` and ``support_damping`` replace the model's when given.

    Returns
    -------
    JeffcottBalls

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> case = load_case("zhakash-k2")
    >>> short = case.analysis("short-supercritical")
    >>> round(steady_model(case.model, short).rotor.eccentricity * 1e3, 3)
    2.34
    """
    from rotorlab.analyses._case import build_model
    from rotorlab.steady import with_parameter

    model = build_model(case_model)
    for name, value in ({} if analysis is None else analysis.overrides()).items():
        model = with_parameter(model, name, value)
    return model


def _annotate(ds: xarray.Dataset, analysis: Any) -> xarray.Dataset:
    ds.attrs["name"] = analysis.name
    ds.attrs["analysis"] = analysis.type
    ds.attrs["regime"] = analysis.regime_text()
    return ds


def _steady(model: Any, case_model: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab import steady

    res = steady.analyze_steady(model, analysis.spin_speed(case_model), family_samples=analysis.family_samples)
    return res.to_dataset()


def _chart(model: Any, case_model: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab import steady

    return steady.stability_chart(model, analysis.spin_speeds(case_model), param=analysis.param,
                                  values=analysis.parameter_values(), family_samples=analysis.family_samples)


def _verify(model: Any, case_model: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab import steady

    ends = analysis.t_end if analysis.t_end is None or np.isscalar(analysis.t_end) else list(analysis.t_end)
    return steady.verify(model, analysis.spin_speeds(case_model), points=analysis.ball_angle_points or 8,
                         initial_ball_angles=analysis.initial_ball_angles, t_end=ends,
                         settle_revolutions=analysis.settle_revolutions, rate_tol=analysis.rate_tol,
                         angle_tol=analysis.angle_tol, rtol=analysis.rtol, atol=analysis.atol,
                         family_samples=analysis.family_samples)  # fmt: skip


def _run_up(model: Any, case_model: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab import steady
    from rotorlab.analyses._builders import speed_profile
    from rotorlab.analyses._run_up_verdicts import jeffcott_run_up_verdicts

    ds = steady.run_up(model, speed_profile(analysis.profile(case_model)), t_end=analysis.t_end,
                       t_start=analysis.t_start, initial_ball_angles=analysis.initial_ball_angles,
                       n_save=analysis.n_save, settle_revolutions=analysis.settle_revolutions,
                       rate_tol=analysis.rate_tol, angle_tol=analysis.angle_tol, rtol=analysis.rtol,
                       atol=analysis.atol)  # fmt: skip
    return jeffcott_run_up_verdicts(model, ds)


_RUNNERS: dict[str, Callable[[Any, Any, Any], xarray.Dataset]] = {
    "steady": _steady, "stability-chart": _chart, "verify": _verify, "run-up": _run_up}


def run_steady_analysis(case_model: Any, analysis: Any,
                        progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Run one steady-motion analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec
        ``Case.model``.
    analysis : SteadySpec or StabilityChartSpec or VerifySpec or RunUpSpec
        One entry of ``Case.analyses``.
    progress : callable, optional
        ``progress(done, total)``, called with ``(1, 1)`` when the analysis is finished.

    Returns
    -------
    xarray.Dataset
        From :meth:`rotorlab.steady.SteadyAnalysis.to_dataset`,
        :func:`rotorlab.steady.stability_chart`, :func:`rotorlab.steady.verify` or
        :func:`rotorlab.steady.run_up`; ``attrs``: ``name``, ``analysis`` (the type) and
        ``regime`` (label and overrides, "" if none).

    Raises
    ------
    ValueError
        The type is not one of :data:`STEADY_ANALYSES`.
    """
    if analysis.type not in _RUNNERS:
        raise ValueError(f"analysis {analysis.name}: {analysis.type!r} is not a steady-motion analysis")
    ds = _RUNNERS[analysis.type](steady_model(case_model, analysis), case_model, analysis)
    if progress is not None:
        progress(1, 1)
    return _annotate(ds, analysis)


# --------------------------------------------------------------------------- tables


def steady_document(analysis: SteadyAnalysis) -> dict[str, Any]:
    """Return a steady analysis as JSON-ready data: SI values plus degrees and rpm, labelled.

    Parameters
    ----------
    analysis : rotorlab.steady.SteadyAnalysis

    Returns
    -------
    dict
        :meth:`~rotorlab.steady.SteadyAnalysis.to_dict` with ``speed_rpm``,
        ``critical_speed_rpm`` and ``stable`` (labels by method) added, and per motion
        ``ball_angles_deg`` and ``phase_deg`` (degrees) next to the SI angles.

    Examples
    --------
    >>> from rotorlab.steady import analyze_steady, steady_case
    >>> case = steady_case("zhakash-k2")
    >>> doc = steady_document(analyze_steady(case.model("enough"), 2 * case.critical_speed()))
    >>> doc["stable"]["exact"], [round(a, 2) for a in doc["motions"][0]["ball_angles_deg"]]
    (['main+', 'main-'], [126.87, -126.87])
    """
    doc = analysis.to_dict()
    doc["speed_rpm"] = analysis.spin_speed * _RPM
    doc["critical_speed_rpm"] = analysis.critical_speed * _RPM
    doc["stable"] = {m: list(analysis.stable(m)) for m in _METHODS}
    for row in doc["motions"]:
        row["ball_angles_deg"] = None if row["ball_angles"] is None else _deg(row["ball_angles"])
        row["phase_deg"] = None if row["phase"] is None else _deg(row["phase"])[0]
    return doc


def chart_intervals(ds: xarray.Dataset) -> dict[str, list[dict[str, Any]]]:
    """Return the stable speed intervals of a chart by method, with the speeds also in rpm.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.steady.stability_chart`.

    Returns
    -------
    dict of str to list of dict
        ``{"exact": [...], "hamilton": [...], "averaged": [...]}``, rows of
        :func:`rotorlab.steady.stable_intervals` plus ``start_rpm`` and ``stop_rpm``.
    """
    from rotorlab.steady import stable_intervals

    out = {}
    for method in _METHODS:
        rows = stable_intervals(ds, method)
        for r in rows:
            r["start_rpm"] = r["start"] * _RPM
            r["stop_rpm"] = r["stop"] * _RPM
        out[method] = rows
    return out


def _steady_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    rows = []
    for j, label in enumerate(ds.motion.values):
        exists = bool(ds.exists.values[j])
        rows.append({
            "motion": str(label), "kind": str(ds.kind.values[j]), "exists": exists,
            "ball_angles_deg": _deg(ds.ball_angle.values[j]) if exists else None,
            "amplitude": _num(ds.amplitude.values[j]) if exists else None,
            "phase_deg": _deg(ds.phase.values[j])[0] if exists else None,
            "h_tilde": _num(ds.h_tilde.values[j]) if exists else None,
            **{f"verdict_{m}": str(ds[f"verdict_{m}"].values[j]) for m in _METHODS},
            "growth_rate": _num(ds.growth_rate.values[j]),
            "disagreement": bool(ds.disagreement.values[j]),
        })  # fmt: skip
    return rows


def _verify_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    rows = []
    outcomes = [str(o) for o in ds.outcome.values]
    for k in range(ds.sizes["speed"]):
        frac = ds.fraction.values[k]
        stable = {m: [str(lab) for lab, s in zip(ds.motion.values, ds[f"stable_{m}"].values[k]) if s]
                  for m in _METHODS}  # fmt: skip
        rows.append({
            "speed": float(ds.speed.values[k]), "speed_rpm": float(ds.speed_rpm.values[k]),
            "speed_ratio": float(ds.speed_ratio.values[k]), "starts": int(ds.sizes["ic"]),
            "t_end": float(ds.t_end.values[k]),
            "fractions": {o: float(f) for o, f in zip(outcomes, frac) if f > 0},
            "stable": stable,
            **{f"agrees_{m}": bool(ds[f"agrees_{m}"].values[k]) for m in _METHODS},
        })  # fmt: skip
    return rows


def _run_up_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    from rotorlab.analyses._run_up_verdicts import run_up_ensemble

    verdicts = "outcome" in ds
    ensemble = (run_up_ensemble([str(o) for o in ds.outcome.values], ds.critical_peak.values,
                                ds.attrs["critical_speeds"]) if verdicts else None)
    rows = []
    for i in range(ds.sizes["ic"]):
        rows.append({
            "ic": i, "initial_ball_angles_deg": _deg(ds.initial_ball_angle.values[i]),
            "max_amplitude": _num(ds.max_amplitude.values[i]),
            "max_amplitude_without": _num(ds.max_amplitude_without.values),
            "speed_at_max_rpm": _num(ds.speed_at_max.values[i] * _RPM),
            "speed_at_max_without_rpm": _num(ds.speed_at_max_without.values * _RPM),
            "final_amplitude": _num(ds.final_amplitude.values[i]),
            "final_amplitude_without": _num(ds.final_amplitude_without.values),
            "synchronised": bool(ds.synchronised.values[i]), "final_motion": str(ds.final_motion.values[i]),
            "final_speed_rpm": float(ds.attrs["final_speed"]) * _RPM,
        })  # fmt: skip
        if verdicts:
            rows[-1].update(outcome=str(ds.outcome.values[i]), settle_estimate_s=_num(ds.settle_estimate.values[i]),
                            critical_peaks=[_num(v) for v in ds.critical_peak.values[i]],
                            critical_peak_underread=[_num(v) for v in ds.critical_peak_underread.values[i]],
                            peak_saves_note=ds.attrs["peak_saves_note"] or None, ensemble=ensemble)
    return rows


def steady_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate the result of a steady-motion analysis (plain Python values, JSON-ready).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_steady_analysis` (``attrs["analysis"]`` names the type).

    Returns
    -------
    list of dict
        ``steady``: one row per motion (``motion``, ``kind``, ``exists``, ``ball_angles_deg``,
        ``amplitude`` (m), ``phase_deg``, ``h_tilde`` (J), ``verdict_exact`` /
        ``verdict_hamilton`` / ``verdict_averaged``, ``growth_rate`` (1/s), ``disagreement``).
        ``stability-chart``: one row per stable interval (``method`` plus the keys of
        :func:`chart_intervals`). ``verify``: one row per speed (``speed`` (rad/s),
        ``speed_rpm``, ``speed_ratio``, ``starts``, ``t_end`` (s), ``fractions`` by outcome,
        ``stable`` labels by method, ``agrees_<method>``). ``run-up``: one row per start
        (amplitudes in m, speeds in rpm, ``synchronised``, ``final_motion``).
    """
    kind = ds.attrs.get("analysis")
    if kind not in _ROWS:
        raise ValueError(f"not the result of a steady-motion analysis: attrs['analysis'] = {kind!r}")
    return _ROWS[kind](ds)


def _chart_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    return [{"method": m, **r} for m, rows in chart_intervals(ds).items() for r in rows]


_ROWS: dict[str, Callable[[xarray.Dataset], list[dict[str, Any]]]] = {
    "steady": _steady_rows, "stability-chart": _chart_rows, "verify": _verify_rows, "run-up": _run_up_rows}
