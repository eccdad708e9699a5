"""Influence coefficients from geometry, and compliance <-> stiffness."""

import math

import numpy as np
import pytest

from rotorlab.linear import (
    HousingSupport,
    InfluenceModel,
    ShaftSpan,
    ShaftSupport,
    compliance_to_stiffness,
    influence_compliance,
    stiffness_to_compliance,
)


def test_cantilever_and_simply_supported_beam_tables():
    ei, L = 2.0, 1.5
    cant = influence_compliance(InfluenceModel((L,), (True,), (ShaftSpan(0.0, L, ei),),
                                               (ShaftSupport.clamp(0.0),)))
    np.testing.assert_allclose(cant, [[L**3 / (3 * ei), L**2 / (2 * ei)],
                                      [L**2 / (2 * ei), L / ei]], rtol=1e-12)
    pinned = influence_compliance(InfluenceModel(
        (L / 2, L / 4), (True, True), (ShaftSpan(0.0, L, ei),),
        (ShaftSupport(0.0, math.inf), ShaftSupport(L, math.inf))))
    assert pinned[0, 0] == pytest.approx(L**3 / (48 * ei), rel=1e-12)
    assert pinned[0, 1] == pytest.approx(0.0, abs=1e-12)  # symmetry: no tilt at midspan
    # Maxwell-Betti: deflection at L/4 from a load at L/2 equals the reverse
    a, b, x = L / 2, L / 2, L / 4
    assert pinned[2, 0] == pytest.approx(b * x * (L**2 - b**2 - x**2) / (6 * ei * L), rel=1e-12)


def test_elastic_bearings_add_their_compliance_and_spans_with_steps():
    ei, L, k = 3.0, 2.0, 50.0
    rigid = influence_compliance(InfluenceModel(
        (1.0,), (True,), (ShaftSpan(0.0, L, ei),),
        (ShaftSupport(0.0, math.inf), ShaftSupport(L, math.inf))))
    soft = influence_compliance(InfluenceModel(
        (1.0,), (True,), (ShaftSpan(0.0, L, ei),), (ShaftSupport(0.0, k), ShaftSupport(L, k))))
    # midspan: each bearing carries P/2, moves P/(2k), the centre moves P/(2k) more
    assert soft[0, 0] - rigid[0, 0] == pytest.approx(1.0 / (2 * k), rel=1e-12)
    stepped = influence_compliance(InfluenceModel(
        (L,), (True,), (ShaftSpan(0.0, 1.0, ei), ShaftSpan(1.0, L, 2 * ei)),
        (ShaftSupport.clamp(0.0),)))
    # tip of a stepped cantilever by the unit-load method
    expected = (1 / ei) * ((L - 0) ** 3 - (L - 1.0) ** 3) / 3 + (1 / (2 * ei)) * (L - 1.0) ** 3 / 3
    assert stepped[0, 0] == pytest.approx(expected, rel=1e-12)


def test_housing_support_is_a_rigid_motion_added_to_every_station():
    cq, cm = 1e4, 1e3
    hs = HousingSupport(0.0, cq, cm)
    model = InfluenceModel((0.1, 0.3), (False, True), (ShaftSpan(0.0, 0.3, 500.0),),
                           (ShaftSupport.clamp(0.0),), hs)
    d = influence_compliance(model)
    z = np.array([0.1, 0.3])
    np.testing.assert_allclose(d[0, 0], 1 / cq + z[0] ** 2 / cm)
    np.testing.assert_allclose(d[0, 2], 1 / cq + z[0] * z[1] / cm)
    np.testing.assert_allclose(d[1, 3], 1 / cm)
    shaft_only = influence_compliance(InfluenceModel((0.3,), (True,),
                                                     (ShaftSpan(0.0, 0.3, 500.0),),
                                                     (ShaftSupport.clamp(0.0),)))
    np.testing.assert_allclose(d[2:, 2:] - (d[2:, 2:] - shaft_only), shaft_only)
    np.testing.assert_allclose(d, d.T)
    rigid = influence_compliance(InfluenceModel((0.1,), (False,), (ShaftSpan(0.0, 0.3, 5.0),),
                                                (ShaftSupport.clamp(0.0),),
                                                HousingSupport(0.0, math.inf, math.inf)))
    np.testing.assert_array_equal(rigid, 0.0)


def test_influence_model_validation():
    span = (ShaftSpan(0.0, 1.0, 1.0),)
    with pytest.raises(ValueError, match="do not hold the shaft"):
        influence_compliance(InfluenceModel((0.5,), (True,), span, (ShaftSupport(0.0, 1e3),)))
    with pytest.raises(ValueError, match="outside the shaft"):
        InfluenceModel((2.0,), (True,), span, (ShaftSupport.clamp(0.0),))
    with pytest.raises(ValueError, match="contiguous"):
        InfluenceModel((0.5,), (True,), (ShaftSpan(0.0, 0.4, 1.0), ShaftSpan(0.5, 1.0, 1.0)),
                       (ShaftSupport.clamp(0.0),))
    with pytest.raises(ValueError, match="ShaftSpan.end"):
        ShaftSpan(1.0, 0.5, 1.0)
    with pytest.raises(ValueError, match="ShaftSupport.stiffness"):
        ShaftSupport(0.0, -1.0)
    with pytest.raises(ValueError, match="HousingSupport.translational_stiffness"):
        HousingSupport(0.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="one entry per station"):
        InfluenceModel((0.5,), (True, False), span, (ShaftSupport.clamp(0.0),))


def test_compliance_stiffness_round_trip_and_errors():
    rng = np.random.default_rng(3)
    a = rng.standard_normal((6, 6))
    k = a @ a.T + 6 * np.eye(6)
    d = stiffness_to_compliance(k)
    np.testing.assert_allclose(compliance_to_stiffness(d), k, rtol=1e-10)
    np.testing.assert_array_equal(d, d.T)
    with pytest.raises(ValueError, match="symmetric"):
        compliance_to_stiffness([[1.0, 0.5], [0.0, 1.0]])
    with pytest.raises(ValueError, match="positive definite"):
        compliance_to_stiffness([[1.0, 2.0], [2.0, 1.0]])
    with pytest.raises(ValueError, match="square"):
        compliance_to_stiffness(np.ones((2, 3)))
