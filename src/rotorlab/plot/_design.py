"""Figures of a design search: the evaluated designs over the varied parameters (the winner marked,
infeasible designs crossed), the best objective against the evaluations, and, with two
objectives, the trade-off (every feasible design and the Pareto front). No pyplot: Agg-free
``Figure`` objects."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["design_figure", "tradeoff_figure", "design_figures", "best_so_far"]


def best_so_far(ds: xarray.Dataset, k: int = 0) -> np.ndarray:
    """The least value of objective ``k`` among the feasible designs up to each evaluation (NaN
    before the first feasible one)."""
    obj = np.asarray(ds["objective_value"].values[:, k], dtype=float)
    ok = np.asarray(ds["feasible"].values, dtype=bool)
    return np.fmin.accumulate(np.where(ok, obj, np.nan))


def _label(ds: xarray.Dataset, key: str, name: str) -> str:
    unit = json.loads(ds.attrs.get(key, "{}")).get(name, "")
    return f"{name} ({unit})" if unit and unit != "1" else name


def design_figure(ds: xarray.Dataset) -> Figure:
    """Left: the designs in the plane of the first two varied parameters (one parameter: against
    the first objective), coloured by the first objective, infeasible ones crossed, the winner a
    star. Right: the best feasible objective against the evaluations."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax, conv = fig.subplots(1, 2)
    names = [str(v) for v in ds["variable"].values]
    x = np.asarray(ds["value"].values, dtype=float)
    obj = np.asarray(ds["objective_value"].values[:, 0], dtype=float)
    ok = np.asarray(ds["feasible"].values, dtype=bool)
    best = int(ds.attrs["best"])
    first = str(ds["objective"].values[0])
    y = x[:, 1] if len(names) > 1 else obj
    finite = np.isfinite(obj)
    if (ok & finite).any():
        sc = ax.scatter(x[ok & finite, 0], y[ok & finite], c=obj[ok & finite], cmap="viridis", s=28,
                        label="feasible")  # fmt: skip
        fig.colorbar(sc, ax=ax, label=_label(ds, "objective_units", first))
    if (~ok).any():
        ax.scatter(x[~ok, 0], y[~ok], marker="x", color="tab:red", s=24, label="infeasible")
    if best >= 0:
        ax.scatter([x[best, 0]], [y[best]], marker="*", s=220, color="gold", edgecolor="black", zorder=5,
                   label="winner")  # fmt: skip
    bounds = json.loads(ds.attrs.get("bounds", "{}"))
    ax.set_xlim(*bounds.get(names[0], ax.get_xlim()))
    if len(names) > 1:
        ax.set_ylim(*bounds.get(names[1], ax.get_ylim()))
    ax.set_xlabel(_label(ds, "units", names[0]))
    ax.set_ylabel(_label(ds, "units", names[1]) if len(names) > 1 else _label(ds, "objective_units", first))
    from matplotlib.ticker import MaxNLocator

    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.legend(loc="best", fontsize=8)
    ax.set_title(f"{ds.sizes['trial']} designs ({ds.attrs['optimizer']})", fontsize=10)
    conv.plot(np.arange(1, ds.sizes["trial"] + 1), best_so_far(ds), drawstyle="steps-post", color="tab:blue")
    conv.scatter(np.arange(1, ds.sizes["trial"] + 1)[ok], obj[ok], s=10, color="tab:blue", alpha=0.4, label="feasible")
    conv.scatter(np.arange(1, ds.sizes["trial"] + 1)[~ok], obj[~ok], s=14, marker="x", color="tab:red",
                 label="infeasible")  # fmt: skip
    conv.legend(loc="best", fontsize=8)
    conv.set_xlabel("evaluation")
    conv.set_ylabel(f"best feasible {_label(ds, 'objective_units', first)}")
    conv.set_title("best so far", fontsize=10)
    return fig


def tradeoff_figure(ds: xarray.Dataset) -> Figure:
    """The two objectives of every feasible design, the Pareto front joined, the winner a star."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.6), layout="constrained")
    ax = fig.subplots()
    a, b = (str(o) for o in ds["objective"].values[:2])
    obj = np.asarray(ds["objective_value"].values, dtype=float)
    ok = np.asarray(ds["feasible"].values, dtype=bool)
    front = np.asarray(ds["pareto"].values, dtype=bool)
    ax.scatter(obj[ok & ~front, 0], obj[ok & ~front, 1], s=18, color="0.6", label="feasible")
    if (~ok).any():
        keep = ~ok & np.isfinite(obj).all(axis=1)
        ax.scatter(obj[keep, 0], obj[keep, 1], marker="x", s=18, color="tab:red", label="infeasible")
    order = np.argsort(obj[front, 0])
    ax.plot(obj[front, 0][order], obj[front, 1][order], "o-", color="tab:blue", label="Pareto front")
    best = int(ds.attrs["best"])
    if best >= 0:
        ax.scatter([obj[best, 0]], [obj[best, 1]], marker="*", s=220, color="gold", edgecolor="black", zorder=5,
                   label="recommended")  # fmt: skip
    ax.set_xlabel(_label(ds, "objective_units", a))
    ax.set_ylabel(_label(ds, "objective_units", b))
    ax.legend(loc="best", fontsize=8)
    ax.set_title("trade-off", fontsize=10)
    return fig


def design_figures(ds: xarray.Dataset, name: str) -> dict[str, Any]:
    """The figures of one design result, by file stem (the trade-off only with two objectives, the
    sensitivity bars of the winner only where they were computed)."""
    out = {f"{name}_design": design_figure(ds)}
    if ds.sizes["objective"] > 1:
        out[f"{name}_tradeoff"] = tradeoff_figure(ds)
    from rotorlab.analyses._design_case import sensitivity_view

    view = sensitivity_view(ds)
    if view is not None:  # the winner's Sobol indices: the tolerances bars
        from rotorlab.plot._tolerances import sensitivity_figure

        out[f"{name}_sensitivity"] = sensitivity_figure(view)
    return out
