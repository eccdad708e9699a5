"""Impossible or degenerate runs (issue 28, items 8-11): never a success with exit code 0.

Two kinds, each on a built-in machine case changed by ``--set`` (or one text change):

- refused up front (exit code 2, a message naming the key path, the value and what is allowed or
  what to change, no traceback, nothing written), before any integration: a rotor that rests on
  its stator under gravity (item 8), a motor that cannot spin the machine up (item 9), a time
  history too large to store (item 11);
- run, then failed (exit code 3, the reason on stderr, ``status`` < 0 in the rows): a
  self-excited structure that grows beyond the linear model's validity, or is unstable at the
  final speed (item 10).

An impossible run that is reported as a success is a bug: add it here.
"""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

runner = CliRunner()

#: washer-horizontal with a 10 mm clearance around the axis: the drum (40 kg, the two 0.5 kg
#: balls) sags m g / k = 41 * 9.81 / 25e3 = 16.09 mm on its springs, onto the stator.
ON_STATOR = ["--set", 'model.clearances=[{at = "drum", gap = "10 mm"}]']
#: washer-horizontal's suspension with cross-coupled stiffness q = 15 kN/m: self-excited above
#: q = c sqrt(k / m) = 400 * 25 = 10 kN/m (the eigenvalues of m s^2 + c s + k -+ i q).
SELF_EXCITED = ["--set", "model.structure.bearings[0].kxy=15 kN/m", "--set", "model.structure.bearings[0].kyx=-15 kN/m"]
NO_PASSING = ["--set", "analysis[1].passing_torque=false"]
FILE = "{d}/case.toml"

# (id, argv with {d} for the working folder, (base case, old text, new text) or None, words of the message)
REFUSED: list[tuple[str, list[str], tuple[str, str, str] | None, list[str]]] = [
    # ---- item 8: the clearance smaller than the static sag across the axis -------------------
    ("rest-on-stator-simulate", ["simulate", "washer-horizontal", "--speed-rpm", "1300", "--t-end", "1", *ON_STATOR],
     None, ["model.clearances[0].gap = 10 mm", "16.09 mm", "'drum'", "center_at_rest = true", "gap > 16.09 mm"]),
    ("rest-on-stator-run-up", ["run-up", "washer-horizontal", "--t-end", "1", *ON_STATOR], None,  # no balls: 40 kg
     ["model.clearances[0].gap = 10 mm", "15.7 mm", "center_at_rest = true"]),
    ("rest-on-stator-knock", ["run", FILE, "--out", "{d}/o"], ("washer-knock", "center_at_rest = true", ""),
     ["model.clearances[0].gap = 10 mm", "16.09 mm", "center_at_rest = true"]),
    ("rest-on-stator-centre-above-the-axis", ["run", "washer-horizontal", "--out", "{d}/o", "--set",
                                              'model.clearances=[{at = "drum", gap = "10 mm", center = ["0 mm", "5 mm"]}]'],
     None, ["model.clearances[0].gap = 10 mm", "20.7 mm", "center_at_rest = true"]),  # 5 + 15.70 mm (no balls)
    # ---- item 9: a motor that cannot spin the machine up -------------------------------------
    # (passing_torque off: it refused a torque <= 0 for its own reason, the run-ups did not)
    ("motor-zero-stall-torque", ["run-up", "washer-horizontal", *NO_PASSING, "--set", "model.drive.stall_torque=0 N*m"],
     None, ["model.drive.stall_torque", '"0 N*m"', "must be > 0 N*m", "never spins"]),
    ("motor-negative-stall-torque", ["run", "washer-horizontal", "--out", "{d}/o", *NO_PASSING, "--set",
                                     "model.drive.stall_torque=-10 N*m"], None,
     ["model.drive.stall_torque", '"-10 N*m"', "must be > 0 N*m", "backwards"]),
    ("motor-table-without-torque-at-rest", ["validate", "washer-horizontal", "--set",
                                            'model.drive={profile = "motor", speeds = ["0 rad/s", "100 rad/s"], '
                                            'torques = ["0 N*m", "5 N*m"], polar_inertia = "0.8 kg*m^2"}'], None,
     ["model.drive.torques", "initial speed (0 rad/s), 0 N*m, must be > 0 N*m"]),
    # ---- item 11: a time history that cannot be stored ---------------------------------------
    ("simulate-n-save-absurd", ["simulate", "pico21-balancer", "--analysis", "vibration-no-race", "--set",
                                "analysis[3].n_save=1e10"], None,
     ["n_save = 10000000000 saved states of 1 trajectory x 12 entries", "memory", "save fewer states (n_save)"]),
    ("simulate-n-save-absurd-two-starts", ["simulate", "pico21-balancer", "--analysis", "vibration-one-race",
                                           "--set", "analysis[4].n_save=1e10", "--out", "{d}/o.nc"], None,
     ["n_save = 10000000000 saved states of 2 trajectories x 16 entries", "memory"]),
    ("run-up-n-save-absurd", ["run-up", "washer-horizontal", "--set", "analysis[0].n_save=1e12"], None,
     ["n_save = 1000000000000 saved states of 1 trajectory x 10 entries", "memory", "save fewer states (n_save)"]),
]


def builtin(name: str) -> str:
    return resources.files("rotorlab.cases").joinpath(f"{name}.toml").read_text(encoding="utf-8")


def _tree(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


@pytest.mark.parametrize("name, argv, case, words", REFUSED, ids=[entry[0] for entry in REFUSED])
def test_an_impossible_run_is_refused_before_it_runs(name, argv, case, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a default output folder would land here
    if case is not None:
        base, old, new = case
        text = builtin(base)
        assert old in text
        (tmp_path / "case.toml").write_text(text.replace(old, new), encoding="utf-8")
    before = _tree(tmp_path)
    result = runner.invoke(app, [a.replace("{d}", str(tmp_path)) for a in argv])
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output, result.output
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    assert _tree(tmp_path) == before, "something was written"


# ---- item 10: runs that fail after they ran: exit code 3, never status 0 ---------------------------


def _failed_run_up(argv):
    result = runner.invoke(app, ["run-up", "washer-horizontal", "--analysis", "run-up-no-balls", *argv, "--json"])
    assert result.exit_code == 3, (result.exit_code, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output, result.output
    (row,) = json.loads(result.stdout)["rows"]
    return row, result.stderr


def test_a_self_excited_structure_growing_beyond_the_linear_model_fails():
    """10 s of run-up: the suspension's whirl grows at about 2.3 1/s to ~1e8 m (reported with
    status 0 before): far more than the drum's size (its radius of gyration sqrt(1.5 / 40) =
    0.194 m), so the sanity monitor fails the run (IMPOSSIBLE, -5) and says why."""
    row, err = _failed_run_up(["--t-end", "10", *SELF_EXCITED])
    assert row["status"] == -5 and row["outcome"] == "failed"
    assert "station 'drum' moved" in err and "0.194 m" in err and "small deflections" in err


def test_a_structure_unstable_at_the_final_speed_fails_before_it_has_grown():
    """1 s of the same run-up: the whirl is still small (no sanity check fires) but the
    structure is unstable at the final speed: the run is no steady motion (UNSTABLE, -6)."""
    row, err = _failed_run_up(["--t-end", "1", *SELF_EXCITED])
    residual = row["residual_amplitude"]["drum"]
    assert residual is not None and residual < 0.194
    assert row["status"] == -6 and row["outcome"] == "failed"
    assert "unstable at" in err and "grows at" in err and "self-excited" in err


def test_the_stable_suspension_still_runs_up_with_status_0():
    """The negative control: the same run-up without the cross-coupling succeeds."""
    result = runner.invoke(app, ["run-up", "washer-horizontal", "--analysis", "run-up-no-balls", "--t-end", "1",
                                 "--json"])
    assert result.exit_code == 0, result.output
    (row,) = json.loads(result.stdout)["rows"]
    assert row["status"] == 0 and row["outcome"] == "no balancer"
