"""The registry of a ``machine``'s attachment parts in case files (:mod:`rotorlab.models._parts`).

Each entry maps a case key (``[[model.<key>]]``, a field of :class:`rotorlab.io.MachineSpec`) to
its spec class: a :class:`rotorlab.io._station._Station` (where it sits) with its quantities, a
class attribute ``description`` and ``build(node)``, which returns the part
(:class:`rotorlab.models._parts.AbstractPart`) or, for a key that is a field of
:class:`rotorlab.models.Machine` (``unbalances``), the item that field holds. Registering a part
is one line here; the order is the case table's.
"""

from __future__ import annotations

from typing import Any

from rotorlab.io._absorber_spec import AbsorberSpec
from rotorlab.io._linear_analyses import UnbalanceSpec

__all__ = ["PART_SPECS"]

PART_SPECS: dict[str, Any] = {
    "unbalances": UnbalanceSpec,
    "absorbers": AbsorberSpec,
}
