"""Figure of a rotor in its clearance (``rub`` analysis): the orbit of the last window over the
clearance circle, with the closed-form orbit of the measured regime dashed. Built without pyplot."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["rub_orbit_figure", "rub_figures"]


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
