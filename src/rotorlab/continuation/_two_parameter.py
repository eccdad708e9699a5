"""Fold and Hopf curves of a machine's steady motions in two named parameters.

A fold or Hopf point located on a branch in the first parameter ``p1`` (speed, say) is continued
in a second one ``p2`` (ball mass, ball damping, unbalance ...) with ``p1`` free, by the minimally
augmented systems (Govaerts 2000, ch. 4; Kuznetsov 2004, sec. 10.2):

- fold: ``F(x, p1, p2) = 0`` and ``g = 0``, g from the bordered system
  ``[[F_x, b], [c^T, 0]] [v; g] = [0; 1]`` (b, c: the left and right null vectors of ``F_x`` at the
  located fold); g vanishes exactly where ``F_x`` is singular;
- Hopf: ``F = 0`` and ``Re lambda(x, p1, p2) = 0`` for the eigenvalue of the co-rotating
  linearization that crossed (followed from point to point: the one nearest the previous point's).

Each is one residual of ``n + 1`` equations in ``u = (x, p1, p2)`` handed to
:func:`rotorlab.continuation.continue_curve` with ``p2`` as its parameter, both ways from the
located point, so the stability chart becomes curves: the Hopf curve bounds the speeds where the
balanced state is stable.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorlab.continuation._core import ContinuationSettings, continue_curve
from rotorlab.continuation._machine_problem import MachineEquilibria, as_machine, current_value
from rotorlab.continuation._result import ContinuationResult, SpecialPoint

__all__ = ["TwoParameterCurve", "continue_special_point", "two_parameter_curves"]


@dataclass(frozen=True)
class TwoParameterCurve:
    """A fold or Hopf curve in the plane of two parameters.

    Parameters
    ----------
    type : {"fold", "hopf"}
    parameters : (str, str)
        ``(p1, p2)``: the branch's parameter and the second one.
    values : ndarray, shape (n, 2)
        ``(p1, p2)`` along the curve (SI), in order.
    states : ndarray, shape (n, n_state)
        The co-rotating steady motion at each point.
    frequency : ndarray, shape (n,)
        The crossing pair's imaginary part (rad/s) along a Hopf curve; NaN on a fold curve.
    label : str
        The branch it was found on ("main+", "side 00", ...).
    end : str
        Why each half ended (``"bound/step"``: the p2-decreasing half, then the increasing one;
        ``"bogdanov-takens"`` where the Hopf pair became real).
    boundary : bool
        Whether the point it was continued from changes the branch's stability (a stability
        boundary; a Hopf point of a pair crossing on an already unstable branch is not).
    crossing : tuple of str
        On a ``"floquet-boundary"`` (the balanced state on anisotropic supports,
        :func:`rotorlab.continuation.floquet_boundary`): where the critical Floquet multiplier
        leaves the unit circle at each point, ``"+1"``, ``"-1"`` or ``"complex"``; else empty.
    """

    type: str
    parameters: tuple[str, str]
    values: np.ndarray
    states: np.ndarray
    frequency: np.ndarray
    label: str = ""
    end: str = ""
    boundary: bool = True
    crossing: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        p1, p2 = self.parameters
        pts = []
        for k in range(len(self.values)):
            pt = {p1: _num(self.values[k, 0]), p2: _num(self.values[k, 1])}
            if self.type != "fold":
                pt["frequency_rad_s"] = _num(self.frequency[k])
            if self.crossing:
                pt["crossing"] = self.crossing[k]
            pts.append(pt)
        return {"type": self.type, "parameters": [p1, p2], "label": self.label, "end": self.end,
                "stability_boundary": self.boundary, "points": pts}


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


class _Augmented(ABC):
    """The fold or Hopf system in ``u = (x, p1, p2)``: the equilibrium equations and one
    condition (:class:`_Fold`, :class:`_Hopf`, by the special point's type in :data:`_SYSTEMS`)."""

    def __init__(self, prob: MachineEquilibria, u0: np.ndarray, frequency: float):
        self.prob, self.n = prob, prob.n

    @abstractmethod
    def condition(self, u) -> float:
        """The extra equation that makes the equilibrium this special point."""

    def restart(self, frequency: float) -> None:
        """Before each half of the curve (nothing to forget here)."""

    def finish(self, u: np.ndarray, p2: float, ends: list[str]) -> tuple[np.ndarray, np.ndarray, list[str]]:
        """The curve's points, their frequency (rad/s; NaN: none) and how each half ended."""
        return u, np.full(len(u), np.nan), ends

    def condition_row(self, u) -> np.ndarray:
        """The condition's derivative over ``u``: central differences (steps 1e-4 of each
        unknown's scale)."""
        row = np.empty(u.size)
        for j in range(u.size):
            h = 1e-4 * (self.scale[j] if j < self.n else max(abs(u[j]), self.scale[j]))
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            row[j] = (self.condition(up) - self.condition(um)) / (2.0 * h)
        return row

    def jacobian(self, u) -> np.ndarray:
        """Rows of F from :meth:`MachineEquilibria.jacobian`, then the condition's row."""
        u = np.asarray(u, dtype=float)
        return np.vstack([self.prob.jacobian(u), self.condition_row(u)])

    def residual(self, u) -> np.ndarray:
        f = self.prob.residual(u)
        if not np.all(np.isfinite(f)):  # a parameter value the model refuses
            return np.full(self.n + 1, np.nan)
        return np.concatenate([f, [self.condition(u)]])

    def follow(self, point) -> float:
        """A 'test' that never changes sign, called at each accepted point."""
        return 1.0


class _Fold(_Augmented):
    """A zero eigenvalue: the last entry of the bordered system's solution (a fold curve; the
    condition's row by central differences, the condition holding a difference Jacobian itself)."""

    def __init__(self, prob: MachineEquilibria, u0: np.ndarray, frequency: float):
        super().__init__(prob, u0, frequency)
        jx = prob.jacobian(u0)[:, :self.n]
        w, _, vt = np.linalg.svd(jx)
        self.b, self.c = w[:, -1], vt[-1]

    def condition(self, u) -> float:
        jx = self.prob.jacobian(u)[:, :self.n]
        a = np.block([[jx, self.b[:, None]], [self.c[None, :], np.zeros((1, 1))]])
        rhs = np.zeros(self.n + 1)
        rhs[-1] = 1.0
        return float(np.linalg.solve(a, rhs)[-1])


class _Hopf(_Augmented):
    """The real part of the tracked pair's eigenvalue (a Hopf curve; the condition's row from the
    crossing eigenvalue's derivative, :meth:`MachineEquilibria.eigenvalue_gradient`)."""

    def __init__(self, prob: MachineEquilibria, u0: np.ndarray, frequency: float):
        super().__init__(prob, u0, frequency)
        self.frequency = frequency
        self.restart(frequency)

    def restart(self, frequency: float) -> None:
        """Track the pair crossing at ``i frequency`` afresh (no eigenvector yet)."""
        self.ref, self.vec = complex(0.0, frequency), None

    def crossing(self, u) -> complex:
        return self.prob.eigen_triplet(u, self.ref, self.vec)[0]

    def condition(self, u) -> float:
        return self.crossing(u).real

    def condition_row(self, u) -> np.ndarray:
        _, v, w = self.prob.eigen_triplet(u, self.ref, self.vec)
        return self.prob.eigenvalue_gradient(u, v, w).real

    def follow(self, point) -> float:
        """Move the reference to the accepted point's crossing eigenvalue and its mode."""
        self.ref, self.vec, _ = self.prob.eigen_triplet(point.u, self.ref, self.vec)
        return 1.0

    def finish(self, u: np.ndarray, p2: float, ends: list[str]) -> tuple[np.ndarray, np.ndarray, list[str]]:
        """The crossing pair's frequency at each point, followed outwards from the start; the
        curve ends where the pair becomes real (a Bogdanov-Takens point)."""
        prob = self.prob
        freq = np.full(len(u), np.nan)
        k0 = int(np.argmin(np.abs(u[:, -1] - p2)))
        keep = np.ones(len(u), bool)
        for order in (range(k0, len(u)), range(k0, -1, -1)):  # follow the pair outwards
            self.restart(self.frequency)
            for k in order:
                lam = self.crossing(u[k])
                big = max(np.abs(prob.eigenvalues(u[k])).max(), 1.0)
                if abs(lam.imag) <= 1e-6 * big:  # the pair became real: a Bogdanov-Takens point
                    keep[k:] = False if order.step > 0 else keep[k:]
                    keep[:k + 1] = False if order.step < 0 else keep[:k + 1]
                    ends = [e if (order.step > 0) != (j == 0) else "bogdanov-takens" for j, e in enumerate(ends)]
                    break
                freq[k] = abs(lam.imag)
                self.ref, self.vec, _ = prob.eigen_triplet(u[k], self.ref, self.vec)
        return u[keep], freq[keep], ends


#: The augmented system of each special point type that continues in two parameters.
_SYSTEMS = {"fold": _Fold, "hopf": _Hopf}


def continue_special_point(model, point: SpecialPoint, parameter2: str, start2: float, stop2: float, *,
                           settings: ContinuationSettings | None = None, label: str = "") -> TwoParameterCurve:
    """Continue a located fold or Hopf point of ``model`` in ``parameter2`` over ``[start2, stop2]``.

    ``model`` holds the value of ``parameter2`` at which the point was located (it must lie in
    the range); the curve is followed both ways from it.

    Raises
    ------
    ValueError
        Not a fold or Hopf point, the model's value of ``parameter2`` outside the range, or the
        point does not converge onto the augmented system.
    """
    if point.type not in ("fold", "hopf"):
        raise ValueError(f"only fold and Hopf points are continued in two parameters, got {point.type!r}")
    model = as_machine(model)
    prob = MachineEquilibria(model, (point.parameter, parameter2))
    p2 = current_value(model, parameter2)
    lo, hi = min(start2, stop2), max(start2, stop2)
    if not lo <= p2 <= hi:
        raise ValueError(f"{parameter2}: the point was located at {p2:g}, outside the range {lo:g} to {hi:g}")
    x0 = prob.unknowns(point.state)
    u0 = np.concatenate([x0, [point.value, p2]])
    system = _SYSTEMS[point.type](prob, u0, point.frequency)
    scale = prob.scale([point.value, 1.0])
    scale[-1] = hi - lo
    system.scale = scale
    halves, ends = [], []
    for direction in (-1, 1):
        if (direction < 0 and p2 <= lo) or (direction > 0 and p2 >= hi):
            continue
        st = settings if settings is not None else ContinuationSettings(
            ds=0.02, ds_min=1e-6, ds_max=0.25, max_points=200, newton_tol=1e-8, bounds=(lo, hi), chord=True)
        st = ContinuationSettings(**{**st.__dict__, "bounds": (lo, hi), "direction": direction})
        system.restart(point.frequency)
        curve = continue_curve(system.residual, u0, jacobian=system.jacobian, scale=scale, settings=st,
                               tests={"follow": system.follow})
        halves.append(curve.u if direction > 0 else curve.u[::-1])
        ends.append(curve.end)
    u = np.concatenate([halves[0], halves[1][1:]]) if len(halves) == 2 else halves[0]
    u, freq, ends = system.finish(u, p2, ends)
    return TwoParameterCurve(type=point.type, parameters=(point.parameter, parameter2), values=u[:, -2:],
                             states=np.array([prob.state(v[:prob.n]) for v in u]), frequency=freq,
                             label=label, end="/".join(ends), boundary=point.changes_stability is not False)


def two_parameter_curves(model, result: ContinuationResult, parameter2: str, start2: float, stop2: float, *,
                         settings: ContinuationSettings | None = None) -> tuple[TwoParameterCurve, ...]:
    """The fold and Hopf curves through every fold and Hopf point of ``result`` (mirror images, at
    the same parameter value and type, once; a point that an earlier curve passes through is
    not continued again)."""
    seen: list[tuple[str, float]] = []
    out: list[TwoParameterCurve] = []
    p2 = current_value(as_machine(model), parameter2)
    for b in result.branches:
        for sp in b.special_points:
            if sp.type not in ("fold", "hopf"):
                continue
            if any(t == sp.type and abs(v - sp.value) <= 1e-7 * max(1.0, abs(v)) for t, v in seen):
                continue
            if any(c.type == sp.type and _passes_through(c, sp, p2) for c in out):
                continue  # two Hopf points of one curve (it crosses the branch's line twice)
            seen.append((sp.type, sp.value))
            out.append(continue_special_point(model, sp, parameter2, start2, stop2, settings=settings,
                                              label=b.label))
    return tuple(out)


def _passes_through(curve: TwoParameterCurve, point: SpecialPoint, p2: float) -> bool:
    """Whether ``curve`` crosses the line ``parameter2 = p2`` at ``point`` (its parameter value
    and, on a Hopf curve, its frequency): between two of the curve's points, within a quarter
    of their distance of the linear interpolation (the curve bends little between points)."""
    v, f = curve.values, curve.frequency
    d = v[:, 1] - p2
    for k in np.flatnonzero(d[:-1] * d[1:] <= 0.0):
        if d[k] == d[k + 1]:
            continue
        t = d[k] / (d[k] - d[k + 1])
        near = abs(v[k, 0] + t * (v[k + 1, 0] - v[k, 0]) - point.value) <= 0.25 * abs(v[k + 1, 0] - v[k, 0]) + 1e-9
        if np.isfinite(f[k]) and np.isfinite(f[k + 1]):  # a curve with a frequency (Hopf): it must agree
            near = near and abs(f[k] + t * (f[k + 1] - f[k]) - point.frequency) <= 0.25 * abs(f[k + 1] - f[k]) + 1e-6 * point.frequency
        if near:
            return True
    return False
