"""Models: frozen parameter objects plus compiled kernels (see :mod:`rotorlab.models._base`)."""

from rotorlab.models._base import AbstractModel, EventSpec, Kernels, no_events, no_reset

__all__ = ["AbstractModel", "EventSpec", "Kernels", "no_events", "no_reset"]
