"""How the machine analyses are shown: report section, findings, figures (family ``machine``).

Within the family the analysis type (``ds.attrs["analysis"]``) picks its table from a mapping.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from rotorlab.report._findings import Findings

__all__ = ["machine_section", "machine_findings", "machine_figures", "machine_rows_table"]

Rows = Sequence[Mapping[str, Any]]
_RPM = 30.0 / math.pi


def _g(v, digits: int = 4) -> str:
    return "-" if v is None else f"{v:.{digits}g}"


def _mm(v) -> str:
    return "-" if v is None else f"{v * 1e3:.4g}"


def _steady(rows: Rows):
    stations = list(rows[0]["amplitude"]) if rows else []
    header = ("speed (rpm)", "steady motion", "stable", "max Re(lambda) (1/s)", "ball angles (deg)",
              *(f"whirl at {s} (mm)" for s in stations))
    body = [(_g(r["speed_rpm"], 6),
             ("balanced" if r["balanced"] else "partly balanced") if r["exists"] else "none",
             "yes" if r["stable"] else "no", _g(r["max_real_eigenvalue"]),
             ", ".join(_g(a, 5) for a in r["ball_angles_deg"]),
             *(_mm(r["amplitude"][s]) for s in stations)) for r in rows]
    return header, body


def _simulate(rows: Rows):
    stations = list(rows[0]["amplitude"]) if rows else []
    header = ("start", "final speed (rpm)", "final ball angles (deg)",
              *(f"vibration at {s} (mm)" for s in stations), "status")
    body = [(str(r["ic"]), _g(None if r["final_speed"] is None else r["final_speed"] * _RPM, 6),
             "; ".join(f"{k}: {', '.join(_g(a, 5) for a in v)}" for k, v in r["final_ball_angles_deg"].items()),
             *(_mm(r["amplitude"][s]) for s in stations), str(r["status"])) for r in rows]
    if rows:
        body.append(("without balancing", "", "", *(_mm(rows[0]["reference_amplitude"][s]) for s in stations), ""))
    return header, body


def _run_up(rows: Rows):
    r = rows[0]
    stations = list(r["residual_amplitude"])
    header = ("final speed (rpm)", "critical speeds (rpm)", "passed", "captured at (rpm)",
              *(f"residual vibration at {s} (mm)" for s in stations))
    body = [(_g(r["final_speed_rpm"], 6), ", ".join(_g(w * _RPM, 5) for w in r["critical_speeds"]),
             str(r["passed"]), _g(None if r["captured_at"] is None else r["captured_at"] * _RPM, 5),
             *(_mm(r["residual_amplitude"][s]) for s in stations))]
    return header, body


_TABLES = {"machine-steady": _steady, "machine-simulate": _simulate, "machine-run-up": _run_up}


def machine_rows_table(ds: Any, rows: Rows):
    """``(header, body)`` of a machine result's table."""
    return _TABLES[ds.attrs["analysis"]](rows)


def machine_section(ds: Any, rows: Rows) -> str:
    """HTML of one machine result: a note of the races taking part, then its table."""
    from html import escape

    from rotorlab.report._table import table

    header, body = machine_rows_table(ds, rows)
    races = ds.attrs.get("races")
    note = f"<p>Races taking part: {escape(str(races) if races is not None else 'all')}.</p>"
    msg = ds.attrs.get("message")
    if msg:
        note += f"<p><strong>{escape(msg)}</strong></p>"
    return note + table(header, body, numeric=set(range(len(header))))


def _steady_findings(ds, rows):
    msg = ds.attrs.get("message")
    if msg and not any(r["exists"] for r in rows):
        return Findings(f"No balanced steady state: {msg}.")
    stable = [r["speed_rpm"] for r in rows if r["stable"]]
    kind = "balanced" if all(r["balanced"] for r in rows if r["exists"]) else "steady (partly balanced)"
    if not stable:
        return Findings(f"The {kind} state is unstable at every speed checked: the balancer does not settle there.")
    return Findings(f"The {kind} state is stable at {len(stable)} of {len(rows)} speeds "
                    f"({min(stable):.4g} to {max(stable):.4g} rpm, exact eigenvalues).",
                    (f"{len(stable)} of {len(rows)} speeds stable",))


def _simulate_findings(ds, rows):
    ratios = []
    for r in rows:
        for s, a in r["amplitude"].items():
            ref = r["reference_amplitude"][s]
            if a is not None and ref:
                ratios.append(a / ref)
    worst = max(ratios) if ratios else float("nan")
    ok = sum(r["status"] == 0 for r in rows)
    return Findings(f"{ok} of {len(rows)} start(s) finished; the largest vibration is "
                    f"{100 * worst:.3g} % of the unbalance response without balancing.",
                    (f"worst vibration ratio {worst:.3g}",))


def _run_up_findings(ds, rows):
    r = rows[0]
    if r["captured_at"] is not None:
        verdict = (f"The motor is captured below the critical speed {r['captured_at'] * _RPM:.4g} rpm "
                   f"(Sommerfeld effect): final speed {r['final_speed_rpm']:.4g} rpm.")
    else:
        verdict = (f"The run-up passes {r['passed']} critical speed(s) and reaches "
                   f"{r['final_speed_rpm']:.4g} rpm.")
    res = ", ".join(f"{s}: {_mm(v)} mm" for s, v in r["residual_amplitude"].items())
    return Findings(verdict, (f"residual vibration {res}",))


_FINDINGS = {"machine-steady": _steady_findings, "machine-simulate": _simulate_findings,
             "machine-run-up": _run_up_findings}


def machine_findings(ds: Any, rows: Rows) -> Findings:
    """The verdict of a machine result in words."""
    return _FINDINGS[ds.attrs["analysis"]](ds, rows)


def machine_figures(ds: Any, name: str) -> dict[str, Any]:
    """Stability over speed (steady) or speed and vibration over time (run-up); none otherwise."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kind = ds.attrs["analysis"]
    if kind == "machine-steady" and ds.sizes["speed"] > 1 and bool(ds.exists.any()):
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(ds.speed.values * _RPM, ds.max_real_eigenvalue.values, ".-")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("spin speed (rpm)")
        ax.set_ylabel("max Re(lambda) (1/s)")
        ax.set_title(f"{name}: balanced state stable below the line")
        fig.tight_layout()
        return {f"{name}-stability": fig}
    if kind == "machine-run-up":
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
        a1.plot(ds.time.values, ds.speed.values * _RPM)
        for w in ds.attrs["critical_speeds"]:
            a1.axhline(w * _RPM, color="r", lw=0.6, ls="--")
        a1.set_ylabel("speed (rpm)")
        for s in ds.station.values:
            a2.plot(ds.time.values, ds.amplitude.sel(station=s).values * 1e3, label=str(s))
        a2.set_ylabel("radial displacement (mm)")
        a2.set_xlabel("time (s)")
        a2.legend(fontsize="small")
        fig.tight_layout()
        return {f"{name}-run-up": fig}
    return {}
