"""Bad case files: every problem is reported, with key path, value and what is allowed."""

from __future__ import annotations

import pytest

from rotorlab.io import ANALYSIS_SPECS, MODEL_SPECS, CaseError, load_case, parse_case

MODELS = ", ".join(sorted(MODEL_SPECS))
ANALYSES = ", ".join(sorted(ANALYSIS_SPECS))

GOOD = """\
name = "t"
description = "test case"

[model]
type = "jeffcott_balls"
frame = "fixed"
disc_mass = "1 kg"
eccentricity = "1.5 mm"
stiffness = "16.7 kN/m"
damping = "13 N*s/m"

[model.speed]
profile = "constant"
speed = "1200 rpm"

[[model.balls]]
mass = "30 g"
radius = "50 mm"
damping = 1e-4

[[model.balls]]
mass = 0.03
radius = "50 mm"

[[analysis]]
type = "simulate"
name = "sub"
speed_ratio = 0.6
initial_ball_angles = [["0 deg", "90 deg"], ["45 deg", "200 deg"]]
t_end = "20 s"
n_save = 2000
rtol = 1e-8
atol = 1e-10
"""


def errors_of(text: str, origin: str = "case.toml") -> CaseError:
    with pytest.raises(CaseError) as info:
        parse_case(text, origin)
    return info.value


def edit(old: str, new: str, text: str = GOOD, count: int = 1) -> str:
    assert old in text, old
    return text.replace(old, new, count)


def test_good_case_is_valid():
    case = parse_case(GOOD, "case.toml")
    assert case.model.stiffness == 16700.0
    assert case.model.damping == 13.0
    assert case.model.eccentricity == pytest.approx(1.5e-3)


def test_negative_ball_mass():
    err = errors_of(edit("mass = 0.03", "mass = -0.03"))
    assert err.problems == ("model.balls[1].mass = -0.03: must be > 0 (kg)",)
    message = str(err)
    assert message.splitlines()[0] == "invalid case case.toml (1 problem):"
    assert "model.balls[1].mass = -0.03: must be > 0 (kg)" in message


def test_negative_mass_with_unit_shows_si_value():
    err = errors_of(edit("mass = 0.03", 'mass = "-30 g"'))
    assert err.problems == ('model.balls[1].mass = "-30 g": must be > 0 (kg), got -0.03 kg',)


def test_unknown_unit():
    err = errors_of(edit('"16.7 kN/m"', '"12 furlongs"'))
    assert err.problems == ("model.stiffness = \"12 furlongs\": unknown unit 'furlongs'",)


def test_wrong_dimension():
    err = errors_of(edit('disc_mass = "1 kg"', 'disc_mass = "3 m"'))
    assert err.problems == (
        'model.disc_mass = "3 m": wrong dimension: expected a mass (kg), got length',
    )


def test_nan():
    err = errors_of(edit('eccentricity = "1.5 mm"', "eccentricity = nan"))
    assert err.problems == ("model.eccentricity = nan: must be a finite number",)


def test_infinite_stiffness():
    err = errors_of(edit('stiffness = "16.7 kN/m"', "stiffness = inf"))
    assert err.problems == ("model.stiffness = inf: must be a finite number",)


def test_unknown_key_with_suggestion():
    err = errors_of(edit("rtol = 1e-8", "rtoll = 1e-8"))
    (problem,) = err.problems
    assert problem.startswith("analysis[0].rtoll = 1e-08: unknown key 'rtoll'")
    assert "did you mean 'rtol'?" in problem
    assert "allowed: type, name, speed_ratio, speed, initial_ball_angles" in problem


@pytest.mark.parametrize(
    ("old", "new", "path", "hint"),
    [
        ('name = "t"', 'name = "t"\nnmae = "x"', "nmae", "did you mean 'name'?"),
        ("[model.speed]", "[model.sped]", "model.sped", "did you mean 'speed'?"),
        ("[[analysis]]", "[[analyses]]", "analyses", "did you mean 'analysis'?"),
        ("damping = 1e-4", "dampin = 1e-4", "model.balls[0].dampin", "did you mean 'damping'?"),
        ('speed = "1200 rpm"', 'sped = "1200 rpm"', "model.speed.sped", "'speed'"),
    ],
)
def test_extra_keys_are_forbidden_everywhere(old, new, path, hint):
    problems = errors_of(edit(old, new)).problems
    line = next(p for p in problems if p.startswith(path))
    assert "unknown key" in line
    assert hint in line


def test_unknown_model_type():
    err = errors_of(edit('type = "jeffcott_balls"', 'type = "jefcott"'))
    (problem,) = err.problems
    assert problem.startswith(f'model.type = "jefcott": unknown model (known: {MODELS})')
    assert "jeffcott_balls" in MODELS and problem.endswith("did you mean 'jeffcott_balls'?")


def test_missing_model_type():
    err = errors_of(edit('type = "jeffcott_balls"\n', ""))
    assert err.problems == (f"model.type: required key is missing (known: {MODELS})",)


def test_unknown_analysis_type():
    err = errors_of(edit('type = "simulate"', 'type = "campbel"'))
    (problem,) = err.problems
    assert problem.startswith('analysis[0].type = "campbel": unknown analysis type')
    assert f"(known: {ANALYSES})" in problem and "simulate" in ANALYSES
    assert problem.endswith("did you mean 'campbell'?")


def test_unknown_speed_profile():
    err = errors_of(edit('profile = "constant"', 'profile = "constnt"'))
    (problem,) = err.problems
    assert problem.startswith('model.speed.profile = "constnt": unknown speed profile')
    assert "constant, hill, ramp" in problem


def test_missing_required_key_names_what_is_needed():
    err = errors_of(edit('disc_mass = "1 kg"\n', ""))
    assert err.problems == ("model.disc_mass: required key is missing: disc mass M1 (kg)",)


def test_missing_model_table():
    text = 'name = "t"\n'
    err = errors_of(text)
    assert err.problems[0].startswith("model: required key is missing")


def test_frame_choice():
    err = errors_of(edit('frame = "fixed"', 'frame = "rotatin"'))
    assert err.problems == (
        'model.frame = "rotatin": must be one of "fixed", "rotating"; did you mean \'rotating\'?',
    )


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ('disc_mass = "1 kg"', "disc_mass = true", "model.disc_mass = true: must be a number"),
        ('disc_mass = "1 kg"', "disc_mass = [1, 2]", "model.disc_mass = [1, 2]: must be a number"),
        ('disc_mass = "1 kg"', "disc_mass = {a = 1}", "model.disc_mass = {a = 1}: must be a"),
        ("n_save = 2000", "n_save = 1", "analysis[0].n_save = 1: must be an integer >= 2"),
        ("n_save = 2000", "n_save = 20.5", "analysis[0].n_save = 20.5: must be an integer >= 2"),
        ("n_save = 2000", 'n_save = "2000"', 'analysis[0].n_save = "2000": must be an integer'),
        ("n_save = 2000", "n_save = true", "analysis[0].n_save = true: must be an integer"),
        ("rtol = 1e-8", "rtol = 1.0", "analysis[0].rtol = 1.0: must be > 0 and < 1"),
        ("rtol = 1e-8", "rtol = 0", "analysis[0].rtol = 0: must be > 0 and < 1"),
        ("atol = 1e-10", "atol = -1e-10", "analysis[0].atol = -1e-10: must be > 0"),
        ('atol = 1e-10', 'atol = "1 s"', 'analysis[0].atol = "1 s": wrong dimension'),
        ("speed_ratio = 0.6", "speed_ratio = 0", "analysis[0].speed_ratio = 0: must be > 0"),
        ('t_end = "20 s"', 't_end = "-2 s"', 'analysis[0].t_end = "-2 s": must be > 0 (s)'),
        ('t_end = "20 s"', 't_end = "20 m"', 'analysis[0].t_end = "20 m": wrong dimension'),
        ('name = "sub"', 'name = "has space"', 'analysis[0].name = "has space": must be'),
        ('name = "sub"', "name = 3", "analysis[0].name = 3: must be a string"),
        ('name = "t"', 'name = ""', 'name = "": must be 1 to 64 ASCII letters'),
        ('description = "test case"', "description = 1", "description = 1: must be a string"),
        ('name = "t"', 'schema_version = 2\nname = "t"', "schema_version = 2: unsupported"),
        ("damping = 1e-4", "damping = -1e-4", "model.balls[0].damping = -0.0001: must be >= 0"),
        ("damping = 1e-4", "friction = -0.1", "model.balls[0].friction = -0.1: must be >= 0"),
        ("damping = 1e-4", 'friction = "30 deg"', 'model.balls[0].friction = "30 deg": wrong'),
        ("damping = 1e-4", "count = 0", "model.balls[0].count = 0: must be an integer >= 1"),
        ('radius = "50 mm"', "radius = 0", "model.balls[0].radius = 0: must be > 0 (m)"),
        ("eccentricity = \"1.5 mm\"", "eccentricity = -1e-3",
         "model.eccentricity = -0.001: must be >= 0 (m)"),
        ('damping = "13 N*s/m"', 'damping = "-13 N*s/m"',
         'model.damping = "-13 N*s/m": must be >= 0'),
        ('speed = "1200 rpm"', 'speed = "0 rpm"',
         'model.speed.speed = "0 rpm": must be > 0 (rad/s)'),
        ('speed = "1200 rpm"', 'speed = "1200 rmp"', "unknown unit 'rmp'"),
    ],
)
def test_wrong_values_and_types(old, new, expected):
    problems = errors_of(edit(old, new)).problems
    assert any(p.startswith(expected) or expected in p for p in problems), problems


def test_inertia_below_point_mass():
    err = errors_of(edit("damping = 1e-4", 'inertia = "70 kg*mm^2"'))
    assert err.problems == (
        'model.balls[0].inertia = "70 kg*mm^2": must be >= mass * radius^2 = 7.5e-05 kg*m^2 '
        "(a point mass)",
    )


def test_model_and_analysis_must_be_tables_and_lists():
    err = errors_of('model = 3\nanalysis = {a = 1}\n')
    assert err.problems == ("model = 3: must be a table", "analysis = {a = 1}: must be a list")


def test_ball_angle_rows_must_match_the_balls():
    err = errors_of(edit('["45 deg", "200 deg"]', '["45 deg"]'))
    assert err.problems == (
        'analysis[0].initial_ball_angles[1] = ["45 deg"]: has 1 angle(s) but the model has '
        "2 ball(s): give one angle per ball",
    )


def test_ball_angle_rows_count_expanded_balls():
    text = edit("[[model.balls]]\nmass = 0.03\nradius = \"50 mm\"\n", "")
    text = edit("damping = 1e-4", "damping = 1e-4\ncount = 3", text)
    err = errors_of(text)
    assert len(err.problems) == 2
    assert all("the model has 3 ball(s)" in p for p in err.problems)


def test_angles_must_be_a_list_of_lists():
    err = errors_of(edit('[["0 deg", "90 deg"], ["45 deg", "200 deg"]]', '["0 deg", "90 deg"]'))
    assert err.problems[0] == 'analysis[0].initial_ball_angles[0] = "0 deg": must be a list'


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ('t_end = "20 s"', 't_end = "20 s"\nrevolutions = 300',
         "analysis[0]: t_end and revolutions exclude each other: give only one"),
        ('t_end = "20 s"\n', "", "analysis[0]: give one of t_end or revolutions"),
        ("speed_ratio = 0.6", 'speed_ratio = 0.6\nspeed = "10 Hz"',
         "analysis[0]: speed_ratio and speed exclude each other: give only one"),
        ("t_end", "ball_angle_grid = 4\nt_end",
         "analysis[0]: initial_ball_angles and ball_angle_grid exclude each other: give only one"),
        ('initial_ball_angles = [["0 deg", "90 deg"], ["45 deg", "200 deg"]]\n', "",
         "analysis[0]: give one of initial_ball_angles or ball_angle_grid"),
    ],
)
def test_mutually_exclusive_keys(old, new, expected):
    assert expected in errors_of(edit(old, new)).problems


def test_mutual_exclusion_is_reported_with_field_errors():
    text = edit("rtol = 1e-8\n", "")
    text = edit('t_end = "20 s"', 't_end = "20 s"\nrevolutions = 300\nrtol = 2', text)
    problems = errors_of(text).problems
    assert "analysis[0].rtol = 2: must be > 0 and < 1" in problems
    assert "analysis[0]: t_end and revolutions exclude each other: give only one" in problems


def test_no_speed_anywhere():
    text = edit('[model.speed]\nprofile = "constant"\nspeed = "1200 rpm"\n', "")
    text = edit("speed_ratio = 0.6\n", "", text)
    assert errors_of(text).problems == (
        "analysis[0]: no spin speed: give speed_ratio or speed, or a [model.speed] profile",
    )


def test_revolutions_need_a_constant_speed():
    text = edit('profile = "constant"\nspeed = "1200 rpm"',
                'profile = "ramp"\nstart = 0\nstop = "1200 rpm"\nduration = "5 s"')
    text = edit("speed_ratio = 0.6\n", "", text)
    text = edit('t_end = "20 s"', "revolutions = 100", text)
    (problem,) = errors_of(text).problems
    assert problem.startswith("analysis[0].revolutions = 100: needs a constant spin speed")


def test_duplicate_analysis_names():
    text = GOOD + (
        '\n[[analysis]]\ntype = "simulate"\nname = "sub"\n'
        "speed = 1\nball_angle_grid = 2\nt_end = 1\n"
    )
    assert errors_of(text).problems == (
        "analysis[1].name = \"sub\": duplicate analysis name 'sub' (also used by analysis[0])",
    )


def test_default_name_colliding_with_a_given_one():
    text = edit('name = "sub"', 'name = "simulate-1"')
    text += '\n[[analysis]]\ntype = "simulate"\nspeed = 1\nball_angle_grid = 2\nt_end = 1\n'
    (problem,) = errors_of(text).problems
    assert problem.startswith("analysis[1]: duplicate analysis name 'simulate-1'")


def test_all_problems_are_reported_together():
    text = GOOD
    text = edit("mass = 0.03", "mass = -0.03", text)
    text = edit('"16.7 kN/m"', '"12 furlongs"', text)
    text = edit('disc_mass = "1 kg"', 'disc_mass = "3 m"', text)
    text = edit('eccentricity = "1.5 mm"', "eccentricity = nan", text)
    text = edit("rtol = 1e-8", "rtoll = 1e-8", text)
    text = edit('frame = "fixed"', 'frame = "wobbly"', text)
    text = edit('t_end = "20 s"', 't_end = "20 s"\nrevolutions = 3', text)
    err = errors_of(text, "rotor.toml")
    lines = str(err).splitlines()
    assert lines[0] == "invalid case rotor.toml (7 problems):"
    assert len(lines) == 8
    assert all(line.startswith("  ") for line in lines[1:])
    assert err.origin == "rotor.toml"
    joined = "\n".join(err.problems)
    for fragment in [
        "model.balls[1].mass = -0.03: must be > 0 (kg)",
        "model.stiffness = \"12 furlongs\": unknown unit 'furlongs'",
        'model.disc_mass = "3 m": wrong dimension: expected a mass (kg), got length',
        "model.eccentricity = nan: must be a finite number",
        "analysis[0].rtoll = 1e-08: unknown key 'rtoll'",
        'model.frame = "wobbly": must be one of',
        "analysis[0]: t_end and revolutions exclude each other",
    ]:
        assert fragment in joined


def test_toml_syntax_error_gives_line_and_column():
    text = edit('damping = "13 N*s/m"', "damping = 13 N*s/m")
    err = errors_of(text, "case.toml")
    line = GOOD.splitlines().index('damping = "13 N*s/m"') + 1
    assert str(err).startswith(f"case.toml line {line}, column ")
    assert err.origin == "case.toml"


def test_toml_duplicate_table():
    err = errors_of('[model]\ntype = "jeffcott_balls"\n[model]\n', "dup.toml")
    assert str(err).startswith("dup.toml line 3, column")


def test_toml_error_at_end_of_file():
    err = errors_of("x = [1,\n", "end.toml")
    assert str(err).startswith("end.toml line 2")


def test_file_errors_name_the_file(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(edit("mass = 0.03", "mass = -0.03"), encoding="utf-8")
    with pytest.raises(CaseError) as info:
        load_case(path)
    assert str(info.value).splitlines()[0] == f"invalid case {path} (1 problem):"


def test_top_level_must_be_a_table():
    from rotorlab.io import validate_case

    with pytest.raises(CaseError, match="a case must be a table"):
        validate_case([1, 2])  # type: ignore[arg-type]
