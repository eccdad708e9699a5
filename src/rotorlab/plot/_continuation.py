"""Figures of a continuation: the bifurcation diagram and the two-parameter curves over the grid chart.

Datasets from :meth:`rotorlab.continuation.ContinuationResult.to_dataset` (the ``continuation``
analysis adds today's grid chart, ``chart_stable`` over ``chart_value`` x ``chart_speed``).
Built without pyplot (Agg canvas). Speeds are shown in rpm, masses below 1 kg in g.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

import numpy as np

from rotorlab._constants import shown_unit as _shown

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["bifurcation_figure", "two_parameter_figure", "continuation_figures"]

_MARKS = {"fold": ("s", "F"), "hopf": ("o", "H"), "branch": ("D", "BP"), "fold-of-cycles": ("s", "LPC"),
          "period-doubling": ("v", "PD"), "torus": ("^", "NS")}


def _runs(mask: np.ndarray) -> list[slice]:
    """Slices of consecutive equal values of ``mask`` (each run shares its end point with the next)."""
    out, start = [], 0
    for k in range(1, mask.size + 1):
        if k == mask.size or mask[k] != mask[start]:
            out.append(slice(start, min(k + 1, mask.size)))
            start = k
    return out


#: Whirl radii below this (m) are round-off of a balanced state and drawn as zero.
_ZERO_WHIRL = 1e-9


def _with_special_points(ds, b: int, specials: list, param: str):
    """Branch ``b``'s parameter values, amplitudes (m), stability, ball angles (rad; None if
    absent) and periods (s; NaN for equilibria) with each located special point inserted where it
    lies (its stability that of the point after it), so that a stable and an unstable stretch
    meet at the located point, not at the next computed one."""
    v = ds.value.values[b]
    keep = np.isfinite(v)
    v = v[keep]
    amp = ds.amplitude.values[b][keep]
    stable = ds.stable.values[b][keep] > 0.5
    ang = ds.ball_angle.values[b][keep] if "ball_angle" in ds else None
    per = ds.period.values[b][keep]
    for s in sorted(specials, key=lambda s: -int(s.get("index", 0))):
        k = int(s.get("index", 0))
        x = s.get(param)
        if x is None or not 0 < k < v.size:
            continue
        w = (x - v[k - 1]) / (v[k] - v[k - 1]) if v[k] != v[k - 1] else 0.0
        a = s.get("amplitude_m")
        a = amp[k - 1] + w * (amp[k] - amp[k - 1]) if a is None else a
        v, amp, stable = np.insert(v, k, x), np.insert(amp, k, a), np.insert(stable, k, stable[k])
        per = np.insert(per, k, per[k - 1] + w * (per[k] - per[k - 1]))
        if ang is not None:
            ang = np.insert(ang, k, ang[k - 1] + w * (ang[k] - ang[k - 1]), axis=0)
    return v, amp, stable, ang, per


def bifurcation_figure(ds: xarray.Dataset) -> Figure:
    """Draw the bifurcation diagram: amplitude and ball angles against the continued parameter.

    Parameters
    ----------
    ds : xarray.Dataset
        From :meth:`ContinuationResult.to_dataset` (``value``, ``amplitude``, ``stable``,
        ``ball_angle``, ``attrs["special_points"]``).

    Returns
    -------
    matplotlib.figure.Figure
        Top: the largest whirl radius (mm) of each branch, stable solid, unstable dashed;
        then the ball angles (deg) of the steady motions and the period (s) of the whirl
        orbits (periodic branches). Special points are marked (F fold, H Hopf, BP branch
        point), numbered, and explained in words below the axes.
    """
    from matplotlib.figure import Figure

    param = str(ds.parameter.values[0]) if ds.sizes.get("branch") else ""
    factor, unit = _shown(ds.attrs.get("units", ""))
    specials = json.loads(ds.attrs.get("special_points", "[]"))
    notes = []
    for b, sps in enumerate(specials):
        for s in sps:
            if not any(abs(s[param] - t[param]) <= 1e-7 * max(1.0, abs(t[param])) and s["type"] == t["type"]
                       for t, _ in notes):
                notes.append((s, b))
    kinds = [str(k) for k in ds.kind.values] if "kind" in ds.coords else []
    orbits = "periodic" in kinds
    steady = not orbits or "equilibrium" in kinds
    panels = [3.0] + [2.2] * steady + [2.0] * orbits + [0.35 + 0.3 * len(notes)]
    fig = Figure(figsize=(8.5, 4.0 + 2.2 * (len(panels) - 2) + 0.28 * len(notes)), layout="constrained")
    axes = list(fig.subplots(len(panels), 1, height_ratios=panels))
    ax, text = axes[0], axes[-1]
    ax2 = axes[1] if steady else None
    axp = axes[-2] if orbits else None
    top = 0.0
    for b in range(ds.sizes.get("branch", 0)):
        v, amp, stable, ang, per = _with_special_points(ds, b, specials[b] if b < len(specials) else [], param)
        v = v * factor
        amp = np.where(amp < _ZERO_WHIRL, 0.0, amp) * 1e3
        top = max(top, float(np.max(amp, initial=0.0)))
        color = f"C{b % 10}"
        label = str(ds.label.values[b])
        for k, seg in enumerate(_runs(stable)):
            st = bool(stable[seg.start])
            ax.plot(v[seg], amp[seg], color=color, lw=1.8 if st else 1.0, ls="-" if st else "--",
                    label=label if k == 0 else None)
            if kinds and kinds[b] == "periodic":
                axp.plot(v[seg], per[seg], color=color, lw=1.8 if st else 1.0, ls="-" if st else "--")
            elif ang is not None:
                a = np.degrees(ang[seg])
                a[1:][np.abs(np.diff(a, axis=0)) > 180.0] = np.nan  # no line across the +-180 deg wrap
                for j in range(a.shape[1]):
                    ax2.plot(v[seg], a[:, j], color=color, lw=1.4 if st else 0.8, ls="-" if st else "--")
    for n, (s, b) in enumerate(notes, start=1):
        marker, short = _MARKS.get(s["type"], ("*", s["type"]))
        x = s[param] * factor
        amp = s.get("amplitude_m")
        y = amp if amp is not None else float(ds.amplitude.values[b][int(s.get("index", 0))])
        y = 0.0 if not y > _ZERO_WHIRL else 1e3 * y
        ax.plot([x], [y], marker, color="k", ms=7, mfc="none")
        ax.annotate(f"{short}{n}", (x, y), textcoords="offset points", xytext=(4, 6), fontsize=8)
        for a in axes[1:-1]:
            a.axvline(x, color="0.6", lw=0.6, ls=":")
    ax.set_ylabel("largest whirl radius (mm)")
    if top == 0.0:  # every branch balanced: a zero line, not round-off drawn at 1e-22 mm
        ax.set_ylim(-0.05, 1.0)
        ax.text(0.5, 0.5, "no whirl on these branches (below 1 nm): the balls balance the rotor",
                transform=ax.transAxes, ha="center", va="center", fontsize=8, color="0.35")
    what = " and ".join(w for w, on in (("steady motions", steady), ("whirl orbits", orbits)) if on)
    ax.set_title(f"{what} against {param}: solid stable, dashed unstable", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    if ax2 is not None:
        ax2.set_ylabel("ball angles (deg)")
        ax2.set_ylim(-185, 185)
        ax2.set_yticks([-180, -90, 0, 90, 180])
    if axp is not None:
        axp.set_ylabel("orbit period (s)\n(co-rotating frame)")
    for a in axes[1:-1]:
        a.grid(alpha=0.3)
        a.sharex(ax)
    axes[-2].set_xlabel(f"{param} ({unit})")
    text.axis("off")
    lines = [f"{_MARKS.get(s['type'], ('', s['type']))[1]}{n}: {s['description']}" for n, (s, _) in
             enumerate(notes, start=1)] or ["no fold, Hopf or branch point in this range"]
    text.text(0.0, 1.0, "\n".join(lines), va="top", ha="left", fontsize=7.5, wrap=True)
    return fig


#: How each curve type is drawn: legend name, colour, line style.
_CURVE_STYLES = {"hopf": ("Hopf curve", "k", "-"), "fold": ("fold curve", "tab:blue", "--"),
                 "floquet-boundary": ("Floquet stability boundary of the balanced state", "tab:purple", "-")}


def two_parameter_figure(ds: xarray.Dataset) -> Figure:
    """Draw the fold and Hopf curves over today's grid stability chart.

    Parameters
    ----------
    ds : xarray.Dataset
        With ``curve_value`` (curve, curve_point, 2) and, from the ``continuation`` analysis,
        ``chart_stable`` / ``chart_exists`` (chart_value, chart_speed).

    Returns
    -------
    matplotlib.figure.Figure
        Grid cells: the steady motion of the chart stable (green), unstable (red), none (white);
        Hopf curves solid black, fold curves dashed blue, the balanced state's Floquet stability
        boundaries on anisotropic supports solid purple, with their branch's label; thin grey
        where the point does not change the branch's stability.
    """
    from matplotlib.figure import Figure

    p1, p2 = (str(x) for x in ds.curve_parameter.values)
    u1, u2 = (str(x).strip() for x in ds.curve_value.attrs.get("units", ",").split(","))
    f1, s1 = _shown(u1)
    f2, s2 = _shown(u2)
    fig = Figure(figsize=(7.5, 4.6), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    if "chart_stable" in ds:
        st = np.where(ds.chart_exists.values, ds.chart_stable.values.astype(float), np.nan)
        ax.pcolormesh(ds.chart_speed.values * f1, ds.chart_value.values * f2, st, shading="nearest", cmap="RdYlGn",
                      vmin=0, vmax=1, alpha=0.55)
    seen = set()
    for c in range(ds.sizes["curve"]):
        kind = str(ds.curve_type.values[c])
        edge = bool(ds.curve_boundary.values[c]) if "curve_boundary" in ds.coords else True
        v = ds.curve_value.values[c]
        keep = np.isfinite(v[:, 0])
        name, color, ls = _CURVE_STYLES.get(kind, (kind, "k", "-"))
        label = f"{name} ({ds.curve_label.values[c]})" + ("" if edge else ", no stability change")
        ax.plot(v[keep, 0] * f1, v[keep, 1] * f2, color=color if edge else "0.45", ls=ls,
                lw=1.8 if edge else 0.9, label=label if label not in seen else None)
        seen.add(label)
    ax.set_xlabel(f"{p1} ({s1})")
    ax.set_ylabel(f"{p2} ({s2})")
    floquet = "floquet-boundary" in {str(k) for k in ds.curve_type.values}
    ax.set_title("stability chart as curves: grid = " + ("the balanced state's Floquet chart (green: stable),\n"
                 "lines = its continued stability boundaries" if floquet else "today's chart (green: the steady "
                 "motion is stable),\nlines = continued Hopf and fold points"), fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def continuation_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``continuation`` result: ``<name>-bifurcation`` and, with a second
    parameter, ``<name>-curves``."""
    out = {f"{name}-bifurcation": bifurcation_figure(ds)} if ds.sizes.get("branch") else {}
    if "curve_value" in ds:
        out[f"{name}-curves"] = two_parameter_figure(ds)
    return out
