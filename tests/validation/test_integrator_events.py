"""Impacts, their accumulation into sustained contact, and dry friction as stick-slip.

Closed forms:
- bouncing ball (restitution e, gravity a, first impact speed v0): the impacts accumulate at
  T_inf = 2 e v0 / (a (1 - e)) after the first impact (geometric series of flight times
  2 e^k v0 / a), and the ball then rests;
- block launched at v0 against Coulomb friction mu g: stops at t = v0 / (mu g) after
  x = v0^2 / (2 mu g) and stays; with a spring k/m = w0^2 and released at rest from x0 it slides
  for exactly half a period pi / w0 and stops at x1 = -(x0 - 2 mu g / w0^2);
- stuck block pushed by A sin(W t): breaks away when A sin(W t) = mu g.
"""

import math

import numpy as np
import pytest

from rotorlab.integrate import Event, SaveAt, Status, StepControl, solve, solve_ensemble
from rotorlab.models.examples import BouncingBall, FrictionBlock

TIGHT = StepControl(rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("e", [0.5, 0.8, 0.95])
def test_bouncing_ball_impacts_accumulate_at_t_inf_then_rest(e):
    a, h0 = 9.81, 1.0
    ball = BouncingBall(gravity=a, restitution=e, rest_speed=1e-9)
    v0 = math.sqrt(2 * a * h0)
    t_first = math.sqrt(2 * h0 / a)
    sol = solve(ball, [h0, 0.0, 0.0], (0.0, 60.0), save_at=SaveAt(ts=[59.0, 60.0]), control=TIGHT)
    assert sol.status == Status.SUCCESS
    n_expected = ball.impacts_until_rest(v0)
    assert sol.event_counts["impact"] == n_expected
    assert sol.event_times[0] == pytest.approx(t_first, rel=1e-14)
    t_rest = sol.event_times[-1]
    t_inf = ball.accumulation_time(v0)
    # the last impact is where the ball comes to rest; remaining flight time < 2 v_rest/(a(1-e))
    assert t_rest - t_first == pytest.approx(t_inf, abs=2 * ball.rest_speed / (a * (1 - e)) + 1e-9)
    # the ball rests on the floor in contact mode
    np.testing.assert_array_equal(sol.ys[-1], [0.0, 0.0, 1.0])
    # the step size never collapses: about one accepted step per flight
    assert sol.stats["naccept"] < 2 * n_expected + 20
    assert sol.stats["nreject"] < 10


def test_bouncing_ball_flight_heights_follow_restitution():
    a, e = 9.81, 0.7
    ball = BouncingBall(gravity=a, restitution=e, rest_speed=1e-6)
    sol = solve(ball, [2.0, 0.0, 0.0], (0.0, 5.0), control=TIGHT)
    t = np.asarray(sol.event_times)
    flights = np.diff(t[:8])
    # each flight is e times the previous one
    np.testing.assert_allclose(flights[1:] / flights[:-1], e, rtol=1e-9)


def test_ball_lifts_off_when_contact_force_would_pull():
    a, amp = 9.81, 12.0
    ball = BouncingBall(gravity=a, restitution=0.6, rest_speed=1e-6, push_amplitude=amp, push_frequency=1.0)
    sol = solve(ball, [0.0, 0.0, 1.0], (0.0, 2.0), control=TIGHT)
    assert sol.event_names[0] == "lift_off"
    assert sol.event_times[0] == pytest.approx(math.asin(a / amp), rel=1e-12)


def test_impact_event_can_stop_the_trajectory():
    ball = BouncingBall()
    sol = solve(ball, [1.0, 0.0, 0.0], (0.0, 5.0), events=[Event("impact", action="stop")], control=TIGHT)
    assert sol.status == Status.EVENT_STOP
    assert sol.t_final == pytest.approx(math.sqrt(2 / 9.81), rel=1e-13)


def test_events_can_be_disabled():
    ball = BouncingBall()
    sol = solve(ball, [1.0, 0.0, 0.0], (0.0, 1.0), events=[], control=TIGHT)
    assert sol.event_counts == {"impact": 0, "lift_off": 0}
    assert sol.y_final[0] == pytest.approx(1.0 - 9.81 / 2, rel=1e-12)  # falls through the floor


def test_block_with_dry_friction_stops_at_closed_form_time_and_stays():
    mu_g, v0 = 2.0, 3.0
    block = FrictionBlock(friction_accel=mu_g)
    sol = solve(block, block.initial_state(0.0, v0), (0.0, 10.0), save_at=SaveAt(ts=[1.0, 10.0]), control=TIGHT)
    assert sol.status == Status.SUCCESS
    assert sol.event_counts["stop"] == 1
    assert sol.event_times[0] == pytest.approx(v0 / mu_g, rel=1e-12)
    np.testing.assert_allclose(sol.ys[1], [v0**2 / (2 * mu_g), 0.0, 0.0], atol=1e-12)
    # while sliding: x = v0 t - mu g t^2 / 2
    assert sol.ys[0, 0] == pytest.approx(v0 - mu_g / 2, rel=1e-12)
    assert sol.stats["naccept"] < 20


def test_block_on_spring_sticks_after_half_period():
    w0, mu_g = 2.0, 1.0
    x0 = 1.2  # released at rest; spring force w0^2 x0 = 4.8 > mu g
    block = FrictionBlock(friction_accel=mu_g, spring_rate=w0**2)
    sol = solve(block, block.initial_state(x0, 0.0), (0.0, 20.0), control=TIGHT)
    x1 = -(x0 - 2 * mu_g / w0**2)
    t_half = math.pi / w0
    assert sol.event_times[0] == pytest.approx(t_half, rel=1e-9)
    assert sol.event_names[0] == "stop"
    # second half-period: |x1| w0^2 = 2.8 > mu g, so it slides back and stops at x2
    x2 = -(x1 + 2 * mu_g / w0**2)
    assert sol.event_times[1] == pytest.approx(2 * t_half, rel=1e-9)
    # |x2| w0^2 = 0.8 < mu g: stuck for good
    assert abs(x2) * w0**2 < mu_g
    assert sol.event_counts["stop"] == 2
    np.testing.assert_allclose(sol.y_final, [x2, 0.0, 0.0], atol=1e-9)


def test_stuck_block_breaks_away_when_push_exceeds_friction():
    mu_g, amp, w = 1.0, 3.0, 2.0
    block = FrictionBlock(friction_accel=mu_g, push_amplitude=amp, push_frequency=w)
    sol = solve(block, block.initial_state(0.0, 0.0), (0.0, 1.0), control=TIGHT)
    assert sol.event_names[0] == "break_away"
    assert sol.event_times[0] == pytest.approx(math.asin(mu_g / amp) / w, rel=1e-10)
    # it slides forward from there: stuck segments never move
    assert sol.y_final[0] > 0


def test_stick_slip_ensemble_counts_match_single_runs():
    block = FrictionBlock(friction_accel=1.0, spring_rate=4.0)
    x0 = np.linspace(0.3, 3.0, 7)
    y0 = np.stack([block.initial_state(x, 0.0) for x in x0])
    ens = solve_ensemble(block, y0, (0.0, 20.0), control=TIGHT, threads=2)
    for i in range(len(x0)):
        single = solve(block, y0[i], (0.0, 20.0), control=TIGHT)
        np.testing.assert_array_equal(ens.y_final[i], single.y_final)
        assert ens.event_counts[i, 0] == single.event_counts["stop"]
    # the number of half-swings before sticking: each swing loses 2 mu g / w0^2 = 0.5 of amplitude
    expected = [max(0, math.ceil((x * 4.0 - 1.0) / 2.0)) for x in x0]
    np.testing.assert_array_equal(ens.event_counts[:, 0], expected)
