"""Figures of steady-motion results: stability charts, verification fractions, run-ups.

Datasets from :func:`rotorlab.steady.stability_chart`, :func:`rotorlab.steady.verify` and
:func:`rotorlab.steady.run_up`.

Built without pyplot (Agg canvas), like the other figures of :mod:`rotorlab.plot`. Speeds are
shown as omega / p, deflections in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["stability_chart_figure", "verify_figure", "run_up_figure"]

_METHODS = (
    ("stable_hamilton", "seed 003: least H~*, Hessian of f"),
    ("stable_averaged", "seed 002: averaged equations"),
    ("stable_exact", "exact eigenvalues"),
)
_METHOD_COLORS = ("tab:orange", "tab:blue", "tab:green")


def _param_dim(ds: xarray.Dataset) -> str | None:
    extra = [d for d in ds.stable_exact.dims if d not in ("speed", "motion")]
    return extra[0] if extra else None


def _band_figure(ds: xarray.Dataset) -> Figure:
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    labels = [str(m) for m in ds.motion.values]
    ratio = np.asarray(ds.speed_ratio.values, dtype=float)
    half = 0.5 * (ratio[1] - ratio[0]) if ratio.size > 1 else 0.05
    last = 0.5 * (ratio[-1] - ratio[-2]) if ratio.size > 1 else 0.05
    edges = np.concatenate([[ratio[0] - half], 0.5 * (ratio[1:] + ratio[:-1]), [ratio[-1] + last]])
    fig = Figure(figsize=(8.0, 2.2 + 0.55 * len(labels) + 3.0), layout="constrained")
    ax, ax2 = fig.subplots(2, 1, sharex=True, height_ratios=[0.55 * len(labels) + 0.6, 3.0])
    exists = ds.exists.values
    for j, lab in enumerate(labels):
        y0 = len(labels) - 1 - j
        ax.fill_between(edges, y0 - 0.42, y0 + 0.42, color="0.96", lw=0)
        for k in range(ratio.size):
            if exists[k, j]:
                ax.add_patch(_rect(edges[k], y0 - 0.42, edges[k + 1] - edges[k], 0.84, "0.82"))
        for m, (var, _) in enumerate(_METHODS):
            stable = ds[var].values[:, j]
            for k in np.flatnonzero(stable):
                ax.add_patch(_rect(edges[k], y0 + 0.14 - 0.28 * m, edges[k + 1] - edges[k], 0.26, _METHOD_COLORS[m]))
    ax.set_yticks(np.arange(len(labels)))
    ax.set_yticklabels(labels[::-1])
    ax.set_ylim(-0.6, len(labels) - 0.4)
    ax.axvline(1.0, color="k", lw=0.8, ls="--")
    ax.set_title("steady motions: grey = exists; bars = stable by each method", fontsize=10)
    handles = [Patch(color="0.82", label="exists")]
    handles += [Patch(color=c, label=t) for c, (_, t) in zip(_METHOD_COLORS, _METHODS)]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    amp = ds.amplitude.values * 1e3
    stable = ds.stable_exact.values
    for j, lab in enumerate(labels):
        if not np.any(np.isfinite(amp[:, j])) or np.nanmax(amp[:, j]) <= 0:
            continue
        line = ax2.plot(ratio, np.where(stable[:, j], amp[:, j], np.nan), lw=1.8, label=lab)[0]
        ax2.plot(ratio, np.where(~stable[:, j], amp[:, j], np.nan), lw=0.8, ls=":", color=line.get_color())
    ax2.set_yscale("log")
    ax2.axvline(1.0, color="k", lw=0.8, ls="--")
    ax2.set_xlabel("omega / p")
    ax2.set_ylabel("shaft deflection (mm)")
    ax2.set_title("deflection of each motion: solid = exactly stable, dotted = unstable", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax2.set_xlim(edges[0], edges[-1])
    return fig


def _rect(x, y, w, h, color):
    from matplotlib.patches import Rectangle

    return Rectangle((x, y), w, h, color=color, lw=0)


def _map_figure(ds: xarray.Dataset, dim: str) -> Figure:
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    labels = [str(m) for m in ds.motion.values]
    names = ["none"] + labels + ["several"]
    cmap = ListedColormap(["white"] + [f"C{i % 10}" for i in range(len(labels))] + ["0.4"])
    values = np.asarray(ds[dim].values, dtype=float)
    ratio = np.asarray(ds.speed_ratio.transpose(dim, "speed").values, dtype=float)
    yy = np.broadcast_to(values[:, None], ratio.shape)
    fig = Figure(figsize=(11.0, 4.2), layout="constrained")
    axes = fig.subplots(1, 3, sharey=True)
    for ax, (var, title) in zip(axes, _METHODS):
        st = ds[var].transpose(dim, "speed", "motion").values
        count = st.sum(axis=2)
        code = np.where(count == 0, 0, np.where(count == 1, 1 + np.argmax(st, axis=2), len(names) - 1))
        # families of mirror images (main+ / main-) count as one balanced state
        mains = [j for j, lab in enumerate(labels) if lab.startswith("main")]
        if len(mains) == 2:
            both = st[:, :, mains[0]] & st[:, :, mains[1]] & (count == 2)
            code = np.where(both, 1 + mains[0], code)
        ax.pcolormesh(ratio, yy, code, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("omega / p")
        ax.axvline(1.0, color="k", lw=0.6, ls="--")
    unit = ds[dim].attrs.get("units", "")
    axes[0].set_ylabel(f"{dim} ({unit})" if unit else dim)
    pair = len([lab for lab in labels if lab.startswith("main")]) == 2
    handles = [Patch(facecolor=cmap(i), edgecolor="0.6",
                     label="main± (balanced)" if pair and name == "main+" else name)
               for i, name in enumerate(names) if not (pair and name == "main-")]  # fmt: skip
    fig.legend(handles=handles, fontsize=7, loc="outside right upper", title="stable motion")
    return fig


def stability_chart_figure(ds: xarray.Dataset) -> Figure:
    """Draw a stability chart: which steady motions exist and which each method calls stable.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.steady.stability_chart`, over speed only or over speed and one
        parameter.

    Returns
    -------
    matplotlib.figure.Figure
        Speed only: a band per motion (grey where it exists, one coloured bar per method where
        that method calls it stable) above the deflection of each motion (solid where exactly
        stable). Speed and a parameter: one map per method of the stable motion at each point
        (white: none stable, dark grey: several).

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> from rotorlab.steady import stability_chart
    >>> ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    >>> model = JeffcottBalls(RotorParams(2.0, 1e-3, 2e4, 8.0), (ball, ball), speed=ConstantSpeed(1.0))
    >>> fig = stability_chart_figure(stability_chart(model, [50.0, 150.0, 300.0]))
    >>> len(fig.axes)
    2
    """
    dim = _param_dim(ds)
    return _band_figure(ds) if dim is None else _map_figure(ds, dim)


def verify_figure(ds: xarray.Dataset) -> Figure:
    """Draw the basin fractions of a verification: one stacked bar per speed.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.steady.verify`.

    Returns
    -------
    matplotlib.figure.Figure
        Bars split by the motion reached (grey: non-synchronous, other or failed); a cross over a bar
        marks a speed where some start did not end as the exact eigenvalues predict.

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> ds = xr.Dataset({"fraction": (("speed", "outcome"), [[1.0, 0.0], [0.25, 0.75]]),
    ...                  "agrees_exact": (("speed",), [True, False])},
    ...                 coords={"speed_ratio": ("speed", [0.6, 1.2]), "outcome": ["side 00", "non-synchronous"]})
    >>> len(verify_figure(ds).axes)
    1
    """
    from matplotlib.figure import Figure

    outcomes = [str(o) for o in ds.outcome.values]
    ratio = np.asarray(ds.speed_ratio.values, dtype=float)
    frac = np.asarray(ds.fraction.values, dtype=float)
    fig = Figure(figsize=(7.5, 3.6), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    x = np.arange(ratio.size)
    bottom = np.zeros(ratio.size)
    greys = iter(("0.55", "0.75", "0.35"))
    for j, name in enumerate(outcomes):
        if not np.any(frac[:, j] > 0):
            continue
        color = next(greys) if name in ("non-synchronous", "other", "failed") else f"C{j % 10}"
        ax.bar(x, frac[:, j], bottom=bottom, color=color, label=name, width=0.7)
        bottom += frac[:, j]
    for k in np.flatnonzero(~np.asarray(ds.agrees_exact.values, dtype=bool)):
        ax.plot(x[k], 1.04, "x", color="k", ms=8)
    ax.set_xticks(x)
    ax.set_xticklabels([f"{r:.2f}" for r in ratio])
    ax.set_xlabel("omega / p")
    ax.set_ylabel("fraction of starts")
    ax.set_ylim(0, 1.1)
    ax.set_title("where the starts end (x: not as the exact eigenvalues predict)", fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def run_up_figure(ds: xarray.Dataset) -> Figure:
    """Draw a run-up: shaft deflection against time with and without the balancer.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.steady.run_up`.

    Returns
    -------
    matplotlib.figure.Figure
        Deflection (mm, log scale) against time; one line per start with the balancer (dashed
        where the balls did not synchronise), black without it; the speed omega / p on the right
        axis (grey).
    """
    from matplotlib.figure import Figure

    p = float(ds.attrs["critical_speed"])
    t = np.asarray(ds.time.values, dtype=float)
    fig = Figure(figsize=(7.5, 3.8), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    for i in range(ds.sizes["ic"]):
        synced = bool(ds.synchronised.values[i])
        label = f"start {i}: " + (str(ds.final_motion.values[i]) if synced else "not synchronised")
        ax.plot(t, ds.amplitude.values[i] * 1e3, lw=0.8, ls="-" if synced else "--", label=label)
    ax.plot(t, ds.amplitude_without.values * 1e3, color="k", lw=1.2, label="without balancer")
    top = max(float(ds.max_amplitude.max()), float(ds.max_amplitude_without)) * 1e3
    ax.set_yscale("log")
    ax.set_ylim(top * 1e-5, top * 2.0)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("shaft deflection (mm)")
    ax.set_title(f"run-up ({ds.attrs.get('speed_profile', '')})", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.12, 1.0))
    speed = ax.twinx()
    speed.plot(t, np.asarray(ds.speed.values, dtype=float) / p, color="0.5", lw=0.8, ls=":")
    speed.axhline(1.0, color="0.5", lw=0.5)
    speed.set_ylabel("omega / p (dotted)", color="0.4")
    return fig
