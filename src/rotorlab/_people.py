"""Numbers for people: the one place that rounds a value for a sentence, a verdict or a warning.

SI values in, short text out: three significant digits, whole numbers from 1000 up (a speed of
7894 rpm stays 7894 rpm), angles to 0.1 degree, lengths in the unit that reads best (nm, µm,
mm, m) and a length too small to matter as "< 1 nm" instead of "5.88e-09 mm". A ratio is a
percentage below 2 and "33.9 ×" from 2 up (never "3.39e+03 %"). Nothing heavy is imported.

Examples
--------
>>> length(5.88e-12), length(2.86e-2), length(3.1e-6), angle(-0.28099)
('< 1 nm', '28.6 mm', '3.1 µm', '-16.1°')
>>> speed(826.66), relative(0.0421), relative(33.9), number(1.7847), number(7893.6)
('7894 rpm', '4.21 %', '33.9 ×', '1.78', '7894')
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["number", "length", "angle", "angle_deg", "speed", "mass", "duration", "relative", "relative_to", "share",
           "quantity", "unbalance", "torque"]

#: A length below this is shown as "< 1 nm" (m): numerical noise, not a vibration.
SMALLEST_LENGTH = 1e-9


def number(x: float | None, digits: int = 3) -> str:
    """``x`` to ``digits`` significant digits without an exponent where it reads (1e-3 to 1e6),
    whole from 1000 up; "–" for None or NaN.

    >>> number(0.000123456), number(123456.7), number(1.0), number(-0.5), number(2.5e-7)
    ('0.000123', '123457', '1', '-0.5', '2.5e-07')
    """
    if x is None or not math.isfinite(x):
        return "–" if x is None or math.isnan(x) else ("∞" if x > 0 else "-∞")
    if x == 0:
        return "0"
    a = abs(x)
    if a >= 1000:
        return f"{x:.0f}" if a < 1e9 else f"{x:.{digits - 1}e}"
    if a < 1e-3:
        return f"{x:.{digits}g}"
    places = max(0, digits - 1 - math.floor(math.log10(a)))
    text = f"{round(x, places):.{places}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def length(m: float | None) -> str:
    """A length in nm, µm, mm or m; "< 1 nm" below :data:`SMALLEST_LENGTH`."""
    if m is None or not math.isfinite(m):
        return number(m)
    a = abs(m)
    if a < SMALLEST_LENGTH:
        return "< 1 nm"
    for scale, unit in ((1e-6, "nm"), (1e-3, "µm"), (1.0, "mm")):
        if a < scale:
            return f"{number(m / scale * 1e3)} {unit}"
    return f"{number(m)} m"


def angle(rad: float | None) -> str:
    """An angle in degrees to 0.1 degree."""
    return "–" if rad is None or not math.isfinite(rad) else angle_deg(math.degrees(rad))


def angle_deg(deg: float | None) -> str:
    """An angle given in degrees, to 0.1 degree ("-0.0°" shown as "0.0°")."""
    if deg is None or not math.isfinite(deg):
        return "–"
    text = f"{deg:.1f}"
    return ("0.0" if text == "-0.0" else text) + "°"


def speed(rad_s: float | None) -> str:
    """A spin speed in rpm."""
    return "–" if rad_s is None else f"{number(rad_s * 30.0 / math.pi)} rpm"


def mass(kg: float | None) -> str:
    """A mass in g below 1 kg, else in kg."""
    if kg is None or not math.isfinite(kg):
        return number(kg)
    return f"{number(kg * 1e3)} g" if abs(kg) < 1.0 else f"{number(kg)} kg"


def unbalance(kg_m: float | None) -> str:
    """An unbalance (mass times radius) in g*mm below 1 kg*mm, else in kg*m."""
    if kg_m is None or not math.isfinite(kg_m):
        return number(kg_m)
    return f"{number(kg_m * 1e6)} g*mm" if abs(kg_m) < 1e-3 else f"{number(kg_m)} kg*m"


def torque(n_m: float | None) -> str:
    """A torque in N*m."""
    return f"{number(n_m)} N*m"


def duration(s: float | None) -> str:
    """A time in ms, s, min or h."""
    if s is None or not math.isfinite(s):
        return number(s)
    a = abs(s)
    if a < 1.0 and a > 0:
        return f"{number(s * 1e3)} ms"
    if a < 120.0:
        return f"{number(s)} s"
    if a < 7200.0:
        return f"{number(s / 60.0)} min"
    return f"{number(s / 3600.0)} h"


def relative(ratio: float | None) -> str:
    """A ratio to a reference: a percentage below 2, else "N ×"; "< 0.1 %" for a tiny one."""
    if ratio is None or not math.isfinite(ratio):
        return number(ratio)
    if ratio >= 2.0:
        return f"{number(ratio)} ×"
    if 0 < abs(ratio) < 1e-3:
        return "< 0.1 %"
    return f"{number(100.0 * ratio)} %"


def relative_to(ratio: float | None, what: str) -> str:
    """``"33.9 × the unbalance response"`` or ``"4.21 % of the unbalance response"``.

    >>> relative_to(33.9, "the unbalance response"), relative_to(0.0421, "the unbalance response")
    ('33.9 × the unbalance response', '4.21 % of the unbalance response')
    """
    text = relative(ratio)
    return f"{text} {what}" if text.endswith("×") else f"{text} of {what}"


def share(part: int, whole: int) -> str:
    """``"3 of 4 (75 %)"``.

    >>> share(1, 3), share(0, 0)
    ('1 of 3 (33.3 %)', '0 of 0')
    """
    return f"{part} of {whole}" + (f" ({number(100.0 * part / whole)} %)" if whole else "")


_BY_UNIT: dict[str, Callable[[float], str]] = {
    "m": length, "rad": angle, "rad/s": speed, "kg": mass, "s": duration, "kg*m": unbalance, "N*m": torque}


def quantity(value: float | None, unit: str) -> str:
    """``value`` (SI, in ``unit``) for people: the unit's own formatter, else the number and unit.

    >>> quantity(0.0125, "kg"), quantity(25000.0, "N/m"), quantity(0.5, "1")
    ('12.5 g', '25000 N/m', '0.5')
    """
    shown = _BY_UNIT.get(unit)
    if shown is not None:
        return shown(value)
    return number(value) if unit in ("", "1") else f"{number(value)} {unit}"
