"""Which compiled driver runs an ensemble, and whether a model's kernel vectorises in lanes.

Two driver templates, one generator (:mod:`rotorlab.integrate._codegen`):

- :mod:`rotorlab.integrate._core`, the scalar driver: one trajectory per thread at a time, events
  and reset maps; the reference.
- :mod:`rotorlab.integrate._lanes`, the lane driver: ``lanes`` trajectories per thread stepped
  together in SIMD lanes, the same numbers bit for bit.

Both are called as ``driver(inputs, settings, event_table, outputs, n_threads)`` with the groups
of :mod:`rotorlab.integrate._driver_args`.
"""

from __future__ import annotations

import logging
import threading
import time

import numpy as np
from numba import typeof

from rotorlab.integrate._codegen import build

__all__ = ["driver", "check_lanes", "default_lanes", "is_vectorised"]

DEFAULT_LANES = 8  # a multiple of the SIMD width in doubles: 4 (AVX2), 8 (AVX-512)


def default_lanes(kernels, n_traj):
    """The lane width ``lanes="auto"`` chooses: :data:`DEFAULT_LANES` for an ensemble (more than
    one trajectory), else None (one trajectory: the scalar driver). Events, resets and modes run
    on lanes too; a kernel that does not vectorise (``Kernels.vectorises`` False) gives the same
    numbers there, at about scalar speed.

    16 lanes (two AVX-512 registers per value) were measured against 8 with the kernel inlined
    (``bench/README.md``, issue 11): the same CPU time on the benchmark kernel and on the
    toroidal ball's basin, so every model keeps 8 (one compiled driver per model).

    One trajectory stays on the scalar driver even for a kernel that vectorises: on 8 lanes it
    ran 0.89-1.27 times the scalar's CPU time, and a lane copy compiles 5-15 CPU-s longer than
    the scalar one, which links the machine's compiled kernel (``bench/README.md``, issue 24,
    session 13): fewer copies only for a model also run as an ensemble."""
    return DEFAULT_LANES if n_traj > 1 else None


def check_lanes(lanes):
    """Validate ``lanes=`` of :func:`rotorlab.integrate.solve_ensemble`.

    Raises
    ------
    ValueError
        If ``lanes`` is not an integer in [2, 64].
    """
    if isinstance(lanes, bool) or not isinstance(lanes, (int, np.integer)) or not 2 <= lanes <= 64:
        raise ValueError(f"lanes must be an integer in [2, 64] or None, got {lanes!r}")


def _roles(kernels):
    """The model's kernels by the role a driver template binds them to."""
    return {"rhs": kernels.rhs, "events": kernels.events, "reset": kernels.reset}


def driver(kernels, lanes, serial):
    """Return the compiled driver for the model's kernels.

    Parameters
    ----------
    kernels : Kernels
    lanes : int or None
        None: the scalar driver; else the lane driver of that width (validated by
        :func:`check_lanes`).
    serial : bool
        Run on the calling thread.

    Returns
    -------
    callable
        ``run(inputs, settings, event_table, outputs, n_threads)``: the copy's worker run on
        ``n_threads`` threads at once (the calling thread and ``n_threads - 1`` Python threads;
        the compiled code releases the GIL), all taking trajectories from one shared counter.
        Threads of Python rather than a numba parallel region: the copy has one compiled entry
        point instead of a parallel one and a serial one, and no parfor lowering (seconds per
        copy; ``bench/README.md``, issue 24), and any threading layer can run it from several
        threads at once.
    """
    if lanes is None:
        ns = build("rotorlab.integrate._core", _roles(kernels), {"EVENTS": _has_events(kernels)})
        return _Threaded(ns, "integrate_worker", 1, serial)
    ns = build("rotorlab.integrate._lanes", _roles(kernels), _lane_consts(kernels, lanes))
    return _Threaded(ns, "integrate_lanes", int(lanes), serial)


class _Threaded:
    """A copy's worker run on several threads that share one trajectory counter (see :func:`driver`)."""

    def __init__(self, ns, name, per_thread, serial):
        self.ns, self.worker, self.per_thread, self.serial = ns, ns[name], per_thread, serial

    def __call__(self, inputs, settings, event_table, outputs, n_threads):
        args = (np.zeros(1, dtype=np.int64), inputs, settings, event_table, outputs)
        compiled(self.ns, self.worker, args)
        units = -(-outputs.STATUS.shape[0] // self.per_thread)
        n = 1 if self.serial else max(1, min(int(n_threads), units))
        errors = []

        def work():
            try:
                self.worker(*args)
            except BaseException as exc:  # noqa: BLE001 - re-raised on the calling thread
                errors.append(exc)

        threads = [threading.Thread(target=work, daemon=True) for _ in range(n - 1)]
        for t in threads:
            t.start()
        work()
        for t in threads:
            t.join()
        if errors:
            raise errors[0]


def compiled(ns, worker, args):
    """Compile (or load from numba's cache) ``worker`` of the copy ``ns`` for ``args`` before the
    threads start; if the copy announced a compile (:func:`rotorlab.integrate._codegen.
    announce_compile`), say when it is done and how long it took."""
    sig = tuple(typeof(a) for a in args)
    if sig in worker.overloads:
        return
    t0 = time.perf_counter()
    worker.compile(sig)
    what = ns.pop("_ANNOUNCED", None)
    if what is not None:
        logging.getLogger("rotorlab.compile").info("compiled the %s in %.0f s", what, time.perf_counter() - t0)


def _lane_consts(kernels, lanes):
    """The compile-time constants of the lane driver's copy for these kernels."""
    return {"LANES": int(lanes), "N_STATE": kernels.n_state, "INLINE_RHS": int(bool(kernels.inline_lanes)),
            "EVENTS": _has_events(kernels)}


def _has_events(kernels):
    """1 if the model has event functions (the copy then compiles the event handling), else 0."""
    return int(len(kernels.event_specs) > 0)


def _rhs_probe(ns, kernels, W, lanes):
    """The loop over lanes of the rhs (inlined into ``_probe``, or called ``_rhs_lanes``)."""
    return (ns["_probe"] if kernels.inline_lanes else ns["_rhs_lanes"]), "_probe|_rhs_lanes", (W, lanes)


def _events_probe(ns, kernels, W, lanes):
    """The loop over the lanes' event functions."""
    return ns["_events_lanes"], "_events_lanes", (W, lanes, lanes, W, lanes, lanes)


#: what ``is_vectorised(function=...)`` compiles and inspects: (probe, its name pattern, example args)
_PROBES = {"rhs": _rhs_probe, "events": _events_probe}


def is_vectorised(kernels, lanes=None, function="rhs"):
    """Report whether LLVM vectorises the model's ``rhs`` (or ``events``) across ``lanes`` lanes
    on this CPU.

    Compiles (without caching, a few seconds) the loop over lanes that the lane driver runs for
    each stage, inlined or called as the driver does it (``Kernels.inline_lanes``), and inspects
    its optimised LLVM IR; with ``function="events"`` the loop over the lanes' event functions
    at the end of every step (compiled on its own).

    Parameters
    ----------
    kernels : Kernels
    lanes : int, optional
        Lane width; default the one the driver chooses for an ensemble (:func:`default_lanes`).
    function : {"rhs", "events"}
        Which of the model's kernels.

    Returns
    -------
    bool
        True if the loop body is SIMD code (several lanes per instruction) without scalar calls
        of mathematical library functions (``math.sin`` and the like, which LLVM can only call
        one lane at a time).
    """
    import re

    from rotorlab.integrate._codegen import _in_memory

    lanes = default_lanes(kernels, 2) if lanes is None else lanes
    ns = _in_memory("rotorlab.integrate._lanes", _roles(kernels), _lane_consts(kernels, lanes))
    # A called _rhs_lanes is compiled on its own, and the worker runs that machine code in the
    # process that compiled it (its copy linked into _probe or the worker is optimised again and
    # may vectorise where the original does not): inspect the original.
    W = np.zeros(ns["_W_SIZE"] + lanes)
    if function not in _PROBES:
        raise ValueError(f"function must be one of {', '.join(map(repr, _PROBES))}, got {function!r}")
    probe, name, args = _PROBES[function](ns, kernels, W, lanes)
    probe.compile(tuple(typeof(a) for a in args))
    ir = probe.inspect_llvm(probe.signatures[0])
    # the compiled loop (in _rhs_lanes, or inlined into _probe), not the CPython wrappers; the
    # return attributes before the name may hold parentheses (``range(i32 -1, -2)``)
    body = "\n".join(
        f for f in re.split(r"^define ", ir, flags=re.M)
        if re.match(rf"[^@\n]*@_ZN(?!7cpython)[^(\n]*({name})", f)
    )
    packed = re.findall(r"= f(?:mul|add|sub|div) (?:[a-z]+ )*<\d+ x double>", body)
    libm = re.findall(
        r"call [^@\n]*@(?:llvm\.)?(?:sin|cos|sincos|tan|pow|exp|exp2|log|log2|log10|atan2?|asin|acos"
        r"|sinh|cosh|tanh|expm1|log1p|cbrt|hypot)\b",
        body,
    )
    return len(packed) >= 20 and not libm
