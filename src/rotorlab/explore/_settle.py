"""Is a trajectory still settling? The "not settled" verdict, its time to settle, and default horizons.

A ball balancer's start that has not balanced by a horizon is either in *another motion* (a
side motion, a whirl: the names the mappers give) or *not settled*: its distance to the balanced
state (deflection and ball rates in units of their thresholds) is still falling towards it.
:func:`settle_estimate` reads that from the distance at the horizons alone: a start is heading
for balance when its distance fell by more than :data:`FALL_FRACTION` over the last step between
horizons at a logarithmic rate ``s`` that is not slowing down (at least :data:`SLOWING` of the
step before: an approach to another motion's plateau slows down). Its estimated time to settle
is when ``a e^(-s t)`` reaches the threshold. Near the
balanced state the deflection decays as ``e^(Re(lambda) t)`` of the state's slowest mode, so the
estimate meets the eigenvalue there (``tests/unit/test_settle.py``).

:func:`default_horizon` is the simulated time used when a case gives none: :data:`TIME_CONSTANTS`
time constants ``1 / |Re(lambda)|`` of the balanced state's slowest decaying mode, at least
:data:`MIN_REVOLUTIONS` and at most :data:`MAX_REVOLUTIONS` revolutions.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["NOT_SETTLED", "FALL_FRACTION", "TIME_CONSTANTS", "MIN_REVOLUTIONS", "MAX_REVOLUTIONS",
           "SLOWING", "settle_estimate", "default_horizon", "slowest_decay_rate"]  # fmt: skip

#: Label of a start still converging towards the balanced state at a horizon.
NOT_SETTLED = "not settled"
#: A deflection that fell by more than this fraction over the last step between horizons is
#: still changing.
FALL_FRACTION = 0.01
#: A decay towards the balanced state keeps at least this share of its logarithmic rate from one
#: step between horizons to the next (an approach to another motion's plateau slows down).
SLOWING = 0.5
#: Default horizon: this many time constants of the balanced state's slowest decaying mode ...
TIME_CONSTANTS = 10.0
#: ... but at least this many revolutions of the rotor ...
MIN_REVOLUTIONS = 100.0
#: ... and at most this many (the cap).
MAX_REVOLUTIONS = 5000.0


def settle_estimate(amplitude, threshold, horizons) -> np.ndarray:
    """Estimated time (s) at which each deflection falls below ``threshold``, at each horizon.

    Parameters
    ----------
    amplitude : array_like, shape (N, n_horizon)
        Deflection measure at each horizon (m); it is ~0 in the balanced state.
    threshold : array_like, shape (N,)
        Deflection below which a start counts as balanced (m).
    horizons : array_like, shape (n_horizon,)
        Increasing, equally spaced times (s).

    Returns
    -------
    ndarray, shape (N, n_horizon)
        At horizon j: the extrapolated time (s, > horizons[j]) where the start is heading for the
        balanced state (fell by more than :data:`FALL_FRACTION` over the last step, not slowing
        down), NaN elsewhere (already below, not falling, heading elsewhere, or j = 0).

    Examples
    --------
    >>> h = np.arange(1.0, 5.0)
    >>> est = settle_estimate(np.exp(-0.5 * h)[None, :], np.array([np.exp(-0.5 * 6.0)]), h)
    >>> est.round(6)  # a pure exponential reaches e^(-3) at t = 6 s
    array([[nan,  6.,  6.,  6.]])
    >>> settle_estimate((1.0 + np.exp(-h))[None, :], np.array([0.1]), h)[0, 2:]  # heads for 1.0
    array([nan, nan])
    """
    a = np.asarray(amplitude, dtype=float)
    thr = np.asarray(threshold, dtype=float).reshape(-1, 1) * np.ones((1, a.shape[1]))
    h = np.asarray(horizons, dtype=float)
    out = np.full(a.shape, np.nan)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for j in range(1, a.shape[1]):
            dt = h[j] - h[j - 1]
            a0, a1, t = a[:, j - 1], a[:, j], thr[:, j]
            falling = np.isfinite(a0) & np.isfinite(a1) & (a1 < a0 * (1.0 - FALL_FRACTION)) & (a1 > t)
            rate = np.log(a0 / a1) / dt
            if j >= 2:  # towards a plateau the log-decay slows down step by step; towards 0 it does not
                falling &= rate >= SLOWING * np.log(a[:, j - 2] / a0) / dt
            out[:, j] = np.where(falling, h[j] + np.log(a1 / t) / rate, np.nan)
    return out


def slowest_decay_rate(eigenvalues) -> float | None:
    """``-max Re(lambda)`` (1/s) over the eigenvalues of a balanced state, neutral ones (|lambda|
    below 1e-8 of the largest: a family of balanced states) left out; None if it is not
    asymptotically stable.

    Examples
    --------
    >>> slowest_decay_rate([-6.3 + 377j, -6.3 - 377j, -12.0, 0.0])
    6.3
    >>> slowest_decay_rate([-1.0, 0.5]) is None
    True
    """
    ev = np.asarray(eigenvalues, dtype=complex).reshape(-1)
    if ev.size == 0 or not np.all(np.isfinite(ev)):
        return None
    ev = ev[np.abs(ev) > 1e-8 * np.abs(ev).max()]
    top = float(ev.real.max()) if ev.size else 0.0
    return -top if top < 0.0 else None


def default_horizon(decay_rate: float | None, spin_speed: float, fallback: float) -> tuple[float, str]:
    """The simulated time (s) of a basin whose case gives none, and how it was chosen.

    Parameters
    ----------
    decay_rate : float or None
        ``-max Re(lambda)`` of the balanced state (1/s); None when there is no stable one.
    spin_speed : float
        Rotor speed (rad/s), for the revolution bounds.
    fallback : float
        Horizon of the mapper used when ``decay_rate`` is None (s).

    Examples
    --------
    >>> default_horizon(1 / 8.1, 2 * math.pi * 50, 20.0)
    (81.0, 'horizon 81 s = 10 time constants of the slowest mode of the balanced state, 8.1 s')
    >>> default_horizon(6.33, 2 * math.pi * 40, 20.0)[1]
    'horizon 2.5 s = 100 revolutions, the least (10 time constants of the slowest mode of the balanced state, 0.158 s, are 1.58 s)'
    """
    period = 2.0 * math.pi / abs(spin_speed)
    if decay_rate is None or not decay_rate > 0:
        return float(fallback), f"horizon {fallback:.3g} s, the mapper's default (the balanced state is not stable)"
    tau = 1.0 / decay_rate
    t = TIME_CONSTANTS * tau
    what = f"{TIME_CONSTANTS:g} time constants of the slowest mode of the balanced state, {tau:.3g} s"
    if t < MIN_REVOLUTIONS * period:
        t = MIN_REVOLUTIONS * period
        return t, f"horizon {t:.3g} s = {MIN_REVOLUTIONS:g} revolutions, the least ({what}, are {TIME_CONSTANTS * tau:.3g} s)"
    if t > MAX_REVOLUTIONS * period:
        t = MAX_REVOLUTIONS * period
        return t, f"horizon {t:.3g} s = {MAX_REVOLUTIONS:g} revolutions, the cap ({what}, would be {TIME_CONSTANTS * tau:.3g} s)"
    return t, f"horizon {t:.3g} s = {what}"
