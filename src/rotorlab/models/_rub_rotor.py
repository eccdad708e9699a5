"""The parameters of the rub closed forms (:class:`RubRotor`) and what a model with a clearance
says about its contact at saved samples (:class:`ContactSamples`).

Both are re-exported by :mod:`rotorlab.contact` (the closed forms and the rub regimes live
there); they are defined here, below the package, so that a model (the machine's
:meth:`~rotorlab.models.Machine.equivalent_rub_rotor` and
:meth:`~rotorlab.models.Machine.contact_samples`) returns them without importing
:mod:`rotorlab.contact`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rotorlab.models._checks import check_number as _num

__all__ = ["RubRotor", "ContactSamples", "sampled_normal_force"]


@dataclass(frozen=True, slots=True)
class RubRotor:
    """A Jeffcott rotor in a circular clearance: the parameters of the closed forms.

    Parameters
    ----------
    mass : float
        m, rotor mass (kg), > 0.
    stiffness : float
        k, isotropic shaft/support stiffness (N/m), > 0.
    clearance : float
        delta, radial clearance: contact when the rotor centre is at ``|z| >= delta`` (m), > 0.
    damping : float
        c, viscous damping of the rotor (N s/m), >= 0.
    eccentricity : float
        eps, unbalance eccentricity of the centre of mass (m), >= 0.
    stator_stiffness : float
        k_s, radial stiffness of the stator at the contact (N/m), > 0; ``math.inf`` is a rigid
        stator.
    stator_damping : float
        c_s, radial damping of the stator at the contact (N s/m), >= 0.
    stator_mass : float
        m_s, mass of a moving housing (kg), >= 0 (0: massless stator).
    friction : float
        mu, Coulomb friction coefficient of the contact, >= 0.
    rotor_radius : float
        R_r, radius of the rotor at the contact (m), > 0: its surface speed is ``R_r Omega``.

    Examples
    --------
    >>> p = RubRotor(mass=1.0, stiffness=1.0, clearance=1.0, damping=0.1, eccentricity=0.3,
    ...              stator_stiffness=10.0)
    >>> p.natural_frequency
    1.0
    >>> RubRotor(mass=1.0, stiffness=1.0, clearance=0.0)
    Traceback (most recent call last):
    ...
    ValueError: RubRotor.clearance must be a finite number > 0 (m), got 0.0
    """

    mass: float
    stiffness: float
    clearance: float
    damping: float = 0.0
    eccentricity: float = 0.0
    stator_stiffness: float = math.inf
    stator_damping: float = 0.0
    stator_mass: float = 0.0
    friction: float = 0.0
    rotor_radius: float = 1.0

    def __post_init__(self) -> None:
        o = "RubRotor"
        for name, unit in (("mass", "kg"), ("stiffness", "N/m"), ("clearance", "m"), ("rotor_radius", "m")):
            object.__setattr__(self, name, _num(o, name, getattr(self, name), unit=unit))
        for name, unit in (("damping", "N s/m"), ("eccentricity", "m"), ("stator_damping", "N s/m"),
                           ("stator_mass", "kg"), ("friction", "")):  # fmt: skip
            object.__setattr__(self, name, _num(o, name, getattr(self, name), lo_open=False, unit=unit))
        ks = self.stator_stiffness
        if not (isinstance(ks, (int, float)) and ks == math.inf):
            object.__setattr__(self, "stator_stiffness", _num(o, "stator_stiffness", ks, unit="N/m"))

    @property
    def natural_frequency(self) -> float:
        """sqrt(k / m), the free rotor's natural frequency (rad/s)."""
        return math.sqrt(self.stiffness / self.mass)

    @property
    def rigid_stator(self) -> bool:
        """Whether the stator is rigid (``stator_stiffness`` infinite)."""
        return math.isinf(self.stator_stiffness)


class ContactSamples(NamedTuple):
    """What a model with a clearance says about its contact at saved samples (all shape (n,) or
    (n, 2)): gap vector ``w`` (m) and its rate ``dw`` (m/s), contact ``mode`` (0 free, +-1
    sliding, 2 rolling), cumulative ``impacts``, largest normal impulse so far ``peak_impulse``
    (N s), contact ``normal_force`` (N) and ``spin_speed`` (rad/s)."""

    w: np.ndarray
    dw: np.ndarray
    mode: np.ndarray
    impacts: np.ndarray
    peak_impulse: np.ndarray
    normal_force: np.ndarray
    spin_speed: np.ndarray


def sampled_normal_force(ts, ys, mode, law) -> np.ndarray:
    """The contact normal force (N) at saved samples: ``law(t, row)`` where in contact, 0 where
    free and NaN where the sample is not a state (a run that failed fills the samples after its
    end with NaN; the compiled contact law must not see them: at a NaN position it finds the
    centre, and divides by the zero radius there).

    ``ts`` shape (n,), ``ys`` shape (n, n_state), ``mode`` shape (n,) (the contact mode of
    each sample); ``law`` returns the normal force of one state.
    """
    ys = np.asarray(ys, dtype=float)
    valid = np.all(np.isfinite(ys), axis=1)
    ts = np.broadcast_to(np.asarray(ts, dtype=float), valid.shape)
    force = np.where(valid, 0.0, np.nan)
    for i in np.flatnonzero(valid & (mode != 0.0)):
        force[i] = law(float(ts[i]), np.ascontiguousarray(ys[i]))
    return force
