"""Closed-form rotors: Jeffcott, a gyroscopic disc, damped unbalance response, log decrement.

Sources: Friswell et al. (2010), Chapter 3 (Jeffcott rotor: omega_n = sqrt(k/m); rigid disc on a
tilt spring: forward and backward frequencies (I_p Omega +- sqrt(I_p^2 Omega^2 + 4 I_d k_t)) /
(2 I_d); steady unbalance response of the damped Jeffcott rotor); standard beam tables for the
midspan stiffness 48 EI / L^3 of a pinned-pinned shaft. Exact formulas, so tolerances are set
by round-off or by the deliberately small shaft mass.
"""

import math

import numpy as np
import pytest

from rotorlab.linear import (
    RPM,
    Bearing,
    Material,
    RigidBody,
    Unbalance,
    assemble,
    campbell,
    critical_speeds,
    modal,
    uniform_shaft,
    unbalance_response,
)


def _disc_on_springs(m=2.0, k=8e4, idia=0.02, ipol=0.03, kt=5e3, c=0.0):
    return assemble([RigidBody(0, m, idia, ipol), Bearing(0, kxx=k, cxx=c, k_tilt_x=kt)])


def test_jeffcott_limit_sqrt_k_over_m_at_any_speed():
    s = _disc_on_springs()
    for rpm in (0.0, 3000.0, 20000.0):
        f = modal(s, rpm * RPM).natural_frequency
        assert np.sum(np.isclose(f, math.sqrt(8e4 / 2.0), rtol=1e-12)) == 2


def test_jeffcott_rotor_on_flexible_massless_shaft():
    # disc at midspan of a pinned-pinned Euler-Bernoulli shaft: k = 48 EI / L^3
    light = Material(youngs_modulus=2e11, shear_modulus=8e10, density=1e-3)
    shaft = uniform_shaft(2, 0.8, 0.02, material=light, shear=False)
    m = 10.0
    parts = [*shaft, RigidBody(1, m, 1e-2, 2e-2),
             Bearing(0, kxx=1e15), Bearing(2, kxx=1e15)]
    s = assemble(parts)
    ei = 2e11 * math.pi * 0.02 ** 4 / 64
    expected = math.sqrt(48 * ei / 0.8 ** 3 / m)
    for rpm in (0.0, 5000.0):
        f = modal(s, rpm * RPM, n_modes=2).natural_frequency
        np.testing.assert_allclose(f, expected, rtol=1e-6)


@pytest.mark.parametrize("rpm", [0.0, 1000.0, 6000.0, 30000.0])
def test_gyroscopic_disc_forward_and_backward_frequencies(rpm):
    idia, ipol, kt = 0.02, 0.03, 5e3
    om = rpm * RPM
    root = math.sqrt((ipol * om) ** 2 + 4 * idia * kt)
    forward = (ipol * om + root) / (2 * idia)
    backward = (-ipol * om + root) / (2 * idia)
    md = modal(_disc_on_springs(idia=idia, ipol=ipol, kt=kt), om)
    lam = np.sort(md.natural_frequency)
    assert np.isclose(lam, forward, rtol=1e-12).sum() == (1 if rpm > 0 else 2)
    assert np.isclose(lam, backward, rtol=1e-12).sum() == (1 if rpm > 0 else 2)
    if rpm > 0:
        f_idx = np.flatnonzero(np.isclose(md.natural_frequency, forward, rtol=1e-12))[0]
        b_idx = np.flatnonzero(np.isclose(md.natural_frequency, backward, rtol=1e-12))[0]
        assert md.whirl[f_idx] == 1 and md.whirl[b_idx] == -1


def test_gyroscopic_disc_critical_speeds():
    # backward: (I_d + I_p) W^2 = k_t; forward needs I_d > I_p
    flat = critical_speeds(_disc_on_springs(idia=0.02, ipol=0.03, kt=5e3))
    tilt = flat.speed[~np.isclose(flat.speed, 200.0)]
    np.testing.assert_allclose(tilt, [math.sqrt(5e3 / 0.05)], rtol=1e-12)
    assert flat.whirl[np.isclose(flat.speed, math.sqrt(5e3 / 0.05))][0] == -1
    long = critical_speeds(_disc_on_springs(idia=0.03, ipol=0.02, kt=5e3))
    tilt = np.sort(long.speed[~np.isclose(long.speed, 200.0)])
    np.testing.assert_allclose(tilt, [math.sqrt(5e3 / 0.05), math.sqrt(5e3 / 0.01)], rtol=1e-12)
    # 2x: omega = 2 W for the translation: W = sqrt(k/m) / 2
    two = critical_speeds(_disc_on_springs(), harmonics=(2,))
    assert np.isclose(two.speed, 100.0, rtol=1e-12).sum() == 2


def test_damped_jeffcott_unbalance_amplitude_and_phase():
    m, k, c, me = 2.0, 8e4, 40.0, 1e-4
    s = _disc_on_springs(m=m, k=k, c=c)
    w = np.linspace(10.0, 600.0, 60)
    ds = unbalance_response(s, w, [Unbalance(0, me)])
    amp = me * w ** 2 / np.sqrt((k - m * w ** 2) ** 2 + (c * w) ** 2)
    phase = -np.arctan2(c * w, k - m * w ** 2)
    np.testing.assert_allclose(ds.amplitude.sel(dof=0), amp, rtol=1e-10)
    np.testing.assert_allclose(ds.phase.sel(dof=0), phase, rtol=1e-10, atol=1e-12)
    # circular forward orbit, y lags x by 90 degrees
    np.testing.assert_allclose(ds.orbit_minor.sel(node_index=0), ds.orbit_major.sel(node_index=0),
                               rtol=1e-10)
    assert np.all(ds.orbit_whirl.values == 1)
    lag = np.angle(np.exp(1j * (ds.phase.sel(dof=1) - ds.phase.sel(dof=0))))
    np.testing.assert_allclose(lag, -np.pi / 2, atol=1e-12)
    # at resonance the response lags the heavy spot by 90 degrees
    res = unbalance_response(s, [math.sqrt(k / m)], [Unbalance(0, me)])
    assert float(res.phase.sel(dof=0)[0]) == pytest.approx(-np.pi / 2, abs=1e-12)


def test_unbalance_response_is_linear_and_phase_shifts():
    s = _disc_on_springs(c=30.0)
    w = [150.0, 250.0]
    a = unbalance_response(s, w, [Unbalance(0, 1e-4, phase=0.0)])
    b = unbalance_response(s, w, [Unbalance(0, 2e-4, phase=0.7)])
    np.testing.assert_allclose(b.amplitude, 2 * a.amplitude, rtol=1e-12)
    dphi = np.angle(np.exp(1j * (b.phase.sel(dof=0) - a.phase.sel(dof=0))))
    np.testing.assert_allclose(dphi, 0.7, atol=1e-12)


def test_log_decrement_of_a_damped_oscillator():
    m, k, c = 2.0, 8e4, 60.0
    zeta = c / (2 * math.sqrt(k * m))
    md = modal(_disc_on_springs(m=m, k=k, c=c))
    trans = np.isclose(md.natural_frequency, math.sqrt(k / m), rtol=1e-9)
    assert trans.sum() == 2
    np.testing.assert_allclose(md.log_decrement[trans], 2 * np.pi * zeta / math.sqrt(1 - zeta**2),
                               rtol=1e-10)
    np.testing.assert_allclose(md.damping_ratio[trans], zeta, rtol=1e-10)
    assert md.is_stable


def test_cross_coupled_stiffness_destabilises_forward_whirl():
    # k_xy = -k_yx > 0 feeds energy into forward whirl: one growing mode (Friswell, Ch. 7)
    s = assemble([RigidBody(0, 2.0, 0.02, 0.0), Bearing(0, kxx=8e4, kxy=4e3, kyx=-4e3, cxx=5.0,
                                                       k_tilt_x=1e3)])
    md = modal(s, 0.0)
    assert not md.is_stable
    grow = md.eigenvalues.real > 1e-9 * np.abs(md.eigenvalues)
    assert grow.sum() == 1 and md.whirl[grow][0] == 1
    ds = campbell(s, [0.0, 100.0], n_modes=4)
    assert not bool(ds.stable.any()) and ds.attrs["method"] == "isotropic"
