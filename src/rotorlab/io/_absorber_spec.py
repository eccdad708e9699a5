"""Case-file spec of a tuned mass absorber on a ``machine`` (:class:`rotorlab.models.TunedMassAbsorber`)::

    [[model.absorbers]]
    at = "rotor"                     # node: its name (or node = index, or position = z)
    mass = "50 g"
    stiffness = "2000 N/m"
    damping = "0.5 N*s/m"            # optional, default 0
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field

from rotorlab.io._fields import quantity
from rotorlab.io._station import _Station

__all__ = ["AbsorberSpec"]


class AbsorberSpec(_Station):
    """A point mass on an isotropic spring and damper at a station.

    Parameters
    ----------
    mass : float
        m_a (kg), > 0.
    stiffness : float
        k_a (N/m), > 0.
    damping : float
        c_a (N*s/m), >= 0.
    """

    description: ClassVar[str] = "tuned mass absorbers"
    mass: quantity("mass", gt=0) = Field(description="absorber mass m_a (kg)")
    stiffness: quantity("stiffness", gt=0) = Field(description="spring stiffness k_a (N/m)")
    damping: quantity("damping", ge=0) = Field(0.0, description="damper c_a (N*s/m)")

    def build(self, node: int):
        """The :class:`rotorlab.models.TunedMassAbsorber` at ``node``."""
        from rotorlab.models import TunedMassAbsorber

        return TunedMassAbsorber(node, self.mass, self.stiffness, self.damping, self.axial_offset)
