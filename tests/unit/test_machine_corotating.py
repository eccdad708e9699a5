"""The machine's compiled co-rotating kernel (issue 24, item 3; :mod:`rotorlab._kernels.machine_corotating`).

The kernel must be the time derivative of the fixed-frame motion seen from the frame that turns
with the spin: ``y_r(t) = to_frame(t, y_f(t))`` with ``y_f`` integrated on the fixed-frame kernel
(SciPy's DOP853, independent of our integrator) and differentiated by a fourth-order central
difference. Checked on the generic case the kernel claims: an anisotropic, unreduced, gyroscopic
rotor with tilting races, lateral gravity, energy states and a motor (the spin acceleration is the
computed ``theta''``). ``jeffcott_balls``' own co-rotating kernel, under prescribed speeds and
with friction, is the oracle of ``tests/unit/test_jeffcott_machine.py``.
"""

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from test_machine import planar_pair, rigid_two_plane

from rotorlab.integrate import StepControl, solve
from rotorlab.models import Clearance, ConstantSpeed, Gravity, Motor, TunedMassAbsorber


def fixed_motion(mac, t0, y0, offsets):
    """Fixed-frame states at ``t0 + offsets`` from ``y0`` at ``t0`` (DOP853, rtol 1e-13)."""
    p = mac.to_array()
    out = {}
    for sign in (1.0, -1.0):
        hs = sorted((h for h in offsets if h * sign > 0), key=abs)
        sol = solve_ivp(lambda t, y: mac.rhs(t, y, p), (t0, t0 + sign * abs(hs[-1])), y0, method="DOP853",
                        t_eval=[t0 + h for h in hs], rtol=1e-13, atol=1e-15)
        assert sol.status == 0
        out.update({h: sol.y[:, i] for i, h in enumerate(hs)})
    return out


def test_corotating_kernel_is_the_derivative_of_the_fixed_motion_in_the_turning_frame():
    mac = rigid_two_plane(motor=Motor(0.3, polar_inertia=0.6, no_load_speed=2.0), gravity=Gravity((0.0, -0.5, 0.0)))
    assert mac.why_no_rotating_kernel() is None and mac.layout.tilt and mac.is_motor
    assert not mac.structure.is_isotropic and mac.layout.gyroscopic and mac.energy_states
    k, p = mac.rotating_kernels, mac.to_array()
    assert k.rhs is not mac.kernels.rhs and k.n_state == mac.n_state
    rng = np.random.default_rng(7)
    h = 2e-3
    for _ in range(3):
        t0 = rng.uniform(0.0, 5.0)
        yf0 = mac.initial_state(rng.uniform(0, 6, 4), spin_speed=1.1) + 0.1 * rng.normal(size=mac.n_state)
        yf0[mac.layout.i_theta] = rng.uniform(0.0, 6.0)
        ys = fixed_motion(mac, t0, yf0, (-2 * h, -h, h, 2 * h))
        yr = {dt: mac.to_frame(t0 + dt, y, "rotating") for dt, y in ys.items()}
        numeric = (8.0 * (yr[h] - yr[-h]) - (yr[2 * h] - yr[-2 * h])) / (12.0 * h)
        yr0 = mac.to_frame(t0, yf0, "rotating")
        f = np.empty_like(yr0)
        k.rhs(t0, yr0, p, f)
        scale = np.abs(f).max()
        np.testing.assert_allclose(f, numeric, rtol=0, atol=1e-8 * scale)
        # the frame turns: the co-rotating rates differ from the fixed ones by far more than that
        assert np.abs(f - mac.rhs(t0, yf0, p)).max() > 1e-2 * scale
        np.testing.assert_allclose(mac.to_frame(t0, yr0, "fixed"), yf0, rtol=0, atol=1e-14 * np.abs(yf0).max())


def test_machines_without_a_corotating_kernel_say_why():
    base = rigid_two_plane()
    cases = [(replace(base, n_modes=2), "anisotropic and reduced to modes"),
             (replace(base, parts=(TunedMassAbsorber(0, 0.15, 0.4, 0.05),)), "absorbers"),
             (replace(base, clearances=(Clearance(0, 1e-3, rotor_radius=0.05),)), "clearance")]
    for mac, words in cases:
        assert words in mac.why_no_rotating_kernel()
        with pytest.raises(ValueError, match=f"no co-rotating kernel: .*{words}"):
            mac.rotating_kernels
    with pytest.raises(ValueError, match="frame must be 'fixed' or 'rotating', got 'spinning'"):
        base.to_frame(0.0, np.zeros(base.n_state), "spinning")


def test_an_isotropic_machine_simulated_in_its_rotating_frame_follows_its_fixed_frame_run():
    """``solve`` on :meth:`Machine.in_rotating_frame` and on the machine itself, from the same
    start: the same trajectory, turned (the machine of test_machine's planar trajectory test)."""
    mac, _ = planar_pair(ConstantSpeed(2.5), n_modes=2)
    rot = mac.in_rotating_frame()
    assert rot.kernels is mac.rotating_kernels and rot.state_names[:4] == ("u_1", "u_2", "du_1", "du_2")
    yf0 = mac.initial_state([0.3, 2.0])
    yr0 = rot.initial_state([0.3, 2.0])
    np.testing.assert_allclose(rot.to_fixed(0.0, yr0), yf0, rtol=0, atol=1e-15)
    ctl = StepControl(rtol=1e-10, atol=1e-12)
    for t1 in (7.3, 60.0):
        sf = solve(mac, yf0, (0.0, t1), control=ctl)
        sr = solve(rot, yr0, (0.0, t1), control=ctl)
        assert sf.status.name == sr.status.name == "SUCCESS"
        np.testing.assert_allclose(rot.to_fixed(t1, sr.y_final), sf.y_final, rtol=0, atol=1e-7)
        i = mac.layout.i_phi  # the frames differ: psi = phi - Omega t
        assert sr.y_final[i] == pytest.approx(sf.y_final[i] - 2.5 * t1, abs=1e-6) and 2.5 * t1 > 18.0
