"""The common analysis types on the composed machine: campbell/modes of its structure, steady,
stability-chart, simulate and run-up through the registries and the command line.

The planar machine here is the Jeffcott rotor with two balls (disc M1 = 1 kg on c = 1 N/m, d =
0.1 N s/m, unbalance M1 e = 0.01 kg m, two 0.02 kg balls on a 1 m race): its balanced state has the
balls at psi = +-arccos(-M1 e / (2 m l)) from the unbalance (Zhakash et al. 2024, eq. (22) as
corrected in rotorlab.models._jeffcott_balls) and is unstable below p = sqrt(c / (M1 + 2 m)).
"""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import run_analysis, summarize
from rotorlab.cli import app
from rotorlab.io import CampbellSpec, CaseError, load_case, parse_case

PLANAR = """
schema_version = 1
name = "planar-machine"

[model]
type = "machine"
# the two translation modes (the tilt at sqrt(5 / 0.3) = 4.1 rad/s does not couple): the same
# compiled kernel as the machines of test_machine_analyses.py
n_modes = 2

[model.structure]
type = "multibody"

[[model.structure.bodies]]
name = "disc"
position = "0 m"
mass = "1 kg"
diametral_inertia = "0.3 kg*m^2"
polar_inertia = "0 kg*m^2"
spinning = false

[model.structure.elastic]
stiffness = [["1 N/m", "0 N/rad"], ["0 N/rad", "5 N*m/rad"]]
damping = [["0.1 N*s/m", "0 N*s/rad"], ["0 N*s/rad", "0.05 N*m*s/rad"]]

[[model.races]]
at = "disc"
radius = "1 m"
balls = [{ mass = "0.02 kg", damping = "0.05 N*m*s/rad", count = 2 }]

[[model.unbalances]]
at = "disc"
magnitude = "0.01 kg*m"
phase = "30 deg"

[model.drive]
profile = "constant"
speed = "2.5 rad/s"

[[analysis]]
type = "steady"
name = "above"
speed = "2.5 rad/s"

[[analysis]]
type = "steady"
name = "below"
speed = "0.8 rad/s"

[[analysis]]
type = "stability-chart"
name = "chart"
speeds = ["0.8 rad/s", "2.5 rad/s", 3]
param = "ball_mass"
values = ["0.02 kg", "0.04 kg", 2]

[[analysis]]
type = "simulate"
name = "starts"
initial_ball_angles = [["47 deg", "145 deg"], ["-113 deg", "87 deg"], ["36 deg", "36 deg"]]
t_end = "3000 s"

[[analysis]]
type = "simulate"
name = "grid"
ball_angle_grid = 3
t_end = "3000 s"

[[analysis]]
type = "basin"
name = "basin"
x = ["psi_1", "0 deg", "240 deg", 3]
y = ["psi_2", "0 deg", "240 deg", 3]
t_end = "3000 s"
n_horizons = 2
"""
P = 1.0 / math.sqrt(1.04)  # rad/s
PSI = math.degrees(math.acos(-0.01 / (2 * 0.02 * 1.0)))  # 104.48 deg from the unbalance


@pytest.fixture(scope="module")
def planar():
    return parse_case(PLANAR)


def _sorted(angles):
    return sorted(round(a, 6) for a in angles)


def test_campbell_and_modes_of_a_machine_are_those_of_its_structure():
    """rcfw-two-plane: the rigid rotor on k = 1 N/m, c = 0.02 N s/m (translation) and 9 N m/rad,
    0.18 N m s/rad (tilt) at rest has the damped frequencies w_n sqrt(1 - zeta^2) with w_n =
    sqrt(k / M) = 1 rad/s, zeta = c / (2 sqrt(k M)) = 0.01 and w_n = sqrt(9 / 3.25) = 1.664 rad/s,
    zeta = 0.18 / (2 sqrt(9 * 3.25)) (the balls are attachments, not part of the structure)."""
    from rotorlab.analyses import run_linear_analysis

    case = load_case("rcfw-two-plane")
    spec = CampbellSpec(name="cb", start=0.0, stop=3.0, n_speeds=4, n_modes=4)
    ds = run_analysis(case.model, spec)
    ref = run_linear_analysis(case.model.structure, spec)
    np.testing.assert_array_equal(ds.frequency.values, ref.frequency.values)
    zeta = 0.18 / (2 * math.sqrt(9 * 3.25))
    expect = [math.sqrt(1 - 0.01**2)] * 2 + [math.sqrt(9 / 3.25) * math.sqrt(1 - zeta**2)] * 2
    np.testing.assert_allclose(ds.frequency.values[0] * 2 * np.pi, expect, rtol=1e-12)
    res = CliRunner().invoke(app, ["-q", "modes", "rcfw-two-plane", "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    np.testing.assert_allclose(np.array(doc["frequency_hz"]) * 2 * np.pi, expect, rtol=1e-12)


def test_steady_motions_of_the_planar_machine_are_the_seeds_with_their_verdicts(planar):
    rows = summarize(run_analysis(planar.model, planar.analysis("above")))
    # seed 002's four motions of two balls: two mirror balanced ones (the balls at 30 deg, the
    # unbalance, + pi -+ 75.5 deg) and the side motions (balls on the line through the unbalance)
    assert [r["label"] for r in rows] == ["main+", "main-", "side 00", "side 01", "side 10", "side 11"]
    assert all(r["exists"] for r in rows)
    above = [r for r in rows if r["kind"] == "balanced"]
    assert len(above) == 2
    for r in rows[2:]:  # the machine finds each side motion again; all three verdicts: unstable
        assert (r["verdict_exact"], r["verdict_hamilton"], r["verdict_averaged"]) == ("unstable",) * 3
        assert r["max_real_eigenvalue"] > 0
    for r in above:
        (angles,) = r["ball_angles_deg"].values()
        rel = [((a - 30.0 + 180.0) % 360.0) - 180.0 for a in angles]
        np.testing.assert_allclose(_sorted(rel), [-PSI, PSI], atol=2e-6)
        assert all(v == 0.0 for v in r["amplitude"].values())
        # above p all three verdicts say stable (seed 002 averaged, seed 003 Hamilton, exact)
        assert (r["verdict_exact"], r["verdict_hamilton"], r["verdict_averaged"]) == ("stable",) * 3
        assert r["max_real_eigenvalue"] < -1e-4  # every mode damped (tilt included)
    # below p = 0.98 rad/s (seed 002): the balanced motions are unstable and the one with both
    # balls on the unbalance's side ("side 00") is stable, by the seeds' verdicts and exactly
    below = {r["label"]: r for r in summarize(run_analysis(planar.model, planar.analysis("below")))}
    assert 0.8 < P
    for label, verdict in (("main+", "unstable"), ("main-", "unstable"), ("side 00", "stable")):
        r = below[label]
        assert (r["verdict_exact"], r["verdict_hamilton"], r["verdict_averaged"]) == (verdict,) * 3
    (side,) = below["side 00"]["ball_angles_deg"].values()
    assert side[0] == pytest.approx(side[1], abs=1e-9)


def test_no_steady_motion_on_anisotropic_supports_exits_2_naming_why(tmp_path):
    path = tmp_path / "aniso.toml"
    path.write_text(PLANAR.replace('stiffness = [["1 N/m", "0 N/rad"], ["0 N/rad", "5 N*m/rad"]]',
                                   'stiffness = [["1 N/m", "0 N/rad"], ["0 N/rad", "5 N*m/rad"]]\n'
                                   'stiffness_y = [["1.3 N/m", "0 N/rad"], ["0 N/rad", "5 N*m/rad"]]'))
    res = CliRunner().invoke(app, ["validate", str(path)])
    assert res.exit_code == 2 and "anisotropic" in res.output and "simulate" in res.output, res.output


def test_seed_verdicts_are_refused_with_the_reason_off_the_planar_rotor():
    case = parse_case(load_case("rcfw-two-plane").text + '[[analysis]]\ntype = "steady"\nspeed = "4 rad/s"\n')
    rows = summarize(run_analysis(case.model, case.analyses[-1]))
    # two races, each with its mirror pair: 4 balanced motions, all at pi +- 60 deg (eq. (16))
    assert len(rows) == 4 and all(r["verdict_hamilton"] == "n/a" for r in rows)
    assert "only the exact eigenvalues" in rows[0]["seed_verdicts"]
    for r in rows:
        for angles in r["ball_angles_deg"].values():
            np.testing.assert_allclose(_sorted(angles), [-120.0, 120.0], atol=2e-6)


def test_stability_chart_over_speed_and_ball_mass(planar):
    rows = summarize(run_analysis(planar.model, planar.analysis("chart")))
    assert [r["ball_mass"] for r in rows] == [0.02] * 3 + [0.04] * 3
    # p = sqrt(1 / (1 + 2 m)): 0.962 and 0.928 rad/s; stable above (1.65, 2.5), not at 0.8
    assert [r["stable"] for r in rows] == [False, True, True] * 2
    for r, m in zip(rows, [0.02] * 3 + [0.04] * 3):
        (angles,) = r["ball_angles_deg"].values()
        rel = [((a - 30.0 + 180.0) % 360.0) - 180.0 for a in angles]
        psi = math.degrees(math.acos(-0.01 / (2 * m)))
        np.testing.assert_allclose(_sorted(rel), [-psi, psi], atol=2e-6)


def test_simulate_json_gives_angles_per_race_vibration_per_station_and_the_outcome(planar, tmp_path):
    path = tmp_path / "planar.toml"
    path.write_text(PLANAR)
    res = CliRunner().invoke(app, ["-q", "simulate", str(path), "--json"])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.output)["rows"]
    assert [r["outcome"] for r in rows] == ["balanced", "balanced", "not balanced"]
    for r in rows[:2]:
        rel = [((a - 30.0 + 180.0) % 360.0) - 180.0 for a in r["final_ball_angles_deg"]["race 0"]]
        np.testing.assert_allclose(_sorted(rel), [-PSI, PSI], atol=1e-3)
        assert r["amplitude"]["disc"] < 1e-3 * r["reference_amplitude"]["disc"]
    # the balls started together stay together (an invariant set): opposite the unbalance's
    # response, not balanced
    final = rows[2]["final_ball_angles_deg"]["race 0"]
    assert final[0] == pytest.approx(final[1], abs=1e-9)
    # the locked unbalance response U w^2 / |c - M w^2 + i d w|, M = 1.04 kg
    ref = 0.01 * 2.5**2 / abs(1.0 - 1.04 * 2.5**2 + 0.1j * 2.5)
    assert rows[0]["reference_amplitude"]["disc"] == pytest.approx(ref, rel=1e-12)


def test_run_up_command_on_a_machine_and_a_rotor_with_balls():
    res = CliRunner().invoke(app, ["-q", "run-up", "washer-horizontal", "--analysis", "run-up-no-balls",
                                   "--t-end", "3", "--json"])
    assert res.exit_code == 0, res.output
    (row,) = json.loads(res.output)["rows"]
    # the suspension's critical speed sqrt(25e3 / 40) = 25 rad/s: passed within 3 s
    assert row["critical_speeds"][0] == pytest.approx(25.0, rel=1e-12) and row["passed"] == 1
    res = CliRunner().invoke(app, ["run-up", "pico21"])
    assert res.exit_code == 2 and "no run-up analysis" in res.output


def test_basin_over_the_ball_angles_agrees_with_simulate_from_the_same_starts(planar):
    """A 3 x 3 grid of the two ball angles (0, 120, 240 deg): the starts with both balls together
    (the diagonal, an invariant set) cannot balance, the six others balance; ``simulate`` from the
    same starts (``ball_angle_grid = 3``) labels each start the same way."""
    basin = run_analysis(planar.model, planar.analysis("basin"))
    rows = {r["regime"]: r for r in summarize(basin)}
    assert rows["balanced"]["count"] == 6 and rows["not balanced"]["count"] == 3
    assert rows["balanced"]["fraction"] == pytest.approx(6 / 9, abs=1e-15)
    labels = [str(r) for r in basin["regime"].values]
    grid = summarize(run_analysis(planar.model, planar.analysis("grid")))
    angles = [0.0, 120.0, 240.0]
    for r in grid:  # simulate's order: psi_1 slowest, psi_2 fastest
        i, j = divmod(r["ic"], 3)
        expect = labels[int(basin.outcome.sel(psi_1=math.radians(angles[i]), psi_2=math.radians(angles[j]),
                                              method="nearest"))]
        assert r["outcome"] == expect, (r["ic"], r["outcome"], expect)


def test_sweep_over_ball_mass_finds_the_capacity_limit(tmp_path):
    """The two balls can cancel the unbalance only if 2 m l >= M1 e, i.e. m >= 0.005 kg: at
    m = 0.004 kg they cannot (not balanced), at 0.02 kg they do (one start, psi = 46, 149 deg)."""
    path = tmp_path / "planar.toml"
    path.write_text(PLANAR)
    res = CliRunner().invoke(app, ["-q", "sweep", str(path), "--out", str(tmp_path / "s.zarr"), "--param",
                                   "ball_mass=0.004:0.02:2", "--ic", "psi_1=0.8:0.8:1", "--ic", "psi_2=2.6:2.6:1",
                                   "--t-end", "3000", "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["dims"] == ["ball_mass", "psi_1", "psi_2"] and doc["n"] == 2
    assert doc["fractions"]["balanced"] == 0.5 and doc["fractions"]["not balanced"] == 0.5
    import xarray as xr

    ds = xr.open_zarr(tmp_path / "s.zarr", consolidated=False)
    labels = ds.attrs["result_attrs"]["labels"]
    assert [labels[int(k)] for k in ds.outcome.values] == ["not balanced", "balanced"]


def test_sweep_over_any_number_of_the_model_by_key_path(tmp_path):
    """``model.unbalances[0].magnitude`` (with a unit, as in the case file): the two balls' capacity
    is 2 m l = 0.04 kg m, so 10 g m is balanced and 60 g m is not; the store carries its unit."""
    path = tmp_path / "planar.toml"
    path.write_text(PLANAR)
    store = tmp_path / "k.zarr"
    res = CliRunner().invoke(app, ["-q", "sweep", str(path), "--out", str(store), "--param",
                                   "model.unbalances[0].magnitude=10 g*m:60 g*m:2", "--ic", "psi_1=0.8:0.8:1",
                                   "--ic", "psi_2=2.6:2.6:1", "--t-end", "3000", "--json"])
    assert res.exit_code == 0, res.output
    import xarray as xr

    ds = xr.open_zarr(store, consolidated=False)
    key = "model.unbalances[0].magnitude"
    np.testing.assert_allclose(ds[key].values, [0.01, 0.06], rtol=1e-15)
    assert ds[key].attrs["units"] == "kg*m"
    # and so does what rotorlab.sweep reads back (``rotorlab show``: it printed no unit)
    from rotorlab.sweep import open_sweep

    assert open_sweep(store)[key].attrs["units"] == "kg*m"
    labels = ds.attrs["result_attrs"]["labels"]
    assert [labels[int(k)] for k in ds.outcome.values] == ["balanced", "not balanced"]
    # the reference (locked unbalance response) follows the key: U w^2 / |c - M w^2 + i d w|
    w = 2.5
    expect = [u * w**2 / abs(1.0 - 1.04 * w**2 + 0.1j * w) for u in (0.01, 0.06)]
    np.testing.assert_allclose(ds.reference_amplitude.values, expect, rtol=1e-12)
    bad = CliRunner().invoke(app, ["sweep", str(path), "--out", str(tmp_path / "b.zarr"), "--param",
                                   "model.structure.bodies[3].mass=1:2:2", "--ic", "psi_1=0.8:0.8:1"])
    assert bad.exit_code == 2 and "model.<key path>" in bad.output


def test_steady_findings_say_whether_the_balancer_balances(planar):
    from rotorlab.report._machine import machine_findings

    verdicts = {}
    for name in ("above", "below"):
        ds = run_analysis(planar.model, planar.analysis(name))
        verdicts[name] = machine_findings(ds, summarize(ds)).verdict
    assert verdicts["above"].startswith("2 of 6") and "the balancer balances there" in verdicts["above"]
    assert verdicts["below"].startswith("1 of 6") and "the balanced motion is unstable" in verdicts["below"]


def test_simulate_findings_without_balls_name_no_ball_angles():
    """A start without a balancer has no balls: its findings line says so and shows no ball
    angles (it printed "final ball angles - deg")."""
    from rotorlab.report._machine import _simulate_findings

    rows = [{"ic": 0, "outcome": "no balancer", "amplitude": {"rotor": 1.04e-3},
             "reference_amplitude": {"rotor": 1.0e-3}, "final_ball_angles_deg": {}}]
    found = _simulate_findings(None, rows)
    assert found.numbers == ("largest vibration / unbalance response 104 %", "start 0: no balancer")
    assert "104 %" in found.verdict


def test_basin_and_sweep_of_some_races_map_that_variant():
    """``races = [0]`` on a basin (and a sweep) maps the machine with those races only: a second
    race added to the planar case and left out gives the planar machine's own outcomes (starts off
    the diagonal balance, as in the 3 x 3 basin above); ``psi_<i>`` counts the chosen races'
    balls, so ``psi_3`` is refused there with its key path, and accepted with all races."""
    race2 = ('[[model.races]]\nat = "disc"\nradius = "0.5 m"\n'
             'balls = [{ mass = "0.01 kg", damping = "0.05 N*m*s/rad", count = 1 }]\n')
    model = PLANAR[:PLANAR.index("[[analysis]]")]
    text = model.replace("[[model.unbalances]]", race2 + "[[model.unbalances]]", 1)
    text += ('[[analysis]]\ntype = "basin"\nname = "race-0"\nraces = [0]\n'
             'x = ["psi_1", "0 deg", "120 deg", 2]\ny = ["psi_2", "240 deg", "240 deg", 1]\n'
             't_end = "3000 s"\nn_horizons = 2\n')
    case = parse_case(text)
    basin = run_analysis(case.model, case.analysis("race-0"))
    assert [str(basin["regime"].values[int(o)]) for o in basin.outcome.values.ravel()] == ["balanced"] * 2
    bad = text.replace('y = ["psi_2", "240 deg"', 'y = ["psi_3", "240 deg"')
    with pytest.raises(CaseError, match=r"analysis\[0\]\.y = .*'psi_3' names ball 3, but the races \[0\] have 2 ball"):
        parse_case(bad)
    parse_case(bad.replace("races = [0]\n", ""))  # three balls in all: psi_3 is a coordinate
    sweep = text + ('[[analysis]]\ntype = "sweep"\nname = "s"\nraces = [0]\n'
                    'ic = { psi_3 = ["0 deg", "90 deg", 2] }\nt_end = "10 s"\n')
    with pytest.raises(CaseError, match=r"analysis\[1\]\.ic\.psi_3 = .*'psi_3' names ball 3, but the races"):
        parse_case(sweep)


def test_run_up_report_says_what_its_result_arrays_say():
    """The run-up's report (findings and table) against its own arrays and closed forms: passes
    the critical speed p = sqrt(c / (M1 + 2 m)) iff the final speed exceeds 1.05 p, the residual
    vibration is the tail orbit of the amplitude array, "balanced" iff that is at most
    BALANCED_FRACTION of the locked unbalance response U w^2 / |c - M w^2 + i d w| at the final
    speed; the planar case with a motor is the kernel of test_machine_analyses' run-up test."""
    from rotorlab import _people as people
    from rotorlab.explore._outcome import BALANCED_FRACTION
    from rotorlab.report._machine import machine_findings, machine_rows_table

    text = PLANAR[:PLANAR.index("[[analysis]]")].replace('profile = "constant"\nspeed = "2.5 rad/s"',
                          'profile = "motor"\nstall_torque = "0.03 N*m"\nno_load_speed = "3 rad/s"\n'
                          'polar_inertia = "0.05 kg*m^2"')
    text += ('\n[[analysis]]\ntype = "run-up"\nname = "up"\nt_end = "300 s"\nn_save = 300\n'
             'initial_ball_angles = [["47 deg", "145 deg"], ["36 deg", "36 deg"]]\n')
    case = parse_case(text)
    ds = run_analysis(case.model, case.analysis("up"))
    rows = summarize(ds)
    found = machine_findings(ds, rows)
    header, body = machine_rows_table(ds, rows)
    tail = ds.time.values >= 0.9 * ds.time.values[-1]
    for i, r in enumerate(rows):
        w = float(ds.speed.values[i, -1])
        assert r["final_speed"] == pytest.approx(w, rel=1e-12)
        assert r["critical_speeds"][0] == pytest.approx(P, rel=1e-9)
        assert r["passed"] == sum(w > 1.05 * c for c in r["critical_speeds"]) and r["passed"] >= 1
        assert r["captured_at"] is None
        # no gravity: the orbit's centre is the axis, the residual is the tail's largest radius
        amp = ds.amplitude.sel(station="disc").values[i][tail]
        assert r["residual_amplitude"]["disc"] == pytest.approx(amp.max(), rel=0.05)
        ref = 0.01 * w**2 / abs(1.0 - 1.04 * w**2 + 0.1j * w)
        assert r["reference_amplitude"]["disc"] == pytest.approx(ref, rel=1e-9)
        balanced = r["residual_amplitude"]["disc"] <= BALANCED_FRACTION * ref
        assert (r["outcome"] == "balanced") == balanced
        assert f"start {i}: passes {r['passed']} critical speed(s), reaches {w * 30 / math.pi:.4g} rpm" \
            in found.verdict
        assert f"start {i}: residual vibration disc: {people.length(r['residual_amplitude']['disc'])}" in found.numbers[i]
        assert body[i][header.index("passed")] == str(r["passed"])
    good = [r["ic"] for r in rows if r["outcome"] == "balanced"]
    assert good[:1] == [0]  # the balls apart balance above p
    assert found.verdict.startswith(f"The balancer balances from start(s) {', '.join(map(str, good))} ({len(good)} of 2)")


def test_a_chart_unstable_everywhere_below_the_critical_speed_says_why_and_the_remedy(planar):
    """Issue 29: a subcritical machine was "unstable at every speed checked" with no reason and no
    remedy. Below p = 1 / sqrt(1.04) rad/s = 9.36 rpm (balls locked) the balanced state is
    unstable (Zhakash et al. 2024): the findings and the verdict name p and the fix."""
    from rotorlab.analyses import machine_verdict
    from rotorlab.report._machine import machine_findings

    text = PLANAR[:PLANAR.index("[[analysis]]")] + (
        '[[analysis]]\ntype = "stability-chart"\nname = "low"\nspeeds = ["0.3 rad/s", "0.9 rad/s", 3]\n')
    case = parse_case(text)
    ds = run_analysis(case.model, case.analysis("low"))
    rows = summarize(ds)
    assert not any(r["stable"] for r in rows)
    assert ds.attrs["first_critical_speed"] == pytest.approx(P, rel=1e-9)
    found = machine_findings(ds, rows).verdict
    assert found == ("The balanced state is unstable at every speed checked: the balancer does not settle there. "
                     "Every speed checked (2.86 to 8.59 rpm) lies below the first forward critical speed 9.36 rpm, "
                     "where no balancer can balance. Run above the first forward critical speed of 9.36 rpm, or "
                     "soften the mounts.")
    lines = [v for v in machine_verdict(case, {"low": ds}, {"low": rows}) if v.topic == "stable speeds"]
    assert [(v.status, v.sentence, v.fix) for v in lines] == [(
        "no", "The balanced state is unstable at every speed checked (2.86 to 8.59 rpm, low): every speed checked "
        "lies below the first forward critical speed 9.36 rpm.",
        "run above the first forward critical speed of 9.36 rpm, or soften the mounts")]
