"""Properties of the contact law kernels (:mod:`rotorlab._kernels.contact`), on their Python
functions: the impulse obeys Newton's restitution and Coulomb's cone, its energy split is exact,
friction never creates energy (W. J. Stronge, *Impact Mechanics*, CUP 2000, ch. 2-5)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from rotorlab._kernels import contact as law

_impulse = law.newton_coulomb_impulse.py_func
_energy = law.impulse_energy.py_func

speeds = st.floats(1e-6, 10.0)
slips = st.floats(-10.0, 10.0)
masses = st.floats(0.01, 100.0)
restitutions = st.floats(0.0, 1.0)
frictions = st.floats(0.0, 2.0)


def _after(vn, s, pn, pt, wnn, wnt, wtt):
    return vn - wnn * pn + wnt * pt, s - wnt * pn + wtt * pt


@given(vn=speeds, s=slips, m=masses, j_ratio=st.floats(0.0, 5.0), e=restitutions, mu=frictions)
def test_impulse_restitution_cone_and_energy_on_a_spinning_disc(vn, s, m, j_ratio, e, mu):
    """Central impact of a disc (W diagonal: 1/m, 1/m + R^2/J): the normal speed reverses with e,
    the impulse lies in the friction cone, sticks only when it stops the slip, and the kinetic
    energy change equals the split -loss_n - loss_t + drive with both losses >= 0."""
    wnn, wnt, wtt = 1.0 / m, 0.0, (1.0 + j_ratio) / m
    pn, pt, stick = _impulse(vn, s, wnn, wnt, wtt, e, mu)
    vn2, s2 = _after(vn, s, pn, pt, wnn, wnt, wtt)
    assert pn > 0.0
    assert np.isclose(vn2, -e * vn, rtol=1e-12, atol=1e-12 * vn)
    assert abs(pt) <= mu * pn * (1 + 1e-12)
    if stick:
        assert abs(s2) <= 1e-12 * (abs(s) + vn)
    else:
        assert np.isclose(abs(pt), mu * pn, rtol=1e-12) and (mu * pn == 0.0 or np.sign(pt) == -np.sign(s))  # (a subnormal mu*pn rounds pt to 0)
        assert np.sign(s2) == np.sign(s) or s2 == 0.0  # Coulomb slip does not reverse
    ln, lt, drive = _energy(vn, s, pn, pt, wnn, wnt, wtt, 0.0)
    scale = m * (vn * vn + s * s)
    assert ln >= -1e-12 * scale and lt >= -1e-12 * scale
    assert np.isclose(ln, 0.5 * (1 - e * e) * vn * vn / wnn, rtol=1e-10, atol=1e-12 * scale)
    # kinetic energy of translation + spin: T = 1/2 m u^2 + 1/2 J w^2 with J w^2 = m (s - u_t)^2 / j_ratio
    if j_ratio > 0.01:  # (a vanishing J/m R^2 ratio makes the spin energy a huge difference)
        # u_t is free: pick 0; dT of the disc = P . (v- + v+) / 2 in the contact coordinates
        du_t = pt / m
        dspin_speed = (s2 - s) - du_t  # R dw
        t_before = 0.5 * m * (vn * vn) + 0.5 * (m / j_ratio) * s * s
        t_after = 0.5 * m * (vn2**2 + du_t**2) + 0.5 * (m / j_ratio) * (s + dspin_speed) ** 2
        assert np.isclose(t_after - t_before, drive - ln - lt, rtol=1e-9, atol=1e-12 * m * (vn * vn + s * s))


@given(vn=speeds, s=slips, m=masses, mu=frictions, ss=st.floats(-10.0, 10.0))
def test_prescribed_spin_energy_split(vn, s, m, mu, ss):
    """Point mass with a prescribed surface speed ``ss``: the translational kinetic energy changes
    by drive - loss_n - loss_t, the drive work being -P_t R Omega."""
    w = 1.0 / m
    pn, pt, _ = _impulse(vn, s, w, 0.0, w, 1.0, mu)
    vn2, s2 = _after(vn, s, pn, pt, w, 0.0, w)
    ut, ut2 = s - ss, s2 - ss
    dt = 0.5 * m * (vn2**2 + ut2**2 - vn**2 - ut**2)
    ln, lt, drive = _energy(vn, s, pn, pt, w, 0.0, w, ss)
    assert abs(ln) <= 1e-12 * m * vn * vn  # e = 1: no restitution loss
    assert np.isclose(dt, drive - ln - lt, rtol=1e-9, atol=1e-12 * m * (vn * vn + s * s + ss * ss))


def test_frictionless_elastic_impact_only_reverses_the_normal_speed():
    pn, pt, _ = _impulse(2.0, 0.7, 0.5, 0.0, 0.5, 1.0, 0.0)
    assert pn == 8.0 and pt == 0.0  # m = 2: P_n = (1 + e) m v_n
    assert _energy(2.0, 0.7, pn, pt, 0.5, 0.0, 0.5, 0.0) == (0.0, 0.0, 0.0)


def test_stick_inside_the_cone_slip_outside():
    # m = 1, v_n = 1, e = 0: P_n = 1; stopping the slip s = 0.3 needs |P_t| = 0.3
    assert _impulse(1.0, 0.3, 1.0, 0.0, 1.0, 0.0, 0.31)[2] is True
    pn, pt, stick = _impulse(1.0, 0.3, 1.0, 0.0, 1.0, 0.0, 0.29)
    assert (stick, pn, pt) == (False, 1.0, -0.29)


def test_sustained_forces_closed_forms():
    f = law.sustained_forces.py_func
    # rigid stator, circular motion at speed v_t on radius r: N = m (a_n + v_t^2 / r)
    n, ft = f(3.0, -2.0, 4.0, 0.0, 2.0, 0.5, True, True)
    assert n == 0.5 * (3.0 + 8.0) and ft == 0.5 * 2.0
    assert f(3.0, -2.0, 4.0, 0.0, 2.0, 0.5, False, False) == (0.0, 0.0)
    assert law.penalty_normal_force.py_func(1e-3, -1.0, 1e4, 1.0) == 9.0
    assert law.penalty_normal_force.py_func(1e-3, -20.0, 1e4, 1.0) == 0.0  # never pulls
