"""Couple and dynamic unbalance (issue 28 item 4): one :class:`rotorlab.linear.Unbalance`, static
and couple, in the linear response, the composed machine and the case files.

The closed form: a rigid rotor (mass m, diametral and polar inertia I_d, I_p) on two equal
supports at z = +-L (stiffness k, damping c each) has decoupled translation and tilt; in the
complex tilt psi = phi_x + i phi_y its tilting (conical) mode obeys

    I_d psi'' + (2 c L^2 - i I_p Omega) psi' + 2 k L^2 psi = U_c Omega^2 e^{i (Omega t + gamma)}

(the gyroscopic moment of :class:`rotorlab.linear.RigidBody`), so the synchronous response is
``psi = U_c Omega^2 e^{i gamma} / (k_t - (I_d - I_p) Omega^2 + i c_t Omega) e^{i Omega t}`` with
``k_t = 2 k L^2``, ``c_t = 2 c L^2`` and no translation (Friswell et al. 2010, Chapter 3, the rigid
rotor on flexible supports: the conical mode with its gyroscopic ``(I_d - I_p) Omega^2``; Vance,
Zeidan & Murphy 2010, Section 2.7, dynamic unbalance). A principal axis tilted by tau carries the
couple ``(I_d - I_p) tau``: far above the conical mode the body turns about that axis and the
shaft's tilt tends to ``-tau``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorlab.linear import LinearSystem, RigidBody, Unbalance, unbalance_response

M, ID, IP = 1.0, 0.5, 0.3


def two_supports(supports, ip=IP, idia=ID) -> LinearSystem:
    """Rigid rotor (node 0 at its centre of mass) on supports ``(z, k, c)``: the support at z
    moves with ``x + z phi_x`` (and likewise in y)."""
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    for z, k, c in supports:
        for j in (0, 1):
            T = np.zeros((1, 4))
            T[0, j], T[0, j + 2] = 1.0, z
            K += k * T.T @ T
            C += c * T.T @ T
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = ip, -ip
    return LinearSystem(M=np.diag([M, M, idia, idia]), C=C, G=G, K=K)


def response(ds) -> np.ndarray:
    return ds.response_real.values + 1j * ds.response_imag.values


def test_couple_drives_the_conical_mode_as_the_closed_form():
    L, k, c, uc, gamma = 0.4, 2.0, 0.05, 3e-3, 0.7
    s = two_supports([(L, k, c), (-L, k, c)])
    w = np.linspace(0.5, 12.0, 47)  # through the forward conical mode at sqrt(2 k L^2 / (I_d - I_p)) = 4
    q = response(unbalance_response(s, w, [Unbalance(0, couple=uc, couple_phase=gamma)]))
    kt, ct = 2 * k * L * L, 2 * c * L * L
    psi = uc * w**2 * np.exp(1j * gamma) / (kt - (ID - IP) * w**2 + 1j * ct * w)
    np.testing.assert_allclose(q[:, 2], psi, rtol=1e-12)
    np.testing.assert_allclose(q[:, 3], -1j * psi, rtol=1e-12)  # forward circular tilt
    assert np.abs(q[:, :2]).max() < 1e-14 * np.abs(psi).max()  # no translation
    # the supports move by +-L psi: at the mode the orbit is largest
    assert abs(w[np.argmax(np.abs(psi))] - math.sqrt(kt / (ID - IP))) < w[1] - w[0]


@pytest.mark.parametrize(("idia", "ip"), [(0.5, 0.3), (0.2, 0.35)])  # a long body and a flat disc
def test_tilted_principal_axis_is_a_couple_and_self_aligns(idia, ip):
    tau, tilt_phase = 2e-3, -1.2
    body = RigidBody(0, M, idia, ip)
    u = Unbalance.of_tilted_body(body, tau, tilt_phase)
    assert u.couple == pytest.approx(abs(idia - ip) * tau, rel=1e-15) and u.magnitude == 0.0
    s = two_supports([(0.4, 2.0, 0.05), (-0.4, 2.0, 0.05)], ip=ip, idia=idia)
    om = 3e4  # 1e4 x the conical mode (or no forward conical mode at all: I_p > I_d)
    q = response(unbalance_response(s, [om], [u]))[0]
    # the body spins about its principal axis: the shaft tilts by -tau towards tilt_phase, up to
    # c_t / (|I_d - I_p| Omega) < 4e-6 (the damping of the closed form)
    np.testing.assert_allclose(q[2], -tau * np.exp(1j * tilt_phase), rtol=1e-5)
    assert abs(q[2] + tau * np.exp(1j * tilt_phase)) > 1e-7 * tau  # not exactly: the supports act
    # and as a couple it is the closed form at every speed
    lever = (idia - ip) * tau
    for w in (1.0, 5.0):
        qw = response(unbalance_response(s, [w], [u]))[0]
        expected = lever * w**2 * np.exp(1j * tilt_phase) / (2 * 2.0 * 0.16 - (idia - ip) * w**2 + 2j * 0.05 * 0.16 * w)
        np.testing.assert_allclose(qw[2], expected, rtol=1e-12)


def coupled_rotor() -> LinearSystem:
    """Unequal supports: translation and tilt coupled."""
    return two_supports([(1.0, 1.0, 0.3), (-0.8, 1.4, 0.25)])


STATIC = Unbalance(0, 0.01, 0.3, axial_offset=0.2)
COUPLE = Unbalance(0, couple=0.004, couple_phase=1.1)
BOTH = Unbalance(0, 0.01, 0.3, axial_offset=0.2, couple=0.004, couple_phase=1.1)


def test_static_and_couple_add_and_a_couple_is_two_opposite_unbalances():
    s = coupled_rotor()
    w = np.linspace(0.3, 4.0, 25)
    both, static, couple = (response(unbalance_response(s, w, [u])) for u in (BOTH, STATIC, COUPLE))
    scale = np.abs(both).max()
    np.testing.assert_allclose(both, static + couple, rtol=0, atol=1e-13 * scale)
    assert np.abs(static).min() > 1e-6 * scale and np.abs(couple[:, 2]).min() > 1e-6 * scale  # both act
    # the definition of a couple: U at +d/2 and the opposite U at -d/2, U d = U_c (any d)
    d = 0.37
    pair = [Unbalance(0, 0.004 / d, 1.1, axial_offset=d / 2), Unbalance(0, 0.004 / d, 1.1 + math.pi, axial_offset=-d / 2)]
    np.testing.assert_allclose(response(unbalance_response(s, w, pair)), couple, rtol=0, atol=1e-12 * scale)


def test_machine_at_steady_state_agrees_with_unbalance_response():
    """The composed machine (no balls, prescribed speed) started at rest: once the transient has
    died out (decay rate >= 0.1 1/s, 200 s) its motion is the linear unbalance response."""
    from rotorlab.integrate import SaveAt, StepControl, solve
    from rotorlab.models import ConstantSpeed, Machine

    s, om = coupled_rotor(), 2.5
    mac = Machine(s, unbalances=(BOTH,), drive=ConstantSpeed(om))
    assert mac.layout.n_unbalance == 3  # the static part and the couple's two opposite points
    ts = np.linspace(200.0, 200.0 + 2 * math.pi / om, 17)
    sol = solve(mac, mac.initial_state(), (0.0, ts[-1]), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=1e-10, atol=1e-14))  # fmt: skip
    assert sol.status == 0
    q = response(unbalance_response(s, [om], [BOTH]))[0]
    expected = np.real(q[None, :] * np.exp(1j * om * ts)[:, None])
    np.testing.assert_allclose(sol.ys[:, :4], expected, rtol=0, atol=1e-7 * np.abs(q).max())
    assert np.abs(q[2:]).min() > 0.05 * np.abs(q).max()  # the tilts respond


CASE = """
schema_version = 1
name = "couple"
[model]
type = "multibody"
[[model.bodies]]
name = "rotor"
position = "0 m"
mass = "1 kg"
diametral_inertia = "0.5 kg*m^2"
polar_inertia = "0.3 kg*m^2"
[model.elastic]
stiffness = [["2 N/m", "0 N/rad"], ["0 N/rad", "0.32 N*m/rad"]]
damping = [["0.1 N*s/m", "0 N*s/rad"], ["0 N*s/rad", "0.016 N*m*s/rad"]]
[[analysis]]
type = "unbalance_response"
name = "couple"
start = "1 rad/s"
stop = "6 rad/s"
n_speeds = 6
[[analysis.unbalances]]
at = "rotor"
{unbalance}
"""


def test_case_file_couple_is_the_api_couple():
    from rotorlab.analyses import run_analysis
    from rotorlab.io import CaseError, parse_case

    case = parse_case(CASE.format(unbalance='couple = "3 g*m^2"\ncouple_phase = "40 deg"'))
    ds = run_analysis(case.model, case.analyses[0])
    s = two_supports([(0.4, 1.0, 0.05), (-0.4, 1.0, 0.05)])
    api = unbalance_response(s, ds.speed.values, [Unbalance(0, couple=3e-3, couple_phase=math.radians(40.0))])
    np.testing.assert_allclose(response(ds), response(api), rtol=1e-12, atol=1e-18)
    assert ds.attrs["unbalance_couples"] == [pytest.approx(3e-3)]
    with pytest.raises(CaseError, match=r"analysis\[0\]\.unbalances\[0\]: give magnitude .* or couple"):
        parse_case(CASE.format(unbalance='phase = "10 deg"'))


def test_machine_case_takes_the_same_unbalance():
    """``[[model.unbalances]]`` of a machine is the same spec: static with its offset, couple."""
    from rotorlab.analyses._machine_common import machine_model
    from rotorlab.io import parse_case

    text = CASE.split("[[analysis]]")[0].replace('type = "multibody"', 'type = "machine"\n[model.structure]\ntype = "multibody"')
    text = (text.replace("[[model.bodies]]", "[[model.structure.bodies]]").replace("[model.elastic]", "[model.structure.elastic]")
            + '[[model.unbalances]]\nat = "rotor"\nmagnitude = "10 g*m"\nphase = "0.3 rad"\naxial_offset = "0.2 m"\n'
            + 'couple = "4 g*m^2"\ncouple_phase = "1.1 rad"\n[model.drive]\nprofile = "constant"\nspeed = "2.5 rad/s"\n')
    machine = machine_model(parse_case(text).model)
    (u,) = machine.unbalances
    assert (u.node, u.magnitude, u.phase, u.axial_offset, u.couple, u.couple_phase) == pytest.approx((0, 0.01, 0.3, 0.2, 0.004, 1.1), rel=1e-15)
