"""``shock-margin`` (issue 26 item 3) on the built-in ``autobalancer`` at 2 p (seed 002's balancer).

Closed forms: the load shift that leaves two balls unable to balance is ``C - U`` along the
unbalance (the balls' polygon closes iff ``|U'| <= C``, seed 002 eq. (17) eta/2 <= 1); the
linearised-basin impulse uses the distance to the side motion where the balls meet,
``gamma = arccos(eta / 2)`` (seed 002 eq. (16)). Measured (24 directions, 8 bisections): the
estimate's minimum 2.43 N s, the simulated minimal fatal knock 2.32 N s (5 % lower).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

from rotorlab.analyses import build_model
from rotorlab.analyses._shock_margin import (
    BISECTIONS,
    BRACKET,
    balanced_angles,
    linear_impulse,
    load_shift_bound,
    shock_margin,
)
from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
from rotorlab.io import load_case
from rotorlab.models import ConstantSpeed


@pytest.fixture(scope="module")
def model():
    return build_model(load_case("autobalancer").model)


@pytest.fixture(scope="module")
def margin(model):
    return shock_margin(model, [2.0 * model.critical_speed], directions=24)


def test_load_shift_closed_form():
    u, a = 1.5e-3, [1.5e-3, 1.5e-3]  # eta = 1: the autobalancer
    beta = np.radians([0.0, 90.0, 180.0])
    # |U + S e^{i beta}| = C: along U, C - U; across, sqrt(C^2 - U^2); against, C + U
    np.testing.assert_allclose(load_shift_bound(u, a, beta), [1.5e-3, math.sqrt(3e-3**2 - u**2), 4.5e-3], rtol=1e-12)
    # unequal balls (a = 2, 1 g m, C = 3 g m): an unbalance below a_max - a_min = 1 g m cannot be
    # cancelled either; from U = 1.5 g m a shift of 0.5 g m against it reaches that
    s = load_shift_bound(1.5e-3, [2e-3, 1e-3], [math.pi, 0.0])
    np.testing.assert_allclose(s, [0.5e-3, 1.5e-3], rtol=1e-12)


def test_load_shift_checked_by_simulation(margin, model):
    assert margin.stable.values.tolist() == [1]
    assert float(margin.min_load_shift[0]) == pytest.approx(model.capacity - model.imbalance, rel=1e-12)
    assert float(margin.worst_shift_direction[0]) == 0.0
    # every direction: 0.9 of the bound balances again, 1.1 of it does not
    assert np.all(margin.shift_below.values == 1) and np.all(margin.shift_above.values == 0)


def test_linear_estimate_matches_a_matrix_exponential(model):
    om = 2.0 * model.critical_speed
    rot = model.with_frame("rotating").with_speed(ConstantSpeed(om))
    angles = balanced_angles(rot, om)
    gamma = math.acos(model.imbalance / model.balls[0].static_moment / 2.0)  # eta = 1: 60 deg
    assert gamma == pytest.approx(math.pi / 3.0, rel=1e-12)
    np.testing.assert_allclose(np.abs(angles), math.pi - gamma, rtol=1e-9)  # seed 002 eq. (16), eta = 1
    lin = rot.linearize(rot.initial_state(angles), om)
    bound, r, kick = linear_impulse(lin, angles, [math.radians(30.0)])
    assert r == pytest.approx(gamma, rel=1e-9)
    # independent: step the linear system with expm over 1 s, kick of 1 N s along beta = 30 deg
    x = np.zeros(8)
    x[[2, 3, 6, 7]] = np.linalg.solve(lin.M, [math.cos(math.radians(30.0)), math.sin(math.radians(30.0)), 0, 0])
    step = expm(lin.A * 1e-4)
    peak = 0.0
    for _ in range(10000):
        x = step @ x
        peak = max(peak, abs(x[4]), abs(x[5]))
    assert bound[0] == pytest.approx(gamma / peak, rel=2e-3)


def test_simulated_threshold_against_the_linearised_estimate(margin):
    est, sim = float(margin.min_impulse_linear[0]), float(margin.min_impulse_simulated[0])
    assert 2.3 < est < 2.6  # N s
    assert sim == pytest.approx(est, rel=0.10)
    assert np.all(np.isfinite(margin.impulse_simulated.values))
    # with this ball damping every start off the diagonal balances (the case's basin): a fatal knock
    # does not leave the rotor unbalanced, it sends the balls round to another balanced arrangement
    assert set(margin.fatal_outcome.values.ravel()) == {"balanced"}


def test_knocks_just_below_return_and_just_above_do_not(margin, model):
    # an independent re-simulation in the fixed frame (the analysis works in the rotating one)
    om = 2.0 * model.critical_speed
    fixed = model.with_frame("fixed").with_speed(ConstantSpeed(om))
    rot = fixed.with_frame("rotating")
    angles = balanced_angles(rot, om)
    est = float(margin.min_impulse_linear[0])
    worst = float(margin.worst_impulse_direction[0])
    lin = rot.linearize(rot.initial_state(angles), om)
    starts, beta = [], margin.direction.values
    for factor, directions in ((0.9, beta), (1.1, [worst])):
        for b in directions:
            y = rot.initial_state(angles)
            dq = np.linalg.solve(lin.M, [factor * est * math.cos(b), factor * est * math.sin(b), 0.0, 0.0])
            y[2:4] += dq[:2]
            y[6:8] += dq[2:]
            starts.append(rot.to_frame(0.0, y, "fixed"))
    t_end = float(margin.horizon[0])
    sol = solve_ensemble(fixed, np.array(starts), (0.0, t_end), save_at=SaveAt(ts=[t_end]),
                         control=StepControl(rtol=1e-8, atol=1e-10))  # fmt: skip
    end = fixed.to_frame(t_end, np.asarray(sol.y_final), "rotating")
    moved = np.abs(end[:, 4:6] - angles).max(axis=1)
    assert np.all(np.asarray(sol.status) >= 0)
    assert np.all(moved[:-1] < 1e-3)  # 0.9 x the estimate, every direction: back to the same angles
    assert moved[-1] > 0.5  # 1.1 x the estimate at the worst direction: thrown to another arrangement
    assert np.all(np.hypot(end[:, 0], end[:, 1]) < 1e-6)  # both end balanced (the other one with the balls swapped)


# --------------------------------------------------------------------------- the same on a machine


@pytest.fixture(scope="module")
def planar(model):
    """The autobalancer as a planar machine (the same right-hand side to 1e-12, tests/unit/test_machine.py)."""
    from rotorlab.continuation import as_machine

    return as_machine(model)


def test_planar_machine_has_the_rotor_s_shock_margin(margin, planar):
    # the machine runs in the fixed frame from its own balanced state (Machine.balanced_angles), the
    # rotor in its co-rotating frame from seed 002's: the same knocks must be fatal
    m = shock_margin(planar, [float(margin.speed[0])], directions=24)
    assert m.attrs["station"] == "node 0" and m.attrs["capacity"] == pytest.approx(3e-3, rel=1e-12)
    np.testing.assert_allclose(m.impulse_linear.values, margin.impulse_linear.values, rtol=1e-9)
    np.testing.assert_allclose(m.decay_rate.values, margin.decay_rate.values, rtol=1e-9)
    step = BRACKET * margin.impulse_linear.values / 2**BISECTIONS  # the bisection's last bracket
    assert np.all(np.abs(m.impulse_simulated.values - margin.impulse_simulated.values) <= step)
    assert float(m.min_impulse_simulated[0]) == pytest.approx(2.32, abs=0.01)  # N s
    assert set(m.fatal_outcome.values.ravel()) == {"balanced"}  # machine_outcome's label: balanced again
    # load shift C - U = 1.5 g m along the unbalance; 0.9 x balances again, 1.1 x not, every direction
    np.testing.assert_allclose(m.load_shift_bound.values, margin.load_shift_bound.values, rtol=1e-12)
    assert float(m.min_load_shift[0]) == pytest.approx(1.5e-3, rel=1e-12)
    assert np.all(m.shift_below.values == 1) and np.all(m.shift_above.values == 0)


def test_searched_load_shift_of_a_machine_is_the_closed_form(planar):
    # the bisection on Machine.balanced_angles (used where races and unbalances are not in one plane)
    # finds the polygon bound where it holds: a rotated unbalance, directions from it
    from dataclasses import replace

    from rotorlab.analyses._shock_subjects import shock_subject

    turned = replace(planar, unbalances=(replace(planar.unbalances[0], phase=0.7),))
    sub = shock_subject(turned)
    assert sub.moments is not None  # one race in the unbalance's plane: the closed form
    beta = np.radians([0.0, 75.0, 180.0])
    closed = sub.load_shift_bound(beta)
    np.testing.assert_allclose(closed, load_shift_bound(1.5e-3, [1.5e-3, 1.5e-3], beta), rtol=1e-12)
    searched = [sub._searched_shift(b) for b in beta]
    np.testing.assert_allclose(searched, closed, rtol=1e-6)


def test_machine_impulse_is_m_inverse_of_the_station_force(planar):
    # a knock on node 0 of the planar machine, 1 N s at 30 deg from the unbalance turned by 40 deg:
    # the state jumps by M^-1 (B^T e, 0) with e at 70 deg in the fixed (= co-rotating at t = 0) frame
    from dataclasses import replace

    from rotorlab.analyses._shock_subjects import shock_subject
    from rotorlab.models import ConstantSpeed

    om = 2.0 * 125.66802628428869
    turned = replace(planar, unbalances=(replace(planar.unbalances[0], phase=math.radians(40.0)),))
    bal = shock_subject(turned).balanced(om)
    b = math.radians(30.0)
    jump = math.cos(b) * bal.kick[0] + math.sin(b) * bal.kick[1]
    m = turned.with_drive(ConstantSpeed(om))
    lay = m.layout
    M = m.mass_matrix(bal.y)
    dq = np.concatenate([jump[2:4], jump[lay.i_w : lay.i_w + 2]])
    np.testing.assert_allclose(M @ dq, [math.cos(math.radians(70.0)), math.sin(math.radians(70.0)), 0.0, 0.0],
                               atol=1e-12)  # fmt: skip
    # the balanced angles measured from the turned unbalance are seed 002's +-(pi - gamma), gamma = 60 deg
    psi = np.sort(np.mod(bal.angles - math.radians(40.0) + math.pi, 2 * math.pi) - math.pi)
    np.testing.assert_allclose(psi, [-2.0 * math.pi / 3.0, 2.0 * math.pi / 3.0], atol=1e-9)


def test_two_plane_machine_load_shift_is_the_papers_capacity():
    # rcfw-two-plane (Rodrigues et al. 2008): a static unbalance U at the rotor's centre, races of
    # capacity 2 m R = 0.01 kg m at z = +-2 m; each race must carry U'/2, so the balls balance while
    # |U'| <= 4 m R (their eq. (21), m >= m_c = eps / 4): the polygon bound with C = 0.02 kg m, found
    # here by the search on Machine.balanced_angles (two planes: no closed form in the code)
    from rotorlab.analyses._shock_subjects import shock_subject

    sub = shock_subject(build_model(load_case("rcfw-two-plane").model))
    assert sub.moments is None and sub.imbalance == pytest.approx(0.01, rel=1e-12)
    beta = np.radians([0.0, 90.0, 150.0])
    np.testing.assert_allclose(sub.load_shift_bound(beta), load_shift_bound(0.01, [0.005] * 4, beta), rtol=1e-6)
