"""Linear rotor case files: the built-in cases equal the Python builders, the analyses they run,
and the schema's error messages for linear models and analyses."""

from __future__ import annotations

import math
import re
from importlib import resources

import numpy as np
import pytest

from rotorlab.analyses import (
    DATA_AUDITS,
    build_linear_system,
    campbell_summary,
    run_case,
    summarize,
)
from rotorlab.io import CaseError, dump_case, load_case, load_netcdf, parse_case, save_netcdf
from rotorlab.io._linear_analyses import AUDITED_DATA
from rotorlab.linear import RPM, critical_speeds, modal
from rotorlab.linear.cases import PICO21, audit_pico21, friswell_rotor, pico21
from rotorlab.linear.cases._pico21_data import PRINTED_STIFFNESS

MULTIBODY = """
name = "mb"
[model]
type = "multibody"
[[model.bodies]]
name = "housing"
position = "45 mm"
mass = "2.4 kg"
diametral_inertia = "0.018 kg*m^2"
polar_inertia = "0.018 kg*m^2"
spinning = false
on_shaft = false
[[model.bodies]]
name = "armature"
position = "32 mm"
mass = "0.6 kg"
diametral_inertia = "425 kg*mm^2"
polar_inertia = "93 kg*mm^2"
[[model.bodies]]
name = "rotor"
position = "120 mm"
mass = "0.507 kg"
diametral_inertia = "882 kg*mm^2"
polar_inertia = "1529 kg*mm^2"
[model.elastic.geometry]
spans = [{ start = "0 mm", end = "120 mm", flexural_rigidity = "550.3 N*m^2" }]
supports = [{ position = 0, kind = "clamped" }, { position = "86 mm", stiffness = "60 MN/m" }]
[model.elastic.geometry.housing]
translational_stiffness = "13932 N/m"
rotational_stiffness = "932.9282617284414 N*m/rad"
[[analysis]]
type = "campbell"
stop = "3000 rpm"
n_speeds = 11
n_modes = 4
"""

FE = """
name = "fe"
[model]
type = "fe_rotor"
[model.material]
youngs_modulus = "211 GPa"
shear_modulus = "81.2 GPa"
density = "7810 kg/m^3"
[[model.shaft]]
length = "1.5 m"
outer_diameter = "50 mm"
elements = 6
[[model.discs]]
name = "disc 1"
position = "0.5 m"
outer_diameter = "280 mm"
width = "70 mm"
[[model.bearings]]
name = "left"
node = 0
kxx = "1 MN/m"
[[model.bearings]]
name = "right"
position = "1.5 m"
kxx = "1 MN/m"
kyy = "0.8 MN/m"
cxx = "3 kN*s/m"
[[analysis]]
type = "unbalance_response"
stop = "4000 rpm"
n_speeds = 5
[[analysis.unbalances]]
at = "disc 1"
magnitude = "100 g*mm"
"""


# --------------------------------------------------------------------------- case == builder


def test_pico21_case_is_the_python_builder_exactly():
    case = load_case("pico21")
    s, ref = build_linear_system(case.model), pico21()
    for name in "MCGK":
        np.testing.assert_array_equal(getattr(s, name), getattr(ref, name))
    assert s.node_label == ref.node_label == ("stator", "armature", "rotor")
    np.testing.assert_array_equal(s.node_position, ref.node_position)


def test_friswell_case_is_the_python_builder():
    s, ref = build_linear_system(load_case("friswell-rotor").model), friswell_rotor()
    for name in "MCGK":
        a, b = getattr(s, name), getattr(ref, name)
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-13 * np.abs(b).max())
    assert s.node_label == ref.node_label
    np.testing.assert_allclose(modal(s).frequency, modal(ref).frequency, rtol=1e-12)


def test_pico21_case_uses_the_resolved_data():
    model = load_case("pico21").model
    bodies = {b.name: b for b in model.bodies}
    assert list(bodies) == ["stator", "armature", "rotor"]
    assert bodies["stator"].diametral_inertia == PICO21.stator_diametral_inertia
    assert bodies["stator"].spinning is False
    assert bodies["armature"].diametral_inertia == PICO21.armature_diametral_inertia
    assert bodies["armature"].polar_inertia == PICO21.armature_polar_inertia
    assert bodies["rotor"].polar_inertia == PICO21.rotor_polar_inertia
    assert model.elastic.compliance[1][1] == 107.1893779e-5


def test_pico21_case_file_records_every_audit_finding():
    text = resources.files("rotorlab").joinpath("cases", "pico21.toml").read_text()
    comments = "\n".join(line for line in text.splitlines() if line.lstrip().startswith("#"))
    for finding in audit_pico21():
        assert f"[{finding.key}]" in comments
    assert "107.1893779e-5" in comments and "RESOLVED" in comments


def test_geometry_and_stiffness_routes_equal_the_builder():
    geometry = parse_case(MULTIBODY).model
    ref = pico21(source="geometry")
    s = build_linear_system(geometry)
    np.testing.assert_allclose(s.K, ref.K, rtol=1e-12, atol=1e-12 * np.abs(ref.K).max())
    rows = ",\n".join("[" + ", ".join(repr(float(v)) for v in row) + "]"
                      for row in PRINTED_STIFFNESS)
    text = (MULTIBODY.split("[model.elastic.geometry]")[0]
            + f"[model.elastic]\nstiffness = [\n{rows}]\n")
    s = build_linear_system(parse_case(text).model)
    np.testing.assert_allclose(s.K, pico21(source="stiffness").K, rtol=1e-12,
                               atol=1e-9 * np.abs(s.K).max())


def test_fe_case_with_anisotropic_damped_bearing():
    case = parse_case(FE)
    s = build_linear_system(case.model)
    assert s.node_label == ("left", "1", "disc 1", "3", "4", "5", "right")
    free = build_linear_system(case.model.with_values({("bearings", 1, "kxx"): 0.0,
                                                       ("bearings", 1, "kyy"): 0.0}))
    np.testing.assert_allclose(np.diag(s.K - free.K)[24:26], [1e6, 0.8e6], rtol=1e-9)
    assert s.C[24, 24] == 3e3 and s.C[25, 25] == 3e3
    ds = run_case(case)["unbalance_response-0"]
    assert ds.attrs["output_nodes"] == [0, 2, 6]
    rows = summarize(ds)
    assert [r["label"] for r in rows] == ["left", "disc 1", "right"]
    assert all(r["peak_amplitude"] > 0 for r in rows)


def test_dump_case_round_trip_of_the_linear_cases():
    for name in ("pico21", "friswell-rotor"):
        case = load_case(name)
        again = parse_case(dump_case(case), f"{name}-dumped.toml")
        assert again.model_dump_si() == case.model_dump_si()


def test_data_audits_match_the_schema_choices():
    assert tuple(DATA_AUDITS) == AUDITED_DATA


# --------------------------------------------------------------------------- analyses


@pytest.fixture(scope="module")
def pico21_results():
    return run_case(load_case("pico21"))


@pytest.fixture(scope="module")
def friswell_results():
    return run_case(load_case("friswell-rotor"))


def test_friswell_modes_and_critical_speeds(friswell_results):
    rows = summarize(friswell_results["modes-at-rest"])
    f = np.sort(modal(friswell_rotor()).frequency)[:6]
    np.testing.assert_allclose([r["frequency_hz"] for r in rows], f, rtol=1e-10)
    assert [round(r["frequency_hz"], 2) for r in rows] == [13.79, 13.79, 43.66, 43.66, 114.08,
                                                            114.08]
    exact = critical_speeds(friswell_rotor(), max_speed=4000 * RPM)
    # rows: the crossings unbalance excites (forward, on these isotropic bearings) first
    order = [1, 3, 0, 2]
    crit = summarize(friswell_results["critical-speeds"])
    np.testing.assert_allclose([r["speed"] for r in crit], exact.speed[order], rtol=1e-12)
    grid = summarize(friswell_results["campbell"])
    np.testing.assert_allclose([r["speed"] for r in grid], exact.speed[order], rtol=1e-8)
    assert [r["whirl"] for r in grid] == ["F", "F", "B", "B"]
    doc = campbell_summary(friswell_results["campbell"])
    assert len(doc["speed_rpm"]) == 81 and doc["speed_rpm"][-1] == pytest.approx(4000.0)


def test_pico21_analyses(pico21_results):
    assert list(pico21_results) == ["data-audit", "campbell", "critical-speeds", "modes-at-rest",
                                    "modes-at-top-speed", "unbalance-response",
                                    "support-stiffness"]
    audit = summarize(pico21_results["data-audit"])
    assert [r["finding"] for r in audit] == [f.key for f in audit_pico21()]
    crit = [r["speed_rpm"] for r in summarize(pico21_results["critical-speeds"])]
    # forward (excited by unbalance) first, then backward
    assert crit == pytest.approx([588.26, 2090.41, 588.07, 1940.36], abs=0.01)
    fit = {r["parameter"].split(".")[-1]: r
           for r in summarize(pico21_results["support-stiffness"])}
    assert fit["translational_stiffness"]["value"] == pytest.approx(
        PICO21.support_translational_stiffness, rel=2e-3)
    assert fit["rotational_stiffness"]["value"] == pytest.approx(
        PICO21.support_rotational_stiffness, rel=2e-4)
    assert fit["rotational_stiffness"]["unit"] == "N*m/rad"
    assert pico21_results["support-stiffness"].attrs["rms"] < 2e-4


def test_linear_results_survive_netcdf(pico21_results, friswell_results, tmp_path):
    both = {**pico21_results, **{f"f-{k}": v for k, v in friswell_results.items()}}
    for name, ds in both.items():
        back = load_netcdf(save_netcdf(ds, tmp_path / f"{name}.nc"))
        assert back.attrs["analysis"] == ds.attrs["analysis"]
        assert summarize(back) == summarize(ds)


def test_campbell_summary_writes_non_finite_numbers_as_none(friswell_results):
    ds = friswell_results["campbell"].copy(deep=True)
    ds["frequency"][0, 0] = np.nan
    doc = campbell_summary(ds)
    assert doc["frequency_hz"][0][0] is None and doc["frequency_hz"][0][1] is not None


# --------------------------------------------------------------------------- schema errors

# (text, replacement, words the single problem line must contain)
BAD = [
    (MULTIBODY, ('polar_inertia = "93 kg*mm^2"', 'polar_inertia = "930 kg*mm^2"'),
     ['model.bodies[1].polar_inertia = "930 kg*mm^2"', "must be <= 2 * diametral_inertia",
      "swapped"]),
    (MULTIBODY, ('name = "rotor"', 'name = "armature"'),
     ['model.bodies[2].name = "armature"', "names must be unique"]),
    (MULTIBODY, ('spinning = false', 'spinning = 0'),
     ["model.bodies[0].spinning = 0: must be true or false"]),
    (MULTIBODY, ('stiffness = "60 MN/m"', 'stiffness = "60 MN"'),
     ['model.elastic.geometry.supports[1].stiffness = "60 MN"', "expected a stiffness (N/m)"]),
    (MULTIBODY, ('position = "86 mm"', 'position = "186 mm"'),
     ['model.elastic.geometry.supports[1].position = "186 mm"', "outside the shaft"]),
    (MULTIBODY, ('{ position = 0, kind = "clamped" }, ', ""),
     ["model.elastic.geometry.supports: do not hold the shaft"]),
    (MULTIBODY, ('kind = "clamped"', 'kind = "clamp"'),
     ['kind = "clamp": must be one of "elastic", "pinned", "clamped"', "did you mean 'clamped'?"]),
    (MULTIBODY, ("[model.elastic.geometry.housing]\n", "[model.elastic.geometry.housingg]\n"),
     ["unknown key 'housingg'", "did you mean 'housing'?"]),
    (MULTIBODY, ('stop = "3000 rpm"', 'start = "5000 rpm"\nstop = "3000 rpm"'),
     ['analysis[0].stop = "3000 rpm": must be > start = 523.599 rad/s (5000 rpm)']),
    (MULTIBODY, ("n_modes = 4", "n_modes = 13"),
     ["analysis[0].n_modes = 13: must be <= 12 (the model's number of modes)"]),
    (MULTIBODY, ("n_speeds = 11", "n_speeds = 1"),
     ["analysis[0].n_speeds = 1: must be an integer >= 2"]),
    (MULTIBODY, ('stop = "3000 rpm"', 'stop = "3000 m"'),
     ['analysis[0].stop = "3000 m": wrong dimension: expected an angular speed (rad/s)']),
    (MULTIBODY, ("n_modes = 4", "n_modes = 4\nharmonics = [0]"),
     ["analysis[0].harmonics[0] = 0: must be an integer >= 1"]),
    (FE, ('position = "0.5 m"', 'position = "1.6 m"'),
     ['model.discs[0].position = "1.6 m": must be on the shaft, from 0 to 1.5 m']),
    (FE, ('shear_modulus = "81.2 GPa"', 'shear_modulus = "50 GPa"'),
     ['model.material.shear_modulus = "50 GPa": gives Poisson\'s ratio', "need -1 < nu < 0.5"]),
    (FE, ('density = "7810 kg/m^3"', 'density = "7810 kg/m^2"'),
     ['model.material.density = "7810 kg/m^2": wrong dimension: expected a density (kg/m^3)']),
    (FE, ('name = "right"', 'name = "left"'), ['model.bearings[1].name = "left": is used by '
                                               "bearings[0]: names must be unique"]),
    (FE, ('node = 0\n', ''), ["model.bearings[0]: give one of node or position"]),
    (FE, ('width = "70 mm"', 'width = "70 mm"\nmass = "30 kg"'),
     ["model.discs[0]: give either outer_diameter and width, or mass and inertias, not both"]),
    (FE, ('at = "disc 1"', 'at = "disk 1"'),
     ['analysis[0].unbalances[0].at = "disk 1": no node or component of that name',
      "did you mean 'disc 1'?"]),
    (FE, ('at = "disc 1"', 'node = 9'), ["analysis[0].unbalances[0].node = 9: must be < 7"]),
    (FE, ('magnitude = "100 g*mm"', 'magnitude = "100 g"'),
     ['analysis[0].unbalances[0].magnitude = "100 g": wrong dimension: expected an unbalance '
      "(kg*m)"]),
    (FE, ('at = "disc 1"\n', ""), ["analysis[0].unbalances[0]: give one of at, node or position"]),
]


def _problem(text: str, replace: tuple[str, str]) -> str:
    assert replace[0] in text
    with pytest.raises(CaseError) as info:
        parse_case(text.replace(replace[0], replace[1], 1), "bad.toml")
    assert len(info.value.problems) == 1, info.value.problems
    return info.value.problems[0]


@pytest.mark.parametrize(("text", "replace", "words"), BAD, ids=[b[1][1][:30] for b in BAD])
def test_schema_errors_name_key_value_and_rule(text, replace, words):
    problem = _problem(text, replace)
    for word in words:
        assert word in problem, problem


def test_compliance_matrix_errors():
    case = load_case("pico21")
    text = case.text
    first = text.index("compliance = [\n") + len("compliance = [\n")
    row = text[first:text.index("\n", first)]
    problem = _problem(text, (row, row.replace("4.823522006e-05", '"1 m/N"', 1)))
    assert problem.startswith('model.elastic.compliance[0][1] = "1 m/N": wrong dimension: '
                              "expected a translation-tilt compliance (1/N)")
    problem = _problem(text, (row, row.replace("7.33207306e-05", "7.4e-05", 1)))
    assert ("model.elastic.compliance: must be symmetric: [0][2] = 7.4e-05 but [2][0] = "
            "7.33207306e-05") in problem
    problem = _problem(text, (row + "\n", ""))
    assert "compliance = [[4.823522006e-05, " in problem
    assert problem.endswith("must be a square matrix with an even number of rows (translation "
                            "and tilt of each body), got 5 row(s) of length [6]")
    problem = _problem(text, ('bodies = ["stator", "armature", "rotor"]\ncompliance',
                              'bodies = ["stator", "rotor"]\ncompliance'))
    assert "model.elastic.compliance: must be 4 x 4" in problem
    both = "stiffness = [[1.0, 0.0], [0.0, 1.0]]\ncompliance = ["
    problem = _problem(text, ("compliance = [", both))
    assert "model.elastic: compliance and stiffness exclude each other" in problem


def test_identify_errors():
    text = load_case("pico21").text
    problem = _problem(text, ('"elastic.geometry.housing.rotational_stiffness"',
                              '"elastic.geometry.housing.rotational_stifness"'))
    assert ('analysis[6].parameters[1] = "elastic.geometry.housing.rotational_stifness": '
            "model.elastic.geometry.housing has no key 'rotational_stifness'; did you mean "
            "'rotational_stiffness'?") in problem
    problem = _problem(text, ('"elastic.geometry.housing.rotational_stiffness"',
                              '"elastic.geometry.housing.position"'))
    assert "a fitted value must be > 0" in problem
    problem = _problem(text, ("{ speed = \"0 rpm\", mode = 0,", "{ speed = \"0 rpm\", mode = 12,"))
    assert "analysis[6].measurements[0].mode = 12: must be < 12" in problem


def test_linear_analyses_need_a_linear_model():
    text = """
[model]
type = "jeffcott_balls"
disc_mass = 1.0
eccentricity = 1e-3
stiffness = 1e4
[[analysis]]
type = "campbell"
stop = "1000 rpm"
"""
    with pytest.raises(CaseError) as info:
        parse_case(text)
    assert info.value.problems == (
        'analysis[0]: needs a linear rotor model ([model] type "multibody" or "fe_rotor") or a model '
        'built on one (machine), but '
        'the case\'s model is "jeffcott_balls"',)


def test_speeds_are_equally_spaced_and_exact_at_the_ends():
    spec = parse_case(MULTIBODY).analyses[0]
    speeds = spec.speeds()
    assert len(speeds) == 11 and speeds[0] == 0.0 and speeds[-1] == 3000 * math.pi / 30
    assert np.allclose(np.diff(speeds), speeds[-1] / 10)
    assert re.search(r"11 speeds from 0 to 3000 rpm", spec.describe(parse_case(MULTIBODY).model))
