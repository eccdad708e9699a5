"""Figure of a rotor in its clearance (``rub`` analysis): the orbit of the last window over the
clearance circle, with the closed-form orbit of the measured regime dashed. Built without pyplot."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["rub_orbit_figure", "rub_figures", "rub_map_figure", "rub_map_figures"]


def rub_orbit_figure(ds: xarray.Dataset) -> Figure:
    """Orbit of the rotor centre over the window, in units of the clearance."""
    from matplotlib.figure import Figure

    from rotorlab.analyses._rub import _closed_form_for

    d = float(ds.attrs["clearance"])
    fig = Figure(figsize=(5.6, 6.2), layout="constrained")
    ax = fig.subplots()
    th = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(np.cos(th), np.sin(th), color="0.3", lw=1.5, label="clearance")
    ax.plot(ds.x.values / d, ds.y.values / d, color="tab:blue", lw=0.8, label=f"simulated: {ds.attrs['regime_label']}")
    radius, _, _, source = _closed_form_for(ds)
    if radius is not None:
        ax.plot(radius / d * np.cos(th), radius / d * np.sin(th), "--", color="tab:red", lw=1.0,
                label=f"closed form ({source})")  # fmt: skip
    ax.set_aspect("equal")
    ax.set_xlabel("x / clearance")
    ax.set_ylabel("y / clearance")
    fig.legend(loc="outside lower center", fontsize="small", frameon=False)  # below: the orbit fills the axes
    ax.set_title(f"{ds.attrs.get('name', 'rub')}: spin {ds.attrs['spin_speed']:.4g} rad/s")
    return fig


def rub_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``rub`` result, by file stem."""
    return {f"{name}_orbit": rub_orbit_figure(ds)}


def rub_map_figure(ds: xarray.Dataset) -> Figure:
    """Regimes over spin speed x the second axis, with the closed-form grazing boundary."""
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    from rotorlab.contact import RubRegime

    axis = ds.attrs["second_axis"]
    codes = [int(r) for r in RubRegime]
    colours = ["0.25", "0.92", "tab:orange", "tab:red", "tab:purple", "tab:brown"]
    cmap = ListedColormap(colours)
    norm = BoundaryNorm([c - 0.5 for c in codes] + [codes[-1] + 0.5], cmap.N)
    fig = Figure(figsize=(6.4, 4.8), layout="constrained")
    ax = fig.subplots()
    x, y = ds.spin_speed.values, ds[axis].values
    ax.pcolormesh(x, y, ds.regime.values.T.astype(float), cmap=cmap, norm=norm, shading="nearest")
    if "grazing_curve" in ds:  # the closed-form line on a fine grid, not joined between map speeds
        ax.plot(ds.curve_speed.values, ds.grazing_curve.values, "k--", lw=1.2)
    else:
        ax.plot(x, ds.grazing_boundary.values, "k--", lw=1.2)
    ax.set_ylim(y.min() - 0.5 * (np.ptp(y) / max(len(y) - 1, 1)), y.max() + 0.5 * (np.ptp(y) / max(len(y) - 1, 1)))
    ax.set_xlabel("spin speed (rad/s)")
    unit = ds[axis].attrs.get("units", "")
    ax.set_ylabel(f"{axis} ({unit})" if unit else axis)
    present = sorted({int(v) for v in np.unique(ds.regime.values)})
    handles = [Patch(color=colours[codes.index(c)], label=RubRegime(c).label) for c in present]
    from matplotlib.lines import Line2D

    handles.append(Line2D([], [], color="k", ls="--", label="no-rub orbit reaches the clearance (closed form)"))
    fig.legend(handles=handles, loc="outside lower center", ncols=2, fontsize="small")
    ax.set_title(f"{ds.attrs.get('name', 'rub-map')}: rub regimes")
    return fig


def rub_map_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``rub-map`` result, by file stem."""
    return {f"{name}_map": rub_map_figure(ds)}
