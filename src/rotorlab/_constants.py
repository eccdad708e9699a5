"""Unit-conversion constants shared across rotorlab (no imports beyond ``math``).

Everything inside rotorlab is SI; these convert at the edges (messages, tables, figure labels,
options such as ``--speed-rpm``).

Examples
--------
>>> round(2.0 * math.pi * RPM_PER_RAD_S, 12)
60.0
>>> round(RPM_PER_RAD_S * RAD_S_PER_RPM, 15)
1.0
"""

from __future__ import annotations

import math

__all__ = ["RPM_PER_RAD_S", "RAD_S_PER_RPM", "shown_unit"]

#: Revolutions per minute in one rad/s, 30 / pi (= 60 / (2 pi), the same float): a speed in rpm
#: is ``omega * RPM_PER_RAD_S``, one in rad/s is ``rpm / RPM_PER_RAD_S``.
RPM_PER_RAD_S = 30.0 / math.pi

#: rad/s in one revolution per minute, pi / 30 (:data:`rotorlab.linear.RPM`): a speed in rad/s
#: is ``rpm * RAD_S_PER_RPM``.
RAD_S_PER_RPM = math.pi / 30.0


def shown_unit(unit: str) -> tuple[float, str]:
    """The factor and unit an SI value is shown to people in: rad/s as rpm, kg as g, m as mm,
    rad as deg; any other unit as it is.

    >>> shown_unit("rad/s")[1], shown_unit("kg"), shown_unit("N*m*s/rad")
    ('rpm', (1000.0, 'g'), (1.0, 'N*m*s/rad'))
    """
    return {"rad/s": (RPM_PER_RAD_S, "rpm"), "kg": (1e3, "g"), "m": (1e3, "mm"),
            "rad": (180.0 / math.pi, "deg")}.get(unit, (1.0, unit))
