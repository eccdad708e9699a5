"""Run-up objectives and the ``no-housing-contact`` constraint inside ``rotorlab design`` (issue 27
items 1-2), from the command line and from Python, varying named-parameter key paths.

The machine: a 1 kg disc on 1 N/m (critical speed 1 rad/s, damping 0.05 N s/m), unbalance
U = 0.05 kg m, in a rigid housing with a radial clearance g, run up by a servo drive at
0.001 rad/s^2 to 0.5 rad/s (subcritical). The ramp is slow, so the orbit follows the steady
unbalance response, whose radius at the operating speed is the closed form

    r = U w^2 / |k - M w^2 + i c w| = 0.05 * 0.25 / |0.75 + 0.025 i| = 16.657 mm,

and the run-up touches the housing exactly when g <= r (to within the transient left by the
ramp's end: measured 1.1 % of r at this rate, 5.6 % at 0.005 rad/s^2, shrinking with the rate).
The margin of a clear design is (g - d_max) / g; a design whose run-up touched has minus the
share of run-ups that touched (-1: its one run-up).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

runner = CliRunner()

U, W, K, M, C = 0.05, 0.5, 1.0, 1.0, 0.05
R = U * W**2 / abs(K - M * W**2 + 1j * C * W)  # 16.657 mm
OVERSHOOT = 0.012  # the ramp end's transient, relative (1.1 % measured)

CASE = f"""schema_version = 1
name = "disc-housing"
description = "1 kg disc on 1 N/m in a housing, servo-driven to 0.5 rad/s"

[model]
type = "machine"

[model.structure]
type = "multibody"

[[model.structure.bodies]]
name = "disc"
position = "0 m"
mass = "{M} kg"
diametral_inertia = "0.3 kg*m^2"
polar_inertia = "0.05 kg*m^2"

[[model.structure.bearings]]
body = "disc"
kxx = "{K} N/m"
cxx = "{C} N*s/m"
k_tilt_x = "5 N*m/rad"

[[model.unbalances]]
at = "disc"
magnitude = "{U} kg*m"

[[model.clearances]]
at = "disc"
gap = "20 mm"

[model.drive]
profile = "servo"
stall_torque = "0.05 N*m"
operating_speed = "{W} rad/s"
ramp_rate = "0.001 rad/s^2"
gain = "50 N*m*s/rad"
polar_inertia = "0.05 kg*m^2"
"""


@pytest.fixture(scope="module")
def case_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("housing") / "case.toml"
    path.write_text(CASE, encoding="utf-8")
    return path


def _check_rows(rows, name):
    """Every design against the closed form: clear above r (1 + overshoot), touched at or below r."""
    clear = touched = 0
    for row in rows:
        g, margin = row["values"][name], row["margins"]["constraints.no-housing-contact"]
        if g >= R * (1 + OVERSHOOT):
            clear += 1
            assert row["feasible"] and margin == pytest.approx((g - R) / g, abs=OVERSHOOT * R / g)
        elif g <= R:
            touched += 1
            assert not row["feasible"] and margin == -1.0
    assert clear and touched, rows
    best = [r for r in rows if r["best"]]
    assert len(best) == 1 and best[0]["feasible"]
    assert best[0]["objectives"]["run-up-time"] == min(r["objectives"]["run-up-time"] for r in rows if r["feasible"])


def test_housing_contact_boundary_is_the_steady_deflection_from_the_command_line(case_path, tmp_path):
    res = runner.invoke(app, ["design", str(case_path), "--vary", "model.clearances[0].gap=13mm:22mm",
                              "--objective", "run-up-time", "--constraint", "no-housing-contact", "--starts", "1",
                              "--budget", "8", "--json", "--out", str(tmp_path / "d.nc")])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    _check_rows(doc["rows"], "model.clearances[0].gap")
    # the run-up time: 99 % of 0.5 rad/s at 0.001 rad/s^2 (the loop's lag J / K_loop = 1 ms aside)
    assert doc["winner"]["objectives"]["run-up-time"] == pytest.approx(0.99 * W / 0.001, rel=1e-3)
    assert "housing contact checked only on those run-ups" in _not_explored(tmp_path / "d.nc")


def _not_explored(path):
    import xarray as xr

    from rotorlab.report._design import not_explored

    with xr.open_dataset(path) as ds:
        return not_explored(ds.load())


def test_housing_contact_boundary_from_python_with_the_machine_s_key_path(case_path):
    from rotorlab.analyses import DesignProblem, DesignVariable, build_model, design_search
    from rotorlab.analyses._design_case import design_rows
    from rotorlab.design import RunUpSettings
    from rotorlab.io import load_case

    machine = build_model(load_case(case_path).model)
    problem = DesignProblem(machine, (DesignVariable("clearances[0].gap", 0.013, 0.022),), ("run-up-time",),
                            np.array([W]), constraints=("no-housing-contact",), run_up=RunUpSettings(starts=1))
    ds = design_search(problem, budget=6, optimizer_seed=3)
    _check_rows(design_rows(ds), "clearances[0].gap")


def test_contact_constraint_and_run_up_objectives_are_refused_where_they_cannot_apply():
    from rotorlab.analyses import DesignProblem, DesignVariable
    from rotorlab.linear import LinearSystem
    from rotorlab.models import ConstantSpeed, Machine, ServoDrive, Unbalance

    s = LinearSystem(M=np.eye(4), C=np.zeros((4, 4)), G=np.zeros((4, 4)), K=np.eye(4))
    servo = Machine(s, unbalances=(Unbalance(0, 0.01),), drive=ServoDrive(1.0, polar_inertia=0.1, operating_speed=2.0))
    var = (DesignVariable("drive.ramp_rate", 0.1, 1.0),)
    with pytest.raises(ValueError, match="constraints: 'no-housing-contact' needs a machine with a clearance"):
        DesignProblem(servo, var, ("run-up-time",), np.array([2.0]), constraints=("no-housing-contact",))
    with pytest.raises(ValueError, match="constraints: 'touch' is not a constraint .allowed: no-housing-contact"):
        DesignProblem(servo, var, ("run-up-time",), np.array([2.0]), constraints=("touch",))
    fixed = Machine(s, unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(2.0))
    with pytest.raises(ValueError, match="objectives: 'run-up-time' needs a machine driven by a ServoDrive"):
        DesignProblem(fixed, (DesignVariable("unbalances[0].magnitude", 0.01, 0.02),), ("run-up-time",),
                      np.array([2.0]))
