"""Run a case's ``tolerances`` analysis and tabulate it: Sobol indices of P(balanced), the residual
vibration and the transient peak of a balancer machine with respect to uncertain inputs, and
Monte-Carlo envelopes of its vibration over time.

The machines are the points of Saltelli's design (:func:`rotorlab.explore.run_sensitivity`, on
the sweep engine: Zarr store, resume, Dask); each runs :class:`SampleStarts`' ball starts at the
analysis' constant speed. The vibration amplitude is taken over ``n_horizons`` windows that tile
the run: its value in each window is the envelope over time, in the last window the residual
vibration, its largest value the transient peak.

Why several starts per machine: the outcome of one start is 0 or 1 and depends on the start as
much as on the machine; P(balanced) of a machine is what a designer is judged on. With the same
starts at every machine (common random numbers) the fraction that balances is a deterministic
function of the inputs, so Saltelli's estimators apply to it as to any model output; its indices
approach those of P(balanced | inputs) as the starts grow (the scatter of a fraction of k starts,
at most 1 / (4 k) in variance, is the part no input explains).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray

__all__ = ["run_tolerances_analysis", "tolerances_rows", "tolerances_document", "tolerances_task_size",
           "tolerance_study", "ENVELOPE_QUANTILES"]  # fmt: skip

#: Quantiles of the Monte-Carlo envelope: the 5-95 % band and the median.
ENVELOPE_QUANTILES = (0.05, 0.5, 0.95)
#: Saves per revolution in every window (an orbit sampled at an irrational phase step).
_SAVES_PER_TURN = 4.3
#: Machines per chunk when none is given (each runs ``starts`` trajectories).
_CHUNK = 16


def tolerance_study(case_model: Any, spec: Any, machine: Any = None) -> tuple[Any, list[Any]]:
    """The per-sample analysis (:class:`SampleStarts`) and the uncertain inputs of a ``tolerances``
    analysis (ValueError where the case cannot run it); ``machine``: a built machine to run around
    instead of the case's (a design's winner)."""
    from dataclasses import replace

    from rotorlab.analyses._tolerance_machine import SampleStarts, UncertainMachine
    from rotorlab.explore import MachineRegimes
    from rotorlab.explore._sensitivity import UncertainInput
    from rotorlab.models import ConstantSpeed

    source = spec.machine(case_model) if machine is None else machine
    speed = spec.speed if spec.speed is not None else float(source.drive.speed)
    inputs, units = [], []
    for name in spec.inputs:
        dist, param = spec.distribution(name, source)
        inputs.append(UncertainInput(name, dist))
        units.append((name, param.unit))
    nominal = UncertainMachine(MachineRegimes(source.with_drive(ConstantSpeed(speed)), t_end=1.0), tuple(units))
    model = nominal.variant({i.name: i.distribution.centre for i in inputs}, same_layout=False)
    turns = spec.t_end * speed / (2.0 * math.pi) / spec.n_horizons  # windows tiling the run
    regimes = MachineRegimes(model, t_end=spec.t_end, n_horizons=spec.n_horizons, window_revolutions=turns,
                             samples_per_window=max(33, int(math.ceil(_SAVES_PER_TURN * turns)) + 1))  # fmt: skip
    return SampleStarts(replace(nominal, regimes=regimes), spec.starts, spec.seed), inputs


def run_tolerances_analysis(case_model: Any, analysis: Any, progress: Callable[[int, int], None] | None = None, *,
                            chunk_size: int | None = None, store: Any = None, resume: bool = False,
                            executor: Any = None, machine: Any = None) -> xarray.Dataset:  # fmt: skip
    """Run one ``tolerances`` analysis of a case (``machine``: around this built machine instead of
    the case's, e.g. a design's winner).

    Parameters
    ----------
    case_model : rotorlab.io.MachineSpec
    analysis : rotorlab.io.TolerancesSpec
    progress : callable, optional
        ``progress(done, total)`` in machines.
    chunk_size, store, resume, executor
        As for :func:`rotorlab.sweep.run_sweep` (results do not depend on them).

    Returns
    -------
    xarray.Dataset
        :func:`rotorlab.explore.run_sensitivity`'s indices (``S1``, ``S1_conf``, ``ST``,
        ``ST_conf``; dims ``output``, ``input``) and per-sample results (dim ``sample``:
        ``p_balanced``, ``residual_vibration``, ``transient_peak``, ``unbalance_response``,
        ``outcome`` and ``status`` per start, ``amplitude`` per start and window), and the
        envelope ``envelope`` (quantile, horizon) over the A and B samples' starts; attrs
        ``analysis``, ``name``, ``model``, ``speed``, ``failed`` (trajectories).
    """
    from rotorlab.explore._sensitivity import run_sensitivity
    from rotorlab.analyses._tolerance_machine import OUTPUTS

    point, inputs = tolerance_study(case_model, analysis, machine)
    size = chunk_size if chunk_size is not None else analysis.chunk
    if size is None and not (store is not None and resume):  # a resumed store keeps its own
        size = _CHUNK
    indices, points = run_sensitivity(point, inputs, list(OUTPUTS), n=analysis.samples, seed=analysis.seed,
                                      confidence=analysis.confidence, resamples=analysis.resamples,
                                      chunk_size=size,
                                      store=store, resume=resume, executor=executor, progress=progress)  # fmt: skip
    d = len(inputs)
    rows = points["design_row"].values
    mc = (rows == 0) | (rows == d + 1)  # the A and B samples: independent draws of the inputs
    amp = np.asarray(points["amplitude"].values)[mc].reshape(-1, points.sizes["horizon"])
    env = np.nanquantile(amp, ENVELOPE_QUANTILES, axis=0)
    units = dict(point.coordinate_units)
    ds = points.assign_coords({i.name: (points[i.name].dims, points[i.name].values,
                                        {"units": units[i.name], "distribution": i.distribution.describe()})
                               for i in inputs})  # fmt: skip
    ds = ds.assign_coords(sample=("sample", np.arange(ds.sizes["sample"]), {"units": "1", "description": "machine"}),
                          output=indices["output"], input=indices["input"])  # fmt: skip
    per = ", ".join(f"{k} {u}" for k, (u, _) in OUTPUTS.items())
    for name, var in indices.data_vars.items():
        ds[name] = (var.dims, var.values, {**var.attrs, "units": var.attrs.get("units", f"per output: {per}")})
    ds["envelope"] = (("quantile", "horizon"), env, {"units": "m", "description": "quantiles of the vibration "
                      "amplitude over the A and B samples and their starts"})  # fmt: skip
    ds = ds.assign_coords(quantile=("quantile", list(ENVELOPE_QUANTILES), {"units": "1"}))
    status = np.asarray(points["status"].values)
    ds.attrs.update(indices.attrs)
    ds.attrs.update(analysis="tolerances", name=analysis.name, model=str(case_model.type),
                    speed=float(point.mapper.regimes.model.drive.speed), t_end=float(analysis.t_end),
                    starts=int(analysis.starts), failed=int(np.count_nonzero(status < 0)),
                    labels=list(point.mapper.labels), n_inputs=d)  # fmt: skip
    return ds


def tolerances_task_size(case_model: Any, analysis: Any) -> int:
    """Machines a ``tolerances`` analysis simulates (its progress-bar total): N (D + 2)."""
    return int(analysis.samples) * (len(analysis.inputs) + 2)


def _num(value: Any) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def tolerances_rows(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a tolerances result: one row per (output, input).

    Returns
    -------
    list of dict
        ``output``, ``input``, ``S1``, ``S1_conf``, ``ST``, ``ST_conf`` (None where the output does
        not vary or a run failed), ``mean`` and ``variance`` of the output.
    """
    out = []
    for i, output in enumerate(ds["output"].values):
        for j, name in enumerate(ds["input"].values):
            row = {"output": str(output), "input": str(name)}
            row.update({k: _num(ds[k].values[i, j]) for k in ("S1", "S1_conf", "ST", "ST_conf")})
            row.update(mean=_num(ds["mean"].values[i]), variance=_num(ds["variance"].values[i]))
            out.append(row)
    return out


def most_sensitive(ds: xarray.Dataset, output: str) -> tuple[str, float, float] | None:
    """The input with the largest total-order index of ``output``: (name, ST, half-width); None
    where the indices are not defined (the output does not vary)."""
    i = list(ds["output"].values).index(output)
    st = np.asarray(ds["ST"].values[i], dtype=float)
    if not np.any(np.isfinite(st)):
        return None
    j = int(np.nanargmax(st))
    return str(ds["input"].values[j]), float(st[j]), float(ds["ST_conf"].values[i, j])


def tolerances_document(ds: xarray.Dataset) -> dict[str, Any]:
    """A tolerances result as JSON-ready data (the ``rotorlab tolerances --json`` document)."""
    outputs = [str(o) for o in ds["output"].values]
    return {
        "inputs": [str(v) for v in ds["input"].values], "distributions": list(ds.attrs.get("distributions", [])),
        "outputs": outputs, "n_base": int(ds.attrs["n_base"]), "machines": int(ds.sizes["sample"]),
        "starts": int(ds.attrs["starts"]), "seed": int(ds.attrs["seed"]), "confidence": float(ds.attrs["confidence"]),
        "t_end_s": float(ds.attrs["t_end"]), "speed_rad_s": float(ds.attrs["speed"]), "failed": int(ds.attrs["failed"]),
        "most_sensitive": {o: most_sensitive(ds, o) for o in outputs},
        "envelope_m": {f"q{q:g}": [_num(v) for v in ds["envelope"].values[k]]
                       for k, q in enumerate(ds["quantile"].values)},
        "horizons_s": [float(h) for h in ds["horizon"].values], "rows": tolerances_rows(ds),
    }  # fmt: skip
