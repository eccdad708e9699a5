"""The bad-input corpus (issue 14): malformed and edge inputs of every command and case type.

Each entry is a command line, optionally with a case file made by one text change of a built-in
case (each model type: jeffcott_balls, multibody, fe_rotor, toroidal_ball, impact_rotor). For
every one: exit code 2, a message on stderr that names the key path or option (and what is
wrong), no traceback, and nothing written (the folder the command runs in holds exactly what it
held before). Every entry fails at validation or at a size check before any long computation,
so the corpus runs in seconds.

A bad input that is not refused cleanly is a bug: add it here.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import pytest
from typer.testing import CliRunner

from _bad_inputs_design import ENTRIES

from rotorlab.cli import app

runner = CliRunner()


def builtin(name: str) -> str:
    return resources.files("rotorlab.cases").joinpath(f"{name}.toml").read_text(encoding="utf-8")


def mutate(case: str, old: str, new: str, count: int = 1) -> str:
    text = builtin(case)
    assert old in text, f"{old!r} not in {case}"
    return text.replace(old, new, count)


# (id, argv with {d} for the working folder, {case: (base, old, new)} or None, words of the message)
FILE = "{d}/case.toml"
CORPUS: list[tuple[str, list[str], tuple[str, str, str] | None, list[str]]] = [
    # ---- run, with case files of every model type ------------------------------------------
    ("run-unknown-case", ["run", "no-such-case", "--out", "{d}/o"], None, ["no-such-case"]),
    ("run-missing-file", ["run", "{d}/missing.toml", "--out", "{d}/o"], None, ["missing.toml"]),
    ("run-out-is-a-file", ["run", "autobalancer", "--out", "{d}/notes.txt"], None, ["notes.txt"]),
    ("jb-wrong-unit", ["run", FILE, "--out", "{d}/o"], ("autobalancer", 'disc_mass = "1 kg"', 'disc_mass = "1 m"'),
     ["model.disc_mass", "wrong dimension", "mass"]),
    ("jb-garbled-unit", ["validate", FILE], ("autobalancer", 'disc_mass = "1 kg"', 'disc_mass = "1 kg kg / / ("'),
     ["model.disc_mass", "cannot read the unit", "matched parentheses"]),
    ("jb-wrong-type", ["validate", FILE], ("autobalancer", 'disc_mass = "1 kg"', "disc_mass = true"),
     ["model.disc_mass"]),
    ("jb-absurd-ball-count", ["run", FILE, "--out", "{d}/o"], ("autobalancer", "count = 2", "count = 1e8"),
     ["model.balls[0].count", "at most 1000 balls", "TiB"]),
    ("jb-zero-ball-count", ["validate", FILE], ("autobalancer", "count = 2", "count = 0"),
     ["model.balls[0].count", ">= 1"]),
    ("jb-empty-ball-angles", ["simulate", FILE], ("autobalancer", "initial_ball_angles = [\n    [\"0 deg\", \"90 deg\"],\n    [\"45 deg\", \"200 deg\"],\n    [\"120 deg\", \"240 deg\"],\n    [\"170 deg\", \"190 deg\"],\n    [\"300 deg\", \"30 deg\"],\n    [\"10 deg\", \"350 deg\"],\n]", "initial_ball_angles = []"),
     ["analysis[0].initial_ball_angles", "empty"]),
    ("jb-non-ascii-name", ["validate", FILE], ("autobalancer", 'name = "autobalancer"', 'name = "ротор"'),
     ["name", "ASCII letters"]),
    ("jb-unknown-key", ["validate", FILE], ("autobalancer", 'frame = "fixed"', 'frame = "fixed"\nframe_rate = 3'),
     ["model.frame_rate", "unknown key"]),
    ("jb-schema-version", ["validate", FILE], ("autobalancer", "schema_version = 1", "schema_version = 2"),
     ["schema_version", "1"]),
    ("jb-negative-eccentricity", ["validate", FILE], ("autobalancer", 'eccentricity = "1.5 mm"', 'eccentricity = "-1.5 mm"'),
     ["model.eccentricity", ">= 0"]),
    ("jb-nan-stiffness", ["validate", FILE], ("autobalancer", 'stiffness = "16.74 kN/m"', "stiffness = nan"),
     ["model.stiffness", "finite"]),
    ("jb-inf-damping", ["validate", FILE], ("autobalancer", 'damping = "13.32 N*s/m"', "damping = inf"),
     ["model.damping", "finite"]),
    ("jb-speed-in-kg", ["validate", FILE], ("autobalancer", 'speed = "2400 rpm"', 'speed = "2400 kg"'),
     ["model.speed.speed", "wrong dimension"]),
    ("jb-negative-t-end", ["validate", FILE], ("autobalancer", 't_end = "20 s"', 't_end = "-20 s"'),
     ["analysis[0].t_end", "> 0"]),
    ("jb-ratio-with-unit", ["validate", FILE], ("autobalancer", "speed_ratio = 0.6", 'speed_ratio = "0.6 rpm"'),
     ["analysis[0].speed_ratio"]),
    ("jb-rtol-too-big", ["validate", FILE], ("autobalancer", "rtol = 1e-8", "rtol = 2"),
     ["analysis[0].rtol", "< 1"]),
    ("jb-typo-analysis-type", ["validate", FILE], ("autobalancer", 'type = "simulate"', 'type = "simulat"'),
     ["analysis[0].type", "simulate"]),
    ("jb-typo-model-type", ["validate", FILE], ("autobalancer", 'type = "jeffcott_balls"', 'type = "jeffcott_ball"'),
     ["model.type", "jeffcott_balls"]),
    ("jb-unknown-basin-coordinate", ["validate", FILE], ("autobalancer", 'x = ["psi_1"', 'x = ["psi_9"'),
     ["analysis[2].x", "psi_9"]),
    ("jb-n-save-absurd", ["simulate", FILE, "--analysis", "subcritical", "--t-end", "0.1"],
     ("autobalancer", "n_save = 2000", "n_save = 1e10"), ["n_save = 10000000000", "memory", "TiB"]),
    ("jb-n-save-one", ["validate", FILE], ("autobalancer", "n_save = 2000", "n_save = 1"),
     ["analysis[0].n_save", ">= 2"]),
    ("jb-basin-grid-absurd", ["basin", FILE, "--t-end", "0.1"],
     ("autobalancer", '"350 deg", 36]', '"350 deg", 100000]', 2), ["1e+10 points", "psi_1", "memory"]),
    ("mb-negative-mass", ["validate", FILE], ("pico21", 'mass = "2.4 kg"', 'mass = "-2.4 kg"'),
     ["model.bodies[0].mass", "> 0"]),
    ("mb-inertia-wrong-unit", ["run", FILE, "--out", "{d}/o"], ("pico21", 'diametral_inertia = "0.018 kg*m^2"',
                                                                'diametral_inertia = "0.018 kg*m"'),
     ["model.bodies[0].diametral_inertia", "wrong dimension"]),
    ("mb-campbell-stop-wrong-unit", ["campbell", FILE], ("pico21", 'stop = "15000 rpm"', 'stop = "15000 m"'),
     ["stop", "wrong dimension"]),
    ("fe-zero-elements", ["campbell", FILE], ("friswell-rotor", "elements = 6", "elements = 0"),
     ["model.shaft", "elements"]),
    ("fe-density-wrong-unit", ["modes", FILE], ("friswell-rotor", 'density = "7810 kg/m^3"', 'density = "7810 kg/m^2"'),
     ["density", "wrong dimension"]),
    ("fe-unknown-key", ["validate", FILE], ("friswell-rotor", "gyroscopic = true", "gyroscopic = true\ngyro = 1"),
     ["model.gyro", "unknown key"]),
    ("tb-negative-ring", ["validate", FILE], ("strautmanis-torus", 'ring_radius = "0.2 m"', 'ring_radius = "-0.2 m"'),
     ["model.ring_radius", "> 0"]),
    ("tb-basin-count-fraction", ["basin", FILE], ("strautmanis-torus", '"360 deg", 48]', '"360 deg", 4.5]'),
     ["analysis[1].x", "integer"]),
    ("tb-form-typo", ["sweep", FILE, "--out", "{d}/s.zarr"], ("strautmanis-torus", 'form = "rolling"', 'form = "roling"'),
     ["model.form", "rolling"]),
    ("ir-restitution-above-one", ["impacts", FILE], ("krasnov-crusher", "restitution = 0.5", "restitution = 1.5"),
     ["model.housing.restitution", "<= 1"]),
    ("ir-negative-gap", ["impacts", FILE, "--out", "{d}/o.nc"], ("krasnov-crusher", 'gap = "4.5 mm"', 'gap = "-4.5 mm"'),
     ["model.housing.gap", "> 0"]),
    ("ir-interval-wrong-unit", ["impacts-sweep", FILE], ("krasnov-crusher", 'interval = "0.035 s"', 'interval = "0.035 m"'),
     ["model.stones.interval", "wrong dimension"]),
    ("ir-seed-text", ["validate", FILE], ("krasnov-crusher", "seed = 0", 'seed = "zero"'),
     ["analysis[0].seed", "integer"]),
    ("ir-sequences-zero", ["validate", FILE], ("krasnov-crusher", "n_sequences = 16", "n_sequences = 0"),
     ["analysis[1].n_sequences", ">= 1"]),
    ("rb-negative-clearance", ["validate", FILE], ("rub-jeffcott", 'clearance = "1 mm"', 'clearance = "-1 mm"'),
     ["model.clearance", "> 0"]),
    ("rb-friction-text", ["run", FILE, "--out", "{d}/o"], ("rub-jeffcott", "friction = 0.02", 'friction = "high"'),
     ["model.friction"]),
    ("rb-window-wrong-unit", ["validate", FILE], ("rub-jeffcott", 'window = "0.1 s"', 'window = "0.1 m"'),
     ["analysis[0].window", "wrong dimension"]),
    ("rb-unknown-key", ["validate", FILE], ("rub-jeffcott", 'rotor_radius = "50 mm"',
                                            'rotor_radius = "50 mm"\nrotor_radus = 1'),
     ["model.rotor_radus", "unknown key"]),
    ("rb-zero-t-end", ["run", FILE, "--out", "{d}/o"], ("rub-jeffcott", 't_end = "2 s"', 't_end = "0 s"'),
     ["analysis[0].t_end", "> 0"]),
    # ---- validate / cases / global options -------------------------------------------------
    ("validate-toml-syntax", ["validate", FILE], ("autobalancer", 'disc_mass = "1 kg"', 'disc_mass = "1 kg'),
     ["line", "column"]),
    ("validate-empty-file", ["validate", FILE], ("autobalancer", builtin("autobalancer"), ""), ["model"]),
    ("cases-bad-option", ["cases", "--bogus"], None, ["--bogus"]),
    ("quiet-and-verbose", ["-q", "-v", "cases"], None, ["-q/--quiet", "-v/--verbose"]),
    # ---- simulate ----------------------------------------------------------------------------
    ("simulate-negative-speed", ["simulate", "autobalancer", "--speed-rpm", "-5"], None, ["--speed-rpm", "> 0"]),
    ("simulate-nan-speed", ["simulate", "autobalancer", "--speed-rpm", "nan"], None, ["--speed-rpm"]),
    ("simulate-text-speed", ["simulate", "autobalancer", "--speed-rpm", "fast"], None, ["--speed-rpm"]),
    ("simulate-zero-t-end", ["simulate", "autobalancer", "--t-end", "0"], None, ["--t-end", "> 0"]),
    ("simulate-rpm-and-ratio", ["simulate", "autobalancer", "--speed-rpm", "100", "--speed-ratio", "2"], None,
     ["--speed-rpm", "--speed-ratio"]),
    ("simulate-unknown-analysis", ["simulate", "autobalancer", "--analysis", "nope"], None, ["--analysis", "nope"]),
    ("simulate-out-missing-folder", ["simulate", "autobalancer", "--out", "{d}/no/x.nc"], None, ["--out"]),
    ("simulate-linear-model", ["simulate", "pico21"], None, ["jeffcott_balls", "pico21"]),
    # ---- campbell / modes ----------------------------------------------------------------------
    ("campbell-range-two-parts", ["campbell", "pico21", "--speeds-rpm", "0:100"], None, ["--speeds-rpm"]),
    ("campbell-zero-modes", ["campbell", "pico21", "--modes", "0"], None, ["--modes"]),
    ("campbell-plot-format", ["campbell", "pico21", "--plot", "{d}/x.txt"], None, ["--plot"]),
    ("campbell-ball-model", ["campbell", "autobalancer"], None, ["autobalancer"]),
    ("modes-negative-speed", ["modes", "pico21", "--speed-rpm", "-1"], None, ["--speed-rpm"]),
    ("modes-negative-count", ["modes", "pico21", "--modes", "-3"], None, ["--modes"]),
    # ---- steady / stability-chart --------------------------------------------------------------
    ("steady-zero-speed", ["steady", "zhakash-k2", "--speed-rpm", "0"], None, ["--speed-rpm"]),
    ("steady-unknown-regime", ["steady", "zhakash-k2", "--regime", "nope"], None, ["--regime", "nope"]),
    ("steady-linear-model", ["steady", "pico21"], None, ["pico21"]),
    ("chart-zero-points", ["stability-chart", "zhakash-k2", "--speeds-rpm", "1:2:0"], None, ["--speeds-rpm"]),
    ("chart-unknown-param", ["stability-chart", "zhakash-k2", "--param", "bogus=1:2:3"], None, ["--param", "bogus"]),
    ("chart-mixed-units", ["stability-chart", "zhakash-k2", "--param", "eccentricity=1mm:2kg:3"], None, ["--param"]),
    # ---- continue -------------------------------------------------------------------------------
    ("continue-unknown-param", ["continue", "zhakash-k2", "--param", "drive.sped=1:2"], None, ["--param", "drive.sped"]),
    ("continue-no-range", ["continue", "zhakash-k2", "--param", "drive.speed=100"], None, ["--param", "START:STOP"]),
    ("continue-wrong-unit", ["continue", "zhakash-k2", "--param", "drive.speed=1kg:2kg"], None,
     ["--param", "angular speed"]),
    ("continue-bad-from", ["continue", "zhakash-k2", "--param", "drive.speed=800rpm:2000rpm", "--from", "x"], None,
     ["--from", "balanced"]),
    ("continue-no-speed", ["continue", "zhakash-k2", "--param", "ball_mass=40g:5g"], None, ["--speed-rpm"]),
    # ---- basin ------------------------------------------------------------------------------------
    ("basin-absurd-grid", ["basin", "autobalancer", "--x", "psi_1=0:350deg:100000", "--y", "psi_2=0:350deg:100000"],
     None, ["1e+10 points", "memory"]),
    ("basin-unknown-coordinate", ["basin", "autobalancer", "--x", "nope=0:1:3"], None, ["--x", "nope"]),
    ("basin-axis-two-parts", ["basin", "autobalancer", "--x", "psi_1=0:350deg"], None, ["--x"]),
    ("basin-zero-random", ["basin", "autobalancer", "--random", "0"], None, ["--random"]),
    ("basin-zero-workers", ["basin", "autobalancer", "--workers", "0"], None, ["--workers"]),
    ("basin-scheduler-no-scheme", ["basin", "autobalancer", "--scheduler", "localhost"], None, ["--scheduler"]),
    ("basin-zero-chunk", ["basin", "autobalancer", "--chunk", "0"], None, ["--chunk"]),
    ("basin-resume-without-store", ["basin", "autobalancer", "--resume"], None, ["--resume"]),
    ("basin-negative-t-end", ["basin", "autobalancer", "--t-end", "-1"], None, ["--t-end"]),
    ("basin-store-not-a-store", ["basin", "autobalancer", "--store", "{d}/plain", "--resume"], None,
     ["--store", "not a rotorlab sweep store"]),
    # ---- sweep -------------------------------------------------------------------------------------
    ("sweep-missing-out", ["sweep", "autobalancer"], None, ["--out"]),
    ("sweep-ic-two-parts", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", "psi_1=0:6"], None, ["--ic"]),
    ("sweep-unknown-param", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--param", "nope=1:2:3"], None,
     ["--param", "nope"]),
    ("sweep-absurd-grid", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--speed-ratio", "2", "--ic",
                           "psi_1=0:6:100000", "--ic", "psi_2=0:6:100000"], None, ["1e+10 points", "memory"]),
    ("sweep-zero-sample", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--sample", "0", "--ic", "psi_1=0:6"],
     None, ["--sample"]),
    ("sweep-seed-without-sample", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--seed", "3", "--ic",
                                   "psi_1=0:6:4"], None, ["--seed"]),
    ("sweep-out-missing-folder", ["sweep", "autobalancer", "--out", "{d}/no/s.zarr", "--ic", "psi_1=0:6:4"], None,
     ["--out"]),
    ("sweep-bad-per-point", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--per-point", "bogus"], None,
     ["--per-point"]),
    ("sweep-torus-zero-count", ["sweep", "strautmanis-torus", "--out", "{d}/s.zarr", "--ic", "psi=0:6:0"], None,
     ["--ic"]),
    ("sweep-linear-model", ["sweep", "pico21", "--out", "{d}/s.zarr", "--ic", "psi_1=0:1:2"], None, ["pico21"]),
    # ---- show -------------------------------------------------------------------------------------
    ("show-missing-store", ["show", "{d}/missing.zarr"], None, ["STORE", "missing.zarr"]),
    ("show-plain-folder", ["show", "{d}/plain"], None, ["plain", "not a rotorlab sweep store"]),
    ("show-figures-is-file", ["show", "{d}/plain", "--figures", "{d}/notes.txt"], None, ["plain"]),
    # ---- basin-stability (issue 26 item 2) -----------------------------------------------------------
    ("bstab-unknown-param", ["basin-stability", "autobalancer", "--param", "nope=1:2:3"], None,
     ["--param", "nope", "ball_damping"]),
    ("bstab-param-no-count", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3"], None,
     ["--param", "NAME=START:STOP:N"]),
    ("bstab-decreasing-range", ["basin-stability", "autobalancer", "--param", "ball_damping=2e-3:1e-3:3"], None,
     ["--param", "STOP must be > START"]),
    ("bstab-negative-damping", ["basin-stability", "autobalancer", "--param", "ball_damping=-1e-3:2e-3:3"], None,
     ["--param", "ball_damping", "-0.001", "allowed range"]),
    ("bstab-zero-starts", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--starts", "0"],
     None, ["--starts = 0", ">= 1"]),
    ("bstab-width-too-big", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--ci-width",
     "0.5"], None, ["--ci-width = 0.5", "0.5)"]),
    ("bstab-width-zero", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--ci-width", "0"],
     None, ["--ci-width = 0", "half-width"]),
    ("bstab-width-nan", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--ci-width",
     "nan"], None, ["--ci-width = nan"]),
    ("bstab-starts-and-width", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--starts",
     "10", "--ci-width", "0.1"], None, ["--starts", "--ci-width", "exclude"]),
    ("bstab-no-param", ["basin-stability", "autobalancer"], None, ["--param", "no basin-stability analysis"]),
    ("bstab-bad-range", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--range",
     "psi_9=0:1"], None, ["--range", "psi_9"]),
    ("bstab-flat-range", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2", "--range",
     "psi_1=1:1"], None, ["--range", "HIGH must be > LOW"]),
    ("bstab-linear-model", ["basin-stability", "pico21", "--param", "spin_speed=1:2:2"], None, ["pico21"]),
    ("bstab-resume-without-store", ["basin-stability", "autobalancer", "--param", "ball_damping=1e-3:2e-3:2",
     "--resume"], None, ["--resume", "--store"]),
    # ---- design (issue 27) ---------------------------------------------------------------------
    ("design-unknown-param", ["design", "autobalancer", "--vary", "nope=1:2", "--objective", "ball-mass", "--param",
     "spin_speed=2400rpm:2400rpm:1"], None, ["--vary", "nope", "ball_damping"]),
    ("design-negative-damping", ["design", "autobalancer", "--vary", "ball_damping=-1e-3:2e-3", "--objective",
     "ball-mass", "--param", "spin_speed=2400rpm:2400rpm:1"], None, ["--vary", "ball_damping", "-0.001", "must be >= 0"]),
    ("design-case-negative-damping", ["run", FILE, "--out", "{d}/o"], ("autobalancer", "[[analysis]]",
     '[[analysis]]\ntype = "design"\nvary = {ball_damping = ["-1e-3 N*m*s", "2e-3 N*m*s"]}\n'
     'objectives = ["ball-mass"]\nparam = {spin_speed = ["2400 rpm", "2400 rpm", 1]}\n\n[[analysis]]'),
     ["analysis[0].vary.ball_damping", "-0.001", "must be >= 0"]),
    ("design-unknown-objective", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective", "fastest",
     "--param", "spin_speed=2400rpm:2400rpm:1"], None, ["--objective", "fastest", "ball-mass"]),
    ("design-unknown-optimizer", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective", "ball-mass",
     "--param", "spin_speed=2400rpm:2400rpm:1", "--optimizer", "sgd"], None, ["--optimizer", "sgd", "tpe"]),
    ("design-de-two-objectives", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective", "ball-mass",
     "--objective", "residual-vibration", "--param", "spin_speed=2400rpm:2400rpm:1", "--optimizer",
     "differential-evolution"], None, ["--objective", "differential-evolution", "two"]),
    ("design-too-few-starts", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective", "ball-mass",
     "--param", "spin_speed=2400rpm:2400rpm:1", "--starts", "64"], None, ["--starts", "min_balanced", "381"]),
    ("design-no-analysis", ["design", "autobalancer"], None, ["--vary", "no design analysis"]),
    ("design-resume-without-store", ["design", "autobalancer", "--resume"], None, ["--resume", "--store"]),
    ("design-linear-model", ["design", "pico21", "--vary", "disc_mass=1:2", "--objective", "ball-mass", "--param",
     "spin_speed=1:2:2"], None, ["pico21"]),
    ("design-case-unknown-objective", ["design", FILE], ("autobalancer", "[[analysis]]",
     '[[analysis]]\ntype = "design"\nvary = {ball_mass = ["10 g", "40 g"]}\nobjectives = ["nope"]\n'
     'param = {spin_speed = ["2400 rpm", "2400 rpm", 1]}\n\n[[analysis]]'), ["objectives", "nope", "ball-mass"]),
    ("design-unknown-constraint", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective",
     "ball-mass", "--param", "spin_speed=2400rpm:2400rpm:1", "--constraint", "nope"], None,
     ["--constraint", "nope", "no-housing-contact"]),
    ("design-contact-without-clearance", ["design", "autobalancer", "--vary", "ball_mass=10g:40g", "--objective",
     "ball-mass", "--param", "spin_speed=2400rpm:2400rpm:1", "--constraint", "no-housing-contact"], None,
     ["constraints", "no-housing-contact", "needs a machine with a clearance"]),
    ("design-run-up-objective-motor", ["design", "washer-horizontal", "--vary", "model.drive.stall_torque=5:20",
     "--objective", "run-up-time", "--param", "spin_speed=100:100:1"], None,
     ["objectives", "run-up-time", 'profile = "servo"']),
    # ---- the run-up designer's servo drive (issue 27 item 2) ----------------------------------------
    ("servo-negative-ramp-rate", ["validate", FILE], ("washer-horizontal", 'profile = "motor"',
     'profile = "servo"\noperating_speed = "100 rad/s"\nramp_rate = "-5 rad/s^2"'),
     ["model.drive.ramp_rate", "-5"]),
    ("servo-no-operating-speed", ["validate", FILE], ("washer-horizontal", 'profile = "motor"',
     'profile = "servo"\nramp_rate = "5 rad/s^2"'), ["model.drive.operating_speed"]),
    ("servo-ramp-rate-wrong-unit", ["validate", FILE], ("washer-horizontal", 'profile = "motor"',
     'profile = "servo"\noperating_speed = "100 rad/s"\nramp_rate = "5 rad/s"'),
     ["model.drive.ramp_rate", "angular acceleration"]),
    ("run-up-design-motor-case", ["run-up-design", "washer-horizontal", "--vary", "drive.stall_torque=5:20"], None,
     ["run-up-design", 'profile = "servo"', "'motor'"]),
    ("run-up-design-unknown-param", ["run-up-design", FILE, "--vary", "drive.ramp_rat=1:20", "--set",
     "analysis[1].passing_torque=false"],
     ("washer-horizontal", 'profile = "motor"', 'profile = "servo"\noperating_speed = "100 rad/s"\n'
      'ramp_rate = "5 rad/s^2"'),
     ["--vary", "drive.ramp_rat", "drive.ramp_rate"]),
    ("run-up-design-too-few-starts", ["run-up-design", FILE, "--vary", "drive.ramp_rate=1:20", "--starts", "50",
     "--set", "analysis[1].passing_torque=false"],
     ("washer-horizontal", 'profile = "motor"', 'profile = "servo"\noperating_speed = "100 rad/s"\n'
      'ramp_rate = "5 rad/s^2"'), ["--starts", "50", "--min-balanced", "381"]),
    ("run-up-design-contact-without-clearance", ["run-up-design", FILE, "--vary", "drive.ramp_rate=1:20",
     "--constraint", "no-housing-contact", "--set", "analysis[1].passing_torque=false"],
     ("washer-horizontal", 'profile = "motor"', 'profile = "servo"\noperating_speed = "100 rad/s"\n'
      'ramp_rate = "5 rad/s^2"'), ["--constraint", "no-housing-contact", "needs a machine with a clearance"]),
    ("run-up-design-unknown-constraint", ["run-up-design", FILE, "--vary", "drive.ramp_rate=1:20",
     "--constraint", "nope", "--set", "analysis[1].passing_torque=false"],
     ("washer-horizontal", 'profile = "motor"', 'profile = "servo"\noperating_speed = "100 rad/s"\n'
      'ramp_rate = "5 rad/s^2"'), ["--constraint", "nope", "no-housing-contact"]),
    # ---- impacts / impacts-sweep ----------------------------------------------------------------
    ("impacts-negative-stone", ["impacts", "krasnov-crusher", "--stone-mass", "-1"], None, ["--stone-mass"]),
    ("impacts-zero-t-end", ["impacts", "krasnov-crusher", "--t-end", "0"], None, ["--t-end"]),
    ("impacts-ball-model", ["impacts", "autobalancer"], None, ["autobalancer", "impact_rotor"]),
    ("impacts-negative-seed", ["impacts", "krasnov-crusher", "--seed", "-1"], None, ["--seed"]),
    ("impacts-unknown-analysis", ["impacts", "krasnov-crusher", "--analysis", "nope"], None, ["--analysis", "nope"]),
    ("isweep-decreasing-range", ["impacts-sweep", "krasnov-crusher", "--stone-mass", "1:0.5:3"], None,
     ["--stone-mass"]),
    ("isweep-restitution-range", ["impacts-sweep", "krasnov-crusher", "--param", "restitution=0:2:3"], None,
     ["--param", "restitution"]),
    ("isweep-unknown-param", ["impacts-sweep", "krasnov-crusher", "--param", "bogus=1:2:3"], None,
     ["--param", "bogus"]),
    ("isweep-zero-sequences", ["impacts-sweep", "krasnov-crusher", "--sequences", "0"], None, ["--sequences"]),
    ("isweep-resume-without-out", ["impacts-sweep", "krasnov-crusher", "--resume"], None, ["--resume"]),
    ("isweep-negative-workers", ["impacts-sweep", "krasnov-crusher", "--workers", "-1"], None, ["--workers"]),
    # ---- edge numbers ------------------------------------------------------------------------------
    ("simulate-infinite-t-end", ["simulate", "autobalancer", "--t-end", "inf"], None, ["--t-end", "finite"]),
    ("simulate-overflowing-speed", ["simulate", "autobalancer", "--speed-rpm", "1e400"], None,
     ["--speed-rpm", "finite"]),
    ("impacts-nan-stone", ["impacts", "krasnov-crusher", "--stone-mass", "nan"], None, ["--stone-mass"]),
    ("sweep-negative-chunk", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", "psi_1=0:6:4", "--chunk", "-1"],
     None, ["--chunk"]),
    ("jb-huge-exponent", ["validate", FILE], ("autobalancer", 'eccentricity = "1.5 mm"', 'eccentricity = "1e400 mm"'),
     ["model.eccentricity", "finite"]),
    ("ir-n-save-absurd", ["impacts", FILE, "--t-end", "0.01"], ("krasnov-crusher", "seed = 0", "seed = 0\nn_save = 1e12"),
     ["n_save = 1000000000000", "memory"]),
]

# ---- machine (a rotor of any structure with races, drive, gravity) -----------------------------
MACHINE = [
    ("mc-negative-race-radius", ["validate", FILE], ("washer-horizontal", 'radius = "0.27 m"', 'radius = "-0.27 m"'),
     ["model.races[0].radius", "> 0"]),
    ("mc-negative-ball-coulomb", ["validate", FILE], ("washer-horizontal", 'damping = "0.05 N*m*s/rad", count = 2',
                                                       'damping = "0.05 N*m*s/rad", coulomb = -0.1, count = 2'),
     ["model.races[0].balls[0].coulomb", ">= 0", "-0.1"]),
    ("mc-ball-rolling-wrong-unit", ["validate", FILE], ("washer-horizontal", 'damping = "0.05 N*m*s/rad", count = 2',
                                                         'damping = "0.05 N*m*s/rad", rolling = "1 kg", count = 2'),
     ["model.races[0].balls[0].rolling", "wrong dimension"]),
    ("mc-drive-profile-typo", ["validate", FILE], ("washer-horizontal", 'profile = "motor"', 'profile = "motorr"'),
     ["model.drive.profile", "motor"]),
    ("mc-gravity-wrong-unit", ["validate", FILE], ("washer-horizontal", '"-9.81 m/s^2"', '"-9.81 m/s"'),
     ["model.gravity.vector[1]", "wrong dimension"]),
    ("mc-unknown-body", ["run", FILE, "--out", "{d}/o"], ("washer-horizontal", 'at = "drum"', 'at = "drun"'),
     ["model.races[0].at", "drun"]),
    ("mc-zero-speeds", ["validate", FILE], ("pico21-balancer", 'speeds = ["300 rpm", "15000 rpm", 30]',
                                             'speeds = ["300 rpm", "15000 rpm", 0]'),
     ["analysis[1].speeds", ">= 1"]),
    ("mc-negative-t-end", ["validate", FILE], ("washer-horizontal", 't_end = "40 s"', 't_end = "-40 s"'),
     ["analysis[0].t_end", "> 0"]),
    ("mc-steady-under-gravity", ["validate", FILE], ("washer-horizontal", "n_save = 8000\n",
                                                      'n_save = 8000\n\n[[analysis]]\ntype = "steady"\n'
                                                      'speed = "100 rad/s"\n'),
     ["analysis[1].type", "gravity acts across the axis", "simulate"]),
    ("run-up-no-analysis", ["run-up", "pico21"], None, ["no run-up analysis"]),
    ("run-up-zero-t-end", ["run-up", "washer-horizontal", "--t-end", "0"], None, ["--t-end", "> 0"]),
    ("mc-campbell-modes-too-many", ["campbell", "rcfw-two-plane", "--speeds-rpm", "0:30:4", "--modes", "9"], None, ["--modes", "4"]),
    ("mc-steady-command-under-gravity", ["steady", "washer-horizontal", "--speed-rpm", "1000"], None,
     ["gravity acts across the axis", "simulate"]),
    ("mc-absurd-ball-count", ["validate", FILE], ("washer-horizontal", "count = 2 }", "count = 1e8 }"),
     ["model.races[0].balls[0].count", "at most 1000 balls"]),
    ("mc-empty-ball-angles", ["validate", FILE], ("washer-horizontal",
                                                   'initial_ball_angles = [["-100 deg", "-80 deg"], ["-90 deg", "-90 deg"]]',
                                                   "initial_ball_angles = []"),
     ["analysis[1].initial_ball_angles", "empty"]),
    ("mc-n-save-absurd", ["run", FILE, "--out", "{d}/o"], ("washer-horizontal", "n_save = 8000", "n_save = 1e12"),
     ["n_save = 1000000000000", "memory"]),
    ("mc-unknown-key", ["validate", FILE], ("washer-horizontal", 'stall_torque = "10 N*m"',
                                             'stall_torque = "10 N*m"\nstall_torq = 3'),
     ["model.drive.stall_torq", "unknown key"]),
]

# ---- --set KEY=VALUE on every analysis command (issue 12): refused like the same edit of the file --------
SET = [
    ("set-run-negative-mass", ["run", "autobalancer", "--out", "{d}/o", "--set", "model.disc_mass=-1 kg"], None,
     ["model.disc_mass", '"-1 kg"', "> 0"]),
    ("set-simulate-index-past-end", ["simulate", "autobalancer", "--set", "model.balls[4].mass=20g"], None,
     ["model.balls[4].mass", "model.balls has 1 entry", "from 0 to 0"]),
    ("set-campbell-unknown-key", ["campbell", "friswell-rotor", "--set", "model.bearings[0].kxx2=1e6"], None,
     ["model.bearings[0].kxx2", "unknown key", "kxx"]),
    ("set-modes-wrong-unit", ["modes", "friswell-rotor", "--set", "model.material.density=7810 kg"], None,
     ["model.material.density", "wrong dimension"]),
    ("set-steady-into-a-value", ["steady", "zhakash-k2", "--set", "model.disc_mass.unit=kg"], None,
     ["model.disc_mass.unit", '"2 kg"', "single value"]),
    ("set-stability-chart-no-equals", ["stability-chart", "zhakash-k2", "--set", "model.disc_mass"], None,
     ["--set model.disc_mass", "KEY=VALUE"]),
    ("set-basin-bad-toml", ["basin", "autobalancer", "--set", "analysis[2].x=[psi_1"], None,
     ["--set analysis[2].x=[psi_1", "not a TOML value"]),
    ("set-sweep-bad-key-path", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", "psi_1=0:6:4",
                                "--set", "model..mass=1"], None, ["--set model..mass=1", "not a key path"]),
    ("set-impacts-list-without-index", ["impacts", "krasnov-crusher", "--set", "analysis.seed=1"], None,
     ["analysis.seed", "analysis is a list", "analysis[0].seed"]),
    ("set-isweep-negative-gap", ["impacts-sweep", "krasnov-crusher", "--set", "model.housing.gap=-4 mm"], None,
     ["model.housing.gap", "-4 mm"]),
    ("set-validate-typo-in-list-name", ["validate", "autobalancer", "--set", "model.bals[0].mass=1"], None,
     ["model.bals[0].mass", "did you mean 'balls'"]),
    ("set-validate-empty-value", ["validate", "autobalancer", "--set", "model.disc_mass="], None,
     ["--set model.disc_mass=", "no value"]),
    ("set-validate-two-problems", ["validate", "autobalancer", "--set", "model.disc_mass=0", "--set",
                                   "model.stiffness=-1"], None, ["model.disc_mass = 0", "model.stiffness = -1"]),
]
CORPUS += SET
MACHINE += [
    ("set-mc-race-radius-digit-index", ["validate", "washer-horizontal", "--set", "model.races.0.radius=-0.2 m"], None,
     ["model.races[0].radius", "> 0"]),
    ("set-mc-race-past-end", ["run", "pico21-balancer", "--out", "{d}/o", "--set", "model.races.2.radius=1"], None,
     ["model.races.2.radius", "model.races has 2 entries"]),
]

if resources.files("rotorlab.cases").joinpath("washer-horizontal.toml").is_file():  # once the machine model landed
    CORPUS += MACHINE

# ---- a machine with a clearance (rotor-stator contact) and its knock analysis -------------------
KNOCK = [
    ("mk-negative-gap", ["validate", FILE], ("washer-knock", 'gap = "10 mm"', 'gap = "-10 mm"'),
     ["model.clearances[0].gap", "> 0"]),
    ("mk-gap-wrong-unit", ["validate", FILE], ("washer-knock", 'gap = "10 mm"', 'gap = "10 kg"'),
     ["model.clearances[0].gap", "wrong dimension"]),
    ("mk-restitution-above-1", ["validate", FILE], ("washer-knock", "restitution = 0.3", "restitution = 1.3"),
     ["model.clearances[0].restitution", "<= 1"]),
    ("mk-unknown-clearance-key", ["validate", FILE], ("washer-knock", "friction = 0.3", "friction = 0.3\nfrition = 3"),
     ["model.clearances[0].frition", "unknown key"]),
    ("mk-center-twice", ["validate", FILE], ("washer-knock", "center_at_rest = true",
                                             'center_at_rest = true\ncenter = ["0 mm", "1 mm"]'),
     ["model.clearances[0].center_at_rest", "not both"]),
    ("mk-negative-ball-damping", ["validate", FILE], ("washer-knock", '["0.002 N*m*s/rad"', '["-0.002 N*m*s/rad"'),
     ["analysis[0].ball_damping[0]", ">= 0"]),
    ("mk-zero-starts", ["run", FILE, "--out", "{d}/o"], ("washer-knock", "starts = 80", "starts = 0"),
     ["analysis[0].starts", ">= 1"]),
    ("mk-no-balls", ["run", FILE, "--out", "{d}/o"], ("washer-knock", "seed = 0", "seed = 0\nraces = []"),
     ["analysis[0]", "needs balls"]),
    ("mk-friction-with-clearance", ["validate", FILE], ("washer-knock", 'damping = "0.05 N*m*s/rad", count = 2',
                                                         'damping = "0.05 N*m*s/rad", coulomb = 0.1, count = 2'),
     ["model.races[0].balls[0].coulomb", "must be 0 with a clearance", "0.1"]),
    ("mk-starts-absurd", ["run", FILE, "--out", "{d}/o"], ("washer-knock", "starts = 80", "starts = 1e12"),
     ["starts = 1000000000000", "memory"]),
]

if resources.files("rotorlab.cases").joinpath("washer-knock.toml").is_file():
    CORPUS += KNOCK

# ---- unbounded counts, ranges, nesting and key paths (issue 28, items 12 and 14): each bounded where it is read --
HUGE = "1" + "0" * 30
DEEP = "[" * 5000 + "]" * 5000
BOUNDS = [
    ("basin-workers-absurd", ["basin", "autobalancer", "--workers", "100000"], None,
     ["--workers = 100000", "must be an integer >= 1 and <= 256"]),
    ("sweep-workers-absurd", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", "psi_1=0:6:4", "--workers",
                              "100000"], None, ["--workers = 100000", "<= 256"]),
    ("sweep-chunk-absurd", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", "psi_1=0:6:4", "--chunk", HUGE],
     None, [f"--chunk = {HUGE}", "<= 1000000"]),
    ("basin-chunk-1e30", ["basin", "autobalancer", "--chunk", "1e30"], None, ["--chunk = 1e30", "<= 1000000"]),
    ("isweep-chunk-absurd", ["impacts-sweep", "krasnov-crusher", "--out", "{d}/i.zarr", "--chunk", HUGE], None,
     ["--chunk", "<= 1000000"]),
    ("isweep-sequences-absurd", ["impacts-sweep", "krasnov-crusher", "--sequences", HUGE], None,
     ["--sequences", "<= 1000000000"]),
    ("impacts-seed-absurd", ["impacts", "krasnov-crusher", "--seed", HUGE], None, ["--seed", "<= 9223372036854775807"]),
    ("campbell-speed-overflow", ["campbell", "rcfw-two-plane", "--speeds-rpm", "0:1e300:5"], None,
     ["--speeds-rpm = 0:1e300:5", "STOP must be a finite number <= 1e+07 rpm"]),
    ("campbell-speeds-count-absurd", ["campbell", "pico21", "--speeds-rpm", f"0:100:{HUGE}"], None,
     ["--speeds-rpm", "N must be <= 100000"]),
    ("chart-speed-overflow", ["stability-chart", "zhakash-k2", "--speeds-rpm", "1:1e300:3"], None,
     ["--speeds-rpm = 1:1e300:3", "<= 1e+07 rpm"]),
    ("modes-speed-overflow", ["modes", "pico21", "--speed-rpm", "1e300"], None, ["--speed-rpm = 1e+300", "at most 1e+07 rpm"]),
    ("sweep-axis-count-absurd", ["sweep", "autobalancer", "--out", "{d}/s.zarr", "--ic", f"psi_1=0:6:{HUGE}"], None,
     ["--ic", "N must be <= 1000000"]),
    ("sweep-case-chunk-absurd", ["sweep", FILE, "--out", "{d}/s.zarr"],
     ("autobalancer", "", builtin("autobalancer") + '\n[[analysis]]\ntype = "sweep"\nspeed_ratio = 2.0\nt_end = "1 s"\n'
      'ic = { psi_1 = ["0 deg", "300 deg", 3] }\nchunk = 1e30\n'), ["analysis[3].chunk", "<= 1000000"]),
    ("toml-deep-array", ["validate", FILE], ("autobalancer", "schema_version = 1", "schema_version = 1\nq = " + DEEP),
     ["case.toml", "nested", "at most 32"]),
    ("toml-deep-inline-tables", ["run", FILE, "--out", "{d}/o"],
     ("autobalancer", "schema_version = 1", "schema_version = 1\nq = " + "{a=" * 3000 + "1" + "}" * 3000),
     ["case.toml", "nested", "at most 32"]),
    ("toml-deep-table-header", ["validate", FILE],
     ("autobalancer", "", builtin("autobalancer") + "\n[" + ".".join(["a"] * 5000) + "]\nb = 1\n"),
     ["case.toml", "a.a.a", "nested deeper than 32 levels"]),
    ("toml-deep-but-parsable", ["validate", FILE], ("autobalancer", "schema_version = 1",
                                                    "schema_version = 1\nq = " + "[" * 40 + "]" * 40),
     ["q[0][0]", "nested deeper than 32 levels"]),
    ("set-deep-value", ["validate", "autobalancer", "--set", "model.x=" + DEEP], None, ["--set model.x=[[[", "at most 32"]),
    ("set-long-key-path", ["simulate", "autobalancer", "--set", ".".join(["model"] * 5000) + "=1"], None,
     ["--set model.model", "5000 keys and indices, at most 32"]),
    ("set-key-path-deeper-than-allowed", ["validate", "autobalancer", "--set", ".".join(["model"] * 20) + "=" + "[" * 20
                                          + "]" * 20], None, ["nested deeper than 32 levels"]),  # fmt: skip
]
CORPUS += BOUNDS
# ---- the margin analyses (issue 26 items 3, 4) ----------------------------------------------------
MARGINS = [
    ("sm-zero-directions", ["shock-margin", "autobalancer", "--directions", "0"], None, ["--directions", "0"]),
    ("sm-negative-speed", ["shock-margin", "autobalancer", "--speed-rpm", "-5"], None,
     ["--speed-rpm", "-5", "> 0"]),
    ("sm-both-speeds", ["shock-margin", "autobalancer", "--speed-rpm", "2400", "--speed-ratio", "2"], None,
     ["--speed-rpm", "--speed-ratio", "only one"]),
    ("sm-torus", ["shock-margin", "strautmanis-torus"], None, ["shock-margin", "jeffcott_balls", "toroidal_ball"]),
    ("sm-friction-balls", ["shock-margin", FILE], ("autobalancer", 'damping = "2e-3 N*m*s"',
                                                   'damping = "2e-3 N*m*s"\nfriction = 0.01'),
     ["shock-margin.type", "without Coulomb friction"]),
    ("sm-machine-gravity", ["shock-margin", "washer-horizontal", "--speed-rpm", "1000"], None,
     ["shock-margin.type", "gravity acts across the axis"]),
    ("sm-machine-ramp", ["shock-margin", "washer-horizontal"], None, ["shock-margin.speed", "not constant"]),
    ("sm-out-is-folder", ["shock-margin", "autobalancer", "--out", "{d}/plain"], None, ["--out", "folder"]),
    ("sm-case-directions", ["validate", FILE], ("autobalancer", "n_horizons = 10",
                                                'n_horizons = 10\n\n[[analysis]]\ntype = "shock-margin"\n'
                                                'directions = -3'),
     ["directions", "-3"]),
    ("fm-no-friction", ["friction-margin", "autobalancer"], None, ["friction-margin", "friction", "> 0"]),
    ("fm-torus-no-friction", ["friction-margin", FILE], ("strautmanis-torus", 'rolling_friction = "1e-5 m"',
                                                         'rolling_friction = "0 m"'),
     ["rolling_friction", "> 0"]),
    # four balls on tilting races are covered; balls without friction, gravity across the axis and
    # anisotropic supports are not (no steady response for the stuck balls to ride on)
    ("fm-machine-tilting-no-friction", ["friction-margin", "rcfw-two-plane"], None,
     ["friction-margin.type", "coulomb or rolling > 0"]),
    ("fm-machine-gravity", ["friction-margin", FILE, "--speed-rpm", "1000"],
     ("washer-horizontal", 'damping = "0.05 N*m*s/rad", count = 2',
      'damping = "0.05 N*m*s/rad", coulomb = 0.01, count = 2'),
     ["friction-margin.type", "gravity acts across the axis"]),
    ("fm-machine-anisotropic", ["friction-margin", FILE, "--speed-rpm", "1000"],
     ("washer-horizontal", 'cxx = "400 N*s/m"\nk_tilt_x = "3 kN*m/rad"\n\n[[model.races]]\nat = "drum"\nradius = "0.27 m"\n'
                           'balls = [{ mass = "0.5 kg", damping = "0.05 N*m*s/rad", count = 2 }]',
      'kyy = "30 kN/m"\ncxx = "400 N*s/m"\nk_tilt_x = "3 kN*m/rad"\n\n[[model.races]]\nat = "drum"\nradius = "0.27 m"\n'
      'balls = [{ mass = "0.5 kg", damping = "0.05 N*m*s/rad", coulomb = 0.01, count = 2 }]'),
     ["friction-margin.type", "anisotropic"]),
    ("fm-machine-no-friction", ["friction-margin", "washer-horizontal", "--speed-rpm", "1000"], None,
     ["friction-margin.type", "coulomb or rolling > 0"]),
    ("fm-small-grid", ["friction-margin", "strautmanis-torus", "--grid", "5"], None, ["--grid", "5"]),
    ("fm-nan-ratio", ["friction-margin", "strautmanis-torus", "--speed-ratio", "nan"], None, ["--speed-ratio"]),
]
CORPUS += MARGINS

# the tolerances and design entries (issue 27) and the knock case's clearance centre
CORPUS += ENTRIES


def _tree(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


def test_the_corpus_is_large_and_covers_every_command_and_model_type():
    assert len(CORPUS) >= 60
    assert len({entry[0] for entry in CORPUS}) == len(CORPUS)
    commands = {entry[1][0] for entry in CORPUS} | {entry[1][2] for entry in CORPUS if entry[1][0] == "-q"}
    assert commands >= {"run", "simulate", "campbell", "modes", "steady", "stability-chart", "continue", "basin", "sweep",
                        "show", "impacts", "impacts-sweep", "validate", "cases", "design", "run-up-design"}  # fmt: skip
    bases = {entry[2][0] for entry in CORPUS if entry[2]}
    assert bases >= {"autobalancer", "pico21", "friswell-rotor", "strautmanis-torus", "krasnov-crusher", "rub-jeffcott"}


@pytest.mark.parametrize("name, argv, case, words", CORPUS, ids=[entry[0] for entry in CORPUS])
def test_bad_input_is_refused_cleanly(name, argv, case, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a default output folder would land here
    (tmp_path / "plain").mkdir()
    (tmp_path / "plain" / "notes.txt").write_text("not a store")
    (tmp_path / "notes.txt").write_text("a file")
    if case is not None:
        base, old, new = case[:3]
        text = builtin(base)
        (tmp_path / "case.toml").write_text(text.replace(old, new) if old else new, encoding="utf-8")
    before = _tree(tmp_path)
    result = runner.invoke(app, [a.replace("{d}", str(tmp_path)) for a in argv])
    message = result.stderr
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output, result.output
    for word in words:
        assert word in message, (word, message)
    assert _tree(tmp_path) == before, "something was written"
