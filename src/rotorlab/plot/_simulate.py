"""Figures of simulation results (:func:`rotorlab.analyses.simulate` Datasets).

Figures are built as :class:`matplotlib.figure.Figure` objects without pyplot, so nothing here
touches matplotlib's global backend or figure registry; they render with the Agg canvas
(``fig.savefig("f.png")``). Display units: deflection in mm, angles in degrees, speeds in rpm.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S

if TYPE_CHECKING:
    import xarray
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "amplitude_figure",
    "ball_angle_figure",
    "final_positions_figure",
    "orbit_figure",
    "simulation_figures",
    "speed_label",
    "configuration_label",
]

_LINESTYLES = ("-", "--", ":", "-.")


def _new_figure(n_panels: int, *, polar: bool = False, width: float = 7.0,
                height: float = 3.0) -> tuple[Figure, list[Axes]]:  # fmt: skip
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height * n_panels + 0.4), layout="constrained")
    kw = {"projection": "polar"} if polar else {}
    axes = [fig.add_subplot(n_panels, 1, k + 1, **kw) for k in range(n_panels)]
    return fig, axes


def _colors(n: int) -> list:
    from matplotlib import colormaps

    cmap = colormaps["tab10" if n <= 10 else "viridis"]
    return [cmap(i if n <= 10 else i / max(n - 1, 1)) for i in range(n)]


#: Up to this many starts, each has its colour and legend entry; beyond it, the starts are
#: coloured and counted by the motion they reached (a legend of 64 starts would hide the axes).
MAX_LISTED_STARTS = 8


def _start_styles(ds: xarray.Dataset, k: int) -> list[tuple[object, str | None]]:
    """Colour and legend entry (None: no entry) of every start at speed ``k``."""
    n_ic = ds.sizes["ic"]
    outcomes = [str(v) for v in ds.outcome.values[k]]
    if n_ic <= MAX_LISTED_STARTS:
        return [(c, f"{configuration_label(ds, i)}: {outcomes[i]}")
                for i, c in enumerate(_colors(n_ic))]
    kinds = sorted(set(outcomes), key=outcomes.index)
    colors = dict(zip(kinds, _colors(len(kinds)), strict=True))
    styles, seen = [], set()
    for name in outcomes:
        label = None
        if name not in seen:
            seen.add(name)
            label = f"{name} ({outcomes.count(name)} of {n_ic} starts)"
        styles.append((colors[name], label))
    return styles


def _legend(ax: Axes) -> None:
    """Put the legend beside the axes (never over the curves)."""
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)


def _time_axis(ax: Axes, t_end: float) -> None:
    """Stretch the start of a long run: linear near 0, logarithmic beyond ``t_end / 40`` (the
    axis label says so).

    The transient of a start-up lasts a fraction of a second and the settled motion the rest:
    on a linear axis of 20 s the transient is squeezed into the first pixels.
    """
    width = t_end / 40.0
    ax.set_xscale("asinh", linear_width=width)
    ticks = [v for v in (0.0, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0)
             if v <= t_end * (1 + 1e-9) and (v == 0.0 or v >= width / 2)]
    ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
    ax.minorticks_off()
    ax.set_xlim(0.0, t_end)
    ax.set_xlabel(f"time (s): linear up to {width:.2g} s, logarithmic beyond")


def speed_label(ds: xarray.Dataset, k: int) -> str:
    """Return the panel title of speed ``k``: rpm, Hz and omega/p.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(coords={"speed": ("speed", [251.3]), "speed_ratio": ("speed", [2.0])})
    >>> speed_label(ds, 0)
    'omega = 2400 rpm (40.0 Hz), omega/p = 2.00'
    """
    om = float(ds.speed.values[k])
    rpm = om * RPM_PER_RAD_S
    return f"omega = {rpm:.0f} rpm ({om / (2 * math.pi):.1f} Hz), omega/p = {float(ds.speed_ratio.values[k]):.2f}"


def configuration_label(ds: xarray.Dataset, i: int) -> str:
    """Return the legend entry of initial configuration ``i``: its ball angles in degrees.

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> ds = xr.Dataset({"initial_ball_angle": (("ic", "ball"), np.radians([[0.0, 90.0]]))})
    >>> configuration_label(ds, 0)
    'start (0°, 90°)'
    """
    degs = np.degrees(ds.initial_ball_angle.values[i])
    return "start (" + ", ".join(f"{d:.0f}°" for d in degs) + ")"


def _break_wraps(values_deg: np.ndarray) -> np.ndarray:
    """Insert NaN where a wrapped angle jumps by more than 180 degrees (no vertical lines)."""
    out = np.array(values_deg, dtype=float)
    jumps = np.abs(np.diff(out)) > 180.0
    out[1:][jumps] = np.nan
    return out


def amplitude_figure(ds: xarray.Dataset, *, log: bool = False) -> Figure:
    """Plot the shaft deflection against time: one panel per speed, one line per start.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.
    log : bool
        Logarithmic deflection axis (shows the convergence to balance).

    Returns
    -------
    matplotlib.figure.Figure
        The dashed line is the deflection the unbalance alone causes.
    """
    n_speed, n_ic = ds.sizes["speed"], ds.sizes["ic"]
    fig, axes = _new_figure(n_speed)
    t = ds.time.values
    lw = 1.0 if n_ic <= MAX_LISTED_STARTS else 0.6
    for k, ax in enumerate(axes):
        for i, (color, label) in enumerate(_start_styles(ds, k)):
            ax.plot(t, ds.amplitude.values[k, i] * 1e3, color=color, lw=lw, label=label)
        ref = float(ds.reference_amplitude.values[k]) * 1e3
        ax.axhline(ref, color="k", ls="--", lw=0.8, label="unbalance alone")
        if log:
            ax.set_yscale("log")
        ax.set_title(speed_label(ds, k), fontsize=10)
        _time_axis(ax, float(t[-1]))
        ax.set_ylabel("shaft deflection (mm)")
        ax.grid(alpha=0.3)
        _legend(ax)
    return fig


def ball_angle_figure(ds: xarray.Dataset) -> Figure:
    """Plot the ball angles from the unbalance against time (degrees, wrapped to (-180, 180]).

    One panel per speed; colour = start configuration, line style = ball.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    n_speed, n_ic, n_ball = ds.sizes["speed"], ds.sizes["ic"], ds.sizes["ball"]
    fig, axes = _new_figure(n_speed)
    t = ds.time.values
    lw = 1.0 if n_ic <= MAX_LISTED_STARTS else 0.6
    for k, ax in enumerate(axes):
        for i, (color, label) in enumerate(_start_styles(ds, k)):
            for b in range(n_ball):
                ax.plot(t, _break_wraps(np.degrees(ds.ball_angle.values[k, i, :, b])),
                        color=color, ls=_LINESTYLES[b % len(_LINESTYLES)], lw=lw,
                        label=label if b == 0 else None)  # fmt: skip
        ax.set_ylim(-185, 185)
        ax.set_yticks(np.arange(-180, 181, 60))
        ax.set_title(speed_label(ds, k) + "; line style = ball", fontsize=10)
        _time_axis(ax, float(t[-1]))
        ax.set_ylabel("ball angle from unbalance (deg)", fontsize=9)
        ax.grid(alpha=0.3)
        _legend(ax)
    return fig


def final_positions_figure(ds: xarray.Dataset) -> Figure:
    """Show where the balls ended on the disc (polar; the unbalance points to 0 degrees).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.

    Returns
    -------
    matplotlib.figure.Figure
        One polar panel per speed; each start configuration's final ball angles are markers
        on a ring of its own (inner ring = first start).
    """
    n_speed, n_ic = ds.sizes["speed"], ds.sizes["ic"]
    fig, axes = _new_figure(n_speed, polar=True, width=7.0, height=3.6)
    ms = 6 if n_ic <= MAX_LISTED_STARTS else 3
    for k, ax in enumerate(axes):
        ax.annotate("", xy=(0.0, n_ic + 1.0), xytext=(0.0, 0.0),
                    arrowprops={"arrowstyle": "->", "color": "k", "lw": 1.5})  # fmt: skip
        ax.text(0.05, 0.55 * (n_ic + 1.0), "unbalance", ha="center", va="bottom", fontsize=8)
        for i, (color, label) in enumerate(_start_styles(ds, k)):
            ang = ds.final_ball_angle.values[k, i]
            ax.plot(ang, np.full(ang.shape, i + 1.0), "o", color=color, ms=ms, label=label)
        ax.set_rmax(n_ic + 1.5)
        ax.set_yticklabels([])
        ax.set_title(speed_label(ds, k), fontsize=10)
        ax.set_xlabel(f"radius: start number, 1 (centre) to {n_ic} (rim)", fontsize=8)
        _legend(ax)
    return fig


def orbit_figure(ds: xarray.Dataset, *, revolutions: float = 5.0) -> Figure:
    """Plot the orbit of the disc centre in the fixed frame over the last revolutions.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.
    revolutions : float
        How many revolutions (at the final speed) before the end to draw.

    Returns
    -------
    matplotlib.figure.Figure
        x and y in mm; one panel per speed, one line per start. The saved points are drawn as
        they are, so the orbit looks polygonal when fewer than ~20 points fall on a revolution.
    """
    n_speed, n_ic = ds.sizes["speed"], ds.sizes["ic"]
    fig, axes = _new_figure(n_speed, width=5.0, height=4.5)
    t = ds.time.values
    for k, ax in enumerate(axes):
        om = float(ds.speed.values[k])
        sel = t >= t[-1] - revolutions * 2.0 * math.pi / om
        for i, (color, label) in enumerate(_start_styles(ds, k)):
            ax.plot(ds.x.values[k, i, sel] * 1e3, ds.y.values[k, i, sel] * 1e3, ".-",
                    color=color, lw=0.6, ms=2, label=label)  # fmt: skip
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(speed_label(ds, k), fontsize=10)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.grid(alpha=0.3)
        _legend(ax)
    return fig


def simulation_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """Return the standard figures of one simulation, keyed by file stem.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.
    name : str
        Analysis name, the prefix of every key.

    Returns
    -------
    dict of str to Figure
        ``<name>_amplitude``, and for a model with balls ``<name>_ball_angles`` and
        ``<name>_final_positions``.
    """
    figures = {f"{name}_amplitude": amplitude_figure(ds)}
    if ds.sizes.get("ball", 0) > 0:
        figures[f"{name}_ball_angles"] = ball_angle_figure(ds)
        figures[f"{name}_final_positions"] = final_positions_figure(ds)
    return figures
