"""Wiring of the basin analyses (issue 5): case-file specs, built-in cases, ``rotorlab basin``,
``rotorlab run`` and the report.

The numerics are validated in tests/validation/test_toroidal_seed004.py and
tests/unit/test_explore_*.py; here the point is that they arrive intact through case files, the
command line and the report, and that bad input is refused with exit code 2 and nothing written.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.analyses import basin_document, basin_rows, compare_basins, run_basin_analysis, run_case
from rotorlab.cli import app
from rotorlab.explore import BalancerRegimes, TorusRegimes
from rotorlab.io import (
    BALANCER_COORDINATES,
    TORUS_COORDINATES,
    CaseError,
    coordinate_dimensions,
    dump_case,
    load_case,
    parse_case,
)
from rotorlab.io._sweep_specs import sweep_coordinates
from rotorlab.io._units import DIMENSIONS

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


def _small_torus(t_end: str = "6 s", n: int = 5) -> str:
    """strautmanis-torus with small grids and a short horizon."""
    text = load_case("strautmanis-torus").text
    text = text.replace('t_end = "240 s"', f't_end = "{t_end}"').replace("n_horizons = 24", "n_horizons = 3")
    return re.sub(r'(\["(?:psi|dpsi)", [^\]]*?, )48\]', rf"\g<1>{n}]", text)


# --------------------------------------------------------------------------- specs


def test_coordinate_tables_match_the_mappers():
    torus = load_case("strautmanis-torus")
    auto = load_case("autobalancer")
    from rotorlab.analyses import basin_mapper

    tm = basin_mapper(torus.model, torus.analysis("basin-k1e-5"))
    bm = basin_mapper(auto.model, auto.analysis("basin"))
    assert isinstance(tm, TorusRegimes) and isinstance(bm, BalancerRegimes)
    named = {m: {k for k in m.coordinate_units if not k.startswith("model.")} for m in (tm, bm)}
    assert set(coordinate_dimensions(torus.model)) == named[tm] == set(TORUS_COORDINATES)
    assert set(coordinate_dimensions(auto.model)) == named[bm]
    assert set(BALANCER_COORDINATES) < named[bm]
    # every number of the [model] table as model.<key path>: the spec takes it too (sweeps_keys)
    for mapper, model in ((tm, torus.model), (bm, auto.model)):
        keys = set(mapper.coordinate_units) - named[mapper]
        assert keys == {f"model.{n}" for n in mapper.model.parameters.names} and len(keys) >= 7
        known = sweep_coordinates(model, "param")
        assert all(k in known for k in keys) and "model.balls[9].mass" not in known
    # the io dimensions give the mapper's units
    for mapper, model in ((tm, torus.model), (bm, auto.model)):
        for name, dim in coordinate_dimensions(model).items():
            unit = mapper.coordinate_units[name].replace(" ", "*")
            assert DIMENSIONS[dim].si.replace(" ", "*") in (unit, "") or (dim, unit) == ("dimensionless", "1")


def test_builtin_cases_parse_to_si():
    case = load_case("strautmanis-torus")
    m = case.model
    assert (m.ring_radius, m.tube_radius, m.ball_radius, m.spin_speed, m.offset, m.rolling_friction) == (
        0.2, 0.015, 0.0125, 140.0, 0.02, 1e-5)
    a, b = case.analysis("basin-k1e-5"), case.analysis("basin-k1e-4")
    assert a.x == ("psi", 0.0, 2 * math.pi, 48) and a.y == ("dpsi", -280.0, 140.0, 48)
    assert a.fixed == {"alpha": 0.0, "dalpha": 0.0}
    assert b.fixed == {"alpha": 0.0, "dalpha": 0.0, "rolling_friction": 1e-4}
    assert a.t_end == b.t_end == 240.0
    # round trip through the writer
    again = parse_case(dump_case(case))
    assert again.analysis("basin-k1e-4").fixed == b.fixed and again.model == case.model
    auto = load_case("autobalancer").analysis("basin")
    assert auto.x == ("psi_1", 0.0, math.radians(350.0), 36) and auto.speed_ratio == 2.0


BAD = [
    ('x = ["psy", 0, 1, 3]', "unknown coordinate 'psy'; did you mean 'psi'?"),
    ('x = ["psi", "0 kg", 1, 3]', "start: wrong dimension: expected an angle (rad), got mass"),
    ('x = ["psi", 0, 1, 0]', "count (the fourth entry) must be an integer >= 1"),
    ('x = ["psi", 1, 0, 3]', "stop must be > start"),
    ('x = ["psi", 0, 1]', "must be [name, start, stop, count]"),
    ('x = ["rolling_friction", -1e-5, 1e-4, 3]', "must be >= 0 (m)"),
    ('x = ["dpsi", 0, 1, 3]', "must vary another coordinate than x (dpsi)"),
    ('x = ["psi_1", 0, 1, 3]', "'psi_1' is not a coordinate of this toroidal_ball model"),
    ('x = ["ball_radius", 0.01, 0.02, 3]', "ball_radius must stay < tube_radius at every start"),
    ('x = ["psi", 0, 1, 3]\nfixed = { dpsi = 0 }', "is varied by x or y; it cannot also be fixed"),
    ('x = ["psi", 0, 1, 3]\nspeed_ratio = 2', "applies to a rotor with balls only"),
    ('x = ["psi", 0, 1, 3]\nsamples = 0', "must be an integer >= 1"),
    ('x = ["psi", 0, 1, 3]\nfixed = { alpha = "2 s" }', "alpha: wrong dimension"),
]


@pytest.mark.parametrize(("line", "message"), BAD)
def test_bad_basin_entries_name_the_key(line, message):
    text = load_case("strautmanis-torus").text.split("[[analysis]]")[0]
    text += f'[[analysis]]\ntype = "basin"\ny = ["dpsi", -10, 10, 2]\n{line}\n'
    with pytest.raises(CaseError) as err:
        parse_case(text, "bad.toml")
    assert message in str(err.value)
    assert "analysis[0]." in str(err.value) or "analysis[0]:" in str(err.value)


def test_balancer_basin_needs_a_constant_speed_and_balls():
    auto = load_case("autobalancer").text
    head = auto.split("[[analysis]]")[0].replace('[model.speed]\nprofile = "constant"\nspeed = "2400 rpm"', "")
    with pytest.raises(CaseError, match="needs a constant spin speed"):
        parse_case(head + '[[analysis]]\ntype = "basin"\nx = ["psi_1", 0, 1, 2]\ny = ["psi_2", 0, 1, 2]\n')
    with pytest.raises(CaseError, match="applies to a toroidal_ball model only"):
        parse_case(head + '[[analysis]]\ntype = "basin"\nspeed_ratio = 2\nspare_turns = 1\n'
                   'x = ["psi_1", 0, 1, 2]\ny = ["psi_2", 0, 1, 2]\n')
    with pytest.raises(CaseError, match="needs a toroidal_ball model"):
        parse_case(head + '[[analysis]]\ntype = "working-point"\n')


# --------------------------------------------------------------------------- analyses


def test_working_point_analysis_holds_the_papers_point():
    case = load_case("strautmanis-torus")
    ds = run_basin_analysis(case.model, case.analysis("working-point"))
    rows = {r["quantity"]: r["value"] for r in basin_rows(ds)}
    assert rows["psi_band_lo"] < 3.14156 < rows["psi_band_hi"]
    assert rows["alpha_band_lo"] < 1.56825 < rows["alpha_band_hi"]
    assert rows["psi"] == pytest.approx(math.pi, abs=1e-15)
    # Fig. 3: the tangential force vanishes at pi and pulls back towards it on both sides
    t = ds.tangential.values
    i = int(np.argmin(abs(ds.ring_angle.values - math.pi)))
    assert abs(t[i]) < 1e-9 and t[i - 10] > 0 and t[i + 10] < 0
    assert ds.ring_angle.size == 361 and ds.tangential.attrs["units"] == "N/kg"
    # Fig. 5: a ball released at psi = 2 rad, alpha = 0 spirals in and sticks inside the band
    assert ds.attrs["release_stuck"] == 1 and 0.0 < rows["released_settle_time"] < 10.0
    assert rows["psi_band_lo"] <= rows["released_final_psi"] <= rows["psi_band_hi"]
    assert rows["alpha_band_lo"] <= rows["released_final_alpha"] <= rows["alpha_band_hi"]
    assert ds.release_psi.values[0] == 2.0 and ds.release_dpsi.attrs["units"] == "rad/s"


def test_each_mapper_gives_the_value_its_starts_use():
    # start_value(name) is the value the starts take for a coordinate not given: giving that
    # value explicitly changes no start state and no parameter, for every coordinate.
    from rotorlab.analyses import basin_mapper
    from rotorlab.analyses._case import build_model
    from rotorlab.explore import MachineRegimes

    torus, auto = load_case("strautmanis-torus"), load_case("autobalancer")
    pico = load_case("pico21-balancer")
    mappers = [basin_mapper(torus.model, torus.analysis("basin-k1e-5")),
               basin_mapper(auto.model, auto.analysis("basin")), MachineRegimes(build_model(pico.model))]
    for mapper in mappers:
        _, y_base, p_base = mapper.starts({})
        for name in mapper.coordinate_units:
            value = mapper.start_value(name)
            assert value is not None, name
            _, y, p = mapper.starts({name: np.array([value])})
            np.testing.assert_allclose(y, y_base, rtol=1e-15, atol=0, err_msg=name)
            np.testing.assert_allclose(p, p_base, rtol=1e-15, atol=0, err_msg=name)
    # the case files' numbers (SI): the torus offset 20 mm; the autobalancer basin at twice
    # p = sqrt(c / (M1 + 2 m)), 30 g balls; pico21-balancer at 10000 rpm with 5 g balls
    torus_m, auto_m, pico_m = mappers
    assert torus_m.start_value("offset") == 0.02 and torus_m.start_value("psi") == 0.0
    assert auto_m.start_value("spin_speed") == pytest.approx(2.0 * math.sqrt(16740.0 / 1.06), rel=1e-15)
    assert auto_m.start_value("ball_mass") == 0.03 and auto_m.start_value("dpsi_2") == 0.0
    assert auto_m.start_value("psi_3") is None and auto_m.start_value("model.x") is None
    assert pico_m.start_value("spin_speed") == pytest.approx(10000.0 * math.pi / 30.0, rel=1e-15)
    assert pico_m.start_value("ball_mass") == 0.005 and pico_m.start_value("ball_damping") == 2e-4
    assert pico_m.start_value("psi_4") == pico_m.base_angles[3] and pico_m.start_value("psi_5") is None


def test_basin_analysis_fractions_and_document():
    case = parse_case(_small_torus())
    ds = run_basin_analysis(case.model, case.analysis("basin-k1e-4"), chunk_size=7)
    assert ds.label.dims == ("dpsi", "psi", "horizon") and ds.label.shape == (5, 5, 3)
    assert np.allclose(ds.fraction.sum("regime"), 1.0)
    assert ds.attrs["fixed_rolling_friction"] == 1e-4
    doc = basin_document(ds)
    assert doc["n"] == 25 and doc["mode"] == "grid" and doc["t_end_s"] == 6.0
    assert set(doc["fractions"]) == {"working", "spare", "other"}
    assert sum(doc["fractions"].values()) == pytest.approx(1.0)
    counts = {k: int((ds.outcome.values == j).sum()) for j, k in enumerate(doc["fractions"])}
    assert {k: v * 25 for k, v in doc["fractions"].items()} == pytest.approx(counts)
    json.dumps(doc)  # JSON-ready
    # same fractions whatever the chunking
    again = run_basin_analysis(case.model, case.analysis("basin-k1e-4"), chunk_size=25)
    assert np.array_equal(again.label.values, ds.label.values)


def test_random_basin_has_wilson_intervals_and_is_seeded():
    text = _small_torus() + '\n[[analysis]]\ntype = "basin"\nname = "random"\nsamples = 20\nseed = 7\n' \
        'x = ["psi", 0, 6.28, 2]\ny = ["dpsi", -100, 100, 2]\nt_end = "3 s"\nn_horizons = 2\n'
    case = parse_case(text)
    a = run_basin_analysis(case.model, case.analysis("random"))
    b = run_basin_analysis(case.model, case.analysis("random"))
    assert a.label.dims == ("ic", "horizon") and a.sizes["ic"] == 20
    assert np.array_equal(a.psi.values, b.psi.values) and np.array_equal(a.label.values, b.label.values)
    doc = basin_document(a)
    assert doc["mode"] == "random" and doc["seed"] == 7
    for name, (lo, hi) in doc["ci"].items():
        assert lo <= doc["fractions"][name] <= hi


def test_compare_basins_verdict_follows_the_numbers():
    import xarray as xr

    def fake(name, k, fractions):
        fr = np.array(fractions, dtype=float)
        return xr.Dataset({"fraction": (("horizon", "regime"), np.stack([fr, 1 - fr], axis=1))},
                          coords={"horizon": [10.0, 20.0, 30.0], "regime": ["working", "spare"]},
                          attrs={"analysis": "basin", "x": "psi", "y": "dpsi", "mode": "grid",
                                 "fixed_alpha": 0.0, "fixed_rolling_friction": k})  # fmt: skip

    grows = compare_basins({"a": fake("a", 1e-5, [0.2, 0.5, 0.9]), "b": fake("b", 1e-4, [0.6, 0.8, 0.95])})
    assert grows["parameter"] == "rolling_friction" and grows["larger_wins"] == [True, True, True]
    assert "gives a larger working fraction" in grows["verdict"] and "With larger" not in grows["verdict"]
    flips = compare_basins({"a": fake("a", 1e-5, [0.2, 0.5, 0.99]), "b": fake("b", 1e-4, [0.6, 0.8, 0.97])})
    assert flips["larger_wins"] == [True, True, False]
    assert flips["verdict"] == ("After 30 s, rolling_friction = 0.0001 gives a smaller working fraction than "
                                "rolling_friction = 1e-05: 97.0% against 99.0%. With larger rolling_friction the "
                                "working fraction is larger at 10-20 s and smaller at 30 s.")
    assert compare_basins({"a": fake("a", 1e-5, [0.1, 0.2, 0.3])}) is None


# --------------------------------------------------------------------------- command line


def test_basin_command_json_plot_and_netcdf(tmp_path):
    case = tmp_path / "torus.toml"
    case.write_text(_small_torus())
    png, nc = tmp_path / "map.png", tmp_path / "map.nc"
    res = invoke("basin", str(case), "--x", "psi=0:360deg:4", "--y", "dpsi=-280:140:3", "--t-end", "4",
                 "--fix", "rolling_friction=0.1mm", "--plot", str(png), "--out", str(nc), "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["n"] == 12 and doc["t_end_s"] == 4.0 and doc["x"] == "psi" and doc["y"] == "dpsi"
    assert doc["fixed"]["rolling_friction"] == pytest.approx(1e-4)
    assert sum(doc["fractions"].values()) == pytest.approx(1.0)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    from rotorlab.io import load_netcdf

    ds = load_netcdf(nc)
    assert ds.label.shape == (3, 4, 3) and ds.psi.values[-1] == pytest.approx(2 * math.pi)


def test_basin_command_random_and_table(tmp_path):
    res = invoke("basin", "autobalancer", "--x", "psi_1=0:6.2:2", "--y", "psi_2=0:6.2:2", "--random", "6",
                 "--seed", "3", "--t-end", "4")
    assert res.exit_code == 0, res.output
    assert "balanced" in res.stdout and "6 starts" in res.stdout
    js = invoke("basin", "autobalancer", "--x", "psi_1=0:6.2:2", "--y", "psi_2=0:6.2:2", "--random", "6",
                "--seed", "3", "--t-end", "4", "--json")
    doc = json.loads(js.stdout)
    assert doc["mode"] == "random" and doc["n"] == 6 and set(doc["ci"]) == set(doc["fractions"])


@pytest.mark.parametrize(("args", "message"), [
    (("--x", "psy=0:1:3"), "--x = psy=0:1:3: 'psy' is not a coordinate"),
    (("--x", "psi_1=0:1"), "must be START:STOP:N"),
    (("--x", "psi_1=0:1kg:3"), "wrong dimension"),
    (("--fix", "disc_mass=-1"), "--fix: disc_mass: must be > 0 (kg)"),
    (("--fix", "nothing=1"), "--fix = nothing=1: must be NAME=VALUE"),
    (("--t-end", "-3"), "--t-end = -3: must be a finite number > 0 (s)"),
    (("--random", "0"), "--random = 0: must be an integer >= 1"),
    (("--analysis", "nope"), "--analysis = nope: no basin analysis of that name (basin analyses: basin)"),
    (("--x", "psi_1=0:1:3", "--y", "psi_1=0:2:3"), "must vary another coordinate than --x"),
])
def test_basin_command_bad_input(tmp_path, args, message):
    out = tmp_path / "never.nc"
    res = invoke("basin", "autobalancer", *args, "--out", str(out))
    assert res.exit_code == 2, res.output
    assert message in res.output and "Traceback" not in res.output
    assert not out.exists()


def test_basin_command_needs_a_basin_model(tmp_path):
    res = invoke("basin", "pico21")
    assert res.exit_code == 2 and "basins need a jeffcott_balls, toroidal_ball or machine model" in res.output
    case = tmp_path / "no-basin.toml"
    case.write_text(load_case("strautmanis-torus").text.split("[[analysis]]")[0])
    res = invoke("basin", str(case), "--x", "psi=0:1:2")
    assert res.exit_code == 2 and "has no basin analysis: give --y" in res.output


def test_run_writes_basin_sections_and_the_friction_comparison(tmp_path):
    case = tmp_path / "torus.toml"
    case.write_text(_small_torus(n=4))
    out = tmp_path / "out"
    res = invoke("run", str(case), "--out", str(out), "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert set(doc["analyses"]) == {"working-point", "basin-k1e-5", "basin-k1e-4"}
    for name in ("basin-k1e-5_map", "basin-k1e-5_fractions", "basin-k1e-4_map", "working-point_force",
                 "working-point_phase"):
        assert (out / f"{name}.png").is_file()
    page = (out / "report.html").read_text()
    assert "Comparison: working fraction against rolling_friction" in page
    results = run_case(parse_case(case.read_text()))
    verdict = compare_basins(results)["verdict"]
    assert verdict in page.replace("&#x27;", "'")
    assert "seed 004 (rad)" in page and "friction band" in page
