"""Damping matrices of a multibody model's elastic structure (``[model.elastic] damping``).

The two-plane balancer of Rodrigues et al. (2008) sits on two dampers c = 0.01 at z = +-3 of a
rigid rotor: on (x, phi_x) their matrix is ``sum_i c_i [[1, z_i], [z_i, z_i^2]]`` =
``[[0.02, 0], [0, 0.18]]`` (their eq. (8) and (20): c11 = 0.02, c12 = 0, c22 = 0.18).
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.analyses import build_linear_system
from rotorlab.io import CaseError, parse_case

CASE = """
name = "long-rotor"
[model]
type = "multibody"
[[model.bodies]]
name = "rotor"
position = "0 m"
mass = "1 kg"
diametral_inertia = "3.25 kg*m^2"
polar_inertia = "0.5 kg*m^2"
[model.elastic]
stiffness = [[1.0, 0.0], [0.0, 9.0]]
damping = [["0.02 N*s/m", 0.0], [0.0, "0.18 N*m*s/rad"]]
"""


def test_damping_matrix_reaches_the_structure():
    s = build_linear_system(parse_case(CASE).model)
    np.testing.assert_allclose(s.K, np.diag([1.0, 1.0, 9.0, 9.0]), rtol=1e-15)
    np.testing.assert_allclose(s.C, np.diag([0.02, 0.02, 0.18, 0.18]), rtol=1e-15)
    plain = build_linear_system(parse_case(CASE.split("damping =")[0]).model)
    assert not plain.C.any()


def test_damping_y_and_scale():
    text = CASE.replace("[model.elastic]\n", "[model.elastic]\nscale = 2.0\n") + \
        "damping_y = [[0.01, 0.005], [0.005, 0.3]]\n"
    s = build_linear_system(parse_case(text).model)
    np.testing.assert_allclose(s.C[np.ix_([0, 2], [0, 2])], [[0.04, 0.0], [0.0, 0.36]], rtol=1e-15)
    np.testing.assert_allclose(s.C[np.ix_([1, 3], [1, 3])], [[0.02, 0.01], [0.01, 0.6]], rtol=1e-15)
    np.testing.assert_allclose(s.K[0, 0], 2.0)


def _problem(text: str) -> str:
    with pytest.raises(CaseError) as info:
        parse_case(text, "bad.toml")
    assert len(info.value.problems) == 1, info.value.problems
    return info.value.problems[0]


@pytest.mark.parametrize(("replace", "words"), [
    (('"0.02 N*s/m"', '"0.02 N/m"'),
     ['model.elastic.damping[0][0] = "0.02 N/m"', "expected a damping coefficient (N*s/m)"]),
    (('0.0], [0.0, "0.18', '"1 N/m"], [0.0, "0.18'),
     ["model.elastic.damping[0][1]", "translation-tilt damping (N*s/rad)"]),
    (("damping = [[", "damping_y = [["), ["model.elastic.damping_y: needs damping (the x-plane)"]),
    (('damping = [["0.02 N*s/m", 0.0], [0.0, "0.18 N*m*s/rad"]]', "damping = [[0.02]]"),
     ["model.elastic.damping = [[0.02]]", "must be a square matrix with an even number of rows"]),
    (('damping = [["0.02 N*s/m", 0.0], [0.0, "0.18 N*m*s/rad"]]',
      "damping = [[0.02, 0.0, 0.0, 0.0], [0.0, 0.18, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]"),
     ["model.elastic.damping: must be 2 x 2", "got 4 x 4"]),
    (('damping = [["0.02 N*s/m", 0.0], [0.0, "0.18 N*m*s/rad"]]', "damping = [[0.02, 0.1], [0.0, 0.18]]"),
     ["model.elastic.damping: must be symmetric: [0][1] = 0.1 but [1][0] = 0"]),
    (('damping = [["0.02 N*s/m", 0.0], [0.0, "0.18 N*m*s/rad"]]', "damping = [[0.02, 0.1], [0.1, 0.18]]"),
     ["model.elastic.damping: must be positive semi-definite", "eigenvalue -0.0280625"]),
], ids=["unit", "coupling-unit", "y-alone", "odd", "size", "asymmetric", "indefinite"])
def test_damping_errors_name_key_value_and_rule(replace, words):
    problem = _problem(CASE.replace(*replace, 1))
    for word in words:
        assert word in problem, problem


def test_singular_damping_is_accepted():
    text = CASE.replace('[0.0, "0.18 N*m*s/rad"]', "[0.0, 0.0]")
    s = build_linear_system(parse_case(text).model)
    np.testing.assert_allclose(np.diag(s.C), [0.02, 0.02, 0.0, 0.0])
