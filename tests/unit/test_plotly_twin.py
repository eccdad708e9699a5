"""The interactive twin of a figure (:func:`rotorlab.plot.to_plotly`) carries what the PNG shows:
the same data, the legend, and for a basin map the regime of each start under the pointer."""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from rotorlab.plot import basin_figure, campbell_figure, to_plotly


def test_basin_map_twin_names_the_regime_of_each_start():
    x = np.radians(np.arange(0.0, 360.0, 45.0))
    label = np.zeros((8, 8, 1), dtype=np.int16)
    label[np.arange(8), np.arange(8), 0] = 2  # the balls start together: they move as one
    label[1, 5, 0] = 1
    names = ["balanced", "non-synchronous", "side (180°, 180°)", "other"]
    ds = xr.Dataset({"label": (("psi_2", "psi_1", "horizon"), label, {"labels": names})},
                    coords={"psi_1": ("psi_1", x, {"units": "rad"}), "psi_2": ("psi_2", x, {"units": "rad"}),
                            "horizon": ("horizon", [4.0], {"units": "s"})},
                    attrs={"input_units_psi_1": "deg", "input_units_psi_2": "deg"})
    twin = to_plotly(basin_figure(ds))
    json.dumps(twin)  # what the report embeds
    (mesh,) = [d for d in twin["data"] if d["type"] == "heatmap"]
    np.testing.assert_allclose(mesh["x"], np.degrees(x))
    expected = [[names[k] for k in row] for row in label[:, :, 0]]
    assert mesh["text"] == expected  # row j is psi_2[j], column i psi_1[i]
    legend = [d["name"] for d in twin["data"] if d.get("showlegend")]
    assert legend == ["balanced (85.9%)", "non-synchronous (1.6%)", "side (180°, 180°) (12.5%)", "other (0.0%)"]
    assert twin["layout"]["xaxis"]["title"]["text"] == "psi_1 (deg)"


def test_campbell_twin_has_the_branches_and_critical_speeds_of_the_result():
    from rotorlab.linear import RPM, campbell
    from rotorlab.linear.cases import friswell_rotor

    ds = campbell(friswell_rotor(), RPM * np.linspace(0, 4000, 21), n_modes=4)
    twin = to_plotly(campbell_figure(ds))
    (crit,) = [d for d in twin["data"] if d["name"] == "critical speed"]
    on_1x = ds.critical_harmonic.values == 1
    np.testing.assert_allclose(crit["x"], ds.critical_speed_rpm.values[on_1x])
    np.testing.assert_allclose(crit["y"], ds.critical_frequency.values[on_1x])
    branches = [d for d in twin["data"] if d["name"].startswith("mode")]
    assert {d["name"].split("-")[0] for d in branches} == {"mode0", "mode1", "mode2", "mode3"}
    assert {d["name"] for d in twin["data"] if d.get("showlegend")} == {"forward", "backward", "critical speed"}
    assert [d["line"]["dash"] for d in twin["data"] if d["name"] in ("forward", "backward")] == ["solid", "dash"]
