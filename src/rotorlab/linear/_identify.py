"""Identification of unknown stiffnesses from measured natural frequencies (least squares)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.optimize
import xarray as xr

from rotorlab.linear._eigen import Solver
from rotorlab.linear._system import LinearSystem

__all__ = ["FrequencyMeasurement", "Identification", "identify_parameters"]


@dataclass(frozen=True, slots=True)
class FrequencyMeasurement:
    """One measured natural frequency.

    Parameters
    ----------
    speed : float
        Spin speed Omega at which it was measured (rad/s), >= 0.
    mode : int
        Which natural frequency: its rank (0 = lowest) among the system's damped natural
        frequencies at that speed, >= 0.
    frequency : float
        Measured value (Hz), > 0.
    weight : float
        Weight of its relative residual, > 0 (e.g. 1 / relative standard deviation).

    Examples
    --------
    >>> FrequencyMeasurement(speed=0.0, mode=0, frequency=9.78).weight
    1.0
    """

    speed: float
    mode: int
    frequency: float
    weight: float = 1.0

    def __post_init__(self) -> None:
        o = "FrequencyMeasurement"
        if isinstance(self.mode, bool) or not isinstance(self.mode, (int, np.integer)) \
                or self.mode < 0:
            raise ValueError(f"{o}.mode must be an integer >= 0, got {self.mode!r}")
        object.__setattr__(self, "mode", int(self.mode))
        for name, unit, strict in (("speed", "rad/s", False), ("frequency", "Hz", True),
                                   ("weight", "1", True)):
            try:
                v = float(getattr(self, name))
            except (TypeError, ValueError):
                v = math.nan
            if not math.isfinite(v) or v < 0 or (strict and v == 0):
                rule = "> 0" if strict else ">= 0"
                raise ValueError(f"{o}.{name} must be a finite number {rule} ({unit}), "
                                 f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)


@dataclass(frozen=True)
class Identification:
    """Result of :func:`identify_parameters`.

    Attributes
    ----------
    names : tuple of str
        Parameter names.
    values : ndarray, shape (p,)
        Identified parameters (their own units).
    initial : ndarray, shape (p,)
        Starting values.
    predicted : ndarray, shape (k,)
        Model frequencies at the identified parameters (Hz).
    measured : ndarray, shape (k,)
        Measured frequencies (Hz).
    residual : ndarray, shape (k,)
        Weighted relative residuals ``w (f_model - f_measured) / f_measured`` (1).
    rms : float
        Root mean square of ``residual`` (1).
    relative_std : ndarray, shape (p,)
        Linearised standard deviation of each parameter relative to its value, from the
        Jacobian and the residual variance (NaN if fewer measurements than parameters).
    success : bool
        The optimiser's convergence flag.
    n_evaluations : int
        Model evaluations used.
    """

    names: tuple[str, ...]
    values: np.ndarray
    initial: np.ndarray
    predicted: np.ndarray
    measured: np.ndarray
    residual: np.ndarray
    rms: float
    relative_std: np.ndarray
    success: bool
    n_evaluations: int

    def as_dict(self) -> dict[str, float]:
        """Return ``{name: value}``."""
        return {k: float(v) for k, v in zip(self.names, self.values)}

    def to_dataset(self) -> xr.Dataset:
        """Return an :class:`xarray.Dataset` with dims ``parameter`` and ``measurement``."""
        return xr.Dataset(
            {
                "value": ("parameter", self.values, {"units": "as given"}),
                "initial": ("parameter", self.initial, {"units": "as given"}),
                "relative_std": ("parameter", self.relative_std, {"units": "1"}),
                "predicted": ("measurement", self.predicted, {"units": "Hz"}),
                "measured": ("measurement", self.measured, {"units": "Hz"}),
                "residual": ("measurement", self.residual, {"units": "1"}),
            },
            coords={"parameter": ("parameter", list(self.names), {"units": "1"})},
            attrs={"title": "identified parameters", "rms": self.rms,
                   "success": int(self.success), "n_evaluations": self.n_evaluations},
        )


def _model_frequencies(system: LinearSystem, measurements) -> np.ndarray:
    speeds = sorted({m.speed for m in measurements})
    spec = Solver(system).solve(speeds)
    freq = np.sort(np.abs(spec.eigenvalues.imag), axis=1) / (2.0 * np.pi)
    row = {s: i for i, s in enumerate(speeds)}
    out = np.empty(len(measurements))
    for j, m in enumerate(measurements):
        f = freq[row[m.speed]]
        if m.mode >= f.size:
            raise ValueError(f"FrequencyMeasurement.mode = {m.mode} but the model has only "
                             f"{f.size} modes")
        out[j] = f[m.mode]
    return out


def identify_parameters(build: Callable[[np.ndarray], LinearSystem],
                        initial: Sequence[float],
                        measurements: Sequence[FrequencyMeasurement], *,
                        names: Sequence[str] | None = None,
                        bounds: tuple[Sequence[float], Sequence[float]] | None = None,
                        ) -> Identification:
    """Fit positive model parameters (e.g. support stiffnesses) to measured frequencies.

    Parameters
    ----------
    build : callable
        ``build(values) -> LinearSystem`` for a parameter vector (their own units, > 0).
    initial : sequence of float
        Starting values, > 0.
    measurements : sequence of FrequencyMeasurement
        Natural frequencies measured at rest and/or at some speeds.
    names : sequence of str, optional
        Parameter names for the result (default ``p0, p1, ...``).
    bounds : (lower, upper), optional
        Bounds on the parameters (> 0); default (0, inf).

    Returns
    -------
    Identification

    Notes
    -----
    Minimises ``sum_j (w_j (f_j(p) - f_j^meas) / f_j^meas)^2`` over ``log p`` (so the
    parameters stay positive and very different magnitudes, N/m next to N m/rad, are equally
    well scaled) with a trust-region least-squares solver. Measurements at speed see the
    gyroscopic splitting, which separates the influence of tilt and translation stiffness.

    References
    ----------
    Seed 000, conclusion 3 (support stiffnesses determined from measured natural frequencies
    and their change with spin speed).
    """
    p0 = np.asarray(initial, dtype=float)
    if p0.ndim != 1 or p0.size == 0 or not np.all(np.isfinite(p0)) or np.any(p0 <= 0):
        raise ValueError(f"initial must be a non-empty sequence of finite numbers > 0, got "
                         f"{initial!r}")
    meas = list(measurements)
    if not meas:
        raise ValueError("measurements must not be empty")
    nm = tuple(names) if names is not None else tuple(f"p{i}" for i in range(p0.size))
    if len(nm) != p0.size:
        raise ValueError(f"names must have {p0.size} entries, got {len(nm)}")
    f_meas = np.array([m.frequency for m in meas])
    wts = np.array([m.weight for m in meas])
    if bounds is None:
        lb, ub = np.full(p0.size, -np.inf), np.full(p0.size, np.inf)
    else:
        lo, hi = (np.asarray(b, dtype=float) for b in bounds)
        if np.any(lo <= 0) or np.any(hi <= lo):
            raise ValueError("bounds must satisfy 0 < lower < upper")
        lb, ub = np.log(lo), np.log(hi)

    def residual(logp: np.ndarray) -> np.ndarray:
        return wts * (_model_frequencies(build(np.exp(logp)), meas) - f_meas) / f_meas

    sol = scipy.optimize.least_squares(residual, np.log(p0), bounds=(lb, ub), x_scale=1.0,
                                       xtol=1e-12, ftol=1e-12, gtol=1e-12)
    values = np.exp(sol.x)
    r = sol.fun
    dof = r.size - p0.size
    rel_std = np.full(p0.size, np.nan)
    if dof > 0:
        s2 = float(r @ r) / dof
        try:
            cov = s2 * np.linalg.inv(sol.jac.T @ sol.jac)
            rel_std = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        except np.linalg.LinAlgError:
            pass
    predicted = _model_frequencies(build(values), meas)
    return Identification(names=nm, values=values, initial=p0, predicted=predicted,
                          measured=f_meas, residual=r, rms=float(np.sqrt(np.mean(r * r))),
                          relative_std=rel_std, success=bool(sol.success),
                          n_evaluations=int(sol.nfev))
