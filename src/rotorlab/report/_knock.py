"""Presentation of the ``machine-knock`` analysis: does the machine strike its housing during the
run-up, how likely, how hard, and which ball damping avoids it (rows of
:func:`rotorlab.analyses._knock.knock_rows`). The figure is drawn by :mod:`rotorlab.plot._knock`."""

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


def knock_figures(ds: xarray.Dataset, name: str) -> dict[str, Figure]:
    """The figures of one ``machine-knock`` result, by file stem (:mod:`rotorlab.plot._knock`)."""
    from rotorlab.plot._knock import knock_figure

    return {f"{name}_knock": knock_figure(ds)}


def _dampings(values: Sequence[float]) -> str:
    return ", ".join(f"{d:.3g}" for d in values) + " N m s/rad"


def _verdict(ds: xarray.Dataset, rows: Rows) -> str:
    """The choice first (which ball damping keeps the run-up off the housing, with the confidence
    the number of starts gives), then how often and how hard the others strike, then the run
    without balls for reference."""
    a = ds.attrs
    done = [r for r in rows if r["contact_probability"] is not None]
    if not done:
        return "Every run failed: no contact probability to report (see the failed runs column)."
    clear = [r for r in done if r["contact_probability"] == 0.0]
    hit = [r for r in done if r["contact_probability"] > 0.0]
    if clear:
        high = max(r["probability_high"] for r in clear)
        finished = sorted({r["runs"] - r["failed"] for r in clear})  # per damping: its runs that did not fail
        starts = str(finished[0]) if len(finished) == 1 else f"{finished[0]} to {finished[-1]}"
        out = (f"Choose a ball damping of {_dampings([r['ball_damping'] for r in clear])}: "
               "no run-up touched the housing "
               f"there (0 of {starts} random ball starts; contact probability below "
               f"{_pct(high)} with 95 % confidence{'' if high < 0.05 else ', more starts narrow this'}).")  # fmt: skip
    else:
        best = min(done, key=lambda r: (r["contact_probability"], r["largest_impulse"] or 0.0))
        out = ("Every ball damping tried lets some run-ups touch the housing; "
               f"the fewest at {best['ball_damping']:.3g} "
               f"N m s/rad ({_pct(best['contact_probability'])}, largest impulse {_imp(best['largest_impulse'])}).")
    if hit:
        worst = max(hit, key=lambda r: r["largest_impulse"] or 0.0)
        lo, hi = (_pct(f(r["contact_probability"] for r in hit)) for f in (min, max))
        out += (f" At {_dampings([r['ball_damping'] for r in hit])} it is touched in "
                f"{lo if lo == hi else f'{lo} to {hi}'} of the run-ups, hardest at {worst['ball_damping']:.3g} "
                f"N m s/rad (largest impulse {_imp(worst['largest_impulse'])}).")  # fmt: skip
    nb = a.get("no_balls_impacts")
    if nb is None or not np.isfinite(nb):
        out += " The run-up without balls failed."
    elif nb == 0:
        out += " Without balls the run-up stays clear" + (": the balls cause the contact." if hit else ".")
    else:
        out += f" Without balls it strikes {int(nb)} times (largest impulse {_imp(a.get('no_balls_peak_impulse'))})."
    return out


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
    return Findings(_verdict(ds, rows), numbers + tuple(_ends(ds, r) for r in rows if "outcomes" in r))


def _ends(ds: xarray.Dataset, r: Mapping[str, Any]) -> str:
    """Where the run-ups of one damping ended: balanced (share, Wilson interval), the other
    outcomes, and the run-up that would settle those not settled."""
    from rotorlab.analyses._verdict import MARGIN, round_up_horizon

    n = sum(k for o, k in r["outcomes"].items() if o != "failed")
    text = (f"ball damping {r['ball_damping']:.3g} N m s/rad: balanced at the end in {r['outcomes'].get('balanced', 0)} "
            f"of {n} run-ups")
    if r["balanced_share"] is not None:
        text += f" ({_pct(r['balanced_share'])}, Wilson 95 % interval {_pct(r['balanced_low'])} to {_pct(r['balanced_high'])})"
    others = [f"{k} {o}" for o, k in r["outcomes"].items() if o not in ("balanced", "failed")]
    text += ("; " + ", ".join(others)) if others else ""
    if r["not_settled"] and r["settle_by_s"] is not None:
        text += (f"; the {r['not_settled']} not settled (still converging towards balance) are estimated to balance by "
                 f"{r['settle_by_s']:.3g} s: {float(ds.attrs['t_end']):.3g} s is too short for their verdict, "
                 f"{round_up_horizon(MARGIN * r['settle_by_s']):g} s would do")
    elif r["not_settled"]:
        text += (f"; the {r['not_settled']} not settled were still spinning up at {float(ds.attrs['t_end']):.3g} s: "
                 "too short for their verdict, a longer run-up is needed")
    return text


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
