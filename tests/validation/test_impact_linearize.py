"""``ImpactRotor.linearize``: M, C, G, K of the free small motions (seed 001, eqs (2.2), (4.1)).

Checked against the compiled kernel (``state_matrix`` differentiates the right-hand side) and
against the structure the mechanics demands: M diagonal positive, G skew, C symmetric and
proportional to the membrane stiffness (Sorokin's internal friction), the non-symmetric part of K
equal to omega0 J C (internal friction seen from the rotating frame), and a Hamiltonian spectrum
(lambda and -lambda both eigenvalues) without internal friction.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.models import krasnov_crusher

_BASE = krasnov_crusher()
MODELS = {
    "general": _BASE,
    "translational": krasnov_crusher(translational=True),
    "slow, unequal membranes": replace(_BASE, rotor=replace(_BASE.rotor, spin_speed=80.0, stiffness_2=1.0e6,
                                                            internal_friction=0.05)),
}


def _kept(model):
    """State entries of the state matrix that the linearization covers."""
    return [0, 1, 4, 5] if model.translational else list(range(8))


@pytest.mark.parametrize("name", MODELS)
def test_first_order_form_is_the_kernel_state_matrix(name):
    model = MODELS[name]
    lin = model.linearize()
    A = model.state_matrix()[np.ix_(_kept(model), _kept(model))]
    assert np.max(np.abs(lin.A - A)) <= 1e-13 * np.max(np.abs(A))
    # sorted by imaginary part: the real parts of the translational pairs tie to round-off
    ev_lin, ev_ker = (np.array(sorted(np.linalg.eigvals(a), key=lambda z: (round(z.imag, 6), z.real)))
                      for a in (lin.A, A))  # fmt: skip
    assert np.allclose(ev_lin, ev_ker, rtol=1e-9, atol=1e-9 * np.max(np.abs(ev_ker)))
    assert np.all(ev_lin.real < 0)  # internal friction damps every free motion (seed 001, section 5)


@pytest.mark.parametrize("name", MODELS)
def test_matrix_structure(name):
    model = MODELS[name]
    lin = model.linearize()
    r = model.rotor
    n = lin.M.shape[0]
    assert n == (2 if model.translational else 4)
    assert np.array_equal(lin.M, np.diag(np.diag(lin.M))) and np.all(np.diag(lin.M) > 0)
    assert lin.M[0, 0] == r.mass and (n == 2 or lin.M[2, 2] == r.inertia_transverse)
    assert np.array_equal(lin.G, -lin.G.T) and lin.G[1, 0] == 2 * r.mass * r.spin_speed
    assert np.array_equal(lin.C, lin.C.T) and np.all(np.linalg.eigvalsh(lin.C) >= 0)
    # the circulatory part of K is omega0 J C: internal friction against the rotating membranes
    J = np.zeros((n, n))
    half = n // 2
    for k in range(half):
        u1, u2 = 2 * k, 2 * k + 1  # axes 1 and 2 of (u, t)
        J[u1, u2], J[u2, u1] = -1.0, 1.0
    skew = (lin.K - lin.K.T) / 2
    assert np.allclose(skew, r.spin_speed * J @ lin.C, rtol=1e-12, atol=1e-9 * np.max(np.abs(lin.K)))
    # its symmetric part: membranes minus the centrifugal softening (u: c - m omega0^2)
    assert np.isclose(lin.K[0, 0], r.stiffness - r.mass * r.spin_speed**2, rtol=1e-12)


def test_without_internal_friction_the_spectrum_is_hamiltonian():
    base = krasnov_crusher()
    model = replace(base, rotor=replace(base.rotor, internal_friction=0.0))
    lin = model.linearize()
    assert np.all(lin.C == 0) and np.array_equal(lin.K, lin.K.T)
    ev = np.linalg.eigvals(lin.A)
    # lambda and -lambda: here on the imaginary axis, so the frequencies come in +- pairs
    assert np.allclose(np.sort(ev.imag), np.sort(-ev.imag), rtol=1e-10)
    # above the critical speed the rotating-frame K is indefinite, yet gyroscopic terms stabilize
    assert np.min(np.linalg.eigvalsh(lin.K)) < 0 and np.max(np.abs(ev.real)) < 1e-8 * np.max(np.abs(ev))
