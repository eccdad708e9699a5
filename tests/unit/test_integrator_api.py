"""Status codes, input validation and invariance of ensemble results."""


import numpy as np
import pytest

from rotorlab.integrate import Event, SaveAt, Status, StepControl, solve, solve_ensemble
from rotorlab.models.examples import BouncingBall, HarmonicOscillator

from _models import BLOWUP_P, FAILING, NAN_P


# y' = y^2 blows up at t = 1 / y0; y' = -sqrt(y) reaches y = 0 at t = 2 sqrt(y0), then the
# square root of a negative is NaN: one canonical kernel, its parameter choosing (tests/_models.py)
BLOWUP = NAN = FAILING


def test_status_step_underflow_at_finite_time_blowup():
    sol = solve_ensemble(BLOWUP, [[1.0], [0.1]], (0.0, 2.0), params=BLOWUP_P)
    assert sol.status[0] in (Status.STEP_UNDERFLOW, Status.NONFINITE)
    assert sol.t_final[0] == pytest.approx(1.0, rel=1e-3)
    # one bad trajectory never aborts the ensemble: the other one finishes
    assert sol.status[1] == Status.SUCCESS
    assert sol.y_final[1, 0] == pytest.approx(0.1 / (1 - 0.2), rel=1e-5)


def test_status_nonfinite():
    sol = solve(NAN, [1.0], (0.0, 5.0), params=NAN_P)
    assert sol.status == Status.NONFINITE
    assert sol.t_final == pytest.approx(2.0, rel=1e-2)
    assert "non-finite" in sol.status.message


def test_status_max_steps():
    sol = solve(HarmonicOscillator(), [1.0, 0.0], (0.0, 100.0), control=StepControl(max_steps=10))
    assert sol.status == Status.MAX_STEPS
    assert sol.stats["naccept"] + sol.stats["nreject"] == 10
    assert sol.t_final < 100.0


def test_results_identical_whatever_threads_and_chunks():
    rng = np.random.default_rng(1)
    osc = HarmonicOscillator()
    y0 = rng.normal(size=(23, 2))
    params = rng.uniform(0.5, 3.0, size=(23, 1))
    kw = dict(params=params, save_at=SaveAt(ts=np.linspace(0, 5, 7)), control=StepControl(rtol=1e-9, atol=1e-12))
    a = solve_ensemble(osc, y0, (0.0, 5.0), threads=1, **kw)
    b = solve_ensemble(osc, y0, (0.0, 5.0), threads=2, **kw)
    c = solve_ensemble(osc, y0, (0.0, 5.0), chunk_size=4, **kw)
    for other in (b, c):
        np.testing.assert_array_equal(a.ys, other.ys)
        np.testing.assert_array_equal(a.y_final, other.y_final)
        np.testing.assert_array_equal(a.stats, other.stats)


def test_progress_callback_reports_chunks():
    calls = []
    solve_ensemble(HarmonicOscillator(), np.ones((10, 2)), (0.0, 1.0), chunk_size=4,
                   progress=lambda done, total: calls.append((done, total)))
    assert calls == [(4, 10), (8, 10), (10, 10)]


def test_per_trajectory_end_times_and_save_grids():
    osc = HarmonicOscillator(frequency=1.0)
    t1 = np.array([1.0, 2.0, 3.0])
    ts = np.array([[0.5, 1.0, np.inf], [0.5, 1.0, 2.0], [1.0, 2.0, 3.0]])
    sol = solve_ensemble(osc, [1.0, 0.0], (0.0, t1), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-13))
    np.testing.assert_allclose(sol.t_final, t1)
    np.testing.assert_allclose(sol.y_final[:, 0], np.cos(t1), atol=1e-9)
    assert np.all(np.isnan(sol.ys[0, 2]))
    np.testing.assert_allclose(sol.ys[2, :, 0], np.cos([1.0, 2.0, 3.0]), atol=1e-9)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(y0=[1.0]), r"y0 must have shape \(2,\)"),
        (dict(y0=[np.nan, 0.0]), "y0 must be finite"),
        (dict(t_span=(0.0, -1.0)), "t1 > t0"),
        (dict(save_at=SaveAt(ts=[2.0, 1.0])), "increasing"),
        (dict(save_at=SaveAt(ts=[0.0, 20.0])), "within the time span"),
        (dict(events=[Event("impact")]), "unknown event 'impact'"),
    ],
)
def test_bad_input_is_rejected_with_a_clear_message(kwargs, match):
    args = dict(y0=[1.0, 0.0], t_span=(0.0, 1.0))
    args.update(kwargs)
    y0, t_span = args.pop("y0"), args.pop("t_span")
    with pytest.raises(ValueError, match=match):
        solve(HarmonicOscillator(), y0, t_span, **args)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(rtol=0.0), "rtol"),
        (dict(atol=-1.0), "atol"),
        (dict(max_step=0.0), "max_step"),
        (dict(max_steps=0), "max_steps"),
    ],
)
def test_step_control_validates(kwargs, match):
    with pytest.raises(ValueError, match=match):
        StepControl(**kwargs)


def test_solution_to_dataset_has_units():
    sol = solve(BouncingBall(), [1.0, 0.0, 0.0], (0.0, 1.0), save_at=SaveAt(ts=[0.0, 0.5, 1.0]))
    ds = sol.to_dataset()
    assert ds["time"].attrs["units"] == "s"
    assert list(ds["state"].values) == ["h", "v", "mode"]
    ens = solve_ensemble(BouncingBall(), [[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], (0.0, 1.0))
    ds = ens.to_dataset()
    assert ds.sizes["ic"] == 2
    assert all("units" in ds[v].attrs for v in ds.data_vars)
