"""Run the linear analyses of a case (Campbell, modes, critical speeds, unbalance response,
identification, data audit) and tabulate their results.

Every result is an :class:`xarray.Dataset` whose ``attrs["analysis"]`` is the analysis type;
:func:`summarize_linear` turns it into plain rows for tables and JSON, and
:func:`campbell_summary` / :func:`modes_summary` give the documented ``--json`` documents of
``rotorlab campbell`` and ``rotorlab modes``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.io._linear_build import build_linear_system
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

__all__ = [
    "LINEAR_ANALYSES",
    "DATA_AUDITS",
    "run_linear_analysis",
    "run_linear_case_analysis",
    "summarize_linear",
    "critical_entry",
    "critical_summary",
    "campbell_summary",
    "modes_summary",
]

#: Analysis types computed by :func:`run_linear_analysis`.
LINEAR_ANALYSES = ("campbell", "modes", "critical_speeds", "unbalance_response", "identify",
                   "data_audit")

_WHIRL = {1: "F", -1: "B", 0: "M"}


def _audit_pico21() -> Any:
    from rotorlab.linear.cases import audit_pico21

    return audit_pico21()


#: Data sets the ``data_audit`` analysis can audit: name to a function returning findings
#: (objects with ``key``, ``printed``, ``resolved``, ``evidence``, ``measure``).
DATA_AUDITS: Mapping[str, Callable[[], Any]] = {"pico21": _audit_pico21}


def _labels(ds: xarray.Dataset, spec: Any, dim: str, nodes: Any) -> xarray.Dataset:
    labels = np.array(spec.node_labels(), dtype=object)[np.asarray(nodes, dtype=int)]
    return ds.assign_coords(node_label=(dim, labels.astype(str), {"units": "1"}))


def _campbell(spec: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab.linear import campbell

    return campbell(build_linear_system(spec), list(analysis.speeds()),
                    n_modes=analysis.n_modes, harmonics=analysis.harmonics)


def _modes(spec: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab.linear import modal

    modes = modal(build_linear_system(spec), analysis.speed, n_modes=analysis.n_modes)
    ds = modes.to_dataset()
    ds = _labels(ds, spec, "dof", ds.node.values)
    ds["speed_rpm"] = ((), analysis.speed * _RPM, {"units": "rev/min"})
    return ds


def _critical_speeds(spec: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab.linear import critical_speeds

    cs = critical_speeds(build_linear_system(spec), harmonics=analysis.harmonics,
                         max_speed=analysis.max_speed)
    ds = cs.to_dataset()
    ds["critical_frequency"] = ("critical", cs.harmonic * cs.speed / (2.0 * math.pi),
                                {"units": "Hz", "long_name": "natural frequency = h x speed"})
    ds.attrs["harmonics"] = list(analysis.harmonics)
    return ds


def _output_nodes(spec: Any, analysis: Any) -> list[int]:
    names = spec.component_nodes()
    if analysis.outputs:
        return [names[n] for n in analysis.outputs]
    labels = spec.node_labels()
    named = [i for i, lab in enumerate(labels) if lab != str(i)]
    return named or list(range(len(labels)))


def _unbalance_response(spec: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab.linear import unbalance_response

    unbalances = [u.unbalance(spec.locate(u.node, u.at, u.position)[0]) for u in analysis.unbalances]
    ds = unbalance_response(build_linear_system(spec), list(analysis.speeds()), unbalances)
    ds = _labels(ds, spec, "node_index", ds.node_index.values)
    ds.attrs["output_nodes"] = _output_nodes(spec, analysis)
    return ds


def _identify(spec: Any, analysis: Any) -> xarray.Dataset:
    from rotorlab.linear import FrequencyMeasurement, identify_parameters

    base = analysis.fit_model(spec)
    paths = analysis.paths()
    initial = [base.value_at(p)[0] for p in paths]

    def build(values: np.ndarray) -> Any:
        return build_linear_system(base.with_values(dict(zip(paths, values))))

    meas = [FrequencyMeasurement(m.speed, m.mode, m.frequency, m.weight)
            for m in analysis.measurements]
    result = identify_parameters(build, initial, meas, names=analysis.parameters)
    ds = result.to_dataset()
    units = [base.unit_at(p) for p in paths]
    ds["unit"] = ("parameter", np.array(units, dtype=str))
    ds["value"].attrs["units"] = ds["initial"].attrs["units"] = "see unit"
    ds = ds.assign_coords(
        measurement_speed=("measurement", [m.speed for m in meas], {"units": "rad/s"}),
        measurement_speed_rpm=("measurement", [m.speed * _RPM for m in meas],
                               {"units": "rev/min"}),
        measurement_mode=("measurement", [m.mode for m in meas], {"units": "1"}),
    )
    return ds


def _data_audit(spec: Any, analysis: Any) -> xarray.Dataset:
    import xarray as xr

    findings = DATA_AUDITS[analysis.data]()
    text = {k: np.array([str(getattr(f, k)) for f in findings], dtype=str)
            for k in ("printed", "resolved", "evidence")}
    return xr.Dataset(
        {**{k: ("finding", v) for k, v in text.items()},
         "measure": ("finding", np.array([f.measure for f in findings], dtype=float),
                     {"units": "1", "long_name": "size of the discrepancy (see evidence)"})},
        coords={"finding": ("finding", np.array([f.key for f in findings], dtype=str))},
        attrs={"title": f"audit of the printed data of {analysis.data}", "data": analysis.data},
    )


_RUNNERS = {
    "campbell": _campbell,
    "modes": _modes,
    "critical_speeds": _critical_speeds,
    "unbalance_response": _unbalance_response,
    "identify": _identify,
    "data_audit": _data_audit,
}


#: Linear analyses that run on the linear structure of any model that has one (a machine's).
_STRUCTURAL = ("campbell", "modes", "critical_speeds", "unbalance_response")


def run_linear_analysis(case_model: Any, analysis: Any) -> xarray.Dataset:
    """Run one linear analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.MultibodySpec or rotorlab.io.FeRotorSpec
        ``Case.model``; or a model with a linear structure (``machine``), whose structure the
        campbell, modes, critical_speeds and unbalance_response analyses run on.
    analysis : CampbellSpec, ModesSpec, CriticalSpeedsSpec, UnbalanceResponseSpec, IdentifySpec
        or DataAuditSpec
        One entry of ``Case.analyses``.

    Returns
    -------
    xarray.Dataset
        From :func:`rotorlab.linear.campbell`, :meth:`rotorlab.linear.Modes.to_dataset`,
        :meth:`rotorlab.linear.CriticalSpeeds.to_dataset`,
        :func:`rotorlab.linear.unbalance_response` or
        :meth:`rotorlab.linear.Identification.to_dataset`, with node labels added; or the
        findings of a data audit (dim ``finding``). ``attrs["analysis"]`` is the analysis
        type and ``attrs["model"]`` the model type; ``attrs["mesh"]`` says how an ``fe_rotor``
        mesh was refined, when it was.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> case = load_case("friswell-rotor")
    >>> ds = run_linear_analysis(case.model, case.analysis("modes-at-rest"))
    >>> ds.frequency.values.round(2).tolist()
    [13.79, 13.79, 43.66, 43.66, 114.08, 114.08]
    """
    runner = _RUNNERS.get(analysis.type)
    if runner is None:
        raise ValueError(f"analysis type {analysis.type!r} is not a linear analysis "
                         f"(linear: {', '.join(LINEAR_ANALYSES)})")
    structure = case_model.linear_structure()
    if structure is not None and analysis.type in _STRUCTURAL:
        case_model = structure  # a machine's linear analyses are those of its structure
    if analysis.type != "data_audit":
        build_linear_system(case_model)  # a clear error for a model that is not linear
    ds = runner(case_model, analysis)
    ds.attrs["analysis"] = analysis.type
    ds.attrs["model"] = case_model.type
    note = getattr(case_model, "mesh_note", lambda: "")()
    if note:
        ds.attrs["mesh"] = note  # the nodes added so that discs and bearings sit on nodes
    return ds


def run_linear_case_analysis(case_model: Any, analysis: Any,
                             progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """:func:`run_linear_analysis` with progress (0 of 1, then 1 of 1) and ``attrs["name"]``."""
    if progress is not None:
        progress(0, 1)
    ds = run_linear_analysis(case_model, analysis)
    ds.attrs["name"] = analysis.name
    if progress is not None:
        progress(1, 1)
    return ds


def _num(value: Any, digits: int | None = None) -> float | None:
    v = float(value) + 0.0  # no negative zero
    if not math.isfinite(v):
        return None
    return v if digits is None else round(v, digits)


def _grid(value: Any) -> float | None:
    """A grid speed in rpm, to 12 significant digits (3000, not 2999.9999999999995)."""
    v = _num(value)
    return None if v is None else float(f"{v:.12g}")


#: Damped and undamped critical speeds differing by more than this share are both shown.
DIFFERENCE_SHOWN = 0.03


def _crossing_rows(ds: xarray.Dataset, mode: bool) -> list[dict[str, Any]]:
    """One row per critical speed: those unbalance excites first, then the others, each by speed.

    A Campbell diagram's crossings are damped crossings (the undamped speed of the same mode
    beside them); a ``critical_speeds`` result's are undamped (the damped crossing beside them).
    """
    from rotorlab.linear import DEFINITIONS, NOT_EXCITED_NOTE

    rows = []
    harmonic = ds["critical_harmonic" if mode else "harmonic"].values
    isotropic = bool(ds.attrs.get("isotropic", 0))
    definition = "damped crossing" if mode else "undamped"
    n = ds.sizes.get("critical", 0)

    def var(name: str, default: float | bool) -> np.ndarray:  # results saved before issue 29
        return ds[name].values if name in ds else np.full(n, default)

    if mode:
        damped, undamped = ds.critical_speed_rpm.values, var("critical_undamped_rpm", np.nan)
        zeta, excited = var("critical_damping_ratio", np.nan), var("critical_excited_by_unbalance", True)
    else:
        damped, undamped = var("damped_crossing_rpm", np.nan), ds.critical_speed_rpm.values
        zeta, excited = var("damping_ratio", np.nan), var("excited_by_unbalance", True)
    for k in range(n):
        w = float(ds.critical_speed.values[k])
        h = int(harmonic[k])
        whirl = _WHIRL[int(ds["critical_whirl" if mode else "whirl"].values[k])]
        d, u = _num(damped[k]), _num(undamped[k])
        note = ""
        if not excited[k]:
            note = NOT_EXCITED_NOTE if h == 1 and isotropic else f"a {h}x line: not excited by unbalance"
        row = {"speed": w, "speed_rpm": w * _RPM, "definition": definition,
               "definition_text": DEFINITIONS[definition],
               "damped_crossing_rpm": d, "undamped_rpm": u, "damping_ratio": _num(zeta[k]),
               "both_shown": bool(d is not None and u is not None
                                  and abs(d - u) > DIFFERENCE_SHOWN * u),
               "frequency_hz": h * w / (2.0 * math.pi), "harmonic": h, "whirl": whirl,
               "excited_by_unbalance": bool(excited[k]), "note": note}
        if mode:
            row["mode"] = int(ds.critical_mode.values[k])
        rows.append(row)
    rows.sort(key=lambda r: (not r["excited_by_unbalance"], r["speed"]))
    return rows


def summarize_linear(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a linear result in plain rows (JSON-ready; non-finite numbers become None).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_linear_analysis`.

    Returns
    -------
    list of dict
        ``campbell``, ``critical_speeds``: one row per critical speed, those unbalance excites
        first (``speed`` in rad/s and ``speed_rpm``: the damped crossing for a Campbell diagram,
        the undamped critical speed for ``critical_speeds``, as ``definition`` says;
        ``damped_crossing_rpm``, ``undamped_rpm``, ``damping_ratio`` of the mode at the
        crossing, ``both_shown`` when they differ by more than 3 %, ``frequency_hz``,
        ``harmonic``, ``whirl`` "F"/"B"/"M", ``excited_by_unbalance``, ``note`` (e.g. "not
        excited by unbalance on isotropic supports"), and for a Campbell diagram the branch
        ``mode``). ``modes``: one row per mode (``mode``,
        ``frequency_hz``, ``whirl``, ``damping_ratio``, ``log_decrement``). ``unbalance_response``:
        one row per shown node (``node``, ``label``, ``peak_amplitude`` (m, largest semi-axis of
        the orbit, refined between grid speeds; None when undamped: unbounded),
        ``peak_speed_rpm``, ``note``: why there is no peak, or ""). ``identify``: one row per parameter (``parameter``,
        ``unit``, ``initial``, ``value``, ``relative_std``). ``data_audit``: one row per finding
        (``finding``, ``printed``, ``resolved``, ``evidence``, ``measure``).
    """
    kind = ds.attrs.get("analysis")
    if kind not in _ROWS:
        raise ValueError(f"not a linear result: attrs['analysis'] = {kind!r}")
    return _ROWS[kind](ds)


def _modes_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    return [{"mode": int(ds.mode.values[k]), "frequency_hz": _num(ds.frequency.values[k]),
             "whirl": _WHIRL[int(ds.whirl.values[k])], "damping_ratio": _num(ds.damping_ratio.values[k]),
             "log_decrement": _num(ds.log_decrement.values[k])}
            for k in range(ds.sizes["mode"])]  # fmt: skip


def _unbalance_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    return [{"node": int(node), "label": str(ds.node_label.values[node]),
             "peak_amplitude": _num(ds.peak_orbit.values[node]),
             "peak_speed_rpm": _num(ds.peak_speed.values[node] * _RPM),
             "note": str(ds.attrs.get("note", ""))}
            for node in ds.attrs.get("output_nodes", [])]


def _identify_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    return [{"parameter": str(ds.parameter.values[i]), "unit": str(ds.unit.values[i]),
             "initial": float(ds.initial.values[i]), "value": float(ds.value.values[i]),
             "relative_std": _num(ds.relative_std.values[i])}
            for i in range(ds.sizes["parameter"])]  # fmt: skip


def _audit_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    return [{"finding": str(ds.finding.values[i]), "printed": str(ds.printed.values[i]),
             "resolved": str(ds.resolved.values[i]), "evidence": str(ds.evidence.values[i]),
             "measure": _num(ds.measure.values[i])}
            for i in range(ds.sizes["finding"])]  # fmt: skip


_ROWS: Mapping[str, Callable[[xarray.Dataset], list[dict[str, Any]]]] = {
    "campbell": lambda ds: _crossing_rows(ds, mode=True),
    "critical_speeds": lambda ds: _crossing_rows(ds, mode=False),
    "modes": _modes_rows,
    "unbalance_response": _unbalance_rows,
    "identify": _identify_rows,
    "data_audit": _audit_rows,
}



def campbell_summary(ds: xarray.Dataset) -> dict[str, Any]:
    """Return the JSON document of ``rotorlab campbell --json``.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.linear.campbell`.

    Returns
    -------
    dict
        Exactly ``speed_rpm`` (list, 12 significant digits), ``frequency_hz`` (per speed, a list per mode),
        ``whirl`` (per speed, ``"F"``, ``"B"`` or ``"M"`` per mode) and
        ``critical_speeds_rpm`` (list, ascending: the damped crossings), then
        ``critical_speed_definition`` ("damped crossing") and ``critical_speeds``: one entry per
        crossing, those unbalance excites first (:func:`critical_entry`); non-finite numbers
        are None.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> case = load_case("friswell-rotor")
    >>> doc = campbell_summary(run_linear_analysis(case.model, case.analysis("campbell")))
    >>> sorted(doc), sorted(doc["whirl"][-1][:2])
    (['critical_speed_definition', 'critical_speeds', 'critical_speeds_rpm', 'frequency_hz', 'speed_rpm', 'whirl'], ['B', 'F'])
    >>> [round(f, 2) for f in doc["frequency_hz"][0]], len(doc["speed_rpm"])
    ([13.79, 13.79, 43.66, 43.66, 114.08, 114.08], 81)
    """
    freq = ds.frequency.values
    return {
        "speed_rpm": [_grid(v) for v in ds.speed_rpm.values],
        "frequency_hz": [[_num(v) for v in row] for row in freq],
        "whirl": [[_WHIRL[int(c)] for c in row] for row in ds.whirl.values],
        "critical_speeds_rpm": [_num(v) for v in ds.critical_speed_rpm.values],
        "critical_speed_definition": "damped crossing",
        "critical_speeds": [critical_entry(r) for r in _crossing_rows(ds, mode=True)],
    }


def critical_entry(row: Mapping[str, Any]) -> dict[str, Any]:
    """The JSON entry of one critical speed (keys with units) from a row of :func:`summarize_linear`.

    Examples
    --------
    >>> critical_entry({"definition": "undamped", "damped_crossing_rpm": 1030.0,
    ...                 "undamped_rpm": 1000.0, "damping_ratio": 0.1, "whirl": "B", "harmonic": 1,
    ...                 "excited_by_unbalance": False, "note": "n", "speed_rpm": 1000.0})["speed_rpm"]
    1000.0
    """
    return {"speed_rpm": row["speed_rpm"], "definition": row["definition"],
            "damped_crossing_rpm": row["damped_crossing_rpm"], "undamped_rpm": row["undamped_rpm"],
            "damping_ratio": row["damping_ratio"], "whirl": row["whirl"], "harmonic": row["harmonic"],
            "excited_by_unbalance": row["excited_by_unbalance"], "note": row["note"]}


def modes_summary(ds: xarray.Dataset) -> dict[str, Any]:
    """Return the JSON document of ``rotorlab modes --json``.

    Parameters
    ----------
    ds : xarray.Dataset
        From :meth:`rotorlab.linear.Modes.to_dataset` (with ``speed_rpm``).

    Returns
    -------
    dict
        ``speed_rpm`` (number), and per mode (lists): ``frequency_hz``, ``whirl`` ("F", "B",
        "M"), ``damping_ratio``, ``log_decrement``; non-finite numbers are None.
    """
    rows = summarize_linear(ds)
    return {
        "speed_rpm": _grid(ds.speed_rpm.values),
        "frequency_hz": [r["frequency_hz"] for r in rows],
        "whirl": [r["whirl"] for r in rows],
        "damping_ratio": [r["damping_ratio"] for r in rows],
        "log_decrement": [r["log_decrement"] for r in rows],
    }


def critical_summary(spec: Any, n: int = 6) -> dict[str, Any]:
    """The lowest ``n`` 1x critical speeds of a model's linear structure, for ``validate --json``.

    Parameters
    ----------
    spec : AbstractModelSpec
        A model whose ``linear_structure()`` is not None (else the result is empty).
    n : int
        How many, the lowest undamped ones.

    Returns
    -------
    dict
        ``{"critical_speeds": [...]}`` (entries of :func:`critical_entry`, undamped with their
        damped crossings, those unbalance excites first), or ``{}``.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> doc = critical_summary(load_case("friswell-rotor").model)
    >>> [(round(e["speed_rpm"]), e["whirl"], e["excited_by_unbalance"]) for e in doc["critical_speeds"][:4]]
    [(830, 'F', True), (2756, 'F', True), (8841, 'F', True), (825, 'B', False)]
    """
    structure = spec.linear_structure()
    if structure is None:
        return {}
    return {"critical_speeds": critical_entries(build_linear_system(structure), n)}


def critical_entries(system: Any, n: int = 6) -> list[dict[str, Any]]:
    """The lowest ``n`` undamped 1x critical speeds of a ``LinearSystem`` as entries of
    :func:`critical_entry` (each with its damped crossing), those unbalance excites first."""
    from rotorlab.linear import critical_speeds

    lowest = critical_speeds(system, damped=False).speed[:n]  # damped crossings of these only
    cs = critical_speeds(system, max_speed=float(lowest[-1]) if lowest.size else None)
    ds = cs.to_dataset().isel(critical=slice(0, n))
    ds["critical_frequency"] = ("critical", ds.harmonic.values * ds.critical_speed.values / (2.0 * math.pi))
    ds.attrs["analysis"] = "critical_speeds"
    return [critical_entry(r) for r in _crossing_rows(ds, mode=False)]

