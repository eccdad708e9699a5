"""Rub regimes of the composed machine: the ``rub`` analysis of a machine case and regime maps
over speed x clearance on the sweep engine, against the closed forms (Black 1968; Choy & Padovan
1987) and against the reference Jeffcott rub model on the same points."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import run_analysis, summarize
from rotorlab.analyses._rub import rub_prediction
from rotorlab.contact import JeffcottRub, RubRotor, full_rub, no_rub_radius
from rotorlab.contact._regimes import RubRegime, RubRegimes
from rotorlab.io import load_case, parse_case
from rotorlab.linear import LinearSystem
from rotorlab.models import Clearance, ConstantSpeed, ElasticStator, Machine, Unbalance
from rotorlab.report._rub import rub_findings
from rotorlab.sweep import Points, Sweep, run_sweep

RUB = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.6, stator_stiffness=10.0,
               friction=0.02, rotor_radius=0.5)  # fmt: skip

# rub-jeffcott as a machine: one 10 kg body on 1e6 N/m (316 N s/m), 6 kg mm unbalance, 1 mm clearance
MACHINE_CASE = """
schema_version = 1
name = "rub-machine"
[model]
type = "machine"
[model.structure]
type = "multibody"
[[model.structure.bodies]]
name = "rotor"
position = "0 m"
mass = "10 kg"
diametral_inertia = "0.1 kg*m^2"
polar_inertia = "0.1 kg*m^2"
[[model.structure.bearings]]
body = "rotor"
kxx = "1e6 N/m"
cxx = "316.227766 N*s/m"
k_tilt_x = "1e4 N*m/rad"
[[model.unbalances]]
at = "rotor"
magnitude = "6 kg*mm"
[[model.clearances]]
at = "rotor"
gap = "1 mm"
friction = 0.02
rotor_radius = "50 mm"
stator = { stiffness = "1e7 N/m" }
[model.drive]
profile = "constant"
speed = "474.341649 rad/s"
[[analysis]]
type = "rub"
name = "full-rub"
t_end = "2 s"
window = "0.1 s"
"""


def test_the_rub_analysis_of_a_machine_case_gives_the_jeffcott_case_and_its_closed_form():
    machine = parse_case(MACHINE_CASE)
    ds = run_analysis(machine.model, machine.analyses[0])
    a = ds.attrs
    ref = load_case("rub-jeffcott")
    b = run_analysis(ref.model, ref.analyses[0]).attrs
    assert a["status"] == 0 and a["regime"] == b["regime"] == RubRegime.FULL_RUB
    (radius,) = b["branch_radius"]
    assert a["branch_radius"] == pytest.approx([radius], rel=1e-12)  # the equivalent rotor is exact here
    assert a["mean_radius"] == pytest.approx(radius, rel=1e-4)
    assert a["peak_force"] == pytest.approx(b["peak_force"], rel=1e-6)
    assert a["whirl_ratio"] == pytest.approx(1.0, abs=1e-4)
    # the report's box: the contact force beside its closed form, and the stability verdict from
    # the critical friction (0.048 > 0.02: stable, and the run indeed stays on the branch)
    verdict, radius_line, whirl_line, force_line, friction_line = (lambda f: (f.verdict, *f.numbers))(
        rub_findings(ds, summarize(ds)))
    assert verdict == "full rub (forward); closed forms allow: full rub (forward)"
    assert force_line.startswith("contact normal force (peak): ") and force_line.endswith(" N")
    assert a["friction"] < a["critical_friction"] == pytest.approx(0.0484, abs=5e-4)
    assert friction_line.startswith("friction 0.02 is below the critical 0.048")
    assert "full rub is stable" in friction_line


def _machine(p: RubRotor, speed: float) -> Machine:
    s = LinearSystem(M=np.diag([p.mass, p.mass, 1.0, 1.0]), C=np.diag([p.damping, p.damping, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([p.stiffness, p.stiffness, 1.0, 1.0]))  # fmt: skip
    cl = Clearance(0, p.clearance, ElasticStator(p.stator_stiffness), friction=p.friction, rotor_radius=p.rotor_radius)
    return Machine(s, unbalances=(Unbalance(0, p.mass * p.eccentricity),), drive=ConstantSpeed(speed), clearances=(cl,))


def test_a_speed_by_clearance_map_of_the_machine_puts_each_regime_where_the_closed_forms_do():
    speeds, clearances = [0.5, 1.5, 1.5], [1.0, 1.0, 1.2]
    points = Points({"spin_speed": speeds, "clearance": clearances}, dim="point")
    ds = run_sweep(Sweep(RubRegimes(_machine(RUB, 1.5), t_end=300.0, window=40.0), points=points))
    ref = run_sweep(Sweep(RubRegimes(JeffcottRub(RUB, 1.5), t_end=300.0, window=40.0), points=points))
    assert ds.status.values.tolist() == [0, 0, 0]
    assert ds.regime.values.tolist() == ref.regime.values.tolist() == [
        RubRegime.NO_CONTACT, RubRegime.FULL_RUB, RubRegime.FULL_RUB]
    allowed = [rub_prediction(replace(RUB, clearance=d), w)["regimes"] for w, d in zip(speeds, clearances)]
    assert allowed == [["no contact"], ["full rub (forward)"], ["no contact", "full rub (forward)"]]
    for i, (w, d) in enumerate(zip(speeds, clearances)):
        assert RubRegime(int(ds.regime.values[i])).label in allowed[i]
    # where both coexist (1.07 fits in 1.2), the run-through from rest lands on the stable upper
    # rub branch, with its closed-form contact force
    for i in (1, 2):
        branch = full_rub(replace(RUB, clearance=clearances[i]), speeds[i])[0]
        assert ds.peak_force.values[i] == pytest.approx(branch.normal_force, rel=2e-3)
    assert no_rub_radius(RUB, 1.5) < clearances[2]
    for name in ("contact_fraction", "whirl_ratio", "peak_force"):
        assert np.allclose(ds[name].values, ref[name].values, rtol=1e-6, atol=1e-9), name


def test_a_machine_map_names_its_coordinates_and_refuses_others():
    m = _machine(RUB, 1.5)
    assert set(RubRegimes(m, t_end=2.0, window=1.0).coordinate_units) == {
        "spin_speed", "clearance", "friction", "restitution", "unbalance", "stator_stiffness"}
    with pytest.raises(ValueError, match="unknown coordinate 'eccentricity'"):
        Sweep(RubRegimes(m, t_end=2.0, window=1.0), points=Points({"eccentricity": [1.0]}))
    with pytest.raises(ValueError, match="RubRegimes.model must be a model with a clearance"):
        RubRegimes(replace(m, clearances=()), t_end=2.0, window=1.0)


# the machine case over spin speed x unbalance: below the critical speed (316 rad/s) no rub branch
# coexists with the no-rub orbit, so every cell has one closed-form regime; polar inertia 0 (no
# gyroscopic coupling) gives the kernel layout the map above already compiled
MAP_CASE = MACHINE_CASE.replace('polar_inertia = "0.1 kg*m^2"', 'polar_inertia = "0 kg*m^2"') + """
[[analysis]]
type = "rub-map"
name = "unbalance-map"
spin_speed = ["200 rad/s", "300 rad/s", 3]
unbalance = ["2 kg*mm", "18 kg*mm", 9]
t_end = "1 s"
window = "0.1 s"
samples = 100
"""


def test_a_speed_by_unbalance_map_changes_regime_at_the_grazing_unbalance_and_rubs_on_the_closed_form_branch():
    case = parse_case(MAP_CASE)
    ds = run_analysis(case.model, case.analysis("unbalance-map"))
    m, k, c, delta = 10.0, 1e6, 316.227766, 1e-3
    rotor = RubRotor(mass=m, stiffness=k, clearance=delta, damping=c, stator_stiffness=1e7, friction=0.02,
                     rotor_radius=0.05)  # fmt: skip
    assert ds.regime.shape == (3, 9) and np.all(ds.status.values == 0)
    units = ds.unbalance.values
    for i, w in enumerate(ds.spin_speed.values):
        # grazing: the no-rub orbit U w^2 / |k - m w^2 + i c w| (Jeffcott) equals the clearance
        grazing = delta * abs(k - m * w**2 + 1j * c * w) / w**2
        assert ds.grazing_boundary.values[i] == pytest.approx(grazing, rel=1e-9)
        labels = [RubRegime(int(r)) for r in ds.regime.values[i]]
        assert labels == [RubRegime.NO_CONTACT if u < grazing else RubRegime.FULL_RUB for u in units], (w, labels)
        for j, u in enumerate(units):
            allowed = rub_prediction(replace(rotor, eccentricity=u / m), float(w))["regimes"]
            assert [labels[j].label] == allowed
            if labels[j] == RubRegime.FULL_RUB:  # the rub settles on the closed-form branch
                (branch,) = full_rub(replace(rotor, eccentricity=u / m), float(w))
                assert ds.peak_force.values[i, j] == pytest.approx(branch.normal_force, rel=2e-3), (w, u)
                assert ds.whirl_ratio.values[i, j] == pytest.approx(1.0, abs=1e-3)
            else:
                assert ds.peak_force.values[i, j] == 0.0
    # the boundary falls between cells at each speed, and moves with speed as the closed form does
    assert [int((ds.regime.values[i] == RubRegime.NO_CONTACT).sum()) for i in range(3)] == [7, 3, 0]
    assert ds.attrs["closed_form_decided"] == ds.attrs["closed_form_agree"] == 27
    # the fine line the figure draws passes through the map's own grazing values
    fine = ds.grazing_curve.sel(curve_speed=ds.spin_speed.values).values
    assert np.array_equal(fine, ds.grazing_boundary.values) and ds.sizes["curve_speed"] >= 201
