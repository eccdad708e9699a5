"""Figures of the linear analyses: unbalance response, mode shapes, and the standard set.

Figures are :class:`matplotlib.figure.Figure` objects built without pyplot. Display units:
spin speed in rev/min, frequency in Hz, deflection in mm, axial position in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.plot._campbell import campbell_figure

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["unbalance_response_figure", "mode_shapes_figure", "linear_figures"]

_WHIRL = {1: "forward", -1: "backward", 0: "mixed"}


def _figure(width: float = 7.0, height: float = 4.2) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def unbalance_response_figure(ds: xarray.Dataset, *, nodes=None,
                              title: str | None = None) -> Figure:
    """Draw the orbit size of some nodes versus spin speed (log scale).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.linear.unbalance_response`.
    nodes : sequence of int, optional
        Nodes to draw; default ``ds.attrs["output_nodes"]``, else all.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        One line per node: the largest semi-axis of its orbit (mm).

    Examples
    --------
    >>> from rotorlab.linear import Unbalance, unbalance_response
    >>> from rotorlab.linear.cases import friswell_rotor
    >>> ds = unbalance_response(friswell_rotor(), [10.0, 50.0, 100.0], [Unbalance(2, 1e-4)])
    >>> unbalance_response_figure(ds, nodes=[2]).axes[0].get_yscale()
    'log'
    """
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    if nodes is None:
        nodes = ds.attrs.get("output_nodes", list(range(ds.sizes["node_index"])))
    rpm = np.asarray(ds.speed_rpm.values, dtype=float)
    labels = ds.node_label.values if "node_label" in ds.coords else ds.node_index.values
    for node in np.atleast_1d(nodes):
        amp = np.asarray(ds.orbit_major.values[:, int(node)], dtype=float) * 1e3
        ax.plot(rpm, np.where(amp > 0, amp, np.nan), lw=1.4, label=str(labels[int(node)]))
    ax.set_yscale("log")
    ax.set_xlim(rpm[0], rpm[-1])
    ax.set_xlabel("spin speed (rev/min)")
    ax.set_ylabel("orbit semi-major axis (mm)")
    undamped = str(ds.attrs.get("note", "")).startswith("undamped")
    ax.set_title(("unbalance response" if title is None else title)
                 + ("\n(undamped: unbounded at the critical speeds; the peaks follow the grid)"
                    if undamped else ""))
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    return fig


def _translation_shape(ds: xarray.Dataset, k: int) -> tuple[np.ndarray, str]:
    """Mode ``k``'s translation in its main plane (x or y), in phase with the node that moves
    most and scaled to 1; and the plane's name ("x" or "y")."""
    direction = ds.direction.values
    best = None
    for plane in ("x", "y"):
        sel = direction == plane
        s = ds.shape_real.values[k, sel] + 1j * ds.shape_imag.values[k, sel]
        if best is None or np.max(np.abs(s)) > np.max(np.abs(best[0])) * (1 + 1e-9):
            best = (s, plane)
    s, plane = best
    pivot = s[np.argmax(np.abs(s))]
    return ((s / pivot).real if pivot != 0 else s.real), plane


def mode_shapes_figure(ds: xarray.Dataset, *, max_modes: int = 6,
                       title: str | None = None) -> Figure:
    """Draw the translational shape of the lowest modes along the rotor axis.

    Parameters
    ----------
    ds : xarray.Dataset
        From :meth:`rotorlab.linear.Modes.to_dataset`.
    max_modes : int
        Draw at most this many modes (the lowest).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        One line per mode: the translation of each node in the mode's main plane (x or y),
        in phase with the node that moves most, scaled to 1; nodes in the order of their axial
        position (node number where the positions are unknown). Modes of equal frequency and
        shape (the x and y modes of an isotropic rotor at rest) are one line; whirl
        (forward, backward) is named only for a spinning rotor.
    """
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    direction = ds.direction.values
    sel = direction == "x"
    pos = ds.node_position.values[sel] if "node_position" in ds.coords else np.full(sel.sum(),
                                                                                    np.nan)
    known = np.all(np.isfinite(pos))
    z = pos * 1e3 if known else np.arange(sel.sum(), dtype=float)
    order = np.argsort(z, kind="stable")
    labels = ds.node_label.values[sel] if "node_label" in ds.coords else None
    speed = float(ds.attrs.get("speed", 0.0))
    drawn: list[tuple[float, np.ndarray, list]] = []  # (frequency, curve, [count, line, text])
    for k in range(min(max_modes, ds.sizes["mode"])):
        f = float(ds.frequency.values[k])
        curve, plane = _translation_shape(ds, k)
        twin = next((d for d in drawn if abs(d[0] - f) <= 1e-6 * max(f, 1e-12)
                     and np.allclose(np.abs(d[1]), np.abs(curve), atol=1e-6)), None)
        if twin is not None:  # a degenerate pair (x and y, or both whirls at rest): one curve
            twin[2][0] += 1
            continue
        # At rest a rotor has no whirl direction: name it only when spinning.
        what = plane if speed == 0.0 else _WHIRL[int(ds.whirl.values[k])]
        (line,) = ax.plot(z[order], curve[order], "o-", lw=1.3, ms=3)
        drawn.append((f, curve, [1, line, what]))
    for f, _, (count, line, what) in drawn:
        pair = "a pair, x and y" if speed == 0.0 else f"{what}, {count} modes"
        line.set_label(f"{f:.4g} Hz ({what if count == 1 else pair})")
    if labels is not None and len(labels) <= 12:
        for zi, lab in zip(z, labels):
            ax.annotate(str(lab), (zi, 0.0), fontsize=7, color="0.35", rotation=90,
                        xytext=(0, 4), textcoords="offset points", ha="center", va="bottom")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("axial position (mm)" if known else "node")
    ax.set_ylabel("translation (scaled)")
    at = "at rest" if speed == 0.0 else f"at {speed * RPM_PER_RAD_S:.6g} rev/min"
    ax.set_title(f"mode shapes {at}" if title is None else title)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    return fig


def linear_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """Return the standard figures of one linear analysis, keyed by file stem.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.run_linear_analysis` (``attrs["analysis"]`` says which).
    name : str
        Analysis name, the prefix of every key.

    Returns
    -------
    dict of str to Figure
        ``<name>_campbell`` for a Campbell diagram, ``<name>_shapes`` for modes,
        ``<name>_orbits`` for an unbalance response; nothing for the other analyses (their
        results are tables).
    """
    kind = ds.attrs.get("analysis")
    if kind == "campbell":
        title = f"Campbell diagram: {ds.attrs.get('case', name)}"
        return {f"{name}_campbell": campbell_figure(ds, title=title)}
    if kind == "modes":
        return {f"{name}_shapes": mode_shapes_figure(ds)}
    if kind == "unbalance_response":
        return {f"{name}_orbits": unbalance_response_figure(ds)}
    return {}
