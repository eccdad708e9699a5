"""Report sections of the steady-motion analyses (``steady``, ``stability-chart``, ``verify``,
``run-up``) and the table of the seeds' typos and contradicted conclusions.

Values are shown in the units an engineer reads (rpm, degrees, mm) with the unit in every column
header; the NetCDF files next to the report keep SI.
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.analyses._steady import STEADY_ANALYSES, steady_rows

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["STEADY_ANALYSES", "STEADY_FIGURES", "steady_figures", "steady_section", "seed_notes_section"]

#: Figure of each steady-motion analysis type: (file-stem suffix, plot function name).
STEADY_FIGURES = {
    "stability-chart": ("chart", "stability_chart_figure"),
    "verify": ("fractions", "verify_figure"),
    "run-up": ("run-up", "run_up_figure"),
}
_METHODS = ("hamilton", "averaged", "exact")
_METHOD_NAMES = {"hamilton": "seed 003 (least H~*)", "averaged": "seed 002 (averaged)", "exact": "exact"}
_SEEDS = {"002": "Seed 002 (Zhakash et al. 2024)", "003": "Seed 003 (Filimonikhin & Filimonikhina)"}
_NUM = ' class="num"'


def _e(value: Any) -> str:
    return html.escape(str(value), quote=True)


def _table(header: list[str], rows: list[list[Any]], numeric: set[int] = frozenset()) -> str:
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td{_NUM if j in numeric else ""}>{_e(c)}</td>' for j, c in enumerate(r)) + "</tr>"
        for r in rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _angles(values: list[float], spec: str) -> str:
    return "(" + ", ".join(format(a, spec) for a in values) + ")"


def _f(value: float | None, spec: str, scale: float = 1.0) -> str:
    return "–" if value is None or not math.isfinite(value) else format(value * scale, spec)


def steady_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """Return the figure of a steady-motion result by file stem (``<name>_<kind>``; none for steady).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.run_steady_analysis`.
    name : str
        Analysis name.
    """
    import rotorlab.plot as plot

    entry = STEADY_FIGURES.get(ds.attrs.get("analysis", ""))
    if entry is None:
        return {}
    suffix, function = entry
    return {f"{name}_{suffix}": getattr(plot, function)(ds)}


def _steady_html(ds: xarray.Dataset, rows: list[dict[str, Any]]) -> str:
    om = float(ds.attrs["spin_speed"])
    parts = [f"<p>Speed {om * _RPM:.6g} rpm = {om:.6g} rad/s, ω/p = {float(ds.attrs['speed_ratio']):.4g}; "
             f"unbalance M1 e = {float(ds.attrs['imbalance']):.4g} kg·m, capacity Σ m_i l_i = "
             f"{float(ds.attrs['capacity']):.4g} kg·m.</p>"]  # fmt: skip
    header = ["motion", "exists", "ball angles (deg)", "deflection (mm)", "phase (deg)", "H~* (J)",
              *(_METHOD_NAMES[m] for m in _METHODS), "growth rate (1/s)"]  # fmt: skip
    body = []
    for r in rows:
        angles = "–" if r["ball_angles_deg"] is None else _angles(r["ball_angles_deg"], ".2f")
        body.append([r["motion"], "yes" if r["exists"] else "no", angles, _f(r["amplitude"], ".4g", 1e3),
                     _f(r["phase_deg"], ".1f"), _f(r["h_tilde"], ".5g"),
                     *(r[f"verdict_{m}"] for m in _METHODS), _f(r["growth_rate"], ".3g")])  # fmt: skip
    parts.append(_table(header, body, numeric={3, 4, 5, 9}))
    stable = [r["motion"] for r in rows if r["verdict_exact"] == "stable"]
    parts.append(f"<p>Exactly stable: {_e(', '.join(stable) or 'none')}.</p>")
    messages = [m for m in str(ds.attrs.get("disagreements", "")).split("\n") if m]
    if messages:
        parts.append("<h3>Disagreements between the methods</h3><ul>"
                     + "".join(f"<li>{_e(m)}</li>" for m in messages) + "</ul>")  # fmt: skip
    else:
        parts.append('<p class="muted">The three methods agree on every motion.</p>')
    return "\n".join(parts)


def _chart_html(ds: xarray.Dataset, rows: list[dict[str, Any]]) -> str:
    param = ds.attrs.get("parameter")
    speed = ds.speed.values
    text = f"<p>{speed.size} speeds from {speed[0] * _RPM:.5g} to {speed[-1] * _RPM:.5g} rpm"
    if param:
        vals, unit = ds[param].values, ds[param].attrs.get("units", "")
        text += f", {vals.size} values of {_e(param)} from {vals[0]:.4g} to {vals[-1]:.4g} {_e(unit)}"
    parts = [text + ". Speed intervals (grid speeds) in which each motion is stable:</p>"]
    header = ["method", "motion", *([f"{param} ({ds[param].attrs.get('units', '')})"] if param else []),
              "from (rpm)", "to (rpm)", "ω/p from", "ω/p to"]  # fmt: skip
    body = [[_METHOD_NAMES[r["method"]], r["motion"], *([f"{r[param]:.4g}"] if param else []),
             f"{r['start_rpm']:.0f}", f"{r['stop_rpm']:.0f}", f"{r['start_ratio']:.3g}", f"{r['stop_ratio']:.3g}"]
            for r in rows if not param or r["method"] == "exact"]  # fmt: skip
    if param:
        parts[0] = parts[0].replace("each motion is stable:", "each motion is exactly stable:")
    n = len(header)
    parts.append(_table(header, body, numeric=set(range(n - 4, n)) | ({2} if param else set())))
    return "\n".join(parts)


def _verify_html(ds: xarray.Dataset, rows: list[dict[str, Any]]) -> str:
    outcomes = [str(o) for o in ds.outcome.values if any(str(o) in r["fractions"] for r in rows)]
    header = ["speed (rpm)", "ω/p", "starts", "simulated (s)", *(f"{o} (%)" for o in outcomes),
              "exactly stable", *(f"agrees: {_METHOD_NAMES[m]}" for m in _METHODS)]  # fmt: skip
    body = []
    for r in rows:
        body.append([f"{r['speed_rpm']:.0f}", f"{r['speed_ratio']:.3g}", r["starts"], f"{r['t_end']:.3g}",
                     *(f"{100 * r['fractions'].get(o, 0.0):.1f}" for o in outcomes),
                     ", ".join(r["stable"]["exact"]) or "none",
                     *("yes" if r[f"agrees_{m}"] else "NO" for m in _METHODS)])  # fmt: skip
    text = ("<p>Fraction of the starts (balls at rest relative to the rotor, disc on the axis) that end on each "
            "motion: its basin fraction. A start agrees with a method when it ends on a motion the method calls "
            "stable, or stays unsettled where the method predicts no stable motion.</p>")  # fmt: skip
    return text + _table(header, body, numeric=set(range(0, 4 + len(outcomes))))


def _run_up_html(ds: xarray.Dataset, rows: list[dict[str, Any]]) -> str:
    p = float(ds.attrs["critical_speed"])
    speed = ds.speed.values
    text = (f"<p>{_e(ds.attrs.get('speed_profile', ''))} from {speed[0] * _RPM:.5g} rpm (ω/p = {speed[0] / p:.3g}) "
            f"to {speed[-1] * _RPM:.5g} rpm (ω/p = {speed[-1] / p:.3g}), simulated for "
            f"{float(ds.time[-1] - ds.time[0]):.4g} s. "
            "Largest shaft deflection with and without the balancer:</p>")  # fmt: skip
    header = ["start", "start angles (deg)", "peak with balls (mm)", "at (rpm)", "peak without (mm)", "at (rpm)",
              "final with balls (mm)", "final without (mm)", "synchronised", "final motion"]  # fmt: skip
    body = [[r["ic"], _angles(r["initial_ball_angles_deg"], ".1f"),
             _f(r["max_amplitude"], ".4g", 1e3), _f(r["speed_at_max_rpm"], ".0f"),
             _f(r["max_amplitude_without"], ".4g", 1e3), _f(r["speed_at_max_without_rpm"], ".0f"),
             _f(r["final_amplitude"], ".3g", 1e3), _f(r["final_amplitude_without"], ".3g", 1e3),
             "yes" if r["synchronised"] else "no", r["final_motion"]] for r in rows]  # fmt: skip
    return text + _table(header, body, numeric={2, 3, 4, 5, 6, 7})


def steady_section(ds: xarray.Dataset, rows: list[dict[str, Any]] | None = None) -> str:
    """Return the HTML of a steady-motion result (the tables; figures are added by the report).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.run_steady_analysis`.
    rows : list of dict, optional
        :func:`rotorlab.analyses.steady_rows` of ``ds`` (computed when not given).

    Returns
    -------
    str
        ``steady``: the motions table (angles in degrees, deflection in mm, phase, H~*, the three
        verdicts, growth rate) and every disagreement; ``stability-chart``: the stable speed
        intervals; ``verify``: basin fractions and the agreement flags per method; ``run-up``:
        peak deflections with and without the balancer and the synchronisation.
    """
    kind = ds.attrs.get("analysis")
    rows = steady_rows(ds) if rows is None else rows
    regime = ds.attrs.get("regime")
    head = f'<p class="muted">Regime: {_e(regime)}</p>' if regime else ""
    render = {"steady": _steady_html, "stability-chart": _chart_html, "verify": _verify_html,
              "run-up": _run_up_html}[kind]  # fmt: skip
    return head + render(ds, rows)


def seed_notes_section(seeds: Mapping[str, str] | None = None) -> str:
    """Return the HTML tables of :data:`rotorlab.steady.SEED_NOTES`, one per seed.

    Parameters
    ----------
    seeds : mapping of str to str, optional
        Seed number to heading; default seeds 002 and 003.

    Returns
    -------
    str
    """
    from rotorlab.steady import SEED_NOTES

    parts = ["<h2>Seed papers: typos and contradicted conclusions</h2>",
             '<p class="muted">What each seed prints, what holds, and the test that checks it '
             "(rotorlab.steady.SEED_NOTES).</p>"]  # fmt: skip
    for seed, heading in (seeds or _SEEDS).items():
        rows = [[n.where, n.kind, n.printed, n.corrected, n.test] for n in SEED_NOTES if n.seed == seed]
        if rows:
            parts += [f"<h3>{_e(heading)}</h3>", _table(["where", "kind", "printed", "what holds", "test"], rows)]
    return "\n".join(parts)
