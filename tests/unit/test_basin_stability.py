"""Basin stability over a parameter (issue 26 item 2): P(balanced), P(each other motion) and
P(not settled) with Wilson intervals at every value, from seeded random starts, adaptive until the
intervals are as narrow as asked, on the sweep engine.

The statistics run on a case with a known fraction (a pure-numpy analysis: a start "hits" where its
angle is below 2 pi p, so P(hit) = p exactly); the physics on the built-in ``autobalancer`` (seed
002 numbers, its compiled driver shared with the other tests), against long-horizon grids.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.stats import binom, binomtest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.explore import RandomStarts, basin_stability_over, starts_for_half_width, wilson_interval
from rotorlab.io import BasinStabilitySpec, load_case
from rotorlab.sweep import ChunkVar, DaskExecutor, GridAxis

D = math.radians
TURN = {"psi_1": (0.0, 2.0 * math.pi)}


@dataclass(frozen=True)
class KnownFraction:
    """A start hits (label 0) where psi_1 < 2 pi p: P(hit) = p for psi_1 uniform over a turn."""

    coordinate_units = {"psi_1": "rad", "p": "1"}

    def run_chunk(self, coords, threads=None):
        miss = (coords["psi_1"] >= 2.0 * math.pi * coords["p"]).astype(np.int16)
        flag = {"labels": ["hit", "miss"], "units": "1"}
        n = miss.size
        return {"label": ChunkVar(("horizon",), miss[:, None], flag), "outcome": ChunkVar((), miss, flag),
                "status": ChunkVar((), np.zeros(n, np.int32), {"units": "1"}),
                "label_since": ChunkVar((), np.ones(n), {"units": "s"})}  # fmt: skip

    def trailing_coords(self):
        return {"horizon": (np.array([1.0]), {"units": "s"})}

    def result_attrs(self):
        return {"labels": ["hit", "miss"]}


def test_wilson_interval_is_scipys_in_closed_form():
    rng = np.random.default_rng(5)
    for _ in range(40):
        n = int(rng.integers(1, 3000))
        k = int(rng.integers(0, n + 1))
        conf = float(rng.choice([0.8, 0.95, 0.99]))
        ci = binomtest(k, n).proportion_ci(confidence_level=conf, method="wilson")
        lo, hi = wilson_interval(k, n, conf)
        assert float(lo) == pytest.approx(ci.low, abs=1e-12) and float(hi) == pytest.approx(ci.high, abs=1e-12)
    # n broadcast against the counts; the half-width bound of starts_for_half_width holds at k = n/2
    lo, hi = wilson_interval(np.array([[0, 5], [10, 20]]), np.array([[10], [20]]))
    assert lo.shape == (2, 2) and hi[0, 0] == pytest.approx(0.2775, abs=1e-4) and hi[1, 1] == 1.0
    n = starts_for_half_width(0.01)
    assert np.diff(wilson_interval(n // 2, n))[0] / 2 <= 0.01 < np.diff(wilson_interval(n // 2 - 1, n - 2))[0] / 2


def test_wilson_coverage_by_simulation_on_a_known_fraction():
    # 3000 independent seeds of 40 starts at p = 0.3: the share of intervals that hold p agrees with
    # the exact coverage sum_k Binom(k; 40, 0.3) [p in CI(k)] (0.9406 for n = 40: Wilson's is not exact)
    n, p, seeds = 40, 0.3, 3000
    k_all = np.arange(n + 1)
    lo, hi = wilson_interval(k_all, n)
    exact = float(np.sum(binom.pmf(k_all, n, p) * ((lo <= p) & (p <= hi))))
    assert 0.93 < exact < 0.96
    ks = np.array([np.count_nonzero(RandomStarts(KnownFraction(), (("psi_1", 0.0, 2 * math.pi),), s)
                                    .draw(np.arange(n))["psi_1"] < 2 * math.pi * p) for s in range(seeds)])  # fmt: skip
    assert abs(ks.mean() / n - p) < 4 * math.sqrt(p * (1 - p) / (n * seeds))  # the draws are uniform
    covered = np.mean((lo[ks] <= p) & (p <= hi[ks]))
    assert abs(covered - exact) < 4 * math.sqrt(exact * (1 - exact) / seeds), (covered, exact)
    # the pipeline counts exactly those starts, and adaptive sampling keeps the coverage: 60 seeds
    # x 5 fractions, each sampled until its interval is within +-0.1
    ds = basin_stability_over(KnownFraction(), GridAxis("p", 0.3, 0.3, 1), TURN, seed=7, starts=n)
    assert int(ds["count"].values[0, -1, 0]) == ks[7] and float(ds.ci_low[0, 0]) == pytest.approx(lo[ks[7]])
    hits, total = 0, 0
    truth = np.linspace(0.1, 0.9, 5)
    for seed in range(60):
        ds = basin_stability_over(KnownFraction(), GridAxis("p", 0.1, 0.9, 5), TURN, seed=seed, ci_width=0.1,
                                  chunk_size=16)  # fmt: skip
        assert np.all(ds.half_width.values <= 0.1)
        hits += int(np.sum((ds.ci_low.values[:, 0] <= truth) & (truth <= ds.ci_high.values[:, 0])))
        total += truth.size
    assert 0.91 <= hits / total <= 0.99, hits / total


def test_adaptive_rounds_reach_the_width_and_stop_early_where_the_fraction_is_extreme():
    ds = basin_stability_over(KnownFraction(), GridAxis("p", 0.0, 0.5, 3), TURN, seed=1, ci_width=0.03)
    n = ds.n.values
    assert np.all(ds.half_width.values <= 0.03) and ds.attrs["rounds"] >= 2
    # p = 0: no start hits, 128 starts do (upper end 3.8 / n); p = 1/2 needs the most
    assert n[0] == 128 and n[2] > n[1] > n[0] and n[2] <= starts_for_half_width(0.03) + 127
    assert ds.probability.values[0, 0] == 0.0 and abs(ds.probability.values[2, 0] - 0.5) < 0.03
    assert np.all(ds.computed.values.sum(axis=1) == n) and np.all(ds.outcome.values[~ds.computed.values] == -1)


def test_results_are_the_same_from_memory_a_store_a_resume_and_dask(tmp_path):
    kw = {"seed": 4, "ci_width": 0.04, "chunk_size": 32}
    axis = GridAxis("p", 0.2, 0.8, 4)
    ref = basin_stability_over(KnownFraction(), axis, TURN, **kw)
    stored = basin_stability_over(KnownFraction(), axis, TURN, store=tmp_path / "a.zarr", **kw)
    for name in ("n", "count", "outcome", "start_psi_1"):
        np.testing.assert_array_equal(ref[name].values, stored[name].values)

    calls = []

    def stop_after_a_few(done, total):
        calls.append(done)
        if len(calls) == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        basin_stability_over(KnownFraction(), axis, TURN, store=tmp_path / "b.zarr", progress=stop_after_a_few, **kw)
    resumed = basin_stability_over(KnownFraction(), axis, TURN, store=tmp_path / "b.zarr", resume=True, **kw)
    on_dask = basin_stability_over(KnownFraction(), axis, TURN, executor=DaskExecutor(workers=2), **kw)
    for other in (resumed, on_dask):
        for name in ("n", "count", "outcome", "start_psi_1", "ci_low"):
            np.testing.assert_array_equal(ref[name].values, other[name].values)
    # a different seed draws different starts
    other = basin_stability_over(KnownFraction(), axis, TURN, **{**kw, "seed": 5})
    assert not np.array_equal(other.start_psi_1.values, ref.start_psi_1.values)


@pytest.fixture(scope="module")
def case():
    return load_case("autobalancer")


def _run(case, **kw):
    from rotorlab.analyses._basin_stability import run_basin_stability_analysis

    return run_basin_stability_analysis(case.model, BasinStabilitySpec(name="bs", **kw))


def test_autobalancer_at_2p_balances_from_every_start_as_the_long_grid_says(case):
    from rotorlab.analyses._basin import run_basin_analysis
    from rotorlab.analyses._basin_stability import basin_stability_rows

    ds = _run(case, param={"ball_damping": [2e-3, 2e-3, 1]}, ci_width=0.05, seed=2)
    rows = basin_stability_rows(ds)
    # the default horizon: 100 revolutions at 2400 rpm (10 time constants, 1.58 s, are fewer)
    assert float(ds.horizon[-1]) == pytest.approx(2.5, rel=1e-3) and "100 revolutions" in ds.attrs["horizon_rule"]
    assert rows[0]["n"] == 128 and rows[0]["balanced"] == 1.0 and rows[0]["settled"]
    assert rows[0]["balanced_ci"][0] == pytest.approx(1.0 - 3.72 / 128, abs=2e-3)  # Wilson's lower end, 0 misses
    assert rows[0]["time_constant_s"] == pytest.approx(1.0 / 6.331, rel=1e-3)  # the slowest mode (test_settle.py)
    # a long-horizon grid (20 s, 127 time constants): every start off the diagonal balances
    grid = run_basin_analysis(case.model, case.analysis("basin").model_copy(
        update={"x": ("psi_1", D(5), D(335), 6), "y": ("psi_2", D(12), D(342), 6)}))  # fmt: skip
    off = np.asarray(grid.outcome.values).ravel()
    assert np.all(off == 0)
    assert rows[0]["balanced_ci"][0] <= off.size / off.size <= rows[0]["balanced_ci"][1]


def test_settle_times_of_the_random_starts_follow_the_slowest_eigenvalue(case):
    # the same seeded starts: at 1 s some are still converging, with a settle time extrapolated at
    # the balanced state's slowest mode; classified every 0.05 s up to 2 s, they balance then
    short = _run(case, param={"ball_damping": [2e-3, 2e-3, 1]}, starts=48, seed=3, t_end=1.0, n_horizons=2,
                 window_revolutions=2.0)  # fmt: skip
    fine = _run(case, param={"ball_damping": [2e-3, 2e-3, 1]}, starts=48, seed=3, t_end=2.0, n_horizons=40,
                window_revolutions=2.0)  # fmt: skip
    np.testing.assert_array_equal(short.start_psi_1.values, fine.start_psi_1.values)
    names = [str(r) for r in short.regime.values]
    waiting = short.outcome.values[0] == names.index("not settled")
    assert waiting.sum() >= 3 and short.probability.values[0, names.index("not settled")] == waiting.mean()
    est = short.settle_estimate.values[0][waiting]
    assert np.all(fine.outcome.values[0] == 0)
    since = fine.label_since.values[0][waiting]
    assert np.all(np.abs(since - est) <= 0.06), (since, est)
    from rotorlab.analyses._basin_stability import basin_stability_rows

    row = basin_stability_rows(short)[0]
    assert not row["settled"] and "too short for a verdict" in row["verdict"]


def test_coexisting_whirl_is_named_and_its_share_agrees_with_a_long_grid(case):
    from rotorlab.analyses._basin import run_basin_analysis
    from rotorlab.analyses._basin_stability import basin_stability_rows
    from rotorlab.report._basin_stability import basin_stability_findings

    ds = _run(case, param={"ball_damping": [2e-4, 2e-3, 2]}, ci_width=0.05, seed=0)
    rows = basin_stability_rows(ds)
    low = rows[0]
    assert low["half_width"] <= 0.05 and low["n"] > rows[1]["n"]
    assert low["fractions"]["non-synchronous"] > 0.3 and "not balanced" not in low["fractions"]
    grid = run_basin_analysis(case.model, case.analysis("basin").model_copy(update={
        "x": ("psi_1", D(5), D(355), 12), "y": ("psi_2", D(12), D(342), 12), "t_end": 40.0,
        "fixed": {"ball_damping": 2e-4}}))  # fmt: skip
    frac = grid.fraction.isel(horizon=-1).values
    names = [str(r) for r in grid.regime.values]
    glo, ghi = wilson_interval(grid["count"].isel(horizon=-1).values, int(grid["count"].isel(horizon=-1).sum()))
    for label in ("balanced", "non-synchronous"):  # the two estimates' intervals overlap
        k = names.index(label)
        lo, hi = low["ci"][label]
        assert lo <= ghi[k] and glo[k] <= hi, (label, low["ci"][label], frac[k])
    verdict = basin_stability_findings(ds, rows).verdict
    assert "A non-synchronous whirl takes up to" in verdict and "balanced ranges from" in verdict


def test_command_json_figure_and_netcdf(tmp_path):
    import xarray as xr

    args = ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--starts", "24", "--t-end",
            "1.0", "--seed", "9", "--range", "psi_1=0:180deg", "--range", "psi_2=180:360deg", "--plot",
            str(tmp_path / "f.png"), "--out", str(tmp_path / "r.nc")]
    res = CliRunner().invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["param"] == "ball_damping" and doc["values"] == [1e-3, 2e-3] and doc["mode"] == "starts"
    assert [r["n"] for r in doc["rows"]] == [24, 24] and doc["starts_total"] == 48 and doc["seed"] == 9
    assert doc["ranges"] == {"psi_1": [0.0, pytest.approx(math.pi)], "psi_2": [pytest.approx(math.pi),
                                                                                pytest.approx(2 * math.pi)]}
    assert all(abs(sum(r["fractions"].values()) - 1.0) < 1e-12 for r in doc["rows"])
    assert (tmp_path / "f.png").stat().st_size > 10_000
    back = xr.open_dataset(tmp_path / "r.nc")
    np.testing.assert_allclose(back.probability.values[:, 0], [r["balanced"] for r in doc["rows"]])
    text = CliRunner().invoke(app, [*args[:-4]]).stdout
    assert "basin-stability: Over ball_damping" in text and "Wilson 95 %" in text


def test_range_unit_applies_to_both_ends(tmp_path):
    # psi_1=10:170deg:3 was read as 10 rad to 170 deg
    res = CliRunner().invoke(app, ["basin", "autobalancer", "--x", "psi_1=10:170deg:3", "--y",
                                   "psi_2=200:350deg:2", "--t-end", "0.05", "--out", str(tmp_path / "b.nc")])
    assert res.exit_code == 0, res.output
    import xarray as xr

    ds = xr.open_dataset(tmp_path / "b.nc")
    np.testing.assert_allclose(np.degrees(ds.psi_1.values), [10.0, 90.0, 170.0])
    np.testing.assert_allclose(np.degrees(ds.psi_2.values), [200.0, 350.0])


def test_random_starts_over_the_rotor_state(case):
    from rotorlab.analyses._basin import basin_mapper

    mapper = basin_mapper(case.model, case.analysis("basin"))
    omega = mapper.model.speed.speed
    assert omega == pytest.approx(2.0 * 125.668, rel=1e-5)  # 2 p, the basin's speed_ratio
    model, y0, _ = mapper.starts({"rotor_u": np.array([1e-3, 0.0]), "rotor_v": np.array([0.0, -2e-3]),
                                  "psi_1": np.array([1.0, 1.0])})  # fmt: skip
    # fixed frame at t = 0: the disc centre at (u, v), moving with the rotor, omega x r
    assert model.frame == "fixed"
    np.testing.assert_allclose(y0[:, :4], [[1e-3, 0.0, 0.0, omega * 1e-3], [0.0, -2e-3, omega * 2e-3, 0.0]],
                               rtol=1e-12, atol=1e-15)  # fmt: skip
    # the unbalance alone deflects the disc by 1.88 mm at 2 p: starts anywhere within +-2 mm balance
    ds = _run(case, param={"ball_damping": [2e-3, 2e-3, 1]}, starts=32, seed=1,
              ranges={"psi_1": [0.0, 2 * math.pi], "psi_2": [0.0, 2 * math.pi], "rotor_u": [-2e-3, 2e-3],
                      "rotor_v": [-2e-3, 2e-3]})  # fmt: skip
    u = ds.start_rotor_u.values[0]
    assert u.min() < -1e-3 and u.max() > 1e-3 and np.all(ds.outcome.values[0] == 0)


def test_a_case_file_analysis_runs_under_rotorlab_run_with_its_report(tmp_path):
    from importlib import resources

    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    text = text[: text.index("[[analysis]]")] + '''
[[analysis]]
type = "basin-stability"
name = "damping-range"
param = {ball_damping = ["1e-3 N*m*s", "2e-3 N*m*s", 2]}
starts = 16
seed = 1
t_end = "1 s"
'''
    (tmp_path / "c.toml").write_text(text, encoding="utf-8")
    res = CliRunner().invoke(app, ["run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert "damping-range: Over ball_damping" in res.stdout
    html = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert "the share of random start-ups that end balanced" in html and "16 starts per value" in html
    assert list((tmp_path / "out").rglob("damping-range_basin_stability.png"))


def test_case_file_checks_name_the_key(case, tmp_path):
    from importlib import resources

    from pydantic import ValidationError

    spec = BasinStabilitySpec(param={"ball_damping": [1e-3, 2e-3, 2]}, ci_width=0.001)
    issue = spec.case_issues(case.model)[0]
    assert issue.loc == ("ci_width",) and "must be >= 0.00219" in issue.message and "200000 starts" in issue.message
    with pytest.raises(ValidationError, match="psi_1: unknown param coordinate"):
        BasinStabilitySpec(param={"psi_1": [0.0, 1.0, 2]})
    third = BasinStabilitySpec(param={"ball_damping": [1e-3, 2e-3, 2]}, ranges={"psi_3": [0.0, 1.0]})
    assert [(i.loc, i.message) for i in third.case_issues(case.model)] == [(("ranges", "psi_3"), "the model has 2 ball(s)")]
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    text = text[: text.index("[[analysis]]")] + ('[[analysis]]\ntype = "basin-stability"\nparam = {ball_damping = '
                                                 '[1e-3, 2e-3, 2]}\nstarts = 10\nci_width = 0.1\n')
    (tmp_path / "c.toml").write_text(text, encoding="utf-8")
    res = CliRunner().invoke(app, ["validate", str(tmp_path / "c.toml")])
    assert res.exit_code == 2 and "analysis[0]" in res.output and "ci_width" in res.output, res.output


def test_balancer_group_in_arrays_is_classify_per_start(case):
    # group() labels whole chunks in array operations (it holds the GIL); one classify call per
    # start and horizon is the reference, on features spread around every threshold
    from rotorlab.analyses._basin import basin_mapper
    from rotorlab.explore._outcome import classify
    from rotorlab.explore._settle import NOT_SETTLED
    from rotorlab.integrate import Status

    mapper = basin_mapper(case.model, case.analysis("basin"))
    rng = np.random.default_rng(11)
    n, h = 3000, 3
    ref = rng.uniform(1e-3, 3e-3, n)
    f = {"amplitude": ref[:, None] * rng.choice([0.01, 0.049, 0.051, 0.5, 2.0], (n, h)),
         "reference_amplitude": ref, "rotor_speed": rng.choice([250.0, -250.0], n),
         "max_rate": 250.0 * rng.choice([0.0, 0.9e-4, 1.1e-4, 1e-2, np.nan], (n, h)),
         "status_code": rng.choice([0, 0, 0, 1, -1, -3], n),
         "settle_estimate": np.where(rng.random((n, h)) < 0.2, 5.0, np.nan)}  # fmt: skip
    for b in (1, 2):  # near 0, near 180 deg, in between, just inside/outside the 30 deg tolerance, NaN
        degrees = rng.choice([0.0, 10.0, -29.0, 31.0, 90.0, 175.0, -151.0, 149.0, np.nan], (n, h))
        f[f"ball_angle_{b}"] = np.radians(degrees)
    f["amplitude"][rng.random((n, h)) < 0.02] = np.nan
    got = mapper.group(f)
    names = mapper.labels
    for i, j in np.ndindex(n, h):
        code = int(f["status_code"][i])
        text = classify(code, Status(code).message, f["amplitude"][i, j], ref[i],
                        [f["ball_angle_1"][i, j], f["ball_angle_2"][i, j]], f["max_rate"][i, j], f["rotor_speed"][i])
        if text != "balanced" and code >= 0 and np.isfinite(f["settle_estimate"][i, j]):
            text = NOT_SETTLED
        assert got[i, j] == (names.index(text) if text in names else names.index("other")), (i, j, text)
    assert len(set(got.ravel().tolist())) == len(names)  # every label occurs
