"""Report sections of the rotor striking its housing (seed 001): runs, sweeps, reconstructions.

Datasets from :func:`rotorlab.analyses.impact_run` and :func:`rotorlab.analyses.impact_sweep`;
the figures come from :func:`rotorlab.plot.impact_figures`.
"""

from __future__ import annotations

import html
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray

__all__ = ["impact_section", "reconstructions_section", "SWEEP_COLUMNS", "sweep_cells"]


def _e(value: Any) -> str:
    return html.escape(str(value))


def _table(header: list[str], rows: list[list[Any]], numeric: set[int] = frozenset()) -> str:
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td class="num">{_e(c)}</td>' if i in numeric else f"<td>{_e(c)}</td>"
                         for i, c in enumerate(r)) + "</tr>"
        for r in rows
    )  # fmt: skip
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _runaway_rows(s: dict[str, Any]) -> list[list[Any]]:
    """Rows of a run stopped at the backward whirl: before its runaway and the runaway itself."""
    if s["runaway_start_s"] is None:
        return []
    eta = "-" if s["energy_ratio_before_runaway"] is None else f"{s['energy_ratio_before_runaway']:.4g}"
    return [
        ["runaway to the backward whirl from", f"{s['runaway_start_s']:.6g}", "s"],
        ["eta before the runaway", eta, ""],
        ["impacts before the runaway", s["impacts_before_runaway"], ""],
        ["impacts in the runaway", s["impacts_runaway"], ""],
        ["energy against friction in the runaway", f"{s['energy_friction_runaway_J']:.4g}", "J"],
    ]


def _run_html(ds: xarray.Dataset) -> str:
    from rotorlab.analyses import impact_summary

    s = impact_summary(ds)
    eta = "-" if s["energy_ratio"] is None else f"{s['energy_ratio']:.4g}"
    rows = [
        ["regime", s["regime"] + (" (run stopped at the backward whirl)" if s["backward_whirl"] else ""), ""],
        ["impacts (every located one, or approach >= count_speed)", s["impacts"], ""],
        ["impacts, chatter included", s["impacts_all"], ""],
        ["sliding episodes", s["slides"], ""],
        ["time in sliding contact", f"{s['sliding_time_s']:.4g}", "s"],
        ["energy on the stones", f"{s['energy_stones_J']:.4g}", "J"],
        ["energy against friction at the housing", f"{s['energy_friction_J']:.4g}", "J"],
        ["work of the stones on the vibration", f"{s['work_stones_J']:.4g}", "J"],
        ["vibration energy gained (fixed frame)", f"{s['energy_vibration_J']:.4g}", "J"],
        ["eta (seed 001, Fig. 5)", eta, ""],
        *_runaway_rows(s),
        ["largest approach speed", f"{s['max_approach_speed_m_s']:.4g}", "m/s"],
        ["largest penetration (should be 0)", f"{s['max_penetration_m']:.3g}", "m"],
        ["stones", s["n_stones"], ""],
        ["seed of the stone sequence", s["seed"], "numpy.random.default_rng"],
        ["run ended at", f"{s['t_final_s']:.6g}", "s"],
    ]
    detail = ds.attrs.get("status_detail")
    note = ""
    if detail:
        if s["status"] < 0:
            text, cls = "Failed: " + detail, "outcome-bad"
        elif s["backward_whirl"]:  # not failed, but not the requested run either: say it as plainly
            text, cls = detail[:1].upper() + detail[1:], "outcome-bad"
        else:
            text, cls = "Note: " + detail, "muted"
        note = f'<p class="{cls}">{_e(text)}</p>'
    return "<h3>Result</h3>" + note + _table(["quantity", "value", "unit"], rows, numeric={1})


#: Columns of an impacts-sweep table after the swept value (HTML report and console), in the order
#: of :func:`sweep_cells`; a last column "seed 001" gives the paper's count where it has one.
SWEEP_COLUMNS = ("impacts median", "quartiles", "min-max", "none", "rebounds", "sliding", "backward whirl", "failed",
                 "eta median")  # fmt: skip


def sweep_cells(row: dict[str, Any]) -> list[str]:
    """The cells of one value of :func:`rotorlab.analyses.sweep_summary` (:data:`SWEEP_COLUMNS`):
    medians, quartiles and range over the runs that did not fail ("-" where every run failed)."""
    r = row["regimes"]
    eta = "-" if row["energy_ratio_median"] is None else f"{row['energy_ratio_median']:.3g}"
    if row["impacts_median"] is None:  # every run at this value failed
        med = quart = span = "-"
    else:
        med, quart = f"{row['impacts_median']:g}", f"{row['impacts_q25']:g}-{row['impacts_q75']:g}"
        span = f"{row['impacts_min']}-{row['impacts_max']}"
    return [f"{row['value']:.4g}", med, quart, span, *(str(r[k]) for k in ("none", "rebounds", "sliding",
            "backward_whirl", "failed")), eta]  # fmt: skip


def _sweep_html(ds: xarray.Dataset) -> str:
    from rotorlab.analyses import paper_counts, sweep_summary

    doc = sweep_summary(ds)
    paper = paper_counts(ds)
    unit = f" ({doc['units']})" if doc["units"] not in ("", "1") else ""
    header = [doc["param"] + unit, *SWEEP_COLUMNS, "seed 001"]
    rows = [[*sweep_cells(row), "-" if p is None else p] for row, p in zip(doc["rows"], paper)]
    text = (f'<p class="muted">{doc["n_sequences"]} random stone sequences per value (seeds {doc["seed"]} to '
            f'{doc["seed"] + doc["n_sequences"] - 1}, the same at every value), {doc["t_end_s"]:g} s each. '
            "Regime counts are numbers of runs; a failed run (physically impossible result or integrator failure) "
            "is counted as failed, not in a regime, and left out of the medians; a run stopped at the dry-friction "
            "backward whirl (the rotor rolls on its housing, which this model cannot carry) counts its impacts up to "
            "the stop, not over the whole time. The paper's counts come from one sequence each and from "
            "parameters it does not give (start radius, number of guides, guide sequence).</p>")  # fmt: skip
    return "<h3>Impacts over stone sequences</h3>" + text + _table(header, rows, numeric={0, 1, 4, 5, 6, 7, 8, 9, 10})


def impact_section(ds: xarray.Dataset) -> str:
    """Return the HTML tables of an ``impacts`` or ``impacts-sweep`` result.

    Examples
    --------
    >>> from rotorlab.analyses import impact_run
    >>> from rotorlab.models import krasnov_crusher
    >>> "<table>" in impact_section(impact_run(krasnov_crusher(), t_end=0.2, n_save=20))
    True
    """
    if ds.attrs.get("analysis") == "impacts":
        return _run_html(ds)
    return _sweep_html(ds)


def reconstructions_section() -> str:
    """Return the HTML table of the formulas of seed 001 rebuilt from mechanics.

    Examples
    --------
    >>> "(3.9)" in reconstructions_section()
    True
    """
    from rotorlab.models._impact_rotor import RECONSTRUCTIONS

    rows = [[r.equation, r.printed, r.reconstructed, r.check, r.test] for r in RECONSTRUCTIONS]
    return ("<h2>Seed 001: formulas garbled in print, rebuilt from mechanics</h2>"
            '<p class="muted">rotorlab.models._impact_rotor.RECONSTRUCTIONS; each is checked by the test named.</p>'
            + _table(["equation", "printed (OCR)", "used", "checked by", "test"], rows))  # fmt: skip
