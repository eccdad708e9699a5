"""A distribution-free confidence interval of a median from order statistics.

Of ``n`` independent draws of any continuous distribution, sorted ``x_(1) <= ... <= x_(n)``, the
interval ``[x_(j), x_(n+1-j)]`` holds the population median with probability
``1 - 2 P(B <= j - 1)``, ``B ~ Binomial(n, 1/2)`` (each draw falls below the median with
probability 1/2): :func:`median_interval` takes the narrowest such interval whose coverage is at
least the confidence asked for, or the whole sample's range, with its own lower coverage, when
``n`` is too small for that (``n < 6`` at 95 %).

Reference: Conover W.J. Practical Nonparametric Statistics, 3rd ed., Wiley 1999, sec. 3.2
(confidence interval for a quantile).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["median_interval"]


def _binom_cdf_half(k: int, n: int) -> float:
    """``P(B <= k)`` for ``B ~ Binomial(n, 1/2)``, exact."""
    return sum(math.comb(n, i) for i in range(k + 1)) / 2.0**n if k >= 0 else 0.0


def median_interval(values, confidence: float = 0.95) -> tuple[float, float, float, float]:
    """Median of a sample and its distribution-free interval.

    Parameters
    ----------
    values : array_like
        The sample; NaN entries are left out.
    confidence : float
        In (0, 1).

    Returns
    -------
    (median, low, high, coverage) : floats
        The sample median, the order statistics ``x_(j)``, ``x_(n+1-j)`` and the exact coverage
        of that interval for the population median (>= ``confidence`` unless the sample is too
        small: then the sample's range and its coverage ``1 - 2^(1-n)``); all NaN for an empty
        sample.

    Examples
    --------
    >>> [round(v, 4) for v in median_interval(np.arange(1.0, 21.0))]  # n = 20: x_(6), x_(15)
    [10.5, 6.0, 15.0, 0.9586]
    >>> [round(v, 4) for v in median_interval([3.0, 1.0, 2.0])]  # too few for 95 %: the range
    [2.0, 1.0, 3.0, 0.75]
    """
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence!r}")
    x = np.sort(np.asarray(values, dtype=float).ravel())
    x = x[np.isfinite(x)]
    n = x.size
    if n == 0:
        return (math.nan,) * 4
    j = 1  # the largest j (1-based) whose interval still covers with the confidence asked
    while j + 1 <= (n + 1) // 2 and 1.0 - 2.0 * _binom_cdf_half(j, n) >= confidence:
        j += 1
    coverage = 1.0 - 2.0 * _binom_cdf_half(j - 1, n)
    return float(np.median(x)), float(x[j - 1]), float(x[n - j]), float(coverage)
