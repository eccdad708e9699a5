"""The generator of compiled drivers (``rotorlab.integrate._codegen``): its cache key covers every
module a kernel depends on, transitively, a cached copy is checked before it is imported, and
copies are written only to the cache directory."""

import importlib
import sys
import textwrap

import numpy as np
import pytest

from rotorlab.integrate import StepControl, solve_ensemble
from rotorlab.integrate import _codegen
from rotorlab.models import Kernels

KERNEL = """
from numba import njit

from {helper} import slope


@njit(cache=True, nogil=True)
def rhs(t, y, p, out):
    out[0] = slope()
"""

HELPER = """
from numba import njit


@njit(cache=True, nogil=True)
def slope():
    return {value}
"""


def test_dependencies_are_transitive():
    deps = _codegen.dependencies(["rotorlab._kernels.jeffcott_balls"])
    assert "rotorlab._kernels.speed" in deps  # imported by the kernel module (profile)
    core = _codegen.dependencies(["rotorlab.integrate._core"])
    assert {"rotorlab.integrate._tableau", "rotorlab.models._base"} <= set(core)
    assert not any(d.split(".")[0] in ("numba", "numpy", "math") for d in deps + core)


@pytest.fixture
def kernel_package(tmp_path, monkeypatch):
    """A kernel module and the helper module it imports, in a temporary package, and a
    temporary driver cache."""
    pkg = tmp_path / "rlgen_tmp"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    monkeypatch.setenv("ROTORLAB_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.syspath_prepend(str(tmp_path))

    def write(value):
        (pkg / "helper.py").write_text(textwrap.dedent(HELPER.format(value=value)))
        (pkg / "kern.py").write_text(textwrap.dedent(KERNEL.format(helper="rlgen_tmp.helper")))
        for name in ("rlgen_tmp.kern", "rlgen_tmp.helper", "rlgen_tmp"):
            sys.modules.pop(name, None)
        importlib.invalidate_caches()
        return Kernels(rhs=importlib.import_module("rlgen_tmp.kern").rhs, n_state=1)

    yield write, tmp_path / "cache" / "drivers"
    for name in [m for m in sys.modules if m.startswith("rlgen_tmp")]:
        sys.modules.pop(name, None)


def _final(kernels):
    # dy/dt = slope() from y = 0 over one second: y(1) = slope() up to the round-off of the steps
    sol = solve_ensemble(kernels, [0.0], (0.0, 1.0), params=[0.0], threads=1, control=StepControl(rtol=1e-6, atol=1e-9))
    return float(sol.y_final[0, 0])


def test_changed_dependency_forces_a_recompile(kernel_package):
    write, drivers = kernel_package
    assert _final(write("2.0")) == pytest.approx(2.0, rel=1e-14)
    first = sorted(p.name for p in drivers.glob("core_*.py"))
    # only the helper changes (the kernel module's text is the same): numba's own cache of the
    # kernel would not notice, the generated driver must
    kernels = write("3.25")
    assert _final(kernels) == pytest.approx(3.25, rel=1e-14)
    second = sorted(p.name for p in drivers.glob("core_*.py"))
    assert len(first) == len(second) == 1 and first != second  # the stale copy is pruned
    # a cached copy that differs from the text it should have is rewritten before it is imported
    path = drivers / second[0]
    good = path.read_bytes()
    path.write_bytes(good.replace(b"def integrate_one(", b"def integrate_one_broken("))
    _codegen._LOADED.clear()
    sys.modules.pop(f"_rotorlab_gen_{path.stem}", None)
    assert _final(kernels) == pytest.approx(3.25, rel=1e-14)
    assert path.read_bytes() == good


def test_lane_copy_key_covers_dependencies(kernel_package):
    write, _ = kernel_package

    def key(kernels):
        name = _codegen._importable_name(kernels.rhs)
        text = _codegen._render("rotorlab.integrate._lanes", {"rhs": name}, {"LANES": 4, "N_STATE": 1})
        return text, _codegen.source_digest(text, _codegen.dependencies(["rotorlab.integrate._lanes", name[0]]))

    text_a, key_a = key(write("2.0"))
    text_b, key_b = key(write("3.25"))
    assert text_a == text_b  # the generated text is the same ...
    assert key_a != key_b  # ... but the key sees the helper


def test_unwritable_cache_compiles_in_memory(tmp_path, monkeypatch):
    """No copy is written anywhere when the cache directory cannot be created."""
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("ROTORLAB_CACHE_DIR", str(blocker))
    assert _codegen.cache_dir() is None


def test_functions_bound_to_a_copys_kernels_carry_the_copys_module_name():
    """numba names a compiled function by module, qualified name and a per-process counter, and a
    process links every caller to the first definition of a name it loads. The lane driver binds
    the scalar driver's event location and reset functions to its own model's kernels; under
    _core's module name, a copy loaded from numba's cache could call another model's copy compiled
    in another process with the same counter value (the fresh-clone suite saw the bouncing ball's
    lanes end in another model's states). Each bound function must carry its copy's module."""
    from rotorlab.integrate._drivers import _lane_consts, _roles
    from rotorlab.models.examples import BouncingBall, FrictionBlock

    names = set()
    for model in (BouncingBall(), FrictionBlock()):
        k = model.kernels
        ns = _codegen.build("rotorlab.integrate._lanes", _roles(k), _lane_consts(k, 8))
        for fn in ("_events_in_step", "_resolve_cut", "_initial_step", "_events_at", "_rhs_once"):
            assert ns[fn].py_func.__module__ in (ns["__name__"], k.rhs.py_func.__module__), fn
        for fn in ("_events_in_step", "_resolve_cut", "_initial_step"):
            assert ns[fn].py_func.__module__ == ns["__name__"], fn
        assert ns["_EV"]["_g_at"].py_func.__module__ == ns["__name__"]
        names.add(ns["__name__"])
    assert len(names) == 2
