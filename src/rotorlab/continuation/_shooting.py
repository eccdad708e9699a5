"""Multiple shooting for periodic orbits on the compiled ensemble integrator.

An orbit of period ``T`` is cut into ``m`` segments with starts ``x_0 .. x_{m-1}``; the unknowns
are the starts, the period (an autonomous orbit) and the continued parameter ``lam``, and the
equations are the continuity of consecutive segments, the closing of the last one onto the first
(``phi(x_{m-1}) = x_0 + 2 pi k`` with ``k`` the winding of each coordinate: an angle of the
co-rotating frame may return only modulo whole turns) and, for an autonomous orbit, a phase
condition. Each evaluation integrates the ``m`` starts, their ``2 n`` copies perturbed up and
down in each state (central-difference columns of the segment Jacobians) and two copies at the
perturbed parameter as one ensemble, ``m (2 n + 3)`` trajectories in one compiled call (one lane
group on the lane driver). Central differences (steps ``6e-6`` of each state's size) keep the
trivial multiplier within 3e-6 of 1 next to a multiplier of 1163 (the Van der Pol cycle run
backwards; about 1e-8 on the stable cycle); forward ones (1e-7) left 3e-5 there.

Why fixed steps: the segments are integrated by the compiled Dormand–Prince 5 scheme with a
fixed number of equal steps per segment (first and largest step equal, error control off), the
same for the nominal and every perturbed start. The finite differences are then derivatives of
one smooth map (the discrete flow), accurate to about ``sqrt(eps)``; with adaptive steps each
perturbed start would choose its own steps and the columns would carry errors of the order of
the tolerance divided by the perturbation (about 1e-3 at rtol 1e-10), enough to move a Floquet
multiplier across the unit circle. The number of steps per period is chosen once, from an
adaptive integration of the starting orbit at ``rtol`` (1.5 times its step count).

Phase condition: ``sum_i ((x_i - r_i) / s) . (f(r_i) / s) = 0`` against the previous orbit ``r``
(AUTO's and BifurcationKit's choice, discretised at the segment starts, ``s`` the typical size
of each state); :meth:`Shooting.set_reference` moves ``r`` to each accepted orbit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from rotorlab.integrate import Lanes, SaveAt, StepControl, solve_ensemble

__all__ = ["Shooting", "refuse_events", "steps_per_period"]

BACKEND = Lanes(8)  # one compiled driver per model, whatever the number of trajectories


def refuse_events(model: Any) -> None:
    """Raise ValueError if the model has events: shooting needs a smooth flow."""
    kernels = getattr(model, "kernels", model)
    specs = getattr(kernels, "event_specs", ())
    if specs:
        names = ", ".join(s.name for s in specs)
        raise ValueError(
            f"periodic orbits of a model with events ({names}) are not supported: multiple shooting "
            "differentiates the flow, and an impact, stick-slip switch or contact makes it "
            "non-smooth at the events; continue the equilibria of the smooth part instead, or "
            "remove the events (a model without friction or contact)"
        )


def _control(span: float, k: int) -> StepControl:
    """``k`` equal Dormand–Prince steps over ``span`` (error control off: every step accepted)."""
    h = span / k * (1.0 + 1e-9)  # the k-th step is clipped onto the end: exactly k steps
    return StepControl(rtol=0.5, atol=1e300, first_step=h, max_step=h, max_steps=k + 8)


def steps_per_period(model: Any, y0: np.ndarray, period: float, params: np.ndarray, rtol: float,
                     typ: np.ndarray, t0: float = 0.0) -> int:
    """1.5 times the most accepted steps of adaptive integrations over one period at ``rtol``
    from ``y0`` and from ``y0`` moved by its typical size in each state (the linearised flow,
    hence the multipliers, must be resolved too, also about an orbit at rest)."""
    y0 = np.asarray(y0, dtype=float)
    starts = np.vstack([y0, y0 + np.diag(typ)])
    sol = solve_ensemble(model, starts, (t0, t0 + period), params=params,
                         control=StepControl(rtol=rtol, atol=rtol * typ), backend=BACKEND)
    if int(sol.status[0]) != 0:
        raise ValueError(f"the starting orbit cannot be integrated over one period: {sol.status[0]!r}")
    ok = sol.status == 0
    return max(8, int(math.ceil(1.5 * sol.stats[ok, 1].max())))


class Shooting:
    """The multiple-shooting residual ``F(u)``, ``u = (x_0, .., x_{m-1}, [T], lam)``, and its Jacobian.

    Parameters
    ----------
    model : model
        A smooth model (``kernels`` without events).
    params_at : callable
        ``lam -> packed parameter vector`` of the model.
    segments : int
        ``m >= 1``.
    steps : int
        Fixed Dormand–Prince steps per period (``ceil(steps / m)`` per segment).
    typ : array_like, shape (n,)
        Typical size of each state (finite-difference steps, phase condition).
    winding : array_like of int, shape (n,)
        Whole turns of each coordinate per period (0 for ordinary coordinates).
    forcing_period : float, optional
        A forced (time-periodic) system: the period is this fixed value and not an unknown, and
        there is no phase condition. None: an autonomous orbit.
    lam_scale : float
        Typical size of the parameter (its finite-difference step).
    """

    def __init__(self, model: Any, params_at: Callable[[float], np.ndarray], *, segments: int, steps: int,
                 typ: np.ndarray, winding: np.ndarray, forcing_period: float | None = None,
                 lam_scale: float = 1.0, fd_rel: float = 6e-6):
        refuse_events(model)
        if int(segments) < 1:
            raise ValueError(f"segments must be >= 1, got {segments!r}")
        self.model = model
        self.kernels = model.kernels
        self.n = self.kernels.n_state
        self.m = int(segments)
        self.params_at = params_at
        self.k = max(4, int(math.ceil(steps / self.m)))
        self.typ = np.asarray(typ, dtype=float)
        self.winding = np.asarray(winding, dtype=float)
        self.forcing_period = forcing_period
        self.autonomous = forcing_period is None
        self.lam_scale = float(lam_scale)
        self.fd_rel = float(fd_rel)
        self.size = self.m * self.n + (1 if self.autonomous else 0) + 1
        self.density = math.inf  # steps per second, set by the first reference orbit
        self._cache: dict[bytes, tuple] = {}
        self._ref: np.ndarray | None = None
        self._ref_flow: np.ndarray | None = None

    # ---- layout -----------------------------------------------------------------------------
    def unpack(self, u: np.ndarray) -> tuple[np.ndarray, float, float]:
        """The segment starts (m, n), the period and the parameter of ``u``."""
        x = np.asarray(u[: self.m * self.n], dtype=float).reshape(self.m, self.n)
        period = float(u[self.m * self.n]) if self.autonomous else float(self.forcing_period)
        return x, period, float(u[-1])

    def pack(self, starts: np.ndarray, period: float, lam: float) -> np.ndarray:
        head = np.asarray(starts, dtype=float).ravel()
        return np.concatenate([head, [period] if self.autonomous else [], [lam]])

    def flow(self, t: float, y: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The vector field ``f(t, y)`` with parameters ``p`` (the model's compiled rhs)."""
        out = np.empty(self.n)
        self.kernels.rhs(float(t), np.ascontiguousarray(y, dtype=float), p, out)
        return out

    def set_reference(self, u: np.ndarray) -> None:
        """Make the orbit ``u`` the reference of the phase condition."""
        if not self.autonomous:
            return
        x, period, lam = self.unpack(u)
        # the same step density as the first orbit's: a period that grows along the branch (near a
        # homoclinic or saddle-node-on-circle end) keeps its resolution
        if period > 0 and math.isfinite(period):
            if not math.isfinite(self.density):
                self.density = self.k * self.m / period
            self.k = max(4, int(math.ceil(self.density * period / self.m)))
        p = np.asarray(self.params_at(lam), dtype=float)
        self._cache.clear()  # the phase row changes
        if self._ref is None:
            self._check_autonomous(x[0], period, p)
        self._ref = x.copy()
        self._ref_flow = np.array([self.flow(0.0, xi, p) for xi in x]) / self.typ**2
        self._ref_flow /= max(np.linalg.norm(self._ref_flow * self.typ), 1e-300)

    def _check_autonomous(self, x: np.ndarray, period: float, p: np.ndarray) -> None:
        """Raise ValueError if the vector field depends on time (a forced system, a speed ramp)."""
        f0, f1 = self.flow(0.0, x, p), self.flow(0.377 * period, x, p)
        # A forcing or a speed ramp changes the field by O(1); a co-rotating machine kernel (which
        # turns the state by the spin angle theta(t) into the fixed frame and back) changes it by
        # round-off only: 1.9e-11 of its largest entry on zhakash-k2 at 1371 rpm. Hence 1e-9.
        if not np.allclose(f0, f1, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(f0), initial=1e-300))):
            raise ValueError(
                "the model's right-hand side depends on time (a forcing or a varying speed): an autonomous "
                "periodic orbit has no fixed period; give forced=True and the forcing's period"
            )

    # ---- integration ------------------------------------------------------------------------
    def segment_times(self, period: float) -> np.ndarray:
        return np.arange(self.m) * (period / self.m) if not self.autonomous else np.zeros(self.m)

    def _integrate(self, y0: np.ndarray, params: np.ndarray, period: float, per_segment: int,
                   save: np.ndarray | None = None):
        """Integrate ``per_segment`` rows per segment (rows grouped by segment) over one segment
        each; the final states (rows, n) and the saved states (rows, n_save, n) or None."""
        span = period / self.m
        ctrl = _control(span, self.k)
        if self.autonomous:
            sol = solve_ensemble(self.model, y0, (0.0, span), params=params, control=ctrl, backend=BACKEND,
                                 save_at=SaveAt(ts=save) if save is not None else SaveAt())
            ok = np.all(sol.status == 0)
            return (sol.y_final if ok else None), (sol.ys if ok and save is not None else None)
        finals, saved = [], []
        for i, t0 in enumerate(self.segment_times(period)):
            rows = slice(i * per_segment, (i + 1) * per_segment)
            prow = params if params.shape[0] == 1 else params[rows]
            sol = solve_ensemble(self.model, y0[rows], (t0, t0 + span), params=prow, control=ctrl, backend=BACKEND,
                                 save_at=SaveAt(ts=t0 + save) if save is not None else SaveAt())
            if not np.all(sol.status == 0):
                return None, None
            finals.append(sol.y_final)
            saved.append(sol.ys)
        return np.vstack(finals), (np.concatenate(saved) if save is not None else None)

    def evaluate(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The residual, its Jacobian, the segment Jacobians (m, n, n) and the segment ends (m, n)."""
        u = np.asarray(u, dtype=float)
        key = u.tobytes()
        if key in self._cache:
            return self._cache[key]
        n, m = self.n, self.m
        x, period, lam = self.unpack(u)
        hx = self.fd_rel * np.maximum(self.typ, np.abs(x))
        hl = self.fd_rel * max(self.lam_scale, abs(lam))
        rows = 2 * n + 3  # nominal, +h_j, -h_j, lam + h, lam - h
        y0 = np.repeat(x[:, None, :], rows, axis=1)
        idx = np.arange(n)
        y0[:, 1 + idx, idx] += hx
        y0[:, 1 + n + idx, idx] -= hx
        p0 = np.asarray(self.params_at(lam), dtype=float)
        params = np.repeat(p0[None, :], m * rows, axis=0).reshape(m, rows, -1)
        params[:, rows - 2] = np.asarray(self.params_at(lam + hl), dtype=float)
        params[:, rows - 1] = np.asarray(self.params_at(lam - hl), dtype=float)
        size = m * n + (1 if self.autonomous else 0)
        ends = None
        if period > 0 and math.isfinite(period) and np.all(np.isfinite(params)) and np.all(np.isfinite(y0)):
            ends, _ = self._integrate(y0.reshape(-1, n), params.reshape(m * rows, -1), period, rows)
        if ends is None or not np.all(np.isfinite(ends)):
            out = (np.full(size, np.nan), np.full((size, self.size), np.nan),
                   np.full((m, n, n), np.nan), np.full((m, n), np.nan))
            self._remember(key, out)
            return out
        ends = ends.reshape(m, rows, n)
        e = ends[:, 0]
        g = np.transpose((ends[:, 1 : n + 1] - ends[:, n + 1 : 2 * n + 1]) / (2 * hx[:, :, None]), (0, 2, 1))
        dlam = (ends[:, rows - 2] - ends[:, rows - 1]) / (2 * hl)
        r = e - np.roll(x, -1, axis=0)
        r[-1] -= 2.0 * math.pi * self.winding
        jac = np.zeros((size, self.size))
        for i in range(m):
            rows = slice(i * n, (i + 1) * n)
            jac[rows, i * n : (i + 1) * n] += g[i]
            j = (i + 1) % m
            jac[rows, j * n : (j + 1) * n] -= np.eye(n)
            jac[rows, -1] = dlam[i]
        f = r.ravel()
        if self.autonomous:
            t_end = np.zeros(m)
            for i in range(m):
                jac[i * n : (i + 1) * n, m * n] = self.flow(t_end[i], e[i], p0) / m
            if self._ref is None:
                self.set_reference(u)
            phase = float(np.sum((x - self._ref) * self._ref_flow))
            jac[-1, : m * n] = self._ref_flow.ravel()
            f = np.concatenate([f, [phase]])
        out = (f, jac, g, e)
        self._remember(key, out)
        return out

    def _remember(self, key: bytes, value: tuple) -> None:
        if len(self._cache) >= 8:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = value

    def residual(self, u: np.ndarray) -> np.ndarray:
        return self.evaluate(u)[0]

    def jacobian(self, u: np.ndarray) -> np.ndarray:
        return self.evaluate(u)[1]

    def sample(self, u: np.ndarray, per_segment: int) -> np.ndarray:
        """The orbit at ``m * per_segment`` equally spaced times over one period, shape (., n)."""
        x, period, lam = self.unpack(u)
        span = period / self.m
        ts = np.linspace(0.0, span, per_segment + 1)[:-1]
        p0 = np.asarray(self.params_at(lam), dtype=float)
        _, ys = self._integrate(x, p0[None, :], period, 1, save=ts)
        if ys is None:
            raise ValueError("the orbit could not be integrated for sampling")
        return ys.reshape(self.m * per_segment, self.n)
