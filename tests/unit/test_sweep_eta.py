"""A long sweep says how long before it starts (issue 29: a 25-million-start basin just started,
about 17 days on that machine, with no estimate).

The engine times a pilot (:func:`rotorlab.sweep.long_run_guard`); ``basin`` and ``sweep`` print
the estimate and refuse one above 10 min without ``--yes`` (exit code 2, nothing written).
"""

from __future__ import annotations

import re

import pytest
from typer.testing import CliRunner

import rotorlab.sweep._eta as eta
from rotorlab.cli import app
from rotorlab.explore import MapperAnalysis, TorusRegimes
from rotorlab.models import strautmanis_torus
from rotorlab.sweep import Estimate, GridAxis, LongRunDeclined, Sweep, long_run_guard, run_sweep, store_info

runner = CliRunner()


def _sweep(n: int) -> Sweep:
    # the sweep of run_sweep's example (a compiled model the suite already has), n x n points
    mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=1.0, n_horizons=1)
    return Sweep(MapperAnalysis(mapper), axes=(GridAxis("psi", 1.0, 5.0, n), GridAxis("dpsi", -1.0, 1.0, n)))


def test_a_guarded_sweep_is_estimated_on_a_pilot_and_may_be_declined(tmp_path, monkeypatch):
    monkeypatch.setattr(eta, "PILOT_ABOVE", 16)
    seen: list[Estimate] = []

    def decline(estimate):
        seen.append(estimate)
        return False

    store = tmp_path / "s.zarr"
    with long_run_guard(decline), pytest.raises(LongRunDeclined) as caught:
        run_sweep(_sweep(5), store=store, chunk_size=10)
    (estimate,) = seen
    assert caught.value.estimate is estimate and not store.exists()  # declined before anything is written
    assert (estimate.points, estimate.pilot_points) == (25, min(eta.PILOT_POINTS, 25))
    assert estimate.seconds == pytest.approx(25 * estimate.seconds_per_point) and estimate.seconds_per_point > 0
    # accepted: the sweep runs; interrupted after its first chunk, a resumed run is estimated on
    # the points it still misses
    def stop_after_one(p):
        if p.computed == 1:
            raise KeyboardInterrupt

    with long_run_guard(lambda e: seen.append(e) or True), pytest.raises(KeyboardInterrupt):
        run_sweep(_sweep(5), store=store, chunk_size=10, progress=stop_after_one)
    assert seen[-1].points == 25 and store_info(store)["chunks_done"] == 1
    with long_run_guard(lambda e: seen.append(e) or True):
        full = run_sweep(_sweep(5), store=store, resume=True)
    assert seen[-1].points == 15 and int(full.label.isel(horizon=-1).size) == 25
    # without a guard, or below PILOT_ABOVE points, nothing is timed
    seen.clear()
    run_sweep(_sweep(3))
    with long_run_guard(lambda e: seen.append(e) or True):
        run_sweep(_sweep(3))  # 9 points < 16
    assert seen == []


def test_a_basin_of_days_asks_for_yes_with_its_estimate(tmp_path, monkeypatch):
    store = tmp_path / "big.zarr"
    args = ["basin", "autobalancer", "--x", "psi_1=0:360deg:5000", "--y", "psi_2=0:360deg:5000",
            "--store", str(store)]
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    found = re.search(r"estimated (\S+) (days|h) for 25,000,000 starts \((\S+) s each, timed on 32 of them in "
                      r"this process\): longer than 10 min\. Give --yes to run it", res.output)
    assert found, res.output
    value, unit, each = float(found[1]), found[2], float(found[3])
    # the estimate is the points times the measured time per start (as printed, 2 digits)
    assert value * {"days": 86400.0, "h": 3600.0}[unit] == pytest.approx(25e6 * each, rel=0.1)
    assert not store.exists()  # nothing written
    # with --yes the estimate is printed and the sweep runs (made short here: 20 x 20 starts
    # estimated as long by a threshold of 0 s)
    import rotorlab.cli._sweep_common as common

    monkeypatch.setattr(eta, "PILOT_ABOVE", 100)
    monkeypatch.setattr(common, "LONG_RUN_S", 0.0)
    small = ["basin", "autobalancer", "--x", "psi_1=0:360deg:20", "--y", "psi_2=0:360deg:20", "--t-end", "1",
             "--store", str(store)]
    assert runner.invoke(app, small).exit_code == 2 and not store.exists()
    res = runner.invoke(app, [*small, "--yes"])
    assert res.exit_code == 0, res.output
    assert re.search(r"estimated \S+ \S+ for 400 starts", res.output)
    assert store_info(store)["chunks_done"] == store_info(store)["n_chunks"]
