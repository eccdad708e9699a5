"""Public interface of the integrator: ``solve`` and ``solve_ensemble`` and their small objects.

The split follows diffrax: *what* is solved (a model: its :class:`~rotorlab.models.Kernels` and a
packed parameter vector), *how* steps adapt (:class:`StepControl`), *what* is saved
(:class:`SaveAt`), *which* events act and how (:class:`Event`); results carry per-trajectory
:class:`Status` codes and never raise from inside an ensemble.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from rotorlab.integrate._results import EnsembleSolution, Solution, Status
from rotorlab.integrate._sanity import sanity_check
from rotorlab.models._base import EventSpec, Kernels

__all__ = [
    "Status",
    "StepControl",
    "SaveAt",
    "Event",
    "Solution",
    "EnsembleSolution",
    "solve",
    "solve_ensemble",
]


@dataclass(frozen=True, slots=True)
class StepControl:
    """How the adaptive Dormand–Prince 5(4) steps are controlled.

    Parameters
    ----------
    rtol : float
        Relative tolerance, in (0, 1).
    atol : float or array_like, shape (n_state,)
        Absolute tolerance (units of each state), > 0.
    first_step : float or None
        Initial step (s); ``None`` chooses it (Hairer's heuristic).
    max_step : float
        Largest step (s), > 0.
    max_steps : int
        Maximum number of step attempts per trajectory.
    """

    rtol: float = 1e-6
    atol: float | tuple[float, ...] = 1e-9
    first_step: float | None = None
    max_step: float = math.inf
    max_steps: int = 10_000_000

    def __post_init__(self) -> None:
        if not (0.0 < self.rtol < 1.0):
            raise ValueError(f"rtol must be in (0, 1), got {self.rtol!r}")
        atol = np.atleast_1d(np.asarray(self.atol, dtype=float))
        if atol.ndim != 1 or not np.all(np.isfinite(atol)) or np.any(atol <= 0):
            raise ValueError(f"atol must be > 0 and finite, got {self.atol!r}")
        if self.first_step is not None and not (self.first_step > 0 and math.isfinite(self.first_step)):
            raise ValueError(f"first_step must be > 0 and finite or None, got {self.first_step!r}")
        if not self.max_step > 0:
            raise ValueError(f"max_step must be > 0, got {self.max_step!r}")
        if int(self.max_steps) < 1:
            raise ValueError(f"max_steps must be >= 1, got {self.max_steps!r}")


@dataclass(frozen=True, slots=True)
class SaveAt:
    """What to save along each trajectory (the final state is always kept).

    Parameters
    ----------
    ts : array_like or None
        Save times (s), increasing, within the time span; shape (n_save,) shared by all
        trajectories or (N, n_save) per trajectory (pad a short row with ``inf``).
    every_revolution : bool
        Save stroboscopically, once per revolution of the rotor: at the times where the spin
        angle has advanced by a whole number of turns since ``t0`` (the model must provide
        ``revolution_times(t0, t1, p)``). Exclusive with ``ts``.
    """

    ts: Any = None
    every_revolution: bool = False

    def __post_init__(self) -> None:
        if self.ts is not None and self.every_revolution:
            raise ValueError("give either ts or every_revolution=True, not both")


@dataclass(frozen=True, slots=True)
class Event:
    """Select one of the model's event functions and say what happens at its zeros.

    The condition itself is the model's compiled event function of that name (see
    :class:`rotorlab.models.EventSpec`); it is not a Python callable because the integrator is
    compiled and cached once per model, and numba cannot cache closures.

    Parameters
    ----------
    name : str
        Name of the model's event function.
    direction : {-1, 0, 1} or None
        Crossing direction that triggers it; ``None`` keeps the model's default.
    action : {"reset", "stop", "count"} or None
        ``"reset"`` applies the model's reset map (impact, stick/slip switch) and continues,
        ``"stop"`` ends the trajectory (terminal event), ``"count"`` records it only;
        ``None`` keeps the model's default.
    """

    name: str
    direction: int | None = None
    action: Literal["reset", "stop", "count"] | None = None

    def __post_init__(self) -> None:
        if self.direction not in (None, -1, 0, 1):
            raise ValueError(f"Event direction must be -1, 0, 1 or None, got {self.direction!r}")
        if self.action not in (None, "reset", "stop", "count"):
            raise ValueError(
                f"Event action must be 'reset', 'stop', 'count' or None, got {self.action!r}"
            )


_ACTION_CODES = {"reset": 0, "stop": 1, "count": 2, "off": 3}


# ------------------------------------------------------------------------------------------------
def _kernels_of(model: Any) -> Kernels:
    kernels = getattr(model, "kernels", model)
    if not isinstance(kernels, Kernels):
        raise TypeError(
            "model must be a rotorlab model (with .kernels and .to_array()) or a Kernels bundle, "
            f"got {type(model).__name__}"
        )
    return kernels


def _event_tables(specs: Sequence[EventSpec], events: Sequence[Event] | None):
    n_ev = len(specs)
    names = tuple(s.name for s in specs)
    ev_dir = np.array([s.direction for s in specs], dtype=np.int64)
    ev_act = np.array([_ACTION_CODES[s.action] for s in specs], dtype=np.int64)
    if events is not None:
        ev_act[:] = _ACTION_CODES["off"]
        for ev in events:
            if not isinstance(ev, Event):
                raise TypeError(f"events must be Event objects, got {type(ev).__name__}")
            if ev.name not in names:
                raise ValueError(
                    f"unknown event {ev.name!r}; this model's events are: {', '.join(names) or 'none'}"
                )
            k = names.index(ev.name)
            spec = specs[k]
            ev_dir[k] = spec.direction if ev.direction is None else ev.direction
            ev_act[k] = _ACTION_CODES[spec.action if ev.action is None else ev.action]
    if n_ev == 0:
        ev_dir = np.zeros(1, dtype=np.int64)
        ev_act = np.full(1, _ACTION_CODES["off"], dtype=np.int64)
    return n_ev, names, ev_dir, ev_act


def _as_2d(a: Any, width: int, what: str) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != width:
        raise ValueError(f"{what} must have shape ({width},) or (N, {width}), got {np.shape(a)}")
    if not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(f"{what} must be finite; entry {tuple(int(i) for i in bad)} is {arr[tuple(bad)]}")
    return np.ascontiguousarray(arr)


def _save_grid(save_at: SaveAt, model: Any, t0: float, T1: np.ndarray, P: np.ndarray) -> np.ndarray:
    if save_at.every_revolution:
        fn = getattr(model, "revolution_times", None)
        if fn is None:
            raise ValueError("SaveAt(every_revolution=True) needs a model with revolution_times()")
        rows = [np.asarray(fn(t0, float(T1[min(i, T1.size - 1)]), P[i]), dtype=float) for i in range(P.shape[0])]
        if T1.size > P.shape[0]:
            rows = [np.asarray(fn(t0, float(t1), P[0]), dtype=float) for t1 in T1]
        width = max((r.size for r in rows), default=0)
        TS = np.full((len(rows), width), np.inf)
        for i, r in enumerate(rows):
            TS[i, : r.size] = r
        return TS
    if save_at.ts is None:
        return np.empty((1, 0))
    TS = np.asarray(save_at.ts, dtype=float)
    if TS.ndim == 1:
        TS = TS[None, :]
    if TS.ndim != 2:
        raise ValueError(f"SaveAt.ts must be 1-D or 2-D, got shape {TS.shape}")
    finite = np.where(np.isfinite(TS), TS, np.nan)
    if np.any(np.diff(TS, axis=1)[np.isfinite(np.diff(TS, axis=1))] < 0) or np.any(np.isnan(TS)):
        raise ValueError("SaveAt.ts must be increasing and contain no NaN")
    if np.nanmin(finite, initial=t0) < t0 or np.any(finite > T1.max()):
        raise ValueError(f"SaveAt.ts must lie within the time span [{t0}, {T1.max()}]")
    return np.ascontiguousarray(TS)


@contextlib.contextmanager
def _threads(n: int | None):
    if n is None:
        yield
        return
    import numba

    old = numba.get_num_threads()
    numba.set_num_threads(max(1, min(int(n), numba.config.NUMBA_NUM_THREADS)))
    try:
        yield
    finally:
        numba.set_num_threads(old)


def solve_ensemble(
    model: Any,
    y0: Any,
    t_span: tuple[float, Any],
    *,
    params: Any = None,
    save_at: SaveAt = SaveAt(),
    control: StepControl = StepControl(),
    events: Sequence[Event] | None = None,
    max_events_recorded: int = 0,
    threads: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    lanes: int | Literal["auto"] | None = "auto",
    backend: Any = "auto",
) -> EnsembleSolution:
    """Integrate many trajectories of one model in one compiled, parallel call.

    Parameters
    ----------
    model : model object or Kernels
        Provides ``kernels`` and ``to_array()`` (see :mod:`rotorlab.models._base`).
    y0 : array_like, shape (n_state,) or (N, n_state)
        Initial states; one row is shared by all trajectories.
    t_span : (t0, t1)
        Start time and end time (s); ``t1`` may be an array of shape (N,) (one per trajectory).
    params : array_like, shape (n_param,) or (N, n_param), optional
        Packed parameter vectors; default ``model.to_array()``.
    save_at : SaveAt
    control : StepControl
    events : sequence of Event, optional
        Active events and their actions; ``None`` uses the model's defaults, ``[]`` disables all.
    max_events_recorded : int
        How many event times to keep per trajectory (counts are always kept).
    threads : int, optional
        Number of threads (default: numba's); ``1`` runs serially. Results do not depend on it.
    chunk_size : int, optional
        Integrate in chunks of this many trajectories (results do not depend on it); with
        ``progress`` the callback is called after each chunk as ``progress(done, total)``.
    backend : "auto", "scalar", "lanes", Lanes or Scalar
        Where the ensemble runs (:mod:`rotorlab.integrate._backends`). ``Lanes(width)`` steps
        ``width`` trajectories together per thread in SIMD lanes (8 suits AVX2 and AVX-512): the
        same numbers as the scalar driver, several times faster when the model's ``rhs``
        vectorises (see :mod:`rotorlab.integrate._lanes`, "Lane-friendly kernels"); events,
        reset maps and modes included. ``Scalar()``: one trajectory per thread at a time (the
        reference). ``"auto"`` (default): ``Lanes(8)`` when there are several trajectories,
        else ``Scalar()``.
    lanes : int, "auto" or None
        The older spelling of ``backend``: ``lanes=8`` is ``backend=Lanes(8)``, ``lanes=None``
        is ``backend=Scalar()``; give one of the two.

    Returns
    -------
    EnsembleSolution

    Examples
    --------
    >>> import numpy as np
    >>> from rotorlab.integrate import solve_ensemble, SaveAt, StepControl
    >>> from rotorlab.models.examples import HarmonicOscillator
    >>> osc = HarmonicOscillator(frequency=2.0)
    >>> sol = solve_ensemble(osc, [[1.0, 0.0], [0.0, 1.0]], (0.0, np.pi),
    ...                      control=StepControl(rtol=1e-10, atol=1e-12))
    >>> np.round(sol.y_final, 8) + 0.0
    array([[1., 0.],
           [0., 1.]])
    """
    from rotorlab.integrate._backends import resolve_backend
    from rotorlab.integrate._driver_args import EventTable, Inputs, Outputs, Settings

    kernels = _kernels_of(model)
    n = kernels.n_state
    Y0 = _as_2d(y0, n, "y0")
    if params is None:
        if not hasattr(model, "to_array"):
            raise ValueError("params must be given when model is a bare Kernels bundle")
        params = model.to_array()
    P = _as_2d(params, np.asarray(params).shape[-1], "params")
    t0 = float(t_span[0])
    T1 = np.atleast_1d(np.asarray(t_span[1], dtype=float)).ravel()
    if not math.isfinite(t0) or not np.all(np.isfinite(T1)) or np.any(T1 <= t0):
        raise ValueError(f"t_span must be (t0, t1) with finite t1 > t0, got {t_span!r}")
    sizes = {a.shape[0] for a in (Y0, P) if a.shape[0] > 1} | ({T1.size} if T1.size > 1 else set())
    if len(sizes) > 1:
        raise ValueError(f"y0, params and t1 disagree on the number of trajectories: {sorted(sizes)}")
    N = sizes.pop() if sizes else 1
    chosen = resolve_backend(backend, lanes, kernels, N)
    TS = _save_grid(save_at, model, t0, T1, P)
    if TS.shape[0] not in (1, N):
        raise ValueError(f"per-trajectory save times must have {N} rows, got {TS.shape[0]}")
    atol = np.broadcast_to(np.asarray(control.atol, dtype=float), (n,)).copy() if np.size(control.atol) in (1, n) else None
    if atol is None:
        raise ValueError(f"atol must be a scalar or have {n} entries, got {np.size(control.atol)}")
    n_ev, names, ev_dir, ev_act = _event_tables(kernels.event_specs, events)
    n_cont = n - kernels.n_discrete
    n_save = TS.shape[1]
    max_rec = max(0, int(max_events_recorded))

    from rotorlab._memory import check_memory

    check_memory(8.0 * N * n * (n_save + 4), f"{N} trajectories x {n_save} saved states x {n} state entries",
                 "save fewer states (n_save) or integrate fewer trajectories")  # fmt: skip
    YS = np.full((N, n_save, n), np.nan)
    YF = np.empty((N, n))
    STATUS = np.empty(N, dtype=np.int64)
    TEND = np.empty(N)
    EVC = np.zeros((N, max(n_ev, 1)), dtype=np.int64)
    RECT = np.full((N, max_rec), np.nan)
    RECK = np.full((N, max_rec), -1, dtype=np.int64)
    STATS = np.zeros((N, 4), dtype=np.int64)
    first_step = -1.0 if control.first_step is None else float(control.first_step)
    run = chosen.driver(kernels, serial=threads == 1)
    settings = Settings(
        t0, float(control.rtol), n_cont, first_step, float(control.max_step), int(control.max_steps)
    )
    event_table = EventTable(n_ev, ev_dir, ev_act)
    step = N if chunk_size is None else max(1, int(chunk_size))

    def sl(a: np.ndarray, lo: int, hi: int) -> np.ndarray:
        return a if a.shape[0] == 1 else a[lo:hi]

    import numba

    with _threads(threads):
        n_threads = numba.get_num_threads()
        for lo in range(0, N, step):
            hi = min(N, lo + step)
            run(
                Inputs(sl(Y0, lo, hi), sl(P, lo, hi), sl(T1, lo, hi), sl(TS, lo, hi), atol),
                settings,
                event_table,
                Outputs(
                    YS[lo:hi], YF[lo:hi], STATUS[lo:hi], TEND[lo:hi], EVC[lo:hi], RECT[lo:hi],
                    RECK[lo:hi], STATS[lo:hi],
                ),
                n_threads,
            )
            if progress is not None:
                progress(hi, N)
    notes = sanity_check(model, n_cont, YS, YF, TEND, STATUS, P)
    state_names = tuple(getattr(model, "state_names", tuple(f"y{i}" for i in range(n))))
    return EnsembleSolution(
        ts=TS[0] if TS.shape[0] == 1 else TS,
        ys=YS,
        t_final=TEND,
        y_final=YF,
        status=STATUS,
        stats=STATS,
        event_counts=EVC[:, :n_ev],
        event_times=RECT,
        event_index=RECK,
        event_names=names,
        state_names=state_names,
        notes=notes,
        driver=chosen.name,
    )


def solve(
    model: Any,
    y0: Any,
    t_span: tuple[float, float],
    *,
    params: Any = None,
    save_at: SaveAt = SaveAt(),
    control: StepControl = StepControl(),
    events: Sequence[Event] | None = None,
    max_events_recorded: int = 10_000,
) -> Solution:
    """Integrate one trajectory (see :func:`solve_ensemble` for the parameters).

    Examples
    --------
    >>> import numpy as np
    >>> from rotorlab.integrate import solve, SaveAt, StepControl
    >>> from rotorlab.models.examples import HarmonicOscillator
    >>> sol = solve(HarmonicOscillator(frequency=1.0), [1.0, 0.0], (0.0, 2 * np.pi),
    ...             save_at=SaveAt(ts=[np.pi]), control=StepControl(rtol=1e-10, atol=1e-12))
    >>> round(float(sol.ys[0, 0]), 8), sol.status.name
    (-1.0, 'SUCCESS')
    """
    y0 = np.asarray(y0, dtype=float)
    if y0.ndim != 1:
        raise ValueError(f"y0 must be one state vector, shape (n_state,), got {y0.shape}")
    if params is not None and np.asarray(params).ndim != 1:
        raise ValueError("params must be one parameter vector for solve(); use solve_ensemble")
    ens = solve_ensemble(
        model, y0, t_span, params=params, save_at=save_at, control=control, events=events,
        max_events_recorded=max_events_recorded, threads=1,
    )  # fmt: skip
    return ens.trajectory(0)

