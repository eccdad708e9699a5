"""The composed machine model (issue 12): equivalence, exact balance, invariants, vectorisation.

References for the numbers: the planar special case is ``jeffcott_balls`` (itself checked against
Zhakash et al. 2024 and Filimonikhin & Filimonikhina in tests/validation); the balanced state of
two equal balls against a static unbalance U at their plane is psi = +-arccos(U / (2 m l))
(force balance ``U + 2 m l cos psi = 0`` along the unbalance, the closed form of Filimonikhin's
balanced motion); the energy identities follow from Lagrange's equations (module docstring of
:mod:`rotorlab.models._machine`).
"""

import math

import numpy as np
import pytest

from rotorlab.integrate import SaveAt, StepControl, solve, solve_ensemble
from rotorlab.linear import LinearSystem
from rotorlab.models import (
    Ball,
    BallParams,
    BallRace,
    ConstantSpeed,
    Gravity,
    HillRunUp,
    JeffcottBalls,
    LinearRamp,
    Machine,
    Motor,
    RotorParams,
    Unbalance,
)

M1, ECC, STIFF, DAMP = 1.0, 0.01, 1.0, 0.02
BM, BL, BC = 0.02, 1.0, 0.01


def planar_structure(kx=STIFF, ky=STIFF, d=DAMP, tilt_inertia=0.3, tilt_stiffness=5.0):
    return LinearSystem(M=np.diag([M1, M1, tilt_inertia, tilt_inertia]),
                        C=np.diag([d, d, 0.0, 0.0]), G=np.zeros((4, 4)),
                        K=np.diag([kx, ky, tilt_stiffness, tilt_stiffness]))


def planar_pair(speed, **kw):
    """The same machine as ``machine`` (4 DOFs, or 2 modes) and as ``jeffcott_balls``."""
    balls = (Ball(BM, inertia=1e-3, damping=BC), Ball(1.1 * BM, damping=0.9 * BC))
    mac = Machine(planar_structure(), races=(BallRace(0, BL, balls),),
                  unbalances=(Unbalance(0, M1 * ECC),), drive=speed, **kw)
    jb = JeffcottBalls(RotorParams(M1, ECC, STIFF, DAMP),
                       (BallParams(BM, BL, BM * BL**2 + 1e-3, BC), BallParams(1.1 * BM, BL, None, 0.9 * BC)),
                       speed=speed)
    return mac, jb


def to_machine(mac, yj):
    """Map a jeffcott_balls state [x, y, vx, vy, phi, w] to the machine's state."""
    y = np.zeros(mac.n_state)
    nz = mac.n_coordinates
    if mac.n_modes is None:
        y[[0, 1]], y[[nz, nz + 1]] = yj[:2], yj[2:4]
    else:  # q = Phi^T M x for the x/y modes
        sel = mac.basis[[0, 1], :]  # x = Phi[0] q, y = Phi[1] q
        y[:nz] = np.linalg.lstsq(sel, yj[:2], rcond=None)[0]
        y[nz:2 * nz] = np.linalg.lstsq(sel, yj[2:4], rcond=None)[0]
    y[2 * nz:] = yj[4:]
    return y


def from_machine(mac, ym):
    q = mac.displacements(ym)
    nz = mac.n_coordinates
    v = ym[nz:2 * nz] @ mac.basis.T
    return np.concatenate([q[:2], v[:2], ym[2 * nz:]])


def assert_same_rhs(mac, jb, seed, n, t_max):
    """The machine's right-hand side is jeffcott_balls' to 1e-12 at ``n`` random times in
    [0, t_max] and random (normal) states."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        t = rng.uniform(0.0, t_max)
        yj = rng.normal(size=8)
        fm = from_machine(mac, mac.rhs(t, to_machine(mac, yj)))
        fj = jb.rhs(t, yj)
        np.testing.assert_allclose(fm, fj, rtol=0, atol=1e-12 * np.abs(fj).max())


@pytest.mark.parametrize("n_modes", [None, 2])
@pytest.mark.parametrize("speed", [ConstantSpeed(2.5), LinearRamp(0.5, 3.0, 10.0)])
def test_planar_machine_is_jeffcott_balls_rhs(speed, n_modes):
    mac, jb = planar_pair(speed, n_modes=n_modes)
    assert_same_rhs(mac, jb, seed=7, n=40, t_max=20.0)


def test_planar_machine_is_jeffcott_balls_trajectory():
    mac, jb = planar_pair(ConstantSpeed(2.5), n_modes=2)
    yj0 = jb.initial_state([0.3, 2.0])
    ctl = StepControl(rtol=1e-10, atol=1e-12)
    sj = solve(jb, yj0, (0.0, 60.0), control=ctl)
    sm = solve(mac, to_machine(mac, yj0), (0.0, 60.0), control=ctl)
    np.testing.assert_allclose(from_machine(mac, sm.y_final), sj.y_final, rtol=0, atol=1e-7)


def test_planar_machine_under_a_hill_run_up_follows_the_profile_and_is_jeffcott_balls():
    """A Hill run-up omega(t) = omega_max t^n / (t_half^n + t^n) through the critical speed
    p = sqrt(c / (M1 + m1 + m2)) ~ 0.98 rad/s: the machine's kernel reads the closed-form spin
    speed and acceleration and theta = int omega dt (quadrature here), its right-hand side is
    jeffcott_balls' on random states and its trajectory is jeffcott_balls' (the one kernel a
    Hill machine needs: the profile kind is compile-time)."""
    from scipy.integrate import quad

    from rotorlab._kernels.speed import profile

    wmax, th, n = 2.5, 8.0, 3.0
    hill = HillRunUp(wmax, th, n)
    mac, jb = planar_pair(hill, n_modes=2)
    p, k = mac.to_array(), mac.layout.offsets["speed"]
    for t in (0.5, 4.0, 8.0, 13.0, 40.0):
        w = wmax * t**n / (th**n + t**n)
        dw = wmax * n * th**n * t ** (n - 1) / (th**n + t**n) ** 2
        theta = quad(lambda u: wmax * u**n / (th**n + u**n), 0.0, t, epsabs=0, epsrel=1e-13)[0]
        np.testing.assert_allclose(profile(t, p, k), (theta, w, dw), rtol=1e-12)
    assert wmax * 8.0**n / (th**n + 8.0**n) == wmax / 2  # t_half: half the final speed
    assert_same_rhs(mac, jb, seed=11, n=20, t_max=40.0)
    yj0 = jb.initial_state([0.3, 2.0])
    ctl = StepControl(rtol=1e-10, atol=1e-12)
    sj = solve(jb, yj0, (0.0, 40.0), control=ctl)
    sm = solve(mac, to_machine(mac, yj0), (0.0, 40.0), control=ctl)
    assert sj.status == 0 and sm.status == 0
    np.testing.assert_allclose(from_machine(mac, sm.y_final), sj.y_final, rtol=0, atol=1e-7)


def two_ball_balanced(kx, ky, speed):
    """Two equal balls on the planar structure, kept in its two lowest modes: the x and y
    translations exactly (diagonal, uncoupled structure; the tilt modes, 5 / 0.3 >> ky, carry no
    force), and the layout of :func:`planar_pair` with ``n_modes=2`` (one compiled copy)."""
    u = M1 * ECC
    mac = Machine(planar_structure(kx, ky), races=(BallRace(0, BL, (Ball(BM, damping=BC),) * 2),),
                  unbalances=(Unbalance(0, u),), drive=ConstantSpeed(speed), n_modes=2)
    assert np.abs(mac.basis[2:]).max() < 1e-12 and abs(np.linalg.det(mac.basis[:2])) > 0.5  # x, y exactly
    psi = math.acos(-u / (2 * BM * BL))  # U + 2 m l cos(psi) = 0
    return mac, np.array([psi, -psi])


def test_anisotropic_support_balanced_state_has_zero_vibration():
    mac, psi = two_ball_balanced(1.0, 2.7, 3.1)  # kx != ky: no co-rotating equilibrium exists
    assert mac.why_no_rotating_frame().startswith("the structure is anisotropic")
    np.testing.assert_allclose(mac.balanced_angles(psi + 0.1) % (2 * np.pi), psi % (2 * np.pi), atol=1e-9)
    y0 = mac.initial_state(psi)
    sol = solve(mac, y0, (0.0, 40.0), save_at=SaveAt(ts=np.linspace(0, 40, 201)),
                control=StepControl(rtol=1e-10, atol=1e-14))
    amp = mac.station_amplitudes(sol.ys)[:, 0]
    # only the round-off of the cancelled forces (U Omega^2 ~ 0.1 N, residual ~1e-17 N) drives
    # the structure: 1e-10 of the eccentricity; an unbalanced rotor moves by ~e
    f = mac.rhs(0.0, y0)
    nz = mac.n_coordinates
    assert np.abs(f[nz:2 * nz]).max() < 1e-15
    assert amp.max() < 1e-10 * ECC
    rel = sol.ys[:, mac.layout.i_phi:mac.layout.i_w] - 3.1 * sol.ts[:, None]
    np.testing.assert_allclose(rel, np.broadcast_to(psi, rel.shape), atol=1e-10)


def rigid_two_plane(motor=None, gravity=None, damping=0.01):
    """Rigid rotor on two anisotropic supports, gyroscopic, two 2-ball races off the centre."""
    M = np.diag([1.0, 1.0, 3.25, 3.25])
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = 0.5, -0.5
    # supports at z = +-3: k (x + z phi_x) with kx, ky per support; one cross term
    K = np.zeros((4, 4))
    C = np.zeros((4, 4))
    for zs, kx, ky in ((3.0, 0.5, 0.6), (-3.0, 0.55, 0.45)):
        for j, k in ((0, kx), (1, ky)):
            T = np.zeros((1, 4))
            T[0, j], T[0, j + 2] = 1.0, zs
            K += k * T.T @ T
            C += damping * T.T @ T
    K[0, 1] += 0.02
    s = LinearSystem(M=M, C=C, G=G, K=K)
    races = (BallRace(0, 1.0, (Ball(0.02, inertia=1e-4, damping=0.01), Ball(0.025, damping=0.012)), axial_offset=2.0),
             BallRace(0, 1.0, (Ball(0.02, damping=0.01), Ball(0.02, damping=0.01)), axial_offset=-2.0))
    unb = (Unbalance(0, 0.01, 0.3, axial_offset=1.0), Unbalance(0, 0.004, 2.0, axial_offset=-1.5))
    return Machine(s, races=races, unbalances=unb, gravity=gravity,
                   drive=motor if motor is not None else ConstantSpeed(1.3), energy_states=True)


def test_mass_matrix_symmetric_positive_definite_and_consistent_with_rhs():
    mac = rigid_two_plane(motor=Motor(0.3, polar_inertia=0.6, no_load_speed=2.0),
                          gravity=Gravity((0.0, -0.5, 0.0)))
    rng = np.random.default_rng(3)
    y = mac.initial_state(rng.uniform(0, 6, 4), spin_speed=1.1) + 0.1 * rng.normal(size=mac.n_state)
    Mf = mac.mass_matrix(y)
    np.testing.assert_allclose(Mf, Mf.T, atol=0)
    assert np.linalg.eigvalsh(Mf).min() > 0
    # M q'' from the kernel equals the generalised forces computed independently of the
    # Schur elimination: check via the energy rate with zero damping/motor below instead, and
    # here that the kernel's accelerations satisfy the ball equations J phi'' + m l t.B z'' = Q
    lay = mac.layout
    f = mac.rhs(0.0, y)
    nz, nb = lay.n_z, lay.n_balls
    qdd = np.concatenate([f[nz:2 * nz], f[lay.i_w:lay.i_w + nb], [f[lay.i_theta + 1]]])
    row = Mf[nz:nz + nb] @ qdd
    m, l, J, c, race = mac._ball_arrays
    phi, w = y[lay.i_phi:lay.i_phi + nb], y[lay.i_w:lay.i_w + nb]
    om = y[lay.i_theta + 1]
    Q = -c * (w - om) + m * l * (0.0 * -np.sin(phi) + -0.5 * np.cos(phi))
    # the races tilt with the rotor: the ball's velocity term m l^2 (e_b . phi') (t_b . phi')
    # (rigid ball kinematics, rotorlab.models._machine; Rodrigues et al. 2008 eq. (13) plus the
    # second-order term of test_rcfw_reference._axial_term)
    dphi = y[nz + 2:nz + 4]
    Q += m * l**2 * (np.cos(phi) * dphi[0] + np.sin(phi) * dphi[1]) * (-np.sin(phi) * dphi[0] + np.cos(phi) * dphi[1])
    assert lay.tilt and m.max() * (dphi @ dphi) > 1e-8  # far above the tolerance below
    np.testing.assert_allclose(row, Q, atol=1e-13)


def test_energy_conserved_without_damping_friction_or_motor_torque():
    """A free-spinning rotor (motor torque 0), no damping: T + V constant, with gyroscopics,
    anisotropic and cross-coupled... symmetric supports, unbalances, gravity, two races."""
    mac = rigid_two_plane(motor=Motor(0.0, polar_inertia=0.6, no_load_speed=1.0),
                          gravity=Gravity((0.3, -0.5, -9.8)), damping=0.0)
    s = mac.structure
    K = 0.5 * (s.K + s.K.T)  # no circulatory term either
    nodamp = [Ball(b.mass, b.inertia, 0.0) for r in mac.races for b in r.balls]
    races = (BallRace(0, 1.0, tuple(nodamp[:2]), axial_offset=2.0), BallRace(0, 1.0, tuple(nodamp[2:]), axial_offset=-2.0))
    mac = Machine(LinearSystem(M=s.M, C=s.C, G=s.G, K=K), races=races, unbalances=mac.unbalances,
                  gravity=mac.gravity, drive=mac.drive, energy_states=True)
    y0 = mac.initial_state([0.1, 2.0, 4.0, 5.0], spin_speed=1.2, z=[0.01, -0.02, 0.003, 0.001])
    sol = solve(mac, y0, (0.0, 30.0), save_at=SaveAt(ts=np.linspace(0, 30, 31)),
                control=StepControl(rtol=1e-11, atol=1e-13))
    e = np.array([mac.energy(y) for y in sol.ys])
    assert np.ptp(e) < 1e-9 * np.abs(e).max()
    np.testing.assert_allclose(sol.ys[:, -2:], 0.0, atol=1e-15)


@pytest.mark.parametrize("drive", [ConstantSpeed(1.3), Motor(0.4, polar_inertia=0.6, no_load_speed=2.0)])
def test_power_balance(drive):
    """drive work = change of kinetic + potential energy + dissipated energy (energy states)."""
    mac = rigid_two_plane(motor=drive, gravity=Gravity((0.0, -0.2, -9.8)))
    y0 = mac.initial_state([0.1, 2.0, 4.0, 5.0], ball_rates=[0.3, -0.2, 0.0, 0.1], spin_speed=0.1)
    ts = np.linspace(0.0, 25.0, 26)
    sol = solve(mac, y0, (0.0, 25.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-13))
    res = mac.energy_balance(sol.ts, sol.ys)
    work = np.abs(sol.ys[:, mac.layout.i_energy]).max()
    assert work > 1e-3
    assert np.abs(res).max() < 1e-6 * work


def test_tabulated_motor_interpolates_and_ramp_is_the_profile():
    lin = rigid_two_plane(motor=Motor(0.4, polar_inertia=0.6, no_load_speed=2.0))
    tab = rigid_two_plane(motor=Motor(((0.0, 0.5, 1.0, 2.0), (0.4, 0.3, 0.2, 0.0)), polar_inertia=0.6))
    y = lin.initial_state([0.1, 2.0, 4.0, 5.0])
    for om in (0.0, 0.25, 0.7, 1.5, 2.0):
        y[lin.layout.i_theta + 1] = om
        np.testing.assert_allclose(tab.rhs(0.0, y), lin.rhs(0.0, y), rtol=1e-13, atol=1e-15)
    y[lin.layout.i_theta + 1] = 3.0  # held beyond the table: 0, the linear law gives -0.1
    assert tab.rhs(0.0, y)[lin.layout.i_energy] == 0.0
    ramp = rigid_two_plane(motor=LinearRamp(0.2, 1.5, 12.0))
    # the inlined ramp equals the shared profile kernel (theta, Omega, Omega') at any time
    const = rigid_two_plane()
    for t in (-1.0, 0.0, 3.3, 12.0, 20.0):
        th, om = ramp.spin(t)
        dom = float(ramp.drive.spin_acceleration(t))
        yr = ramp.initial_state([0.1, 2.0, 4.0, 5.0], t0=t)
        p = const.to_array()
        p[:6] = [0.0, om, 0.0, 0.0, 0.0, 0.0]
        a, b = ramp.rhs(t, yr), const.rhs(th / om, yr, p)
        np.testing.assert_allclose(a[:4], b[:4], atol=1e-14)
        if dom == 0.0:
            np.testing.assert_allclose(a[:-2], b[:-2], rtol=1e-13, atol=1e-14)


def test_relabelling_balls_and_races_changes_nothing():
    mac = rigid_two_plane()
    r0, r1 = mac.races
    swapped = Machine(mac.structure, races=(BallRace(r1.node, r1.radius, r1.balls[::-1], r1.axial_offset),
                                            BallRace(r0.node, r0.radius, r0.balls[::-1], r0.axial_offset)),
                      unbalances=mac.unbalances[::-1], drive=mac.drive, energy_states=True)
    psi = np.array([0.1, 2.0, 4.0, 5.0])
    perm = [3, 2, 1, 0]
    ctl = StepControl(rtol=1e-10, atol=1e-13)
    a = solve(mac, mac.initial_state(psi), (0.0, 20.0), control=ctl).y_final
    b = solve(swapped, swapped.initial_state(psi[perm]), (0.0, 20.0), control=ctl).y_final
    lay = mac.layout
    np.testing.assert_allclose(b[:8], a[:8], atol=1e-9)
    np.testing.assert_allclose(b[lay.i_phi:lay.i_phi + 4], a[lay.i_phi:lay.i_phi + 4][perm], atol=1e-8)
    np.testing.assert_allclose(b[lay.i_energy:], a[lay.i_energy:], rtol=1e-8)


def test_co_rotating_linearization_matches_jeffcott_balls():
    mac, jb = planar_pair(ConstantSpeed(2.5), n_modes=2)
    balls = (Ball(BM, damping=BC),) * 2
    mac = Machine(mac.structure, races=(BallRace(0, BL, balls),), unbalances=mac.unbalances,
                  drive=ConstantSpeed(2.5), n_modes=2)
    jb = JeffcottBalls(RotorParams(M1, ECC, STIFF, DAMP), (BallParams(BM, BL, None, BC),) * 2,
                       speed=ConstantSpeed(2.5), frame="rotating")
    psi = math.acos(-M1 * ECC / (2 * BM * BL))
    yr = mac.balanced_state()
    np.testing.assert_allclose(np.sort(yr[4:6]), np.sort([psi, 2 * np.pi - psi]), atol=1e-9)
    lin = mac.linearize(yr)
    assert np.abs(lin.residual).max() < 1e-14
    ref = jb.linearize(np.r_[0.0, 0.0, 0.0, 0.0, yr[4:6], 0.0, 0.0], 2.5).eigenvalues
    got = lin.eigenvalues
    np.testing.assert_allclose(np.sort_complex(got), np.sort_complex(ref), atol=1e-7)
    assert lin.is_stable  # above the critical speed 1/sqrt(1.04): the balanced state is stable
    np.testing.assert_allclose(lin.M, lin.M.T, atol=1e-15)


def test_no_steady_equilibria_message_for_gravity_across_the_axis():
    mac = rigid_two_plane(gravity=Gravity((0.0, -9.81, 0.0)))
    with pytest.raises(ValueError, match="no co-rotating equilibria: the structure is anisotropic"):
        mac.linearize(np.zeros(16))
    iso, _ = planar_pair(ConstantSpeed(2.0))
    iso = Machine(iso.structure, races=iso.races, unbalances=iso.unbalances,
                  gravity=Gravity((0.0, -9.81, 0.0)), drive=iso.drive)
    assert "gravity acts across the axis" in iso.why_no_rotating_frame()


def test_bad_input_names_the_field():
    s = planar_structure()
    with pytest.raises(ValueError, match=r"Ball.mass must be a finite number > 0 \(kg\), got -1"):
        Ball(-1.0)
    with pytest.raises(ValueError, match=r"Machine.races\[0\].node must be < 1"):
        Machine(s, races=(BallRace(3, 1.0, (Ball(0.1),)),), drive=ConstantSpeed(1.0))
    with pytest.raises(ValueError, match="n_modes must be even"):
        Machine(s, n_modes=3, drive=ConstantSpeed(1.0))
    with pytest.raises(ValueError, match=r"Ball.coulomb must be a finite number >= 0 \(1\), got -0.01"):
        Ball(0.1, coulomb=-0.01)


def test_kernel_vectorises_in_the_lane_driver():
    from rotorlab.integrate._drivers import is_vectorised

    assert is_vectorised(rigid_two_plane().kernels, lanes=8)


def test_lanes_give_the_scalar_numbers_from_one_compiled_kernel():
    """Same bits on both drivers and any number of threads; the lane driver's scalar
    evaluations, the scalar driver and the Python callers call the generated kernel module's own
    compiled ``rhs`` (compiled once per model and cached with the module: issue 24), not copies
    compiled again for each driver or array type."""
    from rotorlab.integrate import _codegen, _drivers

    mac = rigid_two_plane()
    rng = np.random.default_rng(0)
    y0 = np.array([mac.initial_state(a) for a in rng.uniform(0, 2 * np.pi, (11, 4))])
    a = solve_ensemble(mac, y0, (0.0, 5.0), threads=1, lanes=None)  # the scalar reference
    b = solve_ensemble(mac, y0, (0.0, 5.0), threads=1, lanes=8)
    c = solve_ensemble(mac, y0, (0.0, 5.0), threads=2, lanes=8)
    np.testing.assert_array_equal(a.y_final, b.y_final)
    np.testing.assert_array_equal(b.y_final, c.y_final)
    assert mac.rhs(0.0, y0[0]).shape == (mac.n_state,)
    k = mac.kernels
    core = _codegen.build("rotorlab.integrate._core", _drivers._roles(k), {"EVENTS": 0})
    lanes = _codegen.build("rotorlab.integrate._lanes", _drivers._roles(k), _drivers._lane_consts(k, 8))
    assert lanes["_rhs_once"] is k.rhs and core["rhs"] is k.rhs
    assert len(k.rhs.signatures) == 1  # one specialisation: every caller passes contiguous arrays


def test_modal_reduction_converges_and_reports_its_change():
    """An FE shaft on bearings (Timoshenko elements, a disc): keeping more modes moves the
    locked-ball unbalance response less and less; the full basis reproduces the unreduced one."""
    from rotorlab.linear import Bearing, RigidBody, assemble, uniform_shaft

    els = list(uniform_shaft(6, 1.0, 0.04)) + [RigidBody.disc(3, 0.3, 0.04, 7800.0),
                                               Bearing(0, kxx=2e6, cxx=200.0), Bearing(6, kxx=2e6, cxx=200.0)]
    s = assemble(els)
    race = (BallRace(3, 0.12, (Ball(0.05, damping=0.01),) * 2),)
    unb = (Unbalance(2, 2e-4),)  # off the midspan: symmetric and antisymmetric modes respond
    om = 100.0  # below the first critical speed (about 187 rad/s)
    full = Machine(s, races=race, unbalances=unb, drive=ConstantSpeed(om))
    changes = [Machine(s, races=race, unbalances=unb, drive=ConstantSpeed(om), n_modes=k).reduction_change(om)
               for k in (2, 4, 8, 16)]
    assert full.reduction_change(om) == 0.0
    assert np.all(np.diff(changes) < 0) and changes[-1] < 1e-3
    every = Machine(s, races=race, unbalances=unb, drive=ConstantSpeed(om), n_modes=s.n_dof)
    np.testing.assert_allclose(every._locked_response(om), full._locked_response(om), rtol=1e-9)


@pytest.mark.parametrize("friction", [0.0, 0.3])
def test_impacts_on_a_tilting_race_keep_the_energy_balance(friction):
    """A clearance on a machine whose race tilts (balls on the tilting race, a motor): every
    impact's Delassus matrix comes from the same Schur system as the accelerations, the balls'
    axial unknowns included, so the energy balance closes (Stronge, *Impact Mechanics*, 2000,
    ch. 5: e = 1 without friction loses nothing, with friction exactly the friction work)."""
    from rotorlab.models import Clearance

    k = 2.0 * (2 * math.pi * 5.0) ** 2
    s = LinearSystem(M=np.diag([2.0, 2.0, 0.01, 0.01]), C=np.zeros((4, 4)), G=np.zeros((4, 4)),
                     K=np.diag([k, k, 50.0, 50.0]))
    race = BallRace(0, 0.04, (Ball(0.05), Ball(0.05)), axial_offset=0.1)
    m = Machine(s, races=(race,), unbalances=(Unbalance(0, 1e-4, axial_offset=-0.05),),
                drive=Motor(torque=2.0, polar_inertia=0.01, no_load_speed=40.0), energy_states=True,
                clearances=(Clearance(0, 1e-3, restitution=1.0, friction=friction, rotor_radius=0.05,
                                      axial_offset=0.05),))
    assert m.layout.tilt
    y0 = m.initial_state(ball_angles=[0.3, 2.0], ball_rates=[5.0, -3.0], spin_speed=20.0,
                         z=[2e-4, 0.0, 0.002, -0.001], dz=[0.0, 0.05, 0.02, 0.0])
    sol = solve(m, y0, (0.0, 1.0), control=StepControl(rtol=1e-10, atol=1e-13), max_events_recorded=10)
    assert sol.status.name == "SUCCESS", sol.status.message
    y = sol.y_final
    assert y[-3] > 10 and np.abs(y[2:4]).max() > 1e-4  # impacts, and the race tilts
    ie = m.layout.i_energy
    gain, sources = m.energy(y) - m.energy(y0), y[ie] - y[ie + 1] + y[-4] - y[-5]
    assert gain == pytest.approx(sources, abs=1e-8 * m.energy(y0))
    if friction == 0.0:  # an elastic frictionless impact dissipates nothing (to round-off)
        assert abs(y[-5]) < 1e-15 * m.energy(y0)
    else:
        assert y[-5] > 1e-3 * m.energy(y0)


def test_on_a_horizontal_axis_the_balls_hang_below_the_race_at_low_speed():
    """Gravity across the axis at a low speed (the drag c Omega of the oil below the weight's
    torque m l g): a ball does not go round with the rotor but hangs still, lifted from the bottom
    of the race to where the drag holds its weight, ``c Omega = m l g cos(phi)`` (the torque
    balance of its equation at rest; the structure at rest in its sag)."""
    g, om = 9.81, 2.5
    balls = (Ball(BM, inertia=1e-3, damping=BC), Ball(1.1 * BM, damping=0.9 * BC))
    mac = Machine(planar_structure(d=1.0), races=(BallRace(0, BL, balls),),
                  unbalances=(Unbalance(0, 0.0),), gravity=Gravity((0.0, -g, 0.0)),
                  drive=ConstantSpeed(om), n_modes=2)
    y0 = mac.initial_state([0.3, 2.0])  # balls at rest relative to the rotor
    # the slowest transient is the hanging ball's swing, damped at c / (2 J) ~ 0.24 1/s
    sol = solve(mac, y0, (0.0, 100.0), control=StepControl(rtol=1e-10, atol=1e-12))
    lay = mac.layout
    phi = np.angle(np.exp(1j * sol.y_final[lay.i_phi:lay.i_w]))
    expect = -np.arccos(np.array([BC, 0.9 * BC]) * om / (np.array([BM, 1.1 * BM]) * BL * g))
    assert np.all(expect > -np.pi / 2) and np.all(expect < 0.0)  # between the bottom and the side
    np.testing.assert_allclose(phi, expect, atol=1e-7)
    np.testing.assert_allclose(sol.y_final[lay.i_w:lay.i_w + 2], 0.0, atol=1e-7)
