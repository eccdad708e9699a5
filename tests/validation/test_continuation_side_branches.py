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
    assert [t for t, _ in a] == [t for t, _ in b] and len(a) >= 10
    assert np.allclose([v for _, v in a], [v for _, v in b], rtol=1e-8, atol=0)
