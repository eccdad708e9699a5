"""The sanity checks of ``rotorlab validate`` and ``rotorlab run``: each one's printed message, with
its numbers from closed forms, and the fix it names (issue 29 item 2); a warning never changes the
exit code.

The washer cases: a 40 kg drum on 25 kN/m, 400 N*s/m per direction, two 0.5 kg balls on a
0.27 m race (capacity 0.27 kg*m), unbalance 0.125 kg*m, gravity 9.81 m/s^2 across the axis, a
10 mm gap (washer-knock) and a 10 N*m stall torque.
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from rotorlab.analyses import SANITY_CHECKS, sanity_warnings
from rotorlab.cli import app
from rotorlab.io import load_case

runner = CliRunner()


def _validate(case: str, *sets: str):
    args = ["validate", case]
    for s in sets:
        args += ["--set", s]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output  # a warning is no error
    assert result.stdout.startswith(f"OK: {case}")
    return [line for line in result.stdout.splitlines() if line.startswith("warning (")]


def test_the_built_in_washers_and_centrifuges_pass_every_check():
    for case in ("washer-horizontal", "washer-knock", "pico21-balancer", "rcfw-two-plane"):
        assert _validate(case) == [], case


# (case, --set values, the one warning printed); the numbers from closed forms:
SINGLE = [
    # a bare 20 read as 20 m (the issue's own examples: a body position, a shaft)
    ("washer-knock", ["model.structure.bodies[0].position=20"],
     'warning (unit-slip): model.structure.bodies[0].position = 20 m is far outside the sizes of the machines '
     'rotorlab models (up to 5 m): a number without a unit is read in SI; write its unit, e.g. "20 mm"'),
    ("friswell-rotor", ["model.shaft[0].length=20"],
     'warning (unit-slip): model.shaft[0].length = 20 m is far outside the sizes of the machines rotorlab models (up '
     'to 5 m): a number without a unit is read in SI; write its unit, e.g. "20 mm"'),
    # autobalancer: p = sqrt(c / (M1 + 2 m)) = sqrt(16740 / 1.06) = 125.67 rad/s = 1200 rpm; its subcritical
    # analysis runs at 0.6 p = 720 rpm
    ("autobalancer", [],
     "warning (below-critical): analysis subcritical is 720 rpm, below the first forward critical speed 1200 rpm "
     "(undamped, balls locked): a balancer works only above 1200 rpm, below it the balls add to the unbalance; run "
     "above 1200 rpm, or soften the mounts (lower support stiffness) until the critical speed falls below 720 rpm"),
    # at rest the drum and balls (41 kg) sag 41 x 9.81 / 25000 = 16.1 mm against the 10 mm gap
    ("washer-knock", ["model.clearances[0].center_at_rest=false"],
     "warning (sag-gap): at rest under gravity the clearance station lies 16.1 mm from the stator's centre, against "
     "a gap of 10 mm: the rotor rests on its stator and knocks in every run-up, with or without balls; give "
     "model.clearances[0].center_at_rest = true (the stator centred where the rotor rests)"),
    # U g = 0.125 x 9.81 = 1.23 N*m
    ("washer-horizontal", ["model.drive.stall_torque=1 N*m"],
     "warning (motor-torque): the motor's stall torque 1 N*m is below the unbalance's gravity torque U g = 1.23 N*m: "
     "from rest it cannot lift the unbalance over the top; give model.drive.stall_torque > 1.23 N*m"),
    # the suspension mode decays at c / (2 M), M = 41 kg (balls locked): tau = 82 / 400 = 0.205 s; 0.4 s < 3 tau,
    # and 10 tau = 2.05 s rounds up to 2.1 s
    ("washer-knock", ["analysis[0].t_end=0.4 s"],
     "warning (horizon): analysis[0] (knock).t_end = 400 ms is shorter than 3 time constants of the slowest mode "
     "(205 ms, structure with the balls locked): its start-up transient has not died out; give t_end >= 2.1 s (10 "
     "time constants)"),
]


@pytest.mark.parametrize(("case", "sets", "message"), SINGLE, ids=[m.split(")")[0][9:] + "-" + c for c, _, m in SINGLE])
def test_each_check_prints_its_numbers_and_fix(case, sets, message):
    assert _validate(case, *sets) == [message]


def test_an_unbalance_that_puts_the_mass_centre_metres_off_the_axis_is_a_unit_slip():
    """50 read as 50 kg*m on the 40 kg drum: e = 50 / 40 = 1.25 m (and the balls' 0.27 kg*m
    cannot cancel it)."""
    lines = _validate("washer-knock", "model.unbalances[0].magnitude=50")
    assert lines[0] == ('warning (unit-slip-unbalance): the unbalance 50 kg*m on a 40 kg rotor puts its mass centre '
                        '1.25 m off the axis (more than 50 mm is no machine\'s): a number without a unit is read as '
                        'kg*m (or m); check model.unbalances and write its unit, e.g. "50 g*mm"')
    assert lines[1].startswith("warning (ball-capacity)")


def test_balls_heavier_than_the_rotor_are_a_unit_slip():
    """zhakash-k2: a 2 kg disc; two balls of 10 kg are 20 kg, ten times the disc."""
    lines = _validate("zhakash-k2", "model.balls[0].mass=10")
    slip = [line for line in lines if line.startswith("warning (unit-slip-balls)")]
    assert slip == ['warning (unit-slip-balls): the balls weigh 20 kg together on a 2 kg rotor (more than 50 % of '
                    'it): balancer balls are a small part of the rotor; check model.balls[0].mass = 10 kg (a mass in '
                    'grams needs its unit, e.g. "10 g")']


def test_balls_that_cannot_cancel_the_unbalance_say_both_numbers():
    """Capacity 2 x 0.5 kg x 0.27 m = 0.27 kg*m against 0.5 kg*m: 0.5 / 0.27 = 1.85 times heavier."""
    lines = _validate("washer-knock", "model.unbalances[0].magnitude=0.5 kg*m")
    assert "warning (ball-capacity): the balls can cancel at most 0.27 kg*m (sum of ball mass x race radius); the " \
           "unbalance is 0.5 kg*m: they cannot balance it; make the balls at least 1.85 times heavier (or their " \
           "race radius larger), or the unbalance smaller" in lines


def test_every_check_is_tested_here_and_validate_json_lists_the_warnings():
    tested = {"unit-slip", "unit-slip-unbalance", "unit-slip-balls", "ball-capacity", "below-critical", "sag-gap",
              "motor-torque", "horizon"}
    assert set(SANITY_CHECKS) == tested
    result = runner.invoke(app, ["validate", "washer-horizontal", "--set", "model.drive.stall_torque=1 N*m", "--json"])
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert [w["check"] for w in doc["warnings"]] == ["motor-torque"]
    w = doc["warnings"][0]
    assert w["numbers"]["gravity_torque"] == pytest.approx(0.125 * 9.81)
    assert w["fix"] == "give model.drive.stall_torque > 1.23 N*m"
    assert [x.check for x in sanity_warnings(load_case("washer-horizontal"))] == []


def test_every_command_prints_the_warnings_before_it_runs_and_quiet_hides_them():
    # campbell: a single-analysis command (linear, no compile); the warning reaches stderr before its
    # progress line, the command still succeeds, and -q keeps stderr empty
    args = ["campbell", "friswell-rotor", "--set", "model.shaft[0].length=20", "--json"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert lines[0].startswith("warning (unit-slip): model.shaft[0].length = 20 m is far outside"), lines
    json.loads(result.stdout)  # the JSON on stdout is untouched
    quiet = runner.invoke(app, ["-q", *args])
    assert quiet.exit_code == 0 and quiet.stderr == ""
