"""Models: frozen parameter objects plus compiled kernels (see :mod:`rotorlab.models._base`)."""

from rotorlab.models._absorber import TunedMassAbsorber, absorber_response
from rotorlab.models._base import AbstractModel, EventSpec, Kernels, no_events, no_reset
from rotorlab.models._benchmark import BENCHMARK, BenchmarkProblem
from rotorlab.models._impact_rotor import (
    CentrifugeRotor,
    Housing,
    ImpactRotor,
    StoneFeed,
    StonePush,
    StoneSequence,
    krasnov_crusher,
    stone_push,
)
from rotorlab.models._jeffcott_balls import JeffcottBalls, fixed_to_rotating, rotating_to_fixed
from rotorlab.models._jeffcott_params import BallParams, RotorParams
from rotorlab.models._jeffcott_physics import Linearization
from rotorlab.models._machine import (
    Ball,
    BallRace,
    Clearance,
    ElasticStator,
    Gravity,
    Machine,
    MachineLinearization,
    Motor,
    Unbalance,
)
from rotorlab.models._machine_corotating import CoRotatingMachine
from rotorlab.models._servo import ServoDrive
from rotorlab.models._protocol import AbstractParametrisedModel, Parameter, ParameterSpace
from rotorlab.models._speed import ConstantSpeed, HillRunUp, LinearRamp, speed_from_array
from rotorlab.models._toroidal_ball import ToroidalBall, WorkingPoint, strautmanis_torus

# In the order the API page shows them (autodoc follows __all__): the models users build first,
# the interfaces for implementers of a new model last.
__all__ = ["Machine", "CoRotatingMachine", "MachineLinearization", "Ball", "BallRace", "Unbalance", "Gravity",
           "Motor", "ServoDrive", "Clearance", "ElasticStator"]
__all__ += ["JeffcottBalls", "RotorParams", "BallParams", "Linearization", "fixed_to_rotating",
            "rotating_to_fixed", "ConstantSpeed", "LinearRamp", "HillRunUp", "speed_from_array"]
__all__ += ["ToroidalBall", "WorkingPoint", "strautmanis_torus"]
__all__ += ["ImpactRotor", "CentrifugeRotor", "Housing", "StoneFeed", "StonePush", "StoneSequence",
            "krasnov_crusher", "stone_push"]
__all__ += ["TunedMassAbsorber", "absorber_response"]
__all__ += ["BENCHMARK", "BenchmarkProblem"]
__all__ += ["AbstractModel", "EventSpec", "Kernels", "no_events", "no_reset", "AbstractParametrisedModel",
            "Parameter", "ParameterSpace"]
