"""Honest labels on the composed machine: a start still converging towards balance is *not
settled* (with its estimated time to settle), in ``simulate`` and in a basin of the machine's
regime mapper, never "not balanced".

The machine is the planar Jeffcott rotor with two balls of ``test_machine_analyses`` at 2 rad/s
(above its critical speed 0.98 rad/s): its balanced state's slowest mode decays at
``-max Re(lambda) = 5.17e-3 1/s`` (a 193 s time constant, the co-rotating linearisation), and
the start (0.3, 2.0) rad is still 4.9 times the balanced threshold after 600 s.
"""

import math

import numpy as np
import xarray as xr
from test_machine_common import PLANAR

from rotorlab.analyses._machine import _simulate_rows, machine_simulate
from rotorlab.analyses._verdict import MARGIN, basin_verdict, round_up_horizon
from rotorlab.explore import MachineRegimes
from rotorlab.explore._basin import basin_fractions
from rotorlab.explore._mapper import map_starts
from rotorlab.explore._outcome import BALANCED_FRACTION
from rotorlab.explore._settle import slowest_decay_rate
from rotorlab.linear import LinearSystem
from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance

S = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
                 G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
MACHINE = Machine(S, races=(BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * 2),), unbalances=(Unbalance(0, 0.01),),
                  drive=ConstantSpeed(2.0), n_modes=2)  # fmt: skip
START = [0.3, 2.0]


def _slowest() -> float:
    return slowest_decay_rate(MACHINE.linearize(MACHINE.balanced_state()).eigenvalues)


def test_a_converging_machine_start_is_not_settled_at_the_slowest_modes_rate_and_settles_by_its_estimate():
    rate = _slowest()
    np.testing.assert_allclose(rate, 5.17e-3, rtol=1e-3)
    ds = machine_simulate(MACHINE, [START], t_end=600.0)
    assert str(ds.outcome.values[0]) == "not settled"  # it was "not balanced"
    est = float(ds.settle_estimate.values[0])
    threshold = BALANCED_FRACTION * float(ds.reference_amplitude.max())
    amp = float(ds.amplitude.max())
    assert amp > threshold and 600.0 < est < 1200.0
    # the decay the estimate extrapolates is that of the balanced state's slowest mode
    np.testing.assert_allclose(math.log(amp / threshold) / (est - 600.0), rate, rtol=0.15)
    assert _simulate_rows(ds)[0]["settle_estimate_s"] == est
    again = machine_simulate(MACHINE, [START], t_end=round_up_horizon(MARGIN * est))
    assert str(again.outcome.values[0]) == "balanced" and math.isnan(float(again.settle_estimate.values[0]))


def test_a_machine_basin_too_short_says_not_settled_and_the_horizon_that_would_do():
    mapper = MachineRegimes(MACHINE, t_end=600.0, n_horizons=10)
    ds = map_starts(mapper, {"psi_1": np.array([START[0], -2.5]), "psi_2": np.array([START[1], 1.0])})
    labels = list(ds["label"].attrs["labels"])
    final = [labels[k] for k in ds["label"].isel(horizon=-1).values]
    assert final[0] == "not settled"
    est = float(ds["settle_estimate"].isel(horizon=-1).values[0])
    assert 600.0 < est < 1200.0
    counts = basin_fractions(ds)
    verdict_ds = xr.Dataset({"count": counts["count"], "outcome": ds["label"].isel(horizon=-1),
                             "settle_estimate": ds["settle_estimate"]}, coords=counts.coords,
                            attrs={"slowest_decay_rate": mapper.balanced_decay_rate()})
    np.testing.assert_allclose(verdict_ds.attrs["slowest_decay_rate"], _slowest(), rtol=1e-12)
    verdict = basin_verdict(verdict_ds)
    assert not verdict["settled"] and verdict["not_settled"] >= 1
    assert verdict["horizon_needed_s"] >= MARGIN * est and "would do" in verdict["sentence"]
    longer = map_starts(MachineRegimes(MACHINE, t_end=verdict["horizon_needed_s"], n_horizons=10),
                        {"psi_1": np.array(START[:1]), "psi_2": np.array(START[1:])})
    assert labels[int(longer["label"].isel(horizon=-1).values[0])] == "balanced"


# the PLANAR case of test_machine_common with this machine's damping and speed, and a sweep
SWEEP_CASE = (PLANAR[:PLANAR.index("[[analysis]]")]
              .replace('damping = [["0.1 N*s/m", "0 N*s/rad"], ["0 N*s/rad", "0.05 N*m*s/rad"]]',
                       'damping = [["0.02 N*s/m", "0 N*s/rad"], ["0 N*s/rad", "0 N*m*s/rad"]]')
              .replace('damping = "0.05 N*m*s/rad", count = 2', 'damping = "0.01 N*m*s/rad", count = 2')
              .replace('phase = "30 deg"\n', "").replace('speed = "2.5 rad/s"', 'speed = "2 rad/s"')
              + '[[analysis]]\ntype = "sweep"\nname = "s"\nt_end = "600 s"\nn_horizons = 10\n'
              'ic = { psi_1 = ["0.3 rad", "0.3 rad", 1], psi_2 = ["2 rad", "2 rad", 1] }\n')


def test_a_machine_sweep_too_short_is_judged_against_the_slowest_mode_and_names_the_horizon():
    """The same machine as a case file: its sweep's verdict tests the horizon against the
    balanced state's slowest mode (600 s are 3.1 time constants of 193 s) and asks for 10 of
    them, 2000 s rounded up, beyond 1.25 times the start's estimated settle time."""
    from rotorlab.analyses import run_analysis, summarize
    from rotorlab.io import parse_case
    from rotorlab.report._findings import basin_findings

    case = parse_case(SWEEP_CASE)
    ds = run_analysis(case.model, case.analysis("s"))
    np.testing.assert_allclose(ds.attrs["slowest_decay_rate"], _slowest(), rtol=1e-9)
    found = basin_findings(ds, summarize(ds))
    assert found.verdict.startswith("no verdict yet (horizon too short)")
    sentence = basin_verdict(ds)["sentence"]
    assert "1 of 1 starts are not settled" in sentence and "A horizon of 2000 s would do." in sentence
    assert round_up_horizon(10.0 / _slowest()) == 2000.0
    assert sentence in found.numbers
    assert any("3.1 time constants of the balanced state's slowest mode, 193 s" in n for n in found.numbers)
