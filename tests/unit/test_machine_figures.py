"""What the machine's figures and tables show a reader (issue 29: a start-up figure of 3 starts x
7 stations drew 21 curves and 7 reference lines with no legend; the tables had a column per
unnamed finite-element node, all-zero whirl columns and a raw status column; the run-up figure
showed the static sag, not the vibration, without the gap and with unlabelled critical speeds).

The Datasets are built by hand (what the analyses return, see
:func:`rotorlab.analyses.machine_simulate` and :func:`rotorlab.analyses.machine_run_up`): the
figures are checked on known numbers, without a simulation.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from rotorlab.plot import machine_figures, to_plotly
from rotorlab.report._machine import machine_rows_table

# an FE rotor of 7 nodes: two bearings and a disc have names, four shaft nodes do not
STATIONS = ["bearing A", "1", "2", "disc", "4", "5", "bearing B"]


def _start_ups(stations=STATIONS, peak=3):
    """3 starts: vibration decaying from 1 mm, largest at station ``peak``."""
    t = np.linspace(0.0, 2.0, 101)
    shape = 0.2 + np.exp(-np.abs(np.arange(len(stations)) - peak))  # station weights, largest at peak
    disp = 1e-3 * np.exp(-2.0 * t)[None, :, None] * shape[None, None, :] * np.array([1.0, 0.5, 0.25])[:, None, None]
    return xr.Dataset(
        {"displacement": (("ic", "time", "station"), disp),
         "amplitude": (("ic", "station"), disp[:, -1, :]),
         "reference_amplitude": (("station",), 2e-4 * shape),
         "outcome": (("ic",), np.array(["balanced", "balanced", "not balanced"]))},
        coords={"ic": [0, 1, 2], "time": t, "station": stations},
        attrs={"analysis": "simulate"})


def test_start_up_figure_draws_the_named_stations_with_a_legend():
    ds = _start_ups()
    fig = machine_figures(ds, "start-up")["start-up-vibration"]
    (ax,) = fig.axes
    curves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2]
    assert len(curves) == 3 * 3  # 3 starts x the 3 named stations (not 3 x 7 = 21)
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "disc, start 2: not balanced" in legend and "bearing A, start 0: balanced" in legend
    assert {f"without balancing at {s}" for s in ("bearing A", "disc", "bearing B")} <= set(legend)
    assert not any(f"{s}," in text for s in ("1", "2", "4", "5") for text in legend)
    disc = next(ln for ln in curves if ln.get_label() == "disc, start 1: balanced")
    np.testing.assert_allclose(disc.get_ydata(), ds.displacement.values[1, :, 3] * 1e3)


def test_without_names_the_station_that_vibrates_most_is_drawn():
    ds = _start_ups(stations=[str(k) for k in range(7)], peak=4)
    (ax,) = machine_figures(ds, "s")["s-vibration"].axes
    curves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2]
    assert len(curves) == 3 and ax.get_title() == "s: vibration at 4"
    assert {t.get_text() for t in ax.get_legend().get_texts()} == {
        "start 0: balanced", "start 1: balanced", "start 2: not balanced", "without balancing"}


def test_run_up_figure_shows_the_vibration_about_the_rest_position_the_gap_and_the_critical_speeds():
    t = np.linspace(0.0, 10.0, 201)
    sag = 0.0157  # m: 40 kg on 25 kN/m
    from_rest = 0.008 * np.sin(np.pi * t / 10.0) ** 2
    ds = xr.Dataset(
        {"speed": (("ic", "time"), (100.0 * t / 10.0)[None]),
         "amplitude": (("ic", "time", "station"), (sag + from_rest)[None, :, None]),
         "displacement_from_rest": (("ic", "time", "station"), from_rest[None, :, None]),
         "clearance_distance": (("ic", "time"), from_rest[None]),  # the stator centred at rest
         "residual_amplitude": (("ic", "station"), np.array([[1e-4]])),
         "outcome": (("ic",), np.array(["balanced"]))},
        coords={"time": t, "station": ["drum"]},
        attrs={"analysis": "run-up", "critical_speeds": [24.7, 65.0], "gap": 0.03, "clearance_station": "drum"})
    speed_ax, vib_ax = machine_figures(ds, "up")["up-run-up"].axes
    assert vib_ax.get_ylabel() == "distance from the rest position (mm)"
    (curve,) = [ln for ln in vib_ax.get_lines() if len(ln.get_xdata()) > 2]
    np.testing.assert_allclose(curve.get_ydata(), from_rest * 1e3)  # no 15.7 mm of sag
    legend = [x.get_text() for x in vib_ax.get_legend().get_texts()]
    assert legend == ["drum, start 0: balanced", "gap at drum: 30 mm"]
    gap = next(ln for ln in vib_ax.get_lines() if ln.get_label() == "gap at drum: 30 mm")
    assert gap.get_ydata()[0] == 30.0
    # the critical speeds are lines on the speed panel with their value written on them
    labels = [a.get_text() for a in speed_ax.texts]
    assert labels == ["critical speed 1: 235.9 rpm", "critical speed 2: 620.7 rpm"]
    # the interactive twin carries the same: curves, the gap as a line, the labels
    twin = to_plotly(speed_ax.figure)
    assert {"drum, start 0: balanced", "gap at drum: 30 mm"} <= {d["name"] for d in twin["data"] if d["showlegend"]}
    red = [s["y0"] for s in twin["layout"]["shapes"] if s["line"]["color"] == "rgba(255,0,0,1)"]
    assert red == pytest.approx([24.7 * 30 / np.pi, 65.0 * 30 / np.pi, 30.0], rel=1e-12)
    assert {"critical speed 1: 235.9 rpm", "critical speed 2: 620.7 rpm"} <= {a["text"] for a in
                                                                            twin["layout"]["annotations"]}


def test_machine_tables_keep_named_stations_drop_zero_columns_and_the_raw_status():
    amp = {s: (0.0 if s == "bearing A" else 1e-4) for s in STATIONS}
    rows = [{"ic": i, "initial_ball_angles_deg": {"race 0": [0.0, 60.0]}, "final_speed_rpm": 3000.0,
             "final_ball_angles_deg": {"race 0": [-128.68, 128.68]}, "amplitude": amp,
             "reference_amplitude": {s: 0.0 if s == "bearing A" else 2e-4 for s in STATIONS},
             "outcome": "balanced" if i == 0 else "failed", "status": 0 if i == 0 else -3} for i in range(2)]
    header, body = machine_rows_table(_start_ups(), rows)
    # the named stations that vibrate (bearing A stays at 0 in every row: no column of zeros)
    assert header == ("start", "initial ball angles", "final speed (rpm)", "final ball angles",
                      "vibration at disc (mm)", "vibration at bearing B (mm)", "outcome")
    assert [b[-1] for b in body] == ["balanced", "failed", ""]
    assert body[-1][4:6] == ("0.2", "0.2")  # without balancing, mm
    # a steady chart whose whirl is zero (balanced) everywhere has no whirl column; round-off is 0
    chart = [{"speed_rpm": 3000.0, "exists": True, "balanced": True, "stable": True, "max_real_eigenvalue": -1.0,
              "ball_angles_deg": {"race 0": [-128.68, 128.68]}, "amplitude": {s: 5.88e-12 for s in STATIONS}}]
    ds = _start_ups().assign_attrs(analysis="stability-chart")
    header, _ = machine_rows_table(ds, chart)
    assert not any("whirl" in h for h in header)
