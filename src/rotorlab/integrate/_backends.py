"""Where an ensemble runs: the backend value of :func:`rotorlab.integrate.solve_ensemble`.

A backend turns a model's :class:`~rotorlab.models.Kernels` into a compiled driver callable as
``run(inputs, settings, event_table, outputs, n_threads)`` with the argument groups of
:mod:`rotorlab.integrate._driver_args`; :func:`solve_ensemble` validates the inputs, allocates
the outputs, cuts the ensemble into chunks and runs the sanity monitor the same way whatever the
backend. Two backends exist, both on the CPU:

- :class:`Scalar`: one trajectory per thread at a time (the template
  :mod:`rotorlab.integrate._core`); the reference every other backend matches.
- :class:`Lanes`: ``width`` trajectories per thread stepped together in SIMD lanes (the template
  :mod:`rotorlab.integrate._lanes`), bit for bit the scalar driver's numbers.

``backend="auto"`` (the default) takes ``Lanes(8)`` for an ensemble and ``Scalar()`` for one
trajectory (:func:`rotorlab.integrate._drivers.default_lanes`).

For implementers (a new backend, e.g. a GPU one, is one module):

1. Write a frozen dataclass with a ``name`` (the :attr:`EnsembleSolution.driver` label it
   reports) and ``driver(kernels, serial) -> run`` returning a callable with the signature
   above that fills the output arrays in place (device copies are the backend's own business)
   and gives each trajectory the same status codes as the scalar driver.
2. Register it with :func:`register_backend` so that ``backend="<name>"`` selects it.
3. Test it against :class:`Scalar` on the models of ``tests/unit/test_lanes_events.py`` (events,
   resets and modes included); a backend that is not bit-identical says by how much it differs
   and why in its docstring.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from rotorlab.integrate import _drivers

__all__ = ["Backend", "Scalar", "Lanes", "BACKENDS", "register_backend", "resolve_backend"]


class Backend(Protocol):
    """What :func:`rotorlab.integrate.solve_ensemble` needs of a backend."""

    name: str

    def driver(self, kernels: Any, serial: bool) -> Callable[..., None]: ...


@dataclass(frozen=True, slots=True)
class Scalar:
    """The scalar driver: one trajectory per thread at a time (the reference)."""

    @property
    def name(self) -> str:
        return "scalar"

    def driver(self, kernels: Any, serial: bool) -> Callable[..., None]:
        return _drivers.driver(kernels, None, serial)


@dataclass(frozen=True, slots=True)
class Lanes:
    """The lane driver: ``width`` trajectories per thread stepped together in SIMD lanes.

    Parameters
    ----------
    width : int
        Lanes per thread, in [2, 64]; 8 (the default) suits AVX2 and AVX-512.

    Raises
    ------
    ValueError
        If ``width`` is not an integer in [2, 64].
    """

    width: int = _drivers.DEFAULT_LANES

    def __post_init__(self) -> None:
        _drivers.check_lanes(self.width)

    @property
    def name(self) -> str:
        return f"lanes{int(self.width)}"

    def driver(self, kernels: Any, serial: bool) -> Callable[..., None]:
        return _drivers.driver(kernels, int(self.width), serial)


#: Backends selectable by name (``backend="scalar"``, ``backend="lanes"``: its default width).
BACKENDS: dict[str, Callable[[], Backend]] = {"scalar": Scalar, "lanes": Lanes}


def register_backend(name: str, factory: Callable[[], Backend]) -> None:
    """Make ``backend=name`` select ``factory()`` in :func:`rotorlab.integrate.solve_ensemble`."""
    if name == "auto" or not name.isidentifier():
        raise ValueError(f"a backend name must be an identifier other than 'auto', got {name!r}")
    BACKENDS[name] = factory


def resolve_backend(backend: Any, lanes: Any, kernels: Any, n_traj: int) -> Backend:
    """The backend an ensemble of ``n_traj`` trajectories runs on.

    Parameters
    ----------
    backend : Backend, str
        A backend value, a name of :data:`BACKENDS`, or ``"auto"``: :class:`Lanes` for an
        ensemble, :class:`Scalar` for one trajectory.
    lanes : int, "auto" or None
        The older spelling (``lanes=8`` is ``Lanes(8)``, ``lanes=None`` is ``Scalar()``); only
        read when ``backend`` is ``"auto"``.

    Raises
    ------
    ValueError
        An unknown backend name, a bad lane width, or ``backend`` and ``lanes`` both given.
    """
    if isinstance(backend, str):
        if backend != "auto":
            if lanes != "auto":
                raise ValueError(f"give backend= or lanes=, not both (backend={backend!r}, lanes={lanes!r})")
            if backend not in BACKENDS:
                raise ValueError(
                    f"unknown backend {backend!r}; known: 'auto', {', '.join(repr(k) for k in BACKENDS)}"
                )
            return BACKENDS[backend]()
        if isinstance(lanes, str) and lanes == "auto":
            width = _drivers.default_lanes(kernels, n_traj)
            return Scalar() if width is None else Lanes(width)
        return Scalar() if lanes is None else Lanes(lanes)
    if lanes != "auto":
        raise ValueError(f"give backend= or lanes=, not both (backend={backend!r}, lanes={lanes!r})")
    if not callable(getattr(backend, "driver", None)) or not isinstance(getattr(backend, "name", None), str):
        raise TypeError(
            f"backend must be 'auto', a name of {sorted(BACKENDS)} or a backend value such as "
            f"Lanes(8) or Scalar(), got {backend!r}"
        )
    return backend
