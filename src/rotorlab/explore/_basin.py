"""Basins on 2-D grids, basin fractions and basin stability from seeded random starts.

These functions only choose start points and count labels; integrating and labelling is the
mapper's job (:func:`rotorlab.explore.map_starts`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from rotorlab._wilson import wilson_interval
from rotorlab.explore._mapper import AbstractMapper, MapperAnalysis, run_mapped
from rotorlab.sweep._axes import GridAxis, Sample

__all__ = ["GridAxis", "basin_map", "basin_fractions", "basin_stability", "wilson_interval"]

def basin_map(
    mapper: AbstractMapper,
    x: GridAxis,
    y: GridAxis,
    *,
    fixed: Mapping[str, float] | None = None,
    threads: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    store: Any = None,
    resume: bool = False,
    executor: Any = None,
):
    """Label every point of a 2-D grid of start coordinates (a basin map).

    Parameters
    ----------
    mapper : AbstractMapper
    x, y : GridAxis
        The two varied coordinates (any two of the mapper's state entries or parameters).
    fixed : mapping of str to float, optional
        Values of other coordinates (default: the mapper's base values).
    threads, chunk_size, progress
        As for :func:`map_starts`; results do not depend on them.
    store : path-like, optional
        Write every chunk to this Zarr store as it finishes (:func:`rotorlab.sweep.run_sweep`),
        so that an interrupted map can be resumed; the Dataset is the same as without it.
    resume : bool
        Continue ``store``: compute only its missing chunks (it must hold the same map).
    executor : rotorlab.sweep.InProcess, LocalProcesses or DaskExecutor, optional
        Where the chunks run (instead of ``threads``); results do not depend on it.

    Returns
    -------
    xarray.Dataset
        Dims ``(y.name, x.name, horizon)`` in place of ``ic``; otherwise the variables of
        :func:`map_starts`. ``attrs["fixed_<name>"]`` records the fixed coordinates.

    Examples
    --------
    >>> from rotorlab.explore import TorusRegimes
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> mapper = TorusRegimes(strautmanis_torus(1e-4), t_end=4.0, n_horizons=2)
    >>> ds = basin_map(mapper, GridAxis("psi", 1.0, 5.0, 3), GridAxis("dpsi", -20.0, 20.0, 2))
    >>> ds.label.dims, [str(v) for v in ds.outcome.attrs["labels"]]
    (('dpsi', 'psi', 'horizon'), ['working', 'spare', 'other'])
    """
    if not isinstance(x, GridAxis) or not isinstance(y, GridAxis):
        raise TypeError("x and y must be GridAxis objects")
    if x.name == y.name:
        raise ValueError(f"x and y must be different coordinates, both are {x.name!r}")
    fixed = dict(fixed or {})
    clash = {x.name, y.name} & set(fixed)
    if clash:
        raise ValueError(f"coordinates {sorted(clash)} are both varied and fixed")
    from rotorlab.sweep import Sweep

    sweep = Sweep(MapperAnalysis(mapper), axes=(y, x), fixed=fixed)
    return run_mapped(sweep, threads=threads, chunk_size=chunk_size, progress=progress, store=store, resume=resume,
                      executor=executor)  # fmt: skip


def basin_fractions(ds):
    """Fraction of start points carrying each label, at every horizon.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`map_starts`, :func:`basin_map` or :func:`basin_stability`: a ``label``
        variable with a ``horizon`` dim and ``attrs["labels"]``.

    Returns
    -------
    xarray.Dataset
        Dims ``horizon`` and ``regime`` (the label names): ``fraction`` (1) and ``count`` (1);
        ``attrs["n"]``.
        Fractions at each horizon sum to 1; ``.isel(horizon=-1)`` are the final fractions and
        their change along ``horizon`` shows whether the simulated time was long enough.

    Examples
    --------
    >>> import xarray as xr
    >>> lab = xr.DataArray([[0, 0], [1, 0], [2, 2]], dims=("ic", "horizon"),
    ...                    attrs={"labels": ["a", "b", "c"]})
    >>> fr = basin_fractions(xr.Dataset({"label": lab}, coords={"horizon": [1.0, 2.0]}))
    >>> fr.fraction.sel(horizon=2.0).values.round(3).tolist()
    [0.667, 0.0, 0.333]
    """
    import xarray as xr

    label = ds["label"]
    names = list(label.attrs["labels"])
    other_dims = [d for d in label.dims if d != "horizon"]
    lab = label.transpose(*other_dims, "horizon").values.reshape(-1, label.sizes["horizon"])
    n = lab.shape[0]
    counts = np.stack([(lab == k).sum(axis=0) for k in range(len(names))], axis=1)
    return xr.Dataset(
        {
            "fraction": (("horizon", "regime"), counts / max(n, 1), {"units": "1"}),
            "count": (("horizon", "regime"), counts, {"units": "1"}),
        },
        coords={"horizon": ds["horizon"], "regime": names},
        attrs={"n": n},
    )


def basin_stability(
    mapper: AbstractMapper,
    ranges: Mapping[str, tuple[float, float]],
    n: int,
    *,
    seed: int,
    confidence: float = 0.95,
    fixed: Mapping[str, float] | None = None,
    threads: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    store: Any = None,
    resume: bool = False,
    executor: Any = None,
):
    """Probability of reaching each regime from random starts (basin stability).

    Start coordinates are drawn uniformly and independently from ``ranges`` with
    ``numpy.random.default_rng(seed)``, one coordinate after the other in the order of
    ``ranges``; the same seed always gives the same starts and, the mapper being pure, the same
    labels.

    Parameters
    ----------
    mapper : AbstractMapper
    ranges : mapping of str to (low, high)
        Coordinates to draw and their ranges.
    n : int
        Number of starts, >= 1.
    seed : int
        Seed of the random generator.
    confidence : float
        Level of the Wilson score intervals, in (0, 1).
    fixed, threads, chunk_size, progress, store, resume, executor
        As for :func:`basin_map`.

    Returns
    -------
    xarray.Dataset
        Dims ``horizon``, ``regime`` and ``ic``: ``probability`` (horizon, regime), ``ci_low``,
        ``ci_high`` (Wilson interval), ``count``, and the per-start variables of
        :func:`map_starts`; attrs ``seed``, ``confidence``, ``n``.

    References
    ----------
    Menck P.J., Heitzig J., Marwan N., Kurths J. How basin stability complements the linear-
    stability paradigm. Nature Physics 9 (2013) 89-92.
    """
    if isinstance(n, bool) or int(n) != n or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")
    if not ranges:
        raise ValueError("ranges must name at least one coordinate to draw")
    sample = Sample(ranges, int(n), seed, dim="ic")
    clash = set(ranges) & set(fixed or {})
    if clash:
        raise ValueError(f"coordinates {sorted(clash)} are both drawn and fixed")
    from rotorlab.sweep import Sweep

    sweep = Sweep(MapperAnalysis(mapper), sample=sample, fixed=dict(fixed or {}))
    ds = run_mapped(sweep, threads=threads, chunk_size=chunk_size, progress=progress, store=store, resume=resume,
                    executor=executor)  # fmt: skip
    fr = basin_fractions(ds)
    low, high = wilson_interval(fr["count"].values, int(n), confidence)
    out = ds.assign(
        probability=fr["fraction"].assign_attrs(units="1"),
        count=fr["count"],
        ci_low=(("horizon", "regime"), low, {"units": "1", "confidence": confidence}),
        ci_high=(("horizon", "regime"), high, {"units": "1", "confidence": confidence}),
    )
    out.attrs.update(seed=int(seed), confidence=float(confidence), n=int(n))
    return out
