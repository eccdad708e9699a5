"""Sweep ranges outside a parameter's allowed values (issue 28 item 13).

A sweep over a model parameter whose range leaves the key's limits (a negative mass or radius,
a restitution above 1) used to create its Zarr store and fail on its first chunk, so that
``--resume`` could never finish it. The range is now checked against the model's named
parameters (:class:`rotorlab.models.ParameterSpace`, the same limits as the case file's keys)
before anything is written: exit code 2, the option, the value and the allowed range, no store.
Each end of a range also passes the model's own checks (a ball inside its tube), again before
the store. No entry integrates anything.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

runner = CliRunner()

#: (id, arguments after ``sweep CASE --out STORE``, words of the message)
RANGES = [
    ("machine-ball-mass-negative", ["pico21-balancer", "--speed-rpm", "3000", "--param",
                                    "model.races[0].balls[1].mass=-10g:20g:3"],
     ["--param", "model.races[0].balls[1].mass = -0.01", "must be > 0 kg"]),
    ("machine-race-radius-negative", ["pico21-balancer", "--speed-rpm", "3000", "--param",
                                      "model.races[0].radius=-0.1:0.1:2"],
     ["--param", "model.races[0].radius = -0.1", "must be > 0 m"]),
    ("machine-unbalance-sample", ["pico21-balancer", "--speed-rpm", "3000", "--sample", "4", "--param",
                                  "model.unbalances[0].magnitude=-1e-4:1e-4"],
     ["--param", "model.unbalances[0].magnitude = -0.0001", "must be >= 0 kg*m"]),
    ("machine-restitution-above-one", ["washer-knock", "--speed-rpm", "600", "--param",
                                       "model.clearances[0].restitution=0.5:1.5:2"],
     ["--param", "model.clearances[0].restitution = 1.5", "must be >= 0 and <= 1"]),
    ("machine-bearing-stiffness-negative", ["washer-horizontal", "--speed-rpm", "600", "--param",
                                            "model.structure.bearings[0].kxx=-1:1:2"],
     ["--param", "model.structure.bearings[0].kxx = -1", "must be >= 0 N/m"]),
    ("machine-ball-damping-negative", ["pico21-balancer", "--speed-rpm", "3000", "--param",
                                       "ball_damping=-1e-3:1e-3:2"],
     ["--param", "ball_damping = -0.001", "must be >= 0"]),
    ("jeffcott-disc-mass-zero", ["autobalancer", "--param", "disc_mass=0:1:2"],
     ["--param", "disc_mass = 0", "must be > 0 kg"]),
    ("jeffcott-ball-mass-negative", ["autobalancer", "--param", "ball_mass=-1:0.02:2"],
     ["--param", "ball_mass = -1", "must be > 0 kg"]),
    ("jeffcott-key-path-ball-mass-negative", ["autobalancer", "--param", "model.balls[1].mass=-1:0.02:2"],
     ["--param", "model.balls[1].mass = -1", "must be > 0 kg"]),
    ("jeffcott-spin-speed-zero", ["autobalancer", "--param", "spin_speed=0:100:2"],
     ["--param", "spin_speed = 0", "must be > 0 rad/s"]),
    ("torus-key-path-offset-negative", ["strautmanis-torus", "--param", "model.offset=-1e-3:1e-3:2",
                                        "--ic", "psi=0:1:2"],
     ["--param", "model.offset = -0.001", "must be >= 0 m"]),
    ("torus-ball-radius-beyond-the-tube", ["strautmanis-torus", "--param", "model.ball_radius=0.01:0.02:2",
                                           "--ic", "psi=0:1:2"],
     ["--param = model.ball_radius=0.01:0.02:2", "ball_radius must be < tube_radius (0.015 m), got 0.02"]),
    ("torus-rolling-friction-negative", ["strautmanis-torus", "--param", "rolling_friction=-1e-4:1e-4:2",
                                         "--ic", "psi=0:1:2"],
     ["--param", "rolling_friction = -0.0001", "must be >= 0 m"]),
]


@pytest.mark.parametrize("name, args, words", RANGES, ids=[r[0] for r in RANGES])
def test_a_range_outside_the_limits_is_refused_before_the_store(name, args, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    store = tmp_path / "s.zarr"
    result = runner.invoke(app, ["sweep", args[0], "--out", str(store), "--t-end", "1", *args[1:]])
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output, result.output
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    assert list(tmp_path.iterdir()) == [], "something was written"


def test_the_check_refuses_only_values_outside_the_limits():
    """The ends of a range are checked against the key's limits: inside them (and on a closed
    limit) the sweep is built and passes; one end outside is refused."""
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.cli._output import BadInput
    from rotorlab.cli._sweep import _check_ranges
    from rotorlab.io import SweepSpec, load_case

    case = load_case("pico21-balancer")
    spec = SweepSpec(name="s", speed="3000 rpm", t_end=1.0)
    for key, ok, bad in (("model.races[0].balls[1].mass", (0.01, 0.02, 3), (-0.01, 0.02, 3)),
                         ("model.unbalances[0].magnitude", (0.0, 1e-4, 2), (-1e-9, 1e-4, 2))):
        sweep = build_sweep(case.model, spec, axes={key: ok})
        _check_ranges(sweep.analysis.mapper, (("--param", [f"{key}=..."]),), {key: ok})
        with pytest.raises(BadInput, match="is outside its allowed range"):
            _check_ranges(sweep.analysis.mapper, (("--param", [f"{key}=..."]),), {key: bad})
