"""The generator of compiled drivers (``rotorlab.integrate._codegen``) and the one writer of every
generated module (``rotorlab._codewriter``, also the machine's kernel modules): the cache key covers
every module a kernel depends on, transitively, a cached file is checked before it is imported, and
files are written only to the cache directory (in memory when it is not writable)."""

import importlib
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from rotorlab import _codewriter
from rotorlab.integrate import StepControl, solve_ensemble
from rotorlab.integrate import _codegen
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed, Kernels, Machine, Unbalance

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
    deps = _codewriter.dependencies(["rotorlab._kernels.jeffcott_balls"])
    assert "rotorlab._kernels.speed" in deps  # imported by the kernel module (profile)
    core = _codewriter.dependencies(["rotorlab.integrate._core"])
    assert {"rotorlab.integrate._tableau", "rotorlab.models._base"} <= set(core)
    assert not any(d.split(".")[0] in ("numba", "numpy", "math") for d in deps + core)
    # the writer of the copies is part of their key, not the whole package: a "from rotorlab
    # import" line in it named the package root, whose __init__ imports everything (every build
    # read 160 modules, 4 CPU-s per warm run of pico21-balancer, and any edit renamed every copy)
    writer = _codewriter.dependencies(["rotorlab.integrate._codegen"])
    assert "rotorlab._codewriter" in writer and "rotorlab" not in writer and len(writer) <= 4, writer


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
        return text, _codewriter.source_digest(text, _codewriter.dependencies(["rotorlab.integrate._lanes", name[0]]))

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


def _small_machine():
    """A planar rotor with one unbalance, no race (12 states): its kernel compiles in about a second."""
    s = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([1.0, 1.0, 5.0, 5.0]))
    return Machine(s, unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(1.3))


@pytest.fixture
def fresh_machine_modules(monkeypatch):
    """No machine kernel module loaded in this process (restored afterwards), so that
    ``kernel_module`` writes and imports its module again."""
    from rotorlab._kernels import machine_codegen

    monkeypatch.setattr(machine_codegen, "_LOADED", {})
    for name in [m for m in sys.modules if m.startswith("_rotorlab_machine_")]:
        monkeypatch.delitem(sys.modules, name)
    return machine_codegen


def test_machine_kernel_modules_and_driver_copies_go_through_one_writer(tmp_path, monkeypatch, fresh_machine_modules):
    """Both generated kinds are written by ``rotorlab._codewriter.write`` into the one cache
    folder; a corrupted kernel module is rewritten before it is imported, as a corrupted driver copy
    is (``test_changed_dependency_forces_a_recompile``), and gives the numbers of the good one."""
    monkeypatch.setenv("ROTORLAB_CACHE_DIR", str(tmp_path))
    written = []
    real_write = _codewriter.write
    monkeypatch.setattr(_codewriter, "write", lambda d, stem, text, **kw: written.append(stem) or real_write(d, stem, text, **kw))
    mac = _small_machine()
    first = fresh_machine_modules.kernel_module(mac.layout)
    from rotorlab.integrate._drivers import _roles

    monkeypatch.setattr(_codegen, "_LOADED", {})
    core = _codegen.build("rotorlab.integrate._core", _roles(mac.kernels), {"EVENTS": 0})
    assert len(written) == 2 and written[0].startswith("_rotorlab_machine_") and written[1].startswith("core_e0_")
    assert written[0] == first.__name__ and core["__name__"] == f"_rotorlab_gen_{written[1]}"
    path = Path(first.__file__)
    assert path.parent == tmp_path / "drivers" and (tmp_path / "drivers" / f"{written[1]}.py").exists()

    y = np.linspace(0.1, 1.2, mac.n_state)
    p = mac.to_array()
    good_out = np.empty_like(y)
    first.rhs(0.0, y, p, good_out)
    assert np.all(np.isfinite(good_out)) and np.any(good_out != 0.0)
    good = path.read_bytes()
    assert b"out[0] = " in good
    path.write_bytes(good.replace(b"out[0] = ", b"out[0] = 1.0 + ", 1))
    monkeypatch.setattr(fresh_machine_modules, "_LOADED", {})
    del sys.modules[first.__name__]
    second = fresh_machine_modules.kernel_module(mac.layout)
    assert second is not first and path.read_bytes() == good
    out = np.empty_like(y)
    second.rhs(0.0, y, p, out)
    np.testing.assert_array_equal(out, good_out)


def test_unwritable_cache_compiles_machine_kernels_in_memory(tmp_path, monkeypatch, fresh_machine_modules):
    """Without a writable cache folder the machine's kernel module is compiled in memory, as the
    driver copies are: no file anywhere (it used to go to a new temporary folder per process)."""
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("ROTORLAB_CACHE_DIR", str(blocker))
    mac = _small_machine()
    module = fresh_machine_modules.kernel_module(mac.layout)
    assert getattr(module, "__file__", None) is None and module.KEYED_BY_SOURCES is True
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]
    y = np.linspace(0.1, 1.2, mac.n_state)
    out = np.empty_like(y)
    module.rhs(0.0, y, mac.to_array(), out)
    np.testing.assert_array_equal(out, mac.rhs(0.0, y))  # the module's rhs is the model's
