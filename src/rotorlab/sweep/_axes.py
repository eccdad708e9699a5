"""What a sweep varies: grid axes, value lists, seeded random samples and explicit point lists.

A sweep's points are either the Cartesian product of its axes (one result dimension per axis,
first axis slowest), a seeded uniform random sample (one dimension, ``sample``), or an explicit
list of points (one dimension, e.g. ``ic``). Every object here is a frozen value; the points it
stands for are the same on every machine and in every process.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["GridAxis", "ListAxis", "Sample", "Points", "point_columns"]

_AXIS = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*([^:]+):([^:]+):([^:]+)\s*$")
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def _check_name(owner: str, name: Any) -> None:
    if not isinstance(name, str) or not _NAME.match(name):
        raise ValueError(f"{owner}.name must be an identifier (ASCII letters, digits, '_'), got {name!r}")


@dataclass(frozen=True, slots=True)
class GridAxis:
    """One axis of a grid: ``num`` equally spaced values of a named coordinate.

    Parameters
    ----------
    name : str
        A coordinate of the per-point analysis (state entry or parameter).
    start, stop : float
        First and last value (both included), in the coordinate's (SI) unit.
    num : int
        Number of values, >= 1.

    Examples
    --------
    >>> GridAxis.parse("dpsi=-280:140:4").values.tolist()
    [-280.0, -140.0, 0.0, 140.0]
    """

    name: str
    start: float
    stop: float
    num: int

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"GridAxis.name must be a non-empty string, got {self.name!r}")
        for attr in ("start", "stop"):
            v = float(getattr(self, attr))
            if not math.isfinite(v):
                raise ValueError(f"GridAxis.{attr} must be finite, got {getattr(self, attr)!r}")
            object.__setattr__(self, attr, v)
        if isinstance(self.num, bool) or int(self.num) != self.num or self.num < 1:
            raise ValueError(f"GridAxis.num must be an integer >= 1, got {self.num!r}")
        object.__setattr__(self, "num", int(self.num))

    @classmethod
    def parse(cls, text: str) -> GridAxis:
        """Parse ``"NAME=A:B:N"`` (the command-line form)."""
        m = _AXIS.match(text)
        if m is None:
            raise ValueError(f"grid axis must look like NAME=A:B:N, got {text!r}")
        name, a, b, n = m.groups()
        try:
            return cls(name, float(a), float(b), int(n))
        except ValueError as exc:
            raise ValueError(f"grid axis {text!r}: {exc}") from None

    @property
    def values(self) -> np.ndarray:
        """The grid values, shape (num,)."""
        return np.linspace(self.start, self.stop, self.num)

    def describe(self) -> dict[str, Any]:
        """Return the axis as plain JSON data."""
        return {"kind": "grid", "name": self.name, "start": self.start, "stop": self.stop, "num": self.num}


@dataclass(frozen=True, slots=True)
class ListAxis:
    """One axis of a grid given by its values.

    Parameters
    ----------
    name : str
        A coordinate of the per-point analysis.
    values : tuple of float
        The values (at least one, finite), in the coordinate's (SI) unit.

    Examples
    --------
    >>> ListAxis("ball_mass", (0.01, 0.02, 0.05)).values.tolist()
    [0.01, 0.02, 0.05]
    """

    name: str
    values_: tuple[float, ...]

    def __init__(self, name: str, values: Any) -> None:
        _check_name("ListAxis", name)
        vals = tuple(float(v) for v in np.atleast_1d(np.asarray(values, dtype=float)).ravel())
        if not vals or not all(math.isfinite(v) for v in vals):
            raise ValueError(f"ListAxis.values must be one or more finite numbers, got {values!r}")
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "values_", vals)

    @property
    def num(self) -> int:
        """Number of values."""
        return len(self.values_)

    @property
    def values(self) -> np.ndarray:
        """The values, shape (num,)."""
        return np.array(self.values_)

    def describe(self) -> dict[str, Any]:
        """Return the axis as plain JSON data."""
        return {"kind": "list", "name": self.name, "values": list(self.values_)}


@dataclass(frozen=True, slots=True)
class Sample:
    """A seeded uniform random sample of start points.

    Coordinates are drawn independently from ``ranges`` with ``numpy.random.default_rng(seed)``,
    one coordinate after the other in the order given, ``n`` values each: the same seed always
    gives the same points.

    Parameters
    ----------
    ranges : mapping of str to (low, high)
        Coordinates to draw and their ranges (finite, high >= low), in SI units.
    n : int
        Number of points, >= 1.
    seed : int
        Seed of the random generator.
    dim : str
        Name of the result dimension (default ``"sample"``).

    Examples
    --------
    >>> s = Sample({"psi": (0.0, 1.0)}, n=3, seed=1)
    >>> s.draw()["psi"].round(3).tolist()
    [0.512, 0.95, 0.144]
    """

    ranges: tuple[tuple[str, float, float], ...]
    n: int
    seed: int
    dim: str = "sample"

    def __init__(self, ranges: Mapping[str, tuple[float, float]] | Any, n: int, seed: int,
                 dim: str = "sample") -> None:  # fmt: skip
        items = ranges.items() if isinstance(ranges, Mapping) else ((r[0], (r[1], r[2])) for r in ranges)
        norm = []
        for name, (lo, hi) in items:
            lo, hi = float(lo), float(hi)
            if not (math.isfinite(lo) and math.isfinite(hi) and hi >= lo):
                raise ValueError(f"range of {name!r} must be finite with high >= low, got {(lo, hi)!r}")
            norm.append((name, lo, hi))
        if not norm:
            raise ValueError("ranges must name at least one coordinate to draw")
        if len({r[0] for r in norm}) != len(norm):
            raise ValueError("Sample.ranges names a coordinate twice")
        if isinstance(n, bool) or int(n) != n or n < 1:
            raise ValueError(f"n must be an integer >= 1, got {n!r}")
        if isinstance(seed, bool) or int(seed) != seed:
            raise ValueError(f"Sample.seed must be an integer, got {seed!r}")
        _check_name("Sample", dim)
        object.__setattr__(self, "ranges", tuple(norm))
        object.__setattr__(self, "n", int(n))
        object.__setattr__(self, "seed", int(seed))
        object.__setattr__(self, "dim", dim)

    def draw(self) -> dict[str, np.ndarray]:
        """Return the drawn coordinates, name -> array of shape (n,)."""
        rng = np.random.default_rng(self.seed)
        return {name: rng.uniform(lo, hi, self.n) for name, lo, hi in self.ranges}

    def describe(self) -> dict[str, Any]:
        """Return the sample as plain JSON data."""
        return {"kind": "sample", "ranges": [list(r) for r in self.ranges], "n": self.n, "seed": self.seed,
                "dim": self.dim}  # fmt: skip


def point_columns(coords: Mapping[str, Any], known: Mapping[str, Any] | None = None) -> tuple[dict[str, np.ndarray], int]:
    """Return the coordinates of a list of points as equal-length float columns, and their count.

    Parameters
    ----------
    coords : mapping of str to array_like, shape (N,) or scalar
        Scalars are shared by all points.
    known : mapping, optional
        The allowed names (ValueError for any other).

    Examples
    --------
    >>> cols, n = point_columns({"psi": [0.0, 1.0], "dpsi": 3.0})
    >>> n, cols["dpsi"].tolist()
    (2, [3.0, 3.0])
    """
    out: dict[str, np.ndarray] = {}
    sizes = set()
    for name, values in dict(coords).items():
        if known is not None and name not in known:
            raise ValueError(f"unknown coordinate {name!r}; this mapper accepts: {', '.join(known)}")
        arr = np.atleast_1d(np.asarray(values, dtype=float))
        if arr.ndim != 1 or not np.all(np.isfinite(arr)):
            raise ValueError(f"coordinate {name!r} must be a finite 1-D array, got shape {arr.shape}")
        out[name] = arr
        sizes.add(arr.size)
    sizes.discard(1)
    if len(sizes) > 1:
        raise ValueError(f"coordinates disagree on the number of start points: {sorted(sizes)}")
    n = sizes.pop() if sizes else 1
    return {k: np.broadcast_to(v, (n,)).copy() for k, v in out.items()}, n


@dataclass(frozen=True, eq=False)
class Points:
    """An explicit list of points: every coordinate has one value per point.

    Parameters
    ----------
    coords : mapping of str to array_like, shape (N,) or scalar
        Coordinates; scalars are shared by all points.
    dim : str
        Name of the result dimension (default ``"ic"``).

    Examples
    --------
    >>> Points({"psi": [0.0, 1.0], "dpsi": 3.0}).coords["dpsi"].tolist()
    [3.0, 3.0]
    """

    coords: Mapping[str, np.ndarray]
    dim: str = "ic"

    def __post_init__(self) -> None:
        _check_name("Points", self.dim)
        full, _ = point_columns(self.coords)
        for v in full.values():
            v.setflags(write=False)
        object.__setattr__(self, "coords", full)

    @property
    def n(self) -> int:
        """Number of points."""
        return next(iter(self.coords.values())).size if self.coords else 1

    def describe(self) -> dict[str, Any]:
        """Return the points as plain JSON data (values by their SHA-256)."""
        import hashlib

        h = hashlib.sha256()
        for name in sorted(self.coords):
            h.update(name.encode())
            h.update(np.ascontiguousarray(self.coords[name]).tobytes())
        return {"kind": "points", "dim": self.dim, "n": self.n, "names": sorted(self.coords),
                "sha256": h.hexdigest()}  # fmt: skip
