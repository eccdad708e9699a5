"""Figures of basins and regimes: basin maps (seed 004 Fig. 6), fractions against the simulated
time, and the restoring force on the toroidal ball (seed 004 Fig. 3).

Datasets from :func:`rotorlab.explore.basin_map`, :func:`rotorlab.explore.basin_fractions` and
:meth:`rotorlab.models._toroidal_ball.ToroidalBall.restoring_force`. Built without pyplot (Agg
canvas), like the other figures of :mod:`rotorlab.plot`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["basin_figure", "basin_figures", "fractions_figure", "restoring_force_figure", "working_phase_figure",
           "label_colors"]

# The paper draws the working basin dark: the first label (working / balanced) is dark.
_PALETTE = ("#1f2a44", "#e8b04a", "#9bb7d4", "#c8553d", "#6a994e", "#8e7dbe", "#bcbcbc")
_NAMES = {"psi": "ψ₀", "dpsi": "ψ̇₀", "alpha": "α₀", "dalpha": "α̇₀"}


def label_colors(labels) -> dict[str, str]:
    """Colour of each label: the first dark, ``other`` light grey.

    Examples
    --------
    >>> label_colors(["working", "spare", "other"])["other"]
    '#bcbcbc'
    """
    out = {}
    for k, name in enumerate(labels):
        out[str(name)] = _PALETTE[-1] if name == "other" else _PALETTE[k % (len(_PALETTE) - 1)]
    return out


def _input_unit(ds, name: str) -> str | None:
    """The unit coordinate ``name`` was given in, as recorded in ``attrs["input_units_<name>"]``.

    A ball angle that was not given (a ball not varied, starting where the model puts it) is
    shown in the unit of the ball angles that were given when they were all given in one unit,
    so that one figure uses one unit.
    """
    unit = ds.attrs.get(f"input_units_{name}")
    if unit is None and name.startswith("psi"):
        given = {v for k, v in ds.attrs.items() if k.startswith("input_units_psi")}
        unit = given.pop() if len(given) == 1 else None
    return unit


def _display(ds, name: str) -> tuple[float, str]:
    """Scale and unit to show coordinate ``name`` in: degrees for angles given in degrees.

    Case files and the command line take angles in any unit and keep radians; the unit they
    were written in is recorded with the result (``attrs["input_units_<name>"]``), never
    guessed from the numbers.
    """
    units = ds[name].attrs.get("units", "")
    if units == "rad" and _input_unit(ds, name) == "deg":
        return 180.0 / np.pi, "deg"
    return 1.0, units


def _axis_label(ds, name: str) -> str:
    _, units = _display(ds, name)
    return f"{_NAMES.get(name, name)} ({units})" if units else _NAMES.get(name, name)


def _start_values(ds) -> str:
    """The fixed start coordinates (and where the balls not varied start), for a title."""
    parts = []
    for key, value in ds.attrs.items():
        if key.startswith("fixed_"):
            name = key[6:]
        elif key.startswith("value_psi_"):  # the start angle of a ball that is not varied
            name = key[6:]
        else:
            continue
        if _input_unit(ds, name) == "deg":
            parts.append(f"{_NAMES.get(name, name)} = {np.degrees(float(value)):g}°")
        else:
            unit = ds.attrs.get(f"units_{name}", "")
            parts.append(f"{_NAMES.get(name, name)} = {float(value):g} {unit}".rstrip())
    return ", ".join(dict.fromkeys(parts))


def basin_figure(ds: xarray.Dataset, *, horizon: float | None = None, title: str | None = None) -> Figure:
    """Draw a basin map: the label of every start point of a 2-D grid.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.explore.basin_map` (``label`` with two grid dims and ``horizon``),
        or random starts from :func:`rotorlab.analyses.run_basin` (``label`` on ``ic``; the
        coordinate names in ``attrs["x"]`` and ``attrs["y"]``), drawn as dots.
    horizon : float, optional
        Simulated time whose labels are drawn (s); default the last one.
    title : str, optional
        The title's first line; a second line says where the coordinates that are not varied
        start (``attrs["fixed_<name>"]``, and the start angle ``attrs["value_psi_<i>"]`` of
        every ball that is not varied).

    Returns
    -------
    matplotlib.figure.Figure
        One panel; the legend gives each label's fraction of the grid. Angles given in
        degrees (``attrs["input_units_<name>"] = "deg"``) are drawn in degrees.
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    label = ds["label"]
    sel = label.isel(horizon=-1) if horizon is None else label.sel(horizon=horizon, method="nearest")
    t = float(sel["horizon"])
    names = [str(v) for v in label.attrs["labels"]]
    colors = label_colors(names)
    cmap = ListedColormap([colors[n] for n in names])
    norm = BoundaryNorm(np.arange(len(names) + 1) - 0.5, len(names))
    fig = Figure(figsize=(6.4, 5.0), layout="constrained")
    ax = fig.subplots()
    if label.dims[0] == "ic":  # random starts: one dot per start, at its drawn coordinates
        xdim, ydim = ds.attrs["x"], ds.attrs["y"]
        sx, sy = _display(ds, xdim)[0], _display(ds, ydim)[0]
        ax.scatter(ds[xdim].values * sx, ds[ydim].values * sy, c=sel.values, cmap=cmap, norm=norm, s=9,
                   linewidths=0)
    else:
        ydim, xdim = [d for d in label.dims if d != "horizon"]
        sx, sy = _display(ds, xdim)[0], _display(ds, ydim)[0]
        x, y = ds[xdim].values * sx, ds[ydim].values * sy
        ax.pcolormesh(x, y, sel.transpose(ydim, xdim).values, cmap=cmap, norm=norm, shading="nearest")
    ax.set_xlabel(_axis_label(ds, xdim))
    ax.set_ylabel(_axis_label(ds, ydim))
    values = sel.values.ravel()
    handles = [Patch(color=colors[n], label=f"{n} ({np.mean(values == k):.1%})") for k, n in enumerate(names)]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    fixed = _start_values(ds)
    ax.set_title((title or f"regimes after {t:g} s") + (f"\nother starts: {fixed}" if fixed else ""))
    return fig


def fractions_figure(fr: xarray.Dataset, *, title: str | None = None) -> Figure:
    """Draw basin fractions against the simulated time (horizon).

    A fraction that still changes at the last horizon means the simulated time was too short
    for that regime to settle (a long transient).

    Parameters
    ----------
    fr : xarray.Dataset or mapping of str to xarray.Dataset
        From :func:`rotorlab.explore.basin_fractions`; several are drawn with different line
        styles, keyed by their legend text.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    sets = fr if isinstance(fr, dict) else {"": fr}
    fig = Figure(figsize=(6.4, 4.0), layout="constrained")
    ax = fig.subplots()
    styles = ("-", "--", ":", "-.")
    for j, (key, f) in enumerate(sets.items()):
        names = [str(v) for v in f.regime.values]
        colors = label_colors(names)
        for name in names:
            ax.plot(f.horizon.values, f.fraction.sel(regime=name).values, styles[j % 4], marker="o", ms=3,
                    color=colors[name], label=f"{name} {key}".strip())  # fmt: skip
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("fraction of starts")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(frameon=False, fontsize="small")
    ax.set_title(title or "basin fractions against the simulated time")
    return fig


def restoring_force_figure(ds: xarray.Dataset, *, title: str | None = None) -> Figure:
    """Draw the tangential force on a ball at rest against its ring angle (seed 004 Fig. 3).

    Parameters
    ----------
    ds : xarray.Dataset
        From ``ToroidalBall.restoring_force`` (``tangential`` and ``friction_limit`` on ``psi``).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        The tangential force per unit mass and the band ``±k N / r`` inside which rolling
        resistance holds the ball.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.0), layout="constrained")
    ax = fig.subplots()
    psi = ds.psi.values
    limit = ds.friction_limit.values
    ax.fill_between(psi, -limit, limit, color="0.85", label="held by rolling resistance (±k N / r)")
    ax.plot(psi, ds.tangential.values, color=_PALETTE[0], label="tangential force P_τ / m")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.axvline(np.pi, color="k", lw=0.6, ls="--")
    ax.set_xlabel("ring angle ψ (rad)")
    ax.set_ylabel(f"force per unit mass ({ds.tangential.attrs.get('units', '')})")
    ax.legend(frameon=False, fontsize="small")
    ax.set_title(title or "restoring force on the ball at rest (seed 004 Fig. 3)")
    return fig


def working_phase_figure(ds: xarray.Dataset, *, title: str | None = None) -> Figure:
    """Draw the phase portrait of a ball released towards the working point (seed 004 Fig. 5).

    Parameters
    ----------
    ds : xarray.Dataset
        From a ``working-point`` analysis (``release_*`` on ``time``, ``psi``/``alpha`` of the
        equilibrium, ``psi_band``/``alpha_band``).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels, (psi, psi') and (alpha, alpha'), with the friction band shaded and the
        paper's printed working point marked.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9.0, 4.0), layout="constrained")
    axes = fig.subplots(1, 2)
    paper = {"psi": 3.14156, "alpha": 1.56825}
    for ax, q, sym in zip(axes, ("psi", "alpha"), ("ψ", "α")):
        ax.axvspan(*(float(v) for v in ds[f"{q}_band"].values), color="0.85", label="friction band")
        ax.plot(ds[f"release_{q}"].values, ds[f"release_d{q}"].values, color=_PALETTE[0], lw=0.8,
                label="released ball")  # fmt: skip
        ax.plot([paper[q]], [0.0], "x", color=_PALETTE[3], ms=8, label=f"seed 004: {sym} = {paper[q]}")
        ax.set_xlabel(f"{sym} (rad)")
        ax.set_ylabel(f"d{sym}/dt (rad/s)")
        ax.grid(alpha=0.3)
    axes[0].legend(frameon=False, fontsize="small")
    start = ", ".join(f"{v:g}" for v in ds.attrs.get("release_start", []))
    fig.suptitle(title or f"phase portrait of a ball released at ({start}) (seed 004 Fig. 5)")
    return fig


def basin_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """Return the figures of a ``basin`` or ``working-point`` result by file stem.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.run_basin_analysis`.
    name : str
        Analysis name; the stems are ``<name>_map``, ``<name>_map_first`` and ``<name>_map_mid``
        (the map at the first horizon and halfway through the simulated time, each when it
        differs from the final one) and ``<name>_fractions`` (basin)
        or ``<name>_force`` and ``<name>_phase`` (working point); a ``sweep`` result gets
        :func:`sweep_figures`.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
    """
    if ds.attrs.get("analysis") == "working-point":
        curve = ds[["tangential", "friction_limit"]].rename(ring_angle="psi")
        k = float(ds.attrs.get("rolling_friction", np.nan))
        return {f"{name}_force": restoring_force_figure(
            curve, title=f"restoring force on the ball at rest, k = {k:g} m (seed 004 Fig. 3)"),
            f"{name}_phase": working_phase_figure(ds)}
    if ds.attrs.get("analysis") == "sweep":
        return sweep_figures(ds, name)
    if ds.attrs.get("analysis") != "basin":
        return {}
    fr = ds[["fraction"]]
    out = {f"{name}_map": basin_figure(ds, title=f"{name}: regimes after {float(ds.horizon[-1]):g} s")}
    h = ds.horizon.values
    mid = int(np.argmin(np.abs(h - h[-1] / 2.0)))
    # Where the map still changes, show it earlier too: at the first horizon (the basins of
    # analyses with the same horizons can be compared there) and halfway (a long transient).
    for suffix, j in (("first", 0), ("mid", mid)):
        if j < h.size - 1 and (suffix == "first" or j > 0) and not np.array_equal(ds.fraction.values[j],
                                                                                  ds.fraction.values[-1]):
            out[f"{name}_map_{suffix}"] = basin_figure(ds, horizon=float(h[j]),
                                                       title=f"{name}: regimes after {float(h[j]):g} s")
    out[f"{name}_fractions"] = fractions_figure(fr, title=f"{name}: fractions against the simulated time")
    return out


def sweep_figures(ds: xarray.Dataset, name: str | None = None) -> dict[str, Figure]:
    """Return the figures of a sweep of a regime mapper by file stem (``rotorlab show``, ``rotorlab run``).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.sweep.run_sweep` with :class:`rotorlab.explore.MapperAnalysis`
        (``label`` over the swept dims and ``horizon``), or from a ``sweep`` analysis.
    name : str, optional
        Analysis name: the stems are ``<name>_basin`` (the map of the last horizon, for a grid of
        two swept quantities only) and ``<name>_fractions``; without a name ``basin`` and
        ``fractions``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
    """
    from rotorlab.explore import basin_fractions

    prefix = f"{name}_" if name else ""
    out = {}
    dims = [d for d in ds["label"].dims if d != "horizon"]
    if len(dims) == 2 and not {"sample", "ic"} & set(dims):
        title = f"{name}: regimes after {float(ds.horizon[-1]):g} s" if name else None
        out[f"{prefix}basin"] = basin_figure(ds, title=title)
    fr = ds[["fraction"]] if "fraction" in ds else basin_fractions(ds)
    out[f"{prefix}fractions"] = fractions_figure(fr, title=f"{name}: fractions against the simulated time"
                                                 if name else None)  # fmt: skip
    return out
