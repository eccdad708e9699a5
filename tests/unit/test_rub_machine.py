"""The rub rotor is a preset of the machine (issue 24, item 3).

The oracle is the rub rotor's own hand-written kernel (:mod:`rotorlab._kernels.jeffcott_rub`, itself
checked against the closed forms of :mod:`rotorlab.contact` in tests/validation): the preset
machine must give its right-hand side, its event functions and its reset maps (impacts with
restitution and Coulomb friction, chatter settling, lift-off, stick, slip) to 1e-12 at random
states, inside and beyond the clearance and in every contact mode, including modes that do not
fit the state (contact set while the rotor is off the stator, rolling while it slips), with a
rigid and an elastic stator. Its energy is the rub rotor's plus exactly the unbalance coupling
``U Omega t_u . v`` and the gravity potential ``-m g . z`` the rub rotor leaves out.
"""

import math

import numpy as np
import pytest

from rotorlab._kernels import jeffcott_rub as oracle
from rotorlab.contact import JeffcottRub, RubRotor

RIGID = JeffcottRub(RubRotor(mass=1.3, stiffness=2.0, clearance=0.8, damping=0.07, eccentricity=0.3,
                             friction=0.25, rotor_radius=0.4), spin_speed=1.7, restitution=0.6,
                    rest_speed=0.05, gravity=(0.3, -0.9))  # fmt: skip
ELASTIC = JeffcottRub(RubRotor(mass=1.3, stiffness=2.0, clearance=0.8, damping=0.07, eccentricity=0.3,
                               stator_stiffness=40.0, stator_damping=0.5, friction=0.25, rotor_radius=0.4),
                      spin_speed=1.7, gravity=(0.3, -0.9))  # fmt: skip
MODES = (0.0, 1.0, -1.0, 2.0)


def states(model, seed, n=40):
    """Random times and states: radius 0.5 to 1.3 clearances, any velocity, each contact mode."""
    rng = np.random.default_rng(seed)
    delta = model.rotor.clearance
    for i in range(n):
        r, a = delta * rng.uniform(0.5, 1.3), rng.uniform(0.0, 2.0 * math.pi)
        y = np.array([r * math.cos(a), r * math.sin(a), *rng.normal(size=2), *rng.uniform(0.0, 1.0, 2),
                      float(rng.integers(0, 5)), rng.uniform(0.0, 0.1), MODES[i % 4]])
        yield rng.uniform(0.0, 20.0), y


def close(a, b):
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * max(1.0, float(np.abs(b).max())))


@pytest.mark.parametrize("model", [RIGID, ELASTIC], ids=["rigid", "elastic"])
def test_preset_machine_has_the_rhs_events_and_resets_of_the_rub_rotor(model):
    mac = model.machine
    assert mac.n_state == 9 and mac.layout.n_discrete == 3
    assert mac.clearances[0].kind == ("rigid" if model.rotor.rigid_stator else "elastic")
    np.testing.assert_array_equal(mac.basis[:2], np.eye(2))  # coordinates are x, y themselves
    assert [e.name for e in model.kernels.event_specs] == ["contact", "lift_off", "stick", "slip"]
    p = model.to_array()
    own = p[:oracle.N_PARAM]
    assert p.size == mac.layout.n_param and np.array_equal(p[oracle.N_PARAM:], mac.to_array()[oracle.N_PARAM:])
    k = model.kernels
    fired = set()
    for t, y in states(model, seed=7):
        fo, fm = np.empty(9), np.empty(9)
        oracle.rhs(t, y, own, fo)
        k.rhs(t, y, p, fm)
        close(fm, fo)
        go, gm = np.empty(4), np.empty(4)
        oracle.events(t, y, own, go)
        k.events(t, y, p, gm)
        close(gm, go)
        for ev in range(4):
            yo, ym = np.empty(9), np.empty(9)
            oracle.reset(ev, t, y, own, yo)
            k.reset(ev, t, y, p, ym)
            close(ym, yo)
            fired.add((ev, y[8], yo[8]))
    # the reset maps went through their branches: impacts that rebound (rigid) or slide either
    # way, chatter settled into rolling (rigid), sliding after the cone is reached either way
    after = {ev: {new for e, _, new in fired if e == ev} for ev in range(4)}
    assert after[0] >= ({0.0, 1.0, -1.0, 2.0} if model.rotor.rigid_stator else {1.0, -1.0})
    assert after[1] == {0.0} and after[2] >= {1.0, -1.0, 2.0} and after[3] == {1.0, -1.0}


@pytest.mark.parametrize("model", [RIGID, ELASTIC], ids=["rigid", "elastic"])
def test_preset_machine_energy_is_the_rub_rotors_plus_the_unbalance_coupling_and_gravity(model):
    mac, r = model.machine, model.rotor
    w, gx, gy = model.spin_speed, *model.gravity
    for t, y in states(model, seed=3, n=12):
        coupling = r.mass * r.eccentricity * w * (-math.sin(w * t) * y[2] + math.cos(w * t) * y[3])
        gravity = -r.mass * (gx * y[0] + gy * y[1]) - r.mass * r.eccentricity * (gx * math.cos(w * t) + gy * math.sin(w * t))
        assert mac.energy(y, t) == pytest.approx(float(model.energy(y)) + coupling + gravity, rel=1e-12, abs=1e-12)


def test_rigid_and_elastic_stators_share_one_compiled_kernel():
    """A massless stator is rigid or elastic at run time (its stiffness k_s > 0): one layout,
    one kernel module, one driver copy for both (the rub rotor had one kernel for both)."""
    assert RIGID.machine.layout == ELASTIC.machine.layout and RIGID.kernels.rhs is ELASTIC.kernels.rhs


def test_pack_fills_both_the_rub_rotors_entries_and_the_machines():
    p = RIGID.pack({"clearance": 0.9, "spin_speed": 2.0})
    v = RIGID.with_parameters(clearance=0.9, spin_speed=2.0)
    np.testing.assert_array_equal(p, v.to_array())
    assert p[oracle.P_D] == 0.9 and p[oracle.P_W] == 2.0
    o = v.machine.layout.offsets
    assert p[o["clearance"]] == 0.9 and p[o["speed"] + 1] == 2.0 and p[o["clearance"] + 10] == 0.0


@pytest.mark.parametrize("model", [RIGID, ELASTIC], ids=["rigid", "elastic"])
def test_kernel_takes_the_entries_every_rub_rotor_shares_as_constants_with_the_same_bits(model):
    """The rub rotor's kernel is its machine's with the entries every rub rotor shares folded in
    (``B = I``, the diagonal structure's zeros, phase 0, a centred clearance without
    stabilisation: :func:`rotorlab.models._rub_machine.rub_layout`): it reads none of them, and
    gives the machine's own kernel's numbers bit for bit (rhs, events, every reset map) at
    random states in every contact mode."""
    import inspect
    import re

    from rotorlab.models._rub_machine import _structural_entries, rub_layout

    fixed = dict(rub_layout(model).fixed)
    p = model.to_array()
    # every claim holds (30 entries: 2 stations' B and H B^T, 4 L blocks, H K, H C, the phase,
    # the clearance's centre, stabilisation and housing mass)
    assert fixed == _structural_entries(model.machine.layout) and len(fixed) == 30
    assert all(p[k] == v for k, v in fixed.items())
    k, plain = model.kernels, model.machine.kernels
    for f in (k.rhs, k.events, k.reset):
        read = {int(i) for i in re.findall(r"\bp\[(\d+)\]", inspect.getsource(f.py_func))}
        assert not read & fixed.keys(), f.__name__
    assert {int(i) for i in re.findall(r"\bp\[(\d+)\]", inspect.getsource(plain.rhs.py_func))} & fixed.keys()
    for t, y in states(model, seed=11):
        a, b = np.empty(9), np.empty(9)
        k.rhs(t, y, p, a)
        plain.rhs(t, y, p, b)
        np.testing.assert_array_equal(a, b)
        ga, gb = np.empty(4), np.empty(4)
        k.events(t, y, p, ga)
        plain.events(t, y, p, gb)
        np.testing.assert_array_equal(ga, gb)
        for ev in range(4):
            ya, yb = np.empty(9), np.empty(9)
            assert k.reset(ev, t, y, p, ya) == plain.reset(ev, t, y, p, yb)
            np.testing.assert_array_equal(ya, yb)
