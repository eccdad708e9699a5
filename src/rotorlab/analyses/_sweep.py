"""From a case's ``sweep`` analysis (or the ``rotorlab sweep`` options) to a :class:`~rotorlab.sweep.Sweep`.

The per-point analysis is the case model's regime mapper, built like a ``basin`` analysis' by
:func:`rotorlab.analyses.basin_mapper` (:class:`rotorlab.explore.BalancerRegimes` for a rotor
with balls, :class:`rotorlab.explore.TorusRegimes` for a toroidal ball), wrapped in
:class:`rotorlab.explore.MapperAnalysis`; the points are a grid over the given parameters and
initial conditions (first one slowest) or a seeded random sample of their ranges.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["build_sweep", "run_sweep_analysis"]


def build_sweep(case_model: Any, spec: Any, *, axes: Mapping[str, tuple] | None = None,
                sample: int | None = None, seed: int | None = None, t_end: float | None = None) -> Any:  # fmt: skip
    """Build the sweep of a case's ``sweep`` analysis, optionally with other points.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec or rotorlab.io.ToroidalBallSpec
        ``Case.model``.
    spec : rotorlab.io.SweepSpec
        The analysis (base speed, tolerances, horizons; its ``param`` and ``ic`` unless ``axes``).
    axes : mapping of str to (start, stop, count) or (low, high), optional
        Coordinates to vary instead of the spec's (SI).
    sample, seed : int, optional
        Instead of the spec's: draw ``sample`` random points with ``seed``.
    t_end : float, optional
        Simulated time (s) instead of the spec's.

    Returns
    -------
    rotorlab.sweep.Sweep

    Raises
    ------
    ValueError
        A coordinate the model does not have, or ranges that do not fit grid / sample.

    Examples
    --------
    >>> from rotorlab.io import load_case, SweepSpec
    >>> case = load_case("autobalancer")
    >>> spec = SweepSpec(speed_ratio=2.0, ic={"psi_1": [0.0, 3.0, 4]}, t_end=1.0)
    >>> sw = build_sweep(case.model, spec)
    >>> sw.dims, sw.n_points
    (('psi_1',), 4)
    >>> torus = load_case("strautmanis-torus")
    >>> sw = build_sweep(torus.model, SweepSpec(param={"rolling_friction": [1e-5, 1e-4, 2]},
    ...                                         ic={"psi": [0.0, 6.0, 3]}, t_end=1.0))
    >>> type(sw.analysis.mapper).__name__, sw.dims, sw.shape
    ('TorusRegimes', ('rolling_friction', 'psi'), (2, 3))
    """
    from rotorlab.analyses._basin import basin_mapper
    from rotorlab.explore import MapperAnalysis
    from rotorlab.sweep import GridAxis, Sample, Sweep

    omega = spec.spin_speed(case_model)
    duration = t_end if t_end is not None else (
        spec.t_end if spec.t_end is not None else spec.revolutions * 2.0 * math.pi / omega)  # fmt: skip
    analysis = MapperAnalysis(basin_mapper(case_model, spec, t_end=duration))
    chosen = dict(axes) if axes is not None else {**spec.param, **spec.ic}
    n_sample = sample if sample is not None else (spec.sample if axes is None else None)
    if n_sample is not None:
        bad = [k for k, v in chosen.items() if len(v) != 2]
        if bad:
            raise ValueError(f"with a sample, give ranges LOW:HIGH (not grids) for {', '.join(bad)}")
        return Sweep(analysis, sample=Sample({k: (v[0], v[1]) for k, v in chosen.items()}, n_sample,
                                             spec.seed if seed is None else seed))  # fmt: skip
    bad = [k for k, v in chosen.items() if len(v) != 3]
    if bad:
        raise ValueError(f"give grids START:STOP:N (or a sample) for {', '.join(bad)}")
    return Sweep(analysis, axes=tuple(GridAxis(k, *v) for k, v in chosen.items()))


def run_sweep_analysis(case_model: Any, spec: Any, progress: Callable[[int, int], None] | None = None) -> Any:
    """Run a case's ``sweep`` analysis in this process (no store) and return its Dataset.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec or rotorlab.io.ToroidalBallSpec
        ``Case.model``.
    spec : rotorlab.io.SweepSpec
    progress : callable, optional
        ``progress(done, total)``: points finished.

    Returns
    -------
    xarray.Dataset
        The sweep's Dataset (:func:`rotorlab.sweep.run_sweep`; dims: one per swept quantity,
        or ``sample``, then ``horizon``) plus ``fraction`` and ``count`` (horizon, regime) of
        :func:`rotorlab.explore.basin_fractions`; attrs ``analysis = "sweep"``, ``name``,
        ``mode`` (``"grid"`` or ``"sample"``, with ``seed``).

    Examples
    --------
    >>> from rotorlab.io import load_case, SweepSpec
    >>> case = load_case("strautmanis-torus")
    >>> ds = run_sweep_analysis(case.model, SweepSpec(name="s", ic={"psi": [1.0, 5.0, 3]}, t_end=1.0,
    ...                                               n_horizons=1))
    >>> ds.fraction.sum("regime").values.tolist(), ds.attrs["mode"]
    ([1.0], 'grid')
    """
    from rotorlab.explore import basin_fractions
    from rotorlab.sweep import run_sweep

    def report(p: Any) -> None:
        if progress is not None:
            progress(p.done, p.total)

    sweep = build_sweep(case_model, spec)
    ds = run_sweep(sweep, chunk_size=spec.chunk, progress=report)
    fr = basin_fractions(ds)
    ds = ds.assign(fraction=fr["fraction"], count=fr["count"])
    ds["fraction"].attrs.update(units="1", description="fraction of the points with each label")
    ds["count"].attrs.update(units="1", description="number of points with each label")
    ds.attrs.update(analysis="sweep", name=spec.name, model=str(case_model.type),
                    mode="grid" if sweep.axes else "sample")  # fmt: skip
    if sweep.sample is not None:
        ds.attrs["seed"] = sweep.sample.seed
    return ds
