"""``rotorlab new``: every template validates, loads and (one of them) runs; bad input is refused.

Bad input: exit code 2, a message naming the argument and what is allowed, no traceback, and
nothing written (an existing file is left byte for byte).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import TEMPLATES, load_case

runner = CliRunner()
ROSS_FILE = Path(__file__).parents[1] / "data" / "ross" / "rotor_example.toml"


@pytest.mark.parametrize("template", sorted(TEMPLATES))
def test_template_validates_and_loads(tmp_path: Path, template: str) -> None:
    out = tmp_path / "mine.toml"
    res = runner.invoke(app, ["new", template, str(out)])
    assert res.exit_code == 0, res.output
    text = out.read_text()
    # commented: a comment on at least every fourth line, units written out
    lines = [ln for ln in text.splitlines() if ln.strip()]
    assert sum("#" in ln for ln in lines) >= len(lines) / 4
    assert "Units:" in text
    res = runner.invoke(app, ["validate", str(out)])
    assert res.exit_code == 0, res.output
    assert res.output.startswith("OK: ")
    case = load_case(out)
    assert case.analyses, "a template carries analyses to run"


def test_washer_template_explains_center_at_rest_and_drive_inertia(tmp_path: Path) -> None:
    """The comment's static sag m g / k matches the file's numbers and is more than half the
    gap (hence center_at_rest), and the motor's polar inertia is explained."""
    out = tmp_path / "w.toml"
    assert runner.invoke(app, ["new", "washer", str(out)]).exit_code == 0
    text = out.read_text()
    model = load_case(out).model
    mass = model.structure.bodies[0].mass
    k = model.structure.bearings[0].kxx
    sag = mass * 9.81 / k
    assert sag == pytest.approx(0.0157, abs=5e-5)          # 40 kg * 9.81 / 25 kN/m
    assert "15.7 mm" in text
    clearance = model.clearances[0]
    assert sag > 0.5 * clearance.gap and clearance.center_at_rest
    assert f"{1e3 * clearance.gap:.0f} - {1e3 * sag:.1f} = {1e3 * (clearance.gap - sag):.1f} mm" in text
    assert model.drive.polar_inertia == pytest.approx(0.8)
    assert "polar_inertia is the inertia of everything the motor turns" in text


def test_template_runs_campbell_end_to_end(tmp_path: Path) -> None:
    """The two-plane template: a 1 kg-class rigid rotor on two supports; its critical speeds on
    the 1x line are closed forms: sqrt(k / m) (cylindrical, F and B) and for the conical forward
    mode sqrt(k_tilt / (I_d - I_p)) (rigid rotor on isotropic supports, Friswell et al. 2010,
    Chapter 3)."""
    out = tmp_path / "tp.toml"
    assert runner.invoke(app, ["new", "two-plane", str(out)]).exit_code == 0
    res = runner.invoke(app, ["campbell", str(out), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    rpm = 60.0 / (2.0 * 3.141592653589793)
    cyl = (100e3 / 18.4) ** 0.5 * rpm            # 704 rpm
    con_f = (2250.0 / (0.1495 - 0.023)) ** 0.5 * rpm  # 1274 rpm
    crit = doc["critical_speeds_rpm"]
    # damping is light (zeta ~ 0.04): the damped crossings lie within 1 % of the undamped values
    assert any(abs(c / cyl - 1) < 0.01 for c in crit)
    assert any(abs(c / con_f - 1) < 0.01 for c in crit)


def test_new_from_ross_writes_a_valid_case(tmp_path: Path) -> None:
    out = tmp_path / "r.toml"
    res = runner.invoke(app, ["new", "--from-ross", str(ROSS_FILE), str(out)])
    assert res.exit_code == 0, res.output
    case = load_case(out)
    assert case.model.type == "fe_rotor" and case.model.n_elements == 6
    assert "saved by ROSS" in out.read_text()


@pytest.mark.parametrize(("argv", "words"), [
    (["new", "bogus", "{d}/x.toml"], ["TEMPLATE = 'bogus'", "centrifuge, washer, fe-rotor, two-plane"]),
    (["new", "washer"], ["give a template", "centrifuge"]),
    (["new", "washer", "{d}/x.txt"], ["NAME", "x.txt", ".toml"]),
    (["new", "washer", "{d}/nofolder/x.toml"], ["NAME", "does not exist"]),
    (["new", "--from-ross", "{d}/missing.toml", "{d}/x.toml"], ["missing.toml", "cannot read"]),
    (["new", "--from-ross", "{d}/existing.toml", "{d}/x.toml"], ["not a rotor saved by ROSS"]),
    (["new", "--from-ross", str(ROSS_FILE)], ["give one NAME.toml"]),
])
def test_bad_new_is_refused_and_writes_nothing(tmp_path: Path, argv: list[str], words: list[str]) -> None:
    (tmp_path / "existing.toml").write_text("name = 'x'\n")
    before = sorted(p.name for p in tmp_path.iterdir())
    res = runner.invoke(app, [a.replace("{d}", str(tmp_path)) for a in argv])
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    for w in words:
        assert w in res.stderr, res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_existing_file_is_kept_without_force(tmp_path: Path) -> None:
    out = tmp_path / "mine.toml"
    out.write_text("# mine\n")
    res = runner.invoke(app, ["new", "washer", str(out)])
    assert res.exit_code == 2
    assert "--force" in res.stderr and "exists" in res.stderr
    assert out.read_text() == "# mine\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"]
    res = runner.invoke(app, ["new", "washer", str(out), "--force"])
    assert res.exit_code == 0
    assert "center_at_rest" in out.read_text()
