"""The drive's lines in the machine's generated kernel: the spin (a prescribed profile of each
kind, or a motor's states) and a motor's torque characteristic, one entry per kind.

:data:`DRIVES` maps a layout's ``drive`` (``"profile"``, ``"linear"``, ``"table"``) to its
:class:`DriveLines`; a prescribed profile's spin lines come from :data:`PROFILE_SPIN` by the
layout's ``speed_kind`` (whether each vectorises: :data:`rotorlab._kernels.machine_layout.SPEED_KINDS`).
The spin lines define ``theta``, ``om`` (and ``dom``, the spin's rate, for a prescribed spin);
the torque lines define ``torque`` (a motor's, the right-hand side of its spin equation).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from rotorlab._kernels.machine_layout import Layout

__all__ = ["DRIVES", "PROFILE_SPIN", "DriveLines", "spin_lines", "torque_lines"]


def _constant(k: int) -> list[str]:
    return [f"    om = p[{k + 1}]", "    theta = om * t", "    dom = 0.0"]


def _ramp(k: int) -> list[str]:
    return [f"    w0 = p[{k + 1}]", f"    w1 = p[{k + 2}]", f"    dur = p[{k + 3}]",
            "    slope = (w1 - w0) / dur", "    tc = min(max(t, 0.0), dur)", "    om = w0 + slope * tc",
            "    theta = w0 * tc + 0.5 * slope * tc * tc + om * (t - tc)",
            "    dom = slope if (t >= 0.0 and t < dur) else 0.0"]


def _general(k: int) -> list[str]:  # any profile through rotorlab._kernels.speed.profile
    return [f"    theta, om, dom = profile(t, p, {k})"]


#: Spin lines of a prescribed profile by its kind, given the offset of the speed block.
PROFILE_SPIN: dict[str, Callable[[int], list[str]]] = {"constant": _constant, "ramp": _ramp, "hill": _general}


def _prescribed(lay: Layout) -> list[str]:
    return PROFILE_SPIN[lay.speed_kind](lay.offsets["speed"])


def _motor_spin(lay: Layout) -> list[str]:
    return [f"    theta = y[{lay.i_theta}]", f"    om = y[{lay.i_theta + 1}]"]


def _linear_torque(lay: Layout) -> list[str]:
    km = lay.offsets["motor"]
    return [f"    torque = p[{km + 1}] * (1.0 - om / p[{km + 2}])"]


def _table_torque(lay: Layout) -> list[str]:  # piecewise linear, held at the ends
    km, nt = lay.offsets["motor"], lay.n_table
    ks, kt = km + 3, km + 3 + nt
    out = [f"    torque = p[{kt}]"]
    for q in range(nt - 1):
        out += [f"    fr = min(max((om - p[{ks + q}]) / (p[{ks + q + 1}] - p[{ks + q}]), 0.0), 1.0)",
                f"    torque += fr * (p[{kt + q + 1}] - p[{kt + q}])"]
    return out


def _servo(characteristic: Callable[[Layout], list[str]]) -> Callable[[Layout], list[str]]:
    """A speed-commanded drive (rotorlab.models._servo): the command from the speed block
    ``[w0, rate, w_dwell, t_dwell_end, w_op, K]``, its torque K (cmd - om) limited to
    +-T_max(om) of the characteristic."""
    def lines(lay: Layout) -> list[str]:
        k = lay.offsets["speed"]
        return characteristic(lay) + [
            "    tlim = max(torque, 0.0)",
            f"    if t < p[{k + 3}]:",
            f"        wcmd = min(p[{k}] + p[{k + 1}] * t, p[{k + 2}])",
            "    else:",
            f"        wcmd = min(p[{k + 2}] + p[{k + 1}] * (t - p[{k + 3}]), p[{k + 4}])",
            f"    torque = min(tlim, max(-tlim, p[{k + 5}] * (wcmd - om)))"]
    return lines


@dataclass(frozen=True)
class DriveLines:
    """The spin lines of a drive kind and, for a motor, its torque lines (None: prescribed)."""

    spin: Callable[[Layout], list[str]]
    torque: Callable[[Layout], list[str]] | None = None


#: The drive kinds of a layout (``Layout.drive``).
DRIVES: dict[str, DriveLines] = {
    "profile": DriveLines(_prescribed),
    "linear": DriveLines(_motor_spin, _linear_torque),
    "table": DriveLines(_motor_spin, _table_torque),
    "servo_linear": DriveLines(_motor_spin, _servo(_linear_torque)),
    "servo_table": DriveLines(_motor_spin, _servo(_table_torque)),
}


def spin_lines(lay: Layout) -> list[str]:
    """The lines defining ``theta`` and ``om`` (and ``dom`` for a prescribed spin)."""
    return DRIVES[lay.drive].spin(lay)


def torque_lines(lay: Layout) -> list[str]:
    """The lines defining a motor's ``torque`` at ``om``."""
    return DRIVES[lay.drive].torque(lay)
