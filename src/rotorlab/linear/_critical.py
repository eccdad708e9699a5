"""Critical speeds: undamped (exactly, one eigenproblem per harmonic) and damped crossings.

Two definitions are in use and they differ with damping: the *undamped* critical speed, where a
natural frequency of the rotor without its damping equals h times the spin speed, and the
*damped crossing*, where a damped natural frequency ``Im lambda`` of the rotor as it is meets the
h x line of the Campbell diagram. Every result here says which it gives, gives both where they
differ, with the mode's damping ratio at the crossing, and whether unbalance excites the mode:
unbalance is a forward 1x force, so on isotropic supports it excites forward whirl only
(Friswell et al. 2010, Sections 3.5 and 5.9); on anisotropic supports the whirl is elliptical
and a backward mode responds too.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import xarray as xr

from rotorlab._constants import RPM_PER_RAD_S
from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear._eigen import Solver, whirl_of_shapes
from rotorlab.linear._modal import normalize_shapes
from rotorlab.linear._system import LinearSystem

__all__ = ["CriticalSpeeds", "critical_speeds", "excited_by_unbalance", "NOT_EXCITED_NOTE",
           "DEFINITIONS"]

#: How each kind of critical speed is defined (the text every output carries).
DEFINITIONS = {
    "undamped": "undamped: a natural frequency of the rotor without damping equals h x speed",
    "damped crossing": "damped crossing: a damped natural frequency (Im lambda) meets the h x line "
                       "of the Campbell diagram",
}
#: The note on a critical speed that unbalance cannot excite.
NOT_EXCITED_NOTE = "not excited by unbalance on isotropic supports"


def excited_by_unbalance(whirl, harmonic, isotropic: bool) -> np.ndarray:
    """Return whether unbalance excites each critical speed.

    Unbalance is a synchronous force turning with the rotor: it drives the 1x line only, and on
    isotropic supports (``x + i y`` decouples) only forward whirl. On anisotropic supports the
    modes whirl elliptically and backward modes respond too.

    Examples
    --------
    >>> excited_by_unbalance([1, -1, 1], [1, 1, 2], isotropic=True).tolist()
    [True, False, False]
    >>> excited_by_unbalance([1, -1], [1, 1], isotropic=False).tolist()
    [True, True]
    """
    w, h = np.asarray(whirl), np.asarray(harmonic)
    return (h == 1) & ((w != -1) | (not isotropic))


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
    damped_speed : ndarray, shape (k,)
        The damped crossing of the same mode (rad/s): where its damped natural frequency
        ``Im lambda`` of the rotor with its damping meets the line; NaN where the mode does not
        reach the line (overdamped). Equal to ``speed`` without damping.
    damping_ratio : ndarray, shape (k,)
        The mode's damping ratio ``-Re lambda / |lambda|`` at the damped crossing.
    excited : ndarray of bool, shape (k,)
        Whether unbalance excites it (:func:`excited_by_unbalance`).
    isotropic : bool
        Whether the rotor is isotropic (then backward whirl is not excited by unbalance).
    """

    speed: np.ndarray
    harmonic: np.ndarray
    whirl: np.ndarray
    shapes: np.ndarray
    damped_speed: np.ndarray
    damping_ratio: np.ndarray
    excited: np.ndarray
    isotropic: bool

    @property
    def speed_rpm(self) -> np.ndarray:
        """Critical speeds in rev/min."""
        return self.speed * RPM_PER_RAD_S

    #: What ``speed`` is (see :data:`DEFINITIONS`); ``damped_speed`` is the "damped crossing".
    definition = "undamped"

    @property
    def damped_speed_rpm(self) -> np.ndarray:
        """Damped crossings in rev/min."""
        return self.damped_speed * RPM_PER_RAD_S

    def to_dataset(self) -> xr.Dataset:
        """Return an :class:`xarray.Dataset` with dim ``critical``.

        ``critical_speed`` (rad/s) and ``critical_speed_rpm`` are the undamped critical speeds
        (attribute ``definition``); ``damped_crossing_rpm`` and ``damping_ratio`` the damped
        crossing of the same mode; ``excited_by_unbalance`` a flag.
        """
        und = {"definition": DEFINITIONS["undamped"]}
        return xr.Dataset(
            {
                "critical_speed": ("critical", self.speed, {"units": "rad/s", **und}),
                "critical_speed_rpm": ("critical", self.speed_rpm, {"units": "rev/min", **und}),
                "damped_crossing_rpm": ("critical", self.damped_speed_rpm, {
                    "units": "rev/min", "definition": DEFINITIONS["damped crossing"]}),
                "damping_ratio": ("critical", self.damping_ratio, {
                    "units": "1", "long_name": "damping ratio of the mode at the damped crossing"}),
                "excited_by_unbalance": ("critical", self.excited, {
                    "units": "1", "long_name": "unbalance excites the mode"}),
                "harmonic": ("critical", self.harmonic, {"units": "1"}),
                "whirl": ("critical", self.whirl, {"units": "1", "flag_values": [1, -1, 0],
                                                   "flag_meanings": "forward backward mixed"}),
            },
            attrs={"title": "critical speeds (undamped, with the damped crossings)",
                   "definition": "undamped", "isotropic": int(self.isotropic)},
        )


def critical_speeds(system: LinearSystem, *, harmonics: Sequence[int] = (1,),
                    max_speed: float | None = None, damped: bool = True) -> CriticalSpeeds:
    """Compute the critical speeds of the undamped rotor exactly.

    Parameters
    ----------
    system : LinearSystem
        Its damping C is ignored.
    harmonics : sequence of int
        Excitation orders h >= 1 (1: synchronous unbalance).
    max_speed : float, optional
        Drop critical speeds above this (rad/s).
    damped : bool
        Also find each mode's damped crossing (a few eigen-solves per critical speed); false:
        ``damped_speed`` and ``damping_ratio`` are NaN.

    Returns
    -------
    CriticalSpeeds
        The undamped critical speeds, ascending, each with the damped crossing of its mode,
        the mode's damping ratio there and whether unbalance excites it.

    Notes
    -----
    A free vibration ``q = u exp(i h Omega t)`` of ``M q'' + Omega G q' + K q = 0`` satisfies
    ``K u = Omega^2 (h^2 M - i h G) u``. The right-hand matrix is Hermitian, so with K
    symmetric positive definite this is a Hermitian-definite pencil ``(h^2 M - i h G) u = mu K
    u`` with real ``mu = 1 / Omega^2``: every positive ``mu`` is a critical speed, and a mode
    whose ``mu <= 0`` (e.g. the forward tilting mode of a disc with ``I_p > I_d``) never meets
    the line. No speed grid, no interpolation. A non-symmetric or singular K falls back to the
    general pencil. The damped crossing of each mode is then found from there by the secant
    method on ``|Im lambda(Omega)| - h Omega`` of the damped rotor, the mode followed by its shape
    (MAC), to 1e-10 relative.

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
    iso = bool(system.is_isotropic)
    if not speed.size:  # none (up to max_speed)
        empty = np.zeros(0)
        return CriticalSpeeds(speed=speed, harmonic=harmonic, whirl=np.zeros(0, np.int8), shapes=shp,
                              damped_speed=empty, damping_ratio=empty, excited=np.zeros(0, bool),
                              isotropic=iso)
    L = system.length_scale
    shp = normalize_shapes(shp, L)
    _, code = whirl_of_shapes(shp, L)
    if damped:
        solver = Solver(system)
        with single_threaded_blas():
            damped = np.array([_damped_crossing(solver, w, u, h) for w, u, h in zip(speed, shp, harmonic)])
    else:
        damped = np.full((speed.size, 2), np.nan)
    return CriticalSpeeds(speed=speed, harmonic=harmonic, whirl=code, shapes=shp,
                          damped_speed=damped[:, 0], damping_ratio=damped[:, 1],
                          excited=excited_by_unbalance(code, harmonic, iso), isotropic=iso)


def _damped_crossing(solver: Solver, speed0: float, shape0: np.ndarray, h: int) -> tuple[float, float]:
    """The damped crossing of the mode of shape ``shape0`` at undamped critical speed ``speed0``.

    Secant iterations on ``g(Omega) = |Im lambda(Omega)| - h Omega`` from ``speed0``, the mode
    picked by MAC of the full shapes against ``shape0`` first and its own previous shape after.
    Returns (NaN, NaN) if it does not converge in 40 steps or the mode stops oscillating.
    """
    def branch(x: float, ref: np.ndarray, freq: float):
        # the mode by MAC of the full shapes (a forward and a backward mode can share the
        # solver's tracking vector); among equally similar shapes the nearest in frequency
        sp = solver.solve([x])
        v = sp.shapes[0]
        mac = np.abs(v.conj() @ ref) ** 2 / np.maximum(np.einsum("ij,ij->i", v.conj(), v).real, 1e-300)
        mac = mac / max(mac.max(), 1e-300)
        near = np.abs(np.abs(sp.eigenvalues[0].imag) - freq)
        k = int(np.argmin(np.where(mac >= 1.0 - 1e-6, near, np.inf)))
        lam = sp.eigenvalues[0, k]
        shape = v[k] / max(np.linalg.norm(v[k]), 1e-300)
        return abs(lam.imag) - h * x, shape, lam

    g0, ref, lam = branch(speed0, shape0 / max(np.linalg.norm(shape0), 1e-300), h * speed0)
    x0, x1 = speed0, speed0 * (1.0 + 1e-4)
    g1, ref, lam = branch(x1, ref, abs(lam.imag))
    for _ in range(40):
        if g1 == g0:
            break
        x2 = x1 - g1 * (x1 - x0) / (g1 - g0)
        if not np.isfinite(x2) or x2 <= 0:
            break
        x0, g0 = x1, g1
        x1 = x2
        g1, ref, lam = branch(x1, ref, abs(lam.imag))
        if abs(x1 - x0) <= 1e-10 * x1:
            if lam.imag == 0:
                break
            zeta = float(-lam.real / abs(lam))
            return float(x1), (0.0 if abs(zeta) < 1e-12 else zeta)
    return float("nan"), float("nan")


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
