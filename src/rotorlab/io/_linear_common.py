"""Shared parts of the linear rotor specs: labels, matrices with units, bearings, key paths.

A linear rotor model (``multibody``, ``fe_rotor``) derives from
:class:`AbstractLinearModelSpec`, which knows its nodes without building any matrix: their
labels, axial positions and number of degrees of freedom (four per node: x, y, phi_x, phi_y).
Analyses refer to nodes by label, index or position (:meth:`AbstractLinearModelSpec.locate`),
and the ``identify`` analysis changes model values by key path
(:meth:`AbstractLinearModelSpec.with_values`).
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any

from pydantic import BaseModel, Field, PlainValidator, WithJsonSchema

from rotorlab.io._errors import Issue, IssueGroup, did_you_mean, format_path
from rotorlab.io._fields import AbstractModelSpec, Unit, _error, _Spec, plain_data, quantity
from rotorlab.io._units import DIMENSIONS, UnitError, convert

__all__ = [
    "AbstractLinearModelSpec",
    "BearingCoefficients",
    "label",
    "plane_matrix",
    "parse_path",
    "matrix_issues",
]

_PATH_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)")


class _LabelValidator:
    def __call__(self, value: Any) -> str:
        if not isinstance(value, str):
            raise _error("must be a string (a name, e.g. \"rotor\" or \"disc 1\")")
        if not value.strip() or len(value) > 64 or any(ord(c) < 0x20 for c in value):
            raise _error("must be 1 to 64 printable characters, not only spaces")
        return value


def label() -> Any:
    """Return the annotated type of a node or body name (1-64 printable characters)."""
    return Annotated[str, PlainValidator(_LabelValidator()), WithJsonSchema({"type": "string"})]


#: Dimensions of the entries of a plane matrix on (translation, tilt) pairs, by
#: ``(row % 2) + (column % 2)``: translation-translation, translation-tilt, tilt-tilt.
_PLANE_DIMENSIONS = {
    "compliance": ("compliance", "compliance_coupling", "rotational_compliance"),
    "stiffness": ("stiffness", "stiffness_coupling", "rotational_stiffness"),
    "damping": ("damping", "damping_coupling", "torque_damping"),
}


class _MatrixValidator:
    """Read a square matrix over (translation, tilt) pairs, each entry in its own unit."""

    def __init__(self, kind: str) -> None:
        self.dims = tuple(DIMENSIONS[d] for d in _PLANE_DIMENSIONS[kind])

    def __call__(self, value: Any) -> tuple[tuple[float, ...], ...]:
        if (not isinstance(value, (list, tuple)) or not value
                or not all(isinstance(row, (list, tuple)) for row in value)):
            raise _error("must be a square matrix: a list of rows, each a list of numbers")
        n = len(value)
        lengths = sorted({len(row) for row in value})
        if n % 2 or lengths != [n]:
            raise _error(f"must be a square matrix with an even number of rows (translation "
                         f"and tilt of each body), got {n} row(s) of length {lengths}")
        issues, out = [], []
        for i, row in enumerate(value):
            converted = []
            for j, x in enumerate(row):
                try:
                    converted.append(convert(x, self.dims[i % 2 + j % 2]))
                except UnitError as exc:
                    issues.append(Issue((i, j), str(exc), x))
                    converted.append(math.nan)
            out.append(tuple(converted))
        if issues:
            raise IssueGroup(issues)
        return tuple(out)


def plane_matrix(kind: str) -> Any:
    """Return the annotated type of a compliance or stiffness matrix of one lateral plane.

    Parameters
    ----------
    kind : {"compliance", "stiffness", "damping"}
        Entries (2i, 2j) are m/N (N/m, N*s/m), entries (2i, 2j+1) and (2i+1, 2j) 1/N (N/rad,
        N*s/rad), entries (2i+1, 2j+1) rad/(N*m) (N*m/rad, N*m*s/rad); a string with a unit is
        checked against the unit of its place.
    """
    schema = {"type": "array", "items": {"type": "array",
                                         "items": {"anyOf": [{"type": "number"},
                                                             {"type": "string"}]}}}
    unit = "; ".join(DIMENSIONS[d].si for d in _PLANE_DIMENSIONS[kind])  # per place, as in the docstring
    return Annotated[tuple[tuple[float, ...], ...], PlainValidator(_MatrixValidator(kind)),
                     WithJsonSchema(schema), Unit(unit)]


def square_symmetric_issues(key: str, a: tuple[tuple[float, ...], ...], size: int):
    """Check a plane matrix's size and symmetry; return ``(matrix, issues)`` (issues empty if fine).

    The one shape and symmetry check of stiffness, compliance and damping plane matrices.
    """
    import numpy as np

    m = np.array(a, dtype=float)
    if m.shape != (size, size):
        return m, [Issue((key,), f"must be {size} x {size} (translation and tilt of each of the "
                                  f"{size // 2} connected bodies), got {m.shape[0]} x "
                                  f"{m.shape[1]}", show_value=False)]
    diff = np.abs(m - m.T)
    if diff.max() > 1e-8 * float(np.abs(m).max()):
        i, j = np.unravel_index(int(np.argmax(diff)), diff.shape)
        return m, [Issue((key,), f"must be symmetric: [{i}][{j}] = {m[i, j]:.10g} but "
                                 f"[{j}][{i}] = {m[j, i]:.10g}", show_value=False)]
    return m, []


def matrix_issues(key: str, a: tuple[tuple[float, ...], ...], size: int) -> list[Issue]:
    """Check a plane matrix: its size, symmetry (Maxwell-Betti) and positive definiteness.

    Parameters
    ----------
    key : str
        Its key, the ``loc`` of the issues.
    a : tuple of tuple of float
        The matrix (SI).
    size : int
        Required number of rows (twice the number of bodies it connects).

    Returns
    -------
    list of Issue
    """
    import numpy as np

    m, issues = square_symmetric_issues(key, a, size)
    if issues:
        return issues
    try:
        np.linalg.cholesky(0.5 * (m + m.T))
    except np.linalg.LinAlgError:
        return [Issue((key,), "must be positive definite (every deflection needs energy)",
                      show_value=False)]
    return []


class BearingCoefficients(_Spec):
    """Stiffness and damping coefficients of a linear bearing or support.

    Parameters
    ----------
    kxx, kyy : float
        Direct stiffness (N/m), >= 0; ``kyy`` omitted means ``kxx`` (isotropic).
    kxy, kyx : float
        Cross-coupled stiffness (N/m).
    cxx, cyy : float
        Direct damping (N*s/m), >= 0; ``cyy`` omitted means ``cxx``.
    cxy, cyx : float
        Cross-coupled damping (N*s/m).
    k_tilt_x, k_tilt_y : float
        Moment stiffness on phi_x, phi_y (N*m/rad), >= 0; ``k_tilt_y`` omitted means
        ``k_tilt_x``.
    """

    kxx: quantity("stiffness", ge=0) = Field(description="direct stiffness k_xx (N/m)")
    kyy: quantity("stiffness", ge=0) | None = Field(
        None, description="direct stiffness k_yy, default k_xx (N/m)")
    kxy: quantity("stiffness") = Field(0.0, description="cross-coupled stiffness k_xy (N/m)")
    kyx: quantity("stiffness") = Field(0.0, description="cross-coupled stiffness k_yx (N/m)")
    cxx: quantity("damping", ge=0) = Field(0.0, description="direct damping c_xx (N*s/m)")
    cyy: quantity("damping", ge=0) | None = Field(
        None, description="direct damping c_yy, default c_xx (N*s/m)")
    cxy: quantity("damping") = Field(0.0, description="cross-coupled damping c_xy (N*s/m)")
    cyx: quantity("damping") = Field(0.0, description="cross-coupled damping c_yx (N*s/m)")
    k_tilt_x: quantity("rotational_stiffness", ge=0) = Field(
        0.0, description="moment stiffness on phi_x (N*m/rad)")
    k_tilt_y: quantity("rotational_stiffness", ge=0) | None = Field(
        None, description="moment stiffness on phi_y, default k_tilt_x (N*m/rad)")

    def coefficients(self) -> dict[str, float | None]:
        """Return the keyword arguments of :class:`rotorlab.linear.Bearing` (SI)."""
        return {k: getattr(self, k) for k in ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy",
                                              "cyx", "k_tilt_x", "k_tilt_y")}


def parse_path(text: str) -> tuple[str | int, ...] | None:
    """Split a key path such as ``"bearings[0].kxx"`` into keys and indices.

    Returns
    -------
    tuple of str or int, or None
        None if ``text`` is not a key path.

    Examples
    --------
    >>> parse_path("elastic.geometry.housing.translational_stiffness")
    ('elastic', 'geometry', 'housing', 'translational_stiffness')
    >>> parse_path("bearings[1].kxx"), parse_path("bearings.[1]")
    (('bearings', 1, 'kxx'), None)
    """
    parts: list[str | int] = []
    for piece in text.split("."):
        match = _PATH_PART.fullmatch(piece)
        if match is None:
            return None
        parts.append(match[1])
        parts += [int(i) for i in re.findall(r"\[(\d+)\]", match[2])]
    return tuple(parts)


class AbstractLinearModelSpec(AbstractModelSpec):
    """Base of the linear rotor models: nodes with four DOFs each (x, y, phi_x, phi_y).

    For implementers
    ----------------
    1. Implement :meth:`node_labels` and :meth:`node_positions` (cheap: no matrices).
    2. Teach :func:`rotorlab.analyses.build_model` to build its
       :class:`rotorlab.linear.LinearSystem`, with nodes in the same order.
    """

    def linear_structure(self) -> AbstractLinearModelSpec:
        """The model itself (the linear analyses run on it)."""
        return self

    def node_labels(self) -> tuple[str, ...]:
        """Return the name of every node, in node order."""
        raise NotImplementedError

    def node_positions(self) -> tuple[float, ...]:
        """Return the axial position of every node (m; NaN where unknown)."""
        raise NotImplementedError

    def component_nodes(self) -> dict[str, int]:
        """Return the names an analysis may use with ``at``, mapped to their node."""
        return {name: i for i, name in enumerate(self.node_labels())}

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.node_positions())

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom, ``4 n_nodes``."""
        return 4 * self.n_nodes

    def locate(self, node: int | None, at: str | None,
               position: float | None) -> tuple[int | None, str, str]:
        """Find the node an analysis refers to by index, name or axial position.

        Returns
        -------
        (int or None, str, str)
            The node, or None with the offending key and a message saying what is allowed.
        """
        if node is not None:
            n = self.n_nodes
            if node >= n:
                return None, "node", f"must be < {n} (the model has {n} nodes)"
            return node, "", ""
        if at is not None:
            names = self.component_nodes()
            if at not in names:
                hint = did_you_mean(at, names)
                listing = ", ".join(f'"{n}"' for n in names)
                return None, "at", ("no node or component of that name"
                                    + (f"; {hint}" if hint else "") + f" (names: {listing})")
            return names[at], "", ""
        z = self.node_positions()
        known = [(i, p) for i, p in enumerate(z) if not math.isnan(p)]
        if not known:
            return None, "position", "the model's nodes have no positions: give node or at"
        span = max(abs(p) for _, p in known) or 1.0
        for i, p in known:
            if abs(p - position) <= 1e-9 * span:
                return i, "", ""
        listing = ", ".join(f"{p:.6g}" for _, p in known)
        return None, "position", f"is not at a node (nodes at {listing} m)"

    def value_at(self, path: tuple[str | int, ...]) -> tuple[Any, str]:
        """Return the value at a key path, or ``(None, message)`` if the path leads nowhere."""
        node: Any = self
        for k, part in enumerate(path):
            where = format_path(("model", *path[:k])) if k else "model"
            if isinstance(part, int):
                if not isinstance(node, tuple) or part >= len(node):
                    size = len(node) if isinstance(node, tuple) else 0
                    return None, f"{where} has {size} entries: index {part} is out of range"
                node = node[part]
            elif isinstance(node, BaseModel):
                fields = list(type(node).model_fields)
                if part not in fields:
                    hint = did_you_mean(part, fields)
                    return None, (f"{where} has no key '{part}'" + (f"; {hint}" if hint else "")
                                  + f" (keys: {', '.join(fields)})")
                node = getattr(node, part)
            else:
                return None, f"{where} is not a table"
        return node, ""

    def unit_at(self, path: tuple[str | int, ...]) -> str:
        """Return the SI unit of the value at a key path, from its field's description."""
        owner: Any = self
        unit = ""
        for part in path:
            if isinstance(part, int):
                owner = owner[part]
                continue
            info = type(owner).model_fields.get(part) if isinstance(owner, BaseModel) else None
            if info is None:
                return ""
            match = re.search(r"\(([^()]*(?:\([^()]*\))?[^()]*)\)\s*$", info.description or "")
            unit = match[1] if match else ""
            owner = getattr(owner, part)
        return "1" if unit == "-" else unit

    def with_values(self, values: dict[tuple[str | int, ...], float]) -> AbstractLinearModelSpec:
        """Return a copy of the model with the values at the given key paths replaced (SI).

        The copy is validated again, so a value that breaks a rule raises pydantic's
        ``ValidationError``.
        """
        data = plain_data(self.model_dump())
        for path, value in values.items():
            node = data
            for part in path[:-1]:
                node = node[part]
            node[path[-1]] = float(value)
        return type(self).model_validate(data)
