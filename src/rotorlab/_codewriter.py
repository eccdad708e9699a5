"""The one writer of generated modules: their cache key, the byte check, the write and the import.

Two generators produce Python source compiled by numba: the driver copies of
:mod:`rotorlab.integrate._codegen` (the integrator templates with their marked lines changed) and
the machine kernels of :mod:`rotorlab._kernels.machine_codegen` (one ``rhs`` per layout). Both
hand their text to this module, which sits below both packages (as :mod:`rotorlab._compile_cache`,
whose folder and lock it uses), so that a generated module is keyed, checked, written and
imported one way:

- **The key** (:func:`source_digest`) hashes the generated text, the source of every module it
  depends on (:func:`dependencies`: found through import statements and globals, transitively;
  the standard library and the compiled-numerics packages are left out) and the versions of
  Python, numba, NumPy and llvmlite. A module named by this key may be linked by other compiled
  code from numba's cache as it is (``KEYED_BY_SOURCES``): a change to anything it depends on
  gives a new name.
- **The byte check** (:func:`write`): before a cached file is imported its bytes are compared
  with the text generated now; a file that differs (edited, truncated, corrupted) is rewritten
  atomically and numba's cache of it dropped.
- **The import** (:func:`load`) runs the file as a module under the given name, registered in
  ``sys.modules`` so that other generated modules (and numba's cache) find it by that name.
- **No cache directory** (:func:`rotorlab._compile_cache.cache_dir` is None: not writable): the
  text is compiled in memory without numba caching (:func:`in_memory`), never written elsewhere.
"""

from __future__ import annotations

import ast
import hashlib
import importlib
import importlib.util
import inspect
import os
import sys
import tempfile
import types
from collections.abc import Iterable
from pathlib import Path
from typing import Any

__all__ = ["dependencies", "source_digest", "imported_modules", "write", "load", "loaded", "in_memory",
           "generated_module", "has_numba_cache"]

# third-party packages whose versions (not sources) enter the key
_VERSIONED = ("numba", "numpy", "llvmlite")
_SKIP_TOP = {"numba", "numpy", "llvmlite", "scipy", "typing_extensions", "_pytest", "pytest"}


def _module_of(obj: Any) -> str | None:
    if isinstance(obj, types.ModuleType):
        return obj.__name__
    if isinstance(obj, (types.FunctionType, type)):
        return getattr(obj, "__module__", None)
    if type(obj).__name__.endswith("Dispatcher"):  # numba's (and numba-compatible) dispatchers
        return getattr(getattr(obj, "py_func", None), "__module__", None)
    return None


def _followed_name(name: str) -> bool:
    top = name.split(".", 1)[0]
    return not (top in _SKIP_TOP or top in sys.stdlib_module_names or name == "__main__")


def _followed(name: str) -> bool:
    if not _followed_name(name):
        return False
    mod = sys.modules.get(name)
    path = getattr(mod, "__file__", None)
    if path is None:
        return False
    # installed third-party packages are covered by the interpreter's and numba's versions only
    parts = Path(path).parts
    return name.split(".", 1)[0] == "rotorlab" or not ("site-packages" in parts or "dist-packages" in parts)


def imported_modules(text: str) -> set[str]:
    """Modules named by the import statements of the source ``text`` (any depth; ``from m import
    X`` names ``m``, and ``m.X`` when that is a loaded module)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.add(node.module)
            found.update(f"{node.module}.{a.name}" for a in node.names if f"{node.module}.{a.name}" in sys.modules)
    return found


def _imports(name: str) -> set[str]:
    path = inspect.getsourcefile(sys.modules[name])
    return imported_modules(Path(path).read_text()) if path else set()


def dependencies(modules: Iterable[str]) -> list[str]:
    """``modules`` and every module they depend on, transitively, sorted.

    A module's dependencies are the modules its import statements name (constants imported with
    ``from m import X`` are compiled in, so ``m`` counts) and the defining modules of the
    functions, classes and numba dispatchers among its globals. The standard library and the
    compiled-numerics packages (numba, numpy, llvmlite, scipy) are not followed.
    """
    seen: set[str] = set()
    todo = list(modules)
    while todo:
        name = todo.pop()
        if name in seen or not _followed_name(name):
            continue
        try:
            importlib.import_module(name)
        except ImportError:
            continue
        if not _followed(name):
            continue
        seen.add(name)
        found = _imports(name)
        found.update(filter(None, (_module_of(v) for v in vars(sys.modules[name]).values())))
        todo.extend(d for d in found if d not in seen and _followed_name(d))
    return sorted(seen)


def source_digest(text: str, modules: Iterable[str]) -> str:
    """Hash (20 hex digits) of a generated text, the sources of ``modules`` and the interpreter
    and library versions."""
    h = hashlib.sha256(text.encode())
    h.update(sys.version.encode())
    for pkg in _VERSIONED:
        h.update(f"{pkg}={importlib.import_module(pkg).__version__}".encode())
    for mod in modules:
        path = inspect.getsourcefile(sys.modules[mod])
        h.update(mod.encode())
        h.update(Path(path).read_bytes() if path else b"")
    return h.hexdigest()[:20]


def has_numba_cache(directory: Path, stem: str) -> bool:
    """Whether numba has cached compiled code of the file ``directory/stem.py``."""
    return any((directory / "__pycache__").glob(f"{stem}.*.nbi"))


def _drop_numba_cache(directory: Path, stem: str) -> None:
    for cached in (directory / "__pycache__").glob(f"{stem}.*"):
        cached.unlink(missing_ok=True)


def _prune(directory: Path, prefix: str) -> None:
    """Delete the files ``prefix_<20-hex digest>.py`` (and their numba cache)."""
    for old in directory.glob(f"{prefix}_*.py"):
        if len(old.stem) == len(prefix) + 21:  # prefix + "_" + 20-hex digest
            _drop_numba_cache(directory, old.stem)
            old.unlink(missing_ok=True)


def write(directory: Path, stem: str, text: str, *, prune: str | None = None) -> Path:
    """Return ``directory/stem.py`` holding exactly ``text``, written if its bytes differ.

    A file that is written anew loses numba's cache; with ``prune``, the files of older keys
    ``<prune>_<digest>.py`` go first (their sources changed: nobody imports them again)."""
    path = directory / f"{stem}.py"
    if not (path.exists() and path.read_bytes() == text.encode()):
        if prune is not None:
            _prune(directory, prune)
        _drop_numba_cache(directory, stem)
        fd, tmp = tempfile.mkstemp(dir=directory, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    return path


def loaded(name: str) -> bool:
    """Whether the module ``name`` is imported in this process."""
    return name in sys.modules


def load(name: str, path: Path, attrs: dict[str, Any] | None = None) -> types.ModuleType:
    """Import the file ``path`` as the module ``name`` (the loaded one if ``name`` is loaded);
    ``attrs`` are set on it before its code runs."""
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    module.__dict__.update(attrs or {})
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


def in_memory(name: str, text: str, attrs: dict[str, Any] | None = None) -> types.ModuleType:
    """Run ``text`` as the module ``name`` without a file: numba compiles it without caching.

    ``attrs`` are globals set before the code runs (a driver's kernels that are not importable);
    the module is registered in ``sys.modules`` so that other generated modules import it."""
    module = types.ModuleType(name)
    module.__dict__.update(attrs or {})
    sys.modules[name] = module
    code = compile(text.replace("cache=True", "cache=False"), f"<rotorlab {name}>", "exec")
    exec(code, module.__dict__)  # noqa: S102 - our own generated source
    return module


def generated_module(
    name: str, text: str, directory: Path | None, attrs: dict[str, Any] | None = None
) -> types.ModuleType:
    """The module ``name`` running ``text``: from ``directory/name.py`` (written if its bytes
    differ, :func:`write`), or in memory if ``directory`` is None (:func:`in_memory`)."""
    if name in sys.modules:
        return sys.modules[name]
    if directory is None:
        return in_memory(name, text, attrs)
    return load(name, write(directory, name, text), attrs)
