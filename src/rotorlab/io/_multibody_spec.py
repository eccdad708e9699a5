"""Case-file spec of the ``multibody`` model: rigid bodies joined by an elastic structure.

This is the model of seed 000 (the Pico 21 centrifuge): rigid bodies at stations along the axis
(a translation and a tilt per body and lateral plane), coupled by a compliance matrix (inverted
to a stiffness matrix), a stiffness matrix, or a compliance computed from the geometry of a
shaft in a housing on elastic feet; optionally also linear bearings from a body to the ground.

Layout::

    [model]
    type = "multibody"
    [[model.bodies]]            # one per body, in node order
    name = "rotor"
    position = "120 mm"
    mass = "0.507 kg"
    diametral_inertia = "882 kg*mm^2"
    polar_inertia = "1529 kg*mm^2"
    [model.elastic]             # one of: compliance, stiffness, geometry
    compliance = [[...], ...]   # 2m x 2m over (x_1, phi_1, x_2, phi_2, ...)
    [[model.bearings]]          # optional: springs and dampers from a body to the ground
    body = "rotor"
    kxx = "1 kN/m"
"""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field, model_validator

from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import _choice, _Spec, exclusive_issues, flag, quantity
from rotorlab.io._linear_common import (
    AbstractLinearModelSpec,
    BearingCoefficients,
    label,
    matrix_issues,
    plane_matrix,
    square_symmetric_issues,
)

__all__ = [
    "RigidBodySpec",
    "ShaftSpanSpec",
    "ShaftSupportSpec",
    "HousingSpec",
    "GeometrySpec",
    "ElasticSpec",
    "GroundBearingSpec",
    "MultibodySpec",
    "elastic_issues",
]


class RigidBodySpec(_Spec):
    """One rigid axisymmetric body.

    Parameters
    ----------
    name : str
        Unique name (the node label).
    position : float, optional
        Axial position z of the centre of mass (m); needed by ``elastic.geometry``.
    mass : float
        m (kg), > 0.
    diametral_inertia : float
        I_d about a diameter through the centre of mass (kg*m^2), >= 0.
    polar_inertia : float
        I_p about the axis (kg*m^2), 0 <= I_p <= 2 I_d.
    spinning : bool
        True if the body turns with the shaft (gyroscopic moments); false for a stator.
    on_shaft : bool
        True if the body sits on the shaft, false if it is part of the housing; used by
        ``elastic.geometry`` only.
    """

    name: label() = Field(description="unique name of the body")
    position: quantity("length") | None = Field(None, description="axial position z (m)")
    mass: quantity("mass", gt=0) = Field(description="mass (kg)")
    diametral_inertia: quantity("inertia", ge=0) = Field(
        description="diametral moment of inertia I_d (kg*m^2)")
    polar_inertia: quantity("inertia", ge=0) = Field(
        0.0, description="polar moment of inertia I_p (kg*m^2)")
    spinning: flag() = Field(True, description="turns with the shaft")
    on_shaft: flag() = Field(
        True, description="sits on the shaft; false for a part of the housing")

    @model_validator(mode="after")
    def _check_inertia(self) -> RigidBodySpec:
        if self.polar_inertia > 2.0 * self.diametral_inertia * (1.0 + 1e-9):
            raise IssueGroup([Issue(
                ("polar_inertia",),
                f"must be <= 2 * diametral_inertia = {2 * self.diametral_inertia:.6g} kg*m^2 "
                "(no rigid body has I_p > 2 I_d; are the two inertias swapped?)",
                self.polar_inertia)])
        return self


class ShaftSpanSpec(_Spec):
    """A stretch of shaft with constant flexural rigidity EI.

    Parameters
    ----------
    start, end : float
        Axial positions (m), start < end.
    flexural_rigidity : float
        EI (N*m^2), > 0.
    """

    start: quantity("length") = Field(description="start position (m)")
    end: quantity("length") = Field(description="end position (m)")
    flexural_rigidity: quantity("flexural_rigidity", gt=0) = Field(
        description="flexural rigidity EI (N*m^2)")

    @model_validator(mode="after")
    def _check_order(self) -> ShaftSpanSpec:
        if not self.end > self.start:
            raise IssueGroup([Issue(("end",), f"must be > start = {self.start:.6g} m", self.end)])
        return self


class ShaftSupportSpec(_Spec):
    """How the shaft is held in the housing at one position.

    Parameters
    ----------
    position : float
        z (m).
    kind : {"elastic", "pinned", "clamped"}
        An elastic bearing (``stiffness`` required), a rigid pin, or a clamp (the shaft built
        into the housing: rigid in translation and tilt).
    stiffness : float, optional
        Radial stiffness C_Pi of an elastic bearing (N/m), > 0.
    tilt_stiffness : float
        Moment stiffness of an elastic or pinned support (N*m/rad), >= 0.
    """

    position: quantity("length") = Field(description="axial position z (m)")
    kind: _choice("elastic", "pinned", "clamped") = Field(
        "elastic", description="elastic, pinned or clamped")
    stiffness: quantity("stiffness", gt=0) | None = Field(
        None, description="radial stiffness of an elastic bearing (N/m)")
    tilt_stiffness: quantity("rotational_stiffness", ge=0) = Field(
        0.0, description="moment stiffness (N*m/rad)")

    @model_validator(mode="after")
    def _check_kind(self) -> ShaftSupportSpec:
        issues = []
        if self.kind == "elastic" and self.stiffness is None:
            issues.append(Issue(("stiffness",), "required for an elastic support (or set kind "
                                                "= \"pinned\" or \"clamped\")", show_value=False))
        if self.kind != "elastic" and self.stiffness is not None:
            issues.append(Issue(("stiffness",), f"a {self.kind} support is rigid: remove the "
                                                "stiffness or set kind = \"elastic\"",
                                self.stiffness))
        if self.kind == "clamped" and self.tilt_stiffness != 0:
            issues.append(Issue(("tilt_stiffness",), "a clamped support is rigid in tilt: "
                                                     "remove it", self.tilt_stiffness))
        if issues:
            raise IssueGroup(issues)
        return self

    @property
    def holds_tilt(self) -> bool:
        """Whether the support resists tilting."""
        return self.kind == "clamped" or self.tilt_stiffness > 0


class HousingSpec(_Spec):
    """Elastic feet of a rigid housing, lumped at one point O.

    Parameters
    ----------
    position : float
        z_O (m), where the support reaction acts.
    translational_stiffness : float
        C_Q (N/m), > 0.
    rotational_stiffness : float
        C_M (N*m/rad), > 0.
    """

    position: quantity("length") = Field(0.0, description="position of the feet z_O (m)")
    translational_stiffness: quantity("stiffness", gt=0) = Field(
        description="translational stiffness C_Q of the feet (N/m)")
    rotational_stiffness: quantity("rotational_stiffness", gt=0) = Field(
        description="rotational stiffness C_M of the feet (N*m/rad)")


class GeometrySpec(_Spec):
    """A shaft in a rigid housing on elastic feet, seen from the bodies (seed 000).

    Parameters
    ----------
    spans : tuple of ShaftSpanSpec
        Contiguous stretches of shaft.
    supports : tuple of ShaftSupportSpec
        Bearings and clamps that hold the shaft in the housing.
    housing : HousingSpec, optional
        The housing's feet; omitted: the housing is fixed to the ground.
    """

    spans: tuple[ShaftSpanSpec, ...] = Field(min_length=1, description="shaft spans")
    supports: tuple[ShaftSupportSpec, ...] = Field(
        min_length=1, description="supports of the shaft in the housing")
    housing: HousingSpec | None = Field(None, description="elastic feet of the housing")


class ElasticSpec(_Spec):
    """The elastic structure joining bodies: exactly one of compliance, stiffness, geometry.

    Parameters
    ----------
    bodies : tuple of str, optional
        Names of the connected bodies, in the order of the matrix rows; default all bodies.
    compliance : tuple of tuple of float, optional
        Influence coefficients of the x-plane on ``(P_1, M_1, P_2, M_2, ...)`` ->
        ``(x_1, phi_1, ...)``: entries (m/N; 1/N; rad/(N*m)), inverted to stiffness.
    compliance_y : tuple of tuple of float, optional
        The same for the y-plane; omitted: isotropic.
    stiffness, stiffness_y : tuple of tuple of float, optional
        Stiffness matrices instead (N/m; N/rad; N*m/rad).
    scale : float
        Factor applied to every matrix entry (as in a printed table "x 1e-5"), > 0.
    geometry : GeometrySpec, optional
        Compute the compliance from a shaft-in-housing geometry (isotropic).
    damping, damping_y : tuple of tuple of float, optional
        Viscous damping of the structure on the same coordinates (N*s/m; N*s/rad; N*m*s/rad),
        symmetric positive semi-definite, scaled like the other matrices; ``damping_y``
        omitted: the y-plane has ``damping``. E.g. dampers c_i at positions z_i of a rigid body
        give ``sum_i c_i [[1, z_i], [z_i, z_i^2]]`` (Rodrigues et al. 2008, eq. (8)).
    """

    bodies: tuple[label(), ...] | None = Field(None, description="connected bodies, in order")
    compliance: plane_matrix("compliance") | None = Field(
        None, description="compliance matrix of the x-plane (m/N; 1/N; rad/N/m)")
    compliance_y: plane_matrix("compliance") | None = Field(
        None, description="compliance matrix of the y-plane (m/N; 1/N; rad/N/m)")
    stiffness: plane_matrix("stiffness") | None = Field(
        None, description="stiffness matrix of the x-plane (N/m; N/rad; N*m/rad)")
    stiffness_y: plane_matrix("stiffness") | None = Field(
        None, description="stiffness matrix of the y-plane (N/m; N/rad; N*m/rad)")
    scale: quantity("dimensionless", gt=0) = Field(
        1.0, description="factor applied to every matrix entry (-)")
    geometry: GeometrySpec | None = Field(None, description="shaft-in-housing geometry")
    damping: plane_matrix("damping") | None = Field(
        None, description="damping matrix of the x-plane (N*s/m; N*s/rad; N*m*s/rad)")
    damping_y: plane_matrix("damping") | None = Field(
        None, description="damping matrix of the y-plane (N*s/m; N*s/rad; N*m*s/rad)")

    #: Pairs of keys that exclude each other (and whether one of them is required).
    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("compliance", "stiffness", False),
        ("compliance", "geometry", False),
        ("stiffness", "geometry", False),
    )

    @model_validator(mode="after")
    def _check_sources(self) -> ElasticSpec:
        given = {k for k in ("compliance", "stiffness", "geometry") if getattr(self, k) is not None}
        issues = exclusive_issues(self.exclusive, given)
        if not given:
            issues.append(Issue((), "give one of compliance, stiffness or geometry",
                                show_value=False))
        for y, x in (("compliance_y", "compliance"), ("stiffness_y", "stiffness"),
                     ("damping_y", "damping")):
            if getattr(self, y) is not None and getattr(self, x) is None:
                issues.append(Issue((y,), f"needs {x} (the x-plane)", show_value=False))
        if issues:
            raise IssueGroup(issues)
        return self

    @property
    def source(self) -> str:
        """``"compliance"``, ``"stiffness"`` or ``"geometry"``."""
        return next(k for k in ("compliance", "stiffness", "geometry")
                    if getattr(self, k) is not None)

    def matrices(self, kind: str | None = None) -> tuple[tuple[tuple[float, ...], ...], ...]:
        """Return the given x- and y-plane matrices, scaled (y omitted when isotropic).

        ``kind`` is ``"damping"`` for the damping matrices (empty without them); default: the
        stiffness source (compliance or stiffness).
        """
        out = []
        kind = self.source if kind is None else kind
        for key in (kind, f"{kind}_y"):
            a = getattr(self, key, None)
            if a is not None:
                out.append(tuple(tuple(self.scale * v for v in row) for row in a))
        return tuple(out)


def damping_issues(key: str, a: tuple[tuple[float, ...], ...], size: int) -> list[Issue]:
    """Check a damping plane matrix: its size, symmetry and that it dissipates (eigenvalues >= 0).

    Unlike a stiffness matrix it may be singular (dampers on only some coordinates).
    """
    import numpy as np

    m, issues = square_symmetric_issues(key, a, size)
    if issues:
        return issues
    scale = float(np.abs(m).max())
    low = float(np.linalg.eigvalsh(0.5 * (m + m.T)).min())
    if low < -1e-12 * scale:
        return [Issue((key,), f"must be positive semi-definite (dampers dissipate energy): it "
                              f"has the eigenvalue {low:.6g}", show_value=False)]
    return []


def elastic_issues(elastic: ElasticSpec, bodies: tuple[RigidBodySpec, ...]) -> list[Issue]:
    """Check an elastic structure against the bodies it connects (``loc`` relative to it).

    Parameters
    ----------
    elastic : ElasticSpec
    bodies : tuple of RigidBodySpec
        All bodies of the model.

    Returns
    -------
    list of Issue
    """
    by_name = {b.name: b for b in bodies}
    names = elastic.bodies if elastic.bodies is not None else tuple(by_name)
    issues = []
    for i, name in enumerate(names):
        if name not in by_name:
            issues.append(Issue(("bodies", i), f"no body of that name (bodies: "
                                               f"{', '.join(by_name)})", name))
    if len(set(names)) != len(names):
        issues.append(Issue(("bodies",), "lists a body twice", list(names)))
    if issues:
        return issues
    connected = [by_name[n] for n in names]
    for key in ("damping", "damping_y"):
        a = getattr(elastic, key)
        if a is not None:
            issues += damping_issues(key, tuple(tuple(elastic.scale * v for v in row) for row in a),
                                     2 * len(connected))
    if elastic.geometry is None:
        for key in (elastic.source, f"{elastic.source}_y"):
            a = getattr(elastic, key)
            if a is not None:
                scaled = tuple(tuple(elastic.scale * v for v in row) for row in a)
                issues += matrix_issues(key, scaled, 2 * len(connected))
        return issues
    return issues + _geometry_issues(elastic.geometry, connected)


def _geometry_issues(geo: GeometrySpec, bodies: list[RigidBodySpec]) -> list[Issue]:
    issues = []
    spans = sorted(geo.spans, key=lambda s: s.start)
    for a, b in zip(spans[:-1], spans[1:]):
        if abs(a.end - b.start) > 1e-12 * max(1.0, abs(b.start)):
            issues.append(Issue(("geometry", "spans"), f"must be contiguous: one ends at "
                                                       f"{a.end:.6g} m, the next starts at "
                                                       f"{b.start:.6g} m", show_value=False))
    lo, hi = spans[0].start, spans[-1].end
    tol = 1e-12 * max(1.0, abs(lo), abs(hi))
    for i, s in enumerate(geo.supports):
        if not lo - tol <= s.position <= hi + tol:
            issues.append(Issue(("geometry", "supports", i, "position"),
                                f"lies outside the shaft [{lo:.6g}, {hi:.6g}] m", s.position))
    translational = {round(s.position, 12) for s in geo.supports}
    if not (any(s.kind == "clamped" for s in geo.supports) or len(translational) >= 2
            or any(s.holds_tilt for s in geo.supports)):
        issues.append(Issue(("geometry", "supports"), "do not hold the shaft: give a clamp, "
                                                      "two supports at different positions, or "
                                                      "a support with tilt_stiffness",
                            show_value=False))
    for b in bodies:
        if b.position is None:
            issues.append(Issue(("geometry",), f"needs the position of body '{b.name}'",
                                show_value=False))
        elif b.on_shaft and not lo - tol <= b.position <= hi + tol:
            issues.append(Issue(("geometry", "spans"), f"body '{b.name}' at {b.position:.6g} m "
                                                       f"lies outside the shaft [{lo:.6g}, "
                                                       f"{hi:.6g}] m", show_value=False))
        elif not b.on_shaft and geo.housing is None:
            issues.append(Issue(("geometry", "housing"), f"body '{b.name}' is part of the "
                                                         "housing (on_shaft = false), which has "
                                                         "no feet: give the housing table",
                                show_value=False))
    return issues


class GroundBearingSpec(BearingCoefficients):
    """Springs and dampers from one body to the ground.

    Parameters
    ----------
    body : str
        Name of the body.
    kxx, kyy, kxy, kyx, cxx, cyy, cxy, cyx, k_tilt_x, k_tilt_y : float
        See :class:`~rotorlab.io._linear_common.BearingCoefficients`.
    """

    body: label() = Field(description="name of the supported body")


class MultibodySpec(AbstractLinearModelSpec):
    """Rigid bodies on an elastic structure (seed 000), four DOFs per body.

    Parameters
    ----------
    bodies : tuple of RigidBodySpec
        The bodies, one node each, in order; unique names.
    elastic : ElasticSpec, optional
        The elastic structure joining them.
    bearings : tuple of GroundBearingSpec
        Springs and dampers from bodies to the ground.
    """

    type: Literal["multibody"] = "multibody"
    bodies: tuple[RigidBodySpec, ...] = Field(min_length=1, description="rigid bodies")
    elastic: ElasticSpec | None = Field(None, description="elastic structure joining bodies")
    bearings: tuple[GroundBearingSpec, ...] = Field((), description="supports to the ground")

    @model_validator(mode="after")
    def _check_model(self) -> MultibodySpec:
        names = [b.name for b in self.bodies]
        issues = [Issue(("bodies", i, "name"), "is used by an earlier body: names must be "
                                               "unique", n)
                  for i, n in enumerate(names) if n in names[:i]]
        if self.elastic is not None:
            issues += [Issue(("elastic", *x.loc), x.message, x.value, x.show_value)
                       for x in elastic_issues(self.elastic, self.bodies)]
        for i, b in enumerate(self.bearings):
            if b.body not in names:
                issues.append(Issue(("bearings", i, "body"), f"no body of that name (bodies: "
                                                             f"{', '.join(names)})", b.body))
        if self.elastic is None and not self.bearings:
            issues.append(Issue((), "nothing holds the bodies: give [model.elastic] or "
                                    "[[model.bearings]]", show_value=False))
        if issues:
            raise IssueGroup(issues)
        return self

    def node_labels(self) -> tuple[str, ...]:
        """Return the body names."""
        return tuple(b.name for b in self.bodies)

    def node_positions(self) -> tuple[float, ...]:
        """Return the body positions (m; NaN where not given)."""
        return tuple(float("nan") if b.position is None else b.position for b in self.bodies)

    def describe(self) -> str:
        """Return e.g. ``"multibody: 3 rigid bodies (...), 12 DOFs, coupled by ..."``."""
        how = "no elastic structure" if self.elastic is None else (
            f"coupled by a {self.elastic.source} matrix" if self.elastic.geometry is None
            else "coupled by a shaft-in-housing geometry")
        extra = f", {len(self.bearings)} ground bearing(s)" if self.bearings else ""
        bodies = f"{len(self.bodies)} rigid bod" + ("y" if len(self.bodies) == 1 else "ies")
        return (f"multibody: {bodies} ({', '.join(self.node_labels())}), {self.n_dof} DOFs, "
                f"{how}{extra}")
