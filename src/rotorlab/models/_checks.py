"""Checks of parameter values shared by the model dataclasses (``__post_init__``)."""

from __future__ import annotations

import math

__all__ = ["check_number"]


def check_number(owner: str, name: str, value, *, lo: float | None = 0.0, lo_open: bool = True,
                 hi: float | None = None, hi_open: bool = False, unit: str = "") -> float:  # fmt: skip
    """Check a number against its bounds and return it as a float.

    Parameters
    ----------
    owner, name : str
        Class and field, for the message (``"Housing"``, ``"gap"``).
    value : object
        The value given.
    lo, hi : float or None
        Bounds (None: none); by default the value must be > 0.
    lo_open, hi_open : bool
        Whether the bound itself is excluded.
    unit : str
        SI unit, for the message.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Not a finite number within the bounds; the message names ``owner.name``, the bounds, the
        unit and the value.

    Examples
    --------
    >>> check_number("Housing", "gap", "4.5e-3", unit="m")
    0.0045
    >>> check_number("Housing", "restitution", 1.5, lo_open=False, hi=1.0)
    Traceback (most recent call last):
    ...
    ValueError: Housing.restitution must be a finite number >= 0 and <= 1, got 1.5
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    ok = math.isfinite(v)
    if ok and lo is not None:
        ok = v > lo if lo_open else v >= lo
    if ok and hi is not None:
        ok = v < hi if hi_open else v <= hi
    if not ok:
        parts = []
        if lo is not None:
            parts.append(f"{'>' if lo_open else '>='} {lo:g}")
        if hi is not None:
            parts.append(f"{'<' if hi_open else '<='} {hi:g}")
        bound = " and ".join(parts) or "finite"
        u = f" ({unit})" if unit else ""
        raise ValueError(f"{owner}.{name} must be a finite number {bound}{u}, got {value!r}")
    return v
