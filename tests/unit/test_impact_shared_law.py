"""Seed 001's impact map is the shared contact law (``rotorlab._kernels.contact``) at point P.

The impulse of (3.9) as printed (Krasnov, Tovstik & Tovstik 2003, reconstructed in
``rotorlab.models._impact_rotor``): ``S_n = (1 + k) m* v``, ``u'+ = u'- - (S_n/m)(sin(beta) e + f
e_perp)``, ``t'+ = t'- - (S_n/A1)(l_P e + f h_P e_perp)``. On random states the seed's reset equals
it, and so does ``newton_coulomb_impulse`` with the Delassus entries of P (``B M^-1 B^T`` of the
contact point's velocity map) to round-off: the kernel's impact reset *is* that shared function
(see the note in ``rotorlab._kernels.impact_rotor``), so this checks the shared law against the
printed map.
"""

import math

import numpy as np
import pytest

from rotorlab._kernels import impact_rotor as k
from rotorlab._kernels.contact import newton_coulomb_impulse
from rotorlab.models import krasnov_crusher


def _on_housing(model, rng, v_min):
    """A random state with P on the housing (|w| = gap) approaching it at >= v_min (m/s)."""
    h = model.housing
    sb, lp = math.sin(h.cone_angle), h.lever()
    y = model.initial_state()
    y[k.T1:k.T2 + 1] = 0.0 if model.translational else rng.normal(0, 2e-3, 2)
    phi = rng.uniform(0, 2 * np.pi)
    e = np.array([np.cos(phi), np.sin(phi)])
    y[k.U1:k.U2 + 1] = (h.gap * e - lp * y[k.T1:k.T2 + 1]) / sb  # w = gap e
    y[k.DU1:k.DU2 + 1] = rng.normal(0, 0.05, 2)
    if not model.translational:
        y[k.DT1:k.DT2 + 1] = rng.normal(0, 0.2, 2)
    vn = e @ (sb * y[k.DU1:k.DU2 + 1] + lp * y[k.DT1:k.DT2 + 1])
    y[k.DU1:k.DU2 + 1] += (v_min + abs(vn) + rng.uniform(0, 0.05) - vn) * e / sb
    return y, e


@pytest.mark.parametrize("translational", [False, True])
def test_delassus_of_p_is_b_minv_bt(translational):
    m = krasnov_crusher(translational=translational)
    p = m.to_array()
    h, r = m.housing, m.rotor
    sb, lp, hp = math.sin(h.cone_angle), h.lever(), h.height
    e = np.array([0.6, 0.8])
    ep = np.array([-e[1], e[0]])
    n = 2 if translational else 4
    b = np.array([[*(sb * e), *(lp * e)], [*ep, *(hp * ep)]])[:, :n]  # (v_n, tangential speed of P)
    minv = np.diag([1 / r.mass, 1 / r.mass, 1 / r.inertia_transverse, 1 / r.inertia_transverse][:n])
    w = b @ minv @ b.T
    assert np.allclose(k.delassus(p), (w[0, 0], w[0, 1], w[1, 1]), rtol=1e-14, atol=1e-14 * w[0, 0])
    assert 1 / k.delassus(p)[0] == pytest.approx(m.equivalent_mass, rel=1e-14)


@pytest.mark.parametrize("translational", [False, True])
def test_shared_impulse_equals_printed_39_on_random_states(translational):
    rng = np.random.default_rng(16)
    for _ in range(200):
        kr, f = rng.uniform(0.05, 1.0), rng.uniform(0.0, 0.6)
        m = krasnov_crusher(translational=translational, restitution=kr, friction=f)
        p = m.to_array()
        h, r = m.housing, m.rotor
        sb, lp, hp = math.sin(h.cone_angle), h.lever(), h.height
        y, e = _on_housing(m, rng, v_min=h.rest_speed / kr + 1e-3)
        ep = np.array([-e[1], e[0]])
        v = e @ (sb * y[k.DU1:k.DU2 + 1] + lp * y[k.DT1:k.DT2 + 1])
        y_new = np.empty_like(y)
        assert k.reset(k.EV_IMPACT, 0.5, y, p, y_new) == 0
        sn = (1 + kr) * m.equivalent_mass * v  # (3.9)
        du = y[k.DU1:k.DU2 + 1] - sn / r.mass * (sb * e + f * ep)
        dt = y[k.DT1:k.DT2 + 1] - (0.0 if translational else sn / r.inertia_transverse) * (lp * e + f * hp * ep)
        assert np.allclose(y_new[k.DU1:k.DU2 + 1], du, rtol=1e-13, atol=1e-15)
        assert np.allclose(y_new[k.DT1:k.DT2 + 1], dt, rtol=1e-13, atol=1e-15)
        assert y_new[k.S_SUM] == pytest.approx(sn, rel=1e-14)
        pn, pt, stick = newton_coulomb_impulse(v, k.slip_speed(y, p, *e), *k.delassus(p), kr, f)  # shared law
        assert not stick and pn == pytest.approx(sn, rel=1e-14) and pt == pytest.approx(-f * sn, rel=1e-14, abs=1e-300)
        assert y_new[k.E_REST] == pytest.approx(0.5 * m.equivalent_mass * (1 - kr * kr) * v * v, rel=1e-12)
        v_after = e @ (sb * y_new[k.DU1:k.DU2 + 1] + lp * y_new[k.DT1:k.DT2 + 1])
        assert v_after == pytest.approx(-kr * v, rel=1e-12)  # Newton: v+ = -k v-
