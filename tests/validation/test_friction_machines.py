"""``friction-margin`` of any machine (issue 26 item 4): races that tilt and three or more balls.

References: the holding torque and normal force of a stuck ball are the machine kernel's own
(its ``terms``: the race's torque on each ball and its friction bound, at a state), and the
steady response is an equilibrium of the kernel's right-hand side in the co-rotating frame; the
three-ball closed form is derived in :func:`test_three_equal_balls_closed_form`. The tilting
machine is the rigid two-plane rotor of ``tests/unit/test_machine_friction.py`` (the same kernel
layout: four balls on two tilting races, two unbalances, energy states, a constant speed) on
the isotropic supports of the built-in case ``rcfw-two-plane``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import build_model
from rotorlab.analyses._friction_machine import MachineStick, _frictionless, balanced_family
from rotorlab.analyses._friction_margin import friction_margin
from rotorlab.analyses._friction_search import worst_stuck
from rotorlab.io import load_case
from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance


def two_plane(speed: float, coulomb: float) -> Machine:
    """The rigid long rotor of the built-in case ``rcfw-two-plane`` (Rodrigues et al. 2008: isotropic
    supports at z = +-3 m, gyroscopic) with two tilting 2-ball races at z = +-2 m carrying unequal balls
    with Coulomb and rolling friction, and two unbalances (the layout of the friction tests' rotor)."""
    structure = build_model(load_case("rcfw-two-plane").model).structure

    def balls(masses, inertias):
        return tuple(Ball(m, inertia=i, damping=0.01, coulomb=coulomb, rolling=0.2 * coulomb)
                     for m, i in zip(masses, inertias))

    races = (BallRace(0, 1.0, balls((0.02, 0.025), (1e-4, 0.0)), axial_offset=2.0),
             BallRace(0, 1.0, balls((0.02, 0.02), (0.0, 2e-4)), axial_offset=-2.0))
    unb = (Unbalance(0, 0.01, 0.3, axial_offset=1.0), Unbalance(0, 0.004, 2.0, axial_offset=-1.5))
    return Machine(structure, races=races, unbalances=unb, drive=ConstantSpeed(speed), energy_states=True)


def fixed_state(mac, stick, psi, om):
    """The fixed-frame state at t = 0 of the balls stuck at psi (mode 0) on the steady response."""
    lay = mac.layout
    nz, nb = lay.n_z, lay.n_balls
    y = np.zeros(lay.n_state)
    z = stick.coordinates(psi)
    y[:nz], y[nz:2 * nz] = z, mac._rot_pairs(z, om)
    y[lay.i_phi:lay.i_phi + nb], y[lay.i_w:lay.i_w + nb] = psi, om
    return y


def test_tilting_holding_torque_is_the_kernels():
    # At the co-rotating steady state of the stuck balls, mapped to the fixed frame, the kernel's holding
    # torque and friction bound are the closed form's, and its accelerations are those of the steady
    # motion (z'' = -Omega^2 z, the balls' relative acceleration 0).
    from rotorlab._kernels import machine_codegen as cg

    om = 4.0
    mac = two_plane(om, 0.05)
    assert mac.layout.tilt and mac.structure.is_isotropic
    stick = MachineStick(mac, om)
    assert stick.tilting
    terms, p = cg.kernel_module(mac.layout).terms, mac.to_array()
    nz, nb = mac.layout.n_z, mac.layout.n_balls
    scale = stick.m * stick.l * om**2
    tilt_share = []
    for psi in np.random.default_rng(1).uniform(-math.pi, math.pi, (6, nb)):
        y = fixed_state(mac, stick, psi, om)
        buf = np.zeros(2 * nb)
        terms(0.0, y, p, -1, buf)
        _, hold, allow = stick.holding(psi)
        top = np.abs(buf).max()
        np.testing.assert_allclose(hold * scale, buf[0::2], rtol=0, atol=1e-10 * top)
        np.testing.assert_allclose(allow * scale, buf[1::2], rtol=0, atol=1e-10 * top)
        f = mac.rhs(0.0, y)
        z = y[:nz]
        np.testing.assert_allclose(f[nz:2 * nz], -om * om * z, rtol=0, atol=1e-12 * om * om * np.abs(z).max())
        assert np.all(f[mac.layout.i_w:mac.layout.i_w + nb] == 0.0)
        # the tilt's own term l (e . phi) (t . phi) is not negligible against the tolerance
        e = np.stack([np.cos(psi), np.sin(psi)], -1)
        phi = np.einsum("bkz,z->bk", stick.T, z)
        tilt_share.append(np.abs(stick.l * np.sum(e * phi, -1) * (e[:, 0] * phi[:, 1] - e[:, 1] * phi[:, 0])).max()
                          / np.abs(hold).max())
    assert min(tilt_share) > 1e-4
    # without the balls' tilt inertia the response is not steady in the kernel: the terms matter
    red = mac.reduced
    pairs = np.zeros((nz, nz))
    pairs[0::2, 1::2], pairs[1::2, 0::2] = -np.eye(nz // 2), np.eye(nz // 2)
    plain = red["K"] - om * om * mac._m0() + om * (red["C"] + om * red["G"]) @ pairs
    psi = np.zeros(nb)
    y = fixed_state(mac, stick, psi, om)
    y[:nz] = np.linalg.solve(plain, om * om * mac.balance_residual(psi))
    y[nz:2 * nz] = mac._rot_pairs(y[:nz], om)
    assert np.abs(mac.rhs(0.0, y)[nz:2 * nz] + om * om * y[:nz]).max() > 1e-3 * om * om * np.abs(y[:nz]).max()


@pytest.fixture(scope="module")
def rotor():
    return build_model(load_case("autobalancer").model)


def planar(rotor, n_balls: int, coulomb: float, unbalance: float) -> Machine:
    """The autobalancer as a planar machine with ``n_balls`` of its balls, friction and an unbalance (kg m)."""
    from rotorlab.continuation import as_machine

    m = as_machine(rotor)
    race = m.races[0]
    ball = replace(race.balls[0], coulomb=coulomb)
    return replace(m, races=(replace(race, balls=(ball,) * n_balls),),
                   unbalances=(replace(m.unbalances[0], magnitude=unbalance),))


def search(machine, om):
    stick = MachineStick(machine.with_drive(ConstantSpeed(om)), om)
    starts = balanced_family(_frictionless(machine).with_drive(ConstantSpeed(om)))
    return stick, worst_stuck(stick.holding, starts, scale=float(stick.kap.max()))


def test_two_balls_search_is_the_grid(rotor):
    # two balls: the optimiser from the balanced arrangements finds the grid's worst residual, to the grid's
    # resolution (the band is a thin parallelogram whose far corner a grid cuts off: the grid's worst
    # approaches the optimiser's from below as the grid is refined)
    om = 2.0 * rotor.critical_speed
    m = planar(rotor, 2, 1e-3, 1.5e-3)
    stick, res = search(m, om)
    assert res["kept"] == res["runs"] >= 6
    gaps = []
    for n in (121, 241, 481):
        g = float(friction_margin("machine", m, [om], grid=n, simulate=False).worst_residual[0])
        assert res["worst"] >= g * (1.0 - 1e-9)  # never below a point of the grid
        gaps.append(res["worst"] - g)
    assert gaps[2] < 0.6 * gaps[1] < 0.36 * gaps[0] and gaps[2] < 0.01 * res["worst"]
    assert np.abs(stick.terms(res["worst_at"])[1]).min() < 1e-9 * 0.05  # on the band's edge
    assert res["worst"] == pytest.approx(2.0 * 1e-3 * 0.05, rel=0.03)  # the strips' corner 2 f l


def test_three_equal_balls_closed_form(rotor):
    # Three equal balls, a small unbalance (1 % of one ball's m l) and small friction f: the balanced family
    # is nearly the equilateral triangle at any orientation. Ball i sticks while the rotor deflection w
    # across it is within f l, |w x e_i| <= f l: three strips whose normals are 120 deg apart meet in a
    # regular hexagon of apothem f l, its corners 2 f l / sqrt(3) from the centre; turning the triangle
    # turns the hexagon, so the worst |w| over the stuck set joined to the family is 2 f l / sqrt(3).
    f, l = 1e-3, 0.05
    om = 2.0 * rotor.critical_speed
    stick, res = search(planar(rotor, 3, f, 1.5e-5), om)
    assert res["kept"] == res["runs"] >= 12
    assert res["worst"] == pytest.approx(2.0 * f * l / math.sqrt(3.0), rel=0.02)
    # and more than the two-ball parallelogram's reach of the same strips (f l / cos 60 deg = 2 f l) allows
    # for three: the third ball's strip cuts the corners
    assert res["worst"] < 0.7 * 2.0 * f * l


def test_tilting_machine_band_checked_by_simulation():
    # four balls on two tilting races: the worst arrangement lies on the edge of the stuck set, its
    # residual is the steady response there, and released stuck just inside the balls stay, just outside
    # one slips (simulated on the machine's own kernel for 200 revolutions)
    om = 4.0
    mac = two_plane(om, 0.002)
    ds = friction_margin("machine", mac, [om])
    assert "SLSQP" in ds.attrs["search"]
    stick = MachineStick(mac, om)
    centre = balanced_family(_frictionless(mac))
    offset = ds.worst_angles.values[0]
    worst = float(ds.worst_residual[0])
    amp = [float(stick.terms(c + offset)[0]) for c in centre]
    assert min(abs(a / worst - 1.0) for a in amp) < 1e-9
    assert ds.check_inside.values.tolist() == [1] and ds.check_outside.values.tolist() == [1]
