r"""The worst residual over the stuck set of three or more balls, by constrained optimisation.

With n balls the arrangements where every ball sticks (every holding-torque margin of
:class:`rotorlab.analyses._friction_machine.MachineStick` <= 0) form an n-dimensional set, and
with n >= 3 the balanced arrangements of the machine without friction are themselves a family
(n minus the number of balance conditions parameters). The *stuck set* of the analysis is the
part of it connected to that family; its *worst arrangement* maximises the residual vibration
(the largest node deflection, m) over it. A grid over n angles grows as grid^n, so it is found
by SciPy's SLSQP (:func:`scipy.optimize.minimize`) instead:

- starts: distinct balanced arrangements of the machine without friction (seeded least-squares
  solves, :meth:`rotorlab.models.Machine.balanced_angles`), each left in a seeded random
  direction by a step small enough that every ball still sticks (at a balanced arrangement
  the residual is zero and so is its gradient);
- climb: maximise the squared residual over the ball angles (each within half a turn of its
  start) subject to ``+-hold_b - allow_b <= 0`` per ball (the two smooth halves of ``|hold_b| <=
  allow_b``: the holding torque and what friction allows, per ``m_b l_b Omega^2``), in steps of at
  most :data:`STEP` rad per angle, a step kept only when every one of :data:`SEGMENT_SAMPLES`
  points of its segment sticks: the end is joined to the balanced start by a stuck polyline, in
  the stuck set's component that holds it;
- the band of each ball: the extreme offsets of its angle from the best run's start (two more
  climbs per ball); from each of these ends the residual is climbed again (a thin neck of the
  stuck set, where the residual falls, stops a climb from the start but not one from beyond it).

The result is the largest of local maxima (a lower bound of the worst residual over the component:
a climb cannot cross a region where the residual falls, short of the band's ends). Checked against
the grid search for two balls and against the three-ball closed form in
``tests/validation/test_friction_machines.py``.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

__all__ = ["worst_stuck", "SEGMENT_SAMPLES"]

#: Points of the segment from the start to a result that must all stick.
SEGMENT_SAMPLES = 201
#: Direction steps per balanced start.
DIRECTIONS = 3
#: The largest step of one climb (rad per angle), and the most steps.
STEP = 0.25
MAX_STEPS = 60


def _margins(holding, psi):
    amp, hold, allow = holding(psi)
    return amp, np.abs(hold) - allow


def _stuck(holding, psi, tol) -> np.ndarray:
    return np.all(_margins(holding, psi)[1] <= tol, axis=-1)


def _joined(holding, a, b, tol) -> bool:
    s = np.linspace(0.0, 1.0, SEGMENT_SAMPLES)[:, None]
    return bool(np.all(_stuck(holding, a + s * (b - a), tol)))


def _leave(holding, start, rng, tol):
    """A stuck arrangement a small random step from the balanced ``start``, or None."""
    d = rng.normal(size=start.size)
    d /= np.linalg.norm(d)
    for k in range(30):
        x = start + 1e-2 * 0.5**k * d
        if _stuck(holding, x, -tol):
            return x
    return None


def _step(objective, holding, x, lo, hi, scale):
    from scipy.optimize import minimize

    def cons(x):
        _, hold, allow = holding(x)
        return np.concatenate([allow - hold, allow + hold]) / scale

    res = minimize(objective, x, method="SLSQP", bounds=list(zip(lo, hi)),
                   constraints=[{"type": "ineq", "fun": cons}], options={"maxiter": 200, "ftol": 1e-14})
    return res.x


def _climb(objective, holding, x0, centre, scale, tol):
    """Maximise ``-objective`` from the stuck ``x0`` in steps of at most :data:`STEP` rad per angle, each
    step joined to the last by a stuck segment: the end is joined to ``x0`` by a stuck polyline."""
    x, rho, prev = x0, STEP, x0
    f = objective(x)
    for _ in range(MAX_STEPS):
        lo, hi = np.maximum(centre - math.pi, x - rho), np.minimum(centre + math.pi, x + rho)
        xn = _step(objective, holding, x, lo, hi, scale)
        fn = objective(xn)
        if fn >= f or not _joined(holding, x, xn, tol):
            if fn >= f - 1e-12 * max(abs(f), 1e-300) and _joined(holding, x, xn, tol):
                break  # no further gain
            rho *= 0.5
            if rho < 1e-6:
                break
            continue
        free = (np.all((xn > lo + 1e-9) | (lo <= centre - math.pi))
                and np.all((xn < hi - 1e-9) | (hi >= centre + math.pi)))
        gain = f - fn
        prev, x, f = x, xn, fn
        if free and gain <= 1e-10 * max(abs(f), 1e-300):
            break
    return x, prev


def worst_stuck(holding: Callable, starts, *, scale: float, seed: int = 0) -> dict:
    """The worst arrangement over the stuck set joined to the balanced ``starts`` (module docstring).

    Parameters
    ----------
    holding : callable
        ``holding(psi) -> (amplitude, hold, allow)`` at stuck angles ``psi`` (..., n) (as
        :meth:`MachineStick.holding`).
    starts : sequence of array_like
        Balanced arrangements of the machine without friction (rad).
    scale : float
        The size of ``hold`` and ``allow`` (m; the largest friction arm): scales the objective
        and the constraints.

    Returns
    -------
    dict
        ``worst`` (m), ``worst_at`` (rad), ``centre`` (its start, rad), ``before`` (the last point of
        the stuck polyline from ``centre`` to ``worst_at``, rad), ``low``, ``high`` (each ball's band,
        rad from ``centre``), ``runs``, ``kept`` (the runs that ended stuck).
    """
    rng = np.random.default_rng(seed)
    tol = 1e-8 * scale

    def objective(x):
        return -((holding(x)[0] / scale) ** 2)

    best = None
    runs = kept = 0
    for start in starts:
        start = np.asarray(start, dtype=float)
        for _ in range(DIRECTIONS):
            x0 = _leave(holding, start, rng, tol)
            if x0 is None:
                continue
            runs += 1
            x, prev = _climb(objective, holding, x0, start, scale, tol)
            if not _stuck(holding, x, tol):
                continue
            kept += 1
            amp = float(holding(x)[0])
            if best is None or amp > best[0]:
                best = (amp, x, start, prev)
    n = len(np.asarray(starts[0])) if len(starts) else 0
    out = {"worst": math.nan, "worst_at": np.full(n, math.nan), "centre": np.full(n, math.nan),
           "before": np.full(n, math.nan),
           "low": np.full(n, math.nan), "high": np.full(n, math.nan), "runs": runs, "kept": kept}
    if best is None:
        return out
    amp, x, start, prev = best
    x0 = _leave(holding, start, rng, tol)
    ends = []
    for b in range(n):
        for sign, key in ((-1.0, "low"), (1.0, "high")):
            xb, _ = _climb(lambda x, b=b, sign=sign: -sign * (x[b] - start[b]), holding, x0, start, scale, tol)
            if _stuck(holding, xb, tol):
                out[key][b] = xb[b] - start[b]
                ends.append(xb)
    for xb in ends:  # from the band's ends (past a neck of the stuck set a climb from the start cannot cross)
        runs += 1
        xe, pe = _climb(objective, holding, xb, start, scale, tol)
        if _stuck(holding, xe, tol):
            kept += 1
            if float(holding(xe)[0]) > amp:
                amp, x, prev = float(holding(xe)[0]), xe, pe
    out.update(worst=amp, worst_at=x, centre=start, runs=runs, kept=kept, before=prev)
    return out
