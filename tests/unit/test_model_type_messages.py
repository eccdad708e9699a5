"""A case whose model type an analysis cannot run on is refused with the types it can run on.

Review of the session-5 diff: the lists of accepted model types were written out in several
messages, and some had fallen behind the code (a machine runs basins, sweeps, simulate and the
steady analyses, but the sweep, simulate and steady messages named jeffcott_balls or toroidal_ball
only). They now come from one place each: the model specs that name start coordinates (basins,
sweeps), ``SimulateSpec.model_types`` and the model's own ``steady_issues`` (the steady commands:
``tests/unit/test_steady_cli.py::test_steady_commands_need_a_rotor_with_balls``). Refused on the
command line: exit 2, no traceback, nothing written.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from rotorlab.analyses._registry import MODEL_TYPES
from rotorlab.cli import app
from rotorlab.io import CaseError, SimulateSpec, load_case
from rotorlab.io._coordinates import mappable_text

runner = CliRunner()

#: Every model type with a regime mapper in the analyses' registry: what basins and sweeps run on.
MAPPED = sorted(k for k, entry in MODEL_TYPES.items() if entry.mapper is not None)


def test_the_mappable_types_are_those_with_a_regime_mapper():
    # io cannot import the analyses; its list (specs naming start coordinates) must be the same
    text = mappable_text(load_case("friswell-rotor").model)
    assert MAPPED == ["jeffcott_balls", "machine", "toroidal_ball"]
    listed = text.split(" model (")[0].removeprefix("a ").replace(" or ", ", ").split(", ")
    assert sorted(listed) == MAPPED
    assert text.endswith("not model type 'fe_rotor'")


@pytest.mark.parametrize("command", ["basin", "sweep"])
def test_basin_and_sweep_commands_name_every_mappable_type(command, tmp_path):
    out = tmp_path / "out.zarr"
    args = [command, "friswell-rotor", "--param", "spin_speed=1:2:3"] if command == "sweep" else [command, "friswell-rotor"]
    result = runner.invoke(app, [*args, "--out" if command == "sweep" else "--store", str(out)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert all(kind in result.output for kind in MAPPED), result.output
    assert "'fe_rotor'" in result.output
    assert list(tmp_path.iterdir()) == []


def test_a_sweep_analysis_on_a_linear_rotor_names_every_mappable_type(tmp_path):
    path = tmp_path / "sweep.toml"
    path.write_text(load_case("pico21").text.split("[[analysis]]")[0]
                    + '[[analysis]]\ntype = "sweep"\nic = { psi_1 = ["0 deg", "300 deg", 3] }\nt_end = "1 s"\n')
    with pytest.raises(CaseError) as err:
        load_case(path)
    message = str(err.value)
    assert 'analysis[0].type = "sweep"' in message
    assert all(kind in message for kind in MAPPED), message


def test_simulate_command_names_its_model_types(tmp_path):
    assert SimulateSpec.model_types == ("jeffcott_balls", "machine")
    result = runner.invoke(app, ["simulate", "strautmanis-torus", "--out", str(tmp_path / "x.nc")])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "simulate needs a rotor with balls ([model] type jeffcott_balls or machine)" in result.output
    assert list(tmp_path.iterdir()) == []
