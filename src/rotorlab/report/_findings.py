"""What each analysis found, in words and key numbers with units: the report's summary boxes.

One function per presentation family, ``findings(ds, rows) -> Findings``; each reads the
summary rows of :func:`rotorlab.analyses.summarize` (and the Dataset for context), so the
numbers in a box are the numbers of the tables below it. Within a family the analysis type
(``ds.attrs["analysis"]``) picks its sentence from a table of functions.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rotorlab import _people as people

if TYPE_CHECKING:
    import xarray

__all__ = ["Findings", "simulation_findings", "basin_findings", "steady_findings", "impact_findings",
           "linear_findings"]  # fmt: skip

Rows = Sequence[Mapping[str, Any]]
_WHIRL = {"F": "forward", "B": "backward", "M": "mixed"}


@dataclass(frozen=True)
class Findings:
    """The verdict of one analysis in words, and its key numbers (each with its unit)."""

    verdict: str
    numbers: tuple[str, ...] = ()


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" + ("" if n == 1 else "s")


def _pct(part: int, whole: int) -> str:
    return f"{people.number(100.0 * part / whole)} %" if whole else "–"


def _percent(fraction: float) -> str:
    return f"{people.number(100.0 * fraction)} %"


def _span(values: Sequence[float], shown: Callable[[float], str] = lambda v: f"{v:.3g}") -> str:
    low, high = shown(min(values)), shown(max(values))
    return low if low == high else f"{low} to {high}"


def _list(values: Sequence[float], fmt: str = ".0f") -> str:
    return ", ".join(format(v, fmt) for v in values)


# --------------------------------------------------------------------------- simulations


def simulation_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """Outcomes per speed ("balanced from 4 of 4 starts") and the final deflections.

    Examples
    --------
    >>> rows = [{"speed_rpm": 2400.0, "speed_ratio": 2.0, "outcome": "balanced",
    ...          "final_amplitude": 1e-6, "amplitude_ratio": 0.001}] * 2
    >>> f = simulation_findings(None, rows)
    >>> f.verdict
    'at 2400 rpm (omega/p = 2): balanced from 2 of 2 starts (100 %)'
    """
    from rotorlab.analyses._verdict import round_up_horizon
    from rotorlab.explore._settle import NOT_SETTLED

    verdicts, numbers = [], []
    for rpm in dict.fromkeys(r["speed_rpm"] for r in rows):
        here = [r for r in rows if r["speed_rpm"] == rpm]
        counts = Counter(r["outcome"] for r in here)
        parts = [f"{o} from {c} of {len(here)} starts ({_pct(c, len(here))})" for o, c in counts.most_common()]
        verdicts.append(f"at {rpm:.0f} rpm (omega/p = {here[0]['speed_ratio']:.3g}): " + "; ".join(parts))
        waiting = [r.get("settle_estimate_s") for r in here if r["outcome"] == NOT_SETTLED]
        if waiting:
            t_end = ds.attrs.get("t_end") if ds is not None else None
            by = max((t for t in waiting if t is not None), default=None)
            numbers.append(f"at {rpm:.0f} rpm {len(waiting)} of {len(here)} starts are not settled (still converging "
                           "towards balance" + (f", estimated to settle by {by:.3g} s" if by is not None else "")
                           + ")" + (f": the simulated time, {float(t_end):g} s, is too short for a verdict"
                                    if t_end is not None else "")
                           + (f"; a t_end of {round_up_horizon(1.25 * by):g} s would do" if by is not None else ""))
        amps = [r["final_amplitude"] for r in here if r["final_amplitude"] is not None]
        ratios = [r["amplitude_ratio"] for r in here if r["amplitude_ratio"] is not None]
        if amps:
            numbers.append(f"final shaft deflection at {rpm:.0f} rpm: {_span(amps, people.length)}"
                           + (f" ({_span(ratios, people.relative)} against the unbalance alone)" if ratios else ""))
    return Findings(". ".join(verdicts), tuple(numbers))


# --------------------------------------------------------------------------- basins and sweeps


def _working_point(ds: xarray.Dataset, rows: Rows) -> Findings:
    v = {r["quantity"]: r for r in rows}
    inside = v["psi_band_lo"]["value"] <= v["psi"]["value"] <= v["psi_band_hi"]["value"]
    verdict = (f"working point psi = {v['psi']['value']:.6g} rad, alpha = {v['alpha']['value']:.6g} rad"
               + ("" if inside else " (outside its own friction band)"))
    return Findings(verdict, (
        f"friction band psi {v['psi_band_lo']['value']:.6g} to {v['psi_band_hi']['value']:.6g} rad, "
        f"alpha {v['alpha_band_lo']['value']:.6g} to {v['alpha_band_hi']['value']:.6g} rad",
        f"small-oscillation frequencies {v['ring_frequency']['value']:.4g} and "
        f"{v['cross_section_frequency']['value']:.4g} rad/s",
        f"a released ball settles after {v['released_settle_time']['value']:.3g} s",
    ))  # fmt: skip


def _fractions(ds: xarray.Dataset, rows: Rows) -> Findings:
    if not rows:
        return Findings("no starts")
    n = rows[0]["n"]
    t_end = float(ds["horizon"].values[-1]) if "horizon" in ds.coords else math.nan
    first = rows[0]
    verdict = (f"{first['regime']} from {first['count']} of {n} starts ({_percent(first['fraction'])}) "
               f"after {t_end:g} s")
    numbers = [f"{r['regime']}: {r['count']} of {n} starts ({_percent(r['fraction'])})" for r in rows[1:]
               if r["count"]]
    if first.get("ci_low") is not None:
        numbers.append(f"{first['regime']} confidence interval {people.number(100.0 * first['ci_low'])} to "
                       f"{_percent(first['ci_high'])}")  # fmt: skip
    if first.get("fraction_half") is not None and first["fraction_half"] != first["fraction"]:
        numbers.append(f"{first['regime']} after {first['horizon_half_s']:g} s: {_percent(first['fraction_half'])}")
    if "count" in ds and "outcome" in ds:
        from rotorlab.analyses._verdict import basin_verdict

        test = basin_verdict(ds)
        if not test["settled"]:
            verdict = f"no verdict yet (horizon too short): {verdict}, so far"
        numbers.append(test["sentence"])
    if ds.attrs.get("horizon_rule"):
        numbers.append(str(ds.attrs["horizon_rule"]))
    return Findings(verdict, tuple(numbers))


_BASIN_FINDINGS: Mapping[str, Callable[[Any, Rows], Findings]] = {"working-point": _working_point}


def basin_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """Fraction of starts in each regime ("balanced from 1290 of 1296 starts (99.5 %)")."""
    return _BASIN_FINDINGS.get(ds.attrs.get("analysis", ""), _fractions)(ds, rows)


# --------------------------------------------------------------------------- steady motions


def _motions(ds: xarray.Dataset, rows: Rows) -> Findings:
    stable = [r["motion"] for r in rows if r["exists"] and r["verdict_exact"] == "stable"]
    exist = [r for r in rows if r["exists"]]
    disagree = sum(r["disagreement"] for r in rows)
    verdict = (f"stable by the exact eigenvalues: {', '.join(stable)}" if stable
               else "no steady motion is stable by the exact eigenvalues")  # fmt: skip
    numbers = [f"{_count(len(exist), 'steady motion')} exist"]
    numbers += [f"{r['motion']}: shaft deflection {r['amplitude'] * 1e3:.3g} mm" for r in exist
                if r["amplitude"] is not None and r["motion"] in stable]  # fmt: skip
    numbers.append(f"{_count(disagree, 'disagreement')} between the three methods")
    return Findings(verdict, tuple(numbers))


def _chart(ds: xarray.Dataset, rows: Rows) -> Findings:
    """Where the balanced (main) motions are stable by the exact eigenvalues, per value of the
    chart's second parameter if it has one; the other methods and the side motions after."""
    param = ds.attrs.get("parameter") or None
    unit = ds[param].attrs.get("units", "") if param and param in ds.coords else ""

    def spans(rs: Rows) -> str:  # main+ and main- share their intervals: each interval once
        found = dict.fromkeys((round(r["start_rpm"]), round(r["stop_rpm"])) for r in rs)
        return ", ".join(f"{a} to {b} rpm" for a, b in found) or "nowhere"

    def main(rs: Rows, method: str) -> Rows:
        return [r for r in rs if r["method"] == method and str(r["motion"]).startswith("main")]

    methods = [m for m in dict.fromkeys(r["method"] for r in rows) if m != "exact"]
    if param is None:
        side = [r for r in rows if r["method"] == "exact" and not str(r["motion"]).startswith("main")]
        numbers = [f"by {m}: {spans(main(rows, m))}" for m in methods]
        if side:
            names = ", ".join(dict.fromkeys(str(r["motion"]) for r in side))
            numbers.append(f"side motions ({names}) stable (exact) at {spans(side)}")
        return Findings(f"balanced motion stable (exact) at {spans(main(rows, 'exact'))}", tuple(numbers))
    values = [float(v) for v in ds[param].values] if param in ds.coords else sorted({r[param] for r in rows})
    per = {v: main([r for r in rows if r.get(param) == v], "exact") for v in values}
    idx = [i for i, v in enumerate(values) if per[v]]
    if not idx:
        verdict = f"balanced motion stable (exact) for none of the {len(values)} values of {param}"
    elif idx == list(range(idx[0], idx[-1] + 1)):  # one run of values: its ends
        verdict = (f"balanced motion stable (exact) for {param} = {values[idx[0]]:.4g} to {values[idx[-1]]:.4g} "
                   f"{unit} ({len(idx)} of {len(values)} values)").replace("  ", " ")
    else:
        verdict = (f"balanced motion stable (exact) for {len(idx)} of {len(values)} values of {param}: "
                   f"{_list([values[i] for i in idx], '.4g')} {unit}").rstrip()
    return Findings(verdict, tuple(f"{param} = {v:.4g} {unit}: {spans(rs)}".replace("  ", " ")
                                   for v, rs in per.items()))


def _verify(ds: xarray.Dataset, rows: Rows) -> Findings:
    parts, numbers = [], []
    for r in rows:
        best = max(r["fractions"].items(), key=lambda kv: kv[1]) if r["fractions"] else ("none", 0.0)
        parts.append(f"at {r['speed_rpm']:.0f} rpm {_percent(best[1])} of {r['starts']} starts end {best[0]}")
        numbers.append(f"at {r['speed_rpm']:.0f} rpm the simulation agrees with: "
                       + (", ".join(m for m in ("exact", "hamilton", "averaged") if r[f"agrees_{m}"]) or "no method"))
    return Findings("; ".join(parts), tuple(numbers))


def _run_up(ds: xarray.Dataset, rows: Rows) -> Findings:
    if not rows:
        return Findings("no starts")
    peak = max(rows, key=lambda r: r["max_amplitude"] or 0.0)
    synced = sum(r["synchronised"] for r in rows)
    verdict = (f"peak shaft deflection {peak['max_amplitude'] * 1e3:.3g} mm at {peak['speed_at_max_rpm']:.0f} rpm "
               f"with the balancer, {peak['max_amplitude_without'] * 1e3:.3g} mm at "
               f"{peak['speed_at_max_without_rpm']:.0f} rpm without")  # fmt: skip
    numbers = [f"balls synchronised in {synced} of {len(rows)} run-ups",
               f"final deflection {peak['final_amplitude'] * 1e3:.3g} mm at {peak['final_speed_rpm']:.0f} rpm"]
    ens = rows[0].get("ensemble")
    if ens and ens["balanced_share"] is not None:
        numbers.append(f"balanced at the end of the ramp in {ens['balanced']} of {ens['runs']} run-ups "
                       f"({ens['balanced_share_low']:.0%} to {ens['balanced_share_high']:.0%}, "
                       f"{ens['confidence']:.0%} Wilson), {ens['not_settled']} not settled")
        numbers += [f"transient peak at {c['speed'] * 30 / math.pi:.0f} rpm: median {c['median'] * 1e3:.3g} mm "
                    f"({c['low'] * 1e3:.3g} to {c['high'] * 1e3:.3g} mm, {c['coverage']:.0%})"
                    for c in ens["critical_peaks"] if c["median"] is not None]
    if rows[0].get("peak_saves_note"):
        numbers.append(rows[0]["peak_saves_note"])
    return Findings(verdict, tuple(numbers))


_STEADY_FINDINGS: Mapping[str, Callable[[Any, Rows], Findings]] = {
    "steady": _motions, "stability-chart": _chart, "verify": _verify, "run-up": _run_up}


def steady_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """Stable motions, stable speed intervals, verified fractions or run-up peaks."""
    return _STEADY_FINDINGS[ds.attrs["analysis"]](ds, rows)


# --------------------------------------------------------------------------- impacts


def _impact_run(ds: xarray.Dataset, rows: Rows) -> Findings:
    s = rows[0]
    eta = "–" if s["energy_ratio"] is None else f"{s['energy_ratio']:.3g}"
    if s.get("runaway_start_s") is not None:  # eta at the stop is the runaway's: give the run's before it
        pre = "–" if s["energy_ratio_before_runaway"] is None else f"{s['energy_ratio_before_runaway']:.3g}"
        eta = (f"{pre} before the runaway to the backward whirl from t = {s['runaway_start_s']:.4g} s ({eta} at the "
               f"stop; the runaway: {_count(s['impacts_runaway'], 'impact')}, "
               f"{s['energy_friction_runaway_J']:.3g} J against friction)")  # fmt: skip
    numbers = (f"sliding for {s['sliding_time_s']:.3g} s", f"energy ratio eta = {eta}",
               f"largest approach speed {s['max_approach_speed_m_s']:.3g} m/s")  # fmt: skip
    if s["regime"] == "failed":  # no regime and no count to trust: say why, nothing else
        return Findings(f"FAILED at t = {s['t_final_s']:.4g} s of {s['t_end_s']:g} s: {s['status_detail']}")
    if s["backward_whirl"]:  # the count is up to the stop, not over the requested time
        return Findings(f"stopped at t = {s['t_final_s']:.4g} s of {s['t_end_s']:g} s: the rotor rolls on its housing "
                        f"(dry-friction backward whirl, which this model cannot carry); "
                        f"{_count(s['impacts'], 'impact')} up to the stop", numbers)  # fmt: skip
    return Findings(f"regime {s['regime']}: {_count(s['impacts'], 'impact')} in {s['t_end_s']:g} s", numbers)


def _impact_sweep(ds: xarray.Dataset, rows: Rows) -> Findings:
    param, unit = ds.attrs.get("param", "value"), ds.attrs.get("param_units", "")
    numbers = []
    runs = sum(sum(r["regimes"].values()) for r in rows)
    for key, what in (("failed", "failed (left out of the medians)"),
                      ("backward_whirl", "stopped at the dry-friction backward whirl (their counts run to the stop)")):
        n = sum(r["regimes"][key] for r in rows)
        if n:  # first, so that it is never among the lines cut from the box
            at = ", ".join(f"{r['value']:g}" for r in rows if r["regimes"][key])
            numbers.append(f"{n} of {runs} runs {what}, at {param} = {at} {unit}".rstrip())
    numbers += [f"{param} = {r['value']:g} {unit}: median {r['impacts_median']:g} impacts, "
                f"mostly {r['regime'].replace('_', ' ')}" for r in rows if r["impacts_median"] is not None]  # fmt: skip
    medians = [r["impacts_median"] for r in rows if r["impacts_median"] is not None]
    verdict = (f"median impacts {min(medians):g} to {max(medians):g} over {len(rows)} values of {param}"
               if medians else "no finished runs")  # fmt: skip
    return Findings(verdict, tuple(numbers))


_IMPACT_FINDINGS: Mapping[str, Callable[[Any, Rows], Findings]] = {
    "impacts": _impact_run, "impacts-sweep": _impact_sweep}


def impact_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The regime and impact count of a run, or the median counts of a sweep."""
    return _IMPACT_FINDINGS[ds.attrs["analysis"]](ds, rows)


# --------------------------------------------------------------------------- linear rotors


def _crossings(ds: xarray.Dataset, rows: Rows) -> Findings:
    if not rows:
        return Findings("no critical speed in the range")
    def one(r) -> str:
        other = r["undamped_rpm"] if r["definition"] == "damped crossing" else r["damped_crossing_rpm"]
        both = (f"; {'undamped' if r['definition'] == 'damped crossing' else 'damped crossing'} "
                f"{other:.0f}, damping ratio {r['damping_ratio']:.2g}") if r["both_shown"] else ""
        return f"{r['speed_rpm']:.0f} ({_WHIRL[r['whirl']]}{both}" + (f"; {r['note']})" if r["note"] else ")")

    speeds = ", ".join(one(r) for r in rows)
    lines = sorted({r["harmonic"] for r in rows})
    return Findings(f"critical speeds ({rows[0]['definition']}) {speeds} rpm",
                    (f"natural frequencies there {_list([r['frequency_hz'] for r in rows], '.4g')} Hz",
                     "excitation line" + ("s " if len(lines) > 1 else " ") + ", ".join(f"{h}x" for h in lines)))


def _modes(ds: xarray.Dataset, rows: Rows) -> Findings:
    freqs = [r["frequency_hz"] for r in rows if r["frequency_hz"] is not None]
    whirl = Counter(_WHIRL[r["whirl"]] for r in rows)
    zeta = [r["damping_ratio"] for r in rows if r["damping_ratio"] is not None]
    damping = ("undamped (every damping ratio is 0)" if zeta and max(map(abs, zeta)) == 0.0 else
               f"damping ratios {min(zeta):.3g} to {max(zeta):.3g}" if zeta else "damping ratios unknown")
    if float(ds.attrs.get("speed", math.nan)) == 0.0:  # a rotor that does not spin has no whirl direction
        pairs = sum(1 for a, b in zip(freqs[::2], freqs[1::2]) if abs(a - b) <= 1e-6 * max(abs(a), 1e-12))
        shape = (f"at rest: no whirl direction; {pairs} pair(s) of equal frequency (x and y)" if pairs
                 else "at rest: no whirl direction")
        return Findings(f"natural frequencies {_list(freqs, '.4g')} Hz", (shape, damping))
    return Findings(f"natural frequencies {_list(freqs, '.4g')} Hz",
                    (", ".join(f"{n} {w}" for w, n in whirl.items()) + " whirl", damping))


def _unbalance(ds: xarray.Dataset, rows: Rows) -> Findings:
    shown = [r for r in rows if r["peak_amplitude"] is not None]
    note = next((r["note"] for r in rows if r.get("note")), "")
    if not shown:
        return Findings(note or "no finite response")
    top = max(shown, key=lambda r: r["peak_amplitude"])
    return Findings(f"largest orbit {top['peak_amplitude'] * 1e3:.4g} mm at {top['peak_speed_rpm']:.0f} rpm "
                    f"(node {top['label']})",
                    tuple(f"node {r['label']}: {r['peak_amplitude'] * 1e3:.4g} mm at {r['peak_speed_rpm']:.0f} rpm"
                          for r in shown) + ((note,) if note else ()))  # fmt: skip


def _identify(ds: xarray.Dataset, rows: Rows) -> Findings:
    ok = "converged" if int(ds.attrs.get("success", 0)) else "did NOT converge"
    return Findings(f"least squares {ok}; rms residual {float(ds.attrs.get('rms', math.nan)):.3g}",
                    tuple(f"{r['parameter']} = {r['value']:.6g} {r['unit']}" for r in rows))


def _audit(ds: xarray.Dataset, rows: Rows) -> Findings:
    return Findings(f"{_count(len(rows), 'finding')} in the printed data, each resolved",
                    (", ".join(r["finding"] for r in rows),))


_LINEAR_FINDINGS: Mapping[str, Callable[[Any, Rows], Findings]] = {
    "campbell": _crossings, "critical_speeds": _crossings, "modes": _modes, "unbalance_response": _unbalance,
    "identify": _identify, "data_audit": _audit}


def linear_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """Critical speeds, natural frequencies, peak responses, identified parameters or findings."""
    return _LINEAR_FINDINGS[ds.attrs["analysis"]](ds, rows)
