"""A rotor saved by ROSS, imported with rotorlab.io.import_ross: ROSS's own natural frequencies.

The fixture tests/data/ross/rotor_example.toml was written by ROSS 2.3.0 (``Rotor.save``) from
its ``rotor_example()`` (six Timoshenko elements of 0.25 m, d = 50 mm, two steel discs of
32.6 kg at nodes 2 and 4, bearings kxx = 1 MN/m, kyy = 0.8 MN/m at both ends, undamped);
rotor_example.json beside it holds ROSS's ``run_modal`` frequencies (wn and wd, rad/s) at 0 and
500 rad/s with ROSS's mode types and whirl, made by dev/ross_fixture.py.

Tolerance 1e-9 relative. Both codes use the same element: the Timoshenko beam with shear
(Cowper's coefficient for a circular section), rotary inertia and the gyroscopic matrix, as in
Friswell et al. (2010), Chapter 5; with identical data the frequencies agree to round-off
(measured 7e-13 at rest, 9e-13 at 500 rad/s), and the whirl of each mode at 500 rad/s agrees
where ROSS calls it forward or backward. Two differences in what is modelled: ROSS has six
DOFs a node and one of its eight lowest modes is torsional (774.35 rad/s, the same at both
speeds), which rotorlab's lateral model does not have: the comparison takes ROSS's lateral
modes. The supports are anisotropic, so at rest each whirl is elliptical ("mixed").
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from rotorlab.io import CaseError, import_ross, validate_case
from rotorlab.linear import modal

DATA = Path(__file__).parents[1] / "data" / "ross"
REFERENCE = json.loads((DATA / "rotor_example.json").read_text())


def _system():
    from rotorlab.analyses import build_linear_system

    return build_linear_system(validate_case(import_ross(DATA / "rotor_example.toml")).model)


def test_fixture_was_written_by_ross() -> None:
    assert REFERENCE["ross_version"] == "2.3.0"
    assert 'ross_version = "2.3.0"' in (DATA / "rotor_example.toml").read_text()


@pytest.mark.parametrize("speed", REFERENCE["speeds_rad_s"])
def test_natural_frequencies_match_ross(speed: float) -> None:
    ref = REFERENCE["modal"][f"{speed:g}"]
    lateral = [k for k, t in enumerate(ref["mode_type"]) if t == "Lateral"]
    assert len(lateral) == 7  # one torsional mode among ROSS's eight lowest
    wn = np.array(ref["wn_rad_s"])[lateral]
    wd = np.array(ref["wd_rad_s"])[lateral]
    modes = modal(_system(), speed, n_modes=len(lateral))
    lam = modes.eigenvalues
    np.testing.assert_allclose(np.abs(lam), wn, rtol=1e-9)     # undamped natural frequencies
    np.testing.assert_allclose(np.abs(lam.imag), wd, rtol=1e-9)  # damped (no damping: the same)
    # whirl where ROSS calls it forward or backward, at 500 rad/s: B F B F B F (at rest the
    # orbits on these anisotropic supports are straight lines: no whirl direction to compare)
    code = {"Forward": 1, "Backward": -1}
    for k, j in enumerate(lateral if speed > 0 else ()):
        if ref["whirl"][j] in code:
            assert modes.whirl[k] == code[ref["whirl"][j]], (speed, k)


def test_imported_model_carries_ross_data() -> None:
    model = validate_case(import_ross(DATA / "rotor_example.toml")).model
    assert model.n_elements == 6 and model.shear and model.rotary_inertia and model.gyroscopic
    assert model.material.youngs_modulus == pytest.approx(211e9)
    assert [d.mass for d in model.discs] == pytest.approx([32.58972765304033] * 2)
    b = model.bearings[0]
    assert (b.kxx, b.kyy) == (1e6, 8e5)


@pytest.mark.parametrize(("old", "new", "words"), [
    ("odr = 0.05\n", "odr = 0.06\n", ["Shaft Element 0", "odr = 0.06", "tapered"]),
    ("kxx = [ 1000000.0,]", "kxx = [ 1000000.0, 2000000.0,]", ["Bearing 0", "kxx", "2 values"]),
    ("mxx = [ 0,]", "mxx = [ 5.0,]", ["Bearing 0", "mxx", "mass"]),
    ('["DiskElement_Disk 1"]', '["PointMass_Disk 1"]', ["PointMass", "supported: ShaftElement"]),
    ("alpha = 0.0", "alpha = 1.5", ["alpha = 1.5", "must be 0"]),
])
def test_what_fe_rotor_cannot_hold_is_refused(tmp_path: Path, old: str, new: str, words: list[str]) -> None:
    text = (DATA / "rotor_example.toml").read_text()
    assert old in text
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(old, new, 1))
    with pytest.raises(CaseError) as err:
        import_ross(bad)
    for w in words:
        assert w in str(err.value), str(err.value)
