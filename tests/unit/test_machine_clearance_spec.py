"""The machine's clearance in case files (``[[model.clearances]]``): units, key paths, the model
built from it, and its kernel on the lane driver."""

from __future__ import annotations

import math

import numpy as np
import pytest
from llvmlite import binding as ll

from rotorlab.io import CaseError, load_case, parse_case
from rotorlab.io._machine_spec import build_machine
from rotorlab.models import Clearance, ElasticStator

CLEARANCE = '''
[[model.clearances]]
at = "drum"
gap = "30 mm"
restitution = 0.4
friction = 0.3
rotor_radius = "0.3 m"
rest_speed = "1 mm/s"
stator = { stiffness = "200 kN/m", damping = "500 N*s/m", mass = "20 kg" }
'''


def _washer(extra: str) -> str:
    text = load_case("washer-horizontal").text
    return text.replace("[model.gravity]", extra.strip() + "\n\n[model.gravity]", 1)


def test_a_clearance_table_builds_the_machine_clearance_in_si():
    m = build_machine(parse_case(_washer(CLEARANCE)).model)
    (c,) = m.clearances
    assert c == Clearance(0, 0.03, ElasticStator(2e5, 500.0, 20.0), restitution=0.4, friction=0.3,
                          rotor_radius=0.3, rest_speed=1e-3)  # fmt: skip
    assert c.kind == "housing" and m.state_names[-9:-5] == ("x_housing", "y_housing", "vx_housing", "vy_housing")
    assert m.kernels.n_discrete == 3 and [e.name for e in m.kernels.event_specs] == [
        "contact", "lift_off", "stick", "slip"]
    rigid = build_machine(parse_case(_washer(CLEARANCE.replace(
        'stator = { stiffness = "200 kN/m", damping = "500 N*s/m", mass = "20 kg" }\n', ""))).model)
    assert rigid.clearances[0].kind == "rigid"
    cone = build_machine(parse_case(_washer(CLEARANCE + 'conical = { half_angle = "30 deg", lever = "0.1 m" }\n')).model)
    assert cone.clearances[0].conical == pytest.approx((math.pi / 6, 0.1), rel=1e-15)


@pytest.mark.parametrize("old, new, words", [
    ('gap = "30 mm"', 'gap = "-30 mm"', ["model.clearances[0].gap", "> 0"]),
    ('gap = "30 mm"', 'gap = "30 kg"', ["model.clearances[0].gap", "wrong dimension"]),
    ("restitution = 0.4", "restitution = 1.4", ["model.clearances[0].restitution", "<= 1"]),
    ('at = "drum"\ngap', 'at = "drun"\ngap', ["model.clearances[0].at", "drun"]),
    ('mass = "20 kg"', 'mass = "20 kg", k = 3', ["model.clearances[0].stator.k", "unknown key"]),
])  # fmt: skip
def test_bad_clearance_entries_name_their_key_path(old, new, words):
    text = _washer(CLEARANCE)
    assert old in text
    with pytest.raises(CaseError) as err:
        parse_case(text.replace(old, new, 1))
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_at_most_one_clearance_per_machine():
    with pytest.raises(CaseError) as err:
        parse_case(_washer(CLEARANCE + CLEARANCE))
    assert "model.clearances" in str(err.value) and "at most 1" in str(err.value)


@pytest.mark.skipif(not any(ll.get_host_cpu_features().get(f) for f in ("avx", "sse2", "neon")),
                    reason="no SIMD unit known to LLVM on this CPU")
def test_the_machine_kernel_with_a_clearance_vectorises_in_the_lane_driver():
    """The clearance kernel vectorises in the lane driver (events run on lanes too)."""
    from rotorlab.integrate._drivers import is_vectorised
    from rotorlab.linear import LinearSystem
    from rotorlab.models import ConstantSpeed, Machine, Unbalance

    s = LinearSystem(M=np.diag([1.0, 1.0, 1.0, 1.0]), C=np.diag([0.1, 0.1, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 1.0, 1.0]))  # fmt: skip
    m = Machine(s, unbalances=(Unbalance(0, 0.6),), drive=ConstantSpeed(1.5),
                clearances=(Clearance(0, 1.0, ElasticStator(10.0), friction=0.02, rotor_radius=0.5),))
    assert m.kernels.vectorises and is_vectorised(m.kernels, lanes=8)
