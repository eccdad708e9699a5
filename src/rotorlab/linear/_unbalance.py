"""The unbalance of a rotor at a node: static (a mass off the axis) and couple (a tilted mass
distribution), one type for the linear response, the composed machine and the case files."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from rotorlab.linear._elements import _num

# bounds (gt, ge, lt, le) of the named parameters (rotorlab.models._parameters)
_GT0, _GE0, _FREE = (0.0, None, None, None), (None, 0.0, None, None), (None, None, None, None)

__all__ = ["Unbalance", "COUPLE_LEVER"]

#: Lever d (m) of the two opposite point unbalances ``couple / d`` at ``axial_offset +- d / 2``
#: that stand for a couple where only point unbalances are modelled (the machine's kernel): their
#: generalised forces, kinetic-energy couplings and (cancelling) weights are those of the couple
#: for any d, the equations being linear in ``U B``.
COUPLE_LEVER = 1.0


@dataclass(frozen=True, slots=True)
class Unbalance:
    """An unbalance turning with the rotor at a node: static, couple, or both (dynamic).

    Parameters
    ----------
    node : int
        Node where it acts (>= 0); it must spin with the rotor.
    magnitude : float
        Static unbalance U = m e (kg m), >= 0.
    phase : float
        beta, angle of its heavy spot from +x at t = 0 (theta = 0), in the sense of rotation (rad):
        it points along ``theta + beta``.
    axial_offset : float
        Axial distance a of the static unbalance's plane from the node along +z (m): its force
        acts at ``(x + a phi_x, y + a phi_y)`` and so has the moment a F on the tilt.
    couple : float
        Couple unbalance U_c (kg m^2), >= 0: two opposite unbalances U at axial distance d with
        ``U d = U_c``, or a principal axis tilted from the spin axis (:meth:`of_tilted_body`).
    couple_phase : float
        gamma (rad): the angle (from +x at t = 0, in the sense of rotation) of the heavy spot on
        the +z side of the couple.

    Notes
    -----
    Turning at Omega (theta = Omega t) it loads its node with the force and moment ::

        (F_x, F_y) = U Omega^2 (cos(theta + beta), sin(theta + beta))
        (M_x, M_y) = a (F_x, F_y) + U_c Omega^2 (cos(theta + gamma), sin(theta + gamma))

    on the DOFs ``x, y, phi_x, phi_y`` (a tilt phi_x moves the point at z by ``z phi_x`` along
    x); in complex amplitudes (:meth:`node_force`) ``F_x = U Omega^2 e^{i beta}``, ``F_y = -i F_x``
    and likewise for the moments. For a rigid body on two supports the couple drives the
    tilting (conical) mode alone (Friswell et al. 2010, Sections 3.6 and 6.2; Vance, Zeidan and
    Murphy 2010, Section 2.7 "dynamic unbalance").

    Examples
    --------
    >>> Unbalance(node=2, magnitude=1e-4).phase
    0.0
    >>> Unbalance(0, couple=2e-3, couple_phase=0.0).node_force()[2:]
    array([0.002+0.j   , 0.   -0.002j])
    """

    #: Named parameters (field, unit, bounds (gt, ge, lt, le)) of a machine's ``unbalances[i]``
    #: (:mod:`rotorlab.models._parameters`); a couple from or to 0 changes the compiled layout.
    fields: ClassVar[tuple] = (("magnitude", "kg*m", _GE0), ("phase", "rad", _FREE),
                               ("axial_offset", "m", _FREE), ("couple", "kg*m^2", _GE0),
                               ("couple_phase", "rad", _FREE))

    node: int
    magnitude: float = 0.0
    phase: float = 0.0
    axial_offset: float = 0.0
    couple: float = 0.0
    couple_phase: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.node, bool) or not isinstance(self.node, (int, np.integer)) \
                or self.node < 0:
            raise ValueError(f"Unbalance.node must be an integer >= 0, got {self.node!r}")
        object.__setattr__(self, "node", int(self.node))
        for name, unit, low in (("magnitude", "kg m", 0.0), ("phase", "rad", None),
                                ("axial_offset", "m", None), ("couple", "kg m^2", 0.0),
                                ("couple_phase", "rad", None)):
            object.__setattr__(self, name, _num("Unbalance", name, getattr(self, name), unit, low=low))

    @classmethod
    def of_tilted_body(cls, body, tilt: float, tilt_phase: float = 0.0, *,
                       eccentricity: float = 0.0, phase: float = 0.0) -> Unbalance:
        """Return the dynamic unbalance of a rigid body whose principal axis is off the spin axis.

        Parameters
        ----------
        body : rotorlab.linear.RigidBody
            Mass m, diametral and polar inertia I_d, I_p about its centre (at its node).
        tilt : float
            tau, small angle of its symmetry (principal) axis from the spin axis (rad).
        tilt_phase : float
            Direction (from +x at t = 0, sense of rotation) towards which the +z end of the
            principal axis leans (rad).
        eccentricity : float
            Distance e of its centre of mass from the spin axis (m), >= 0.
        phase : float
            Direction of that offset (rad).

        Returns
        -------
        Unbalance
            ``magnitude = m e`` and the couple of the products of inertia ``I_xz, I_yz = (I_p
            - I_d) tau (cos, sin)(tilt_phase)``: ``U_c = |I_d - I_p| tau``, at ``tilt_phase``
            for a long body (I_d > I_p), at ``tilt_phase + pi`` for a flat one.

        Notes
        -----
        The inertia tensor of the tilted body is ``I_d 1 + (I_p - I_d) n n^T`` with ``n = (tau
        cos, tau sin, 1)``; spinning at Omega its angular momentum turns and needs the moment
        ``Omega^2 (-I_yz, I_xz)``, whose reaction on the shaft is the couple above. At high speed
        the body turns about its principal axis: the shaft's tilt tends to ``-tau`` at the
        body (see the tests).

        Examples
        --------
        >>> from rotorlab.linear import RigidBody
        >>> u = Unbalance.of_tilted_body(RigidBody(0, 2.0, 0.05, 0.02), tilt=0.01, tilt_phase=0.5)
        >>> round(u.couple, 12), u.couple_phase
        (0.0003, 0.5)
        """
        tau = _num("Unbalance", "tilt", tilt, "rad", low=None)
        lever = (body.diametral_inertia - body.polar_inertia) * tau
        return cls(body.node, body.mass * _num("Unbalance", "eccentricity", eccentricity, "m"), phase,
                   couple=abs(lever), couple_phase=float(tilt_phase) + (math.pi if lever < 0 else 0.0))

    def node_force(self) -> np.ndarray:
        """Complex amplitudes per Omega^2 of the load on its node's ``x, y, phi_x, phi_y`` (kg m,
        kg m^2): ``[f, -i f, a f + c, -i (a f + c)]``, ``f = U e^{i beta}``, ``c = U_c e^{i gamma}``."""
        f = self.magnitude * np.exp(1j * self.phase)
        m = self.axial_offset * f + self.couple * np.exp(1j * self.couple_phase)
        return np.array([f, -1j * f, m, -1j * m])

    def point_unbalances(self) -> tuple[tuple[float, float, float], ...]:
        """The point unbalances ``(axial_offset, m e, phase)`` that load the node as this one does.

        The static part at ``axial_offset`` (always, even if 0: a magnitude varied through 0 keeps
        the machine's compiled layout); a couple > 0 as ``couple / d`` at ``axial_offset + d / 2``
        and the opposite one at ``axial_offset - d / 2`` (d = :data:`COUPLE_LEVER`).
        """
        out = [(self.axial_offset, self.magnitude, self.phase)]
        if self.couple > 0.0:
            d, u = COUPLE_LEVER, self.couple / COUPLE_LEVER
            out.append((self.axial_offset + d / 2, u, self.couple_phase))
            out.append((self.axial_offset - d / 2, u, self.couple_phase + math.pi))
        return tuple(out)
