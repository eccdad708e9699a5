"""One way through (issue 24, item 4): ``rotorlab run`` builds a case's model once and hands it
down to every analysis, the sanity checks, the verdict and the report; figures are drawn in
``rotorlab.plot`` only; a library call never switches pyplot's backend nor leaves a figure open.
(No package circle and ``io`` importing no analysis layer: ``test_import_cycles.py``.)"""

from __future__ import annotations

import ast
import json
import sys
from pathlib import Path

from typer.testing import CliRunner

import rotorlab
from rotorlab.cli import app
from rotorlab.io import _linear_build

ROOT = Path(rotorlab.__file__).parent
runner = CliRunner()


def test_run_builds_the_case_model_once_and_every_analysis_uses_it(tmp_path, monkeypatch):
    # friswell-rotor: an fe_rotor with five linear analyses; its structure is assembled by _fe_rotor
    built = []
    real = _linear_build._fe_rotor

    def counting(spec):
        system = real(spec)
        built.append(system)
        return system

    monkeypatch.setattr(_linear_build, "_fe_rotor", counting)
    result = runner.invoke(app, ["run", "friswell-rotor", "--out", str(tmp_path / "o"), "--json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert len(doc["analyses"]) == 5
    assert len(built) == 1, f"the model was built {len(built)} times"  # 12 before the fix
    assert sorted(p.stem for p in (tmp_path / "o").glob("*.nc")) == sorted(doc["analyses"])


def test_a_single_analysis_command_builds_the_model_once(tmp_path, monkeypatch):
    calls = []
    real = _linear_build._fe_rotor
    monkeypatch.setattr(_linear_build, "_fe_rotor", lambda spec: calls.append(1) or real(spec))
    result = runner.invoke(app, ["modes", "friswell-rotor", "--speed-rpm", "3000", "--json"])
    assert result.exit_code == 0, result.output
    assert len(calls) == 1


def test_validating_and_building_a_machine_case_builds_its_machine_once(monkeypatch):
    # pico21-balancer's validation asks its machine whether it has steady motions (two stability
    # charts), `rotorlab validate` and the analyses ask for its critical speed; before, each question
    # built the machine again (`rotorlab run pico21-balancer`: 3 builds, `validate`: 15)
    from rotorlab.analyses._case import build_model
    from rotorlab.io import _build, load_case
    from rotorlab.io._build import build_machine

    made = []
    real = _build._machine
    monkeypatch.setattr(_build, "_machine", lambda spec: made.append(spec) or real(spec))
    case = load_case("pico21-balancer")
    assert len(made) == 1  # validation needed the machine: built once
    machine = build_model(case.model)
    assert build_machine(case.model) is machine and case.model.critical_speed() > 0
    assert len(made) == 1
    edited = case.model.model_copy(update={"n_modes": case.model.n_modes})  # another spec object
    assert build_machine(edited) is not machine and len(made) == 2


def _calls(tree: ast.AST) -> list[str]:
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            out.append(f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else "")
    return out


def _sources():
    for path in sorted(ROOT.rglob("*.py")):
        yield path.relative_to(ROOT), ast.parse(path.read_text(encoding="utf-8"))


def test_figures_are_drawn_in_plot_only_and_pyplot_never_imported():
    pyplot, switched, drawn = [], [], []
    for rel, tree in _sources():
        for node in ast.walk(tree):
            if isinstance(node, ast.Import) and any(a.name == "matplotlib.pyplot" for a in node.names):
                pyplot.append(f"{rel}:{node.lineno}")
            if isinstance(node, ast.ImportFrom) and node.module and (
                    node.module == "matplotlib.pyplot"
                    or node.module == "matplotlib" and any(a.name in ("pyplot", "use") for a in node.names)):
                pyplot.append(f"{rel}:{node.lineno}")
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "use"
                    and isinstance(node.func.value, ast.Name) and node.func.value.id in ("matplotlib", "mpl")):
                switched.append(f"{rel}:{node.lineno}")
        if rel.parts[0] != "plot" and "Figure" in _calls(tree):
            drawn.append(str(rel))
    assert not pyplot, pyplot
    assert not switched, switched
    assert not drawn, f"figures drawn outside rotorlab/plot: {drawn}"  # report/_knock.py before


def test_a_run_leaves_no_pyplot_figure_open_and_the_backend_alone(tmp_path):
    import matplotlib

    backend = matplotlib.get_backend()
    before = set(sys.modules["matplotlib.pyplot"].get_fignums()) if "matplotlib.pyplot" in sys.modules else set()
    result = runner.invoke(app, ["run", "friswell-rotor", "--out", str(tmp_path / "o")])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (tmp_path / "o").glob("*.png"))  # figures were drawn
    assert matplotlib.get_backend() == backend
    if "matplotlib.pyplot" in sys.modules:
        assert set(sys.modules["matplotlib.pyplot"].get_fignums()) == before
