"""Parameters of the impact_rotor model and the case-file specs: validation and packing."""

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab._kernels import impact_rotor as K
from rotorlab.analyses import classify_impacts, impact_model, stacked_params
from rotorlab.io import CaseError, load_case, parse_case
from rotorlab.models import (
    CentrifugeRotor,
    Housing,
    ImpactRotor,
    StoneFeed,
    StoneSequence,
    krasnov_crusher,
    stone_push,
)

ROTOR = (635.7, 70.35, 115.68, 160.0, 3.22e6, 3.22e6, -0.05, 0.2)


@pytest.mark.parametrize("index, name, value, words", [
    (0, "mass", 0.0, "CentrifugeRotor.mass must be a finite number > 0 (kg)"),
    (1, "inertia_transverse", math.nan, "CentrifugeRotor.inertia_transverse must be a finite number > 0"),
    (3, "spin_speed", -5.0, "CentrifugeRotor.spin_speed must be a finite number > 0 (rad/s)"),
    (4, "stiffness_1", "x", "CentrifugeRotor.stiffness_1 must be a finite number > 0 (N/m)"),
    (7, "height_2", -0.05, "CentrifugeRotor.height_2 must differ from height_1"),
])
def test_rotor_validation_names_the_parameter(index, name, value, words):
    args = list(ROTOR)
    args[index] = value
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        CentrifugeRotor(*args)
    with pytest.raises(ValueError, match="internal_friction must be a finite number >= 0"):
        CentrifugeRotor(*ROTOR, internal_friction=-0.1)


def test_housing_validation():
    ok = dict(radius=0.625, height=-0.2, gap=4.5e-3, cone_angle=math.radians(55))
    for key, bad, words in (("gap", 0.0, "Housing.gap must be a finite number > 0 (m)"),
                            ("cone_angle", 2.0, "Housing.cone_angle must be a finite number > 0 and <= 1.5708"),
                            ("restitution", 1.2, "Housing.restitution must be a finite number >= 0 and <= 1"),
                            ("friction", -0.1, "Housing.friction must be a finite number >= 0"),
                            ("count_speed", -1e-3, "Housing.count_speed must be a finite number >= 0 (m/s)")):  # fmt: skip
        with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
            Housing(**{**ok, key: bad})
    # issue 30: every located impact counts by default; a positive count threshold must lie above rest_speed
    assert Housing(**ok).count_speed == 0.0 and Housing(**ok, rest_speed=0.01).rest_speed == 0.01
    with pytest.raises(ValueError, match=r"Housing.rest_speed must be < count_speed \(0.001 m/s\), got 0.01"):
        Housing(**ok, rest_speed=0.01, count_speed=1e-3)
    assert Housing(**ok).lever() == pytest.approx(0.625 * math.cos(math.radians(55)) - 0.2 * math.sin(math.radians(55)))


def test_stone_feed_validation_and_sequences():
    base = dict(mass=0.7, interval=0.035, radius=0.6, height=0.28, spiral_angle=math.radians(30), guide_friction=0.5)
    for key, bad, words in (("mass", -1.0, "StoneFeed.mass must be a finite number > 0 (kg)"),
                            ("start_radius", 0.6, "StoneFeed.start_radius must be a finite number > 0 and < 0.6"),
                            ("n_guides", 0, "StoneFeed.n_guides must be an integer >= 1"),
                            ("guides", "spiral", "StoneFeed.guides must be 'random' or 'cyclic'"),
                            ("guide_friction", 2.0, "StoneFeed.guide_friction must be < cot"),
                            ("time_jitter", 0.5, "StoneFeed.time_jitter must be a finite number >= 0 and < 0.5")):  # fmt: skip
        with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
            StoneFeed(**{**base, key: bad})
    feed = StoneFeed(**base)
    a, b = feed.sequence(2.0, seed=7), feed.sequence(2.0, seed=7)
    assert np.array_equal(a.guides, b.guides) and a.seed == 7
    assert not np.array_equal(a.guides, feed.sequence(2.0, seed=8).guides)
    assert np.allclose(np.diff(a.times), 0.035) and a.times[0] == pytest.approx(0.035)
    cyc = replace(feed, guides="cyclic").sequence(0.2)
    assert cyc.guides.tolist() == [0, 1, 2, 3, 0]
    spread = replace(feed, mass_spread=0.2, time_jitter=0.3).sequence(5.0, seed=1)
    assert 0.56 <= spread.masses.min() < spread.masses.max() <= 0.84
    assert np.all(np.diff(spread.times) > 0)
    with pytest.raises(ValueError, match="strictly increasing"):
        StoneSequence(np.array([0.2, 0.1]), np.ones(2), np.zeros(2, dtype=int))


def test_packed_parameters_follow_the_documented_layout():
    model = krasnov_crusher().with_stones(0.5, seed=2)
    p = model.to_array()
    assert p[K.P_M] == 635.7 and p[K.P_A1] == 70.35 and p[K.P_W0] == 160.0
    assert p[K.P_C] == pytest.approx(6.44e6) and p[K.P_NM] == pytest.approx(0.075)
    assert p[K.P_CS] == pytest.approx(3.22e6 / 2 * 0.25**2)
    assert p[K.P_GAP] == 4.5e-3 and p[K.P_K] == 0.5 and p[K.P_F] == 0.2
    assert 1.0 / p[K.P_IMS] == pytest.approx(model.equivalent_mass)
    n = int(p[K.P_NST])
    assert n == len(model.sequence) == 14
    st = p[int(p[K.P_OST]):int(p[K.P_OST]) + 4 * n].reshape(n, 4)
    assert np.allclose(st[:, 0], model.sequence.times)
    assert np.allclose(st[:, 1], 0.7 * 160.0**2 * 0.6)
    bp = p[int(p[K.P_OBP]):int(p[K.P_OBP]) + int(p[K.P_NBP])]
    assert np.all(np.diff(bp) > 0) and bp.size == 28
    # padded stacks keep each row's own offsets
    P = stacked_params([model, krasnov_crusher().with_stones(0.2, seed=0)])
    assert P.shape == (2, p.size) and np.array_equal(P[0], p)


def test_model_checks_its_parts_and_initial_state():
    m = krasnov_crusher()
    with pytest.raises(ValueError, match="ImpactRotor.housing must be a Housing"):
        ImpactRotor(m.rotor, "housing", m.stones)
    with pytest.raises(ValueError, match="initial state must be clear of the housing"):
        m.initial_state(u=(0.01, 0.0))
    assert krasnov_crusher(translational=True).initial_state(tilt=(0.1, 0.1))[K.T1] == 0.0
    with pytest.raises(ValueError, match="stone_push.guide_friction must be < cot"):
        stone_push(0.25, math.radians(30), 1.8)


def test_regime_codes():
    args = ([0, 3, 40, 40, 7, 0], [0, 0.01, 0.5, 0.1, 0.3, 0], 10.0, [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 1, -3])
    # sliding for 0.1 %, 5 %, 1 % of the 10 s run: under the former 2 % ("noticeable") only the
    # 5 % run slides; under the default 0.1 % all three do
    assert classify_impacts(*args, sliding_fraction=0.02).tolist() == [0, 1, 2, 1, 3, -1]
    assert classify_impacts(*args).tolist() == [0, 2, 2, 2, 3, -1]


def test_case_files_build_the_section5_models():
    m = impact_model(load_case("krasnov-crusher").model)
    ref = krasnov_crusher()
    assert np.allclose(m.to_array(), ref.to_array(), rtol=1e-13, atol=0)
    t = impact_model(load_case("krasnov-crusher-translational").model, stone_mass=1.3)
    ref_t = krasnov_crusher(translational=True, stone_mass=1.3, interval=0.07, internal_friction=0.5,
                            restitution=0.7, friction=0.3)  # fmt: skip
    assert np.allclose(t.to_array(), ref_t.to_array(), rtol=1e-13, atol=0)


def test_bad_case_values_name_the_key():
    text = load_case("krasnov-crusher").text
    bad = text.replace('gap = "4.5 mm"', 'gap = "-4.5 mm"').replace('guide_friction = 0.5', 'guide_friction = 3.0')
    with pytest.raises(CaseError) as err:
        parse_case(bad)
    msg = str(err.value)
    assert "model.housing.gap" in msg and "must be > 0" in msg
    assert "model.stones.guide_friction" in msg and "cot(spiral_angle)" in msg
    bad = text.replace('param = "stone_mass"', 'param = "colour"')
    with pytest.raises(CaseError, match="param"):
        parse_case(bad)
    bad = text.replace('values = ["0.5 kg"', 'values = ["0.5 m"')
    with pytest.raises(CaseError, match="values"):
        parse_case(bad)
