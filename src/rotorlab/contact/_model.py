"""The Jeffcott rotor in a circular clearance: the reference model of the contact law.

The smallest model on the kernel contract (:mod:`rotorlab.models._base`) that carries the whole
contact law of :mod:`rotorlab._kernels.contact`: located impacts with Newton restitution and a
Coulomb impulse (stick or slip, the rotor's surface speed in the slip), chatter turned into
sustained contact, sliding and rolling sustained contact (full rub, backward whirl), stick-slip
transitions and lift-off, against a rigid or an elastic (massless) stator. It is what the closed
forms of :mod:`rotorlab.contact._theory` are checked against in simulation.

Equations (fixed frame, complex ``z = x + i y``)::

    m z'' + c z' + k z = m eps Omega^2 e^{i Omega t} + m g + (-N + i F_t) z / |z|   (in contact)

with ``N`` and ``F_t`` from the contact law: a rigid stator holds ``|z| = delta`` (``N`` the
constraint force), an elastic one pushes with ``N = max(0, k_s (|z| - delta) + c_s d|z|/dt)``;
sliding ``F_t = -mu sign(s) N`` with the slip ``s = u_t + R_r Omega``, rolling ``F_t`` keeps
``s = 0`` while ``|F_t| <= mu N``. The spin ``Omega`` is prescribed (a drive holds it: its work
through the friction torque is the ``drive`` state).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rotorlab._kernels import jeffcott_rub as _k
from rotorlab.contact._theory import RubRotor
from rotorlab.models._base import Kernels
from rotorlab.models._checks import check_number as _num
from rotorlab.models._machine_clearance import pressed_contact_mode
from rotorlab.models._parameters import rub_slots
from rotorlab.models._protocol import ParametrisedMixin

__all__ = ["JeffcottRub"]

MODES = {0: "free", 1: "sliding (positive slip)", -1: "sliding (negative slip)", 2: "rolling"}


@dataclass(frozen=True, slots=True)
class JeffcottRub(ParametrisedMixin):
    """A Jeffcott rotor at constant spin in a circular clearance with a rigid or elastic stator.

    Its named parameters (:attr:`parameters`, :meth:`with_parameters`, :meth:`pack`) are the
    ``rub_rotor`` table's keys: ``mass``, ``stiffness``, ``damping``, ``eccentricity``,
    ``clearance``, ``stator_stiffness`` and ``stator_damping`` (elastic stator only),
    ``friction``, ``rotor_radius``, ``restitution``, ``rest_speed``, ``spin_speed``.

    Parameters
    ----------
    rotor : RubRotor
        Rotor, clearance, stator and friction (``stator_mass`` must be 0: a moving housing needs
        the composed machine).
    spin_speed : float
        Omega, prescribed spin speed (rad/s), >= 0.
    restitution : float
        e, Newton's coefficient of restitution of a rigid stator, in [0, 1].
    rest_speed : float
        Rebound speed (m/s) below which a pressed rotor's impacts are treated as accumulated
        (chatter): one plastic impulse, then sustained contact. The skipped time is below
        ``2 rest_speed / (a (1 - e))`` for a pressing acceleration ``a``. It must exceed the
        speed the integrator resolves, ``sqrt(2 a atol)``: a rebound lower than the position
        tolerance cannot be located.
    gravity : tuple of float
        (g_x, g_y), lateral acceleration of gravity (m/s^2).

    Notes
    -----
    State ``[x, y, vx, vy, dissipated, drive_work, impacts, peak_impulse, mode]`` (the last three
    discrete); its 15 packed parameters and events are documented in
    :mod:`rotorlab._kernels.jeffcott_rub` (now the tests' oracle): the packed vector carries
    them first, then those of the preset machine (:attr:`machine`) whose generated kernel runs
    every simulation. ``energy(y) = m |v|^2 / 2 + k |z|^2 / 2`` (+ the
    stator's ``k_s p^2 / 2``); without unbalance, gravity and rotor damping,
    ``energy(y) - energy(y0) = drive_work - dissipated`` exactly.

    Examples
    --------
    >>> from rotorlab.contact import RubRotor
    >>> m = JeffcottRub(RubRotor(1.0, 1.0, 1.0, stator_stiffness=10.0), spin_speed=1.5)
    >>> m.to_array()[[4, 5, 6, 14]].tolist()
    [1.5, 1.0, 10.0, 0.0]
    >>> m.with_parameters(clearance=0.8).rotor.clearance, float(m.pack({"spin_speed": 2.0})[4])
    (0.8, 2.0)
    """

    rotor: RubRotor
    spin_speed: float
    restitution: float = 0.5
    rest_speed: float = 1e-5
    gravity: tuple[float, float] = field(default=(0.0, 0.0))

    def __post_init__(self) -> None:
        o = "JeffcottRub"
        if not isinstance(self.rotor, RubRotor):
            raise ValueError(f"{o}.rotor must be a RubRotor, got {type(self.rotor).__name__}")
        if self.rotor.stator_mass != 0.0:
            raise ValueError(
                f"{o}.rotor.stator_mass must be 0 (a massless stator), got {self.rotor.stator_mass!r} kg"
            )
        object.__setattr__(self, "spin_speed", _num(o, "spin_speed", self.spin_speed, lo_open=False, unit="rad/s"))
        object.__setattr__(self, "restitution", _num(o, "restitution", self.restitution, lo_open=False, hi=1.0))
        object.__setattr__(self, "rest_speed", _num(o, "rest_speed", self.rest_speed, unit="m/s"))
        g = tuple(_num(o, f"gravity[{i}]", v, lo=None, unit="m/s^2") for i, v in enumerate(self.gravity))
        if len(g) != 2:
            raise ValueError(f"{o}.gravity must be (g_x, g_y), got {self.gravity!r}")
        object.__setattr__(self, "gravity", g)

    @property
    def machine(self):
        """The :class:`~rotorlab.models.Machine` this rotor is (:mod:`rotorlab.models._rub_machine`):
        its generated kernel runs every simulation of this model."""
        from rotorlab.models._rub_machine import rub_machine

        return rub_machine(self)

    @property
    def kernels(self) -> Kernels:
        """The preset machine's compiled kernels (events ``contact``, ``lift_off``, ``stick``,
        ``slip``), with the preset's structural entries as constants
        (:func:`rotorlab.models._rub_machine.rub_kernels`); the packed vector is :meth:`to_array`."""
        from rotorlab.models._rub_machine import rub_kernels

        return rub_kernels(self)

    def _compiled_layout(self):
        from rotorlab.models._rub_machine import rub_layout

        return rub_layout(self)

    def _parameter_slots(self):
        return rub_slots(self)

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("x", "y", "vx", "vy", "dissipated", "drive_work", "impacts", "peak_impulse", "mode")

    def to_array(self) -> np.ndarray:
        """The packed parameters: the 15 of :mod:`rotorlab._kernels.jeffcott_rub`, then the
        preset machine's (its kernel's, ``param_base``)."""
        r = self.rotor
        rigid = r.rigid_stator
        own = np.array([
            r.mass, r.stiffness, r.damping, r.eccentricity, self.spin_speed, r.clearance,
            0.0 if rigid else r.stator_stiffness, r.stator_damping, r.friction, r.rotor_radius,
            self.restitution, self.rest_speed, self.gravity[0], self.gravity[1], 1.0 if rigid else 0.0,
        ])  # fmt: skip
        p = self.machine.to_array()
        p[:own.size] = own
        return p

    def initial_state(self, position=(0.0, 0.0), velocity=(0.0, 0.0)) -> np.ndarray:
        """State at rest in the contact accounting: free (mode 0) inside the clearance, pressed
        into an elastic stator sliding with the sign of its slip (:meth:`start_mode`); the position
        must be inside the clearance for a rigid stator."""
        x, y = (float(v) for v in position)
        if self.rotor.rigid_stator and math.hypot(x, y) > self.rotor.clearance:
            raise ValueError(
                f"JeffcottRub.initial_state: position {position!r} lies outside the rigid stator "
                f"(clearance {self.rotor.clearance:g} m)"
            )
        y0 = np.array([x, y, float(velocity[0]), float(velocity[1]), 0.0, 0.0, 0.0, 0.0, 0.0])
        y0[_k.MODE] = self.start_mode(y0, self.to_array())
        return y0

    def start_mode(self, y, params) -> float:
        """Contact mode that the start ``y`` takes under the packed parameters ``params`` (a rub
        map's point): 0 inside the clearance (or beyond a rigid stator: the sanity check then fails
        the run); pressed into an elastic stator, sliding with the sign of its slip
        (:func:`rotorlab.models._machine_clearance.pressed_contact_mode`, as the machine's)."""
        p = np.asarray(params, dtype=float)
        if p[_k.P_RIGID] != 0.0 or math.hypot(y[_k.X], y[_k.Y]) <= p[_k.P_D]:
            return 0.0
        return pressed_contact_mode(y[_k.X:_k.Y + 1], y[_k.VX:_k.VY + 1], p[_k.P_R] * p[_k.P_W])

    def impossible_states(self, ys, y_final, t_final, params) -> list[str]:
        """Sanity monitor (kernel contract item 6): runs where the rotor went through a rigid stator.

        A rigid stator holds the centre on ``|z| <= delta`` up to the event tolerance; beyond
        ``delta (1 + 1e-6)`` a rebound lower than the integrator resolves was missed (raise
        ``rest_speed`` above ``sqrt(2 a atol)``): a failed run. (An elastic stator may yield by
        any amount: its deflection is the physics, e.g. a full rub on a soft stator.)

        Parameters
        ----------
        ys : ndarray, shape (N, n_save, 9)
        y_final : ndarray, shape (N, 9)
        t_final : ndarray, shape (N,)
        params : ndarray, shape (N or 1, 15)

        Returns
        -------
        list of str
            Per run, empty or the message naming the radius, the clearance and the time.
        """
        ys, y_final, params = np.asarray(ys, float), np.asarray(y_final, float), np.atleast_2d(params)
        n = y_final.shape[0]
        delta = np.broadcast_to(params[:, _k.P_D], (n,))
        rigid = np.broadcast_to(params[:, _k.P_RIGID] != 0.0, (n,))
        radius = np.hypot(ys[..., _k.X], ys[..., _k.Y]) if ys.size else np.zeros((n, 0))
        r_final = np.hypot(y_final[:, _k.X], y_final[:, _k.Y])
        out = []
        for i in range(n):
            r = np.concatenate([radius[i][np.isfinite(radius[i])], [r_final[i]]])
            worst = float(r.max())
            if not rigid[i] or worst <= delta[i] * (1.0 + 1e-6):
                out.append("")
            else:
                out.append(f"the rotor passed through the rigid stator: radius {worst:.6g} m, "
                           f"{worst - delta[i]:.3g} m beyond the clearance {delta[i]:g} m (by t = {t_final[i]:.6g} s); "
                           "a rebound lower than the tolerances resolve was missed: raise rest_speed")  # fmt: skip
        return out

    @property
    def rub_parameters(self) -> dict[str, tuple[int, str]]:
        """Parameters a rub map may vary: name -> (index in :meth:`to_array`, unit)."""
        out = {"spin_speed": (_k.P_W, "rad/s"), "clearance": (_k.P_D, "m"), "eccentricity": (_k.P_EPS, "m"),
               "friction": (_k.P_MU, "1"), "stator_stiffness": (_k.P_KS, "N/m"), "restitution": (_k.P_E, "1")}
        if self.rotor.rigid_stator:  # a rigid stator has no stiffness to vary
            del out["stator_stiffness"]
        return out

    def contact_samples(self, ts, ys, params=None):
        """The contact at saved samples (:class:`rotorlab.contact.ContactSamples`); the normal
        force from the preset machine's compiled contact law (the states are the machine's)."""
        return self.machine.contact_samples(ts, ys, self.to_array() if params is None else params,
                                            layout=self._compiled_layout())

    def gap_state(self, position=(0.0, 0.0), velocity=(0.0, 0.0)) -> np.ndarray:
        """Initial state with the centre at ``position`` (m) moving at ``velocity`` (m/s)."""
        return self.initial_state(position, velocity)

    def whirl_state(self, radius: float, whirl_speed: float) -> np.ndarray:
        """Initial state on a circular whirl: ``(radius, 0)`` moving at ``(0, whirl_speed radius)``."""
        return self.initial_state((radius, 0.0), (0.0, whirl_speed * radius))

    def equivalent_rub_rotor(self) -> RubRotor:
        """The rotor of the closed forms (:class:`RubRotor`): this model's own."""
        return self.rotor

    def energy(self, y) -> np.ndarray:
        """Kinetic + shaft + stator elastic energy (J), shape of ``y[..., 0]``."""
        y = np.asarray(y, dtype=float)
        r = self.rotor
        rad = np.hypot(y[..., 0], y[..., 1])
        e = 0.5 * r.mass * (y[..., 2] ** 2 + y[..., 3] ** 2) + 0.5 * r.stiffness * rad**2
        if not r.rigid_stator:
            pen = np.maximum(rad - r.clearance, 0.0)
            e = e + 0.5 * r.stator_stiffness * pen**2
        return e
