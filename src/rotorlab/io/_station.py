"""Where an attachment of a ``machine`` sits in a case file (the races', unbalances',
clearances' and parts' ``node`` / ``at`` / ``position`` and ``axial_offset``)."""

from __future__ import annotations

from pydantic import Field, model_validator

from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import _Spec, integer, quantity
from rotorlab.io._linear_common import label

__all__ = ["_Station"]


class _Station(_Spec):
    """Where an attachment sits: one of ``node`` (index), ``at`` (name) or ``position`` (z)."""

    node: integer(ge=0) | None = Field(None, description="node index")
    at: label() | None = Field(None, description="name of a node or component")
    position: quantity("length") | None = Field(None, description="axial position of a node (m)")
    axial_offset: quantity("length") = Field(0.0, description="offset along +z from the node (m)")

    @model_validator(mode="after")
    def _one_place(self):
        given = [k for k in ("node", "at", "position") if getattr(self, k) is not None]
        if len(given) != 1:
            raise IssueGroup([Issue((), "give exactly one of node, at or position"
                                    + (f" (got {', '.join(given)})" if given else ""),
                                    show_value=False)])
        return self
