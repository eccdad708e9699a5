"""Element interface and the lumped elements: rigid bodies, bearings, elastic connections.

For implementers
----------------
An element is any object with

1. ``nodes``: a tuple of node numbers; the element's DOFs are the four DOFs of each of these
   nodes in order, ``(x, y, phi_x, phi_y)`` per node (:mod:`rotorlab.linear._system`);
2. methods ``M()``, ``C()``, ``K()``, ``G()`` returning real arrays of shape
   ``(4 len(nodes), 4 len(nodes))``: mass, viscous damping, stiffness and gyroscopic matrix per
   unit spin speed, in SI units. ``M`` must be symmetric and ``G`` skew-symmetric.

Elements are frozen dataclasses whose ``__post_init__`` validates every field and raises
``ValueError`` naming it. :func:`rotorlab.linear.assemble` adds the element matrices into the
global ones; nothing else is required. (The shape mirrors ROSS's element classes.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["AbstractElement", "RigidBody", "Bearing", "ElasticConnection"]


@runtime_checkable
class AbstractElement(Protocol):
    """What :func:`rotorlab.linear.assemble` needs of an element (see module docstring)."""

    @property
    def nodes(self) -> tuple[int, ...]: ...  # pragma: no cover - protocol

    def M(self) -> np.ndarray: ...  # pragma: no cover - protocol

    def C(self) -> np.ndarray: ...  # pragma: no cover - protocol

    def K(self) -> np.ndarray: ...  # pragma: no cover - protocol

    def G(self) -> np.ndarray: ...  # pragma: no cover - protocol


def _num(owner: str, name: str, value, unit: str, *, low: float | None = 0.0,
         strict: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    bad = not math.isfinite(v)
    if low is not None and not bad:
        bad = v < low or (strict and v == low)
    if bad:
        rule = "a finite number" if low is None else (
            f"a finite number {'>' if strict else '>='} {low:g}")
        raise ValueError(f"{owner}.{name} must be {rule} ({unit}), got {value!r}")
    return v


def _node(owner: str, name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise ValueError(f"{owner}.{name} must be an integer >= 0, got {value!r}")
    return int(value)


@dataclass(frozen=True, slots=True)
class RigidBody:
    """Rigid axisymmetric body (disc, rotor, armature, housing) with its centre at a node.

    Parameters
    ----------
    node : int
        Node at the body's centre of mass (>= 0).
    mass : float
        m (kg), >= 0.
    diametral_inertia : float
        I_d about a diameter through the centre of mass (kg m^2), >= 0.
    polar_inertia : float
        I_p about the spin axis (kg m^2), 0 <= I_p <= 2 I_d (no rigid body has I_p > 2 I_d:
        I_p = I_x + I_y - 2 int z^2 dm).
    spinning : bool
        True if the body turns with the shaft (gyroscopic moments ``I_p Omega``); False for a
        stator or housing.

    Notes
    -----
    Linearised kinetic energy (seed 000, T_2A and T_3R; Friswell et al. 2010, Chapter 5):
    ``T = m (x'^2 + y'^2)/2 + I_d (phi_x'^2 + phi_y'^2)/2 - I_p Omega phi_y' phi_x``, whence
    ``M = diag(m, m, I_d, I_d)`` and ``G[phi_x, phi_y] = I_p = -G[phi_y, phi_x]``.

    Examples
    --------
    >>> b = RigidBody(node=1, mass=0.507, diametral_inertia=882e-6, polar_inertia=1529e-6)
    >>> float(b.G()[2, 3]), float(b.G()[3, 2])
    (0.001529, -0.001529)
    >>> RigidBody(node=0, mass=1.0, diametral_inertia=1e-3, polar_inertia=3e-3)
    Traceback (most recent call last):
    ...
    ValueError: RigidBody.polar_inertia must be <= 2 * diametral_inertia = 0.002 (kg m^2), got 0.003
    """

    node: int
    mass: float
    diametral_inertia: float
    polar_inertia: float = 0.0
    spinning: bool = True

    def __post_init__(self) -> None:
        o = "RigidBody"
        object.__setattr__(self, "node", _node(o, "node", self.node))
        object.__setattr__(self, "mass", _num(o, "mass", self.mass, "kg"))
        idia = _num(o, "diametral_inertia", self.diametral_inertia, "kg m^2")
        ipol = _num(o, "polar_inertia", self.polar_inertia, "kg m^2")
        if ipol > 2.0 * idia * (1.0 + 1e-9):
            raise ValueError(f"{o}.polar_inertia must be <= 2 * diametral_inertia = "
                             f"{2 * idia:g} (kg m^2), got {self.polar_inertia!r}")
        object.__setattr__(self, "diametral_inertia", idia)
        object.__setattr__(self, "polar_inertia", ipol)
        object.__setattr__(self, "spinning", bool(self.spinning))

    @classmethod
    def disc(cls, node: int, outer_diameter: float, width: float, density: float,
             inner_diameter: float = 0.0, spinning: bool = True) -> RigidBody:
        """Return a uniform annular disc.

        Parameters
        ----------
        node : int
            Node at the disc's centre.
        outer_diameter, width : float
            D and axial thickness h (m), > 0.
        density : float
            rho (kg/m^3), > 0.
        inner_diameter : float
            Bore d (m), 0 <= d < D (the disc is keyed onto a shaft of this diameter).
        spinning : bool
            See the class.

        Returns
        -------
        RigidBody
            ``m = rho pi (D^2 - d^2) h / 4``, ``I_p = m (D^2 + d^2) / 8``,
            ``I_d = I_p / 2 + m h^2 / 12``.

        Examples
        --------
        >>> round(RigidBody.disc(2, 0.28, 0.07, 7810.0, inner_diameter=0.05).mass, 3)
        32.59
        """
        D = _num("RigidBody.disc", "outer_diameter", outer_diameter, "m", strict=True)
        h = _num("RigidBody.disc", "width", width, "m", strict=True)
        rho = _num("RigidBody.disc", "density", density, "kg/m^3", strict=True)
        d = _num("RigidBody.disc", "inner_diameter", inner_diameter, "m")
        if d >= D:
            raise ValueError(f"RigidBody.disc inner_diameter must be < outer_diameter = {D:g} "
                             f"(m), got {inner_diameter!r}")
        m = rho * math.pi * (D * D - d * d) * h / 4.0
        ip = m * (D * D + d * d) / 8.0
        return cls(node=node, mass=m, diametral_inertia=ip / 2.0 + m * h * h / 12.0,
                   polar_inertia=ip, spinning=spinning)

    @property
    def nodes(self) -> tuple[int]:
        """The body's node."""
        return (self.node,)

    def M(self) -> np.ndarray:
        """``diag(m, m, I_d, I_d)`` (kg, kg m^2)."""
        return np.diag([self.mass, self.mass, self.diametral_inertia, self.diametral_inertia])

    def C(self) -> np.ndarray:
        """Zero (4, 4)."""
        return np.zeros((4, 4))

    def K(self) -> np.ndarray:
        """Zero (4, 4)."""
        return np.zeros((4, 4))

    def G(self) -> np.ndarray:
        """Gyroscopic matrix per unit speed (kg m^2): ``I_p`` at (phi_x, phi_y), skew."""
        g = np.zeros((4, 4))
        if self.spinning:
            g[2, 3] = self.polar_inertia
            g[3, 2] = -self.polar_inertia
        return g


class _Massless:
    """Mass and gyroscopic matrices of a massless element on ``nodes`` (4 DOF each): zero."""

    __slots__ = ()

    def M(self) -> np.ndarray:
        """Zero: the element is massless."""
        n = 4 * len(self.nodes)
        return np.zeros((n, n))

    def G(self) -> np.ndarray:
        """Zero."""
        n = 4 * len(self.nodes)
        return np.zeros((n, n))


@dataclass(frozen=True, slots=True)
class Bearing(_Massless):
    """Linear bearing or support: springs and dampers from a node to ground or to another node.

    Force on the node (to ground): ``-[[kxx, kxy], [kyx, kyy]] [x, y] - (same with c) [x', y']``,
    and moments ``-k_tilt_x phi_x``, ``-k_tilt_y phi_y``. With ``node_b`` set, the element acts
    on the relative motion ``node - node_b`` (a bearing between a shaft and its housing).

    Parameters
    ----------
    node : int
        Node (>= 0).
    kxx, kyy : float
        Direct stiffness (N/m), >= 0; ``kyy=None`` means ``kxx`` (isotropic).
    kxy, kyx : float
        Cross-coupled stiffness (N/m), any finite value.
    cxx, cyy : float
        Direct damping (N s/m), >= 0; ``cyy=None`` means ``cxx``.
    cxy, cyx : float
        Cross-coupled damping (N s/m).
    k_tilt_x, k_tilt_y : float
        Tilt (moment) stiffness on phi_x and phi_y (N m/rad), >= 0; ``k_tilt_y=None`` means
        ``k_tilt_x``. A housing on elastic feet has ``kxx = C_Q`` and ``k_tilt_x = C_M``
        (seed 000).
    node_b : int or None
        Second node for a connection between two nodes; None for ground.

    Examples
    --------
    >>> b = Bearing(node=0, kxx=1e6)
    >>> b.K()[:2, :2]
    array([[1000000.,       0.],
           [      0., 1000000.]])
    >>> Bearing(node=0, kxx=-1.0)
    Traceback (most recent call last):
    ...
    ValueError: Bearing.kxx must be a finite number >= 0 (N/m), got -1.0
    """

    node: int
    kxx: float
    kyy: float | None = None
    kxy: float = 0.0
    kyx: float = 0.0
    cxx: float = 0.0
    cyy: float | None = None
    cxy: float = 0.0
    cyx: float = 0.0
    k_tilt_x: float = 0.0
    k_tilt_y: float | None = None
    node_b: int | None = None

    def __post_init__(self) -> None:
        o = "Bearing"
        object.__setattr__(self, "node", _node(o, "node", self.node))
        if self.node_b is not None:
            nb = _node(o, "node_b", self.node_b)
            if nb == self.node:
                raise ValueError(f"{o}.node_b must differ from node = {self.node}, got {nb}")
            object.__setattr__(self, "node_b", nb)
        for name, unit, pair in (("kxx", "N/m", None), ("kyy", "N/m", "kxx"),
                                 ("cxx", "N s/m", None), ("cyy", "N s/m", "cxx"),
                                 ("k_tilt_x", "N m/rad", None),
                                 ("k_tilt_y", "N m/rad", "k_tilt_x")):
            value = getattr(self, name)
            if value is None and pair is not None:
                value = getattr(self, pair)
            object.__setattr__(self, name, _num(o, name, value, unit))
        for name, unit in (("kxy", "N/m"), ("kyx", "N/m"), ("cxy", "N s/m"), ("cyx", "N s/m")):
            object.__setattr__(self, name, _num(o, name, getattr(self, name), unit, low=None))

    @property
    def nodes(self) -> tuple[int, ...]:
        """``(node,)`` or ``(node, node_b)``."""
        return (self.node,) if self.node_b is None else (self.node, self.node_b)

    def _expand(self, local: np.ndarray) -> np.ndarray:
        if self.node_b is None:
            return local
        return np.block([[local, -local], [-local, local]])

    def K(self) -> np.ndarray:
        """Stiffness (4 or 8 square) (N/m, N m/rad)."""
        k = np.zeros((4, 4))
        k[0, 0], k[0, 1], k[1, 0], k[1, 1] = self.kxx, self.kxy, self.kyx, self.kyy
        k[2, 2], k[3, 3] = self.k_tilt_x, self.k_tilt_y
        return self._expand(k)

    def C(self) -> np.ndarray:
        """Damping (4 or 8 square) (N s/m)."""
        c = np.zeros((4, 4))
        c[0, 0], c[0, 1], c[1, 0], c[1, 1] = self.cxx, self.cxy, self.cyx, self.cyy
        return self._expand(c)



def _plane_matrix(owner: str, name: str, value, m: int, *, symmetric: bool) -> np.ndarray:
    a = np.array(value, dtype=float, copy=True)
    if a.shape != (2 * m, 2 * m):
        raise ValueError(f"{owner}.{name} must have shape {(2 * m, 2 * m)} (translation and tilt "
                         f"of each of the {m} nodes), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{owner}.{name} must be finite")
    if symmetric:
        scale = max(np.abs(a).max(), 1e-300)
        if np.abs(a - a.T).max() > 1e-8 * scale:
            raise ValueError(f"{owner}.{name} must be symmetric")
        a = 0.5 * (a + a.T)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, slots=True)
class ElasticConnection(_Massless):
    """Stiffness (and optional damping) matrix joining several nodes, plane by plane.

    This is how a multibody model on elastic supports is written (seed 000): the elastic
    structure between the bodies is reduced to a matrix over the bodies' translations and tilts.

    Parameters
    ----------
    nodes : tuple of int
        The m nodes connected, distinct.
    stiffness_x : array_like, shape (2m, 2m)
        Symmetric stiffness of the x-plane on ``(x_1, phi_x_1, x_2, phi_x_2, ...)`` (N/m, N/rad,
        N m/rad): ``[P_1, M_1, P_2, M_2, ...] = stiffness_x @ [x_1, phi_x_1, ...]``.
    stiffness_y : array_like, shape (2m, 2m), optional
        The same for the y-plane on ``(y_i, phi_y_i)``; None means isotropic (= stiffness_x).
    damping_x, damping_y : array_like, shape (2m, 2m), optional
        Viscous damping per plane (N s/m, ...); default none; ``damping_y=None`` copies x.

    See Also
    --------
    rotorlab.linear.compliance_to_stiffness : invert a compliance (influence coefficient)
        matrix.
    ElasticConnection.from_compliance

    Examples
    --------
    >>> import numpy as np
    >>> e = ElasticConnection(nodes=(0,), stiffness_x=np.diag([1e4, 1e2]))
    >>> e.K().diagonal()
    array([10000., 10000.,   100.,   100.])
    """

    nodes: tuple[int, ...]
    stiffness_x: np.ndarray
    stiffness_y: np.ndarray | None = None
    damping_x: np.ndarray | None = None
    damping_y: np.ndarray | None = None

    def __post_init__(self) -> None:
        o = "ElasticConnection"
        nodes = tuple(_node(o, "nodes", n) for n in self.nodes)
        if not nodes or len(set(nodes)) != len(nodes):
            raise ValueError(f"{o}.nodes must be distinct node numbers, got {self.nodes!r}")
        object.__setattr__(self, "nodes", nodes)
        m = len(nodes)
        kx = _plane_matrix(o, "stiffness_x", self.stiffness_x, m, symmetric=True)
        ky = kx if self.stiffness_y is None else _plane_matrix(o, "stiffness_y",
                                                                 self.stiffness_y, m,
                                                                 symmetric=True)
        object.__setattr__(self, "stiffness_x", kx)
        object.__setattr__(self, "stiffness_y", ky)
        if self.damping_x is None:
            if self.damping_y is not None:
                raise ValueError(f"{o}.damping_y needs damping_x")
        else:
            cx = _plane_matrix(o, "damping_x", self.damping_x, m, symmetric=False)
            cy = cx if self.damping_y is None else _plane_matrix(o, "damping_y", self.damping_y,
                                                                 m, symmetric=False)
            object.__setattr__(self, "damping_x", cx)
            object.__setattr__(self, "damping_y", cy)

    @classmethod
    def from_compliance(cls, nodes, compliance_x, compliance_y=None) -> ElasticConnection:
        """Return the connection whose stiffness is the inverse of a compliance matrix.

        Parameters
        ----------
        nodes : tuple of int
            The m nodes, in the order of the matrix rows.
        compliance_x : array_like, shape (2m, 2m)
            Influence coefficients of the x-plane, ``[x_1, phi_x_1, ...] = delta @ [P_1, M_1,
            ...]`` (m/N, 1/N, rad/(N m)), symmetric positive definite.
        compliance_y : array_like, optional
            The y-plane's; None means isotropic.

        Returns
        -------
        ElasticConnection

        References
        ----------
        Seed 000: ``||C_ij|| = ||delta_ij||^-1`` (stiffness matrix as the inverse of the
        compliance matrix), and the force expressions P_i, M_i printed after it.
        """
        from rotorlab.linear._influence import compliance_to_stiffness

        kx = compliance_to_stiffness(compliance_x)
        ky = None if compliance_y is None else compliance_to_stiffness(compliance_y)
        return cls(nodes=tuple(nodes), stiffness_x=kx, stiffness_y=ky)

    def _scatter(self, ax: np.ndarray | None, ay: np.ndarray | None) -> np.ndarray:
        m = len(self.nodes)
        out = np.zeros((4 * m, 4 * m))
        if ax is None:
            return out
        base = 4 * np.arange(m)
        xp = np.stack([base, base + 2], axis=1).reshape(-1)
        yp = np.stack([base + 1, base + 3], axis=1).reshape(-1)
        out[np.ix_(xp, xp)] = ax
        out[np.ix_(yp, yp)] = ay
        return out

    def K(self) -> np.ndarray:
        """Stiffness (4m, 4m) in node-major DOF order."""
        return self._scatter(self.stiffness_x, self.stiffness_y)

    def C(self) -> np.ndarray:
        """Damping (4m, 4m); zero unless damping was given."""
        return self._scatter(self.damping_x, self.damping_y)

