"""Every kernel that declares itself lane-friendly (``Kernels.vectorises``) vectorises in the lane
driver, and the models choose such a kernel wherever they can, so that a new or changed kernel
cannot silently fall back to scalar code on the ensemble paths.

The check compiles the lane driver's per-stage loop over lanes and inspects its optimised LLVM IR
(:func:`rotorlab.integrate._drivers.is_vectorised`: packed ``<N x double>`` arithmetic and no
scalar library call).
"""

import pytest
from llvmlite import binding as ll

from rotorlab.integrate._drivers import is_vectorised
from rotorlab.models import JeffcottBalls
from rotorlab.models._base import Kernels
from rotorlab.models._jeffcott_params import BallParams, RotorParams
from rotorlab.models._speed import ConstantSpeed, HillRunUp, LinearRamp
from rotorlab.models._toroidal_ball import strautmanis_torus

pytestmark = pytest.mark.skipif(
    not any(ll.get_host_cpu_features().get(f) for f in ("avx", "sse2", "neon")),
    reason="no SIMD unit known to LLVM on this CPU",
)


def _declared():
    """(name, Kernels) of every kernel bundle the package declares lane-friendly."""
    out = []
    rotor = RotorParams(disc_mass=10.0, eccentricity=1e-4, stiffness=1e5, damping=20.0)
    ball = BallParams(mass=0.05, radius=0.1, damping=1e-4)
    for frame in ("fixed", "rotating"):  # the preset machine's kernel of either frame
        for n in (1, 2, 3):  # the ball count is a compile-time constant of each lane copy
            for speed in (ConstantSpeed(200.0), LinearRamp(0.0, 200.0, 1.0)) if n == 2 else (ConstantSpeed(200.0),):
                model = JeffcottBalls(rotor, (ball,) * n, speed=speed, frame=frame)
                out.append((f"jeffcott_balls {frame} n={n} {type(speed).__name__}", model.kernels))
    out.append(("toroidal_ball", strautmanis_torus(1e-5).kernels))
    return out


@pytest.mark.parametrize("name,kernels", _declared(), ids=[n for n, _ in _declared()])
def test_declared_kernel_vectorises(name, kernels):
    assert isinstance(kernels, Kernels) and kernels.vectorises
    assert is_vectorised(kernels, lanes=8), f"{name}: the lane driver's loop did not vectorise"


def test_models_choose_the_lane_friendly_kernel():
    rotor = RotorParams(disc_mass=10.0, eccentricity=1e-4, stiffness=1e5, damping=20.0)
    ball = BallParams(mass=0.05, radius=0.1, damping=1e-4)
    for speed in (ConstantSpeed(200.0), LinearRamp(0.0, 200.0, 1.0)):
        for frame in ("fixed", "rotating"):
            model = JeffcottBalls(rotor, (ball, ball), speed=speed, frame=frame)
            assert model.kernels.vectorises, (speed, frame)
    # a Hill run-up needs exp/log (scalar library calls): the generic kernel, scalar driver
    hill = JeffcottBalls(rotor, (ball, ball), speed=HillRunUp(200.0, 1.0, 2.0))
    assert not hill.kernels.vectorises


def _machines():
    """Machines of every generated part, inlined into the lane driver (up to 12 states) or called,
    with the lane-friendly flag each declares (a Hill run-up's profile needs exp/log)."""
    import numpy as np

    from rotorlab.analyses import build_model
    from rotorlab.io import load_case
    from rotorlab.linear import LinearSystem
    from rotorlab.models import Ball, BallRace, Clearance, ConstantSpeed, ElasticStator, LinearRamp, Machine, Motor, Unbalance

    planar_s = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]), G=np.zeros((4, 4)),
                            K=np.diag([1.0, 1.0, 5.0, 5.0]))  # fmt: skip

    def planar(balls=(Ball(0.02, damping=0.01),) * 2, drive=ConstantSpeed(2.5), **kw):
        return Machine(planar_s, races=(BallRace(0, 1.0, balls),), unbalances=(Unbalance(0, 0.01),), drive=drive,
                       n_modes=2, **kw)  # fmt: skip

    M = np.diag([1.0, 1.0, 3.25, 3.25])
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = 0.5, -0.5
    K = np.zeros((4, 4))
    for zs in (3.0, -3.0):
        for j in (0, 1):
            T = np.zeros((1, 4))
            T[0, j], T[0, j + 2] = 1.0, zs
            K += 0.5 * T.T @ T
    rigid = LinearSystem(M=M, C=0.02 * K, G=G, K=K)

    def two_plane(balls):
        races = tuple(BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * balls, axial_offset=a) for a in (2.0, -2.0))
        return Machine(rigid, races=races, unbalances=(Unbalance(0, 0.01, 0.0, axial_offset=1.0),),
                       drive=ConstantSpeed(2.0))

    friction = (Ball(0.02, damping=0.01, coulomb=0.01, rolling=0.001),) * 2
    table = Motor(((0.0, 0.5, 1.0, 2.0), (0.4, 0.3, 0.2, 0.0)), polar_inertia=0.6)
    contact = Clearance(0, 1.0, ElasticStator(10.0), friction=0.02, rotor_radius=0.5)
    return {
        "planar": lambda: planar(),
        "two-plane-1": lambda: two_plane(1),
        "two-plane-2": lambda: two_plane(2),
        "friction, tabulated motor": lambda: planar(friction, table),
        "clearance, ramp": lambda: planar(drive=LinearRamp(0.0, 2.5, 10.0), clearances=(contact,)),
        "pico21-balancer": lambda: build_model(load_case("pico21-balancer").model),
        "hill run-up": lambda: planar(drive=HillRunUp(2.5, 1.0, 2.0)),
    }


@pytest.mark.parametrize("name", list(_machines()))
def test_machine_kernel_vectorises_as_its_lane_driver_calls_it(name):
    """The machine's generated kernel vectorises as the lane driver runs it, inlined (up to 12
    states, ``Machine._inline_lanes``) or called, exactly when it says so (``Kernels.vectorises``):
    every part but a Hill run-up's profile."""
    machine = _machines()[name]()
    kernels = machine.kernels
    assert kernels.inline_lanes is (kernels.n_state <= 12), name
    assert kernels.vectorises is (name != "hill run-up"), name
    assert is_vectorised(kernels) is kernels.vectorises, f"{name}: declares vectorises={kernels.vectorises}"


@pytest.mark.parametrize("name", ["clearance, ramp", "rub-jeffcott"])
def test_clearance_events_vectorise_in_the_lane_driver(name):
    """After every step the lane driver evaluates all lanes' event functions in one loop: a
    clearance's (the generated ``events``, its ``contact_terms`` inlined) vectorises there, as the
    rub rotor's hand-written events did; called per lane it did not (the rub map's lane ensemble
    ran 1.4x the hand-written kernel's CPU time for that alone, ``bench/rub.py``)."""
    from rotorlab.analyses import build_model
    from rotorlab.io import load_case

    model = build_model(load_case(name).model) if name == "rub-jeffcott" else _machines()[name]()
    assert model.kernels.n_events == 4
    assert is_vectorised(model.kernels, function="events"), name
