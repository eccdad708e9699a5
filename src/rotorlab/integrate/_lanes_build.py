"""Build the per-model compiled copies of the lane driver (:mod:`rotorlab.integrate._lanes`, the
template) and run them with the signature of the scalar drivers.

The template holds only compiled code; this module writes a copy of it per model, lane width and
state size (the ``# @kernel``, ``# @lanes`` and ``# @n_state`` lines replaced) next to the scalar
drivers of :mod:`rotorlab.integrate._specialize`, imports it and reuses numba's on-disk cache.
"""

from __future__ import annotations

import numpy as np

__all__ = ["lane_driver", "is_vectorised", "lane_drivers_for"]


_LOADED: dict = {}
_ACT_OFF = 3  # rotorlab.integrate._core.ACT_OFF


def lane_driver(kernels, lanes, n_ev, ev_act, serial):
    """Return a function with the signature of the scalar drivers that runs the lane driver.

    Parameters
    ----------
    kernels : Kernels
    lanes : int
        Trajectories per thread stepped together, 2 to 64; best a multiple of the SIMD width in
        doubles (4 with AVX2, 8 with AVX-512). 8 is a good choice on both.
    n_ev : int
    ev_act : int64 array
        Event actions (all must be "off": the lane driver does not locate events).
    serial : bool
        Run on the calling thread.

    Raises
    ------
    ValueError
        If ``lanes`` is out of range or an event is active.
    """
    import numba

    if isinstance(lanes, bool) or not isinstance(lanes, (int, np.integer)) or not 2 <= lanes <= 64:
        raise ValueError(f"lanes must be an integer in [2, 64] or None, got {lanes!r}")
    if n_ev > 0 and np.any(np.asarray(ev_act) != _ACT_OFF):
        raise ValueError(
            "lanes= runs without event location; this model has active events: pass events=[] "
            "to switch them off, or lanes=None to use the scalar driver"
        )
    width = int(lanes)
    parallel, single = lane_drivers_for(kernels, width)

    def run(
        n_ev, Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, ev_dir,
        ev_act, YS, YF, STATUS, TEND, EVC, RECT, RECK, STATS,
    ):  # fmt: skip
        drv = single if serial else parallel
        drv(
            Y0, P, t0, T1, TS, rtol, atol, n_cont, first_step, max_step, max_steps, width,
            YS, YF, STATUS, TEND, STATS, numba.get_num_threads(),
        )  # fmt: skip

    return run


def is_vectorised(kernels, lanes=8):
    """Report whether LLVM vectorises the model's ``rhs`` across ``lanes`` lanes on this CPU.

    Compiles (without caching, a few seconds) the loop over lanes that the lane driver runs for
    each stage and inspects its optimised LLVM IR.

    Parameters
    ----------
    kernels : Kernels
    lanes : int

    Returns
    -------
    bool
        True if the loop body is SIMD code (several lanes per instruction) without scalar calls
        of mathematical library functions (``math.sin`` and the like, which LLVM can only call
        one lane at a time).
    """
    import re

    from numba import typeof

    ns = _namespace(kernels, lanes, {})
    probe = ns["_probe"]
    W = np.zeros(ns["_W_SIZE"])
    PL = np.zeros(lanes)
    probe.compile((typeof(W), typeof(PL), typeof(lanes)))
    ir = probe.inspect_llvm(probe.signatures[0])
    # the compiled loop (in _rhs_lanes, or inlined into _probe), not the CPython wrappers
    body = "\n".join(
        f for f in re.split(r"^define ", ir, flags=re.M)
        if re.match(r"[^(]*@_ZN[^(]*(_probe|_rhs_lanes)", f)
    )
    packed = re.findall(r"= f(?:mul|add|sub|div) (?:[a-z]+ )*<\d+ x double>", body)
    libm = re.findall(
        r"call [^@\n]*@(?:llvm\.)?(?:sin|cos|sincos|tan|pow|exp|exp2|log|log2|log10|atan2?|asin|acos"
        r"|sinh|cosh|tanh|expm1|log1p|cbrt|hypot)\b",
        body,
    )
    return len(packed) >= 20 and not libm


def _namespace(kernels, width, namespace):
    """Execute the template's source with ``rhs`` bound to the kernel, without on-disk caching."""
    lines = _source(width, kernels.n_state)
    source = "\n".join(ln for ln in lines if not ln.rstrip().endswith("# @kernel"))
    namespace.update({"rhs": kernels.rhs, "__name__": "_rotorlab_lanes_uncached"})
    exec(compile(source.replace("cache=True", "cache=False"), "<rotorlab lane driver>", "exec"), namespace)  # noqa: S102
    return namespace


def _source(width, n_state):
    """The template's (:mod:`rotorlab.integrate._lanes`) source with ``LANES = width`` and
    ``N_STATE = n_state``."""
    import inspect
    from pathlib import Path

    from rotorlab.integrate import _lanes

    lines = Path(inspect.getsourcefile(_lanes)).read_text().splitlines()
    for mark, value in (("# @lanes", f"LANES = {int(width)}"), ("# @n_state", f"N_STATE = {int(n_state)}")):
        marked = [i for i, line in enumerate(lines) if line.rstrip().endswith(mark)]
        if len(marked) != 1:
            raise RuntimeError(f"rotorlab.integrate._lanes must have exactly one '{mark}' line")
        lines[marked[0]] = f"{value}  {mark}"
    return lines


def lane_drivers_for(kernels, width=8):
    """Return ``(parallel, serial)`` lane drivers of ``width`` lanes for the model's ``rhs``.

    Both take the arguments of :func:`rotorlab.integrate._lanes.integrate_lanes`. The copy of the
    template :mod:`rotorlab.integrate._lanes` with the
    ``# @kernel`` line importing the model's ``rhs`` and ``LANES = width`` is written next to the
    scalar drivers of :mod:`rotorlab.integrate._specialize` (same cache directory and pruning);
    kernels that are not importable module-level functions are compiled without on-disk caching.
    """
    import importlib.util
    import os
    import sys
    import tempfile

    from rotorlab.integrate import _specialize as spec

    name = spec._importable_name(kernels.rhs)
    if name is None:
        return _uncached(kernels, width)
    key = (f"{name[0]}.{name[1]}", width, kernels.n_state)
    if key in _LOADED:
        return _LOADED[key]
    directory = spec._cache_dir()
    if directory is None:
        return _uncached(kernels, width)
    mod, fn = name
    deps = [mod, "rotorlab.integrate._lanes", "rotorlab.integrate._core", "rotorlab.integrate._tableau"]
    deps += _kernel_dependencies(mod)
    digest = spec._source_hash(deps)
    stem = f"lanes{width}n{kernels.n_state}_{mod.rsplit('.', 1)[-1]}_{fn}_{digest}"
    path = directory / f"{stem}.py"
    if not path.exists():
        spec._prune(directory, stem.rsplit("_", 1)[0])
        lines = _source(width, kernels.n_state)
        marked = [i for i, line in enumerate(lines) if line.rstrip().endswith("# @kernel")]
        if len(marked) != 1:
            raise RuntimeError("rotorlab.integrate._lanes must have exactly one '# @kernel' line")
        lines[marked[0]] = f"from {mod} import {fn} as rhs  # @kernel"
        header = "# Generated by rotorlab.integrate._lanes from _lanes.py; do not edit.\n"
        fd, tmp = tempfile.mkstemp(dir=directory, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(header + "\n".join(lines) + "\n")
        os.replace(tmp, path)
    spec.announce_compile(directory, stem, f"{width}-lane integrator for {mod.rsplit('.', 1)[-1]}")
    mod_name = f"_rotorlab_lanes_{stem}"
    module_spec = importlib.util.spec_from_file_location(mod_name, path)
    module = importlib.util.module_from_spec(module_spec)
    sys.modules[mod_name] = module
    module_spec.loader.exec_module(module)
    _LOADED[key] = (module.integrate_lanes, module.integrate_lanes_serial)
    return _LOADED[key]


def _kernel_dependencies(mod):
    """Modules of the compiled functions a kernel module uses (numba's cache does not see them)."""
    import importlib

    found = []
    for obj in vars(importlib.import_module(mod)).values():
        py_func = getattr(obj, "py_func", None)
        if py_func is not None and py_func.__module__ not in (mod, "__main__"):
            found.append(py_func.__module__)
    return sorted(set(found))


def _uncached(kernels, width):
    """Compile the lane driver with the kernel bound directly, without on-disk caching."""
    key = (id(kernels.rhs), width, kernels.n_state)
    if key not in _LOADED:
        ns = _namespace(kernels, width, {})
        _LOADED[key] = (kernels.rhs, ns["integrate_lanes"], ns["integrate_lanes_serial"])
    return _LOADED[key][1:]
