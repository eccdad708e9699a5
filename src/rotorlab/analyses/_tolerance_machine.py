"""What a ``tolerances`` analysis runs at each sample: a machine whose uncertain inputs take the
sample's values, released from several ball starts, each start labelled and its vibration
envelope kept.

:class:`UncertainMachine` is a regime mapper (:class:`rotorlab.explore.AbstractMapper`): the
labels, horizons, features and grouping are those of :class:`rotorlab.explore.MachineRegimes`
(balanced, not balanced, non-synchronous, not settled, other); its coordinates are the uncertain
inputs, set through the machine's named parameters (``with_parameters``: the case is never
validated again) and the aliases ``ball_mass``, ``ball_damping``, ``support_anisotropy``
(:func:`rotorlab.continuation.with_value`). :class:`SampleStarts` is the per-point analysis of the
sweep engine: each sample point runs ``starts`` ball starts, the same at every sample (common
random numbers: the start angles are :class:`rotorlab.explore.RandomStarts`' draws of start
numbers 0 .. starts - 1), in one ensemble on the lane driver.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["UncertainMachine", "SampleStarts", "OUTPUTS"]

#: The outputs whose Sobol indices a tolerances analysis estimates: name -> (unit, description).
OUTPUTS = {
    "p_balanced": ("1", "fraction of the starts that balance"),
    "residual_vibration": ("m", "vibration amplitude in the last window, mean over the starts"),
    "transient_peak": ("m", "largest vibration amplitude of any window, mean over the starts"),
}
#: Aliases applied after the named parameters, in this order (the anisotropy last: it is measured
#: from the isotropic machine the others make).
_ALIAS_ORDER = ("ball_mass", "ball_damping", "support_anisotropy")


@dataclass(frozen=True)
class UncertainMachine:
    """Mapper of (uncertain inputs, ball starts) of a machine to balancer regimes.

    Parameters
    ----------
    regimes : rotorlab.explore.MachineRegimes
        The nominal machine (every input at its distribution's median) at a constant speed, with
        the horizons and windows the labels and amplitudes are taken on.
    inputs : tuple of (str, str)
        The uncertain inputs and their SI units.
    """

    regimes: Any
    inputs: tuple[tuple[str, str], ...]

    @property
    def labels(self) -> tuple[str, ...]:
        return self.regimes.labels

    @property
    def control(self) -> Any:
        return self.regimes.control

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        from rotorlab.explore._mapper import ball_coordinate_units

        return {**ball_coordinate_units(self.regimes.model.n_balls), **dict(self.inputs)}

    def horizons(self) -> np.ndarray:
        return self.regimes.horizons()

    def save_times(self) -> np.ndarray:
        return self.regimes.save_times()

    def features(self, sol: Any, P: np.ndarray) -> dict[str, Any]:
        return self.regimes.features(sol, P)

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray:
        return self.regimes.group(features)

    def variant(self, values: Mapping[str, float], *, same_layout: bool = True) -> Any:
        """The nominal machine with the inputs ``values`` (SI); ValueError naming the values (and,
        with ``same_layout``, where the compiled layout would change)."""
        from rotorlab.continuation._machine_problem import with_value

        base = self.regimes.model
        named = {k: float(v) for k, v in values.items() if k not in _ALIAS_ORDER}
        try:
            m = base.with_parameters(**named) if named else base
            for name in _ALIAS_ORDER:
                if name in values:
                    m = with_value(m, name, float(values[name]))
        except (KeyError, ValueError) as exc:
            text = exc.args[0] if exc.args else str(exc)
            raise ValueError(f"at {', '.join(f'{k} = {v:g}' for k, v in values.items())}: {text}") from None
        if same_layout and m.layout != base.layout:
            raise ValueError(f"at {', '.join(f'{k} = {v:g}' for k, v in values.items())}: the machine's compiled "
                             "layout changes (a feature switched on or off); keep every input on one side of 0")
        return m

    def starts(self, coords: Mapping[str, np.ndarray]) -> tuple[Any, np.ndarray, np.ndarray]:
        model = self.regimes.model
        n_pts = max((np.asarray(v).size for v in coords.values()), default=1)
        nb = model.n_balls
        base = self.regimes.base_angles
        angles = np.stack([np.broadcast_to(coords.get(f"psi_{i + 1}", base[i]), (n_pts,)) for i in range(nb)], axis=1)
        rates = np.stack([np.broadcast_to(coords.get(f"dpsi_{i + 1}", 0.0), (n_pts,)) for i in range(nb)], axis=1)
        names = [k for k, _ in self.inputs if k in coords]
        if names:
            keys = np.stack([np.broadcast_to(coords[k], (n_pts,)) for k in names], axis=1)
            uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
            inverse = inverse.reshape(-1)
        else:
            uniq, inverse = np.empty((1, 0)), np.zeros(n_pts, dtype=np.int64)
        Y0 = np.empty((n_pts, model.n_state))
        P = np.empty((n_pts, model.to_array().size))
        for j, row in enumerate(uniq):
            m = self.variant(dict(zip(names, (float(v) for v in row))))
            sel = np.flatnonzero(inverse == j)
            Y0[sel] = [m.initial_state(angles[i], ball_rates=rates[i]) for i in sel]
            P[sel] = m.to_array()
        return model, Y0, P


@dataclass(frozen=True, eq=False)
class SampleStarts:
    """Per-point analysis: one sample of the uncertain inputs -> ``starts`` ball starts -> labels,
    amplitudes and the three outputs of :data:`OUTPUTS`.

    Parameters
    ----------
    mapper : UncertainMachine
    starts : int
        Ball starts per sample, >= 1 (start numbers 0 .. starts - 1 of
        :class:`rotorlab.explore.RandomStarts` over every ball angle in [0, 2 pi)).
    seed : int
        Seed of the starts.
    """

    mapper: UncertainMachine
    starts: int
    seed: int

    def __post_init__(self) -> None:
        if isinstance(self.starts, bool) or int(self.starts) != self.starts or self.starts < 1:
            raise ValueError(f"SampleStarts.starts must be an integer >= 1, got {self.starts!r}")

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return dict(self.mapper.inputs)

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return {"start": (np.arange(int(self.starts)), {"units": "1", "description": "ball start number"}),
                "horizon": (np.asarray(self.mapper.horizons(), dtype=float), {"units": "s"})}  # fmt: skip

    def result_attrs(self) -> dict[str, Any]:
        return {"labels": list(self.mapper.labels), "t_end": float(self.mapper.horizons()[-1]),
                "starts": int(self.starts)}  # fmt: skip

    def start_angles(self) -> dict[str, np.ndarray]:
        """The ball start angles (rad), ``psi_<i>`` -> shape (starts,): the same at every sample."""
        from rotorlab.explore import MapperAnalysis
        from rotorlab.explore._stability import RandomStarts

        n = self.mapper.regimes.model.n_balls
        ranges = tuple((f"psi_{i + 1}", 0.0, 2.0 * math.pi) for i in range(n))
        return RandomStarts(MapperAnalysis(self.mapper), ranges, self.seed).draw(np.arange(int(self.starts)))

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        from rotorlab.explore import MapperAnalysis
        from rotorlab.sweep import ChunkVar

        k = int(self.starts)
        cols = {name: np.asarray(v, dtype=float) for name, v in coords.items()}
        m = next(iter(cols.values())).size
        angles = self.start_angles()
        every = {**{name: np.repeat(v, k) for name, v in cols.items()}, **{a: np.tile(v, m) for a, v in angles.items()}}
        out = MapperAnalysis(self.mapper).run_chunk(every, threads=threads)
        outcome = np.asarray(out["outcome"].values).reshape(m, k)
        amplitude = np.asarray(out["amplitude"].values, dtype=float).reshape(m, k, -1)
        status = np.asarray(out["status"].values).reshape(m, k)
        ref = np.asarray(out["reference_amplitude"].values, dtype=float).reshape(m, k)[:, 0]
        values = {"p_balanced": np.mean(outcome == 0, axis=1), "residual_vibration": amplitude[:, :, -1].mean(axis=1),
                  "transient_peak": amplitude.max(axis=2).mean(axis=1)}  # fmt: skip
        result = {name: ChunkVar((), values[name], {"units": u, "description": d}) for name, (u, d) in OUTPUTS.items()}
        flags = dict(out["outcome"].attrs)
        result.update({
            "outcome": ChunkVar(("start",), outcome.astype(np.int16), flags),
            "amplitude": ChunkVar(("start", "horizon"), amplitude, {"units": "m", "description":
                                  "largest vibration amplitude of any station over each window"}),
            "status": ChunkVar(("start",), status.astype(np.int32), {"units": "1"}),
            "unbalance_response": ChunkVar((), ref, {"units": "m", "description":
                                           "largest unbalance response with the balls locked"}),
        })  # fmt: skip
        return result
