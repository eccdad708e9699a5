"""How the machine analyses are shown: report section, findings, figures (family ``machine``).

Within the family the analysis type (``ds.attrs["analysis"]``) picks its table from a mapping.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from rotorlab import _people as people
from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.report._findings import Findings

__all__ = ["machine_section", "machine_findings", "machine_figures", "machine_rows_table"]

Rows = Sequence[Mapping[str, Any]]


def _g(v, digits: int = 4) -> str:
    return "-" if v is None else f"{v:.{digits}g}"


def _mm(v) -> str:
    return "-" if v is None else f"{v * 1e3:.4g}"


def _races(angles) -> str:
    """Ball angles by race, to 0.1 degree (a table's cell or a sentence)."""
    if not angles:
        return "-"
    return "; ".join(f"{k}: {', '.join(people.angle_deg(a) for a in v)}" for k, v in angles.items())





def _stations(rows: Rows, key: str) -> list[str]:
    for r in rows:
        if r.get(key):
            return list(r[key])
    return []


def _steady(rows: Rows):
    stations = _stations(rows, "amplitude")
    header = ("motion", "kind", "ball angles", "exact", "seed 003 (Hamilton)", "seed 002 (averaged)",
              "max Re(lambda) (1/s)", *(f"whirl at {s} (mm)" for s in stations))
    body = [(r.get("label", str(r["motion"])), r["kind"] if r["exists"] else "absent", _races(r["ball_angles_deg"]),
             r["verdict_exact"], r["verdict_hamilton"], r["verdict_averaged"], _g(r["max_real_eigenvalue"]),
             *(_mm((r["amplitude"] or {}).get(s)) for s in stations)) for r in rows]
    return header, body


def _chart(rows: Rows):
    stations = _stations(rows, "amplitude")
    param = [k for k in (rows[0] if rows else {}) if k in ("ball_mass", "ball_damping")]
    header = (*param, "speed (rpm)", "steady motion", "stable", "max Re(lambda) (1/s)", "ball angles",
              *(f"whirl at {s} (mm)" for s in stations))
    body = [(*(_g(r[k]) for k in param), _g(r["speed_rpm"], 6),
             ("balanced" if r["balanced"] else "partly balanced") if r["exists"] else "none",
             "yes" if r["stable"] else "no", _g(r["max_real_eigenvalue"]), _races(r["ball_angles_deg"]),
             *(_mm(r["amplitude"][s]) for s in stations)) for r in rows]
    return header, body


def _simulate(rows: Rows):
    stations = _stations(rows, "amplitude")
    header = ("start", "initial ball angles", "final speed (rpm)", "final ball angles",
              *(f"vibration at {s} (mm)" for s in stations), "outcome", "status")
    body = [(str(r["ic"]), _races(r["initial_ball_angles_deg"]), _g(r["final_speed_rpm"], 6),
             _races(r["final_ball_angles_deg"]), *(_mm(r["amplitude"][s]) for s in stations), r["outcome"],
             str(r["status"])) for r in rows]
    if rows:
        body.append(("without balancing", "", "", "", *(_mm(rows[0]["reference_amplitude"][s]) for s in stations),
                     "", ""))
    return header, body


def _run_up(rows: Rows):
    stations = _stations(rows, "residual_amplitude")
    header = ("start", "final speed (rpm)", "undamped forward critical speeds (rpm)", "passed",
              "captured at (rpm)",
              *(f"residual vibration at {s} (mm)" for s in stations),
              *(f"without balancing at {s} (mm)" for s in stations), "outcome")
    body = [(str(r["ic"]), _g(r["final_speed_rpm"], 6), ", ".join(_g(w * _RPM, 5) for w in r["critical_speeds"]),
             str(r["passed"]), _g(None if r["captured_at"] is None else r["captured_at"] * _RPM, 5),
             *(_mm(r["residual_amplitude"][s]) for s in stations),
             *(_mm(r["reference_amplitude"][s]) for s in stations), r["outcome"]) for r in rows]
    if rows and "passing_torque" in rows[0]:  # passing_torque = true
        header = (*header, "smallest passing torque with balls (N*m)", "without balls (N*m)")
        body = [(*b, _g(r["passing_torque"]), _g(r["passing_torque_without_balls"])) for b, r in zip(body, rows)]
    return header, body


_TABLES = {"steady": _steady, "stability-chart": _chart, "simulate": _simulate, "run-up": _run_up}


def machine_rows_table(ds: Any, rows: Rows):
    """``(header, body)`` of a machine result's table."""
    return _TABLES[ds.attrs["analysis"]](rows)


def machine_section(ds: Any, rows: Rows) -> str:
    """HTML of one machine result: a note of the races taking part, then its table."""
    from html import escape

    from rotorlab.report._table import table

    header, body = machine_rows_table(ds, rows)
    races = ds.attrs.get("races")
    which = "all" if races is None else ("none (no balancer)" if not races else ", ".join(map(str, races)))
    note = f"<p>Races taking part: {escape(which)}.</p>"
    msg = ds.attrs.get("message")
    if msg:
        note += f"<p><strong>{escape(msg)}</strong></p>"
    if ds.attrs.get("seed_verdicts"):
        note += f"<p>Seed verdicts: {escape(str(ds.attrs['seed_verdicts']))}.</p>"
    return note + table(header, body, numeric=set(range(len(header))))


def _steady_findings(ds, rows):
    msg = ds.attrs.get("message")
    if msg and not any(r["exists"] for r in rows):
        return Findings(f"No steady motion: {msg}.")
    stable = [r for r in rows if r["exists"] and r["stable"]]
    kinds = sorted({r["kind"] for r in rows if r["exists"]})
    speed = rows[0]["speed"] if rows else None
    at = f" at {speed * _RPM:.5g} rpm" if speed else ""
    # motions that would pass the clearance (analyses._machine.clearance_violation) are named too
    beyond = f" Beyond the clearance: {msg}." if msg and "clearance" in str(msg) else ""
    if not stable:
        return Findings(f"None of the {len(rows)} {'/'.join(kinds)} steady motion(s){at} is stable (exact "
                        f"eigenvalues): the balancer does not settle there.{beyond}")
    if any(r["kind"] == "balanced" for r in stable):
        what = "the balancer balances there."
    elif "balanced" in kinds:
        what = "the balanced motion is unstable: the balls settle where they do not balance."
    else:
        what = ("the balls settle in a partly balanced state: they cannot cancel the unbalance at every "
                "station (see the whirl per station).")
    return Findings(f"{len(stable)} of {len(rows)} {'/'.join(kinds)} steady motion(s){at} are stable (exact "
                    f"eigenvalues): {what}{beyond}",
                    tuple(f"motion {r.get('label', r['motion'])}: balls at {_races(r['ball_angles_deg'])}, "
                          f"max Re(lambda) = {_g(r['max_real_eigenvalue'])} 1/s" for r in stable))


def _chart_findings(ds, rows):
    msg = ds.attrs.get("message")
    if msg and not any(r["exists"] for r in rows):
        return Findings(f"No steady motion: {msg}.")
    param = [k for k in (rows[0] if rows else {}) if k in ("ball_mass", "ball_damping")]
    if param:
        stable = sum(r["stable"] for r in rows)
        return Findings(f"The balanced state is stable at {stable} of {len(rows)} points of the chart over speed "
                        f"and {param[0]} (exact eigenvalues).", (f"{stable} of {len(rows)} points stable",))
    balanced = all(r["balanced"] for r in rows if r["exists"])
    kind = "balanced" if balanced else "steady (partly balanced)"
    from rotorlab.explore._outcome import true_runs

    spans = true_runs([r["speed_rpm"] for r in rows], [r["stable"] for r in rows])
    if not spans:
        p = ds.attrs.get("first_critical_speed")
        speeds = [r["speed_rpm"] for r in rows]
        why = (f" Every speed checked ({people.number(min(speeds))} to {people.number(max(speeds))} rpm) lies below "
               f"the first forward critical speed {people.speed(p)}, where no balancer can balance." if p is not None
               and max(speeds) < p * _RPM else "")
        fix = (f" Run above the first forward critical speed of {people.speed(p)}, or soften the mounts."
               if p is not None else "")
        return Findings(f"The {kind} state is unstable at every speed checked: the balancer does not settle there."
                        + why + fix)
    text = ", ".join(f"{a:.5g}-{b:.5g}" if a != b else f"{a:.5g}" for a, b in spans)
    return Findings(f"The {kind} state is stable from {text} rpm (exact eigenvalues; {sum(r['stable'] for r in rows)} "
                    f"of {len(rows)} speeds): " + ("the balancer balances there." if balanced else
                                                   "the balls settle in a partly balanced state: they cannot cancel the unbalance "
                                                   "at every station (see the whirl per station)."),
                    (f"stable at {text} rpm",))


def _simulate_findings(ds, rows):
    # the measure of the outcome: the largest vibration of any station against the largest
    # unbalance response of any station (locked balls), per start
    ratios = []
    for r in rows:
        amp = [a for a in r["amplitude"].values() if a is not None]
        ref = max((v for v in r["reference_amplitude"].values() if v is not None), default=0.0)
        if amp and ref:
            ratios.append(max(amp) / ref)
    worst = max(ratios) if ratios else float("nan")
    by: dict[str, list[int]] = {}
    for r in rows:
        by.setdefault(r["outcome"], []).append(r["ic"])
    good = by.get("balanced", [])
    if not rows:
        return Findings("No starts.")
    if "no balancer" in by:
        verdict = (f"Without a balancer the vibration is {people.relative_to(worst, 'the locked unbalance response')} "
                   "(the reference for the variants with balls).")
    elif len(good) == len(rows):
        verdict = f"The balancer balances from every start ({len(rows)}): vibration at most " \
                  f"{people.relative_to(worst, 'the unbalance response')}."
    elif good:
        verdict = (f"The balancer balances from {len(good)} of {len(rows)} starts (start(s) "
                   f"{', '.join(map(str, good))}); " + "; ".join(f"{k} from start(s) {', '.join(map(str, v))}"
                                                                  for k, v in by.items() if k != "balanced") + ".")
    else:
        verdict = ("The balancer does not balance from any start: " + "; ".join(
            f"{k} from start(s) {', '.join(map(str, v))}" for k, v in by.items()) +
            f" (vibration up to {people.relative_to(worst, 'the unbalance response')}).")
    return Findings(verdict, (f"largest vibration / unbalance response {people.relative(worst)}",
                              *(f"start {r['ic']}: {r['outcome']}" + (f", final ball angles "
                                f"{_races(r['final_ball_angles_deg'])}" if r["outcome"] != "no balancer" else "")
                                for r in rows)))


def _run_up_findings(ds, rows):
    parts, numbers = [], []
    verdicts = {"balanced": "the balancer balances", "not balanced": "the balancer does not balance",
                "non-synchronous": "the balls keep circling (non-synchronous), not balanced",
                "no balancer": "no balancer", "captured": "not balanced", "failed": "failed",
                "below critical speed": "not above its first critical speed, where a balancer cannot balance"}
    for r in rows:
        if r["captured_at"] is not None:
            parts.append(f"start {r['ic']}: captured at the critical speed {r['captured_at'] * _RPM:.4g} rpm "
                         f"(Sommerfeld effect), final speed {r['final_speed_rpm']:.4g} rpm")
        else:
            parts.append(f"start {r['ic']}: passes {r['passed']} critical speed(s), reaches "
                         f"{r['final_speed_rpm']:.4g} rpm; {verdicts.get(r['outcome'], r['outcome'])}")
        res = ", ".join(f"{s}: {people.length(v)} (without balancing {people.length(r['reference_amplitude'][s])})"
                        for s, v in r["residual_amplitude"].items())
        numbers.append(f"start {r['ic']}: residual vibration {res}")
    good = [r["ic"] for r in rows if r["outcome"] == "balanced"]
    head = ""
    if any(r["outcome"] != "no balancer" for r in rows):
        head = (f"The balancer balances from {'every start' if len(good) == len(rows) else 'no start' if not good else 'start(s) ' + ', '.join(map(str, good))} "
                f"({len(good)} of {len(rows)}). ")
    tail = _passing_torque_text(ds, rows)
    return Findings(head + "; ".join(parts) + ".", ((tail,) if tail else ()) + tuple(numbers))


def _passing_torque_text(ds, rows) -> str:
    """The smallest passing stall torque with and without the balls (``passing_torque = true``)."""
    if not rows or "passing_torque" not in rows[0]:
        return ""
    r0 = rows[0]
    crit = f"{r0['critical_speeds'][0] * _RPM:.4g} rpm" if r0["critical_speeds"] else "-"
    how = f"(found to {r0['passing_torque_rtol']:g} by run-ups of {float(ds.time.values[-1]):g} s from each start)"
    msg = r0.get("passing_torque_message")
    bare = r0["passing_torque_without_balls"]
    if bare is None:
        return f"The smallest stall torque that passes the first critical speed ({crit}) was not found: {msg}."
    without = f"{bare:.4g} N*m without"
    if all(r["outcome"] == "no balancer" for r in rows):
        return f"The smallest stall torque that passes the first critical speed ({crit}): {without} balls {how}."
    values = [r["passing_torque"] for r in rows]
    if all(v is not None and f"{v:.4g}" == f"{values[0]:.4g}" for v in values):
        ratio = r0["passing_torque_ratio"]
        withb = f"{values[0]:.4g} N*m with the balls"
        change = f", ratio {ratio:.3g}" if ratio is not None else ""
    else:
        withb = "with the balls " + ", ".join(f"{'not found' if v is None else f'{v:.4g} N*m'} from start {r['ic']}"
                                               for r, v in zip(rows, values))
        change = ""
    note = f" ({msg})" if msg else ""
    own = r0.get("motor_stall_torque")
    mine = f"; this motor's is {own:.4g} N*m" if own is not None else ""
    return (f"The smallest stall torque that passes the first critical speed ({crit}): {withb}, {without}{change} "
            f"{how}{mine}.{note}{_limits_text(rows)}")


def _limits_text(rows) -> str:
    """What limits the passing torques: the rotor captured below the target, or a ball left behind."""
    r0 = rows[0]
    target = r0.get("passing_torque_target_speed")
    limits = sorted({r["passing_torque_limited_by"] for r in rows if r.get("passing_torque_limited_by")})
    bare = r0.get("passing_torque_without_balls_limited_by")
    if target is None or not (limits or bare):
        return ""
    parts = []
    if limits and any(r["outcome"] != "no balancer" for r in rows):
        parts.append(f"with the balls by {' / '.join(limits)}")
    if bare:
        parts.append(f"without by {bare}")
    sync = " with the balls turning with the rotor" if r0.get("passing_synchronise") else ""
    return (f" A run-up passes when it ends above {target * _RPM:.4g} rpm{sync}; the torque is limited"
            f" {', '.join(parts)}.")


_FINDINGS = {"steady": _steady_findings, "stability-chart": _chart_findings, "simulate": _simulate_findings,
             "run-up": _run_up_findings}


def machine_findings(ds: Any, rows: Rows) -> Findings:
    """The verdict of a machine result in words."""
    return _FINDINGS[ds.attrs["analysis"]](ds, rows)


def _simulate_figure(ds: Any, name: str, plt) -> Any:
    """Each station's distance from the axis over time (log scale), one colour per start and one
    line style per station, and dotted the same without balancing (the locked unbalance response,
    as in the table); starts ending with the largest vibration are drawn first."""
    n_ic, stations = ds.sizes["ic"], list(ds.station.values)
    fig, ax = plt.subplots(figsize=(6.5, 3.6))
    t = np.asarray(ds.time.values, dtype=float)
    disp = np.asarray(ds.displacement.values, dtype=float) * 1e3
    order = np.argsort(-np.asarray(ds.amplitude.values, dtype=float).max(axis=1), kind="stable")
    styles = ("-", "--", ":", "-.")
    legend = n_ic * len(stations) <= 12
    for rank, i in enumerate(order):
        for k, s in enumerate(stations):
            ax.plot(t, disp[i, :, k], color=f"C{i % 10}", lw=0.8, ls=styles[k % 4],
                    zorder=2 + rank, label=f"{s}, start {i}: {ds.outcome.values[i]}" if legend else None)
    for k, s in enumerate(stations):
        ref = float(ds.reference_amplitude.values[k]) * 1e3
        if ref > 0:
            ax.axhline(ref, color="k", lw=0.8, ls=styles[k % 4], alpha=0.6,
                       label=f"{s}, without balancing" if legend else None)
    ax.set_yscale("log")
    # from the smallest distance after the start at rest (0) up: seven decades at most
    later = disp[:, 1:, :]
    top = max(float(later.max(initial=0.0)), float(ds.reference_amplitude.max()) * 1e3)
    low = float(later[later > 0].min(initial=top))
    if top > 0:
        ax.set_ylim(max(0.5 * low, 1e-7 * top), 2.0 * top)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("distance from the axis (mm)")
    ax.set_title(f"{name}: vibration (black: without balancing)", fontsize=10)
    ax.grid(alpha=0.3)
    if legend:
        ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return fig


def _stability_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    """A stability chart: stable region over speed x parameter, or max Re(lambda) over speed."""
    if not bool(ds.exists.any()):
        return {}
    if "parameter" in ds.dims:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        st = np.where(ds.exists.values, ds.stable.values.astype(float), np.nan)
        ax.pcolormesh(ds.speed.values * _RPM, ds.parameter.values, st, shading="nearest", cmap="RdYlGn",
                      vmin=0, vmax=1)
        ax.set_xlabel("spin speed (rpm)")
        ax.set_ylabel(f"{ds.attrs['parameter']} ({ds.parameter.attrs.get('units', '')})")
        ax.set_title(f"{name}: balanced state stable (green)")
        fig.tight_layout()
        return {f"{name}-stability": fig}
    if ds.sizes["speed"] > 1:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(ds.speed.values * _RPM, ds.max_real_eigenvalue.values, ".-")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("spin speed (rpm)")
        ax.set_ylabel("max Re(lambda) (1/s)")
        ax.set_title(f"{name}: balanced state stable below the line")
        fig.tight_layout()
        return {f"{name}-stability": fig}
    return {}


def _simulate_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    """A simulation with its time history: vibration over time."""
    return {f"{name}-vibration": _simulate_figure(ds, name, plt)} if "displacement" in ds else {}


def _run_up_figures(ds: Any, name: str, plt: Any) -> dict[str, Any]:
    """A run-up: speed and vibration over time, per start."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    # the start that ends with the largest vibration is drawn first, so that a balanced
    # start's thin band is not hidden under an unbalanced one's (same colour per start)
    residual = np.asarray(ds.residual_amplitude.values, dtype=float).reshape(ds.sizes["ic"], -1)
    order = np.argsort(-residual.max(axis=1), kind="stable")
    for rank, i in enumerate(order):
        colour = f"C{i % 10}"
        a1.plot(ds.time.values, ds.speed.values[i] * _RPM, color=colour, label=f"start {i}")
        for k, s in enumerate(ds.station.values):
            a2.plot(ds.time.values, ds.amplitude.sel(station=s).values[i] * 1e3, color=colour,
                    ls=("-", "--", ":", "-.")[k % 4], zorder=2 + rank,
                    label=f"{s}, start {i}: {ds.outcome.values[i]}")
    for w in ds.attrs["critical_speeds"]:
        a1.axhline(w * _RPM, color="r", lw=0.6, ls="--")
    a1.set_ylabel("speed (rpm)")
    a2.set_ylabel("radial displacement (mm)")
    a2.set_xlabel("time (s)")
    a2.legend(fontsize="small")
    fig.tight_layout()
    return {f"{name}-run-up": fig}


# The machine presentation's figures, by the analysis that made the Dataset (ds.attrs["analysis"]);
# an analysis without an entry has no figure.
_FIGURES = {"stability-chart": _stability_figures, "simulate": _simulate_figures, "run-up": _run_up_figures}


def machine_figures(ds: Any, name: str) -> dict[str, Any]:
    """Stability over speed (steady), vibration over time (simulate with its time history) or
    speed and vibration over time (run-up); none otherwise."""
    draw = _FIGURES.get(ds.attrs["analysis"])
    if draw is None:
        return {}
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return draw(ds, name, plt)
