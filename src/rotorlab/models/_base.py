"""The kernel contract every model implements, and what the integrator needs of a model.

A *model* is a frozen Python object (parameters in SI units) that hands the integrator a
:class:`Kernels` bundle of compiled functions plus a packed parameter vector. The integrator never
sees anything else of the model: no Python objects, no closures, no global state.

For implementers
----------------
1. Write the right-hand side as a module-level ``@njit(cache=True, nogil=True)`` function
   ``rhs(t, y, p, out) -> None``: ``t`` float (s), ``y`` float64 state, shape (n_state,), ``p``
   float64 parameters, shape (n_param,), ``out`` float64, shape (n_state,), to be filled with
   dy/dt. It must not allocate and must not close over parameters: everything it needs is in ``p``.
2. Discrete (piecewise-constant) states, such as a contact or stick/slip mode, go at the *end* of
   ``y``; their derivative is zero and they are changed only by reset maps. Declare how many with
   ``n_discrete``: the integrator leaves them out of the error norm.
3. If the model has events (impacts, stick/slip transitions, lift-off), write
   ``events(t, y, p, g) -> None`` filling ``g`` (shape (n_events,)) with the event functions, and
   ``reset(k, t, y, p, y_new) -> int`` that writes the state just after event ``k`` into ``y_new``
   and returns 0 to continue or 1 to stop the trajectory. Both are module-level compiled functions
   so that numba can cache the integrator specialised on them. Models without events use
   :func:`no_events` and :func:`no_reset`.
4. Describe the events in ``event_specs`` (:class:`EventSpec`: name, direction, action). The user
   selects or changes them through :class:`rotorlab.integrate.Event` objects.
5. Provide ``to_array()`` (the packed parameter vector, order documented and tested),
   ``state_names`` and, where it has a meaning, ``energy`` and ``linearize``.
6. Optionally, a sanity monitor: a method ``impossible_states(ys, y_final, t_final, params) ->
   sequence of str`` that receives the saved states (shape (N, n_save, n_state), NaN after a
   trajectory ended), the final states (N, n_state), the end times (N,) and the packed
   parameters (N or 1 rows; read the model's numbers from them, not from ``self``, because an
   ensemble may stack the parameters of several variants) and returns, per trajectory, an empty
   string or a message naming a physically impossible state with its numbers (a penetration
   beyond the clearance, an energy above what the sources can supply). The integrator calls it
   in Python after every compiled call and marks those trajectories
   :attr:`rotorlab.integrate.Status.IMPOSSIBLE` (a failure, never a success); non-finite and
   absurdly large states are checked for every model without it.
7. Make ``rhs`` lane-friendly (see "Lane-friendly kernels" in :mod:`rotorlab.integrate._lanes`:
   :func:`rotorlab._kernels._vmath.sincos` instead of ``math.sin``/``cos``, sizes such as the
   ball count from ``y.shape[0]``, which the lane driver makes a compile-time constant, no
   library calls, ``error_model="numpy"`` when a discarded arm may divide by zero) and declare
   it with ``Kernels(..., vectorises=True)``. Every ensemble runs on the lane driver by default
   (same numbers as the scalar driver, events included); a lane-friendly kernel makes it fast. ``tests/unit/test_vectorise.py`` asserts that every
   kernel so declared vectorises, inlined into the lane driver's step loop (the default) or
   called, as ``Kernels(inline_lanes=...)`` says; set it False only for a kernel that no longer
   vectorises inlined (the large generated machine kernels).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, Protocol, runtime_checkable

import numpy as np
from numba import njit

__all__ = [
    "EventSpec",
    "Kernels",
    "AbstractModel",
    "no_events",
    "no_rhs",
    "no_reset",
]

EventAction = Literal["reset", "stop", "count"]


@njit(cache=True, nogil=True)
def no_rhs(t, y, p, out):  # pragma: no cover - compiled
    """Placeholder right-hand side (zero derivative) bound in the integrator's template module."""
    for i in range(y.shape[0]):
        out[i] = 0.0


@njit(cache=True, nogil=True)
def no_events(t, y, p, g):  # pragma: no cover - compiled
    """Event kernel of a model without events (``n_events = 0``)."""
    return None


@njit(cache=True, nogil=True)
def no_reset(k, t, y, p, y_new):  # pragma: no cover - compiled
    """Reset kernel of a model without events: copy the state, continue."""
    for i in range(y.shape[0]):
        y_new[i] = y[i]
    return 0


@dataclass(frozen=True, slots=True)
class EventSpec:
    """One event function of a model.

    Parameters
    ----------
    name : str
        Identifier used in results and in :class:`rotorlab.integrate.Event`.
    direction : int
        -1: only zero crossings from positive to negative trigger; +1: only negative to positive;
        0: both.
    action : {"reset", "stop", "count"}
        ``"reset"``: apply the model's reset map and continue; ``"stop"``: end the trajectory
        (status ``EVENT_STOP``) at the event; ``"count"``: only record it.
    """

    name: str
    direction: int = 0
    action: EventAction = "reset"

    def __post_init__(self) -> None:
        if self.direction not in (-1, 0, 1):
            raise ValueError(f"direction must be -1, 0 or +1, got {self.direction!r}")
        if self.action not in ("reset", "stop", "count"):
            raise ValueError(f"action must be 'reset', 'stop' or 'count', got {self.action!r}")


@dataclass(frozen=True, slots=True)
class Kernels:
    """The compiled functions and sizes the integrator needs of a model.

    Parameters
    ----------
    rhs : numba dispatcher
        ``rhs(t, y, p, out)``, see the module docstring.
    n_state : int
        Length of the state vector, discrete states included.
    n_discrete : int
        Number of trailing piecewise-constant states (excluded from error control).
    events : numba dispatcher
        ``events(t, y, p, g)``; :func:`no_events` if the model has none.
    reset : numba dispatcher
        ``reset(k, t, y, p, y_new) -> int``; :func:`no_reset` if the model has none.
    event_specs : tuple of EventSpec
        One per event function, in the order ``events`` fills ``g``.
    vectorises : bool
        True if ``rhs`` is lane-friendly (vectorised by the lane driver, checked by the tests).
    inline_lanes : bool
        True (the default): the lane driver inlines its loop over lanes that calls ``rhs`` into
        its step loop (faster: the kernel's constants stay in registers across the stages).
        False keeps it a call, for kernels that LLVM no longer vectorises inlined (the machine's
        generated kernels, with hundreds of parameter loads); ``tests/unit/test_vectorise.py``
        checks each kernel as its driver compiles it. Same results either way, bit for bit.
    """

    rhs: Any
    n_state: int
    n_discrete: int = 0
    events: Any = no_events
    reset: Any = no_reset
    event_specs: tuple[EventSpec, ...] = ()
    vectorises: bool = False
    inline_lanes: bool = True

    def __post_init__(self) -> None:
        if self.n_state < 1:
            raise ValueError(f"n_state must be >= 1, got {self.n_state}")
        if not 0 <= self.n_discrete < self.n_state:
            raise ValueError(
                f"n_discrete must be in [0, n_state), got {self.n_discrete} for n_state={self.n_state}"
            )

    @property
    def n_events(self) -> int:
        """Number of event functions."""
        return len(self.event_specs)


@runtime_checkable
class AbstractModel(Protocol):
    """What :func:`rotorlab.integrate.solve` needs of a model object.

    For implementers
    ----------------
    1. ``kernels`` returns a :class:`Kernels` (the same object every call).
    2. ``to_array()`` returns the packed float64 parameter vector.
    3. ``state_names`` names each entry of the state vector, in order.
    """

    @property
    def kernels(self) -> Kernels: ...

    @property
    def state_names(self) -> tuple[str, ...]: ...

    def to_array(self) -> np.ndarray: ...
