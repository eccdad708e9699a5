"""Steady motions against Zhakash et al. 2024 (seed 002): averaged equations, and where the exact
analysis contradicts them.

The corrected formulas are those of :mod:`rotorlab.models._jeffcott_balls`; the contradictions
are listed in :mod:`rotorlab.steady._corrections`. Case numbers refer to the built-in case
``zhakash-k2`` (:func:`rotorlab.steady.steady_case`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams
from rotorlab.steady import analyze_steady, averaged_jacobian, run_up, steady_case, verify

CASE = steady_case("zhakash-k2")
P = CASE.critical_speed()
M1, C, M_BALL, R = CASE.rotor.disc_mass, CASE.rotor.stiffness, CASE.balls[0].mass, CASE.balls[0].radius
BETA0 = CASE.balls[0].damping / (M_BALL * R**2)


def _equal_model(eta, om=1.0, damping=None):
    rotor = RotorParams(M1, eta * M_BALL * R / M1, C, CASE.rotor.damping if damping is None else damping)
    return JeffcottBalls(rotor, CASE.balls, speed=ConstantSpeed(om))


def _p_seed(alpha, om, eta, big_m):
    """Corrected eq. (11): P_s = -(omega^2 W / beta0) [eta sin a_s + sum_j sin(a_s - a_j)]."""
    w = M_BALL / big_m * om**2 / (C / big_m - om**2)
    a = np.asarray(alpha, dtype=float)
    return -(om**2 * w / BETA0) * (eta * np.sin(a) + np.sum(np.sin(a[:, None] - a[None, :]), axis=1))


def _fd_jacobian(fun, x, h=1e-6):
    cols = []
    for j in range(x.size):
        e = np.zeros(x.size)
        e[j] = h
        cols.append((fun(x + e) - fun(x - e)) / (2 * h))
    return np.array(cols).T


@pytest.mark.parametrize("ratio", [0.7, 1.8])
def test_averaged_jacobian_is_the_corrected_P_s(ratio):
    """dP_s/dalpha_j of (11) (equal balls, eq. (14)); for unequal balls the gradient flow of
    D = H~* (eqs. (24)-(25) corrected): P = -grad D / b, so stationarity of D gives (11), not (9)."""
    model = _equal_model(1.2)
    om = ratio * model.critical_speed
    rng = np.random.default_rng(3)
    for _ in range(5):
        alpha = rng.uniform(-np.pi, np.pi, 2)
        ref = _fd_jacobian(lambda a: _p_seed(a, om, 1.2, model.total_mass), alpha)
        np.testing.assert_allclose(averaged_jacobian(model, om, alpha), ref, rtol=1e-6, atol=1e-8 * np.abs(ref).max())
    specs = ((0.02, 0.05, 1e-3), (0.05, 0.07, 4e-3), (0.03, 0.06, 2e-3))
    balls = tuple(BallParams(m, l, damping=b) for m, l, b in specs)
    three = JeffcottBalls(RotorParams(1.5, 2e-3, 900.0, 3.0), balls, speed=ConstantSpeed(om))
    b = np.array([x.damping for x in balls])

    undamped = replace(three, rotor=replace(three.rotor, damping=0.0))

    def d_undamped(psi):
        z = undamped.locked_response(psi, om)
        y = np.zeros(three.n_state)
        y[0], y[1], y[4:7] = z.real, z.imag, psi
        return float(undamped.with_frame("rotating").with_speed(ConstantSpeed(om)).reduced_hamiltonian(y))

    psi = rng.uniform(-np.pi, np.pi, 3)
    grad = _fd_jacobian(lambda q: np.array([d_undamped(q)]), psi, h=1e-5)[0]
    flow = lambda q: -_fd_jacobian(lambda r: np.array([d_undamped(r)]), q, h=1e-5)[0] / b  # noqa: E731
    np.testing.assert_allclose(averaged_jacobian(three, om, psi), _fd_jacobian(flow, psi, h=1e-4), rtol=2e-4,
                               atol=1e-6 * np.abs(grad).max() / b.min())  # fmt: skip


@pytest.mark.parametrize("eta", [0.4, 1.2, 1.9, 2.1, 2.6])
def test_existence_condition_17(eta):
    """Main solution 1 exists iff eta / 2 < 1; its angles are +-(pi - arccos(eta / 2))."""
    res = analyze_steady(_equal_model(eta), 2.0 * P)
    main = res.motion("main+")
    assert main.exists == (eta < 2)
    if eta < 2:
        gamma = math.acos(eta / 2)
        np.testing.assert_allclose(main.ball_angles, [math.pi - gamma, -(math.pi - gamma)], atol=1e-13)
        np.testing.assert_allclose(res.motion("main-").ball_angles, -main.ball_angles, atol=1e-13)
        assert main.amplitude == 0.0


@pytest.mark.parametrize("eta", [1.2, 2.6])
@pytest.mark.parametrize("ratio", [0.6, 2.0])
def test_main_solution_stable_above_p_by_22(eta, ratio):
    """(20)-(23) corrected: solution 1 stable iff omega > p (the sentence after (23) says
    unstable); 2 iff omega < p; 3 iff omega > p and eta > 2; 4 never. A, B as (21), (23)."""
    model = _equal_model(eta)
    om = ratio * model.critical_speed
    res = analyze_steady(model, om)
    k = om**4 * M_BALL / (BETA0 * (C - model.total_mass * om**2))  # K = omega^2 W / beta0
    expect = {"side 00": (2 * k * (1 + eta), k**2 * eta * (eta + 2)),
              "side 11": (2 * k * (1 - eta), k**2 * eta * (eta - 2)),
              "side 01": (-2 * k, -(k**2) * eta**2)}  # fmt: skip
    if eta < 2:
        expect["main+"] = (-2 * k, k**2 * eta**2 * (1 - eta**2 / 4))
    for label, (a, b) in expect.items():
        st = res.motion(label).stability
        assert st.averaged_a == pytest.approx(a, rel=1e-9)
        assert st.averaged_b == pytest.approx(b, rel=1e-9, abs=1e-9 * k * k)
    stable = set(res.stable("averaged"))
    if ratio < 1:
        assert stable == {"side 00"}
    else:
        assert stable == ({"main+", "main-"} if eta < 2 else {"side 11"})
    assert stable == set(res.stable("hamilton"))  # seed 003's method agrees here


def _growth(model, label, ratio):
    return analyze_steady(model, ratio * P).motion(label).stability.growth_rate


def test_window_above_critical_speed_exact_and_simulated():
    """(20)-(22) say the main solution is stable for every omega > p; exactly it is unstable up to
    omega* = 1.457 p, where nothing is stable and the balls whirl together at about 0.95 p."""
    model = CASE.model("enough")
    edge = brentq(lambda r: _growth(model, "main+", r), 1.3, 1.6, xtol=1e-5)
    assert edge == pytest.approx(1.457, abs=2e-3)
    res = analyze_steady(model, 1.2 * P)
    assert res.stable("exact") == () and res.stable("averaged") == ("main+", "main-")
    assert {(d.label, d.method, d.exact) for d in res.disagreements} >= {("main+", "averaged", "unstable")}
    ds = verify(model, [1.2 * P], points=3, t_end=12.0)
    assert set(ds.reached.values.ravel()) == {"non-synchronous"}
    assert np.all(np.abs(ds.mean_ball_speed.values / P - 0.95) < 0.03)
    assert bool(ds.agrees_exact.values[0]) and not bool(ds.agrees_averaged.values[0])
    short = CASE.model("short")  # the third solution (eta > 2) has its own window
    lo = brentq(lambda r: _growth(short, "side 11", r), 1.02, 1.2, xtol=1e-5)
    hi = brentq(lambda r: _growth(short, "side 11", r), 1.3, 1.8, xtol=1e-5)
    assert (lo, hi) == (pytest.approx(1.100, abs=2e-3), pytest.approx(1.582, abs=2e-3))


def test_coexisting_whirl_above_the_window():
    """At 1.6 p the main motions are exactly stable, yet some starts from rest end in the
    non-synchronous whirl near p (a second attractor that no eigenvalue can show)."""
    model = CASE.model("enough")
    res = analyze_steady(model, 1.6 * P)
    assert res.stable("exact") == ("main+", "main-") and res.disagreements == ()
    starts = np.radians([[-30.0, -15.0], [120.0, -120.0]])
    ds = verify(model, [1.6 * P], initial_ball_angles=starts, t_end=60.0)
    assert ds.reached.values[0].tolist() == ["non-synchronous", "main+"]
    assert np.abs(ds.mean_ball_speed.values[0, 0] / P - 0.96).max() < 0.02
    assert 0.015 < ds.final_amplitude.values[0, 0] < 0.025
    assert not bool(ds.agrees_exact.values[0])


def test_solutions_2_and_3_vanish_near_p():
    """With beta > 0 solutions 2 and 3 (|s| = 2 m R > M1 r) merge and vanish near p."""
    model = CASE.model("enough")
    for ratio, exists in ((0.96, True), (0.98, False), (1.02, False), (1.04, True)):
        res = analyze_steady(model, ratio * P)
        assert res.motion("side 00").exists == exists and res.motion("side 11").exists == exists
    res = analyze_steady(model, 0.99 * P)
    assert res.stable("averaged") == ("side 00",) and res.stable("exact") == ()
    assert ("side 00", "averaged", "absent") in {(d.label, d.method, d.exact) for d in res.disagreements}
    assert analyze_steady(CASE.model("short"), 0.99 * P).motion("side 00").exists  # |s| < M1 r


def test_no_support_damping_destabilises_the_main_solution():
    """beta = 0: the main solution grows at every speed above p; the growth rate of the linear
    analysis is what a simulation from a nearby state shows."""
    model = CASE.model("enough")
    model = replace(model, rotor=replace(model.rotor, damping=0.0))
    rates = {r: _growth(model, "main+", r) for r in (1.5, 2.0, 4.0, 10.0)}
    assert all(g > 0 for g in rates.values()), rates
    om = 2.0 * P
    main = analyze_steady(model, om).motion("main+")
    lin = model.linearize(main.states()[0], spin_speed=om)
    lam, vec = np.linalg.eig(lin.A)
    k = int(np.argmax(lam.real))
    rot = model.with_speed(ConstantSpeed(om)).with_frame("rotating")
    y0 = main.states()[0] + 1e-7 * np.real(vec[:, k]) / np.abs(vec[:4, k]).max()
    ts = np.linspace(0.0, 30.0, 6001)
    sol = solve(rot, y0, (0.0, 30.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-14))
    amp = np.hypot(sol.ys[:, 0], sol.ys[:, 1])
    period = 2 * np.pi / abs(lam[k].imag)
    a1 = amp[(ts > 8.0) & (ts < 8.0 + 2 * period)].max()
    a2 = amp[(ts > 28.0 - 2 * period) & (ts < 28.0)].max()
    assert math.log(a2 / a1) / 20.0 == pytest.approx(lam[k].real, rel=0.03)
    assert lam[k].real == pytest.approx(rates[2.0], rel=1e-9)


def test_run_up_capture_and_synchronisation():
    """A slow run-up (2 p per second) leaves the balls captured at about p, 30 mm at 2.5 p; a fast
    one (10 p per second) balances the rotor."""
    model = CASE.model("enough")
    starts = [[0.3, 2.0], [1.0, -2.5]]
    slow = run_up(model, LinearRamp(0.3 * P, 2.5 * P, 1.1), t_end=16.1, initial_ball_angles=starts)
    assert not slow.synchronised.values.any()
    assert np.all(slow.final_amplitude.values > 0.02) and np.all(slow.max_amplitude.values < 0.035)
    assert float(slow.final_amplitude_without) < 2e-3  # the disc alone would pass p and settle
    fast = run_up(model, LinearRamp(0.3 * P, 2.5 * P, 0.22), t_end=15.22, initial_ball_angles=starts)
    assert fast.synchronised.values.all()
    assert set(fast.final_motion.values) <= {"main+", "main-"}
    assert np.all(fast.final_amplitude.values < 1e-5)


def test_verify_both_regimes():
    """Done-when: from every start of the grid the simulation ends as the exact eigenvalues
    predict; seed 002 (and 003) fail only in the window above p."""
    fractions = {}
    for regime in ("enough", "short"):
        ds = verify(CASE.model(regime), CASE.speeds(), points=4)
        assert ds.agrees_exact.values.all(), regime
        assert ds.agrees_averaged.values.tolist() == [True, False, True, True]
        assert ds.agrees_hamilton.values.tolist() == [True, False, True, True]
        fractions[regime] = {
            round(float(r), 1): {str(o): float(f) for o, f in zip(ds.outcome.values, row) if f > 0}
            for r, row in zip(ds.speed_ratio.values, ds.fraction.values)
        }
    assert fractions["enough"][0.6] == {"side 00": 1.0} and fractions["enough"][1.2] == {"non-synchronous": 1.0}
    for ratio in (2.0, 3.0):
        assert sum(v for k, v in fractions["enough"][ratio].items() if k.startswith("main")) == pytest.approx(1.0)
        assert fractions["short"][ratio] == {"side 11": 1.0}
