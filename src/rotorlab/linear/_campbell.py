"""Campbell diagram: natural frequencies versus spin speed, tracked, with critical speeds."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.optimize
import xarray as xr

from rotorlab._constants import RAD_S_PER_RPM
from rotorlab.linear._critical import DEFINITIONS, critical_speeds, excited_by_unbalance
from rotorlab.linear._eigen import Solver, Spectrum, whirl_of_shapes
from rotorlab.linear._modal import log_decrement, normalize_shapes
from rotorlab.linear._system import LinearSystem

__all__ = ["campbell", "track_modes", "RPM"]

#: rad/s per rev/min.
RPM = RAD_S_PER_RPM


def track_modes(track: np.ndarray, eigenvalues: np.ndarray, n_modes: int) -> np.ndarray:
    """Follow modes across speeds by their shapes (MAC), not by sorting frequencies.

    Parameters
    ----------
    track : ndarray, shape (S, m, p), complex
        Unit vectors of the m candidate modes at each of S speeds.
    eigenvalues : ndarray, shape (S, m), complex
        Their eigenvalues (1/s), used to pick the ``n_modes`` lowest at the first speed and to
        break ties between equally similar shapes.
    n_modes : int
        Number of branches to follow.

    Returns
    -------
    ndarray of int, shape (S, n_modes)
        ``order[s, k]``: the candidate at speed s that continues branch k.

    Notes
    -----
    Between neighbouring speeds the modal assurance criterion ``MAC_ij = |u_i^H v_j|^2`` of
    every tracked branch against every candidate is computed in one batched product, and the
    one-to-one assignment maximising the total MAC is taken (Hungarian algorithm), with a small
    penalty on the frequency jump to decide between degenerate shapes. Where two branches cross
    their shapes stay distinct, so the branches pass through each other instead of swapping as
    sorting by frequency would make them.

    References
    ----------
    Friswell et al. (2010), Chapter 5 (ordering eigenvalues by MAC in Campbell diagrams).
    """
    S, m, _ = track.shape
    if int(n_modes) != n_modes or not 1 <= n_modes <= m:
        raise ValueError(f"n_modes must be an integer in [1, {m}], got {n_modes!r}")
    n_modes = int(n_modes)
    mag = np.abs(eigenvalues)
    order = np.empty((S, n_modes), dtype=np.intp)
    order[0] = np.argsort(mag[0], kind="stable")[:n_modes]
    if S == 1:
        return order
    mac = np.abs(np.matmul(track[:-1].conj(), track[1:].transpose(0, 2, 1))) ** 2
    scale = np.maximum(mag.max(axis=1), 1e-300)
    for s in range(S - 1):
        cur = order[s]
        jump = np.abs(mag[s + 1][None, :] - mag[s, cur][:, None]) / scale[s]
        cost = (1.0 - mac[s][cur, :]) + 0.1 * jump
        rows, cols = scipy.optimize.linear_sum_assignment(cost)
        order[s + 1, rows] = cols
    return order


def _refine(solver: Solver, lo: float, hi: float, guess: float, ref: np.ndarray,
            harmonic: int) -> float:
    """Root of ``omega_branch(Omega) - h Omega`` in [lo, hi], the branch picked by MAC.

    Newton's method with the exact eigenvalue derivative where the solver has one (Hermitian
    methods: 3-4 eigen-solves), else Brent's method.
    """

    def branch(speed: float):
        sp = solver.solve([speed])
        mac = np.abs(sp.track[0].conj() @ ref) ** 2
        # a forward and a backward mode can share a tracking vector (a rigid body's tilt in the
        # isotropic solver): among equally similar ones, the nearest to the line
        near = np.abs(np.abs(sp.eigenvalues[0].imag) - harmonic * speed)
        k = int(np.argmin(np.where(mac >= mac.max() * (1.0 - 1e-6), near, np.inf)))
        return float(abs(sp.eigenvalues[0, k].imag)) - harmonic * speed, sp.track[0, k]

    x = guess
    for _ in range(12):
        gx, z = branch(x)
        slope = solver.frequency_slope(x, z[None, :])
        if slope is None:
            break
        step = gx / (float(slope[0]) - harmonic)
        x_new = x - step
        if not lo <= x_new <= hi:
            break
        if abs(step) <= 1e-13 * max(abs(x), 1.0):
            return x_new
        x = x_new

    def g(speed: float) -> float:
        return branch(speed)[0]

    glo, ghi = g(lo), g(hi)
    if glo == 0.0:
        return lo
    if ghi == 0.0 or glo * ghi > 0:
        return hi if ghi == 0.0 else np.nan
    return float(scipy.optimize.brentq(g, lo, hi, xtol=1e-12 * max(hi, 1.0), rtol=1e-13))


def _zeta_at(solver: Solver, speed: float, ref: np.ndarray) -> float:
    """Damping ratio -Re lambda / |lambda| of the mode of track vector ``ref`` at ``speed``."""
    sp = solver.solve([speed])
    lam = sp.eigenvalues[0, int(np.argmax(np.abs(sp.track[0].conj() @ ref) ** 2))]
    return float(-lam.real / abs(lam)) + 0.0 if lam != 0 else float("nan")


def _undamped_partners(system: LinearSystem, cross, harmonics) -> tuple[np.ndarray, np.ndarray]:
    """The undamped critical speed of each damped crossing's mode (NaN if none matches) and
    whether unbalance excites it, from :func:`critical_speeds` (the crossing matched to the damped
    crossing it computes from the undamped mode, to 1e-6 relative)."""
    und = np.full(len(cross), np.nan)
    if not cross:
        return und, np.zeros(0, bool)
    # the undamped partner of a crossing lies near it: modes up to twice the highest crossing
    cs = critical_speeds(system, harmonics=harmonics, max_speed=2.0 * max(c[0] for c in cross))
    for i, (root, h, _, w, _) in enumerate(cross):
        ok = (cs.harmonic == h) & np.isfinite(cs.damped_speed)
        if ok.any():
            j = np.flatnonzero(ok)[np.argmin(np.abs(cs.damped_speed[ok] - root))]
            if abs(cs.damped_speed[j] - root) <= 1e-6 * root:
                und[i] = cs.speed[j]
    exc = excited_by_unbalance([c[3] for c in cross], [c[1] for c in cross], cs.isotropic)
    return und, exc


def _crossings(speeds, lam, whirl, track, harmonics, solver, refine):
    out = []
    omega = np.abs(lam.imag)
    for h in harmonics:
        g = omega - h * speeds[:, None]
        for k in range(lam.shape[1]):
            gk = g[:, k]
            idx = np.flatnonzero((gk[:-1] > 0) & (gk[1:] <= 0) | (gk[:-1] < 0) & (gk[1:] >= 0))
            for s in idx:
                lo, hi = speeds[s], speeds[s + 1]
                root = lo - gk[s] * (hi - lo) / (gk[s + 1] - gk[s])
                if refine:
                    r = _refine(solver, lo, hi, root, track[s, k], h)
                    root = r if np.isfinite(r) else root
                w = whirl[s, k] if whirl[s, k] == whirl[s + 1, k] else whirl[s + 1, k]
                out.append((root, h, k, w, _zeta_at(solver, root, track[s, k])))
    out.sort(key=lambda t: (t[0], t[1], t[2]))
    return out


def campbell(system: LinearSystem, speeds: Sequence[float], *, n_modes: int = 6,
             harmonics: Sequence[int] = (1,), method: str = "auto", refine: bool = True,
             shapes: bool = False) -> xr.Dataset:
    """Compute a Campbell diagram: tracked natural frequencies versus spin speed.

    Parameters
    ----------
    system : LinearSystem
    speeds : sequence of float
        Spin speeds Omega (rad/s), increasing; use ``RPM * rpm`` to convert from rev/min.
    n_modes : int
        Number of branches, the lowest at the first speed.
    harmonics : sequence of int
        Excitation lines ``n x`` whose crossings with the branches are reported as critical
        speeds (1 = synchronous).
    method : str
        Eigen-solver (see :mod:`rotorlab.linear._eigen`); ``"auto"`` picks by structure.
    refine : bool
        Refine each crossing to machine precision by root-finding on the tracked branch
        (otherwise linear interpolation between grid speeds).
    shapes : bool
        Also return the mode shapes (``shape_real``, ``shape_imag`` over ``dof``).

    Returns
    -------
    xarray.Dataset
        Dims ``speed`` (coordinate in rad/s, with ``speed_rpm``), ``mode`` and ``critical``.
        Variables: ``frequency`` (Hz, damped natural frequency), ``growth_rate`` (1/s, Re
        lambda), ``log_decrement``, ``damping_ratio``, ``whirl`` (+1 F, -1 B, 0 mixed),
        ``whirl_index``, ``stable`` (every mode of the system, tracked or not, decays or is
        neutral), and per crossing ``critical_speed`` (rad/s), ``critical_speed_rpm`` (the
        damped crossing: where the damped natural frequency meets the line),
        ``critical_undamped_rpm`` (the undamped critical speed of the same mode),
        ``critical_damping_ratio`` (of the mode at the crossing),
        ``critical_excited_by_unbalance``,
        ``critical_frequency`` (Hz), ``critical_harmonic``, ``critical_mode``,
        ``critical_whirl``.

    Notes
    -----
    Branches are followed by mode shape (:func:`track_modes`), so a forward and a backward
    branch that cross keep their identity. For isotropic conservative rotors the default
    solver separates forward from backward whirl exactly (sign of the frequency in the complex
    coordinate ``x + i y``).

    References
    ----------
    Seed 000 (Campbell diagram of the Pico 21 centrifuge, Fig. 7); Friswell et al. (2010),
    Chapters 3 and 5 (Campbell diagrams, critical speeds as crossings with the 1x line).

    Examples
    --------
    >>> from rotorlab.linear import Bearing, RigidBody, assemble
    >>> s = assemble([RigidBody(0, 1.0, 1e-2, 1.5e-2), Bearing(0, kxx=1e4, k_tilt_x=1e2)])
    >>> ds = campbell(s, RPM * np.linspace(0.0, 3000.0, 31), n_modes=4)
    >>> ds.frequency.sizes["speed"], ds.frequency.sizes["mode"]
    (31, 4)
    >>> ds.critical_speed.values.round(4).tolist()  # backward tilt, then sqrt(k/m) twice
    [63.2456, 100.0, 100.0]
    """
    w = np.asarray(speeds, dtype=float)
    if w.ndim != 1 or w.size == 0 or not np.all(np.isfinite(w)):
        raise ValueError("speeds must be a non-empty finite 1-D sequence (rad/s)")
    if w.size > 1 and np.any(np.diff(w) <= 0):
        raise ValueError("speeds must be strictly increasing")
    hs = tuple(int(h) for h in harmonics)
    if any(h < 1 for h in hs):
        raise ValueError(f"harmonics must be integers >= 1, got {tuple(harmonics)!r}")
    solver = Solver(system, method)
    spec: Spectrum = solver.solve(w)
    order = track_modes(spec.track, spec.eigenvalues, n_modes)
    lam = np.take_along_axis(spec.eigenvalues, order, axis=1)
    shp = np.take_along_axis(spec.shapes, order[:, :, None], axis=1)
    trk = np.take_along_axis(spec.track, order[:, :, None], axis=1)
    L = system.length_scale
    shp = normalize_shapes(shp, L)
    index, code = whirl_of_shapes(shp, L)
    # label branches by frequency at the first speed
    first = np.lexsort((np.abs(lam[0]), np.abs(lam[0].imag)))
    lam, shp, trk, index, code = (a[:, first] for a in (lam, shp, trk, index, code))
    scale = np.maximum(np.abs(spec.eigenvalues).max(axis=1), 1.0)
    max_growth = spec.eigenvalues.real.max(axis=1)
    stable = max_growth <= 1e-9 * scale
    cross = _crossings(w, lam, code, trk, hs, solver, refine)
    crit = np.array([c[0] for c in cross], dtype=float)
    undamped, excited = _undamped_partners(system, cross, hs)
    damped_def = {"definition": DEFINITIONS["damped crossing"]}
    freq = np.abs(lam.imag) / (2.0 * np.pi)
    mag = np.abs(lam)
    data = {
        "frequency": (("speed", "mode"), freq,
                      {"units": "Hz", "long_name": "damped natural frequency"}),
        "growth_rate": (("speed", "mode"), lam.real,
                        {"units": "1/s", "long_name": "real part of the eigenvalue"}),
        "log_decrement": (("speed", "mode"), log_decrement(lam), {"units": "1"}),
        "damping_ratio": (("speed", "mode"), -lam.real / np.where(mag > 0, mag, 1.0),
                          {"units": "1"}),
        "whirl": (("speed", "mode"), code,
                  {"units": "1", "flag_values": [1, -1, 0],
                   "flag_meanings": "forward backward mixed"}),
        "whirl_index": (("speed", "mode"), index, {"units": "1"}),
        "stable": ("speed", stable, {"units": "1", "long_name": "no mode grows"}),
        "max_growth_rate": ("speed", max_growth, {"units": "1/s"}),
        "critical_speed": ("critical", crit, {"units": "rad/s", **damped_def}),
        "critical_speed_rpm": ("critical", crit / RPM, {"units": "rev/min", **damped_def}),
        "critical_undamped_rpm": ("critical", undamped / RPM, {
            "units": "rev/min", "definition": DEFINITIONS["undamped"]}),
        "critical_damping_ratio": ("critical", np.array([c[4] for c in cross], dtype=float), {
            "units": "1", "long_name": "damping ratio of the mode at the crossing"}),
        "critical_excited_by_unbalance": ("critical", excited, {
            "units": "1", "long_name": "unbalance excites the mode"}),
        "critical_frequency": ("critical", np.array([c[1] for c in cross], dtype=float) * crit
                               / (2.0 * np.pi), {"units": "Hz"}),
        "critical_harmonic": ("critical", np.array([c[1] for c in cross], dtype=np.int64),
                              {"units": "1"}),
        "critical_mode": ("critical", np.array([c[2] for c in cross], dtype=np.int64),
                          {"units": "1"}),
        "critical_whirl": ("critical", np.array([c[3] for c in cross], dtype=np.int8),
                           {"units": "1", "flag_values": [1, -1, 0],
                            "flag_meanings": "forward backward mixed"}),
    }
    coords = {
        "speed": ("speed", w, {"units": "rad/s", "long_name": "spin speed"}),
        "speed_rpm": ("speed", w / RPM, {"units": "rev/min"}),
        "mode": ("mode", np.arange(lam.shape[1]), {"units": "1"}),
    }
    if shapes:
        n = system.n_dof
        data["shape_real"] = (("speed", "mode", "dof"), shp.real, {"units": "m or rad"})
        data["shape_imag"] = (("speed", "mode", "dof"), shp.imag, {"units": "m or rad"})
        coords["dof"] = ("dof", np.arange(n), {"units": "1"})
        coords["node"] = ("dof", system.dof_node, {"units": "1"})
        coords["direction"] = ("dof", np.array(system.dof_direction), {"units": "1"})
    return xr.Dataset(data, coords=coords, attrs={
        "title": "Campbell diagram", "method": solver.method, "tracking": "MAC",
        "critical_definition": "damped crossing", "isotropic": int(system.is_isotropic),
        "harmonics": list(hs)})
