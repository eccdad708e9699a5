"""The machine a rub rotor is (:attr:`rotorlab.contact.JeffcottRub.machine`).

One node whose translations carry the rotor (mass m, stiffness k, damping c), its tilt kept out by
``n_modes = 2`` (a tilt stiffer than the translation, so the two kept modes are the x and y
translations, scaled to unit displacement by ``unit_modes``: the machine's coordinates are x, y
themselves); the unbalance ``m eps`` at phase 0; lateral gravity ``(g_x, g_y)``; a constant spin;
a :class:`~rotorlab.models.Clearance` at that node with the rub rotor's clearance, restitution,
friction, rotor radius and rest speed, a rigid stator or a massless elastic one (``k_s, c_s``),
centred on the axis and without the machine's Baumgarte stabilisation (``stabilisation = 0``:
the rub rotor's rigid contact holds ``r'' = 0`` exactly).

Term by term (``tests/unit/test_rub_machine.py``): the machine's contact point is the centre
(``B = I``), its Delassus matrix ``W = I / m``, so :func:`rotorlab._kernels.contact.delassus_forces`
is :func:`~rotorlab._kernels.contact.sustained_forces` of the point mass, the impulse law is the
same :func:`~rotorlab._kernels.contact.newton_coulomb_impulse` with ``W = I / m``, and the
pressing test of a settling impact (``b_n > 0``) is the rub rotor's ``a_n + v_t^2 / delta > 0``
with the radius ``|w|`` of the projected state (``delta`` to round-off). The states are the same
entry for entry (``[x, y, vx, vy, dissipated, drive_work, impacts, peak_impulse, mode]``), so are
the right-hand sides, events and reset maps (to round-off) and the event names. The energies
differ by the machine's unbalance coupling ``U Omega t_u . v`` and its gravity potential, which
the rub rotor's :meth:`~rotorlab.contact.JeffcottRub.energy` leaves out.

The packed parameters are the rub rotor's 15 (:mod:`rotorlab._kernels.jeffcott_rub`) followed by
the machine's (``param_base``): the model's own helpers (``start_mode``, the sanity monitor, a
rub map's rows) read the first, the machine's kernel the rest. The old kernel
(:mod:`rotorlab._kernels.jeffcott_rub`) is kept only as the tests' oracle.

Measured against the old kernel (rub-jeffcott's rotor, its 9 x 7 speed x clearance map, 5 s from
rest, rtol 1e-9; and a rigid-stator map of 20 points): the same statuses and contact modes at
every saved sample, states within 2.6e-10 (elastic) and 8.4e-13 (rigid) of the largest entry.
CPU (``bench/rub.py``): the lane ensemble took 1.6-1.8 times the old kernel's, for two measured
causes: the lane driver's loop over the lanes' event functions called the generated
``contact_terms`` per lane (no SIMD; now inlined, it vectorises), and the general structure's
arithmetic (``B z`` with ``B = I``, products with the diagonal structure's zeros). The kernel
(:func:`rub_kernels`) therefore takes the entries every rub rotor shares as compile-time
constants (:func:`rub_layout`, ``Layout.fixed``): the same bits, 1.04-1.08 times the old
kernel's CPU time on lanes (``bench/README.md``, issue 24 session 13).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

__all__ = ["rub_machine", "rub_kernels", "rub_layout", "RUB_PARAM_BASE"]

#: The rub rotor's own packed entries in front of the machine's.
RUB_PARAM_BASE = 15


@lru_cache(maxsize=256)
def rub_machine(model):
    """Return the :class:`~rotorlab.models.Machine` that ``model`` (a JeffcottRub) is."""
    from rotorlab.linear import LinearSystem
    from rotorlab.models._machine import Machine
    from rotorlab.models._machine_parts import Clearance, ElasticStator, Gravity, Unbalance
    from rotorlab.models._speed import ConstantSpeed

    r = model.rotor
    m, k, c = r.mass, r.stiffness, r.damping
    # the tilt carries nothing: stiffer than the translation, it is left out by n_modes = 2
    s = LinearSystem(M=np.diag([m, m, m, m]), C=np.diag([c, c, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([k, k, 4.0 * k + 1.0, 4.0 * k + 1.0]))
    stator = "rigid" if r.rigid_stator else ElasticStator(r.stator_stiffness, r.stator_damping)
    cl = Clearance(0, r.clearance, stator, restitution=model.restitution, friction=r.friction,
                   rotor_radius=r.rotor_radius, rest_speed=model.rest_speed, stabilisation=0.0)
    gx, gy = model.gravity
    gravity = Gravity((gx, gy, 0.0)) if (gx, gy) != (0.0, 0.0) else None
    return Machine(s, unbalances=(Unbalance(0, m * r.eccentricity),), gravity=gravity,
                   drive=ConstantSpeed(model.spin_speed), clearances=(cl,), n_modes=2, unit_modes=True,
                   param_base=RUB_PARAM_BASE)


def _structural_entries(lay) -> dict[int, float]:
    """The packed entries of the preset machine that every rub rotor has, whatever its named
    parameters: the coordinates are x and y themselves (every station's ``B = I``), the structure
    is diagonal (the off-diagonal entries of ``H B^T``, ``L``, ``H K``, ``H C`` are 0), the
    unbalance has phase 0, the clearance is centred, without Baumgarte stabilisation and without
    housing mass. (A rigid stator's ``k_s = c_s = 0`` and a zero gravity are left run-time
    numbers: rigid and elastic stators, with gravity or without, share one compiled kernel.)"""
    out: dict[int, float] = {}
    o, ns = lay.offsets, lay.n_all_stations
    for s in range(ns):
        out.update(zip(range(lay.station_B(s), lay.station_B(s) + 4), (1.0, 0.0, 0.0, 1.0)))
        out.update({lay.station_HBT(s) + 1: 0.0, lay.station_HBT(s) + 2: 0.0})
        for s2 in range(ns):
            out.update({lay.pair_L(s, s2) + 1: 0.0, lay.pair_L(s, s2) + 2: 0.0})
    out.update({o["HK"] + 1: 0.0, o["HK"] + 2: 0.0, o["HC"] + 1: 0.0, o["HC"] + 2: 0.0})
    out.update({o["unbalances"] + 1: 1.0, o["unbalances"] + 2: 0.0})
    kc = o["clearance"]
    out.update({kc + 7: 0.0, kc + 8: 0.0, kc + 9: 0.0, kc + 10: 0.0})
    return out


@lru_cache(maxsize=256)
def rub_layout(model):
    """The preset machine's layout with its structural entries as compile-time constants
    (``Layout.fixed``, folded into the generated kernel by :mod:`rotorlab._kernels.machine_fold`):
    the kernel then does the arithmetic of the hand-written one, not that of a general structure.
    An entry is taken only where the packed vector holds the value it must have (a claim that
    did not hold would leave the entry a run-time number: slower, never wrong)."""
    from dataclasses import replace

    mac = rub_machine(model)
    p = mac.to_array()
    claims = _structural_entries(mac.layout)
    return replace(mac.layout, fixed=tuple((k, v) for k, v in claims.items() if p[k] == v))


@lru_cache(maxsize=256)
def rub_kernels(model):
    """The compiled kernels of the rub rotor: its preset machine's, generated for :func:`rub_layout`."""
    return rub_machine(model).kernels_for(rub_layout(model))
