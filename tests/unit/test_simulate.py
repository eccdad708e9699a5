"""Unit tests of rotorlab.analyses: simulate's Dataset, the outcome labels, build_model, summarize."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorlab.analyses import (
    build_model,
    classify,
    reference_amplitude,
    run_analysis,
    simulate,
    summarize,
    wrap_angle,
)
from rotorlab.io import load_case, missing_units, parse_case
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams

ROTOR = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
BALL = BallParams(mass=0.03, radius=0.05, damping=2e-3)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(1.0))
P = MODEL.critical_speed


@pytest.fixture(scope="module")
def two_speeds():
    return simulate(MODEL, speeds=[0.6 * P, 2.0 * P], initial_ball_angles=[[0.0, 1.6], [0.8, 3.5], [2.0, 4.0]],
                    t_end=6.0, n_save=301)  # fmt: skip


def test_dataset_layout_and_units(two_speeds):
    ds = two_speeds
    assert dict(ds.sizes) == {"speed": 2, "ic": 3, "time": 301, "ball": 2}
    assert ds.amplitude.dims == ("speed", "ic", "time")
    assert ds.ball_angle.dims == ("speed", "ic", "time", "ball")
    assert ds.outcome.dims == ("speed", "ic")
    assert ds.final_ball_angle.dims == ("speed", "ic", "ball")
    assert missing_units(ds) == []
    assert ds.speed.attrs["units"] == "rad/s" and ds.time.attrs["units"] == "s"
    np.testing.assert_allclose(ds.speed_ratio.values, [0.6, 2.0], rtol=1e-12)
    np.testing.assert_allclose(ds.speed_rpm.values, ds.speed.values * 60 / (2 * np.pi))
    assert ds.time.values[0] == 0.0 and ds.time.values[-1] == 6.0
    assert float(ds.critical_speed) == pytest.approx(math.sqrt(16740.0 / 1.06))
    np.testing.assert_array_equal(ds.ball.values, [1, 2])
    np.testing.assert_allclose(ds.initial_ball_angle.values, [[0.0, 1.6], [0.8, 3.5], [2.0, 4.0]])


def test_frames_agree(two_speeds):
    ds = two_speeds
    np.testing.assert_allclose(np.hypot(ds.x, ds.y), ds.amplitude, rtol=1e-12, atol=1e-18)
    # at t = 0 the disc centre is at rest on the axis and the balls sit at their start angles
    assert np.all(ds.amplitude.values[:, :, 0] == 0.0)
    np.testing.assert_allclose(ds.ball_angle.values[:, :, 0, :],
                               np.broadcast_to(wrap_angle(ds.initial_ball_angle.values), (2, 3, 2)))  # fmt: skip
    assert np.all(ds.ball_angle.values > -np.pi) and np.all(ds.ball_angle.values <= np.pi)


def test_steady_motion_is_rotating_frame_equilibrium(two_speeds):
    """At the end of a settled run the disc centre turns with the rotor: x + i y = e^{i w t} z."""
    ds = two_speeds.isel(speed=0, ic=0)
    om = float(ds.speed)
    t = ds.time.values[-20:]
    z = (ds.x.values[-20:] + 1j * ds.y.values[-20:]) * np.exp(-1j * om * t)
    np.testing.assert_allclose(z, z[-1], rtol=1e-6)
    # and it is the locked response with the balls at their final angles
    expected = MODEL.locked_response(ds.final_ball_angle.values, om)
    assert abs(z[-1] - expected) < 1e-6 * abs(expected)


def test_outcomes_on_both_sides_of_the_critical_speed(two_speeds):
    ds = two_speeds
    assert list(ds.outcome.values[0]) == ["side (0°, 0°)"] * 3
    assert list(ds.outcome.values[1]) == ["balanced"] * 3
    np.testing.assert_allclose(np.sort(np.degrees(ds.final_ball_angle.values[1]), axis=1),
                               [[-120.0, 120.0]] * 3, atol=0.05)  # fmt: skip
    ref = ds.reference_amplitude.values
    np.testing.assert_allclose(ref, reference_amplitude(1.5e-3, 16740.0, 1.06, 13.32, ds.speed.values))
    assert np.all(ds.final_amplitude.values[0] > 2.9 * ref[0])
    assert np.all(ds.final_amplitude.values[1] < 1e-4 * ref[1])
    assert np.all(ds.status.values == 0)
    assert np.all(ds.max_final_rate.values < 1e-4)


def test_integrates_where_cheapest_and_agrees_with_the_co_rotating_frame(two_speeds):
    """Issue 28 item 7: above 1.8 p (balls able to balance) the start-ups are integrated in the
    fixed frame, below in the co-rotating one; the co-rotating integration of every start (the
    previous path) gives the same motion to the integrator tolerance, in far more steps."""
    ds = two_speeds
    assert ds.attrs["integration_frame"] == "rotating, fixed"
    old = simulate(MODEL, speeds=[0.6 * P, 2.0 * P], initial_ball_angles=ds.initial_ball_angle.values,
                   t_end=6.0, n_save=301, frame="rotating")  # fmt: skip
    assert old.attrs["integration_frame"] == "rotating, rotating"
    np.testing.assert_array_equal(ds.outcome.values, old.outcome.values)
    np.testing.assert_allclose(ds.final_ball_angle.values, old.final_ball_angle.values, rtol=0, atol=1e-7)
    ref = ds.reference_amplitude.values[:, None]
    assert np.all(np.abs(ds.final_amplitude.values - old.final_amplitude.values) <= 1e-6 * ref)
    for name in ("x", "y", "amplitude"):  # whole histories, m (the disc moves up to 9 mm)
        np.testing.assert_allclose(ds[name].values, old[name].values, rtol=0, atol=1e-8)
    np.testing.assert_array_equal(ds.n_steps.values[0], old.n_steps.values[0])  # same frame below p
    assert np.all(2 * ds.n_steps.values[1] < old.n_steps.values[1])  # fewer than half the steps


def test_saved_fixed_frame_states_are_converted_exactly():
    """The fixed-frame states the integrator saves are the Dataset's x, y; the ball angles and rates
    are phi_i - Omega t and w_i - Omega at the same times, bit for bit."""
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    om, angles = 2.0 * P, np.array([[0.1, 2.0], [1.0, 3.0]])
    ds = simulate(MODEL, speeds=[om], initial_ball_angles=angles, t_end=0.5, n_save=11)
    fixed = MODEL.with_speed(ConstantSpeed(om)).with_frame("fixed")
    y0 = np.array([fixed.initial_state(a) for a in angles])
    ts = ds.time.values
    sol = solve_ensemble(fixed, y0, (0.0, 0.5), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-8, atol=1e-10))
    ys = sol.ys
    np.testing.assert_array_equal(ds.x.values[0], ys[:, :, 0])
    np.testing.assert_array_equal(ds.y.values[0], ys[:, :, 1])
    np.testing.assert_array_equal(ds.amplitude.values[0], np.hypot(ys[:, :, 0], ys[:, :, 1]))
    np.testing.assert_array_equal(ds.ball_angle.values[0], wrap_angle(ys[:, :, 4:6] - (om * ts)[:, None]))
    np.testing.assert_array_equal(ds.ball_rate.values[0], ys[:, :, 6:8] - om)
    np.testing.assert_array_equal(ds.final_ball_angle.values[0], wrap_angle(sol.y_final[:, 4:6] - om * 0.5))
    np.testing.assert_array_equal(ds.n_steps.values[0], sol.stats[:, 1] + sol.stats[:, 2])


def test_progress_reports_every_trajectory():
    calls = []
    simulate(MODEL, speeds=[2.0 * P, 3.0 * P], initial_ball_angles=[[0.0, 2.0]] * 5, t_end=0.05,
             n_save=3, progress=lambda done, total: calls.append((done, total)))  # fmt: skip
    assert calls[-1] == (10, 10)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    assert all(t == 10 for _, t in calls)


def test_threads_do_not_change_results():
    kw = dict(speeds=[2.0 * P], initial_ball_angles=[[0.1, 2.0], [1.0, 3.0], [2.0, 5.0]], t_end=0.5, n_save=11)
    a = simulate(MODEL, threads=1, **kw)
    b = simulate(MODEL, threads=2, **kw)
    np.testing.assert_array_equal(a.amplitude.values, b.amplitude.values)


def test_follow_the_model_speed_profile():
    ramp = MODEL.with_speed(LinearRamp(0.0, 2.0 * P, 0.5))
    ds = simulate(ramp, speeds=None, initial_ball_angles=[[0.5, 2.5]], t_end=1.0, n_save=11)
    assert ds.speed.values[0] == pytest.approx(2.0 * P)
    assert ds.attrs["speed_profile"] == "LinearRamp"


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"speeds": [-1.0]}, "speeds must be finite numbers > 0"),
        ({"speeds": [float("nan")]}, "speeds must be finite numbers > 0"),
        ({"t_end": 0.0}, "t_end must be a finite number > 0"),
        ({"n_save": 1}, "n_save must be an integer >= 2"),
        ({"initial_ball_angles": [[0.0, 1.0, 2.0]]}, r"shape \(n_configurations, 2\)"),
        ({"initial_ball_angles": [[0.0, float("inf")]]}, "must be finite"),
        ({"frame": "inertial"}, "frame must be 'auto', 'fixed' or 'rotating', got 'inertial'"),
    ],
)
def test_bad_arguments(kwargs, message):
    args = {"speeds": [P], "initial_ball_angles": [[0.0, 1.0]], "t_end": 1.0, "n_save": 10, **kwargs}
    with pytest.raises(ValueError, match=message):
        simulate(MODEL, **args)


def test_model_type_checked():
    with pytest.raises(TypeError, match="JeffcottBalls"):
        simulate(object(), speeds=[1.0], initial_ball_angles=[[0.0]], t_end=1.0)


# ------------------------------------------------------------------------------ classification


def test_wrap_angle():
    np.testing.assert_allclose(wrap_angle([np.pi, -np.pi, 3 * np.pi, 2 * np.pi + 0.1, -0.1]),
                               [np.pi, np.pi, np.pi, 0.1, -0.1])  # fmt: skip


@pytest.mark.parametrize(
    ("amplitude", "angles_deg", "rate", "expected"),
    [
        (1e-9, [120.0, -120.0], 0.0, "balanced"),
        (0.049e-3, [100.0, -100.0], 0.0, "balanced"),
        (3e-3, [-16.0, -16.0], 0.0, "side (0°, 0°)"),
        (1e-3, [179.0, -178.0], 0.0, "side (180°, 180°)"),
        (2e-3, [175.0, 5.0], 0.0, "side (0°, 180°)"),
        (2e-3, [-25.0, 20.0], 0.0, "side (0°, 0°)"),
        (2e-3, [60.0, -40.0], 0.0, "steady (-40°, 60°)"),
        (2e-3, [60.0, -40.0], 0.03, "non-synchronous"),
        (2e-3, [60.0, -40.0], float("nan"), "non-synchronous"),
    ],
)
def test_classify(amplitude, angles_deg, rate, expected):
    # reference 1 mm, speed 250 rad/s: settled means |rate| <= 0.025 rad/s
    assert classify(0, "", amplitude, 1e-3, np.radians(angles_deg), rate, 250.0) == expected


def test_classify_failed_and_no_balls():
    assert classify(-3, "state became non-finite", np.nan, 1e-3, [np.nan], np.nan, 10.0) == (
        "failed: state became non-finite"
    )
    assert classify(0, "", 1e-3, 1e-3, [], 0.0, 10.0) == "unbalanced"
    assert classify(0, "", 1e-9, 1e-3, [], 0.0, 10.0) == "balanced"


def test_reference_amplitude_closed_form():
    # undamped Jeffcott rotor: M1 e w^2 / |c - M w^2|
    assert reference_amplitude(2e-3, 400.0, 1.0, 0.0, 10.0) == pytest.approx(2e-3 * 100 / 300)
    # damped, at resonance: M1 e w / d
    assert reference_amplitude(2e-3, 400.0, 1.0, 4.0, 20.0) == pytest.approx(2e-3 * 20 / 4.0)


# ------------------------------------------------------------------------------ from a case


def test_build_model_from_case():
    case = load_case("autobalancer")
    model = build_model(case.model)
    assert model.n_balls == 2 and model.frame == "fixed"
    assert model.rotor.stiffness == 16740.0 and model.rotor.damping == pytest.approx(13.32)
    assert model.balls[0].inertia == pytest.approx(0.03 * 0.05**2)
    assert model.critical_speed == pytest.approx(case.model.critical_speed())
    assert float(model.speed.spin_speed(0.0)) == pytest.approx(2400 * 2 * np.pi / 60)


_SMALL = """
name = "small"
[model]
type = "jeffcott_balls"
disc_mass = 1.0
eccentricity = 1.5e-3
stiffness = 16740.0
damping = 13.32
[[model.balls]]
mass = 0.03
radius = 0.05
damping = 2e-3
count = 2
[[analysis]]
type = "simulate"
name = "fast"
speed = "2400 rpm"
ball_angle_grid = 2
revolutions = 40
n_save = 20
"""


def test_run_analysis_and_summarize():
    case = parse_case(_SMALL)
    assert build_model(case.model).speed.speed == 0.0  # no [model.speed]: a rotor at rest
    ds = run_analysis(case.model, case.analyses[0])
    assert ds.attrs["name"] == "fast"
    assert ds.sizes["ic"] == 4 and ds.time.values[-1] == pytest.approx(1.0)
    rows = summarize(ds)
    assert len(rows) == 4
    assert set(rows[0]) == {
        "speed", "speed_rpm", "speed_hz", "speed_ratio", "ic", "initial_ball_angles_deg",
        "final_amplitude", "reference_amplitude", "amplitude_ratio", "final_ball_angles_deg",
        "outcome", "status", "settle_estimate_s",
    }  # fmt: skip
    assert rows[0]["speed_rpm"] == pytest.approx(2400.0)
    assert rows[0]["speed_hz"] == pytest.approx(40.0)
    assert rows[1]["initial_ball_angles_deg"] == [0.0, 180.0]
    assert all(isinstance(r["outcome"], str) for r in rows)


def test_unrunnable_analysis_type_rejected_before_running():
    from types import SimpleNamespace

    case = parse_case(_SMALL)
    other = SimpleNamespace(type="no-such-analysis", name="eq")
    with pytest.raises(ValueError, match="analysis eq: type 'no-such-analysis' cannot be run here"):
        run_analysis(case.model, other)
