"""Impact sweeps on the sweep engine (issues 6, 7): per-point analysis, checkpoints, executors.

A point of an impact sweep is (swept parameter, seed of the stone sequence); its result must be
the same bits whatever the chunk it is in, the chunk size, the executor, and however often the
sweep was interrupted and resumed. Interruptions are made by a progress callback that raises
KeyboardInterrupt after k chunks (no timing involved). Runs are short (1 s of rotor time).
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import ImpactAnalysis, impact_run, impact_sweep, impact_sweep_definition
from rotorlab.cli import app
from rotorlab.models import krasnov_crusher
from rotorlab.sweep import DaskExecutor, InProcess, LocalProcesses, SweepStoreError, open_sweep, run_sweep, store_info

MASSES = [0.6, 1.5, 3.0]
KW = {"n_sequences": 3, "t_end": 1.0, "seed": 7}


def assert_same_bits(a, b):
    assert set(a.variables) == set(b.variables)
    for name in a.variables:
        x, y = a[name].values, b[name].values
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name
        assert a[name].attrs == b[name].attrs, name


@pytest.fixture(scope="module")
def reference():
    """The sweep in one chunk, in this process, without a store."""
    return impact_sweep(krasnov_crusher(), MASSES, **KW)


def test_reference_has_all_three_regimes_growing_with_mass(reference):
    # the sweep is not trivial: no impacts at 0.6 kg in 1 s, rebounds at 1.5 kg, sliding at 3 kg
    # (1.5 kg: one run of 3 already slides for 2 % of the second; 3 kg: two of 3)
    assert reference.impacts.values[0].tolist() == [0, 0, 0]
    assert (reference.impacts.values[1] > 0).all() and (reference.impacts.values[2] > reference.impacts.values[1]).all()
    reg = reference.regime.values.tolist()
    assert reg[0] == [0, 0, 0] and 1 in reg[1] and 0 not in reg[1] and 2 in reg[2] and min(reg[2]) >= 1
    assert reference.seed.values.tolist() == [7, 8, 9]


def test_a_point_is_the_single_run_with_the_same_seed():
    model = krasnov_crusher()
    out = ImpactAnalysis(model, t_end=1.0).run_chunk({"stone_mass": np.array([3.0, 1.5]), "seed": np.array([8.0, 7.0])})
    for i, (mass, seed) in enumerate([(3.0, 8), (1.5, 7)]):
        run = impact_run(replace(model, stones=replace(model.stones, mass=mass)), 1.0, seed=seed, n_save=20)
        for name in ("impacts", "impacts_all", "slides", "sliding_time", "eta", "energy_stones", "energy_friction",
                     "whirl", "t_final", "status", "n_steps", "regime"):  # fmt: skip
            assert out[name].values[i] == run[name].values, name
        # the single run also looks at its saved states, so it can only see more penetration
        assert out["max_penetration"].values[i] <= run["max_penetration"].values < 1e-9


def test_interrupted_sweep_resumed_equals_uninterrupted(tmp_path, reference):
    store = tmp_path / "runs.zarr"
    calls = []

    def stop_after_two(done, total):
        calls.append(done)
        if len(calls) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        impact_sweep(krasnov_crusher(), MASSES, store=store, chunk_size=2, progress=stop_after_two, **KW)
    info = store_info(store)
    assert calls == [2, 4] and info["n_chunks"] == 5 and info["chunks_done"] == 2 and not info["complete"]
    with pytest.raises(SweepStoreError, match="unfinished"):
        open_sweep(store)
    resumed_calls = []
    ds = impact_sweep(krasnov_crusher(), MASSES, store=store, resume=True,
                      progress=lambda done, total: resumed_calls.append(done), **KW)  # fmt: skip
    # only the three missing chunks ran (the store keeps its chunk size); none ran twice
    assert resumed_calls == [6, 8, 9]
    assert store_info(store)["done"].tolist() == [1, 1, 2, 2, 2]
    assert_same_bits(ds, reference)
    runs = open_sweep(store)
    assert runs.impacts.dims == ("stone_mass", "seed") and runs.impacts.attrs["units"] == "1"
    assert np.array_equal(runs.impacts.values, reference.impacts.values)


def test_a_resume_with_other_options_is_refused_and_changes_nothing(tmp_path):
    store = tmp_path / "runs.zarr"
    impact_sweep(krasnov_crusher(), [0.8], store=store, n_sequences=1, t_end=0.2)
    with pytest.raises(SweepStoreError, match="different sweep"):
        impact_sweep(krasnov_crusher(), [0.8], store=store, resume=True, n_sequences=1, t_end=0.3)
    with pytest.raises(SweepStoreError, match="exists"):
        impact_sweep(krasnov_crusher(), [0.8], store=store, n_sequences=1, t_end=0.2)
    assert store_info(store)["runs"] == 1


@pytest.mark.parametrize("executor, chunk", [
    (InProcess(threads=1), 1),
    (LocalProcesses(workers=2, threads=1), 2),
    (DaskExecutor(workers=2), 4),
])  # fmt: skip
def test_executors_and_chunk_sizes_give_the_same_bits(reference, executor, chunk):
    sweep = impact_sweep_definition(krasnov_crusher(), MASSES, **KW)
    runs = run_sweep(sweep, chunk_size=chunk, executor=executor)
    for name in ("impacts", "impacts_all", "sliding_time", "eta", "energy_friction", "n_steps", "regime"):
        assert np.array_equal(runs[name].values, reference[name].values, equal_nan=True), name


# --------------------------------------------------------------------------- command line
runner = CliRunner()
ARGS = ("impacts-sweep", "krasnov-crusher", "--stone-mass", "1:3:2", "--sequences", "2", "--t-end", "1", "--json")


def test_cli_store_interrupted_and_resumed_gives_the_plain_result(tmp_path, monkeypatch):
    import rotorlab.sweep

    plain = json.loads(runner.invoke(app, list(ARGS)).stdout)
    store = tmp_path / "s.zarr"
    real = rotorlab.sweep.run_sweep

    def interrupted(sweep, **kw):
        outer = kw["progress"]

        def progress(p):
            outer(p)
            if p.computed == 1:
                raise KeyboardInterrupt

        return real(sweep, **{**kw, "progress": progress})

    monkeypatch.setattr(rotorlab.sweep, "run_sweep", interrupted)
    r = runner.invoke(app, [*ARGS, "--out", str(store)])
    assert r.exit_code == 130, r.output
    assert "1 of 2 chunks are kept" in r.stderr and "--resume" in r.stderr
    monkeypatch.setattr(rotorlab.sweep, "run_sweep", real)
    r = runner.invoke(app, [*ARGS, "--out", str(store), "--resume"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["sweep"]["chunks"] == {"total": 2, "computed": 1, "skipped": 1}
    assert doc["files"] == [str(store)]
    assert doc["rows"] == plain["rows"] and doc["rows"][1]["impacts_median"] > doc["rows"][0]["impacts_median"] > 0


@pytest.mark.parametrize("extra, words", [
    (("--workers", "0"), "--workers = 0: must be an integer >= 1"),
    (("--chunk", "0"), "--chunk = 0: must be an integer >= 1"),
    (("--scheduler", "nowhere"), "--scheduler = nowhere: must be an address like tcp://HOST:PORT"),
    (("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"), "--scheduler and --workers exclude each other"),
    (("--resume",), "--resume needs --out STORE.zarr"),
    (("--resume", "--out", "r.nc"), "--resume needs --out STORE.zarr"),
    (("--out", "missing/s.zarr"), "--out = missing/s.zarr: folder"),
])  # fmt: skip
def test_cli_bad_sweep_options_exit_2_and_write_nothing(tmp_path, monkeypatch, extra, words):
    monkeypatch.chdir(tmp_path)
    r = runner.invoke(app, [*ARGS, *extra])
    assert r.exit_code == 2, r.output
    assert words in r.stderr and "Traceback" not in r.output
    assert list(tmp_path.iterdir()) == []


def test_cli_existing_or_foreign_store_is_refused_untouched(tmp_path):
    store = tmp_path / "s.zarr"
    args = ["impacts-sweep", "krasnov-crusher", "--stone-mass", "1:1:1", "--sequences", "1", "--t-end", "0.2",
            "--out", str(store)]  # fmt: skip
    assert runner.invoke(app, args).exit_code == 0
    r = runner.invoke(app, args)
    assert r.exit_code == 2 and "exists; give --resume" in r.stderr
    r = runner.invoke(app, [*args[:-2], "--t-end", "0.3", "--out", str(store), "--resume"])
    assert r.exit_code == 2 and f"--out = {store}" in r.stderr and "different sweep" in r.stderr
    assert store_info(store)["runs"] == 1
