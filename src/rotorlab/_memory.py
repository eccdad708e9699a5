"""Size checks before large allocations: refuse up front, stating the memory a request needs.

An absurd size (a 100000 x 100000 basin grid, ``n_save = 1e10``) otherwise ends in a
``MemoryError`` (or the machine swapping) after a long wait. Every place that allocates in
proportion to a user's numbers calls :func:`check_memory` first with the bytes it is about to
need; the command line turns :class:`TooLarge` into exit code 2 (bad input).
"""

from __future__ import annotations

import os

__all__ = ["TooLarge", "check_memory", "physical_memory", "format_bytes"]


class TooLarge(ValueError):
    """A request would need more memory than this machine has; the message says how much and for what."""


def physical_memory() -> int | None:
    """Bytes of physical memory of this machine (None where the system does not say)."""
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
        return None


def format_bytes(n: float) -> str:
    """``n`` bytes in the largest binary unit that keeps it >= 1 (e.g. ``"74.5 GiB"``).

    Examples
    --------
    >>> format_bytes(512), format_bytes(3 * 2**30), format_bytes(8e15)
    ('512 B', '3 GiB', '7.11 PiB')
    """
    units = ("B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB")
    k = 0
    value = float(n)
    while value >= 1024 and k < len(units) - 1:
        value /= 1024
        k += 1
    return f"{value:.3g} {units[k]}"


def check_memory(n_bytes: float, what: str, advice: str, *, limit: float | None = None) -> None:
    """Raise :class:`TooLarge` when ``n_bytes`` exceed this machine's physical memory.

    Parameters
    ----------
    n_bytes : float
        Bytes about to be allocated (a float: products of absurd sizes overflow no integer).
    what : str
        What needs them, with the sizes that make them up (``"n_save = 1e+10 saved states of
        4 trajectories x 8 entries"``); the message starts with it.
    advice : str
        What to reduce.
    limit : float, optional
        Bytes allowed (default: the physical memory; no check where it is unknown).

    Examples
    --------
    >>> check_memory(8e6, "a small array", "fewer points", limit=1e9)
    >>> check_memory(8e12, "1e12 points", "fewer points", limit=1e9)
    Traceback (most recent call last):
    ...
    rotorlab._memory.TooLarge: 1e12 points need about 7.28 TiB of memory, more than this machine has (954 MiB): fewer points
    """
    limit = physical_memory() if limit is None else limit
    if limit is not None and float(n_bytes) > limit:
        raise TooLarge(f"{what} need about {format_bytes(n_bytes)} of memory, more than this machine has "
                       f"({format_bytes(limit)}): {advice}")  # fmt: skip
