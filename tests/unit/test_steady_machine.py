"""The steady motions of ``jeffcott_balls`` are solved and judged by the machine's co-rotating frame
(issue 24, item 3): one implementation for every isotropic machine, the seeds' closed forms and
verdicts a layer on it.

Oracles: the analytic linearization of :meth:`rotorlab.models.JeffcottBalls.linearize`
(Filimonikhin & Filimonikhina eqs. (9)-(11), kept as a test oracle) and the closed-form side
motions of seed 003 eq. (13).
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.analyses._machine_steady import machine_motions
from rotorlab.continuation import as_machine
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams, Unbalance
from rotorlab.steady import analyze_steady, find_steady_motions

BALL = BallParams(0.03, 0.06, damping=2e-3)
ROTOR = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(1.0))


def test_exact_eigenvalues_are_the_machines_and_match_the_analytic_linearization(monkeypatch):
    om = 1.3 * MODEL.critical_speed
    oracle = {m.label: np.sort_complex(MODEL.linearize(m.states()[0], spin_speed=om).eigenvalues)
              for m in find_steady_motions(MODEL, om) if m.exists}
    # the steady analysis never calls the rotor's own linearization: the machine judges
    monkeypatch.setattr(JeffcottBalls, "linearize", lambda *a, **k: pytest.fail("JeffcottBalls.linearize called"))
    res = analyze_steady(MODEL, om)
    machine = as_machine(MODEL).with_drive(ConstantSpeed(om))
    assert len(oracle) == 6
    for m in res.motions:
        y = machine.rotating_state([m.deflection.real, m.deflection.imag, 0.0, 0.0], m.ball_angles)
        assert np.max(np.abs(machine.rotating_rhs(y))) < 1e-12  # an equilibrium of the machine
        got = np.sort_complex(m.stability.eigenvalues)
        np.testing.assert_array_equal(got, np.sort_complex(machine.linearize(y).eigenvalues))
        scale = np.max(np.abs(oracle[m.label]))
        assert np.max(np.abs(got - oracle[m.label])) < 1e-8 * scale
        assert m.stability.growth_rate == pytest.approx(float(np.max(oracle[m.label].real)), abs=1e-8 * scale)


def test_no_side_motion_at_undamped_resonance():
    """Omega^2 = c / M to round-off, d = 0: |c - M Omega^2| ~ 1e-14 c, and eq. (13)'s deflection
    ``Omega^2 (Me + s) / (c - M Omega^2)`` is no steady motion (the old code listed one of ~1e13 m
    that the co-rotating frame does not balance)."""
    model = JeffcottBalls(RotorParams(1.0, 0.00390625, 100.0, 0.0), (BallParams(0.0625, 0.125, damping=0.00390625),),
                          speed=ConstantSpeed(1.0))
    om = model.critical_speed
    motions = find_steady_motions(model, om)
    assert [m.label for m in motions] == ["side 0", "side 1"]
    assert not any(m.exists for m in motions)
    assert all(m.stability.exact == "absent" for m in analyze_steady(model, om).motions)


def test_ball_friction_gives_the_smooth_parts_motions_and_says_so():
    rough = JeffcottBalls(ROTOR, (BallParams(0.03, 0.06, damping=2e-3, friction=0.05),) * 2,
                          speed=ConstantSpeed(1.0))
    om = 1.6 * MODEL.critical_speed
    smooth, got = analyze_steady(MODEL, om), analyze_steady(rough, om)
    assert smooth.friction == "" and "friction" not in smooth.to_dataset().attrs
    assert "smooth part" in got.friction and got.to_dataset().attrs["friction"] == got.friction
    assert got.to_dict()["friction"] == got.friction
    for a, b in zip(smooth.motions, got.motions):
        assert (a.label, a.exists, a.stability.exact) == (b.label, b.exists, b.stability.exact)
        np.testing.assert_array_equal(a.ball_angles, b.ball_angles)
        np.testing.assert_array_equal(a.stability.eigenvalues, b.stability.eigenvalues)


def test_a_machine_in_the_planar_limit_is_judged_by_its_own_eigenvalues():
    """A machine that is the planar rotor but with its unbalance at 40 deg and undamped tilt modes
    of its own: the seeds' motions turned by 40 deg, the machine's eigenvalues (its tilt modes
    included: a real part 0 where the planar rotor's largest is negative)."""
    from dataclasses import replace

    base = as_machine(MODEL).with_drive(ConstantSpeed(1.6 * MODEL.critical_speed))
    beta = np.radians(40.0)
    tilted = replace(base, n_modes=None, unbalances=(Unbalance(0, base.unbalances[0].magnitude, beta),))
    ds = machine_motions(tilted)
    ref = analyze_steady(MODEL, 1.6 * MODEL.critical_speed)
    assert list(ds.label.values) == list(ref.labels)
    assert list(ds.verdict_hamilton.values) == [m.stability.hamilton for m in ref.motions]
    for j, m in enumerate(ref.motions):
        if not m.exists:
            assert not ds.exists.values[j]
            continue
        turned = np.angle(np.exp(1j * (ds.ball_angle.values[j] - m.ball_angles - beta)))
        np.testing.assert_allclose(turned, 0.0, atol=1e-12)
        assert ds.amplitude.values[j, 0] == pytest.approx(m.amplitude, rel=1e-12, abs=1e-18)
        # the tilt modes (stiffness 4c, no damping) are undamped: the largest real part is 0
        lam = ds.max_real_eigenvalue.values[j]
        assert lam == pytest.approx(max(m.stability.growth_rate, 0.0), abs=1e-8 * MODEL.critical_speed)
