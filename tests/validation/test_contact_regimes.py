"""Rub regimes on the sweep engine: each regime where the closed forms put it, with its features
equal to the closed-form values (Black 1968 / Choy & Padovan 1987 full rub; Crandall 1990 rolling
backward whirl)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.contact import JeffcottRub, RubRotor, critical_friction, full_rub, no_rub_radius, rolling_whirl
from rotorlab.contact._regimes import RubRegime, RubRegimes, classify_rub
from rotorlab.sweep import Points, Sweep, run_sweep

RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0)
MU_C = critical_friction(RUB, 1.5)


def test_regime_map_over_speed_and_friction():
    model = JeffcottRub(replace(RUB, friction=0.5 * MU_C), 1.5)
    speeds = [0.5, 1.5, 1.5, 3.0]
    frictions = [0.5 * MU_C, 0.5 * MU_C, 1.4 * MU_C, 0.5 * MU_C]
    ds = run_sweep(Sweep(RubRegimes(model, t_end=400.0, window=50.0),
                         points=Points({"spin_speed": speeds, "friction": frictions}, dim="point")))  # fmt: skip
    assert ds.status.values.tolist() == [0, 0, 0, 0]
    assert ds.regime.values.tolist() == [RubRegime.NO_CONTACT, RubRegime.FULL_RUB, RubRegime.IMPACTS, RubRegime.FULL_RUB]
    # 0.5 rad/s: the no-rub orbit (radius 0.2) whirls synchronously
    assert no_rub_radius(RUB, 0.5) < RUB.clearance and ds.whirl_ratio.values[0] == pytest.approx(1.0, abs=1e-6)
    # full rub: synchronous, in contact throughout, pressing with the closed-form normal force
    for i in (1, 3):
        q = replace(RUB, friction=frictions[i])
        branch = full_rub(q, speeds[i])[0]
        assert ds.contact_fraction.values[i] == 1.0 and ds.impact_rate.values[i] == 0.0
        assert ds.whirl_ratio.values[i] == pytest.approx(1.0, abs=1e-5)
        assert ds.peak_force.values[i] == pytest.approx(branch.normal_force, rel=2e-3)
    # at 3 rad/s the no-rub orbit coexists (radius 0.67 < clearance), yet from rest the run-through
    # lands on the upper rub branch (radius 7.0)
    assert no_rub_radius(RUB, 3.0) < RUB.clearance
    # above the critical friction the full rub breaks up into intermittent contact
    assert 0.0 < ds.contact_fraction.values[2] < 1.0 and ds.impact_rate.values[2] > 0.0
    assert ds.regime.attrs["flag_meanings"].startswith("-1: integration failed; 0: no contact")


def test_backward_whirl_rolling_is_classified_with_the_theory_whirl_ratio():
    roll = RubRotor(mass=1.0, stiffness=1.0, clearance=0.01, damping=0.05, stator_stiffness=100.0,
                    friction=0.3, rotor_radius=0.1)  # fmt: skip
    model = JeffcottRub(roll, 0.3)
    z0 = 1.01 * roll.clearance
    # the kick's radial oscillation on the stator (10 rad/s) decays at c / 2m = 0.025 1/s: 250 s
    f = classify_rub(model, model.initial_state((z0, 0.0), (0.0, -2.5 * z0)), 250.0, 20.0)
    assert f.regime == RubRegime.BACKWARD_ROLLING
    assert f.contact_fraction == 1.0 and f.rolling_fraction == 1.0
    assert f.whirl_ratio == pytest.approx(rolling_whirl(roll, 0.3).whirl_speed / 0.3, rel=1e-4)
    assert f.peak_force == pytest.approx(rolling_whirl(roll, 0.3).normal_force, rel=1e-2)


def test_bad_analysis_values_name_the_field():
    model = JeffcottRub(RUB, 1.5)
    with pytest.raises(ValueError, match=r"RubRegimes.window must be a finite number > 0 and < 10 \(s\), got 20.0"):
        RubRegimes(model, t_end=10.0, window=20.0)
    with pytest.raises(ValueError, match="unknown coordinate 'speed'"):
        Sweep(RubRegimes(model, t_end=10.0, window=5.0), points=Points({"speed": [1.0]}))
    assert np.isfinite(MU_C)
