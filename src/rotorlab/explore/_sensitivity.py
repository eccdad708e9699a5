"""Variance-based sensitivity (Sobol indices) of any per-point analysis to uncertain inputs with
stated distributions, evaluated on the sweep engine.

Layers: an :class:`UncertainInput` is a named coordinate of a per-point analysis with a
:class:`Distribution` (normal by mean and standard deviation or a relative tolerance, uniform
between bounds, either truncated where the physics demands it); :func:`sobol_sample` draws
Saltelli's design for first- and total-order indices (``SALib.sample.sobol``: a scrambled Sobol
sequence on the unit cube, seeded) and maps it through each input's quantile function
(``scipy.stats``); :func:`sobol_indices` estimates the indices and their bootstrap intervals
(``SALib.analyze.sobol``); :func:`run_sensitivity` runs the analysis at every sample point as a
:class:`rotorlab.sweep.Sweep` of :class:`~rotorlab.sweep.Points` (Zarr store, resume, any
executor: results do not depend on them) and estimates the indices of the outputs asked for.

Why SALib and scipy: the Saltelli/Jansen estimators and their bootstrap are SALib's (a
well-kept library; Herman & Usher 2017), the truncated normal's quantile is scipy's.

References
----------
Saltelli A., Annoni P., Azzini I., Campolongo F., Ratto M., Tarantola S. Variance based sensitivity
analysis of model output. Design and estimator for the total sensitivity index. Computer Physics
Communications 181 (2010) 259-270 (Table 2: the estimators; section 4: the Ishigami test).
Herman J., Usher W. SALib: An open-source Python library for sensitivity analysis. Journal of Open
Source Software 2(9) (2017) 97.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab._distributions import U_CLIP, Distribution

__all__ = ["Distribution", "UncertainInput", "sobol_sample", "sobol_indices", "run_sensitivity", "SAMPLE_DIM",
           "saltelli_rows", "U_CLIP"]  # fmt: skip

#: Name of the sample dimension of a sensitivity run.
SAMPLE_DIM = "sample"
@dataclass(frozen=True, slots=True)
class UncertainInput:
    """A coordinate of a per-point analysis (e.g. a model's named parameter ``races[0].radius``)
    and its :class:`Distribution`."""

    name: str
    distribution: Distribution


def _problem(inputs: Sequence[UncertainInput]) -> dict[str, Any]:
    names = [i.name for i in inputs]
    if len(inputs) < 2 or len(set(names)) != len(names):
        raise ValueError(f"Sobol indices need two or more different inputs, got {names}")
    return {"num_vars": len(inputs), "names": names, "bounds": [[0.0, 1.0]] * len(inputs)}


def saltelli_rows(n_inputs: int) -> int:
    """Rows of the design per base sample: ``A``, ``A_B^(i)`` for each input, ``B`` (first and
    total order only, Saltelli et al. 2010)."""
    return int(n_inputs) + 2


def sobol_sample(inputs: Sequence[UncertainInput], n: int, seed: int) -> dict[str, np.ndarray]:
    """Saltelli's design for first- and total-order indices, in the inputs' own values (SI).

    Parameters
    ----------
    inputs : sequence of UncertainInput
        Two or more, different names.
    n : int
        Base samples, a power of 2 (the Sobol sequence's balance), >= 2.
    seed : int
        Seed of the scrambling: the same seed gives the same design.

    Returns
    -------
    dict of str to ndarray, shape (n (D + 2),)
        Each input's values, row ``k (D + 2) + j`` being base sample k's matrix A (j = 0),
        A with column i from B (j = i + 1) and B (j = D + 1).
    """
    from SALib.sample import sobol as sobol_design

    problem = _problem(inputs)
    if isinstance(n, bool) or int(n) != n or n < 2 or int(n) & (int(n) - 1):
        raise ValueError(f"the base sample size must be a power of 2 >= 2, got {n!r}")
    u = sobol_design.sample(problem, int(n), calc_second_order=False, scramble=True, seed=int(seed))
    u = np.clip(u, U_CLIP, 1.0 - U_CLIP)
    return {i.name: i.distribution.quantile(u[:, k]) for k, i in enumerate(inputs)}


def sobol_indices(names: Sequence[str], y: np.ndarray, *, confidence: float = 0.95, resamples: int = 200,
                  seed: int = 0) -> dict[str, np.ndarray]:  # fmt: skip
    """First- and total-order Sobol indices of the outputs ``y`` of :func:`sobol_sample`'s design.

    Returns
    -------
    dict
        ``S1``, ``S1_conf``, ``ST``, ``ST_conf`` (arrays over ``names``; the ``_conf`` are half-widths
        of the bootstrap intervals at ``confidence``), ``variance`` and ``mean`` of ``y`` (the A and
        B rows). NaN indices where ``y`` does not vary (every sample gave the same value) or holds
        a NaN.
    """
    from SALib.analyze import sobol as sobol_analysis

    y = np.asarray(y, dtype=float).reshape(-1)
    d = len(names)
    base = y.reshape(-1, saltelli_rows(d))[:, [0, d + 1]]
    out = {"mean": float(np.mean(base)), "variance": float(np.var(base))}
    if not np.all(np.isfinite(y)) or np.ptp(y) == 0.0:
        nan = np.full(d, math.nan)
        return {"S1": nan, "S1_conf": nan, "ST": nan, "ST_conf": nan, **out}
    problem = {"num_vars": d, "names": list(names), "bounds": [[0.0, 1.0]] * d}
    si = sobol_analysis.analyze(problem, y, calc_second_order=False, num_resamples=int(resamples),
                                conf_level=float(confidence), seed=int(seed) + 1)  # fmt: skip
    # (+ 1: SALib draws its bootstrap unseeded for a seed that is false, i.e. 0)
    return {k: np.asarray(si[k], dtype=float) for k in ("S1", "S1_conf", "ST", "ST_conf")} | out


def _units(points: Any, outputs: Sequence[str], power: int = 1) -> str:
    """The units of the outputs' means (``power`` 2: variances), one per output."""
    units = [str(points[o].attrs.get("units", "1")) for o in outputs]
    shown = [u if power == 1 or u == "1" else f"({u})^{power}" for u in units]
    return shown[0] if len(set(shown)) == 1 else "per output: " + ", ".join(f"{o} {u}" for o, u in zip(outputs, shown))


def run_sensitivity(analysis: Any, inputs: Sequence[UncertainInput], outputs: Sequence[str], *, n: int, seed: int,
                    confidence: float = 0.95, resamples: int = 200, fixed: Mapping[str, float] | None = None,
                    chunk_size: int | None = None, store: Any = None, resume: bool = False, executor: Any = None,
                    progress: Callable[[int, int], None] | None = None):  # fmt: skip
    """Sobol indices of scalar outputs of a per-point analysis with respect to uncertain inputs.

    Parameters
    ----------
    analysis : rotorlab.sweep.AbstractPointAnalysis
        Takes every input's name as a coordinate; ``outputs`` are result variables with one value
        per point.
    inputs : sequence of UncertainInput
    outputs : sequence of str
        The result variables whose indices are estimated.
    n, seed : int
        Base samples (a power of 2) and seed of :func:`sobol_sample`; the bootstrap uses ``seed``.
    confidence, resamples
        Level and resamples of the bootstrap intervals.
    fixed : mapping, optional
        Further coordinates held at a value (SI).
    chunk_size, store, resume, executor
        As for :func:`rotorlab.sweep.run_sweep` (results do not depend on them).
    progress : callable, optional
        ``progress(done, total)`` in sample points.

    Returns
    -------
    (xarray.Dataset, xarray.Dataset)
        The indices, dims ``(output, input)``: ``S1``, ``S1_conf``, ``ST``, ``ST_conf``, and ``mean``,
        ``variance`` (output); and the per-point results of the sweep (dim ``sample``, each input
        a coordinate, ``design_row``: 0 = A, i = A_B^(i), D + 1 = B).
    """
    import xarray as xr

    from rotorlab.sweep import Points, Sweep, run_sweep

    design = sobol_sample(inputs, n, seed)
    sweep = Sweep(analysis, points=Points(design, dim=SAMPLE_DIM), fixed=dict(fixed or {}))
    report = None if progress is None else (lambda p: progress(p.done, p.total))
    points = run_sweep(sweep, store=store, resume=resume, chunk_size=chunk_size, executor=executor,
                       progress=report)  # fmt: skip
    for key in ("sweep", "fingerprint", "complete"):
        points.attrs.pop(key, None)
    names = [i.name for i in inputs]
    rows = np.arange(points.sizes[SAMPLE_DIM]) % saltelli_rows(len(names))
    points["design_row"] = ((SAMPLE_DIM,), rows, {"units": "1", "description": "0: A, i: A_B^(i), D + 1: B"})
    table = {k: [] for k in ("S1", "S1_conf", "ST", "ST_conf", "mean", "variance")}
    for name in outputs:
        if points[name].dims != (SAMPLE_DIM,):
            raise ValueError(f"output {name!r} must have one value per sample, has dims {points[name].dims}")
        si = sobol_indices(names, points[name].values, confidence=confidence, resamples=resamples, seed=seed)
        for key in table:
            table[key].append(si[key])
    dims2 = ("output", "input")
    indices = xr.Dataset(
        {"S1": (dims2, np.array(table["S1"]), {"units": "1", "description": "first-order Sobol index"}),
         "S1_conf": (dims2, np.array(table["S1_conf"]), {"units": "1", "confidence": confidence,
                                                         "description": "half-width of the bootstrap interval"}),
         "ST": (dims2, np.array(table["ST"]), {"units": "1", "description": "total-order Sobol index"}),
         "ST_conf": (dims2, np.array(table["ST_conf"]), {"units": "1", "confidence": confidence,
                                                         "description": "half-width of the bootstrap interval"}),
         "mean": (("output",), np.array(table["mean"]), {"units": _units(points, outputs),
                                                         "description": "mean over the A and B samples"}),
         "variance": (("output",), np.array(table["variance"]), {"units": _units(points, outputs, 2),
                                                                 "description": "variance over the A and B samples"})},
        coords={"output": list(outputs), "input": names},
        attrs={"n_base": int(n), "seed": int(seed), "confidence": float(confidence), "resamples": int(resamples),
               "n_points": int(points.sizes[SAMPLE_DIM]), "estimator": "SALib.analyze.sobol (Saltelli 2010, Jansen)",
               "distributions": [f"{i.name}: {i.distribution.describe()}" for i in inputs]},
    )  # fmt: skip
    return indices, points
