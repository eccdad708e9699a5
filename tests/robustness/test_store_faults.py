"""Fault injection on sweep stores (issue 14, items 2, 3, 5, 6, 7, 9): lost chunk files, a full
disk, damaged metadata, hostile attributes, two runs on one store, leftovers of killed runs.

The sweep is the toroidal ball of seed 004 over 0.3 s at 6 points in chunks of 2 (milliseconds);
the command-line tests use the built-in autobalancer at 8 points over 0.3 s.
"""

from __future__ import annotations

import errno
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.explore import MapperAnalysis, TorusRegimes
from rotorlab.models._toroidal_ball import strautmanis_torus
from rotorlab.sweep import GridAxis, Sweep, SweepStoreError, open_sweep, run_sweep, store_info
from rotorlab.sweep import _store

runner = CliRunner()
SWEEP = Sweep(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=0.3, n_horizons=2)),
              axes=(GridAxis("psi", 0.5, 5.5, 6),))  # fmt: skip
CLI_SWEEP = ["sweep", "autobalancer", "--speed-ratio", "2", "--ic", "psi_1=0:6:4", "--ic", "psi_2=1:5:2",
             "--t-end", "0.3", "--chunk", "2"]  # fmt: skip


def bits(ds) -> dict[str, bytes]:
    return {name: ds[name].values.tobytes() for name in ds.data_vars}


@pytest.fixture(scope="module")
def reference():
    return run_sweep(SWEEP, chunk_size=2)


def chunk_file(store: Path, name: str, k: int) -> Path:
    return next((store / name / "c" / str(k)).rglob("*")) if (store / name / "c" / str(k)).is_dir() else \
        store / name / "c" / str(k)  # fmt: skip


# ------------------------------------------------------------------------------ item 2: lost chunk
def test_a_lost_chunk_file_is_found_and_recomputed(reference, tmp_path):
    store = tmp_path / "s.zarr"
    run_sweep(SWEEP, store=store, chunk_size=2)
    lost = chunk_file(store, "ring_rate", 1)
    lost.unlink()
    info = store_info(store)
    assert info["lost"] == [1] and info["chunks_done"] == 2 and not info["complete"]
    with pytest.raises(SweepStoreError, match="unfinished"):
        open_sweep(store)
    seen = []
    with pytest.warns(UserWarning, match=r"chunk\(s\) 1 were marked done but their data files are missing"):
        out = run_sweep(SWEEP, store=store, resume=True, progress=seen.append)
    assert seen[-1].computed == 1 and seen[-1].skipped == 2
    assert bits(out) == bits(reference)
    assert store_info(store)["complete"] and lost.is_file()


def test_show_reports_a_lost_chunk_and_resume_recomputes_it(tmp_path):
    store = tmp_path / "c.zarr"
    assert runner.invoke(app, [*CLI_SWEEP, "--out", str(store)]).exit_code == 0
    before = open_sweep(store)
    chunk_file(store, "label", 2).unlink()
    res = runner.invoke(app, ["show", str(store)])
    assert res.exit_code == 0
    assert "3 of 4 chunks done" in res.stdout and "chunk(s) 2 are marked done but their data files are missing" \
        in res.stdout  # fmt: skip
    doc = json.loads(runner.invoke(app, ["show", str(store), "--json"]).stdout)
    assert doc["lost_chunks"] == [2] and doc["chunks"]["done"] == 3 and doc["complete"] is False
    res = runner.invoke(app, [*CLI_SWEEP, "--out", str(store), "--resume", "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["chunks"] == {"total": 4, "computed": 1, "skipped": 3}
    assert "warning: " in res.stderr and "computing them again" in res.stderr
    assert bits(open_sweep(store)) == bits(before)


# ------------------------------------------------------------------------------ item 3: disk full
def _full_disk_on(monkeypatch, calls_before_failure: int, target: Path) -> list[int]:
    """Make the store's writer fail with ENOSPC after ``calls_before_failure`` writes."""
    count = [0]
    original = _store.ZarrSink._write_values

    def failing(self, arr, lo, hi, values):
        count[0] += 1
        if count[0] > calls_before_failure:
            raise OSError(errno.ENOSPC, "No space left on device", str(target))
        original(self, arr, lo, hi, values)

    monkeypatch.setattr(_store.ZarrSink, "_write_values", failing)
    return count


def test_disk_full_names_the_path_keeps_the_store_and_resume_continues(reference, tmp_path, monkeypatch):
    store = tmp_path / "d.zarr"
    # chunk 0 writes all its variables; chunk 1 fails on its third variable
    n_vars = len(reference.data_vars)
    _full_disk_on(monkeypatch, n_vars + 2, store / "some" / "file")
    with pytest.raises(_store.StoreWriteError) as err:
        run_sweep(SWEEP, store=store, chunk_size=2)
    text = str(err.value)
    assert str(store / "some" / "file") in text and "No space left on device" in text and "--resume" in text
    info = store_info(store)  # not damaged: attributes of every array were written with it
    assert info["chunks_done"] == 1 and info["done"].tolist() == [1, 0, 0]
    monkeypatch.undo()  # space is free again
    out = run_sweep(SWEEP, store=store, resume=True)
    assert bits(out) == bits(reference)


def test_disk_full_while_creating_a_variable_leaves_a_resumable_store(reference, tmp_path, monkeypatch):
    store = tmp_path / "v.zarr"
    original = _store.ZarrSink._array

    def failing(self, name, *args, **kwargs):
        if name == "label":
            raise OSError(errno.ENOSPC, "No space left on device", str(self.path / name / "zarr.json"))
        return original(self, name, *args, **kwargs)

    monkeypatch.setattr(_store.ZarrSink, "_array", failing)
    with pytest.raises(_store.StoreWriteError, match="label/zarr.json"):
        run_sweep(SWEEP, store=store, chunk_size=2)
    assert store_info(store)["chunks_done"] == 0
    monkeypatch.undo()
    assert bits(run_sweep(SWEEP, store=store, resume=True)) == bits(reference)


def test_disk_full_in_the_cli_exits_1_with_the_path_and_no_internal_error(tmp_path, monkeypatch):
    store = tmp_path / "f.zarr"
    _full_disk_on(monkeypatch, 3, store / "label" / "c" / "1" / "0")
    res = runner.invoke(app, [*CLI_SWEEP, "--out", str(store)])
    assert res.exit_code == 1
    assert "internal error" not in res.stderr and "Traceback" not in res.output
    assert f"cannot write {store / 'label' / 'c' / '1' / '0'}" in res.stderr and "No space left" in res.stderr
    monkeypatch.undo()
    res = runner.invoke(app, [*CLI_SWEEP, "--out", str(store), "--resume"])
    assert res.exit_code == 0, res.output
    assert store_info(store)["complete"]


# ------------------------------------------------------------------------------ item 5: damaged metadata
def _edit_json(path: Path, change) -> None:
    doc = json.loads(path.read_text())
    change(doc)
    path.write_text(json.dumps(doc))


DAMAGE = {
    "deleted-variable": (lambda s: shutil.rmtree(s / "ring_rate"), "result variable 'ring_rate' is missing"),
    "edited-shape": (lambda s: _edit_json(s / "ring_rate" / "zarr.json", lambda d: d.update(shape=[7, *d["shape"][1:]])),
                     "variable 'ring_rate' has shape (7,"),
    "wrong-dims": (lambda s: _edit_json(s / "zarr.json", lambda d: d["attributes"].update(dims=["x", "y"])),
                   "'dims'"),
    "wrong-n-chunks": (lambda s: _edit_json(s / "zarr.json", lambda d: d["attributes"].update(n_chunks=99)),
                       "'n_chunks' = 99"),
    "result-attrs-not-a-table": (lambda s: _edit_json(s / "zarr.json",
                                                      lambda d: d["attributes"].update(result_attrs="oops")),
                                 "'result_attrs'"),
    "lost-dims-attribute": (lambda s: _edit_json(s / "label" / "zarr.json", lambda d: d["attributes"].pop("_dims")),
                            "'label' has lost its attribute '_dims'"),
    "marks-resized": (lambda s: _edit_json(s / "_done" / "zarr.json", lambda d: d.update(shape=[5])),
                      "completion marks"),
    "input-units-not-deg-or-rad": (lambda s: _edit_json(s / "zarr.json",
                                                        lambda d: d["attributes"].update(input_units={"psi": "grad"})),
                                   "'input_units'"),
    "shape-not-n-points": (lambda s: _edit_json(s / "zarr.json", lambda d: d["attributes"].update(shape=[5])),
                           "'shape' [5]"),
}


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_damaged_metadata_is_refused_as_damaged_with_exit_2(kind, tmp_path):
    store = tmp_path / "m.zarr"
    run_sweep(SWEEP, store=store, chunk_size=2)
    damage, words = DAMAGE[kind]
    damage(store)
    with pytest.raises(SweepStoreError, match="damaged") as err:
        store_info(store)
    assert words in str(err.value)
    with pytest.raises(SweepStoreError, match="damaged"):
        run_sweep(SWEEP, store=store, resume=True)
    res = runner.invoke(app, ["show", str(store)])
    assert res.exit_code == 2 and "damaged" in res.stderr and words in res.stderr, res.output
    assert "internal error" not in res.output and "Traceback" not in res.output


def test_resume_of_a_damaged_store_in_the_cli_exits_2(tmp_path):
    store = tmp_path / "r.zarr"
    assert runner.invoke(app, [*CLI_SWEEP, "--out", str(store)]).exit_code == 0
    shutil.rmtree(store / "outcome")
    res = runner.invoke(app, [*CLI_SWEEP, "--out", str(store), "--resume"])
    assert res.exit_code == 2 and "damaged" in res.stderr and "'outcome'" in res.stderr


# ------------------------------------------------------------------------------ item 6: hostile attributes
def test_show_strips_terminal_escapes_and_truncates_huge_attributes(tmp_path):
    store = tmp_path / "h.zarr"
    with pytest.raises(KeyboardInterrupt):  # unfinished: show prints, draws no figures (fast)
        run_sweep(SWEEP, store=store, chunk_size=2, progress=lambda p: _stop_after(p, 2))
    hostile = "torus\x1b[2J\x1b]0;pwned\x07\x1b[31m"

    def change(doc):
        doc["attributes"]["result_attrs"].update(mapper=hostile, t_end="\x1b[2J" + "y" * 2_000_000)
        doc["attributes"]["versions"]["rotorlab"] = "0.1\x1b]0;title\x07"

    _edit_json(store / "zarr.json", change)
    res = runner.invoke(app, ["show", str(store)])
    assert res.exit_code == 0, res.output
    assert "\x1b" not in res.stdout and "\x07" not in res.stdout
    assert "analysis: torus, t_end yyy" in res.stdout and "... (2000004 characters)" in res.stdout
    assert len(res.stdout) < 5000
    doc = json.loads(runner.invoke(app, ["show", str(store), "--json"]).stdout)
    assert doc["analysis"] == "torus" and len(doc["result"]["t_end"]) < 300


# ------------------------------------------------------------------------------ item 7: one writer at a time
def test_a_second_run_on_a_store_in_use_is_refused(reference, tmp_path):
    store = tmp_path / "l.zarr"
    run_sweep(SWEEP, store=store, chunk_size=2, progress=None)
    held = _store._StoreLock(store)  # another run holds the store (flock: another open file description)
    try:
        with pytest.raises(SweepStoreError, match=r"in use by another rotorlab run \(process \d+\)"):
            run_sweep(SWEEP, store=store, resume=True)
        res = runner.invoke(app, ["basin", "strautmanis-torus", "--store", str(store), "--resume"])
        assert res.exit_code == 2
        fresh = tmp_path / "new.zarr"
        creator = _store._StoreLock(fresh)
        try:
            with pytest.raises(SweepStoreError, match="in use"):
                run_sweep(SWEEP, store=fresh, chunk_size=2)
            assert not fresh.exists() and not list(tmp_path.glob(".new.zarr.creating-*"))
        finally:
            creator.release()
    finally:
        held.release()
    assert not (tmp_path / ".l.zarr.lock").exists()
    assert bits(run_sweep(SWEEP, store=store, resume=True)) == bits(reference)
    assert not list(tmp_path.glob(".*.lock"))


def test_two_concurrent_resumes_compute_each_chunk_once(tmp_path, monkeypatch):
    """The first run holds the store while it computes; a second started meanwhile is refused."""
    store = tmp_path / "c.zarr"
    with pytest.raises(KeyboardInterrupt):
        run_sweep(SWEEP, store=store, chunk_size=2, progress=lambda p: _stop_after(p, 1))
    second = []

    def start_second(p):
        if p.computed == 1 and not second:
            try:
                run_sweep(SWEEP, store=store, resume=True)
            except SweepStoreError as exc:
                second.append(str(exc))

    run_sweep(SWEEP, store=store, resume=True, progress=start_second)
    assert second and "in use by another rotorlab run" in second[0]
    assert store_info(store)["done"].tolist() == [1, 2, 2]


def _stop_after(p, n):
    if p.computed >= n:
        raise KeyboardInterrupt


# ------------------------------------------------------------------------------ item 9: leftovers
def test_a_stale_creating_folder_is_removed_by_the_next_run(reference, tmp_path):
    store = tmp_path / "k.zarr"
    stale = tmp_path / ".k.zarr.creating-999999"
    stale.mkdir()
    (stale / "zarr.json").write_text("{}")
    with pytest.raises(KeyboardInterrupt):
        run_sweep(SWEEP, store=store, chunk_size=2, progress=lambda p: _stop_after(p, 1))
    assert not stale.exists()
    stale.mkdir()
    out = run_sweep(SWEEP, store=store, resume=True)
    assert not stale.exists() and bits(out) == bits(reference)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k.zarr"]
