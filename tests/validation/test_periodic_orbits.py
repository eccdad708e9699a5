"""The non-synchronous whirl of ``zhakash-k2`` as a periodic orbit, continued in the speed.

The built-in case's README and ``test_steady_seed002.py::test_coexisting_whirl_above_the_window``
found the whirl only by simulation (a tenth of the starts at 1.6 p end in it). Here it is an
orbit of the co-rotating frame (both balls together, each turning once backwards per period:
winding -1 on both ball angles), found from such a simulation, checked against independent long
simulations (period and amplitude to 1e-4), and continued in the speed: upwards it stays stable
until a branch point of orbits (a second multiplier +1) just below a fold of cycles, above which
a simulation started on the last orbit balances the rotor; downwards its period grows without
bound as the speed approaches the saddle-node at which the side motions 00 and 11 are born
(``rotorlab.steady.analyze_steady``), the end of a whirl born on the circle of that saddle-node.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorlab.continuation import ContinuationSettings, continue_periodic, find_periodic_orbit, orbit_from_simulation
from rotorlab.integrate import Lanes, SaveAt, StepControl, solve_ensemble
from rotorlab.models import ConstantSpeed
from rotorlab.steady import analyze_steady, steady_case

CASE = steady_case("zhakash-k2")
P = CASE.critical_speed()
MODEL = CASE.model("enough")
START = np.radians([-30.0, -15.0])  # ends in the whirl at 1.6 p (test_steady_seed002)


def _rot(om):
    return MODEL.with_speed(ConstantSpeed(om)).with_frame("rotating")


def _at(om):
    return MODEL.with_speed(ConstantSpeed(om)).to_array()


def _simulated(om, y0, t_settle, period_guess):
    """Period (upward crossings of u through its mean, 20000 samples over 4 periods) and amplitude
    (largest |u + i v|, parabola through the peak) of a long simulation (rtol 1e-11)."""
    rot = _rot(om)
    ctrl = StepControl(rtol=1e-11, atol=1e-13)
    settled = solve_ensemble(rot, y0, (0.0, t_settle), control=ctrl, backend=Lanes(8))
    ts = np.linspace(0.0, 4 * period_guess, 20001)
    win = solve_ensemble(rot, settled.y_final[0], (0.0, ts[-1]), save_at=SaveAt(ts=ts), control=ctrl, backend=Lanes(8))
    assert int(settled.status[0]) == 0 and int(win.status[0]) == 0
    ys = win.ys[0]
    s = ys[:, 0] - ys[:, 0].mean()
    k = np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))
    tc = ts[k] - s[k] * (ts[k + 1] - ts[k]) / (s[k + 1] - s[k])
    r = np.hypot(ys[:, 0], ys[:, 1])
    j = int(np.argmax(r[1:-1])) + 1
    den = r[j - 1] - 2 * r[j] + r[j + 1]
    return float(np.mean(np.diff(tc))), float(r[j] - 0.125 * (r[j + 1] - r[j - 1]) ** 2 / den), ys[-1]


@pytest.fixture(scope="module")
def whirl():
    return orbit_from_simulation(_rot(1.6 * P), _rot(1.6 * P).initial_state(START), t_settle=40.0, t_window=3.0,
                                 angles=(4, 5), segments=5, parameter="speed", value=1.6 * P)


@pytest.fixture(scope="module")
def upwards(whirl):
    return continue_periodic(_rot(1.6 * P), whirl, _at, parameter="speed", label="whirl",
                             settings=ContinuationSettings(ds=0.05, ds_max=0.5, max_points=112, bounds=(0.3 * P, 4.7 * P)))


def test_whirl_from_simulation_agrees_with_a_long_simulation(whirl):
    assert whirl.winding.tolist() == [0, 0, 0, 0, -1, -1, 0, 0]
    assert whirl.stable and whirl.trivial_error < 1e-7
    assert abs(whirl.state[4] - whirl.state[5]) < 1e-8  # the balls whirl together
    # independent: the same start settled 60 s instead of 40 s, no shooting
    period, amplitude, _ = _simulated(1.6 * P, _rot(1.6 * P).initial_state(START), 60.0, whirl.period)
    assert period == pytest.approx(whirl.period, rel=1e-4)
    assert amplitude == pytest.approx(whirl.amplitude, rel=1e-4)
    assert 0.015 < whirl.amplitude < 0.025  # test_steady_seed002's range for this whirl


def test_whirl_labels_identical_for_1_to_20_segments(whirl, upwards):
    """The stable whirl at 1.6 p and the unstable one between the branch point and the fold."""
    bp, fold = (s.index for s in upwards.special_points[:2])
    i = (bp + fold) // 2
    cases = [(1.6 * P, whirl.state, whirl.period, True), (upwards.values[i], upwards.states[i], upwards.period[i], False)]
    for om, state, period, stable in cases:
        mus = []
        for m in (1, 3, 5, 10, 20):
            orbit = find_periodic_orbit(_rot(om), state, period, params=_at(om), segments=m, winding=whirl.winding)
            assert orbit.stable is stable and orbit.trivial_error < 1e-6
            mus.append(np.abs(orbit.multipliers[:3]))
        assert np.ptp(mus, axis=0).max() < 1e-5


def test_whirl_up_in_speed_stable_until_a_branch_point_then_folds(upwards):
    (bp, fold) = upwards.special_points[:2]
    assert (bp.type, fold.type) == ("branch", "fold-of-cycles")
    assert 4.58 * P < bp.value < fold.value < 4.59 * P
    assert upwards.stable[: bp.index].all() and not upwards.stable[bp.index : fold.index].any()
    assert upwards.values[: fold.index].min() == pytest.approx(1.6 * P)
    assert upwards.extra["trivial_multiplier_error"][: fold.index].max() < 1e-6
    # below the branch point the orbit is an attractor: a perturbed start returns to it
    i = int(np.argmin(np.abs(upwards.values - 4.55 * P)))
    y0 = upwards.states[i] + np.r_[0, 0, 0, 0, 1e-5, -1e-5, 0, 0]
    period, amplitude, _ = _simulated(upwards.values[i], y0, 20.0, upwards.period[i])
    assert period == pytest.approx(upwards.period[i], rel=1e-4)
    assert amplitude == pytest.approx(upwards.amplitude[i], rel=1e-4)
    # above the fold there is no whirl: the last orbit's state settles on the balanced motion
    _, amplitude, y_end = _simulated(4.62 * P, upwards.states[fold.index], 30.0, 0.02)
    assert amplitude < 1e-9 and np.max(np.abs(y_end[6:])) < 1e-6
    # balls at +-(pi - gamma), gamma = arccos(eta / 2) (seed 002), 2 gamma apart modulo a turn
    eta = MODEL.rotor.disc_mass * MODEL.rotor.eccentricity / (MODEL.balls[0].mass * MODEL.balls[0].radius)
    separation = math.remainder(y_end[4] - y_end[5], 2 * math.pi)
    assert abs(abs(separation) - 2 * math.acos(eta / 2)) < 1e-6


def test_whirl_down_in_speed_ends_at_the_saddle_node_of_the_side_motions(whirl):
    lo, hi = 0.96, 0.985  # side motion 00 exists below the saddle-node, not above (up to 1.03 p)
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if analyze_steady(MODEL, mid * P).motion("side 00").exists else (lo, mid)
    branch = continue_periodic(_rot(1.6 * P), whirl, "speed.speed", label="whirl",  # the model's named parameter
                               settings=ContinuationSettings(ds=0.05, ds_max=0.5, max_points=70, direction=-1,
                                                             bounds=(0.3 * P, 4.7 * P)))
    assert branch.parameter == "speed.speed" and branch.stable.all() and branch.special_points == ()
    assert np.all(np.diff(branch.values) < 0) and np.all(branch.values > hi * P)
    tail = branch.period[-10:]
    assert np.all(np.diff(tail) > 0) and tail[-1] > 2.0  # from 0.1 s at 1.6 p, without bound
    assert branch.values[-1] < 0.98 * P
    # near a saddle-node on the orbit the period grows as (speed - speed_sn)^(-1/2): T^-2 is
    # linear in the speed and vanishes at the saddle-node
    slope, icpt = np.polyfit(branch.values[-6:], branch.period[-6:] ** -2.0, 1)
    assert -icpt / slope / P == pytest.approx(hi, abs=2e-3)
