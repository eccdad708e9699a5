"""Campbell diagram figure of :func:`rotorlab.linear.campbell` results.

Built as a :class:`matplotlib.figure.Figure` without pyplot (no global matplotlib state).
Display units: spin speed in rev/min, frequency in Hz. Forward-whirl branches are solid,
backward-whirl branches dashed, mixed ones dotted; the n x excitation lines are thin grey lines
and critical speeds are circles on them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["campbell_figure", "WHIRL_STYLES"]

#: Line style per whirl code: forward, backward, mixed.
WHIRL_STYLES = {1: "-", -1: "--", 0: ":"}
_WHIRL_NAMES = {1: "forward", -1: "backward", 0: "mixed"}


def _segments(x: np.ndarray, y: np.ndarray, code: np.ndarray):
    """Split one branch into runs of constant whirl (joined at the boundaries)."""
    start = 0
    for i in range(1, code.size + 1):
        if i == code.size or code[i] != code[start]:
            stop = min(i + 1, code.size)
            yield x[start:stop], y[start:stop], int(code[start])
            start = i


def _close_groups(x: np.ndarray, y: np.ndarray, dx: float, dy: float):
    """Group points closer than (dx, dy) to the previous one (in x order), for one label each.

    Examples
    --------
    >>> [list(map(float, g[0])) for g in _close_groups(np.array([1475.0, 1490.0, 5200.0]),
    ...                                                 np.array([24.6, 24.8, 86.8]), 240, 10)]
    [[1475.0, 1490.0], [5200.0]]
    """
    order = np.argsort(x, kind="stable")
    groups: list[tuple[list[float], list[float]]] = []
    for i in order:
        if groups and x[i] - groups[-1][0][-1] < dx and abs(y[i] - groups[-1][1][-1]) < dy:
            groups[-1][0].append(x[i])
            groups[-1][1].append(y[i])
        else:
            groups.append(([x[i]], [y[i]]))
    return [(np.array(gx), np.array(gy)) for gx, gy in groups]


def campbell_figure(ds: xarray.Dataset, *, ax: Axes | None = None, title: str | None = None,
                    harmonics=None, show_critical: bool = True) -> Figure:
    """Draw a Campbell diagram.

    Parameters
    ----------
    ds : xarray.Dataset
        Result of :func:`rotorlab.linear.campbell` (``frequency``, ``whirl``, ``speed_rpm``,
        and the ``critical_*`` variables).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.
    title : str, optional
        Axes title; default "Campbell diagram".
    harmonics : sequence of int, optional
        Excitation lines to draw; default the harmonics the Dataset was computed with.
    show_critical : bool
        Mark the critical speeds.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from rotorlab.linear import RPM, campbell
    >>> from rotorlab.linear.cases import friswell_rotor
    >>> ds = campbell(friswell_rotor(), RPM * np.linspace(0, 4000, 21), n_modes=4)
    >>> fig = campbell_figure(ds)
    >>> fig.axes[0].get_xlabel()
    'spin speed (rev/min)'
    """
    if ax is None:
        from matplotlib.figure import Figure

        fig = Figure(figsize=(7.0, 4.5), layout="constrained")
        ax = fig.add_subplot(1, 1, 1)
    else:
        fig = ax.figure
    from matplotlib import colormaps

    rpm = np.asarray(ds.speed_rpm.values, dtype=float)
    freq = np.asarray(ds.frequency.values, dtype=float)
    whirl = np.asarray(ds.whirl.values)
    n_modes = freq.shape[1]
    cmap = colormaps["tab10" if n_modes <= 10 else "viridis"]
    from matplotlib.lines import Line2D

    seen = set()
    for k in range(n_modes):
        color = cmap(k if n_modes <= 10 else k / max(n_modes - 1, 1))
        for xs, ys, code in _segments(rpm, freq[:, k], whirl[:, k]):
            seen.add(code)
            ax.plot(xs, ys, WHIRL_STYLES[code], color=color, lw=1.6,
                    gid=f"mode{k}-{_WHIRL_NAMES[code]}")
    handles = [Line2D([], [], ls=WHIRL_STYLES[c], color="k", lw=1.4, label=_WHIRL_NAMES[c])
               for c in (1, -1, 0) if c in seen]
    top = float(np.nanmax(freq)) if freq.size else 1.0
    ax.set_xlim(rpm[0], rpm[-1])
    ax.set_ylim(0.0, 1.05 * top)
    x_span, y_top = float(rpm[-1] - rpm[0]) or 1.0, 1.05 * top
    hs = list(ds.attrs.get("harmonics", [1])) if harmonics is None else list(harmonics)
    for h in hs:
        ax.plot(rpm, h * rpm / 60.0, "-", color="0.55", lw=0.9, gid=f"harmonic{h}")
        # label the line where it leaves the axes: the right edge, or the top
        x_end = min(float(rpm[-1]), 60.0 * y_top / h)
        room = h * x_end / 60.0 < 0.92 * y_top  # room above the line's end for its label
        ax.annotate(f"{h}x", (x_end, h * x_end / 60.0), fontsize=8, color="0.4",
                    xytext=(-3, 3 if room else -3), textcoords="offset points", ha="right",
                    va="bottom" if room else "top")
    if show_critical and "critical_speed_rpm" in ds and ds.sizes.get("critical", 0):
        sel = np.isin(ds.critical_harmonic.values, hs)
        cr = ds.critical_speed_rpm.values[sel]
        cf = ds.critical_frequency.values[sel]
        handles += ax.plot(cr, cf, "o", mfc="none", mec="k", ms=7, label="critical speed",
                           gid="critical")
        for xs, ys in _close_groups(cr, cf, 0.06 * x_span, 0.08 * y_top):
            right = xs[0] > rpm[0] + 0.8 * x_span  # near the right edge: label to the left
            ax.annotate(" / ".join(f"{x:.0f}" for x in xs), (xs[0], ys[0]), fontsize=7,
                        xytext=(-4 if right else 4, -10), textcoords="offset points",
                        ha="right" if right else "left")
    ax.set_xlabel("spin speed (rev/min)")
    ax.set_ylabel("natural frequency (Hz)")
    ax.set_title("Campbell diagram" if title is None else title)
    ax.grid(True, lw=0.3)
    ax.legend(handles=handles, loc="upper left", fontsize=8)
    return fig
