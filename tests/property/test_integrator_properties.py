"""Property tests of the integrator: invariants that must hold for any admissible input."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rotorlab.integrate import SaveAt, Status, StepControl, solve, solve_ensemble
from rotorlab.models.examples import BouncingBall, FrictionBlock, HarmonicOscillator

FAST = settings(max_examples=25, deadline=None)


@FAST
@given(
    w=st.floats(0.2, 20.0),
    x0=st.floats(-2.0, 2.0),
    v0=st.floats(-2.0, 2.0),
    rtol=st.sampled_from([1e-6, 1e-8, 1e-10]),
)
def test_oscillator_energy_error_is_bounded_by_the_tolerance(w, x0, v0, rtol):
    osc = HarmonicOscillator(frequency=w)
    T = 20.0 / w  # about three periods
    ts = np.linspace(0.0, T, 50)
    sol = solve(osc, [x0, v0], (0.0, T), save_at=SaveAt(ts=ts), control=StepControl(rtol=rtol, atol=rtol * 1e-3))
    energy = 0.5 * (w * w * sol.ys[:, 0] ** 2 + sol.ys[:, 1] ** 2)
    e0 = 0.5 * (w * w * x0 * x0 + v0 * v0)
    assert np.max(np.abs(energy - e0)) <= 50 * rtol * max(e0, 1e-6) + 1e-12


@FAST
@given(
    n=st.integers(1, 40),
    chunk=st.integers(1, 40),
    threads=st.sampled_from([1, 2]),
    seed=st.integers(0, 2**31 - 1),
)
def test_ensemble_results_do_not_depend_on_chunking_or_threads(n, chunk, threads, seed):
    rng = np.random.default_rng(seed)
    block = FrictionBlock(friction_accel=1.0, spring_rate=4.0)
    y0 = np.stack([block.initial_state(x, 0.0) for x in rng.uniform(-3, 3, n)])
    ref = solve_ensemble(block, y0, (0.0, 10.0), threads=1)
    other = solve_ensemble(block, y0, (0.0, 10.0), threads=threads, chunk_size=chunk)
    np.testing.assert_array_equal(ref.y_final, other.y_final)
    np.testing.assert_array_equal(ref.event_counts, other.event_counts)


@FAST
@given(e=st.floats(0.1, 0.9), h0=st.floats(0.05, 3.0), a=st.floats(1.0, 20.0))
def test_bounces_accumulate_at_t_inf_for_any_restitution(e, h0, a):
    ball = BouncingBall(gravity=a, restitution=e, rest_speed=1e-7)
    v0 = math.sqrt(2 * a * h0)
    t_first = math.sqrt(2 * h0 / a)
    t_inf = ball.accumulation_time(v0)
    # The count is ill-defined when a rebound speed e^k v0 ties with rest_speed (within the
    # integration error of the impact speeds): e = 0.1, v0 = 1 gives 1e-7 exactly.
    ratios = [e**k * v0 / ball.rest_speed for k in range(1, 200) if e**k * v0 > 0.5 * ball.rest_speed]
    assume(all(abs(r - 1.0) > 1e-6 for r in ratios))
    sol = solve(ball, [h0, 0.0, 0.0], (0.0, t_first + 1.5 * t_inf + 1.0), control=StepControl(rtol=1e-10, atol=1e-12))
    assert sol.status == Status.SUCCESS
    assert sol.event_counts["impact"] == ball.impacts_until_rest(v0)
    assert abs(sol.event_times[-1] - t_first - t_inf) <= 2 * ball.rest_speed / (a * (1 - e)) + 1e-9 * t_inf
    assert sol.y_final[2] == 1.0
