"""Seed 001, eqs. (2.2) and (4.1): the rotating-frame equations against the fixed frame.

Reconstruction 2 (membrane forces with Sorokin's internal friction) reads the printed
``(gamma / w0)(u' + w0 x u)`` as the velocity relative to the *fixed* membranes: in the fixed
frame the membranes are springs ``c`` with viscous dampers ``c gamma / w0``. Here the model's
compiled rotating-frame kernel is compared with the fixed-frame equations, written independently
in complex form (X = x + i y, Theta = tilt, both fixed frame)::

    m X''                       = F_m + F_q,     F_m = -c (X_m + (gamma/w0) X_m'),  X_m = X + n_m Theta
    A1 Theta'' - i A3 w0 Theta' = n_m F_m - c_* (Theta + (gamma/w0) Theta') + h_q F_q

(Euler's equations of a symmetric rotor spinning at w0 with small tilt) integrated by scipy and
rotated by exp(-i w0 t).
"""

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.models import CentrifugeRotor, krasnov_crusher

W0 = 160.0


def test_membrane_coefficients_are_the_sum_of_the_two_membranes():
    r = CentrifugeRotor(635.7, 70.35, 115.68, W0, 2.0e6, 3.5e6, -0.05, 0.2, 0.2)
    c, nm, cs = r.stiffness, r.membrane_offset, r.tilt_stiffness
    assert c * nm == pytest.approx(2.0e6 * -0.05 + 3.5e6 * 0.2)
    assert cs + c * nm**2 == pytest.approx(2.0e6 * 0.05**2 + 3.5e6 * 0.2**2, rel=1e-14)


def _fixed_frame(model, t_eval, z0, stones):
    r = model.rotor
    m, a1, a3 = r.mass, r.inertia_transverse, r.inertia_polar
    c, nm, cs, gw = r.stiffness, r.membrane_offset, r.tilt_stiffness, r.internal_friction / W0
    hq = model.stones.height
    push = model.push()
    seq = model.sequence
    scale = seq.masses * W0**2 * model.stones.radius * np.exp(1j * seq.angles())

    def fq(t):
        tau = W0 * (t - seq.times)
        on = (tau >= 0) & (tau < push.tau_end)
        if not stones or not on.any():
            return 0j
        j = np.interp(tau[on], push.tau, push.jx) + 1j * np.interp(tau[on], push.tau, push.jy)
        return np.exp(1j * W0 * t) * np.sum(scale[on] * j)

    def f(t, s):
        x, th, dx, dth = s[0] + 1j * s[1], s[2] + 1j * s[3], s[4] + 1j * s[5], s[6] + 1j * s[7]
        fm = -c * ((x + nm * th) + gw * (dx + nm * dth))
        q = fq(t)
        ddx = (fm + q) / m
        ddth = (1j * a3 * W0 * dth + nm * fm - cs * (th + gw * dth) + hq * q) / a1
        return [dx.real, dx.imag, dth.real, dth.imag, ddx.real, ddx.imag, ddth.real, ddth.imag]

    # integrate piecewise between stone arrivals and departures
    bps = np.unique(np.concatenate([seq.times, seq.times + push.tau_end / W0])) if stones else []
    edges = [t_eval[0], *[b for b in bps if t_eval[0] < b < t_eval[-1]], t_eval[-1]]
    out = np.empty((8, t_eval.size))
    s = np.asarray(z0, dtype=float)
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (t_eval >= lo) & (t_eval <= hi)
        sol = solve_ivp(f, (lo, hi), s, method="DOP853", rtol=1e-11, atol=1e-14, dense_output=True)
        out[:, sel] = sol.sol(t_eval[sel])
        s = sol.y[:, -1]
    return out


def _to_rotating(out, ts):
    rot = np.exp(-1j * W0 * ts)
    x = (out[0] + 1j * out[1]) * rot
    th = (out[2] + 1j * out[3]) * rot
    return np.column_stack([x.real, x.imag, th.real, th.imag])


def _no_housing(model):
    return replace(model, housing=replace(model.housing, gap=1.0))


def test_free_vibration_with_internal_friction_matches_the_fixed_frame():
    model = _no_housing(krasnov_crusher())
    u0, t0, du0, dt0 = (1e-3, -5e-4), (2e-3, 1e-3), (0.05, -0.02), (0.1, 0.03)
    y0 = model.initial_state(u0, t0, du0, dt0)
    ts = np.linspace(0.0, 0.5, 51)
    sol = solve(model, y0, (0.0, 0.5), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-15))
    # fixed-frame initial state: X = u, X' = u' + i w0 u
    z = [u0[0], u0[1], t0[0], t0[1], du0[0] - W0 * u0[1], du0[1] + W0 * u0[0],
         dt0[0] - W0 * t0[1], dt0[1] + W0 * t0[0]]  # fmt: skip
    ref = _to_rotating(_fixed_frame(model, ts, z, stones=False), ts)
    got = sol.ys[:, 0:4]
    scale = np.max(np.abs(ref), axis=0)
    assert np.max(np.abs(got - ref) / scale) < 1e-7
    # the internal friction damps: amplitude after 0.5 s well below the start
    assert np.hypot(*got[-1, :2]) < 0.5 * np.hypot(*u0)


def test_stone_pushes_match_the_fixed_frame():
    model = _no_housing(krasnov_crusher()).with_stones(0.3, seed=2)
    ts = np.linspace(0.0, 0.3, 61)
    sol = solve(model, model.initial_state(), (0.0, 0.3), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=1e-10, atol=1e-14))  # fmt: skip
    ref = _to_rotating(_fixed_frame(model, ts, np.zeros(8), stones=True), ts)
    got = sol.ys[:, 0:4]
    scale = np.max(np.abs(ref), axis=0)
    assert np.max(np.abs(got - ref) / scale) < 1e-4
    assert sol.event_counts["stone"] == 8 + 7  # 8 stones arrive, 7 leave before 0.3 s


def _fixed_frame_roots(model):
    """Roots s of the fixed-frame characteristic equation (X, Theta ~ exp(s t))."""
    r = model.rotor
    m, a1, a3 = r.mass, r.inertia_transverse, r.inertia_polar
    c, nm, cs, gw = r.stiffness, r.membrane_offset, r.tilt_stiffness, r.internal_friction / W0
    P = np.polynomial.Polynomial
    damp = P([1.0, gw])  # 1 + (gamma / w0) s
    d11 = P([0.0, 0.0, m]) + c * damp
    d12 = c * nm * damp
    d22 = P([0.0, -1j * a3 * W0, a1]) + (c * nm**2 + cs) * damp
    return (d11 * d22 - d12 * d12).roots()


def test_eigenvalues_of_the_rotating_frame_are_the_fixed_frame_ones_shifted_by_the_spin():
    # u = exp(-i w0 t) X: every fixed-frame root s appears as s - i w0 (and its conjugate)
    model = krasnov_crusher()
    ev = np.linalg.eigvals(model.state_matrix())
    expect = _fixed_frame_roots(model) - 1j * W0
    expect = np.concatenate([expect, expect.conj()])
    for z in expect:
        assert np.min(np.abs(ev - z)) < 1e-8 * abs(z)
    # the slow backward tilt whirl of a disc-like rotor (A3 > A1): fixed-frame -5.3 rad/s
    slow = expect[np.argmin(np.abs(expect.real))]
    assert abs(slow.imag) - W0 == pytest.approx(5.32, abs=0.01)
