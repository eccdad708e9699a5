"""The numbers of seed paper 000 exactly as printed, misprints included.

Babenko A.E., Lavrenko Ia.I., Strackeljan J., "Investigation of laboratory centrifuge motion as
multibody system" (in Ukrainian). Nothing here is corrected: :mod:`._pico21` audits these tables
against each other and resolves them. Generalised forces and displacements are ordered
``(P1, M1, P2, M2, P3, M3)`` and ``(xi1, psi1, xi2, psi2, xi3, psi3)``: body 1 is the stator
with the housing, body 2 the motor armature, body 3 the centrifuge rotor.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "FORCES",
    "PRINTED_PARAMETERS",
    "PRINTED_ENERGY_IN_FORCES",
    "PRINTED_COMPLIANCE",
    "PRINTED_STIFFNESS",
    "PRINTED_STIFFNESS_COLUMN_LABELS",
    "PRINTED_ENERGY_IN_DISPLACEMENTS",
]

#: Order of the generalised forces (and, pairwise, of the x-plane displacements).
FORCES = ("P1", "M1", "P2", "M2", "P3", "M3")

#: "Для чисельного розрахунку використовувались наступні параметри центрифуги" (value, unit as
#: printed). R: rotor, A: armature (anchor), S: stator.
PRINTED_PARAMETERS = {
    "m_R": (0.507, "kg"),
    "m_A": (0.6, "kg"),
    "m_S": (2.4, "kg"),
    "l": (86.0, "mm"),
    "l_1": (45.0, "mm"),
    "l_2": (32.0, "mm"),
    "l_3": (120.0, "mm"),
    "I_R": (882.0, "kg mm^2"),
    "I_R0": (1529.0, "kg mm^2"),
    "I_A": (93.0, "kg mm^2"),
    "I_A0": (425.0, "kg mm^2"),
    "I_S": (0.018, "kg mm^2"),
    "I_S0": (0.018, "kg mm^2"),
}

#: Potential energy as a quadratic form in the forces, "Спростивши та згрупувавши члени ...":
#: coefficient of each printed product (Pi = sum of coefficient * product).
PRINTED_ENERGY_IN_FORCES = {
    ("P2", "P2"): 0.00003644122459,
    ("M2", "P2"): 0.00003452119679,
    ("M3", "P2"): 0.00003405918930,
    ("P3", "P2"): 0.00007588797397,
    ("P3", "M2"): 0.0001284593280,
    ("P3", "P3"): 0.00004366099383,
    ("M3", "P3"): 0.0001314498422,
    ("M3", "M2"): 0.001061990566,
    ("M3", "M3"): 0.0005888039632,
    ("M2", "M2"): 0.0005444108767,
    ("P3", "P1"): 0.00007756542997,
    ("P2", "P1"): 0.00007332073060,
    ("P1", "P1"): 0.00003697389423,
    ("M3", "P1"): 0.00004823522006,
    ("M3", "M1"): 0.001071893779,
    ("P3", "M1"): 0.0001286272535,
    ("M2", "P1"): 0.00004823522006,
    ("M2", "M1"): 0.001071893779,
    ("P2", "M1"): 0.00003430060093,
    ("P1", "M1"): 0.00004823522006,
    ("M1", "M1"): 0.0005359468895,
}

#: The compliance matrix ||delta_ij|| as printed (the factor 10^-5 applied), rows and columns in
#: the order of :data:`FORCES`.
PRINTED_COMPLIANCE = np.array([
    [7.394778845, 4.823522006, 7.332073059, 4.823522006, 7.756542995, 4.823522006],
    [4.823522006, 107.193778999, 3.430060091, 107.193778999, 12.862725349, 107.193778999],
    [7.3320730599, 3.430060091, 7.288244917, 3.452119679, 7.588797395, 3.405918929],
    [4.823522006, 107.193778999, 3.452119679, 108.882175339, 12.845932800, 106.1990566],
    [7.756542995, 12.862725349, 7.588797395, 12.845932800, 8.732198765, 13.144984220],
    [4.823522006, 107.193778999, 3.405918929, 106.1990566, 13.144984220, 117.760792639],
]) * 1e-5
PRINTED_COMPLIANCE.setflags(write=False)

#: The forces in terms of displacements, "P_1 = 2.4665...e8 (xi_1 + eta_1) - ...": row i holds
#: the six printed coefficients of force i, in the printed order of the terms.
PRINTED_STIFFNESS = np.array([
    [2.46650323058199584e8, -3.99534296177572106e6, -2.16524188848188698e8,
     2.86077985157029238e6, -3.01122022080636360e7, 5.77536878491423560e5],
    [-3.99534296177823702e6, 2.63472010161050305e5, 5.22931441159042530e6,
     -1.25613852706632316e5, -1.23459839000073937e6, 23678.9497972274876],
    [-2.16524188848226636e8, 5.22931441158880014e6, 2.16202652747254848e8,
     -2.67714356996323030e6, 3.21536096883397724e5, 2.34348439624087565e5],
    [2.86077985157055594e6, -1.25613852706608684e5, -2.67714356996304450e6,
     96732.3703999549034, -1.83636281569839485e5, 7851.33698327812908],
    [-3.01122022080257610e7, -1.23459839000163298e6, 3.21536096845479915e5,
     -1.83636281569389947e5, 2.97906661133220158e7, -8.11885318178503658e5],
    [5.77536878490345902e5, 23678.9497972498358, 2.34348439625119442e5,
     7851.3369832656553, -8.11885318178457441e5, 32407.641815033657],
])
PRINTED_STIFFNESS.setflags(write=False)

#: The displacement pair printed after each coefficient of :data:`PRINTED_STIFFNESS`.
PRINTED_STIFFNESS_COLUMN_LABELS = (
    ("xi1+eta1", "psi1+theta1", "xi2+eta2", "psi2+theta2", "xi3+eta2", "psi3+theta2"),
) + tuple(
    ("xi1+eta1", "psi1+theta1", "xi2+eta2", "psi2+theta2", "xi3+eta3", "psi3+theta3")
    for _ in range(5)
)

#: Potential energy in the displacements, "Потенціальна енергія системи запишеться", as
#: printed: (coefficient, first symbol, second symbol), in printed order.
PRINTED_ENERGY_IN_DISPLACEMENTS = (
    (5.229315675e6, "psi1", "xi1"),
    (16203.81435, "psi2", "psi2"),
    (3.215336585e5, "xi2", "xi3"),
    (1.489532418e7, "xi3", "xi3"),
    (1.317360102e5, "psi1", "psi1"),
    (5.775363391e5, "xi1", "psi3"),
    (-2.677144261e6, "xi2", "psi2"),
    (-3.011218201e7, "xi1", "xi3"),
    (2.860780407e6, "xi1", "psi2"),
    (7851.333057, "psi2", "psi3"),
    (-8.118848369e5, "xi3", "psi3"),
    (1.081013434e8, "xi2", "xi2"),
    (48366.19082, "psi2", "psi2"),
    (-1.256138793e5, "psi1", "psi2"),
    (23678.93149, "psi1", "psi3"),
    (-2.165242205e8, "xi1", "xi2"),
    (-1.836361448e5, "psi2", "xi3"),
    (23678.93149, "theta1", "theta3"),
    (7851.333057, "theta2", "theta3"),
    (-1.836361448e5, "theta2", "eta3"),
    (1.081013434e8, "eta2", "eta2"),
    (48366.19082, "theta2", "theta2"),
    (-2.677144261e6, "eta2", "theta2"),
    (3.215336585e5, "eta2", "eta3"),
    (2.343484975e5, "eta2", "theta3"),
    (1.2333251673e8, "eta1", "eta1"),
    (-3.995344907e6, "eta1", "theta1"),
    (-2.165242205e8, "eta1", "eta2"),
    (2.860780407e6, "eta1", "theta2"),
    (-3.011218201e7, "eta1", "eta3"),
    (-1.234597708e6, "theta1", "eta3"),
    (5.775363391e5, "eta1", "theta3"),
    (1.317360102e5, "theta1", "theta1"),
    (5.229315675e6, "theta1", "eta2"),
    (-1.256138793e5, "theta1", "theta2"),
    (2.343484975e5, "xi2", "psi3"),
    (-1.234597708e6, "psi1", "xi3"),
    (1.489532418e7, "eta3", "eta3"),
    (-8.118848369e5, "eta3", "theta3"),
    (16203.81435, "theta3", "theta3"),
    (1.2333251673e8, "xi1", "xi1"),
    (-3.995344907e6, "xi1", "psi1"),
)
