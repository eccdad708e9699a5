"""Unit tests of the steady-motion results: Datasets, parameters, cases, seed notes, figure."""

from __future__ import annotations

import ast
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams
from rotorlab.steady import (
    OTHER_OUTCOMES,
    PARAMETERS,
    SEED_NOTES,
    analyze_steady,
    ball_grid,
    motion_labels,
    run_up,
    stability_chart,
    stable_intervals,
    steady_case,
    steady_case_names,
    verify,
    with_parameter,
)

ROOT = Path(__file__).resolve().parents[2]
BALL = BallParams(mass=0.03, radius=0.06, damping=2.16e-3)
ROTOR = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(1.0))


def _check_units(ds):
    for name, var in ds.data_vars.items():
        assert "units" in var.attrs, name


def test_analysis_dataset():
    res = analyze_steady(MODEL, 2.0 * MODEL.critical_speed)
    ds = res.to_dataset()
    assert dict(ds.sizes) == {"motion": 6, "ball": 2}
    assert list(ds.motion.values) == list(motion_labels(2))
    _check_units(ds)
    assert ds.attrs["speed_ratio"] == pytest.approx(2.0)
    assert ds.stable_exact.values.tolist() == [True, True, False, False, False, False]
    assert res.motion("side 11").kind == "side"
    with pytest.raises(KeyError, match="no steady motion 'main'"):
        res.motion("main")
    with pytest.raises(ValueError, match="method must be"):
        res.motions[0].stability.is_stable("energy")
    assert np.isfinite(ds.averaged_A.values).all() and np.isfinite(ds.averaged_B.values).all()


def test_disagreements_are_listed_in_the_dataset():
    res = analyze_steady(MODEL, 1.2 * MODEL.critical_speed)
    ds = res.to_dataset()
    assert ds.disagreement.values.tolist()[:2] == [True, True]
    assert {(d.label, d.method) for d in res.disagreements} == {
        ("main+", "hamilton"), ("main+", "averaged"), ("main-", "hamilton"), ("main-", "averaged")}  # fmt: skip
    assert "omega/p = 1.2" in ds.attrs["disagreements"]


def test_with_parameter():
    two = JeffcottBalls(ROTOR, (BallParams(0.02, 0.1, inertia=3e-4, damping=1e-3), BallParams(0.04, 0.1, damping=3e-3)),
                        speed=ConstantSpeed(1.0))  # fmt: skip
    heavier = with_parameter(two, "ball_mass", 0.03)
    assert [b.mass for b in heavier.balls] == pytest.approx([0.03, 0.06])
    assert heavier.balls[0].inertia == pytest.approx(4.5e-4)
    assert [b.damping for b in with_parameter(two, "ball_damping", 2e-3).balls] == pytest.approx([2e-3, 6e-3])
    undamped = JeffcottBalls(ROTOR, (BallParams(0.02, 0.1),) * 2, speed=ConstantSpeed(1.0))
    assert [b.damping for b in with_parameter(undamped, "ball_damping", 1e-3).balls] == [1e-3, 1e-3]
    assert with_parameter(two, "eccentricity", 2e-3).rotor.eccentricity == 2e-3
    assert with_parameter(two, "support_damping", 3.0).rotor.damping == 3.0
    with pytest.raises(ValueError, match="unknown chart parameter 'mass'"):
        with_parameter(two, "mass", 1.0)
    with pytest.raises(ValueError, match="needs a model with balls"):
        with_parameter(JeffcottBalls(ROTOR, (), speed=ConstantSpeed(1.0)), "ball_mass", 1.0)
    assert set(PARAMETERS) == {"ball_mass", "ball_damping", "eccentricity", "support_damping"}


def test_stability_chart_dims_and_coordinates():
    p = MODEL.critical_speed
    ds = stability_chart(MODEL, [0.5 * p, 2.0 * p, 3.0 * p])
    assert dict(ds.sizes) == {"speed": 3, "motion": 6, "ball": 2}
    _check_units(ds)
    assert ds.balanced.values.tolist() == [False, True, True]
    assert ds.n_stable_exact.values.tolist() == [1, 2, 2]
    chart = stability_chart(MODEL, [0.5 * p, 2.0 * p], param="ball_mass", values=[0.02, 0.03, 0.05])
    assert chart.stable_exact.dims == ("ball_mass", "speed", "motion")
    assert chart.ball_mass.attrs["units"] == "kg" and chart.attrs["parameter"] == "ball_mass"
    assert chart.speed_ratio.dims == ("ball_mass", "speed")
    expect = [math.sqrt(2e4 / (2.0 + 2 * m)) for m in (0.02, 0.03, 0.05)]
    np.testing.assert_allclose(chart.critical_speed.values, expect)
    with pytest.raises(ValueError, match="give both param and values"):
        stability_chart(MODEL, [p], param="ball_mass")
    with pytest.raises(ValueError, match="speeds must be"):
        stability_chart(MODEL, [0.0])


def test_stability_chart_figures():
    from matplotlib.figure import Figure

    from rotorlab.plot._stability import stability_chart_figure

    p = MODEL.critical_speed
    fig = stability_chart_figure(stability_chart(MODEL, np.linspace(0.5, 2.5, 5) * p))
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    chart = stability_chart(MODEL, np.linspace(0.5, 2.5, 4) * p, param="support_damping", values=[0.0, 8.0, 16.0])
    fig = stability_chart_figure(chart)
    assert len(fig.axes) == 3 and len(fig.legends) == 1


def test_verify_and_run_up_figures():
    from rotorlab.plot._stability import run_up_figure, verify_figure

    p = MODEL.critical_speed
    ds = verify(MODEL, [0.5 * p, 2.0 * p], initial_ball_angles=[[0.5, 2.5], [1.0, -2.0]], t_end=5.0)
    assert len(verify_figure(ds).axes) == 1
    ds = run_up(MODEL, LinearRamp(0.3 * p, 2.0 * p, 1.0), t_end=2.0, n_save=100)
    assert len(run_up_figure(ds).axes) == 2  # deflection and the speed on a twin axis


def test_ball_grid_avoids_invariant_sets():
    g = ball_grid(2, 6)
    assert g.shape == (36, 2)
    assert np.all(np.abs(g[:, 0] - g[:, 1]) > 0.1)  # two equal balls never start together
    assert not np.any(np.all(np.isclose(np.sin(g), 0.0, atol=1e-12), axis=1))  # never all on the line
    with pytest.raises(ValueError):
        ball_grid(2, 0)


def test_verify_dataset():
    p = MODEL.critical_speed
    ds = verify(MODEL, [0.5 * p], points=2, t_end=20.0)
    assert dict(ds.sizes) == {"speed": 1, "ic": 4, "ball": 2, "motion": 6, "outcome": 9}
    assert list(ds.outcome.values)[-3:] == list(OTHER_OUTCOMES)
    _check_units(ds)
    np.testing.assert_allclose(ds.fraction.sum("outcome").values, 1.0)
    assert ds.reached.values.tolist() == [["side 00"] * 4]
    assert bool(ds.agrees_exact.values[0]) and ds.t_end.values[0] == 20.0
    friction = JeffcottBalls(ROTOR, (BallParams(0.03, 0.06, friction=0.1),) * 2, speed=ConstantSpeed(1.0))
    with pytest.raises(ValueError, match="without Coulomb friction"):
        verify(friction, [p])
    with pytest.raises(ValueError, match="speeds must be"):
        verify(MODEL, [-1.0])


def test_run_up_dataset():
    p = MODEL.critical_speed
    ds = run_up(MODEL, LinearRamp(0.3 * p, 2.5 * p, 4.0), t_end=5.0, n_save=300,
                initial_ball_angles=[[0.3, 2.0]])  # fmt: skip
    assert dict(ds.sizes) == {"ic": 1, "time": 300, "ball": 2}
    _check_units(ds)
    assert ds.speed.values[-1] == pytest.approx(2.5 * p)
    assert float(ds.max_amplitude_without) > float(ds.final_amplitude_without)
    assert ds.attrs["critical_speed_without"] == pytest.approx(math.sqrt(2e4 / 2.0))
    p0 = ds.attrs["critical_speed_without"]
    assert p0 < float(ds.speed_at_max_without) < 1.3 * p0  # a passage at finite rate peaks late
    with pytest.raises(ValueError, match="t_end"):
        run_up(MODEL, LinearRamp(0.3 * p, 2.5 * p, 0.5), t_end=0.0)


def test_cases_cover_the_regimes():
    assert steady_case_names() == ("zhakash-k2", "filimonikhin-n2")
    z = steady_case("zhakash-k2")
    eta = {r: z.model(r).imbalance / z.balls[0].static_moment for r in z.regime_names}
    assert eta == pytest.approx({"enough": 1.2, "short": 2.6})
    assert z.balls[0] == z.balls[1] and z.balls[0].damping / (0.03 * 0.06**2) == pytest.approx(20.0)
    f = steady_case("filimonikhin-n2")
    s1, s2 = (b.static_moment for b in f.balls)
    me = {r: f.model(r).imbalance for r in f.regime_names}
    assert s2 - s1 < me["enough"] < s1 + s2 and me["short"] > s1 + s2 and me["dominant"] < s2 - s1
    assert f.model("undamped").rotor.damping == 0.0 and f.model("enough").rotor.damping > 0
    ratios = [w / f.critical_speed() for w in f.speeds()]
    assert min(ratios) < 1 < max(ratios)
    with pytest.raises(ValueError, match="no regime 'x'"):
        f.model("x")
    with pytest.raises(ValueError, match="built-in cases: zhakash-k2, filimonikhin-n2"):
        steady_case("nope")


def _test_functions(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    return {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}


def test_every_seed_note_names_an_existing_test():
    assert {n.seed for n in SEED_NOTES} == {"002", "003"}
    for note in SEED_NOTES:
        file, name = note.test.split("::")
        assert name in _test_functions(ROOT / file), note


def test_results_round_trip_through_netcdf(tmp_path):
    """Every Dataset carries units on its numeric variables and survives NetCDF (io.save_netcdf)."""
    from rotorlab.io import load_netcdf, missing_units, save_netcdf

    p = MODEL.critical_speed
    datasets = {
        "steady": analyze_steady(MODEL, 1.2 * p).to_dataset(),
        "chart": stability_chart(MODEL, [0.5 * p, 2.0 * p], param="eccentricity", values=[5e-4, 1e-3]),
        "verify": verify(MODEL, [2.0 * p], initial_ball_angles=[[0.5, 2.5]], t_end=5.0),
        "run_up": run_up(MODEL, LinearRamp(0.3 * p, 2.0 * p, 1.0), t_end=2.0, n_save=50),
    }
    for name, ds in datasets.items():
        assert missing_units(ds) == [], name
        back = load_netcdf(save_netcdf(ds, tmp_path / f"{name}.nc"))
        for var in ds.data_vars:
            np.testing.assert_array_equal(back[var].values, ds[var].values, err_msg=f"{name}.{var}")


def test_analysis_to_dict_is_json():
    import json

    short = JeffcottBalls(replace(ROTOR, eccentricity=2e-2), (BALL, BALL), speed=ConstantSpeed(1.0))
    res = analyze_steady(short, 150.0)
    d = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert [m["label"] for m in d["motions"]] == list(motion_labels(2))
    assert d["motions"][0]["exists"] is False and d["motions"][0]["ball_angles"] is None
    side = d["motions"][-1]
    assert side["verdicts"] == {"hamilton": "stable", "averaged": "stable", "exact": "stable"}
    assert side["amplitude"] == pytest.approx(res.motion("side 11").amplitude)
    assert d["speed_ratio"] == pytest.approx(150.0 / res.critical_speed)


def test_stable_intervals():
    p = MODEL.critical_speed
    ratios = np.array([0.5, 0.8, 1.2, 2.0, 3.0])
    ds = stability_chart(MODEL, ratios * p, param="support_damping", values=[0.0, 8.0])
    rows = stable_intervals(ds)
    damped = [(r["motion"], r["start_ratio"], r["stop_ratio"]) for r in rows if r["support_damping"] == 8.0]
    above = (pytest.approx(2.0), pytest.approx(3.0))
    assert damped == [("main+", *above), ("main-", *above), ("side 00", pytest.approx(0.5), pytest.approx(0.8))]
    undamped = {r["motion"] for r in rows if r["support_damping"] == 0.0}
    assert undamped == {"side 00"}  # no support damping: nothing stable above p
    seed = {r["motion"] for r in stable_intervals(ds, "hamilton") if r["support_damping"] == 0.0}
    assert seed == {"main+", "main-", "side 00"}
    with pytest.raises(ValueError, match="method must be"):
        stable_intervals(ds, "energy")
