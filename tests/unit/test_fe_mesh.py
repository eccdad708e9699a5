"""The ``fe_rotor`` mesh is refined so that discs and bearings given by position sit on nodes.

Written with one shaft element, the Friswell rotor (Example 5.9.1: discs at 0.5 m and 1.0 m of
a 1.5 m shaft) is refined to three equal elements of 0.5 m: its matrices must be those of the
same rotor assembled in Python with ``uniform_shaft(3, ...)`` and the discs on nodes 1 and 2.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.analyses import build_linear_system, run_linear_analysis
from rotorlab.io import CaseError, load_case, parse_case
from rotorlab.linear import STEEL, Bearing, Material, RigidBody, assemble, uniform_shaft
from rotorlab.linear.cases._friswell import friswell_rotor

FRISWELL = load_case("friswell-rotor").text


def test_refined_mesh_is_the_rotor_with_nodes_at_the_discs():
    case = parse_case(FRISWELL.replace("elements = 6", "elements = 1"))
    assert case.model.refinement() == pytest.approx((0.5, 1.0))
    assert "2 node(s) added at z = 0.5, 1 m" in case.model.describe()
    system = build_linear_system(case.model)
    steel = Material(youngs_modulus=211e9, shear_modulus=81.2e9, density=7810.0)
    discs = [RigidBody.disc(n, d, 0.07, 7810.0, inner_diameter=0.05)
             for n, d in ((1, 0.28), (2, 0.35))]
    python = assemble([*uniform_shaft(3, 1.5, 0.05, material=steel), *discs,
                       Bearing(node=0, kxx=1e6), Bearing(node=3, kxx=1e6)])
    for name in ("M", "K", "G", "C"):
        np.testing.assert_allclose(getattr(system, name), getattr(python, name), rtol=1e-12,
                                   atol=1e-9 * np.abs(getattr(python, name)).max())
    assert system.node_label == ("bearing A", "disc 1", "disc 2", "bearing B")


def test_written_mesh_unchanged_when_parts_sit_on_nodes():
    case = load_case("friswell-rotor")
    assert case.model.refinement() == ()
    system = build_linear_system(case.model)
    np.testing.assert_array_equal(system.K, friswell_rotor().K)  # bit for bit, as before


def test_refinement_stated_in_results_and_nodes_by_written_index():
    text = FRISWELL.replace("elements = 6", "elements = 2").replace(
        'position = "0.5 m"', 'position = "0.6 m"')
    case = parse_case(text)
    # nodes of the sections as written: 0, 0.75, 1.5; added: 0.6 (disc 1) and 1.0 (disc 2)
    assert case.model.node_positions() == pytest.approx((0.0, 0.6, 0.75, 1.0, 1.5))
    assert case.model.locate(1, None, None)[0] == 2  # written node 1 (z = 0.75) is node 2 now
    ds = run_linear_analysis(case.model, case.analysis("modes-at-rest"))
    assert ds.attrs["mesh"].startswith("mesh refined: 2 node(s) added at z = 0.6, 1 m")


def test_position_off_the_shaft_is_an_error():
    with pytest.raises(CaseError, match=r"model.discs\[0\].position .*must be on the shaft, "
                                        r"from 0 to 1.5 m"):
        parse_case(FRISWELL.replace('position = "0.5 m"', 'position = "1.7 m"'))
