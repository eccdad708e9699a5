"""Mode tracking through crossings: branches keep their identity (no swapping).

A rotor made of two uncoupled parts has exactly crossing branches: a body on anisotropic
springs with speed-independent frequencies 100 and 110 rad/s, and a gyroscopic disc whose
backward tilting frequency falls from 141 rad/s through both. Sorting by frequency would swap
the branches at each crossing; tracking by mode shape must not.
"""

import numpy as np

from rotorlab.linear import Bearing, RigidBody, assemble, campbell, track_modes


def _crossing_rotor():
    return assemble([
        RigidBody(0, 1.0, 1e-4), Bearing(0, kxx=1e4, kyy=1.21e4, k_tilt_x=1e4),
        RigidBody(1, 1e-4, 1.0, 1.8), Bearing(1, kxx=1e6, k_tilt_x=2e4),
    ])


def test_branches_pass_through_each_other():
    s = _crossing_rotor()
    assert not s.is_isotropic
    speeds = np.linspace(0.0, 400.0, 81) + 0.37  # no grid point exactly at a crossing
    ds = campbell(s, speeds, n_modes=4, refine=False)
    assert ds.attrs["method"] == "hermitian"
    w = 2 * np.pi * ds.frequency.values
    flat = [k for k in range(4) if np.ptp(w[:, k]) < 1e-6]
    assert sorted(np.round(w[0, flat], 6)) == [100.0, 110.0]
    backward = [k for k in range(4) if np.all(np.diff(w[:, k]) < 0)]
    assert len(backward) == 1
    b = w[:, backward[0]]
    assert b[0] > 110.0 and b[-1] < 100.0  # it really crosses both
    assert np.all(ds.whirl.values[1:, backward[0]] == -1)
    # sorting by frequency would have swapped: the sorted second branch is not constant
    assert np.ptp(np.sort(w, axis=1)[:, 1]) > 5.0


def test_track_modes_follows_shapes_not_order():
    # two candidates whose eigenvalues cross at step 2 and whose vectors keep their identity
    e1, e2 = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    track = np.array([[e1, e2], [e1, e2], [e2, e1], [e2, e1]], dtype=complex)
    lam = 1j * np.array([[1.0, 2.0], [1.4, 1.6], [1.4, 1.6], [1.0, 2.0]])
    order = track_modes(track, lam, 2)
    np.testing.assert_array_equal(order, [[0, 1], [0, 1], [1, 0], [1, 0]])


def test_track_modes_rejects_bad_counts():
    import pytest

    track = np.ones((2, 3, 3), dtype=complex)
    with pytest.raises(ValueError, match="n_modes must be an integer in"):
        track_modes(track, np.ones((2, 3)), 4)
