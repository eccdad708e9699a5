"""The engineer's verdict on a machine: one screen that opens every report and ``rotorlab run``.

Lines, each with a topic, a status (``yes``, ``no``, ``not-settled`` or ``info``), a sentence
with numbers rounded for people (:mod:`rotorlab._people`) and, for a "no", the one change that
would fix it: the critical speeds (which unbalance excites), the operating speed against them,
whether it balances (from what share of starts, within what time), the stable speed range, the
run-up (passes the criticals? transient peak) and contact (share of run-ups). Everything comes
from the results the case's analyses produced; where an analysis was not in the case the line
says "not computed" and names the analysis that would tell. Only the critical speeds are
computed here (a linear eigenvalue problem).

For implementers
----------------
An analysis type adds its evidence with ``register_evidence("my-type", evidence)``, where
``evidence(ds, rows, facts) -> list[VerdictLine]`` reads its Dataset and summary rows
(:func:`rotorlab.analyses.summarize`); ``facts`` is the case's
:class:`~rotorlab.analyses._facts.MachineFacts` or None.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from rotorlab import _people as people
from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab._registry import Registry
from rotorlab.analyses._facts import MachineFacts, machine_facts

__all__ = ["VerdictLine", "STATUSES", "VERDICT_EVIDENCE", "register_evidence", "machine_verdict", "explain_regime"]

#: The statuses of a verdict line.
STATUSES = ("yes", "no", "not-settled", "info")
Rows = Sequence[Mapping[str, Any]]


@dataclass(frozen=True)
class VerdictLine:
    """One line of the verdict: ``topic``, ``status`` (one of :data:`STATUSES`), ``sentence`` and
    ``fix`` (the one change that would turn a "no" into a "yes"; "" when none is known)."""

    topic: str
    status: str
    sentence: str
    fix: str = ""

    def to_dict(self) -> dict[str, str]:
        return {"topic": self.topic, "status": self.status, "sentence": self.sentence, "fix": self.fix}


Evidence = Callable[[Any, Rows, "MachineFacts | None"], list[VerdictLine]]
#: Evidence functions by analysis type (see the module's "For implementers" list).
VERDICT_EVIDENCE: Registry[Evidence] = Registry("analysis type with verdict evidence")


def register_evidence(analysis_type: str, evidence: Evidence, *, replace: bool = False) -> None:
    """Add the verdict evidence of an analysis type to :data:`VERDICT_EVIDENCE`."""
    VERDICT_EVIDENCE.register(analysis_type, evidence, replace=replace)


# --------------------------------------------------------------------------- regime names

_REGIMES: dict[str, str] = {
    "balanced": "the balls settled where they cancel the unbalance",
    "non-synchronous": "the balls keep circling relative to the rotor instead of settling",
    "not settled": "still converging towards balance when the simulation ended",
    "steady": "the balls settled off the balanced angles (held by friction)",
    "not balanced": "the balls settled but the vibration is above the balanced threshold",
    "captured": "the rotor is held at a critical speed (the Sommerfeld effect)",
    "unbalanced": "a rotor without balls",
    "no balancer": "no balls: the reference",
    "below critical speed": "the run-up ended below the first critical speed, where a balancer cannot balance",
}


def _side(label: str) -> str:
    nominal = label[label.index("(") + 1:label.rindex(")")].split(",")
    on = sum(a.strip() == "0°" for a in nominal)
    where = ("all on the unbalance's side, adding to it" if on == len(nominal) else
             "all opposite the unbalance" if on == 0 else f"{on} on the unbalance's side, {len(nominal) - on} opposite")
    return f"the balls settled on the line through the unbalance, {where}; nominal angles"


def explain_regime(label: str) -> str:
    """What a regime label means, in words.

    >>> explain_regime("side (0°, 0°)")
    "the balls settled on the line through the unbalance, all on the unbalance's side, adding to it; nominal angles"
    >>> explain_regime("non-synchronous")
    'the balls keep circling relative to the rotor instead of settling'
    """
    if label.startswith("side (") and label.endswith(")"):
        return _side(label)
    bits = label.removeprefix("side ")
    if bits != label and bits and set(bits) <= {"0", "1"}:  # a steady side motion (seed 003's number k)
        away = bits.count("1")
        return (f"a side motion: the balls on the line of the rotor's deflection, {len(bits) - away} towards it and "
                f"{away} away from it; they do not cancel the unbalance")
    if label.startswith("main"):
        return "a balanced motion: the balls where they cancel the unbalance"
    for key in sorted(_REGIMES, key=len, reverse=True):
        if label == key or label.startswith(key + " (") or label.startswith(key + ":"):
            return _REGIMES[key]
    return ""


def _named(label: str, angles: Sequence[float | None] | None = None) -> str:
    why = explain_regime(label)
    seen = f", measured {', '.join(people.angle_deg(a) for a in angles)}" if angles and why.endswith("angles") else ""
    return f"{label} [{why}{seen}]" if why else label


# --------------------------------------------------------------------------- evidence


def _balance_status(outcomes: Sequence[str]) -> str:
    if outcomes and all(o == "balanced" for o in outcomes):
        return "yes"
    return "not-settled" if any(o == "not settled" for o in outcomes) else "no"


def _balance_fix(facts: MachineFacts | None, speed: float | None, status: str, t_end: float | None) -> str:
    if status == "yes":
        return ""
    if facts is not None and facts.balls and facts.capacity < facts.unbalance:
        return (f"heavier balls: they cancel at most {people.unbalance(facts.capacity)}, the unbalance is "
                f"{people.unbalance(facts.unbalance)}")
    p = facts.first_forward if facts is not None else None
    if p is not None and speed is not None and speed < p:
        return f"run above the first forward critical speed of {people.speed(p)}, or soften the mounts"
    if status == "not-settled" and t_end:
        return f"simulate longer than {people.duration(t_end)} for a verdict"
    return ""


def _angles_of(row: Mapping[str, Any]) -> list[float | None] | None:
    a = row.get("final_ball_angles_deg")
    if isinstance(a, Mapping):
        return [v for vs in a.values() for v in vs]
    return list(a) if a else None


def _starts(rows: Rows, facts: MachineFacts | None, speed: float | None, t_end: float | None,
            where: str) -> VerdictLine:
    outcomes = [str(r["outcome"]) for r in rows]
    status = _balance_status(outcomes)
    counts: dict[str, list[Mapping[str, Any]]] = {}
    for r in rows:
        counts.setdefault(str(r["outcome"]), []).append(r)
    parts = [f"{_named(o, _angles_of(rs[0]) if o != 'balanced' else None)} from {people.share(len(rs), len(rows))} "
             "starts" for o, rs in sorted(counts.items(), key=lambda kv: -len(kv[1]))]
    within = f" within {people.duration(t_end)}" if t_end else ""
    good = len(counts.get("balanced", []))
    word = {"yes": "Balances", "no": "Balances from some starts only" if good else "Does not balance",
            "not-settled": "Not settled"}[status]
    return VerdictLine("balances", status, f"{word} {where}{within}: " + "; ".join(parts) + ".",
                       _balance_fix(facts, speed, status, t_end))


def _settled_by(ds: Any, row: Mapping[str, Any]) -> float | None:
    """When a balanced start's vibration fell for good below the balanced threshold
    (:data:`~rotorlab.explore._outcome.BALANCED_FRACTION` of the unbalance response), from its
    saved history (s); None without one."""
    import numpy as np

    from rotorlab.explore._outcome import BALANCED_FRACTION

    var = "amplitude" if "amplitude" in ds and "time" in ds["amplitude"].dims else "displacement"
    if var not in ds or "time" not in ds[var].dims or "reference_amplitude" not in ds:
        return None
    ratio = ds[var] / ds["reference_amplitude"]
    if "station" in ratio.dims:
        ratio = ratio.max("station")
    pick = {d: row[k] for d, k in (("ic", "ic"), ("speed", "speed")) if d in ratio.dims and k in row}
    try:
        r = np.asarray(ratio.sel(pick).values, dtype=float).reshape(-1)
    except (KeyError, ValueError):
        return None
    above = np.nonzero(~(r <= BALANCED_FRACTION))[0]
    t = np.asarray(ds["time"].values, dtype=float)
    if r.size != t.size or (above.size and above[-1] == r.size - 1):
        return None
    return float(t[above[-1] + 1]) if above.size else float(t[0])


def _simulate_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    t_end = ds.attrs.get("t_end")
    t_end = float(t_end) if t_end is not None else float(ds.time.values[-1]) if "time" in ds.coords else None
    by_speed: dict[float, list[Mapping[str, Any]]] = {}
    for r in rows:
        rpm = r.get("speed_rpm", r.get("final_speed_rpm"))
        by_speed.setdefault(round(float(rpm), 6) if rpm is not None else math.nan, []).append(r)
    out = []
    name = ds.attrs.get("name", "")
    for rpm, rs in by_speed.items():
        if all(r["outcome"] == "no balancer" for r in rs):
            continue
        speed = rpm / _RPM if math.isfinite(rpm) else None
        line = _starts(rs, facts, speed, t_end, f"at {people.speed(speed)} ({name})")
        times = [_settled_by(ds, r) for r in rs if r["outcome"] == "balanced"]
        if times and all(t is not None for t in times):
            when = (f"settled by {people.duration(max(times))}" if max(times) > 0 else
                    "were balanced from the start")
            line = VerdictLine(line.topic, line.status, line.sentence[:-1] + f"; the balanced ones {when}.", line.fix)
        out.append(line)
    return out


def _basin_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    if not rows or "count" not in ds or "outcome" not in ds or "balanced" not in [str(r) for r in ds["regime"].values]:
        return []  # not a balancer's basin (e.g. a toroidal ball's working and spare points)
    from rotorlab.analyses._verdict import basin_verdict

    test = basin_verdict(ds)
    n = rows[0]["n"]
    parts = [f"{_named(str(r['regime']))} from {people.share(int(r['count']), n)} starts" for r in rows if r["count"]]
    good = sum(int(r["count"]) for r in rows if r["regime"] == "balanced")
    status = "not-settled" if not test["settled"] else ("yes" if good == n else "no")
    speed = ds.attrs.get("spin_speed")
    where = f"at {people.speed(float(speed))} " if speed is not None else ""
    fix = (f"a horizon of {people.duration(test['horizon_needed_s'])}" if status == "not-settled" else
           _balance_fix(facts, float(speed) if speed is not None else None, status, None))
    word = {"yes": "Balances", "no": "Balances only partly", "not-settled": "No verdict yet"}[status]
    t_end = float(ds["horizon"].values[-1])
    return [VerdictLine("balances", status, f"{word} {where}({ds.attrs.get('name', '')}, basin, within "
                        f"{people.duration(t_end)}): " + "; ".join(parts) + ".", fix)]


def _run_up_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    if not rows or "passed" not in rows[0]:
        return _jeffcott_run_up(ds, rows, facts)
    import numpy as np

    name = ds.attrs.get("name", "")
    crit = rows[0]["critical_speeds"]
    passed = [r for r in rows if r["captured_at"] is None and r["passed"] >= 1]
    peak = float(np.nanmax(ds["amplitude"].values)) if "amplitude" in ds else math.nan
    status = "yes" if len(passed) == len(rows) else "no"
    first = f" ({people.speed(crit[0])})" if crit else ""
    sag = " (the static sag under gravity included)" if facts is not None and facts.lateral_gravity > 0 else ""
    sentence = (f"{name}: {people.share(len(passed), len(rows))} starts pass the first critical speed{first}; "
                f"largest distance from the axis {people.length(peak)}{sag}, final speed "
                f"{people.speed(max(r['final_speed'] for r in rows if r['final_speed'] is not None))}.")
    fix = ""
    if status == "no":
        need = [r.get("passing_torque") for r in rows if r.get("passing_torque") is not None]
        fix = (f"a stall torque of at least {people.torque(max(need))} (the smallest that passes)" if need else
               "a stronger motor (more stall torque); passing_torque = true finds the least")
    lines = [VerdictLine("run-up", status, sentence, fix)]
    with_balls = [r for r in rows if r["outcome"] != "no balancer"]
    if with_balls:
        t_end = float(ds.time.values[-1]) if "time" in ds.coords else None
        top = max(r["final_speed"] for r in with_balls if r["final_speed"] is not None)
        lines.append(_starts(with_balls, facts, top, t_end, f"after the run-up ({name})"))
    return lines


def _jeffcott_run_up(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    if not rows or "max_amplitude" not in rows[0]:
        return []
    peak = max(rows, key=lambda r: r["max_amplitude"] or 0.0)
    synced = sum(bool(r["synchronised"]) for r in rows)
    status = "yes" if synced == len(rows) else "no"
    return [VerdictLine("run-up", status, f"{ds.attrs.get('name', '')}: transient peak "
                        f"{people.length(peak['max_amplitude'])} at {people.number(peak['speed_at_max_rpm'])} rpm "
                        f"(without balls {people.length(peak['max_amplitude_without'])}); balls synchronised in "
                        f"{people.share(synced, len(rows))} run-ups.",
                        "" if status == "yes" else "a faster run-up through the critical speed")]


def _chart_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    from rotorlab.explore._outcome import true_runs

    if not rows or ds.attrs.get("parameter") or any(k in rows[0] for k in ("ball_mass", "ball_damping")):
        return []
    if "start_rpm" in rows[0]:  # a rotor with balls: the stable intervals of the balanced (main) motions
        main = [r for r in rows if r["method"] == "exact" and str(r["motion"]).startswith("main")]
        spans = sorted(dict.fromkeys((r["start_rpm"], r["stop_rpm"]) for r in main))
        speeds = list(ds.speed.values * _RPM) if "speed" in ds.coords else [a for s in spans for a in s]
    elif "speed_rpm" in rows[0] and "stable" in rows[0]:
        speeds = [r["speed_rpm"] for r in rows]
        spans = true_runs(speeds, [bool(r["stable"]) and bool(r["exists"]) for r in rows])
    else:
        return []
    if not speeds:
        return []
    checked = f"{people.number(min(speeds))} to {people.number(max(speeds))} rpm"
    name = ds.attrs.get("name", "")
    if spans:
        text = ", ".join(f"{people.number(a)} to {people.number(b)} rpm" if a != b else f"{people.number(a)} rpm"
                         for a, b in spans)
        return [VerdictLine("stable speeds", "yes", f"The balanced state is stable from {text} ({name}; checked "
                            f"{checked}, exact eigenvalues).")]
    p = facts.first_forward if facts is not None else None
    reason, fix = "", ""
    if p is not None and max(speeds) < p * _RPM:
        reason = f": every speed checked lies below the first forward critical speed {people.speed(p)}"
    if p is not None:
        fix = f"run above the first forward critical speed of {people.speed(p)}, or soften the mounts"
    return [VerdictLine("stable speeds", "no", f"The balanced state is unstable at every speed checked ({checked}, "
                        f"{name}){reason}.", fix)]


def _knock_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    probs = [r for r in rows if r.get("contact_probability") is not None]
    if not probs:
        return []

    def at(r: Mapping[str, Any]) -> str:
        n = int(r["runs"]) - int(r.get("failed") or 0)
        hit = round(r["contact_probability"] * n)
        bound = (f", at most {people.relative(r['probability_high'])} with 95 % confidence"
                 if hit == 0 and r.get("probability_high") is not None else "")
        return (f"{people.share(hit, n)} run-ups at ball damping {people.number(r['ball_damping'])} N*m*s/rad"
                + bound + (f", largest impulse {people.number(r['largest_impulse'])} N*s" if hit else ""))

    worst = max(probs, key=lambda r: r["contact_probability"])
    best = min(probs, key=lambda r: r["contact_probability"])
    margins = [r["least_margin"] for r in probs if r.get("least_margin") is not None]
    every = ds.attrs.get("margin_sample_interval")
    sampled = f", sampled every {people.duration(every)}" if every else ""
    if worst["contact_probability"] == 0:
        least = (f"; least margin {people.length(min(margins))} of the {people.length(ds.attrs['gap'])} gap"
                 f"{sampled}" if margins and "gap" in ds.attrs else "")
        return [VerdictLine("contact", "yes", f"No contact: {at(worst)}{least} ({ds.attrs.get('name', '')}).")]
    text = f"Touches the stator in {at(worst)}" + (f"; {at(best)}" if best is not worst else "")
    fix = (f"a ball damping of {people.number(best['ball_damping'])} N*m*s/rad"
           if best["contact_probability"] < worst["contact_probability"] else
           "a larger gap (or, for a stator centred where the rotor rests, model.clearances[0].center_at_rest = true)")
    if facts is not None and facts.rest_offset is not None and facts.gap is not None and facts.rest_offset > facts.gap:
        text += (f"; at rest the rotor already lies {people.length(facts.rest_offset)} from the stator's centre, "
                 f"beyond the gap {people.length(facts.gap)}: it rests on the stator, with or without balls")
        fix = f"give {facts.gap_key}.center_at_rest = true (the stator centred where the rotor rests)"
    clear = [r["least_margin"] for r in probs if r.get("least_margin") is not None and r["contact_probability"] == 0]
    least = (f"; where no run-up touched, the least margin is {people.length(min(clear))}{sampled}" if clear
             else "; least margin 0 (touched)")
    return [VerdictLine("contact", "no", text + f" ({ds.attrs.get('name', '')}{least}).", fix)]


def _steady_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    if not rows or "exists" not in rows[0]:
        return []
    speed = rows[0].get("speed", ds.attrs.get("spin_speed"))
    speed = float(speed) if speed is not None else None

    def stable_balanced_motion(r: Mapping[str, Any]) -> bool:
        if "verdict_exact" in r:  # a rotor with balls: the main (balanced) motions, exact eigenvalues
            return str(r["motion"]).startswith("main") and r["verdict_exact"] == "stable"
        return bool(r["stable"]) and r["kind"] == "balanced"

    stable_balanced = any(r["exists"] and stable_balanced_motion(r) for r in rows)
    status = "yes" if stable_balanced else "no"
    at = f" at {people.speed(speed)}" if speed else ""
    stable = [str(r.get("label", r["motion"])) for r in rows if r["exists"] and (
        r["verdict_exact"] == "stable" if "verdict_exact" in r else r["stable"])]
    text = ("stable (exact eigenvalues)" if stable_balanced else "absent or unstable") + (
        f"; stable there: {', '.join(_named(m) for m in stable)}" if stable and not stable_balanced else "")
    return [VerdictLine("balances", status, f"The balanced steady motion{at} is {text} ({ds.attrs.get('name', '')}).",
                        _balance_fix(facts, speed, status, None))]


def _tolerances_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    from rotorlab.analyses._tolerances import most_sensitive

    top = most_sensitive(ds, "p_balanced") if "output" in ds.coords else None
    if top is None:
        return []
    name, st, conf = top
    return [VerdictLine("tolerances", "info", f"P(balanced) is most sensitive to {name} (total Sobol index "
                        f"{st:.2f} ± {conf:.2f}; {ds.attrs.get('name', '')}).")]


for _type, _fn in (("tolerances", _tolerances_evidence), ("simulate", _simulate_evidence), ("basin", _basin_evidence), ("run-up", _run_up_evidence),
                   ("stability-chart", _chart_evidence), ("machine-knock", _knock_evidence),
                   ("steady", _steady_evidence)):
    register_evidence(_type, _fn)


def _design_evidence(ds: Any, rows: Rows, facts: MachineFacts | None) -> list[VerdictLine]:
    from rotorlab.analyses._design_case import design_evidence

    return design_evidence(ds, rows, facts)


register_evidence("design", _design_evidence)


# --------------------------------------------------------------------------- the verdict

_WHIRL = {"F": "forward", "B": "backward", "M": "mixed"}


def _critical_line(case: Any, facts: MachineFacts | None) -> VerdictLine | None:
    entries = facts.critical_speeds if facts is not None else []
    where = "balls locked" if facts is not None and facts.balls else "structure"
    if not entries:
        from rotorlab.analyses._linear import critical_summary

        entries = critical_summary(case.model).get("critical_speeds", [])
    if not entries:
        p = case.model.critical_speed() if hasattr(case.model, "critical_speed") else None
        if p is None:
            return None
        return VerdictLine("critical speeds", "info", f"{people.speed(p)} (undamped).")
    seen, parts = set(), []
    for e in entries:
        key = (people.number(e["speed_rpm"]), e["whirl"])
        if key in seen or len(parts) >= 4:
            continue
        seen.add(key)
        excited = "excited by unbalance" if e["excited_by_unbalance"] else (e["note"] or "not excited by unbalance")
        parts.append(f"{people.number(e['speed_rpm'])} rpm {_WHIRL.get(e['whirl'], e['whirl'])} ({excited})")
    return VerdictLine("critical speeds", "info", f"undamped, {where}: " + "; ".join(parts) + ".")


def _operating_line(facts: MachineFacts | None) -> VerdictLine | None:
    if facts is None or not facts.operating or facts.first_forward is None:
        return None
    p = facts.first_forward
    speeds: dict[str, list[str]] = {}
    for where, w in facts.operating:
        speeds.setdefault(people.number(w), []).append(where.removeprefix("analysis ").replace(
            "the drive's final speed", "drive"))
    parts = [f"{people.speed(w)} ({', '.join(speeds[people.number(w)])}) = {people.number(w / p)} p"
             for w in sorted({float(people.number(w)): w for _, w in facts.operating}.values())]
    low = [w for _, w in facts.operating if w < p]
    head = f"p = {people.speed(p)}, the first forward critical speed; runs at " + "; ".join(parts) + "."
    if not facts.balls:
        return VerdictLine("operating speed", "info", head)
    if not low:
        return VerdictLine("operating speed", "yes", head + " All above p, where a balancer can work.")
    return VerdictLine("operating speed", "no", head + f" A balancer works only above {people.speed(p)}.",
                       f"run above {people.speed(p)}, or soften the mounts until p falls below "
                       f"{people.speed(min(low))}")


def machine_verdict(case: Any, results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[VerdictLine]:
    """The verdict on a case's machine from its results.

    Parameters
    ----------
    case : rotorlab.io.Case
    results : mapping of str to xarray.Dataset
        By analysis name (:func:`rotorlab.analyses.run_case`).
    rows : mapping of str to list of dict
        Their summary rows (:func:`rotorlab.analyses.summarize`).

    Returns
    -------
    list of VerdictLine
        Critical speeds and the operating speed first, then the evidence of each analysis in
        the case's order, then "not computed" lines for a balancer machine's missing topics.
    """
    try:
        facts = machine_facts(case)
    except (ValueError, ArithmeticError):
        facts = None
    lines = [line for line in (_critical_line(case, facts), _operating_line(facts)) if line is not None]
    stable_at: dict[Any, str] = {}  # the races of a variant -> the chart that found it stable somewhere
    found = []
    for a in case.analyses:
        ds = results.get(a.name)
        evidence = VERDICT_EVIDENCE.get(a.type)
        if ds is not None and evidence is not None:
            races = ds.attrs.get("races")
            key = None if races is None else tuple(int(r) for r in (races if hasattr(races, "__len__") else [races]))
            for line in evidence(ds, rows.get(a.name, []), facts):
                found.append((key, line))
                if line.topic == "stable speeds" and line.status == "yes":
                    stable_at.setdefault(key, a.name)
    for key, line in found:  # a "no" without a fix: where a chart of the same races found it stable
        if line.topic == "balances" and line.status == "no" and not line.fix and key in stable_at:
            line = VerdictLine(line.topic, line.status, line.sentence,
                               f"run at a speed where the balanced state is stable (see {stable_at[key]})")
        lines.append(line)
    if facts is not None and facts.balls:
        have = {line.topic for line in lines}
        for topic, analysis in (("balances", "simulate or basin"), ("stable speeds", "stability-chart"),
                                ("run-up", "run-up")):
            if topic not in have:
                lines.append(VerdictLine(topic, "info", f"not computed; add a {analysis} analysis to the case."))
        if facts.gap is not None and "contact" not in have:
            lines.append(VerdictLine("contact", "info", "not computed; add a machine-knock analysis to the case."))
    return lines
