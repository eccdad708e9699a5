"""The sanity monitor (issue 14, item 1): physically impossible states end in a failed status with
a message, and no command exits 0 with a result it knows is impossible (exit code 3).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from importlib import resources

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab._kernels import impact_rotor as _k
from rotorlab.cli import app
from rotorlab.integrate import SaveAt, Status, StepControl, solve, solve_ensemble
from rotorlab.models import krasnov_crusher
from rotorlab.models.examples import HarmonicOscillator

runner = CliRunner()


def test_absurd_magnitudes_fail_for_every_model():
    """x'' = -w^2 x from x0 = 1, v0 = 1e30 with w = 0.01 reaches |x| = v0 / w = 1e32 (closed
    form), beyond ABSURD_MAGNITUDE = 1e30: IMPOSSIBLE; the unit start beside it succeeds."""
    osc = HarmonicOscillator(frequency=0.01)
    t_quarter = np.pi / 2 / 0.01
    sol = solve_ensemble(osc, [[1.0, 0.0], [1.0, 1e30]], (0.0, t_quarter), save_at=SaveAt(ts=[t_quarter]),
                         control=StepControl(rtol=1e-8, atol=1e-8))  # fmt: skip
    assert sol.status.tolist() == [Status.SUCCESS, Status.IMPOSSIBLE]
    assert sol.notes[0] == "" and "beyond any physical magnitude" in sol.notes[1]
    assert sol.trajectory(1).note == sol.notes[1] and not sol.trajectory(1).success
    assert abs(sol.y_final[1, 0] - 1e32) < 1e26  # the state itself is kept, only flagged
    # seen only in a saved state: with v0 = 2e29, x(T/4) = 2e31 is saved, the final state at T/2
    # (x = -1, v = -2e29) is within the bound
    sol = solve_ensemble(osc, [1.0, 2e29], (0.0, 2 * t_quarter), save_at=SaveAt(ts=[t_quarter]),
                         control=StepControl(rtol=1e-8, atol=1e-8))  # fmt: skip
    assert abs(sol.y_final[0, 1] + 2e29) < 1e23 and sol.status[0] == Status.IMPOSSIBLE
    assert "state entry 0 reached 2e+31" in sol.notes[0]


@dataclass(frozen=True)
class Budgeted:
    """The harmonic oscillator with a sanity check of its energy against a budget: an undamped
    oscillator without sources keeps E = (v^2 + w^2 x^2) / 2 (per unit mass), so a final energy
    above E(0) (1e-6 relative) is impossible. ``params`` row: ``[w]``."""

    inner: HarmonicOscillator = HarmonicOscillator(1.0)
    seen: list = None

    kernels = property(lambda self: self.inner.kernels)
    state_names = property(lambda self: self.inner.state_names)

    def to_array(self):
        return self.inner.to_array()

    def impossible_states(self, ys, y_final, t_final, params):
        self.seen.append(np.array(params))
        w = np.broadcast_to(params[:, 0], (y_final.shape[0],))
        e0 = 0.5 * (ys[:, 0, 1] ** 2 + (w * ys[:, 0, 0]) ** 2)
        e1 = 0.5 * (y_final[:, 1] ** 2 + (w * y_final[:, 0]) ** 2)
        return [f"energy {b:.6g} J/kg above its budget {a:.6g}" if b > a * (1 + 1e-6) else ""
                for a, b in zip(e0, e1)]  # fmt: skip


def test_a_model_check_sees_each_trajectorys_own_parameters():
    """Three trajectories with their own w; the saved first state is x = 1, v = 0 for all. The
    check is given the parameters of each: with the integrator's true dynamics none is flagged;
    with the parameters handed to the check doubled for the second only (as if the budget were
    computed for another model) that one is flagged, the others not."""
    model = Budgeted(seen=[])
    params = np.array([[1.0], [2.0], [3.0]])
    sol = solve_ensemble(model, [1.0, 0.0], (0.0, 1.0), params=params, save_at=SaveAt(ts=[0.0, 1.0]),
                         control=StepControl(rtol=1e-10, atol=1e-12))  # fmt: skip
    assert sol.status.tolist() == [0, 0, 0] and model.seen[-1].tolist() == params.tolist()

    class Lying(Budgeted):
        def impossible_states(self, ys, y_final, t_final, params):
            p = np.array(params)
            p[1, 0] *= 0.5  # the check believes w = 1 for trajectory 1: its E(0) budget is 4 x too small
            return super().impossible_states(ys, y_final, t_final, p)

    sol = solve_ensemble(Lying(seen=[]), [1.0, 0.0], (0.0, 1.0), params=params, save_at=SaveAt(ts=[0.0, 1.0]),
                         control=StepControl(rtol=1e-10, atol=1e-12))  # fmt: skip
    assert sol.status.tolist() == [0, Status.IMPOSSIBLE, 0]
    assert sol.notes[1].startswith("energy") and "above its budget" in sol.notes[1]


def test_impact_rotor_check_flags_penetration_beyond_the_gap():
    """P may pass the housing only by the event tolerance; beyond the whole gap the run is
    impossible, whether seen in the recorded maximum or in a saved state."""
    model = krasnov_crusher().with_stones(t_end=0.1, seed=0)
    p = model.to_array()[None, :]
    gap = model.housing.gap
    yf = np.zeros((3, _k.N_STATE))
    yf[:, _k.PEN_MAX] = [1e-9, 2.0 * gap, 0.0]
    ys = np.full((3, 2, _k.N_STATE), np.nan)
    ys[:, 0, :] = 0.0
    ys[2, 1, :] = 0.0
    ys[2, 1, _k.U1] = 3.0 * gap / np.sin(model.housing.cone_angle)  # |w| = 3 gap in a saved state
    notes = model.impossible_states(ys, yf, np.array([0.1, 0.1, 0.1]), p)
    assert notes[0] == ""
    assert "went 0.009 m through the housing (gap 0.0045 m)" in notes[1]
    assert "went 0.009 m through the housing" in notes[2]


def _case(old: str, new: str) -> str:
    text = resources.files("rotorlab.cases").joinpath("krasnov-crusher.toml").read_text(encoding="utf-8")
    assert old in text
    return text.replace(old, new)


def test_restitution_one_with_heavy_stones_is_the_rolling_backward_whirl_not_a_success(tmp_path):
    """Issue 14/16: restitution 1.0 with 3 kg stones piled up 1.4 million 'impacts' and a
    penetration of 2e6 m, reported as success (seed 001's own impulse, friction always along
    -e_perp, pushed the backward whirl past rolling). With the shared contact law the friction
    impulse sticks once the slip of P vanishes: the rotor rolls on the housing, the dry-friction
    backward whirl, where the run stops and is labelled so (exit 0, with the time in the detail);
    the energy ledger shows the vibration energy came from the drive (tests/unit/test_impact_ledger.py).
    A run the integrator cannot finish (stones of 1e300 kg overflow the state) is failed, exit 3."""
    case = tmp_path / "elastic.toml"
    case.write_text(_case("restitution = 0.5", "restitution = 1.0"))
    res = runner.invoke(app, ["impacts", str(case), "--stone-mass", "3", "--t-end", "0.2", "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["regime"] == "backward_whirl" and doc["status"] == Status.EVENT_STOP and doc["backward_whirl"]
    assert doc["t_final_s"] < 0.2 and doc["impacts"] < 1e5 and doc["max_penetration_m"] < 1e-12
    assert "onset of the dry-friction backward whirl" in doc["status_detail"]
    assert doc["energy_vibration_J"] < doc["energy_friction_J"] + doc["work_stones_J"]
    res = runner.invoke(app, ["impacts", "krasnov-crusher", "--stone-mass", "1e300", "--t-end", "0.2", "--json"])
    assert res.exit_code == 3, res.output
    doc = json.loads(res.stdout)
    assert doc["regime"] == "failed" and doc["status"] < 0 and "non-finite" in doc["status_detail"]
    assert "failed results" in res.stderr


def test_absurd_disc_mass_fails_and_exits_3(tmp_path):
    """A 1e-300 kg disc (critical speed ~1e150 rad/s) cannot be integrated: every trajectory fails
    (its step size falls below the round-off of the time, or it runs out of steps). Before the
    exit code was 0 with 'failed:' outcomes; the results are printed and the command exits 3.
    (This test used a 1e308 kg disc, whose state overflowed until session 13; the machine kernel no
    longer overflows there, and at 1e-152 rad/s nothing moves in 0.5 s.)"""
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    (tmp_path / "heavy.toml").write_text(text.replace('disc_mass = "1 kg"', 'disc_mass = "1e-300 kg"'))
    res = runner.invoke(app, ["simulate", str(tmp_path / "heavy.toml"), "--analysis", "supercritical",
                              "--t-end", "0.5", "--json"])  # fmt: skip
    assert res.exit_code == 3, res.output
    rows = json.loads(res.stdout)["rows"]
    assert rows and all(r["outcome"].startswith("failed") for r in rows)
    assert "failed results: supercritical: 6 of 6 failed" in res.stderr


@pytest.mark.parametrize("bad", [[], None])
def test_exit_if_failed_passes_usable_results(bad):
    import typer
    import xarray as xr

    from rotorlab.cli._output import exit_if_failed

    exit_if_failed({"a": xr.Dataset({"status": ("ic", np.array([0, 1], dtype=np.int32))}), "b": None})
    with pytest.raises(typer.Exit) as err:
        exit_if_failed({"a": xr.Dataset({"status": ("ic", np.array([0, -5, -1], dtype=np.int32))})})
    assert err.value.exit_code == 3
    # a single run's status as an attribute (the rub analysis), with its message
    exit_if_failed({"r": xr.Dataset(attrs={"status": 0, "status_message": "reached the end time"})})
    with pytest.raises(typer.Exit):
        exit_if_failed({"r": xr.Dataset(attrs={"status": -5, "status_message": "passed through the stator"})})
