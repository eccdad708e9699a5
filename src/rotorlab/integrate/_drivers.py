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

import numpy as np

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
    toroidal ball's basin, so every model keeps 8 (one compiled driver per model)."""
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
    """
    if lanes is None:
        ns = build("rotorlab.integrate._core", _roles(kernels))
        return ns["integrate_serial" if serial else "integrate_ensemble"]
    ns = build("rotorlab.integrate._lanes", _roles(kernels), _lane_consts(kernels, lanes))
    return ns["integrate_lanes_serial" if serial else "integrate_lanes"]


def _lane_consts(kernels, lanes):
    """The compile-time constants of the lane driver's copy for these kernels."""
    return {"LANES": int(lanes), "N_STATE": kernels.n_state, "INLINE_RHS": int(bool(kernels.inline_lanes))}


def is_vectorised(kernels, lanes=None):
    """Report whether LLVM vectorises the model's ``rhs`` across ``lanes`` lanes on this CPU.

    Compiles (without caching, a few seconds) the loop over lanes that the lane driver runs for
    each stage, inlined or called as the driver does it (``Kernels.inline_lanes``), and inspects
    its optimised LLVM IR.

    Parameters
    ----------
    kernels : Kernels
    lanes : int, optional
        Lane width; default the one the driver chooses for an ensemble (:func:`default_lanes`).

    Returns
    -------
    bool
        True if the loop body is SIMD code (several lanes per instruction) without scalar calls
        of mathematical library functions (``math.sin`` and the like, which LLVM can only call
        one lane at a time).
    """
    import re

    from numba import typeof

    from rotorlab.integrate._codegen import _in_memory

    lanes = default_lanes(kernels, 2) if lanes is None else lanes
    ns = _in_memory("rotorlab.integrate._lanes", _roles(kernels), _lane_consts(kernels, lanes))
    # A called _rhs_lanes is compiled on its own, and the worker runs that machine code in the
    # process that compiled it (its copy linked into _probe or the worker is optimised again and
    # may vectorise where the original does not): inspect the original.
    probe = ns["_probe"] if kernels.inline_lanes else ns["_rhs_lanes"]
    W = np.zeros(ns["_W_SIZE"] + lanes)
    probe.compile((typeof(W), typeof(lanes)))
    ir = probe.inspect_llvm(probe.signatures[0])
    # the compiled loop (in _rhs_lanes, or inlined into _probe), not the CPython wrappers; the
    # return attributes before the name may hold parentheses (``range(i32 -1, -2)``)
    body = "\n".join(
        f for f in re.split(r"^define ", ir, flags=re.M)
        if re.match(r"[^@\n]*@_ZN(?!7cpython)[^(\n]*(_probe|_rhs_lanes)", f)
    )
    packed = re.findall(r"= f(?:mul|add|sub|div) (?:[a-z]+ )*<\d+ x double>", body)
    libm = re.findall(
        r"call [^@\n]*@(?:llvm\.)?(?:sin|cos|sincos|tan|pow|exp|exp2|log|log2|log10|atan2?|asin|acos"
        r"|sinh|cosh|tanh|expm1|log1p|cbrt|hypot)\b",
        body,
    )
    return len(packed) >= 20 and not libm
