"""The verdict of a basin: do its fractions still change, and is the horizon long enough?

"The fractions no longer change" is said only when a stated test shows it
(:func:`basin_verdict`): the fraction of every label at the last two horizons agree within their
Wilson 95 % intervals, no start is labelled *not settled* (still converging towards the
balanced state, :mod:`rotorlab.explore._settle`), and the horizon is at least
:data:`MIN_TIME_CONSTANTS` time constants of the balanced state's slowest mode (where known).
Otherwise the horizon is too short for a verdict, and the verdict names the horizon that would
do: 1.25 times the latest estimated settle time of the starts not settled, or twice the horizon
when only the fractions moved, and at least 10 time constants of the slowest mode.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import xarray

__all__ = ["basin_verdict", "round_up_horizon", "MARGIN", "MIN_TIME_CONSTANTS"]

#: The horizon that would do is this many times the latest estimated settle time (and at least
#: :data:`rotorlab.explore._settle.TIME_CONSTANTS` time constants of the slowest mode).
MARGIN = 1.25
#: A horizon shorter than this many time constants of the balanced state's slowest mode gives no
#: verdict, whatever the labels (the fractions of a run that has barely begun agree, too).
MIN_TIME_CONSTANTS = 3.0


def round_up_horizon(t: float) -> float:
    """Up to two significant digits: 41.3 -> 42, 0.372 -> 0.38."""
    if not (math.isfinite(t) and t > 0):
        return t
    scale = 10.0 ** (math.floor(math.log10(t)) - 1)
    return math.ceil(t / scale - 1e-9) * scale


def basin_verdict(ds: xarray.Dataset, confidence: float = 0.95) -> dict[str, Any]:
    """Test whether a basin's fractions have stopped changing.

    Parameters
    ----------
    ds : xarray.Dataset
        With ``count`` (horizon, regime), ``horizon``, ``outcome`` and, for a balancer,
        ``settle_estimate`` (from :func:`rotorlab.analyses.run_basin_analysis` or a sweep).
    confidence : float
        Level of the Wilson intervals of the test.

    Returns
    -------
    dict
        ``settled`` (bool: the test passed), ``not_settled`` (starts labelled not settled at the
        last horizon), ``n``, ``settle_by_s`` (their latest estimated settle time, s, or None),
        ``fractions_agree`` (bool or None with a single horizon), ``horizons_compared_s``,
        ``horizon_needed_s`` (None when settled) and ``sentence``.
    """
    from rotorlab.explore._basin import wilson_interval
    from rotorlab.explore._settle import NOT_SETTLED, TIME_CONSTANTS

    horizons = np.asarray(ds["horizon"].values, dtype=float)
    counts = np.asarray(ds["count"].values).reshape(horizons.size, -1)
    n = int(counts[-1].sum())
    t_end = float(horizons[-1])
    names = [str(r) for r in ds["regime"].values]
    waiting = 0
    settle_by = None
    if NOT_SETTLED in names:
        code = names.index(NOT_SETTLED)
        mask = np.asarray(ds["outcome"].values).ravel() == code
        waiting = int(mask.sum())
        if waiting and "settle_estimate" in ds:
            est = np.asarray(ds["settle_estimate"].isel(horizon=-1).values, dtype=float).ravel()[mask]
            settle_by = float(np.nanmax(est)) if np.isfinite(est).any() else None
    agree = None
    compared = [t_end]
    if horizons.size >= 2 and n > 0:
        compared = [float(horizons[-2]), t_end]
        lo1, hi1 = wilson_interval(counts[-2], int(counts[-2].sum()), confidence)
        lo2, hi2 = wilson_interval(counts[-1], n, confidence)
        agree = bool(np.all((lo1 <= hi2) & (lo2 <= hi1)))
    rate = float(ds.attrs.get("slowest_decay_rate", math.nan))
    tau = 1.0 / rate if math.isfinite(rate) and rate > 0 else None
    short = tau is not None and t_end < MIN_TIME_CONSTANTS * tau
    settled = bool(agree) and waiting == 0 and not short
    pct = f"{confidence:.0%}".replace("%", " %")
    if settled:
        sentence = (f"The fractions no longer change: at {compared[0]:.3g} s and {t_end:.3g} s they agree within their "
                    f"Wilson {pct} intervals, and no start is still converging.")
        need = None
    else:
        reasons = []
        if waiting:
            by = f", estimated to settle by {settle_by:.3g} s" if settle_by is not None else ""
            reasons.append(f"{waiting} of {n} starts are not settled (still converging towards balance{by})")
        if agree is False:
            reasons.append(f"the fractions at {compared[0]:.3g} s and {t_end:.3g} s differ beyond their Wilson {pct} "
                           "intervals")
        elif agree is None:
            reasons.append("one horizon alone cannot show that the fractions stopped changing")
        if short:
            reasons.append(f"it is shorter than {MIN_TIME_CONSTANTS:g} time constants of the balanced state's slowest "
                           f"mode ({tau:.3g} s)")
        need = MARGIN * settle_by if settle_by is not None and settle_by > t_end else 2.0 * t_end
        need = round_up_horizon(max(need, TIME_CONSTANTS * tau if tau is not None else 0.0))
        sentence = (f"The horizon, {t_end:.3g} s, is too short for a verdict: " + "; ".join(reasons)
                    + f". A horizon of {need:g} s would do.")
    return {"settled": settled, "not_settled": waiting, "n": n, "settle_by_s": settle_by,
            "fractions_agree": agree, "horizons_compared_s": compared, "horizon_needed_s": need,
            "sentence": sentence}  # fmt: skip
