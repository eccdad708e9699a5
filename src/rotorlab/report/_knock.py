"""Presentation of the ``machine-knock`` analysis: does the machine strike its housing during the
run-up, how likely, how hard, and which ball damping avoids it (rows of
:func:`rotorlab.analyses._knock.knock_rows`). Figures are built without pyplot."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["knock_figures", "knock_section", "knock_findings", "knock_tables"]

Rows = Sequence[Mapping[str, Any]]


def _pct(v: float | None) -> str:
    return "–" if v is None else f"{100.0 * v:.0f} %"


def _imp(v: float | None) -> str:
    return "–" if v is None else f"{v:.3g} N s"


def _safe(rows: Rows) -> list[float]:
    """The dampings whose whole 95 % interval lies below 5 % contact probability."""
    return [r["ball_damping"] for r in rows if r["probability_high"] is not None and r["probability_high"] < 0.05]


def knock_figure(ds: xarray.Dataset) -> Figure:
    """Contact probability (95 % interval) and the largest impulse against ball damping."""
    from matplotlib.figure import Figure

    d = ds.ball_damping.values
    fig = Figure(figsize=(6.4, 5.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    p = ds.contact_probability.values
    err = np.vstack([p - ds.probability_low.values, ds.probability_high.values - p])
    ax1.errorbar(d, 100.0 * p, yerr=100.0 * err, fmt="o-", capsize=3, color="tab:red")
    ax1.set_ylabel("runs that touch the housing (%)")
    ax1.set_ylim(-2.0, 102.0)
    ax1.set_title(f"{ds.attrs.get('name', 'knock')}: {ds.attrs['starts']} random ball starts, "
                  f"{ds.attrs['gap'] * 1e3:.3g} mm clearance")
    ax2.plot(d, ds.largest_impulse.values, "s-", color="tab:blue", label="with balls: largest of all starts")
    nb = ds.attrs.get("no_balls_peak_impulse")
    if nb is not None and np.isfinite(nb):
        ax2.axhline(nb, color="0.4", ls="--", label="without balls")
    ax2.set_ylabel("largest impact impulse (N s)")
    ax2.set_xlabel("ball damping (N m s/rad)")
    if np.all(d > 0) and d.size > 1 and d.max() / d.min() > 20:
        ax2.set_xscale("log")
    ax2.legend(fontsize="small")
    return fig


def knock_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``machine-knock`` result, by file stem."""
    return {f"{name}_knock": knock_figure(ds)}


def _verdict(ds: xarray.Dataset, rows: Rows) -> str:
    a = ds.attrs
    worst = max(rows, key=lambda r: -1.0 if r["contact_probability"] is None else r["contact_probability"])
    nb = a.get("no_balls_impacts")
    ref = ("without balls the run-up does not touch the housing" if nb == 0 else
           f"without balls it strikes {int(nb)} times (largest impulse {_imp(a.get('no_balls_peak_impulse'))})"
           if nb is not None and np.isfinite(nb) else "the run without balls failed")
    safe = _safe(rows)
    clear = [r["ball_damping"] for r in rows if r["contact_probability"] == 0.0]
    advice = ("no run touched it at ball damping " + ", ".join(f"{d:.3g}" for d in clear) + " N m s/rad"
              if clear else "every ball damping tried lets some run-ups touch it")
    advice += ("; at " + ", ".join(f"{d:.3g}" for d in safe) + " N m s/rad the contact probability is below "
               "5 % with 95 % confidence" if safe else "; no damping tried shows a contact probability below 5 % with 95 % "
                                        "confidence (more starts narrow the interval)")
    return (f"The rotor touches its housing in up to {_pct(worst['contact_probability'])} of the run-ups "
            f"(ball damping {worst['ball_damping']:.3g} N m s/rad); {ref}; {advice}.")


def knock_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the verdict, then one table row per damping."""
    from rotorlab.report._table import table

    body = [[f"{r['ball_damping']:.4g}", _pct(r["contact_probability"]),
             f"{_pct(r['probability_low'])} – {_pct(r['probability_high'])}", _imp(r["largest_impulse"]),
             "–" if r["mean_impacts"] is None else f"{r['mean_impacts']:.3g}", f"{r['failed']} of {r['runs']}"]
            for r in rows]  # fmt: skip
    head = f"<p>{_verdict(ds, rows)}</p>"
    return head + table(["ball damping (N m s/rad)", "touch the housing", "95 % interval",
                         "largest impulse", "impacts per run (mean)", "failed runs"], body, numeric={0, 4})


def knock_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The verdict and, per damping, the probability and the largest impulse."""
    numbers = tuple(f"ball damping {r['ball_damping']:.3g} N m s/rad: contact in {_pct(r['contact_probability'])} "
                    f"of runs, largest impulse {_imp(r['largest_impulse'])}" for r in rows)  # fmt: skip
    return Findings(_verdict(ds, rows), numbers)


def knock_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run``: one per ``machine-knock`` result."""
    from rich.table import Table

    out = []
    for name, ds in results.items():
        t = Table(title=f"{name}: {_verdict(ds, rows[name])}", title_justify="left")
        for col in ("ball damping (N m s/rad)", "touch the housing", "95 % interval", "largest impulse"):
            t.add_column(col, justify="right")
        for r in rows[name]:
            t.add_row(f"{r['ball_damping']:.4g}", _pct(r["contact_probability"]),
                      f"{_pct(r['probability_low'])} – {_pct(r['probability_high'])}", _imp(r["largest_impulse"]))
        out.append(t)
    return out
