"""Periodic orbits: one orbit by multiple shooting, and a branch of them continued in a parameter.

:func:`find_periodic_orbit` corrects a start (a state and a period guess, or the segment starts)
onto a periodic orbit at a fixed parameter; :func:`continue_periodic` follows the orbit in a
parameter with :func:`rotorlab.continuation.continue_curve` and returns a
:class:`~rotorlab.continuation.Branch` of kind ``"periodic"`` with the period, the Floquet
multipliers, the stability label and the located folds of cycles, period doublings and torus
points. Starting points from a Hopf point and from a simulation are in
:mod:`rotorlab.continuation._starts`. The residual is :class:`~._shooting.Shooting`; the
multipliers and test functions are :mod:`~._floquet`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab.continuation import _floquet as fq
from rotorlab.continuation._core import ContinuationSettings, CurvePoint, _Stepper, continue_curve, fold_test
from rotorlab.continuation._machine_problem import format_value
from rotorlab.continuation._result import SPECIAL_POINT_TYPES, Branch, SpecialPoint
from rotorlab.continuation._shooting import BACKEND, Shooting, refuse_events, steps_per_period
from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

__all__ = ["PeriodicOrbit", "find_periodic_orbit", "continue_periodic", "params_function"]

#: What a special point of an orbit branch means, where the equilibria's words do not fit.
_WORDS = {"branch": "branch point of periodic orbits: a second Floquet multiplier reaches +1 and another "
                    "family of orbits crosses this one (e.g. one that breaks the orbit's symmetry)"}

SAMPLES = 2048  # points per period for the amplitude (refined by a parabola through the peak: error ~ dt^3)


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit found by multiple shooting.

    Parameters
    ----------
    states : ndarray, shape (m, n)
        The segment starts; ``states[0]`` is the orbit's state at phase 0.
    period : float
        The period (s).
    value : float
        The parameter's value (``parameter``).
    multipliers : ndarray of complex, shape (n,)
        Floquet multipliers, largest modulus first.
    trivial : int
        Index of the trivial multiplier (1 for an autonomous orbit), -1 for a forced orbit.
    stable : bool
        Every non-trivial multiplier inside the unit circle.
    amplitude : float
        Largest Euclidean norm of the amplitude coordinates over the orbit.
    winding : ndarray of int, shape (n,)
        Whole turns of each coordinate per period.
    steps : int
        Fixed integration steps per period (the discrete flow the orbit is exact for).
    forcing_period : float or None
        The fixed period of a forced orbit; None for an autonomous one.
    parameter : str
        Name of the parameter.
    tangent : ndarray or None
        A direction (unknowns ``(starts, [period], value)``) in which to continue, from a start
        that knows one (a Hopf point: growing amplitude); None otherwise.
    """

    states: np.ndarray
    period: float
    value: float
    multipliers: np.ndarray
    trivial: int
    stable: bool
    amplitude: float
    winding: np.ndarray
    steps: int
    forcing_period: float | None = None
    parameter: str = "lam"
    tangent: np.ndarray | None = None

    @property
    def segments(self) -> int:
        return int(self.states.shape[0])

    @property
    def state(self) -> np.ndarray:
        """The state at phase 0."""
        return self.states[0]

    @property
    def trivial_error(self) -> float:
        """``|mu_trivial - 1|`` (0 for a forced orbit): how well the monodromy matrix is resolved."""
        return 0.0 if self.trivial < 0 else float(abs(self.multipliers[self.trivial] - 1.0))


def _typical(starts: np.ndarray, state_scale: Any) -> np.ndarray:
    if state_scale is not None:
        typ = np.broadcast_to(np.asarray(state_scale, dtype=float), starts.shape[1:]).copy()
        if np.any(typ <= 0) or not np.all(np.isfinite(typ)):
            raise ValueError(f"state_scale must be positive and finite, got {state_scale!r}")
        return typ
    typ = np.maximum(np.abs(starts).max(axis=0), np.ptp(starts, axis=0))
    return np.maximum(typ, 1e-6 * max(float(typ.max()), 1e-300))


def _winding(winding: Any, n: int) -> np.ndarray:
    w = np.zeros(n, dtype=int) if winding is None else np.asarray(winding)
    if w.shape != (n,) or not np.all(w == np.round(w)):
        raise ValueError(f"winding must be {n} whole numbers (turns per period of each state), got {winding!r}")
    return w.astype(int)


def _peak(a: np.ndarray) -> float:
    """The largest value of a periodic sample, refined by a parabola through the peak."""
    k = int(np.argmax(a))
    y0, y1, y2 = a[k - 1], a[k], a[(k + 1) % a.size]
    den = y0 - 2.0 * y1 + y2
    return float(y1 - 0.125 * (y2 - y0) ** 2 / den) if den < 0 else float(y1)


def orbit_info(shoot: Shooting, u: np.ndarray, amplitude: Sequence[int]) -> dict[str, Any]:
    """Multipliers, trivial index, stability and amplitude of the orbit ``u``."""
    _, _, g, _ = shoot.evaluate(u)
    x, period, lam = shoot.unpack(u)
    flow = shoot.flow(0.0, x[0], np.asarray(shoot.params_at(lam), dtype=float)) if shoot.autonomous else None
    mu, triv = fq.floquet_multipliers(g, flow, shoot.typ)
    ys = shoot.sample(u, max(4, math.ceil(SAMPLES / shoot.m)))
    amp = _peak(np.sqrt(np.sum(ys[:, list(amplitude)] ** 2, axis=1)))
    return {"multipliers": mu, "trivial": triv, "stable": fq.is_stable(mu, triv), "amplitude": amp,
            "state": x[0].copy(), "period": period, "value": lam, "states": x.copy()}


def _guess_starts(model: Any, start: np.ndarray, period: float, params: np.ndarray, m: int, rtol: float,
                  t0: float) -> tuple[np.ndarray, np.ndarray]:
    """The segment starts and the states sampled over one period from ``start`` (n,) or the
    starts themselves (m, n)."""
    if start.ndim == 2:
        return start, start
    per = 64 // m + 1
    ts = t0 + np.arange(m * per) * period / (m * per)
    sol = solve_ensemble(model, start, (t0, t0 + period), params=params, save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=rtol, atol=rtol * np.maximum(np.abs(start), 1e-3)),
                         backend=BACKEND)
    if int(sol.status[0]) != 0:
        raise ValueError("the start cannot be integrated over one period guess")
    return sol.ys[0][::per], sol.ys[0]


def _make_orbit(shoot: Shooting, u: np.ndarray, parameter: str, amplitude: Sequence[int],
                tangent: np.ndarray | None = None) -> PeriodicOrbit:
    info = orbit_info(shoot, u, amplitude)
    return PeriodicOrbit(states=info["states"], period=info["period"], value=info["value"],
                         multipliers=info["multipliers"], trivial=info["trivial"], stable=info["stable"],
                         amplitude=info["amplitude"], winding=shoot.winding.astype(int), steps=shoot.k * shoot.m,
                         forcing_period=shoot.forcing_period, parameter=parameter, tangent=tangent)


def _check_trivial(orbit: PeriodicOrbit, tol: float) -> PeriodicOrbit:
    if orbit.trivial_error > tol:
        raise ValueError(
            f"the trivial Floquet multiplier is {orbit.multipliers[orbit.trivial]:.8g}, {orbit.trivial_error:.2e} "
            f"from 1 (allowed {tol:g}): the monodromy matrix is not resolved; give more steps per period"
        )
    return orbit


def find_periodic_orbit(model: Any, start: Any, period: float, *, params: Any = None, segments: int = 5,
                        winding: Any = None, forced: bool = False, steps: int | None = None, rtol: float = 1e-9,
                        state_scale: Any = None, amplitude: Sequence[int] = (0, 1), tol: float = 1e-10,
                        trivial_tol: float = 1e-4, max_newton: int = 20, parameter: str = "lam",
                        value: float = 0.0) -> PeriodicOrbit:
    """Correct a start onto a periodic orbit of ``model`` by multiple shooting.

    Parameters
    ----------
    model : model
        A smooth model (no events) with ``kernels`` and ``to_array()``.
    start : array_like, shape (n,) or (segments, n)
        A state on or near the orbit (the segment starts are then taken from an integration over
        ``period``), or the segment starts themselves.
    period : float
        The period guess (s); for ``forced=True`` the fixed period of the forcing.
    params : array_like, optional
        The packed parameters; default ``model.to_array()``.
    segments : int
        Number of shooting segments ``m``.
    winding : array_like of int, shape (n,), optional
        Whole turns per period of each state (angles of a co-rotating frame); default none.
    forced : bool
        A time-periodic (non-autonomous) system: ``period`` is fixed, ``start`` is at ``t = 0``.
    steps : int, optional
        Fixed integration steps per period; default 1.5 times an adaptive integration's at ``rtol``.
    state_scale : array_like, shape (n,), optional
        Typical size of each state; default from the start.
    amplitude : sequence of int
        The states whose Euclidean norm is the orbit's amplitude (default the first two).
    tol : float
        Newton tolerance (scaled update).
    trivial_tol : float
        Largest allowed ``|mu_trivial - 1|``.
    parameter, value : str, float
        The name and value of the parameter the orbit is at (the start of a continuation in it).

    Returns
    -------
    PeriodicOrbit

    Raises
    ------
    ValueError
        A model with events, a start that does not converge, or an unresolved monodromy matrix.

    Examples
    --------
    The Van der Pol limit cycle at mu = 1 (period 6.66328685932313):

    >>> from rotorlab.continuation import find_periodic_orbit
    >>> from rotorlab.models.examples import PlanarOscillator
    >>> orbit = find_periodic_orbit(PlanarOscillator.van_der_pol(1.0), [2.0, 0.0], 6.6)
    >>> round(orbit.period, 7), orbit.stable
    (6.6632869, True)
    """
    refuse_events(model)
    n = model.kernels.n_state
    p = np.asarray(model.to_array() if params is None else params, dtype=float)
    start = np.asarray(start, dtype=float)
    if start.shape not in ((n,), (segments, n)):
        raise ValueError(f"start must have shape ({n},) or ({segments}, {n}), got {start.shape}")
    if not (period > 0 and math.isfinite(period)):
        raise ValueError(f"period must be > 0 and finite, got {period!r}")
    starts, samples = _guess_starts(model, start, period, p, segments, rtol, 0.0)
    typ = _typical(samples, state_scale)
    if steps is None:
        steps = steps_per_period(model, starts[0], period, p, rtol, typ)
    shoot = Shooting(model, lambda lam: p, segments=segments, steps=steps, typ=typ,
                     winding=_winding(winding, n), forcing_period=period if forced else None)
    u0 = shoot.pack(starts, period, float(value))
    u = _newton(shoot, u0, tol, max_newton)
    return _check_trivial(_make_orbit(shoot, u, parameter, amplitude), trivial_tol)


def _scale(shoot: Shooting, period: float, lam_scale: float) -> np.ndarray:
    head = np.tile(shoot.typ, shoot.m)
    return np.concatenate([head, [period] if shoot.autonomous else [], [lam_scale]])


def _newton(shoot: Shooting, u0: np.ndarray, tol: float, max_newton: int, row: np.ndarray | None = None,
            lam_scale: float = 1.0) -> np.ndarray:
    """Newton's method on the shooting equations plus one linear row (default: fixed parameter)."""
    x, period, _ = shoot.unpack(u0)
    scale = _scale(shoot, period, lam_scale)
    stepper = _Stepper(shoot.residual, shoot.jacobian, scale,
                       ContinuationSettings(newton_tol=tol, max_newton=max_newton))
    if row is None:
        row = np.zeros(u0.size)
        row[-1] = 1.0
    shoot.set_reference(u0)
    u, _ = stepper.correct(u0, row)
    if u is None:
        raise ValueError("Newton's method did not converge onto a periodic orbit from this start "
                         "(a better period guess, more segments or a start closer to the orbit)")
    return u


def params_function(model: Any, params_at: Callable[[float], Any] | str) -> Callable[[float], np.ndarray]:
    """``value -> packed parameters``: ``params_at`` itself, or for a name of the model's named
    parameters (``model.parameters``, e.g. ``"speed.speed"``) ``model.pack({name: value})``."""
    if isinstance(params_at, str):
        name = params_at
        if not hasattr(model, "pack") or name not in getattr(model.parameters, "names", ()):
            known = ", ".join(getattr(getattr(model, "parameters", None), "names", ())) or "none"
            raise ValueError(f"unknown parameter {name!r} of {type(model).__name__}; its parameters: {known}")
        return lambda value: np.asarray(model.pack({name: float(value)}), dtype=float)
    return lambda value: np.asarray(params_at(value), dtype=float)


def continue_periodic(model: Any, orbit: PeriodicOrbit, params_at: Callable[[float], Any] | str, *,
                      parameter: str | None = None, settings: ContinuationSettings = ContinuationSettings(),
                      parameter_scale: float | None = None, state_scale: Any = None,
                      amplitude: Sequence[int] = (0, 1), trivial_tol: float = 1e-4,
                      label: str = "periodic orbit", unit: str | None = None) -> Branch:
    """Continue a periodic orbit in a parameter by multiple shooting.

    Parameters
    ----------
    model : model
        The model the orbit belongs to (no events).
    orbit : PeriodicOrbit
        The first orbit (its ``value`` is the parameter's; it is corrected at that value).
    params_at : callable or str
        ``value -> packed parameters`` of the model at that parameter value, or the name of one
        of the model's named parameters (``model.parameters``; then ``model.pack``).
    parameter : str, optional
        The parameter's name (the branch's and the JSON's key); default ``params_at`` when it is
        a name, else ``orbit.parameter``.
    settings : ContinuationSettings
        Steps, bounds and number of orbits (``max_points``).
    parameter_scale : float, optional
        Typical size of the parameter (arclength weight); default ``max(|value|, 1)``.
    state_scale : array_like, optional
        Typical size of each state; default from the orbit.
    amplitude : sequence of int
        The states whose Euclidean norm is the amplitude.
    trivial_tol : float
        A point whose trivial multiplier is further than this from 1 is labelled unstable
        (unresolved), and ``extra["trivial_multiplier_error"]`` says so.
    label : str
        What the branch is, for people.
    unit : str, optional
        The parameter's SI unit: the special points' sentences then give its value as people
        read it (rad/s as rpm, kg as g: :func:`rotorlab.continuation.format_value`); without
        one, the plain number.

    Returns
    -------
    Branch
        Kind ``"periodic"``: values, phase-0 states, stability, amplitude, Floquet multipliers
        (``spectrum``), period; special points ``fold-of-cycles``, ``branch`` (a multiplier +1
        away from a fold), ``period-doubling``, ``torus``.
    """
    refuse_events(model)
    parameter = parameter or (params_at if isinstance(params_at, str) else orbit.parameter)
    at = params_function(model, params_at)
    lam_scale = float(parameter_scale) if parameter_scale is not None else max(abs(orbit.value), 1.0)
    typ = _typical(orbit.states, state_scale)
    shoot = Shooting(model, at, segments=orbit.segments,
                     steps=orbit.steps, typ=typ, winding=orbit.winding, forcing_period=orbit.forcing_period,
                     lam_scale=lam_scale)
    u0 = shoot.pack(orbit.states, orbit.period, orbit.value)
    shoot.set_reference(u0)
    scale = _scale(shoot, orbit.period, lam_scale)
    floq: dict[bytes, tuple[np.ndarray, int]] = {}

    def mult(pt: CurvePoint) -> tuple[np.ndarray, int]:
        key = pt.u.tobytes()
        if key not in floq:
            x, _, lam = shoot.unpack(pt.u)
            g = shoot.evaluate(pt.u)[2]
            flow = shoot.flow(0.0, x[0], shoot.params_at(lam)) if shoot.autonomous else None
            floq[key] = fq.floquet_multipliers(g, flow, typ)
        return floq[key]

    tests = {"fold-of-cycles": fold_test,
             "branch": lambda pt: fq.plus_one_value(*mult(pt)),
             "period-doubling": lambda pt: fq.period_doubling_value(*mult(pt)),
             "torus": lambda pt: fq.torus_value(*mult(pt))}
    infos: list[dict[str, Any]] = []

    def on_point(pt: CurvePoint) -> None:
        info = orbit_info(shoot, pt.u, amplitude)
        infos.append(info)
        shoot.set_reference(pt.u)

    curve = continue_curve(shoot.residual, u0, jacobian=shoot.jacobian, scale=scale, settings=settings,
                           tests=tests, tangent0=orbit.tangent, on_point=on_point)
    errs = np.array([0.0 if i["trivial"] < 0 else abs(i["multipliers"][i["trivial"]] - 1.0) for i in infos])
    stable = np.array([i["stable"] for i in infos]) & (errs <= trivial_tol)
    specials = []
    folds = {c.index for c in curve.crossings if c.name == "fold-of-cycles"}
    confirm = {"torus": fq.is_torus, "period-doubling": fq.is_period_doubling, "branch": fq.is_plus_one}
    for c in curve.crossings:
        mu, triv = mult(c.point)
        if c.name in confirm and not confirm[c.name](mu, triv):
            continue  # a neutral saddle, or an unresolved zero: not a bifurcation
        if c.name == "branch" and c.index in folds:
            continue  # the multiplier +1 of a fold, reported as the fold
        if c.name in ("fold-of-cycles", "branch") and c.index == 1 and orbit.tangent is not None:
            # born at a Hopf point: the parameter moves as the amplitude squared and the radial
            # multiplier is 1 + O(amplitude^2), so both tests are zero to round-off at the first
            # orbit and change sign there by noise; the orbit's birth, not a bifurcation of it
            continue
        x, period, lam = shoot.unpack(c.point.u)
        freq = math.nan
        if c.name == "torus":
            rest = np.delete(mu, triv) if triv >= 0 else mu
            pair = rest[np.argmin(np.abs(np.abs(rest) - 1.0) + (np.abs(rest.imag) < 1e-6))]
            freq = abs(float(np.angle(pair))) / period
        change = _stability_change(stable, c.index)
        specials.append(SpecialPoint(
            type=c.name, parameter=parameter, value=lam, state=x[0].copy(), index=c.index, frequency=freq,
            description=f"{label}: {_WORDS.get(c.name, SPECIAL_POINT_TYPES[c.name])}, at {parameter} = "
                        f"{format_value(lam, unit) if unit else f'{lam:.10g}'} "
                        f"(period {period:.6g} s){change}" + ("" if c.converged else " (location not converged)")))
    return Branch(
        kind="periodic", parameter=parameter, values=np.array([i["value"] for i in infos]),
        states=np.array([i["state"] for i in infos]), stable=stable,
        amplitude=np.array([i["amplitude"] for i in infos]),
        spectrum=np.array([i["multipliers"] for i in infos]), period=np.array([i["period"] for i in infos]),
        special_points=tuple(specials), label=label, end=curve.end,
        extra={"trivial_multiplier_error": errs},
    )


def _stability_change(stable: np.ndarray, index: int) -> str:
    if index < 1 or index >= stable.size or stable[index - 1] == stable[index]:
        return ""
    before, after = ("stable", "unstable") if stable[index - 1] else ("unstable", "stable")
    return f"; the orbits are {before} before it and {after} after it along the branch"
