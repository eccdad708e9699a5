"""Wilson score intervals of a binomial proportion and the sample sizes they imply: the one place
these are computed (basin fractions, basin stability, knock probabilities; the case-file schema
checks a target width with them). No heavy imports: SciPy's normal quantile is imported when used.
"""

from __future__ import annotations

import math

import numpy as np

from rotorlab._limits import MAX_STARTS

__all__ = ["wilson_interval", "starts_for_half_width", "min_half_width"]


def wilson_interval(count, n, confidence: float = 0.95):
    """Wilson score interval of a binomial proportion.

    Parameters
    ----------
    count : int or array_like
        Successes.
    n : int or array_like
        Trials, >= 1 (broadcast against ``count``).
    confidence : float
        In (0, 1).

    Returns
    -------
    (low, high) : ndarrays
        Of the broadcast shape of ``count`` and ``n``: ``(k + z^2/2) / (n + z^2) -+ z / (n + z^2)
        sqrt(k (n - k) / n + z^2 / 4)`` with ``z`` the two-sided normal quantile, the interval of
        ``scipy.stats.binomtest(k, n).proportion_ci(confidence, method="wilson")`` in closed form
        (vectorised: adaptive basin stability evaluates it for many counts).

    References
    ----------
    Wilson E.B. Probable inference, the law of succession, and statistical inference. J. Amer.
    Statist. Assoc. 22 (1927) 209-212.

    Examples
    --------
    >>> [round(float(v), 4) for v in wilson_interval(50, 100)]
    [0.4038, 0.5962]
    """
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence!r}")
    k, n = np.broadcast_arrays(np.asarray(count, dtype=float), np.asarray(n, dtype=float))
    if np.any(n < 1):
        raise ValueError(f"n must be >= 1, got {np.asarray(n).min()!r}")
    z = _z(confidence)
    centre = (k + z * z / 2.0) / (n + z * z)
    half = z / (n + z * z) * np.sqrt(np.maximum(k * (n - k) / n, 0.0) + z * z / 4.0)
    low, high = np.clip(centre - half, 0.0, 1.0), np.clip(centre + half, 0.0, 1.0)
    low = np.where(k <= 0, 0.0, low)  # exact ends, as SciPy's
    high = np.where(k >= n, 1.0, high)
    return low, high


def _z(confidence: float) -> float:
    """The two-sided normal quantile of ``confidence`` (1.96 for 0.95)."""
    from scipy.stats import norm

    return float(norm.ppf(0.5 + confidence / 2.0))


def starts_for_half_width(width: float, confidence: float = 0.95) -> int:
    """The fewest starts whose Wilson interval has a half-width <= ``width`` whatever the fraction.

    The half-width ``z / (n + z^2) sqrt(k (n - k) / n + z^2 / 4)`` is largest at ``k = n / 2``,
    where it is ``z / (2 sqrt(n + z^2))``; so ``n >= z^2 / (4 W^2) - z^2`` starts always do.

    Examples
    --------
    >>> starts_for_half_width(0.05), starts_for_half_width(0.01)
    (381, 9600)
    """
    if not 0.0 < width < 0.5:
        raise ValueError(f"width must be in (0, 0.5), got {width!r}")
    z = _z(confidence)
    return max(1, math.ceil(z * z / (4.0 * width * width) - z * z))


def min_half_width(confidence: float = 0.95) -> float:
    """The narrowest target half-width :data:`MAX_STARTS` starts per value guarantee."""
    z = _z(confidence)
    return z / (2.0 * math.sqrt(MAX_STARTS + z * z))
