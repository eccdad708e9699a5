"""Built-in machines for the linear analyses, as Python builders of a LinearSystem.

``CASES`` maps each case name to its builder (callable without arguments):

``"pico21"``
    :func:`pico21`: the Pico 21 laboratory centrifuge of seed 000, three rigid bodies on
    elastic supports, with every inconsistency of the printed data resolved (see
    :mod:`rotorlab.linear.cases._pico21` and :func:`audit_pico21`).
``"friswell-rotor"``
    :func:`friswell_rotor`: Friswell et al. (2010), Example 5.9.1.
"""

from rotorlab.linear.cases._friswell import friswell_rotor
from rotorlab.linear.cases._pico21 import (
    PICO21,
    RESOLVED_COMPLIANCE,
    Pico21Data,
    pico21,
    pico21_influence_model,
)
from rotorlab.linear.cases._pico21_audit import Finding, audit_pico21

__all__ = ["friswell_rotor", "pico21", "Pico21Data", "PICO21", "RESOLVED_COMPLIANCE",
           "pico21_influence_model", "audit_pico21", "Finding", "CASES"]

CASES = {"pico21": pico21, "friswell-rotor": friswell_rotor}
