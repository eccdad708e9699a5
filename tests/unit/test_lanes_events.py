"""Events, reset maps and modes on the lane driver: the scalar driver's numbers bit for bit.

The lane driver locates the events of each lane's accepted step with the scalar driver's own
code (:func:`rotorlab.integrate._core._events_in_step` and ``_resolve_cut``, bound to the model's
kernels), so event times, records, counts, states after resets, step counts and statuses must be
identical, whatever the lane a trajectory ran in, its neighbours, the threads or the chunks. Each
model with events is compared on a small ensemble whose members hit events at different times
(impacts, chatter into sustained contact, lift-off, stick/slip, stone pushes, terminal events),
plus closed forms where one exists (the free fall of the bouncing ball).
"""

import math

import numpy as np
import pytest

from rotorlab.contact import JeffcottRub, RubRotor
from rotorlab.integrate import Event, SaveAt, Status, StepControl, solve_ensemble
from rotorlab.models import krasnov_crusher
from rotorlab.models._toroidal_ball import strautmanis_torus
from rotorlab.models.examples import BouncingBall, FrictionBlock

FIELDS = ("status", "stats", "t_final", "y_final", "ys", "event_counts", "event_times", "event_index")


def _both(model, y0, t1, **kw):
    """The scalar reference and the lane driver (default, 2 threads) on the same ensemble."""
    kw = {"max_events_recorded": 25, **kw}
    ref = solve_ensemble(model, y0, (0.0, t1), lanes=None, threads=2, **kw)
    got = solve_ensemble(model, y0, (0.0, t1), threads=2, **kw)
    assert got.driver == "lanes8" and ref.driver == "scalar"
    for f in FIELDS:
        np.testing.assert_array_equal(getattr(got, f), getattr(ref, f), err_msg=f)
    return ref


@pytest.fixture(scope="module")
def ball_starts():
    rng = np.random.default_rng(3)
    n = 13  # not a multiple of the lane width: lanes refill at different times
    return np.c_[rng.uniform(0.1, 2.0, n), np.zeros(n), np.zeros(n)]


def test_bouncing_ball_impacts_chatter_and_contact(ball_starts):
    g, e = 9.81, 0.8
    ref = _both(BouncingBall(gravity=g, restitution=e), ball_starts, 3.0,
                save_at=SaveAt(ts=np.linspace(0.0, 3.0, 7)), control=StepControl(rtol=1e-10, atol=1e-12))  # fmt: skip
    assert np.all(ref.status == Status.SUCCESS)
    # first impact of a ball dropped from rest at height h: sqrt(2 h / g) (free fall)
    h = ball_starts[:, 0]
    np.testing.assert_allclose(ref.event_times[:, 0], np.sqrt(2.0 * h / g), rtol=1e-10)
    # the impacts accumulate (chatter, at t = sqrt(2h/g) (1 + e) / (1 - e)) into resting contact
    t_rest = np.sqrt(2.0 * h / g) * (1.0 + e) / (1.0 - e)
    rests = t_rest < 3.0
    assert rests.any() and not rests.all()
    np.testing.assert_array_equal(ref.y_final[rests, 2], 1.0)
    np.testing.assert_array_equal(ref.y_final[rests, :2], 0.0)


def test_bouncing_ball_lift_off_and_pushes():
    rng = np.random.default_rng(4)
    y0 = np.c_[rng.uniform(0.0, 0.5, 11), rng.uniform(-1.0, 1.0, 11), np.zeros(11)]
    ball = BouncingBall(restitution=0.6, rest_speed=1e-3, push_amplitude=12.0, push_frequency=5.0)
    ref = _both(ball, y0, 4.0, control=StepControl(rtol=1e-9, atol=1e-12))
    assert np.all(ref.event_counts[:, 1] >= 1)  # the push lifts the ball off the floor


@pytest.mark.parametrize("action", ["stop", "count"])
def test_terminal_and_counted_events(ball_starts, action):
    ref = _both(BouncingBall(), ball_starts, 3.0, events=[Event("impact", action=action)],
                save_at=SaveAt(ts=np.linspace(0.0, 3.0, 13)), control=StepControl(rtol=1e-10, atol=1e-12))  # fmt: skip
    fall = np.sqrt(2.0 * ball_starts[:, 0] / 9.81)
    if action == "stop":
        assert np.all(ref.status == Status.EVENT_STOP)
        np.testing.assert_allclose(ref.t_final, fall, rtol=1e-10)
        assert np.all(np.isnan(ref.ys[ref.ts[None, :] > fall[:, None]]))  # nothing saved after the stop
    else:  # counted only: the ball falls through the floor, one crossing each
        assert np.all(ref.status == Status.SUCCESS)
        np.testing.assert_array_equal(ref.event_counts[:, 0], 1)
        np.testing.assert_allclose(ref.y_final[:, 0], ball_starts[:, 0] - 0.5 * 9.81 * 3.0**2, rtol=1e-9)


def test_friction_block_stick_slip():
    rng = np.random.default_rng(5)
    y0 = np.c_[rng.uniform(-1, 1, 10), rng.uniform(-1, 1, 10), np.sign(rng.uniform(-1, 1, 10))]
    block = FrictionBlock(friction_accel=1.0, spring_rate=4.0, push_amplitude=3.0, push_frequency=2.0)
    ref = _both(block, y0, 10.0, control=StepControl(rtol=1e-9, atol=1e-12))
    # every block comes to rest; some stick there and break away later
    assert np.all(ref.event_counts[:, 0] >= 1) and np.any(ref.event_counts[:, 1] >= 1)


def test_toroidal_ball_stick_slip():
    rng = np.random.default_rng(6)
    model = strautmanis_torus(1e-4)
    y0 = model.initial_state(rng.uniform(0, 2 * np.pi, 12), rng.uniform(-0.5, 0.5, 12), rng.uniform(-10, 10, 12))
    ref = _both(model, y0, 1.0, control=StepControl(rtol=1e-8, atol=1e-10), save_at=SaveAt(ts=[0.5, 1.0]))
    counts = ref.event_counts.sum(axis=0)
    assert counts[0] > 0 and counts[2] > 0 and counts[3] > 0  # stick_psi, stick_alpha, slip_alpha


def test_rub_impacts_and_sustained_contact():
    rotor = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.05, stator_stiffness=100.0,
                     friction=0.3, rotor_radius=0.1)  # fmt: skip
    model = JeffcottRub(rotor, spin_speed=0.5, restitution=0.7)
    rng = np.random.default_rng(7)
    y0 = np.array([model.initial_state((0.01 * rng.uniform(0.2, 0.9), 0.0), (0.0, 0.01 * rng.uniform(0.5, 2)))
                   for _ in range(10)])  # fmt: skip
    ref = _both(model, y0, 30.0, control=StepControl(rtol=1e-9, atol=1e-12))
    assert np.all(ref.status == Status.SUCCESS)
    counts = ref.event_counts.sum(axis=0)
    assert counts[0] > 0 and counts[1] > 0 and counts[2] > 0, dict(zip(ref.event_names, counts))


def test_impact_rotor_stones_impacts_sliding():
    model = krasnov_crusher(stone_mass=1.5, friction=0.2).with_stones(0.3, seed=0)
    rng = np.random.default_rng(8)
    y0 = np.array([model.initial_state(du=tuple(rng.uniform(-0.5, 0.5, 2))) for _ in range(10)])
    ref = _both(model, y0, 0.3, control=StepControl(rtol=1e-9, atol=1e-13), save_at=SaveAt(ts=[0.1, 0.2, 0.3]))
    counts = dict(zip(ref.event_names, ref.event_counts.sum(axis=0)))
    assert counts["impact"] > 0 and counts["stone"] > 0


def test_event_lanes_independent_of_neighbours_threads_and_chunks(ball_starts):
    kw = dict(control=StepControl(rtol=1e-10, atol=1e-12), max_events_recorded=25)
    ball = BouncingBall()
    ref = solve_ensemble(ball, ball_starts, (0.0, 3.0), lanes=None, threads=1, **kw)
    for lanes, threads, chunk in ((8, 1, 5), (3, 2, None)):
        got = solve_ensemble(ball, ball_starts[::-1], (0.0, 3.0), lanes=lanes, threads=threads, chunk_size=chunk, **kw)
        np.testing.assert_array_equal(got.y_final[::-1], ref.y_final)
        np.testing.assert_array_equal(got.event_times[::-1], ref.event_times)
        np.testing.assert_array_equal(got.stats[::-1], ref.stats)
    assert math.isfinite(ref.event_times[0, 0])
