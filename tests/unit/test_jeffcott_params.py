"""Parameter objects, packing, state layout and frame conversion of ``jeffcott_balls``."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from rotorlab.models import (
    BallParams,
    ConstantSpeed,
    HillRunUp,
    JeffcottBalls,
    LinearRamp,
    RotorParams,
    fixed_to_rotating,
    rotating_to_fixed,
)

ROTOR = RotorParams(disc_mass=3.0, eccentricity=2e-3, stiffness=1.2e4, damping=5.0)
BALLS = (
    BallParams(0.04, 0.09, damping=1e-3, friction=0.3),
    BallParams(0.06, 0.11, inertia=0.06 * 0.11**2 + 1e-5, damping=2e-3),
)


@pytest.mark.parametrize(
    "kwargs, field, fragment",
    [
        (dict(disc_mass=0.0, eccentricity=0.0, stiffness=1.0), "disc_mass", "> 0 (kg)"),
        (dict(disc_mass=-2.0, eccentricity=0.0, stiffness=1.0), "disc_mass", "got -2.0"),
        (dict(disc_mass=math.nan, eccentricity=0.0, stiffness=1.0), "disc_mass", "got nan"),
        (dict(disc_mass=1.0, eccentricity=-1e-3, stiffness=1.0), "eccentricity", ">= 0 (m)"),
        (dict(disc_mass=1.0, eccentricity=0.0, stiffness=-1.0), "stiffness", "(N/m)"),
        (dict(disc_mass=1.0, eccentricity=0.0, stiffness=math.inf), "stiffness", "got inf"),
        (dict(disc_mass=1.0, eccentricity=0.0, stiffness=1.0, damping=-0.1), "damping", "N s/m"),
        (dict(disc_mass="heavy", eccentricity=0.0, stiffness=1.0), "disc_mass", "'heavy'"),
    ],
)
def test_rotor_params_reject_bad_values(kwargs, field, fragment):
    with pytest.raises(ValueError, match=f"RotorParams.{field} must be") as info:
        RotorParams(**kwargs)
    assert fragment in str(info.value)


@pytest.mark.parametrize(
    "kwargs, field, fragment",
    [
        (dict(mass=0.0, radius=0.1), "mass", "> 0 (kg)"),
        (dict(mass=-0.1, radius=0.1), "mass", "got -0.1"),
        (dict(mass=0.1, radius=0.0), "radius", "> 0 (m)"),
        (dict(mass=0.1, radius=math.nan), "radius", "nan"),
        (dict(mass=0.1, radius=0.1, inertia=0.5e-3), "inertia", ">= mass * radius**2 = 0.001"),
        (dict(mass=0.1, radius=0.1, inertia=-1.0), "inertia", "> 0"),
        (dict(mass=0.1, radius=0.1, damping=-1.0), "damping", "N m s/rad"),
        (dict(mass=0.1, radius=0.1, friction=-0.2), "friction", ">= 0 (1)"),
        (dict(mass=0.1, radius=0.1, friction=math.inf), "friction", "inf"),
    ],
)
def test_ball_params_reject_bad_values(kwargs, field, fragment):
    with pytest.raises(ValueError, match=f"BallParams.{field} must be") as info:
        BallParams(**kwargs)
    assert fragment in str(info.value)


def test_ball_inertia_defaults_to_point_mass_and_compares_equal():
    assert BallParams(0.2, 0.3).inertia == pytest.approx(0.2 * 0.09, rel=1e-15)
    assert BallParams(0.2, 0.3) == BallParams(0.2, 0.3, inertia=0.2 * 0.3 * 0.3)
    assert BallParams(0.2, 0.3).static_moment == pytest.approx(0.06, rel=1e-15)


@pytest.mark.parametrize(
    "factory, fragment",
    [
        (lambda: ConstantSpeed(math.nan), "ConstantSpeed.speed must be finite"),
        (lambda: LinearRamp(0.0, 10.0, 0.0), "LinearRamp.duration must be > 0 (s)"),
        (lambda: LinearRamp(math.inf, 10.0, 1.0), "LinearRamp.start must be finite"),
        (lambda: HillRunUp(100.0, -1.0, 2.0), "HillRunUp.t_half must be > 0 (s)"),
        (lambda: HillRunUp(100.0, 1.0, 0.0), "HillRunUp.exponent must be > 0"),
        (lambda: HillRunUp(100.0, 1.0, 5000.0), "HillRunUp.exponent must be in [0.01, 1000]"),
    ],
)
def test_speed_profiles_reject_bad_values(factory, fragment):
    with pytest.raises(ValueError) as info:
        factory()
    assert fragment in str(info.value)


def test_model_rejects_bad_configuration():
    with pytest.raises(ValueError, match="frame must be 'fixed' or 'rotating'"):
        JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(1.0), frame="inertial")
    with pytest.raises(ValueError, match=r"balls\[1\] must be a BallParams"):
        JeffcottBalls(ROTOR, (BALLS[0], 3.0), speed=ConstantSpeed(1.0))
    with pytest.raises(ValueError, match="speed must be ConstantSpeed"):
        JeffcottBalls(ROTOR, BALLS, speed=100.0)
    with pytest.raises(TypeError):
        JeffcottBalls(ROTOR, BALLS)  # the speed profile is required


@pytest.mark.parametrize(
    "speed", [ConstantSpeed(-12.5), LinearRamp(1.0, 80.0, 4.0), HillRunUp(300.0, 2.0, 1.7)]
)
@pytest.mark.parametrize("frame", ["fixed", "rotating"])
def test_packed_order_and_round_trip(speed, frame):
    model = JeffcottBalls(ROTOR, BALLS, speed=speed, frame=frame)
    p = model.to_array()
    # both frames run the preset machine's kernels: its packed parameters follow the model's
    tail = model.machine.to_array()[24:]
    assert p.dtype == np.float64 and p.shape == (12 + 6 * 2 + tail.size,)
    np.testing.assert_array_equal(p[24:], tail)
    assert tail.size == model.machine.layout.n_param - 24 > 0
    assert p[0] == 2.0 and p[1] == 1.0  # n, friction modes present
    np.testing.assert_array_equal(p[2:6], [3.0, 2e-3, 1.2e4, 5.0])
    np.testing.assert_array_equal(p[6:12], speed.to_array())
    for i, b in enumerate(BALLS):  # the sixth entry is derived: 1 / J
        block = p[12 + 6 * i : 18 + 6 * i]
        np.testing.assert_array_equal(block, [b.mass, b.radius, b.inertia, b.damping, b.friction, 1.0 / b.inertia])
    assert p[12 + 4] == 0.3 and p[18 + 2] == 0.06 * 0.11**2 + 1e-5
    again = JeffcottBalls.from_array(p, frame=frame)
    assert again == model
    np.testing.assert_array_equal(again.to_array(), p)


def test_speed_blocks():
    np.testing.assert_array_equal(ConstantSpeed(3.0).to_array(), [0, 3, 0, 0, 0, 0])
    np.testing.assert_array_equal(LinearRamp(1.0, 2.0, 3.0).to_array(), [1, 1, 2, 3, 0, 0])
    hill = HillRunUp(10.0, 2.0, 3.0).to_array()
    np.testing.assert_array_equal(hill[:4], [2, 10, 2, 3])
    f_a, g_a = HillRunUp(10.0, 2.0, 3.0).integrals(2.0 ** (-1.0 / 3.0))
    assert hill[4] == g_a and hill[5] == HillRunUp(10.0, 2.0, 3.0).integrals(2.0 ** (1.0 / 3.0))[1]


def test_sizes_names_and_kernels():
    plain = JeffcottBalls(ROTOR, (BALLS[1],) * 3, speed=ConstantSpeed(10.0))
    assert plain.n_state == 10 and not plain.has_friction
    assert plain.state_names[4:] == ("phi_1", "phi_2", "phi_3", "w_1", "w_2", "w_3")
    assert plain.kernels is plain.kernels and plain.kernels.n_events == 0
    rot = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(10.0), frame="rotating")
    assert rot.n_state == 10 and rot.has_friction
    assert rot.state_names == ("u", "v", "du", "dv", "psi_1", "psi_2", "dpsi_1", "dpsi_2",
                               "mode_1", "mode_2")  # fmt: skip
    k = rot.kernels
    assert k.n_state == 10 and k.n_discrete == 2
    assert [s.name for s in k.event_specs] == ["stick_1", "slip_1", "stick_2", "slip_2"]
    assert all(s.direction == -1 and s.action == "reset" for s in k.event_specs)
    assert JeffcottBalls(ROTOR, (), speed=ConstantSpeed(1.0)).n_state == 4


def test_derived_quantities():
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(10.0))
    assert model.total_mass == pytest.approx(3.1, rel=1e-15)
    assert model.critical_speed == pytest.approx(math.sqrt(1.2e4 / 3.1), rel=1e-15)
    assert model.imbalance == pytest.approx(6e-3, rel=1e-15)
    assert model.capacity == pytest.approx(0.04 * 0.09 + 0.06 * 0.11, rel=1e-15)


def test_frame_conversion_round_trip_and_geometry():
    rng = np.random.default_rng(11)
    y = rng.normal(size=(5, 7, 4 + 3 * 2))
    th = rng.uniform(-20, 20, size=(5, 7))
    om = rng.normal(size=(5, 7)) * 30
    back = fixed_to_rotating(th, om, rotating_to_fixed(th, om, y, 2), 2)
    np.testing.assert_allclose(back, y, rtol=0, atol=1e-12)
    yf = rotating_to_fixed(th, om, y, 2)
    # ball centre positions agree in both descriptions
    for i in range(2):
        pr = (y[..., 0] + 1j * y[..., 1] + 0.1 * np.exp(1j * y[..., 4 + i])) * np.exp(1j * th)
        pf = yf[..., 0] + 1j * yf[..., 1] + 0.1 * np.exp(1j * yf[..., 4 + i])
        np.testing.assert_allclose(pf, pr, atol=1e-12)
    np.testing.assert_array_equal(yf[..., 8:], y[..., 8:])  # modes untouched


def test_initial_state_rest_and_steady():
    model = JeffcottBalls(ROTOR, BALLS, speed=ConstantSpeed(90.0), frame="rotating")
    y0 = model.initial_state([0.3, -2.0])
    np.testing.assert_array_equal(y0[:4], 0.0)
    np.testing.assert_array_equal(y0[4:8], [0.3, -2.0, 0.0, 0.0])
    assert y0[8] == 0.0 and y0[9] == 1.0  # ball 1 held by friction, ball 2 frictionless
    ys = model.initial_state([0.3, -2.0], rotor="steady")
    z = model.locked_response([0.3, -2.0])
    assert ys[0] + 1j * ys[1] == z
    fixed = model.with_frame("fixed").initial_state([0.3, -2.0], rotor="steady", t0=0.7)
    th = 90.0 * 0.7
    np.testing.assert_allclose(fixed[0] + 1j * fixed[1], z * np.exp(1j * th), rtol=1e-14)
    np.testing.assert_allclose(fixed[2] + 1j * fixed[3], 1j * 90.0 * z * np.exp(1j * th), rtol=1e-14)
    np.testing.assert_allclose(fixed[4:6], np.array([0.3, -2.0]) + th, rtol=1e-15)
    np.testing.assert_allclose(fixed[6:8], 90.0, rtol=1e-15)
    with pytest.raises(ValueError, match="ball_angles must have 2 entries"):
        model.initial_state([0.1])
    with pytest.raises(ValueError, match="rotor must be 'rest' or 'steady'"):
        model.initial_state([0.1, 0.2], rotor="moving")


def test_import_compiles_nothing():
    code = (
        "import rotorlab, rotorlab.models\n"
        "from rotorlab._kernels import jeffcott_balls as k, speed as s\n"
        "fns = [k.rhs_fixed, k.rhs_rotating, k.events_fixed, k.reset_rotating, s.profile]\n"
        "assert all(len(f.signatures) == 0 for f in fns), [f.signatures for f in fns]\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
