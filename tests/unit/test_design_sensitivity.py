"""The sensitivity of a design's winner (issue 27 item 4): a design analysis with a
``sensitivity`` table runs the tolerances engine at its winning design, its dataset carries the
indices bit for bit as a separate ``tolerances`` run at the winner gives them, and the report
shows the bars and says which input P(balanced) is most sensitive to.

Physics: the built-in ``pico21-balancer`` (its compiled driver is the tolerances tests'), rotor
race only, the ball mass varied with the ball mass as objective (no constraint: the search itself
simulates nothing), 2 base samples x 1 start of 0.02 s at the winner.
"""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest

from rotorlab.analyses._design_case import design_evidence, design_rows, run_design_analysis, sensitivity_sentence
from rotorlab.io import DesignSpec, TolerancesSpec, load_case

SENSITIVITY = {"inputs": {"ball_damping": {"distribution": "uniform", "tolerance": 0.5},
                          "races[0].radius": {"distribution": "normal", "tolerance": 0.01}},
               "samples": 2, "starts": 1, "t_end": "0.02 s", "n_horizons": 2}  # fmt: skip
SPEC = {"name": "light", "vary": {"ball_mass": ["4 g", "6 g"]}, "objectives": ["ball-mass"],
        "param": {"spin_speed": ["10000 rpm", "10000 rpm", 1]}, "min_balanced": None, "budget": 2,
        "verify": False, "races": [0], "n_horizons": 2, "seed": 5}  # fmt: skip
KEYS = ("S1", "S1_conf", "ST", "ST_conf")


@pytest.fixture(scope="module")
def case():
    return load_case("pico21-balancer")


@pytest.fixture(scope="module")
def designed(case):
    spec = DesignSpec.model_validate({**SPEC, "sensitivity": SENSITIVITY})
    assert spec.case_issues(case.model) == []
    return spec, run_design_analysis(case.model, spec)


def test_the_indices_are_those_of_a_tolerances_run_at_the_winner_bit_for_bit(designed, tmp_path):
    from rotorlab.analyses._tolerances import run_tolerances_analysis

    spec, ds = designed
    best = int(ds.attrs["best"])
    mass = float(ds["value"].values[best, 0])
    assert 0.004 <= mass <= 0.006 and ds.attrs["sensitivity_seed"] == 5  # the design's seed by default
    # the objective is the winner's: two balls of that mass on race 0 (was the base 2 x 5 g for any design)
    assert np.allclose(ds["objective_value"].values[:, 0], 2.0 * ds["value"].values[:, 0], rtol=1e-12)
    # the same machine written as a case: every ball's mass the winner's (SI number), then tolerances
    text = resources.files("rotorlab.cases").joinpath("pico21-balancer.toml").read_text(encoding="utf-8")
    assert text.count('mass = "5 g"') == 2
    path = tmp_path / "winner.toml"
    path.write_text(text.replace('mass = "5 g"', f"mass = {mass!r}"), encoding="utf-8")
    winner = load_case(path)
    tol = TolerancesSpec.model_validate({**SENSITIVITY, "type": "tolerances", "seed": 5, "races": [0],
                                         "speed": "10000 rpm"})  # fmt: skip
    assert tol.case_issues(winner.model) == []
    ref = run_tolerances_analysis(winner.model, tol)
    assert list(ds["input"].values) == list(ref["input"].values) and list(ds["output"].values) == list(ref["output"].values)
    for key in KEYS:
        assert np.array_equal(ds[key].values, ref[key].values, equal_nan=True), key
    assert np.array_equal(ds["sensitivity_mean"].values, ref["mean"].values)
    assert ds.attrs["sensitivity_machines"] == ref.sizes["sample"] == 2 * (2 + 2)
    from rotorlab.analyses._design_case import design_document

    doc = design_document(ds)["sensitivity"]
    assert doc["inputs"] == ["ball_damping", "races[0].radius"] and doc["sentence"] == sensitivity_sentence(ds)
    assert doc["ST"][1] == [float(v) for v in ref["ST"].values[1]]
    # the radius moves the residual vibration at all: its indices are numbers, not the NaN of a constant output
    assert np.isfinite(ds["ST"].sel(output="residual_vibration").values).all()


def test_the_sentence_names_the_input_with_the_largest_total_index(designed):
    _, ds = designed
    p = list(ds["output"].values).index("p_balanced")
    st = ds["ST"].values[p]
    if np.isfinite(st).any():
        j = int(np.nanargmax(st))
        assert f"most sensitive to {ds['input'].values[j]} (ST " in sensitivity_sentence(ds)
    else:  # 0.02 s: no start balances at any machine, P(balanced) does not vary and the sentence says so
        assert "the same for every sampled machine (8 machines x 1 starts)" in sensitivity_sentence(ds)
    # an output that varies: its row in place of P(balanced)'s gives the sentence with ST and its interval
    other = ds.copy(deep=True)
    r = list(ds["output"].values).index("residual_vibration")
    for key in KEYS:
        other[key].values[p] = ds[key].values[r]
    j = int(np.nanargmax(ds["ST"].values[r]))
    st, half = ds["ST"].values[r, j], ds["ST_conf"].values[r, j]
    from rotorlab import _people as people

    assert sensitivity_sentence(other).startswith(
        f"P(balanced) of the recommended design is most sensitive to {ds['input'].values[j]} "
        f"(ST {people.number(st, 2)} ± {people.number(half, 2)}; 8 machines x 1 starts)")
    line = design_evidence(other, design_rows(other), None)[0]
    assert line.status == "yes" and f"most sensitive to {ds['input'].values[j]}" in line.sentence


def test_the_report_shows_the_bars_and_the_sentence_and_without_a_table_says_not_computed(case, designed, tmp_path):
    from rotorlab.plot._design import design_figures
    from rotorlab.report._design import design_findings
    from rotorlab.report._write import write_report

    spec, ds = designed
    figures = design_figures(ds, "light")
    assert set(figures) == {"light_design", "light_sensitivity"}
    run = case.model_copy(update={"analyses": [spec]})
    html = write_report(tmp_path / "out", run, {"light": ds}, {"light": figures},
                        {"light": design_rows(ds)}).read_text(encoding="utf-8")  # fmt: skip
    assert (tmp_path / "out" / "light_sensitivity.png").stat().st_size > 10_000
    assert "light_sensitivity" in html and sensitivity_sentence(ds) in html.replace("&#x27;", "'")
    assert "sensitivity not computed" not in html
    # the same design without its indices: no bars, and what was not explored says so
    bare = ds.drop_vars([*KEYS, "sensitivity_mean", "sensitivity_variance", "input", "output"])
    assert set(design_figures(bare, "light")) == {"light_design"}
    found = design_findings(bare, design_rows(bare))
    assert found.numbers[-1].endswith("; sensitivity not computed (give the analysis a sensitivity table).")
    assert design_evidence(bare, design_rows(bare), None)[0].sentence.endswith("; its sensitivity not computed (light).")
