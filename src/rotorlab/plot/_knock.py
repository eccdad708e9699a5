"""The figure of a ``machine-knock`` result: contact probability and largest impulse against ball
damping. Built without pyplot."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["knock_figure"]


def knock_figure(ds: xarray.Dataset) -> Figure:
    """Contact probability (95 % interval) and the largest impulse against ball damping."""
    from matplotlib.figure import Figure

    d = ds.ball_damping.values
    fig = Figure(figsize=(6.4, 5.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    p = ds.contact_probability.values
    err = np.vstack([p - ds.probability_low.values, ds.probability_high.values - p])
    ax1.errorbar(d, 100.0 * p, yerr=100.0 * err, fmt="o-", capsize=3, color="tab:red")
    ax1.set_ylabel("runs that touch the housing (%)")
    ax1.set_ylim(-2.0, 102.0)
    ax1.set_title(f"{ds.attrs.get('name', 'knock')}: {ds.attrs['starts']} random ball starts, "
                  f"{ds.attrs['gap'] * 1e3:.3g} mm clearance")
    ax2.plot(d, ds.largest_impulse.values, "s-", color="tab:blue", label="with balls: largest of all starts")
    nb = ds.attrs.get("no_balls_peak_impulse")
    if nb is not None and np.isfinite(nb):
        ax2.axhline(nb, color="0.4", ls="--", label="without balls")
    ax2.set_ylabel("largest impact impulse (N s)")
    ax2.set_xlabel("ball damping (N m s/rad)")
    if np.all(d > 0) and d.size > 1 and d.max() / d.min() > 20:
        ax2.set_xscale("log")
    ax2.legend(fontsize="small")
    return fig
