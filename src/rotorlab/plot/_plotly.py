"""The interactive twin of a matplotlib figure: the same data as a Plotly figure (a JSON dict).

The report shows the figures people explore rather than read (Campbell diagrams, bifurcation
diagrams, basin maps, sweep results) as Plotly figures, zoomable, with the values under the
pointer and legend entries that hide their curves; the PNG of the same figure is still written
for papers. The interactive figure is read off the drawn matplotlib figure, so the two show the
same curves, colours, labels and legends and no figure is written twice.

What is carried over: the axes (position, labels, title, limits, log scales), lines (with their
colour, style, width, markers and legend label), horizontal and vertical reference lines, filled
areas and spans, scatter points, colour meshes (``pcolormesh``, e.g. a basin map: each cell's
value under the pointer is named by the legend entry of its colour), text annotations, and
legend entries made of patches. What is not (images, 3-D axes) is left out of the
interactive figure and stays in the PNG.

Plotly itself is not imported: the result is the plain ``{"data": [...], "layout": {...}}``
dict that ``Plotly.newPlot`` takes (the report inlines plotly.js once, see
:func:`plotly_script`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["to_plotly", "plotly_script"]

_DASH = {"-": "solid", "--": "dash", ":": "dot", "-.": "dashdot", "solid": "solid", "dashed": "dash",
         "dotted": "dot", "dashdot": "dashdot"}
_SYMBOL = {"o": "circle", "s": "square", "D": "diamond", "d": "diamond", "^": "triangle-up",
           "v": "triangle-down", "x": "x", "+": "cross", "*": "star", ".": "circle", "p": "pentagon"}
_PX_PER_IN = 96


def _rgba(color: Any, alpha: float | None = None) -> str:
    from matplotlib.colors import to_rgba

    r, g, b, a = to_rgba(color)
    a = a if alpha is None else alpha
    return f"rgba({round(255 * r)},{round(255 * g)},{round(255 * b)},{a:.3g})"


def _values(a: Any) -> list:
    """Finite floats as floats, the rest as None (a gap in a Plotly line)."""
    arr = np.ma.filled(np.ma.asarray(a, dtype=float), np.nan).ravel()
    return [float(v) if np.isfinite(v) else None for v in arr]


def _label(artist: Any) -> str | None:
    text = artist.get_label()
    return None if not text or text.startswith("_") else str(text)


def _line(line: Any, ax: Any, axis: dict[str, str], x: Any = None, y: Any = None) -> dict | None:
    """A Line2D in data coordinates as a scatter trace (its data, or ``x``, ``y``)."""
    if x is None:
        x, y = line.get_xdata(orig=False), line.get_ydata(orig=False)
    if len(x) == 0:
        return None
    style = _DASH.get(str(line.get_linestyle()), "solid")
    marker = str(line.get_marker())
    mode = ("lines" if line.get_linestyle() not in ("None", "", " ", "none") else "") + (
        "+markers" if marker not in ("None", "", " ", "none") else "")
    mode = mode.strip("+") or "lines"
    name = _label(line)
    trace = {"type": "scatter", "x": _values(x), "y": _values(y), "mode": mode, **axis,
             "line": {"color": _rgba(line.get_color(), line.get_alpha()), "dash": style,
                      "width": float(line.get_linewidth())},
             "name": name or (line.get_gid() or ""), "showlegend": bool(name and ax.get_legend()),
             "legendgroup": name or None}
    if "markers" in mode:
        face = line.get_markerfacecolor()
        trace["marker"] = {"symbol": _SYMBOL.get(marker, "circle") + ("-open" if face in ("none", "None") else ""),
                           "size": float(line.get_markersize()),
                           "color": _rgba(line.get_markeredgecolor() if face in ("none", "None") else face)}
    return trace


def _reference_line(line: Any, ax: Any, axis: dict[str, str]) -> dict | None:
    """axhline / axvline (one coordinate in axes fraction) as a Plotly shape."""
    x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    style = {"color": _rgba(line.get_color(), line.get_alpha()), "width": float(line.get_linewidth()),
             "dash": _DASH.get(str(line.get_linestyle()), "solid")}
    if line.get_transform() == ax.get_yaxis_transform():  # horizontal: x in axes fraction
        return {"type": "line", "xref": f"{axis['xaxis']} domain", "yref": axis["yaxis"], "x0": float(x[0]),
                "x1": float(x[-1]), "y0": float(y[0]), "y1": float(y[-1]), "line": style}
    if line.get_transform() == ax.get_xaxis_transform():  # vertical
        return {"type": "line", "xref": axis["xaxis"], "yref": f"{axis['yaxis']} domain", "x0": float(x[0]),
                "x1": float(x[-1]), "y0": float(y[0]), "y1": float(y[-1]), "line": style}
    return None


def _mesh(mesh: Any, axis: dict[str, str], names: dict[str, str]) -> dict:
    """A QuadMesh (pcolormesh) as a heatmap with the mesh's own colours; the value under the
    pointer is named by the legend entry of its colour where there is one."""
    coords = np.asarray(mesh.get_coordinates())  # (ny + 1, nx + 1, 2) cell corners
    z = np.ma.filled(np.ma.asarray(mesh.get_array(), dtype=float), np.nan).reshape(
        coords.shape[0] - 1, coords.shape[1] - 1)
    xs = 0.5 * (coords[0, 1:, 0] + coords[0, :-1, 0])
    ys = 0.5 * (coords[1:, 0, 1] + coords[:-1, 0, 1])
    lo, hi = float(mesh.norm.vmin), float(mesh.norm.vmax)
    values = np.unique(z[np.isfinite(z)])
    stops = np.linspace(lo, hi, 65) if values.size > 64 else values
    span = (hi - lo) or 1.0
    scale, text = [], None
    for v in stops:
        f = min(max((v - lo) / span, 0.0), 1.0)
        scale.append([f, _rgba(mesh.to_rgba(np.array([v]))[0])])
    if values.size <= 64:  # categorical: one colour per value, steps between them
        scale = [[0.0, scale[0][1]]] + [s for i, s in enumerate(scale) for s in
                                         ([[max(scale[i][0] - 1e-9, 0.0), scale[i - 1][1]], s] if i else [])]
        scale.append([1.0, scale[-1][1]])
        named = {v: names.get(_rgba(mesh.to_rgba(np.array([v]))[0])) for v in values}
        if all(named.values()):
            text = [[named.get(v, "") if np.isfinite(v) else "" for v in row] for row in z]
    trace = {"type": "heatmap", "x": _values(xs), "y": _values(ys), "z": [_values(r) for r in z],
             "zmin": lo, "zmax": hi, "colorscale": scale, "showscale": text is None and values.size > 64, **axis}
    if text is not None:
        trace.update(text=text, hovertemplate="x %{x}<br>y %{y}<br>%{text}<extra></extra>")
    return trace


def _collection(coll: Any, axis: dict[str, str]) -> list[dict]:
    """Scatter points (PathCollection) and filled areas (PolyCollection)."""
    from matplotlib.collections import PathCollection, PolyCollection

    if isinstance(coll, PathCollection):
        xy = np.asarray(coll.get_offsets())
        if xy.size == 0:
            return []
        face = coll.get_facecolors()
        arr = coll.get_array()
        colors = [_rgba(c) for c in (coll.to_rgba(arr) if arr is not None else face)]
        if len(colors) == 1:
            colors = colors[0]
        return [{"type": "scatter", "mode": "markers", "x": _values(xy[:, 0]), "y": _values(xy[:, 1]),
                 "marker": {"color": colors, "size": 5}, "name": _label(coll) or "", "showlegend": False, **axis}]
    if isinstance(coll, PolyCollection):
        out = []
        face = coll.get_facecolors()
        for k, path in enumerate(coll.get_paths()):
            v = path.vertices
            out.append({"type": "scatter", "x": _values(v[:, 0]), "y": _values(v[:, 1]), "fill": "toself",
                        "mode": "lines", "line": {"width": 0},
                        "fillcolor": _rgba(face[k % len(face)]) if len(face) else "rgba(0,0,0,0.2)",
                        "name": _label(coll) or "", "showlegend": bool(_label(coll) and k == 0), **axis})
        return out
    return []


def _patch_shapes(ax: Any, axis: dict[str, str]) -> list[dict]:
    """axvspan / axhspan rectangles (Polygon patches) as shapes."""
    from matplotlib.patches import Polygon, Rectangle

    shapes = []
    for p in ax.patches:
        if not isinstance(p, (Polygon, Rectangle)) or not p.get_visible():
            continue
        verts = p.get_transform().transform(p.get_path().vertices)
        data = ax.transData.inverted().transform(verts)
        vertical = p.get_transform().contains_branch_seperately(ax.transData)
        xref = axis["xaxis"] if vertical[0] else f"{axis['xaxis']} domain"
        yref = axis["yaxis"] if vertical[1] else f"{axis['yaxis']} domain"
        frac = ax.transAxes.inverted().transform(verts)
        xs = data[:, 0] if vertical[0] else frac[:, 0]
        ys = data[:, 1] if vertical[1] else frac[:, 1]
        shapes.append({"type": "rect", "xref": xref, "yref": yref, "x0": float(xs.min()), "x1": float(xs.max()),
                       "y0": float(ys.min()), "y1": float(ys.max()), "line": {"width": 0},
                       "fillcolor": _rgba(p.get_facecolor()), "layer": "below"})
    return shapes


def _texts(ax: Any, axis: dict[str, str]) -> list[dict]:
    out = []
    for t in ax.texts:
        if not t.get_visible() or not t.get_text().strip():
            continue
        xy = getattr(t, "xy", None)
        coords = getattr(t, "xycoords", None)
        refs = {"data": ("xaxis", ""), "axes fraction": ("xaxis", " domain")}
        pair = coords if isinstance(coords, tuple) else (coords, coords)
        if xy is not None and all(isinstance(c, str) and c in refs for c in pair):
            x, y = xy
            xref = axis["xaxis"] + refs[pair[0]][1]
            yref = axis["yaxis"] + refs[pair[1]][1]
        elif t.get_transform() == ax.transAxes:
            (x, y), xref, yref = t.get_position(), f"{axis['xaxis']} domain", f"{axis['yaxis']} domain"
        elif t.get_transform() == ax.transData:
            (x, y), xref, yref = t.get_position(), axis["xaxis"], axis["yaxis"]
        else:
            continue
        text = t.get_text().replace("\n", "<br>")
        out.append({"x": float(x), "y": float(y), "xref": xref, "yref": yref, "text": text,
                    "showarrow": False, "font": {"size": 10, "color": _rgba(t.get_color())},
                    "textangle": -float(t.get_rotation()),
                    "xanchor": {"center": "center", "right": "right"}.get(t.get_ha(), "left"),
                    "yanchor": {"center": "middle", "top": "top", "baseline": "bottom"}.get(t.get_va(), "bottom")})
    return out


def _legend_entries(ax: Any, axis: dict[str, str], named: set[str]) -> tuple[list[dict], dict[str, str]]:
    """Legend entries without a curve of their own (patches, proxy lines): a legend-only trace
    each, and the label of each patch colour (to name a mesh's values)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    legend = ax.get_legend()
    if legend is None:
        return [], {}
    traces, names = [], {}
    for handle, text in zip(legend.legend_handles, legend.get_texts()):
        label = text.get_text()
        if isinstance(handle, Patch):
            color = _rgba(handle.get_facecolor())
            names[color] = label.rsplit(" (", 1)[0] if label.endswith("%)") else label
            marker = {"symbol": "square", "size": 12, "color": color}
            traces.append({"type": "scatter", "x": [None], "y": [None], "mode": "markers", "name": label,
                           "marker": marker, "showlegend": True, **axis})
        elif isinstance(handle, Line2D) and label not in named:
            trace = _line(handle, ax, axis, [np.nan], [np.nan])
            traces.append({**trace, "name": label, "showlegend": True})
    return traces, names


def _axis(ax: Any, which: str) -> dict:
    scale = ax.get_xscale() if which == "x" else ax.get_yscale()
    lo, hi = ax.get_xlim() if which == "x" else ax.get_ylim()
    log = scale == "log"
    rng = [float(np.log10(lo)), float(np.log10(hi))] if log else [float(lo), float(hi)]
    label = ax.get_xlabel() if which == "x" else ax.get_ylabel()
    return {"type": "log" if log else "linear", "range": rng, "title": {"text": label.replace("\n", "<br>")},
            "showgrid": True, "zeroline": False, "automargin": True}


def to_plotly(fig: Figure) -> dict[str, Any]:
    """Return the Plotly twin of a drawn matplotlib figure.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Drawn (``savefig`` or ``canvas.draw`` done), so that its layout is final.

    Returns
    -------
    dict
        ``{"data": [...], "layout": {...}}``, JSON-serialisable, for ``Plotly.newPlot``.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> fig = Figure(); ax = fig.subplots()
    >>> _ = ax.plot([0, 1], [2, 3], label="a"); _ = ax.legend(); _ = ax.set_xlabel("t (s)")
    >>> out = to_plotly(fig)
    >>> out["data"][0]["name"], out["data"][0]["y"], out["layout"]["xaxis"]["title"]["text"]
    ('a', [2.0, 3.0], 't (s)')
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import QuadMesh

    if fig.canvas is None or not hasattr(fig.canvas, "get_renderer"):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    data, shapes, notes = [], [], []
    width, height = fig.get_size_inches() * _PX_PER_IN
    layout: dict[str, Any] = {"width": round(float(width) * 1.25), "height": round(float(height) * 1.25),
                              "margin": {"l": 60, "r": 20, "t": 40, "b": 50}, "hovermode": "closest",
                              "plot_bgcolor": "white", "legend": {"font": {"size": 10}}}
    axes = [a for a in fig.axes if a.axison and a.get_visible() and a.name == "rectilinear"]
    for n, ax in enumerate(axes, start=1):
        suffix = "" if n == 1 else str(n)
        axis = {"xaxis": f"x{suffix}", "yaxis": f"y{suffix}"}
        pos = ax.get_position()
        layout[f"xaxis{suffix}"] = {**_axis(ax, "x"), "domain": [float(pos.x0), float(pos.x1)],
                                    "anchor": axis["yaxis"], "gridcolor": "#e5e5e5", "linecolor": "#444",
                                    "mirror": True, "showline": True}
        layout[f"yaxis{suffix}"] = {**_axis(ax, "y"), "domain": [float(pos.y0), float(pos.y1)],
                                    "anchor": axis["xaxis"], "gridcolor": "#e5e5e5", "linecolor": "#444",
                                    "mirror": True, "showline": True}
        names = {}
        if ax.get_legend() is not None:
            names = _legend_entries(ax, axis, set())[1]
        first = len(data)
        for c in ax.collections:
            if not c.get_visible():
                continue
            if isinstance(c, QuadMesh):
                data.append(_mesh(c, axis, names))
            else:
                data += _collection(c, axis)
        for line in ax.lines:
            if not line.get_visible():
                continue
            if line.get_transform() in (ax.get_yaxis_transform(), ax.get_xaxis_transform()):
                shape = _reference_line(line, ax, axis)
                if shape is not None:
                    shapes.append(shape)
                continue
            trace = _line(line, ax, axis)
            if trace is not None:
                data.append(trace)
        named = {t["name"] for t in data[first:] if t.get("showlegend")}
        data += _legend_entries(ax, axis, named)[0]
        shapes += _patch_shapes(ax, axis)
        notes += _texts(ax, axis)
        title = ax.get_title()
        if title:
            notes.append({"text": f"<b>{title}</b>".replace("\n", "<br>"), "xref": f"{axis['xaxis']} domain",
                          "yref": f"{axis['yaxis']} domain", "x": 0.5, "y": 1.0, "yanchor": "bottom",
                          "xanchor": "center", "showarrow": False, "font": {"size": 12}})
    legends = [a.get_legend() for a in axes if a.get_legend() is not None]
    if legends:  # where the (first) matplotlib legend is: inside the axes or beside them
        box = legends[0].get_window_extent().transformed(fig.transFigure.inverted())
        layout["legend"].update(x=float(box.x0), y=float(box.y1), xanchor="left", yanchor="top",
                                bgcolor="rgba(255,255,255,0.8)")
    seen = set()
    for trace in data:  # one legend entry per label
        if trace.get("showlegend"):
            if trace["name"] in seen:
                trace["showlegend"] = False
            seen.add(trace["name"])
    layout["shapes"] = shapes
    layout["annotations"] = notes
    layout["showlegend"] = bool(seen)
    return {"data": data, "layout": layout}


def plotly_script() -> str:
    """The plotly.js bundle (minified), inlined once in a report that shows interactive figures."""
    from plotly.offline import get_plotlyjs

    return get_plotlyjs()
