"""Build the :class:`rotorlab.linear.LinearSystem` of a validated linear model spec.

``multibody`` specs become rigid bodies, one node each, joined by an
:class:`~rotorlab.linear.ElasticConnection` (from the compliance matrix inverted, the stiffness
matrix, or the compliance of a shaft-in-housing geometry) and ground bearings; ``fe_rotor``
specs become Timoshenko shaft elements, rigid discs and bearings. The element order and the
arithmetic are those of the Python builders in :mod:`rotorlab.linear.cases`, so a case file
and a builder with the same data give the same matrices.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from rotorlab.linear import LinearSystem

__all__ = ["build_linear_system", "influence_model"]


def influence_model(spec: Any) -> Any:
    """Return the :class:`rotorlab.linear.InfluenceModel` of a multibody spec's geometry.

    Parameters
    ----------
    spec : rotorlab.io.MultibodySpec
        With ``elastic.geometry`` given.

    Returns
    -------
    rotorlab.linear.InfluenceModel
        Stations: the connected bodies, in the order of ``elastic.bodies``.
    """
    from rotorlab.linear import HousingSupport, InfluenceModel, ShaftSpan, ShaftSupport

    elastic = spec.elastic
    geo = elastic.geometry
    by_name = {b.name: b for b in spec.bodies}
    stations = [by_name[n] for n in (elastic.bodies or by_name)]
    supports = []
    for s in geo.supports:
        if s.kind == "clamped":
            supports.append(ShaftSupport.clamp(s.position))
        else:
            k = s.stiffness if s.kind == "elastic" else math.inf
            supports.append(ShaftSupport(s.position, k, s.tilt_stiffness))
    housing = None if geo.housing is None else HousingSupport(
        geo.housing.position, geo.housing.translational_stiffness,
        geo.housing.rotational_stiffness)
    return InfluenceModel(
        station_position=tuple(b.position for b in stations),
        station_on_shaft=tuple(b.on_shaft for b in stations),
        spans=tuple(ShaftSpan(s.start, s.end, s.flexural_rigidity) for s in geo.spans),
        shaft_supports=tuple(supports),
        housing_support=housing,
    )


def _multibody(spec: Any) -> LinearSystem:
    from rotorlab.linear import (
        Bearing,
        ElasticConnection,
        RigidBody,
        assemble,
        compliance_to_stiffness,
        influence_compliance,
    )

    index = {b.name: i for i, b in enumerate(spec.bodies)}
    elements: list[Any] = [
        RigidBody(i, b.mass, b.diametral_inertia, b.polar_inertia, spinning=b.spinning)
        for i, b in enumerate(spec.bodies)
    ]
    elastic = spec.elastic
    if elastic is not None:
        nodes = tuple(index[n] for n in (elastic.bodies or index))
        if elastic.source == "geometry":
            planes = [compliance_to_stiffness(influence_compliance(influence_model(spec)))]
        elif elastic.source == "compliance":
            planes = [compliance_to_stiffness(np.array(a)) for a in elastic.matrices()]
        else:
            planes = [0.5 * (np.array(a) + np.array(a).T) for a in elastic.matrices()]
        damping = [0.5 * (np.array(a) + np.array(a).T) for a in elastic.matrices("damping")]
        elements.append(ElasticConnection(nodes=nodes, stiffness_x=planes[0],
                                          stiffness_y=planes[1] if len(planes) > 1 else None,
                                          damping_x=damping[0] if damping else None,
                                          damping_y=damping[1] if len(damping) > 1 else None))
    elements += [Bearing(node=index[b.body], **b.coefficients()) for b in spec.bearings]
    return assemble(elements, n_nodes=len(spec.bodies), node_position=spec.node_positions(),
                    node_label=spec.node_labels())


def _fe_rotor(spec: Any) -> LinearSystem:
    from rotorlab.linear import Bearing, Material, RigidBody, assemble, uniform_shaft

    def material(m: Any) -> Material:
        return Material(youngs_modulus=m.youngs_modulus, shear_modulus=m.shear_modulus,
                        density=m.density)

    elements: list[Any] = []
    added = spec.refinement()  # nodes inserted so that discs and bearings sit on nodes
    node, start = 0, 0.0
    for section in spec.shaft:
        kw = {"inner_diameter": section.inner_diameter,
              "material": material(section.material or spec.material), "shear": spec.shear,
              "rotary_inertia": spec.rotary_inertia, "gyroscopic": spec.gyroscopic}
        le = section.length / section.elements
        inside = [z - start for z in added if start < z < start + section.length]
        if not inside:  # the section as written: equal elements
            elements += uniform_shaft(section.elements, section.length, section.outer_diameter,
                                      first_node=node, **kw)
            node += section.elements
        else:  # the written nodes and the inserted ones, in order
            cuts = sorted({*(le * k for k in range(section.elements + 1)), *inside})
            for a, b in zip(cuts[:-1], cuts[1:], strict=True):
                elements += uniform_shaft(1, b - a, section.outer_diameter, first_node=node, **kw)
                node += 1
        start += section.length
    for d in spec.discs:
        at = spec.node_of(d)
        if d.mass is not None:
            elements.append(RigidBody(at, d.mass, d.diametral_inertia, d.polar_inertia or 0.0))
        else:
            rho = d.density if d.density is not None else spec.material.density
            elements.append(RigidBody.disc(at, d.outer_diameter, d.width, rho,
                                           inner_diameter=d.inner_diameter))
    elements += [Bearing(node=spec.node_of(b), **b.coefficients()) for b in spec.bearings]
    return assemble(elements, n_nodes=node + 1, node_label=spec.node_labels())


def build_linear_system(spec: Any) -> LinearSystem:
    """Build the linear system ``M q'' + (C + Omega G) q' + K q = f`` of a linear model spec.

    Parameters
    ----------
    spec : rotorlab.io.MultibodySpec or rotorlab.io.FeRotorSpec
        A validated ``[model]`` table (SI values).

    Returns
    -------
    rotorlab.linear.LinearSystem
        Nodes in the order of the spec (bodies; shaft nodes from z = 0), labelled as
        :meth:`~rotorlab.io.AbstractLinearModelSpec.node_labels` says.

    Raises
    ------
    ValueError
        ``spec`` is not a linear model spec.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> s = build_linear_system(load_case("friswell-rotor").model)
    >>> s.n_nodes, round(s.total_mass, 2)
    (7, 107.12)
    """
    from rotorlab.io._built import built_once, handed_down_structure
    from rotorlab.linear import LinearSystem

    built = handed_down_structure(spec)
    if built is not None:  # the run's machine's structure (rotorlab.io._built)
        return built
    return built_once(spec, _linear_system, LinearSystem)  # built once per spec object


#: the builder (a function of this module, looked up when called) of each linear model type
_LINEAR_BUILDERS = {"multibody": "_multibody", "fe_rotor": "_fe_rotor"}


def _linear_system(spec: Any) -> Any:
    kind = getattr(spec, "type", None)
    if kind not in _LINEAR_BUILDERS:
        raise ValueError(f"model type {kind!r} is not a linear rotor model "
                         f"(linear models: {', '.join(_LINEAR_BUILDERS)})")
    return globals()[_LINEAR_BUILDERS[kind]](spec)
