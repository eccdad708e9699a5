"""The torque-limited, speed-commanded drive (:class:`rotorlab.models.ServoDrive`).

On the disc of tests/validation/test_machine_sommerfeld.py (1 kg on 1 N/m, critical speed
1 rad/s, damping 0.05 N s/m, polar inertia J = 0.05 kg m^2), one compiled layout throughout.
"""

import math

import numpy as np
import pytest

from rotorlab.integrate import SaveAt, StepControl, solve, solve_ensemble
from rotorlab.linear import LinearSystem
from rotorlab.models import Machine, ServoDrive, Unbalance

STRUCTURE = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.05, 0.05, 0.0, 0.0]),
                         G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
J = 0.05
CTL = StepControl(rtol=1e-10, atol=1e-12)


def machine(limit, unbalance=0.05, **command):
    kw = dict(operating_speed=2.5, ramp_rate=0.05, gain=1.0) | command
    return Machine(STRUCTURE, unbalances=(Unbalance(0, unbalance),),
                   drive=ServoDrive(limit, polar_inertia=J, **kw), n_modes=2, energy_states=True)


def speeds(m, ts):
    sol = solve(m, m.initial_state(spin_speed=0.0), (0.0, ts[-1]), save_at=SaveAt(ts=ts), control=CTL)
    assert np.all(sol.status == 0) if np.ndim(sol.status) else sol.status == 0
    return sol, sol.ys[:, m.layout.i_theta + 1]


def test_unsaturated_speed_follows_the_proportional_loop_in_closed_form():
    """Limit never reached, no unbalance: J W' = K (a t - W), so W = a t - (a J / K)(1 - e^(-K t / J))."""
    a, K = 0.05, 1.0
    m = machine(100.0, unbalance=0.0, ramp_rate=a, gain=K)
    ts = np.linspace(0.0, 40.0, 41)
    _, w = speeds(m, ts)
    np.testing.assert_allclose(w, a * ts - a * J / K * (1.0 - np.exp(-K * ts / J)), atol=1e-8)


def test_saturated_speed_rises_at_limit_over_inertia_then_reaches_the_command():
    """A constant limit T far below the loop's demand: W = T (t - t_s / 2) / J until the command
    is met, t_s = T / (K a) the loop's unsaturated start (J W' = K a t there, W ~ 0)."""
    T = 0.01
    m = machine(T, unbalance=0.0, ramp_rate=10.0, gain=50.0)  # demand 50 (2.5 - W) >> 0.01
    ts = np.linspace(0.0, 12.0, 25)
    _, w = speeds(m, ts)
    t_s = T / (50.0 * 10.0)
    early = (ts > 0) & (ts <= 12.0 * 0.9)
    np.testing.assert_allclose(w[early], T * (ts[early] - t_s / 2) / J, rtol=0, atol=2e-8)
    _, w_end = speeds(m, np.array([0.0, 2.5 * J / T + 5.0]))
    assert abs(w_end[-1] - 2.5) < 1e-6  # then held at the operating speed


def test_power_ledger_closes_with_the_limited_drive():
    """drive work = change of kinetic + potential energy + dissipated energy, with the torque
    switching between the loop and the limit through the resonance."""
    m = machine(0.02, ramp_rate=0.2, gain=0.05)
    ts = np.linspace(0.0, 60.0, 61)
    sol, w = speeds(m, ts)
    res = m.energy_balance(sol.ts, sol.ys)
    work = np.abs(sol.ys[:, m.layout.i_energy]).max()
    assert work > 1e-2
    assert np.abs(res).max() < 1e-6 * work


def test_low_limit_is_captured_at_the_critical_speed_a_higher_one_passes():
    """With the motor's characteristic T_s (1 - W / 3) as limit (the Sommerfeld test's motor):
    T_s = 0.0115 N m is captured below the critical speed 1 rad/s, 0.0135 passes (thresholds
    0.01333-0.01335 N m for the free motor); the servo then settles at its operating speed."""
    def servo(ts_):
        return ServoDrive(ts_, polar_inertia=J, no_load_speed=3.0, operating_speed=2.5,
                          ramp_rate=10.0, gain=5.0)
    m = Machine(STRUCTURE, unbalances=(Unbalance(0, 0.05),), drive=servo(0.0115), n_modes=2,
                energy_states=True)
    P = np.array([m.with_drive(servo(t)).to_array() for t in (0.0115, 0.0135)])
    sol = solve_ensemble(m, m.initial_state(spin_speed=0.0), (0.0, 400.0), params=P,
                         control=StepControl(rtol=1e-8, atol=1e-10))
    assert np.all(sol.status == 0)
    w = sol.y_final[:, m.layout.i_theta + 1]
    assert 0.9 < w[0] < 1.0
    assert abs(w[1] - 2.5) < 0.02


def test_named_parameters_and_bad_values():
    m = machine(0.02)
    names = {s.parameter.name for s in m._parameter_slots()}
    for f in ("drive.ramp_rate", "drive.dwell_speed", "drive.dwell_time", "drive.stall_torque"):
        assert f in names
    d = ServoDrive(0.02, polar_inertia=J, operating_speed=2.0, ramp_rate=0.5, dwell_speed=1.5,
                   dwell_time=3.0)
    assert math.isclose(d.command_duration, 2.0 / 0.5 + 3.0)
    np.testing.assert_allclose(d.command([1.0, 3.0, 5.0, 6.5, 9.0]), [0.5, 1.5, 1.5, 1.75, 2.0])
    with pytest.raises(ValueError, match="ServoDrive.ramp_rate"):
        ServoDrive(0.02, polar_inertia=J, operating_speed=2.0, ramp_rate=0.0)


def test_run_up_designer_finds_the_fastest_ramp_the_torque_limit_allows():
    """No unbalance, constant limit T = 0.01 N m, J = 0.05 kg m^2: the shortest run-up to 99 % of
    2.5 rad/s is the torque-limited one, 0.99 * 2.5 J / T = 12.375 s, for every ramp rate above
    T / J = 0.2 rad/s^2; slower ramps take 0.99 * 2.5 / a. The design search over the ramp rate
    finds it; a capture makes a design infeasible (run-up-time inf)."""
    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search
    from rotorlab.design import DESIGN_OBJECTIVES, DesignPoint, RunUpSettings

    fine = RunUpSettings(n_save=4000)
    base = machine(0.01, unbalance=0.0, ramp_rate=0.05, gain=50.0)
    ops = np.array([2.5])
    t_slow = DESIGN_OBJECTIVES["run-up-time"].value(DesignPoint(base, ops, run_up=fine))
    assert t_slow == pytest.approx(0.99 * 2.5 / 0.05, rel=2e-3)
    pb = DesignProblem(base, (DesignVariable("drive.ramp_rate", 0.02, 1.0),), ("run-up-time",), ops, run_up=fine)
    ds = design_search(pb, optimizer="tpe", budget=12, optimizer_seed=1, verify=False)
    assert bool(ds["feasible"].values.all())
    best = float(ds["objective_value"].values[ds["pareto"].values, 0][0])
    assert best == pytest.approx(0.99 * 2.5 * J / 0.01, rel=2e-3)
    captured = Machine(STRUCTURE, unbalances=(Unbalance(0, 0.05),), n_modes=2, energy_states=True,
                       drive=ServoDrive(0.0115, polar_inertia=J, no_load_speed=3.0, operating_speed=2.5,
                                        ramp_rate=10.0, gain=5.0))
    assert DESIGN_OBJECTIVES["run-up-time"].value(DesignPoint(captured, ops)) == math.inf


def test_case_file_servo_drive_builds_the_model(tmp_path):
    """``[model.drive] profile = "servo"`` with people's units builds the ServoDrive in SI; without a
    no-load speed the limit is constant."""
    from importlib import resources

    from rotorlab.io import load_case

    text = resources.files("rotorlab.cases").joinpath("washer-horizontal.toml").read_text(encoding="utf-8")
    text = text.replace('profile = "motor"\nstall_torque = "10 N*m"\nno_load_speed = "150 rad/s"',
                        'profile = "servo"\nstall_torque = "10 N*m"\noperating_speed = "955 rpm"\n'
                        'ramp_rate = "5 rad/s^2"\ndwell_speed = "300 rpm"\ndwell_time = "2 s"\ngain = "3 N*m*s/rad"')
    text = text.replace("passing_torque = true", "passing_torque = false")
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    from rotorlab.io._build import build_machine

    d = build_machine(load_case(path).model).drive
    assert isinstance(d, ServoDrive)
    assert d.operating_speed == pytest.approx(955 * math.pi / 30)
    assert (d.ramp_rate, d.dwell_time, d.gain) == (5.0, 2.0, 3.0)
    assert d.dwell_speed == pytest.approx(10 * math.pi)
    assert float(d.torque_at(1e4)) == pytest.approx(10.0)  # constant limit


def test_peak_limit_is_enforced_and_an_impossible_one_is_no_design():
    """Unbalance 0.05 kg m on the 1 rad/s disc, constant limit 0.05 N m (T / J = 1 rad/s^2): the
    transient peak at the critical speed falls as the passage speeds up (0.33 m at 0.02 rad/s^2,
    0.108 m at 0.1, 0.028 m at 1.0; Lewis 1932). With run-up-peak <= 0.1 m every design slower than
    about 0.1 rad/s^2 is infeasible and the winner keeps under it; with 0.01 m (below the fastest
    passage the torque allows) no design is feasible, and none is reported as the winner."""
    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search

    base = machine(0.05, unbalance=0.05, ramp_rate=0.1, gain=50.0)
    ops = np.array([2.5])
    var = (DesignVariable("drive.ramp_rate", 0.02, 1.0),)
    ds = design_search(DesignProblem(base, var, ("run-up-time",), ops, limits={"run-up-peak": 0.1}),
                       budget=8, optimizer_seed=2, verify=False)
    rate = ds["value"].values[:, 0]
    feasible = ds["feasible"].values
    assert feasible.any() and not feasible.all()
    assert np.all(rate[~feasible] < 0.11) and np.all(rate[feasible] > 0.09)
    win = np.flatnonzero(ds["pareto"].values)[0]
    assert ds["margin"].values[win, 0] >= 0.0
    assert ds["objective_value"].values[win, 0] == pytest.approx(0.99 * 2.5 / max(rate[win], 1.0), rel=0.02)
    none = design_search(DesignProblem(base, var, ("run-up-time",), ops, limits={"run-up-peak": 0.01}),
                         budget=4, optimizer_seed=2, verify=False)
    assert not none["feasible"].values.any() and not none["pareto"].values.any()


def test_balanced_share_constraint_reads_the_run_ups_wilson_bound():
    """Two 20 g balls at 0.5 m (capacity 0.02 kg m) run up to 2.5 rad/s (2.5 x the critical speed),
    8 starts, 300 s to settle: an unbalance of 0.01 kg m is balanced from every start, so
    run-up-unbalanced = 1 - 8 / (8 + 1.96^2) = 0.3244 (the Wilson bound of 8 / 8); 0.05 kg m is
    beyond the capacity and never balanced: 1."""
    from rotorlab.design import DESIGN_OBJECTIVES, DesignPoint, RunUpSettings
    from rotorlab.models import Ball, BallRace

    settings = RunUpSettings(starts=8, settle=300.0)
    z = 1.959963984540054
    for u, expected in ((0.01, 1.0 - 8.0 / (8.0 + z * z)), (0.05, 1.0)):
        m = Machine(STRUCTURE, races=(BallRace(0, 0.5, (Ball(0.02, damping=0.005),) * 2),),
                    unbalances=(Unbalance(0, u),), n_modes=2,
                    drive=ServoDrive(0.05, polar_inertia=J, operating_speed=2.5, ramp_rate=1.0, gain=50.0))
        value = DESIGN_OBJECTIVES["run-up-unbalanced"].value(DesignPoint(m, np.array([2.5]), run_up=settings))
        assert value == pytest.approx(expected, rel=1e-9)


def test_two_run_up_searches_in_one_process_keep_their_own_settings():
    """The run-up settings (starts, seed) belong to each design problem: two searches with
    different settings, one after the other and at the same time in two threads, each give
    exactly the result it gives alone (a module-level settings table shared by the searches would
    hand one search the other's starts), and the settings do change the result."""
    from concurrent.futures import ThreadPoolExecutor

    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search
    from rotorlab.design import RunUpSettings
    from rotorlab.models import Ball, BallRace

    m = Machine(STRUCTURE, races=(BallRace(0, 0.5, (Ball(0.02, damping=0.005),) * 2),),
                unbalances=(Unbalance(0, 0.01),), n_modes=2,
                drive=ServoDrive(0.05, polar_inertia=J, operating_speed=2.5, ramp_rate=1.0, gain=50.0))
    ops = np.array([2.5])

    def search(starts, seed):
        pb = DesignProblem(m, (DesignVariable("drive.ramp_rate", 0.2, 1.0),), ("run-up-peak",), ops,
                           run_up=RunUpSettings(starts=starts, seed=seed, n_save=400))
        ds = design_search(pb, budget=2, optimizer_seed=0, verify=False)
        return ds["value"].values.copy(), ds["objective_value"].values.copy()

    a, b = search(2, 1), search(3, 2)
    assert not np.array_equal(a[1], b[1])  # other starts, other transient peaks
    assert np.array_equal(a[0], b[0])  # the same optimiser seed proposes the same ramp rates
    with ThreadPoolExecutor(2) as pool:
        fa, fb = pool.submit(search, 2, 1), pool.submit(search, 3, 2)
        both = fa.result(), fb.result()
    for alone, together in zip((a, b), both):
        np.testing.assert_array_equal(together[0], alone[0])
        np.testing.assert_array_equal(together[1], alone[1])
    assert np.array_equal(search(2, 1)[1], a[1])  # and again after the other one


def test_a_run_up_design_runs_on_the_sweep_engine_resumes_and_runs_on_dask_to_the_same_bits(tmp_path):
    """The run-ups of each design are a sweep over its starts: a store per design
    (``eval-runup-<hash>.zarr``); a search resumed after losing some stores, and one on two local
    Dask workers, give the same bits as the search in memory."""
    import shutil

    from rotorlab.analyses._design import DesignProblem, DesignVariable, design_search
    from rotorlab.design import RunUpSettings
    from rotorlab.models import Ball, BallRace
    from rotorlab.sweep import DaskExecutor, open_sweep

    m = Machine(STRUCTURE, races=(BallRace(0, 0.5, (Ball(0.02, damping=0.005),) * 2),),
                unbalances=(Unbalance(0, 0.01),), n_modes=2,
                drive=ServoDrive(0.05, polar_inertia=J, operating_speed=2.5, ramp_rate=1.0, gain=50.0))
    pb = DesignProblem(m, (DesignVariable("drive.ramp_rate", 0.2, 1.0),), ("run-up-peak",), np.array([2.5]),
                       limits={"run-up-unbalanced": 0.9}, run_up=RunUpSettings(starts=5, seed=4, n_save=400))

    def data(ds):
        out = ds.copy()
        out.attrs = {k: v for k, v in ds.attrs.items() if not k.endswith("cpu_s")}
        return out

    ref = design_search(pb, budget=3, optimizer_seed=1)
    store = tmp_path / "evals"
    stored = design_search(pb, budget=3, optimizer_seed=1, store=store)
    assert data(stored).identical(data(ref))
    kept = sorted(store.glob("eval-runup-*.zarr"))
    assert len(kept) == 3 and open_sweep(kept[0]).sizes["start"] == 5
    for p in kept[::2]:
        shutil.rmtree(p)
    resumed = design_search(pb, budget=3, optimizer_seed=1, store=store, resume=True)
    assert data(resumed).identical(data(ref))
    on_dask = design_search(pb, budget=3, optimizer_seed=1, executor=DaskExecutor(workers=2, threads=1))
    assert data(on_dask).identical(data(ref))
    assert np.all(np.isfinite(ref["objective_value"].values))  # every design passed its critical speed
