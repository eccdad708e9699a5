"""Element matrices (Timoshenko shaft, rigid body, bearing, elastic connection) and assembly."""

import math

import numpy as np
import pytest

from rotorlab.linear import (
    STEEL,
    Bearing,
    ElasticConnection,
    LinearSystem,
    Material,
    RigidBody,
    ShaftElement,
    assemble,
    dof_index,
    shear_coefficient,
    uniform_shaft,
)


def _closed_forms(e: ShaftElement):
    """Timoshenko element matrices in closed form (Przemieniecki; Friswell et al. 2010, Ch. 5)."""
    p, L = e.shear_parameter, e.length
    rho, A, I = e.material.density, e.area, e.second_moment
    EI = e.material.youngs_modulus * I
    K = EI / (L ** 3 * (1 + p)) * np.array([
        [12, 6 * L, -12, 6 * L], [6 * L, (4 + p) * L * L, -6 * L, (2 - p) * L * L],
        [-12, -6 * L, 12, -6 * L], [6 * L, (2 - p) * L * L, -6 * L, (4 + p) * L * L]])
    a, b = 312 + 588 * p + 280 * p * p, (44 + 77 * p + 35 * p * p) * L
    c, d = 108 + 252 * p + 140 * p * p, -(26 + 63 * p + 35 * p * p) * L
    e2, f = (8 + 14 * p + 7 * p * p) * L * L, -(6 + 14 * p + 7 * p * p) * L * L
    MT = rho * A * L / (840 * (1 + p) ** 2) * np.array(
        [[a, b, c, d], [b, e2, -d, f], [c, -d, a, -b], [d, f, -b, e2]])
    g, h, k = (3 - 15 * p) * L, (4 + 5 * p + 10 * p * p) * L * L, (-1 - 5 * p + 5 * p * p) * L * L
    MR = rho * I / (30 * (1 + p) ** 2 * L) * np.array(
        [[36, g, -36, g], [g, h, -g, k], [-36, -g, 36, -g], [g, k, -g, h]])
    return K, MT, MR


@pytest.mark.parametrize("length,do,di", [(0.25, 0.05, 0.0), (0.05, 0.08, 0.03), (1.0, 0.02, 0.0)])
def test_timoshenko_matrices_match_closed_forms(length, do, di):
    e = ShaftElement(0, length, do, di, STEEL)
    M, K, R = e.plane_matrices()
    Kc, MT, MR = _closed_forms(e)
    np.testing.assert_allclose(K, Kc, rtol=1e-12, atol=1e-12 * np.abs(Kc).max())
    np.testing.assert_allclose(M, MT + MR, rtol=1e-12, atol=1e-12 * np.abs(M).max())
    np.testing.assert_allclose(R, MR, rtol=1e-12, atol=1e-12 * np.abs(MR).max())


def test_euler_bernoulli_limit_is_the_classical_consistent_element():
    e = ShaftElement(0, 0.3, 0.04, material=STEEL, shear=False, rotary_inertia=False)
    L = e.length
    M, K, _ = e.plane_matrices()
    m420 = e.mass / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L * L, 13 * L,
                                    -3 * L * L], [54, 13 * L, 156, -22 * L],
                                    [-13 * L, -3 * L * L, -22 * L, 4 * L * L]])
    np.testing.assert_allclose(M, m420, rtol=1e-12, atol=1e-15)
    assert e.shear_parameter == 0.0
    np.testing.assert_allclose(K[0, 0], 12 * STEEL.youngs_modulus * e.second_moment / L ** 3)


def test_shaft_element_structure():
    e = ShaftElement(3, 0.2, 0.05)
    assert e.nodes == (3, 4)
    M, G, K = e.M(), e.G(), e.K()
    np.testing.assert_allclose(G, -G.T)
    np.testing.assert_allclose(M, M.T)
    # rigid translation along x carries the element mass, rigid tilt gives no strain
    u = np.zeros(8)
    u[[0, 4]] = 1.0
    assert u @ M @ u == pytest.approx(e.mass, rel=1e-12)
    tilt = np.zeros(8)
    tilt[[0, 2, 4, 6]] = [0.0, 1.0, 0.2, 1.0]
    assert np.abs(K @ tilt).max() < 1e-6 * np.abs(K).max()
    # gyroscopic coupling = twice the rotary inertia (J = 2 I), between the planes
    _, _, R = e.plane_matrices()
    np.testing.assert_allclose(G[np.ix_([0, 2, 4, 6], [1, 3, 5, 7])], 2 * R)
    assert not ShaftElement(0, 0.2, 0.05, gyroscopic=False).G().any()


def test_shear_coefficient_solid_and_hollow():
    nu = 0.3
    assert shear_coefficient(nu) == pytest.approx(6 * (1 + nu) / (7 + 6 * nu))
    assert shear_coefficient(nu, 0.99) == pytest.approx(0.53, abs=0.01)  # thin tube ~ 1/2


@pytest.mark.parametrize("kwargs,match", [
    (dict(node=-1, length=1.0, outer_diameter=0.1), "ShaftElement.node"),
    (dict(node=0, length=0.0, outer_diameter=0.1), "ShaftElement.length"),
    (dict(node=0, length=1.0, outer_diameter=0.1, inner_diameter=0.1), "inner_diameter"),
    (dict(node=0, length=1.0, outer_diameter=0.1, material="steel"), "ShaftElement.material"),
])
def test_shaft_element_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ShaftElement(**kwargs)


def test_material_validation():
    with pytest.raises(ValueError, match="Material.density"):
        Material(2e11, 8e10, -1.0)


def test_rigid_body_and_disc():
    d = RigidBody.disc(4, 0.35, 0.07, 7810.0, inner_diameter=0.05)
    m = 7810.0 * math.pi / 4 * (0.35 ** 2 - 0.05 ** 2) * 0.07
    assert d.mass == pytest.approx(m)
    assert d.polar_inertia == pytest.approx(m * (0.35 ** 2 + 0.05 ** 2) / 8)
    assert d.diametral_inertia == pytest.approx(d.polar_inertia / 2 + m * 0.07 ** 2 / 12)
    still = RigidBody(0, 2.4, 0.018, 0.018, spinning=False)
    assert not still.G().any()
    with pytest.raises(ValueError, match="RigidBody.mass"):
        RigidBody(0, -1.0, 1.0)
    with pytest.raises(ValueError, match="RigidBody.node"):
        RigidBody(True, 1.0, 1.0)
    with pytest.raises(ValueError, match="inner_diameter"):
        RigidBody.disc(0, 0.1, 0.01, 7800.0, inner_diameter=0.2)


def test_bearing_defaults_cross_terms_and_two_nodes():
    b = Bearing(2, kxx=1e6, kxy=3e4, kyx=-2e4, cxx=50.0, cyx=1.0, k_tilt_x=7.0)
    assert (b.kyy, b.cyy, b.k_tilt_y) == (1e6, 50.0, 7.0)
    K, C = b.K(), b.C()
    assert (K[0, 1], K[1, 0], C[1, 0]) == (3e4, -2e4, 1.0)
    assert K[2, 2] == K[3, 3] == 7.0
    link = Bearing(0, kxx=5.0, node_b=3)
    assert link.nodes == (0, 3)
    np.testing.assert_allclose(link.K()[0, [0, 4]], [5.0, -5.0])
    with pytest.raises(ValueError, match="node_b must differ"):
        Bearing(1, kxx=1.0, node_b=1)
    with pytest.raises(ValueError, match="Bearing.cxx"):
        Bearing(1, kxx=1.0, cxx=math.nan)


def test_elastic_connection_planes_and_compliance():
    kx = np.array([[2e5, 1e3], [1e3, 50.0]])
    ky = 2 * kx
    e = ElasticConnection((4,), kx, ky)
    K = e.K()
    np.testing.assert_allclose(K[np.ix_([0, 2], [0, 2])], kx)
    np.testing.assert_allclose(K[np.ix_([1, 3], [1, 3])], ky)
    f = ElasticConnection.from_compliance((0,), np.linalg.inv(kx))
    np.testing.assert_allclose(f.stiffness_x, kx, rtol=1e-10)
    with pytest.raises(ValueError, match="stiffness_x must be symmetric"):
        ElasticConnection((0,), [[1.0, 2.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match=r"must have shape \(4, 4\)"):
        ElasticConnection((0, 1), kx)
    with pytest.raises(ValueError, match="distinct"):
        ElasticConnection((1, 1), np.eye(4))
    with pytest.raises(ValueError, match="damping_y needs damping_x"):
        ElasticConnection((0,), kx, damping_y=kx)


def test_assemble_positions_labels_and_errors():
    s = assemble([*uniform_shaft(3, 0.9, 0.03), Bearing(0, kxx=1e6), Bearing(3, kxx=1e6)])
    np.testing.assert_allclose(s.node_position, [0.0, 0.3, 0.6, 0.9])
    assert s.node_label == ("0", "1", "2", "3")
    assert s.dof_direction[:4] == ("x", "y", "phi_x", "phi_y")
    assert s.dof_unit[:4] == ("m", "m", "rad", "rad")
    assert dof_index(3, "phi_y") == 15
    with pytest.raises(ValueError, match="n_nodes = 2"):
        assemble(uniform_shaft(3, 0.9, 0.03), n_nodes=2)
    with pytest.raises(ValueError, match="positive definite"):
        assemble([Bearing(0, kxx=1.0)])  # no mass at all
    with pytest.raises(ValueError, match="at least one element"):
        assemble([])

    class Bad:
        nodes = (0,)

        def M(self):
            return np.eye(3)

        C = K = G = M

    with pytest.raises(ValueError, match=r"Bad.M\(\) must have shape"):
        assemble([Bad()])


def test_linear_system_validation():
    eye = np.eye(4)
    with pytest.raises(ValueError, match="multiple of 4"):
        LinearSystem(M=np.eye(3), C=np.eye(3), G=np.eye(3), K=np.eye(3))
    with pytest.raises(ValueError, match="skew-symmetric"):
        LinearSystem(M=eye, C=0 * eye, G=eye, K=eye)
    with pytest.raises(ValueError, match="M must be symmetric"):
        LinearSystem(M=eye + np.triu(np.ones((4, 4)), 1), C=0 * eye, G=0 * eye, K=eye)
    with pytest.raises(ValueError, match=r"K must have shape \(4, 4\)"):
        LinearSystem(M=eye, C=0 * eye, G=0 * eye, K=np.eye(8))
    with pytest.raises(ValueError, match="node_label must have 1"):
        LinearSystem(M=eye, C=0 * eye, G=0 * eye, K=eye, node_label=("a", "b"))
    s = LinearSystem(M=eye, C=0 * eye, G=0 * eye, K=eye)
    with pytest.raises(ValueError):
        s.M[0, 0] = 2.0  # read-only
    assert s.length_scale == 1.0
    np.testing.assert_allclose(s.dynamic_stiffness(1.0, 2j), (1 - 4) * eye)
