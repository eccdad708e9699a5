"""Report section and findings of the ``rub`` analysis: the regime, and every measured number with
its closed-form value beside it (rows of :func:`rotorlab.analyses._rub.rub_rows`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["rub_section", "rub_findings", "rub_map_section", "rub_map_findings", "rub_map_tables"]

Rows = Sequence[Mapping[str, Any]]


def _fmt(v: Any) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.5g}"
    return str(v)


def rub_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the regime sentence and the measured / closed-form table."""
    from rotorlab.report._table import table

    a = ds.attrs
    head = (f"<p>Simulated regime: <b>{_fmt(rows[0]['measured'])}</b>; the closed forms allow: "
            f"{_fmt(rows[0]['closed_form'])}.</p>")  # fmt: skip
    if a.get("status", 0) < 0:
        head += f"<p>The integration failed: {a.get('status_message', '')}.</p>"
    body = [[r["quantity"], _fmt(r["measured"]), _fmt(r["closed_form"]), r["unit"], r["source"]] for r in rows[1:]]
    return head + table(["quantity", "simulated", "closed form", "unit", "source"], body, numeric={1, 2})


def rub_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The regime with the closed-form prediction, the whirl radius, speed ratio and contact force,
    and whether the friction is below the full rub's critical friction."""
    a = ds.attrs
    if a.get("status", 0) < 0:
        return Findings(f"FAILED: {a.get('status_message', '')}; closed forms allow: {rows[0]['closed_form']}")
    numbers = [f"{r['quantity']}: {_fmt(r['measured'])} (closed form {_fmt(r['closed_form'])}) {r['unit']}".rstrip()
               for r in rows[1:4]]  # fmt: skip
    mu, mu_c = a.get("friction"), a.get("critical_friction")  # the numbers of rub_rows' last row
    if len(rows) > 1 and mu is not None and mu_c is not None and np.isfinite(mu_c):
        stable = float(mu) < float(mu_c)
        numbers.append(f"friction {_fmt(float(mu))} is {'below' if stable else 'above'} the critical "
                       f"{_fmt(float(mu_c))}: the full rub is {'stable' if stable else 'unstable'} "
                       "(closed form)")  # fmt: skip
    return Findings(f"{rows[0]['measured']}; closed forms allow: {rows[0]['closed_form']}", tuple(numbers))


def rub_map_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the regimes of the map, with how many points and where."""
    from rotorlab.report._table import table

    axis = ds.attrs["second_axis"]
    unit = ds[axis].attrs.get("units", "")
    body = [[r["regime"], r["points"], f"{100 * r['share']:.0f} %",
             f"{r['spin_speed_min']:.4g} – {r['spin_speed_max']:.4g}",
             f"{r[f'{axis}_min']:.4g} – {r[f'{axis}_max']:.4g}"] for r in rows]  # fmt: skip
    head = (f"<p>{ds.attrs['points']} points over spin speed x {axis}; the dashed line of the map is "
            "where the closed-form no-rub orbit just reaches the clearance: on its contact side no orbit clear of "
            "the stator exists. On its other side the rotor may still rub where a full-rub branch coexists with "
            "the no-rub orbit (above the critical speed); there the map shows where the run from the common "
            "start lands.</p>")
    return head + table(["regime", "points", "share", "spin speed (rad/s)", f"{axis} ({unit})"], body, numeric={1, 2})


def rub_map_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The regimes found and their shares, and the agreement with the closed forms."""
    a = ds.attrs
    numbers = ()
    if "closed_form_decided" in a:
        rest = int(a["points"]) - int(a["closed_form_decided"])
        numbers = (f"at the {a['closed_form_decided']} points where the closed forms allow one regime, the map "
                   f"shows it at {a['closed_form_agree']}"
                   + (f"; at the other {rest} they allow several (coexistence: the map shows where the runs "
                      "land) or none, or the run failed" if rest else ""),)  # fmt: skip
    return Findings("regimes found: " + "; ".join(f"{r['regime']} ({100 * r['share']:.0f} %)" for r in rows), numbers)


def rub_map_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run``: one per ``rub-map`` result."""
    from rich.table import Table

    out = []
    for name, ds in results.items():
        axis = ds.attrs["second_axis"]
        t = Table(title=f"{name}: rub regimes over spin speed x {axis}", title_justify="left")
        for col in ("regime", "points", "spin speed (rad/s)", axis):
            t.add_column(col)
        for r in rows[name]:
            t.add_row(r["regime"], str(r["points"]), f"{r['spin_speed_min']:.4g} – {r['spin_speed_max']:.4g}",
                      f"{r[f'{axis}_min']:.4g} – {r[f'{axis}_max']:.4g}")
        out.append(t)
    return out
