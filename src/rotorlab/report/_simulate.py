"""Report section of a simulation: the spin speeds used and the outcome of every start."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rotorlab._constants import RPM_PER_RAD_S as _RPM
from rotorlab.report._table import escape, table

if TYPE_CHECKING:
    import xarray

__all__ = ["simulation_section"]


def _angles(values: Sequence[float | None]) -> str:
    return "(" + ", ".join("–" if v is None else f"{v:.1f}°" for v in values) + ")"


def _outcome_cell(outcome: str) -> str:
    css = "outcome-balanced" if outcome == "balanced" else "outcome-bad"
    return f'<span class="{css}">{escape(outcome)}</span>'


def _amp(v: float | None) -> str:
    return "–" if v is None else f"{v * 1e3:.4g}"


def _ratio(v: float | None) -> str:
    return "–" if v is None else f"{v:.3g}"


def simulation_section(ds: xarray.Dataset, rows: Sequence[Mapping[str, Any]]) -> str:
    """Return the HTML of a simulation: spin speeds used, then one outcome row per start.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`.
    rows : sequence of dict
        :func:`rotorlab.analyses.summarize` of ``ds``.
    """
    speeds = [(f"{float(om):.6g}", f"{float(om) * _RPM:.6g}", f"{float(om) / (2 * math.pi):.6g}",
               f"{float(ds.speed_ratio.values[k]):.4g}") for k, om in enumerate(ds.speed.values)]  # fmt: skip
    header = ("speed (rpm)", "omega/p", "start angles", "final deflection (mm)",
              "× unbalance alone", "final ball angles", "outcome")  # fmt: skip
    body = [
        (f"{r['speed_rpm']:.0f}", f"{r['speed_ratio']:.3g}", _angles(r["initial_ball_angles_deg"]),
         _amp(r["final_amplitude"]), _ratio(r["amplitude_ratio"]),
         _angles(r["final_ball_angles_deg"]), _outcome_cell(r["outcome"]))  # fmt: skip
        for r in rows
    ]
    return "\n".join([
        "<h3>Spin speeds used</h3>",
        table(("rad/s", "rpm", "Hz", "omega/p"), speeds, numeric={0, 1, 2, 3}),
        "<h3>Outcomes</h3>",
        table(header, body, numeric={0, 1, 3, 4}, raw={6}),
    ])
