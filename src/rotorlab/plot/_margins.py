"""Figures of the margin analyses: the minimal fatal shock against speed and direction
(``shock-margin``) and the friction band with its worst residual against speed
(``friction-margin``). Built without pyplot; people's units (rpm, N s, g mm, deg, um)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["shock_margin_figures", "friction_margin_figures"]


def shock_margin_figure(ds: xarray.Dataset) -> Figure:
    """Left: minimal fatal impulse (linearised estimate, simulated) and load shift against speed.
    Right: the impulse against direction at each speed (polar)."""
    from matplotlib.figure import Figure

    rpm = ds.speed.values * RPM_PER_RAD_S
    fig = Figure(figsize=(10.0, 4.6), layout="constrained")
    ax1 = fig.add_subplot(1, 2, 1)
    ax1.plot(rpm, ds.min_impulse_linear.values, "o-", color="tab:blue", label="impulse, linearised basin")
    if int(ds.attrs.get("simulated", 0)):
        ax1.plot(rpm, ds.min_impulse_simulated.values, "s--", color="tab:red", label="impulse, simulated")
    ax1.set_xlabel("speed (rpm)")
    ax1.set_ylabel("minimal fatal impulse (N s)")
    ax3 = ax1.twinx()
    ax3.plot(rpm, ds.min_load_shift.values * 1e6, "^:", color="tab:green", label="load shift")
    ax3.set_ylabel("minimal fatal load shift (g mm)")
    ax1.set_ylim(bottom=0.0)
    ax3.set_ylim(bottom=0.0)
    lines = ax1.get_lines() + ax3.get_lines()
    ax1.legend(lines, [ln.get_label() for ln in lines], loc="lower right", fontsize="small")
    unstable = [f"{v:.0f}" for v, ok in zip(rpm, ds.stable.values) if not ok]
    note = f"\n(balanced state not stable at {', '.join(unstable)} rpm: no margin)" if unstable else ""
    ax1.set_title(f"{ds.attrs.get('name', 'shock margin')}: worst direction per speed{note}", fontsize="medium")
    ax2 = fig.add_subplot(1, 2, 2, projection="polar")
    beta = np.append(ds.direction.values, ds.direction.values[:1])
    for i, om in enumerate(ds.speed.values):
        if not ds.stable.values[i]:
            continue
        line = ax2.plot(beta, np.append(ds.impulse_linear.values[i], ds.impulse_linear.values[i, :1]),
                        label=f"{om * RPM_PER_RAD_S:.0f} rpm")[0]
        if int(ds.attrs.get("simulated", 0)):
            sim = ds.impulse_simulated.values[i]
            ax2.plot(ds.direction.values, sim, "o", ms=3, color=line.get_color())
    ax2.set_title("impulse (N s) against its direction\n(from the unbalance; line: linearised, dots: simulated)",
                  fontsize="small")
    ax2.legend(fontsize="x-small", loc="lower left", bbox_to_anchor=(1.0, 0.0))
    return fig


def shock_margin_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``shock-margin`` result, by file stem."""
    return {f"{name}_shock_margin": shock_margin_figure(ds)}


def friction_margin_figure(ds: xarray.Dataset) -> Figure:
    """The band of every coordinate (deg, from the balanced angle) and the worst residual against speed."""
    from matplotlib.figure import Figure

    rpm = ds.speed.values * RPM_PER_RAD_S
    fig = Figure(figsize=(6.4, 5.6), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    for k, coord in enumerate(ds.coordinate.values):
        lo, hi = np.degrees(ds.band_low.values[:, k]), np.degrees(ds.band_high.values[:, k])
        ax1.fill_between(rpm, lo, hi, alpha=0.3, label=str(coord))
        ax1.plot(rpm, lo, "o-", rpm, hi, "o-", color="0.3", lw=0.8, ms=3)
    ax1.set_ylabel("stuck band (deg from balanced)")
    ax1.legend(fontsize="small")
    ax1.set_title(f"{ds.attrs.get('name', 'friction margin')}: where friction holds the balls")
    worst = ds.worst_residual.values * 1e6
    ax2.plot(rpm, worst, "o-", color="tab:red")
    agree = (ds.check_inside.values == 1) & (ds.check_outside.values == 1)
    if agree.any():  # released stuck just inside the balls stayed, just outside they moved
        ax2.plot(rpm[agree], worst[agree], "o", mfc="none", mec="k", ms=9, label="confirmed by simulation")
        ax2.legend(fontsize="x-small", loc="lower right")
    ax2.set_title(f"searched by {ds.attrs.get('search', 'grid')}", fontsize="x-small")
    ax2.ticklabel_format(axis="y", useOffset=False)
    ax2.set_ylim(0.0, 1.1 * np.nanmax(worst) if np.isfinite(worst).any() else 1.0)
    ax2.set_ylabel(f"worst {ds.attrs.get('residual', 'residual')} (um)")
    ax2.set_xlabel("speed (rpm)")
    return fig


def friction_margin_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``friction-margin`` result, by file stem."""
    return {f"{name}_friction_margin": friction_margin_figure(ds)}
