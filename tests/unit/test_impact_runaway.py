"""The crusher's last milliseconds (issue 28, item 5) and a stone leaving a sliding contact.

A run stopped at the dry-friction backward whirl ends in a runaway: the contact point whirls
backwards on the housing, friction feeds the whirl and the normal force grows with its square,
so nearly all the run's friction work (and, with restitution 1, its impacts) comes in its last
milliseconds. The run's values before the runaway and the runaway's own are reported apart.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab._kernels import impact_rotor as k
from rotorlab.analyses import impact_run, impact_summary
from rotorlab.analyses._impacts import _control
from rotorlab.integrate import SaveAt, solve_ensemble
from rotorlab.models import StoneSequence, krasnov_crusher


@pytest.mark.parametrize(("mass", "restitution", "seed"), [
    (3.0, 0.5, 1),  # the seed's case: into the whirl through a sliding contact
    (1.0, 1.0, 0),  # restitution 1: through impacts (issue 28: eta 137-215 at the stop)
])  # fmt: skip
def test_the_runaway_is_reported_apart_from_the_run_before_it(mass, restitution, seed):
    """eta at the stop is 47 (3 kg) and about 140 (restitution 1) but below 2 before the
    runaway, which holds more than 98 % of the friction work; the values before the runaway are
    those of the same run re-simulated to the runaway's start (independent of the records)."""
    model = krasnov_crusher(stone_mass=mass, restitution=restitution)
    ds = impact_run(model, t_end=10.0, seed=seed, n_save=10)
    s = impact_summary(ds)
    assert s["regime"] == "backward_whirl" and s["runaway_start_s"] < s["t_final_s"] < 1.0
    assert s["energy_ratio"] > 20.0 and s["energy_ratio_before_runaway"] < 2.0
    assert s["energy_friction_runaway_J"] > 0.98 * s["energy_friction_J"]
    assert s["impacts_before_runaway"] + s["impacts_runaway"] == s["impacts"]
    from rotorlab.report._findings import impact_findings

    eta_line = impact_findings(ds, [s]).numbers[1]
    assert eta_line.startswith(f"energy ratio eta = {s['energy_ratio_before_runaway']:.3g} before the runaway")
    assert f"({s['energy_ratio']:.3g} at the stop;" in eta_line
    # the same stones, integrated only to the runaway's start
    run = model.with_stones(10.0, seed)
    t_run = s["runaway_start_s"] + 1e-6
    yf = solve_ensemble(run, run.initial_state(), (0.0, t_run), save_at=SaveAt(ts=[t_run]),
                        control=_control(1e-8, 1e-11), threads=1).y_final[0]  # fmt: skip
    h = run.housing
    e_fr = yf[k.W_DRIVE] + h.friction * h.radius * run.rotor.spin_speed * yf[k.INT_N]
    assert yf[k.WHIRL] == 0.0 and int(yf[k.N_IMP]) == s["impacts_before_runaway"]
    assert e_fr / run.stone_energy(t_run) == pytest.approx(s["energy_ratio_before_runaway"], rel=1e-3)


def test_a_run_not_stopped_has_no_runaway():
    ds = impact_run(krasnov_crusher(stone_mass=0.8), t_end=2.0, seed=0, n_save=10)
    s = impact_summary(ds)
    assert s["regime"] == "rebounds" and s["runaway_start_s"] is None
    assert s["impacts_runaway"] == 0 and s["energy_friction_runaway_J"] == 0.0
    assert s["impacts_before_runaway"] == s["impacts"] and s["energy_ratio_before_runaway"] == s["energy_ratio"]


def test_a_stone_leaving_a_sliding_contact_that_it_held_lifts_the_rotor_off():
    """Translational rotor on the housing (|u| = Delta along x) whirling forwards at 80 rad/s in
    the fixed frame, below the natural frequency sqrt(c/m) = 100.6 rad/s: on its own the housing
    would have to pull it (N = m Delta (80^2 - c/m) = -10.7 kN); a 5 kg stone at the rim of guide 0
    pushes it outwards with about 110 kN (1.4 m omega0^2 R_q), so N > 0 while the stone is on its
    guide. When it leaves (a breakpoint, the force drops at once) the rotor must lift off there:
    a sliding contact with N < 0 would hold the rotor on the housing by pulling."""
    base = krasnov_crusher(translational=True, interval=0.07, internal_friction=0.5, restitution=0.7,
                           friction=0.3, stone_mass=5.0)  # fmt: skip
    model = replace(base, sequence=StoneSequence([0.01], [5.0], [0], base.stones.n_guides))
    p = model.to_array()
    t_dep = 0.01 + model.push().tau_end / model.rotor.spin_speed
    assert p[int(p[k.P_OBP]) + 1] == pytest.approx(t_dep, rel=1e-12)
    delta, w0, whirl = model.housing.gap, model.rotor.spin_speed, 80.0
    y = model.initial_state()
    y[k.U1] = delta
    y[k.DU2] = (whirl - w0) * delta  # fixed-frame velocity whirl * delta along y
    y[k.MODE], y[k.I_BP], y[k.T_START] = 1.0, 1.0, 0.02
    n_held, _, _ = k.contact_force(t_dep, y, p)
    assert n_held > 5e4
    y_new = np.empty_like(y)
    assert k.reset(k.EV_STONE, t_dep, y, p, y_new) == 0
    assert y_new[k.I_BP] == 2.0
    n_free, _, _ = k.contact_force(t_dep, y_new, p)
    m, c = model.rotor.mass, model.rotor.stiffness
    assert n_free == pytest.approx(m * delta * (whirl**2 - c / m), rel=1e-9)
    assert y_new[k.MODE] == 0.0 and y_new[k.T_RESET] == t_dep
    assert y_new[k.T_SLIDE] == pytest.approx(t_dep - 0.02, rel=1e-12)
    assert math.isclose(k.whirl_speed(y_new, p), whirl, rel_tol=1e-9) and y_new[k.R_T] == t_dep
