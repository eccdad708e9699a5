"""Unit conversion of case-file quantities (rotorlab.io.to_si)."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rotorlab.io import DIMENSIONS, CaseError, to_si


@pytest.mark.parametrize(
    ("value", "dimension", "expected"),
    [
        ("14800 rpm", "angular_speed", 14800 * 2 * math.pi / 60),  # 1549.85 rad/s
        ("1200 rpm", "angular_speed", 40 * math.pi),
        ("20 Hz", "angular_speed", 2 * math.pi * 20),
        ("1 kHz", "angular_speed", 2 * math.pi * 1000),
        ("5 rad/s", "angular_speed", 5.0),
        ("5 1/s", "angular_speed", 5.0),
        ("5/s", "angular_speed", 5.0),
        ("360 deg/s", "angular_speed", 2 * math.pi),
        ("100 rev/min", "angular_speed", 100 * 2 * math.pi / 60),
        ("2 rps", "angular_speed", 4 * math.pi),
        ("1200 rpm", "frequency", 20.0),
        ("20 Hz", "frequency", 20.0),
        ("882 kg*mm^2", "inertia", 882e-6),
        ("882 kg*mm²", "inertia", 882e-6),
        ("882 kg mm^2", "inertia", 882e-6),
        ("30 deg", "angle", math.pi / 6),
        ("30°", "angle", math.pi / 6),
        ("0.5 rev", "angle", math.pi),
        ("0.25", "angle", 0.25),
        ("1.5 mm", "length", 1.5e-3),
        ("3 µm", "length", 3e-6),
        ("3 um", "length", 3e-6),
        ("1 in", "length", 0.0254),
        ("30 g", "mass", 0.03),
        ("1 kg", "mass", 1.0),
        ("2 t", "mass", 2000.0),
        ("16.74 kN/m", "stiffness", 16740.0),
        ("3 MN/m", "stiffness", 3.0e6),
        ("13 N*s/m", "damping", 13.0),
        ("13 kg/s", "damping", 13.0),
        ("2e-4 N*m*s", "torque_damping", 2e-4),
        ("2e-4 N*m*s/rad", "torque_damping", 2e-4),
        ("20 s", "time", 20.0),
        ("2 min", "time", 120.0),
        ("250 ms", "time", 0.25),
        ("5 %", "dimensionless", 0.05),
        ("1e-8", "dimensionless", 1e-8),
        ("10 N*m/rad", "rotational_stiffness", 10.0),
        ("2 um/N", "compliance", 2e-6),
        ("9.81 m/s^2", "acceleration", 9.81),
    ],
)
def test_string_with_unit_is_converted_to_si(value, dimension, expected):
    assert to_si(value, dimension, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("dimension", sorted(DIMENSIONS))
def test_plain_numbers_are_si(dimension):
    assert to_si(2.5, dimension, "x") == 2.5
    assert to_si(3, dimension, "x") == 3.0
    assert isinstance(to_si(3, dimension, "x"), float)


def test_hertz_counts_cycles_but_one_over_second_is_radians():
    assert to_si("1 Hz", "angular_speed", "x") == pytest.approx(2 * math.pi)
    assert to_si("1 1/s", "angular_speed", "x") == pytest.approx(1.0)
    assert to_si("1 1/s", "frequency", "x") == pytest.approx(1.0)
    assert to_si("1 rad/s", "frequency", "x") == pytest.approx(1 / (2 * math.pi))


@pytest.mark.parametrize(
    ("value", "dimension", "fragments"),
    [
        ("12 furlongs", "stiffness", ["x = \"12 furlongs\"", "unknown unit 'furlongs'"]),
        ("3 kgs", "mass", ["unknown unit 'kgs'", "did you mean 'kg'?"]),
        ("3 m", "mass", ["x = \"3 m\"", "wrong dimension", "expected a mass (kg)", "got length"]),
        ("20 Hz", "time", ["expected a time (s)", "got angular speed"]),
        ("30 deg", "dimensionless", ["expected a dimensionless number", "got angle"]),
        ("5 rpm", "angle", ["expected an angle (rad)", "got angular speed"]),
        ("3", "mass", ["got a plain number", "write 3 without quotes"]),
        ("nan kg", "mass", ["must be a finite number"]),
        ("1e400 kg", "mass", ["must be a finite number"]),
        ("kg", "mass", ["cannot read a quantity"]),
        ("", "mass", ["cannot read a quantity"]),
        ("3.5.2 kg", "mass", ["cannot read a quantity"]),
        ("3 kg*", "mass", ["cannot read the unit 'kg*'"]),
        ("3 kg + 2 g", "mass", ["cannot read the unit"]),
        ("1 c", "velocity", ["unknown unit 'c'"]),
    ],
)
def test_bad_strings_name_the_key_value_and_reason(value, dimension, fragments):
    with pytest.raises(CaseError) as info:
        to_si(value, dimension, "x")
    message = str(info.value)
    assert message.startswith("x = ")
    for fragment in fragments:
        assert fragment in message


@pytest.mark.parametrize(
    ("value", "shown", "reason"),
    [
        (True, "true", "got a boolean"),
        ([1.0, 2.0], "[1.0, 2.0]", "got a list"),
        ({"a": 1}, "{a = 1}", "got a table"),
        (float("nan"), "nan", "must be a finite number"),
        (float("inf"), "inf", "must be a finite number"),
        (10**400, "1000", "must be a finite number"),
    ],
)
def test_wrong_types_and_non_finite_numbers(value, shown, reason):
    with pytest.raises(CaseError) as info:
        to_si(value, "mass", "model.disc_mass")
    message = str(info.value)
    assert message.startswith(f"model.disc_mass = {shown}")
    assert reason in message


def test_unknown_dimension_is_a_programming_error():
    with pytest.raises(ValueError, match="unknown dimension 'masss'") as info:
        to_si(1.0, "masss", "x")
    assert not isinstance(info.value, CaseError)


def test_case_error_is_a_value_error():
    with pytest.raises(ValueError):
        to_si("3 m", "mass", "x")


@given(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False))
def test_millimetres_are_thousandths_of_a_metre(x):
    assert to_si(f"{x!r} mm", "length", "x") == pytest.approx(x / 1000, rel=1e-12, abs=1e-300)


@given(st.floats(min_value=0, max_value=1e5, allow_nan=False))
def test_rpm_and_hertz_agree(f):
    rpm = to_si(f"{f * 60!r} rpm", "angular_speed", "x")
    hz = to_si(f"{f!r} Hz", "angular_speed", "x")
    assert rpm == pytest.approx(hz, rel=1e-12, abs=1e-300)


def test_pint_is_not_imported_with_rotorlab_io():
    code = "import sys, rotorlab.io; print('pint' in sys.modules, 'xarray' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]
