"""BalancerRegimes: regimes of the two-ball autobalancer (seed 002 numbers of the built-in case)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from rotorlab.explore import BalancerRegimes, GridAxis, balancer_labels, basin_fractions, basin_map, map_starts
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, LinearRamp, RotorParams

ROTOR = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
BALL = BallParams(mass=0.03, radius=0.05, damping=2e-3)
MODEL = JeffcottBalls(ROTOR, (BALL, BALL), speed=ConstantSpeed(251.3))  # about 2 p
P = MODEL.critical_speed


def test_labels():
    assert balancer_labels(1) == ("balanced", "side (0°)", "side (180°)", "non-synchronous", "not settled", "other")
    assert len(balancer_labels(3)) == 4 + 4


def test_supercritical_starts_balance_and_subcritical_go_to_the_unbalance():
    mapper = BalancerRegimes(MODEL, t_end=12.0, n_horizons=3)
    ds = map_starts(mapper, {"psi_1": [0.5, 0.5], "psi_2": [2.5, 2.5], "spin_speed": [2.0 * P, 0.6 * P]})
    names = ds.label.attrs["labels"]
    assert [names[k] for k in ds.outcome.values] == ["balanced", "side (0°, 0°)"]
    assert ds.label.values[0, 0] == 0  # balanced already after 4 s
    np.testing.assert_allclose(np.degrees(np.abs([ds.ball_angle_1[0, -1], ds.ball_angle_2[0, -1]])), 120.0, atol=0.1)
    assert float(ds.amplitude[0, -1]) < 1e-3 * float(ds.reference_amplitude[0])
    assert ds.spin_speed.attrs["units"] == ds.rotor_speed.attrs["units"] == "rad/s" and ds.amplitude.attrs["units"] == "m"


def test_balls_are_interchangeable():
    mapper = BalancerRegimes(MODEL, t_end=4.0, n_horizons=2)
    a = map_starts(mapper, {"psi_1": [0.3, 1.0], "psi_2": [2.0, 4.0]})
    b = map_starts(mapper, {"psi_1": [2.0, 4.0], "psi_2": [0.3, 1.0]})
    np.testing.assert_array_equal(a.label.values, b.label.values)


def test_weak_ball_damping_leaves_non_synchronous_balls():
    # seed 004's "spare" regime on a Jeffcott rotor: with b = 2e-4 N m s both balls together
    # lag the rotor (the case's docstring: about half of the supercritical starts)
    weak = BalancerRegimes(MODEL, t_end=10.0, n_horizons=2)
    ds = basin_map(weak, GridAxis("psi_1", 0.0, 2.0, 2), GridAxis("psi_2", 0.2, 0.2, 1), fixed={"ball_damping": 2e-4})
    names = ds.outcome.attrs["labels"]
    assert "non-synchronous" in {names[k] for k in ds.outcome.values.ravel()}
    fr = basin_fractions(ds)
    np.testing.assert_allclose(fr.fraction.sum("regime").values, 1.0)


def test_chunks_do_not_change_results():
    mapper = BalancerRegimes(MODEL, t_end=3.0, n_horizons=2)
    starts = {"psi_1": np.linspace(0, 6, 5), "psi_2": np.linspace(1, 3, 5)}
    xr.testing.assert_identical(map_starts(mapper, starts, chunk_size=2, threads=2),
                                map_starts(mapper, starts, threads=1))  # fmt: skip


def test_parameter_coordinates_and_checks():
    mapper = BalancerRegimes(MODEL, t_end=1.0, n_horizons=1)
    _, Y0, Pk = mapper.starts({"ball_mass": np.array([0.03, 0.06]), "damping": np.array([13.32, 20.0])})
    assert Pk[1, 12] == 0.06 and Pk[1, 14] == pytest.approx(0.06 * 0.05**2) and Pk[1, 5] == 20.0
    assert Y0.shape == (2, MODEL.n_state)
    for frame in ("fixed", "rotating"):  # the starts of all points at once: initial_state's numbers
        m, Y0, _ = BalancerRegimes(MODEL, frame=frame).starts({"psi_1": np.array([0.3, 2.0]), "dpsi_2": np.array([0.0, 5.0])})
        one = [m.initial_state([a, math.pi], ball_rates=[0.0, r]) for a, r in ((0.3, 0.0), (2.0, 5.0))]
        np.testing.assert_array_equal(Y0, one)
        assert m.frame == frame
    with pytest.raises(ValueError, match="ball_friction"):
        mapper.starts({"ball_friction": np.array([0.0, 0.01])})
    with pytest.raises(ValueError, match="ConstantSpeed"):
        BalancerRegimes(MODEL.with_speed(LinearRamp(0.0, 200.0, 2.0)))
    with pytest.raises(ValueError, match="base_angles"):
        BalancerRegimes(MODEL, base_angles=(0.0,))
    with pytest.raises(ValueError, match="samples_per_window"):
        BalancerRegimes(MODEL, samples_per_window=1)
    assert mapper.base_angles == pytest.approx((0.0, math.pi))


def test_frame_is_chosen_from_the_base_model():
    # fixed where the base model spins at >= 1.8 p and the balls can balance it (eta = M1 e / (2 m l) = 0.5)
    assert BalancerRegimes(MODEL).frame == "fixed"  # 2.0 p
    assert BalancerRegimes(MODEL.with_speed(ConstantSpeed(1.7 * P))).frame == "rotating"
    heavy = JeffcottBalls(RotorParams(1.0, 4e-3, 16740.0, 13.32), (BALL, BALL), speed=ConstantSpeed(3 * P))
    assert heavy.capacity < heavy.imbalance and BalancerRegimes(heavy).frame == "rotating"
    assert BalancerRegimes(MODEL, frame="rotating").frame == "rotating"
    with pytest.raises(ValueError, match="frame must be 'fixed', 'rotating' or None, got 'inertial'"):
        BalancerRegimes(MODEL, frame="inertial")


@pytest.mark.parametrize("friction, n", [(0.0, 3), (0.02, 1)])
def test_fixed_and_rotating_frames_agree(friction, n):
    # the same starts integrated in either frame: same labels, features equal to the tolerance
    # (rtol 1e-8 on states of O(1e-3) m and O(1) rad). With friction the first start sticks and
    # slips (3 stick, 1 slip event, both kernels have them); one start on one thread, so that
    # the test runs on the serial scalar driver that test_jeffcott_friction compiles (the
    # friction lane drivers of both frames cost about 2 CPU-minutes cold). No start on the
    # invariant diagonal psi_1 = psi_2: unstable at 2 p, it is left by round-off, in one frame and
    # not the other (psi = (1, 1) stayed on it in the fixed frame, non-synchronous at 2 s, and
    # balanced in the co-rotating one; 1e-9 off it both frames balance).
    starts = {"psi_1": np.array([0.5, 1.0, 2.0])[:n], "psi_2": np.array([2.5, 1.3, 4.5])[:n],
              "spin_speed": np.array([2.0, 2.0, 0.6])[:n] * P, "ball_friction": np.full(n, friction)}  # fmt: skip
    a, b = (map_starts(BalancerRegimes(MODEL, t_end=2.0, n_horizons=2, frame=f), starts, threads=1)
            for f in ("fixed", "rotating"))
    np.testing.assert_array_equal(a.label.values, b.label.values)
    ref = float(a.reference_amplitude.max())
    np.testing.assert_allclose(a.amplitude.values, b.amplitude.values, rtol=0, atol=1e-6 * ref)
    for i in (1, 2):
        np.testing.assert_allclose(a[f"ball_angle_{i}"].values, b[f"ball_angle_{i}"].values, rtol=0, atol=1e-6)
    np.testing.assert_allclose(a.max_rate.values, b.max_rate.values, rtol=0, atol=1e-6 * float(P))
