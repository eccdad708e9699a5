"""No circle among rotorlab's packages: the imports, read from the sources with ``ast`` (those
inside functions too), point one way.

A package here is a sub-package of ``rotorlab`` (``io``, ``models``, ``_kernels`` ...) or one of
its top-level modules (``_memory``, ``_compile_cache`` ...). A circle means that no package can
be read, tested or replaced without the others of the circle (issue 24: {analyses, explore, io}
and {_kernels, contact, integrate, models} were two).
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

import rotorlab

ROOT = Path(rotorlab.__file__).parent


def _package(path: Path) -> str:
    parts = path.relative_to(ROOT).parts
    return parts[0] if len(parts) > 1 else parts[0].removesuffix(".py")


def _module(path: Path) -> list[str]:
    parts = ["rotorlab", *path.relative_to(ROOT).with_suffix("").parts]
    return parts[:-1] if parts[-1] == "__init__" else parts


def package_imports() -> dict[str, dict[str, list[str]]]:
    """package -> imported package -> the places (``file:line``) that import it."""
    known = {_package(p) for p in ROOT.rglob("*.py")}
    edges: dict[str, dict[str, list[str]]] = defaultdict(lambda: defaultdict(list))
    for path in sorted(ROOT.rglob("*.py")):
        src = _package(path)
        here = _module(path)
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:  # relative: from the file's package upwards
                    base = here if path.name == "__init__.py" else here[:-1]
                    base = base[: len(base) - node.level + 1]
                    names = [".".join(base + ([node.module] if node.module else []))]
                else:
                    names = [node.module or ""]
                names += [f"{names[0]}.{a.name}" for a in node.names]
            else:
                continue
            for name in names:
                parts = name.split(".")
                if parts[0] == "rotorlab" and len(parts) > 1 and parts[1] in known and parts[1] != src:
                    edges[src][parts[1]].append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return edges


def circles(edges: dict[str, dict[str, list[str]]]) -> list[list[str]]:
    """The strongly connected components of more than one package (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def module_imports(package: str) -> dict[str, dict[str, list[str]]]:
    """module -> sibling module of the same package it imports -> the places (``file:line``).

    Modules are the files of ``rotorlab/<package>/`` (sub-packages by their ``__init__``); imports
    of the package itself (its ``__init__``, which re-exports every module) are not edges.
    """
    folder = ROOT / package
    names = {".".join(_module(p)): p for p in folder.rglob("*.py") if p.name != "__init__.py"}
    edges: dict[str, dict[str, list[str]]] = defaultdict(lambda: defaultdict(list))
    for name, path in sorted(names.items()):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
                targets = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            else:
                continue
            for t in targets:
                if t in names and t != name:
                    edges[name][t].append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return edges


#: Packages whose modules still import each other in a circle (registries that import their
#: entries and entries that import the registry); every other package has none.
MODULE_CIRCLES_KNOWN = {"analyses", "io", "continuation", "models"}


def test_no_module_circle_inside_a_package():
    """Inside a package too the modules import one way (issue 24: ``steady/_motions`` and
    ``steady/_stability`` imported each other; the records both use live in ``steady/_records``)."""
    packages = sorted(p.name for p in ROOT.iterdir() if (p / "__init__.py").is_file())
    found = {}
    for package in packages:
        if package in MODULE_CIRCLES_KNOWN:
            continue
        edges = module_imports(package)
        if circles(edges):
            found[package] = [f"{a} -> {b}: {', '.join(edges[a][b][:2])}" for c in circles(edges)
                              for a in c for b in c if b in edges[a]]
    assert not found, found
    seen = module_imports("steady")  # the reader sees the package's own imports
    assert "rotorlab.steady._motions" in seen["rotorlab.steady._stability"]
    assert "rotorlab.steady._records" in seen["rotorlab.steady._motions"]


def test_the_reader_finds_a_circle():
    edges = {"a": {"b": ["a.py:1"]}, "b": {"c": ["b.py:2"]}, "c": {"a": ["c.py:3"]}, "d": {"a": ["d.py:1"]}}
    assert circles(edges) == [["a", "b", "c"]]
    real = package_imports()
    # what the reader sees: io builds models, the CLI calls the analyses (lazy imports too)
    assert "models" in real["io"] and "analyses" in real["cli"] and "integrate" in real["explore"]


def test_no_circle_among_the_packages():
    edges = package_imports()
    found = circles(edges)
    detail = [f"{a} -> {b}: {', '.join(edges[a][b][:3])}" for c in found for a in c for b in c if b in edges[a]]
    assert not found, "package circles " + str(found) + ":\n" + "\n".join(detail)


def test_io_imports_no_analysis_layer():
    """Validation and spec -> model building (``rotorlab.io``) use models and linear systems only."""
    edges = package_imports()
    assert not set(edges["io"]) & {"analyses", "explore", "steady", "sweep", "contact", "plot", "report", "cli"}, \
        dict(edges["io"])
