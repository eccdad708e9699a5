"""Starting points of a periodic-orbit branch: a Hopf point, or a simulated orbit.

- :func:`orbit_from_hopf`: near a Hopf point ``(x0, lam0)`` with crossing eigenvalue ``i w`` and
  eigenvector ``v`` the orbits are ``x0 + eps Re(v e^{i w t}) + O(eps^2)`` with period
  ``2 pi / w + O(eps^2)``, at a parameter ``lam0 + O(eps^2)`` (Kuznetsov 2004, ch. 3.5). The
  guess at amplitude ``eps`` is corrected with the projection of the first start on ``Re v``
  held fixed (the parameter free), so that Newton's method cannot fall back onto the
  equilibrium; a second orbit at ``1.25 eps`` gives the direction in which the amplitude grows.
- :func:`orbit_from_simulation`: integrate a start until it settles, detect the period from the
  returns to a Poincaré section (the upward crossings of one state through its mean) whose
  states repeat (angles compared modulo whole turns, which gives their winding), and correct the
  returned state by shooting.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rotorlab.continuation._periodic import (
    PeriodicOrbit, _check_trivial, _make_orbit, _newton, find_periodic_orbit, params_function,
)
from rotorlab.continuation._shooting import BACKEND, Shooting, refuse_events, steps_per_period
from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

__all__ = ["orbit_from_hopf", "orbit_from_simulation"]


def _hopf_pair(shoot_flow: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, typ: np.ndarray):
    """The eigenvalue with positive imaginary part nearest the imaginary axis, and its vector."""
    n = x0.size
    jac = np.empty((n, n))
    for j in range(n):
        h = 1e-7 * max(typ[j], abs(x0[j]))
        xp, xm = x0.copy(), x0.copy()
        xp[j] += h
        xm[j] -= h
        jac[:, j] = (shoot_flow(xp) - shoot_flow(xm)) / (2 * h)
    lam, vec = np.linalg.eig(jac)
    cand = np.flatnonzero(lam.imag > 1e-12)
    if cand.size == 0:
        raise ValueError("no complex eigenvalue at this point: it is not a Hopf point")
    k = cand[np.argmin(np.abs(lam[cand].real))]
    return float(lam[k].imag), vec[:, k]


def orbit_from_hopf(model: Any, state: Any, value: float, params_at: Callable[[float], Any] | str, *,
                    frequency: float | None = None, eigenvector: Any = None, amplitude: float = 1e-3,
                    segments: int = 5, steps: int | None = None, rtol: float = 1e-9,
                    state_scale: Any = None, parameter: str | None = None, parameter_scale: float | None = None,
                    amplitude_states: Sequence[int] = (0, 1), trivial_tol: float = 1e-4) -> PeriodicOrbit:
    """A small periodic orbit near a Hopf point, with the direction of growing amplitude.

    Parameters
    ----------
    model : model
        A smooth model (no events).
    state : array_like, shape (n,)
        The equilibrium at the Hopf point.
    value : float
        The parameter's value there.
    params_at : callable or str
        ``value -> packed parameters``, or the name of one of the model's named parameters.
    frequency : float, optional
        The crossing eigenvalue's imaginary part ``w`` (rad/s); default from a numerical
        Jacobian of the model's right-hand side at ``state``.
    eigenvector : array_like of complex, shape (n,), optional
        Its eigenvector; default as ``frequency``.
    amplitude : float
        ``eps``: the guess's largest deviation from ``state``, relative to ``state_scale``.
    segments, steps, rtol, state_scale, amplitude_states, trivial_tol
        As :func:`rotorlab.continuation.find_periodic_orbit` (``amplitude_states`` is its
        ``amplitude``). ``state_scale`` (default ``max(|state|, 1)``) is also the scale of the
        eigenvector: the guess deviates by ``amplitude * state_scale`` in its largest component.
    parameter : str, optional
        The parameter's name (default ``params_at`` when it is a name, else ``"lam"``).
    parameter_scale : float, optional
        Typical size of the parameter (default ``max(|value|, 1)``).

    Returns
    -------
    PeriodicOrbit
        Corrected at amplitude ``eps`` (its parameter is ``value + O(eps^2)``), with ``tangent``
        pointing to larger orbits: :func:`rotorlab.continuation.continue_periodic` follows it.
    """
    refuse_events(model)
    x0 = np.asarray(state, dtype=float)
    n = model.kernels.n_state
    if x0.shape != (n,):
        raise ValueError(f"state must have shape ({n},), got {x0.shape}")
    parameter = parameter or (params_at if isinstance(params_at, str) else "lam")
    params_at = params_function(model, params_at)
    p = params_at(value)
    typ = (np.maximum(np.abs(x0), 1.0) if state_scale is None
           else np.broadcast_to(np.asarray(state_scale, dtype=float), (n,)).copy())

    def flow(x: np.ndarray) -> np.ndarray:
        out = np.empty(n)
        model.kernels.rhs(0.0, np.ascontiguousarray(x), p, out)
        return out

    if frequency is None or eigenvector is None:
        w, v = _hopf_pair(flow, x0, typ)
        frequency = w if frequency is None else frequency
        eigenvector = v if eigenvector is None else eigenvector
    w = abs(float(frequency))
    v = np.asarray(eigenvector, dtype=complex)
    v = v / np.max(np.abs(v) / typ)  # largest component = its typical size
    v = v * np.exp(-1j * np.angle(v[np.argmax(np.abs(v) / typ)]))  # that component real at t = 0
    period = 2.0 * math.pi / w
    t = np.arange(segments) * period / segments
    lam_scale = float(parameter_scale) if parameter_scale is not None else max(abs(value), 1.0)

    def guess(eps: float) -> np.ndarray:
        return x0 + eps * np.real(v[None, :] * np.exp(1j * w * t)[:, None])

    if steps is None:
        steps = steps_per_period(model, guess(amplitude)[0], period, p, rtol, typ)
    shoot = Shooting(model, params_at, segments=segments, steps=steps,
                     typ=typ, winding=np.zeros(n), lam_scale=lam_scale)
    scale_row = np.zeros(shoot.size)
    scale_row[:n] = np.real(v) / shoot.typ
    scale_row /= np.linalg.norm(scale_row)
    us = []
    for eps in (amplitude, 1.25 * amplitude):
        u = _newton(shoot, shoot.pack(guess(eps), period, value), 1e-10, 20, row=scale_row, lam_scale=lam_scale)
        us.append(u)
    tangent = us[1] - us[0]
    orbit = _make_orbit(shoot, us[0], parameter, amplitude_states, tangent=tangent)
    return _check_trivial(orbit, trivial_tol)


def _returns(ts: np.ndarray, ys: np.ndarray, section: int) -> tuple[np.ndarray, np.ndarray]:
    """Times and states (linear interpolation) of the upward crossings of ``ys[:, section]``
    through its mean."""
    s = ys[:, section] - ys[:, section].mean()
    k = np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))
    f = -s[k] / (s[k + 1] - s[k])
    return ts[k] + f * (ts[k + 1] - ts[k]), ys[k] + f[:, None] * (ys[k + 1] - ys[k])


def orbit_from_simulation(model: Any, start: Any, *, t_settle: float, t_window: float, params: Any = None,
                          section: int = 0, angles: Sequence[int] = (), segments: int = 5,
                          max_multiple: int = 8, return_tol: float = 1e-3, rtol: float = 1e-10,
                          samples: int = 20000, **options: Any) -> PeriodicOrbit:
    """The periodic orbit a simulation settles on, corrected by shooting.

    Parameters
    ----------
    model : model
        An autonomous smooth model (no events).
    start : array_like, shape (n,)
        The initial state of the simulation.
    t_settle : float
        Integrate this long first (s) and forget it.
    t_window : float
        Then look for the period in this much more (s); it should hold several periods.
    params : array_like, optional
        Packed parameters (default ``model.to_array()``).
    section : int
        The state whose upward crossings through its mean are the returns.
    angles : sequence of int
        The states that are angles: compared modulo 2 pi, their whole turns per period become
        the orbit's winding.
    segments : int
        Shooting segments.
    max_multiple : int
        Look for a return after up to this many section crossings (a period-k orbit).
    return_tol : float
        Largest difference of returning states, relative to each state's range in the window.
    rtol : float
        Tolerance of the simulation.
    samples : int
        Saved states in the window.
    **options
        Passed on to :func:`rotorlab.continuation.find_periodic_orbit` (``steps``,
        ``state_scale``, ``amplitude``, ``trivial_tol``).

    Raises
    ------
    ValueError
        A model with events, a failed simulation, or no repeating return (a quasi-periodic or
        chaotic motion, or an equilibrium).
    """
    refuse_events(model)
    n = model.kernels.n_state
    p = np.asarray(model.to_array() if params is None else params, dtype=float)
    y = np.asarray(start, dtype=float)
    atol = rtol * np.maximum(np.abs(y), 1e-3)
    ctrl = StepControl(rtol=rtol, atol=atol)
    sol = solve_ensemble(model, y, (0.0, t_settle), params=p, control=ctrl, backend=BACKEND)
    if int(sol.status[0]) != 0:
        raise ValueError(f"the simulation from the start failed: {sol.status[0]!r}")
    ts = np.linspace(0.0, t_window, samples)
    win = solve_ensemble(model, sol.y_final[0], (0.0, t_window), params=p, save_at=SaveAt(ts=ts), control=ctrl,
                         backend=BACKEND)
    if int(win.status[0]) != 0:
        raise ValueError(f"the simulation failed in the window: {win.status[0]!r}")
    ys = win.ys[0]
    tc, yc = _returns(ts, ys, section)
    if tc.size < 3:
        raise ValueError(f"state {section} crosses its mean fewer than 3 times in the window: no periodic motion "
                         "detected (an equilibrium, or a window shorter than a few periods)")
    rng = np.ptp(ys, axis=0)
    ang = np.zeros(n, dtype=bool)
    ang[list(angles)] = True
    rng[ang] = np.minimum(np.maximum(rng[ang], 1e-12), 2 * math.pi)
    rng = np.maximum(rng, 1e-12 * max(float(rng.max()), 1e-300))
    for k in range(1, min(max_multiple, tc.size - 1) + 1):
        d = yc[k:] - yc[:-k]
        turns = np.where(ang, np.round(d / (2 * math.pi)), 0.0)
        err = np.abs(d - 2 * math.pi * turns) / rng
        last = slice(max(0, err.shape[0] - 3), None)
        if np.max(err[last]) < return_tol and np.all(turns[last] == turns[-1]):
            period = float(np.mean(tc[k:][last] - tc[:-k][last]))
            y_start = yc[-1 - k].copy()
            y_start[ang] = np.angle(np.exp(1j * y_start[ang]))  # the flow is the same a whole turn on
            return find_periodic_orbit(model, y_start, period, params=p, segments=segments,
                                       winding=turns[-1].astype(int), rtol=rtol * 10, **options)
    raise ValueError(f"no return of the section crossings repeats within {max_multiple} crossings "
                     f"(relative tolerance {return_tol:g}): the motion is not periodic in this window")
