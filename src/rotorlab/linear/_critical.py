"""Critical speeds of the undamped rotor, exactly, from one eigenproblem per harmonic."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import xarray as xr

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear._eigen import whirl_of_shapes
from rotorlab.linear._modal import normalize_shapes
from rotorlab.linear._system import LinearSystem

__all__ = ["CriticalSpeeds", "critical_speeds"]


@dataclass(frozen=True)
class CriticalSpeeds:
    """Spin speeds at which a natural frequency equals a multiple of the spin speed.

    Attributes
    ----------
    speed : ndarray, shape (k,)
        Critical speeds Omega_c (rad/s), ascending.
    harmonic : ndarray of int, shape (k,)
        The excitation order h: ``omega = h Omega_c``.
    whirl : ndarray of int8, shape (k,)
        +1 forward, -1 backward, 0 mixed.
    shapes : ndarray, shape (k, n), complex
        The mode shapes at the critical speeds.
    """

    speed: np.ndarray
    harmonic: np.ndarray
    whirl: np.ndarray
    shapes: np.ndarray

    @property
    def speed_rpm(self) -> np.ndarray:
        """Critical speeds in rev/min."""
        return self.speed * RPM_PER_RAD_S

    def to_dataset(self) -> xr.Dataset:
        """Return an :class:`xarray.Dataset` with dim ``critical``."""
        return xr.Dataset(
            {
                "critical_speed": ("critical", self.speed, {"units": "rad/s"}),
                "critical_speed_rpm": ("critical", self.speed_rpm, {"units": "rev/min"}),
                "harmonic": ("critical", self.harmonic, {"units": "1"}),
                "whirl": ("critical", self.whirl, {"units": "1", "flag_values": [1, -1, 0],
                                                   "flag_meanings": "forward backward mixed"}),
            },
            attrs={"title": "critical speeds of the undamped rotor"},
        )


def critical_speeds(system: LinearSystem, *, harmonics: Sequence[int] = (1,),
                    max_speed: float | None = None) -> CriticalSpeeds:
    """Compute the critical speeds of the undamped rotor exactly.

    Parameters
    ----------
    system : LinearSystem
        Its damping C is ignored.
    harmonics : sequence of int
        Excitation orders h >= 1 (1: synchronous unbalance).
    max_speed : float, optional
        Drop critical speeds above this (rad/s).

    Returns
    -------
    CriticalSpeeds

    Notes
    -----
    A free vibration ``q = u exp(i h Omega t)`` of ``M q'' + Omega G q' + K q = 0`` satisfies
    ``K u = Omega^2 (h^2 M - i h G) u``. The right-hand matrix is Hermitian, so with K
    symmetric positive definite this is a Hermitian-definite pencil ``(h^2 M - i h G) u = mu K
    u`` with real ``mu = 1 / Omega^2``: every positive ``mu`` is a critical speed, and a mode
    whose ``mu <= 0`` (e.g. the forward tilting mode of a disc with ``I_p > I_d``) never meets
    the line. No speed grid, no interpolation. A non-symmetric or singular K falls back to the
    general pencil.

    References
    ----------
    Friswell et al. (2010), Chapters 3 and 5 (critical speeds from the undamped model);
    seed 000 (resonances at the crossings of the Campbell diagram).

    Examples
    --------
    >>> from rotorlab.linear import Bearing, RigidBody, assemble
    >>> s = assemble([RigidBody(0, 2.0, 1e-3), Bearing(0, kxx=800.0, k_tilt_x=1.0)])
    >>> critical_speeds(s).speed.round(6).tolist()  # sqrt(k/m) = 20 rad/s, twice
    [20.0, 20.0, 31.622777, 31.622777]
    """
    hs = tuple(int(h) for h in harmonics)
    if not hs or any(h < 1 for h in hs):
        raise ValueError(f"harmonics must be integers >= 1, got {tuple(harmonics)!r}")
    K, M, G = system.K, system.M, system.G
    sym = np.abs(K - K.T).max() <= 1e-12 * max(np.abs(K).max(), 1e-300)
    with single_threaded_blas():
        speed, harmonic, shp = _pencils(K, M, G, hs, sym)
    keep = np.ones(speed.size, bool) if max_speed is None else speed <= float(max_speed)
    order = np.argsort(speed[keep], kind="stable")
    speed, harmonic, shp = speed[keep][order], harmonic[keep][order], shp[keep][order]
    if not speed.size:  # none (up to max_speed)
        return CriticalSpeeds(speed=speed, harmonic=harmonic, whirl=np.zeros(0, np.int8), shapes=shp)
    L = system.length_scale
    shp = normalize_shapes(shp, L)
    _, code = whirl_of_shapes(shp, L)
    return CriticalSpeeds(speed=speed, harmonic=harmonic, whirl=code, shapes=shp)


def _pencils(K, M, G, hs, sym):
    speeds, harm, shapes = [], [], []
    for h in hs:
        B = h * h * M - 1j * h * G
        om2, U = None, None
        if sym:
            try:
                mu, U = scipy.linalg.eigh(B, K)
                ok = mu > 1e-14 * np.abs(mu).max()
                om2, U = 1.0 / mu[ok], U[:, ok]
            except np.linalg.LinAlgError:
                om2 = None
        if om2 is None:
            ev, U = scipy.linalg.eig(K, B)
            ok = np.isfinite(ev) & (ev.real > 0) & (np.abs(ev.imag) <= 1e-8 * np.abs(ev))
            om2, U = ev[ok].real, U[:, ok]
        speeds.append(np.sqrt(om2))
        harm.append(np.full(om2.size, h))
        shapes.append(U.T)
    return (np.concatenate(speeds), np.concatenate(harm).astype(np.int64),
            np.concatenate(shapes, axis=0))
