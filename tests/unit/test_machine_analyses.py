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
    np.testing.assert_allclose(weak.attrs["critical_speeds"], [P, math.sqrt(5.0 / 0.3)], rtol=1e-9)
    assert weak.attrs["passed"] == 0 and weak.attrs["captured_at"] == weak.attrs["critical_speeds"][0]
    assert strong.attrs["passed"] == 1 and math.isnan(strong.attrs["captured_at"])
