"""``rotorlab show`` on stores of any per-point analysis, and ``rotorlab sweep --per-point stability``.

The stability sweep's verdicts equal :func:`rotorlab.steady.stability_chart` bit for bit, also after
an interruption (a progress callback raising KeyboardInterrupt) and ``--resume``.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.cli import _sweep_common as cli_sweep
from rotorlab.cli import app
from rotorlab.sweep import open_sweep, store_info

runner = CliRunner()
STAB = ["sweep", "zhakash-k2", "--per-point", "stability", "--param", "ball_mass=20g:40g:2",
        "--param", "speed_rpm=500:3000:3", "--chunk", "2"]  # fmt: skip
VARS = ("exists", "stable_hamilton", "stable_averaged", "stable_exact", "growth_rate", "amplitude", "h_tilde")


def invoke(*args: str):
    return runner.invoke(app, list(args))


def test_show_names_the_analysis_of_an_impact_store(tmp_path):
    out = tmp_path / "x.zarr"
    res = invoke("--quiet", "impacts-sweep", "krasnov-crusher", "--stone-mass", "0.5:1:2", "--sequences", "2",
                 "--t-end", "0.3", "--out", str(out))  # fmt: skip
    assert res.exit_code == 0, res.output
    res = invoke("show", str(out))
    assert res.exit_code == 0, res.output
    assert "analysis: impact-points" in res.output and "analysis: ?" not in res.output
    assert "4 finished runs" in res.output and "impacts per run" in res.output
    doc = json.loads(invoke("show", str(out), "--json").stdout)
    assert doc["analysis"] == "impact-points" and doc["fractions"] is None and doc["figures"] == []
    assert doc["impacts"]["n"] == 4 and sum(doc["impacts"]["regimes"].values()) == pytest.approx(1.0)


def _chart(ds):
    from rotorlab.analyses import build_model
    from rotorlab.io import load_case
    from rotorlab.steady import stability_chart

    model = build_model(load_case("zhakash-k2").model)
    return stability_chart(model, ds.spin_speed.values, param="ball_mass", values=ds.ball_mass.values)


def test_stability_sweep_equals_stability_chart_and_resumes_bit_identical(tmp_path, monkeypatch):
    full = tmp_path / "full.zarr"
    res = invoke(*STAB, "--out", str(full))
    assert res.exit_code == 0, res.output
    assert "a main (balanced) motion" in res.output
    ds = open_sweep(full)
    assert ds.sizes["ball_mass"] == 2 and ds.sizes["spin_speed"] == 3 and ds.spin_speed.attrs["units"] == "rad/s"
    np.testing.assert_array_equal(ds.spin_speed.values, np.linspace(500, 3000, 3) * 2 * np.pi / 60)
    chart = _chart(ds)
    for name in VARS:
        assert ds[name].values.tobytes() == chart[name].values.tobytes(), name

    # interrupted after two chunks (the bar is called at the start and after each chunk), then resumed
    part = tmp_path / "part.zarr"
    calls = []

    def stop(self, p):
        calls.append(p)
        if len(calls) == 3:
            raise KeyboardInterrupt

    monkeypatch.setattr(cli_sweep.SweepBar, "__call__", stop)
    res = invoke(*STAB, "--out", str(part))
    assert res.exit_code == 130 and store_info(part)["chunks_done"] == 2
    monkeypatch.undo()
    res = invoke(*STAB, "--out", str(part), "--resume", "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["chunks"] == {"total": 3, "computed": 1, "skipped": 2}
    resumed = open_sweep(part)
    for name in ds.variables:
        assert resumed[name].values.tobytes() == ds[name].values.tobytes(), name

    res = invoke("show", str(part), "--json")
    shown = json.loads(res.stdout)
    assert shown["analysis"] == "stability-chart" and shown["stability"] == doc["stability"]
    balanced = chart.balanced.values.ravel()
    assert shown["stability"]["balanced"] == np.count_nonzero(balanced) / balanced.size


def test_stability_sweep_over_speed_ratio_at_a_fixed_speed_and_bad_input(tmp_path):
    out = tmp_path / "r.zarr"
    res = invoke("--quiet", "sweep", "zhakash-k2", "--per-point", "stability", "--param", "speed_ratio=0.5:2:2",
                 "--out", str(out))  # fmt: skip
    assert res.exit_code == 0, res.output
    ds = open_sweep(out)
    assert list(ds.dims) == ["speed_ratio", "motion", "ball"]
    for args, needle in (
        (["--per-point", "nope"], "--per-point"),
        (["--per-point", "stability", "--param", "psi_1=0:1:2"], "--param"),
        (["--per-point", "stability", "--param", "ball_mass=0:1:2"], "--param"),
        (["--per-point", "stability", "--param", "speed_rpm=100:200:2", "--speed-rpm", "100"], "--speed-rpm"),
        (["--per-point", "stability", "--ic", "psi_1=0:1:2"], "--ic"),
        (["--per-point", "stability"], "--param"),
    ):
        bad = tmp_path / "bad.zarr"
        res = invoke("sweep", "zhakash-k2", *args, "--out", str(bad))
        assert res.exit_code == 2, (args, res.output)
        assert needle in res.output and not bad.exists(), (args, res.output)
