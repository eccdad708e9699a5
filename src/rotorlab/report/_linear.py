"""HTML tables of the linear analyses in the report (critical speeds, modes, fits, audits)."""

from __future__ import annotations

import html
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

__all__ = ["linear_section"]

_WHIRL = {"F": "forward", "B": "backward", "M": "mixed"}
_WHIRL_CODE = {1: "forward", -1: "backward", 0: "mixed"}


def _e(value: Any) -> str:
    return html.escape(str(value), quote=True)


def _g(value: float | None, digits: int = 6) -> str:
    return "–" if value is None or not np.isfinite(value) else f"{value:.{digits}g}"


def _crossings(rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    """Critical speeds, those unbalance excites first, each with its definition, the other
    definition's value where they differ by more than 3 %, the mode's damping ratio and whirl."""
    if not rows:
        return '<p class="muted">No branch crosses an excitation line in this range.</p>'
    header = ["speed (rpm)", "definition", "other definition (rpm)", "damping ratio",
              "frequency (Hz)", "line", "whirl", "excited by unbalance"]
    has_mode = "mode" in rows[0]
    if has_mode:
        header.insert(6, "branch")
    body = []
    for r in rows:
        damped = r["definition"] == "damped crossing"
        other = r["undamped_rpm"] if damped else r["damped_crossing_rpm"]
        other_text = ("-" if other is None else f"{other:.4g} ({'undamped' if damped else 'damped crossing'})"
                      if r["both_shown"] else "within 3 %")
        row = [_g(r["speed_rpm"]), r["definition"], other_text, _g(r["damping_ratio"], 3),
               _g(r["frequency_hz"]), f"{r['harmonic']}x"]
        if has_mode:
            row.append(str(r["mode"]))
        body.append(row + [_WHIRL[r["whirl"]], "yes" if r["excited_by_unbalance"] else f"no: {r['note']}"])
    definition = rows[0]["definition_text"]
    return (table(header, body, numeric={0, 3, 4})
            + f'\n<p class="muted">{_e(definition[0].upper() + definition[1:])}.</p>')


def _campbell(ds: Any, rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    freq, whirl = ds.frequency.values, ds.whirl.values
    rpm = ds.speed_rpm.values
    ends = [(str(k), _WHIRL_CODE[int(whirl[0, k])], _g(freq[0, k]),
             _WHIRL_CODE[int(whirl[-1, k])], _g(freq[-1, k])) for k in range(freq.shape[1])]
    unstable = rpm[~ds.stable.values.astype(bool)]
    stability = ("Every mode decays or is neutral over the whole range (no instability)."
                 if unstable.size == 0 else
                 f"Unstable at {unstable.size} of {rpm.size} speeds, from {unstable[0]:.6g} rpm.")
    return "\n".join([
        "<h3>Critical speeds (damped crossings of the excitation lines)</h3>",
        _crossings(rows, table),
        "<h3>Natural frequencies at the ends of the range</h3>",
        table(("branch", f"whirl at {rpm[0]:.6g} rpm", "frequency (Hz)",
               f"whirl at {rpm[-1]:.6g} rpm", "frequency (Hz)"), ends, numeric={2, 4}),
        f'<p class="muted">{_e(stability)}</p>',
    ])


def _modes(rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    body = [(str(r["mode"]), _g(r["frequency_hz"]), _WHIRL[r["whirl"]], _g(r["damping_ratio"], 4),
             _g(r["log_decrement"], 4)) for r in rows]
    return "<h3>Modes</h3>\n" + table(("mode", "frequency (Hz)", "whirl", "damping ratio",
                                        "log decrement"), body, numeric={1, 3, 4})


def _unbalance(ds: Any, rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    a = ds.attrs
    n_unb = len(a.get("unbalance_nodes", []))
    couples = a.get("unbalance_couples", [0.0] * n_unb)
    couple_phases = a.get("unbalance_couple_phases", [0.0] * n_unb)
    parts = ", ".join(f"{m:.6g} kg*m at node {n} ({ph:.4g} rad)"
                      + (f" and a couple {c:.6g} kg*m^2 ({cph:.4g} rad)" if c else "")
                      for n, m, ph, c, cph in zip(a.get("unbalance_nodes", []), a.get("unbalance_magnitudes", []),
                                                  a.get("unbalance_phases", []), couples, couple_phases))
    body = [(r["label"], str(r["node"]),
             "–" if r["peak_amplitude"] is None else f"{r['peak_amplitude'] * 1e3:.4g}",
             _g(r["peak_speed_rpm"])) for r in rows]
    return "\n".join([
        f'<p class="muted">Unbalance: {_e(parts)}.</p>',
        "<h3>Largest orbit</h3>",
        *([f'<p class="muted">{_e(ds.attrs["note"])}</p>'] if ds.attrs.get("note") else []),
        table(("node", "index", "orbit semi-major axis (mm)", "at speed (rpm)"), body,
              numeric={2, 3}),
    ])


def _identify(ds: Any, rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    params = [(r["parameter"], r["unit"], _g(r["initial"]), _g(r["value"]),
               "–" if r["relative_std"] is None else f"{100 * r['relative_std']:.3g} %")
              for r in rows]
    meas = [(_g(float(ds.measurement_speed_rpm.values[j])), str(int(ds.measurement_mode.values[j])),
             _g(float(ds.measured.values[j])), _g(float(ds.predicted.values[j])),
             f"{float(ds.residual.values[j]):.3e}") for j in range(ds.sizes["measurement"])]
    ok = "converged" if int(ds.attrs.get("success", 0)) else "did NOT converge"
    return "\n".join([
        "<h3>Identified parameters</h3>",
        table(("parameter", "unit", "start", "identified", "standard deviation"), params,
              numeric={2, 3, 4}),
        "<h3>Measured and fitted natural frequencies</h3>",
        table(("speed (rpm)", "mode (rank)", "measured (Hz)", "model (Hz)",
               "weighted relative residual"), meas, numeric={0, 2, 3, 4}),
        f'<p class="muted">Least squares {ok} after {int(ds.attrs.get("n_evaluations", 0))} '
        f'model evaluations; rms of the residuals {float(ds.attrs.get("rms", np.nan)):.3e}.</p>',
    ])


def _audit(rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    body = [(r["finding"], r["printed"], r["resolved"], r["evidence"]) for r in rows]
    return "<h3>Data-audit findings</h3>\n" + table(("finding", "as printed", "resolved as",
                                                      "evidence"), body)


def linear_section(kind: str, ds: Any, rows: Sequence[dict[str, Any]],
                   table: Callable[..., str]) -> str:
    """Return the HTML tables of one linear analysis.

    Parameters
    ----------
    kind : str
        The analysis type.
    ds : xarray.Dataset
        Its result.
    rows : sequence of dict
        :func:`rotorlab.analyses.summarize_linear` of ``ds``.
    table : callable
        ``table(header, rows, numeric=...)`` renders an HTML table.

    Returns
    -------
    str
        "" for an analysis type without tables.
    """
    render = _SECTIONS.get(kind)
    return "" if render is None else render(ds, rows, table)


def _critical(ds: Any, rows: Sequence[dict[str, Any]], table: Callable[..., str]) -> str:
    return "<h3>Critical speeds (undamped, with the damped crossings)</h3>\n" + _crossings(rows, table)


_SECTIONS: dict[str, Callable[[Any, Sequence[dict[str, Any]], Callable[..., str]], str]] = {
    "campbell": _campbell,
    "critical_speeds": _critical,
    "modes": lambda ds, rows, table: _modes(rows, table),
    "unbalance_response": _unbalance,
    "identify": _identify,
    "data_audit": lambda ds, rows, table: _audit(rows, table),
}
