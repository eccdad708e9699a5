"""``rotorlab continue --from hopf|simulation``: whirl orbits of ``zhakash-k2`` as periodic branches.

The reference is the long simulation of tests/validation/test_periodic_orbits.py
(``_simulated``: the whirl's start (-30, -15) deg at 1.6 p settled 60 s with rtol 1e-11, then the
mean period of upward crossings over 4 periods, 20000 samples), run once for this file:
period 0.10043187047729873 s and largest |u + i v| 0.021836641849358268 m at 1.6 p =
157.6526845062869 rad/s. The command finds the whirl from its own start (an offset grid of ball
angles), not from that one.
"""

from __future__ import annotations

import json
import math

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import ContinuationSpec

runner = CliRunner()
SPEED = 157.6526845062869  # 1.6 p of zhakash-k2 (rad/s)
PERIOD, AMPLITUDE = 0.10043187047729873, 0.021836641849358268


@pytest.fixture(scope="module")
def whirl_json():
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", f"drive.speed={SPEED!r}:170", "--from", "simulation",
                              "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout[res.stdout.index("{"):])


def test_from_simulation_gives_the_whirl_of_the_long_simulation(whirl_json):
    (branch,) = whirl_json["branches"]
    first = branch["points"][0]
    assert first["drive.speed"] == pytest.approx(SPEED, rel=1e-12)
    assert first["period_s"] == pytest.approx(PERIOD, rel=1e-4)
    assert first["amplitude_m"] == pytest.approx(AMPLITUDE, rel=1e-4)
    assert "ball angles" in whirl_json["periodic_start"] and "offset grid" in whirl_json["periodic_start"]


def test_periodic_branch_json_shape(whirl_json):
    (branch,) = whirl_json["branches"]
    assert (branch["kind"], branch["parameter"], branch["label"], branch["end"]) == \
        ("periodic", "drive.speed", "whirl", "bound")
    speeds = [p["drive.speed"] for p in branch["points"]]
    assert speeds[-1] == pytest.approx(170.0) and all(b > a for a, b in zip(speeds, speeds[1:]))
    for p in branch["points"]:
        assert p["stable"] is True  # test_periodic_orbits: stable from 0.974 p to the branch point at 4.584 p
        assert len(p["multipliers"]) == 8 and all(len(z) == 2 for z in p["multipliers"])
        moduli = sorted(math.hypot(*z) for z in p["multipliers"])
        assert abs(moduli[-1] - 1.0) < 1e-6 and moduli[-2] < 1.0  # the trivial one, the rest inside
        assert 0.08 < p["period_s"] < 0.11  # it shortens with the speed
    assert branch["special_points"] == []
    assert whirl_json["units"]["drive.speed"] == "rad/s"


def test_from_simulation_in_words(tmp_path):
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", f"drive.speed={SPEED!r}:160", "--from", "simulation",
                              "--plot", str(tmp_path / "w.png")])
    assert res.exit_code == 0, res.output
    text = " ".join(res.stdout.split())
    assert "A whirl orbit exists and is stable from 1505.5 to 1527.9 rpm" in text
    assert (tmp_path / "w.png").stat().st_size > 10_000


@pytest.mark.parametrize("value", ["orbit", "Hopf", "simulate"])
def test_a_bad_from_value_exits_2_naming_the_allowed_ones(value, tmp_path):
    out = tmp_path / "o.nc"
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", "drive.speed=1000rpm:1600rpm", "--from", value,
                              "--out", str(out)])
    assert res.exit_code == 2
    assert "--from" in res.output and repr(value) in res.output
    for word in ("balanced", "side", "all", "hopf", "simulation"):
        assert word in res.output
    assert "Traceback" not in res.output and not out.exists()


def test_periodic_orbits_of_a_machine_are_refused_with_exit_2():
    res = runner.invoke(app, ["continue", "rcfw-two-plane", "--param", "drive.speed=1000rpm:1600rpm", "--from",
                              "simulation"])
    assert res.exit_code == 2 and "jeffcott_balls" in res.output and "Traceback" not in res.output


def test_the_case_file_takes_the_same_from_values():
    for value in ("hopf", "simulation"):
        spec = ContinuationSpec(name="c", param="drive.speed", range=["1000 rpm", "1600 rpm"], start_from=value)
        assert spec.start_from == value and "whirl orbits" in spec.describe(None)
    with pytest.raises(ValueError, match="hopf, simulation"):
        ContinuationSpec(name="c", param="drive.speed", range=["1000 rpm", "1600 rpm"], start_from="orbits")


def test_a_model_with_events_is_refused_with_exit_2(tmp_path):
    text = (tmp_path / "zk.toml")
    from importlib import resources

    case = resources.files("rotorlab.cases").joinpath("zhakash-k2.toml").read_text()
    text.write_text(case[: case.index("[[analysis]]")].replace('count = 2', 'count = 2\nfriction = 0.01'))
    out = tmp_path / "o.nc"
    res = runner.invoke(app, ["continue", str(text), "--param", "drive.speed=1500rpm:1600rpm", "--from", "simulation",
                              "--out", str(out)])
    assert res.exit_code == 2 and "Traceback" not in res.output and not out.exists()
    assert "periodic orbits of a model with events (stick_1, slip_1, stick_2, slip_2) are not supported" in \
        " ".join(res.output.split())


def test_periodic_orbits_in_another_parameter_are_refused_with_exit_2():
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", "ball_mass=30g:20g", "--speed-rpm", "1500", "--from",
                              "simulation"])
    assert res.exit_code == 2 and "drive.speed only" in res.output


def test_from_hopf_starts_an_orbit_at_the_hopf_point_with_its_period():
    """Near a Hopf point the orbit's period is 2 pi / w of the crossing pair (Kuznetsov 2004, 3.5)."""
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", "drive.speed=1300rpm:1380rpm", "--from", "hopf",
                              "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout[res.stdout.index("{"):])
    hopf = {round(s["drive.speed"], 6): s for b in doc["branches"] if b["kind"] == "equilibrium"
            for s in b["special_points"] if s["type"] == "hopf"}
    (h,) = hopf.values()  # main+ and main- share it: 1371 rpm
    (orbit,) = [b for b in doc["branches"] if b["kind"] == "periodic"]
    first = orbit["points"][0]
    assert first["drive.speed"] == pytest.approx(h["drive.speed"], rel=1e-6)
    assert first["period_s"] == pytest.approx(2 * math.pi / h["frequency_rad_s"], rel=1e-5)
    assert first["amplitude_m"] < 1e-5 < max(p["amplitude_m"] for p in orbit["points"])
    assert orbit["label"].startswith("born at the Hopf point of main")


def test_orbits_born_at_hopf_points_have_no_bifurcation_at_their_birth(monkeypatch):
    """zhakash-k2 from 800 to 3000 rpm, the first 6 orbits of each Hopf point's branch: at the
    first step away from a Hopf point the parameter moves as the amplitude squared and a second
    multiplier is 1 + O(amplitude^2), so the fold and branch tests are zero to round-off there.
    Before, side 01's orbits reported a fold of cycles at 1077.3 rpm and a branch point at
    1468.8 rpm, each at its Hopf point's speed to 2e-10: the orbits' birth, not a bifurcation."""
    import rotorlab.analyses._continuation_periodic as cp

    monkeypatch.setattr(cp, "HOPF_ORBITS", 6)
    res = runner.invoke(app, ["continue", "zhakash-k2", "--param", "drive.speed=800rpm:3000rpm", "--from", "hopf",
                              "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout[res.stdout.index("{"):])
    hopf = sorted({round(s["drive.speed"], 6) for b in doc["branches"] if b["kind"] == "equilibrium"
                   for s in b["special_points"] if s["type"] == "hopf"})
    orbits = [b for b in doc["branches"] if b["kind"] == "periodic"]
    assert len(hopf) == 3 and len(orbits) == 3  # main+ at 1371 rpm, side 01 at 1077 and 1469 rpm
    for b in orbits:
        assert len(b["points"]) == 6 and b["special_points"] == [], b["special_points"]
