"""The ``impacts`` and ``impacts-sweep`` commands (seed 001): output, JSON, bad input.

Bad input exits with code 2, a message naming the option or key, no traceback and no file
written. Runs are kept short (a fraction of a second of rotor time).
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import load_netcdf

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


def test_impacts_json_has_the_documented_keys():
    r = invoke("impacts", "krasnov-crusher", "--stone-mass", "1.0", "--t-end", "1.5", "--seed", "3", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert {"regime", "impacts", "sliding_time_s", "energy_ratio"} <= set(doc)
    assert doc["regime"] in ("none", "rebounds", "sliding", "backward_whirl")
    assert doc["impacts"] > 0 and doc["stone_mass_kg"] == 1.0 and doc["t_end_s"] == 1.5 and doc["seed"] == 3
    assert doc["max_penetration_m"] < 1e-9
    assert doc["n_stones"] == 42


def test_impacts_table_and_files(tmp_path):
    out, plot = tmp_path / "run.nc", tmp_path / "p.png"
    r = invoke("impacts", "krasnov-crusher", "--t-end", "1", "--out", str(out), "--plot", str(plot))
    assert r.exit_code == 0, r.output
    assert "regime" in r.stdout and "impacts" in r.stdout
    ds = load_netcdf(out)
    assert ds.sizes["stone"] == 28 and ds.attrs["seed"] == 0
    assert plot.stat().st_size > 1000


def test_impacts_sweep_json_with_paper_column():
    r = invoke("impacts-sweep", "krasnov-crusher", "--stone-mass", "0.5:1.0:2", "--sequences", "2", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["param"] == "stone_mass" and doc["n_sequences"] == 2 and doc["t_end_s"] == 10.0
    rows = doc["rows"]
    assert [row["value"] for row in rows] == [0.5, 1.0]
    assert [row["paper_impacts"] for row in rows] == [0, 400]
    assert rows[1]["impacts_median"] > rows[0]["impacts_median"]


def test_impacts_sweep_other_parameter_table():
    r = invoke("impacts-sweep", "krasnov-crusher", "--param", "friction=0:0.4:2", "--sequences", "1",
               "--t-end", "0.5")  # fmt: skip
    assert r.exit_code == 0, r.output
    assert "friction" in r.stdout and "paper" not in r.stdout


@pytest.mark.parametrize("args, words", [
    (("impacts", "krasnov-crusher", "--stone-mass", "-1"), "--stone-mass = -1: must be a finite number > 0 (kg)"),
    (("impacts", "krasnov-crusher", "--t-end", "0"), "--t-end = 0: must be a finite number > 0 (s)"),
    (("impacts", "krasnov-crusher", "--seed", "-2"), "--seed = -2: must be an integer >= 0"),
    (("impacts", "krasnov-crusher", "--analysis", "nope"), "--analysis = nope: no impacts analysis"),
    (("impacts", "autobalancer"), "needs an impact_rotor model"),
    (("impacts", "no-such-case"), "no-such-case"),
    (("impacts-sweep", "krasnov-crusher", "--sequences", "0"), "--sequences = 0: must be an integer >= 1"),
    (("impacts-sweep", "krasnov-crusher", "--stone-mass", "1:0.5:3"), "--stone-mass = 1:0.5:3: STOP must be > START"),
    (("impacts-sweep", "krasnov-crusher", "--stone-mass", "0:1:3"), "--stone-mass = 0:1:3: masses must be > 0"),
    (("impacts-sweep", "krasnov-crusher", "--param", "colour=1:2:2"), "--param = colour=1:2:2: must be NAME=A:B:N"),
    (("impacts-sweep", "krasnov-crusher", "--stone-mass", "1:2:2", "--param", "friction=0:1:2"),
     "--stone-mass and --param exclude each other"),
])
def test_bad_input_exits_2_names_the_option_and_writes_nothing(tmp_path, args, words):
    out = tmp_path / "r.nc"
    r = invoke(*args, "--out", str(out))
    assert r.exit_code == 2, r.output
    assert words in r.stderr
    assert "Traceback" not in r.output
    assert not out.exists()


def test_bad_output_path_is_bad_input(tmp_path):
    r = invoke("impacts", "krasnov-crusher", "--out", str(tmp_path / "missing" / "r.nc"))
    assert r.exit_code == 2 and "--out" in r.stderr and "does not exist" in r.stderr
    r = invoke("impacts-sweep", "krasnov-crusher", "--plot", str(tmp_path))
    assert r.exit_code == 2 and "--plot" in r.stderr and "is a folder" in r.stderr


def test_validate_and_cases_list_the_crusher():
    r = invoke("validate", "krasnov-crusher")
    assert r.exit_code == 0, r.output
    assert "impacts over 5 s" in r.stdout and "stone_mass sweep" in r.stdout
    r = invoke("cases", "--json")
    doc = json.loads(r.stdout)
    assert "krasnov-crusher" in doc["cases"] and "krasnov-crusher-translational" in doc["cases"]


def test_run_writes_the_report_section_and_figures(tmp_path):
    from rotorlab.io import load_case

    text = load_case("krasnov-crusher").text
    head = text[: text.index("[[analysis]]")]
    case = tmp_path / "small.toml"
    case.write_text(head.replace('name = "krasnov-crusher"', 'name = "small"') + """
[[analysis]]
type = "impacts"
name = "one"
t_end = "1 s"
stone_mass = "1 kg"

[[analysis]]
type = "impacts-sweep"
name = "masses"
values = ["0.6 kg", "1.2 kg"]
n_sequences = 2
t_end = "1 s"
""")
    out = tmp_path / "out"
    r = invoke("run", str(case), "--out", str(out), "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert sorted(doc["files"]) == ["masses.nc", "masses_sweep.png", "one.nc", "one_p_trajectory.png", "report.html"]
    assert doc["analyses"]["one"]["rows"][0]["stone_mass_kg"] == 1.0
    page = (out / "report.html").read_text()
    assert "Seed 001: formulas garbled in print" in page and "(4.1)" in page
    assert "Impacts over stone sequences" in page and "energy against friction at the housing" in page
