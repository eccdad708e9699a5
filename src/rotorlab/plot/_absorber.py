"""Figure of a tuned mass absorber's effect: a station's unbalance-response amplitude over spin
speed with and without the machine's absorbers (:func:`rotorlab.models.absorber_response`).
Built without pyplot."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["absorber_response_figure"]


def absorber_response_figure(ds: xarray.Dataset) -> Figure:
    """Amplitude (mm) over speed (rpm) with and without the absorbers, log scale."""
    from matplotlib.figure import Figure

    rpm = ds.speed.values * 30.0 / np.pi
    fig = Figure(figsize=(6.4, 4.4), layout="constrained")
    ax = fig.subplots()
    ax.semilogy(rpm, ds.amplitude_without.values * 1e3, color="0.4", lw=1.2, label="without absorber")
    ax.semilogy(rpm, ds.amplitude.values * 1e3, color="tab:blue", lw=1.5,
                label=f"with {ds.attrs['absorbers']} absorber(s)")
    ax.set_xlabel("spin speed (rpm)")
    ax.set_ylabel(f"amplitude at node {ds.attrs['node']} (mm)")
    ax.legend(frameon=False)
    ax.set_title("unbalance response, balls locked (linear)")
    return fig
