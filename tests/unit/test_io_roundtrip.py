"""Property: any valid case survives dump_case -> parse_case unchanged."""

from __future__ import annotations

import math

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rotorlab.io import dump_case, parse_case, validate_case


def quantity(low: float, high: float, units: list[tuple[str, float]]):
    """A value in [low, high] (SI), written either as a plain number or with one of ``units``.

    ``units`` pairs a unit with its size in SI, so ``x`` SI is written ``f"{x / size} {unit}"``.
    """
    si = st.floats(min_value=low, max_value=high, allow_nan=False, allow_infinity=False)
    with_unit = st.tuples(si, st.sampled_from(units)).map(
        lambda pair: f"{pair[0] / pair[1][1]!r} {pair[1][0]}"
    )
    return st.one_of(si, with_unit)


MASS = [("kg", 1.0), ("g", 1e-3)]
LENGTH = [("m", 1.0), ("mm", 1e-3), ("um", 1e-6)]
SPEED = [("rad/s", 1.0), ("rpm", 2 * math.pi / 60), ("Hz", 2 * math.pi)]
TIME = [("s", 1.0), ("ms", 1e-3), ("min", 60.0)]
ANGLE = [("rad", 1.0), ("deg", math.pi / 180), ("rev", 2 * math.pi)]


@st.composite
def balls(draw):
    mass = draw(quantity(1e-3, 1.0, MASS))
    radius = draw(quantity(1e-3, 0.5, LENGTH))
    ball = {"mass": mass, "radius": radius}
    if draw(st.booleans()):
        # at least the point-mass inertia: compute it in SI from the SI values
        m = validate_number(mass, MASS)
        r = validate_number(radius, LENGTH)
        ball["inertia"] = m * r * r * draw(st.floats(min_value=1.0, max_value=3.0))
    if draw(st.booleans()):
        ball["damping"] = draw(quantity(0.0, 1e-2, [("N*m*s", 1.0), ("N*mm*s/rad", 1e-3)]))
    if draw(st.booleans()):
        ball["friction"] = draw(st.floats(min_value=0.0, max_value=0.5))
    if draw(st.booleans()):
        ball["count"] = draw(st.integers(min_value=1, max_value=3))
    return ball


def validate_number(value, units) -> float:
    if isinstance(value, float):
        return value
    number, unit = value.split(" ")
    return float(number) * dict(units)[unit]


@st.composite
def profiles(draw):
    kind = draw(st.sampled_from(["none", "constant", "ramp", "hill"]))
    if kind == "none":
        return None
    if kind == "constant":
        return {"profile": "constant", "speed": draw(quantity(0.1, 2e3, SPEED))}
    if kind == "ramp":
        return {
            "profile": "ramp",
            "start": draw(quantity(0.0, 2e3, SPEED)),
            "stop": draw(quantity(0.0, 2e3, SPEED)),
            "duration": draw(quantity(1e-2, 100.0, TIME)),
        }
    return {
        "profile": "hill",
        "max_speed": draw(quantity(0.1, 2e3, SPEED)),
        "t_half": draw(quantity(1e-2, 100.0, TIME)),
        "exponent": draw(st.floats(min_value=0.01, max_value=1000.0)),
    }


@st.composite
def analyses(draw, n_balls: int, profile):
    options = ["speed_ratio", "speed"] + (["profile"] if profile is not None else [])
    mode = draw(st.sampled_from(options))
    entry = {"type": "simulate"}
    if mode == "speed_ratio":
        entry["speed_ratio"] = draw(st.floats(min_value=0.01, max_value=10.0))
    elif mode == "speed":
        entry["speed"] = draw(quantity(0.1, 2e3, SPEED))
    if draw(st.booleans()):
        angle = quantity(-10.0, 10.0, ANGLE)
        rows = st.lists(st.lists(angle, min_size=n_balls, max_size=n_balls), min_size=1, max_size=4)
        entry["initial_ball_angles"] = draw(rows)
    else:
        entry["ball_angle_grid"] = draw(st.integers(min_value=1, max_value=4))
    constant = mode != "profile" or profile["profile"] == "constant"
    if constant and draw(st.booleans()):
        entry["revolutions"] = draw(st.floats(min_value=0.5, max_value=1e4))
    else:
        entry["t_end"] = draw(quantity(1e-3, 1e3, TIME))
    if draw(st.booleans()):
        entry["n_save"] = draw(st.integers(min_value=2, max_value=100_000))
    if draw(st.booleans()):
        entry["rtol"] = draw(st.floats(min_value=1e-14, max_value=0.5))
    if draw(st.booleans()):
        entry["atol"] = draw(st.floats(min_value=1e-16, max_value=1.0))
    return entry


@st.composite
def cases(draw):
    model = {
        "type": "jeffcott_balls",
        "disc_mass": draw(quantity(1e-2, 1e4, MASS)),
        "eccentricity": draw(quantity(0.0, 1e-2, LENGTH)),
        "stiffness": draw(quantity(1.0, 1e9, [("N/m", 1.0), ("kN/m", 1e3), ("MN/m", 1e6)])),
    }
    if draw(st.booleans()):
        model["frame"] = draw(st.sampled_from(["fixed", "rotating"]))
    if draw(st.booleans()):
        model["damping"] = draw(quantity(0.0, 1e3, [("N*s/m", 1.0), ("kg/s", 1.0)]))
    profile = draw(profiles())
    if profile is not None:
        model["speed"] = profile
    ball_list = draw(st.lists(balls(), max_size=3))
    if ball_list or draw(st.booleans()):
        model["balls"] = ball_list
    n_balls = sum(b.get("count", 1) for b in ball_list)
    entries = draw(st.lists(analyses(n_balls, profile), max_size=3))
    names = draw(
        st.lists(
            st.from_regex(r"a[A-Za-z0-9_.-]{0,12}", fullmatch=True),
            min_size=len(entries),
            max_size=len(entries),
            unique=True,
        )
    )
    for entry, name in zip(entries, names, strict=True):
        if draw(st.booleans()):
            entry["name"] = name
    doc = {"model": model, "analysis": entries}
    if draw(st.booleans()):
        doc["name"] = draw(st.from_regex(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,20}", fullmatch=True))
    if draw(st.booleans()):
        doc["description"] = draw(st.text(max_size=40))
    if draw(st.booleans()):
        doc["schema_version"] = 1
    return doc


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases())
def test_any_valid_case_survives_dump_and_load(doc):
    case = validate_case(doc)
    text = dump_case(case)
    again = parse_case(text, "dumped.toml")
    assert again.model_dump_si() == case.model_dump_si()
    assert dump_case(again) == text


@settings(max_examples=50, deadline=None)
@given(st.text(max_size=60))
def test_any_description_survives_dump_and_load(description):
    doc = {
        "description": description,
        "model": {"type": "jeffcott_balls", "disc_mass": 1, "eccentricity": 0, "stiffness": 1},
    }
    case = validate_case(doc)
    assert parse_case(dump_case(case)).description == description
