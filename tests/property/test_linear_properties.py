"""Hypothesis properties of random rotors: matrix structure, spectra, stability, linearity."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorlab.linear import (
    Bearing,
    RigidBody,
    ShaftElement,
    Unbalance,
    assemble,
    campbell,
    compliance_to_stiffness,
    modal,
    stiffness_to_compliance,
    unbalance_response,
)
from rotorlab.linear._eigen import Solver

SETTINGS = settings(max_examples=25, deadline=None)


@st.composite
def rotors(draw, isotropic=None, damped=False):
    n_el = draw(st.integers(1, 4))
    parts = []
    for i in range(n_el):
        do = draw(st.floats(0.02, 0.1))
        di = do * draw(st.floats(0.0, 0.8))
        parts.append(ShaftElement(i, draw(st.floats(0.05, 0.5)), do, di))
    for node in range(n_el + 1):
        if draw(st.booleans()):
            D = draw(st.floats(0.12, 0.5))
            parts.append(RigidBody.disc(node, D, draw(st.floats(0.01, 0.1)), 7800.0,
                                        inner_diameter=0.02))
    iso = draw(st.booleans()) if isotropic is None else isotropic
    for node in (0, n_el):
        kxx = draw(st.floats(1e5, 1e8))
        kyy = kxx if iso else kxx * draw(st.floats(0.3, 3.0))
        c = draw(st.floats(1.0, 1e3)) if damped else 0.0
        parts.append(Bearing(node, kxx=kxx, kyy=kyy, cxx=c))
    return assemble(parts)


@SETTINGS
@given(rotors())
def test_matrix_structure(s):
    np.testing.assert_allclose(s.M, s.M.T, atol=0)
    np.testing.assert_allclose(s.K, s.K.T, rtol=0, atol=1e-9 * np.abs(s.K).max())
    np.testing.assert_allclose(s.G, -s.G.T, atol=0)
    assert np.linalg.eigvalsh(s.M).min() > 0
    assert np.linalg.eigvalsh(s.K).min() > -1e-9 * np.abs(s.K).max()


@SETTINGS
@given(rotors(), st.floats(0.0, 2000.0))
def test_undamped_rotor_is_neutrally_stable_and_every_solver_agrees(s, speed):
    ref = Solver(s, "dense").solve([speed])
    lam = ref.eigenvalues[0]
    assert np.all(np.abs(lam.real) <= 1e-6 * np.abs(lam))
    f_ref = np.sort(np.abs(lam.imag))[:6]
    methods = ["hermitian", "state-space"] + (["isotropic-hermitian", "isotropic"]
                                             if s.is_isotropic else [])
    for method in methods:
        sol = Solver(s, method).solve([speed])
        f = np.sort(np.abs(sol.eigenvalues[0].imag))[:6]
        np.testing.assert_allclose(f, f_ref, rtol=1e-6, err_msg=method)
        if method in ("hermitian", "isotropic-hermitian"):
            np.testing.assert_array_equal(sol.eigenvalues[0].real, 0.0)


@SETTINGS
@given(rotors(isotropic=True), st.floats(1.0, 2000.0))
def test_isotropic_pairs_at_rest_and_pure_whirl_at_speed(s, speed):
    f0 = modal(s, 0.0).frequency
    np.testing.assert_allclose(f0[0::2], f0[1::2], rtol=1e-9)
    md = modal(s, speed)
    np.testing.assert_allclose(np.abs(md.whirl_index), 1.0, atol=1e-9)
    assert set(md.whirl.tolist()) <= {1, -1}


@SETTINGS
@given(rotors(damped=True), st.floats(0.0, 2000.0))
def test_direct_bearing_damping_never_destabilises(s, speed):
    md = modal(s, speed)
    assert md.is_stable
    assert np.all(md.log_decrement >= -1e-9)


@SETTINGS
@given(rotors(), st.floats(10.0, 2000.0), st.floats(0.0, 6.3), st.floats(0.0, 6.3))
def test_unbalance_response_superposes(s, speed, p1, p2):
    u1, u2 = Unbalance(0, 1e-4, p1), Unbalance(s.n_nodes - 1, 3e-4, p2)
    a = unbalance_response(s, [speed], [u1])
    b = unbalance_response(s, [speed], [u2])
    ab = unbalance_response(s, [speed], [u1, u2])
    qa = a.response_real + 1j * a.response_imag
    qb = b.response_real + 1j * b.response_imag
    qab = ab.response_real + 1j * ab.response_imag
    np.testing.assert_allclose(qab, qa + qb, rtol=1e-9, atol=1e-12 * float(np.abs(qab).max()))


@SETTINGS
@given(rotors(), st.floats(100.0, 3000.0))
def test_campbell_branches_lie_on_the_dense_spectrum(s, top):
    speeds = np.linspace(0.0, top, 9)
    ds = campbell(s, speeds, n_modes=4, refine=False)
    dense = Solver(s, "dense").solve(speeds)
    full = np.abs(dense.eigenvalues.imag) / (2 * np.pi)
    for i in range(speeds.size):
        gap = np.abs(ds.frequency.values[i][:, None] - full[i][None, :]).min(axis=1)
        assert np.all(gap <= 1e-6 * ds.frequency.values[i])
    assert np.all(np.abs(ds.whirl_index.values) <= 1.0 + 1e-12)


@SETTINGS
@given(st.integers(1, 6), st.integers(0, 2**32 - 1))
def test_compliance_stiffness_inverse_pair(n, seed):
    rng = np.random.default_rng(seed)
    a = rng.standard_normal((n, n))
    k = a @ a.T + n * np.eye(n)
    back = compliance_to_stiffness(stiffness_to_compliance(k))
    np.testing.assert_allclose(back, k, rtol=1e-8, atol=1e-10 * np.abs(k).max())
