"""Linear rotordynamics: element matrices, assembly, modes, Campbell diagrams, critical speeds.

Build a :class:`LinearSystem` (``M q'' + (C + Omega G) q' + K q = f``) from elements --
Timoshenko :class:`ShaftElement`, :class:`RigidBody`, :class:`Bearing`,
:class:`ElasticConnection` (a stiffness or compliance matrix between bodies, as in seed 000) --
with :func:`assemble`, or from the geometry of a shaft in a housing on elastic feet with
:func:`influence_compliance`. Then analyse it: :func:`modal`, :func:`campbell`,
:func:`critical_speeds`, :func:`unbalance_response`, :func:`identify_parameters`.
Built-in machines are in :mod:`rotorlab.linear.cases`.

Examples
--------
>>> import numpy as np
>>> from rotorlab.linear import RPM, campbell
>>> from rotorlab.linear.cases import friswell_rotor
>>> ds = campbell(friswell_rotor(), RPM * np.linspace(0, 4000, 41), n_modes=6)
>>> ds.frequency.isel(speed=0).round(2).values.tolist()
[13.79, 13.79, 43.66, 43.66, 114.08, 114.08]
"""

from rotorlab.linear._assembly import assemble, uniform_shaft
from rotorlab.linear._campbell import RPM, campbell, track_modes
from rotorlab.linear._critical import (
    DEFINITIONS,
    NOT_EXCITED_NOTE,
    CriticalSpeeds,
    critical_speeds,
    excited_by_unbalance,
)
from rotorlab.linear._eigen import METHODS, whirl_of_shapes
from rotorlab.linear._elements import AbstractElement, Bearing, ElasticConnection, RigidBody
from rotorlab.linear._identify import FrequencyMeasurement, Identification, identify_parameters
from rotorlab.linear._influence import (
    HousingSupport,
    InfluenceModel,
    ShaftSpan,
    ShaftSupport,
    compliance_to_stiffness,
    influence_compliance,
    stiffness_to_compliance,
)
from rotorlab.linear._modal import WHIRL_LABELS, Modes, log_decrement, modal, whirl_labels
from rotorlab.linear._response import unbalance_response
from rotorlab.linear._unbalance import Unbalance
from rotorlab.linear._shaft import STEEL, Material, ShaftElement, shear_coefficient
from rotorlab.linear._system import DIRECTIONS, LinearSystem, dof_index

__all__ = [
    # system and assembly
    "LinearSystem", "DIRECTIONS", "dof_index", "assemble", "uniform_shaft",
    # elements
    "AbstractElement", "ShaftElement", "Material", "STEEL", "shear_coefficient", "RigidBody",
    "Bearing", "ElasticConnection",
    # influence coefficients
    "compliance_to_stiffness", "stiffness_to_compliance", "ShaftSpan", "ShaftSupport",
    "HousingSupport", "InfluenceModel", "influence_compliance",
    # analyses
    "modal", "Modes", "campbell", "track_modes", "RPM", "critical_speeds", "CriticalSpeeds",
    "excited_by_unbalance", "DEFINITIONS", "NOT_EXCITED_NOTE",
    "unbalance_response", "Unbalance", "identify_parameters", "FrequencyMeasurement",
    "Identification", "log_decrement", "whirl_of_shapes", "whirl_labels", "WHIRL_LABELS",
    "METHODS",
]
