"""A sweep analysis in a case file records the unit each varied angle was written in, like a basin.

Review of the session-5 diff: ``rotorlab sweep --ic psi_1=0deg:300deg:N`` recorded "deg" and the
map was drawn in degrees (issue 13), but the same sweep written in a case file
(``ic = { psi_1 = ["0 deg", "300 deg", N] }``, run by ``rotorlab run`` or ``rotorlab sweep CASE``)
recorded nothing, so its map was drawn in radians. The values stay SI (radians) either way.
"""

from __future__ import annotations

import math

import pytest

from rotorlab.analyses._sweep import build_sweep
from rotorlab.io import SweepSpec, load_case, parse_case


def _case(ic: str, param: str = "") -> str:
    head = load_case("autobalancer").text.split("[[analysis]]")[0]
    return head + f'[[analysis]]\ntype = "sweep"\nspeed_ratio = 2.0\nt_end = "1 s"\n{param}ic = {{ {ic} }}\n'


def test_a_case_file_sweep_records_the_unit_of_its_angles():
    case = parse_case(_case('psi_1 = ["0 deg", "180 deg", 3], psi_2 = [0, 3.0, 2], dpsi_1 = ["-1 rpm", "1 rpm", 2]'))
    spec = case.analysis("sweep-0")
    # an angle in degrees, an angle in plain numbers (radians); a rate is not an angle: not recorded
    assert spec.input_units == {"psi_1": "deg", "psi_2": "rad"}
    assert spec.ic["psi_1"][1] == pytest.approx(math.pi, rel=1e-15)  # SI inside
    sweep = build_sweep(case.model, spec)
    assert sweep.input_units == {"psi_1": "deg", "psi_2": "rad"}
    assert sweep.display_attrs() == {"input_units_psi_1": "deg", "input_units_psi_2": "rad"}


def test_only_the_varied_coordinates_keep_their_unit():
    case = parse_case(_case('psi_1 = ["0 deg", "180 deg", 3], psi_2 = ["0 deg", "90 deg", 2]'))
    spec = case.analysis("sweep-0")
    # the command line's axes replace the case's: psi_2 is no longer varied
    sweep = build_sweep(case.model, spec, axes={"psi_1": (0.0, 1.0, 2)})
    assert sweep.input_units == {"psi_1": "deg"}
    # a spec built in Python from SI numbers records radians
    assert SweepSpec(ic={"psi_1": [0.0, 1.0, 2]}, t_end=1.0).input_units == {"psi_1": "rad"}
