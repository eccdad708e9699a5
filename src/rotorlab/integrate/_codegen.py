"""The one generator of per-model compiled drivers (the scalar :mod:`._core` and the lanes :mod:`._lanes`).

Why generated copies
--------------------
A numba function that takes other compiled functions as *arguments* is keyed in numba's on-disk
cache by the dispatcher types, which differ from one process to the next, so it is recompiled
(seconds) in every new process. A function whose arguments are arrays and scalars, and which
reaches the model's kernels as module *globals*, is cached normally. So for each model a driver
template (a module of compiled code) is copied with its marked lines changed and imported:

- ``... import no_rhs as rhs  # @kernel rhs``: imports the model's kernel of that role instead;
- ``LANES = 8  # @const LANES``: a compile-time constant of this copy (lane width, state size);
- ``from rotorlab.integrate._lane_rows import (  # @template``: imports from the copy of that
  sibling template generated for the same model and constants (a template too large for one
  module is split into templates this way; each declares the constants and kernels it uses).

The templates stay the single source of the integrators; the copies are never edited.

The cache key
-------------
The copy's file name carries the model's rhs, a short hash of the names of all its kernels (its
events and reset map too), and a hash of its own text, of the source of **every module the kernels
and the template depend on, transitively** (:func:`rotorlab._codewriter.dependencies`: found through
their import statements and globals; the standard library and installed third-party packages are
left out, the versions of Python, numba, NumPy and llvmlite are hashed instead). Editing e.g.
``rotorlab/_kernels/speed.py`` therefore gives a new file, which numba compiles afresh; the copy
re-compiles the model's kernels from their Python source (``py_func``) rather than linking their
own cached binaries, whose numba cache only watches their own file. A kernel whose module says
``KEYED_BY_SOURCES = True`` (the machine's generated kernel modules, named by a hash of every
source they depend on) is linked as it is by the scalar driver and the lane driver's scalar
evaluations: compiled once, cached with its module, and shared with the Python callers
(:func:`rotorlab.integrate._core._own`). The lane driver also compiles the kernel inlined into its
loop over lanes (that is what vectorises).

Each copy has one compiled entry point, its worker (``integrate_worker``, ``integrate_lanes``),
run on several threads by :func:`rotorlab.integrate._drivers.driver`; a copy for a model without
event functions (``EVENTS = 0``) compiles no event handling.

The key, the byte check, the write and the import are those of every generated module
(:mod:`rotorlab._codewriter`, which writes the machine's kernel modules too): before importing a
cached copy its bytes are compared with the text generated now; a copy that differs (edited,
truncated, corrupted) is rewritten and its numba cache dropped. Copies go only to
the cache directory ``$ROTORLAB_CACHE_DIR/drivers`` (default ``$XDG_CACHE_HOME/rotorlab/drivers``,
``~/.cache/rotorlab/drivers``); if it is not writable the driver is compiled in memory without
caching (a few seconds per process), never written elsewhere. Kernels that are not importable
module-level functions (defined in ``__main__``, closures) are compiled the same way, in memory.
"""

from __future__ import annotations

import hashlib
import importlib
import inspect
import itertools
from pathlib import Path
from typing import Any

import rotorlab._codewriter as _codewriter  # not "from rotorlab import": the copies are keyed on what they import
from rotorlab._compile_cache import BUILD_LOCK, cache_dir, compiling_for

__all__ = ["build", "cache_dir", "announce_compile"]

_LOADED: dict[tuple, tuple[tuple, dict[str, Any]]] = {}
_UNCACHED = itertools.count()  # numbers the modules compiled in memory


def _importable_name(dispatcher: Any) -> tuple[str, str] | None:
    """``(module, name)`` if ``dispatcher`` is reachable as a module-level attribute."""
    py_func = getattr(dispatcher, "py_func", None)
    if py_func is None:
        return None
    mod, name = py_func.__module__, py_func.__qualname__
    if mod == "__main__" or "<" in name or "." in name:
        return None
    try:
        if getattr(importlib.import_module(mod), name) is not dispatcher:
            return None
    except (ImportError, AttributeError):
        return None
    return mod, name


def _template_lines(template: str) -> list[str]:
    path = inspect.getsourcefile(importlib.import_module(template))
    return Path(path).read_text().splitlines()  # type: ignore[arg-type]


# The marks a template's lines may carry, ``# @KIND NAME``: for each kind, what the mark names
# (from the line's code and the mark's NAME) and the line written in the copy for a value.
_MARKS: dict[str, tuple[Any, Any]] = {
    # ``from m import no_rhs as rhs  # @kernel rhs``: the model's kernel of that role
    "kernel": (lambda code, name: name, lambda line, name, v: f"from {v[0]} import {v[1]} as {name}  # @kernel {name}"),
    # ``LANES = 8  # @const LANES``: a compile-time constant
    "const": (lambda code, name: name, lambda line, name, v: f"{name} = {int(v)}  # @const {name}"),
    # ``from rotorlab.integrate._lane_rows import (  # @template``: a sibling template's copy
    "template": (lambda code, name: code.split()[1], lambda line, name, v: line.replace(f"from {name} import", f"from {v} import", 1)),
}


def _marked(template: str) -> list[tuple[int, str, str]]:
    """``(line index, kind, name)`` of every marked line of ``template`` (kinds of ``_MARKS``)."""
    found = []
    for i, line in enumerate(_template_lines(template)):
        code, sep, mark = line.rpartition("# @")
        kind, _, name = mark.strip().partition(" ")
        if sep and kind in _MARKS:
            found.append((i, kind, _MARKS[kind][0](code, name)))
    return found


def _marks(template: str) -> dict[str, set[str]]:
    """What ``template`` marks, by kind: roles (``kernel``), constants (``const``) and sibling
    templates (``template``), with the kernels and constants its siblings mark added to its own
    under ``"kernel+"`` and ``"const+"``."""
    own: dict[str, set[str]] = {kind: set() for kind in _MARKS}
    for _, kind, name in _marked(template):
        own[kind].add(name)
    for kind in ("kernel", "const"):
        own[kind + "+"] = own[kind].union(*(_marks(sib)[kind] for sib in own["template"]))
    return own


def _render(
    template: str, kernels: dict[str, tuple[str, str]], consts: dict[str, int], siblings: dict[str, str] | None = None
) -> str:
    """The template's source with its marked lines replaced (see ``_MARKS``); a ``# @template``
    line imports from the generated copy ``siblings[module]`` instead (left as it is without
    ``siblings``). Kernels and constants a sibling declares may be among those given."""
    lines = _template_lines(template)
    values = {"kernel": kernels, "const": consts, "template": siblings or {}}
    for i, kind, name in _marked(template):
        if name in values[kind]:
            lines[i] = _MARKS[kind][1](lines[i], name, values[kind][name])
    marks = _marks(template)
    missing = (set(kernels) - marks["kernel+"]) | (set(consts) - marks["const+"])
    if missing:
        raise RuntimeError(f"{template} and its siblings have no '# @kernel'/'# @const' line for {sorted(missing)}")
    return f"# Generated by rotorlab.integrate._codegen from {template}; do not edit.\n" + "\n".join(lines) + "\n"


def _split(template: str, kernels: dict[str, Any], consts: dict[str, int]):
    """Generate the sibling templates ``template`` imports (``# @template`` lines) with their
    share of ``kernels`` and ``consts``; return the template's own share and the siblings'
    generated module names. A template too large for one module is split this way: each part is
    a template, and the part that imports another gets that part's copy for the same model."""
    marks = _marks(template)
    modules: dict[str, str] = {}
    for sib in marks["template"]:
        sm = _marks(sib)
        ns = build(sib, {r: d for r, d in kernels.items() if r in sm["kernel"]}, {k: v for k, v in consts.items() if k in sm["const"]})
        modules[sib] = ns["__name__"]
    # what no sibling declares stays with the template (_render names what nobody declares)
    own_k = marks["kernel"] | (set(kernels) - (marks["kernel+"] - marks["kernel"]))
    own_c = marks["const"] | (set(consts) - (marks["const+"] - marks["const"]))
    return {r: d for r, d in kernels.items() if r in own_k}, {k: v for k, v in consts.items() if k in own_c}, modules


def build(template: str, kernels: dict[str, Any], consts: dict[str, int] | None = None) -> dict[str, Any]:
    """Return the namespace of ``template`` compiled for the given kernels and constants.

    Parameters
    ----------
    template : str
        Module name of a driver template (``"rotorlab.integrate._core"``, ``"..._lanes"``).
    kernels : dict
        Role (``"rhs"``, ``"events"``, ``"reset"``) to the model's numba dispatcher.
    consts : dict, optional
        Compile-time constants of the copy (``{"LANES": 8, "N_STATE": 4}``).

    Returns
    -------
    dict
        The generated module's namespace (its compiled entry points by name).
    """
    consts = dict(consts or {})
    disp = tuple(kernels[r] for r in sorted(kernels))
    key = (template, tuple(sorted(consts.items())), tuple(id(d) for d in disp))
    hit = _LOADED.get(key)
    if hit is not None and all(a is b for a, b in zip(hit[0], disp)):
        return hit[1]
    with BUILD_LOCK:
        hit = _LOADED.get(key)  # built by another thread meanwhile
        if hit is not None and all(a is b for a, b in zip(hit[0], disp)):
            return hit[1]
        names = {role: _importable_name(d) for role, d in kernels.items()}
        directory = cache_dir()
        if directory is None or any(n is None for n in names.values()):
            namespace = _in_memory(template, kernels, consts)
        else:
            _, own_consts, siblings = _split(template, kernels, consts)
            namespace = _cached(template, names, own_consts, siblings, directory, consts)  # type: ignore[arg-type]
        _LOADED[key] = (disp, namespace)
        return namespace


def _cached(
    template: str,
    names: dict[str, tuple[str, str]],
    consts: dict[str, int],
    siblings: dict[str, str],
    directory: Path,
    all_consts: dict[str, int],
) -> dict[str, Any]:
    """Write (if needed) and import the copy of ``template``; ``all_consts`` (its own and its
    siblings' constants) name it, so that copies for other lane widths or sizes are kept."""
    text = _render(template, names, consts, siblings)
    deps = _codewriter.dependencies([template, __name__] + [m for m, _ in names.values()])
    digest = _codewriter.source_digest(text, deps)
    tag = template.rsplit(".", 1)[-1].lstrip("_")
    if all_consts:  # core_e1, lanes_e0i0l8n20: the template, then its constants
        tag += "_" + "".join(f"{k[0].lower()}{v}" for k, v in sorted(all_consts.items()))
    if names:
        mod, fn = names.get("rhs", next(iter(names.values())))
        # The name is that of the whole kernel set, not of its rhs alone: models that share an
        # rhs but not their events or reset map (Jeffcott balls with and without friction) get
        # copies of different names, and neither prunes the other's as "older" (which made each
        # recompile the driver every time the other had run).
        kset = hashlib.sha256(repr(sorted(names.items())).encode()).hexdigest()[:6]
        stem = f"{tag}_{mod.rsplit('.', 1)[-1]}_{fn}_{kset}_{digest}"
    else:  # a sibling template without kernels (the lane driver's workspace layout)
        stem = f"{tag}_{digest}"
    # the copies of the same kernels generated from older sources are pruned
    path = _codewriter.write(directory, stem, text, prune=stem.rsplit("_", 1)[0])
    mod_name = f"_rotorlab_gen_{stem}"
    announced = None
    if names and not _codewriter.loaded(mod_name):  # a sibling without kernels is compiled with its importer
        lanes = f"{all_consts['LANES']}-lane integrator" if "LANES" in all_consts else "scalar integrator"
        announced = announce_compile(directory, stem, f"{lanes} for {compiling_for() or 'this model'}")
    module = _codewriter.load(mod_name, path)
    if announced:  # rotorlab.integrate._drivers says when its compile is done
        module._ANNOUNCED = announced
    return vars(module)


def announce_compile(directory: Path, stem: str, what: str) -> str | None:
    """Log (logger ``rotorlab.compile``, INFO) that ``stem`` has no numba cache yet: the first
    call compiles it (tens of seconds). The command line shows this on stderr.

    Returns ``what`` if it was announced (the caller then logs the elapsed time when the compile
    is done, :func:`rotorlab.integrate._drivers.compiled`), else None."""
    if _codewriter.has_numba_cache(directory, stem):
        return None
    import logging

    logging.getLogger("rotorlab.compile").info("compiling the %s (first run only) ...", what)
    return what


def _in_memory(template: str, kernels: dict[str, Any], consts: dict[str, int]) -> dict[str, Any]:
    """Compile the template with the kernels bound as globals, without on-disk caching.

    The module is registered in ``sys.modules`` under a name of its own, so that a template
    importing it as a sibling (``# @template``) finds it; siblings are built by :func:`build`."""
    kernels, own_consts, siblings = _split(template, kernels, consts)
    placeholder = {role: ("rotorlab.models._base", "no_rhs") for role in kernels}
    source = _render(template, placeholder, own_consts, siblings)
    lines = [ln for ln in source.splitlines() if "# @kernel " not in ln]
    name = f"_rotorlab_gen_uncached_{template.rsplit('.', 1)[-1]}_{next(_UNCACHED)}"
    return vars(_codewriter.in_memory(name, "\n".join(lines), kernels))
