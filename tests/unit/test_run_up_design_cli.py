"""``rotorlab run-up-design``: the shortest torque-limited run-up (issue 27 item 2) from the command line.

The horizontal washer (built-in ``washer-horizontal``: J = 0.8 kg m^2) with a servo drive of
constant torque limit T = 10 N m, operating speed 100 rad/s and a stiff speed loop (K = 100 N m
s/rad, so the loop never leaves the limit before 99 % of the speed), without balls and without
unbalance: the shortest run-up to 99 % is the torque-limited one, 0.99 * 100 J / T = 7.92 s, for
every ramp rate above T / J = 12.5 rad/s^2.
"""

from __future__ import annotations

import json
from importlib import resources

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

runner = CliRunner()


def case_text(balls: bool) -> str:
    text = resources.files("rotorlab.cases").joinpath("washer-horizontal.toml").read_text(encoding="utf-8")
    text = text[:text.index("[[analysis]]")] + '[[analysis]]\ntype = "run-up"\nt_end = "20 s"\n'
    text = text.replace('profile = "motor"\nstall_torque = "10 N*m"\nno_load_speed = "150 rad/s"',
                        'profile = "servo"\nstall_torque = "10 N*m"\noperating_speed = "100 rad/s"\n'
                        'ramp_rate = "5 rad/s^2"\ngain = "100 N*m*s/rad"')
    if not balls:
        start = text.index("[[model.races]]")
        text = text[:start] + text[text.index("[[model.unbalances]]"):]
    return text


def test_shortest_run_up_is_the_torque_limited_one(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(case_text(balls=False), encoding="utf-8")
    r = runner.invoke(app, ["run-up-design", str(path), "--vary", "drive.ramp_rate=1:50", "--budget", "6",
                            "--set", "model.unbalances[0].magnitude=0 kg*m", "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["run_up_time"] == pytest.approx(0.99 * 100 * 0.8 / 10, rel=2e-3)
    assert doc["best"]["drive.ramp_rate"] > 12.5
    assert sorted(tmp_path.iterdir()) == [path]  # nothing written


@pytest.mark.parametrize(("argv", "words"), [
    (["--vary", "drive.nope=1:2"], ["--vary", "drive.nope", "drive.ramp_rate"]),
    (["--vary", "drive.ramp_rate=-1:2"], ["--vary", "drive.ramp_rate", "-1"]),
    (["--vary", "drive.ramp_rate=1:20", "--starts", "8"], ["--starts", "0.99"]),
    (["--vary", "drive.ramp_rate=1:20", "--peak-limit", "-1"], ["--peak-limit"]),
    (["--vary", "drive.ramp_rate=1:20", "--optimizer", "sgd"], ["--optimizer", "sgd", "tpe"]),
    (["--vary", "drive.ramp_rate=1:20", "--settle", "-1"], ["--settle"]),
    ([], ["--vary"]),
])
def test_bad_input_exit_2_naming_the_option(tmp_path, argv, words):
    path = tmp_path / "case.toml"
    path.write_text(case_text(balls=True), encoding="utf-8")
    r = runner.invoke(app, ["run-up-design", str(path), *argv])
    assert r.exit_code == 2, r.output
    assert "Traceback" not in r.output
    for w in words:
        assert w in r.output
    assert sorted(tmp_path.iterdir()) == [path]


def test_motor_case_is_refused_naming_the_drive():
    r = runner.invoke(app, ["run-up-design", "washer-horizontal", "--vary", "drive.stall_torque=5:20"])
    assert r.exit_code == 2
    assert 'profile = "servo"' in r.output and "'motor'" in r.output


def test_rotorlab_design_takes_the_run_up_objective_and_a_drive_key_path(tmp_path):
    """The same shortest run-up through ``rotorlab design`` (the design search's own command, its
    --store and optimisers): ``run-up-time`` of the servo drive varied by its key path
    ``model.drive.ramp_rate``; the operating range defaults to the drive's operating speed and
    without balls there is no P(balanced) to require."""
    path = tmp_path / "case.toml"
    path.write_text(case_text(balls=False), encoding="utf-8")
    r = runner.invoke(app, ["design", str(path), "--vary", "model.drive.ramp_rate=1:50", "--objective",
                            "run-up-time", "--budget", "6", "--set", "model.unbalances[0].magnitude=0 kg*m", "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["winner"]["objectives"]["run-up-time"] == pytest.approx(0.99 * 100 * 0.8 / 10, rel=2e-3)
    assert doc["winner"]["values"]["model.drive.ramp_rate"] > 12.5
    assert doc["operating"] == {"param": "model.drive.operating_speed", "values": [100.0]}
    slow = [row for row in doc["rows"] if row["values"]["model.drive.ramp_rate"] < 12.5]
    for row in slow:  # a ramp below T / J sets the pace: 0.99 * 100 / a
        assert row["objectives"]["run-up-time"] == pytest.approx(99.0 / row["values"]["model.drive.ramp_rate"],
                                                                 rel=2e-3)
    assert doc["check"]["inside_search_interval"] is None and sorted(tmp_path.iterdir()) == [path]
