"""Seed 001, eqs. (3.5)-(3.9): the impact map and the energy of the small motions.

Reconstruction 1 (the garbled impact map (3.9)) is checked by: the normal speed after the map is
``-k`` times the speed before; the impulse is ``(1 + k) m* v`` with the equivalent mass of (3.9);
with k = 1 and f = 0 (elastic, frictionless) the Jacobi energy of the rotating frame is conserved
through every impact; with k < 1 it drops by exactly the sum of ``1/2 m* (1 - k^2) v^2``.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab._kernels import impact_rotor as K
from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.models import krasnov_crusher


def _model(k, f, translational=False, gamma=0.0):
    m = krasnov_crusher(translational=translational, internal_friction=gamma, restitution=k, friction=f)
    return m


def _state_on_housing(model, phi, v_in):
    """A state with P on the housing at angle phi, approaching it at v_in, plus a tangential speed."""
    gap = model.housing.gap
    sb = math.sin(model.housing.cone_angle)
    e = np.array([math.cos(phi), math.sin(phi)])
    y = model.initial_state()
    share = 1.0 if model.translational else 0.5  # share of the gap taken by the displacement
    y[K.U1:K.U2 + 1] = share * gap / sb * e
    lp = model.housing.lever()
    if not model.translational:
        y[K.T1:K.T2 + 1] = 0.5 * gap / lp * e
    y[K.DU1:K.DU2 + 1] = v_in / sb * e + 0.1 * np.array([-e[1], e[0]])
    return y


@pytest.mark.parametrize("translational", [False, True])
def test_impact_map_reverses_the_normal_speed_with_restitution(translational):
    model = _model(0.5, 0.2, translational)
    p = model.to_array()
    y = _state_on_housing(model, 0.7, 0.3)
    w = model.gap_vector(y)
    assert np.hypot(*w) == pytest.approx(model.housing.gap, rel=1e-12)
    e = w / np.hypot(*w)
    v_before = e @ model.gap_vector(y[4:8])
    y_new = np.empty_like(y)
    assert K.reset(K.EV_IMPACT, 1.0, y, p, y_new) == 0
    v_after = e @ model.gap_vector(y_new[4:8])
    assert v_after == pytest.approx(-0.5 * v_before, rel=1e-12)
    # impulse (3.9): S_n = (1 + k) m* v, 1/m* = sin^2(beta)/m + l_P^2/A1
    sb, lp = math.sin(model.housing.cone_angle), model.housing.lever()
    inv = sb**2 / 635.7 + (0.0 if translational else lp**2 / 70.35)
    sn = 1.5 * v_before / inv
    assert y_new[K.S_SUM] == pytest.approx(sn, rel=1e-12)
    # plane impulse -S_n (sin(beta) e + f e_perp) on the centre of mass
    e_perp = np.array([-e[1], e[0]])
    assert np.allclose((y_new[4:6] - y[4:6]) * 635.7, -sn * (sb * e + 0.2 * e_perp), rtol=1e-12)
    assert y_new[K.N_IMP] == 1 and y_new[K.V_MAX] == pytest.approx(v_before)


@pytest.mark.parametrize("translational", [False, True])
def test_elastic_frictionless_impacts_conserve_energy(translational):
    model = _model(1.0, 0.0, translational)
    y0 = model.initial_state(u=(1e-3, 0.0), du=(0.8, 0.2), dtilt=(0.0, 0.0 if translational else 2.0))
    ts = np.linspace(0.0, 2.0, 401)
    sol = solve(model, y0, (0.0, 2.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-14))
    assert sol.status.name == "SUCCESS"
    assert sol.y_final[K.N_IMP] > 50
    assert sol.y_final[K.N_SLIDE] == 0
    h = model.jacobi_energy(sol.ys)
    assert np.max(np.abs(h - h[0])) < 1e-7 * h[0]
    assert np.max(np.hypot(*model.gap_vector(sol.ys).T)) <= model.housing.gap * (1 + 1e-9)


def test_restitution_loss_is_the_energy_lost():
    model = _model(0.5, 0.0)
    y0 = model.initial_state(du=(0.5, 0.0), dtilt=(0.0, 1.0))
    sol = solve(model, y0, (0.0, 1.0), control=StepControl(rtol=1e-10, atol=1e-14))
    yf = sol.y_final
    assert yf[K.N_ALL] >= 3
    lost = model.jacobi_energy(y0) - model.jacobi_energy(yf)
    assert lost > 0.1 * model.jacobi_energy(y0)
    assert yf[K.E_REST] == pytest.approx(lost, rel=1e-6)


def test_chatter_turns_into_sliding_and_lifts_off_when_the_force_would_pull():
    # Heavy stones push the rotor against the housing: runs of impacts accumulate into sliding
    # (P stays on the housing, |w| = gap) which ends when the normal force would pull.
    model = krasnov_crusher(stone_mass=1.5, friction=0.0).with_stones(2.0, seed=0)
    y0 = model.initial_state()
    ts = np.linspace(0.0, 2.0, 20001)
    sol = solve(model, y0, (0.0, 2.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-14))
    yf = sol.y_final
    assert yf[K.N_SLIDE] >= 1 and sol.event_counts["lift_off"] >= 1
    sliding = sol.ys[:, K.MODE] == 1.0
    r = np.hypot(*model.gap_vector(sol.ys).T)
    assert sliding.any()
    assert np.max(np.abs(r[sliding] / model.housing.gap - 1.0)) < 1e-6
    assert yf[K.PEN_MAX] < 1e-9 * model.housing.gap


def test_friction_energy_vanishes_without_friction_and_eta_is_the_ratio():
    from rotorlab.analyses import impact_run

    model = krasnov_crusher(stone_mass=1.0)
    ds = impact_run(model, t_end=2.0, seed=3, n_save=10)
    assert int(ds.impacts) > 5 and float(ds.energy_friction) > 0
    assert float(ds.eta) == pytest.approx(float(ds.energy_friction) / float(ds.energy_stones))
    # stones' energy: 57 stones fully accelerated, W = 1.1472 m R_q^2 w0^2 each (+ partial last)
    per_stone = 1.0 * (0.6 * 160.0) ** 2 * model.push().work[-1]
    assert float(ds.energy_stones) == pytest.approx(57 * per_stone, rel=0.02)
    free = impact_run(replace(model, housing=replace(model.housing, friction=0.0)), t_end=2.0, seed=3, n_save=10)
    assert int(free.impacts) > 5 and float(free.energy_friction) == 0.0 and float(free.eta) == 0.0
