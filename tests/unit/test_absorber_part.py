"""The tuned mass absorber as a machine part: its case key, named parameters, kernel layout,
co-rotating refusal and figure (the physics: tests/validation/test_absorber.py), and its place
among the other attachments (the two-plane rotor of test_machine with a motor, tilting races,
gravity and an absorber, its kernel run as Python: no driver compiled here)."""

import numpy as np
import pytest

from test_machine import rigid_two_plane
from test_machine_common import PLANAR

from rotorlab.io import CaseError, parse_case
from rotorlab.io._build import build_machine
from rotorlab.models import Gravity, Motor, TunedMassAbsorber, absorber_response

# the planar machine of test_machine_common (1 kg disc on 1 N/m, 0.1 N s/m; its two translation
# modes) without its races, with an absorber
CASE = PLANAR.split("[[model.races]]")[0].replace("{", "{{").replace("}", "}}") + """
[[model.unbalances]]
magnitude = "10 g*m"             # U w^2 = 22.5 mN at 1.5 rad/s
at = "disc"

[[model.absorbers]]              # a 100 g mass on a spring and a damper at the disc
at = "disc"
mass = "100 g"
stiffness = "{stiffness}"
damping = "20 g/s"

[model.drive]
profile = "constant"
speed = "1.5 rad/s"

[[analysis]]
type = "simulate"
name = "run"
t_end = "10 s"
initial_ball_angles = [[]]
"""


def test_the_case_key_builds_the_part_with_si_values_and_named_parameters():
    """``[[model.absorbers]]`` through the unit parser: 100 g, 225 N/mm -> 225000 N/m, 20 g/s;
    its parameters ``absorbers[0].<field>`` with units, bounds checked by ``with_parameters``."""
    m = build_machine(parse_case(CASE.format(stiffness="225 N/mm")).model)
    (a,) = m.parts
    assert (a.node, a.mass, a.stiffness, a.damping) == (0, pytest.approx(0.1), pytest.approx(225000.0),
                                                        pytest.approx(0.02))
    ps = m.parameters
    assert ps["absorbers[0].mass"].unit == "kg" and ps["absorbers[0].stiffness"].unit == "N/m"
    assert ps["absorbers[0].stiffness"].value == pytest.approx(225000.0)
    m2 = m.with_parameters(**{"absorbers[0].stiffness": 0.225})
    p2 = m.pack({"absorbers[0].stiffness": 0.225})
    np.testing.assert_array_equal(m2.to_array(), p2)
    assert m2.layout == m.layout and p2[m.layout.places("ta")[0].param + 1] == 0.225
    with pytest.raises(ValueError, match=r"absorbers\[0\]\.mass = -1: must be > 0 kg"):
        m.with_parameters(**{"absorbers[0].mass": -1.0})


def test_a_bad_absorber_names_its_key_path_and_value():
    with pytest.raises(CaseError) as exc:
        parse_case(CASE.format(stiffness="-3 N/m"))
    assert "model.absorbers[0].stiffness" in str(exc.value) and "-3" in str(exc.value)
    with pytest.raises(CaseError, match=r"model\.absorbers\[0\]\.stiffness"):
        parse_case(CASE.format(stiffness="3 kg"))


def test_the_absorber_s_states_names_and_parameter_block_extend_the_layout():
    m = build_machine(parse_case(CASE.format(stiffness="0.225 N/m")).model)
    lay = m.layout
    assert m.state_names[lay.i_parts:lay.i_parts + 4] == ("x_absorber_1", "y_absorber_1", "vx_absorber_1",
                                                         "vy_absorber_1")
    assert lay.n_state == 4 + 4 and lay.key.endswith("pta")
    place, = lay.places("ta")
    p = m.to_array()
    np.testing.assert_array_equal(p[place.param:place.param + 3], [0.1, 0.225, 0.02])
    np.testing.assert_array_equal(p[lay.station_B(place.station):lay.station_B(place.station) + 4],
                                  m.station_matrix(0).ravel())
    y = m.initial_state(z=[1e-3, -2e-3], dz=[0.1, 0.2])
    np.testing.assert_array_equal(y[place.state:place.state + 4], [1e-3, -2e-3, 0.1, 0.2])


def test_the_co_rotating_frame_refuses_an_absorber_and_says_why():
    m = build_machine(parse_case(CASE.format(stiffness="0.225 N/m")).model)
    assert not m.has_rotating_frame
    assert "tuned mass absorber" in m.why_no_rotating_frame()
    with pytest.raises(ValueError, match="no co-rotating equilibria: the machine has a tuned mass absorber"):
        m.steady_state()


def test_bad_absorber_values_are_refused():
    with pytest.raises(ValueError, match=r"TunedMassAbsorber\.damping must be >= 0"):
        TunedMassAbsorber(0, 1.0, 1.0, -0.1)
    with pytest.raises(ValueError, match=r"TunedMassAbsorber\.mass must be > 0"):
        TunedMassAbsorber(0, 0.0, 1.0)


def test_the_figure_draws_the_response_with_and_without_the_absorber():
    from rotorlab.plot import absorber_response_figure

    m = build_machine(parse_case(CASE.format(stiffness="0.225 N/m")).model)
    ds = absorber_response(m, 0, np.linspace(0.5, 2.5, 41))
    fig = absorber_response_figure(ds)
    without, with_ = fig.axes[0].get_lines()
    np.testing.assert_allclose(without.get_ydata(), ds.amplitude_without.values * 1e3)
    np.testing.assert_allclose(with_.get_ydata(), ds.amplitude.values * 1e3)
    np.testing.assert_allclose(with_.get_xdata(), ds.speed.values * 30 / np.pi)
    # tuned to w = 1.5 rad/s (k_a = m_a w^2), damped: the absorber's dynamic stiffness there is
    # -m_a w^2 + i m_a w k_a / c_a, so the amplitude is U w^2 / |K - M w^2 + i w C - m_a w^2 + i m_a w k_a / c_a|
    k, w = 20, 1.5
    expect = 0.01 * w * w / abs(1.0 - w * w + 0.1j * w - 0.1 * w * w + 1j * 0.1 * w * 0.225 / 0.02)
    assert ds.speed.values[k] == pytest.approx(w, rel=1e-12)
    assert ds.amplitude.values[k] == pytest.approx(expect, rel=1e-12) and expect < 0.6 * ds.amplitude_without.values[k]


def test_power_identity_with_balls_on_tilting_races_a_motor_gravity_and_an_absorber():
    """The absorber's station forces enter the Schur system of the balls and the spin (``h``):
    at disturbed states of the gyroscopic, anisotropic two-plane rotor with two tilting 2-ball
    races, a motor, lateral gravity and an absorber off the node (axial offset 1.5), the rate of
    the energy along the kernel's dy/dt (central difference) is the drive power minus the
    dissipated power the kernel writes, to 1e-8 of the largest term; leaving out the absorber's
    own energy breaks it by far more. The kernel is run as Python (``rhs.py_func``): no driver
    is compiled for this layout."""
    from dataclasses import replace

    from rotorlab._kernels.machine_codegen import kernel_module

    base = rigid_two_plane(motor=Motor(0.4, polar_inertia=0.6, no_load_speed=2.0), gravity=Gravity((0.2, -0.3, -9.8)))
    mac = replace(base, parts=(TunedMassAbsorber(0, 0.15, 0.4, 0.05, axial_offset=1.5),), energy_states=True)
    lay = mac.layout
    assert lay.tilt and lay.motor
    rhs, p = kernel_module(lay).rhs.py_func, mac.to_array()
    part, place = mac.parts[0], lay.places("ta")[0]
    rng = np.random.default_rng(3)
    for _ in range(3):
        y = mac.initial_state(rng.uniform(0, 2 * np.pi, 4), ball_rates=rng.normal(0, 0.3, 4), spin_speed=1.1,
                              z=rng.normal(0, 0.02, 4), dz=rng.normal(0, 0.05, 4))
        y[place.state:place.state + 4] += rng.normal(0, 0.05, 4)  # the absorber off its station, moving
        f = np.empty_like(y)
        rhs(0.0, y, p, f)
        h = 1e-6
        rate = (mac.energy(y + h * f) - mac.energy(y - h * f)) / (2 * h)
        power, diss = f[lay.i_energy], f[lay.i_energy + 1]
        scale = max(abs(power), abs(diss), abs(rate))
        assert abs(rate - (power - diss)) < 1e-8 * scale
        own = (part.energy(mac, y + h * f, place) - part.energy(mac, y - h * f, place)) / (2 * h)
        assert abs(own) > 1e-3 * scale


def test_every_drive_and_profile_kind_of_a_layout_has_its_kernel_lines():
    """The drive registry of the generator (``machine_drive``) covers the layout's kinds."""
    from rotorlab._kernels.machine_drive import DRIVES, PROFILE_SPIN
    from rotorlab._kernels.machine_layout import DRIVE_KINDS, SPEED_KINDS

    assert set(DRIVES) == set(DRIVE_KINDS) and set(PROFILE_SPIN) == set(SPEED_KINDS)
    assert DRIVES["profile"].torque is None and all(DRIVES[k].torque for k in DRIVE_KINDS if k != "profile")


def test_the_reference_without_balancing_includes_the_absorber():
    """A simulation's ``reference_amplitude`` (the unbalance response without balancing) is that
    of the machine with its absorber: at the tuned speed, damped, the closed form of
    test_the_figure_draws_the_response_with_and_without_the_absorber (9.55 mm, not the bare
    17.87 mm), and the response of absorber_response at every speed."""
    from rotorlab.analyses._machine_common import unbalance_amplitudes

    m = build_machine(parse_case(CASE.format(stiffness="0.225 N/m")).model)
    w = 1.5
    expect = 0.01 * w * w / abs(1.0 - w * w + 0.1j * w - 0.1 * w * w + 1j * 0.1 * w * 0.225 / 0.02)
    assert unbalance_amplitudes(m, w)[0] == pytest.approx(expect, rel=1e-12)
    for om in (0.7, 1.2, 2.0):
        assert unbalance_amplitudes(m, om)[0] == pytest.approx(float(absorber_response(m, 0, [om]).amplitude[0]),
                                                               rel=1e-10)
