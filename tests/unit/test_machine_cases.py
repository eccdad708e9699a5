"""The machine model in case files: built-in cases, variants, errors with key paths."""

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import run_analysis, summarize
from rotorlab.cli import app
from rotorlab.io import CaseError, load_case, parse_case



def test_builtin_machine_cases_validate_and_build():
    for name, n_state in (("pico21-balancer", 2 * 6 + 2 * 4), ("washer-horizontal", 8 + 4 + 2)):
        case = load_case(name)
        from rotorlab.analyses import build_model

        m = build_model(case.model)
        assert m.n_state == n_state
    pico = build_model(load_case("pico21-balancer").model)
    # the case file's statement: 12 modes instead of 6 move the unbalance response at 10000 rpm
    # by about 3 % (2.85 %)
    assert 0.02 < pico.reduction_change(2 * np.pi * 10000 / 60) < 0.03


def test_no_steady_motion_under_gravity_across_the_axis_is_refused_with_the_reason():
    text = load_case("washer-horizontal").text + '[[analysis]]\ntype = "steady"\nspeed = "100 rad/s"\n'
    with pytest.raises(CaseError) as err:
        parse_case(text)
    assert "gravity acts across the axis" in str(err.value) and "simulate" in str(err.value)
    res = CliRunner().invoke(app, ["steady", "washer-horizontal", "--speed-rpm", "1000"])
    assert res.exit_code == 2 and "gravity acts across the axis" in res.output
    assert "Traceback" not in res.output


def test_two_race_variant_balances_exactly_and_a_flat_rotor_loses_it_at_speed():
    """Pico 21's centrifuge rotor is flat (I_p = 1529 > I_d = 882 kg mm^2): its two-plane balanced
    state is stable in a band above the critical speeds and unstable at the top speed, as
    Rodrigues et al. (2008, Section 5) find for disc-like rotors; one race leaves the couple."""
    case = load_case("pico21-balancer")
    two = case.analysis("stability-two-races").model_copy(update={"speeds": (4000 * np.pi / 30,
                                                                               14000 * np.pi / 30, 2)})
    rows = summarize(run_analysis(case.model, two))
    assert [r["balanced"] for r in rows] == [True, True]
    assert [r["stable"] for r in rows] == [True, False]
    assert all(a == 0.0 for r in rows for a in r["amplitude"].values())
    one = case.analysis("stability-one-race").model_copy(update={"speeds": (10000 * np.pi / 30,
                                                                             10000 * np.pi / 30, 1)})
    (row,) = summarize(run_analysis(case.model, one))
    assert row["exists"] and not row["balanced"] and row["stable"]
    assert 1e-8 < row["amplitude"]["stator"] < 1e-6  # the couple is left: 0.3 um at the stator


def test_bad_machine_input_names_the_key_path():
    text = load_case("washer-horizontal").text
    bad = text.replace('at = "drum"\nradius', 'at = "drun"\nradius', 1)
    with pytest.raises(CaseError) as err:
        parse_case(bad)
    assert "model.races[0].at" in str(err.value) and "drum" in str(err.value)
    bad = text.replace("races = []", "races = [3]")
    with pytest.raises(CaseError) as err:
        parse_case(bad)
    assert "races[0]" in str(err.value) and "must be < 1" in str(err.value)
    bad = text.replace('damping = "0.05 N*m*s/rad", count = 2', 'damping = "0.05 N*m*s/rad", coulomb = -0.1, count = 2')
    with pytest.raises(CaseError) as err:
        parse_case(bad)
    assert "model.races[0].balls[0].coulomb" in str(err.value) and ">= 0" in str(err.value)
    good = text.replace('damping = "0.05 N*m*s/rad", count = 2',
                        'damping = "0.05 N*m*s/rad", coulomb = 0.1, rolling = "1 mm", count = 2')
    balls = parse_case(good).model.races[0].balls
    assert [(b.coulomb, b.rolling) for b in balls] == [(0.1, 1e-3)] * 2


def test_cli_validate_bad_machine_case_exits_2(tmp_path):
    text = load_case("washer-horizontal").text.replace('stall_torque = "10 N*m"\n', "")
    path = tmp_path / "w.toml"
    path.write_text(text)
    res = CliRunner().invoke(app, ["validate", str(path)])
    assert res.exit_code == 2
    assert "stall_torque" in res.output


def test_readme_machine_case_and_python_example():
    """The README's 'Put a balancer on your own rotor' case validates and its Python runs."""
    import re
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    sec = re.search(r"^## Put a balancer on your own rotor\n(.*?)(?=^## )", readme, re.S | re.M)[1]
    (toml,) = re.findall(r"^```toml\n(.*?)^```", sec, re.S | re.M)
    case = parse_case(toml)
    assert case.model.type == "machine" and [a.type for a in case.analyses] == ["stability-chart", "simulate"]
    # its start-ups balance as the README promises: each start ends in the balanced state of two
    # equal balls, U + 2 m l cos(psi) = 0 (psi = +-128.68 deg for U = 1.5 g m, m = 20 g, l = 60 mm),
    # which the slowest ball mode (Re = -2.49 1/s at 3000 rpm) reaches well within t_end = 4 s
    (ball,) = case.model.races[0].balls[:1]
    psi = np.arccos(-case.model.unbalances[0].magnitude / (2 * ball.mass * case.model.races[0].radius))
    assert np.degrees(psi) == pytest.approx(128.68, abs=0.01)
    start_up = run_analysis(case.model, case.analysis("start-up"))
    rows = summarize(start_up)
    assert [r["outcome"] for r in rows] == ["balanced", "balanced"] and all(r["status"] == 0 for r in rows)
    np.testing.assert_allclose(np.sort(np.abs(start_up.final_ball_angle.values), axis=1), psi, atol=1e-6)
    (code,) = re.findall(r"^```python\n(.*?)^```", sec, re.S | re.M)
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README", "exec"), {})  # noqa: S102
    # 314 rad/s against a critical speed sqrt(2e5 / 8.04) = 158 rad/s: above it, stable
    assert out.getvalue().strip() == "True"


FE_MACHINE = """
schema_version = 1
name = "fe-machine"

[model]
type = "machine"

[model.structure]
type = "fe_rotor"
material = { youngs_modulus = "211 GPa", shear_modulus = "81.2 GPa", density = "7810 kg/m^3" }
shaft = [{ length = "1.5 m", outer_diameter = "50 mm", elements = 12 }]
discs = [{ name = "disc", position = "0.75 m", outer_diameter = "280 mm", width = "70 mm", inner_diameter = "50 mm" }]
bearings = [{ name = "A", position = "0 m", kxx = "1 MN/m" }, { name = "B", position = "1.5 m", kxx = "1 MN/m" }]

[[model.races]]
at = "disc"
radius = "100 mm"
balls = [{ mass = "20 g", count = 2 }]

[model.drive]
profile = "constant"
speed = "3000 rpm"
"""


def test_n_modes_the_machine_cannot_take_is_a_case_error_not_a_crash(tmp_path):
    """What ``Machine`` refuses about ``n_modes`` is refused by the case with its key path and
    exit code 2 (before, the model raised on build: 'internal error', exit code 1): an odd count on
    an isotropic structure (its modes come in x/y pairs), and none for a structure with more DOFs
    than the compiled kernel takes (12 Timoshenko elements: 13 nodes x 4 = 52 DOFs > 40)."""
    with pytest.raises(CaseError) as err:
        load_case("pico21-balancer", overrides={"model.n_modes": 3})
    assert "model.n_modes = 3: must be even for an isotropic structure" in str(err.value)
    assert load_case("pico21-balancer", overrides={"model.n_modes": 4}).model.n_modes == 4
    with pytest.raises(CaseError) as err:
        parse_case(FE_MACHINE)
    assert "model.n_modes: required: the structure has 52 DOFs" in str(err.value)
    assert parse_case(FE_MACHINE.replace('type = "machine"\n', 'type = "machine"\nn_modes = 8\n')).model.n_modes == 8
    path = tmp_path / "fe.toml"
    path.write_text(FE_MACHINE)
    for args in (["validate", str(path)], ["simulate", "pico21-balancer", "--set", "model.n_modes=3"]):
        res = CliRunner().invoke(app, args)
        assert res.exit_code == 2 and "model.n_modes" in res.output and "internal error" not in res.output


def test_derived_quantities_give_the_static_unbalance_and_the_reduction_check():
    """Pico 21's unbalances: 50 g mm static plus a couple of 20 g mm at phases 90 and 270 deg
    (at +-15 mm): the static resultant a race must cancel is |50 + 20 i - 20 i| = 50 g mm, not the
    sum of magnitudes 90 g mm; its structure is reduced to 6 modes, and the report says how much
    the unbalance response at the drive speed moves when they double (the case file: 2.8 %)."""
    from rotorlab.analyses import build_model
    from rotorlab.analyses._machine_common import machine_quantities

    case = load_case("pico21-balancer")
    rows = {r["quantity"]: r["value"] for r in machine_quantities(case.model)}
    assert rows["static unbalance |sum m e exp(i phase)|"] == pytest.approx(50e-6, rel=1e-12)
    change = rows["change of the unbalance response at the drive speed when n_modes = 6 doubles"]
    assert change == build_model(case.model).reduction_change(10000 * np.pi / 30)
    assert 0.02 < change < 0.03
    rows = {r["quantity"] for r in machine_quantities(load_case("rcfw-two-plane").model)}
    assert not any("n_modes" in q for q in rows)  # unreduced: nothing to check


def test_a_stability_chart_verdict_does_not_depend_on_the_speeds_before_it():
    """Several partly balanced steady motions coexist (Pico 21 with one race: the couple is left);
    each speed of a chart is solved on its own, so 2300 rpm gets the same motion and verdict in a
    chart from 1300 rpm as alone (continuing the motion from speed to speed stayed on an unstable
    branch from 1700 to 2400 rpm while the motion found at each speed alone is stable there)."""
    case = load_case("pico21-balancer")
    one = case.analysis("stability-one-race")

    def chart(lo, hi, n):
        a = one.model_copy(update={"speeds": (lo * np.pi / 30, hi * np.pi / 30, n)})
        return {round(r["speed"] * 30 / np.pi): r for r in summarize(run_analysis(case.model, a))}

    long, alone = chart(1300, 2400, 12), chart(2300, 2400, 2)
    for rpm in (2300, 2400):
        assert long[rpm]["exists"] and alone[rpm]["exists"]
        assert long[rpm]["stable"] == alone[rpm]["stable"]
        np.testing.assert_allclose(long[rpm]["ball_angles_deg"]["race 0"], alone[rpm]["ball_angles_deg"]["race 0"],
                                   atol=1e-6)
