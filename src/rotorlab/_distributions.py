"""Distributions of uncertain inputs (SI), for sensitivity and tolerance studies: normal (by mean
and standard deviation), truncated where a quantity must stay in a range, and uniform; their
quantile functions are scipy's (``scipy.stats.norm``, ``truncnorm``, ``uniform``).

A leaf module: case-file specs (:mod:`rotorlab.io`) check distributions with it, and
:mod:`rotorlab.explore` samples them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Distribution", "U_CLIP"]

#: The design's unit-cube values are kept in [U_CLIP, 1 - U_CLIP] (an open interval for the
#: quantile functions: a normal's draws stay within 6.1 std of its mean).
U_CLIP = 0.5 / (1 << 30)


class _Normal:
    """A normal by mean and std, truncated to [low, high] where those are finite."""

    @staticmethod
    def check(d: Distribution) -> None:
        if not (math.isfinite(d.mean) and math.isfinite(d.std) and d.std > 0):
            raise ValueError(f"a normal distribution needs a finite mean and std > 0, got mean = {d.mean:g}, "
                             f"std = {d.std:g}")  # fmt: skip
        from scipy import stats

        kept = stats.norm.cdf(d.high, d.mean, d.std) - stats.norm.cdf(d.low, d.mean, d.std)
        if not kept >= 1e-6:
            raise ValueError(f"the truncation [{d.low:g}, {d.high:g}] keeps less than 1e-6 of the normal's "
                             f"probability (mean {d.mean:g}, std {d.std:g})")  # fmt: skip

    @staticmethod
    def frozen(d: Distribution) -> Any:
        from scipy import stats

        if math.isinf(d.low) and math.isinf(d.high):
            return stats.norm(loc=d.mean, scale=d.std)
        a, b = (d.low - d.mean) / d.std, (d.high - d.mean) / d.std
        return stats.truncnorm(a, b, loc=d.mean, scale=d.std)

    @staticmethod
    def describe(d: Distribution) -> str:
        text = f"normal(mean {d.mean:.6g}, std {d.std:.6g})"
        if math.isfinite(d.low) or math.isfinite(d.high):
            text += f" truncated to [{d.low:.6g}, {d.high:.6g}]"
        return text


class _Uniform:
    """A uniform between finite low and high."""

    @staticmethod
    def check(d: Distribution) -> None:
        if not (math.isfinite(d.low) and math.isfinite(d.high)):
            raise ValueError("a uniform distribution needs finite low and high")

    @staticmethod
    def frozen(d: Distribution) -> Any:
        from scipy import stats

        return stats.uniform(loc=d.low, scale=d.high - d.low)

    @staticmethod
    def describe(d: Distribution) -> str:
        return f"uniform [{d.low:.6g}, {d.high:.6g}]"


#: Each distribution kind: its checks, its scipy frozen distribution and its words.
_KINDS: dict[str, Any] = {"normal": _Normal, "uniform": _Uniform}


@dataclass(frozen=True, slots=True)
class Distribution:
    """The distribution of one uncertain input (SI).

    Parameters
    ----------
    kind : {"normal", "uniform"}
    mean, std : float
        A normal's mean and standard deviation (> 0).
    low, high : float
        A uniform's bounds (low < high); for a normal, optional truncation bounds (-inf, +inf
        when not given; e.g. ``low = 0`` for a quantity that must stay positive).

    Examples
    --------
    >>> d = Distribution("normal", mean=1.0, std=0.1, low=0.95)
    >>> bool(d.quantile(np.array([1e-9]))[0] >= 0.95), round(float(d.quantile(np.array([0.5]))[0]), 4)
    (True, 1.0397)

    (the median m of the kept part: Phi((m - 1) / 0.1) = Phi(-0.5) + (1 - Phi(-0.5)) / 2, z = 0.397)
    >>> Distribution("uniform", low=2.0, high=4.0).quantile(np.array([0.25])).tolist()
    [2.5]
    """

    kind: str
    mean: float = math.nan
    std: float = math.nan
    low: float = -math.inf
    high: float = math.inf

    def __post_init__(self) -> None:
        if self.kind not in _KINDS:
            raise ValueError(f"distribution {self.kind!r} is not known (allowed: {', '.join(_KINDS)})")
        lo, hi = float(self.low), float(self.high)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise ValueError(f"the bounds must satisfy low < high, got low = {lo:g}, high = {hi:g}")
        _KINDS[self.kind].check(self)

    def _frozen(self) -> Any:
        return _KINDS[self.kind].frozen(self)

    def quantile(self, u: np.ndarray) -> np.ndarray:
        """The values at probabilities ``u`` in (0, 1) (the inverse of the distribution function)."""
        return np.asarray(self._frozen().ppf(np.asarray(u, dtype=float)), dtype=float)

    @property
    def centre(self) -> float:
        """The median (the nominal value of the input)."""
        return float(self._frozen().median())

    def moments(self) -> tuple[float, float]:
        """Mean and variance (of the truncated distribution where truncated)."""
        f = self._frozen()
        return float(f.mean()), float(f.var())

    def describe(self) -> str:
        """The distribution in words, e.g. ``normal(mean 0.005, std 0.0001) truncated to [0, inf)``."""
        return _KINDS[self.kind].describe(self)
