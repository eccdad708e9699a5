"""Every side branch of the two-plane balancer ``rcfw-two-plane`` over 0.5-6 rad/s (issue 25).

The side motions (balls on the line of the rotor's deflection, seeds 002/003) sweep through the
cylindrical critical speed, where the whirl grows twenty-fold and the balls' common phase turns
slowly: a branch must still end at a bound of the range or close, not run out of points.

References, all independent of the continuation: a special point is what its name says at the
located state (a fold: the state Jacobian dF/dx singular; a branch point: the full Jacobian
[dF/dx dF/dlam] rank deficient; a Hopf point: a complex pair on the imaginary axis, from the
co-rotating linearization's eigenvalues), each to the round-off of the central differences
(1e-6); the rotor, its supports (+-3 m) and races (+-2 m) are symmetric about the mid-plane and
the unbalance lies in it, so the branch of side 0001 (race 1's balls towards the deflection, race
2's apart) and its mirror image side 0100 carry the same special points at the same speeds.
"""

import numpy as np
import pytest

from rotorlab.analyses import build_model
from rotorlab.continuation import MachineEquilibria, as_machine, continue_equilibria, starting_motions, with_value
from rotorlab.continuation._equilibria import equilibrium_settings
from rotorlab.io import load_case


@pytest.fixture(scope="module")
def side():
    m = with_value(as_machine(build_model(load_case("rcfw-two-plane").model)), "drive.speed", 0.5)
    return m, continue_equilibria(m, "drive.speed", 0.5, 6.0, start_from="side")


def test_every_side_branch_reaches_a_bound_or_closes(side):
    """Before, all 16 ended at max_points (1000) between 0.97 and 1.07 rad/s."""
    m, r = side
    assert {b.end for b in r.branches} <= {"bound", "closed"}, [(b.label, b.end) for b in r.branches]
    # every side motion at 0.5 rad/s is a branch's end at 0.5 rad/s, up to identical balls exchanged
    nz = m.n_coordinates
    ends = [b.states[i] for b in r.branches for i in (0, -1) if b.values[i] == pytest.approx(0.5, abs=1e-12)]
    swaps = [[0, 1, 2, 3], [1, 0, 2, 3], [0, 1, 3, 2], [1, 0, 3, 2]]

    def apart(y, e, perm):  # z in units of the unbalance's 0.03 m, ball angles modulo 2 pi
        dz = np.abs(y[:nz] - e[:nz]).max() / 0.03
        dpsi = np.abs(np.angle(np.exp(1j * (y[2 * nz:2 * nz + 4][perm] - e[2 * nz:2 * nz + 4])))).max()
        return max(dz, dpsi)

    starts = starting_motions(m, "side")
    assert len(starts) == 16
    for label, y in starts:
        assert min(apart(y, e, p) for e in ends for p in swaps) < 1e-6, label


def test_special_points_are_unique_and_what_they_say(side):
    m, r = side
    prob = MachineEquilibria(m, ("drive.speed",))
    n = prob.n
    checked = 0
    for b in r.branches:
        pts = b.special_points
        for i, a in enumerate(pts):
            for c in pts[i + 1:]:
                assert not (a.type == c.type and abs(a.value - c.value) <= 1e-6 * a.value), (b.label, a, c)
            if "not converged" in a.description:
                continue
            u = np.concatenate([prob.unknowns(a.state), [a.value]])
            j = prob.jacobian(u)
            if a.type == "fold":
                s = np.linalg.svd(j[:, :n], compute_uv=False)
                assert s[-1] <= 1e-6 * s[0], (b.label, a.value, s[-1] / s[0])
            elif a.type == "branch":
                s = np.linalg.svd(j, compute_uv=False)
                assert s[-1] <= 1e-6 * s[0], (b.label, a.value, s[-1] / s[0])
            else:
                ev = prob.eigenvalues(u)
                pair = ev[np.argmin(np.abs(ev.real) + (np.abs(ev.imag) < 1e-9))]
                assert abs(pair.real) <= 1e-6 * abs(ev).max() and abs(pair.imag) > 1e-6, (b.label, a.value, pair)
            checked += 1
    assert checked >= 20


def test_mirror_image_branches_have_the_same_special_points(side):
    _, r = side
    got = {b.label: [(s.type, s.value) for s in b.special_points] for b in r.branches}
    a, b = got["side 0001"], got["side 0100"]
    assert [t for t, _ in a] == [t for t, _ in b] and len(a) >= 4
    assert np.allclose([v for _, v in a], [v for _, v in b], rtol=1e-8, atol=0)


def test_no_jump_onto_a_neighbouring_branch_every_point_located(side):
    """Side 0001 passes, near 0.983 rad/s, within a step (0.025, scaled) of a neighbouring branch.
    Before, a step landed on it (and a later one jumped back): two branch points "location not
    converged" on side 0001 / side 0100 (put at 0.961 rad/s, outside the step 0.983-0.993 that
    bracketed it, and at 0.988 rad/s in the second jump's step). Reference: the same branch
    continued with steps half as long has the same folds, to the location tolerance (it also
    sees a Hopf point 4e-6 rad/s from the first fold, which the longer steps pass over: two
    crossings within one step); the switched branch leaves side 0011 with the balls of a race
    apart."""
    m, r = side
    for b in r.branches:
        for sp in b.special_points:
            assert "not converged" not in sp.description, (b.label, sp.value, sp.description)
    (one,) = [b for b in r.branches if b.label == "side 0001"]
    fine = continue_equilibria(m, "drive.speed", 0.5, 6.0, start_from="side 0001", switch=False,
                               settings=equilibrium_settings(0.5, 6.0, ds_max=0.025, max_points=4000)).branches[0]

    def folds(b):  # two folds within 1e-6 rad/s are one (the branch turns back and forth within that)
        v = [s.value for s in b.special_points if s.type == "fold"]
        return [x for k, x in enumerate(v) if k == 0 or abs(x - v[k - 1]) > 1e-6]

    assert len(folds(one)) == 4 and [s.type for s in one.special_points] == ["fold"] * 4
    np.testing.assert_allclose(folds(fine), folds(one), rtol=1e-8, atol=0)
    assert fine.end == one.end == "bound" and fine.values[-1] == one.values[-1] == 0.5
    (new,) = [b for b in r.branches if b.label.startswith("balls apart (from side 0011 at")]
    (bp,) = [s for b in r.branches if b.label == "side 0011" for s in b.special_points if s.type == "branch"]
    assert new.values[0] == bp.value and bp.value == pytest.approx(1.2439, abs=1e-4)
    psi = new.extra["ball_angle"][1:]
    gap = np.maximum(np.abs(np.angle(np.exp(1j * (psi[:, 0] - psi[:, 1])))),
                     np.abs(np.angle(np.exp(1j * (psi[:, 2] - psi[:, 3])))))
    assert np.all(gap > 1e-6) and new.end == "bound"
