"""A torque-limited, speed-commanded drive (what a variable-frequency drive does).

The drive commands a speed profile -- a ramp at ``ramp_rate`` from the initial speed, an optional
dwell at ``dwell_speed`` for ``dwell_time``, then the ramp on to ``operating_speed`` and a hold --
and its speed loop asks for the torque ``K (Omega_cmd(t) - Omega)`` (``gain`` K, N m s/rad),
limited by the motor's torque characteristic T_max(Omega) (linear or tabulated, as
:class:`rotorlab.models.Motor`)::

    T = min(T_max(Omega), max(-T_max(Omega), K (Omega_cmd(t) - Omega)))

The spin angle and speed are states (a :class:`Motor` subclass), so a rotor whose torque limit
is too low for the resonance's drag is captured at a critical speed (the Sommerfeld effect). The
command's six numbers ride in the machine's speed block (unused with a motor); the kernel's lines
are ``rotorlab._kernels.machine_drive.DRIVES["servo_linear" | "servo_table"]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from rotorlab.models._machine_parts import Motor, _num
from rotorlab.models._parameters import _GE0, _GT0

__all__ = ["ServoDrive"]


@dataclass(frozen=True, slots=True)
class ServoDrive(Motor):
    """A speed-commanded motor whose torque is limited by its characteristic.

    Parameters
    ----------
    torque, polar_inertia, no_load_speed
        The torque limit T_max(Omega) and the spinning inertia, as :class:`Motor`
        (``no_load_speed`` may be ``inf``: a constant limit ``torque``).
    operating_speed : float
        The command's final speed (rad/s), > 0.
    ramp_rate : float
        The command's acceleration (rad/s^2), > 0.
    dwell_speed, dwell_time : float
        Hold the command at ``dwell_speed`` (rad/s, clipped to [initial, operating]) for
        ``dwell_time`` (s, >= 0; 0: no dwell).
    gain : float
        Proportional speed-loop gain K (N m s/rad), > 0.
    initial_speed : float
        The command's speed at t = 0 (rad/s), >= 0 (the machine's initial spin speed).
    """

    #: Named parameters of the command: ``drive.<field>``
    fields: ClassVar[tuple] = (("ramp_rate", "rad/s^2", _GT0), ("dwell_speed", "rad/s", _GE0),
                               ("dwell_time", "s", _GE0), ("operating_speed", "rad/s", _GT0),
                               ("gain", "N*m*s/rad", _GT0))

    operating_speed: float = 1.0
    ramp_rate: float = 1.0
    dwell_speed: float = 0.0
    dwell_time: float = 0.0
    gain: float = 1.0
    initial_speed: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.torque, (tuple, list)) and self.no_load_speed == math.inf:
            object.__setattr__(self, "no_load_speed", 1e300)  # a constant limit
        Motor.__post_init__(self)
        o = "ServoDrive"
        for name, unit, strict in (("operating_speed", "rad/s", True), ("ramp_rate", "rad/s^2", True),
                                   ("dwell_speed", "rad/s", False), ("dwell_time", "s", False),
                                   ("gain", "N m s/rad", True), ("initial_speed", "rad/s", False)):
            object.__setattr__(self, name, _num(o, name, getattr(self, name), unit, strict=strict))
        if self.initial_speed > self.operating_speed:
            raise ValueError(f"ServoDrive.initial_speed must be <= operating_speed "
                             f"({self.operating_speed:g} rad/s), got {self.initial_speed!r}")

    @property
    def drive_kind(self) -> str:
        return "servo_" + self.kind

    @property
    def dwell(self) -> float:
        """The dwell speed clipped to [initial, operating] (rad/s)."""
        return min(max(self.dwell_speed, self.initial_speed), self.operating_speed)

    def speed_block(self) -> np.ndarray:
        """``[w0, rate, w_dwell, t_dwell_end, w_op, K]``: the command in the speed block."""
        wd = self.dwell
        t_end = (wd - self.initial_speed) / self.ramp_rate + self.dwell_time
        return np.array([self.initial_speed, self.ramp_rate, wd, t_end, self.operating_speed, self.gain])

    def command(self, t):
        """The commanded speed Omega_cmd(t) (rad/s) at times ``t`` (s)."""
        w0, a, wd, te, wop, _ = self.speed_block()
        t = np.asarray(t, dtype=float)
        return np.where(t < te, np.minimum(w0 + a * t, wd), np.minimum(wd + a * (t - te), wop))

    @property
    def command_duration(self) -> float:
        """When the command reaches the operating speed (s)."""
        w0, a, wd, te, wop, _ = self.speed_block()
        return te + (wop - wd) / a

    def torque_command(self, t, speed):
        """The drive's torque at times ``t`` and speeds ``speed`` (N m)."""
        tl = self.torque_at(speed)
        return np.minimum(tl, np.maximum(-tl, self.gain * (self.command(t) - np.asarray(speed, float))))

    def scaled(self, factor: float) -> ServoDrive:
        """This drive with its torque limit times ``factor`` (> 0)."""
        m = Motor.scaled(self, factor)
        return replace(self, torque=m.torque)
