"""Figures of the rotor striking its housing (seed 001, Figs. 3, 4, 5 and the impact table).

Datasets from :func:`rotorlab.analyses.impact_run` and :func:`rotorlab.analyses.impact_sweep`.
Built without pyplot (Agg canvas), like the other figures of :mod:`rotorlab.plot`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["p_trajectory_figure", "impact_sweep_figure", "impact_figures"]

_REGIME_COLORS = {"none": "0.75", "rebounds": "tab:blue", "sliding": "tab:orange", "backward_whirl": "tab:red"}


def p_trajectory_figure(ds: xarray.Dataset) -> Figure:
    """Trajectory of the gap point P in the rotating frame, in units of the gap (seed Figs. 3, 4).

    The circle of radius 1 is the housing: P touches it at an impact; sliding stretches are
    drawn in orange.

    Examples
    --------
    >>> from rotorlab.analyses import impact_run
    >>> from rotorlab.models import krasnov_crusher
    >>> fig = p_trajectory_figure(impact_run(krasnov_crusher(), t_end=0.3, n_save=100))
    >>> fig.axes[0].get_xlabel()
    'w_x / gap'
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(5.6, 5.6), layout="constrained")
    ax = fig.subplots()
    x, y = ds.p_x.values, ds.p_y.values
    ok = np.isfinite(x)
    ax.plot(x[ok], y[ok], lw=0.5, color="tab:blue")
    sliding = ok & (ds["mode"].values == 1.0)
    if sliding.any():
        ax.plot(np.where(sliding, x, np.nan), np.where(sliding, y, np.nan), lw=1.5, color="tab:orange",
                label="sliding")  # fmt: skip
        ax.legend(loc="lower right")
    th = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(np.cos(th), np.sin(th), color="k", lw=1.2)
    ax.plot([0.0], [0.0], "k+")
    ax.set_aspect("equal")
    ax.set_xlim(-1.1, 1.1)
    ax.set_ylim(-1.1, 1.1)
    ax.set_xlabel("w_x / gap")
    ax.set_ylabel("w_y / gap")
    a = ds.attrs
    ax.set_title(f"P in the rotating frame, {a.get('stone_mass', float('nan')):g} kg stones, "
                 f"{float(ds.t_final):.3g} s\n{a.get('regime', '')}: {int(ds.impacts)} impacts, "
                 f"sliding {float(ds.sliding_time):.3g} s", fontsize=9)  # fmt: skip
    return fig


def impact_sweep_figure(ds: xarray.Dataset) -> Figure:
    """Impacts (median and quartiles over sequences), regimes and eta against the swept parameter.

    Examples
    --------
    >>> from rotorlab.analyses import impact_sweep
    >>> from rotorlab.models import krasnov_crusher
    >>> fig = impact_sweep_figure(impact_sweep(krasnov_crusher(), [0.5, 1.0], n_sequences=2, t_end=0.5))
    >>> len(fig.axes)
    3
    """
    from matplotlib.figure import Figure

    from rotorlab.analyses import REGIMES

    v = ds.value.values
    label = f"{ds.attrs.get('param', 'value')}" + (f" ({ds.attrs['param_units']})" if ds.attrs.get("param_units", "1") != "1" else "")
    fig = Figure(figsize=(7.0, 8.0), layout="constrained")
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True, height_ratios=[3, 1.2, 2.2])
    med, lo, hi = ds.impacts_median.values, ds.impacts_q25.values, ds.impacts_q75.values
    ax1.fill_between(v, np.maximum(lo, 0.5), np.maximum(hi, 0.5), color="tab:blue", alpha=0.25, lw=0,
                     label="quartiles")  # fmt: skip
    ax1.plot(v, np.maximum(med, 0.5), "o-", color="tab:blue", label="median")
    ax1.set_yscale("log")
    ax1.set_ylabel(f"impacts in {ds.attrs.get('t_end', 0):g} s")
    ax1.legend(loc="upper left", fontsize=8)
    ax1.set_title(f"{ds.sizes['sequence']} random stone sequences per value", fontsize=9)
    bottom = np.zeros(v.size)
    width = 0.8 * (np.min(np.diff(v)) if v.size > 1 else 1.0)
    for c, lab in enumerate(REGIMES):
        frac = ds.regime_fraction.values[:, c]
        ax2.bar(v, frac, width, bottom=bottom, color=_REGIME_COLORS[lab], label=lab)
        bottom += frac
    ax2.set_ylim(0, 1)
    ax2.set_ylabel("regimes")
    ax2.legend(loc="upper left", fontsize=7, ncol=4)
    eta = ds.eta_median.values
    ax3.fill_between(v, ds.eta_q25.values, ds.eta_q75.values, color="tab:red", alpha=0.2, lw=0)
    ax3.plot(v, eta, "s-", color="tab:red")
    ax3.axhline(1.0, color="k", lw=0.6, ls="--")
    ax3.set_ylabel("eta = E_friction / E_stones")
    ax3.set_xlabel(label)
    return fig


def impact_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one impact result, by file stem (``<name>_p_trajectory`` or ``<name>_sweep``)."""
    if ds.attrs.get("analysis") == "impacts":
        return {f"{name}_p_trajectory": p_trajectory_figure(ds)}
    if ds.attrs.get("analysis") == "impacts-sweep":
        return {f"{name}_sweep": impact_sweep_figure(ds)}
    return {}
