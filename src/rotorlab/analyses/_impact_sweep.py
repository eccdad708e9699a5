"""Impact sweeps on the sweep engine: many random stone sequences at each value of a parameter.

:class:`ImpactAnalysis` is the per-point analysis of :mod:`rotorlab.sweep` for the centrifuge
rotor striking its housing (seed 001): a point is one run from rest, given by the values of
:data:`~rotorlab.analyses.SWEEP_PARAMS` (``stone_mass``, ``interval``, ...) and the ``seed`` of
its stone sequence; its result is the run's bookkeeping (impacts, sliding time, energy ratio,
regime ...). :func:`impact_sweep` runs it over a ``value x sequence`` grid through
:func:`rotorlab.sweep.run_sweep`, in memory or into a resumable Zarr store, in-process, on local
processes or on Dask, and summarizes the sequences per value (median, quartiles, regimes).

Every run is integrated on its own, so a point's result never depends on the chunk it is in,
the chunk size, the executor or the number of threads.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.analyses._impacts import (
    _DESCRIPTIONS,
    _UNITS,
    REGIMES,
    SLIDING_FRACTION,
    SWEEP_PARAMS,
    _control,
    _model_attrs,
    _scalars,
    classify_impacts,
    stacked_params,
)

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import ImpactRotor

__all__ = ["ImpactAnalysis", "impact_sweep", "impact_sweep_definition", "summarize_impact_sweep"]

#: Result variables of a point, in order (see :func:`rotorlab.analyses.impact_run`).
POINT_VARIABLES = ("impacts", "impacts_all", "slides", "sliding_time", "max_penetration", "max_approach_speed",
                   "energy_stones", "energy_friction", "energy_restitution", "eta", "runaway_start",
                   "impacts_before_runaway", "energy_friction_before_runaway", "eta_before_runaway",
                   "impacts_runaway", "energy_friction_runaway", "whirl", "t_final", "status", "n_steps",
                   "regime")  # fmt: skip


def _with_params(model: ImpactRotor, values: Mapping[str, float]) -> ImpactRotor:
    """``model`` with the :data:`SWEEP_PARAMS` in ``values`` replaced (SI)."""
    for name, value in values.items():
        part, fld, _ = SWEEP_PARAMS[name]
        model = replace(model, **{part: replace(getattr(model, part), **{fld: float(value)})})
    return model


@dataclass(frozen=True, slots=True)
class ImpactAnalysis:
    """One run from rest per point, with its own seeded stone sequence (a sweep's point analysis).

    Coordinates: any of :data:`~rotorlab.analyses.SWEEP_PARAMS` (replacing the model's value)
    and ``seed`` (the seed of the stone sequence, :meth:`rotorlab.models.StoneFeed.sequence`;
    default 0). The result of a point is what :func:`~rotorlab.analyses.impact_run` reports of
    a run (without the trajectory): ``impacts``, ``impacts_all``, ``slides``, ``sliding_time``,
    ``max_penetration``, ``max_approach_speed``, ``energy_stones``, ``energy_friction``,
    ``energy_restitution``, ``eta``, ``whirl``, ``t_final``, ``status``, ``n_steps`` and
    ``regime`` (code, see :func:`~rotorlab.analyses.classify_impacts`).

    Parameters
    ----------
    model : ImpactRotor
        The base model (its stone feed; any sequence it carries is replaced).
    t_end : float
        Duration of each run (s), > 0.
    rtol, atol : float
        Integrator tolerances (atol in m, m/s, rad, rad/s).
    sliding_fraction : float
        See :func:`~rotorlab.analyses.classify_impacts`.

    Examples
    --------
    >>> from rotorlab.models import krasnov_crusher
    >>> a = ImpactAnalysis(krasnov_crusher(), t_end=1.0)
    >>> out = a.run_chunk({"stone_mass": np.array([0.5, 3.0]), "seed": np.array([0.0, 0.0])})
    >>> out["impacts"].values.tolist()[0], bool(out["impacts"].values[1] > 0), out["sliding_time"].attrs["units"]
    (0, True, 's')
    """

    model: Any
    t_end: float = 10.0
    rtol: float = 1e-8
    atol: float = 1e-11
    sliding_fraction: float = SLIDING_FRACTION

    def __post_init__(self) -> None:
        from rotorlab.models import ImpactRotor

        if not isinstance(self.model, ImpactRotor):
            raise TypeError(f"ImpactAnalysis.model must be an ImpactRotor, got {type(self.model).__name__}")
        if not (self.t_end > 0 and math.isfinite(self.t_end)):
            raise ValueError(f"t_end must be a finite number > 0 (s), got {self.t_end!r}")
        # the base model's own sequence plays no part: leave it out of the description
        object.__setattr__(self, "model", ImpactRotor(self.model.rotor, self.model.housing, self.model.stones))
        for name in ("t_end", "rtol", "atol", "sliding_fraction"):
            object.__setattr__(self, name, float(getattr(self, name)))

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return {**{name: unit for name, (_, _, unit) in SWEEP_PARAMS.items()}, "seed": "1"}

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return {}

    def result_attrs(self) -> dict[str, Any]:
        attrs = _model_attrs(self.model, self.t_end, self.sliding_fraction)
        return {**attrs, "analysis": "impact-points", "regimes": list(REGIMES), "rtol": self.rtol, "atol": self.atol}

    def models(self, coords: Mapping[str, np.ndarray]) -> list[ImpactRotor]:
        """The model of each point, with its stone sequence drawn."""
        cols = {k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in coords.items()}
        n = next(iter(cols.values())).size if cols else 1
        seeds = cols.pop("seed", np.zeros(n))
        unknown = set(cols) - set(SWEEP_PARAMS)
        if unknown:
            raise ValueError(f"unknown coordinate(s) {sorted(unknown)}; accepted: {', '.join(self.coordinate_units)}")
        out = []
        for i in range(n):
            if seeds[i] != int(seeds[i]) or seeds[i] < 0:
                raise ValueError(f"seed must be an integer >= 0, got {seeds[i]!r}")
            base = _with_params(self.model, {k: v[i] for k, v in cols.items()})
            out.append(base.with_stones(self.t_end, int(seeds[i])))
        return out

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        """Run one chunk of points (see :class:`rotorlab.sweep.AbstractPointAnalysis`)."""
        from rotorlab.integrate import solve_ensemble
        from rotorlab.sweep import ChunkVar

        models = self.models(coords)
        sol = solve_ensemble(models[0], models[0].initial_state(), (0.0, self.t_end), params=stacked_params(models),
                             control=_control(self.rtol, self.atol), threads=threads)  # fmt: skip
        sc = _scalars(models, sol)
        sc["regime"] = classify_impacts(sc["impacts"], sc["sliding_time"], sc["t_final"], sc["whirl"], sc["status"],
                                        self.sliding_fraction)  # fmt: skip
        return {k: ChunkVar((), sc[k], {"units": _UNITS[k], "description": _DESCRIPTIONS[k]}) for k in POINT_VARIABLES}


def impact_sweep_definition(model: ImpactRotor, values: Sequence[float], *, param: str = "stone_mass",
                            n_sequences: int = 16, t_end: float = 10.0, seed: int = 0, rtol: float = 1e-8,
                            atol: float = 1e-11, sliding_fraction: float = SLIDING_FRACTION) -> Any:  # fmt: skip
    """The :class:`rotorlab.sweep.Sweep` of :func:`impact_sweep`: axes ``param`` and ``seed``.

    Raises
    ------
    ValueError
        Unknown ``param``, empty ``values``, ``n_sequences`` < 1, bad ``t_end`` or ``seed``.

    Examples
    --------
    >>> from rotorlab.models import krasnov_crusher
    >>> sw = impact_sweep_definition(krasnov_crusher(), [0.5, 1.0], n_sequences=3, seed=10)
    >>> sw.dims, sw.shape, sw.coordinates()["seed"].tolist()
    (('stone_mass', 'seed'), (2, 3), [10.0, 11.0, 12.0, 10.0, 11.0, 12.0])
    """
    from rotorlab.sweep import ListAxis, Sweep

    if param not in SWEEP_PARAMS:
        raise ValueError(f"param must be one of {', '.join(SWEEP_PARAMS)}, got {param!r}")
    values = np.atleast_1d(np.asarray(values, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError("values must be a non-empty 1-D sequence")
    if int(n_sequences) < 1:
        raise ValueError(f"n_sequences must be >= 1, got {n_sequences!r}")
    if isinstance(seed, bool) or int(seed) != seed or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    analysis = ImpactAnalysis(model, t_end=t_end, rtol=rtol, atol=atol, sliding_fraction=sliding_fraction)
    seeds = int(seed) + np.arange(int(n_sequences))
    return Sweep(analysis, axes=(ListAxis(param, values), ListAxis("seed", seeds)))


def default_chunk(sweep: Any, *, split: bool) -> int:
    """Runs per chunk of an impact sweep: one value's sequences if ``split``, else every run."""
    n_val, n_seq = sweep.shape
    return n_seq if split else n_val * n_seq


def impact_sweep(model: ImpactRotor, values: Sequence[float], *, param: str = "stone_mass",
                 n_sequences: int = 16, t_end: float = 10.0, seed: int = 0, rtol: float = 1e-8,
                 atol: float = 1e-11, sliding_fraction: float = SLIDING_FRACTION,
                 threads: int | None = None, progress: Callable[[int, int], None] | None = None,
                 store: Any = None, resume: bool = False, executor: Any = None,
                 chunk_size: int | None = None) -> xarray.Dataset:  # fmt: skip
    """Run many random stone sequences at each value of one parameter (the seed's table, Fig. 5).

    Sequence j uses the seed ``seed + j`` at every value (common random numbers), so values are
    compared on the same stones. A use of the sweep engine: :func:`rotorlab.sweep.run_sweep`
    with :class:`ImpactAnalysis` over the axes ``param`` x ``seed``.

    Parameters
    ----------
    model : ImpactRotor
    values : sequence of float
        Values of ``param`` (SI).
    param : str
        One of :data:`SWEEP_PARAMS`: ``stone_mass`` (kg), ``interval`` (s),
        ``internal_friction``, ``restitution``, ``friction``.
    n_sequences : int
        Random stone sequences per value, >= 1.
    t_end : float
        Duration of each run (s).
    seed : int
        Seed of the first sequence, >= 0.
    rtol, atol : float
        Integrator tolerances.
    sliding_fraction : float
        See :func:`classify_impacts`.
    threads : int, optional
        Threads of the ensemble in this process (results do not depend on it); ignored when an
        ``executor`` is given.
    progress : callable, optional
        ``progress(done, total)`` (runs) after each chunk of runs.
    store : path-like, optional
        Zarr store (folder) that receives the runs chunk by chunk, with completion marks (see
        :func:`rotorlab.sweep.run_sweep`); it opens with :func:`rotorlab.sweep.open_sweep` as
        the per-run table over ``param`` x ``seed``.
    resume : bool
        Continue the runs in ``store`` (only its missing chunks are computed).
    executor : InProcess, LocalProcesses or DaskExecutor, optional
        Where the chunks run (default: this process). Results do not depend on it.
    chunk_size : int, optional
        Runs per chunk (default: all runs in one chunk, or one value's sequences per chunk with
        a ``store``, an ``executor`` or ``progress``; a resumed store keeps its own). Results do
        not depend on it.

    Returns
    -------
    xarray.Dataset
        Dims ``value`` (the swept parameter, named in ``attrs["param"]``) and ``sequence``:
        every scalar of :func:`impact_run` plus ``regime``; per value the median and quartiles of
        ``impacts`` and ``eta`` and the fraction of runs in each regime (dim ``regime``).

    Raises
    ------
    rotorlab.sweep.SweepStoreError
        ``store`` exists without ``resume``, or holds another sweep.
    KeyboardInterrupt
        From ``progress`` or Ctrl-C: the finished chunks are kept in ``store``.

    Examples
    --------
    >>> from rotorlab.models import krasnov_crusher
    >>> ds = impact_sweep(krasnov_crusher(), [0.5, 1.0], n_sequences=2, t_end=2.0)
    >>> ds.impacts.values[0].tolist(), bool((ds.impacts.values[1] > 5).all()), ds.attrs["param"]
    ([0, 0], True, 'stone_mass')
    """
    from rotorlab.sweep import InProcess, run_sweep

    sweep = impact_sweep_definition(model, values, param=param, n_sequences=n_sequences, t_end=t_end, seed=seed,
                                    rtol=rtol, atol=atol, sliding_fraction=sliding_fraction)  # fmt: skip
    if chunk_size is None and not (resume and store is not None):
        chunk_size = default_chunk(sweep, split=store is not None or progress is not None or executor is not None)

    def report(p: Any) -> None:
        if progress is not None and p.computed:
            progress(p.done, p.total)

    runs = run_sweep(sweep, store=store, resume=resume, chunk_size=chunk_size,
                     executor=executor or InProcess(threads), progress=report)  # fmt: skip
    return summarize_impact_sweep(runs, model, param=param, seed=int(seed))


def summarize_impact_sweep(runs: xarray.Dataset, model: ImpactRotor, *, param: str, seed: int) -> xarray.Dataset:
    """The Dataset of :func:`impact_sweep` from the per-run table of its sweep (dims ``param``, ``seed``)."""
    import xarray as xr

    unit = SWEEP_PARAMS[param][2]
    values = np.asarray(runs[param].values, dtype=float)
    n_seq = runs.sizes["seed"]
    t_end, sliding_fraction = float(runs.attrs["t_end"]), float(runs.attrs["sliding_fraction"])
    sc = {k: np.asarray(runs[k].values) for k in POINT_VARIABLES}
    data = {k: (("value", "sequence"), v, {"units": _UNITS[k], "description": _DESCRIPTIONS[k]})
            for k, v in sc.items()}  # fmt: skip
    for name in ("impacts", "eta", "eta_before_runaway", "sliding_time"):
        arr = np.where(sc["regime"] < 0, np.nan, sc[name].astype(float))  # a failed run has no value
        with warnings.catch_warnings():  # a value whose runs all failed has no quantiles (NaN), as meant
            warnings.simplefilter("ignore", RuntimeWarning)
            q = np.nanquantile(arr, [0.25, 0.5, 0.75], axis=1) if np.isfinite(arr).any() else np.full((3, values.size), np.nan)
        for tag, row in zip(("q25", "median", "q75"), q):
            data[f"{name}_{tag}"] = (("value",), row, {"units": _UNITS[name], "description": f"{tag} over sequences"})
    frac = np.stack([(sc["regime"] == c).mean(axis=1) for c in range(len(REGIMES))], axis=1)
    data["regime_fraction"] = (("value", "regime_label"), frac, {"units": "1"})
    data["failed_fraction"] = (("value",), (sc["regime"] < 0).mean(axis=1), {"units": "1"})
    data["seed"] = (("sequence",), seed + np.arange(n_seq), {"units": "1", "description": "seed of the stone sequence"})
    ds = xr.Dataset(data, coords={"value": ("value", values, {"units": unit, "long_name": param}),
                                  "sequence": ("sequence", np.arange(n_seq), {"units": "1"}),
                                  "regime_label": list(REGIMES)})  # fmt: skip
    ds.attrs.update(_model_attrs(model, t_end, sliding_fraction))
    ds.attrs.update({"analysis": "impacts-sweep", "param": param, "param_units": unit, "seed": int(seed),
                     "n_sequences": int(n_seq)})  # fmt: skip
    return ds
