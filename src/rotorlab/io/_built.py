"""The model a run has built from its case, handed down to everything that runs on the case.

:func:`rotorlab.analyses.run_case` (and the CLI's single-analysis commands) build a case's model
once, with :func:`rotorlab.analyses.build_model`, and run the analyses, the sanity checks, the
verdict facts and the report inside :func:`built_model`. Within it, the builders of a spec
(:func:`rotorlab.analyses.build_model`, every registered ``ModelType.build``,
:func:`rotorlab.io.build_machine`, :func:`rotorlab.io.build_linear_system`) return that model for
that very spec object (``is``, never equality: an edited copy of a spec is another model), so an
analysis never builds the case's model again. A variant (another speed, other races) is derived
from the built model (``with_drive``, ``with_parameters``), never re-built from the spec.

Outside such a block, and for what a case's validation builds before a run starts (whether a
machine has steady motions, its critical speed, a tolerances study's inputs), the builders
remember the model of each spec *object* for as long as that object lives (:func:`built_once`):
validating a case and then running it builds its model once.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

__all__ = ["built_model", "built_once", "handed_down", "handed_down_structure"]

_BUILT: ContextVar[tuple[tuple[Any, Any], ...]] = ContextVar("rotorlab_built_models", default=())
# (id of the spec, builder) -> (weak reference to the spec, its model); an entry leaves with its spec
_ONCE: dict[tuple[int, Any], tuple[weakref.ref, Any]] = {}


@contextmanager
def built_model(spec: Any, model: Any) -> Iterator[Any]:
    """Within the block, building ``spec`` (this object) gives ``model``.

    >>> with built_model(spec := object(), "the model"):
    ...     handed_down(spec), handed_down(object())
    ('the model', None)
    >>> handed_down(spec) is None
    True
    """
    token = _BUILT.set(((spec, model), *_BUILT.get()))
    try:
        yield model
    finally:
        _BUILT.reset(token)


def handed_down(spec: Any, kind: type | None = None) -> Any:
    """The model built from ``spec`` in an enclosing :func:`built_model` (of type ``kind`` when
    given), or None."""
    for s, m in _BUILT.get():
        if s is spec and (kind is None or isinstance(m, kind)):
            return m
    return None


def handed_down_structure(spec: Any) -> Any:
    """The linear system of a handed-down model whose structure table is ``spec`` (a machine's
    ``[model.structure]``), or None."""
    for _, m in _BUILT.get():
        source = getattr(m, "structure_source", None)
        if source is not None and source.spec is spec:
            return source.system
    return None


def built_once(spec: Any, build: Callable[[Any], Any], kind: type | None = None) -> Any:
    """The model of ``spec`` built by ``build``: the run's (:func:`handed_down`), else the one
    ``build`` made before from this very object (``is``: an edited copy is another spec), else
    ``build(spec)``, remembered while ``spec`` lives (specs and models are immutable).

    >>> class Spec: pass
    >>> made = []
    >>> def build(spec):
    ...     made.append(spec)
    ...     return f"model {len(made)}"
    >>> s = Spec()
    >>> built_once(s, build), built_once(s, build), built_once(Spec(), build)
    ('model 1', 'model 1', 'model 2')
    """
    model = handed_down(spec, kind)
    if model is not None:
        return model
    key = (id(spec), build)
    entry = _ONCE.get(key)
    if entry is not None and entry[0]() is spec:
        return entry[1]
    model = build(spec)
    try:
        # the dict is bound now: at interpreter exit the module's globals may already be None
        ref = weakref.ref(spec, lambda _r, key=key, once=_ONCE: once.pop(key, None))
    except TypeError:  # an object without weak references is not remembered
        return model
    _ONCE[key] = (ref, model)
    return model
