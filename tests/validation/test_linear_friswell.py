"""Friswell et al. (2010), Example 5.9.1: the two-disc rotor on isotropic bearings.

Sources and what they support
-----------------------------
* We could not establish the book's own table of natural frequencies reliably, so no number is
  attributed to the book here.
* Peer code: the ROSS port of this example (petrobras/ross, docs/examples/example_05_09_01.rst)
  prints the natural frequencies of the same model (six Timoshenko elements, annular discs of
  bore 50 mm, same steel) in rad/s: at rest 86.65811435, 274.31285391, 716.78631221 (each
  twice); at 4000 rev/min 85.389467, 87.7958637, 251.78460413, 294.71333087, 600.17936195,
  827.07536193. An independent implementation of the same equations, printed to 8-10 digits:
  we compare at 1e-7.
* Independent check: for an Euler-Bernoulli shaft the natural frequencies at rest are the roots
  of the exact (transcendental) dynamic stiffness of the three shaft spans, computed here
  without any FE interpolation; the FE model converges to them at fourth order.
* Invariants: equal pairs at rest, forward branches rise and backward fall, the undamped rotor
  is neutrally stable, mesh refinement converges, every eigen-solver gives the same answer.
"""

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize

from rotorlab.linear import RPM, STEEL, campbell, critical_speeds, modal
from rotorlab.linear._eigen import Solver
from rotorlab.linear.cases import friswell_rotor

ROSS_AT_REST = np.array([86.65811435, 86.65811435, 274.31285391, 274.31285391, 716.78631221,
                         716.78631221])
ROSS_AT_4000 = np.array([85.389467, 87.7958637, 251.78460413, 294.71333087, 600.17936195,
                         827.07536193])


def test_matches_ross_peer_output_at_rest_and_4000_rpm():
    s = friswell_rotor()
    np.testing.assert_allclose(modal(s, 0.0).natural_frequency[:6], ROSS_AT_REST, rtol=1e-7)
    np.testing.assert_allclose(modal(s, 4000 * RPM).natural_frequency[:6], ROSS_AT_4000,
                               rtol=1e-7)


def test_every_solver_gives_the_same_spectrum():
    s = friswell_rotor()
    speeds = RPM * np.array([0.0, 1500.0, 4000.0, 9000.0])
    ref = Solver(s, "dense").solve(speeds)
    f_ref = np.sort(np.abs(ref.eigenvalues.imag), axis=1)
    for method in ("isotropic-hermitian", "hermitian", "isotropic", "state-space"):
        sol = Solver(s, method).solve(speeds)
        f = np.sort(np.abs(sol.eigenvalues.imag), axis=1)
        np.testing.assert_allclose(f, f_ref, rtol=1e-8, err_msg=method)


def test_campbell_invariants_pairs_forward_backward_neutral_stability():
    ds = campbell(friswell_rotor(), RPM * np.linspace(0.0, 10000.0, 101), n_modes=8)
    assert ds.attrs["method"] == "isotropic-hermitian"
    f0 = ds.frequency.isel(speed=0).values
    np.testing.assert_allclose(f0[0::2], f0[1::2], rtol=1e-12)
    np.testing.assert_array_equal(ds.growth_rate.values, 0.0)
    assert bool(ds.stable.all())
    for k in range(8):
        code = np.unique(ds.whirl.values[:, k])
        assert code.size == 1 and code[0] in (1, -1)
        slope = np.diff(ds.frequency.values[:, k])
        assert np.all(slope * code[0] > 0), k  # forward rises, backward falls
    # each pair at rest splits into one backward and one forward branch
    assert np.all(ds.whirl.values[0, 0::2] + ds.whirl.values[0, 1::2] == 0)


def test_first_critical_speeds_are_the_campbell_crossings():
    s = friswell_rotor()
    ds = campbell(s, RPM * np.linspace(0.0, 4000.0, 101), n_modes=6, harmonics=(1, 2))
    exact = critical_speeds(s, harmonics=(1, 2), max_speed=4000 * RPM)
    np.testing.assert_allclose(np.sort(ds.critical_speed.values), exact.speed, rtol=1e-10)
    one = ds.critical_speed_rpm.values[ds.critical_harmonic.values == 1]
    np.testing.assert_allclose(one, [825.13381, 829.87446, 2487.75884, 2756.08756], rtol=1e-7)
    np.testing.assert_array_equal(ds.critical_whirl.values[ds.critical_harmonic.values == 1],
                                  [-1, 1, -1, 1])


def test_timoshenko_mesh_refinement_converges_monotonically():
    f = np.array([modal(friswell_rotor(n), 0.0).frequency[:8:2] for n in (6, 12, 24, 48)])
    steps = np.abs(np.diff(f, axis=0))
    assert np.all(steps[1:] < steps[:-1] / 3.0)
    # the book's six-element mesh is within 4e-4 of the converged frequencies (first 3 pairs)
    assert np.all(np.abs(f[0, :3] - f[-1, :3]) / f[-1, :3] < 4e-4)


def _eb_dynamic_stiffness(length, ei, rho_a, omega):
    """Exact Euler-Bernoulli span stiffness on (w1, w1', w2, w2') at frequency omega."""
    beta = (rho_a * omega ** 2 / ei) ** 0.25
    x = np.array([0.0, length])
    # w = a1 cos + a2 sin + a3 cosh + a4 sinh (beta x)
    def basis(xv, d):
        bx = beta * xv
        cols = {0: [np.cos(bx), np.sin(bx), np.cosh(bx), np.sinh(bx)],
                1: [-np.sin(bx), np.cos(bx), np.sinh(bx), np.cosh(bx)],
                2: [-np.cos(bx), -np.sin(bx), np.cosh(bx), np.sinh(bx)],
                3: [np.sin(bx), -np.cos(bx), np.sinh(bx), np.cosh(bx)]}[d]
        return beta ** d * np.array(cols)
    B = np.array([basis(x[0], 0), basis(x[0], 1), basis(x[1], 0), basis(x[1], 1)])
    E = ei * np.array([basis(x[0], 3), -basis(x[0], 2), -basis(x[1], 3), basis(x[1], 2)])
    return E @ np.linalg.inv(B)


def test_exact_dynamic_stiffness_self_check_static_limit():
    ei, L, rho_a = 1.3, 0.7, 2.1
    k = _eb_dynamic_stiffness(L, ei, rho_a, 1e-3)
    static = ei / L ** 3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                     [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L,
                                                                  4 * L * L]])
    np.testing.assert_allclose(k, static, rtol=1e-6, atol=1e-9)


def test_euler_bernoulli_fe_converges_to_the_exact_continuous_frequencies():
    from rotorlab.linear import RigidBody
    ei = STEEL.youngs_modulus * np.pi * 0.05 ** 4 / 64
    rho_a = STEEL.density * np.pi * 0.05 ** 2 / 4
    discs = [RigidBody.disc(0, D, 0.07, STEEL.density, inner_diameter=0.05) for D in (0.28, 0.35)]

    def det(omega):
        D = np.zeros((8, 8))
        for e in range(3):
            D[2 * e:2 * e + 4, 2 * e:2 * e + 4] += _eb_dynamic_stiffness(0.5, ei, rho_a, omega)
        for node, d in zip((1, 2), discs):
            D[2 * node, 2 * node] -= omega ** 2 * d.mass
            D[2 * node + 1, 2 * node + 1] -= omega ** 2 * d.diametral_inertia
        D[0, 0] += 1e6
        D[6, 6] += 1e6
        return np.linalg.det(D / 1e6)

    fe = {n: modal(friswell_rotor(n, shear=False, rotary_inertia=False)).natural_frequency[:8:2]
          for n in (6, 12, 24, 48)}
    exact = np.array([scipy.optimize.brentq(det, w * 0.99, w * 1.01, xtol=1e-13 * w)
                      for w in fe[48]])
    errors = np.array([np.abs(fe[n] - exact) / exact for n in (6, 12, 24, 48)])
    assert np.all(errors[1:] < errors[:-1] / 8.0)  # fourth order: ~16x per halving
    assert np.all(errors[-1] < 2e-7)


def test_anisotropic_bearings_example_5_9_2_variant():
    s = friswell_rotor(bearing_stiffness_y=0.8e6)
    assert not s.is_isotropic
    m0 = modal(s, 0.0)
    assert m0.frequency[1] / m0.frequency[0] > 1.01  # the pairs split at rest
    np.testing.assert_array_equal(m0.whirl[:4], 0)  # straight-line orbits at rest
    speeds = RPM * np.linspace(0.0, 4500.0, 46)
    ds = campbell(s, speeds, n_modes=6)
    assert ds.attrs["method"] == "hermitian"
    dense = Solver(s, "dense").solve(speeds)
    f_dense = np.sort(np.abs(dense.eigenvalues.imag), axis=1)[:, :6] / (2 * np.pi)
    np.testing.assert_allclose(np.sort(ds.frequency.values, axis=1), f_dense, rtol=1e-8)
    assert set(np.unique(ds.whirl.values[-1])) <= {-1, 0, 1}


def test_damped_bearings_example_5_9_5_variant_is_stable_with_positive_log_decrement():
    s = friswell_rotor(bearing_damping=3e3)
    speeds = RPM * np.linspace(0.0, 4000.0, 21)
    ds = campbell(s, speeds, n_modes=6)
    assert ds.attrs["method"] == "isotropic"
    assert bool(ds.stable.all())
    assert np.all(ds.log_decrement.values > 0)
    dense = Solver(s, "dense").solve(speeds)
    lam = dense.eigenvalues
    osc = lam.imag > 1e-6 * np.abs(lam)
    ld_dense = [np.sort(np.abs(lam[i, osc[i]].imag)) for i in range(speeds.size)]
    for i in range(speeds.size):
        f = np.sort(ds.frequency.values[i]) * 2 * np.pi
        idx = np.searchsorted(ld_dense[i], f - 1e-6 * f)
        np.testing.assert_allclose(ld_dense[i][idx], f, rtol=1e-8)


def test_dense_baseline_is_the_generalised_problem():
    s = friswell_rotor()
    om = 3000 * RPM
    n = s.n_dof
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-s.K, -om * s.G]])
    B = scipy.linalg.block_diag(np.eye(n), s.M)
    lam = scipy.linalg.eigvals(A, B)
    f = np.sort(lam.imag[lam.imag > 0])
    np.testing.assert_allclose(np.sort(modal(s, om).natural_frequency), f, rtol=1e-8)


@pytest.mark.parametrize("n", [3, 9])
def test_other_meshes_keep_discs_at_thirds(n):
    s = friswell_rotor(n)
    assert s.node_label[n // 3] == "disc 1" and s.node_label[2 * n // 3] == "disc 2"
    assert s.node_position[2 * n // 3] == pytest.approx(1.0)
    with pytest.raises(ValueError, match="multiple of 3"):
        friswell_rotor(4)
