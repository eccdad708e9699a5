"""The unbalances and gravity as parts of the composed machine (issue 24, item 2): their places in
the layout, packed blocks, named parameters and case key, the spin equation their spin loads
write with a motor, and gravity's static deflection and energy in closed form. Every kernel is
run as Python (``rhs.py_func``): no driver is compiled here."""

from dataclasses import replace

import numpy as np
import pytest

from test_machine import rigid_two_plane

from rotorlab._kernels.machine_codegen import kernel_module
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed, Gravity, Machine, Motor, Unbalance
from rotorlab.models._gravity_part import GravityPart
from rotorlab.models._unbalance_part import UnbalancePart


def _with_couple(mac):
    """The two-plane rotor with a third, dynamic unbalance (static part and a couple: 3 points)."""
    return replace(mac, unbalances=mac.unbalances + (Unbalance(0, 0.003, 0.7, couple=0.002, couple_phase=1.9),))


def test_each_unbalance_is_a_part_with_its_block_stations_and_named_parameters():
    """Each unbalance becomes an UnbalancePart (the machine keeps the plain Unbalance it was
    given), placed after the races: its packed block is ``(U, cos beta, sin beta)`` per point
    unbalance (a couple ``U_c`` as ``+-U_c / d`` at ``a +- d / 2``, d = 1 m) and its stations' B
    the lateral displacement at those planes; ``unbalances[i].<field>`` sets only its block."""
    mac = _with_couple(rigid_two_plane(gravity=Gravity((0.0, -9.81, 0.0))))
    assert all(type(u) is Unbalance for u in mac.unbalances)
    parts = mac.attachments
    assert [type(p) for p in parts] == [UnbalancePart] * 3 + [GravityPart]
    lay, p = mac.layout, mac.to_array()
    rotor = lay.placed(True)
    assert [part.n_stations for part, _ in rotor] == [1, 1, 3] and lay.n_unbalance == 5
    assert [place.station for _, place in rotor] == [2, 3, 4]  # after the two races
    _, place = rotor[2]
    expect = [(0.003, np.cos(0.7), np.sin(0.7)), (0.002, np.cos(1.9), np.sin(1.9)),
              (0.002, np.cos(1.9 + np.pi), np.sin(1.9 + np.pi))]
    np.testing.assert_allclose(p[place.param:place.param + 9].reshape(3, 3), expect, rtol=0, atol=1e-16)
    for j, a in enumerate((0.0, 0.5, -0.5)):
        k = lay.station_B(place.station + j)
        np.testing.assert_array_equal(p[k:k + 8].reshape(2, 4), [[1, 0, a, 0], [0, 1, 0, a]])
    ps = mac.parameters
    assert ps["unbalances[2].couple"].value == 0.002 and ps["unbalances[2].couple"].unit == "kg*m^2"
    q = mac.pack({"unbalances[2].magnitude": 0.005})
    changed = np.flatnonzero(q != p)
    assert list(changed) == [place.param]
    assert q[place.param] == 0.005
    assert mac.with_parameters(**{"unbalances[2].magnitude": 0.005}).unbalances[2] == \
        Unbalance(0, 0.005, 0.7, couple=0.002, couple_phase=1.9)


def test_the_unbalances_spin_loads_write_the_motor_s_spin_equation():
    """With a motor, theta'' from the kernel satisfies the spin equation of the unbalances (the
    machine's Lagrangian, :mod:`rotorlab.models._unbalance_part`) ::

        J theta'' + sum_u U t_u . B_u z'' = T(Omega) + sum_b c_b (phi_b' - Omega) + sum_u U g . t_u

    evaluated from the kernel's own z'' and the packed B (a couple's points included), to 1e-12
    of its largest term; and the mass matrix's theta column is the parts' ``spin_column``."""
    g = (0.3, -9.81, 0.0)
    motor = Motor(0.4, polar_inertia=0.6, no_load_speed=2.0)
    mac = _with_couple(rigid_two_plane(motor=motor, gravity=Gravity(g)))
    lay = mac.layout
    rhs, p = kernel_module(lay).rhs.py_func, mac.to_array()
    rng = np.random.default_rng(5)
    nz, nb = lay.n_z, lay.n_balls
    for _ in range(3):
        y = mac.initial_state(rng.uniform(0, 2 * np.pi, nb), ball_rates=rng.normal(0, 0.3, nb), spin_speed=1.1,
                              z=rng.normal(0, 0.02, nz), dz=rng.normal(0, 0.05, nz))
        y[lay.i_theta] = rng.uniform(0, 2 * np.pi)
        out = np.empty_like(y)
        rhs(0.0, y, p, out)
        th, om = y[lay.i_theta], y[lay.i_theta + 1]
        zdd, thdd = out[nz:2 * nz], out[lay.i_theta + 1]
        terms = [motor.polar_inertia * thdd, -float(motor.torque_at(om))]
        terms += [-b.damping * (y[lay.i_w + k] - om) for k, b in enumerate(b for r in mac.races for b in r.balls)]
        for u in mac.unbalances:
            for a, me, beta in u.point_unbalances():
                t = np.array([-np.sin(th + beta), np.cos(th + beta)])
                terms += [me * t @ (mac.station_matrix(0, a) @ zdd), -me * t @ np.array(g[:2])]
        assert abs(sum(terms)) < 1e-12 * max(abs(x) for x in terms)
        col = sum(part.spin_column(mac, th) for part in mac.attachments[:3])
        np.testing.assert_array_equal(mac.mass_matrix(y)[:nz, -1], col)


def test_gravity_is_a_part_in_every_machine_with_the_closed_form_sag_and_energy():
    """Gravity is a part of every machine (zero without): both machines have one layout (one
    compiled kernel) and gravity's block holds ``(g_x, g_y)``, set by ``gravity.vector[k]``. A disc of mass m on stiffness k
    rests at ``y = -m g / k``: there the kernel's accelerations vanish and the energy is ``-(m
    g)^2 / (2 k)`` (the spring's ``k y^2 / 2`` plus gravity's ``-f_g . z``)."""
    m, k, g = 2.0, 800.0, 9.81
    s = LinearSystem(M=np.diag([m, m, 0.1, 0.1]), C=np.diag([0.3, 0.3, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([k, k, 50.0, 50.0]))
    bare = Machine(s, drive=ConstantSpeed(3.0))
    mac = Machine(s, gravity=Gravity((0.0, -g, 0.0)), drive=ConstantSpeed(3.0))
    assert bare.layout == mac.layout and [type(q) for q in mac.attachments] == [GravityPart]
    (_, place), = mac.layout.placed(False)
    p = mac.to_array()
    assert list(p[place.param:place.param + 2]) == [0.0, -g] and not bare.to_array()[place.param:place.param + 2].any()
    y = mac.initial_state(z=[0.0, -m * g / k, 0.0, 0.0])
    out = np.empty_like(y)
    kernel_module(mac.layout).rhs.py_func(0.0, y, p, out)
    np.testing.assert_allclose(out, 0.0, rtol=0, atol=1e-15)
    assert mac.energy(y) == pytest.approx(-(m * g) ** 2 / (2 * k), rel=1e-14)
    assert bare.energy(y) == pytest.approx(0.5 * k * (m * g / k) ** 2, rel=1e-14)
    # its named parameters gravity.vector[k] set its block (and the weights' H f_g) only
    assert [n for n in mac.parameters if n.startswith("gravity")] == [f"gravity.vector[{k}]" for k in range(3)]
    assert not [n for n in bare.parameters if n.startswith("gravity")]
    q = mac.pack({"gravity.vector[0]": 1.5})
    hf = mac.layout.offsets["Hf"]
    assert set(np.flatnonzero(q != p)) <= {place.param} | set(range(hf, hf + 4)) and q[place.param] == 1.5


def test_the_case_key_of_the_unbalances_is_a_registered_part():
    """``[[model.unbalances]]`` is registered with the parts' specs; a built machine holds the
    plain unbalances, as its constructor takes them."""
    from test_absorber_part import CASE

    from rotorlab.io import parse_case
    from rotorlab.io._build import build_machine
    from rotorlab.io._part_specs import PART_SPECS

    assert list(PART_SPECS) == ["unbalances", "absorbers"]
    mac = build_machine(parse_case(CASE.format(stiffness="0.225 N/m")).model)
    assert mac.unbalances == (Unbalance(0, 0.01),)
    assert [q.key for q in mac.attachments] == ["unbalances", "gravity", "absorbers"]
