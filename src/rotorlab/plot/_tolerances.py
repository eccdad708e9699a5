"""Figures of a tolerances result: the Sobol indices of each output as bars with their bootstrap
intervals, and the Monte-Carlo envelope of the vibration over time (no pyplot: ``Figure``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["sensitivity_figure", "envelope_figure", "tolerances_figures", "OUTPUT_TITLES"]

#: How each output is named on a figure.
OUTPUT_TITLES = {"p_balanced": "P(balanced)", "residual_vibration": "residual vibration",
                 "transient_peak": "transient peak"}  # fmt: skip


def sensitivity_figure(ds: xarray.Dataset) -> Figure:
    """One panel per output: first-order (S1) and total-order (ST) Sobol index of every input, each
    with its bootstrap interval; an output that did not vary says so instead."""
    from matplotlib.figure import Figure

    outputs = [str(o) for o in ds["output"].values]
    inputs = [str(i) for i in ds["input"].values]
    fig = Figure(figsize=(7.5, 1.2 + 0.28 * len(inputs) * len(outputs)), layout="constrained")
    axes = np.atleast_1d(fig.subplots(len(outputs), 1, sharex=True))
    y = np.arange(len(inputs))
    conf = 100.0 * float(ds.attrs.get("confidence", 0.95))
    for k, (ax, out) in enumerate(zip(axes, outputs)):
        s1, st = np.asarray(ds["S1"].values[k]), np.asarray(ds["ST"].values[k])
        c1, ct = np.asarray(ds["S1_conf"].values[k]), np.asarray(ds["ST_conf"].values[k])
        title = OUTPUT_TITLES.get(out, out)
        if not np.any(np.isfinite(st)):
            ax.text(0.5, 0.5, f"{title}: the same for every sample (no variance to share out)",
                    transform=ax.transAxes, ha="center", va="center", fontsize="small")  # fmt: skip
        else:
            ax.barh(y - 0.2, st, 0.4, xerr=ct, label="total order ST", color="C0", capsize=2)
            ax.barh(y + 0.2, s1, 0.4, xerr=c1, label="first order S1", color="C1", capsize=2)
        ax.set_yticks(y, inputs, fontsize="x-small")
        ax.invert_yaxis()
        ax.axvline(0.0, color="0.4", lw=0.6)
        ax.set_title(title, fontsize="small", loc="left")
        ax.grid(axis="x", alpha=0.3)
    if any(ax.containers for ax in axes):
        next(ax for ax in axes if ax.containers).legend(fontsize="x-small", loc="lower right")
    axes[-1].set_xlabel(f"Sobol index (-); bars: bootstrap {conf:g} % intervals")
    axes[-1].set_xlim(-0.1, 1.1)
    fig.suptitle(f"{ds.attrs.get('name', 'tolerances')}: {int(ds.sizes['sample'])} machines x "
                 f"{int(ds.attrs.get('starts', 1))} starts (N = {int(ds.attrs['n_base'])})", fontsize="medium")  # fmt: skip
    return fig


def envelope_figure(ds: xarray.Dataset) -> Figure:
    """The vibration amplitude over time: median and 5-95 % band over the Monte-Carlo samples (the
    design's A and B machines, every start), with the unbalance response (balls locked) for scale."""
    from matplotlib.figure import Figure

    t = np.asarray(ds["horizon"].values, dtype=float)
    env = 1e6 * np.asarray(ds["envelope"].values, dtype=float)
    q = [float(v) for v in ds["quantile"].values]
    fig = Figure(figsize=(7.0, 4.2), layout="constrained")
    ax = fig.subplots()
    ax.fill_between(t, env[0], env[-1], color="C0", alpha=0.25, lw=0,
                    label=f"{100 * q[0]:g}-{100 * q[-1]:g} % of the machines and starts")  # fmt: skip
    ax.plot(t, env[len(q) // 2], color="C0", label="median")
    ref = 1e6 * float(np.nanmedian(ds["unbalance_response"].values))
    ax.axhline(ref, color="C3", ls="--", lw=1, label=f"unbalance response, balls locked (median {ref:.3g} µm)")
    ax.axhline(0.05 * ref, color="C2", ls=":", lw=1, label="balanced below (5 % of it)")
    ax.set_yscale("log")
    ax.set_xlabel("time (s); amplitude over each window ending there")
    ax.set_ylabel("largest vibration amplitude (µm)")
    ax.set_title(f"{ds.attrs.get('name', 'tolerances')}: Monte-Carlo envelope of the vibration", fontsize="medium")
    ax.legend(fontsize="x-small")
    ax.grid(alpha=0.3, which="both")
    return fig


def tolerances_figures(ds: xarray.Dataset, name: str) -> dict[str, Any]:
    """The figures of one tolerances result, by file stem."""
    return {f"{name}_sensitivity": sensitivity_figure(ds), f"{name}_envelope": envelope_figure(ds)}
