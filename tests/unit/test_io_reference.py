"""The case-file key reference (:mod:`rotorlab.io._reference`) reads units and ranges off the
schema: checked against fields whose declarations are known, and for completeness."""

from __future__ import annotations

from rotorlab.io import ANALYSIS_SPECS, MODEL_SPECS
from rotorlab.io._reference import case_keys, top_level_keys


def _row(rows, path):
    return next(r for r in rows if r.path == path)


def test_declared_units_and_ranges():
    keys = case_keys()
    fe = keys["model"]["fe_rotor"]
    # quantity("pressure", gt=0), required
    assert (_row(fe, "material.youngs_modulus").unit, _row(fe, "material.youngs_modulus").allowed,
            _row(fe, "material.youngs_modulus").default) == ("Pa", "> 0", "required")
    # integer(ge=1) with default 1
    assert (_row(fe, "shaft[].elements").kind, _row(fe, "shaft[].elements").allowed,
            _row(fe, "shaft[].elements").default) == ("integer", ">= 1", "1")
    assert _row(fe, "bearings[].cxx").unit == "N*s/m"
    assert _row(fe, "shear").kind == "true/false" and _row(fe, "shear").default == "true"
    balls = keys["model"]["jeffcott_balls"]
    assert _row(balls, "balls[].damping").unit == "N*m*s/rad"
    # the speed profile: a table chosen by its "profile" key, each profile's keys listed
    assert "constant" in _row(balls, "speed").allowed
    assert _row(balls, "speed.duration").unit == "s"
    hill = _row(balls, "speed.exponent")
    assert hill.allowed == ">= 0.01 and <= 1000"
    simulate = keys["analysis"]["simulate"]
    assert _row(simulate, "initial_ball_angles").unit == "rad"
    assert _row(simulate, "n_save").default == "2000"
    assert [k.path for k in top_level_keys()] == ["schema_version", "name", "description"]


def test_every_field_is_listed():
    keys = case_keys()
    assert list(keys["model"]) == list(MODEL_SPECS)
    assert list(keys["analysis"]) == list(ANALYSIS_SPECS)
    for where, specs in (("model", MODEL_SPECS), ("analysis", ANALYSIS_SPECS)):
        for kind, spec in specs.items():
            paths = {r.path for r in keys[where][kind]}
            for name, field in spec.model_fields.items():
                assert (field.alias or name) in paths, (kind, name)
            # every quantity row has its SI unit, unless dimensionless
            for r in keys[where][kind]:
                assert r.kind and r.default, (kind, r)
