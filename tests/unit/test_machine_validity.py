"""Impossible or degenerate machine runs (issue 28, items 8-11) at the model and analysis layers:
the rest position against the clearance, the validity limits of the linear structure and its
instability, no "balanced" below the first critical speed, one check of the saved states.

The washer of ``washer-horizontal``: 40 kg drum on k = 25 kN/m, c = 400 N s/m per direction, two
0.5 kg balls on a 0.27 m race, diametral inertia 1.5 kg m^2, gravity 9.81 m/s^2 across the axis.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab._memory import TooLarge
from rotorlab.analyses._machine import machine_simulate
from rotorlab.analyses._machine_common import (
    BELOW_CRITICAL,
    _outcome,
    machine_model,
    structure_instability,
    unbalance_amplitudes,
)
from rotorlab.analyses._machine_run_up import _run_up_outcome, machine_run_up
from rotorlab.io import load_case, parse_case
from rotorlab.models import Clearance, ConstantSpeed, Motor

G, K, C, M_DRUM, M_BALLS = 9.81, 25e3, 400.0, 40.0, 1.0


def washer(text_edit=None):
    text = load_case("washer-horizontal").text
    if text_edit is not None:
        text = text.replace(*text_edit)
    return machine_model(parse_case(text).model)


# ---- item 8 ------------------------------------------------------------------------------------


def test_the_rest_position_under_gravity_is_the_static_sag_m_g_over_k():
    """|w_s| = (m_drum + m_balls) g / k = 41 * 9.81 / 25e3 = 16.09 mm: beyond a 10 mm gap round
    the axis (named with the station), inside a 20 mm one, and 0 with the stator centred on it."""
    m = washer()
    sag = (M_DRUM + M_BALLS) * G / K
    radius, why = replace(m, clearances=(Clearance(0, 0.010),)).rest_clearance()
    assert radius == pytest.approx(sag, rel=1e-12)
    assert why is not None and "'drum'" in why and "16.09 mm" in why and "10 mm" in why
    assert replace(m, clearances=(Clearance(0, 0.020),)).rest_clearance() == (pytest.approx(sag, rel=1e-12), None)
    radius, why = replace(m, clearances=(Clearance(0, 0.010, center="static"),)).rest_clearance()
    assert radius < 1e-15 and why is None
    # without the balls the drum alone sags 40 g / k
    assert replace(m, races=(), clearances=(Clearance(0, 0.010),)).rest_clearance()[0] == pytest.approx(
        M_DRUM * G / K, rel=1e-12)


# ---- item 9 ------------------------------------------------------------------------------------


def test_a_machine_that_did_not_spin_up_is_never_balanced():
    """A motor without torque and no gravity: the machine stays at 0 rpm, nothing vibrates and
    the unbalance has no response to compare with (both 0): "balanced" before, now "below
    critical speed" (the first critical speed is 25.6 rad/s with the balls locked)."""
    m = replace(washer(), gravity=None).with_drive(Motor(0.0, polar_inertia=0.8, no_load_speed=150.0))
    one = machine_run_up(m, t_end=0.5, n_save=20)
    for key in ("final_speed", "passed", "captured_at", "status"):
        one[key] = ((), one.attrs.pop(key))
    assert float(one["final_speed"]) == 0.0 and int(one["status"]) == 0
    ref = unbalance_amplitudes(m, 0.0)
    assert np.max(ref) == 0.0 and np.max(one.residual_amplitude.values) == 0.0
    assert _run_up_outcome(m, one, ref) == BELOW_CRITICAL
    # simulate's label: the same vibration is "balanced" only above the first critical speed
    assert _outcome(0, [1e-6], [1e-3], 0.0, 25.0, 2, first_critical=25.6) == BELOW_CRITICAL
    assert _outcome(0, [1e-6], [1e-3], 0.0, 26.0, 2, first_critical=25.6) == "balanced"


# ---- item 10 -----------------------------------------------------------------------------------


def test_the_growth_rate_of_a_self_excited_suspension_is_the_closed_form():
    """Cross-coupled stiffness q on the drum: in z = x + i y, m z'' + c z' + (k -+ i q) z = 0
    (m = 41 kg with the balls locked), roots s = (-c +- sqrt(c^2 - 4 m (k -+ i q))) / (2 m);
    unstable when q > c sqrt(k / m). The largest real part is the growth rate reported; the
    drum's undamped tilt modes add none."""
    q = 15e3
    m = washer(('kxx = "25 kN/m"', 'kxx = "25 kN/m"\nkxy = "15 kN/m"\nkyx = "-15 kN/m"'))
    mass = M_DRUM + M_BALLS
    roots = np.concatenate([np.roots([mass, C, K - 1j * q]), np.roots([mass, C, K + 1j * q])])
    growth, why = structure_instability(m, 100.0)
    assert growth == pytest.approx(roots.real.max(), rel=1e-9) and growth > 2.0
    assert why is not None and "954.93 rpm" in why and f"{growth:.4g} 1/s" in why
    # below the threshold q = c sqrt(k / m) = 9.88 kN/m (m = 41 kg) it is stable
    m = washer(('kxx = "25 kN/m"', 'kxx = "25 kN/m"\nkxy = "9.8 kN/m"\nkyx = "-9.8 kN/m"'))
    assert structure_instability(m, 100.0)[1] is None


def test_the_built_in_machines_are_stable_where_they_run():
    """The negative control: no growing eigenvalue (the washer's undamped tilt modes sit on the
    imaginary axis, the damped Pico 21 housing's just left of it)."""
    for name, speed in (("washer-horizontal", 150.0), ("pico21-balancer", 10000 * np.pi / 30)):
        growth, why = structure_instability(machine_model(load_case(name).model), speed)
        assert why is None and growth < 1e-9


def test_the_sanity_monitor_fails_deflections_beyond_the_machine_size():
    """The washer's size is its race radius 0.27 m (without the races, the drum's radius of
    gyration sqrt(1.5 / 40) = 0.194 m; with a clearance at least ten times its reach): a state
    beyond it, or tilted more than 0.5 rad, fails."""
    m = washer()
    bare = replace(m, races=())
    assert m.size_scale()[0] == pytest.approx(0.27, rel=1e-15)
    assert bare.size_scale()[0] == pytest.approx(np.sqrt(1.5 / 40.0), rel=1e-15)
    # a clearance reaches 10 (gap + |centre|): 10 * (30 + 5) mm = 0.35 m; a 10 mm gap adds nothing
    assert replace(bare, clearances=(Clearance(0, 0.03, center=(0.0, -0.005)),)).size_scale()[0] == pytest.approx(
        0.35, rel=1e-12)
    assert replace(bare, clearances=(Clearance(0, 0.01),)).size_scale()[0] == pytest.approx(0.1936, rel=1e-3)
    p = bare.to_array()
    ys = np.zeros((3, 4, bare.n_state))
    ys[:, 1:] = np.nan  # trajectories that ended: ignored
    y_final = np.zeros((3, bare.n_state))
    y_final[0, 1] = -0.19  # inside
    y_final[1, 0] = 0.2  # beyond 0.194 m
    ys[2, 0, 3] = 0.6  # tilt phi_y beyond 0.5 rad at a saved state
    notes = bare.impossible_states(ys, y_final, np.array([1.0, 2.0, 3.0]), p)
    assert notes[0] == ""
    assert "station 'drum' moved 0.2 m" in notes[1] and "0.194 m" in notes[1] and "t = 2 s" in notes[1]
    assert "node 'drum' tilted by 0.6 rad" in notes[2]


# ---- item 11 -----------------------------------------------------------------------------------


def test_simulate_and_run_up_refuse_the_same_absurd_history_up_front():
    """One check (check_saved_states): before, simulate dropped a history over 256 MB silently."""
    m = washer().with_drive(ConstantSpeed(100.0))
    with pytest.raises(TooLarge, match=r"n_save = 10000000000 saved states of 3 trajectories x 12 entries need"):
        machine_simulate(m, np.zeros((3, 2)), t_end=1.0, n_save=10**10)
    with pytest.raises(TooLarge, match=r"n_save = 10000000000 saved states of 1 trajectory x 12 entries need"):
        machine_run_up(m, t_end=1.0, n_save=10**10)
