"""The tolerances analysis (issue 27 item 3): Sobol indices through rotorlab's own wrapper
(:func:`rotorlab.explore.run_sensitivity` on the sweep engine) checked against closed forms, the
distributions, same seeds / resumed runs giving the same bits, and the machine analysis end to end
(Python and command line)."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from importlib import resources

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.explore._sensitivity import Distribution, UncertainInput, run_sensitivity, sobol_sample
from rotorlab.sweep import ChunkVar

runner = CliRunner()


@dataclass(frozen=True)
class Ishigami:
    """``sin x1 + a sin^2 x2 + b x3^4 sin x1`` as a per-point analysis of the sweep engine."""

    a: float = 7.0
    b: float = 0.1

    @property
    def coordinate_units(self):
        return {"x1": "1", "x2": "1", "x3": "1"}

    def run_chunk(self, c, threads=None):
        y = np.sin(c["x1"]) + self.a * np.sin(c["x2"]) ** 2 + self.b * c["x3"] ** 4 * np.sin(c["x1"])
        return {"y": ChunkVar((), y, {"units": "1"})}

    def trailing_coords(self):
        return {}

    def result_attrs(self):
        return {}


@dataclass(frozen=True)
class Additive:
    """``x1 + 2 x2 + x3``: each input's first- and total-order index is its share of the variance."""

    @property
    def coordinate_units(self):
        return {"x1": "1", "x2": "1", "x3": "1"}

    def run_chunk(self, c, threads=None):
        return {"y": ChunkVar((), c["x1"] + 2.0 * c["x2"] + c["x3"], {"units": "1"})}

    def trailing_coords(self):
        return {}

    def result_attrs(self):
        return {}


PI_BOX = Distribution("uniform", low=-math.pi, high=math.pi)


def test_ishigami_indices_through_the_wrapper():
    # Ishigami & Homma (1990), a = 7, b = 0.1; the analytic values as quoted by Saltelli et al.
    # (2010) section 4: S1 = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437).
    inputs = [UncertainInput(f"x{i}", PI_BOX) for i in (1, 2, 3)]
    ind, points = run_sensitivity(Ishigami(), inputs, ["y"], n=4096, seed=1, chunk_size=5000)
    assert points.sizes["sample"] == 4096 * 5 and list(ind["input"].values) == ["x1", "x2", "x3"]
    s1, st = ind["S1"].values[0], ind["ST"].values[0]
    np.testing.assert_allclose(s1, [0.3139, 0.4424, 0.0], atol=0.02)
    np.testing.assert_allclose(st, [0.5576, 0.4424, 0.2437], atol=0.02)
    assert np.all(ind["S1_conf"].values < 0.06) and np.all(ind["ST_conf"].values < 0.06)
    # the exact values lie inside the bootstrap intervals
    assert np.all(np.abs(st - [0.5576, 0.4424, 0.2437]) <= ind["ST_conf"].values[0])


def test_an_additive_function_shares_its_variance_by_the_distributions():
    # Var(x1 + 2 x2 + x3) = s1^2 + 4 (1/12) + (1 - 2/pi) for x1 ~ N(1, 0.5), x2 ~ U(0, 1) and x3 a
    # standard normal truncated to [0, inf) (half-normal: mean sqrt(2/pi), variance 1 - 2/pi);
    # for an additive function S1 = ST = each term's share.
    d = [Distribution("normal", mean=1.0, std=0.5), Distribution("uniform", low=0.0, high=1.0),
         Distribution("normal", mean=0.0, std=1.0, low=0.0)]  # fmt: skip
    parts = np.array([0.25, 4.0 / 12.0, 1.0 - 2.0 / math.pi])
    inputs = [UncertainInput(f"x{i + 1}", d[i]) for i in range(3)]
    x = sobol_sample(inputs, 1024, seed=5)
    assert x["x3"].min() >= 0.0 and 0.0 <= x["x2"].min() and x["x2"].max() <= 1.0
    assert abs(np.mean(x["x3"]) - math.sqrt(2.0 / math.pi)) < 0.01
    assert d[2].moments() == pytest.approx((math.sqrt(2.0 / math.pi), 1.0 - 2.0 / math.pi))
    ind, _ = run_sensitivity(Additive(), inputs, ["y"], n=4096, seed=5, chunk_size=5000)
    np.testing.assert_allclose(ind["S1"].values[0], parts / parts.sum(), atol=0.02)
    np.testing.assert_allclose(ind["ST"].values[0], parts / parts.sum(), atol=0.02)
    assert float(ind["variance"].values[0]) == pytest.approx(parts.sum(), rel=0.02)
    assert float(ind["mean"].values[0]) == pytest.approx(1.0 + 1.0 + math.sqrt(2.0 / math.pi), abs=0.01)


@pytest.mark.parametrize("kw, words", [
    ({"kind": "lognormal", "mean": 1.0, "std": 1.0}, ["lognormal", "normal, uniform"]),
    ({"kind": "normal", "mean": 1.0, "std": 0.0}, ["std > 0"]),
    ({"kind": "uniform", "low": 1.0}, ["finite low and high"]),
    ({"kind": "uniform", "low": 2.0, "high": 1.0}, ["low < high"]),
    ({"kind": "normal", "mean": 0.0, "std": 1.0, "low": 50.0}, ["less than 1e-6"]),
])  # fmt: skip
def test_a_bad_distribution_is_refused_saying_why(kw, words):
    with pytest.raises(ValueError) as err:
        Distribution(**kw)
    for word in words:
        assert word in str(err.value)


def test_same_seed_same_bits_and_a_resumed_store_gives_the_same_bits(tmp_path):
    inputs = [UncertainInput(f"x{i}", PI_BOX) for i in (1, 2, 3)]
    ref, ref_points = run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=3, chunk_size=50)
    again, _ = run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=3, chunk_size=320)
    assert ref.identical(again)

    def stop(done, total):
        if done >= 100:
            raise KeyboardInterrupt

    store = tmp_path / "s.zarr"
    with pytest.raises(KeyboardInterrupt):
        run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=3, chunk_size=50, store=store, progress=stop)
    resumed, points = run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=3, store=store, resume=True)
    assert resumed.identical(ref)
    assert np.array_equal(points["y"].values, ref_points["y"].values)
    other, _ = run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=4, chunk_size=320)
    assert not np.array_equal(other["ST"].values, ref["ST"].values)
    # seed 0 too: the bootstrap intervals are drawn from the seed (SALib leaves a seed of 0 unseeded)
    zero = [run_sensitivity(Ishigami(), inputs, ["y"], n=64, seed=0, chunk_size=320)[0] for _ in range(2)]
    assert zero[0].identical(zero[1])


# ---- the machine: pico21-balancer (a model the machine tests compile), short runs ------------------------------

_INPUTS = """[analysis.inputs]
"unbalances[0].magnitude" = { distribution = "normal", tolerance = 0.1 }
ball_damping = { distribution = "uniform", low = "1e-4 N*m*s", high = "4e-4 N*m*s" }
"races[1].balls[0].damping" = { distribution = "uniform", tolerance = 0.5 }
"""


def _case_text(**keys) -> str:
    """pico21-balancer's model with one small tolerances analysis (no other analysis)."""
    text = resources.files("rotorlab.cases").joinpath("pico21-balancer.toml").read_text(encoding="utf-8")
    model = text[:text.index("[[analysis]]")]
    head = "\n".join(f"{k} = {json.dumps(v)}" for k, v in {"samples": 4, "starts": 2, "t_end": "0.02 s",
                                                           "n_horizons": 2, **keys}.items())  # fmt: skip
    return model + f'[[analysis]]\ntype = "tolerances"\nname = "tol"\n{head}\n\n' + _INPUTS


def _case(tmp_path, **keys):
    from rotorlab.io import load_case

    path = tmp_path / "tol.toml"
    path.write_text(_case_text(**keys), encoding="utf-8")
    return path, load_case(path)


def test_the_unbalance_response_depends_on_the_unbalance_alone(tmp_path):
    # Closed form: with the balls locked the unbalance response is a function of the unbalance
    # and the structure only, never of the balls' damping: every variance is the unbalance's
    # (S1 = ST = 1 for it), and the damping inputs' indices are exactly 0 (their columns of the
    # design change nothing). The response per unit unbalance stays within the share the other
    # two unbalances of the case add (|U0 h0 + c| / U0).
    from rotorlab.analyses._tolerances import tolerance_study

    _, case = _case(tmp_path, samples=128, starts=1)
    spec = case.analyses[0]
    point, inputs = tolerance_study(case.model, spec)
    ind, points = run_sensitivity(point, inputs, ["unbalance_response"], n=128, seed=0, chunk_size=128)
    s1, st = ind["S1"].values[0], ind["ST"].values[0]
    assert st[1] == 0.0 and st[2] == 0.0 and s1[1] == 0.0 and s1[2] == 0.0
    assert abs(s1[0] - 1.0) < 0.15 and abs(st[0] - 1.0) < 0.15
    u = points["unbalances[0].magnitude"].values
    assert np.std(u[points["design_row"].values == 0]) == pytest.approx(0.1 * 50e-6, rel=0.1)
    ratio = points["unbalance_response"].values / u
    assert np.ptp(ratio) / np.mean(ratio) < 0.01


def test_the_machine_analysis_resumes_to_the_same_bits(tmp_path):
    from rotorlab.analyses._tolerances import run_tolerances_analysis, tolerances_document

    _, case = _case(tmp_path)
    spec = case.analyses[0]
    ref = run_tolerances_analysis(case.model, spec, chunk_size=4)
    assert ref.sizes["sample"] == 4 * 5 and ref.sizes["start"] == 2 and ref.attrs["failed"] == 0

    def stop(done, total):
        if done >= 8:
            raise KeyboardInterrupt

    store = tmp_path / "m.zarr"
    with pytest.raises(KeyboardInterrupt):
        run_tolerances_analysis(case.model, spec, chunk_size=4, store=store, progress=stop)
    resumed = run_tolerances_analysis(case.model, spec, store=store, resume=True)
    for name in ("p_balanced", "residual_vibration", "transient_peak", "amplitude", "envelope", "S1", "ST"):
        assert np.array_equal(resumed[name].values, ref[name].values, equal_nan=True), name
    doc = tolerances_document(ref)
    assert doc["machines"] == 20 and len(doc["rows"]) == 3 * 3
    # the envelope's band holds its median, and the transient peak is the largest window's
    env = ref["envelope"].values
    assert np.all(env[0] <= env[1]) and np.all(env[1] <= env[2])
    assert np.allclose(ref["transient_peak"].values, ref["amplitude"].max("horizon").mean("start").values)


def test_the_tolerances_command_writes_figures_json_and_the_report(tmp_path):
    from rotorlab.cli import app

    path, _ = _case(tmp_path)
    result = runner.invoke(app, ["tolerances", str(path), "--json", "--plot", str(tmp_path / "s.png"),
                                 "--envelope", str(tmp_path / "e.png"), "--out", str(tmp_path / "t.nc")])  # fmt: skip
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    on_dask = runner.invoke(app, ["tolerances", str(path), "--json", "--workers", "2"])
    assert on_dask.exit_code == 0, on_dask.output
    assert json.loads(on_dask.stdout)["rows"] == doc["rows"]  # the same numbers on a local Dask cluster
    assert doc["inputs"] == ["unbalances[0].magnitude", "ball_damping", "races[1].balls[0].damping"]
    assert doc["machines"] == 20 and doc["failed"] == 0
    assert all((tmp_path / f).stat().st_size > 1000 for f in ("s.png", "e.png", "t.nc"))
    out = tmp_path / "report"
    result = runner.invoke(app, ["run", str(path), "--out", str(out)])
    assert result.exit_code == 0, result.output
    html = next(out.rglob("*.html")).read_text(encoding="utf-8")
    assert "tol_sensitivity" in html and "tol_envelope" in html and "Uncertain inputs" in html


def test_the_verdict_names_the_input_p_balanced_is_most_sensitive_to():
    import xarray as xr

    from rotorlab.analyses import VERDICT_EVIDENCE

    ds = xr.Dataset({"ST": (("output", "input"), [[0.1, 0.62], [0.9, 0.0]]),
                     "ST_conf": (("output", "input"), [[0.02, 0.05], [0.1, 0.0]])},
                    coords={"output": ["p_balanced", "transient_peak"], "input": ["ball_mass", "ball_damping"]},
                    attrs={"name": "tol"})  # fmt: skip
    line, = VERDICT_EVIDENCE["tolerances"](ds, [], None)
    assert (line.topic, line.status) == ("tolerances", "info")
    assert line.sentence == "P(balanced) is most sensitive to ball_damping (total Sobol index 0.62 ± 0.05; tol)."
    flat = ds.copy()
    flat["ST"][0] = np.nan  # P(balanced) did not vary: no line
    assert VERDICT_EVIDENCE["tolerances"](flat, [], None) == []


def test_sobol_indices_of_the_unbalance_response_match_the_closed_form_of_u_times_g(tmp_path):
    # Closed form (two independent inputs): with the balls locked the unbalance response of the
    # linear rotor is Y = U G(s), U the unbalance ~ N(U0, (0.1 U0)^2) and G(s) the response per
    # unit unbalance of the structure with its elastic stiffness scaled by s ~ U(0.6, 1.4). Then
    #   V = E[U^2] E[G^2] - E[U]^2 E[G]^2,   S1_U = Var(U) E[G]^2 / V,   S1_s = E[U]^2 Var(G) / V,
    #   ST_U = Var(U) E[G^2] / V,            ST_s = E[U^2] Var(G) / V
    # (Sobol 1993; the interaction Var(U) Var(G) / V is in both totals). E[G], E[G^2] by Gauss-Legendre
    # quadrature of G over s (20 nodes; G is smooth). G is the simulated machine's own locked response
    # (its 6 kept modes, the reference every sample reports), within 5 % of the full structure's
    # (the kept modes' truncation at 10000 rpm). pico21-balancer with its couple's two unbalances set
    # to zero, so that Y is exactly U G(s).
    from rotorlab.analyses._machine_common import unbalance_amplitudes
    from rotorlab.analyses._tolerances import tolerance_study
    from rotorlab.io import load_case

    text = _case_text(samples=512, starts=1).replace('magnitude = "20 g*mm"', 'magnitude = "0 g*mm"')
    text = text[:text.index("[analysis.inputs]")] + (
        '[analysis.inputs]\n"unbalances[0].magnitude" = { distribution = "normal", tolerance = 0.1 }\n'
        '"structure.elastic.scale" = { distribution = "uniform", low = 0.6, high = 1.4 }\n')
    path = tmp_path / "ug.toml"
    path.write_text(text, encoding="utf-8")
    case = load_case(path)
    spec = case.analyses[0]
    point, inputs = tolerance_study(case.model, spec)
    ind, points = run_sensitivity(point, inputs, ["unbalance_response"], n=512, seed=2, chunk_size=512)

    u0, speed = 50e-6, float(point.mapper.regimes.model.drive.speed)

    def g(s):
        m = point.mapper.variant({"structure.elastic.scale": s, "unbalances[0].magnitude": 1.0})
        full = float(np.max(unbalance_amplitudes(m, speed)))
        kept = float(point.mapper.regimes._locked_response(m.to_array()).max())
        assert kept == pytest.approx(full, rel=0.05)
        return kept

    x, w = np.polynomial.legendre.leggauss(20)
    s = 1.0 + 0.4 * x
    gs = np.array([g(v) for v in s])
    eg, eg2 = float(np.sum(w * gs) / 2.0), float(np.sum(w * gs**2) / 2.0)
    var_u, eu, eu2 = (0.1 * u0) ** 2, u0, u0**2 * 1.01
    v = eu2 * eg2 - eu**2 * eg**2
    exact_s1 = np.array([var_u * eg**2, eu**2 * (eg2 - eg**2)]) / v
    exact_st = np.array([var_u * eg2, eu2 * (eg2 - eg**2)]) / v
    assert 0.7 < exact_s1[0] < 0.9 and 0.1 < exact_s1[1] < 0.3  # both inputs matter, U most
    # every sample is U G(s) (to the linear solve's round-off)
    first = np.flatnonzero(points["design_row"].values == 0)[:8]
    u = points["unbalances[0].magnitude"].values[first]
    scale = points["structure.elastic.scale"].values[first]
    np.testing.assert_allclose(points["unbalance_response"].values[first], u * np.array([g(v) for v in scale]),
                               rtol=1e-9)
    s1, st = ind["S1"].values[0], ind["ST"].values[0]
    s1c, stc = ind["S1_conf"].values[0], ind["ST_conf"].values[0]
    # N = 512 base samples (2048 machines): within 0.05 of the closed form, inside the 95 % bootstrap intervals
    np.testing.assert_allclose(s1, exact_s1, atol=0.05)
    np.testing.assert_allclose(st, exact_st, atol=0.05)
    assert np.all(np.abs(s1 - exact_s1) <= s1c) and np.all(np.abs(st - exact_st) <= stc), (s1, st, s1c, stc)
