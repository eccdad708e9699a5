"""Every figure ``rotorlab run`` draws for the built-in cases renders cleanly.

Each built-in case runs on reduced grids and times (what is drawn, not how much, is checked):
every figure must draw without a matplotlib warning (a collapsed constrained layout, a legend
that does not fit, a log axis with no positive data) and with nothing outside the figure (its
tight bounding box inside the canvas: no clipped title, label, legend or annotation).
"""

from __future__ import annotations

import tomllib
import warnings
from importlib import resources
from pathlib import Path

import pytest
import tomli_w
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import builtin_cases

# Smaller settings of the analyses of the built-in cases, by key (what the key holds is kept:
# a time stays a time, a [start, stop, count] keeps its range).
_SHORT_TIME = {"simulate": "1 s", "run-up": "1 s", "impacts": "0.3 s", "impacts-sweep": "0.3 s",
               "basin": "2 s", "working-point": "1 s", "machine-knock": "1 s"}


def _reduce(analysis: dict) -> dict:
    kind = analysis["type"]
    a = dict(analysis)
    if "t_end" in a and kind in _SHORT_TIME:
        a["t_end"] = _SHORT_TIME[kind]
    for key, small in (("n_save", 200), ("n_speeds", 21), ("ball_angle_points", 3),
                       ("n_sequences", 2), ("points", 61), ("n_horizons", 2), ("starts", 2)):
        if key in a:
            a[key] = min(a[key], small)
    for key in ("x", "y"):
        if key in a:
            a[key] = [*a[key][:3], 6]
    if kind == "stability-chart" and "values" in a:
        a["values"] = [*a["values"][:2], 3]
    if kind == "impacts-sweep":
        a["values"] = a["values"][:2]
    if kind == "verify":
        a["ball_angle_points"] = 2
    return a


def _reduced_case(name: str, tmp_path: Path) -> Path:
    text = resources.files("rotorlab.cases").joinpath(f"{name}.toml").read_text()
    doc = tomllib.loads(text)
    doc["analysis"] = [_reduce(a) for a in doc.get("analysis", [])]
    path = tmp_path / f"{name}.toml"
    path.write_text(tomli_w.dumps(doc))
    return path


def _outside(fig) -> list[str]:
    """Artists of ``fig`` whose extent leaves the figure (in pixels, 1 px tolerance)."""
    renderer = fig.canvas.get_renderer()
    width, height = fig.bbox.width, fig.bbox.height
    bad = []
    for ax in fig.axes:
        for artist in [ax, *ax.get_children(), *([ax.get_legend()] if ax.get_legend() else [])]:
            if not artist.get_visible() or artist.figure is None:
                continue
            if artist is not ax and artist.get_clip_on() and artist.get_clip_box() is not None:
                continue  # clipped to the axes: what shows of it is inside them
            try:
                box = artist.get_window_extent(renderer)
            except Exception:  # noqa: BLE001 - artists without an extent
                continue
            if box.width == 0 and box.height == 0:
                continue
            if box.x0 < -1 or box.y0 < -1 or box.x1 > width + 1 or box.y1 > height + 1:
                bad.append(f"{type(artist).__name__} {getattr(artist, 'get_text', lambda: '')()!r}"
                           f" at {box.bounds}")
    tight = fig.get_tightbbox(renderer)
    w_in, h_in = fig.get_size_inches()
    if tight.x0 < -0.02 or tight.y0 < -0.02 or tight.x1 > w_in + 0.02 or tight.y1 > h_in + 0.02:
        bad.append(f"tight bbox {tight.bounds} outside the figure ({w_in} x {h_in} in)")
    return bad


@pytest.mark.parametrize("name", sorted(builtin_cases()))
def test_builtin_case_figures_render_cleanly(name, tmp_path, monkeypatch):
    import rotorlab.report

    drawn = {}

    def keep(out, case, results, figures, tables):
        for name, stems in figures.items():  # by analysis, then by file stem
            drawn.update({f"{name}/{stem}": fig for stem, fig in stems.items()})
        return Path(out) / "report.html"

    monkeypatch.setattr(rotorlab.report, "write_report", keep)
    result = CliRunner().invoke(app, ["-q", "run", str(_reduced_case(name, tmp_path)),
                                      "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert drawn, f"{name}: no figures"
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    for stem, fig in drawn.items():
        FigureCanvasAgg(fig)  # the canvas savefig("x.png") draws on
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            fig.canvas.draw()
        messages = [str(w.message) for w in caught]
        assert not messages, f"{name}/{stem}: {messages}"
        assert not _outside(fig), f"{name}/{stem}: {_outside(fig)}"


def _basin(x_values, **attrs):
    import numpy as np
    import xarray as xr

    n = len(x_values)
    return xr.Dataset(
        {"label": (("psi_2", "psi_1", "horizon"), np.zeros((n, n, 1), dtype=np.int16),
                   {"labels": ["balanced", "other"]})},
        coords={"psi_1": ("psi_1", x_values, {"units": "rad"}),
                "psi_2": ("psi_2", x_values, {"units": "rad"}),
                "horizon": ("horizon", [2.0], {"units": "s"})},
        attrs=attrs)


def test_basin_map_in_the_units_of_its_input():
    import numpy as np

    from rotorlab.plot import basin_figure

    # recorded as given in degrees (the autobalancer case: 0 to 350 deg): drawn in degrees
    deg = np.radians(np.linspace(0.0, 350.0, 8))
    ax = basin_figure(_basin(deg, input_units_psi_1="deg", input_units_psi_2="deg")).axes[0]
    assert ax.get_xlabel() == "psi_1 (deg)" and ax.get_ylabel() == "psi_2 (deg)"
    assert 340.0 < ax.get_xlim()[1] < 380.0
    # the same numbers recorded as given in radians, or with no record (a Dataset built in
    # Python, in SI): drawn in radians; the unit is read from the record, never guessed
    for attrs in ({"input_units_psi_1": "rad", "input_units_psi_2": "rad"}, {}):
        ax = basin_figure(_basin(deg, **attrs)).axes[0]
        assert ax.get_xlabel() == "psi_1 (rad)" and 5.5 < ax.get_xlim()[1] < 7.0
    # one axis in each unit, as given
    ax = basin_figure(_basin(deg, input_units_psi_1="deg", input_units_psi_2="rad")).axes[0]
    assert ax.get_xlabel() == "psi_1 (deg)" and ax.get_ylabel() == "psi_2 (rad)"


def test_three_ball_basin_says_where_the_third_ball_starts():
    import math

    import numpy as np

    from rotorlab.plot import basin_figure

    # the third ball is not varied: its start angle is shown in the unit the varied ones were given in
    ds = _basin(np.radians(np.linspace(0.0, 350.0, 4)), value_psi_3=4.0 * math.pi / 3.0,
                value_dpsi_3=0.0, value_disc_mass=1.0, input_units_psi_1="deg", input_units_psi_2="deg")
    title = basin_figure(ds).axes[0].get_title()
    assert "psi_3 = 240°" in title and "disc_mass" not in title
    ds.attrs.update(input_units_psi_1="rad", input_units_psi_2="rad")
    assert "psi_3 = 4.18879" in basin_figure(ds).axes[0].get_title()
    # a fixed value is shown with its SI unit (attrs units_<name>, from the coordinate's dimension)
    ds.attrs.update(fixed_rolling_friction=1e-4, units_rolling_friction="m", fixed_ball_friction=0.1)
    title = basin_figure(ds).axes[0].get_title()
    assert "rolling_friction = 0.0001 m" in title and "ball_friction = 0.1," in title + ","


def test_the_unit_an_angle_was_written_in_is_recorded_from_the_case_and_the_command_line():
    from rotorlab.cli._basin import _input_units
    from rotorlab.io import BasinSpec, load_case

    spec = load_case("autobalancer").analysis("basin")  # x = ["psi_1", "0 deg", "350 deg", 36]
    assert spec.input_units == {"psi_1": "deg", "psi_2": "deg"}
    assert spec.x[2] == __import__("pytest").approx(350.0 * 3.141592653589793 / 180.0, rel=1e-15)  # SI inside
    si = BasinSpec(x=["psi_1", 0, 6.1, 8], y=["dpsi_1", "-10 rpm", "10 rpm", 3], fixed={"psi_2": "90°"})
    assert si.input_units == {"psi_1": "rad", "psi_2": "deg"}  # dpsi_1 is not an angle: not recorded
    # --x / --fix override the case's record for the coordinates they give
    assert _input_units(spec, "psi_1=0:6.1:8", None, ["psi_3=2 rad"]) == {"psi_1": "rad", "psi_2": "deg",
                                                                         "psi_3": "rad"}
    assert _input_units(None, "psi_2=0:350deg:8", "dpsi_1=0:1:2", None) == {"psi_2": "deg"}


def test_a_balanced_run_up_start_is_drawn_over_an_unbalanced_one():
    """The machine run-up figure: the start that ends with the smallest residual vibration is
    drawn last (on top), so that its thin band shows inside a larger one; each start keeps one
    colour in both panels and its outcome in the legend (washer-horizontal: the balanced start 0
    was hidden under start 1's 10 mm band)."""
    import numpy as np
    import xarray as xr

    from rotorlab.report._machine import machine_figures

    t = np.linspace(0.0, 1.0, 50)
    amp = np.stack([0.016 + 3e-5 * np.sin(40 * t), 0.016 + 0.01 * np.sin(40 * t)])[..., None]
    ds = xr.Dataset(
        {"speed": (("ic", "time"), np.stack([100 * t, 80 * t])),
         "amplitude": (("ic", "time", "station"), amp),
         "residual_amplitude": (("ic", "station"), np.array([[3e-5], [1e-2]])),
         "outcome": (("ic",), np.array(["balanced", "non-synchronous"]))},
        coords={"time": t, "station": ["drum"]},
        attrs={"analysis": "run-up", "critical_speeds": np.array([25.0])})
    fig = machine_figures(ds, "up")["up-run-up"]
    speed_ax, vib_ax = fig.axes
    lines = {ln.get_label(): ln for ln in vib_ax.get_lines()}
    top = max(lines.values(), key=lambda ln: ln.get_zorder())
    assert top.get_label() == "drum, start 0: balanced"
    assert lines["drum, start 1: non-synchronous"].get_zorder() < top.get_zorder()
    colours = {ln.get_label(): ln.get_color() for ln in speed_ax.get_lines() if ln.get_label().startswith("start")}
    assert colours["start 0"] == top.get_color()
    assert colours["start 1"] == lines["drum, start 1: non-synchronous"].get_color() != top.get_color()
