"""Case-file spec of the ``fe_rotor`` model: a Timoshenko shaft with rigid discs and bearings.

The shaft is a chain of sections starting at z = 0, each cut into equal Timoshenko elements
(shear deformation, rotary inertia, gyroscopic matrix); nodes sit at the element ends. Discs
and bearings are placed by axial position (anywhere on the shaft) or by node index (a node of
the sections as written). The mesh is refined automatically: an element with a disc or bearing
inside it is split there, so that every disc and bearing sits on a node
(:meth:`FeRotorSpec.refinement` lists the inserted nodes, and ``describe`` says so).

Layout::

    [model]
    type = "fe_rotor"
    [model.material]
    youngs_modulus = "211 GPa"
    shear_modulus = "81.2 GPa"
    density = "7810 kg/m^3"
    [[model.shaft]]             # sections, from z = 0
    length = "1.5 m"
    outer_diameter = "50 mm"
    elements = 6
    [[model.discs]]
    name = "disc 1"
    position = "0.5 m"
    outer_diameter = "280 mm"
    width = "70 mm"
    [[model.bearings]]
    position = "0 m"
    kxx = "1 MN/m"
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from rotorlab.io._errors import Issue, IssueGroup
from rotorlab.io._fields import _Spec, flag, integer, quantity
from rotorlab.io._linear_common import AbstractLinearModelSpec, BearingCoefficients, label

__all__ = ["MaterialSpec", "ShaftSectionSpec", "DiscSpec", "FeBearingSpec", "FeRotorSpec"]


class MaterialSpec(_Spec):
    """Isotropic elastic material.

    Parameters
    ----------
    youngs_modulus : float
        E (Pa), > 0.
    shear_modulus : float
        G (Pa), > 0, with Poisson's ratio E / (2 G) - 1 in (-1, 0.5).
    density : float
        rho (kg/m^3), > 0.
    """

    youngs_modulus: quantity("pressure", gt=0) = Field(description="Young's modulus E (Pa)")
    shear_modulus: quantity("pressure", gt=0) = Field(description="shear modulus G (Pa)")
    density: quantity("density", gt=0) = Field(description="density (kg/m^3)")

    @model_validator(mode="after")
    def _check_poisson(self) -> MaterialSpec:
        nu = self.youngs_modulus / (2.0 * self.shear_modulus) - 1.0
        if not -1.0 < nu < 0.5:
            raise IssueGroup([Issue(("shear_modulus",), f"gives Poisson's ratio E/(2G) - 1 = "
                                                        f"{nu:.4g}; need -1 < nu < 0.5",
                                    self.shear_modulus)])
        return self


class ShaftSectionSpec(_Spec):
    """A shaft section of constant cross-section, cut into equal elements.

    Parameters
    ----------
    length : float
        (m), > 0.
    outer_diameter : float
        (m), > 0.
    inner_diameter : float
        Bore (m), 0 <= inner < outer.
    elements : int
        Number of equal Timoshenko elements, >= 1.
    material : MaterialSpec, optional
        Default: the model's material.
    """

    length: quantity("length", gt=0) = Field(description="section length (m)")
    outer_diameter: quantity("length", gt=0) = Field(description="outer diameter (m)")
    inner_diameter: quantity("length", ge=0) = Field(0.0, description="bore diameter (m)")
    elements: integer(ge=1) = Field(1, description="number of equal elements")
    material: MaterialSpec | None = Field(None, description="material, default the model's")

    @model_validator(mode="after")
    def _check_bore(self) -> ShaftSectionSpec:
        if self.inner_diameter >= self.outer_diameter:
            raise IssueGroup([Issue(("inner_diameter",), f"must be < outer_diameter = "
                                                         f"{self.outer_diameter:.6g} m",
                                    self.inner_diameter)])
        return self


class DiscSpec(_Spec):
    """A rigid disc at a node: from its geometry, or from mass and inertias.

    Parameters
    ----------
    name : str, optional
        Name (the node's label; usable as ``at`` in analyses).
    node : int, optional
        Node index; excludes ``position``.
    position : float, optional
        Axial position (m), on the shaft (the mesh is refined to put a node there).
    outer_diameter, width : float, optional
        Geometry of a uniform annular disc (m); excludes ``mass``.
    inner_diameter : float
        Bore (m), the shaft diameter for a disc keyed onto it.
    density : float, optional
        (kg/m^3); default the model's material.
    mass : float, optional
        (kg); with ``diametral_inertia`` and ``polar_inertia`` instead of the geometry.
    diametral_inertia, polar_inertia : float, optional
        (kg*m^2).
    """

    name: label() | None = Field(None, description="name of the disc")
    node: integer(ge=0) | None = Field(None, description="node index")
    position: quantity("length") | None = Field(None, description="axial position (m)")
    outer_diameter: quantity("length", gt=0) | None = Field(None, description="outer diameter (m)")
    width: quantity("length", gt=0) | None = Field(None, description="axial width (m)")
    inner_diameter: quantity("length", ge=0) = Field(0.0, description="bore diameter (m)")
    density: quantity("density", gt=0) | None = Field(None, description="density (kg/m^3)")
    mass: quantity("mass", gt=0) | None = Field(None, description="mass (kg)")
    diametral_inertia: quantity("inertia", ge=0) | None = Field(
        None, description="diametral moment of inertia (kg*m^2)")
    polar_inertia: quantity("inertia", ge=0) | None = Field(
        None, description="polar moment of inertia (kg*m^2)")

    @model_validator(mode="after")
    def _check_disc(self) -> DiscSpec:
        issues = []
        if (self.node is None) == (self.position is None):
            issues.append(Issue((), "give one of node or position", show_value=False))
        geometric = self.outer_diameter is not None or self.width is not None
        lumped = any(v is not None for v in (self.mass, self.diametral_inertia,
                                              self.polar_inertia))
        if geometric and lumped:
            issues.append(Issue((), "give either outer_diameter and width, or mass and "
                                    "inertias, not both", show_value=False))
        elif geometric:
            for key in ("outer_diameter", "width"):
                if getattr(self, key) is None:
                    issues.append(Issue((key,), "required with the disc's geometry",
                                        show_value=False))
            if self.outer_diameter is not None and self.inner_diameter >= self.outer_diameter:
                issues.append(Issue(("inner_diameter",), f"must be < outer_diameter = "
                                                         f"{self.outer_diameter:.6g} m",
                                    self.inner_diameter))
        elif lumped:
            for key in ("mass", "diametral_inertia"):
                if getattr(self, key) is None:
                    issues.append(Issue((key,), "required for a disc given by mass and inertia",
                                        show_value=False))
            ip, idia = self.polar_inertia or 0.0, self.diametral_inertia
            if idia is not None and ip > 2.0 * idia * (1.0 + 1e-9):
                issues.append(Issue(("polar_inertia",), f"must be <= 2 * diametral_inertia = "
                                                        f"{2 * idia:.6g} kg*m^2", ip))
        else:
            issues.append(Issue((), "give outer_diameter and width, or mass and "
                                    "diametral_inertia", show_value=False))
        if issues:
            raise IssueGroup(issues)
        return self


class FeBearingSpec(BearingCoefficients):
    """A linear bearing from a shaft node to the ground.

    Parameters
    ----------
    name : str, optional
        Name (the node's label unless a disc names it; usable as ``at``).
    node : int, optional
        Node index; excludes ``position``.
    position : float, optional
        Axial position (m), on the shaft (the mesh is refined to put a node there).
    kxx, kyy, kxy, kyx, cxx, cyy, cxy, cyx, k_tilt_x, k_tilt_y : float
        See :class:`~rotorlab.io._linear_common.BearingCoefficients`.
    """

    name: label() | None = Field(None, description="name of the bearing")
    node: integer(ge=0) | None = Field(None, description="node index")
    position: quantity("length") | None = Field(None, description="axial position (m)")

    @model_validator(mode="after")
    def _check_place(self) -> FeBearingSpec:
        if (self.node is None) == (self.position is None):
            raise IssueGroup([Issue((), "give one of node or position", show_value=False)])
        return self


class FeRotorSpec(AbstractLinearModelSpec):
    """Finite-element rotor: Timoshenko shaft, rigid discs, linear bearings.

    Parameters
    ----------
    material : MaterialSpec
        Material of the shaft (and default density of the discs).
    shaft : tuple of ShaftSectionSpec
        Sections in order from z = 0.
    shear, rotary_inertia, gyroscopic : bool
        Shaft element options (all true: Timoshenko with gyroscopic terms).
    discs : tuple of DiscSpec
    bearings : tuple of FeBearingSpec
    """

    type: Literal["fe_rotor"] = "fe_rotor"
    material: MaterialSpec = Field(description="shaft material")
    shaft: tuple[ShaftSectionSpec, ...] = Field(min_length=1, description="shaft sections")
    shear: flag() = Field(True, description="shear deformation in the shaft elements")
    rotary_inertia: flag() = Field(True, description="rotary inertia of the shaft elements")
    gyroscopic: flag() = Field(True, description="gyroscopic terms of the shaft elements")
    discs: tuple[DiscSpec, ...] = Field((), description="rigid discs")
    bearings: tuple[FeBearingSpec, ...] = Field((), description="bearings to the ground")

    @model_validator(mode="after")
    def _check_places(self) -> FeRotorSpec:
        issues = []
        seen: dict[str, tuple[str, int]] = {}
        for key in ("discs", "bearings"):
            for i, part in enumerate(getattr(self, key)):
                node, bad, message = self.locate(part.node, None, part.position)
                if node is None:
                    issues.append(Issue((key, i, bad), message, getattr(part, bad)))
                if part.name is not None:
                    if part.name in seen or part.name.isdigit():
                        where = seen.get(part.name)
                        why = (f"is used by {where[0]}[{where[1]}]" if where
                               else "is a node number")
                        issues.append(Issue((key, i, "name"), f"{why}: names must be unique",
                                            part.name))
                    seen[part.name] = (key, i)
        if issues:
            raise IssueGroup(issues)
        return self

    def section_nodes(self) -> tuple[float, ...]:
        """Return the node positions of the sections as written (m), before any refinement."""
        z = [0.0]
        for s in self.shaft:
            le = s.length / s.elements
            z += [z[-1] + le * (k + 1) for k in range(s.elements)]
        return tuple(z)

    def _tolerance(self) -> float:
        return 1e-9 * (sum(s.length for s in self.shaft) or 1.0)

    def refinement(self) -> tuple[float, ...]:
        """Return the positions of the nodes inserted so that discs and bearings sit on nodes (m).

        Empty when every disc and bearing given by ``position`` is already at a node of the
        sections (as in the built-in cases).
        """
        written = self.section_nodes()
        tol, length = self._tolerance(), written[-1]
        inserted: list[float] = []
        for part in (*self.discs, *self.bearings):
            z = part.position
            if z is None or not -tol <= z <= length + tol:
                continue
            if all(abs(z - w) > tol for w in (*written, *inserted)):
                inserted.append(float(z))
        return tuple(sorted(inserted))

    def node_positions(self) -> tuple[float, ...]:
        """Return the axial node positions of the refined mesh (m), from 0 to the shaft length."""
        return tuple(sorted((*self.section_nodes(), *self.refinement())))

    def locate(self, node: int | None, at: str | None,
               position: float | None) -> tuple[int | None, str, str]:
        """Find a node by index (of the sections as written), name or axial position."""
        if node is not None:
            written = self.section_nodes()
            if node >= len(written):
                n = len(written)
                return None, "node", f"must be < {n} (the shaft's sections have {n} nodes)"
            position = written[node]
        elif at is not None:
            return super().locate(None, at, None)
        z = self.node_positions()
        tol = self._tolerance()
        for i, p in enumerate(z):
            if abs(p - position) <= tol:
                return i, "", ""
        if not -tol <= position <= z[-1] + tol:
            return None, "position", f"must be on the shaft, from 0 to {z[-1]:.6g} m"
        listing = ", ".join(f"{p:.6g}" for p in z)
        return None, "position", f"is not at a node (nodes at {listing} m)"

    def node_of(self, part: DiscSpec | FeBearingSpec) -> int:
        """Return the node of a disc or bearing of this model."""
        node, _, message = self.locate(part.node, None, part.position)
        if node is None:
            raise ValueError(message)
        return node

    def node_labels(self) -> tuple[str, ...]:
        """Return node labels: a disc's or bearing's name where given, else the node index."""
        labels = [str(i) for i in range(len(self.node_positions()))]
        named = [False] * len(labels)
        for part in (*self.discs, *self.bearings):
            if part.name is not None:
                node = self.node_of(part)
                if not named[node]:
                    labels[node], named[node] = part.name, True
        return tuple(labels)

    def component_nodes(self) -> dict[str, int]:
        """Return node indices (as text) and disc and bearing names, mapped to their node."""
        out = {str(i): i for i in range(len(self.node_positions()))}
        for part in (*self.discs, *self.bearings):
            if part.name is not None:
                out[part.name] = self.node_of(part)
        return out

    @property
    def n_elements(self) -> int:
        """Number of shaft elements (of the refined mesh)."""
        return len(self.node_positions()) - 1

    def section_at(self, z: float) -> ShaftSectionSpec:
        """Return the section that holds axial position ``z`` (m)."""
        end = 0.0
        for s in self.shaft:
            end += s.length
            if z < end:
                return s
        return self.shaft[-1]

    def mesh_note(self) -> str:
        """Say how the mesh was refined ("" if it was not)."""
        added = self.refinement()
        if not added:
            return ""
        where = ", ".join(f"{z:.6g}" for z in added)
        return (f"mesh refined: {len(added)} node(s) added at z = {where} m so that every disc "
                f"and bearing sits on a node")

    def describe(self) -> str:
        """Return e.g. ``"fe_rotor: 6 Timoshenko elements over 1.5 m, 2 discs, ..."``."""
        kind = "Timoshenko" if self.shear else "Euler-Bernoulli"
        note = self.mesh_note()
        return (f"fe_rotor: {self.n_elements} {kind} elements over "
                f"{self.node_positions()[-1]:.6g} m, {len(self.discs)} disc(s), "
                f"{len(self.bearings)} bearing(s), {self.n_dof} DOFs" + (f"; {note}" if note else ""))
