"""The sweep engine: chunking / executor / worker-count invariance (bit for bit), the Zarr store
with its completion marks, resume, and refusal of foreign or damaged stores.

The problem is the toroidal ball of seed 004 over 1.5 s (a few ms per trajectory), so each
sweep takes well under a second in-process.
"""

from __future__ import annotations

import math
import os
import signal

import numpy as np
import pytest
import xarray as xr

from rotorlab.explore import MapperAnalysis, TorusRegimes, basin_stability, map_starts
from rotorlab.models._toroidal_ball import strautmanis_torus
from rotorlab.sweep import (
    DaskExecutor,
    GridAxis,
    InProcess,
    ListAxis,
    LocalProcesses,
    Points,
    Sample,
    Sweep,
    SweepStoreError,
    open_sweep,
    run_sweep,
    store_info,
)

MAPPER = TorusRegimes(strautmanis_torus(1e-4), t_end=1.5, n_horizons=2)
ANALYSIS = MapperAnalysis(MAPPER)
SWEEP = Sweep(ANALYSIS, axes=(GridAxis("dpsi", -40.0, 40.0, 8), GridAxis("psi", 0.0, 6.0, 12)), fixed={"alpha": 0.1})
PROVENANCE = ("sweep", "fingerprint", "complete")


def same(a: xr.Dataset, b: xr.Dataset) -> None:
    """Bit-identical data, coordinates and attributes, apart from a store's provenance attrs."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        for key in PROVENANCE:
            ds.attrs.pop(key, None)
    xr.testing.assert_identical(a, b)
    for name in a.data_vars:  # identical() compares NaN as equal: compare the bits as well
        assert a[name].values.tobytes() == b[name].values.tobytes(), name


@pytest.fixture(scope="module")
def reference() -> xr.Dataset:
    return run_sweep(SWEEP, chunk_size=SWEEP.n_points)


def test_grid_result_has_one_dim_per_axis_and_matches_single_points(reference):
    assert reference.outcome.dims == ("dpsi", "psi")
    assert reference.label.dims == ("dpsi", "psi", "horizon")
    assert reference.psi.attrs["units"] == "rad" and reference.dpsi.attrs["units"] == "rad/s"
    assert all("units" in reference[v].attrs for v in reference.variables)
    assert reference.attrs["fixed_alpha"] == 0.1
    # the point (dpsi[2], psi[5]) integrated on its own gives the same bits
    one = map_starts(MAPPER, {"dpsi": reference.dpsi.values[2], "psi": reference.psi.values[5], "alpha": 0.1})
    for name in ("label", "ring_rate", "n_steps", "settle_time"):
        assert one[name].values[0].tobytes() == reference[name].values[2, 5].tobytes(), name
    # a real mix of regimes, so that invariance below is not checked on a constant
    assert len(np.unique(reference.outcome.values)) >= 2


@pytest.mark.parametrize("chunk", [1, 7, 40])
def test_chunk_size_does_not_change_a_bit(reference, chunk):
    same(reference, run_sweep(SWEEP, chunk_size=chunk, executor=InProcess(threads=1 if chunk == 7 else 2)))


def test_local_processes_and_zarr_store_give_the_same_bits(reference, tmp_path):
    out = run_sweep(SWEEP, store=tmp_path / "p.zarr", chunk_size=13, executor=LocalProcesses(workers=2))
    same(reference, out)
    same(reference, open_sweep(tmp_path / "p.zarr"))
    info = store_info(tmp_path / "p.zarr")
    assert info["complete"] and info["chunks_done"] == info["n_chunks"] == math.ceil(96 / 13)
    assert info["versions"]["rotorlab"] and info["sweep"] == SWEEP.describe()


def test_dask_local_cluster_with_one_worker_killed_mid_run_completes_identically(reference, tmp_path):
    from distributed import Client, LocalCluster

    killed = []
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:  # fmt: skip
        pids = client.run(os.getpid)

        def kill_one(p):
            if p.computed == 1 and not killed:
                busy = [addr for addr, keys in client.processing().items() if keys] or list(pids)
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed.append(pids[busy[0]])

        out = run_sweep(SWEEP, store=tmp_path / "d.zarr", chunk_size=8, progress=kill_one,
                        executor=DaskExecutor(client=client, threads=1))  # fmt: skip
        after = set(client.run(os.getpid).values())
    assert killed and killed[0] not in after  # the worker really died during the run
    same(reference, out)
    assert store_info(tmp_path / "d.zarr")["complete"]


def test_dask_worker_count_invariance(reference):
    same(reference, run_sweep(SWEEP, chunk_size=11, executor=DaskExecutor(workers=1)))


def _where(analysis, k, coords, threads):
    """A chunk function that reports the process it ran in."""
    return k, os.getpid()


def _pids(executor: DaskExecutor) -> set[int]:
    return {pid for _, pid in executor.imap(_where, None, ((k, {}) for k in range(4)))}


def test_dask_local_workers_are_threads_unless_numba_cannot_run_parallel_regions_from_threads(reference, monkeypatch):
    from rotorlab.sweep import _executors

    # one integrator thread a task: no parallel region, the workers are threads of this process
    assert _pids(DaskExecutor(workers=2, threads=1)) == {os.getpid()}
    same(reference, run_sweep(SWEEP, chunk_size=11, executor=DaskExecutor(workers=2, threads=1)))
    # parallel regions from several threads at once abort the process under numba's workqueue
    # layer: then the workers are processes
    monkeypatch.setattr(_executors, "_parallel_regions_threadsafe", lambda: True)
    assert _pids(DaskExecutor(workers=1, threads=2)) == {os.getpid()}
    monkeypatch.setattr(_executors, "_parallel_regions_threadsafe", lambda: False)
    assert os.getpid() not in _pids(DaskExecutor(workers=1, threads=2))


def _interrupt_after(n_chunks: int):
    def progress(p):
        if p.computed == n_chunks:
            raise KeyboardInterrupt

    return progress


def test_interrupted_run_resumes_without_recomputing_finished_chunks(reference, tmp_path):
    store = tmp_path / "r.zarr"
    with pytest.raises(KeyboardInterrupt):
        run_sweep(SWEEP, store=store, chunk_size=10, progress=_interrupt_after(3))
    info = store_info(store)
    assert info["chunks_done"] == 3 and not info["complete"]
    with pytest.raises(SweepStoreError, match="unfinished"):
        open_sweep(store)
    partial = open_sweep(store, partial=True)
    assert partial.attrs["complete"] == 0 and np.isnan(partial.ring_rate.values.reshape(-1, 2)[-1]).all()
    files = {p: p.stat().st_mtime_ns for p in (store / "ring_rate" / "c").rglob("*") if p.is_file()}
    assert len(files) == 3
    seen = []
    out = run_sweep(SWEEP, store=store, resume=True, progress=seen.append)
    assert seen[0].skipped == 3 and seen[-1].computed == 10 - 3 and seen[-1].done == 96
    same(reference, out)
    # no finished chunk was written again; the marks say which run wrote each chunk
    assert {p: p.stat().st_mtime_ns for p in files} == files
    assert store_info(store)["done"].tolist() == [1, 1, 1] + [2] * 7
    # resuming a complete store computes nothing
    seen.clear()
    run_sweep(SWEEP, store=store, resume=True, progress=seen.append)
    assert seen[-1].computed == 0 and seen[-1].skipped == 10


def test_foreign_and_mismatched_stores_are_refused(tmp_path):
    small = Sweep(ANALYSIS, axes=(ListAxis("psi", [1.0, 3.0, 5.0]),))
    store = tmp_path / "s.zarr"
    run_sweep(small, store=store, chunk_size=2)
    with pytest.raises(SweepStoreError, match="exists: give --resume"):
        run_sweep(small, store=store)
    other = Sweep(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=1.0, n_horizons=2)),
                  axes=(ListAxis("psi", [1.0, 3.0, 5.0]),))  # fmt: skip
    with pytest.raises(SweepStoreError, match=r"different sweep; analysis\.mapper\.t_end: stored 1\.5, now 1\.0"):
        run_sweep(other, store=store, resume=True)
    with pytest.raises(SweepStoreError, match="different sweep; points"):
        run_sweep(Sweep(ANALYSIS, axes=(ListAxis("psi", [1.0, 3.0]),)), store=store, resume=True)
    with pytest.raises(SweepStoreError, match="chunks of 2 points"):
        run_sweep(small, store=store, resume=True, chunk_size=3)
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "notes.txt").write_text("not a store")
    with pytest.raises(SweepStoreError, match="not a rotorlab sweep store"):
        run_sweep(small, store=plain, resume=True)
    with pytest.raises(SweepStoreError, match="not a rotorlab sweep store"):
        open_sweep(plain)
    # a store whose attributes never got written (killed while being created) is not trusted
    import zarr

    zarr.open_group(str(tmp_path / "half.zarr"), mode="w", zarr_format=3)
    with pytest.raises(SweepStoreError, match="creation was interrupted"):
        run_sweep(small, store=tmp_path / "half.zarr", resume=True)


def test_damaged_chunk_is_detected(tmp_path):
    small = Sweep(ANALYSIS, axes=(ListAxis("psi", [1.0, 3.0, 5.0]),))
    store = tmp_path / "c.zarr"
    run_sweep(small, store=store, chunk_size=2)
    chunk = next(p for p in (store / "ring_rate" / "c").rglob("*") if p.is_file())
    data = bytearray(chunk.read_bytes())
    data[len(data) // 2] ^= 0xFF
    chunk.write_bytes(bytes(data))
    with pytest.raises(SweepStoreError, match="damaged: chunk 0 of 'ring_rate'"):
        run_sweep(small, store=store, resume=True)
    with pytest.raises(SweepStoreError, match="damaged"):
        open_sweep(store)
    (store / "_done" / "zarr.json").write_text("{broken")
    with pytest.raises(SweepStoreError, match="not a rotorlab sweep store|damaged"):
        store_info(store)


def test_sample_sweep_is_basin_stability_and_points_are_map_starts():
    ranges = {"psi": (0.0, 2 * math.pi), "dpsi": (-50.0, 50.0)}
    bs = basin_stability(MAPPER, ranges, 9, seed=3, fixed={"alpha": 0.0}, chunk_size=4)
    sw = run_sweep(Sweep(ANALYSIS, sample=Sample(ranges, 9, 3, dim="ic"), fixed={"alpha": 0.0}), chunk_size=2)
    for name in ("psi", "dpsi", "alpha", "label", "ring_rate"):
        assert bs[name].values.tobytes() == sw[name].values.tobytes(), name
    pts = run_sweep(Sweep(ANALYSIS, points=Points({"psi": bs.psi.values, "dpsi": bs.dpsi.values, "alpha": 0.0})))
    assert pts.label.values.tobytes() == bs.label.values.tobytes()


def test_sweep_description_checks():
    with pytest.raises(ValueError, match="exactly one of axes, sample or points"):
        Sweep(ANALYSIS)
    with pytest.raises(ValueError, match="exactly one of axes, sample or points"):
        Sweep(ANALYSIS, axes=(GridAxis("psi", 0, 1, 2),), sample=Sample({"dpsi": (0, 1)}, 2, 0))
    with pytest.raises(ValueError, match="unknown coordinate 'theta'"):
        Sweep(ANALYSIS, axes=(GridAxis("theta", 0, 1, 2),))
    with pytest.raises(ValueError, match="varied twice"):
        Sweep(ANALYSIS, axes=(GridAxis("psi", 0, 1, 2), ListAxis("psi", [3.0])))
    with pytest.raises(ValueError, match="both varied and fixed"):
        Sweep(ANALYSIS, axes=(GridAxis("psi", 0, 1, 2),), fixed={"psi": 1.0})
    with pytest.raises(TypeError, match="AbstractPointAnalysis"):
        Sweep(object(), axes=(GridAxis("psi", 0, 1, 2),))
    with pytest.raises(ValueError, match="chunk_size must be an integer >= 1"):
        SWEEP.chunks(0)
    with pytest.raises(ValueError, match="ListAxis.values"):
        ListAxis("psi", [])
    with pytest.raises(ValueError, match="DaskExecutor: give scheduler"):
        DaskExecutor(scheduler="tcp://127.0.0.1:1", workers=2)
    with pytest.raises(ValueError, match="LocalProcesses.workers"):
        LocalProcesses(workers=0)
    # the description identifies the sweep: equal sweeps, equal fingerprints
    again = Sweep(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=1.5, n_horizons=2)),
                  axes=(GridAxis("dpsi", -40.0, 40.0, 8), GridAxis("psi", 0.0, 6.0, 12)), fixed={"alpha": 0.1})  # fmt: skip
    assert again.fingerprint() == SWEEP.fingerprint()
    assert Sweep(ANALYSIS, axes=SWEEP.axes, fixed={"alpha": 0.2}).fingerprint() != SWEEP.fingerprint()
