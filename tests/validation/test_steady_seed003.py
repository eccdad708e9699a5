"""Steady motions against Filimonikhin & Filimonikhina (seed 003): H~* (10)-(17), the Hessian
(19), the cases 1, 2a, 2b, and where the exact analysis contradicts the conclusions.

Case numbers refer to the built-in case ``filimonikhin-n2`` (:func:`rotorlab.steady.steady_case`);
the contradictions are listed in :mod:`rotorlab.steady._corrections`.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams
from rotorlab.steady import analyze_steady, find_steady_motions, hessian_f, steady_case, verify

CASE = steady_case("filimonikhin-n2")
P = CASE.critical_speed()
S1, S2 = (b.static_moment for b in CASE.balls)
THREE = (
    BallParams(0.05, 0.08, inertia=0.05 * 0.08**2 * 1.4, damping=1e-3),
    BallParams(0.07, 0.10, damping=2e-3),
    BallParams(0.04, 0.09, inertia=0.04 * 0.09**2 + 2e-5, damping=1e-3),
)


def _undamped(model):
    return replace(model, rotor=replace(model.rotor, damping=0.0))


@pytest.mark.parametrize("om", [12.0, 35.0])
def test_h_tilde_eqs_14_15(om):
    """2 H~*(0) = -om^2 J (14), 2 H~*(k) = -om^4 (Me + s(k))^2 / (c - M om^2) - om^2 J (15), with
    J = sum J_Oi + M1 e^2 (the disc's own J_O is left out)."""
    model = JeffcottBalls(RotorParams(1.5, 4e-3, 600.0), THREE, speed=ConstantSpeed(om))
    const = om**2 * (model.imbalance * model.rotor.eccentricity + sum(b.inertia for b in THREE))
    den = model.rotor.stiffness - model.total_mass * om**2
    s = np.array([b.static_moment for b in THREE])
    for m in find_steady_motions(model):
        if m.kind == "main":
            assert 2 * m.h_tilde == pytest.approx(-const, rel=1e-13)
        else:
            total = model.imbalance + np.sum(s * (-1.0) ** np.array(m.bits))
            assert 2 * m.h_tilde == pytest.approx(-(om**4) * total**2 / den - const, rel=1e-12)


def test_h_tilde_on_the_constraint_eq_16():
    """With the rotor on the first two of (11): 2 H~* = -om^4 f / (c - M om^2) - om^2 J, f = u^2 + v^2
    of (17); printed (16) leaves out the constant -om^2 J."""
    model = JeffcottBalls(RotorParams(1.5, 4e-3, 600.0), THREE, speed=ConstantSpeed(30.0), frame="rotating")
    om = 30.0
    const = om**2 * (model.imbalance * model.rotor.eccentricity + sum(b.inertia for b in THREE))
    s = np.array([b.static_moment for b in THREE])
    rng = np.random.default_rng(7)
    for _ in range(10):
        psi = rng.uniform(-np.pi, np.pi, 3)
        unb = model.imbalance + np.sum(s * np.exp(1j * psi))
        z = om**2 * unb / (model.rotor.stiffness - model.total_mass * om**2)
        y = np.zeros(model.n_state)
        y[0], y[1], y[4:7] = z.real, z.imag, psi
        f = abs(unb) ** 2
        h2 = 2 * float(model.reduced_hamiltonian(y))
        assert h2 == pytest.approx(-(om**4) * f / (model.rotor.stiffness - model.total_mass * om**2) - const, rel=1e-12)


def test_hessian_eq_19_two_pendulums():
    """Entries of (19) on the main motion and the four side motions (fourth: corrected case ii)."""
    for regime in ("enough", "short", "dominant"):
        me = CASE.model(regime).imbalance
        res = analyze_steady(CASE.model(regime), 2.0 * P)
        printed = {
            "side 00": [[-S1 * (S2 + me), S1 * S2], [S1 * S2, -S2 * (S1 + me)]],
            "side 01": [[-S1 * (me - S2), -S1 * S2], [-S1 * S2, S2 * (me + S1)]],
            "side 11": [[S1 * (me - S2), S1 * S2], [S1 * S2, S2 * (me - S1)]],
        }
        for label, a in printed.items():
            np.testing.assert_allclose(hessian_f(me, [S1, S2], np.pi * np.array(res.motion(label).bits)), a, rtol=1e-12)
        dets = {"side 00": me * S1 * S2 * (S1 + S2 + me), "side 01": -me * S1 * S2 * (me + S1 - S2),
                "side 11": me * S1 * S2 * (me - S1 - S2)}  # fmt: skip
        for label, det in dets.items():
            hess = hessian_f(me, [S1, S2], np.pi * np.array(res.motion(label).bits))
            assert np.linalg.det(hess) == pytest.approx(det, rel=1e-10)
        kinds = {m.label: m.stability.hessian for m in res.motions if m.kind == "side"}
        assert kinds["side 00"] == "maximum"
        assert kinds["side 01"] == ("minimum" if S2 > me + S1 else "saddle")
        assert kinds["side 11"] == ("minimum" if me > S1 + S2 else "saddle")
        if res.motion("main+").exists:
            psi = res.motion("main+").ball_angles
            a = hessian_f(me, [S1, S2], psi)
            np.testing.assert_allclose(np.diag(a), [S1**2, S2**2], rtol=1e-12)
            assert np.linalg.det(a) == pytest.approx(S1**2 * S2**2 * math.sin(psi[1] - psi[0]) ** 2, rel=1e-10)
            assert res.motion("main+").stability.hessian == "minimum"


@pytest.mark.parametrize("regime, above", [("enough", ("main+", "main-")), ("short", ("side 11",)),
                                           ("dominant", ("side 01",))])  # fmt: skip
def test_cases_1_2a_2b(regime, above):
    """Case 1: below omega_cr only the first side motion (all k_i = 0); 2a: above, the main motions;
    2b (corrected, least H~*): all pendulums on the light side; a dominating pendulum: motion 01.
    Outside the windows near p the exact eigenvalues agree."""
    model = CASE.model(regime)
    for ratio in (0.6, 2.0, 3.0):
        res = analyze_steady(model, ratio * P)
        expect = ("side 00",) if ratio < 1 else above
        assert res.stable("hamilton") == expect and res.stable("exact") == expect
        least = min((m for m in res.motions if m.exists), key=lambda m: m.h_tilde)
        assert least.label in expect and least.stability.hamilton_minimal
        assert res.disagreements == ()


def test_dominating_pendulum_no_main_motion():
    """Me < m1 l1 + m2 l2 but m2 l2 > Me + m1 l1: no main motion (case 2a's condition is not
    sufficient); the stable motion 01 is a side motion with a deflection (not a main motion)."""
    model = CASE.model("dominant")
    assert model.imbalance < model.capacity and S2 > model.imbalance + S1
    res = analyze_steady(model, 2.0 * P)
    assert not res.motion("main+").exists and not res.motion("main-").exists
    side = res.motion("side 01")
    x = (2 * P) ** 2 * (model.imbalance + S1 - S2) / (model.rotor.stiffness - model.total_mass * (2 * P) ** 2)
    assert analyze_steady(_undamped(model), 2.0 * P).motion("side 01").deflection == pytest.approx(x, rel=1e-12)
    assert side.amplitude == pytest.approx(abs(x), rel=0.02) and side.amplitude > 1e-5
    ds = verify(model, [2.0 * P], points=3)
    assert set(ds.reached.values.ravel()) == {"side 01"} and bool(ds.agrees_hamilton.values[0])
    assert ds.final_amplitude.values == pytest.approx(side.amplitude, rel=1e-4)


def test_supercritical_main_motions_need_support_damping():
    """Conclusion 3 and the abstract assume undamped supports; then no steady motion is stable above
    omega_cr: H* is not a local minimum there and the pendulums' dissipation destroys the gyroscopic
    stability (without any dissipation the main motion is only marginally stable). With d > 0 the
    main motions are stable above omega* = 1.395 p only."""
    for regime in ("enough", "short", "dominant"):
        model = _undamped(CASE.model(regime))
        for ratio in (1.5, 2.0, 4.0):
            res = analyze_steady(model, ratio * P)
            assert res.stable("exact") == () and len(res.stable("hamilton")) >= 1, (regime, ratio)
            assert {d.method for d in res.disagreements} == {"hamilton", "averaged"}
    undamped = CASE.model("undamped")
    main = analyze_steady(undamped, 2.0 * P).motion("main+")
    assert main.stability.growth_rate == pytest.approx(0.106, abs=1e-3)
    lin = undamped.linearize(main.states()[0], spin_speed=2.0 * P)
    assert np.sum(np.linalg.eigvalsh(lin.K) < 0) == 2  # H~* a saddle of even index: (x, y) block
    conservative = replace(undamped, balls=tuple(replace(b, damping=0.0) for b in undamped.balls))
    assert analyze_steady(conservative, 2.0 * P).motion("main+").stability.exact == "marginal"
    enough = CASE.model("enough")
    edge = brentq(lambda r: analyze_steady(enough, r * P).motion("main+").stability.growth_rate, 1.2, 1.6, xtol=1e-5)
    assert edge == pytest.approx(1.395, abs=2e-3)
    dominant = CASE.model("dominant")
    growth = lambda r: analyze_steady(dominant, r * P).motion("side 01").stability.growth_rate  # noqa: E731
    edge = brentq(growth, 1.2, 1.8, xtol=1e-5)
    assert edge == pytest.approx(1.459, abs=2e-3)
    ds = verify(undamped, [2.0 * P], points=2, t_end=60.0)
    assert set(ds.reached.values.ravel()) == {"non-synchronous"}
    assert bool(ds.agrees_exact.values[0]) and not bool(ds.agrees_hamilton.values[0])


def test_damping_removes_side_motions_below_p():
    """Case 1 with support damping: the first side motion vanishes above 0.782 p (dominant regime)
    and then nothing is stable below p; the pendulums do not synchronise."""
    model = CASE.model("dominant")
    lo, hi = 0.7, 0.9
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if analyze_steady(model, mid * P).motion("side 00").exists else (lo, mid)
    assert lo == pytest.approx(0.782, abs=1e-3)
    res = analyze_steady(model, 0.9 * P)
    assert res.stable("hamilton") == ("side 00",) and res.stable("exact") == ()
    assert ("side 00", "hamilton", "absent") in {(d.label, d.method, d.exact) for d in res.disagreements}
    ds = verify(model, [0.9 * P], points=3, t_end=15.0)
    assert set(ds.reached.values.ravel()) == {"non-synchronous"} and bool(ds.agrees_exact.values[0])


def test_three_pendulums_family_of_main_motions():
    """n = 3: the main motions form a one-parameter family (one neutral eigenvalue); every member is
    stable well above p, and simulations end on the family."""
    pend = tuple(BallParams(m, 0.05, inertia=1.3 * m * 0.05**2, damping=20.0 * m * 0.05**2) for m in (0.03, 0.04, 0.05))
    model = JeffcottBalls(replace(CASE.rotor, eccentricity=1e-3), pend, speed=ConstantSpeed(1.0))
    om = 2.5 * model.critical_speed
    res = analyze_steady(model, om, family_samples=8)
    main = res.motion("main")
    assert main.dimension == 1 and main.samples.shape[0] >= 8
    assert main.stability.exact == "stable" and main.stability.hamilton == "stable"
    assert main.stability.averaged == "stable"
    for y in main.states():
        eig = model.linearize(y, spin_speed=om).eigenvalues
        assert np.sum(np.abs(eig) < 1e-8 * np.abs(eig).max()) == 1
    ds = verify(model, [om], points=2)
    assert set(ds.reached.values.ravel()) == {"main"} and bool(ds.agrees_exact.values[0])


def test_verify_all_regimes():
    """Done-when: from every start of the grid the simulation ends as the exact eigenvalues predict."""
    expected = {
        "enough": [{"side 00"}, {"non-synchronous"}, {"main+", "main-"}, {"main+", "main-"}],
        "short": [{"side 00"}, {"non-synchronous"}, {"side 11"}, {"side 11"}],
        "dominant": [{"side 00"}, {"non-synchronous"}, {"side 01"}, {"side 01"}],
    }
    for regime, ends in expected.items():
        ds = verify(CASE.model(regime), CASE.speeds(), points=3)
        assert ds.agrees_exact.values.all(), regime
        assert [set(row) for row in ds.reached.values] == ends, regime
        assert ds.agrees_hamilton.values.tolist() == [True, False, True, True]
    ds = verify(CASE.model("undamped"), CASE.speeds()[1:], points=2, t_end=30.0)
    assert ds.agrees_exact.values.all() and not ds.agrees_hamilton.values.any()
