"""Rotor-stator contact: the closed forms every rub simulation is checked against.

See :mod:`rotorlab.contact._theory` (and :mod:`rotorlab.contact._whirl` for the backward whirl
and dry whip) for the physics and references (Black 1968; Choy & Padovan
1987; Crandall 1990; Nordmark & Piiroinen 2009).
"""

from rotorlab.contact._model import JeffcottRub
from rotorlab.contact._regimes import (
    WINDOW_RULE,
    RegimeRule,
    RubFeatures,
    RubRegime,
    RubRegimes,
    classify_rub,
    regime_codes,
    rub_features,
)
from rotorlab.contact._theory import (
    RubBranch,
    RubRotor,
    chatter_impact_times,
    chatter_time,
    critical_friction,
    full_rub,
    full_rub_characteristic,
    full_rub_fold_speeds,
    full_rub_jacobian,
    grazing_speeds,
    hurwitz_stable,
    no_rub_radius,
)
from rotorlab.contact._whirl import (
    RollingWhirl,
    SlippingWhip,
    dry_whip_frequency,
    friction_to_roll,
    rolling_whirl,
    slipping_whip,
)

__all__ = [
    "JeffcottRub",
    "RubFeatures",
    "RubRegime",
    "RubRegimes",
    "RegimeRule",
    "WINDOW_RULE",
    "regime_codes",
    "classify_rub",
    "rub_features",
    "RubRotor",
    "RubBranch",
    "RollingWhirl",
    "SlippingWhip",
    "no_rub_radius",
    "grazing_speeds",
    "full_rub",
    "full_rub_fold_speeds",
    "full_rub_jacobian",
    "full_rub_characteristic",
    "hurwitz_stable",
    "critical_friction",
    "rolling_whirl",
    "friction_to_roll",
    "dry_whip_frequency",
    "slipping_whip",
    "chatter_time",
    "chatter_impact_times",
]
