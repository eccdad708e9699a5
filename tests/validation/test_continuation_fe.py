"""Continuation on a finite-element machine (issue 25): the balanced branch of ``pico21-balancer``
(FE rotor in the armature/stator, two races of two balls, the case test_machine_cases.py builds)
in ``drive.speed``.

Reference: today's stability chart (``machine_steady``: the balanced state solved afresh at one
speed and the largest real part of the exact eigenvalues of its co-rotating linearization), an
independent computation at every speed it is asked for. Its zero crossings, found by brentq, are
the Hopf points; the continued branch's stability and ball angles equal the chart's at the
branch's own speeds.
"""

import math

import numpy as np
from scipy.optimize import brentq

from rotorlab.analyses import build_model
from rotorlab.analyses._machine_steady import machine_steady
from rotorlab.continuation import continue_equilibria, with_value
from rotorlab.io import load_case


def test_pico21_balanced_branch_hopf_points_are_the_chart_crossings():
    m = build_model(load_case("pico21-balancer").model)
    r = continue_equilibria(m, "drive.speed", 150.0, 900.0, start_from="balanced")
    b = r.branches[0]
    assert b.end == "bound" and b.values[0] == 150.0 and b.values[-1] == 900.0
    assert [s.type for s in b.special_points] == ["hopf", "hopf"]
    low, high = b.special_points

    def growth(w):
        return float(machine_steady(m, [w]).max_real_eigenvalue[0])

    for s, (a, c) in zip((low, high), ((200.0, 300.0), (600.0, 700.0)), strict=True):
        w0 = brentq(growth, a, c, xtol=1e-12, rtol=1e-14)
        assert abs(s.value - w0) < 1e-8 * w0
        # the sign of the largest real part either side: unstable / stable / unstable
        assert growth(0.99 * w0) * growth(1.01 * w0) < 0
        ev = with_value(m, "drive.speed", s.value).linearize(s.state).eigenvalues
        top = ev[np.argmax(ev.real)]
        assert abs(top.real) < 1e-7 * abs(top) and abs(abs(top.imag) - s.frequency) < 1e-6 * s.frequency
    assert growth(0.99 * low.value) > 0 > growth(1.01 * low.value) and growth(1.01 * high.value) > 0
    assert low.description.startswith(f"balancing becomes stable above {low.value * 30 / math.pi:.4g} rpm")
    assert high.description.startswith(f"balancing is stable only below {high.value * 30 / math.pi:.4g} rpm")
    # stability and ball angles at the branch's own speeds against the chart solved afresh
    chart = machine_steady(m, b.values)
    assert chart.balanced.values.all() and np.array_equal(chart.stable.values, b.stable)
    for race in (0, 1):  # the same motion up to exchanging the two balls of a race
        cols = chart.race.values == race
        ours = np.sort(np.angle(np.exp(1j * b.extra["ball_angle"][:, cols])), axis=1)
        theirs = np.sort(np.angle(np.exp(1j * chart.ball_angle.values[:, cols])), axis=1)
        np.testing.assert_allclose(ours, theirs, atol=1e-8)
    assert b.stable.any() and np.all(b.amplitude < 1e-9)
