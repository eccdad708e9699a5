"""What a design must satisfy besides P(balanced) and the objectives' limits: the registry of
named constraints (:data:`DESIGN_CONSTRAINTS`), each a margin read from an evaluated design.

For implementers
----------------
1. ``register_constraint(Constraint(name, description, margin, refuses))`` where
   ``margin(point) -> float`` reads a :class:`~rotorlab.design.DesignPoint` and returns a
   number >= 0 where the constraint holds (< 0 where it does not, NaN never), and
   ``refuses(model) -> str | None`` says why the constraint cannot apply to a model (None: it
   can), checked before anything runs.
2. A design search names it in ``constraints`` (case file) or ``--constraint`` (command line);
   its margin is recorded as ``constraints.<name>``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from rotorlab._registry import Registry, lazy

__all__ = ["Constraint", "DESIGN_CONSTRAINTS", "register_constraint"]


@dataclass(frozen=True)
class Constraint:
    """A condition every feasible design meets.

    Parameters
    ----------
    name : str
        Its key (``constraints = ["no-housing-contact"]``).
    description : str
        What it requires, in words, and what its margin is.
    margin : callable
        ``margin(point) -> float``: >= 0 where it holds.
    refuses : callable
        ``refuses(model) -> str | None``: why it cannot apply to ``model`` (None: it can).
    run_ups : bool
        Whether it reads the design's run-ups (as :attr:`rotorlab.design.Objective.run_ups`).
    """

    name: str
    description: str
    margin: Callable[[Any], float]
    refuses: Callable[[Any], str | None]
    run_ups: bool = False


#: Constraints by name.
DESIGN_CONSTRAINTS: Registry[Constraint] = Registry("design constraint")


def register_constraint(entry: Constraint, *, replace: bool = False) -> None:
    """Add a :class:`Constraint` to :data:`DESIGN_CONSTRAINTS`."""
    DESIGN_CONSTRAINTS.register(entry.name, entry, replace=replace)


register_constraint(Constraint(
    "no-housing-contact",
    "no run-up of the design touches the housing: margin (gap - largest distance of the clearance station from "
    "the stator's centre over every run-up) / gap; a design whose run-ups touched has minus the share that "
    "touched",
    lazy("rotorlab.analyses._design_run_up:housing_margin"),
    lazy("rotorlab.analyses._design_run_up:no_housing_run_up"), run_ups=True))
