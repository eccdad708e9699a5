"""Loading cases: the built-in autobalancer case, the Case object and its helpers."""

from __future__ import annotations

import math

import pytest

from rotorlab.io import (
    ANALYSIS_SPECS,
    MODEL_SPECS,
    Case,
    CaseError,
    ConstantSpeed,
    HillSpeed,
    JeffcottBallsSpec,
    RampSpeed,
    SimulateSpec,
    builtin_cases,
    dump_case,
    load_case,
    parse_case,
    validate_case,
)

MINIMAL = """
[model]
type = "jeffcott_balls"
disc_mass = 2.0
eccentricity = 1e-3
stiffness = 8000.0
[model.speed]
profile = "constant"
speed = "600 rpm"
"""


def test_builtin_cases_lists_the_autobalancer():
    cases = builtin_cases()
    assert "autobalancer" in cases
    assert "two-ball automatic balancer" in cases["autobalancer"]


def test_builtin_case_names_match_their_files():
    for name in builtin_cases():
        assert load_case(name).name == name


def test_autobalancer_numbers_follow_seed_002():
    case = load_case("autobalancer")
    model = case.model
    assert isinstance(model, JeffcottBallsSpec)
    assert model.type == "jeffcott_balls"
    assert model.frame == "fixed"
    assert model.disc_mass == 1.0
    assert model.n_balls == 2
    for ball in model.balls:
        assert ball.mass == pytest.approx(0.03)
        assert ball.radius == pytest.approx(0.05)
        assert ball.inertia == pytest.approx(0.03 * 0.05**2)  # point mass
        assert ball.damping == pytest.approx(2e-3)
        assert ball.friction == 0.0
    assert model.total_mass == pytest.approx(1.06)
    # critical speed p = 2*pi*20 rad/s, p^2 = c / (M1 + 2 m)
    p = model.critical_speed()
    assert p == pytest.approx(2 * math.pi * 20, rel=1e-3)
    assert model.stiffness == pytest.approx((2 * math.pi * 20) ** 2 * 1.06, rel=1e-3)
    # eta = M1 e / (m R) = 1
    eta = model.disc_mass * model.eccentricity / (0.03 * 0.05)
    assert eta == pytest.approx(1.0)
    # shaft damping ratio d / (2 M p) = 0.05
    assert model.damping / (2 * model.total_mass * p) == pytest.approx(0.05, rel=1e-3)


def test_autobalancer_analyses():
    case = load_case("autobalancer")
    assert [a.name for a in case.analyses] == ["subcritical", "supercritical", "basin"]
    sub, sup = case.analyses[:2]
    p = case.model.critical_speed()
    assert sub.spin_speed(case.model) == pytest.approx(0.6 * p)
    assert sup.spin_speed(case.model) == pytest.approx(2.0 * p)
    expected_deg = [[0, 90], [45, 200], [120, 240], [170, 190], [300, 30], [10, 350]]
    for analysis in (sub, sup):
        assert isinstance(analysis, SimulateSpec)
        angles = analysis.ball_angle_sets(case.model.n_balls)
        assert [[round(math.degrees(a), 9) for a in row] for row in angles] == expected_deg
        assert analysis.t_end == 20.0
        assert analysis.duration(case.model) == 20.0
        assert analysis.n_save == 2000
        assert analysis.rtol == 1e-8
        assert analysis.atol == 1e-10


def test_autobalancer_source_and_text():
    case = load_case("autobalancer")
    assert case.source == "builtin:autobalancer"
    assert 'name = "autobalancer"' in case.text
    assert case.analysis("supercritical").speed_ratio == 2.0
    with pytest.raises(KeyError, match="subcritical, supercritical"):
        case.analysis("nope")


def test_load_from_path(tmp_path):
    path = tmp_path / "my-rotor.toml"
    path.write_text(MINIMAL, encoding="utf-8")
    case = load_case(path)
    assert case.name == "my-rotor"  # default name: file stem
    assert case.source == str(path.resolve())
    assert case.text == MINIMAL
    assert case.model.speed.speed == pytest.approx(20 * math.pi)
    assert load_case(str(path)).model_dump_si() == case.model_dump_si()


def test_existing_file_takes_precedence_over_builtin(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "autobalancer").write_text(MINIMAL, encoding="utf-8")
    assert load_case("autobalancer").model.disc_mass == 2.0


def test_unknown_builtin_lists_the_builtins():
    with pytest.raises(CaseError) as info:
        load_case("autobalancr")
    message = str(info.value)
    assert "unknown case 'autobalancr'" in message
    assert "autobalancer" in message
    assert "did you mean 'autobalancer'?" in message


def test_missing_file(tmp_path):
    with pytest.raises(CaseError, match="case file not found: .*nothere.toml"):
        load_case(tmp_path / "nothere.toml")


def test_directory_is_not_a_case(tmp_path):
    with pytest.raises(CaseError, match="is not a file"):
        load_case(tmp_path)


def test_file_that_is_not_utf8(tmp_path):
    path = tmp_path / "latin.toml"
    path.write_bytes(b'name = "caf\xe9"\n')
    with pytest.raises(CaseError, match="not UTF-8"):
        load_case(path)


def test_parse_case_defaults():
    case = parse_case(MINIMAL)
    assert case.name == "case"
    assert case.description == ""
    assert case.schema_version == 1
    assert case.source == "<string>"
    assert case.analyses == ()
    assert case.model.damping == 0.0
    assert case.model.balls == ()
    assert case.model.critical_speed() == pytest.approx(math.sqrt(8000.0 / 2.0))


def test_case_is_frozen():
    case = parse_case(MINIMAL)
    with pytest.raises(Exception, match="frozen"):
        case.name = "other"
    with pytest.raises(Exception, match="frozen"):
        case.model.disc_mass = 3.0


def test_ball_count_expands_and_inertia_defaults():
    text = MINIMAL + """
[[model.balls]]
mass = "20 g"
radius = "40 mm"
count = 3
[[model.balls]]
mass = "10 g"
radius = "40 mm"
inertia = "20 kg*mm^2"
damping = "1e-4 N*m*s/rad"
friction = 0.02
"""
    model = parse_case(text).model
    assert model.n_balls == 4
    assert [b.mass for b in model.balls] == pytest.approx([0.02, 0.02, 0.02, 0.01])
    assert model.balls[0].inertia == pytest.approx(0.02 * 0.04**2)
    assert model.balls[3].inertia == pytest.approx(20e-6)
    assert model.balls[3].damping == pytest.approx(1e-4)
    assert model.balls[3].friction == 0.02
    assert model.total_mass == pytest.approx(2.07)
    assert "count" not in parse_case(text).model_dump_si()["model"]["balls"][0]


def test_default_analysis_names_and_grid():
    text = MINIMAL + """
[[model.balls]]
mass = 0.01
radius = 0.05
count = 2
[[analysis]]
type = "simulate"
ball_angle_grid = 3
revolutions = 10
[[analysis]]
type = "simulate"
name = "fast"
speed = "20 Hz"
initial_ball_angles = [[0, "180 deg"]]
t_end = 1
"""
    case = parse_case(text)
    first, second = case.analyses
    assert first.name == "simulate-0"
    assert second.name == "fast"
    # neither speed nor speed_ratio: the model's constant profile, 600 rpm
    assert first.spin_speed(case.model) == pytest.approx(20 * math.pi)
    assert first.duration(case.model) == pytest.approx(1.0)  # 10 revolutions at 10 Hz
    sets = first.ball_angle_sets(2)
    assert len(sets) == 9
    assert sets[1] == pytest.approx((0.0, 2 * math.pi / 3))
    assert second.spin_speed(case.model) == pytest.approx(40 * math.pi)
    (row,) = second.ball_angle_sets(2)
    assert row == pytest.approx((0.0, math.pi))


def test_speed_profiles():
    ramp = RampSpeed(start="0 rpm", stop="1200 rpm", duration="10 s")
    assert ramp.speed_at(5.0) == pytest.approx(20 * math.pi)
    assert ramp.speed_at(50.0) == pytest.approx(40 * math.pi)
    assert not ramp.is_constant
    hill = HillSpeed(max_speed="20 Hz", t_half="2 s", exponent=3)
    assert hill.speed_at(2.0) == pytest.approx(20 * math.pi)
    assert hill.speed_at(0.0) == 0.0
    assert hill.final_speed == pytest.approx(40 * math.pi)
    const = ConstantSpeed(speed=10.0)
    assert const.is_constant and const.speed_at(3.0) == 10.0


def test_validate_case_from_a_dict():
    data = {
        "name": "d",
        "model": {
            "type": "jeffcott_balls",
            "disc_mass": "1 kg",
            "eccentricity": 0.0,
            "stiffness": "1 kN/m",
        },
        "analysis": [{"type": "simulate", "speed": 10.0, "ball_angle_grid": 1, "t_end": 2.0}],
    }
    case = validate_case(data)
    assert case.source == "<dict>"
    assert case.model.stiffness == 1000.0
    assert case.analyses[0].ball_angle_sets(0) == ((),)


def test_python_construction_uses_attribute_names():
    case = Case(
        name="py",
        model=JeffcottBallsSpec(disc_mass=1.0, eccentricity=0.0, stiffness=100.0),
        analyses=[SimulateSpec(speed=1.0, ball_angle_grid=1, t_end=1.0)],
    )
    assert case.analyses[0].name == "simulate-0"
    assert case.source == "<python>"


def test_registries():
    assert {"jeffcott_balls", "multibody", "fe_rotor"} <= set(MODEL_SPECS)
    assert {"simulate", "campbell", "modes", "critical_speeds", "unbalance_response", "identify",
            "data_audit"} <= set(ANALYSIS_SPECS)
    for kind, cls in (*MODEL_SPECS.items(), *ANALYSIS_SPECS.items()):
        assert cls.model_fields["type"].default == kind
    with pytest.raises(TypeError):
        MODEL_SPECS["x"] = JeffcottBallsSpec  # type: ignore[index]


def test_model_dump_si_is_plain_data():
    data = load_case("autobalancer").model_dump_si()

    def check(obj):
        if isinstance(obj, dict):
            assert all(isinstance(k, str) for k in obj)
            for v in obj.values():
                check(v)
        elif isinstance(obj, list):
            for v in obj:
                check(v)
        else:
            assert obj is None or isinstance(obj, (str, int, float, bool))

    check(data)
    assert set(data) == {"schema_version", "name", "description", "model", "analyses"}
    assert data["model"]["speed"] == {"profile": "constant", "speed": pytest.approx(80 * math.pi)}
    assert data["analyses"][1]["initial_ball_angles"][0] == pytest.approx([0.0, math.pi / 2])


def test_dump_case_round_trip_of_the_builtin():
    case = load_case("autobalancer")
    text = dump_case(case)
    assert "all values in SI units" in text
    again = parse_case(text, "dumped.toml")
    assert again.model_dump_si() == case.model_dump_si()


def test_json_schema_is_available():
    schema = Case.model_json_schema()
    assert "model" in schema["properties"]
