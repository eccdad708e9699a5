"""The model protocol's named parameters (:mod:`rotorlab.models._protocol`) against the case schema.

For every built-in ``machine``, ``jeffcott_balls``, ``toroidal_ball``, ``impact_rotor`` and
``rub_rotor`` case: the names are the ``[model]`` key
paths and give back the values the case converted to SI; their units and bounds are the schema's;
``pack`` of the current values is the model's own vector; ``with_parameters`` at a key equals the
model built from the case document edited at that key, bit for bit (or both refuse the value);
structural names are refused by ``pack``. No kernel is compiled here.
"""

import math
import re

import numpy as np
import pytest

from rotorlab.analyses import build_model
from rotorlab.io import CaseError, builtin_cases, load_case, validate_case
from rotorlab.io._coordinates import key_quantity
from rotorlab.io._fields import plain_data
from rotorlab.io._schema import MODEL_SPECS

CASES = [name for name in builtin_cases()
         if load_case(name).model.type in ("machine", "jeffcott_balls", "toroidal_ball", "impact_rotor",
                                            "rub_rotor")]


def _edited(case, key, value):
    """The model of the case edited at ``key``: its ``[model]`` table as validated (balls'
    ``count`` expanded), with a ``jeffcott_balls`` ball's inertia left out where the case wrote
    none (a point mass: the spec fills ``mass * radius**2`` again from the edited numbers)."""
    model = plain_data(case.model.model_dump(mode="python"))
    if case.model.type == "jeffcott_balls":
        for ball in model["balls"]:
            if ball["inertia"] == ball["mass"] * ball["radius"] ** 2:
                ball["inertia"] = None
    return build_model(validate_case({"name": "edited", "model": model}, overrides={f"model.{key}": value}).model)


def _other_values(par):
    """Values near the current one that its bounds admit."""
    v = par.value
    return [c for c in (v * 1.1, v * 0.9, v + 0.01, v - 0.01, 0.5 * v) if c != v and par.admits(c)]


def test_the_built_in_cases_cover_both_models():
    kinds = {load_case(n).model.type for n in CASES}
    assert kinds == {"machine", "jeffcott_balls", "toroidal_ball", "impact_rotor", "rub_rotor"} and len(CASES) >= 10


@pytest.mark.parametrize("name", CASES)
def test_names_units_bounds_and_values_are_the_schema_s(name):
    case = load_case(name)
    model = build_model(case.model)
    space = model.parameters
    spec = MODEL_SPECS[case.model.type]
    dumped = plain_data(case.model.model_dump(mode="python"))
    assert len(space) == len(set(space.names)) > 5
    for n in space.names:
        par = space[n]
        if n == "n_modes":  # an integer key, not a quantity: 1 .. the structure's DOFs
            assert par.structural and par.value == case.model.n_modes
            continue
        q = key_quantity(f"model.{n}", spec)
        assert q is not None, n
        assert par.unit == (q.dimension.si or "1"), n
        assert par.bounds == q.bounds, n
        value = dumped
        for k in n.replace("]", "").replace("[", ".").split("."):
            value = value[int(k)] if k.isdigit() else value[k]
            if value is None:  # a jeffcott_balls case without [model.speed]: the model is at rest
                assert n == "speed.speed" and par.value == 0.0
                break
        else:
            assert par.value == float(value), n
    np.testing.assert_array_equal(space.pack(space.values()), model.to_array())


@pytest.mark.parametrize("name", CASES)
def test_with_parameters_is_the_edited_case_bit_for_bit(name):
    case = load_case(name)
    model = build_model(case.model)
    checked = 0
    for n in model.parameters.names:
        par = model.parameters[n]
        if par.structural:
            continue
        if n.startswith("speed.") and getattr(case.model, "speed", 0) is None:
            continue
        for new in _other_values(par):
            try:
                expect = _edited(case, n, new)
            except (CaseError, ValueError):  # the case refuses it (a cross-check): so does the model
                with pytest.raises((ValueError, KeyError)):
                    model.with_parameters(**{n: new})
                continue
            got = model.with_parameters(**{n: new})
            np.testing.assert_array_equal(got.to_array(), expect.to_array(), err_msg=n)
            assert got.parameters[n].value == new
            checked += 1
            break
    assert checked >= 0.7 * len(model.parameters)


def test_pack_refuses_structural_names_and_layout_changes():
    from rotorlab.io._build import build_machine

    m = build_machine(load_case("pico21-balancer").model)
    assert m.parameters.structural("n_modes") and not m.parameters.structural("races[0].balls[0].mass")
    with pytest.raises(ValueError, match=r"n_modes is structural: a new value changes the compiled layout"):
        m.pack({"n_modes": 6})
    # a ball's Coulomb friction from 0 compiles the stick-slip events in: a new layout
    with pytest.raises(ValueError, match=r"races\[0\]\.balls\[0\]\.coulomb = 0.1: changes the compiled layout"):
        m.pack({"races[0].balls[0].coulomb": 0.1})
    # ... while the variant itself is a model of its own
    assert m.with_parameters(**{"races[0].balls[0].coulomb": 0.1}).has_friction
    p = m.pack({"races[0].balls[0].mass": 0.02})
    np.testing.assert_array_equal(p, m.with_parameters(**{"races[0].balls[0].mass": 0.02}).to_array())


def test_a_value_out_of_range_names_the_key_value_and_range():
    from rotorlab.io._build import build_machine

    m = build_machine(load_case("pico21-balancer").model)
    with pytest.raises(ValueError, match=r"^races\[0\]\.balls\[1\]\.mass = -0.01: must be > 0 kg$"):
        m.with_parameters(**{"races[0].balls[1].mass": -0.01})
    with pytest.raises(ValueError, match=r"must be >= 0 and <= 1$"):
        build_machine(load_case("washer-knock").model).with_parameters(**{"clearances[0].restitution": 1.5})
    with pytest.raises(KeyError, match=r"'races\[7\]\.radius' is not a parameter of this Machine"):
        m.with_parameters(**{"races[7].radius": 0.1})
    assert math.isnan(float("nan")) and not m.parameters["races[0].radius"].admits(float("nan"))


def test_a_structure_key_rebuilds_the_structure_from_its_table_alone():
    """``structure.<key path>``: the machine's structure is rebuilt from its own table: the
    drum's bearing ``kxx = 25 kN/m`` (its ``kyy`` not written, so equal to it) doubled adds 25
    kN/m to K at the drum's x and y and nowhere else."""
    from rotorlab.io._build import build_machine

    case = load_case("washer-horizontal")
    m = build_machine(case.model)
    kxx = m.parameters["structure.bearings[0].kxx"].value
    v = m.with_parameters(**{"structure.bearings[0].kxx": 2 * kxx})
    dK = v.structure.K - m.structure.K
    assert kxx == 25e3 and np.count_nonzero(dK) == 2 and dK[0, 0] == dK[1, 1] == kxx
    assert v.parameters["structure.bearings[0].kxx"].value == 2 * kxx


def _old_variant(case_model, keys, races, drive):
    """How a sweep made a ``model.<key path>`` variant before the named parameters: the case
    document edited at those keys, validated and built (the reference the new path must match)."""
    from dataclasses import replace

    from rotorlab.io._build import build_machine

    doc = {"name": "sweep-point", "model": plain_data(case_model.model_dump(mode="python"))}
    m = build_machine(validate_case(doc, overrides={k: float(v) for k, v in keys.items()}).model)
    if races is not None:
        m = replace(m, races=tuple(m.races[i] for i in races))
    return m.with_drive(drive)


@pytest.mark.parametrize("name, races, coords", [
    ("pico21-balancer", (1,), {"model.races[1].balls[0].mass": [0.004, 0.006],
                               "model.unbalances[0].magnitude": [1e-4, 3e-4]}),
    ("washer-horizontal", None, {"model.structure.bearings[0].kxx": [2e4, 3e4],
                                 "model.races[0].radius": [0.2, 0.25]}),
])
def test_sweep_points_are_the_edited_case_s_bit_for_bit(name, races, coords):
    """The starts and packed parameters of a machine sweep over ``model.<key path>`` values
    (through ``Machine.with_parameters``) equal those of the case document edited at each
    point, bit for bit: the sweep's results are unchanged."""
    from rotorlab.analyses._machine import machine_mapper
    from rotorlab.io import SweepSpec

    case = load_case(name)
    spec = SweepSpec(name="s", speed="600 rpm", t_end=1.0, **({"races": list(races)} if races else {}))
    mapper = machine_mapper(case.model, spec, {})
    grid = {k: np.asarray(v, dtype=float) for k, v in coords.items()}
    grid["psi_1"] = np.array([0.3, 1.1])
    _, Y0, P = mapper.starts(grid)
    for i in range(2):
        keys = {k: grid[k][i] for k in coords}
        ref = _old_variant(case.model, keys, races, mapper.model.drive)
        np.testing.assert_array_equal(P[i], ref.to_array())
        angles = list(mapper.base_angles)
        angles[0] = grid["psi_1"][i]
        np.testing.assert_array_equal(Y0[i], ref.initial_state(angles, ball_rates=np.zeros(len(angles))))


def _rub_machine():
    """rub-jeffcott's rotor (10 kg on 1e6 N/m, 6 kg mm, 1 mm gap, 1e7 N/m stator) as a machine."""
    from rotorlab.linear import LinearSystem
    from rotorlab.models import Clearance, ConstantSpeed, ElasticStator, Machine, Unbalance

    s = LinearSystem(M=np.diag([10.0, 10.0, 0.1, 0.1]), C=np.diag([316.227766, 316.227766, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([1e6, 1e6, 1e4, 1e4]))
    cl = Clearance(0, 1e-3, ElasticStator(1e7), friction=0.02, rotor_radius=0.05)
    return Machine(s, unbalances=(Unbalance(0, 6e-3),), drive=ConstantSpeed(474.341649), clearances=(cl,))


@pytest.mark.parametrize("which", ["rub_rotor", "machine"])
def test_a_rub_map_sets_its_points_through_the_named_parameters_bit_for_bit(which):
    """A rub map's points (every coordinate at once) are packed by ``model.pack`` of the named
    parameters: the same vectors as the packed entries the map used to overwrite by index
    (``rub_parameters``), for the rub rotor (its own entries; its preset machine's follow the
    named values) and for a machine with a clearance."""
    from rotorlab.contact import RubRegimes

    model = build_model(load_case("rub-jeffcott").model) if which == "rub_rotor" else _rub_machine()
    regimes = RubRegimes(model, t_end=1.0, window=0.1)
    coords = {k: np.linspace(0.3, 0.9, 5) * (1.0 if k == "restitution" else model.to_array()[i] * 2.0)
              for k, (i, _) in model.rub_parameters.items()}
    old = np.tile(model.to_array(), (5, 1))
    for k, v in coords.items():
        old[:, model.rub_parameters[k][0]] = v
    got = regimes.point_parameters(coords)
    # the rub rotor's own 15 entries lead its vector (its preset machine's follow them)
    n_own = 15 if which == "rub_rotor" else old.shape[1]
    np.testing.assert_array_equal(got[:, :n_own], old[:, :n_own])
    keys = regimes.parameter_keys()
    for i in range(5):  # every entry, the machine kernel's too, is the variant model's
        variant = model.with_parameters(**{keys[k]: float(v[i]) for k, v in coords.items()})
        np.testing.assert_array_equal(got[i], variant.to_array())
    key = keys["clearance"]
    assert key == ("clearance" if which == "rub_rotor" else "clearances[0].gap")
    with pytest.raises(ValueError, match=rf"^{re.escape(key)} = -0.001: must be > 0 m$"):
        regimes.point_parameters({"clearance": np.array([1e-3, -1e-3])})


def test_a_rigid_stator_has_no_stator_parameters():
    """A rub rotor against a rigid stator (no ``stator_stiffness``) has neither stator key: the
    case refuses a stator damping without a stator stiffness, and there is no stiffness to vary."""
    case = load_case("rub-jeffcott")
    doc = {"name": "rigid", "model": plain_data(case.model.model_dump(mode="python"))}
    del doc["model"]["stator_stiffness"]
    model = build_model(validate_case(doc).model)
    assert model.rotor.rigid_stator and "stator_damping" not in model.parameters
    assert "stator_stiffness" not in model.parameters and len(model.parameters) == 10
    edited = build_model(validate_case(doc, overrides={"model.restitution": 0.7}).model)
    np.testing.assert_array_equal(model.with_parameters(restitution=0.7).to_array(), edited.to_array())


def _old_balancer_variant(model, frame, values):
    """How ``BalancerRegimes`` made a point's model before the named parameters (the reference):
    rotor fields replaced, every ball rebuilt keeping J / (m l^2), a new ConstantSpeed."""
    from dataclasses import replace

    from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls

    rotor = replace(model.rotor, **{k: v for k, v in values.items()
                                    if k in ("disc_mass", "eccentricity", "stiffness", "damping")})
    kw = {k[5:]: v for k, v in values.items() if k.startswith("ball_")}
    balls = model.balls
    if kw:
        balls = tuple(BallParams(kw.get("mass", b.mass), kw.get("radius", b.radius),
                                 inertia=b.inertia / (b.mass * b.radius**2) * kw.get("mass", b.mass)
                                 * kw.get("radius", b.radius)**2,
                                 damping=kw.get("damping", b.damping), friction=kw.get("friction", b.friction))
                      for b in model.balls)
    speed = ConstantSpeed(values["spin_speed"]) if "spin_speed" in values else model.speed
    return JeffcottBalls(rotor, balls, speed=speed, frame=frame)


def test_balancer_sweep_aliases_are_named_parameters_bit_for_bit():
    """``ball_mass``, ``ball_radius``, ``ball_damping``, ``spin_speed`` and ``disc_mass`` of a
    ``jeffcott_balls`` sweep resolve to named parameters (``balls[i].mass`` ..., ``speed.speed``)
    and go through ``with_parameters``: every point's packed parameters and start equal those
    the mapper made before, bit for bit; ``model.<key path>`` names the same numbers."""
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.io import SweepSpec

    case = load_case("autobalancer")
    axes = {"ball_mass": (0.01, 0.03, 3), "ball_radius": (0.04, 0.06, 2), "ball_damping": (0.0, 1e-3, 2),
            "spin_speed": (100.0, 200.0, 2), "disc_mass": (1.0, 2.0, 2)}
    mapper = build_sweep(case.model, SweepSpec(name="s", speed_ratio=2.0, t_end=1.0), axes=axes).analysis.mapper
    rng = np.random.default_rng(0)
    coords = {k: rng.choice(np.linspace(*v), 8) for k, v in axes.items()}
    coords["psi_1"] = rng.uniform(0.0, 6.0, 8)
    model, Y0, P = mapper.starts(coords)
    for i in range(8):
        ref = _old_balancer_variant(mapper.model, mapper.frame, {k: float(coords[k][i]) for k in axes})
        np.testing.assert_array_equal(P[i], ref.to_array())
        yr = np.zeros(ref.n_state)
        yr[4:6] = coords["psi_1"][i], mapper.base_angles[1]
        np.testing.assert_array_equal(Y0[i], ref.with_frame("rotating").to_frame(0.0, yr[None], ref.frame)[0])
    assert mapper.coordinate_parameter("ball_mass").bounds == mapper.model.parameters["balls[0].mass"].bounds
    # ball_mass = every ball's mass, and its inertia at the same J / (m l^2)
    b = mapper.model.balls[0]
    keyed = {"model.speed.speed": coords["spin_speed"], "psi_1": coords["psi_1"]}
    for j in range(2):
        keyed[f"model.balls[{j}].mass"] = coords["ball_mass"]
        keyed[f"model.balls[{j}].inertia"] = b.inertia / (b.mass * b.radius**2) * coords["ball_mass"] * b.radius**2
    _, Y0k, Pk = mapper.starts(keyed)
    _, Y0a, Pa = mapper.starts({k: coords[k] for k in ("ball_mass", "spin_speed", "psi_1")})
    np.testing.assert_array_equal(Pk, Pa)
    np.testing.assert_array_equal(Y0k, Y0a)
    with pytest.raises(ValueError, match=r"model\.speed\.speed varies speed\.speed, which another coordinate"):
        mapper.starts({"spin_speed": coords["spin_speed"], "model.speed.speed": coords["spin_speed"]})


def test_torus_sweep_coordinates_are_named_parameters_bit_for_bit():
    """A toroidal ball's parameter coordinates (``offset``, ``spin_speed`` ...) are its named
    parameters (``with_parameters``), also as ``model.<key path>``: the same packed parameters as
    the model's fields replaced directly (the mapper's former path)."""
    from dataclasses import replace

    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.io import SweepSpec

    case = load_case("strautmanis-torus")
    spec = SweepSpec(name="s", param={"model.offset": [0.0, 1e-3, 2]}, ic={"psi": [0.0, 6.0, 3]}, t_end=1.0)
    sweep = build_sweep(case.model, spec)
    mapper = sweep.analysis.mapper
    assert sweep.dims == ("model.offset", "psi")
    rng = np.random.default_rng(1)
    coords = {"spin_speed": rng.choice([50.0, 60.0], 6), "model.offset": rng.choice([0.0, 1e-3], 6),
              "psi": rng.uniform(0.0, 6.0, 6)}
    _, Y0, P = mapper.starts(coords)
    for i in range(6):
        ref = replace(mapper.model, spin_speed=coords["spin_speed"][i], offset=coords["model.offset"][i])
        np.testing.assert_array_equal(P[i], ref.to_array())
        np.testing.assert_array_equal(Y0[i], ref.initial_state(coords["psi"][i], 0.0, 0.0, 0.0))
    assert mapper.coordinate_parameter("model.offset").allowed == ">= 0 m"


def test_with_parameters_sets_its_values_together():
    """A check that ties several numbers (a ball's ``inertia >= mass radius^2``) holds for the
    result, as for a case edited at all those keys at once: a larger radius with the inertia it
    needs is taken in either order; a radius alone that breaks the check is still refused. A
    point-mass ball (the case wrote no inertia) stays one: its inertia follows ``m l^2``."""
    point = build_model(load_case("autobalancer").model)
    b = point.balls[0]
    assert b.inertia == b.mass * b.radius**2
    assert point.with_parameters(**{"balls[0].radius": 0.06}).balls[0].inertia == b.mass * 0.06**2
    model = point.with_parameters(**{"balls[0].inertia": 1.2 * b.inertia})  # a ball with its own inertia
    inertia = 1.2 * b.mass * 0.06**2
    for values in ({"balls[0].radius": 0.06, "balls[0].inertia": inertia},
                   {"balls[0].inertia": inertia, "balls[0].radius": 0.06}):
        got = model.with_parameters(**values)
        assert (got.balls[0].radius, got.balls[0].inertia) == (0.06, inertia)
    with pytest.raises(ValueError, match=r"inertia must be >= mass \* radius\*\*2"):
        model.with_parameters(**{"balls[0].radius": 0.06})


def test_a_key_path_ball_mass_sweep_keeps_a_point_mass_ball_one():
    """autobalancer's balls are point masses (no inertia written): a sweep over
    ``model.balls[0].mass`` up to 40 g (above the 30 g whose m l^2 the inertia had) packs
    ``inertia = m l^2`` of each point, as the case edited at that key; it used to fail every
    point (inertia below m l^2) after the store existed."""
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.io import SweepSpec

    case = load_case("autobalancer")
    axes = {"model.balls[0].mass": (0.02, 0.04, 2)}
    mapper = build_sweep(case.model, SweepSpec(name="s", speed_ratio=2.0, t_end=1.0), axes=axes).analysis.mapper
    _, _, P = mapper.starts({"model.balls[0].mass": np.array([0.02, 0.04])})
    for i, m in enumerate((0.02, 0.04)):
        np.testing.assert_array_equal(P[i], _edited(case, "balls[0].mass", m).with_frame(mapper.frame)
                                      .with_speed(mapper.model.speed).to_array())
        assert P[i, 14] == m * 0.05**2  # balls[0]: mass, radius, inertia at 12, 13, 14
