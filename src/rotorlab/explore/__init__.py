"""Regimes and basins: map start points to labels, basin maps, fractions and basin stability.

Layers (after Attractors.jl): a *mapper* (:class:`TorusRegimes`, :class:`BalancerRegimes`, or
any :class:`AbstractMapper`) integrates start points, computes features chunk by chunk and
groups them into labels; :func:`map_starts`, :func:`basin_map` and :func:`basin_stability` only
choose the start points; :func:`basin_fractions` counts labels. Every result is an
``xarray.Dataset`` with a ``horizon`` dim, so that a fraction that still changes with the
simulated time (a long transient) is visible. Mappers are frozen values: no state is kept
between calls. All three run on the sweep engine (:mod:`rotorlab.sweep`) with
:class:`MapperAnalysis` as the per-point analysis, so the same basin can also run on local
processes or a Dask cluster, checkpointed to a Zarr store.
"""

from rotorlab.explore._balancer import BalancerRegimes, balancer_labels
from rotorlab.explore._basin import GridAxis, basin_fractions, basin_map, basin_stability, wilson_interval
from rotorlab.explore._machine import MACHINE_LABELS, MachineRegimes
from rotorlab.explore._mapper import DEFAULT_CHUNK, AbstractMapper, Feature, MapperAnalysis, label_since, map_starts
from rotorlab.explore._stability import RandomStarts, basin_stability_over, starts_for_half_width
from rotorlab.explore._torus import TORUS_LABELS, TorusRegimes

__all__ = [
    "AbstractMapper",
    "BalancerRegimes",
    "DEFAULT_CHUNK",
    "Feature",
    "GridAxis",
    "MACHINE_LABELS",
    "MachineRegimes",
    "MapperAnalysis",
    "TORUS_LABELS",
    "TorusRegimes",
    "RandomStarts",
    "balancer_labels",
    "basin_fractions",
    "basin_map",
    "basin_stability",
    "basin_stability_over",
    "label_since",
    "map_starts",
    "starts_for_half_width",
    "wilson_interval",
]
