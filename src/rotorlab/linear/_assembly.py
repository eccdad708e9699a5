"""Assembly of element matrices into a :class:`~rotorlab.linear.LinearSystem`."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from rotorlab.linear._elements import AbstractElement
from rotorlab.linear._shaft import STEEL, Material, ShaftElement
from rotorlab.linear._system import LinearSystem

__all__ = ["assemble", "uniform_shaft"]


def assemble(elements: Iterable[AbstractElement], *, n_nodes: int | None = None,
             node_position: Sequence[float] | None = None,
             node_label: Sequence[str] | None = None) -> LinearSystem:
    """Add the elements' M, C, G, K into global matrices.

    Parameters
    ----------
    elements : iterable of elements
        Objects following :class:`~rotorlab.linear.AbstractElement` (shaft elements, rigid
        bodies, bearings, elastic connections, or your own).
    n_nodes : int, optional
        Number of nodes; default one more than the largest node used.
    node_position : sequence of float, optional
        Axial position of each node (m). Default: from the shaft elements' lengths when they
        form one chain starting at node 0, else unknown (NaN).
    node_label : sequence of str, optional
        Name of each node.

    Returns
    -------
    LinearSystem

    Raises
    ------
    ValueError
        If an element returns a matrix of the wrong shape, an element's M is not symmetric or its
        G not skew-symmetric, or a node has no mass (M singular).

    Examples
    --------
    >>> from rotorlab.linear import Bearing, RigidBody
    >>> s = assemble([RigidBody(0, 2.0, 1e-3), Bearing(0, kxx=800.0, k_tilt_x=1.0)])
    >>> s.M.diagonal(), s.K.diagonal()
    (array([2.e+00, 2.e+00, 1.e-03, 1.e-03]), array([800., 800.,   1.,   1.]))
    """
    elements = list(elements)
    if not elements:
        raise ValueError("assemble needs at least one element")
    used = max(max(e.nodes) for e in elements) + 1
    nn = used if n_nodes is None else int(n_nodes)
    if nn < used:
        raise ValueError(f"n_nodes = {nn} but the elements use node {used - 1}")
    n = 4 * nn
    mats = {name: np.zeros((n, n)) for name in ("M", "C", "G", "K")}
    for e in elements:
        dofs = (4 * np.asarray(e.nodes)[:, None] + np.arange(4)).reshape(-1)
        size = dofs.size
        for name, a in mats.items():
            local = np.asarray(getattr(e, name)(), dtype=float)
            if local.shape != (size, size):
                raise ValueError(f"{type(e).__name__}.{name}() must have shape {(size, size)}, "
                                 f"got {local.shape}")
            scale = max(np.abs(local).max(), 1e-300)
            if name == "M" and np.abs(local - local.T).max() > 1e-10 * scale:
                raise ValueError(f"{type(e).__name__}.M() must be symmetric")
            if name == "G" and np.abs(local + local.T).max() > 1e-10 * scale:
                raise ValueError(f"{type(e).__name__}.G() must be skew-symmetric")
            a[np.ix_(dofs, dofs)] += local
    if node_position is None:
        node_position = _chain_positions(elements, nn)
    return LinearSystem(M=mats["M"], C=mats["C"], G=mats["G"], K=mats["K"],
                        node_position=node_position,
                        node_label=None if node_label is None else tuple(node_label))


def _chain_positions(elements, nn: int) -> np.ndarray:
    pos = np.full(nn, np.nan)
    shafts = sorted((e for e in elements if isinstance(e, ShaftElement)), key=lambda e: e.node)
    if shafts and shafts[0].node == 0 and all(
            b.node == a.node + 1 for a, b in zip(shafts[:-1], shafts[1:])):
        pos[0] = 0.0
        for e in shafts:
            pos[e.node + 1] = pos[e.node] + e.length
    return pos


def uniform_shaft(n_elements: int, length: float, outer_diameter: float, *,
                  inner_diameter: float = 0.0, material: Material = STEEL,
                  first_node: int = 0, shear: bool = True, rotary_inertia: bool = True,
                  gyroscopic: bool = True) -> tuple[ShaftElement, ...]:
    """Return a shaft of equal Timoshenko elements.

    Parameters
    ----------
    n_elements : int
        Number of elements (>= 1); the shaft spans nodes ``first_node .. first_node +
        n_elements``.
    length : float
        Total length (m).
    outer_diameter, inner_diameter : float
        Section (m).
    material : Material
    first_node : int
    shear, rotary_inertia, gyroscopic : bool
        Passed to every :class:`ShaftElement`.

    Returns
    -------
    tuple of ShaftElement

    Examples
    --------
    >>> [e.node for e in uniform_shaft(3, 1.5, 0.05)]
    [0, 1, 2]
    """
    if int(n_elements) != n_elements or n_elements < 1:
        raise ValueError(f"n_elements must be an integer >= 1, got {n_elements!r}")
    le = float(length) / int(n_elements)
    return tuple(ShaftElement(node=first_node + i, length=le, outer_diameter=outer_diameter,
                              inner_diameter=inner_diameter, material=material, shear=shear,
                              rotary_inertia=rotary_inertia, gyroscopic=gyroscopic)
                 for i in range(int(n_elements)))
