"""The machine a ``jeffcott_balls`` rotor is (:meth:`rotorlab.models.JeffcottBalls.machine`).

One node whose translations carry the disc (mass M1, stiffness c, damping d), its tilt kept out by
``n_modes = 2`` (a tilt stiffer than the translation, so the two kept modes are the x and y
translations, scaled to unit displacement by ``unit_modes``: the machine's coordinates are x, y
themselves); a race per radius (consecutive balls of one radius share it); the disc's unbalance ``M1 e`` at
phase 0; the same speed profile. A ball of ``jeffcott_balls`` with axial inertia J_i, damping b_i
and friction f_i is a machine :class:`~rotorlab.models.Ball` with own inertia ``J_i - m_i l^2``,
damping b_i and ``coulomb = f_i`` (friction arm ``f_i l``, the jeffcott law's). The state vectors
are the same entry for entry (``[x, y, vx, vy, phi_i, w_i, (mode_i)]``) and so are the right-hand
sides, events and energies (``tests/unit/test_jeffcott_machine.py``). The machine's packed
parameters follow the ``12 + 6 n`` of ``jeffcott_balls`` (``param_base``), so that one vector
serves the model's own helpers and the machine's kernel.

Every simulation runs the machine's generated kernels: in the fixed frame :attr:`Machine.kernels`,
in the co-rotating frame (``frame="rotating"``, chosen at constant speed by
:meth:`~rotorlab.models.JeffcottBalls.cheapest_frame` where the motion settles to a steady
whirl) :attr:`Machine.rotating_kernels`, the fixed frame's lines turned with the spin
(:mod:`rotorlab._kernels.machine_corotating`); both take the same packed vector. The model's
hand-written kernels (:mod:`rotorlab._kernels.jeffcott_balls`) are the tests' oracle
(``tests/unit/test_jeffcott_machine.py``). CPU time against them: ``bench/README.md``
("Issue 24, session 13").
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache
from itertools import groupby

import numpy as np

__all__ = ["jeffcott_machine", "jeffcott_kernels", "jeffcott_layout"]

_KERNELS: dict = {}


@lru_cache(maxsize=256)
def jeffcott_machine(model):
    """Return the :class:`~rotorlab.models.Machine` that ``model`` (a JeffcottBalls, any frame) is.

    Balls of equal radius next to each other share a race (one race for the usual balancer); the
    ball order, hence the state order, is the model's.
    """
    from rotorlab.linear import LinearSystem
    from rotorlab.models._machine import Machine
    from rotorlab.models._machine_parts import Ball, BallRace, Unbalance

    r = model.rotor
    m1, c, d = r.disc_mass, r.stiffness, r.damping
    # the tilt carries nothing: stiffer than the translation, it is left out by n_modes = 2
    s = LinearSystem(M=np.diag([m1, m1, m1, m1]), C=np.diag([d, d, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([c, c, 4.0 * c + 1.0, 4.0 * c + 1.0]))
    races = tuple(
        BallRace(0, radius, tuple(Ball(b.mass, inertia=max(b.inertia - b.mass * radius**2, 0.0),
                                       damping=b.damping, coulomb=b.friction) for b in group))
        for radius, group in ((k, list(g)) for k, g in groupby(model.balls, key=lambda b: b.radius)))
    return Machine(s, races=races, unbalances=(Unbalance(0, m1 * r.eccentricity),), drive=model.speed,
                   n_modes=2, unit_modes=True, param_base=12 + 6 * model.n_balls)


def jeffcott_layout(model):
    """What decides ``model``'s compiled kernel: the frame and the preset machine's layout."""
    return (model.frame, jeffcott_machine(replace(model, frame="fixed")).layout)


#: the preset machine's kernels of each frame of a jeffcott_balls model
_FRAME_KERNELS = {"fixed": "kernels", "rotating": "rotating_kernels"}


def jeffcott_kernels(model):
    """The :class:`~rotorlab.models.Kernels` of ``model`` (shared per compiled layout): the preset
    machine's, of the model's frame, their events named ``stick_<i>``, ``slip_<i>`` by the model's
    ball number ``i``."""
    key = jeffcott_layout(model)
    if key in _KERNELS:
        return _KERNELS[key]
    from rotorlab.models._base import EventSpec

    mac = jeffcott_machine(replace(model, frame="fixed"))
    mk = getattr(mac, _FRAME_KERNELS[model.frame])
    specs = tuple(EventSpec(f"{kind}_{i}", -1, "reset") for i in range(1, model.n_balls + 1)
                  for kind in ("stick", "slip")) if model.has_friction else ()
    _KERNELS[key] = replace(mk, event_specs=specs) if specs else mk
    return _KERNELS[key]
