"""``--set KEY=VALUE`` and ``load_case(..., overrides=...)`` (issue 12): any key of a case set before
validation, with the key-path syntax of the error messages; the result is that of the edited file."""

from __future__ import annotations

import json
import math
from importlib import resources

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import CaseError, apply_overrides, load_case, parse_case, parse_key_path, parse_override

runner = CliRunner()


def _text(name: str) -> str:
    return resources.files("rotorlab.cases").joinpath(f"{name}.toml").read_text(encoding="utf-8")


def _edited(name: str, old: str, new: str) -> str:
    text = _text(name)
    assert text.count(old) == 1, (name, old)
    return text.replace(old, new)


# (built-in case, key path as written in an error message, value, the same edit made in the file)
EDITS = [
    ("autobalancer", "model.disc_mass", "2 kg", ('disc_mass = "1 kg"', 'disc_mass = "2 kg"')),
    ("autobalancer", "model.balls[0].mass", 0.02, ('mass = "30 g"', "mass = 0.02")),
    ("autobalancer", "analysis[2].t_end", "5 s", ('t_end = "20 s"\nn_horizons', 't_end = "5 s"\nn_horizons')),
    ("friswell-rotor", "model.bearings[1].kxx", "3 MN/m", ('position = "1.5 m"\nkxx = "1 MN/m"',
                                                           'position = "1.5 m"\nkxx = "3 MN/m"')),
    ("krasnov-crusher", "model.housing.gap", "6 mm", ('gap = "4.5 mm"', 'gap = "6 mm"')),
    # the machine model (issue 12): a race's plane, a ball entry written with count = 2, the motor
    ("pico21-balancer", "model.races[1].axial_offset", "20 mm", ('axial_offset = "30 mm"', 'axial_offset = "20 mm"')),
    ("rcfw-two-plane", "model.races[0].balls[0].mass", "0.025 kg",
     ('axial_offset = "2 m"\nradius = "1 m"\nballs = [{ mass = "0.005 kg"',
      'axial_offset = "2 m"\nradius = "1 m"\nballs = [{ mass = "0.025 kg"')),
    ("washer-horizontal", "model.drive.stall_torque", "5 N*m", ('stall_torque = "10 N*m"', 'stall_torque = "5 N*m"')),
]


@pytest.mark.parametrize("name, key, value, edit", EDITS, ids=[f"{e[0]}:{e[1]}" for e in EDITS])
def test_an_override_gives_the_case_of_the_edited_file(name, key, value, edit):
    by_override = load_case(name, overrides={key: value})
    by_edit = parse_case(_edited(name, *edit), origin=f"{name}.toml")
    assert by_override.model_dump_si() == by_edit.model_dump_si()
    assert by_override.model_dump_si() != load_case(name).model_dump_si()
    assert by_override.overrides == {key: value}


def test_an_overridden_mass_moves_the_critical_speed_by_the_closed_form():
    # autobalancer: p = sqrt(c / (M1 + sum m)) (seed 002 eq. (10)), c = 16.74 kN/m, two balls of m each
    case = load_case("autobalancer", overrides={"model.disc_mass": "2 kg", "model.balls.0.mass": "20 g"})
    assert case.model.critical_speed() == pytest.approx(math.sqrt(16740.0 / (2.0 + 2 * 0.020)), rel=1e-12)


def test_overrides_apply_in_order_create_missing_tables_and_leave_the_input_alone():
    doc = {"model": {"speed": {"profile": "constant", "speed": 1.0}}, "analysis": [{"type": "simulate"}]}
    out = apply_overrides(doc, {"model.speed": {"profile": "constant", "speed": 2.0}, "model.speed.speed": 3.0,
                                ("analysis", 0, "t_end"): 4.0, "model.new.deep": 5})
    assert out == {"model": {"speed": {"profile": "constant", "speed": 3.0}, "new": {"deep": 5}},
                   "analysis": [{"type": "simulate", "t_end": 4.0}]}
    assert doc == {"model": {"speed": {"profile": "constant", "speed": 1.0}}, "analysis": [{"type": "simulate"}]}


def test_key_paths_and_values_are_read_like_toml():
    assert parse_key_path('analysis[0]."odd.key"[2]') == ("analysis", 0, "odd.key", 2)
    assert parse_key_path("model.races.0.balls[1].mass") == ("model", "races", "0", "balls", 1, "mass")
    assert parse_override('analysis[0]."a=b"=1') == ('analysis[0]."a=b"', 1)
    values = {"3": 3, "1e-3": 0.001, "true": True, "[1, 2]": [1, 2], '"20 g"': "20 g", "20 g": "20 g",
              "2400rpm": "2400rpm", "{profile = 'constant'}": {"profile": "constant"}, " fixed ": "fixed"}
    for text, expected in values.items():
        key, value = parse_override(f"model.x={text}")
        assert (key, value, type(value)) == ("model.x", expected, type(expected)), text
    for bad in ("model.x", "model.x=", "model.x=[1,", 'model.x="open', "model..x=1", "model x=1", "[0]=1"):
        with pytest.raises(CaseError, match="--set"):
            parse_override(bad)


def test_every_bad_path_is_reported_with_its_value_and_what_is_allowed():
    with pytest.raises(CaseError) as info:
        load_case("autobalancer", overrides={"model.balls[2].mass": 1, "model.disc_mass.x": 2,
                                             "model.bals[0].mass": 3, "analysis.t_end": 4})
    assert info.value.problems == (
        "model.balls[2].mass = 1: model.balls has 1 entry: give an index from 0 to 0",
        'model.disc_mass.x = 2: model.disc_mass = "1 kg" is a single value, not a table or list: cannot set a '
        "key inside it",
        "model.bals[0].mass = 3: model.bals is not in the case, so it has no entry [0]; did you mean 'balls'? "
        "(keys of model: type, frame, disc_mass, eccentricity, stiffness, damping, speed, balls)",
        "analysis.t_end = 4: analysis is a list: give an entry's index, e.g. analysis[0].t_end",
    )


def test_a_bad_value_is_validated_like_the_file_and_the_message_says_what_was_set():
    with pytest.raises(CaseError) as info:
        load_case("autobalancer", overrides={"model.disc_mass": "2 m", "model.dsic_mass": 1})
    message = str(info.value)
    assert message.splitlines()[0] == ('invalid case builtin:autobalancer with model.disc_mass = "2 m"; '
                                       "model.dsic_mass = 1 (2 problems):")
    assert 'model.disc_mass = "2 m": wrong dimension' in message
    assert "model.dsic_mass = 1: unknown key 'dsic_mass'; did you mean 'disc_mass'?" in message


def test_the_cli_set_gives_the_numbers_of_the_edited_file(tmp_path):
    edited = tmp_path / "stiffer.toml"
    edited.write_text(_edited("friswell-rotor", 'position = "1.5 m"\nkxx = "1 MN/m"',
                              'position = "1.5 m"\nkxx = "3 MN/m"'), encoding="utf-8")
    argv = ["modes", "--json", "--speed-rpm", "0"]
    by_set = runner.invoke(app, [*argv, "friswell-rotor", "--set", "model.bearings[1].kxx=3 MN/m"])
    by_edit = runner.invoke(app, [*argv, str(edited)])
    plain = runner.invoke(app, [*argv, "friswell-rotor"])
    assert by_set.exit_code == by_edit.exit_code == plain.exit_code == 0, by_set.output
    stiff, soft = json.loads(by_set.stdout), json.loads(plain.stdout)
    assert stiff == json.loads(by_edit.stdout)
    # a stiffer support cannot lower an undamped natural frequency at rest (Rayleigh's monotonicity
    # theorem, M and K symmetric, K grows by a positive semi-definite term) and this one raises the first
    freq = [doc["frequency_hz"] for doc in (stiff, soft)]
    assert all(a >= b * (1 - 1e-12) for a, b in zip(*freq))
    assert freq[0][0] > freq[1][0] * 1.001


def test_every_command_that_takes_a_case_takes_set():
    import typer.main

    group = typer.main.get_command(app)
    with_case = {name: cmd for name, cmd in group.commands.items() if any(p.name == "case" for p in cmd.params)}
    assert {"run", "validate", "simulate", "campbell", "modes", "steady", "basin", "sweep"} <= set(with_case)
    missing = [name for name, cmd in with_case.items() if not any("--set" in p.opts for p in cmd.params)]
    assert missing == []


def test_validate_json_and_the_report_text_name_the_keys_set():
    result = runner.invoke(app, ["validate", "autobalancer", "--json", "--set", "model.disc_mass=2 kg"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["set"] == {"model.disc_mass": "2 kg"}
    assert doc["critical_speed"] == pytest.approx(math.sqrt(16740.0 / 2.06), rel=1e-12)
    text = load_case("autobalancer", overrides={"model.disc_mass": "2 kg"}).text
    assert text.startswith("# Keys set on top of the file below")
    assert '#   model.disc_mass = "2 kg"\n' in text and text.endswith(_text("autobalancer"))


def test_a_run_with_set_says_so_in_its_report_and_json(tmp_path):
    out = tmp_path / "out"
    result = runner.invoke(app, ["run", "friswell-rotor", "--out", str(out), "--json",
                                 "--set", "model.bearings[1].kxx=3 MN/m"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["set"] == {"model.bearings[1].kxx": "3 MN/m"}
    page = (out / "report.html").read_text(encoding="utf-8")
    assert "Keys set on top of the case file (--set): model.bearings[1].kxx = &quot;3 MN/m&quot;" in page
    assert "#   model.bearings[1].kxx = &quot;3 MN/m&quot;" in page  # the case-file text shown says so too


def test_the_set_examples_of_the_readme_and_the_docs_are_valid():
    # every documented command line with --set names keys that exist and values that validate
    import re
    import shlex
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    lines = [line for page in (root / "README.md", root / "docs" / "getting-started.md")
             for block in re.findall(r"^```bash\n(.*?)^```", page.read_text(encoding="utf-8"), re.S | re.M)
             for line in block.splitlines() if line.startswith("rotorlab ") and "--set" in line]
    assert len(lines) >= 4
    for line in lines:
        argv = shlex.split(line)[1:]
        case = argv[1]
        sets = [argv[i + 1] for i, a in enumerate(argv) if a == "--set"]
        result = runner.invoke(app, ["validate", case, *[x for s in sets for x in ("--set", s)]])
        expected = 2 if "dsic_mass" in line else 0  # the docs' example of a typo
        assert result.exit_code == expected, (line, result.output)
