"""Run a case's ``design`` analysis and say what it found: the problem built from the case, the
summary rows (one per evaluated design), the recommendation in one sentence, its margins, the
winner's independent check, and the verdict line.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab import _people as people

if TYPE_CHECKING:
    import xarray

__all__ = ["design_problem", "run_design_analysis", "design_rows", "design_document", "design_task_size",
           "recommendation", "design_evidence", "check_agrees", "winner_model", "with_sensitivity",
           "sensitivity_view", "sensitivity_sentence"]  # fmt: skip


def design_problem(case_model: Any, spec: Any, *, t_end: float | None = None) -> Any:
    """The :class:`~rotorlab.analyses._design.DesignProblem` of a case's ``design`` analysis.

    With a run-up objective, limit or constraint (:attr:`rotorlab.io.DesignSpec.reads_run_ups`)
    the problem holds the machine as built (its servo drive), no regime mapper, the run-ups'
    settings (``starts``, ``seed``) and, with balls, ``run-up-unbalanced <= 1 - min_balanced``;
    otherwise the regime mapper of the basin-stability sweep.

    Raises
    ------
    ValueError
        The problem's issues (``vary.<name>: ...``: unknown name, bounds outside the
        parameter's range, a structural name), or a model without a regime mapper.
    """
    from rotorlab.analyses._design import DesignProblem, DesignVariable
    from rotorlab.design import RunUpSettings

    name, a, b, n = spec.param_axis
    variables = tuple(DesignVariable(k, float(v[0]), float(v[1])) for k, v in spec.vary.items())
    if spec.reads_run_ups:
        from rotorlab.analyses._case import build_model

        model = build_model(case_model)
        limits = dict(spec.limits)
        if spec.min_balanced is not None and getattr(model, "n_balls", 0) and "run-up-unbalanced" not in limits:
            limits["run-up-unbalanced"] = 1.0 - float(spec.min_balanced)
        return DesignProblem(
            model, variables, tuple(spec.objectives), np.linspace(a, b, n), name, None, limits, None, {},
            spec.design_starts, spec.seed, spec.confidence, constraints=tuple(spec.constraints),
            run_up=RunUpSettings(starts=spec.design_starts, seed=spec.seed))  # fmt: skip
    from rotorlab.analyses._basin import basin_mapper

    mapper = basin_mapper(case_model, spec, t_end=t_end)
    return DesignProblem(
        mapper.model, variables, tuple(spec.objectives), np.linspace(a, b, n), name, spec.min_balanced,
        dict(spec.limits), mapper, spec.start_ranges(case_model), spec.design_starts, spec.seed, spec.confidence,
        horizon_given=t_end is not None or spec.t_end is not None, chunk=spec.chunk,
        constraints=tuple(spec.constraints))  # fmt: skip


def run_design_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None, *,
                        t_end: float | None = None, store: Any = None, resume: bool = False,
                        executor: Any = None) -> xarray.Dataset:  # fmt: skip
    """Run one ``design`` analysis of a case (:func:`rotorlab.analyses.design_search`); attrs
    ``analysis``, ``name``, ``model`` added."""
    from rotorlab.analyses._design import design_search
    from rotorlab.analyses._tolerances import run_tolerances_analysis

    problem = design_problem(case_model, analysis, t_end=t_end)
    ds = design_search(problem, optimizer=analysis.optimizer, budget=analysis.budget,
                       optimizer_seed=analysis.optimizer_seed, store=store, resume=resume, executor=executor,
                       verify=analysis.verify, progress=progress)  # fmt: skip
    ds.attrs.update(analysis="design", name=analysis.name, model=str(case_model.type))
    tolerances = analysis.sensitivity_spec(case_model) if hasattr(analysis, "sensitivity_spec") else None
    if tolerances is not None and int(ds.attrs["best"]) >= 0:
        winner = winner_model(problem, ds)
        path = None if store is None else Path(store) / "sensitivity.zarr"
        sens = run_tolerances_analysis(case_model, tolerances, store=path, executor=executor, machine=winner,
                                       resume=resume and path is not None and path.exists())  # fmt: skip
        ds = with_sensitivity(ds, sens)
    return ds


def winner_model(problem: Any, ds: xarray.Dataset) -> Any:
    """The base model with the winning design's named parameters set
    (:meth:`~rotorlab.analyses._design.DesignProblem.model_at`)."""
    best = int(ds.attrs["best"])
    values = {str(n): float(ds["value"].values[best, k]) for k, n in enumerate(ds["variable"].values)}
    return problem.model_at(values)


#: The attrs of a tolerances result a design keeps (prefixed ``sensitivity_``).
_SENSITIVITY_ATTRS = ("n_base", "seed", "confidence", "resamples", "starts", "speed", "t_end", "failed",
                      "distributions")  # fmt: skip


def with_sensitivity(ds: xarray.Dataset, sens: xarray.Dataset) -> xarray.Dataset:
    """The design's dataset with the winner's Sobol indices (``S1``, ``S1_conf``, ``ST``,
    ``ST_conf``: dims ``output``, ``input``; ``sensitivity_mean``, ``sensitivity_variance``:
    ``output``) and the tolerances run's attrs (``sensitivity_<attr>``, ``sensitivity_machines``)."""
    out = ds.assign_coords(output=sens["output"], input=sens["input"])
    for key in ("S1", "S1_conf", "ST", "ST_conf"):
        out[key] = sens[key]
    out["sensitivity_mean"] = sens["mean"]
    out["sensitivity_variance"] = sens["variance"]
    attrs = {f"sensitivity_{k}": sens.attrs[k] for k in _SENSITIVITY_ATTRS}
    attrs["sensitivity_distributions"] = json.dumps(list(attrs["sensitivity_distributions"]))
    out.attrs.update(attrs, sensitivity_machines=int(sens.sizes["sample"]))
    return out


def sensitivity_view(ds: xarray.Dataset) -> xarray.Dataset | None:
    """The winner's indices as a tolerances result (what :func:`rotorlab.plot._tolerances.sensitivity_figure`
    and :func:`rotorlab.analyses._tolerances.most_sensitive` read); None: not computed."""
    import xarray as xr

    if "ST" not in ds:
        return None
    attrs = {k.removeprefix("sensitivity_"): v for k, v in ds.attrs.items() if k.startswith("sensitivity_")}
    attrs["name"] = f"{ds.attrs.get('name', 'design')} (recommended design)"
    view = xr.Dataset({k: ds[k] for k in ("S1", "S1_conf", "ST", "ST_conf")}, attrs=attrs)
    return view.assign_coords(sample=("sample", np.arange(int(attrs["machines"]))))


def sensitivity_sentence(ds: xarray.Dataset) -> str | None:
    """"P(balanced) of the recommended design is most sensitive to X (ST a ± b)", or why no input
    stands out; None: not computed."""
    from rotorlab.analyses._tolerances import most_sensitive

    view = sensitivity_view(ds)
    if view is None:
        return None
    top = most_sensitive(view, "p_balanced")
    machines = f"{int(view.attrs['machines'])} machines x {int(view.attrs['starts'])} starts"
    if top is None:
        return (f"P(balanced) of the recommended design was the same for every sampled machine ({machines}): "
                "no input's tolerance moves it.")  # fmt: skip
    name, st, half = top
    return (f"P(balanced) of the recommended design is most sensitive to {name} (ST {people.number(st, 2)} ± "
            f"{people.number(half, 2)}; {machines}).")


def design_task_size(case_model: Any, analysis: Any) -> int:
    """The designs a ``design`` analysis evaluates (its progress total)."""
    return int(analysis.budget)


def _unit(ds: Any, key: str, name: str) -> str:
    return str(json.loads(ds.attrs.get(key, "{}")).get(name, ""))


def design_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """One row per evaluated design: ``trial``, ``values`` (name -> SI), ``objectives`` (name ->
    SI), ``margins`` (constraint -> margin, >= 0 holds), ``balanced_low`` (the least Wilson
    lower bound of P(balanced) over the operating range, None without starts), ``feasible``,
    ``pareto``, ``best``."""
    best = int(ds.attrs["best"])
    rows = []
    for i in range(ds.sizes["trial"]):
        low = np.asarray(ds["balanced_low"].values[i], dtype=float)
        rows.append({
            "trial": i,
            "values": {str(v): float(ds["value"].values[i, k]) for k, v in enumerate(ds["variable"].values)},
            "objectives": {str(o): float(ds["objective_value"].values[i, k])
                           for k, o in enumerate(ds["objective"].values)},
            "margins": {str(c): float(ds["margin"].values[i, k]) for k, c in enumerate(ds["constraint"].values)},
            "balanced_low": float(np.min(low)) if np.isfinite(low).all() and low.size else None,
            "feasible": bool(ds["feasible"].values[i]), "pareto": bool(ds["pareto"].values[i]), "best": i == best,
        })  # fmt: skip
    return rows


def check_agrees(ds: xarray.Dataset) -> bool | None:
    """Whether the winner's P(balanced) from fresh starts lies within the search's Wilson
    interval at every operating value (None: no check was run)."""
    best = int(ds.attrs["best"])
    check = np.asarray(ds["verify_balanced"].values, dtype=float)
    if best < 0 or not np.isfinite(check).all():
        return None
    lo, hi = ds["balanced_low"].values[best], ds["balanced_high"].values[best]
    return bool(np.all((check >= lo) & (check <= hi)))


def _value_text(ds: Any, name: str, value: float) -> str:
    return people.quantity(value, _unit(ds, "units", name))


def recommendation(ds: xarray.Dataset) -> str:
    """The recommendation in one sentence (or why there is none)."""
    best = int(ds.attrs["best"])
    names = [str(v) for v in ds["variable"].values]
    if best < 0:
        return (f"No design of the {ds.sizes['trial']} evaluated met every constraint: widen the bounds of "
                f"{', '.join(names)}, relax a limit, or raise the budget.")  # fmt: skip
    values = ", ".join(f"{n} = {_value_text(ds, n, float(ds['value'].values[best, k]))}" for k, n in enumerate(names))
    objs = ", ".join(f"{o} {people.quantity(float(v), _unit(ds, 'objective_units', o))}"
                     for o, v in zip(ds["objective"].values, ds["objective_value"].values[best]))  # fmt: skip
    text = f"Build {values}: {objs}"
    low = ds["balanced_low"].values[best]
    if np.isfinite(low).all():
        text += (f", P(balanced) >= {people.number(float(np.min(low)), 3)} over the operating range "
                 f"({float(ds.attrs['confidence']) * 100:g} % lower bound, {int(ds.attrs['starts'])} starts per speed)")
    return text + "."


def design_document(ds: xarray.Dataset) -> dict[str, Any]:
    """A design result as JSON-ready data (``rotorlab design --json``)."""
    best = int(ds.attrs["best"])
    dim = str(ds.attrs["operating"])

    def floats(values):
        return [None if not math.isfinite(float(v)) else float(v) for v in np.asarray(values).reshape(-1)]

    return {
        "recommendation": recommendation(ds), "best": best, "optimizer": ds.attrs["optimizer"],
        "budget": int(ds.attrs["budget"]), "evaluations": int(ds.attrs["evaluations"]), "seed": int(ds.attrs["seed"]),
        "verify_seed": int(ds.attrs["verify_seed"]), "starts": int(ds.attrs["starts"]),
        "operating": {"param": dim, "values": floats(ds[dim].values)},
        "winner": design_rows(ds)[best] if best >= 0 else None,
        "search_interval": {"low": floats(ds["balanced_low"].values[best]),
                            "high": floats(ds["balanced_high"].values[best])} if best >= 0 else None,
        "check": {"balanced": floats(ds["verify_balanced"].values), "low": floats(ds["verify_low"].values),
                  "high": floats(ds["verify_high"].values), "objectives": floats(ds["verify_objective"].values),
                  "inside_search_interval": check_agrees(ds)},
        "cpu_s": float(ds.attrs["cpu_s"]), "rows": design_rows(ds),
        "sensitivity": None if "ST" not in ds else {
            "sentence": sensitivity_sentence(ds), "inputs": [str(v) for v in ds["input"].values],
            "outputs": [str(v) for v in ds["output"].values],
            **{k: [floats(row) for row in ds[k].values] for k in ("S1", "S1_conf", "ST", "ST_conf")}},
    }  # fmt: skip


def design_evidence(ds: Any, rows: Any, facts: Any) -> list[Any]:
    """The verdict line of a design search: the recommendation (yes), or none feasible (no), or a
    winner whose independent check fell outside the search's interval (not settled)."""
    from rotorlab.analyses._page_verdict import VerdictLine

    best = int(ds.attrs["best"])
    name = ds.attrs.get("name", "")
    if best < 0:
        return [VerdictLine("design", "no", recommendation(ds) + f" ({name})",
                            "widen the bounds or relax min_balanced / limits")]  # fmt: skip
    agrees = check_agrees(ds)
    if agrees is False:
        return [VerdictLine("design", "not-settled", recommendation(ds)[:-1] + "; but the winner re-simulated from "
                            f"fresh starts falls outside the search's interval ({name})",
                            "raise starts (the search's intervals are too optimistic for its winner)")]  # fmt: skip
    tail = "; confirmed from fresh random starts" if agrees else ""
    sens = sensitivity_sentence(ds)
    tail += f"; {sens[:-1]}" if sens else "; its sensitivity not computed"
    return [VerdictLine("design", "yes", recommendation(ds)[:-1] + f"{tail} ({name}).")]
