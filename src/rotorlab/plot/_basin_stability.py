"""Figure of a basin-stability result: the probability of every regime against the parameter, with
its Wilson interval as a band (no pyplot: an Agg-free ``Figure``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["basin_stability_figure", "basin_stability_figures", "param_display"]

#: How a parameter is shown: SI unit -> (factor, unit shown).
_SHOWN = {"rad/s": (60.0 / (2.0 * np.pi), "rpm"), "rad": (180.0 / np.pi, "deg")}


def param_display(ds: xarray.Dataset) -> tuple[np.ndarray, str]:
    """The parameter values as shown (rad/s in rpm, rad in deg) and the axis label."""
    name = ds.attrs["param"]
    units = str(ds.attrs.get("param_units", ""))
    factor, shown = _SHOWN.get(units, (1.0, units))
    return np.asarray(ds[name].values, dtype=float) * factor, f"{name} ({shown})" if shown and shown != "1" else name


def basin_stability_figure(ds: xarray.Dataset, title: str | None = None) -> Figure:
    """P(each regime) against the parameter, a band for each Wilson interval; regimes never seen
    are left out (named in the legend title)."""
    from matplotlib.figure import Figure

    x, xlabel = param_display(ds)
    labels = [str(r) for r in ds["regime"].values]
    p = np.asarray(ds["probability"].values)
    lo, hi = np.asarray(ds["ci_low"].values), np.asarray(ds["ci_high"].values)
    fig = Figure(figsize=(7.0, 4.4), layout="constrained")
    ax = fig.subplots()
    seen = [k for k in range(len(labels)) if np.any(p[:, k] > 0)]
    for k in seen:
        (line,) = ax.plot(x, 100.0 * p[:, k], marker="o", ms=3, ls="--" if labels[k] == "not settled" else "-",
                          label=labels[k])
        ax.fill_between(x, 100.0 * lo[:, k], 100.0 * hi[:, k], color=line.get_color(), alpha=0.2, lw=0)
    conf = float(ds.attrs.get("confidence", 0.95))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"starts (%); bands: Wilson {100.0 * conf:g} % intervals")
    ax.set_ylim(-2.0, 102.0)
    n = np.asarray(ds["n"].values)
    starts = f"{n.min()}" if n.min() == n.max() else f"{n.min()} to {n.max()}"
    ax.set_title(title or f"{ds.attrs.get('name', 'basin stability')}: {starts} random starts per value, "
                          f"{float(ds.horizon[-1]):.3g} s each", fontsize="medium")  # fmt: skip
    ax.legend(fontsize="small", title="never seen: " + ", ".join(labels[k] for k in range(len(labels)) if k not in seen)
              if len(seen) < len(labels) else None, title_fontsize="x-small")  # fmt: skip
    ax.grid(alpha=0.3)
    return fig


def basin_stability_figures(ds: xarray.Dataset, name: str) -> dict[str, Any]:
    """The figures of one basin-stability result, by file stem."""
    return {f"{name}_basin_stability": basin_stability_figure(ds)}
