"""The sweep description: what is varied (axes, a sample or a point list), what is held fixed, and
the analysis run at every point; and the interface of a per-point analysis.

A :class:`Sweep` is a frozen value. Its points are numbered 0 .. N-1 (C order over the axes:
first axis slowest) and cut into chunks of consecutive points; the chunk function
:func:`compute_chunk` runs the analysis on one chunk and returns plain arrays, so the same chunk
gives the same bits in this process, in a local worker process or on a Dask worker.
:meth:`Sweep.describe` is the sweep as plain JSON data: a store remembers it, and refuses to be
resumed by a different sweep.
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol, runtime_checkable

import numpy as np

from rotorlab.sweep._axes import GridAxis, ListAxis, Points, Sample

__all__ = [
    "AbstractPointAnalysis",
    "ChunkVar",
    "Sweep",
    "compute_chunk",
    "describe_value",
    "DEFAULT_CHUNK",
]

#: Points per chunk when none is given.
DEFAULT_CHUNK = 1024


class ChunkVar(NamedTuple):
    """One result variable of a chunk: trailing ``dims``, ``values`` (n_points, ...) and ``attrs``."""

    dims: tuple[str, ...]
    values: np.ndarray
    attrs: dict[str, Any]


@runtime_checkable
class AbstractPointAnalysis(Protocol):
    """What a sweep runs at its points (e.g. integrate and classify, or steady-motion stability).

    For implementers
    ----------------
    1. ``coordinate_units``: mapping from every coordinate name the analysis accepts (state
       entries and parameters) to its SI unit.
    2. ``run_chunk(coords, threads)``: from a mapping name -> array of shape (n,) (every
       coordinate of the sweep, fixed ones broadcast) return a dict name -> :class:`ChunkVar`
       whose values have shape (n, ...). The values of a point must depend only on that point's
       coordinates (never on the chunk it is in, the chunk size or ``threads``), and the names,
       trailing dims, dtypes and attrs must be the same for every chunk.
    3. ``trailing_coords()``: dict dim -> (values, attrs) for the trailing dims (e.g.
       ``horizon``), and ``result_attrs()``: attributes of the result Dataset.
    4. Be a frozen, picklable value (it is sent to worker processes) whose
       :func:`describe_value` identifies it: two analyses with the same description must give
       the same results.
    """

    @property
    def coordinate_units(self) -> Mapping[str, str]: ...

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, ChunkVar]: ...

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]: ...

    def result_attrs(self) -> dict[str, Any]: ...


def describe_value(obj: Any) -> Any:
    """Return ``obj`` as plain JSON data that identifies it (dataclasses by type and fields).

    Examples
    --------
    >>> describe_value(GridAxis("x", 0, 1, 3))
    {'type': 'rotorlab.sweep._axes.GridAxis', 'name': 'x', 'start': 0.0, 'stop': 1.0, 'num': 3}
    """
    if hasattr(obj, "describe") and callable(obj.describe) and isinstance(obj, (GridAxis, ListAxis, Sample, Points)):
        return {"type": f"{type(obj).__module__}.{type(obj).__qualname__}",
                **{k: v for k, v in obj.describe().items() if k != "kind"}}  # fmt: skip
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        out: dict[str, Any] = {"type": f"{type(obj).__module__}.{type(obj).__qualname__}"}
        for f in dataclasses.fields(obj):
            out[f.name] = describe_value(getattr(obj, f.name))
        return out
    if isinstance(obj, enum.Enum):
        return describe_value(obj.value)
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else repr(v)
    if isinstance(obj, str) or obj is None:
        return obj
    if isinstance(obj, np.ndarray):
        arr = np.ascontiguousarray(obj)
        if arr.size <= 64 and arr.dtype.kind in "biuf":
            return [describe_value(v) for v in arr.ravel()]
        return {"array": hashlib.sha256(arr.tobytes()).hexdigest(), "shape": list(arr.shape), "dtype": str(arr.dtype)}
    if isinstance(obj, Mapping):
        return {str(k): describe_value(v) for k, v in obj.items()}
    if isinstance(obj, (tuple, list)):
        return [describe_value(v) for v in obj]
    return repr(obj)


@dataclass(frozen=True, eq=False)
class Sweep:
    """A sweep: an analysis run at every point of a grid, a random sample or a point list.

    Parameters
    ----------
    analysis : AbstractPointAnalysis
        What runs at each point, e.g. :class:`rotorlab.explore.MapperAnalysis`.
    axes : tuple of GridAxis or ListAxis
        Grid axes (one result dimension each, in this order; the first varies slowest).
    sample : Sample, optional
        A seeded random sample instead of axes (one dimension, ``sample.dim``).
    points : Points, optional
        An explicit point list instead of axes (one dimension, ``points.dim``).
    fixed : mapping of str to float
        Values of further coordinates, shared by all points (SI).
    input_units : mapping of str to str
        The unit an angle coordinate was written in, ``"deg"`` or ``"rad"`` (the values are SI
        either way). Only for display: results carry it as ``attrs["input_units_<name>"]`` and
        figures draw that coordinate in it; it is not part of :meth:`describe`, so it does not
        change what a resume checks.

    Examples
    --------
    >>> from rotorlab.explore import MapperAnalysis, TorusRegimes
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> sw = Sweep(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=1.0)),
    ...            axes=(GridAxis("dpsi", -20, 20, 3), GridAxis("psi", 0, 6, 4)))
    >>> sw.dims, sw.shape, sw.n_points
    (('dpsi', 'psi'), (3, 4), 12)
    """

    analysis: Any
    axes: tuple[GridAxis | ListAxis, ...] = ()
    sample: Sample | None = None
    points: Points | None = None
    fixed: Mapping[str, float] = dataclasses.field(default_factory=dict)
    input_units: Mapping[str, str] = dataclasses.field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.analysis, AbstractPointAnalysis):
            raise TypeError(f"Sweep.analysis must implement AbstractPointAnalysis, got {type(self.analysis).__name__}")
        axes = tuple(self.axes)
        for a in axes:
            if not isinstance(a, (GridAxis, ListAxis)):
                raise ValueError(f"Sweep.axes must hold GridAxis or ListAxis objects, got {type(a).__name__}")
        object.__setattr__(self, "axes", axes)
        kinds = sum((bool(axes), self.sample is not None, self.points is not None))
        if kinds != 1:
            raise ValueError("a Sweep needs exactly one of axes, sample or points")
        if self.sample is not None and not isinstance(self.sample, Sample):
            raise ValueError(f"Sweep.sample must be a Sample, got {type(self.sample).__name__}")
        if self.points is not None and not isinstance(self.points, Points):
            raise ValueError(f"Sweep.points must be a Points, got {type(self.points).__name__}")
        fixed = {}
        for name, value in dict(self.fixed or {}).items():
            v = float(value)
            if not math.isfinite(v):
                raise ValueError(f"fixed value of {name!r} must be finite, got {value!r}")
            fixed[str(name)] = v
        object.__setattr__(self, "fixed", fixed)
        varied = list(self.varied)
        if len(set(varied)) != len(varied):
            raise ValueError(f"a coordinate is varied twice: {varied}")
        clash = set(varied) & set(fixed)
        if clash:
            raise ValueError(f"coordinates {sorted(clash)} are both varied and fixed")
        known = self.analysis.coordinate_units
        for name in (*varied, *fixed):
            if name not in known:
                raise ValueError(f"unknown coordinate {name!r}; this analysis accepts: {', '.join(known)}")
        units = {str(k): str(v) for k, v in dict(self.input_units or {}).items()}
        for name, unit in units.items():
            if name not in (*varied, *fixed) or unit not in ("deg", "rad"):
                raise ValueError(f"input_units[{name!r}] = {unit!r}: must name a varied or fixed coordinate "
                                 "and be 'deg' or 'rad'")  # fmt: skip
        object.__setattr__(self, "input_units", units)
        from rotorlab._memory import check_memory

        shape = " x ".join(str(s) for s in self.shape)
        n = float(np.prod([float(s) for s in self.shape]))  # a float: absurd grids overflow int64
        check_memory(n * 8.0 * (len(varied) + len(fixed) + len(axes)),
                     f"the coordinates of a sweep of {n:.4g} points ({' x '.join(self.dims)} = {shape})",
                     "sweep fewer points")  # fmt: skip

    @property
    def varied(self) -> tuple[str, ...]:
        """Names of the varied coordinates."""
        if self.axes:
            return tuple(a.name for a in self.axes)
        if self.sample is not None:
            return tuple(r[0] for r in self.sample.ranges)
        return tuple(self.points.coords)

    @property
    def dims(self) -> tuple[str, ...]:
        """Result dimensions of the points (one per axis, or the sample / point-list dim)."""
        if self.axes:
            return tuple(a.name for a in self.axes)
        return (self.sample.dim,) if self.sample is not None else (self.points.dim,)

    @property
    def shape(self) -> tuple[int, ...]:
        """Sizes of :attr:`dims`."""
        if self.axes:
            return tuple(a.num for a in self.axes)
        return (self.sample.n,) if self.sample is not None else (self.points.n,)

    @property
    def n_points(self) -> int:
        """Number of points."""
        return int(np.prod(self.shape))

    def coordinates(self) -> dict[str, np.ndarray]:
        """Every coordinate at every point (fixed ones broadcast): name -> array of shape (N,)."""
        n = self.n_points
        if self.axes:
            index = np.unravel_index(np.arange(n), self.shape)
            out = {a.name: a.values[i] for a, i in zip(self.axes, index)}
        elif self.sample is not None:
            out = self.sample.draw()
        else:
            out = {k: np.array(v) for k, v in self.points.coords.items()}
        for name, value in self.fixed.items():
            out[name] = np.full(n, value)
        return out

    def chunks(self, chunk_size: int) -> list[tuple[int, int]]:
        """Point ranges ``(lo, hi)`` of the chunks, in order."""
        if isinstance(chunk_size, bool) or int(chunk_size) != chunk_size or chunk_size < 1:
            raise ValueError(f"chunk_size must be an integer >= 1, got {chunk_size!r}")
        n, c = self.n_points, int(chunk_size)
        return [(lo, min(n, lo + c)) for lo in range(0, n, c)]

    def describe(self) -> dict[str, Any]:
        """Return the sweep as plain JSON data (what a store checks before a resume)."""
        if self.axes:
            points: Any = [a.describe() for a in self.axes]
        else:
            points = (self.sample or self.points).describe()
        return {"points": points, "fixed": dict(sorted(self.fixed.items())),
                "analysis": describe_value(self.analysis)}  # fmt: skip

    def display_attrs(self) -> dict[str, str]:
        """Result attributes ``input_units_<name>`` (see ``input_units``)."""
        return {f"input_units_{k}": v for k, v in self.input_units.items()}

    def fingerprint(self) -> str:
        """SHA-256 of the canonical JSON of :meth:`describe`."""
        text = json.dumps(self.describe(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()


def compute_chunk(analysis: Any, index: int, coords: Mapping[str, np.ndarray],
                  threads: int | None = None) -> tuple[int, dict[str, tuple[tuple[str, ...], np.ndarray, dict]]]:  # fmt: skip
    """Run ``analysis`` on one chunk of points (the task every executor runs).

    Parameters
    ----------
    analysis : AbstractPointAnalysis
    index : int
        Chunk number (returned unchanged).
    coords : mapping of str to ndarray, shape (n,)
        Coordinates of the chunk's points.
    threads : int, optional
        Integrator threads; results do not depend on it.

    Returns
    -------
    (int, dict)
        ``index`` and the analysis's variables as plain ``(dims, values, attrs)`` tuples.
    """
    out = analysis.run_chunk(coords, threads=threads)
    return index, {name: (tuple(v[0]), np.asarray(v[1]), dict(v[2])) for name, v in out.items()}
