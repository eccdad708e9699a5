"""Report sections of the basin analyses: fractions with their convergence, the working point of
the toroidal ball, and the comparison of basins that differ in one parameter (seed 004's
friction conclusion tested with our numbers)."""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray

__all__ = ["basin_section", "basin_comparison_section", "basin_table_rows"]

_TableFn = Callable[..., str]


def _e(text: Any) -> str:
    return html.escape(str(text))


def _working_point_html(ds: xarray.Dataset, table: _TableFn) -> str:
    psi_band = [float(v) for v in ds.psi_band.values]
    alpha_band = [float(v) for v in ds.alpha_band.values]
    k = float(ds.attrs.get("rolling_friction", math.nan))
    rows = [
        ("ψ (ring angle)", f"{float(ds.psi):.6f}", f"{psi_band[0]:.6f} … {psi_band[1]:.6f}", "3.14156"),
        ("α (cross-section angle)", f"{float(ds.alpha):.6f}", f"{alpha_band[0]:.6f} … {alpha_band[1]:.6f}", "1.56825"),
    ]  # fmt: skip
    inside = (psi_band[0] <= 3.14156 <= psi_band[1]) and (alpha_band[0] <= 1.56825 <= alpha_band[1])
    verdict = ("inside the friction band: a ball at rest there stays at rest, so the paper's point is a "
               "working position of this model" if inside else
               "outside the friction band of this model")  # fmt: skip
    return "".join([
        f"<p>Working equilibrium (frictionless) and the band in which rolling friction k = {k:g} m holds a "
        f"stopped ball ({_e(ds.attrs.get('form', ''))} form). The paper's printed point is {verdict}.</p>",
        table(("coordinate", "equilibrium (rad)", "friction band (rad)", "seed 004 (rad)"), rows, numeric={1, 3}),
        f"<p>Specific normal force N = {float(ds.normal):.5g} m/s²; small-oscillation frequencies "
        f"{float(ds.frequency[0]):.4g} rad/s (ring) and {float(ds.frequency[1]):.4g} rad/s (cross-section).</p>",
    ])  # fmt: skip


def basin_section(ds: xarray.Dataset, rows: Sequence[Mapping[str, Any]] | None, table: _TableFn) -> str:
    """Return the HTML of one basin or working-point result (tables only; figures are added by
    the report).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.run_basin_analysis`.
    rows : list of dict, optional
        :func:`rotorlab.analyses.basin_rows` of ``ds`` (computed if None).
    table : callable
        ``table(header, rows, numeric=...)`` of the report.
    """
    from rotorlab.analyses._basin import basin_rows
    from rotorlab.analyses._verdict import basin_verdict

    if ds.attrs.get("analysis") == "working-point":
        return _working_point_html(ds, table)
    rows = list(rows) if rows is not None else basin_rows(ds)
    n = rows[0]["n"] if rows else 0
    horizons = ds["horizon"].values
    t_end = float(horizons[-1])
    where = (f"{n} random starts (seed {ds.attrs.get('seed')}, Wilson intervals at "
             f"{float(ds.attrs.get('confidence', 0.95)):.0%})" if ds.attrs.get("mode") == "random"
             else f"{n} random points (seed {ds.attrs.get('seed')})" if ds.attrs.get("mode") == "sample"
             else f"a grid of {n} starts")  # fmt: skip
    if "x" in ds.attrs:
        over = f"{ds.attrs.get('x')} × {ds.attrs.get('y')}"
    elif ds.attrs.get("mode") == "sample":  # a sweep's sample: the drawn coordinates
        over = " × ".join(str(k) for k in ds.coords if ds[k].dims == ("sample",) and k != "sample")
    else:  # a sweep's grid: one dim per swept quantity
        over = " × ".join(d for d in ds["label"].dims if d != "horizon")
    fixed = ", ".join(f"{k[6:]} = {float(v):g}" for k, v in ds.attrs.items() if k.startswith("fixed_"))
    half = rows[0]["horizon_half_s"] if rows else t_end
    settled = basin_verdict(ds)["sentence"]
    how = f" ({ds.attrs['horizon_rule']})" if ds.attrs.get("horizon_rule") else ""
    header = ("regime", f"% at {t_end:g} s", "starts", "CI (%)", f"% at {half:g} s",
              "label kept since, median / max (s)")  # fmt: skip
    return "".join([
        f"<p>Regimes of {where} over {_e(over)}"
        + (f" ({_e(fixed)})" if fixed else "") + f", classified every {float(horizons[0]):g} s up to "
        f"{t_end:g} s{_e(how)}.</p>",
        table(header, basin_table_rows(rows), numeric={1, 2, 4}),
        f"<p>{_e(settled)}</p>",
    ])  # fmt: skip


def basin_comparison_section(results: Mapping[str, xarray.Dataset], table: _TableFn) -> str:
    """Return the HTML comparing basins that differ in one fixed parameter ("" if there are none).

    For ``strautmanis-torus`` this tests seed 004's conclusion (larger rolling friction makes the
    working regime more likely) at every horizon; the sentence is computed, not written in.
    """
    from rotorlab.analyses._basin import compare_basins

    cmp = compare_basins(results)
    if cmp is None:
        return ""
    header = ["simulated time (s)", *(f"{cmp['parameter']} = {e['value']:g}" for e in cmp["entries"]),
              f"larger {cmp['parameter']} gives more {cmp['label']}"]  # fmt: skip
    rows = []
    for j, t in enumerate(cmp["horizons_s"]):
        win = cmp["larger_wins"][j]
        rows.append([f"{t:g}", *(f"{100.0 * e['fractions'][j]:.1f} %" for e in cmp["entries"]),
                     "yes" if win is True else "no" if win is False else "mixed"])  # fmt: skip
    return "".join([
        f"<h2>Comparison: {_e(cmp['label'])} fraction against {_e(cmp['parameter'])}</h2>",
        f"<p>{_e(cmp['verdict'])}</p>",
        table(header, rows, numeric=set(range(len(header) - 1))),
    ])


def _percent(value: float | None) -> str:
    return "" if value is None else f"{100.0 * value:.1f}"


def basin_table_rows(rows: Sequence[Mapping[str, Any]]) -> list[list[str]]:
    """Rows of strings for a printed or HTML basin table (regime, %, count, CI, half, since)."""
    out = []
    for r in rows:
        ci = "" if r["ci_low"] is None else f"{_percent(r['ci_low'])} - {_percent(r['ci_high'])}"
        since = "" if r["label_since_median_s"] is None else (
            f"{r['label_since_median_s']:.3g} / {r['label_since_max_s']:.3g}")
        out.append([r["regime"], _percent(r["fraction"]), str(r["count"]), ci, _percent(r["fraction_half"]), since])
    return out
