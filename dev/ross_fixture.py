"""Make the ROSS fixture of tests/unit/test_ross_import.py (not run by the tests).

ROSS is not a dependency of rotorlab: run this in a throwaway environment,

    python -m venv /tmp/rossvenv && /tmp/rossvenv/bin/pip install ross-rotordynamics
    /tmp/rossvenv/bin/python dev/ross_fixture.py

It builds ROSS's own example rotor (``ross.rotor_assembly.rotor_example``: six Timoshenko shaft
elements of 0.25 m, two steel discs, two bearings of kxx = 1 MN/m, kyy = 0.8 MN/m), saves it with
``Rotor.save`` to tests/data/ross/rotor_example.toml, and records ROSS's natural frequencies
(``run_modal``: wn, undamped, and wd, damped, rad/s, with ROSS's mode type, lateral, axial or
torsional, and whirl) at rest and at 500 rad/s beside it in
tests/data/ross/rotor_example.json.
"""

import json
from pathlib import Path

import ross

OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "ross"
SPEEDS = (0.0, 500.0)  # rad/s
N_MODES = 8


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    rotor = ross.rotor_example()
    toml = OUT / "rotor_example.toml"
    toml.unlink(missing_ok=True)  # Rotor.save adds to an existing file
    rotor.save(toml)
    modal = {}
    for speed in SPEEDS:
        m = rotor.run_modal(speed=speed, num_modes=2 * N_MODES)
        modal[f"{speed:g}"] = {
            "wn_rad_s": [float(v) for v in m.wn[:N_MODES]],
            "wd_rad_s": [float(v) for v in m.wd[:N_MODES]],
            # ROSS models 6 DOFs a node: some of its modes are axial or torsional
            "mode_type": [m.shapes[k].mode_type for k in range(N_MODES)],
            "whirl": [str(w) for w in m.whirl_direction()[:N_MODES]],
        }
    doc = {
        "ross_version": ross.__version__,
        "rotor": "ross.rotor_assembly.rotor_example()",
        "file": toml.name,
        "script": "dev/ross_fixture.py",
        "speeds_rad_s": list(SPEEDS),
        "modal": modal,
    }
    (OUT / "rotor_example.json").write_text(json.dumps(doc, indent=2) + "\n")
    print(json.dumps(doc, indent=2))


if __name__ == "__main__":
    main()
