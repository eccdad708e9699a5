"""``rotorlab.models.Machine`` as the two-plane balancer of Rodrigues et al. (2008).

Rodrigues, Champneys, Friswell & Wilson, "Automatic two-plane balancing for rigid rotors", Int.
J. Non-Linear Mech. 43 (2008) 527-541 (numbers quoted from the authors' preprint, University of
Bristol hdl 1983/946, with its equation and figure numbers): the "long rotor" M = 1, R = 1,
Jt = 3.25, Jp = 0.5, supports k = 0.5, c = 0.01 at z = +-3 (eq. (18), (20)), two races with two
balls at z = +-2, ball damping c_b = b / (m Omega_1 R^2) = 0.01, static imbalance eps = 0.01.
The nondimensional set is read as SI (kg, m, N/m, s) with Omega_1 = 1 rad/s.

The machine is a rigid body at one node with the two supports as one elastic connection
(k11 = 1, k12 = 0, k22 = 9, c11 = 0.02, c22 = 0.18: eq. (18), (20)), two :class:`BallRace` at
axial offsets +-2 and an :class:`Unbalance` U = M eps at phase 0.

What is checked, against the independent sympy reference of ``tests/validation/_rcfw_reference.py``
(``dev/derive_rcfw.py``) and the paper:

- the compiled right-hand side equals the reference's with *rigid* ball kinematics (a ball moves
  with its tilting race, axially too, as the paper's equations (9)-(13)) to 1e-12 on random
  states, at constant speed and during a run-up;
- the critical speeds of the structure: Omega_1 = 1, Omega_2 = sqrt(k22 / (Jt - Jp)) ~= 1.81
  (eq. (19)) and the backward conical one sqrt(k22 / (Jt + Jp));
- the balanced state: Machine's ball angles are eq. (16) (pi +- arccos(eps / (4 m))), none below
  m_c = eps / 4 = 0.0025 (eq. (21));
- its linearisation about the balanced state against the reference's complex-step Jacobian, the
  verdicts at the four Fig. 11 points, stability over speed (Fig. 5(a)), the onset of the primary
  stable region at the paper's Omega = 4.59-4.60 (m = 0.025) and 4.90-4.91 (m = 0.03), the disc rotor
  (Jp > Jt) without a stable balanced state (Rodrigues et al. 2011, IJNLM 46, Fig. 13(b));
- short simulations from the start of Fig. 11 (rotor at rest, balls of each race opposite, eq.
  (24)): (iii) balances, (ii) and (iv) do not, (iv) vibrates far more than the rotor without balls;
- the built-in case ``rcfw-two-plane`` (Fig. 11 (iii): m = 0.005, Omega = 4) is this machine and
  its analyses say the same.
"""

from __future__ import annotations

import zlib

import numpy as np
import pytest

import _rcfw_reference as ref
from rotorlab.analyses import build_model, run_case
from rotorlab.analyses._machine import structure_critical_speeds
from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
from rotorlab.io import load_case
from rotorlab.linear import ElasticConnection, RigidBody, assemble, critical_speeds
from rotorlab.models import Ball, BallRace, ConstantSpeed, LinearRamp, Machine, Unbalance


def _plane(k: float, z: float) -> np.ndarray:
    """One isotropic support at axial position z acting on (x, phi_x): k [[1, z], [z, z^2]]."""
    return k * np.array([[1.0, z], [z, z * z]])


def long_rotor(ball_mass: float, eps: float = ref.EPS, drive=None, *, jt: float = ref.JT,
               jp: float = ref.JP) -> Machine:
    """The paper's long rotor as a Machine (module docstring)."""
    zs = (ref.SUPPORT_Z, -ref.SUPPORT_Z)
    stiff = sum(_plane(ref.SUPPORT_K, z) for z in zs)
    damp = sum(_plane(ref.SUPPORT_C, z) for z in zs)
    structure = assemble([RigidBody(0, 1.0, jt, jp),
                          ElasticConnection((0,), stiffness_x=stiff, damping_x=damp)])
    ball = Ball(ball_mass, damping=ref.CB * ball_mass)
    races = tuple(BallRace(0, ref.RACE_R, (ball, ball), axial_offset=z)
                  for z in (ref.RACE_Z, -ref.RACE_Z))
    return Machine(structure, races, (Unbalance(0, 1.0 * eps),),
                   drive=ConstantSpeed(3.0) if drive is None else drive)


def _to_reference(y: np.ndarray) -> np.ndarray:
    """Machine's fixed-frame layout (z, z', phi_b, w_b) -> the reference's (q, q')."""
    return np.concatenate([y[:4], y[8:12], y[4:8], y[12:16]])


def _rotating_to_reference(yr: np.ndarray) -> np.ndarray:
    """Machine's co-rotating layout (z_r, z_r', psi, psi') -> the reference's (q, q')."""
    return np.concatenate([yr[:4], yr[8:12], yr[4:8], yr[12:16]])


def test_structure_is_the_papers_long_rotor():
    """k11 = 1, k12 = 0, k22 = 9, c11 = 0.02, c22 = 0.18 (eqs. (18), (20))."""
    s = long_rotor(0.025).structure
    np.testing.assert_allclose(np.diag(s.K), [1.0, 1.0, 9.0, 9.0], rtol=1e-15)
    np.testing.assert_allclose(np.diag(s.C), [0.02, 0.02, 0.18, 0.18], rtol=1e-14)
    assert np.count_nonzero(s.K - np.diag(np.diag(s.K))) == 0


def test_critical_speeds_of_the_structure():
    """Omega_1 = sqrt(k11 / M) = 1, Omega_2 = sqrt(k22 / (Jt - Jp)) ~= 1.81 (eq. (19)), plus the
    backward conical crossing sqrt(k22 / (Jt + Jp)); the disc rotor has no forward conical one."""
    cs = critical_speeds(long_rotor(0.025).structure)
    om1, om2, om2b = ref.critical_speeds(1.0, ref.JT, ref.JP, 1.0, 9.0)
    np.testing.assert_allclose(np.sort(cs.speed), np.sort([om1, om1, om2b, om2]), rtol=1e-12)
    assert om2 == pytest.approx(ref.OMEGA_CON, abs=0.005)
    disc = critical_speeds(long_rotor(0.025, jt=0.5, jp=0.9).structure)
    np.testing.assert_allclose(np.sort(disc.speed), np.sort([1.0, 1.0, np.sqrt(9.0 / 1.4)]),
                               rtol=1e-12)


def _random_states(model: Machine, rng, count: int, span):
    for _ in range(count):
        t = rng.uniform(*span)
        om = float(model.drive.spin_speed(t))
        y = np.empty(model.n_state)
        y[:4] = rng.normal(scale=0.05, size=4)
        y[4:8] = rng.normal(scale=0.2, size=4)
        y[8:12] = rng.uniform(-7.0, 7.0, size=4)
        y[12:16] = om + rng.normal(scale=2.0, size=4)
        yield t, y


@pytest.mark.parametrize(("drive", "jp", "span"), [
    (ConstantSpeed(2.5), ref.JP, (0.0, 10.0)),
    # a run-up: the rotor's own Jp Omega' tilt coupling depends on which spin angle is
    # prescribed (rotorlab's LinearSystem has none), so that case compares a rotor with Jp = 0;
    # the balls' and the unbalance's Omega' terms are all there
    (LinearRamp(0.5, 4.0, 3.0), 0.0, (0.0, 3.0)),
])
def test_rhs_matches_the_reference(drive, jp, span):
    model = long_rotor(0.025, drive=drive, jp=jp)
    ref_sys = ref.TwoPlane.long_rotor(0.025, kinematics="rigid", jp=jp)
    rng = np.random.default_rng(zlib.crc32(repr(drive).encode()))
    for t, y in _random_states(model, rng, 12, span):
        got = _to_reference(model.rhs(t, y))
        theta, om = model.spin(t)
        expect = ref.fixed_rhs(ref_sys, _to_reference(y), theta, om, float(drive.spin_acceleration(t)))
        assert np.max(np.abs(got - expect)) <= 1e-12 * np.max(np.abs(expect)), (t, y)


@pytest.mark.parametrize("m", [0.025, 0.005])
def test_balanced_angles_are_eq16(m):
    model = long_rotor(m)
    got = model.balanced_angles()
    expect = ref.balanced_angles(ref.EPS, m)
    for race in (slice(0, 2), slice(2, 4)):  # balls of a race may come out swapped
        np.testing.assert_allclose(np.sort(np.mod(got[race], 2 * np.pi)), np.sort(expect[race]),
                                   atol=1e-9)
    assert long_rotor(0.99 * ref.M_CRIT).balanced_angles() is None  # eq. (21): m_c = eps / 4


@pytest.mark.parametrize("omega", [1.5, 2.0, 4.0])
def test_linearization_matches_the_reference(omega):
    """Machine.linearize (finite differences, ~1e-10) against the complex-step Jacobian of the
    reference's co-rotating equations, both about the balanced state of eq. (16)."""
    model = long_rotor(0.025, drive=ConstantSpeed(omega))
    yr = model.balanced_state(ref.balanced_angles(ref.EPS, 0.025))
    lin = model.linearize(yr)
    assert np.max(np.abs(lin.residual)) < 1e-14
    ref_sys = ref.TwoPlane.long_rotor(0.025, kinematics="rigid")
    perm = np.r_[0:4, 8:12, 4:8, 12:16]
    A_ref = ref.jacobian(lambda s: ref.rotating_rhs(ref_sys, s, omega), _rotating_to_reference(yr))
    A = lin.A[np.ix_(perm, perm)]
    assert np.max(np.abs(A - A_ref)) < 1e-7 * np.max(np.abs(A_ref))
    lam, lam_ref = np.linalg.eigvals(A), np.linalg.eigvals(A_ref)
    assert np.max(lam.real) == pytest.approx(np.max(lam_ref.real), abs=1e-7)


@pytest.mark.parametrize(("omega", "eps", "m", "stable"), [
    (2.0, 0.01, 0.025, True),    # Fig. 11 (i): secondary stable region of Fig. 5(a)
    (2.5, 0.01, 0.005, False),   # Fig. 11 (ii): outside it
    (4.0, 0.01, 0.005, True),    # Fig. 11 (iii): primary stable region
    (1.5, 0.025, 0.025, False),  # Fig. 11 (iv): well outside any (Fig. 7)
])
def test_stability_at_the_fig11_points(omega, eps, m, stable):
    model = long_rotor(m, eps, ConstantSpeed(omega))
    assert model.linearize(model.balanced_state()).is_stable == stable


def _stable_speeds(make, omegas) -> np.ndarray:
    out = []
    for om in omegas:
        model = make(om)
        out.append(model.linearize(model.balanced_state()).is_stable)
    return np.array(out)


def test_stability_over_speed():
    """m = 0.025: the speeds where B is stable are the reference's (rigid kinematics) on a grid:
    none below Omega_2, a secondary region holding 2.0, a primary region at high speed (Fig. 5(a))."""
    omegas = np.round(np.arange(0.5, 6.0001, 0.25), 6)
    got = _stable_speeds(lambda om: long_rotor(0.025, drive=ConstantSpeed(om)), omegas)
    rigid = ref.TwoPlane.long_rotor(0.025, kinematics="rigid")
    expect = np.array([ref.spectral_abscissa(rigid, om) < 0 for om in omegas])
    np.testing.assert_array_equal(got, expect)
    assert not got[omegas < ref.OMEGA_CON].any()
    assert got[omegas == 2.0].all() and got[omegas >= 4.75].all() and not got[omegas == 3.0].any()


@pytest.mark.parametrize(("m", "lo", "hi"), [(0.025, 4.59, 4.60), (0.03, 4.90, 4.91)])
def test_primary_region_onset_is_the_papers(m, lo, hi):
    """Fig. 5(a) of Rodrigues et al. (2008) (boundaries read from the figure's vector graphics on
    a 0.01 grid, ``test_rcfw_reference.FIG5A_BOUNDARIES``): the primary stable region of B starts
    between Omega = 4.59 and 4.60 at m = 0.025 and between 4.90 and 4.91 at m = 0.03. The balls'
    axial motion on their tilting races sets it: without it (in-plane balls) it started at 4.48."""
    got = _stable_speeds(lambda om: long_rotor(m, drive=ConstantSpeed(om)), [lo, hi])
    assert got.tolist() == [False, True]


def test_disc_rotor_has_no_stable_balanced_state():
    """Jp > Jt with m = eps: B is unstable at every speed (Rodrigues et al. 2011, Fig. 13(b))."""
    omegas = np.arange(0.5, 10.001, 0.5)
    for eps in (0.002, 0.025):
        got = _stable_speeds(lambda om: long_rotor(eps, eps, ConstantSpeed(om), jt=0.5, jp=0.9),
                             omegas)
        assert not got.any()


def _fig11(omega: float, eps: float, m: float, t_end: float, with_balls: bool = True):
    """Times and vibration A-bar (eq. (23)) of a Fig. 11 run from the start of eq. (24)."""
    model = long_rotor(m if with_balls else 1e-12 * m, eps, ConstantSpeed(omega))
    y0 = model.initial_state(ball_angles=[np.pi / 2, -np.pi / 2, np.pi / 2, -np.pi / 2])
    ts = np.arange(0.0, t_end, 0.2)
    sol = solve_ensemble(model, y0, (0.0, t_end), save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=1e-8, atol=1e-11))
    assert sol.success.all()
    ys = sol.trajectory(0).ys
    return ts, ref.vibration(ys[:, 0], ys[:, 1], ys[:, 2], ys[:, 3])


def _rotor_alone(omega: float, eps: float) -> float:
    """Steady whirl of the rotor without balls: eps W^2 / |1 - W^2 + i c11 W| (no tilt)."""
    return eps * omega**2 / abs(1.0 - omega**2 + 0.02j * omega)


@pytest.mark.parametrize(("omega", "eps", "m"), [(4.0, 0.01, 0.005), (2.0, 0.01, 0.025)])
def test_fig11_balancing_runs(omega, eps, m):
    """Fig. 11 (iii) and (i): the balls find the balanced state and the vibration dies away
    (B's slowest eigenvalue has Re ~ -0.0034 at both points, so it takes ~1000 time units)."""
    ts, a = _fig11(omega, eps, m, 1600.0)
    _, alone = _fig11(omega, eps, m, 600.0, with_balls=False)
    assert alone[-100:].mean() == pytest.approx(_rotor_alone(omega, eps), rel=0.01)
    mid, end = a[(ts > 700) & (ts < 800)].max(), a[ts > 1500].max()
    assert end < 0.1 * mid and end < 0.01 * _rotor_alone(omega, eps)


def test_fig11_runs_that_do_not_balance():
    """Fig. 11 (ii), (Omega, eps, m) = (2.5, 0.01, 0.005): the vibration first dies down, then
    the unstable balanced state gives way to a periodic motion ten times the rotor's own whirl.
    Fig. 11 (iv), (1.5, 0.025, 0.025): "chaotic motion ... far higher than that for the rotor
    without an ABB" (Section 4). With the balls' axial motion the growth from the unstable state
    takes longer: the periodic motion (about 11 times the rotor's own whirl) holds from t ~ 1000."""
    ts, a = _fig11(2.5, 0.01, 0.005, 1300.0)
    late = a[ts > 1200]
    assert late.min() > 5 * _rotor_alone(2.5, 0.01)
    assert a[(ts > 100) & (ts < 300)].min() < 0.2 * late.mean()
    ts, a = _fig11(1.5, 0.025, 0.025, 400.0)
    assert a[ts > 300].max() > 4 * _rotor_alone(1.5, 0.025)


# -- the built-in case ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def rcfw_case():
    case = load_case("rcfw-two-plane")
    return case, run_case(case)


def test_builtin_case_is_the_long_rotor(rcfw_case):
    case, _ = rcfw_case
    model = build_model(case.model)
    expect = long_rotor(0.005, drive=ConstantSpeed(4.0))
    for name in ("M", "C", "G", "K"):
        np.testing.assert_allclose(getattr(model.structure, name), getattr(expect.structure, name),
                                   rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(model.to_array(), expect.to_array(), rtol=1e-14, atol=1e-16)
    # critical speeds with the balls locked: Rodrigues et al. 2011, eq. (32), sqrt(2k / (M + 4m))
    # and, with the balls locked on the axis, sqrt(2k l^2 / (Jt + 4 m z^2 - Jp)) (the cylindrical
    # one is a double root: no gyroscopic split); locked at their race radius R = 1 they add
    # 4 m R^2 / 2 to Jt and 4 m R^2 to Jp (own inertia 0): sqrt(2k l^2 / (Jt + 4 m (z^2 + R^2/2)
    # - Jp - 4 m R^2))
    np.testing.assert_allclose(np.unique(np.round(structure_critical_speeds(model), 12)),
                               [np.sqrt(1.0 / 1.02),
                                np.sqrt(9.0 / (3.25 + 4 * 0.005 * (4 + 0.5) - 0.5 - 4 * 0.005))],
                               rtol=1e-12)


def test_builtin_case_stability_over_speed(rcfw_case):
    """stability-chart: B exists at every speed with the balls at pi +- 60 degrees (eq. (16),
    eps / (4 m) = 1/2), is unstable below Omega_2 and stable from 3 rad/s on (Fig. 5(a) at
    m = 0.005: from 2.94-2.95 rad/s)."""
    ds = rcfw_case[1]["stability-over-speed"]
    om = ds.speed.values
    assert ds.exists.all() and ds.balanced.all() and (ds.status == 0).all()
    np.testing.assert_allclose(np.abs(ds.ball_angle.values), 2 * np.pi / 3, atol=1e-9)
    rigid = ref.TwoPlane.long_rotor(0.005, kinematics="rigid")
    expect = np.array([ref.spectral_abscissa(rigid, w) < 0 for w in om])
    np.testing.assert_array_equal(ds.stable.values, expect)
    assert not ds.stable.values[om < ref.OMEGA_CON].any() and ds.stable.values[om >= 3.0].all()


def test_builtin_case_simulations(rcfw_case):
    """simulate: Fig. 11 (iii) balances from both starts (balls at +-120 degrees, eq.
    (16)); without the balancer the rotor whirls with eps W^2 / |1 - W^2 + i c11 W|; Fig. 11 (ii)
    at 2.5 rad/s ends in a periodic motion several times the rotor's own whirl."""
    res = rcfw_case[1]
    alone = _rotor_alone(4.0, ref.EPS)
    assert float(res["no-balancer"].amplitude.max()) == pytest.approx(alone, rel=0.03)
    # the time history the report plots (n_save = 2000 states over the 600 s): the rotor's
    # distance from the axis settles on the same circle, eps W^2 / |1 - W^2 + i c11 W|
    hist = res["no-balancer"].displacement
    assert hist.dims == ("ic", "time", "station") and hist.sizes["time"] == 2000
    assert hist.attrs["units"] == "m" and hist.time.values[-1] == 600.0
    late = hist.sel(time=slice(500.0, None)).values
    np.testing.assert_allclose(late, alone, rtol=0.03)
    bal = res["fig11-iii-balancing"]
    assert (bal.status == 0).all()
    assert float(bal.amplitude.max()) < 2e-3 * alone
    # the first start ends within 4e-4 rad of the balanced angles; the second (each race's balls
    # together, a large initial couple) is still ~2e-3 rad away at 1600 s, closing at the slowest
    # eigenvalue's rate Re = -0.0034 1/s
    np.testing.assert_allclose(np.abs(bal.final_ball_angle.values[0]), 2 * np.pi / 3, atol=5e-4)
    np.testing.assert_allclose(np.abs(bal.final_ball_angle.values[1]), 2 * np.pi / 3, atol=3e-3)
    unstable = res["fig11-ii-unstable"]
    assert float(unstable.amplitude.min()) > 5 * _rotor_alone(2.5, ref.EPS)
