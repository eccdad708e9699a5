"""An impacts sweep keeps failed runs out of every impact statistic, and says so where all failed.

Review of the session-5 diff: the medians and quartiles left failed runs out, but the range
("min-max") still took their counts (a failed run's count is no result: e.g. the 1.4 million
"impacts" of issue 14), the "mostly" regime of a value whose runs all failed was "none" (the
first of all-zero fractions), and the console table formatted the missing median of such a value
and stopped with a TypeError. The HTML report and the console now share the row cells.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorlab.analyses import sweep_summary
from rotorlab.analyses._impacts import REGIMES
from rotorlab.cli._impacts import impact_tables
from rotorlab.report._impacts import SWEEP_COLUMNS, impact_section, sweep_cells

NAN = float("nan")


def _sweep() -> xr.Dataset:
    """Two stone masses, four sequences: at 1 kg two runs fail (one with 1.4 million partial
    impacts), at 2 kg all four fail. Medians as summarize_impact_sweep makes them (failed left out)."""
    regime = np.array([[1, -1, 2, -1], [-1, -1, -1, -1]])
    impacts = np.array([[3, 1_400_000, 5, 0], [7, 8, 9, 10]])
    frac = np.stack([(regime == c).mean(axis=1) for c in range(len(REGIMES))], axis=1)
    data = {
        "regime": (("value", "sequence"), regime), "impacts": (("value", "sequence"), impacts),
        "impacts_median": (("value",), [4.0, NAN]), "impacts_q25": (("value",), [3.5, NAN]),
        "impacts_q75": (("value",), [4.5, NAN]), "sliding_time_median": (("value",), [0.0, NAN]),
        "eta_median": (("value",), [NAN, NAN]), "regime_fraction": (("value", "regime_label"), frac),
        "failed_fraction": (("value",), (regime < 0).mean(axis=1)),
    }  # fmt: skip
    return xr.Dataset(data, coords={"value": [1.0, 2.0], "sequence": np.arange(4), "regime_label": list(REGIMES)},
                      attrs={"analysis": "impacts-sweep", "param": "stone_mass", "param_units": "kg", "t_end": 1.0,
                             "seed": 0, "n_sequences": 4, "interval": 0.035})  # fmt: skip


def test_failed_runs_are_left_out_of_the_range_and_named_where_all_failed():
    one, two = sweep_summary(_sweep())["rows"]
    assert (one["impacts_min"], one["impacts_max"], one["impacts_median"]) == (3, 5, 4.0)
    assert one["regimes"] == {"none": 0, "rebounds": 1, "sliding": 1, "backward_whirl": 0, "failed": 2}
    assert one["regime"] == "failed"  # 2 of 4 failed: the most frequent outcome
    assert (two["impacts_min"], two["impacts_max"], two["impacts_median"]) == (None, None, None)
    assert two["regime"] == "failed" and two["regimes"]["failed"] == 4


def test_report_and_console_show_the_same_cells():
    ds = _sweep()
    rows = sweep_summary(ds)["rows"]
    assert len(SWEEP_COLUMNS) + 1 == len(sweep_cells(rows[0]))
    assert sweep_cells(rows[0]) == ["1", "4", "3.5-4.5", "3-5", "0", "1", "1", "0", "2", "-"]
    assert sweep_cells(rows[1]) == ["2", "-", "-", "-", "0", "0", "0", "0", "4", "-"]
    (table,) = impact_tables({"masses": ds})  # formatted a None median before: TypeError
    assert [c.header for c in table.columns] == ["stone_mass (kg)", *SWEEP_COLUMNS]
    assert list(table.columns[1].cells) == ["4", "-"] and list(table.columns[8].cells) == ["2", "4"]
    html = impact_section(ds)
    assert "<td" in html and "1400000" not in html
