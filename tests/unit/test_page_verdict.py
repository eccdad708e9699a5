"""The engineer's verdict (issue 29 item 1): each analysis' evidence read from its rows, the status
of each line and the fix of a "no"; numbers rounded for people. No integration here: the rows
are those the analyses write (their keys), with numbers from closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from rotorlab import _people as people
from rotorlab.analyses import VERDICT_EVIDENCE, explain_regime, machine_facts, machine_verdict
from rotorlab.cli._verdict import verdict_text
from rotorlab.io import load_case


def test_people_round_to_three_digits_and_name_zero_and_large_ratios():
    assert people.length(5.88e-12) == "< 1 nm" and people.length(0.0286) == "28.6 mm"
    assert people.relative(33.9) == "33.9 ×" and people.relative(0.339) == "33.9 %"
    assert people.angle_deg(1.7847) == "1.8°" and people.angle(math.radians(-16.05)) == "-16.1°"
    assert people.speed(2 * math.pi * 7894 / 60) == "7894 rpm" and people.number(1.7847) == "1.78"


def test_contact_line_gives_the_share_the_bound_when_none_touched_and_the_damping_that_fixes_it():
    """0 contacts in 8 run-ups: the Wilson 95 % upper bound is z^2 / (n + z^2) = 3.8415 / 11.8415 =
    32.4 %."""
    z2 = 1.959964**2
    rows = [{"ball_damping": 0.01, "contact_probability": 0.0, "probability_low": 0.0,
             "probability_high": z2 / (8 + z2), "largest_impulse": None, "runs": 8, "failed": 0,
             "least_margin": 0.0042},
            {"ball_damping": 0.2, "contact_probability": 1.0, "probability_low": 0.68, "probability_high": 1.0,
             "largest_impulse": 1.71, "runs": 8, "failed": 0, "least_margin": 0.0}]
    knock = xr.Dataset(attrs={"name": "knock", "gap": 0.01, "margin_sample_interval": 0.002})
    (line,) = VERDICT_EVIDENCE["machine-knock"](knock, rows, None)
    assert (line.topic, line.status) == ("contact", "no")
    assert line.sentence == ("Touches the stator in 8 of 8 (100 %) run-ups at ball damping 0.2 N*m*s/rad, largest "
                             "impulse 1.71 N*s; 0 of 8 (0 %) run-ups at ball damping 0.01 N*m*s/rad, at most 32.4 % "
                             "with 95 % confidence (knock; where no run-up touched, the least margin is 4.2 mm, "
                             "sampled every 2 ms).")
    assert line.fix == "a ball damping of 0.01 N*m*s/rad"
    (clear,) = VERDICT_EVIDENCE["machine-knock"](knock, rows[:1], None)
    assert clear.status == "yes" and clear.sentence == (
        "No contact: 0 of 8 (0 %) run-ups at ball damping 0.01 N*m*s/rad, at most 32.4 % with 95 % confidence; least "
        "margin 4.2 mm of the 10 mm gap, sampled every 2 ms (knock).")
    (touched,) = VERDICT_EVIDENCE["machine-knock"](knock, rows[1:], None)
    assert touched.sentence.endswith("(knock; least margin 0 (touched)).")


def test_run_up_line_counts_the_starts_that_pass_and_names_the_passing_torque():
    """A start captured at the critical speed does not pass; the fix is the smallest passing stall
    torque the analysis found; the peak is the largest station distance (gravity: sag included)."""
    facts = machine_facts(load_case("washer-horizontal"))
    crit = [24.693, 67.2]
    rows = [{"ic": 0, "final_speed": 140.0, "critical_speeds": crit, "passed": 2, "captured_at": None,
             "outcome": "balanced", "passing_torque": 5.25},
            {"ic": 1, "final_speed": 25.0, "critical_speeds": crit, "passed": 0, "captured_at": 24.9,
             "outcome": "captured", "passing_torque": 5.25}]
    amp = np.zeros((2, 5, 1))
    amp[1, 3, 0] = 0.0373
    ds = xr.Dataset({"amplitude": (("ic", "time", "station"), amp)}, coords={"time": np.linspace(0, 40, 5)},
                    attrs={"name": "up"})
    run_up, balances = VERDICT_EVIDENCE["run-up"](ds, rows, facts)
    assert (run_up.topic, run_up.status) == ("run-up", "no")
    assert run_up.sentence == ("up: 1 of 2 (50 %) starts pass the first critical speed (236 rpm); largest distance "
                               "from the axis 37.3 mm (the static sag under gravity included), final speed 1337 rpm.")
    assert run_up.fix == "a stall torque of at least 5.25 N*m (the smallest that passes)"
    assert balances.status == "no" and balances.sentence.startswith(
        "Balances from some starts only after the run-up (up) within 40 s: balanced [")
    assert "captured [the rotor is held at a critical speed (the Sommerfeld effect)] from 1 of 2" in balances.sentence


def test_a_not_settled_start_gives_not_settled_and_the_horizon_to_simulate():
    rows = [{"speed_rpm": 2400.0, "outcome": "balanced", "final_ball_angles_deg": [120.0, -120.0]},
            {"speed_rpm": 2400.0, "outcome": "not settled", "final_ball_angles_deg": [110.0, -100.0]}]
    ds = xr.Dataset(attrs={"name": "sim", "t_end": 2.0})
    (line,) = VERDICT_EVIDENCE["simulate"](ds, rows, None)
    assert line.status == "not-settled" and line.fix == "simulate longer than 2 s for a verdict"
    assert "not settled [still converging towards balance when the simulation ended] from 1 of 2 (50 %)" in line.sentence


def test_regime_names_are_explained():
    assert explain_regime("side (0°, 180°)") == ("the balls settled on the line through the unbalance, 1 on the "
                                                 "unbalance's side, 1 opposite; nominal angles")
    assert explain_regime("side 01").startswith("a side motion: the balls on the line of the rotor's deflection, "
                                                "1 towards it and 1 away")
    assert explain_regime("failed: step size too small") == ""


def test_a_machine_without_results_still_gets_its_critical_speeds_and_what_to_add():
    """washer-horizontal, balls locked: the drum's 40 kg plus the two 0.5 kg balls on 25 kN/m,
    p = sqrt(25000 / 41) = 24.69 rad/s = 236 rpm; the drive's no-load speed 150 rad/s = 1432 rpm
    = 6.07 p."""
    case = load_case("washer-horizontal")
    lines = machine_verdict(case, {}, {})
    assert math.sqrt(25e3 / 41) * 30 / math.pi == pytest.approx(235.8, abs=0.05)
    assert [(v.topic, v.status) for v in lines] == [
        ("critical speeds", "info"), ("operating speed", "yes"), ("balances", "info"), ("stable speeds", "info"),
        ("run-up", "info")]
    assert lines[0].sentence.startswith("undamped, balls locked: 236 rpm")
    assert lines[1].sentence == ("p = 236 rpm, the first forward critical speed; runs at 1432 rpm (drive) = 6.07 p. "
                                 "All above p, where a balancer can work.")
    text = verdict_text(lines)
    assert max(map(len, text.splitlines())) <= 100 and text.startswith("Verdict\n  -            critical speeds:")


def test_how_fast_a_start_balances_is_read_from_its_saved_history():
    """A deflection ref * exp(-t) falls below BALANCED_FRACTION = 5 % of the unbalance response at
    t = ln 20 = 2.996 s: on a 0.5 s grid the first saved time below is 3 s."""
    t = np.arange(0.0, 10.01, 0.5)
    ds = xr.Dataset({"amplitude": (("speed", "ic", "time"), 1e-3 * np.exp(-t)[None, None, :]),
                     "reference_amplitude": (("speed",), [1e-3])},
                    coords={"speed": [251.3], "ic": [0], "time": t}, attrs={"name": "sim", "t_end": 10.0})
    rows = [{"speed": 251.3, "speed_rpm": 251.3 * 30 / math.pi, "ic": 0, "outcome": "balanced",
             "final_ball_angles_deg": [120.0, -120.0]}]
    (line,) = VERDICT_EVIDENCE["simulate"](ds, rows, None)
    assert line.status == "yes" and line.sentence.endswith("starts; the balanced ones settled by 3 s.")


def test_contact_of_a_rotor_resting_on_its_stator_names_center_at_rest_not_ball_damping():
    """The issue's tub: sag beyond the gap "knocks in 100 % of run-ups, even without balls". The
    washer-knock drum (41 kg on 25 kN/m) sags 16.1 mm against its 10 mm gap without
    center_at_rest."""
    from rotorlab.io import parse_override

    case = load_case("washer-knock", overrides=dict([parse_override("model.clearances[0].center_at_rest=false")]))
    rows = [{"ball_damping": d, "contact_probability": 1.0, "probability_low": 0.68, "probability_high": 1.0,
             "largest_impulse": 2.0, "runs": 8, "failed": 0} for d in (0.01, 0.2)]
    (line,) = VERDICT_EVIDENCE["machine-knock"](xr.Dataset(attrs={"name": "knock"}), rows, machine_facts(case))
    assert line.status == "no" and ("at rest the rotor already lies 16.1 mm from the stator's centre, beyond the gap "
                                    "10 mm: it rests on the stator, with or without balls") in line.sentence
    assert line.fix == "give model.clearances[0].center_at_rest = true (the stator centred where the rotor rests)"
