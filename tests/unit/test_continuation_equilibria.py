"""Continuation of a machine's steady motions (issue 25, equilibria) on the planar machine with two
balls, whose steady motions have closed forms.

References: the balanced ball angles psi = +-arccos(-U / (2 m l)) of two equal balls against a
static unbalance U (force balance; Filimonikhin's balanced motion, README), which exist for
2 m l > U: the balanced state is born at the ball mass m* = U / (2 l) from the balls-together
motion (both opposite the unbalance, z = 0 there: a pitchfork). The side motions with both
balls on one side (seed 003 eq. (13) with the support damping, rotorlab.steady._motions) exist
while ``d Omega |s| <= M1 e |D|``, ``D = c - M Omega^2 + i d Omega``, s = 2 m l: the pair 00/11
meets at a fold where equality holds. Hopf points are where today's stability chart
(``machine_steady``, exact eigenvalues on a grid) has its largest real part cross zero.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorlab.analyses._machine_steady import machine_motions, machine_steady
from rotorlab.continuation import continue_equilibria, starting_motions, with_value
from rotorlab.linear import LinearSystem
from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance

# the planar machine of test_machine_analyses.py (same compiled kernel): M1 = 1 kg, c = 1 N/m,
# d = 0.02 N s/m, U = 0.01 kg m, two 20 g balls on a 1 m race
S = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
                 G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
U, L, MB, D = 0.01, 1.0, 0.02, 0.02


def machine(speed=2.0):
    return Machine(S, races=(BallRace(0, L, (Ball(MB, damping=0.01),) * 2),), unbalances=(Unbalance(0, U),),
                   drive=ConstantSpeed(speed), n_modes=2)


def test_balanced_branch_in_ball_mass_closed_form_angles_and_pitchfork():
    r = continue_equilibria(machine(), "ball_mass", 0.02, 0.003)
    main = r.branches[0]
    assert main.label == "main+" and main.end == "bound"
    m = main.values
    psi = np.abs(main.extra["ball_angle"])
    np.testing.assert_allclose(psi, np.arccos(-U / (2 * m * L))[:, None] * np.ones(2), atol=1e-9)
    assert np.all(main.amplitude < 1e-12)
    (bp,) = main.special_points
    assert bp.type == "branch" and abs(bp.value - U / (2 * L)) < 1e-8 * U / (2 * L)
    assert "5 g" in bp.description and "symmetry-breaking" in bp.description
    # the switched branches: balls together (psi_1 = psi_2), on both sides of m*, vibrating
    together = [b for b in r.branches if b.label.startswith("balls together")]
    assert len(together) == 2 and len(r.branches) == 3  # main- is the same curve (through the pitchfork)
    lo, hi = sorted(together, key=lambda b: b.values[-1])
    assert lo.values[-1] == pytest.approx(0.003) and hi.values[-1] == pytest.approx(0.02)
    for b in together:
        a = b.extra["ball_angle"]
        np.testing.assert_allclose(np.angle(np.exp(1j * (a[1:, 0] - a[1:, 1]))), 0.0, atol=1e-9)  # [0]: the branch point
        assert b.values[0] == pytest.approx(U / (2 * L), rel=1e-8) and np.all(b.amplitude[1:] > 0)


def test_hopf_point_is_the_stability_chart_eigenvalue_crossing():
    m = machine()
    r = continue_equilibria(m, "drive.speed", 0.5, 3.0, start_from="main+")
    (b,) = r.branches
    (hopf,) = [s for s in b.special_points if s.type == "hopf"]

    def growth(w):  # today's chart at one speed: the largest real part of the exact eigenvalues
        return float(machine_steady(m, [w]).max_real_eigenvalue[0])

    w0 = brentq(growth, 1.2, 2.5, xtol=1e-13, rtol=1e-14)
    assert abs(hopf.value - w0) < 1e-6 * w0
    ev = with_value(m, "drive.speed", w0).linearize(b.states[0]).eigenvalues
    assert hopf.frequency == pytest.approx(abs(ev[np.argmax(ev.real)].imag), rel=1e-6)
    assert not b.stable[b.values < w0 - 1e-3].any() and b.stable[b.values > w0 + 1e-3].all()
    rpm = w0 * 30 / math.pi
    assert hopf.description.startswith(f"balancing becomes stable above {rpm:.4g} rpm")
    d = r.to_dict()["branches"][0]
    assert d["kind"] == "equilibrium" and d["special_points"][0]["drive.speed"] == hopf.value


def test_side_motions_fold_where_the_closed_form_says():
    m = machine(0.9)
    r = continue_equilibria(m, "drive.speed", 0.9, 1.0, start_from="side 00")
    (b,) = r.branches
    (fold,) = [s for s in b.special_points if s.type == "fold"]
    mt, s = 1.0 + 2 * MB, 2 * MB * L

    def gap(w):  # d Omega |s| - M1 e |D|: zero at the fold of side 00 / side 11
        return D * w * s - U * abs(1.0 - mt * w * w + 1j * D * w)

    w0 = brentq(gap, 0.9, 0.99, xtol=1e-14)
    assert abs(fold.value - w0) < 1e-8 * w0
    assert b.values[-1] == pytest.approx(0.9) and b.end == "bound"  # back to 0.9 as side 11
    assert "turns back" in fold.description


def test_starting_motions_are_the_seed_classification():
    m = machine(2.0)
    got = dict(starting_motions(m, "all"))
    ref = machine_motions(m)
    assert sorted(got) == sorted(str(x) for x in ref.label.values)
    for j, lab in enumerate(ref.label.values):
        psi = got[str(lab)][4:6]
        np.testing.assert_allclose(np.angle(np.exp(1j * (psi - ref.ball_angle.values[j]))), 0.0, atol=1e-7)


def test_bad_parameter_and_no_frame_say_why():
    m = machine()
    with pytest.raises(ValueError, match="'drive.sped' is not a continuation parameter"):
        continue_equilibria(m, "drive.sped", 1.0, 2.0)
    with pytest.raises(ValueError, match=r"'races\[3\].balls\[0\].mass' is not a continuation parameter"):
        with_value(m, "races[3].balls[0].mass", 0.1)
    with pytest.raises(ValueError, match=r"races\[0\].balls\[1\].mass = -0.1: must be > 0 kg"):
        with_value(m, "races[0].balls[1].mass", -0.1)
    with pytest.raises(ValueError, match="start and stop must be finite and differ"):
        continue_equilibria(m, "drive.speed", 1.0, 1.0)
    K = S.K.copy()
    K[1, 1] = 1.3
    aniso = Machine(LinearSystem(M=S.M, C=S.C, G=S.G, K=K), races=m.races, unbalances=m.unbalances,
                    drive=ConstantSpeed(2.0))
    with pytest.raises(ValueError, match="no co-rotating equilibria to continue: the structure is anisotropic"):
        continue_equilibria(aniso, "drive.speed", 1.0, 2.0)
    with pytest.raises(ValueError, match="no balanced steady motion at ball_mass = 0.004"):
        continue_equilibria(m, "ball_mass", 0.004, 0.003)


def test_balls_with_friction_continue_the_smooth_part_and_say_so():
    """Issue 25: equilibria of the smooth part of a model with events. With Coulomb and rolling
    friction on the balls (stick-slip: events) the steady motions are those of the machine
    without it, balls resting on their races with no friction torque needed; the result says so
    (refused before). The balanced branch and its pitchfork at U / (2 l) are those of the
    smooth machine, to the bit."""
    from dataclasses import replace

    smooth = machine()
    rough = replace(smooth, races=(BallRace(0, L, (Ball(MB, damping=0.01, coulomb=0.05, rolling=1e-3),) * 2),))
    assert rough.has_friction and rough.why_no_rotating_frame() is not None
    a = continue_equilibria(rough, "ball_mass", 0.02, 0.003, switch=False)
    b = continue_equilibria(smooth, "ball_mass", 0.02, 0.003, switch=False)
    np.testing.assert_array_equal(a.branches[0].values, b.branches[0].values)
    np.testing.assert_array_equal(a.branches[0].stable, b.branches[0].stable)
    (bp,) = a.branches[0].special_points
    assert bp.type == "branch" and abs(bp.value - U / (2 * L)) < 1e-8 * U / (2 * L)
    (note,) = a.notes
    assert "friction is left out" in note and "smooth part" in note and "stick-slip" in note
    assert a.to_dict()["notes"] == [note] and "notes" not in b.to_dict()
