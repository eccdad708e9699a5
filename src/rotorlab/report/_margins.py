"""Presentation of the margin analyses (rows of :func:`rotorlab.analyses._shock_margin.shock_margin_rows`
and :func:`rotorlab.analyses._friction_margin.friction_margin_rows`): the verdict in words with
people's units (rpm, N s, g mm, deg, um), a table per result, the console tables."""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["shock_margin_section", "shock_margin_findings", "shock_margin_tables", "friction_margin_section",
           "friction_margin_findings", "friction_margin_tables"]  # fmt: skip

Rows = Sequence[Mapping[str, Any]]


def _g(v: float | None, fmt: str = ".3g", unit: str = "", scale: float = 1.0) -> str:
    return "–" if v is None else f"{v * scale:{fmt}}{unit}"


def _gmm(v: float | None, unit: str = " g mm") -> str:
    """A load shift (kg m) in g mm, four significant digits, never in exponent form (10000, not 1e+04).

    >>> _gmm(0.01), _gmm(2.598076e-3), _gmm(None)
    ('10000 g mm', '2598 g mm', '–')
    """
    return "–" if v is None else f"{float(f'{v * 1e6:.4g}'):.12g}{unit}"


def _shift_check(r: Mapping[str, Any]) -> str:
    return f"{r['shift_checked']} of {r['shift_directions']}"


def _shock_sentence(r: Mapping[str, Any]) -> str:
    rpm = f"{r['speed_rpm']:.0f} rpm"
    if not r["stable"]:
        return f"At {rpm} the balanced state is not stable (or does not exist): there is no margin to lose."
    sim = r["min_impulse_simulated"]
    knock = (f"a knock of {_g(sim, unit=' N s')} (simulated; linearised estimate {_g(r['min_impulse_linear'], unit=' N s')})"
             if sim is not None else f"a knock of {_g(r['min_impulse_linear'], unit=' N s')} (linearised estimate"
             ", not simulated or none found in the searched range)")  # fmt: skip
    end = r.get("fatal_outcome")
    where = "" if not end else (" (they balance again, in another arrangement, after passing unbalanced ones)"
                                if end == "balanced" else f" (they end in: {end})")
    on = f" on the rotor at {r['station']}" if r.get("station") else ""
    return (f"At {rpm} {knock}{on} at {_g(r['worst_impulse_direction_deg'], '.0f', '°')} from the unbalance throws "
            f"the balls out of balance{where}; a load shift of {_gmm(r['min_load_shift'])} at "
            f"{_g(r['worst_shift_direction_deg'], '.0f', '°')} leaves the balls unable to balance "
            f"(confirmed by simulation just below and above it in {_shift_check(r)} directions).")


def shock_margin_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: one sentence per speed, then one table row per speed."""
    from rotorlab.report._table import table

    head = "".join(f"<p>{_shock_sentence(r)}</p>" for r in rows)
    body = [[f"{r['speed_rpm']:.0f}", "yes" if r["stable"] else "no", _g(r["min_impulse_linear"]),
             _g(r["min_impulse_simulated"]), _g(r["worst_impulse_direction_deg"], ".0f"),
             _gmm(r["min_load_shift"], ""), _g(r["worst_shift_direction_deg"], ".0f"), _shift_check(r),
             _g(r["horizon"])] for r in rows]  # fmt: skip
    return head + table(["speed (rpm)", "balanced state stable", "impulse, linearised (N s)",
                         "impulse, simulated (N s)", "worst knock direction (deg)", "load shift (g mm)",
                         "worst shift direction (deg)", "shift confirmed", "horizon (s)"], body,
                        numeric={0, 2, 3, 4, 5, 6, 8})  # fmt: skip


def shock_margin_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The weakest speed first, then one number per speed."""
    ok = [r for r in rows if r["stable"]]
    if not ok:
        return Findings("The balanced state is not stable at any speed given: no shock margin.")

    def key(r):
        return r["min_impulse_simulated"] if r["min_impulse_simulated"] is not None else r["min_impulse_linear"]

    weakest = min(ok, key=lambda r: key(r) or float("inf"))
    bad = [f"{r['speed_rpm']:.0f}" for r in rows if not r["stable"]]
    tail = f" The balanced state is not stable at {', '.join(bad)} rpm: no margin there." if bad else ""
    numbers = tuple(f"{r['speed_rpm']:.0f} rpm: impulse {_g(key(r), unit=' N s')}, load shift "
                    f"{_gmm(r['min_load_shift'])}" for r in ok)  # fmt: skip
    return Findings("Weakest: " + _shock_sentence(weakest) + tail, numbers)


def shock_margin_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run``: one per ``shock-margin`` result."""
    from rich.table import Table

    out = []
    for name in results:
        t = Table(title=f"{name}: minimal fatal shock of the balanced state", title_justify="left")
        for col in ("speed (rpm)", "impulse lin. (N s)", "impulse sim. (N s)", "knock dir. (deg)",
                    "load shift (g mm)", "shift dir. (deg)", "shift confirmed"):
            t.add_column(col, justify="right")
        for r in rows[name]:
            t.add_row(f"{r['speed_rpm']:.0f}", _g(r["min_impulse_linear"]), _g(r["min_impulse_simulated"]),
                      _g(r["worst_impulse_direction_deg"], ".0f"), _gmm(r["min_load_shift"], ""),
                      _g(r["worst_shift_direction_deg"], ".0f"), _shift_check(r))  # fmt: skip
        out.append(t)
    return out


def _coords(r: Mapping[str, Any]) -> list[str]:
    return [k[: -len("_low_deg")] for k in r if k.endswith("_low_deg")]


def _check(r: Mapping[str, Any]) -> str:
    code = (r["check_inside"], r["check_outside"])
    if code == (1, 1):
        return "confirmed by simulation: released just inside it stays, just outside it moves"
    if -1 in code:
        return "not simulated or failed"
    return "NOT confirmed by simulation"


def _friction_sentence(ds: xarray.Dataset, r: Mapping[str, Any]) -> str:
    rpm = f"{r['speed_rpm']:.0f} rpm"
    if r["worst_residual"] is None:
        return f"At {rpm} there is no balanced state for friction to hold."
    band = ", ".join(f"{c} {_g(r[c + '_low_deg'], '+.3g')} to {_g(r[c + '_high_deg'], '+.3g')}°" for c in _coords(r))
    return (f"At {rpm} friction holds the balls within {band} of the balanced position; the worst "
            f"{ds.attrs.get('residual', 'residual')} there is {_g(r['worst_residual'], '.4g', ' um', 1e6)} "
            f"({_check(r)}).")


def friction_margin_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: one sentence per speed and a table."""
    from rotorlab.report._table import table

    coords = _coords(rows[0]) if rows else []
    head = "".join(f"<p>{_friction_sentence(ds, r)}</p>" for r in rows)
    head += f"<p>The band was searched by {html.escape(str(ds.attrs.get('search', 'a grid')))}.</p>"
    body = [[f"{r['speed_rpm']:.0f}", *(f"{_g(r[c + '_low_deg'], '+.3g')} to {_g(r[c + '_high_deg'], '+.3g')}"
                                        for c in coords),
             _g(r["worst_residual"], ".4g", "", 1e6), _check(r)] for r in rows]  # fmt: skip
    return head + table(["speed (rpm)", *(f"{c} band (deg)" for c in coords),
                         f"worst {ds.attrs.get('residual', 'residual')} (um)", "simulation"], body,
                        numeric={0, len(coords) + 1})  # fmt: skip


def friction_margin_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The speed with the largest residual first, then one number per speed."""
    done = [r for r in rows if r["worst_residual"] is not None]
    if not done:
        return Findings("No balanced state at any speed given: no friction band.")
    worst = max(done, key=lambda r: r["worst_residual"])
    numbers = tuple(f"{r['speed_rpm']:.0f} rpm: worst {ds.attrs.get('residual', 'residual')} "
                    f"{_g(r['worst_residual'], '.4g', ' um', 1e6)}" for r in done)  # fmt: skip
    return Findings("Largest residual: " + _friction_sentence(ds, worst), numbers)


def friction_margin_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run``: one per ``friction-margin`` result."""
    from rich.table import Table

    out = []
    for name, ds in results.items():
        r0 = rows[name]
        coords = _coords(r0[0]) if r0 else []
        t = Table(title=f"{name}: friction band and worst {ds.attrs.get('residual', 'residual')}",
                  title_justify="left")  # fmt: skip
        for col in ("speed (rpm)", *(f"{c} band (deg)" for c in coords), "worst residual (um)", "simulation"):
            t.add_column(col, justify="right")
        for r in r0:
            t.add_row(f"{r['speed_rpm']:.0f}", *(f"{_g(r[c + '_low_deg'], '+.3g')} to {_g(r[c + '_high_deg'], '+.3g')}"
                                                 for c in coords),
                      _g(r["worst_residual"], ".4g", "", 1e6), _check(r))  # fmt: skip
        out.append(t)
    return out
