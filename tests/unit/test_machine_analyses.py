"""Analyses of the composed machine: steady balanced states over speed, simulation, run-up.

The planar machine is the Jeffcott rotor with two balls, whose balanced state has the balls at
psi = +-arccos(-M1 e / (2 m l)) and is unstable below the critical speed p = sqrt(c / (M1 + 2 m))
(Zhakash et al. 2024, eq. (22) as corrected in rotorlab.models._jeffcott_balls; the averaged
criterion there says stable for omega > p, the exact eigenvalues with damping start somewhat
higher, so those are compared with the jeffcott_balls linearization at each speed).
"""

import math

import numpy as np

from rotorlab.analyses._machine import (
    NO_STEADY_STATUS,
    machine_simulate,
    machine_steady,
    unbalance_amplitudes,
)
from rotorlab.analyses._machine_run_up import machine_run_up
from rotorlab.linear import LinearSystem
from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Motor, Unbalance

S = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
                 G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
RACE = (BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * 2),)
UNB = (Unbalance(0, 0.01),)
P = 1.0 / math.sqrt(1.04)
PSI = math.acos(-0.01 / 0.04)


def test_balanced_state_stability_over_speed_is_that_of_jeffcott_balls():
    from rotorlab.models import BallParams, JeffcottBalls, RotorParams

    m = Machine(S, races=RACE, unbalances=UNB, drive=ConstantSpeed(2.0), n_modes=2)
    speeds = np.array([0.5, 0.9, 0.97, 0.99, 1.2, 1.6, 2.5])
    ds = machine_steady(m, speeds)
    assert np.all(ds.status == 0) and np.all(ds.exists)
    ref = []
    for w in speeds:
        jb = JeffcottBalls(RotorParams(1.0, 0.01, 1.0, 0.02), (BallParams(0.02, 1.0, None, 0.01),) * 2,
                           speed=ConstantSpeed(w), frame="rotating")
        ref.append(jb.linearize([0, 0, 0, 0, PSI, -PSI, 0, 0]).eigenvalues.real.max())
    np.testing.assert_allclose(ds.max_real_eigenvalue.values, ref, atol=1e-7)
    assert not np.any(ds.stable.values[speeds < P]) and ds.stable.values[-1]
    np.testing.assert_allclose(np.sort(np.abs(ds.ball_angle.values), axis=1), PSI, atol=1e-9)


def test_no_steady_state_on_anisotropic_supports_says_why():
    K = S.K.copy()
    K[1, 1] = 1.3
    m = Machine(LinearSystem(M=S.M, C=S.C, G=S.G, K=K), races=RACE, unbalances=UNB,
                drive=ConstantSpeed(2.0))
    ds = machine_steady(m, [2.0])
    assert int(ds.status[0]) == NO_STEADY_STATUS and not bool(ds.exists[0])
    assert "anisotropic" in ds.attrs["message"] and "simulate" in ds.attrs["message"]


def test_simulation_ends_balanced_with_the_closed_form_ball_angles():
    m = Machine(S, races=RACE, unbalances=UNB, drive=ConstantSpeed(2.5), n_modes=2)
    ds = machine_simulate(m, [[0.3, 2.0], [-2.5, 1.0]], t_end=2000.0)
    assert np.all(ds.status == 0)
    np.testing.assert_allclose(np.sort(ds.final_ball_angle.values, axis=1), [[-PSI, PSI]] * 2, atol=1e-4)
    # the locked unbalance response: U w^2 / |c - M w^2 + i d w| (no balls acting)
    ref = 0.01 * 2.5**2 / abs(1.0 - 1.04 * 2.5**2 + 0.02j * 2.5)
    np.testing.assert_allclose(float(ds.reference_amplitude[0]), ref, rtol=1e-12)
    assert float(ds.amplitude.max()) < 1e-4 * ref


def test_unbalance_amplitude_of_an_anisotropic_support_is_the_orbit_radius():
    K = S.K.copy()
    K[1, 1] = 3.0
    m = Machine(LinearSystem(M=S.M, C=S.C * 0, G=S.G, K=K), unbalances=UNB, drive=ConstantSpeed(2.0))
    # x = U w^2/(kx - M w^2) cos, y = U w^2/(ky - M w^2) sin: the largest radius is the larger
    ax, ay = 0.04 / abs(1.0 - 4.0), 0.04 / abs(3.0 - 4.0)
    np.testing.assert_allclose(unbalance_amplitudes(m, 2.0)[0], max(ax, ay), rtol=1e-12)


def test_run_up_reports_the_critical_speed_it_is_captured_at():
    def machine(torque):
        return Machine(LinearSystem(
            M=S.M, C=np.diag([0.05, 0.05, 0.0, 0.0]), G=S.G, K=S.K),
            races=(BallRace(0, 0.5, (Ball(0.02, damping=0.005),) * 2),),
            unbalances=(Unbalance(0, 0.05),),
            drive=Motor(torque, polar_inertia=0.05, no_load_speed=3.0), n_modes=2)

    weak = machine_run_up(machine(0.0100), t_end=400.0, n_save=200)
    strong = machine_run_up(machine(0.0115), t_end=400.0, n_save=200)
    # the tilt mode with the balls locked at l = 0.5: J_t + 2 m l^2 / 2 - J_p, J_p = 2 m l^2 (no own
    # inertia), forward whirl
    np.testing.assert_allclose(weak.attrs["critical_speeds"], [P, math.sqrt(5.0 / (0.3 + 0.02 * 0.25 - 0.01))],
                               rtol=1e-9)
    assert weak.attrs["passed"] == 0 and weak.attrs["captured_at"] == weak.attrs["critical_speeds"][0]
    assert strong.attrs["passed"] == 1 and math.isnan(strong.attrs["captured_at"])


def test_locked_critical_speeds_count_the_balls_inertia_about_the_tilt_axes():
    """A rigid rotor (M = 1, J_t = 3.25, J_p = 0.5; the long rotor of Rodrigues et al. 2008) on
    two supports of 0.5 at +-3 (K = diag(1, 1, 9, 9)) with one race of two balls (m = 0.05,
    own inertia J_c = 0.001) at radius l = 1 and axial offset a = 2. Locked, the balls are point
    masses on the race: translation 2 m, coupling 2 m a, transverse inertia 2 m (a^2 + l^2 / 2),
    polar 2 (m l^2 + J_c). A synchronous forward whirl (x, phi_x) = (X, Phi) e^(i w t) of each
    plane then obeys ``det(K2 - w^2 [[M + 2m, 2ma], [2ma, J_t + 2m (a^2 + l^2/2) - J_p - 2 (m l^2 + J_c)]]) = 0``
    (the polar inertia's gyroscopic moment at w = Omega stiffens the forward tilt): a quadratic in
    w^2, here against ``structure_critical_speeds``."""
    from rotorlab.analyses._machine import structure_critical_speeds

    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = 0.5, -0.5
    s = LinearSystem(M=np.diag([1.0, 1.0, 3.25, 3.25]), C=np.zeros((4, 4)), G=G, K=np.diag([1.0, 1.0, 9.0, 9.0]))
    m, l, a, jc = 0.05, 1.0, 2.0, 0.001
    mac = Machine(s, races=(BallRace(0, l, (Ball(m, inertia=jc),) * 2, axial_offset=a),), unbalances=UNB,
                  drive=ConstantSpeed(1.0))
    A, B = 1.0 + 2 * m, 2 * m * a
    D = 3.25 + 2 * m * (a * a + l * l / 2) - 0.5 - 2 * (m * l * l + jc)
    mu = np.roots([A * D - B * B, -(9.0 * A + D), 9.0])
    np.testing.assert_allclose(np.sort(structure_critical_speeds(mac)), np.sort(np.sqrt(mu)), rtol=1e-12)
    # on the axis (the balls' l^2 terms left out, as Rodrigues et al. 2011 eq. (32) locks them)
    # the mostly tilting (higher) critical speed would be 0.8 % off
    D0 = 3.25 + 2 * m * a * a - 0.5
    mu0 = np.roots([A * D0 - B * B, -(9.0 * A + D0), 9.0])
    assert abs(np.sqrt(mu0.max()) / np.sqrt(mu.max()) - 1) > 5e-3
