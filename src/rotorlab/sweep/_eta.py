"""How long a sweep will take, asked before it starts: time a pilot, estimate, let the caller decide.

A command that may run for days (a basin of 25 million starts) says so before it starts. The
engine does the measuring, the command decides: inside :func:`long_run_guard`, every
:func:`rotorlab.sweep.run_sweep` of at least :data:`PILOT_ABOVE` points first times a pilot (a
few points spread over the sweep, after one point that compiles the integrator), estimates the
time of the points left to compute, and hands that :class:`Estimate` to the guard's ``decide``;
``decide`` returning False stops the sweep with :class:`LongRunDeclined` before anything is
written. Every command on the sweep engine (``basin``, ``sweep``, and any later one) gets the
estimate by running inside the guard.
"""

from __future__ import annotations

import contextlib
import contextvars
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Estimate", "LongRunDeclined", "long_run_guard", "estimate_sweep", "PILOT_ABOVE", "PILOT_POINTS",
           "human_duration"]

#: Sweeps of fewer points run without a pilot (a pilot would cost more than it tells).
PILOT_ABOVE = 4096
#: Points a pilot times (spread evenly over the sweep: their cost may depend on where they are).
PILOT_POINTS = 32


def human_duration(seconds: float) -> str:
    """A duration for people: seconds, minutes, hours or days, 2 significant digits.

    Examples
    --------
    >>> human_duration(42.0), human_duration(150.0), human_duration(7200.0), human_duration(1.5e6)
    ('42 s', '2.5 min', '2 h', '17 days')
    >>> human_duration(2.2e7)
    '255 days'
    """
    def fmt(v: float) -> str:
        return f"{v:.0f}" if v >= 10 else f"{v:.2g}"

    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= (2 * size if unit == "days" else size):
            return f"{fmt(seconds / size)} {unit}"
    return f"{fmt(seconds)} s"


@dataclass(frozen=True, slots=True)
class Estimate:
    """The time a sweep will take, from a timed pilot.

    Parameters
    ----------
    points : int
        Points left to compute.
    pilot_points : int
        Points the pilot timed.
    seconds_per_point : float
        Measured (s), in this process with the integrator's threads.
    """

    points: int
    pilot_points: int
    seconds_per_point: float

    @property
    def seconds(self) -> float:
        """Estimated time of the points left (s)."""
        return self.points * self.seconds_per_point

    def describe(self, what: str = "points") -> str:
        """One line: the estimate and how it was made.

        Examples
        --------
        >>> Estimate(25_000_000, 32, 0.058).describe("starts")
        'estimated 17 days for 25,000,000 starts (0.058 s each, timed on 32 of them in this process)'
        """
        return (f"estimated {human_duration(self.seconds)} for {self.points:,} {what} "
                f"({self.seconds_per_point:.2g} s each, timed on {self.pilot_points} of them in this process)")


class LongRunDeclined(RuntimeError):
    """A sweep's :class:`Estimate` was declined by its :func:`long_run_guard` (nothing was written)."""

    def __init__(self, estimate: Estimate) -> None:
        super().__init__(estimate.describe())
        self.estimate = estimate


# the guard's decide function and the sweeps it accepted (by id: an adaptive sweep runs the same
# Sweep in rounds, asked once)
_GUARD: contextvars.ContextVar[tuple[Callable[[Estimate], bool], set[int]] | None] = contextvars.ContextVar(
    "rotorlab_long_run", default=None)


@contextlib.contextmanager
def long_run_guard(decide: Callable[[Estimate], bool]) -> Iterator[None]:
    """Estimate every large sweep run inside the block and let ``decide`` stop it.

    Parameters
    ----------
    decide : callable
        ``decide(Estimate) -> bool``: True runs the sweep, False stops it before it writes
        anything (:class:`LongRunDeclined`). It may also print the estimate.

    Examples
    --------
    >>> with long_run_guard(lambda est: est.seconds < 600.0):
    ...     pass  # run_sweep(...) here asks first when it has PILOT_ABOVE points or more
    """
    token = _GUARD.set((decide, set()))
    try:
        yield
    finally:
        _GUARD.reset(token)


def estimate_sweep(sweep: Any, points: int, threads: int | None = None,
                   pilot_points: int = PILOT_POINTS) -> Estimate:  # fmt: skip
    """Time a pilot of ``sweep`` and estimate ``points`` of it.

    One point runs first (it compiles the integrator, which the sweep needs anyway, and is not
    timed), then ``pilot_points`` points spread evenly over the sweep are timed together, as a
    chunk (:func:`rotorlab.sweep.compute_chunk`). Their results are not kept.

    Parameters
    ----------
    sweep : rotorlab.sweep.Sweep
    points : int
        Points to estimate (those left to compute).
    threads : int, optional
        Integrator threads, as the sweep runs.
    pilot_points : int

    Returns
    -------
    Estimate
    """
    from rotorlab.sweep._spec import compute_chunk

    coords = sweep.coordinates()
    n = sweep.n_points
    pick = np.unique(np.linspace(0, n - 1, min(pilot_points, n)).round().astype(int))
    compute_chunk(sweep.analysis, 0, {k: v[pick[:1]] for k, v in coords.items()}, threads)
    started = time.perf_counter()
    compute_chunk(sweep.analysis, 0, {k: v[pick] for k, v in coords.items()}, threads)
    return Estimate(int(points), int(pick.size), (time.perf_counter() - started) / pick.size)


def check_long_run(sweep: Any, points: int, threads: int | None = None) -> None:
    """What :func:`rotorlab.sweep.run_sweep` asks before it starts: inside a
    :func:`long_run_guard`, a sweep of :data:`PILOT_ABOVE` points or more is estimated on the
    ``points`` it will compute and the guard decides (:class:`LongRunDeclined` if it declines);
    a sweep it accepted is not asked again (the rounds of an adaptive sweep)."""
    guard = _GUARD.get()
    if guard is None or sweep.n_points < PILOT_ABOVE or points <= 0 or id(sweep) in guard[1]:
        return
    estimate = estimate_sweep(sweep, points, threads)
    if not guard[0](estimate):
        raise LongRunDeclined(estimate)
    guard[1].add(id(sweep))
