"""Figures of the machine analyses (model ``machine``): stability over speed, vibration over time
(``simulate``) and speed and vibration over time (``run-up``).

What a machine's figure draws, as an engineer reads it:

- the **named stations** only (a disc's, a bearing's or a body's name; a finite-element node
  without a name is not one), or, with no name at all, the station that vibrates most;
- the vibration **about the rest position** (under gravity the structure sags on its supports:
  the distance from the undeflected axis would show the sag, not the vibration);
- the **gap** of a clearance as a labelled line, and the clearance station's distance from the
  stator's centre where that is not its rest position;
- **critical speeds** as labelled lines;
- a **legend** for every curve and line.

Built with the Agg canvas (no pyplot state), like the other figures of :mod:`rotorlab.plot`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S as _RPM

__all__ = ["machine_figures", "shown_stations", "run_up_figure_machine", "simulate_figure_machine"]

_STYLES = ("-", "--", ":", "-.")


def shown_stations(ds: Any, size: Any) -> list[int]:
    """Indices of the stations a figure or table shows.

    Parameters
    ----------
    ds : xarray.Dataset
        A machine result with a ``station`` coordinate (node labels: a name, or the node's index
        as text for a node without one).
    size : array_like, shape (n_station,)
        How much each station vibrates (chooses the station shown when none has a name).

    Returns
    -------
    list of int
        The named stations and the clearance station (``attrs["clearance_station"]``), in node
        order; with none of them, the station of the largest ``size``.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(coords={"station": ["0", "disc", "2", "B"]})
    >>> shown_stations(ds, [0.0, 1.0, 3.0, 0.5])
    [1, 3]
    >>> shown_stations(xr.Dataset(coords={"station": ["0", "1", "2"]}), [0.0, 3.0, 1.0])
    [1]
    """
    labels = [str(s) for s in ds.station.values]
    gap_at = ds.attrs.get("clearance_station")
    named = [k for k, s in enumerate(labels) if s != str(k) or s == gap_at]
    if named:
        return named
    size = np.nan_to_num(np.asarray(size, dtype=float).reshape(-1), nan=-1.0)
    return [int(np.argmax(size))]


def _vibration(ds: Any) -> tuple[np.ndarray, str]:
    """The distance plotted (m; about the rest position where gravity moves it) and its axis label."""
    if "displacement_from_rest" in ds:
        return np.asarray(ds.displacement_from_rest.values, float), "distance from the rest position (mm)"
    name = "displacement" if "displacement" in ds else "amplitude"
    return np.asarray(ds[name].values, float), "distance from the axis (mm)"


def _gap(ax: Any, ds: Any, k_of: dict[str, int], disp: np.ndarray) -> float:
    """Draw the gap (and the clearance station's distance from the stator's centre where the
    centre is not its rest position); return the gap in mm (0 without a clearance)."""
    gap = ds.attrs.get("gap")
    if gap is None or "clearance_distance" not in ds:
        return 0.0
    at = str(ds.attrs.get("clearance_station"))
    ax.axhline(gap * 1e3, color="r", lw=1.2, label=f"gap at {at}: {gap * 1e3:.3g} mm")
    dist = np.asarray(ds.clearance_distance.values, float) * 1e3
    k = k_of.get(at)
    if k is None or not np.allclose(dist, disp[..., k] * 1e3, rtol=1e-6, atol=1e-6):
        t = np.asarray(ds.time.values, float)
        for curve in dist.reshape(-1, t.size):
            ax.plot(t, curve, color="r", lw=0.7, ls=":", label=f"{at}: from the stator's centre")
    return gap * 1e3


def _legend_beside(ax: Any) -> None:
    ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)


def simulate_figure_machine(ds: Any, name: str, plt: Any) -> Any:
    """Each shown station's vibration over time (log scale), one colour per start and one line
    style per station, and black the same without balancing (the locked unbalance response, as
    in the table); the start ending with the largest vibration is drawn first."""
    n_ic = ds.sizes["ic"]
    t = np.asarray(ds.time.values, dtype=float)
    disp, ylabel = _vibration(ds)
    amp = np.asarray(ds.amplitude.values, dtype=float)
    shown = shown_stations(ds, amp.max(axis=0))
    labels = [str(s) for s in ds.station.values]
    fig, ax = plt.subplots(figsize=(7.5, 3.8))
    order = np.argsort(-amp.max(axis=1), kind="stable")
    one = len(shown) == 1
    for rank, i in enumerate(order):
        for j, k in enumerate(shown):
            who = f"start {i}: {ds.outcome.values[i]}" if one else f"{labels[k]}, start {i}: {ds.outcome.values[i]}"
            ax.plot(t, disp[i, :, k] * 1e3, color=f"C{i % 10}", lw=0.8, ls=_STYLES[j % 4], zorder=2 + rank,
                    label=who if n_ic * len(shown) <= 12 or j == 0 else None)
    for j, k in enumerate(shown):
        ref = float(ds.reference_amplitude.values[k]) * 1e3
        if ref > 0:
            ax.axhline(ref, color="k", lw=0.8, ls=_STYLES[j % 4], alpha=0.6,
                       label="without balancing" + ("" if one else f" at {labels[k]}"))
    gap = _gap(ax, ds, {labels[k]: k for k in shown}, disp)
    ax.set_yscale("log")
    # (mm) from the smallest distance after the start (at rest: 0) up, seven decades at most
    later = disp[:, 1:, shown] * 1e3
    top = max(float(later.max(initial=0.0)), float(ds.reference_amplitude.values[shown].max()) * 1e3, gap)
    low = float(later[later > 0].min(initial=top))
    if top > 0:
        ax.set_ylim(max(0.5 * low, 1e-7 * top), 2.0 * top)
    ax.set_xlabel("time (s)")
    ax.set_ylabel(ylabel)
    where = f" at {labels[shown[0]]}" if one else ""
    ax.set_title(f"{name}: vibration{where}", fontsize=10)
    ax.grid(alpha=0.3)
    _legend_beside(ax)
    return fig


def _critical_lines(ax: Any, speeds: Any) -> None:
    """The critical speeds as dashed red lines, each labelled with its speed (rpm)."""
    for n, w in enumerate(speeds, start=1):
        rpm = float(w) * _RPM
        ax.axhline(rpm, color="r", lw=0.7, ls="--")
        ax.annotate(f"critical speed {n}: {rpm:.4g} rpm", (0.99, rpm), xycoords=("axes fraction", "data"),
                    xytext=(0, 2), textcoords="offset points", fontsize=7, color="r", va="bottom", ha="right")


def run_up_figure_machine(ds: Any, name: str, plt: Any) -> Any:
    """A run-up: speed (with the critical speeds labelled) and the shown stations' vibration about
    the rest position (with the gap) over time, one colour per start."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 5.4), sharex=True)
    t = np.asarray(ds.time.values, float)
    disp, ylabel = _vibration(ds)
    n_ic = ds.sizes.get("ic", 1)
    disp = disp.reshape(n_ic, t.size, -1)
    speed = np.asarray(ds.speed.values, float).reshape(n_ic, t.size)
    residual = np.asarray(ds.residual_amplitude.values, dtype=float).reshape(n_ic, -1)
    outcome = np.asarray(ds.outcome.values).reshape(n_ic) if "outcome" in ds else [""] * n_ic
    shown = shown_stations(ds, residual.max(axis=0))
    labels = [str(s) for s in ds.station.values]
    # the start that ends with the largest vibration is drawn first, so that a balanced start's
    # thin band is not hidden under an unbalanced one's (same colour per start in both panels)
    order = np.argsort(-residual.max(axis=1), kind="stable")
    for rank, i in enumerate(order):
        colour = f"C{i % 10}"
        a1.plot(t, speed[i] * _RPM, color=colour, label=f"start {i}")
        for j, k in enumerate(shown):
            a2.plot(t, disp[i, :, k] * 1e3, color=colour, ls=_STYLES[j % 4], zorder=2 + rank, lw=0.8,
                    label=f"{labels[k]}, start {i}: {outcome[i]}")
    _critical_lines(a1, ds.attrs.get("critical_speeds", []))
    _gap(a2, ds, {labels[k]: k for k in shown}, disp)
    a1.set_ylabel("speed (rpm)")
    a1.set_title(f"{name}: speed and vibration over the run-up", fontsize=10)
    a2.set_ylabel(ylabel)
    a2.set_xlabel("time (s)")
    a1.set_ylim(bottom=0.0)
    a2.set_ylim(bottom=0.0)
    for a in (a1, a2):
        a.grid(alpha=0.3)
    if n_ic > 1:
        _legend_beside(a1)
    _legend_beside(a2)
    return fig


def _stability_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    """A stability chart: stable region over speed x parameter, or max Re(lambda) over speed."""
    if not bool(ds.exists.any()):
        return {}
    if "parameter" in ds.dims:
        from matplotlib.patches import Patch

        fig, ax = plt.subplots(figsize=(6.5, 3.5))
        st = np.where(ds.exists.values, ds.stable.values.astype(float), np.nan)
        ax.pcolormesh(ds.speed.values * _RPM, ds.parameter.values, st, shading="nearest", cmap="RdYlGn",
                      vmin=0, vmax=1)
        ax.set_xlabel("spin speed (rpm)")
        ax.set_ylabel(f"{ds.attrs['parameter']} ({ds.parameter.attrs.get('units', '')})")
        ax.set_title(f"{name}: where the balanced state is stable", fontsize=10)
        from matplotlib import colormaps

        cmap = colormaps["RdYlGn"]
        ax.legend(handles=[Patch(color=cmap(1.0), label="stable"), Patch(color=cmap(0.0), label="unstable")],
                  fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
        return {f"{name}-stability": fig}
    if ds.sizes["speed"] > 1:
        fig, ax = plt.subplots(figsize=(6.5, 3.5))
        ax.plot(ds.speed.values * _RPM, ds.max_real_eigenvalue.values, ".-", label="largest real part")
        ax.axhline(0.0, color="k", lw=0.8, label="stability limit")
        ax.set_xlabel("spin speed (rpm)")
        ax.set_ylabel("max Re(lambda) (1/s)")
        ax.set_title(f"{name}: balanced state stable below the line", fontsize=10)
        ax.legend(fontsize="small")
        return {f"{name}-stability": fig}
    return {}


def _simulate_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    """A simulation with its time history: vibration over time."""
    return {f"{name}-vibration": simulate_figure_machine(ds, name, plt)} if "displacement" in ds else {}


def _run_up_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    return {f"{name}-run-up": run_up_figure_machine(ds, name, plt)}


# The machine presentation's figures, by the analysis that made the Dataset (ds.attrs["analysis"]);
# an analysis without an entry has no figure.
_FIGURES = {"stability-chart": _stability_figures, "simulate": _simulate_figures, "run-up": _run_up_figures}


def machine_figures(ds: Any, name: str) -> dict[str, Any]:
    """Stability over speed (steady), vibration over time (simulate with its time history) or
    speed and vibration over time (run-up); none otherwise."""
    draw = _FIGURES.get(ds.attrs["analysis"])
    return {} if draw is None else draw(ds, name, _Figures)


class _Figures:
    """``subplots`` as pyplot's, without pyplot's global figure registry (constrained layout)."""

    @staticmethod
    def subplots(*args: Any, figsize: tuple[float, float], **kwargs: Any) -> tuple[Any, Any]:
        from matplotlib.figure import Figure

        fig = Figure(figsize=figsize, layout="constrained")
        return fig, fig.subplots(*args, **kwargs)
