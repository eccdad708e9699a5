"""The interfaces of rotorlab.continuation (issue 25): a jeffcott_balls rotor continued as the
machine it equals, the ``continuation`` analysis of a case file with its report figures, and the
``rotorlab continue`` command.

References: zhakash-k2's balanced state is born at the ball mass m* = M1 e / (2 l) = 2 kg x 1.08 mm
/ (2 x 0.06 m) = 18 g (force balance of two equal balls, balls together opposite the unbalance);
its Hopf point is where the largest real part of ``JeffcottBalls.linearize`` (the model's own
co-rotating linearization, not the machine's) crosses zero.
"""

import json
import math
from dataclasses import replace

import numpy as np
from scipy.optimize import brentq
from typer.testing import CliRunner

from rotorlab.analyses import build_model, run_analysis, summarize
from rotorlab.cli import app
from rotorlab.continuation import as_machine, continue_equilibria
from rotorlab.io import load_case, parse_case
from rotorlab.models import ConstantSpeed
from rotorlab.plot import continuation_figures
from rotorlab.report import PRESENTATIONS
from test_machine_common import PLANAR


def test_jeffcott_balls_continues_as_its_machine_hopf_by_its_own_linearization():
    jb = build_model(load_case("zhakash-k2").model)
    p = jb.critical_speed
    r = continue_equilibria(jb, "drive.speed", 0.9 * p, 2.0 * p, start_from="main+")
    (hopf,) = r.branches[0].special_points
    psi = r.branches[0].states[0][4:6]

    def growth(w):
        model = replace(jb, speed=ConstantSpeed(w), frame="rotating")
        return float(model.linearize(np.r_[0.0, 0.0, 0.0, 0.0, psi, 0.0, 0.0], w).eigenvalues.real.max())

    w0 = brentq(growth, 1.2 * p, 1.8 * p, xtol=1e-12, rtol=1e-14)
    assert abs(hopf.value - w0) < 1e-6 * w0
    assert hopf.description.startswith(f"balancing becomes stable above {w0 * 30 / math.pi:.4g} rpm")
    m = as_machine(jb)
    assert m.n_coordinates == 2 and m.races[0].capacity == 2 * 0.03 * 0.06


def test_cli_continue_json_plot_out_and_the_pitchfork_of_zhakash_k2(tmp_path):
    png, nc = tmp_path / "b.png", tmp_path / "b.nc"
    res = CliRunner().invoke(app, ["continue", "zhakash-k2", "--param", "ball_mass=40g:5g", "--speed-rpm", "2000",
                                   "--plot", str(png), "--out", str(nc), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    main = doc["branches"][0]
    assert main["kind"] == "equilibrium" and main["parameter"] == "ball_mass" and doc["units"]["ball_mass"] == "kg"
    (bp,) = main["special_points"]
    assert bp["type"] == "branch" and abs(bp["ball_mass"] - 0.018) < 1e-8 * 0.018
    assert bp["description"] == ("balancing meets another branch of steady motions at 18 g: a symmetry-breaking "
                                 "branch point")
    assert [b["label"].split(" (")[0] for b in doc["branches"]] == ["main+", "balls together", "balls together"]
    assert all(pt["stable"] in (True, False) and pt["amplitude_m"] >= 0 for pt in main["points"])
    assert png.stat().st_size > 10_000 and nc.stat().st_size > 0 and sorted(doc["files"]) == sorted([str(png), str(nc)])
    bad = CliRunner().invoke(app, ["continue", "zhakash-k2", "--param", "ball_mas=1:2"])
    assert bad.exit_code == 2 and "--param = ball_mas=1:2" in bad.output and "ball_mass" in bad.output


def run_planar_speed_curves(name, low, param2, range2):
    """Run a ``continuation`` analysis of the PLANAR case over ``drive.speed`` from ``low`` to 3 rad/s
    with a second parameter; its Dataset and summary rows."""
    text = PLANAR + f"""
[[analysis]]
type = "continuation"
name = "{name}"
param = "drive.speed"
range = ["{low} rad/s", "3 rad/s"]
param2 = "{param2}"
range2 = {json.dumps(list(range2))}
"""
    case = parse_case(text)
    spec = [a for a in case.analyses if a.type == "continuation"][0]
    ds = run_analysis(case.model, spec)
    return ds, summarize(ds)


def test_case_file_continuation_with_curves_over_the_chart_and_its_presentation():
    ds, rows = run_planar_speed_curves("cont", 0.6, "ball_damping", ("0.02 N*m*s/rad", "0.08 N*m*s/rad"))
    hopf = [r for r in rows if r["type"] == "hopf"]
    assert hopf and hopf[0]["description"].startswith("balancing becomes stable above")
    assert "curve_value" in ds and "chart_stable" in ds and ds.chart_stable.shape == (13, 41)
    # the Hopf curve through the point at the case's damping (0.05) crosses it at the same speed
    curve = ds.curve_value.values[0]
    keep = np.isfinite(curve[:, 0])
    w = np.interp(0.05, curve[keep, 1], curve[keep, 0])
    assert abs(w - hopf[0]["value"]) < 1e-4 * w
    figs = continuation_figures(ds, "cont")
    assert sorted(figs) == ["cont-bifurcation", "cont-curves"]
    pres = PRESENTATIONS["continuation"]
    assert "becomes stable above" in pres.section(ds, rows) and pres.findings(ds, rows).verdict.startswith("Balancing")


def test_two_plane_balancer_hopf_is_the_chart_crossing():
    """rcfw-two-plane (Rodrigues et al. 2008's rigid rotor with two races, tilting): four balanced
    layouts; where balancing becomes stable equals today's chart (machine_steady) crossing."""
    from rotorlab.analyses._machine_steady import machine_steady

    m = build_model(load_case("rcfw-two-plane").model)
    r = continue_equilibria(m, "drive.speed", 2.5, 3.5, start_from="main 0")
    (edge,) = [s for s in r.branches[0].special_points if s.changes_stability]
    lo, hi = 0.999 * edge.value, 1.001 * edge.value  # brentq refuses a bracket without a sign change
    w0 = brentq(lambda w: float(machine_steady(m, [w]).max_real_eigenvalue[0]), lo, hi, xtol=1e-13, rtol=1e-14)
    assert edge.type == "hopf" and abs(edge.value - w0) < 1e-6 * w0
    assert edge.description.startswith("balancing becomes stable above")
