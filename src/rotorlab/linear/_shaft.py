"""Timoshenko shaft element: shear deformation, rotary inertia and the gyroscopic matrix.

The element joins node ``node`` to node ``node + 1``. In each lateral plane its DOFs are
``(w1, phi1, w2, phi2)`` (translation, cross-section tilt) and both planes share the same 4x4
matrices (see :mod:`rotorlab.linear._system` for the DOF convention). The matrices are the
integrals of the interpolation functions of Friedman & Kosmatka (1993) -- exact for the static
Timoshenko beam -- evaluated by 4-point Gauss-Legendre quadrature, which is exact for their
polynomial degree (<= 6), so no closed form has to be transcribed:

* stiffness   ``K = int EI N_phi'^T N_phi' + kappa G A (N_w' - N_phi)^T (N_w' - N_phi) dz``
* mass        ``M = int rho A N_w^T N_w + rho I N_phi^T N_phi dz``
* gyroscopic  ``G[x-plane, y-plane] = +int rho J N_phi^T N_phi dz = -G[y-plane, x-plane]``

with ``J = 2 I`` the polar second moment of area. The closed forms they reproduce are those of
Friswell et al. (2010), Chapter 5 (tested in ``tests/unit/test_linear_shaft.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Material", "ShaftElement", "STEEL", "shear_coefficient"]

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(4)
_XI = 0.5 * (_GAUSS_X + 1.0)  # points on [0, 1]
_WXI = 0.5 * _GAUSS_W


def _positive(owner: str, name: str, value, unit: str, *, strict: bool = True) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not math.isfinite(v) or v < 0 or (strict and v == 0):
        rel = ">" if strict else ">="
        raise ValueError(f"{owner}.{name} must be a finite number {rel} 0 ({unit}), "
                         f"got {value!r}")
    return v


@dataclass(frozen=True, slots=True)
class Material:
    """Isotropic linear elastic material.

    Parameters
    ----------
    youngs_modulus : float
        E (Pa), > 0.
    shear_modulus : float
        G (Pa), > 0; Poisson's ratio is ``E / (2 G) - 1`` and must lie in (-1, 0.5).
    density : float
        rho (kg/m^3), > 0.

    Examples
    --------
    >>> round(STEEL.poisson_ratio, 4)
    0.2993
    >>> Material(youngs_modulus=1e9, shear_modulus=0.2e9, density=1.0)
    Traceback (most recent call last):
    ...
    ValueError: Material.shear_modulus gives Poisson's ratio E/(2G) - 1 = 1.5; need -1 < nu < 0.5
    """

    youngs_modulus: float
    shear_modulus: float
    density: float

    def __post_init__(self) -> None:
        for name, unit in (("youngs_modulus", "Pa"), ("shear_modulus", "Pa"),
                           ("density", "kg/m^3")):
            object.__setattr__(self, name, _positive("Material", name, getattr(self, name), unit))
        nu = self.poisson_ratio
        if not -1.0 < nu < 0.5:
            raise ValueError(f"Material.shear_modulus gives Poisson's ratio E/(2G) - 1 = {nu:g}; "
                             "need -1 < nu < 0.5")

    @property
    def poisson_ratio(self) -> float:
        """nu = E / (2 G) - 1 (1)."""
        return self.youngs_modulus / (2.0 * self.shear_modulus) - 1.0


#: The steel of Friswell et al. (2010), Example 5.9.1: E = 211 GPa, G = 81.2 GPa, 7810 kg/m^3.
STEEL = Material(youngs_modulus=211e9, shear_modulus=81.2e9, density=7810.0)


def shear_coefficient(poisson_ratio: float, diameter_ratio: float = 0.0) -> float:
    """Return the shear coefficient kappa of a (hollow) circular section (Cowper/Hutchinson).

    Parameters
    ----------
    poisson_ratio : float
        nu (1).
    diameter_ratio : float
        Inner over outer diameter, in [0, 1) (1).

    Returns
    -------
    float
        ``6 (1 + nu) (1 + r^2)^2 / ((7 + 6 nu) (1 + r^2)^2 + (20 + 12 nu) r^2)``.

    References
    ----------
    Friswell et al. (2010), Chapter 5 (shear coefficient of a hollow circular shaft);
    Cowper (1966), J. Appl. Mech. 33, 335-340.

    Examples
    --------
    >>> round(shear_coefficient(0.3), 4)
    0.8864
    """
    r2 = diameter_ratio * diameter_ratio
    a = (1.0 + r2) ** 2
    nu = poisson_ratio
    return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * r2)


def _shape_functions(xi: np.ndarray, length: float, phi: float):
    """Timoshenko interpolation at xi = z / L: returns N_w, N_w', N_phi, N_phi' (each (q, 4))."""
    L = length
    d = 1.0 + phi
    x, x2, x3 = xi, xi * xi, xi ** 3
    nw = np.stack([1 - 3 * x2 + 2 * x3 + phi * (1 - x),
                   L * (x - 2 * x2 + x3 + phi * (x - x2) / 2),
                   3 * x2 - 2 * x3 + phi * x,
                   L * (-x2 + x3 + phi * (x2 - x) / 2)], axis=1) / d
    dnw = np.stack([-6 * x + 6 * x2 - phi,
                    L * (1 - 4 * x + 3 * x2 + phi * (1 - 2 * x) / 2),
                    6 * x - 6 * x2 + phi,
                    L * (-2 * x + 3 * x2 + phi * (2 * x - 1) / 2)], axis=1) / (d * L)
    nphi = np.stack([6 * (x2 - x) / L,
                     1 - 4 * x + 3 * x2 + phi * (1 - x),
                     6 * (x - x2) / L,
                     -2 * x + 3 * x2 + phi * x], axis=1) / d
    dnphi = np.stack([6 * (2 * x - 1) / L,
                      -4 + 6 * x - phi,
                      6 * (1 - 2 * x) / L,
                      -2 + 6 * x + phi], axis=1) / (d * L)
    return nw, dnw, nphi, dnphi


def _expand(plane: np.ndarray) -> np.ndarray:
    """Place one plane's 4x4 matrix on both planes of the 8x8 element (node-major DOFs)."""
    out = np.zeros((8, 8))
    xp, yp = [0, 2, 4, 6], [1, 3, 5, 7]
    out[np.ix_(xp, xp)] = plane
    out[np.ix_(yp, yp)] = plane
    return out


@dataclass(frozen=True, slots=True)
class ShaftElement:
    """Uniform circular shaft segment between nodes ``node`` and ``node + 1``.

    Parameters
    ----------
    node : int
        Left node (>= 0); the element ends at ``node + 1``.
    length : float
        L (m), > 0.
    outer_diameter : float
        d_o (m), > 0.
    inner_diameter : float
        d_i (m), 0 <= d_i < d_o.
    material : Material
        Elastic constants and density.
    shear : bool
        Include shear deformation (Timoshenko); False gives Euler-Bernoulli stiffness.
    rotary_inertia : bool
        Include the rotary inertia of the cross-sections.
    gyroscopic : bool
        Include the gyroscopic matrix of the spinning shaft.

    Examples
    --------
    >>> e = ShaftElement(node=0, length=0.25, outer_diameter=0.05, material=STEEL)
    >>> round(e.mass, 4)
    3.8337
    >>> e.K().shape
    (8, 8)
    """

    node: int
    length: float
    outer_diameter: float
    inner_diameter: float = 0.0
    material: Material = STEEL
    shear: bool = True
    rotary_inertia: bool = True
    gyroscopic: bool = True

    def __post_init__(self) -> None:
        if int(self.node) != self.node or self.node < 0:
            raise ValueError(f"ShaftElement.node must be an integer >= 0, got {self.node!r}")
        object.__setattr__(self, "node", int(self.node))
        object.__setattr__(self, "length", _positive("ShaftElement", "length", self.length, "m"))
        do = _positive("ShaftElement", "outer_diameter", self.outer_diameter, "m")
        di = _positive("ShaftElement", "inner_diameter", self.inner_diameter, "m", strict=False)
        if di >= do:
            raise ValueError(f"ShaftElement.inner_diameter must be < outer_diameter = {do:g} (m), "
                             f"got {self.inner_diameter!r}")
        object.__setattr__(self, "outer_diameter", do)
        object.__setattr__(self, "inner_diameter", di)
        if not isinstance(self.material, Material):
            raise ValueError(f"ShaftElement.material must be a Material, got {self.material!r}")

    # ------------------------------------------------------------ section properties
    @property
    def nodes(self) -> tuple[int, int]:
        """The two nodes joined."""
        return (self.node, self.node + 1)

    @property
    def area(self) -> float:
        """Cross-section area A (m^2)."""
        return math.pi / 4.0 * (self.outer_diameter ** 2 - self.inner_diameter ** 2)

    @property
    def second_moment(self) -> float:
        """Second moment of area I about a diameter (m^4)."""
        return math.pi / 64.0 * (self.outer_diameter ** 4 - self.inner_diameter ** 4)

    @property
    def mass(self) -> float:
        """Mass rho A L (kg)."""
        return self.material.density * self.area * self.length

    @property
    def shear_parameter(self) -> float:
        """Phi = 12 E I / (kappa G A L^2) (1); 0 when ``shear`` is False."""
        if not self.shear:
            return 0.0
        m = self.material
        kappa = shear_coefficient(m.poisson_ratio, self.inner_diameter / self.outer_diameter)
        return 12.0 * m.youngs_modulus * self.second_moment / (
            kappa * m.shear_modulus * self.area * self.length ** 2)

    # ------------------------------------------------------------ element matrices
    def _integrals(self):
        L, phi = self.length, self.shear_parameter
        nw, dnw, nphi, dnphi = _shape_functions(_XI, L, phi)
        w = _WXI * L
        ww = np.einsum("q,qi,qj->ij", w, nw, nw)
        pp = np.einsum("q,qi,qj->ij", w, nphi, nphi)
        dpdp = np.einsum("q,qi,qj->ij", w, dnphi, dnphi)
        gam = dnw - nphi
        gg = np.einsum("q,qi,qj->ij", w, gam, gam)
        return ww, pp, dpdp, gg

    def plane_matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return the one-plane (M, K, R) on (w1, phi1, w2, phi2).

        ``R = int rho I N_phi^T N_phi dz`` is the rotary-inertia integral; the gyroscopic
        coupling between the planes is ``2 R`` (J = 2 I).
        """
        m = self.material
        A, I = self.area, self.second_moment
        ww, pp, dpdp, gg = self._integrals()
        if self.shear:
            kappa = shear_coefficient(m.poisson_ratio, self.inner_diameter / self.outer_diameter)
            K = m.youngs_modulus * I * dpdp + kappa * m.shear_modulus * A * gg
        else:
            K = _euler_bernoulli_stiffness(m.youngs_modulus * I, self.length)
        R = m.density * I * pp
        M = m.density * A * ww + (R if self.rotary_inertia else 0.0)
        return tuple(0.5 * (a + a.T) for a in (M, K, R))  # exactly symmetric

    def M(self) -> np.ndarray:
        """Mass matrix (8, 8) (kg, kg m, kg m^2)."""
        return _expand(self.plane_matrices()[0])

    def K(self) -> np.ndarray:
        """Stiffness matrix (8, 8) (N/m, N/rad, N m/rad)."""
        return _expand(self.plane_matrices()[1])

    def C(self) -> np.ndarray:
        """Damping matrix (8, 8): zero (no internal shaft damping)."""
        return np.zeros((8, 8))

    def G(self) -> np.ndarray:
        """Gyroscopic matrix per unit speed (8, 8) (kg m^2), skew-symmetric."""
        out = np.zeros((8, 8))
        if self.gyroscopic:
            R2 = 2.0 * self.plane_matrices()[2]
            xp, yp = [0, 2, 4, 6], [1, 3, 5, 7]
            out[np.ix_(xp, yp)] = R2
            out[np.ix_(yp, xp)] = -R2
        return out


def _euler_bernoulli_stiffness(ei: float, L: float) -> np.ndarray:
    """Classical cubic-Hermite beam stiffness on (w1, phi1, w2, phi2) (N/m, N/rad, N m/rad)."""
    return ei / L ** 3 * np.array([[12.0, 6 * L, -12.0, 6 * L],
                                   [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                   [-12.0, -6 * L, 12.0, -6 * L],
                                   [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
