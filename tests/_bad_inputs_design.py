"""Entries of the bad-input corpus (``tests/robustness/test_bad_inputs.py``) for the tolerances and
design analyses (issue 27) and the knock case's clearance centre: the same form as the corpus,
(id, argv with {d} for the working folder, (base case, old text, new text) or None, words of the
message)."""

from __future__ import annotations

from importlib import resources

FILE = "{d}/case.toml"

# ---- tolerances (issue 27): the uncertain inputs of the built-in example, one text change each ------------------
_TOL = '"races[0].radius" = { distribution = "normal", mean = "40 mm", std = "0.1 mm" }'
TOLERANCES = [
    ("tol-unknown-parameter", ["tolerances", FILE, "--plot", "{d}/s.png"],
     ("pico21-balancer", _TOL, '"races[0].radiu" = { distribution = "normal", mean = "40 mm", std = "0.1 mm" }'),
     ['analysis[6].inputs."races[0].radiu"', "not a number of any model"]),
    ("tol-parameter-past-end", ["tolerances", FILE],
     ("pico21-balancer", _TOL, '"races[4].radius" = { distribution = "normal", mean = "40 mm", std = "0.1 mm" }'),
     ['analysis[6].inputs."races[4].radius"', "not a named parameter of this machine", "did you mean",
      "races[0].radius"]),
    ("tol-bad-distribution", ["validate", FILE],
     ("pico21-balancer", _TOL, '"races[0].radius" = { distribution = "lognormal", mean = "40 mm", std = "0.1 mm" }'),
     ['analysis[6].inputs."races[0].radius".distribution', "lognormal", "normal", "uniform"]),
    ("tol-normal-without-std", ["tolerances", FILE],
     ("pico21-balancer", _TOL, '"races[0].radius" = { distribution = "normal", mean = "40 mm" }'),
     ['analysis[6].inputs."races[0].radius"', "give std or tolerance"]),
    ("tol-wrong-unit", ["validate", FILE],
     ("pico21-balancer", _TOL, '"races[0].radius" = { distribution = "normal", mean = "40 kg", std = "0.1 mm" }'),
     ['analysis[6].inputs."races[0].radius".mean', "40 kg", "wrong dimension"]),
    ("tol-uniform-reaches-negative", ["tolerances", FILE],
     ("pico21-balancer", 'ball_damping = { distribution = "uniform", low = "1e-4 N*m*s", high = "4e-4 N*m*s" }',
      'ball_damping = { distribution = "uniform", low = "-1e-4 N*m*s", high = "4e-4 N*m*s" }'),
     ["analysis[6].inputs.ball_damping", "reaches values the parameter cannot take", ">= 0"]),
    ("tol-structural", ["tolerances", FILE],
     ("pico21-balancer", _TOL, 'n_modes = { distribution = "uniform", low = 4, high = 6 }'),
     ["analysis[6].inputs.n_modes", "structural"]),
    ("tol-samples-not-power-of-two", ["tolerances", "pico21-balancer", "--samples", "24"], None,
     ["--samples", "power of 2"]),
    ("tol-no-analysis", ["tolerances", "washer-horizontal"], None, ["no tolerances analysis"]),
    ("tol-jeffcott", ["validate", FILE], ("autobalancer", "n_horizons = 10",
                                          'n_horizons = 10\n\n[[analysis]]\ntype = "tolerances"\n'
                                          'inputs = { ball_damping = { distribution = "uniform", tolerance = 0.1 }, '
                                          'ball_mass = { distribution = "uniform", tolerance = 0.1 } }'),
     ["type", "needs a machine model with balls", "jeffcott_balls"]),
]
ENTRIES = list(TOLERANCES)


def _design_sensitivity(key: str) -> tuple[str, str, str]:
    """pico21-balancer with a design analysis first whose sensitivity table has input ``key``."""
    block = ('[[analysis]]\ntype = "design"\nvary = {ball_mass = ["4 g", "6 g"]}\nobjectives = ["ball-mass"]\n'
             'param = {spin_speed = ["10000 rpm", "10000 rpm", 1]}\nmin_balanced = 0.5\nstarts = 8\nraces = [0]\n'
             'sensitivity = {samples = 2, inputs = {ball_damping = {distribution = "uniform", tolerance = 0.5}, '
             f'"{key}" = {{distribution = "normal", tolerance = 0.01}}}}}}\n\n')  # fmt: skip
    return ("pico21-balancer", '[[analysis]]\ntype = "campbell"', block + '[[analysis]]\ntype = "campbell"')


ENTRIES += [
    ("design-sensitivity-unknown-key", ["design", FILE], _design_sensitivity("races[0].radiu"),
     ['analysis[0].sensitivity.inputs."races[0].radiu"', "not a named parameter of this machine", "did you mean",
      "races[0].radius"]),
    ("design-sensitivity-past-end", ["run", FILE, "--out", "{d}/o"], _design_sensitivity("races[4].radius"),
     ['analysis[0].sensitivity.inputs."races[4].radius"', "not a named parameter of this machine", "races[0].radius"]),
    ("design-sensitivity-jeffcott", ["validate", FILE], ("autobalancer", "n_horizons = 10", 'n_horizons = 10\n\n'
     '[[analysis]]\ntype = "design"\nvary = {ball_mass = ["20 g", "40 g"]}\nobjectives = ["ball-mass"]\n'
     'param = {spin_speed = ["2400 rpm", "2400 rpm", 1]}\nstarts = 32\nmin_balanced = 0.85\nsensitivity = {inputs = '
     '{ball_damping = {distribution = "uniform", tolerance = 0.5}, ball_mass = {distribution = "uniform", '
     'tolerance = 0.1}}}'), ["sensitivity:", "needs a machine model with balls", "jeffcott_balls"]),
]
if resources.files("rotorlab.cases").joinpath("washer-knock.toml").is_file():
    ENTRIES.append(("mk-center-outside-gap", ["validate", FILE], ("washer-knock", "center_at_rest = true",
                                                                 'center = ["0 mm", "12 mm"]'),
                   ["model.clearances[0].center", '["0 mm", "12 mm"]', "12 mm from the axis",
                    "at most the gap, 10 mm"]))  # fmt: skip
