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
from rotorlab.models._jeffcott_balls import _kernels_for
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
    for frame in ("fixed", "rotating"):
        for n in (1, 2, 3):  # the ball count is a compile-time constant of each lane copy
            out.append((f"jeffcott_balls {frame} n={n}", _kernels_for(frame, n, False, True)))
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
