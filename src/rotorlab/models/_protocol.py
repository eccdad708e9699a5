"""The model protocol: named parameters, variants and the packed parameter vector.

Every model exposes its numbers by name, in the case file's own key-path spelling (the
``[model]`` table's keys, as error messages write them: ``races[0].balls[1].mass``,
``drive.speed``, ``unbalances[0].magnitude``, ``structure.bearings[0].kxx``), each with its SI
unit, its current value, its allowed range and whether it is *structural* (changes the compiled
layout: the kernel's sizes, so a new compile, e.g. ``n_modes``). Analyses that vary a model
(sweeps, basins, continuation, design search) go through this protocol, never through the case
schema: ``model.with_parameters(**{name: value})`` is a new model, ``model.pack(values)`` the
kernel's parameter vector for other values, both without validating a case document.

Examples
--------
>>> from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams
>>> m = JeffcottBalls(RotorParams(1.0, 1e-3, 1e4, 10.0), (BallParams(0.02, 0.05),) * 2,
...                   speed=ConstantSpeed(300.0))
>>> space = m.parameters
>>> space.names[:3]
('disc_mass', 'eccentricity', 'stiffness')
>>> space["balls[1].mass"].unit, space["balls[1].mass"].allowed
('kg', '> 0 kg')
>>> m.with_parameters(**{"balls[1].damping": 0.01, "speed.speed": 250.0}).balls[1].damping
0.01
>>> m.parameters.structural("disc_mass"), float(m.pack({"disc_mass": 2.0})[2])
(False, 2.0)
>>> m.with_parameters(**{"balls[1].mass": -1.0})
Traceback (most recent call last):
...
ValueError: balls[1].mass = -1: must be > 0 kg
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

__all__ = ["Parameter", "ParameterSpace", "AbstractParametrisedModel", "ParametrisedMixin", "Slot",
           "bounds_text"]


def bounds_text(gt: float | None = None, ge: float | None = None, lt: float | None = None,
                le: float | None = None, unit: str = "") -> str:
    """The allowed range in words: ``"> 0 kg"``, ``">= 0 and <= 1"``, ``"any finite number"``.

    Examples
    --------
    >>> bounds_text(gt=0.0, unit="kg"), bounds_text(ge=0.0, le=1.0, unit="1")
    ('> 0 kg', '>= 0 and <= 1')
    """
    parts = [f"{op} {v:g}" for op, v in ((">", gt), (">=", ge), ("<", lt), ("<=", le)) if v is not None]
    if not parts:
        return "any finite number"
    return " and ".join(parts) + (f" {unit}" if unit and unit != "1" else "")


@dataclass(frozen=True, slots=True)
class Parameter:
    """One named number of a model.

    Parameters
    ----------
    name : str
        Key path in the case file's spelling, without ``model.`` (``races[0].balls[1].mass``).
    unit : str
        SI unit (``"1"``: dimensionless).
    value : float
        Current value (SI).
    bounds : (gt, ge, lt, le)
        Open and closed limits (None: none); the same as the case file's key.
    structural : bool
        True when a new value changes the compiled layout (the kernel's sizes): such a name is
        varied with ``with_parameters`` (a new model, a new compile), never with ``pack``.
    """

    name: str
    unit: str
    value: float
    bounds: tuple[float | None, float | None, float | None, float | None] = (None, None, None, None)
    structural: bool = False

    @property
    def allowed(self) -> str:
        """The allowed range in words (with the unit)."""
        return bounds_text(*self.bounds, unit=self.unit)

    def admits(self, value: float) -> bool:
        """Whether ``value`` is finite and within the bounds."""
        gt, ge, lt, le = self.bounds
        return (math.isfinite(value) and (gt is None or value > gt) and (ge is None or value >= ge)
                and (lt is None or value < lt) and (le is None or value <= le))

    def check(self, value: Any) -> float:
        """Return ``value`` as a float, or raise ValueError naming the name, the value and the range."""
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{self.name} = {value!r}: must be {self.allowed}") from None
        if not self.admits(v):
            raise ValueError(f"{self.name} = {v:g}: must be {self.allowed}")
        return v


@dataclass(frozen=True, slots=True)
class Slot:
    """A :class:`Parameter` with how a model takes a new value: ``set(model, value) -> model``."""

    parameter: Parameter
    set: Callable[[Any, float], Any]


class ParameterSpace:
    """The named parameters of one model: names, units, values, ranges, and packing.

    Parameters
    ----------
    model : AbstractParametrisedModel
        The model the values belong to.
    slots : sequence of Slot
        One per name, in order.

    Notes
    -----
    ``pack`` is ``model.with_parameters(...).to_array()`` after refusing structural names and
    checking that the compiled layout stays the same (a value that switches a feature on or off,
    e.g. a ball's Coulomb friction from 0, changes it too): the vector fits the kernel already
    compiled for ``model``.
    """

    def __init__(self, model: Any, slots: Sequence[Slot]) -> None:
        self._model = model
        self._slots = {s.parameter.name: s for s in slots}

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(self._slots)

    @property
    def units(self) -> dict[str, str]:
        """Name -> SI unit."""
        return {n: s.parameter.unit for n, s in self._slots.items()}

    def values(self) -> np.ndarray:
        """Current values (SI), in the order of :attr:`names`."""
        return np.array([s.parameter.value for s in self._slots.values()], dtype=float)

    def __contains__(self, name: object) -> bool:
        return name in self._slots

    def __getitem__(self, name: str) -> Parameter:
        return self._slot(name).parameter

    def __iter__(self):
        return iter(self._slots)

    def __len__(self) -> int:
        return len(self._slots)

    def structural(self, name: str) -> bool:
        """True where a new value of ``name`` changes the compiled layout."""
        return self._slot(name).parameter.structural

    def _slot(self, name: str) -> Slot:
        try:
            return self._slots[name]
        except KeyError:
            shown = ", ".join(list(self._slots)[:8]) + (", ..." if len(self._slots) > 8 else "")
            raise KeyError(f"{name!r} is not a parameter of this {type(self._model).__name__} "
                           f"(its parameters: {shown})") from None

    def check(self, name: str, value: Any) -> float:
        """Return ``value`` of ``name`` as a float, or raise ValueError with the allowed range."""
        return self._slot(name).parameter.check(value)

    def apply(self, values: Mapping[str, Any]) -> Any:
        """The model with ``values`` set (each checked against its range); the model itself for
        no values.

        The values are set together, as a case edited at all those keys at once: a check that
        ties several numbers (a ball's ``inertia >= mass radius^2``) holds for the result, not
        for each step; a value the model refuses at one step is set again after the others, and
        the first refusal is raised only when no value can be set any more.
        """
        model = self._model
        pending = [(slot, slot.parameter.check(value)) for slot, value in
                   ((self._slot(name), value) for name, value in values.items())]
        while pending:
            refused = []
            for slot, value in pending:
                try:
                    model = slot.set(model, value)
                except ValueError as exc:
                    refused.append((slot, value, exc))
            if len(refused) == len(pending):
                raise refused[0][2]
            pending = [(slot, value) for slot, value, _ in refused]
        return model

    def _named(self, values: Mapping[str, Any] | Iterable[float]) -> dict[str, Any]:
        if isinstance(values, Mapping):
            return dict(values)
        arr = np.asarray(values, dtype=float).reshape(-1)
        if arr.size != len(self._slots):
            raise ValueError(f"pack takes {len(self._slots)} values (one per name) or a mapping, got {arr.size}")
        return {n: float(v) for n, v, old in zip(self.names, arr, self.values()) if v != old or not math.isfinite(v)}

    def pack(self, values: Mapping[str, Any] | Iterable[float]) -> np.ndarray:
        """Return the kernel's parameter vector with ``values`` (a mapping name -> value, or one
        value per name in the order of :attr:`names`).

        Raises
        ------
        ValueError
            A structural name, a value out of range, or a value that changes the compiled layout.
        """
        named = self._named(values)
        for name in named:
            if self.structural(name):
                raise ValueError(f"{name} is structural: a new value changes the compiled layout (the "
                                 "kernel's sizes); pack does not take it: build the variant with "
                                 "with_parameters (a new model, compiled for its layout)")
        variant = self.apply(named)
        layout = self._model._compiled_layout()
        if layout is not None and variant._compiled_layout() != layout:
            raise ValueError(f"{', '.join(f'{k} = {v:g}' for k, v in named.items())}: changes the compiled "
                             "layout (a feature switched on or off); vary it with with_parameters")
        return variant.to_array()


@runtime_checkable
class AbstractParametrisedModel(Protocol):
    """What every model offers to the analyses that vary it.

    For implementers
    ----------------
    1. List the model's numbers as :class:`Slot` objects in ``_parameter_slots()``: the name is
       the key path of the model's case-file table (``races[0].balls[1].mass``), the unit SI,
       the bounds those of the case-file key (a test compares them for the built-in cases), and
       ``set(model, value)`` returns a new model (``dataclasses.replace`` on the part that holds
       the number; never a case document).
    2. Mark ``structural=True`` where a new value changes the compiled layout (sizes, features
       compiled in or out); ``pack`` refuses those names.
    3. Inherit :class:`ParametrisedMixin`: it gives ``parameters``, ``with_parameters`` and
       ``pack`` from the slots. ``to_array()`` must be the kernel's parameter vector, and
       ``_compiled_layout()`` return what decides the compiled kernel (a value compared with
       ``==``), so that ``pack`` refuses a value that switches a feature on or off.
    4. A model built from a case (``rotorlab.io``) takes the values the case wrote: its
       ``parameters`` must give back every number with the value the case file converted to SI,
       and ``with_parameters(name=v).to_array()`` must equal the vector of the model built from
       the case edited at that key, bit for bit (``tests/unit/test_parameters.py``).
    """

    @property
    def parameters(self) -> ParameterSpace: ...

    def with_parameters(self, **values: float) -> Any: ...

    def pack(self, values: Mapping[str, Any] | Iterable[float]) -> np.ndarray: ...

    def to_array(self) -> np.ndarray: ...


class ParametrisedMixin:
    """``parameters``, ``with_parameters`` and ``pack`` from the model's ``_parameter_slots()``."""

    __slots__ = ()

    def _compiled_layout(self) -> Any:
        """What decides the compiled kernel (sizes, features), compared by ``pack``; None: nothing."""
        return None

    def _parameter_slots(self) -> list[Slot]:  # pragma: no cover - each model defines it
        raise NotImplementedError

    @property
    def parameters(self) -> ParameterSpace:
        """The model's named parameters (:class:`ParameterSpace`)."""
        return ParameterSpace(self, self._parameter_slots())

    def with_parameters(self, **values: float) -> Any:
        """Return a copy with the named parameters set (names as in :attr:`parameters`).

        Raises
        ------
        KeyError
            A name the model does not have.
        ValueError
            A value outside the parameter's range (the message names both).
        """
        return self.parameters.apply(values)

    def pack(self, values: Mapping[str, Any] | Iterable[float]) -> np.ndarray:
        """The kernel's parameter vector with other values (see :meth:`ParameterSpace.pack`)."""
        return self.parameters.pack(values)
