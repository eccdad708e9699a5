"""Map start points to regime labels: the interface of a mapper and the chunked ensemble engine.

The layers follow Attractors.jl: a *mapper* turns start points into trajectories, trajectories
into features and features into labels; grids (:mod:`rotorlab.explore._basin`) and random
sampling (:mod:`rotorlab.explore._fractions`) only choose the start points. A mapper is a frozen
value: it holds no state between calls, so the same start point always gets the same label.

Features are computed chunk by chunk while the ensemble runs ("on the fly"): only the few saved
states each feature needs are kept, never whole trajectories, so a 256 x 256 basin needs
memory for one chunk only. Every trajectory is integrated independently, so results are
bit-identical whatever the chunk size and the number of threads.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

__all__ = ["AbstractMapper", "Feature", "MapperAnalysis", "map_starts", "label_since", "DEFAULT_CHUNK"]

#: Trajectories per chunk when none is given.
DEFAULT_CHUNK = 1024


class Feature(tuple):
    """A computed feature: ``(values, units, description)``; values of shape (N, n_horizon)."""

    __slots__ = ()

    def __new__(cls, values: np.ndarray, units: str, description: str) -> Feature:
        return super().__new__(cls, (np.asarray(values), units, description))


@runtime_checkable
class AbstractMapper(Protocol):
    """What :func:`map_starts` needs to label start points of one model family.

    For implementers
    ----------------
    1. ``labels``: tuple of label names; a trajectory's label is an index into it.
    2. ``coordinate_units``: mapping from every name :meth:`starts` accepts (state entries and
       parameters) to its unit.
    3. ``starts(coords)``: from a mapping name -> array of shape (N,) return ``(model, Y0, P)``:
       the model whose kernels integrate all of them, initial states (N, n_state) and packed
       parameters (N, n_param). Names not given take the mapper's base values.
    4. ``horizons()``: increasing times (s) at which trajectories are classified; the last is
       the simulated time. ``save_times()``: the times whose states the features need.
    5. ``features(sol, P)``: from an :class:`~rotorlab.integrate.EnsembleSolution` of one chunk
       (saved at ``save_times()``) return a dict name -> :class:`Feature` with values of shape
       (N, n_horizon), plus optionally per-trajectory arrays of shape (N,).
    6. ``group(features)``: integer labels of shape (N, n_horizon) from the feature values.
    7. ``control``: the :class:`~rotorlab.integrate.StepControl` of the integration.
    8. For a mapper of case-file basins (a model type's ``mapper``; not needed by
       :func:`map_starts`): ``start_value(name)``, the value (SI) a start takes
       for the coordinate ``name`` when it is not given (the base value of item 3), or None
       where the starts have no single value (balls of different masses) or the name is not a
       coordinate. Reports and figures show it for every coordinate a basin does not vary.
    """

    @property
    def labels(self) -> tuple[str, ...]: ...

    @property
    def coordinate_units(self) -> Mapping[str, str]: ...

    def starts(self, coords: Mapping[str, np.ndarray]) -> tuple[Any, np.ndarray, np.ndarray]: ...

    def horizons(self) -> np.ndarray: ...

    def save_times(self) -> np.ndarray: ...

    def features(self, sol: Any, P: np.ndarray) -> dict[str, Feature]: ...

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray: ...


#: Prefix of a coordinate that names a parameter of the mapper's model by its case-file key path
#: (``model.<key path>``, :attr:`rotorlab.models.AbstractParametrisedModel.parameters`).
KEY_PREFIX = "model."


def ball_coordinate_units(n_balls: int) -> dict[str, str]:
    """Start coordinates of ``n_balls`` balls: angles ``psi_i`` (rad) and rates ``dpsi_i`` (rad/s)."""
    units = {f"psi_{i}": "rad" for i in range(1, n_balls + 1)}
    units.update({f"dpsi_{i}": "rad/s" for i in range(1, n_balls + 1)})
    return units


def ball_start_value(name: str, base_angles: tuple[float, ...]) -> float | None:
    """The start value of a ball coordinate not given: ``psi_<i>`` starts at ``base_angles[i - 1]``
    (rad), ``dpsi_<i>`` at rest relative to the rotor (0 rad/s); None for any other name.

    Examples
    --------
    >>> ball_start_value("psi_2", (0.0, 3.0)), ball_start_value("dpsi_1", (0.0, 3.0))
    (3.0, 0.0)
    >>> ball_start_value("psi_3", (0.0, 3.0)) is None, ball_start_value("spin_speed", ()) is None
    (True, True)
    """
    prefix, _, index = name.partition("_")
    if prefix not in ("psi", "dpsi") or not index.isdigit() or not 1 <= int(index) <= len(base_angles):
        return None
    return float(base_angles[int(index) - 1]) if prefix == "psi" else 0.0


def window_save_times(horizons: np.ndarray, window: float, samples_per_window: int) -> np.ndarray:
    """Save times: ``samples_per_window`` evenly spaced times over the window ending at each horizon."""
    k = np.linspace(-1.0, 0.0, samples_per_window)
    return np.unique(np.maximum(horizons[:, None] + window * k[None, :], 0.0))


def _check_coords(mapper: AbstractMapper, coords: Mapping[str, Any]) -> tuple[dict[str, np.ndarray], int]:
    if not isinstance(mapper, AbstractMapper):
        raise TypeError(f"mapper must implement AbstractMapper, got {type(mapper).__name__}")
    from rotorlab.sweep._axes import point_columns

    return point_columns(coords, mapper.coordinate_units)


def label_since(labels: np.ndarray, horizons: np.ndarray) -> np.ndarray:
    """Return the earliest horizon from which each trajectory's label no longer changes.

    Parameters
    ----------
    labels : ndarray of int, shape (N, n_horizon)
    horizons : ndarray, shape (n_horizon,)
        Times (s), increasing.

    Returns
    -------
    ndarray, shape (N,)
        ``horizons[j]`` for the smallest j with ``labels[:, j:]`` all equal to the last label (s).

    Examples
    --------
    >>> label_since(np.array([[2, 0, 0], [1, 1, 1], [0, 0, 2]]), np.array([1.0, 2.0, 3.0]))
    array([2., 1., 3.])
    """
    labels = np.asarray(labels)
    same = labels == labels[:, -1:]
    # index of the last horizon that differs from the final label, plus one
    differs = ~same
    last_diff = np.where(differs.any(axis=1), labels.shape[1] - 1 - np.argmax(differs[:, ::-1], axis=1), -1)
    return np.asarray(horizons, dtype=float)[last_diff + 1]


@dataclass(frozen=True, slots=True)
class MapperAnalysis:
    """The per-point analysis "integrate, compute features, label" of a mapper, for sweeps.

    This is the chunk body of :func:`map_starts`, :func:`~rotorlab.explore.basin_map` and
    :func:`~rotorlab.explore.basin_stability`, made a value that :func:`rotorlab.sweep.run_sweep`
    runs in-process, on local processes or on Dask workers.

    Parameters
    ----------
    mapper : AbstractMapper
        E.g. :class:`~rotorlab.explore.TorusRegimes` or :class:`~rotorlab.explore.BalancerRegimes`.

    Examples
    --------
    >>> from rotorlab.explore import TorusRegimes
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> a = MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=2.0, n_horizons=2))
    >>> out = a.run_chunk({"psi": np.array([3.1, 0.5])})
    >>> out["label"].dims, out["label"].values.shape, out["n_steps"].attrs["units"]
    (('horizon',), (2, 2), '1')
    """

    mapper: Any

    def __post_init__(self) -> None:
        if not isinstance(self.mapper, AbstractMapper):
            raise TypeError(f"mapper must implement AbstractMapper, got {type(self.mapper).__name__}")

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return self.mapper.coordinate_units

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return {"horizon": (np.asarray(self.mapper.horizons(), dtype=float), {"units": "s"})}

    def result_attrs(self) -> dict[str, Any]:
        horizons = np.asarray(self.mapper.horizons(), dtype=float)
        return {"mapper": type(self.mapper).__name__, "t_end": float(horizons[-1]),
                "labels": list(self.mapper.labels)}  # fmt: skip

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        """Integrate, featurize and label one chunk of start points (see :func:`map_starts`)."""
        from rotorlab.integrate import SaveAt, solve_ensemble
        from rotorlab.sweep import ChunkVar

        mapper = self.mapper
        cols = {k: np.asarray(v, dtype=float) for k, v in coords.items()}
        n = next(iter(cols.values())).size if cols else 1
        model, Y0, P = mapper.starts(cols)
        horizons = np.asarray(mapper.horizons(), dtype=float)
        ts = np.asarray(mapper.save_times(), dtype=float)
        # Neighbouring start points cost alike (a whole band of a basin can be slow), and the
        # parallel loop hands each thread a contiguous block: integrate the chunk in a fixed
        # shuffled order and put the results back. Trajectories are independent, so this
        # changes only the wall time.
        perm = np.random.default_rng(n).permutation(n)
        back = np.argsort(perm)
        Pc = P[perm]
        sol = solve_ensemble(model, Y0[perm], (0.0, float(horizons[-1])), params=Pc, save_at=SaveAt(ts=ts),
                             control=mapper.control, threads=threads)  # fmt: skip
        f = mapper.features(sol, Pc)
        label = mapper.group({k: v[0] for k, v in f.items()})[back].astype(np.int16)
        names = tuple(mapper.labels)
        flag = {"flag_values": list(range(len(names))), "flag_meanings": " ".join(
            n.replace(" ", "_") for n in names), "labels": list(names), "units": "1"}  # fmt: skip
        out = {
            "label": ChunkVar(("horizon",), label, dict(flag)),
            "outcome": ChunkVar((), label[:, -1], dict(flag)),
            "label_since": ChunkVar((), label_since(label, horizons), {"units": "s",
                                    "description": "earliest horizon from which the label stays as at the end"}),
            "status": ChunkVar((), sol.status.astype(np.int32)[back], {"units": "1"}),
            "n_steps": ChunkVar((), (sol.stats[:, 1] + sol.stats[:, 2])[back], {"units": "1"}),
        }  # fmt: skip
        for name, (values, units, desc) in f.items():
            if name in cols or name in out:
                raise ValueError(f"feature {name!r} of {type(mapper).__name__} clashes with a coordinate or result name")
            values = np.asarray(values)[back]
            out[name] = ChunkVar(("horizon",)[: values.ndim - 1], values, {"units": units, "description": desc})
        return out


def _flags_as_arrays(ds):
    """``flag_values`` as int16 arrays (as written before the sweep engine; JSON stores lists)."""
    for name in ("label", "outcome"):
        if name in ds and "flag_values" in ds[name].attrs:
            ds[name].attrs["flag_values"] = np.asarray(ds[name].attrs["flag_values"], dtype=np.int16)
    return ds


def _sweep_progress(progress: Callable[[int, int], None] | None):
    if progress is None:
        return None

    def report(p: Any) -> None:
        if p.computed:
            progress(p.done, p.total)

    return report


def _check_chunk(chunk_size: int | None) -> int:
    if chunk_size is None:
        return DEFAULT_CHUNK
    if isinstance(chunk_size, bool) or int(chunk_size) != chunk_size or chunk_size < 1:
        raise ValueError(f"chunk_size must be >= 1, got {chunk_size!r}")
    return int(chunk_size)


def run_mapped(sweep: Any, *, threads: int | None = None, chunk_size: int | None = None,
               progress: Callable[[int, int], None] | None = None, store: Any = None, resume: bool = False,
               executor: Any = None):  # fmt: skip
    """Run a sweep of :class:`MapperAnalysis` for the explore functions (the shared tail of
    :func:`map_starts`, :func:`~rotorlab.explore.basin_map` and
    :func:`~rotorlab.explore.basin_stability`).

    In memory by default, or chunk by chunk into a Zarr ``store`` (``resume`` continues it; a
    resumed store keeps its chunk size unless ``chunk_size`` is given) on ``executor`` (default
    :class:`rotorlab.sweep.InProcess` with ``threads``). The Dataset is the same either way: the
    store's own attributes (``sweep``, ``fingerprint``, ``complete``) are not copied into it.
    """
    from rotorlab.sweep import InProcess, run_sweep

    if executor is not None and threads is not None:
        raise ValueError("give threads or executor, not both (an executor has its own threads)")
    size = None if store is not None and chunk_size is None else _check_chunk(chunk_size)
    ds = run_sweep(sweep, store=store, resume=resume, chunk_size=size, executor=executor or InProcess(threads),
                   progress=_sweep_progress(progress))  # fmt: skip
    if store is not None:
        for key in ("sweep", "fingerprint", "complete"):
            ds.attrs.pop(key, None)
    return _flags_as_arrays(ds)


def map_starts(
    mapper: AbstractMapper,
    coords: Mapping[str, Any],
    *,
    threads: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
):
    """Integrate and label start points given by named coordinates.

    A use of the sweep engine (:func:`rotorlab.sweep.run_sweep` with :class:`MapperAnalysis` on
    a :class:`~rotorlab.sweep.Points` list), run in this process.

    Parameters
    ----------
    mapper : AbstractMapper
        E.g. :class:`~rotorlab.explore.TorusRegimes` or :class:`~rotorlab.explore.BalancerRegimes`.
    coords : mapping of str to array_like, shape (N,) or scalar
        Start coordinates (state entries or parameters, see ``mapper.coordinate_units``);
        scalars are shared by all points.
    threads : int, optional
        Threads of the integrator (default: numba's). Results do not depend on it.
    chunk_size : int, optional
        Trajectories integrated and featurized together (default :data:`DEFAULT_CHUNK`).
        Results do not depend on it.
    progress : callable, optional
        ``progress(done, total)`` after each chunk.

    Returns
    -------
    xarray.Dataset
        Dims ``ic`` and ``horizon``. Coordinates: ``horizon`` (s) and every given coordinate
        on ``ic`` (with its unit). Variables: ``label`` (ic, horizon; int codes, attrs
        ``flag_values``/``flag_meanings`` and ``labels``), ``outcome`` (ic, label at the last
        horizon), ``label_since`` (ic; horizon from which the label stays, s), every feature,
        ``status``, ``n_steps``.

    Raises
    ------
    ValueError
        Unknown or malformed coordinates.
    """
    from rotorlab.sweep import Points, Sweep

    cols, _ = _check_coords(mapper, coords)
    sweep = Sweep(MapperAnalysis(mapper), points=Points(cols, dim="ic"))
    return run_mapped(sweep, threads=threads, chunk_size=_check_chunk(chunk_size), progress=progress)
