"""The registries keep specs, analysis types and presentations in step, and a new analysis type
needs only its spec, one registry entry and one presentation (the toy analysis below).

The toy analysis computes the centrifugal force of the rotor's unbalance, F = M1 e omega^2 (a
closed form), so its numbers are checked against the formula, not against its own output.
"""

from __future__ import annotations

import json
import math
import re
from typing import Literal

import pytest
from pydantic import Field
from typer.testing import CliRunner

from rotorlab.analyses import ANALYSIS_TYPES, MODEL_TYPES, AnalysisType, run_case, summarize
from rotorlab.cli import app
from rotorlab.io import ANALYSIS_SPECS, MODEL_SPECS, AbstractAnalysisSpec, load_case, parse_case, quantity
from rotorlab.report import PRESENTATIONS, Findings, Presentation, write_report

# --------------------------------------------------------------------------- in step


def test_every_spec_has_an_entry_and_every_entry_a_spec():
    assert list(MODEL_SPECS) == list(MODEL_TYPES)
    assert list(ANALYSIS_SPECS) == list(ANALYSIS_TYPES)
    for name, entry in (*MODEL_TYPES.items(), *ANALYSIS_TYPES.items()):
        assert entry.name == name
    for model in MODEL_TYPES.values():  # a model's own implementations are of common types
        assert set(model.analyses) <= set(ANALYSIS_TYPES)
        assert all(entry.name == name for name, entry in model.analyses.items())


def test_the_model_types_an_analysis_accepts_are_registered_and_include_its_own_entries():
    # An analysis spec's model_types (None: any) names registered model types, and a model type
    # with its own implementation of an analysis type is among the types that spec accepts.
    for spec in ANALYSIS_SPECS.values():
        assert spec.model_types is None or set(spec.model_types) <= set(MODEL_TYPES), spec.__name__
    for model in MODEL_TYPES.values():
        for kind in model.analyses:
            types = ANALYSIS_SPECS[kind].model_types
            assert types is None or model.name in types, (model.name, kind)
    # A case whose model is of another type gets one issue at the analysis' type, naming it.
    models = {m.type: m for m in (load_case(name).model for name in (
        "friswell-rotor", "krasnov-crusher", "autobalancer", "pico21-balancer", "pico21", "rub-jeffcott",
        "strautmanis-torus"))}  # fmt: skip
    assert set(models) == set(MODEL_TYPES)
    for kind, spec in ANALYSIS_SPECS.items():
        for model_type, model in models.items():
            if spec.model_types is None:
                assert spec.wrong_model(model) is None
            elif model_type in spec.model_types:
                assert spec.wrong_model(model) is None
            else:
                issue, = spec.model_construct().case_issues(model)  # unvalidated: only its type is read
                assert (issue.loc, issue.value) == (("type",), kind)
                assert issue.message == spec.wrong_model(model) and repr(model_type) in issue.message.replace('"', "'")


def test_every_analysis_type_has_a_presentation_and_every_presentation_is_used():
    families = {entry.family for entry in ANALYSIS_TYPES.values()}
    families |= {entry.family for model in MODEL_TYPES.values() for entry in model.analyses.values()}
    assert families <= set(PRESENTATIONS)
    assert set(PRESENTATIONS) <= families
    for family, presentation in PRESENTATIONS.items():
        assert presentation.family == family
        for part in (presentation.figures, presentation.section, presentation.findings, presentation.console):
            assert callable(part)
        resolve = getattr(presentation.figures, "resolve", None)  # a lazy name must import
        assert resolve is None or callable(resolve())


def test_registries_are_read_only_mappings_with_helpful_misses():
    with pytest.raises(TypeError):
        ANALYSIS_TYPES["x"] = ANALYSIS_TYPES["simulate"]  # type: ignore[index]
    with pytest.raises(KeyError, match="no analysis type 'nope' .*simulate"):
        ANALYSIS_TYPES["nope"]
    with pytest.raises(ValueError, match="already registered"):
        ANALYSIS_TYPES.register("simulate", ANALYSIS_TYPES["simulate"])


# --------------------------------------------------------------------------- the toy analysis
# Everything a new analysis type needs: its spec, one registry entry, one presentation.


class ToyForceSpec(AbstractAnalysisSpec):
    """Centrifugal force of the unbalance at one speed (a toy analysis for the tests)."""

    type: Literal["toy-force"] = "toy-force"
    speed: quantity("angular_speed", gt=0) = Field(description="spin speed (rad/s)")


def _run_toy(case_model, analysis, progress=None):
    import xarray as xr

    force = case_model.disc_mass * case_model.eccentricity * analysis.speed**2
    if progress is not None:
        progress(1, 1)
    ds = xr.Dataset({"force": ((), force, {"units": "N"})})
    ds.attrs["name"] = analysis.name
    return ds


def _toy_rows(ds):
    return [{"force": float(ds.force)}]


def _toy_figures(ds, name):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.bar(["F"], [float(ds.force)])
    ax.set_ylabel("force (N)")
    return {f"{name}_force": fig}


def _toy_section(ds, rows):
    return f"<p>toy force table: {rows[0]['force']:.6g} N</p>"


def _toy_findings(ds, rows):
    return Findings(f"unbalance force {rows[0]['force']:.4g} N", ("toy number 1 kg",))


def _toy_console(results, rows):
    return [f"toy {name}: {rows[name][0]['force']:.4g} N" for name in results]


TOY_ENTRY = AnalysisType("toy-force", _run_toy, _toy_rows, family="toy")
TOY_PRESENTATION = Presentation("toy", _toy_figures, _toy_section, _toy_findings, _toy_console)


@pytest.fixture
def toy():
    with (ANALYSIS_SPECS.registered("toy-force", ToyForceSpec), ANALYSIS_TYPES.registered("toy-force", TOY_ENTRY),
          PRESENTATIONS.registered("toy", TOY_PRESENTATION)):  # fmt: skip
        yield
    assert "toy-force" not in ANALYSIS_SPECS and "toy" not in PRESENTATIONS


# Two toy analyses whose names share a prefix: "basin_fine" must not show the figures of "basin".
TOY_CASE = """
name = "toy"
[model]
type = "jeffcott_balls"
disc_mass = "2 kg"
eccentricity = "1.5 mm"
stiffness = "16.74 kN/m"
damping = "13.32 N*s/m"
[[analysis]]
type = "toy-force"
name = "basin"
speed = "2400 rpm"
[[analysis]]
type = "toy-force"
name = "basin_fine"
speed = "1200 rpm"
"""


def _force(rpm: float) -> float:
    return 2.0 * 1.5e-3 * (rpm * 2.0 * math.pi / 60.0) ** 2  # M1 e omega^2 (N)


def _sections(text: str) -> dict[str, str]:
    """HTML of each analysis section, by analysis name."""
    parts = re.split(r'<h2 id="analysis-([^"]+)">', text)
    return {parts[i]: parts[i + 1].split("<h2")[0] for i in range(1, len(parts), 2)}


def test_toy_analysis_runs_through_run_case_and_the_report(toy, tmp_path):
    case = parse_case(TOY_CASE, origin="toy.toml")
    results = run_case(case)
    assert results["basin"].attrs["analysis"] == "toy-force"
    rows = {name: summarize(ds) for name, ds in results.items()}
    assert rows["basin"][0]["force"] == pytest.approx(_force(2400.0), rel=1e-12)  # 189.50 N
    assert rows["basin_fine"][0]["force"] == pytest.approx(_force(1200.0), rel=1e-12)
    figures = {name: _toy_figures(ds, name) for name, ds in results.items()}
    text = write_report(tmp_path / "o", case, results, figures, rows).read_text(encoding="utf-8")
    # findings first: both verdicts before the first analysis section
    first_section = text.index('<h2 id="analysis-')
    assert text.index(f"unbalance force {_force(2400.0):.4g} N") < first_section
    assert text.index(f"unbalance force {_force(1200.0):.4g} N") < first_section
    assert text.index("<h2>Software</h2>") > text.index("<h2>Case file</h2>")
    # each analysis shows its own figure only (no matching by name prefix)
    sections = _sections(text)
    assert sections["basin"].count("<img") == 1 and 'alt="basin_force"' in sections["basin"]
    assert sections["basin_fine"].count("<img") == 1 and 'alt="basin_fine_force"' in sections["basin_fine"]
    assert "toy force table: 189.496 N" in sections["basin"]
    # parameters with their unit from the field's metadata
    assert "<td>analysis.basin.speed</td><td class=\"num\">251.327</td><td>rad/s</td>" in sections["basin"]


def test_toy_analysis_runs_through_rotorlab_run(toy, tmp_path):
    path = tmp_path / "toy.toml"
    path.write_text(TOY_CASE)
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["run", str(path), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert f"toy basin: {_force(2400.0):.4g} N" in result.output
    assert sorted(p.name for p in out.glob("*.png")) == ["basin_fine_force.png", "basin_force.png"]
    result = CliRunner().invoke(app, ["run", str(path), "--out", str(out), "--json"])
    doc = json.loads(result.stdout)
    assert doc["analyses"]["basin_fine"] == {"type": "toy-force", "rows": [{"force": pytest.approx(_force(1200.0))}]}


def test_unregistered_type_is_refused_with_the_registered_ones(tmp_path):
    path = tmp_path / "toy.toml"
    path.write_text(TOY_CASE)
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2
    assert 'analysis[0].type = "toy-force"' in result.output and "simulate" in result.output
