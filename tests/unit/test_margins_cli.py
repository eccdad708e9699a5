"""The ``shock-margin`` and ``friction-margin`` commands, their JSON rows, and both analyses through
``rotorlab run`` (registries, figures, report findings)."""

from __future__ import annotations

import json
import math
from importlib import resources

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

runner = CliRunner()


def test_shock_margin_command_json():
    result = runner.invoke(app, ["shock-margin", "autobalancer", "--speed-ratio", "0.8", "--speed-ratio", "2",
                                 "--directions", "4", "--no-simulate", "--json"])  # fmt: skip
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)["rows"]
    assert [r["stable"] for r in rows] == [False, True]  # seed 002: balanced only above p
    assert rows[0]["min_load_shift"] is None and rows[0]["min_impulse_linear"] is None
    r = rows[1]
    assert r["speed_rpm"] == pytest.approx(2400.0, rel=1e-3)
    assert r["min_load_shift"] == pytest.approx(1.5e-3, rel=1e-9)  # C - U = 3 - 1.5 g m
    assert r["worst_shift_direction_deg"] == 0.0
    assert 2.3 < r["min_impulse_linear"] < 2.8 and r["min_impulse_simulated"] is None


def test_friction_margin_command_json():
    result = runner.invoke(app, ["friction-margin", "strautmanis-torus", "--no-simulate", "--json"])
    assert result.exit_code == 0, result.output
    (row,) = json.loads(result.stdout)["rows"]
    assert row["speed_rpm"] == pytest.approx(140.0 * 30.0 / math.pi)
    assert row["psi_high_deg"] == pytest.approx(math.degrees(0.0089), abs=0.01)  # seed 004's band, rolling form
    assert row["check_inside"] == -1  # not simulated, and not reported as checked


def test_both_margins_through_run_and_the_report(tmp_path):
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    head = text[: text.index("[[analysis]]")].replace('damping = "2e-3 N*m*s"', 'damping = "2e-3 N*m*s"\nfriction = 0.01')
    case = tmp_path / "case.toml"
    case.write_text(head + '[[analysis]]\ntype = "friction-margin"\nname = "fm"\nspeed_ratio = [2.0]\ngrid = 61\n'
                    'simulate = false\n', encoding="utf-8")  # fmt: skip
    result = runner.invoke(app, ["run", str(case), "--out", str(tmp_path / "o"), "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert "fm_friction_margin.png" in out["files"]
    (row,) = out["analyses"]["fm"]["rows"]
    assert row["worst_residual"] > 0.0 and row["psi_1_low_deg"] < 0.0 < row["psi_1_high_deg"]
    page = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert "friction holds the balls within psi_1" in page and " um" in page and "not simulated" in page
    assert "searched by a grid of 61 points per coordinate" in page  # how the band was found
    assert row["psi_1_low_deg"] <= row["psi_1_worst_deg"] <= row["psi_1_high_deg"]  # the worst arrangement


def test_shock_margin_through_run_and_the_report(tmp_path):
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    case = tmp_path / "case.toml"
    case.write_text(text[: text.index("[[analysis]]")] + '[[analysis]]\ntype = "shock-margin"\nname = "sm"\n'
                    'speed_ratio = [0.8, 2.0, 3.0]\ndirections = 8\nsimulate = false\n', encoding="utf-8")  # fmt: skip
    result = runner.invoke(app, ["run", str(case), "--out", str(tmp_path / "o"), "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert "sm_shock_margin.png" in out["files"]
    below, *rows = out["analyses"]["sm"]["rows"]
    assert below["stable"] is False and below["min_impulse_linear"] is None
    # the linearised estimate grows with speed (3 p: 4.0 N s against 2.4 N s at 2 p); the load shift does not
    assert rows[1]["min_impulse_linear"] > 1.5 * rows[0]["min_impulse_linear"]
    assert rows[0]["min_load_shift"] == rows[1]["min_load_shift"]
    page = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert "Weakest: At 2400 rpm a knock of" in page and "1500 g mm" in page
    assert "The balanced state is not stable at 960 rpm: no margin there." in page


def test_shock_margin_command_on_a_machine():
    # the same command on a two-plane machine: the load shift its races can no longer cancel
    # (0.01 kg m along the unbalance, Rodrigues et al. 2008 eq. (21)), the knock at the unbalance's node
    result = runner.invoke(app, ["shock-margin", "rcfw-two-plane", "--directions", "2", "--no-simulate", "--json"])
    assert result.exit_code == 0, result.output
    (r,) = json.loads(result.stdout)["rows"]
    assert r["stable"] and r["station"] == "node rotor"
    assert r["min_load_shift"] == pytest.approx(0.01, rel=1e-6) and r["worst_shift_direction_deg"] == 0.0
    assert r["min_impulse_linear"] > 0.0 and r["min_impulse_simulated"] is None
