"""The repository stands alone: nothing in ``src/`` or ``tests/`` names a path outside it.

A user has only the repository (a fresh clone, with no folder of the development machine beside
it), so no source or test file may name an absolute path of a machine or the development
folder next to the repository; the benchmark problem the tests need is
:data:`rotorlab.models.BENCHMARK`. ``bench/`` may compare against that folder when it exists
(it says so when it does not) and is not scanned.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_SUFFIXES = {".py", ".toml", ".md", ".txt", ".cfg", ".json", ".csv", ".rst", ".yaml", ".yml", ".ini"}
# Built from pieces so that this file does not match itself.
_SLASH = "/"
_MACHINE = re.compile(r"(?<![\w.~-])" + _SLASH + r"(work|home|root|Users|mnt|srv|scratch|opt|private)" + _SLASH)
_WINDOWS = re.compile(r"\b[A-Za-z]:\\\\?[A-Za-z]")
_SHARED = re.compile(r"\bshared" + _SLASH)


def _files():
    for top in ("src", "tests"):
        for path in sorted((ROOT / top).rglob("*")):
            if path.suffix in _SUFFIXES and "__pycache__" not in path.parts and path.is_file():
                yield path


def _hits(pattern: re.Pattern[str]) -> list[str]:
    found = []
    for path in _files():
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            if pattern.search(line):
                found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    return found


def test_the_scan_sees_the_files_and_finds_what_it_looks_for():
    names = {p.relative_to(ROOT).as_posix() for p in _files()}
    assert {"src/rotorlab/__init__.py", "tests/unit/test_standalone.py", "src/rotorlab/cases/pico21.toml"} <= names
    assert _MACHINE.search('BENCH = Path("' + _SLASH + 'work' + _SLASH + 'shared' + _SLASH + 'bench")')
    assert _MACHINE.search("open('" + _SLASH + "home" + _SLASH + "me" + _SLASH + "x.txt')")
    assert _WINDOWS.search("C:" + "\\Users\\me")
    assert _SHARED.search("see shared" + _SLASH + "seeds")
    assert not _MACHINE.search("a/work/b, ~/home/x, units N*m/rad, 'rotorlab/cases/x.toml'")


def test_no_absolute_machine_path_in_src_or_tests():
    assert _hits(_MACHINE) + _hits(_WINDOWS) == []


def test_no_reference_to_the_development_folder_beside_the_repository():
    assert _hits(_SHARED) == []


def test_user_documents_link_only_files_of_the_repository():
    link = re.compile(r"\]\(([^)\s]+)\)")
    for doc in ("README.md", "CONTRIBUTING.md", "docs/architecture.md", "bench/README.md"):
        path = ROOT / doc
        for target in link.findall(path.read_text(encoding="utf-8")):
            if target.startswith("#"):
                continue
            assert "://" not in target or target.startswith("https://doi.org/"), (doc, target)
            if "://" not in target:
                assert (path.parent / target.split("#")[0]).resolve().is_relative_to(ROOT), (doc, target)
                assert (path.parent / target.split("#")[0]).exists(), (doc, target)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert not _SHARED.search(readme) and "DESIGN.md" not in readme and "STYLE.md" not in readme
