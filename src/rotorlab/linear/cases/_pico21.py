"""The Pico 21 laboratory centrifuge of seed paper 000: three rigid bodies on elastic supports.

Body 1 is the stator with the housing (does not spin), body 2 the motor armature, body 3 the
centrifuge rotor; each has a translation and a tilt in each lateral plane (12 DOFs). The paper
gives their masses and inertias, a compliance matrix ``delta`` (6 x 6 per plane, isotropic) and
its inverse, and obtains the Campbell diagram from Lagrange's equations with the gyroscopic
terms of the two spinning bodies.

Reading of the model
--------------------
Node 0 = stator at z = l_1 = 45 mm, node 1 = armature at l_2 = 32 mm, node 2 = rotor at l_3 =
120 mm, z measured up the axis from the point O where the housing's feet act. The paper's
(xi, psi) and (eta, theta) are our (x, phi_x) and (y, phi_y). ``delta`` is in SI units (m/N,
1/N, rad/(N m)): ``delta(P1, M_k) / delta(M1, M_k) = 0.045 m = l_1`` for every k, as it must for
the rigid housing, so the lengths in the influence coefficients are in metres.

Printed data that disagree, and how they are resolved
----------------------------------------------------
Each finding is *detected* by :func:`audit_pico21` from the printed tables in
:mod:`._pico21_data`, and tested in ``tests/validation/test_linear_seed000.py``.

1. ``delta(M1, M1) = delta(M1, M2) = delta(M1, M3)`` are printed as ``107.193778999e-5``. The
   same coefficients in the printed quadratic form of the potential energy are
   ``0.0005359468895 M1^2`` (so ``2 x 0.0005359468895 = 107.1893779e-5``) and
   ``0.001071893779 M2 M1``, ``M3 M1``; the rigid-housing identity ``delta(P1, M_k) = l_1
   delta(M1, M_k)`` gives ``4.823522006e-5 / 0.045 = 107.1893779e-5``; and only with this value
   does ``inv(delta)`` reproduce the printed stiffness coefficients. **Resolved:
   107.1893779e-5** (transposed digits in the matrix). Because ``delta`` has condition number
   1.5e6, the misprint (4e-5 relative) changes ``inv(delta)`` by up to a factor 2.2
   (K(P2, xi3): 7.0e5 instead of 3.2e5) -- the disagreement between inv(delta) and the printed
   stiffness noted in issue 3.
2. The printed force P1 multiplies ``(xi3 + eta2)`` and ``(psi3 + theta2)``: **resolved to
   (xi3 + eta3), (psi3 + theta3)** (every other row, and the symmetry K(P1, xi3) = K(P3,
   xi1), say so).
3. The potential energy in the displacements has three misprints, found by comparing it with
   the printed stiffness (``Pi = 1/2 sum C_ij u_i u_j``: coefficient ``C_ii / 2`` on squares,
   ``C_ij`` on products) and with its own y-plane half: ``1.2333251673e8 xi1^2`` (and
   ``eta1^2``) has an extra digit, **1.233251673e8** (= K11 / 2); ``16203.81435 psi2^2`` is
   **psi3^2** (the y-plane has ``theta3^2``, and ``psi2^2`` already appears as 48366.19);
   ``5.229315675e6 psi1 xi1`` is **psi1 xi2** (the y-plane has ``theta1 eta2``; ``xi1 psi1``
   already appears as -3.995e6).
4. The total kinetic energy T printed after the per-body energies drops the cross terms
   ``I_PA gamma' psi2' theta2`` and ``I_PR gamma' psi3' theta3`` that the expansion of
   ``T_2A = ... + I_PA (gamma' + psi2' theta2)^2 / 2`` and ``T_3R`` contain. Without them the
   natural frequencies could not depend on the speed, yet the paper's Campbell diagram (Fig. 7),
   its abstract ("two resonant frequencies instead of one") and conclusion 2 show that they do.
   **Resolved: the gyroscopic terms are kept** (``RigidBody(spinning=True)`` for bodies 2
   and 3, ``spinning=False`` for the stator).
5. ``I_S = I_S0 = 0.018 kg mm^2`` for the 2.4 kg housing would mean a radius of gyration of
   0.087 mm. **Resolved: 0.018 kg m^2** (radius of gyration 86.6 mm, the size of the housing,
   cf. l = 86 mm).
6. The armature's printed pair ``I_A = 93``, ``I_A0 = 425 kg mm^2`` cannot both be right as
   diametral and polar inertia: no rigid body has ``I_p > 2 I_d``. The rotor's pair read the
   same way (``I_R = 882`` diametral, ``I_R0 = 1529`` polar, ``I_p / I_d = 1.73``) is that of a
   flat rotor, as a centrifuge rotor is. **Resolved: the armature's two values are swapped**:
   ``I_d = 425``, ``I_p = 93 kg mm^2`` (``I_p / I_d = 0.22``, a slender cylinder about 87 mm
   long -- the room between the clamp at O and the bearing at l = 86 mm). The alternative
   reading "subscript 0 = diametral for every body" is also admissible but makes the rotor a
   tall body (``I_p / I_d = 0.58``); the armature modes above 1.5 kHz are the only ones that
   depend noticeably on this choice.
7. The text counts "14 degrees of freedom"; its coordinates (xi_i, eta_i, psi_i, theta_i for
   three bodies, plus phi) are 13, of which phi is prescribed (constant speed): the linear
   model has 12.

Geometry behind delta
---------------------
The paper prints neither the shaft's EI nor the bearing and support stiffnesses. Fitting its
influence-coefficient model (:func:`rotorlab.linear.influence_compliance`: rigid housing on
feet at O with C_Q, C_M; shaft clamped into the housing at O; one elastic bearing C_Pi at
z = l = 86 mm) to the 21 distinct printed coefficients gives round numbers, ``C_Q = 13932 N/m``,
``EI = 550.3 N m^2``, ``C_Pi = 6.0e7 N/m`` and ``C_M = 1 / 1.071893779e-3 N m/rad``, with
which the model reproduces every resolved coefficient to 6e-10 (all printed digits). That the
printed l = 86 mm turns out to be the bearing position is a further check of this reading. So
the case can be built three ways -- resolved compliance, printed stiffness, geometry -- and
they agree (tests).

References
----------
Seed 000: Babenko A.E., Lavrenko Ia.I., Strackeljan J., investigation of the Pico 21
laboratory centrifuge as a multibody system (potential energy Pi = Pi_val + Pi_O + Pi_p,
compliance matrix ||delta_ij||, stiffness ||C_ij|| = ||delta_ij||^-1, kinetic energies T_1S,
T_2A, T_3R, Lagrange's equations, Fig. 7 Campbell diagram, conclusion 3 on identification).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorlab.linear._assembly import assemble
from rotorlab.linear._elements import ElasticConnection, RigidBody
from rotorlab.linear._influence import (
    HousingSupport,
    InfluenceModel,
    ShaftSpan,
    ShaftSupport,
    compliance_to_stiffness,
    influence_compliance,
)
from rotorlab.linear._system import LinearSystem
from rotorlab.linear.cases._pico21_data import (
    FORCES,
    PRINTED_ENERGY_IN_FORCES,
    PRINTED_STIFFNESS,
)

__all__ = ["Pico21Data", "PICO21", "RESOLVED_COMPLIANCE", "pico21", "pico21_influence_model"]


def _resolved_compliance() -> np.ndarray:
    """The compliance matrix rebuilt from the printed energy quadratic form (finding 1)."""
    d = np.zeros((6, 6))
    for (a, b), c in PRINTED_ENERGY_IN_FORCES.items():
        i, j = FORCES.index(a), FORCES.index(b)
        if i == j:
            d[i, i] = 2.0 * c
        else:
            d[i, j] = d[j, i] = c
    return d


#: ``delta`` (6 x 6, SI) with finding 1 resolved: taken from the printed potential energy in the
#: forces, which agrees with every other printed coefficient of ``delta`` to <= 3e-10.
RESOLVED_COMPLIANCE = _resolved_compliance()
RESOLVED_COMPLIANCE.setflags(write=False)


def _pos(name: str, value, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not math.isfinite(v) or v <= 0:
        raise ValueError(f"Pico21Data.{name} must be a finite number > 0 ({unit}), got {value!r}")
    return v


@dataclass(frozen=True, slots=True)
class Pico21Data:
    """Parameters of the Pico 21 three-body model, resolved (see module docstring), SI units.

    Parameters
    ----------
    stator_mass, armature_mass, rotor_mass : float
        m_S, m_A, m_R (kg).
    stator_diametral_inertia : float
        I_S (kg m^2); the printed 0.018 "kg mm^2" read as kg m^2 (finding 5).
    armature_diametral_inertia, armature_polar_inertia : float
        (kg m^2); the printed I_A0 and I_A, swapped (finding 6).
    rotor_diametral_inertia, rotor_polar_inertia : float
        I_R and I_R0 (kg m^2).
    stator_position, armature_position, rotor_position : float
        l_1, l_2, l_3 above the support point O (m).
    bearing_position : float
        l (m): the elastic bearing between shaft and housing.
    support_translational_stiffness, support_rotational_stiffness : float
        C_Q (N/m) and C_M (N m/rad) of the housing's feet (reconstructed, see module
        docstring).
    shaft_flexural_rigidity : float
        EI (N m^2) of the shaft, clamped into the housing at O (reconstructed).
    bearing_stiffness : float
        C_Pi (N/m) (reconstructed).

    Examples
    --------
    >>> round(PICO21.support_rotational_stiffness, 3)
    932.928
    >>> import dataclasses
    >>> dataclasses.replace(PICO21, rotor_mass=0.0)
    Traceback (most recent call last):
    ...
    ValueError: Pico21Data.rotor_mass must be a finite number > 0 (kg), got 0.0
    """

    stator_mass: float = 2.4
    armature_mass: float = 0.6
    rotor_mass: float = 0.507
    stator_diametral_inertia: float = 0.018
    armature_diametral_inertia: float = 425e-6
    armature_polar_inertia: float = 93e-6
    rotor_diametral_inertia: float = 882e-6
    rotor_polar_inertia: float = 1529e-6
    stator_position: float = 0.045
    armature_position: float = 0.032
    rotor_position: float = 0.120
    bearing_position: float = 0.086
    support_translational_stiffness: float = 13932.0
    support_rotational_stiffness: float = 1.0 / 1.071893779e-3
    shaft_flexural_rigidity: float = 550.3
    bearing_stiffness: float = 6.0e7

    def __post_init__(self) -> None:
        units = {"mass": "kg", "inertia": "kg m^2", "position": "m"}
        extra = {"support_translational_stiffness": "N/m",
                 "support_rotational_stiffness": "N m/rad",
                 "shaft_flexural_rigidity": "N m^2", "bearing_stiffness": "N/m"}
        for name in self.__slots__:
            unit = extra.get(name) or next(u for k, u in units.items() if name.endswith(k))
            object.__setattr__(self, name, _pos(name, getattr(self, name), unit))

    def bodies(self) -> tuple[RigidBody, RigidBody, RigidBody]:
        """Return the stator (node 0, not spinning), armature (node 1) and rotor (node 2)."""
        return (
            RigidBody(0, self.stator_mass, self.stator_diametral_inertia,
                      self.stator_diametral_inertia, spinning=False),
            RigidBody(1, self.armature_mass, self.armature_diametral_inertia,
                      self.armature_polar_inertia),
            RigidBody(2, self.rotor_mass, self.rotor_diametral_inertia, self.rotor_polar_inertia),
        )


#: The resolved parameter set used by :func:`pico21`.
PICO21 = Pico21Data()


def pico21_influence_model(data: Pico21Data = PICO21) -> InfluenceModel:
    """Return the shaft-in-housing geometry of the centrifuge (seed 000, Figs. 3 and 4).

    Parameters
    ----------
    data : Pico21Data

    Returns
    -------
    InfluenceModel
        Stations stator (on the housing), armature and rotor (on the shaft); shaft from O to the
        rotor, clamped at O, elastic bearing at ``bearing_position``; housing feet at O.
    """
    return InfluenceModel(
        station_position=(data.stator_position, data.armature_position, data.rotor_position),
        station_on_shaft=(False, True, True),
        spans=(ShaftSpan(0.0, data.rotor_position, data.shaft_flexural_rigidity),),
        shaft_supports=(ShaftSupport.clamp(0.0),
                        ShaftSupport(data.bearing_position, data.bearing_stiffness)),
        housing_support=HousingSupport(0.0, data.support_translational_stiffness,
                                       data.support_rotational_stiffness),
    )


def pico21(data: Pico21Data = PICO21, *, source: str = "compliance") -> LinearSystem:
    """Return the linear model of the Pico 21 centrifuge (seed 000).

    Parameters
    ----------
    data : Pico21Data
        Masses and inertias (all sources) and the geometry (``source="geometry"`` only).
    source : {"compliance", "stiffness", "geometry"}
        Where the elastic coupling comes from: the seed's compliance matrix with finding 1
        resolved, inverted (the paper's own route); the printed stiffness coefficients
        (symmetrised); or the influence-coefficient model built from ``data``'s geometry and
        stiffnesses (use this to vary C_Q, C_M, EI, ...).

    Returns
    -------
    LinearSystem
        Nodes 0 stator, 1 armature, 2 rotor, at their heights above O.

    Examples
    --------
    >>> from rotorlab.linear import modal
    >>> modal(pico21()).frequency[:4].round(3).tolist()
    [9.803, 9.803, 33.527, 33.527]
    """
    if source == "compliance":
        k = compliance_to_stiffness(RESOLVED_COMPLIANCE)
    elif source == "stiffness":
        k = 0.5 * (PRINTED_STIFFNESS + PRINTED_STIFFNESS.T)
    elif source == "geometry":
        k = compliance_to_stiffness(influence_compliance(pico21_influence_model(data)))
    else:
        raise ValueError(f"source must be 'compliance', 'stiffness' or 'geometry', "
                         f"got {source!r}")
    conn = ElasticConnection(nodes=(0, 1, 2), stiffness_x=k)
    return assemble([*data.bodies(), conn],
                    node_position=(data.stator_position, data.armature_position,
                                   data.rotor_position),
                    node_label=("stator", "armature", "rotor"))
