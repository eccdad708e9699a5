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

from rotorlab.plot._machine import machine_figures  # noqa: F401  (the figures live in rotorlab.plot)

__all__ = ["machine_section", "machine_findings", "machine_figures", "machine_rows_table"]

Rows = Sequence[Mapping[str, Any]]


def _g(v, digits: int = 4) -> str:
    return "-" if v is None else f"{v:.{digits}g}"


#: A distance below this (m) is round-off of zero: shown as 0 (a balanced state's whirl).
_ZERO = 1e-9


def _mm(v) -> str:
    return "-" if v is None else "0" if abs(v) < _ZERO else f"{v * 1e3:.4g}"


def _races(angles) -> str:
    """Ball angles by race, to 0.1 degree (a table's cell or a sentence)."""
    if not angles:
        return "-"
    return "; ".join(f"{k}: {', '.join(people.angle_deg(a) for a in v)}" for k, v in angles.items())


def _stations(ds: Any, rows: Rows, key: str, *also: str) -> list[str]:
    """The stations a table shows: the named ones (or the one vibrating most: :func:`shown_stations`)
    where any row's ``key`` (or ``also``) is above round-off; no column of zeros."""
    from rotorlab.plot._machine import shown_stations

    names = next((list(r[key]) for r in rows if r.get(key)), [])
    if not names:
        return []

    def size(s: str) -> float:
        return max((abs(v) for r in rows for k in (key, *also) for v in [(r.get(k) or {}).get(s)]
                    if v is not None), default=0.0)

    sizes = [size(s) for s in names]
    picked = [names[k] for k in shown_stations(ds, sizes)] if "station" in ds.coords else names
    return [s for s in picked if size(s) >= _ZERO]


def _steady(ds: Any, rows: Rows):
    stations = _stations(ds, rows, "amplitude")
    header = ("motion", "kind", "ball angles", "exact", "seed 003 (Hamilton)", "seed 002 (averaged)",
              "max Re(lambda) (1/s)", *(f"whirl at {s} (mm)" for s in stations))
    body = [(r.get("label", str(r["motion"])), r["kind"] if r["exists"] else "absent", _races(r["ball_angles_deg"]),
             r["verdict_exact"], r["verdict_hamilton"], r["verdict_averaged"], _g(r["max_real_eigenvalue"]),
             *(_mm((r["amplitude"] or {}).get(s)) for s in stations)) for r in rows]
    return header, body


def _chart(ds: Any, rows: Rows):
    stations = _stations(ds, rows, "amplitude")
    param = [k for k in (rows[0] if rows else {}) if k in ("ball_mass", "ball_damping")]
    header = (*param, "speed (rpm)", "steady motion", "stable", "max Re(lambda) (1/s)", "ball angles",
              *(f"whirl at {s} (mm)" for s in stations))
    body = [(*(_g(r[k]) for k in param), _g(r["speed_rpm"], 6),
             ("balanced" if r["balanced"] else "partly balanced") if r["exists"] else "none",
             "yes" if r["stable"] else "no", _g(r["max_real_eigenvalue"]), _races(r["ball_angles_deg"]),
             *(_mm(r["amplitude"][s]) for s in stations)) for r in rows]
    return header, body


def _outcome_of(r: Mapping[str, Any]) -> str:
    """The outcome, with "(failed)" where the run failed and its outcome does not say so."""
    failed = r.get("status", 0) != 0 and "fail" not in str(r["outcome"])
    return f"{r['outcome']} (failed)" if failed else str(r["outcome"])


def _simulate(ds: Any, rows: Rows):
    stations = _stations(ds, rows, "amplitude", "reference_amplitude")
    header = ("start", "initial ball angles", "final speed (rpm)", "final ball angles",
              *(f"vibration at {s} (mm)" for s in stations), "outcome", "settles by (s)")
    body = [(str(r["ic"]), _races(r["initial_ball_angles_deg"]), _g(r["final_speed_rpm"], 6),
             _races(r["final_ball_angles_deg"]), *(_mm(r["amplitude"][s]) for s in stations), _outcome_of(r),
             _g(r.get("settle_estimate_s"))) for r in rows]
    if rows:
        body.append(("without balancing", "", "", "", *(_mm(rows[0]["reference_amplitude"][s]) for s in stations),
                     "", ""))
    return header, body


def _run_up(ds: Any, rows: Rows):
    stations = _stations(ds, rows, "residual_amplitude", "reference_amplitude")
    header = ("start", "final speed (rpm)", "undamped forward critical speeds (rpm)", "passed",
              "captured at (rpm)",
              *(f"residual vibration at {s} (mm)" for s in stations),
              *(f"without balancing at {s} (mm)" for s in stations), "outcome", "settles by (s)",
              "transient peak at each critical speed passed (mm)")
    body = [(str(r["ic"]), _g(r["final_speed_rpm"], 6), ", ".join(_g(w * _RPM, 5) for w in r["critical_speeds"]),
             str(r["passed"]), _g(None if r["captured_at"] is None else r["captured_at"] * _RPM, 5),
             *(_mm(r["residual_amplitude"][s]) for s in stations),
             *(_mm(r["reference_amplitude"][s]) for s in stations), _outcome_of(r), _g(r.get("settle_estimate_s")),
             ", ".join(_mm(v) for v in r.get("critical_peaks") or [] if v is not None) or "-") for r in rows]
    if rows and "passing_torque" in rows[0]:  # passing_torque = true
        header = (*header, "smallest passing torque with balls (N*m)", "without balls (N*m)")
        body = [(*b, _g(r["passing_torque"]), _g(r["passing_torque_without_balls"])) for b, r in zip(body, rows)]
    return header, body


_TABLES = {"steady": _steady, "stability-chart": _chart, "simulate": _simulate, "run-up": _run_up}


#: Columns left out when no row has a value in them (no column of blanks).
_OPTIONAL = ("settles by (s)",)


def machine_rows_table(ds: Any, rows: Rows):
    """``(header, body)`` of a machine result's table (an optional column that no row fills is
    left out)."""
    header, body = _TABLES[ds.attrs["analysis"]](ds, rows)
    empty = {i for i, h in enumerate(header) if h in _OPTIONAL and all(b[i] in ("", "-") for b in body)}
    if empty:
        header = tuple(h for i, h in enumerate(header) if i not in empty)
        body = [tuple(v for i, v in enumerate(b) if i not in empty) for b in body]
    return header, body


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
        verdict = ("No start has balanced by the end: " + "; ".join(
            f"{k} from start(s) {', '.join(map(str, v))}" for k, v in by.items()) +
            f" (vibration up to {people.relative_to(worst, 'the unbalance response')}).")
    verdict += _not_settled_text(rows, float(ds.attrs.get("t_end", np.nan)) if ds is not None else np.nan)
    return Findings(verdict, (f"largest vibration / unbalance response {people.relative(worst)}",
                              *(f"start {r['ic']}: {r['outcome']}" + (f", final ball angles "
                                f"{_races(r['final_ball_angles_deg'])}" if r["outcome"] != "no balancer" else "")
                                for r in rows)))


def _not_settled_text(rows, t_end: float) -> str:
    """" N of M ... are not settled at the end ..., and the horizon that would do" (or "")."""
    from rotorlab.analyses._verdict import MARGIN, round_up_horizon

    late = [r for r in rows if r["outcome"] == "not settled"]
    if not late:
        return ""
    by = max((r["settle_estimate_s"] for r in late if r.get("settle_estimate_s") is not None), default=None)
    when = f", estimated to balance by {by:.3g} s" if by is not None else ""
    need = f" A simulated time of {round_up_horizon(MARGIN * by):g} s would do." if by is not None else ""
    at = f"at {t_end:.3g} s" if np.isfinite(t_end) else "at the end"
    return (f" {len(late)} of {len(rows)} runs are not settled {at} (still converging towards balance"
            f"{when}): too short for their verdict.{need}")


def _ensemble_text(rows) -> tuple[str, tuple[str, ...]]:
    """The share of run-ups balanced at the ramp's end with its Wilson interval, and the median
    transient peak at each critical speed passed with its order-statistic interval."""
    ens = rows[0].get("ensemble") if rows else None
    if not ens or not ens["runs"]:
        return "", ()
    pct = f"{ens['confidence']:.0%}".replace("%", " %")
    head = ""
    if ens["balanced_share"] is not None and any(r["outcome"] != "no balancer" for r in rows):
        failed = sum(r["outcome"] == "failed" for r in rows)
        head = (f"Balanced at the end of the ramp: {ens['balanced']} of {ens['runs']} run-ups"
                + (" that did not fail" if failed else "") + " "
                f"({100 * ens['balanced_share']:.3g} %, Wilson {pct} interval {100 * ens['balanced_share_low']:.3g}-"
                f"{100 * ens['balanced_share_high']:.3g} %)" + (f"; {failed} failed. " if failed else ". "))
    numbers = []
    for c in ens["critical_peaks"]:
        if c["median"] is None:
            continue
        numbers.append(f"transient peak at the critical speed {c['speed'] * _RPM:.4g} rpm: median {_mm(c['median'])} mm "
                       f"over the {c['runs_passed']} run-ups that passed it, order-statistic interval "
                       f"{_mm(c['low'])}-{_mm(c['high'])} mm (covers the median with probability {c['coverage']:.3g})")
    return head, tuple(numbers)


def _run_up_findings(ds, rows):
    parts, numbers = [], []
    verdicts = {"balanced": "the balancer balances", "not balanced": "the balancer does not balance",
                "not settled": "not settled (the balls still converging towards balance)",
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
    share, peaks = _ensemble_text(rows)
    late = _not_settled_text(rows, float(ds.time.values[-1])) if "time" in ds.coords else ""
    coarse = (ds.attrs.get("peak_saves_note") or "",)
    return Findings(head + share + "; ".join(parts) + "." + late,
                    ((tail,) if tail else ()) + tuple(numbers) + peaks + tuple(c for c in coarse if c))


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
