"""Presentation of the ``tolerances`` analysis: which uncertain input P(balanced), the residual
vibration and the transient peak are most sensitive to (Sobol indices with their bootstrap
intervals, rows of :func:`rotorlab.analyses._tolerances.tolerances_rows`), and the spread of the
vibration over the machines (the Monte-Carlo envelope)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab import _people as people
from rotorlab.report._findings import Findings

if TYPE_CHECKING:
    import xarray

__all__ = ["tolerances_section", "tolerances_findings", "tolerances_tables", "sensitivity_sentences"]

Rows = Sequence[Mapping[str, Any]]
_TITLES = {"p_balanced": "P(balanced)", "residual_vibration": "the residual vibration",
           "transient_peak": "the transient peak"}  # fmt: skip


def _index(v: float | None, conf: float | None) -> str:
    return "–" if v is None else f"{v:.2f} ± {conf:.2f}" if conf is not None else f"{v:.2f}"


def _mean_text(output: str, mean: float | None) -> str:
    if mean is None:
        return "–"
    return f"{people.number(100.0 * mean)} %" if output == "p_balanced" else people.length(mean)


def sensitivity_sentences(ds: xarray.Dataset, rows: Rows) -> list[str]:
    """One sentence per output: its mean over the machines and the input it is most sensitive to
    (largest total-order index, with its interval), or that it did not vary."""
    out = []
    failed = int(ds.attrs.get("failed", 0))
    for output in [str(o) for o in ds["output"].values]:
        mine = [r for r in rows if r["output"] == output]
        title = _TITLES.get(output, output)
        mean = _mean_text(output, mine[0]["mean"] if mine else None)
        ranked = sorted((r for r in mine if r["ST"] is not None), key=lambda r: -r["ST"])
        if not ranked:
            why = f"{failed} integration(s) failed" if failed else "it is the same for every machine"
            out.append(f"{title[0].upper()}{title[1:]} (mean {mean}): no Sobol indices ({why}).")
            continue
        top = ranked[0]
        text = (f"{title[0].upper()}{title[1:]} (mean {mean}) is most sensitive to {top['input']} "
                f"(ST {_index(top['ST'], top['ST_conf'])}, S1 {_index(top['S1'], top['S1_conf'])})")  # fmt: skip
        if len(ranked) > 1:
            text += f", then {ranked[1]['input']} (ST {_index(ranked[1]['ST'], ranked[1]['ST_conf'])})"
        out.append(text + ".")
    return out


def _numbers(ds: xarray.Dataset) -> tuple[str, ...]:
    conf = f"{100.0 * float(ds.attrs.get('confidence', 0.95)):g} %"
    env = np.asarray(ds["envelope"].values, dtype=float)
    q = [float(v) for v in ds["quantile"].values]
    out = [f"{int(ds.sizes['sample'])} machines (N = {int(ds.attrs['n_base'])} base samples x "
           f"({int(ds.attrs['n_inputs'])} inputs + 2)), {int(ds.attrs['starts'])} ball starts each, "
           f"{people.duration(float(ds.attrs['t_end']))} at {people.speed(float(ds.attrs['speed']))} "
           f"(seed {int(ds.attrs['seed'])})",
           f"indices: SALib Saltelli/Jansen estimators, bootstrap {conf} intervals "
           f"({int(ds.attrs.get('resamples', 0))} resamples)",
           f"vibration in the last window: median {people.length(env[len(q) // 2, -1])}, "
           f"{100 * q[0]:g}-{100 * q[-1]:g} % band {people.length(env[0, -1])} to {people.length(env[-1, -1])}"]
    out += [str(d) for d in ds.attrs.get("distributions", [])]
    if int(ds.attrs.get("failed", 0)):
        out.append(f"{int(ds.attrs['failed'])} integration(s) failed: their outputs are not defined")
    return tuple(out)


def tolerances_findings(ds: xarray.Dataset, rows: Rows) -> Findings:
    """The verdict (the most influential input of each output) and the key numbers."""
    return Findings(" ".join(sensitivity_sentences(ds, rows)), _numbers(ds))


def _table_rows(ds: xarray.Dataset, rows: Rows) -> tuple[list[str], list[list[str]]]:
    outputs = [str(o) for o in ds["output"].values]
    head = ["input", *(f"{_TITLES.get(o, o)}: ST / S1" for o in outputs)]
    body = []
    for name in [str(i) for i in ds["input"].values]:
        line = [name]
        for o in outputs:
            r = next(r for r in rows if r["output"] == o and r["input"] == name)
            line.append(f"{_index(r['ST'], r['ST_conf'])} / {_index(r['S1'], r['S1_conf'])}")
        body.append(line)
    return head, body


def tolerances_section(ds: xarray.Dataset, rows: Rows) -> str:
    """HTML: the sentences, the distributions, then one table row per input."""
    from html import escape

    from rotorlab.report._table import table

    head, body = _table_rows(ds, rows)
    items = "".join(f"<li>{escape(str(d))}</li>" for d in ds.attrs.get("distributions", []))
    return ("".join(f"<p>{escape(s)}</p>" for s in sensitivity_sentences(ds, rows))
            + f"<p>Uncertain inputs:</p><ul>{items}</ul>" + table(head, body))  # fmt: skip


def tolerances_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """Rich tables for ``rotorlab run`` and ``rotorlab tolerances``: one per result."""
    from rotorlab.report._table import console_table

    return [console_table(f"{name}: " + " ".join(sensitivity_sentences(ds, rows[name])), *_table_rows(ds, rows[name]),
                          left="input") for name, ds in results.items()]  # fmt: skip
