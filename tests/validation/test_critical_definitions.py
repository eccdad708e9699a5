"""Critical speeds say which definition they follow (issue 29 item 3).

Sources and checks
------------------
* Friswell et al. (2010), Example 5.9.1 (the friswell-rotor case, undamped, isotropic): its 1x
  critical speeds as printed by ROSS's port of the example (see test_linear_friswell.py),
  825.13381 (backward), 829.87446 (forward), 2487.75884 (backward), 2756.08756 (forward) rpm.
  On isotropic supports unbalance (a forward 1x force) excites forward whirl only (Friswell et
  al. 2010, Section 3.5): the backward ones are listed after, marked not excited.
* Closed form: a rigid mass on an isotropic damped bearing, lambda = -zeta w_n +- i w_n
  sqrt(1 - zeta^2); its damped crossing of the 1x line is w_n sqrt(1 - zeta^2), its undamped
  critical speed w_n.
* Definition: at a damped crossing Omega_d the damped rotor has a mode with |Im lambda| = Omega_d
  (checked with an independent eigen-solve, rotorlab.linear.modal), and its damping ratio is
  that mode's -Re lambda / |lambda|.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import critical_summary, summarize_linear
from rotorlab.cli import app
from rotorlab.io import load_case
from rotorlab.linear import RPM, Bearing, RigidBody, assemble, campbell, critical_speeds, modal
from rotorlab.linear.cases import friswell_rotor

PUBLISHED_RPM = [825.13381, 829.87446, 2487.75884, 2756.08756]  # B F B F
NOTE = "not excited by unbalance on isotropic supports"
runner = CliRunner()


def test_friswell_undamped_values_whirl_and_excitation():
    cs = critical_speeds(friswell_rotor(), max_speed=4000 * RPM)
    np.testing.assert_allclose(cs.speed_rpm, PUBLISHED_RPM, rtol=1e-7)
    assert cs.whirl.tolist() == [-1, 1, -1, 1] and cs.isotropic
    assert cs.excited.tolist() == [False, True, False, True]
    # undamped rotor: the damped crossing is the undamped critical speed, damping ratio 0
    np.testing.assert_allclose(cs.damped_speed, cs.speed, rtol=1e-9)
    np.testing.assert_array_equal(cs.damping_ratio, 0.0)
    ds = cs.to_dataset()
    assert ds.critical_speed_rpm.attrs["definition"].startswith("undamped")
    assert ds.damped_crossing_rpm.attrs["definition"].startswith("damped crossing")


def test_friswell_campbell_json_lists_forward_first_and_marks_backward():
    res = runner.invoke(app, ["campbell", "friswell-rotor", "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["critical_speed_definition"] == "damped crossing"
    entries = doc["critical_speeds"]
    assert [e["whirl"] for e in entries] == ["F", "F", "B", "B"]
    np.testing.assert_allclose([e["speed_rpm"] for e in entries],
                               [PUBLISHED_RPM[i] for i in (1, 3, 0, 2)], rtol=1e-7)
    assert [e["excited_by_unbalance"] for e in entries] == [True, True, False, False]
    assert [e["note"] for e in entries] == ["", "", NOTE, NOTE]
    assert all(e["definition"] == "damped crossing" for e in entries)
    # the legacy list keeps its order (ascending) and unit-suffixed name
    assert doc["critical_speeds_rpm"] == pytest.approx(PUBLISHED_RPM, rel=1e-7)


def test_friswell_console_table_says_definition_and_note():
    res = runner.invoke(app, ["campbell", "friswell-rotor"], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.output
    assert "damped crossing" in res.stdout and "* " + NOTE in res.stdout
    lines = [ln for ln in res.stdout.splitlines() if " 1x " in ln and "crossing" in ln]
    assert [("forward" in ln, "no *" in ln) for ln in lines[:4]] == [
        (True, False), (True, False), (False, True), (False, True)]


def test_damped_friswell_gives_both_values_with_the_damping_ratio():
    """Bearings damped (3 kN s/m each, Friswell et al. 2010 Example 5.9.5's variant): the second
    forward crossing moves from 2756 rpm (undamped) to 2979 rpm, 8 % away: both are given."""
    s = friswell_rotor(bearing_damping=3e3)
    cs = critical_speeds(s, max_speed=4000 * RPM)
    np.testing.assert_allclose(cs.speed_rpm, PUBLISHED_RPM, rtol=1e-7)  # damping ignored
    for w_d, zeta, whirl in zip(cs.damped_speed, cs.damping_ratio, cs.whirl):
        m = modal(s, w_d)
        k = int(np.argmin(np.abs(np.abs(m.eigenvalues.imag) - w_d)))
        assert abs(abs(m.eigenvalues[k].imag) - w_d) <= 1e-8 * w_d  # the definition
        assert zeta == pytest.approx(-m.eigenvalues[k].real / abs(m.eigenvalues[k]), rel=1e-6)
        assert m.whirl[k] == whirl
    assert cs.damped_speed_rpm[3] == pytest.approx(2979.29, rel=1e-5)
    assert cs.damping_ratio[3] == pytest.approx(0.2453, abs=2e-4)
    # the Campbell diagram's crossings are these damped crossings, with the undamped beside them
    ds = campbell(s, RPM * np.linspace(0.0, 4000.0, 41), n_modes=6)
    ds.attrs["analysis"] = "campbell"
    rows = summarize_linear(ds)
    fwd = [r for r in rows if r["whirl"] == "F"]
    assert fwd[1]["speed_rpm"] == pytest.approx(cs.damped_speed_rpm[3], rel=1e-8)
    assert fwd[1]["undamped_rpm"] == pytest.approx(PUBLISHED_RPM[3], rel=1e-7)
    assert fwd[1]["both_shown"] and not fwd[0]["both_shown"]  # 0.7 % apart at the first
    assert fwd[1]["damping_ratio"] == pytest.approx(cs.damping_ratio[3], rel=1e-4)


def test_closed_form_damped_crossing_of_a_mass_on_a_damped_bearing():
    m, k, zeta = 2.0, 800.0, 0.3
    c = 2 * zeta * math.sqrt(k * m)
    s = assemble([RigidBody(0, m, 1e-3), Bearing(0, kxx=k, cxx=c, k_tilt_x=1.0)])
    cs = critical_speeds(s)
    wn = math.sqrt(k / m)
    lateral = np.isclose(cs.speed, wn, rtol=1e-12)
    assert lateral.sum() == 2  # forward and backward
    np.testing.assert_allclose(cs.damped_speed[lateral], wn * math.sqrt(1 - zeta ** 2), rtol=1e-9)
    np.testing.assert_allclose(cs.damping_ratio[lateral], zeta, rtol=1e-9)


def test_validate_json_carries_units_and_definitions():
    res = runner.invoke(app, ["validate", "autobalancer", "--json"])
    doc = json.loads(res.stdout)
    assert doc["critical_speed_rpm"] == pytest.approx(doc["critical_speed"] * 60 / (2 * math.pi))
    assert doc["critical_speed_rpm"] == pytest.approx(1200.04, rel=1e-5)  # sqrt(k/M), seed 002
    assert doc["critical_speed_definition"] == "undamped"
    doc = critical_summary(load_case("friswell-rotor").model)
    assert [e["whirl"] for e in doc["critical_speeds"]][-3:] == ["B", "B", "B"]
    assert doc["critical_speeds"][0]["speed_rpm"] == pytest.approx(PUBLISHED_RPM[1], rel=1e-7)


def test_rigid_drum_forward_tilt_crossing_is_the_closed_form():
    """washer-horizontal's drum (I_d = 1.5, I_p = 0.8 kg m^2, k_tilt = 3 kN m/rad, undamped in
    tilt): its forward tilt mode meets the 1x line at sqrt(k_tilt / (I_d - I_p)) = 625.15 rpm
    (rigid rotor, Friswell et al. 2010 Section 3.5), by both definitions. The solver tracks the
    forward and the backward tilt with one vector; the crossing was taken on the backward mode
    and reported at the grid speed 600 rpm before (and the damped crossing of the forward tilt at
    the backward one's 345 rpm)."""
    from rotorlab.analyses import build_linear_system

    s = build_linear_system(load_case("washer-horizontal").model.linear_structure())
    expect = math.sqrt(3e3 / 0.7) / RPM
    cs = critical_speeds(s)
    fwd_tilt = np.isclose(cs.speed_rpm, expect, rtol=1e-9)
    assert fwd_tilt.sum() == 1 and cs.whirl[fwd_tilt][0] == 1
    assert cs.damped_speed_rpm[fwd_tilt][0] == pytest.approx(expect, rel=1e-9)
    ds = campbell(s, RPM * np.linspace(0.0, 1500.0, 31), n_modes=4)
    fwd = ds.critical_speed_rpm.values[ds.critical_whirl.values == 1]
    assert fwd.max() == pytest.approx(expect, rel=1e-9)
    # translation: w_n = sqrt(k / m) = 238.7 rpm undamped, zeta = 0.2: damped crossing
    # w_n sqrt(1 - zeta^2) = 233.9 rpm (2 % apart: one value shown)
    assert fwd.min() == pytest.approx(math.sqrt(25e3 / 40) * math.sqrt(1 - 0.04) / RPM, rel=1e-9)
