"""Basin stability over a parameter: the probability of every regime from seeded random starts, with
Wilson intervals, at each value of a parameter, sampled until the intervals are as narrow as asked.

Layers: :class:`RandomStarts` is a per-point analysis that turns a start *number* into random
start coordinates (the same starts at every parameter value: common random numbers) and runs the
mapper on them; :func:`basin_stability_over` runs the sweep ``parameter x start number`` on the
sweep engine (:func:`rotorlab.sweep.run_sweep`: Zarr store, resume, any executor) in rounds, each
round computing only the chunks that the results so far call for; :func:`starts_for_half_width`
and :func:`needed_starts` are the sample sizes.

Adaptive sampling: the starts of one parameter value fill whole chunks of its own. A round adds
chunks to every value whose widest Wilson interval (over all regimes) is wider than ``2 W``, as
many as the fractions seen so far need (at most four times as many starts as it has), and never
more than :func:`starts_for_half_width` (enough for any fraction, the worst being 1/2). The rounds
depend only on the results, so a resumed run replays them and computes only what is missing.
"""

from __future__ import annotations

import contextlib
import json
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab._limits import MAX_STARTS
from rotorlab._wilson import _z, min_half_width, starts_for_half_width, wilson_interval

__all__ = ["RandomStarts", "basin_stability_over", "starts_for_half_width", "needed_starts", "half_widths",
           "START_DIM", "MAX_STARTS", "ADAPTIVE_CHUNK"]  # fmt: skip

#: Name of the start-number coordinate (and result dim).
START_DIM = "start"
#: Starts drawn from one seeded generator: start ``j`` comes from block ``j // _BLOCK``.
_BLOCK = 256
#: Starts per chunk of an adaptive run when none is given (the step in which a value grows).
ADAPTIVE_CHUNK = 128


def half_widths(counts, n, confidence: float = 0.95) -> np.ndarray:
    """Half the width of the widest Wilson interval over the last axis of ``counts`` (regimes).

    Examples
    --------
    >>> round(float(half_widths(np.array([50, 50]), 100)), 4)
    0.0962
    """
    counts = np.asarray(counts, dtype=float)
    lo, hi = wilson_interval(counts, np.asarray(n, dtype=float)[..., None], confidence)
    return np.max(hi - lo, axis=-1) / 2.0


def needed_starts(counts, n: int, width: float, confidence: float, step: int, cap: int) -> int:
    """The fewest starts (a multiple of ``step``, at most ``cap``) whose widest Wilson interval has
    a half-width <= ``width`` if the fractions stay ``counts / n``.

    Examples
    --------
    >>> needed_starts(np.array([0, 100]), 100, 0.02, 0.95, 64, 2432)  # all balanced: 1.92 / n
    128
    >>> needed_starts(np.array([50, 50]), 100, 0.02, 0.95, 64, 2432)  # a fraction 1/2
    2432
    """
    p = np.asarray(counts, dtype=float) / max(n, 1)
    sizes = np.arange(step, cap + step, step, dtype=float)
    ok = half_widths(p[None, :] * sizes[:, None], sizes, confidence) <= width
    return int(sizes[int(np.argmax(ok))]) if ok.any() else int(cap)


@dataclass(frozen=True, eq=False)
class RandomStarts:
    """Per-point analysis: start number ``j`` -> random start coordinates -> ``analysis``.

    Start ``j`` draws its coordinates uniformly from ``ranges`` with
    ``numpy.random.default_rng([seed, j // 256])`` (row ``j % 256`` of a block of draws), so a
    start is the same in every chunk, process and run, and at every value of a swept parameter.

    Parameters
    ----------
    analysis : AbstractPointAnalysis
        What runs at each start, e.g. :class:`rotorlab.explore.MapperAnalysis`.
    ranges : tuple of (name, low, high)
        Start coordinates of ``analysis`` to draw, in SI; ``low < high`` (a value of its own is
        a fixed coordinate instead).
    seed : int
        Seed of the starts, >= 0.

    Examples
    --------
    >>> from rotorlab.explore import MapperAnalysis, TorusRegimes
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> a = RandomStarts(MapperAnalysis(TorusRegimes(strautmanis_torus(1e-4), t_end=1.0)), (("psi", 0.0, 6.0),), 7)
    >>> a.draw(np.array([3, 300]))["psi"].round(4).tolist() == a.draw(np.array([300, 3]))["psi"][::-1].round(4).tolist()
    True
    """

    analysis: Any
    ranges: tuple[tuple[str, float, float], ...]
    seed: int

    def __post_init__(self) -> None:
        from rotorlab.sweep import AbstractPointAnalysis

        if not isinstance(self.analysis, AbstractPointAnalysis):
            raise TypeError(f"RandomStarts.analysis must implement AbstractPointAnalysis, got "
                            f"{type(self.analysis).__name__}")  # fmt: skip
        known = self.analysis.coordinate_units
        norm = []
        for name, lo, hi in self.ranges:
            lo, hi = float(lo), float(hi)
            if name not in known or name == START_DIM:
                raise ValueError(f"RandomStarts.ranges: {name!r} is not a start coordinate (allowed: {', '.join(known)})")
            if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
                raise ValueError(f"RandomStarts.ranges: {name} must have finite low < high, got ({lo!r}, {hi!r})")
            norm.append((str(name), lo, hi))
        if not norm or len({r[0] for r in norm}) != len(norm):
            raise ValueError("RandomStarts.ranges must name one or more different coordinates")
        if isinstance(self.seed, bool) or int(self.seed) != self.seed or self.seed < 0:
            raise ValueError(f"RandomStarts.seed must be an integer >= 0, got {self.seed!r}")
        object.__setattr__(self, "ranges", tuple(norm))
        object.__setattr__(self, "seed", int(self.seed))

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return {**dict(self.analysis.coordinate_units), START_DIM: "1"}

    def draw(self, index: np.ndarray) -> dict[str, np.ndarray]:
        """The start coordinates of the start numbers ``index`` (SI)."""
        idx = np.asarray(index, dtype=np.int64).reshape(-1)
        u = np.empty((idx.size, len(self.ranges)))
        for block in np.unique(idx // _BLOCK):
            rows = np.random.default_rng([self.seed, int(block)]).random((_BLOCK, len(self.ranges)))
            sel = idx // _BLOCK == block
            u[sel] = rows[idx[sel] % _BLOCK]
        return {name: lo + (hi - lo) * u[:, i] for i, (name, lo, hi) in enumerate(self.ranges)}

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        from rotorlab.sweep import ChunkVar

        cols = {k: np.asarray(v) for k, v in coords.items()}
        drawn = self.draw(np.rint(cols.pop(START_DIM)).astype(np.int64))
        out = self.analysis.run_chunk({**cols, **drawn}, threads=threads)
        units = self.analysis.coordinate_units
        for name, values in drawn.items():
            out[f"start_{name}"] = ChunkVar((), values, {"units": units.get(name, ""), "description": "drawn start"})
        return out

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return self.analysis.trailing_coords()

    def result_attrs(self) -> dict[str, Any]:
        return dict(self.analysis.result_attrs())


def _chunk_plan(starts: int | None, width: float | None, confidence: float, chunk: int | None) -> tuple[int, int]:
    """Starts per chunk and the pool of starts per parameter value (a multiple of it)."""
    if starts is not None:
        if chunk is None:  # whole chunks of at most 1024 starts that make exactly ``starts``
            divisors = [d for d in range(min(starts, 1024), 0, -1) if starts % d == 0]
            chunk = divisors[0] if divisors[0] >= 64 or starts <= 1024 else min(starts, 1024)
        return chunk, -(-starts // chunk) * chunk
    chunk = ADAPTIVE_CHUNK if chunk is None else chunk
    return chunk, -(-starts_for_half_width(width, confidence) // chunk) * chunk


def basin_stability_over(
    analysis: Any,
    axis: Any,
    ranges: Mapping[str, tuple[float, float]],
    *,
    seed: int,
    starts: int | None = None,
    ci_width: float | None = None,
    confidence: float = 0.95,
    fixed: Mapping[str, float] | None = None,
    chunk_size: int | None = None,
    store: Any = None,
    resume: bool = False,
    executor: Any = None,
    progress: Callable[[int, int], None] | None = None,
    input_units: Mapping[str, str] | None = None,
):
    """Probability of every regime from random starts at each value of a parameter (basin stability).

    Parameters
    ----------
    analysis : AbstractMapper or AbstractPointAnalysis
        A mapper (wrapped in :class:`~rotorlab.explore.MapperAnalysis`) or any per-point analysis
        with ``label`` (horizon) and ``outcome`` results and ``result_attrs()["labels"]``.
    axis : rotorlab.sweep.GridAxis or ListAxis
        The parameter and its values (SI).
    ranges : mapping of str to (low, high)
        Start coordinates drawn uniformly at random (e.g. every ball angle over [0, 2 pi)).
    seed : int
        Seed of the starts (:class:`RandomStarts`).
    starts : int, optional
        This many starts at every value (rounded up to whole chunks when ``chunk_size`` does not
        divide it). Excludes ``ci_width``.
    ci_width : float, optional
        Target half-width of the Wilson intervals, in (0, 0.5): starts are added at each value in
        rounds until the widest interval of its regimes is at most this wide on either side
        (default 0.05 when neither is given).
    confidence : float
        Level of the Wilson intervals.
    fixed : mapping of str to float, optional
        Other coordinates held at a value (SI).
    chunk_size : int, optional
        Starts per chunk (adaptive: the step in which a value grows, default
        :data:`ADAPTIVE_CHUNK`).
    store, resume, executor
        As for :func:`rotorlab.sweep.run_sweep`: a Zarr store of the sweep ``(parameter,
        start)``, continued with ``resume``; without a store the rounds keep their starts in
        memory. Results do not depend on the executor or on interruptions.
    progress : callable, optional
        ``progress(done, planned)`` in starts (planned grows with the rounds).
    input_units : mapping of str to str, optional
        Display units of angle coordinates (:class:`rotorlab.sweep.Sweep`).

    Returns
    -------
    xarray.Dataset
        Dims ``(axis.name, regime)``, ``horizon`` and ``start``: ``n`` (starts at each value),
        ``count`` (value, horizon, regime), ``probability``, ``ci_low``, ``ci_high`` (value,
        regime; at the last horizon), ``half_width`` (widest interval's, value), ``computed``
        (value, start), the per-start ``outcome``, ``status``, ``label_since`` and (a balancer)
        ``settle_estimate`` and ``amplitude`` at the last horizon, and the drawn ``start_<name>``; attrs of the
        analysis plus ``seed``, ``confidence``, ``mode`` ("starts" or "ci-width"), ``target_half_width``,
        ``chunk``, ``pool``, ``rounds``, ``param``, ``ranges`` (JSON: name -> [low, high]).

    References
    ----------
    Menck P.J., Heitzig J., Marwan N., Kurths J. How basin stability complements the linear-
    stability paradigm. Nature Physics 9 (2013) 89-92.
    """
    from rotorlab.explore._mapper import AbstractMapper, MapperAnalysis
    from rotorlab.sweep import GridAxis, Sweep
    from rotorlab.sweep._store import MemorySink

    if starts is not None and ci_width is not None:
        raise ValueError("give starts or ci_width, not both")
    if starts is None and ci_width is None:
        ci_width = 0.05
    if starts is not None and (isinstance(starts, bool) or int(starts) != starts or not 1 <= starts <= MAX_STARTS):
        raise ValueError(f"starts must be an integer in [1, {MAX_STARTS}], got {starts!r}")
    if ci_width is not None:
        if not (isinstance(ci_width, (int, float)) and 0.0 < ci_width < 0.5):
            raise ValueError(f"ci_width must be in (0, 0.5), got {ci_width!r}")
        if starts_for_half_width(ci_width, confidence) > MAX_STARTS:
            raise ValueError(f"ci_width = {ci_width:g} needs up to {starts_for_half_width(ci_width, confidence)} starts "
                             f"per value, more than {MAX_STARTS}: ask for {min_half_width(confidence):.3g} or wider")
    point = MapperAnalysis(analysis) if isinstance(analysis, AbstractMapper) else analysis
    chunk, pool = _chunk_plan(None if starts is None else int(starts), ci_width, confidence, chunk_size)
    sampler = RandomStarts(point, tuple((k, *v) for k, v in ranges.items()), seed)
    sweep = Sweep(sampler, axes=(axis, GridAxis(START_DIM, 0.0, float(pool - 1), pool)), fixed=dict(fixed or {}),
                  input_units=dict(input_units or {}))  # fmt: skip
    per = pool // chunk
    n = np.full(axis.num, pool if starts is not None else min(pool, chunk * -(-_first_guess(ci_width, confidence) // chunk)))
    sink = store if store is not None else MemorySink(sweep, chunk)
    with contextlib.ExitStack() as stack:
        # one Dask cluster (or client) for all rounds, not one per round
        executor = stack.enter_context(executor.session()) if hasattr(executor, "session") else executor
        ds, n, rounds = _rounds(sweep, sink, store, resume, chunk, executor, progress, n, axis.num, per, pool, starts,
                                ci_width, confidence)  # fmt: skip
    out = _summary(ds, n, axis.name, confidence)
    out.attrs.update(seed=int(seed), confidence=float(confidence), mode="starts" if starts is not None else "ci-width",
                     target_half_width=float("nan") if ci_width is None else float(ci_width), chunk=int(chunk),
                     pool=int(pool), rounds=rounds, param=axis.name,
                     ranges=json.dumps({k: [float(v[0]), float(v[1])] for k, v in ranges.items()}))  # fmt: skip
    return out


def _rounds(sweep, sink, store, resume, chunk, executor, progress, n, n_values, per, pool, starts, ci_width,
            confidence):  # fmt: skip
    """Run the rounds of :func:`basin_stability_over`: its last Dataset, starts per value, rounds."""
    from rotorlab.sweep import run_sweep

    rounds = 0
    while True:
        rounds += 1
        wanted = [i * per + b for i in range(n_values) for b in range(int(n[i]) // chunk)]
        ds = run_sweep(sweep, store=sink, resume=store is not None and (resume or rounds > 1),
                       chunk_size=chunk if store is not None else None, executor=executor, only=wanted,
                       progress=_progress(progress, chunk, int(n.sum())))  # fmt: skip
        if starts is not None:
            return ds, n, rounds
        counts = _final_counts(ds, n, sweep.axes[0].name)
        wide = half_widths(counts, n, confidence) > ci_width
        grow = np.array([min(pool, max(n[i] + chunk, min(needed_starts(counts[i], int(n[i]), ci_width, confidence,
                                                                        chunk, pool), 4 * n[i])))
                         if wide[i] and n[i] < pool else n[i] for i in range(n_values)])  # fmt: skip
        if np.array_equal(grow, n):
            return ds, n, rounds
        n = grow


def _first_guess(width: float, confidence: float) -> int:
    """Starts at which a fraction of 0 or 1 meets ``width`` (its half-width is z^2 / (2 (n + z^2)))."""
    z = _z(confidence)
    return max(1, math.ceil(z * z / (2.0 * width) - z * z))


def _progress(progress: Callable[[int, int], None] | None, chunk: int, planned: int):
    if progress is None:
        return None

    def report(p: Any) -> None:
        progress(min(planned, p.chunks_done * chunk), planned)

    return report


def _final_counts(ds: Any, n: np.ndarray, dim: str) -> np.ndarray:
    """Counts of every final label over the computed starts at each value, shape (values, regimes)."""
    labels = list(ds["outcome"].attrs["labels"])
    out = np.asarray(ds["outcome"].transpose(dim, START_DIM).values)
    computed = np.arange(out.shape[1])[None, :] < n[:, None]
    return np.stack([np.sum((out == k) & computed, axis=1) for k in range(len(labels))], axis=1)


def _summary(ds: Any, n: np.ndarray, dim: str, confidence: float) -> Any:
    """The fractions, intervals and per-start results of the computed starts."""
    import xarray as xr

    labels = [str(v) for v in ds["outcome"].attrs["labels"]]
    keep = int(n.max())
    part = ds.isel({START_DIM: slice(0, keep)})
    label = np.asarray(part["label"].transpose(dim, START_DIM, "horizon").values)
    computed = np.arange(keep)[None, :] < n[:, None]
    count = np.stack([np.sum((label == k) & computed[:, :, None], axis=1) for k in range(len(labels))], axis=2)
    low, high = wilson_interval(count[:, -1, :], n[:, None].astype(float), confidence)
    values = part[dim].values
    data = {
        "n": ((dim,), n.astype(np.int64), {"units": "1", "description": "random starts at the value"}),
        "count": ((dim, "horizon", "regime"), count, {"units": "1", "description": "starts with each label"}),
        "probability": ((dim, "regime"), count[:, -1, :] / n[:, None], {"units": "1", "description":
                        "fraction of the starts with each final label"}),
        "ci_low": ((dim, "regime"), low, {"units": "1", "confidence": confidence}),
        "ci_high": ((dim, "regime"), high, {"units": "1", "confidence": confidence}),
        "half_width": ((dim,), np.max(high - low, axis=1) / 2.0, {"units": "1", "description":
                       "half the width of the widest Wilson interval"}),
        "computed": ((dim, START_DIM), computed, {"units": "1"}),
    }  # fmt: skip
    for name in part.data_vars:
        var = part[name]
        if name in ("outcome", "status", "label_since") or name.startswith("start_"):
            values_ = np.asarray(var.transpose(dim, START_DIM).values)
            if name == "outcome":  # -1: a start not computed at that value
                values_ = np.where(computed, values_, -1).astype(values_.dtype)
            data[name] = ((dim, START_DIM), values_, dict(var.attrs))
        elif name in ("settle_estimate", "amplitude"):
            data[name] = ((dim, START_DIM), np.asarray(var.isel(horizon=-1).transpose(dim, START_DIM).values),
                          dict(var.attrs))  # fmt: skip
    attrs = {k: v for k, v in ds.attrs.items() if k not in ("sweep", "fingerprint", "complete")}
    attrs["labels"] = labels
    return xr.Dataset(data, coords={dim: (dim, values, dict(part[dim].attrs)), "regime": labels,
                                    "horizon": part["horizon"],
                                    START_DIM: (START_DIM, np.arange(keep), {"units": "1", "description": "start number"})},
                      attrs=attrs)  # fmt: skip
