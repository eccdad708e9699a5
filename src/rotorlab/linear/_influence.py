"""Influence coefficients: compliance <-> stiffness, and compliance built from geometry.

Seed 000 builds its three-body centrifuge from a compliance (flexibility) matrix ``delta``: the
translations and tilts of the bodies' centres caused by unit forces P and moments M applied
there. It obtains ``delta`` from the complementary strain energy of the structure
(Castigliano), with the statically indeterminate bearing reaction X eliminated by Menabrea's
theorem ``dPi/dX = 0``, and inverts it to get the stiffness matrix. This module does the same
for any such machine:

* a rigid housing (stator) on elastic feet at ``z_O``: translational stiffness ``C_Q`` and
  rotational stiffness ``C_M``, ``Pi_O = Q_0^2 / (2 C_Q) + M_0^2 / (2 C_M)``;
* a shaft of piecewise constant ``EI`` held in the housing by supports: clamps, elastic
  bearings (``Pi_p = X^2 / (2 C_Pi)``), optionally with tilt stiffness;
* stations (bodies) on the shaft or on the housing.

Its compliance is ``delta = T^T diag(1/C_Q, 1/C_M) T + delta_shaft``, where ``T`` carries the
support's deflection to the stations as a rigid motion (``eta = eta_0 + theta_0 (z - z_O)``,
``theta = theta_0``) and ``delta_shaft`` is the compliance of the shaft relative to the housing.
The latter is computed exactly by solving the statically indeterminate Euler-Bernoulli shaft
with cubic Hermite elements (exact for point loads), which is what Menabrea's theorem gives in
closed form; ``tests/validation/test_linear_seed000.py`` checks this against the seed's own
formula for X and its strain energies Pi_1..Pi_3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from rotorlab.linear._shaft import _euler_bernoulli_stiffness

__all__ = [
    "compliance_to_stiffness",
    "stiffness_to_compliance",
    "ShaftSpan",
    "ShaftSupport",
    "HousingSupport",
    "InfluenceModel",
    "influence_compliance",
]


def _square_spd(name: str, a) -> np.ndarray:
    m = np.array(a, dtype=float, copy=True)
    if m.ndim != 2 or m.shape[0] != m.shape[1] or m.shape[0] == 0:
        raise ValueError(f"{name} must be a non-empty square matrix, got shape {m.shape}")
    if not np.all(np.isfinite(m)):
        raise ValueError(f"{name} must be finite")
    scale = np.abs(m).max()
    if np.abs(m - m.T).max() > 1e-8 * scale:
        raise ValueError(f"{name} must be symmetric (Maxwell-Betti reciprocity)")
    m = 0.5 * (m + m.T)
    try:
        factor = scipy.linalg.cho_factor(m)
    except np.linalg.LinAlgError:
        raise ValueError(f"{name} must be positive definite") from None
    return m, factor


def compliance_to_stiffness(compliance) -> np.ndarray:
    """Invert a compliance (influence coefficient) matrix into a stiffness matrix.

    Parameters
    ----------
    compliance : array_like, shape (k, k)
        Symmetric positive definite ``delta`` with ``u = delta @ f`` (m/N, 1/N, rad/(N m)).

    Returns
    -------
    ndarray, shape (k, k)
        ``K = delta^-1`` (N/m, N/rad, N m/rad), exactly symmetric.

    Raises
    ------
    ValueError
        If ``compliance`` is not square, finite, symmetric and positive definite.

    Notes
    -----
    The inverse amplifies relative errors of ``delta`` by up to its condition number; for the
    seed's centrifuge that is 1.5e6, so a misprint in the 5th digit of one coefficient changes
    some stiffness coefficients by a factor 2 (see :mod:`rotorlab.linear.cases`).

    References
    ----------
    Seed 000: ``||C_ij|| = ||delta_ij||^-1``.

    Examples
    --------
    >>> compliance_to_stiffness([[2e-6, 0.0], [0.0, 1e-3]])
    array([[500000.,      0.],
           [     0.,   1000.]])
    """
    m, factor = _square_spd("compliance", compliance)
    k = scipy.linalg.cho_solve(factor, np.eye(m.shape[0]))
    return 0.5 * (k + k.T)


def stiffness_to_compliance(stiffness) -> np.ndarray:
    """Invert a stiffness matrix into the compliance (influence coefficient) matrix.

    Parameters
    ----------
    stiffness : array_like, shape (k, k)
        Symmetric positive definite K (N/m, N/rad, N m/rad).

    Returns
    -------
    ndarray, shape (k, k)
        ``delta = K^-1``.

    Examples
    --------
    >>> stiffness_to_compliance([[4.0, 0.0], [0.0, 0.5]])
    array([[0.25, 0.  ],
           [0.  , 2.  ]])
    """
    m, factor = _square_spd("stiffness", stiffness)
    d = scipy.linalg.cho_solve(factor, np.eye(m.shape[0]))
    return 0.5 * (d + d.T)


def _finite(owner, name, value, unit, *, allow_inf=False, strict=True):
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    ok = (math.isfinite(v) or (allow_inf and v == math.inf)) and (v > 0 if strict else True)
    if not ok:
        rule = "> 0" if strict else "finite"
        extra = " or math.inf" if allow_inf else ""
        raise ValueError(f"{owner}.{name} must be a number {rule}{extra} ({unit}), got {value!r}")
    return v


@dataclass(frozen=True, slots=True)
class ShaftSpan:
    """A stretch of shaft with constant flexural rigidity.

    Parameters
    ----------
    start, end : float
        Axial positions z (m), start < end.
    flexural_rigidity : float
        EI (N m^2), > 0.

    Examples
    --------
    >>> ShaftSpan(0.0, 0.12, 550.3).length
    0.12
    """

    start: float
    end: float
    flexural_rigidity: float

    def __post_init__(self) -> None:
        a = _finite("ShaftSpan", "start", self.start, "m", strict=False)
        b = _finite("ShaftSpan", "end", self.end, "m", strict=False)
        if not b > a:
            raise ValueError(f"ShaftSpan.end must be > start = {a:g} (m), got {self.end!r}")
        object.__setattr__(self, "start", a)
        object.__setattr__(self, "end", b)
        object.__setattr__(self, "flexural_rigidity",
                           _finite("ShaftSpan", "flexural_rigidity", self.flexural_rigidity,
                                   "N m^2"))

    @property
    def length(self) -> float:
        """end - start (m)."""
        return self.end - self.start


@dataclass(frozen=True, slots=True)
class ShaftSupport:
    """Connection of the shaft to the housing at one position: a bearing or a clamp.

    Parameters
    ----------
    position : float
        z (m).
    stiffness : float
        Radial stiffness C_Pi (N/m), > 0; ``math.inf`` for a rigid (pinned) support.
    tilt_stiffness : float
        Moment stiffness (N m/rad), >= 0; ``math.inf`` together with ``stiffness=math.inf`` is a
        clamp (the shaft built into the housing).

    Examples
    --------
    >>> ShaftSupport.clamp(0.0).is_clamp
    True
    """

    position: float
    stiffness: float
    tilt_stiffness: float = 0.0

    def __post_init__(self) -> None:
        o = "ShaftSupport"
        object.__setattr__(self, "position", _finite(o, "position", self.position, "m",
                                                     strict=False))
        object.__setattr__(self, "stiffness", _finite(o, "stiffness", self.stiffness, "N/m",
                                                      allow_inf=True))
        t = self.tilt_stiffness
        if t != 0:
            t = _finite(o, "tilt_stiffness", t, "N m/rad", allow_inf=True)
        object.__setattr__(self, "tilt_stiffness", float(t))

    @classmethod
    def clamp(cls, position: float) -> ShaftSupport:
        """Return a clamp (rigid in translation and tilt) at ``position`` (m)."""
        return cls(position=position, stiffness=math.inf, tilt_stiffness=math.inf)

    @property
    def is_clamp(self) -> bool:
        """True for a rigid clamp."""
        return self.stiffness == math.inf and self.tilt_stiffness == math.inf


@dataclass(frozen=True, slots=True)
class HousingSupport:
    """Elastic feet of a rigid housing, lumped at one point O.

    Parameters
    ----------
    position : float
        z_O (m): where the support reaction Q_0, M_0 acts.
    translational_stiffness : float
        C_Q (N/m), > 0, or ``math.inf`` (rigid).
    rotational_stiffness : float
        C_M (N m/rad), > 0, or ``math.inf`` (rigid).

    References
    ----------
    Seed 000: ``eta_0 = Q_0 / C_Q``, ``theta_0 = M_0 / C_M``,
    ``Pi_O = Q_0^2 / (2 C_Q) + M_0^2 / (2 C_M)``.
    """

    position: float
    translational_stiffness: float
    rotational_stiffness: float

    def __post_init__(self) -> None:
        o = "HousingSupport"
        object.__setattr__(self, "position", _finite(o, "position", self.position, "m",
                                                     strict=False))
        object.__setattr__(self, "translational_stiffness",
                           _finite(o, "translational_stiffness", self.translational_stiffness,
                                   "N/m", allow_inf=True))
        object.__setattr__(self, "rotational_stiffness",
                           _finite(o, "rotational_stiffness", self.rotational_stiffness,
                                   "N m/rad", allow_inf=True))


@dataclass(frozen=True, slots=True)
class InfluenceModel:
    """Geometry of a shaft in a rigid housing on elastic feet, seen from its stations.

    Parameters
    ----------
    station_position : tuple of float
        z of each station (body centre) (m), in the order of the compliance matrix rows.
    station_on_shaft : tuple of bool
        For each station, True if it sits on the shaft, False if it is part of the housing.
    spans : tuple of ShaftSpan
        Contiguous, non-overlapping, covering every shaft station and shaft support.
    shaft_supports : tuple of ShaftSupport
        How the shaft is held in the housing; together they must prevent rigid motion.
    housing_support : HousingSupport or None
        The housing's feet; None means the housing is fixed to the ground.

    Examples
    --------
    >>> m = InfluenceModel(station_position=(1.0,), station_on_shaft=(True,),
    ...                    spans=(ShaftSpan(0.0, 1.0, 1.0),),
    ...                    shaft_supports=(ShaftSupport.clamp(0.0),))
    >>> influence_compliance(m)  # cantilever: L^3/3EI, L^2/2EI, L/EI
    array([[0.33333333, 0.5       ],
           [0.5       , 1.        ]])
    """

    station_position: tuple[float, ...]
    station_on_shaft: tuple[bool, ...]
    spans: tuple[ShaftSpan, ...]
    shaft_supports: tuple[ShaftSupport, ...]
    housing_support: HousingSupport | None = None

    def __post_init__(self) -> None:
        o = "InfluenceModel"
        pos = tuple(_finite(o, "station_position", z, "m", strict=False)
                    for z in self.station_position)
        on = tuple(bool(b) for b in self.station_on_shaft)
        if not pos or len(on) != len(pos):
            raise ValueError(f"{o}.station_on_shaft must have one entry per station "
                             f"({len(pos)}), got {len(on)}")
        object.__setattr__(self, "station_position", pos)
        object.__setattr__(self, "station_on_shaft", on)
        spans = tuple(sorted(self.spans, key=lambda s: s.start))
        if not spans:
            raise ValueError(f"{o}.spans must not be empty")
        for a, b in zip(spans[:-1], spans[1:]):
            if abs(a.end - b.start) > 1e-12 * max(1.0, abs(b.start)):
                raise ValueError(f"{o}.spans must be contiguous: one ends at {a.end:g} m, the "
                                 f"next starts at {b.start:g} m")
        object.__setattr__(self, "spans", spans)
        supports = tuple(self.shaft_supports)
        if not supports:
            raise ValueError(f"{o}.shaft_supports must not be empty")
        object.__setattr__(self, "shaft_supports", supports)
        lo, hi = spans[0].start, spans[-1].end
        tol = 1e-12 * max(1.0, abs(lo), abs(hi))
        for z, s in zip(pos, on):
            if s and not lo - tol <= z <= hi + tol:
                raise ValueError(f"{o}.station_position {z:g} m lies outside the shaft "
                                 f"[{lo:g}, {hi:g}] m")
        for sup in supports:
            if not lo - tol <= sup.position <= hi + tol:
                raise ValueError(f"{o}.shaft_supports position {sup.position:g} m lies outside "
                                 f"the shaft [{lo:g}, {hi:g}] m")


def _shaft_compliance(model: InfluenceModel, z_stations: np.ndarray) -> np.ndarray:
    """Compliance of the shaft relative to the housing at the given shaft stations."""
    tol = 1e-12
    pts = [s.start for s in model.spans] + [model.spans[-1].end]
    pts += [s.position for s in model.shaft_supports] + list(z_stations)
    nodes = np.unique(np.round(np.asarray(pts, dtype=float), 15))
    keep = np.concatenate([[True], np.diff(nodes) > tol * max(1.0, np.abs(nodes).max())])
    nodes = nodes[keep]
    n = nodes.size
    K = np.zeros((2 * n, 2 * n))
    for e in range(n - 1):
        mid = 0.5 * (nodes[e] + nodes[e + 1])
        span = next(s for s in model.spans if s.start - tol <= mid <= s.end + tol)
        idx = slice(2 * e, 2 * e + 4)
        K[idx, idx] += _euler_bernoulli_stiffness(span.flexural_rigidity, nodes[e + 1] - nodes[e])
    fixed = []
    for sup in model.shaft_supports:
        i = int(np.argmin(np.abs(nodes - sup.position)))
        for dof, k in ((2 * i, sup.stiffness), (2 * i + 1, sup.tilt_stiffness)):
            if k == math.inf:
                fixed.append(dof)
            else:
                K[dof, dof] += k
    free = np.setdiff1d(np.arange(2 * n), fixed)
    kff = K[np.ix_(free, free)]
    ev = np.linalg.eigvalsh(kff) if kff.size else np.ones(1)
    if ev.min() <= 1e-11 * ev.max():
        raise ValueError("InfluenceModel.shaft_supports do not hold the shaft: it can move as a "
                         "rigid body relative to the housing")
    factor = scipy.linalg.cho_factor(kff)
    sel = []
    for z in z_stations:
        i = int(np.argmin(np.abs(nodes - z)))
        sel += [2 * i, 2 * i + 1]
    full = np.zeros((2 * n, len(sel)))
    loads = np.zeros((free.size, len(sel)))
    pos_in_free = {d: k for k, d in enumerate(free)}
    for col, dof in enumerate(sel):
        if dof in pos_in_free:
            loads[pos_in_free[dof], col] = 1.0
    full[free] = scipy.linalg.cho_solve(factor, loads)
    out = full[sel]
    return 0.5 * (out + out.T)


def influence_compliance(model: InfluenceModel) -> np.ndarray:
    """Return the compliance matrix of the stations of a shaft-in-housing structure.

    Parameters
    ----------
    model : InfluenceModel

    Returns
    -------
    ndarray, shape (2m, 2m)
        ``delta`` on ``(P_1, M_1, ..., P_m, M_m)`` -> ``(eta_1, theta_1, ..., eta_m, theta_m)``
        (m/N, 1/N, rad/(N m)); positive tilt is d(eta)/dz.

    Notes
    -----
    ``delta = T^T diag(1/C_Q, 1/C_M) T + delta_shaft`` (see module docstring). The
    shaft part is the exact Euler-Bernoulli flexibility of the indeterminate shaft, i.e. the
    Hessian of the complementary energy ``Pi_val + Pi_p`` minimised over the redundant
    reactions (Castigliano and Menabrea).

    References
    ----------
    Seed 000: ``Pi = Pi_val + Pi_O + Pi_p``, the integrals ``Pi_1..Pi_3``, the reaction ``X``
    (Menabrea) and ``Pi = 1/2 P^T ||delta_ij|| P``.
    """
    z = np.asarray(model.station_position)
    on = np.asarray(model.station_on_shaft)
    m = z.size
    delta = np.zeros((2 * m, 2 * m))
    hs = model.housing_support
    if hs is not None:
        T = np.zeros((2, 2 * m))
        T[0, 0::2] = 1.0
        T[1, 0::2] = z - hs.position
        T[1, 1::2] = 1.0
        f0 = np.diag([1.0 / hs.translational_stiffness, 1.0 / hs.rotational_stiffness])
        delta += T.T @ f0 @ T
    if on.any():
        idx = np.flatnonzero(on)
        shaft = _shaft_compliance(model, z[idx])
        dof = np.stack([2 * idx, 2 * idx + 1], axis=1).reshape(-1)
        delta[np.ix_(dof, dof)] += shaft
    return 0.5 * (delta + delta.T)
