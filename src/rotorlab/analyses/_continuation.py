"""The ``continuation`` analysis of a case: branches of steady motions in a named parameter (and
fold / Hopf curves in a second one over today's grid stability chart), on a ``machine`` or a
``jeffcott_balls`` model (:func:`rotorlab.continuation.continue_equilibria`).
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

__all__ = ["run_continuation_analysis", "continuation_rows", "continuation_machine", "CHART_SPEEDS", "CHART_VALUES"]

#: Grid of today's stability chart drawn under the two-parameter curves: speeds x values.
CHART_SPEEDS, CHART_VALUES = 41, 13


def continuation_machine(case_model, analysis):
    """The machine a case's continuation starts from: the case's model as a machine
    (:func:`rotorlab.continuation.as_machine`) at the analysis' ``speed`` or the model's constant
    speed, or at ``range[0]`` when the speed is the continued parameter.

    Raises
    ------
    ValueError
        A parameter the machine does not have, or the speed is not continued and neither the
        analysis nor the model gives a constant speed > 0.
    """
    from rotorlab.analyses._case import build_model
    from rotorlab.continuation import as_machine, parameter_unit, with_value
    from rotorlab.models import ConstantSpeed

    from rotorlab.analyses._continuation_periodic import PERIODIC_STARTS, orbit_model

    if analysis.start_from in PERIODIC_STARTS:
        orbit_model(case_model, analysis)  # periodic orbits: a smooth jeffcott_balls rotor in drive.speed
    model = build_model(case_model)
    profile = getattr(model, "speed", None)  # a rotor with its own speed profile (jeffcott_balls)
    if profile is not None and not isinstance(profile, ConstantSpeed):
        from dataclasses import replace

        model = replace(model, speed=ConstantSpeed(1.0))  # replaced below: a steady motion needs one
    machine = as_machine(model)
    for name in (analysis.param, analysis.param2):
        if name is not None:
            parameter_unit(machine, name)  # a name the machine does not have: ValueError naming it
    if analysis.param == "drive.speed":
        return with_value(machine, "drive.speed", analysis.range[0])
    speed = analysis.speed
    if speed is None:
        profile = case_model.speed_profile()
        constant = profile is not None and getattr(profile, "is_constant", True)
        speed = getattr(profile, "final_speed", None) if constant else None
    if speed is None or not speed > 0:
        raise ValueError(f"continuation of {analysis.param}: give the speed (speed = \"1500 rpm\", --speed-rpm); "
                         "the model has no constant speed > 0 of its own")
    return with_value(machine, "drive.speed", float(speed))


def run_continuation_analysis(case_model, analysis, progress=None):
    """Run one ``continuation`` entry; the Dataset of :meth:`ContinuationResult.to_dataset` plus,
    with ``param2`` over the speed, today's grid chart (``chart_stable``, ``chart_exists`` over
    ``chart_value`` x ``chart_speed``: :func:`rotorlab.analyses.machine_steady`; for support_anisotropy
    the balanced state's Floquet exponent), and the JSON of
    the result in ``attrs["result"]``."""
    from rotorlab.continuation import continue_equilibria, smooth_part_note

    from rotorlab.analyses._case import build_model
    from rotorlab.analyses._continuation_periodic import PERIODIC_STARTS, periodic_branches

    machine = continuation_machine(case_model, analysis)
    total = 2 if analysis.param2 is not None else 1
    periodic = analysis.start_from in PERIODIC_STARTS
    result = started = None
    if analysis.start_from != "simulation":
        result = continue_equilibria(machine, analysis.param, *analysis.range,
                                     start_from="all" if periodic else analysis.start_from, switch=analysis.switch,
                                     parameter2=analysis.param2, range2=analysis.range2)
    if periodic:
        from dataclasses import replace

        from rotorlab.continuation import ContinuationResult

        orbits, started = periodic_branches(case_model, analysis, result, machine.basis)
        result = replace(result, branches=result.branches + tuple(orbits)) if result is not None else \
            ContinuationResult(tuple(orbits), units={analysis.param: "rad/s"})
    note = smooth_part_note(build_model(case_model))  # ball friction: the smooth part was continued
    if note and note not in result.notes:
        from dataclasses import replace

        result = replace(result, notes=result.notes + (note,))
    if progress is not None:
        progress(1, total)
    ds = result.to_dataset()
    if analysis.param2 is not None and analysis.param == "drive.speed":
        speeds = np.linspace(*sorted(analysis.range), CHART_SPEEDS)
        values = np.linspace(*sorted(analysis.range2), CHART_VALUES)
        stable, exists = _CHARTS.get(analysis.param2, _steady_chart)(machine, analysis.param2, speeds, values)
        ds["chart_stable"] = (("chart_value", "chart_speed"), stable, {"units": "1"})
        ds["chart_exists"] = (("chart_value", "chart_speed"), exists, {"units": "1"})
        ds = ds.assign_coords(chart_value=("chart_value", values, {"units": result.units[analysis.param2]}),
                              chart_speed=("chart_speed", speeds, {"units": "rad/s"}))
    if progress is not None:
        progress(total, total)
    ds.attrs.update(name=analysis.name, parameter=analysis.param, start_from=analysis.start_from,
                    result=json.dumps({**result.to_dict(), **({"periodic_start": started} if started else {})}))
    return ds


def _steady_chart(machine, param2, speeds, values):
    """Today's grid chart (:func:`rotorlab.analyses.machine_steady`): (stable, exists) per value x speed."""
    from rotorlab.analyses._machine_steady import machine_steady
    from rotorlab.continuation import with_value

    stable = np.zeros((values.size, speeds.size), bool)
    exists = np.zeros_like(stable)
    for k, v in enumerate(values):
        chart = machine_steady(with_value(machine, param2, float(v)), speeds)
        stable[k], exists[k] = chart.stable.values, chart.exists.values
    return stable, exists


def _anisotropy_chart(machine, param2, speeds, values):
    from rotorlab.continuation._anisotropic import anisotropy_chart

    return anisotropy_chart(machine, speeds, values)


#: Grid charts under the curves that are not today's steady-motion chart: param2 -> function.
_CHARTS = {"support_anisotropy": _anisotropy_chart}


def continuation_rows(ds) -> list[dict[str, Any]]:
    """One row per special point (branch, type, parameter value SI, sentence; frequency of a Hopf
    point), then one per branch with its range and stability."""
    doc = json.loads(ds.attrs["result"])
    param = ds.attrs["parameter"]
    rows = []
    for b in doc["branches"]:
        for s in b["special_points"]:
            rows.append({"branch": b["label"], "type": s["type"], "parameter": param, "value": s[param],
                         **({"frequency_rad_s": s["frequency_rad_s"]} if "frequency_rad_s" in s else {}),
                         "description": s["description"]})
    for b in doc["branches"]:
        v = [p[param] for p in b["points"] if p[param] is not None]
        stable = [p["stable"] for p in b["points"]]
        row = {"branch": b["label"], "type": "branch-summary", "parameter": param, "kind": b["kind"],
               "from": min(v) if v else math.nan, "to": max(v) if v else math.nan, "points": len(v),
               "stable_points": int(sum(stable)), "end": b["end"]}
        if b["kind"] == "periodic":
            from rotorlab.analyses._continuation_periodic import orbit_sentence

            per = [p["period_s"] for p in b["points"] if p["period_s"] is not None]
            row.update(period_from_s=min(per, default=math.nan), period_to_s=max(per, default=math.nan),
                       sentence=orbit_sentence(b, doc["units"].get(param, "")), started=doc.get("periodic_start", ""))
        rows.append(row)
    return rows
