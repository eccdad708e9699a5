"""Complex modal analysis at one speed: eigenvalues, mode shapes, whirl, log decrement."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from rotorlab.linear._eigen import Solver, whirl_of_shapes
from rotorlab.linear._system import LinearSystem

__all__ = ["Modes", "modal", "WHIRL_LABELS", "whirl_labels", "normalize_shapes",
           "log_decrement"]

#: Whirl codes used in results: +1 forward, -1 backward, 0 mixed (or planar).
WHIRL_LABELS = {1: "F", -1: "B", 0: "M"}


def whirl_labels(codes) -> np.ndarray:
    """Map whirl codes (+1, -1, 0) to ``"F"``, ``"B"``, ``"M"`` (same shape).

    Examples
    --------
    >>> whirl_labels([1, -1, 0]).tolist()
    ['F', 'B', 'M']
    """
    c = np.asarray(codes)
    return np.where(c > 0, "F", np.where(c < 0, "B", "M"))


def log_decrement(eigenvalues) -> np.ndarray:
    """Return the logarithmic decrement ``-2 pi Re(lambda) / Im(lambda)`` (1).

    Parameters
    ----------
    eigenvalues : array_like, complex
        With Im >= 0 (1/s). Non-oscillating modes (Im = 0) get ``+inf`` if decaying, ``-inf`` if
        growing, 0 if neither.

    Examples
    --------
    >>> float(log_decrement(-0.1 + 10j))
    0.06283185307179587
    """
    lam = np.asarray(eigenvalues, dtype=complex)
    re, im = lam.real, np.abs(lam.imag)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(im > 0, -2.0 * np.pi * re / np.where(im > 0, im, 1.0),
                       -np.sign(re) * np.inf)
    return np.where((im == 0) & (re == 0), 0.0, out)


def normalize_shapes(shapes: np.ndarray, length_scale: float = 1.0) -> np.ndarray:
    """Scale each shape so that its largest component (tilts times ``length_scale``) is 1.

    Parameters
    ----------
    shapes : ndarray, shape (..., n), complex
    length_scale : float
        Length (m) by which tilts are weighted when looking for the largest component.

    Returns
    -------
    ndarray, shape (..., n)
    """
    w = np.ones(shapes.shape[-1])
    w[2::4] = w[3::4] = length_scale
    k = np.argmax(np.abs(shapes * w), axis=-1)
    pivot = np.take_along_axis(shapes, k[..., None], axis=-1)
    pivot = np.where(pivot == 0, 1.0, pivot)
    return shapes / pivot


@dataclass(frozen=True)
class Modes:
    """Complex modes of a rotor at one spin speed, sorted by frequency.

    Attributes
    ----------
    speed : float
        Spin speed Omega (rad/s).
    eigenvalues : ndarray, shape (m,), complex
        ``lambda = -zeta omega_n + i omega_d`` with ``Im >= 0`` (1/s).
    shapes : ndarray, shape (m, n), complex
        Displacement shapes Q (motion ``Re(Q exp(lambda t))``), largest component 1.
    whirl_index : ndarray, shape (m,)
        +1 pure forward ... -1 pure backward (see :func:`whirl_of_shapes`).
    whirl : ndarray of int8, shape (m,)
        +1 forward, -1 backward, 0 mixed/planar.
    node_position : ndarray, shape (n // 4,)
        Axial node positions (m).
    method : str
        Eigen-solver used.
    """

    speed: float
    eigenvalues: np.ndarray
    shapes: np.ndarray
    whirl_index: np.ndarray
    whirl: np.ndarray
    node_position: np.ndarray
    method: str

    @property
    def frequency(self) -> np.ndarray:
        """Damped natural frequencies ``Im(lambda) / (2 pi)`` (Hz)."""
        return np.abs(self.eigenvalues.imag) / (2.0 * np.pi)

    @property
    def natural_frequency(self) -> np.ndarray:
        """Undamped-equivalent natural frequencies ``|lambda|`` (rad/s)."""
        return np.abs(self.eigenvalues)

    @property
    def damping_ratio(self) -> np.ndarray:
        """``-Re(lambda) / |lambda|`` (1)."""
        mag = np.abs(self.eigenvalues)
        return -self.eigenvalues.real / np.where(mag > 0, mag, 1.0)

    @property
    def log_decrement(self) -> np.ndarray:
        """Logarithmic decrement ``-2 pi Re(lambda) / Im(lambda)`` (1)."""
        return log_decrement(self.eigenvalues)

    @property
    def is_stable(self) -> bool:
        """True when no mode grows (``Re(lambda) <= 1e-9 max|lambda|``)."""
        scale = max(np.abs(self.eigenvalues).max(), 1.0)
        return bool(np.all(self.eigenvalues.real <= 1e-9 * scale))

    @property
    def whirl_label(self) -> np.ndarray:
        """``"F"``, ``"B"`` or ``"M"`` per mode."""
        return whirl_labels(self.whirl)

    def to_dataset(self) -> xr.Dataset:
        """Return the modes as an :class:`xarray.Dataset` with dims ``mode`` and ``dof``."""
        n = self.shapes.shape[1]
        nodes = np.repeat(np.arange(n // 4), 4)
        dirs = np.array(["x", "y", "phi_x", "phi_y"] * (n // 4))
        ds = xr.Dataset(
            {
                "frequency": ("mode", self.frequency, {"units": "Hz",
                                                       "long_name": "damped natural frequency"}),
                "growth_rate": ("mode", self.eigenvalues.real,
                                {"units": "1/s", "long_name": "real part of the eigenvalue"}),
                "log_decrement": ("mode", self.log_decrement, {"units": "1"}),
                "damping_ratio": ("mode", self.damping_ratio, {"units": "1"}),
                "whirl": ("mode", self.whirl, {"units": "1", "flag_values": [1, -1, 0],
                                               "flag_meanings": "forward backward mixed"}),
                "whirl_index": ("mode", self.whirl_index, {"units": "1"}),
                "shape_real": (("mode", "dof"), self.shapes.real, {"units": "m or rad"}),
                "shape_imag": (("mode", "dof"), self.shapes.imag, {"units": "m or rad"}),
            },
            coords={
                "mode": ("mode", np.arange(self.eigenvalues.size), {"units": "1"}),
                "dof": ("dof", np.arange(n), {"units": "1"}),
                "node": ("dof", nodes, {"units": "1"}),
                "direction": ("dof", dirs, {"units": "1"}),
                "node_position": ("dof", np.repeat(self.node_position, 4), {"units": "m"}),
            },
            attrs={"speed": self.speed, "speed_units": "rad/s", "method": self.method,
                   "title": "complex modes"},
        )
        return ds


def modal(system: LinearSystem, speed: float = 0.0, *, n_modes: int | None = None,
          method: str = "auto") -> Modes:
    """Compute the complex modes of a rotor at one spin speed.

    Parameters
    ----------
    system : LinearSystem
    speed : float
        Spin speed Omega (rad/s).
    n_modes : int, optional
        Keep the ``n_modes`` lowest (by ``|lambda|``); default all ``n``.
    method : str
        Eigen-solver (see :mod:`rotorlab.linear._eigen`); ``"auto"`` picks by structure.

    Returns
    -------
    Modes
        Sorted by damped natural frequency.

    Notes
    -----
    Eigenvalues of ``(lambda^2 M + lambda (C + Omega G) + K) Q = 0``; one per conjugate pair.

    References
    ----------
    Friswell et al. (2010), Chapter 5; seed 000 (characteristic determinant of the harmonic
    solution).

    Examples
    --------
    >>> from rotorlab.linear import Bearing, RigidBody, assemble
    >>> s = assemble([RigidBody(0, 1.0, 1e-2), Bearing(0, kxx=1e4, k_tilt_x=1e2)])
    >>> modal(s).frequency.round(4).tolist()  # sqrt(k/m)/2pi and sqrt(k_t/I_d)/2pi, twice
    [15.9155, 15.9155, 15.9155, 15.9155]
    """
    solver = Solver(system, method)
    spec = solver.solve([float(speed)])
    lam, shapes = spec.eigenvalues[0], spec.shapes[0]
    order = np.lexsort((np.abs(lam), np.abs(lam.imag)))
    if n_modes is not None:
        if int(n_modes) != n_modes or not 1 <= n_modes <= lam.size:
            raise ValueError(f"n_modes must be an integer in [1, {lam.size}], got {n_modes!r}")
        keep = np.argsort(np.abs(lam), kind="stable")[: int(n_modes)]
        order = keep[np.lexsort((np.abs(lam[keep]), np.abs(lam[keep].imag)))]
    lam, shapes = lam[order], shapes[order]
    L = system.length_scale
    shapes = normalize_shapes(shapes, L)
    index, code = whirl_of_shapes(shapes, L)
    return Modes(speed=float(speed), eigenvalues=lam, shapes=shapes, whirl_index=index,
                 whirl=code, node_position=np.array(system.node_position), method=solver.method)
