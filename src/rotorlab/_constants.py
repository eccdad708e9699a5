"""Unit-conversion constants shared across rotorlab (no imports beyond ``math``).

Everything inside rotorlab is SI; these convert at the edges (messages, tables, figure labels,
options such as ``--speed-rpm``).

Examples
--------
>>> round(2.0 * math.pi * RPM_PER_RAD_S, 12)
60.0
"""

from __future__ import annotations

import math

__all__ = ["RPM_PER_RAD_S"]

#: Revolutions per minute in one rad/s, 30 / pi (= 60 / (2 pi), the same float): a speed in rpm
#: is ``omega * RPM_PER_RAD_S``, one in rad/s is ``rpm / RPM_PER_RAD_S``.
RPM_PER_RAD_S = 30.0 / math.pi
