"""Fold and Hopf curves in two parameters (issue 25) on the planar machine with two balls of
test_continuation_equilibria.py.

References: the fold of the side motions 00/11 lies where ``d Omega 2 m l = M1 e |c - M Omega^2
+ i d Omega|`` (M = M1 + 2 m; rotorlab.steady._motions, seed 003 eq. (13) with the support
damping), a closed form at every ball mass; a point of each curve is checked by an independent
one-parameter continuation at its second parameter's value, and the Hopf curve by today's
stability chart (``machine_steady``: the largest real part of the exact eigenvalues crosses zero).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorlab.analyses._machine_steady import machine_steady
from rotorlab.continuation import continue_equilibria, continue_special_point, two_parameter_curves, with_value
from test_continuation_equilibria import MB, D, L, U, machine


def _fold_speed(mb):
    return brentq(lambda w: D * w * 2 * mb * L - U * abs(1.0 - (1.0 + 2 * mb) * w * w + 1j * D * w), 0.5, 0.99,
                  xtol=1e-15)


def test_fold_curve_speed_by_ball_mass_is_the_closed_form():
    m = machine(0.9)
    r = continue_equilibria(m, "drive.speed", 0.9, 1.0, start_from="side 00")
    (c,) = two_parameter_curves(m, r, "ball_mass", 0.012, 0.03)
    assert c.type == "fold" and c.parameters == ("drive.speed", "ball_mass") and c.end == "bound/bound"
    assert c.values[0, 1] == 0.012 and c.values[-1, 1] == 0.03 and len(c.values) > 5
    ref = np.array([_fold_speed(mb) for mb in c.values[:, 1]])
    np.testing.assert_allclose(c.values[:, 0], ref, rtol=1e-9)
    # an independent one-parameter continuation at the second parameter's value of one curve point
    k = len(c.values) // 3
    again = continue_equilibria(with_value(m, "ball_mass", c.values[k, 1]), "drive.speed", 0.85, 1.0,
                                start_from="side 00")
    (fold,) = [s for s in again.branches[0].special_points if s.type == "fold"]
    assert abs(fold.value - c.values[k, 0]) < 1e-8 * fold.value
    assert c.to_dict()["points"][0] == {"drive.speed": c.values[0, 0], "ball_mass": 0.012}


def test_hopf_curve_speed_by_ball_damping_matches_one_parameter_runs_and_the_chart():
    m = machine(2.0)
    r = continue_equilibria(m, "drive.speed", 0.5, 3.0, start_from="main+")
    (hopf,) = r.branches[0].special_points
    c = continue_special_point(m, hopf, "ball_damping", 0.005, 0.02, label="main+")
    assert c.type == "hopf" and c.end == "bound/bound"
    assert c.values[0, 1] == 0.005 and c.values[-1, 1] == 0.02 and np.all(c.frequency > 0)
    k = len(c.values) // 4
    w, cb = c.values[k]
    mk = with_value(m, "ball_damping", cb)
    again = continue_equilibria(mk, "drive.speed", 0.5, 3.0, start_from="main+")
    (h2,) = again.branches[0].special_points
    assert abs(h2.value - w) < 1e-8 * w and abs(h2.frequency - c.frequency[k]) < 1e-6 * h2.frequency
    crossing = brentq(lambda s: float(machine_steady(mk, [s]).max_real_eigenvalue[0]), 0.5 * w, 1.5 * w,
                      xtol=1e-13, rtol=1e-14)
    assert abs(crossing - w) < 1e-6 * w


def test_speed_by_support_anisotropy_is_refused_saying_what_it_needs():
    """Issue 25's speed x support anisotropy: a parameter that makes the supports anisotropic
    (washer-horizontal's bearing cross-stiffness kxy; its gravity and cabinet left out so that the
    rest has co-rotating equilibria) is refused before anything runs, saying why, what works (the
    balanced state's boundary in speed x support_anisotropy, test_continuation_anisotropy.py) and
    what is not implemented; an isotropic one of the same machine (kxx sets both directions) is
    continued."""
    from dataclasses import replace

    from rotorlab.analyses import build_model
    from rotorlab.continuation import MachineEquilibria
    from rotorlab.io import load_case

    m = replace(build_model(load_case("washer-horizontal").model), gravity=None, clearances=())
    m = with_value(m, "drive.speed", 100.0)
    with pytest.raises(ValueError) as err:
        MachineEquilibria(m, ("drive.speed", "structure.bearings[0].kxy"))
    text = str(err.value)
    assert text.startswith("structure.bearings[0].kxy makes the supports anisotropic")
    assert "Floquet problem" in text and "Not implemented: the other steady motions" in text
    assert "forced periodic motions" in text and "--param2 support_anisotropy=A:B" in text
    MachineEquilibria(m, ("drive.speed", "structure.bearings[0].kxx"))  # isotropic: accepted


def test_fold_curve_speed_by_unbalance_is_the_closed_form():
    """Speed x unbalance: the side motions 00/11 are born at the fold ``d Omega 2 m l = U |D|``, so
    along the fold curve ``U = d Omega 2 m l / |c - M Omega^2 + i d Omega|`` (closed form in the
    unbalance at every speed); the balls cannot balance more than they weigh: there the unbalance
    ratio eta = U / (m l) of every curve point stays below 2 (the balls-together pitchfork of
    test_balanced_branch_in_ball_mass_closed_form_angles_and_pitchfork lies at eta = 2)."""
    m = machine(0.9)
    r = continue_equilibria(m, "drive.speed", 0.9, 1.0, start_from="side 00")
    (c,) = two_parameter_curves(m, r, "unbalances[0].magnitude", 0.005, 0.02)
    assert c.type == "fold" and c.parameters == ("drive.speed", "unbalances[0].magnitude")
    assert c.values[0, 1] == 0.005 and c.values[-1, 1] == 0.02 and len(c.values) > 5
    w = c.values[:, 0]
    ref = [brentq(lambda s: D * s * 2 * MB * L - u * abs(1.0 - (1.0 + 2 * MB) * s * s + 1j * D * s), 0.5, 0.99,
                  xtol=1e-15) for u in c.values[:, 1]]
    np.testing.assert_allclose(w, ref, rtol=1e-9)
    assert np.all(np.diff(w) > 0)  # more unbalance: the fold moves towards the resonance at 1 / sqrt(M)
    assert np.all(c.values[:, 1] / (MB * L) < 2.0)
    # one curve point again by a one-parameter run at its unbalance
    k = 2 * len(c.values) // 3
    again = continue_equilibria(with_value(m, "unbalances[0].magnitude", c.values[k, 1]), "drive.speed", 0.85,
                                0.99, start_from="side 00")
    (fold,) = [s for s in again.branches[0].special_points if s.type == "fold"]
    assert abs(fold.value - c.values[k, 0]) < 1e-8 * fold.value
