"""Lane driver (``solve_ensemble(..., lanes=L)``): the same numbers as the scalar driver.

Both drivers run the same kernel with the same arithmetic (no fused multiply-add contraction:
numba compiles without ``fastmath``; ``sincos`` uses explicit, exactly rounded ``fma``) and the
same step-size controller, so a trajectory gives the same bits on either, whatever the lane it
ran in, the thread, the chunking or the other trajectories. The tests therefore compare exactly.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlab.integrate import SaveAt, Status, StepControl, solve_ensemble
from rotorlab.models import Kernels
from rotorlab.models.examples import BouncingBall, HarmonicOscillator

BENCH = Path(__file__).resolve().parents[2] / "bench"
sys.path.insert(0, str(BENCH))
from _bench_kernel import bench_rhs, bench_rhs_libm  # noqa: E402

from _models import BLOWUP_P, FAILING, NAN_P  # noqa: E402

BENCH_KERNELS = Kernels(rhs=bench_rhs, n_state=8)
# rotorlab.models.BENCHMARK: M, m, R, eps, k, c, beta, Omega
BENCH_P = np.array([1.0, 0.02, 1.0, 0.01, 1.0, 0.02, 0.01, 2.5])


def _bench_y0(idx):
    """Initial states of grid points ``idx`` (as rotorlab.models.BENCHMARK: 256 x 256 grid)."""
    i, j = np.divmod(np.asarray(idx), 256)
    y0 = np.zeros((len(idx), 8))
    y0[:, 4] = 2.0 * np.pi * i / 256
    y0[:, 5] = 2.0 * np.pi * j / 256
    y0[:, 6:] = BENCH_P[7]
    return y0


def assert_same(a, b):
    """Bit-identical ensemble results (NaN where both are NaN)."""
    np.testing.assert_array_equal(a.status, b.status)
    np.testing.assert_array_equal(a.stats, b.stats)
    np.testing.assert_array_equal(a.t_final, b.t_final)
    np.testing.assert_array_equal(a.y_final, b.y_final)
    np.testing.assert_array_equal(a.ys, b.ys)


@pytest.fixture(scope="module")
def bench_case():
    rng = np.random.default_rng(0)
    idx = np.concatenate([rng.permutation(256 * 256)[:255], [37 * 257]])  # + one diagonal point
    n = len(idx)
    params = np.repeat(BENCH_P[None, :], n, axis=0)
    params[:, 7] = rng.uniform(2.3, 2.7, n)  # one spin speed per trajectory
    params[:, 6] = rng.uniform(0.005, 0.02, n)
    t1 = rng.uniform(1.0, 30.0, n)  # very different lengths
    kw = dict(
        params=params, save_at=SaveAt(ts=np.linspace(0.0, 1.0, 6)),
        control=StepControl(rtol=1e-8, atol=1e-10),
    )  # fmt: skip
    scalar = solve_ensemble(BENCH_KERNELS, _bench_y0(idx), (0.0, t1), threads=2, lanes=None, **kw)
    assert scalar.driver == "scalar"
    return idx, t1, kw, scalar


@pytest.mark.parametrize("width", [8, 16])
def test_bench_lanes_bit_identical_to_scalar(bench_case, width):
    """The default width and another one (``solve_ensemble(lanes=...)``): the lanes are independent."""
    idx, t1, kw, scalar = bench_case
    assert np.all(scalar.status == Status.SUCCESS)
    lanes = solve_ensemble(BENCH_KERNELS, _bench_y0(idx), (0.0, t1), threads=2, lanes=width, **kw)
    assert lanes.driver == f"lanes{width}"
    assert_same(lanes, scalar)


def test_bench_lanes_invariant_to_threads_and_chunks(bench_case):
    idx, t1, kw, scalar = bench_case
    serial = solve_ensemble(BENCH_KERNELS, _bench_y0(idx), (0.0, t1), threads=1, lanes=8, chunk_size=37, **kw)
    assert_same(serial, scalar)
    # a trajectory does not depend on its neighbours: the reversed ensemble gives the same rows
    rev = solve_ensemble(
        BENCH_KERNELS, _bench_y0(idx[::-1]), (0.0, t1[::-1]), threads=2, lanes=8,
        **{**kw, "params": kw["params"][::-1]},
    )  # fmt: skip
    np.testing.assert_array_equal(rev.y_final[::-1], scalar.y_final)
    np.testing.assert_array_equal(rev.stats[::-1], scalar.stats)


@pytest.mark.parametrize("n_traj", [1, 3, 8, 13])
def test_refill_with_very_different_lengths(n_traj):
    """N < L, N = L and N not a multiple of L; lengths spanning five decades."""
    osc = HarmonicOscillator(frequency=3.0)
    rng = np.random.default_rng(n_traj)
    y0 = rng.normal(size=(n_traj, 2))
    t1 = np.geomspace(1e-3, 1e2, n_traj) if n_traj > 1 else np.array([70.0])
    rng.shuffle(t1)
    kw = dict(control=StepControl(rtol=1e-9, atol=1e-12), save_at=SaveAt(ts=[0.0, 5e-4, 0.5, 50.0]))
    ref = solve_ensemble(osc, y0, (0.0, t1), threads=1, **kw)
    for lanes, threads in ((8, 1), (3, 2)):
        got = solve_ensemble(osc, y0, (0.0, t1), threads=threads, lanes=lanes, **kw)
        assert_same(got, ref)
    assert np.all(ref.status == Status.SUCCESS)
    np.testing.assert_array_equal(ref.t_final, t1)


def test_negative_start_time_and_step_options():
    """Time crossing zero (min_step from the bits of t), first_step and max_step."""
    osc = HarmonicOscillator(frequency=1.5)
    y0 = np.array([[1.0, 0.0], [0.3, -2.0], [0.0, 1.0]])
    for control in (
        StepControl(rtol=1e-10, atol=1e-12),
        StepControl(rtol=1e-7, atol=1e-9, first_step=1e-3, max_step=0.05),
    ):
        ref = solve_ensemble(osc, y0, (-3.0, np.array([2.0, -1.0, 0.0])), control=control, threads=1)
        got = solve_ensemble(osc, y0, (-3.0, np.array([2.0, -1.0, 0.0])), control=control, threads=1, lanes=8)
        assert_same(got, ref)


def test_status_codes_match_scalar():
    # y = y0 / (1 - y0 t) blows up at t = 1 / y0; y' = -sqrt(y) reaches 0 at t = 2 sqrt(y0), then NaN
    cases = [
        (FAILING, BLOWUP_P, [[1.0], [0.1], [2.0]], 2.0, StepControl()),
        (FAILING, NAN_P, [[1.0], [4.0]], 5.0, StepControl()),
        (HarmonicOscillator().kernels, [1.0], [[1.0, 0.0], [0.0, 1.0]], 100.0, StepControl(max_steps=10)),
    ]
    for kernels, params, y0, t1, control in cases:
        ref = solve_ensemble(kernels, y0, (0.0, t1), params=params, control=control, threads=1)
        got = solve_ensemble(kernels, y0, (0.0, t1), params=params, control=control, threads=1, lanes=8)
        assert_same(got, ref)
    assert set(ref.status) == {Status.MAX_STEPS}


def test_events_switched_off():
    ball = BouncingBall()
    y0 = [[1.0, 0.0, 0.0], [0.5, 0.0, 0.0]]
    ref = solve_ensemble(ball, y0, (0.0, 0.3), events=[], threads=1, lanes=None)
    got = solve_ensemble(ball, y0, (0.0, 0.3), events=[], threads=1, lanes=8)
    assert_same(got, ref)
    assert np.all(got.stats[:, 3] == 0)
    np.testing.assert_allclose(got.y_final[:, 0], [1.0 - 0.5 * 9.81 * 0.09, 0.5 - 0.5 * 9.81 * 0.09], rtol=1e-12)
    y0 = [[0.2, 0.0, 0.0], [0.1, 0.0, 0.0]]  # no impact event: they fall through the floor
    got = solve_ensemble(ball, y0, (0.0, 0.3), events=[], threads=1, lanes=8)
    assert np.all(got.y_final[:, 0] < 0.0)


@pytest.mark.parametrize("bad", [0, 1, 65, 2.5, True, "8"])
def test_invalid_lanes(bad):
    with pytest.raises(ValueError, match="lanes"):
        solve_ensemble(HarmonicOscillator(), [1.0, 0.0], (0.0, 1.0), lanes=bad)


def test_bench_kernel_vectorises():
    """The benchmark kernel (vmath.sincos) vectorises across lanes; with math.sin it does not."""
    from llvmlite import binding as ll

    from rotorlab.integrate._drivers import is_vectorised

    features = ll.get_host_cpu_features()
    if not (features.get("avx") or features.get("sse2") or features.get("neon")):
        pytest.skip("no SIMD unit known to LLVM on this CPU")
    assert is_vectorised(BENCH_KERNELS, lanes=8)
    assert not is_vectorised(Kernels(rhs=bench_rhs_libm, n_state=8), lanes=8)
