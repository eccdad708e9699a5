"""The two-disc rotor of Friswell et al. (2010), Example 5.9.1: the textbook check of FE codes.

A steel shaft 1.5 m long and 50 mm in diameter (E = 211 GPa, G = 81.2 GPa, rho = 7810 kg/m^3),
modelled with six Timoshenko elements of 0.25 m, carries two rigid steel discs 70 mm wide, of
outer diameter 280 mm at 0.5 m (node 2) and 350 mm at 1.0 m (node 4), and rests on isotropic
bearings of 1 MN/m at both ends (nodes 0 and 6), with no damping, no cross-coupling and no
moment stiffness. The discs are annuli keyed onto the shaft (bore 50 mm), which is how the
book's companion toolbox and the ROSS port of this example (``petrobras/ross``,
``docs/examples/example_05_09_01.rst``) model them.
"""

from __future__ import annotations

from rotorlab.linear._assembly import assemble, uniform_shaft
from rotorlab.linear._elements import Bearing, RigidBody
from rotorlab.linear._shaft import STEEL
from rotorlab.linear._system import LinearSystem

__all__ = ["friswell_rotor"]

SHAFT_LENGTH = 1.5  # m
SHAFT_DIAMETER = 0.05  # m
DISC_WIDTH = 0.07  # m
DISC_DIAMETERS = (0.28, 0.35)  # m, at 1/3 and 2/3 of the span
BEARING_STIFFNESS = 1e6  # N/m


def friswell_rotor(n_elements: int = 6, *, bearing_stiffness: float = BEARING_STIFFNESS,
                   bearing_stiffness_y: float | None = None, bearing_damping: float = 0.0,
                   shear: bool = True, rotary_inertia: bool = True,
                   gyroscopic: bool = True) -> LinearSystem:
    """Return the rotor of Friswell et al. (2010), Example 5.9.1.

    Parameters
    ----------
    n_elements : int
        Number of equal shaft elements, a multiple of 3 (the book uses 6); refine to study
        mesh convergence.
    bearing_stiffness : float
        k_xx of both bearings (N/m).
    bearing_stiffness_y : float, optional
        k_yy of both bearings (N/m); default isotropic. Example 5.9.2 of the book uses
        ``bearing_stiffness_y=0.8e6``.
    bearing_damping : float
        c_xx = c_yy of both bearings (N s/m); Example 5.9.5 of the book uses 3e3.
    shear, rotary_inertia, gyroscopic : bool
        Shaft element options (all on: Timoshenko with gyroscopic terms).

    Returns
    -------
    LinearSystem
        ``n_elements + 1`` nodes; node labels ``"bearing A"``, ``"disc 1"``, ``"disc 2"``,
        ``"bearing B"`` at the special nodes.

    References
    ----------
    Friswell, Penny, Garvey & Lees, *Dynamics of Rotating Machines*, Cambridge University
    Press (2010), Example 5.9.1 (and 5.9.2, 5.9.5 for the variants).

    Examples
    --------
    >>> s = friswell_rotor()
    >>> s.n_nodes, round(s.total_mass, 2)  # kg
    (7, 107.12)
    """
    if int(n_elements) != n_elements or n_elements < 3 or n_elements % 3:
        raise ValueError(f"n_elements must be a positive multiple of 3, got {n_elements!r}")
    n = int(n_elements)
    shaft = uniform_shaft(n, SHAFT_LENGTH, SHAFT_DIAMETER, material=STEEL, shear=shear,
                          rotary_inertia=rotary_inertia, gyroscopic=gyroscopic)
    d1, d2 = n // 3, 2 * n // 3
    discs = [RigidBody.disc(node, D, DISC_WIDTH, STEEL.density, inner_diameter=SHAFT_DIAMETER)
             for node, D in zip((d1, d2), DISC_DIAMETERS)]
    bearings = [Bearing(node=node, kxx=bearing_stiffness, kyy=bearing_stiffness_y,
                        cxx=bearing_damping) for node in (0, n)]
    labels = [str(i) for i in range(n + 1)]
    labels[0], labels[d1], labels[d2], labels[n] = "bearing A", "disc 1", "disc 2", "bearing B"
    return assemble([*shaft, *discs, *bearings], node_label=labels)
