"""Design search (issue 27 item 1): common random numbers, the winner's independent check, same
seeds -> same result, a resumed search -> the same bits, the CLI and ``rotorlab run``.

The physics runs on the built-in ``autobalancer`` (seed 002 numbers; its compiled driver is shared
with the basin tests) at 2400 rpm = 2 p with short horizons and few starts; the closed-form
optimum (Den Hartog's absorber) is in tests/validation/test_design_den_hartog.py.
"""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses._design_case import check_agrees, design_rows, recommendation, run_design_analysis
from rotorlab.cli import app
from rotorlab.io import DesignSpec, load_case
from rotorlab.sweep import open_sweep

RPM = 2.0 * np.pi / 60.0
SPEC = {"name": "balls", "vary": {"ball_mass": ["8 g", "40 g"], "ball_damping": ["1e-3 N*m*s", "4e-3 N*m*s"]},
        "objectives": ["ball-mass"], "param": {"spin_speed": ["2400 rpm", "2400 rpm", 1]}, "starts": 32,
        "min_balanced": 0.85, "budget": 6, "n_horizons": 2, "seed": 3}  # fmt: skip


@pytest.fixture(scope="module")
def case():
    return load_case("autobalancer")


def _spec(**kw):
    return DesignSpec.model_validate({**SPEC, **kw})


def _data(ds):
    """The results without the timings (CPU seconds differ from run to run)."""
    out = ds.copy()
    out.attrs = {k: v for k, v in ds.attrs.items() if not k.endswith("cpu_s")}
    return out


@pytest.fixture(scope="module")
def searched(case, tmp_path_factory):
    store = tmp_path_factory.mktemp("design") / "evals"
    return run_design_analysis(case.model, _spec(), store=store), store


def test_every_design_sees_the_same_starts_and_the_check_fresh_ones(searched):
    ds, store = searched
    evals = sorted(store.glob("eval-*.zarr"))
    assert len(evals) == ds.attrs["evaluations"] == 6
    starts = [open_sweep(p)["start_psi_1"].values for p in evals]
    for s in starts[1:]:
        np.testing.assert_array_equal(s, starts[0])  # common random numbers
    (check,) = store.glob("verify-*.zarr")
    fresh = open_sweep(check)["start_psi_1"].values
    assert fresh.shape == starts[0].shape and not np.any(np.isin(fresh, starts[0]))  # independent starts


def test_the_winner_is_the_lightest_feasible_design_and_its_fresh_check_lies_in_the_search_interval(searched):
    ds, _ = searched
    rows = design_rows(ds)
    feasible = [r for r in rows if r["feasible"]]
    assert feasible, rows
    best = min(feasible, key=lambda r: r["objectives"]["ball-mass"])
    assert ds.attrs["best"] == best["trial"] and best["best"]
    # ball-mass is two balls' mass: 2 m
    assert best["objectives"]["ball-mass"] == pytest.approx(2.0 * best["values"]["ball_mass"], rel=1e-12)
    # the constraint: the Wilson lower bound of the search's starts at 2400 rpm against 0.85
    lo, hi = float(ds.balanced_low.values[best["trial"], 0]), float(ds.balanced_high.values[best["trial"], 0])
    assert best["margins"]["min_balanced"] == pytest.approx(lo - 0.85)
    # the independent re-simulation (32 fresh starts): its share inside the search's interval
    fresh = float(ds.verify_balanced.values[0])
    assert lo <= fresh <= hi and check_agrees(ds) is True
    assert "Build ball_mass = " in recommendation(ds) and "P(balanced) >= " in recommendation(ds)
    # the verdict line (VERDICT_EVIDENCE): the recommendation, confirmed; none feasible is a "no"
    from rotorlab.analyses import VERDICT_EVIDENCE

    (line,) = VERDICT_EVIDENCE["design"](ds, rows, None)
    assert line.status == "yes" and "confirmed from fresh random starts" in line.sentence
    none = ds.copy()
    none.attrs["best"] = -1
    (line,) = VERDICT_EVIDENCE["design"](none, rows, None)
    assert line.status == "no" and "No design of the 6 evaluated met every constraint" in line.sentence
    # two balls cancel the unbalance only if 2 m R >= M1 e (seed 002 eq. (17), eta / 2 < 1): m >= 15 g here
    light = [r for r in rows if r["values"]["ball_mass"] < 1.0 * 1.5e-3 / (2 * 0.05)]
    assert light and all(not r["feasible"] and ds.balanced.values[r["trial"], 0] == 0.0 for r in light)


def test_same_seeds_give_the_same_result_a_resumed_search_and_dask_workers_the_same_bits(case, searched, tmp_path):
    ds, store = searched
    again = run_design_analysis(case.model, _spec())  # in memory, from scratch
    assert _data(again).identical(_data(ds))
    # an interrupted search: some designs' stores lost, the check's too; resuming recomputes them
    copy = tmp_path / "evals"
    shutil.copytree(store, copy)
    for p in sorted(copy.glob("eval-*.zarr"))[::2] + list(copy.glob("verify-*.zarr")):
        shutil.rmtree(p)
    resumed = run_design_analysis(case.model, _spec(), store=copy, resume=True)
    assert _data(resumed).identical(_data(ds))
    # on two local Dask workers (one cluster for the whole search): the same bits
    from rotorlab.sweep import DaskExecutor

    on_dask = run_design_analysis(case.model, _spec(), executor=DaskExecutor(workers=2, threads=1))
    assert _data(on_dask).identical(_data(ds))
    # another optimiser seed proposes other designs
    other = run_design_analysis(case.model, _spec(optimizer_seed=1))
    assert not np.array_equal(other.value.values, ds.value.values)


def test_two_objectives_give_a_pareto_front(case):
    ds = run_design_analysis(case.model, _spec(objectives=["ball-mass", "residual-vibration"], budget=6, verify=False))
    obj = ds.objective_value.values
    front = ds.pareto.values
    assert front.any() and np.all(ds.feasible.values[front])
    for i in np.flatnonzero(front):  # no feasible design is at least as good in both and better in one
        better = np.all(obj[ds.feasible.values] <= obj[i], axis=1) & np.any(obj[ds.feasible.values] < obj[i], axis=1)
        assert not better.any()
    for i in np.flatnonzero(ds.feasible.values & ~front):  # every other feasible one is dominated
        assert np.any(np.all(obj[front] <= obj[i], axis=1))
    assert np.isnan(ds.verify_balanced.values).all() and check_agrees(ds) is None
    # the report's trade-off figure: the feasible designs' two objectives, the front among them
    from rotorlab.plot._design import design_figures

    figures = design_figures(ds, "two")
    assert set(figures) == {"two_design", "two_tradeoff"}
    ax = figures["two_tradeoff"].axes[0]
    assert "ball-mass" in ax.get_xlabel() and "residual-vibration" in ax.get_ylabel()
    (line,) = ax.lines  # the front, joined in order of the first objective
    np.testing.assert_array_equal(line.get_xdata(), np.sort(obj[front, 0]))


def test_the_design_command_and_rotorlab_run_with_a_design_analysis(case, tmp_path):
    from importlib import resources

    toml = tmp_path / "case.toml"
    base = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    block = ('[[analysis]]\ntype = "design"\nname = "light"\nvary = {ball_mass = ["20 g", "40 g"]}\n'
             'objectives = ["ball-mass"]\nparam = {spin_speed = ["2400 rpm", "2400 rpm", 1]}\nstarts = 32\n'
             'min_balanced = 0.85\nbudget = 3\nn_horizons = 2\n')  # fmt: skip
    toml.write_text(base.split("[[analysis]]")[0] + block, encoding="utf-8")  # the model and this analysis only
    res = CliRunner().invoke(app, ["design", str(toml), "--json", "--out", str(tmp_path / "d.nc")])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["best"] >= 0 and doc["check"]["inside_search_interval"] is True and len(doc["rows"]) == 3
    import xarray as xr

    with xr.open_dataset(tmp_path / "d.nc") as back:
        assert int(back.attrs["best"]) == doc["best"] and back.sizes["trial"] == 3
    out = tmp_path / "run"
    res = CliRunner().invoke(app, ["run", str(toml), "--out", str(out)])
    assert res.exit_code == 0, res.output
    html = next(out.glob("*.html")).read_text(encoding="utf-8")
    assert "Build ball_mass = " in html and "Not explored:" in html and "fresh random starts" in html
    assert (out / "light_design.png").exists() or list(out.rglob("light_design.png"))


def test_the_problem_names_the_key_path_and_what_is_allowed():
    from rotorlab.analyses import DesignProblem, DesignVariable, build_model

    machine = build_model(load_case("pico21-balancer").model)
    ops = np.array([1000.0])

    def refusal(variables, objectives=("ball-mass",), **kw):
        with pytest.raises(ValueError) as err:
            DesignProblem(machine, variables, objectives, ops, **kw)
        return str(err.value)

    # a name that changes the compiled layout (the structure's mode count) is refused, saying so
    assert "vary.n_modes: changes the compiled layout" in refusal((DesignVariable("n_modes", 2, 4),))
    text = refusal((DesignVariable("races[0].balls[0].mass", -0.01, 0.02),))
    assert "vary.races[0].balls[0].mass: -0.01 is outside the parameter's range: must be > 0 kg" in text
    text = refusal((DesignVariable("nope", 0.0, 1.0),))
    assert "vary.nope: not a named parameter of this model (allowed: " in text and "races[0].balls[0].mass" in text
    assert "'fastest' is not an objective (allowed: ball-mass" in refusal(
        (DesignVariable("races[0].balls[0].mass", 0.01, 0.02),), ("fastest",))
    # P(balanced) needs random starts: a model without its mapper is refused
    assert "min_balanced: needs a model with a regime mapper" in refusal(
        (DesignVariable("races[0].balls[0].mass", 0.01, 0.02),), min_balanced=0.99)
    ok = DesignProblem(machine, (DesignVariable("model.races[0].balls[0].mass", 0.01, 0.02),), ("ball-mass",), ops)
    assert ok.parameter("model.races[0].balls[0].mass").unit == "kg"
