"""Pseudo-arclength continuation of a curve of solutions of ``F(x, lam) = 0``.

The model-independent part of :mod:`rotorlab.continuation`: it follows a one-dimensional
solution curve of ``n`` equations in ``n + 1`` unknowns ``u = (x, lam)`` through folds (Keller's
pseudo-arclength method), watches scalar test functions along it and locates their zeros (folds,
branch points, Hopf points, ...) to a tolerance in ``lam``; :func:`switch_branch` starts the
other branch through a simple branch point. Equilibria of a machine, fold and Hopf curves in two
parameters and periodic orbits are each one residual handed to :func:`continue_curve`.

Written here rather than taken from a library: the Python continuation packages (PyDSTool's
PyCont, pde2path's ports, pycont) are unmaintained or tied to their own model formats, and the
maintained tools (AUTO-07p, BifurcationKit.jl, COCO) are Fortran, Julia and MATLAB. The method
is the textbook one (Keller 1977; Allgower & Georg 2003, ch. 2; Kuznetsov 2004, ch. 10).

Notes
-----
Each step predicts along the unit tangent ``t`` (``J t = 0``, ``|t| = 1`` in scaled variables,
oriented as the previous tangent), ``u_p = u + ds t``, and corrects with Newton's method on

    F(u) = 0,    t . (u - u_p) = 0,

whose Jacobian ``[J; t]`` is regular at regular points and at folds. A step whose Newton
iteration fails or that turns the tangent by more than ``max_turn`` is halved; a step that
converged in few iterations grows. Variables are scaled by ``scale`` (a typical size of each
unknown) so that metres, radians and rad/s weigh alike in the arclength. Where the sizes change
along the curve (a structure whose whirl grows twenty-fold near a resonance), ``rescale`` gives
them at each accepted point and the next step measures the arclength with them, the tangent
re-expressed in the new units: the step then follows the branch's own variables, as AUTO's and
BifurcationKit's weighted arclength norms (Doedel et al., AUTO-07p manual, the ``THU`` weights;
Salinger et al. 2002, LOCA's arclength scaling) do with a fixed or a parameter-driven weight.

A test function ``tau(point)`` whose sign differs between two consecutive points has a zero
between them; it is located by the Illinois variant of regula falsi on the arclength from the
earlier point, each trial point corrected onto the curve, until the parameter changes by less
than ``locate_tol`` between trials.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

import numpy as np

__all__ = [
    "ContinuationSettings",
    "CurvePoint",
    "Crossing",
    "Curve",
    "continue_curve",
    "switch_branch",
    "numerical_jacobian",
    "fold_test",
    "branch_point_test",
]


@dataclass(frozen=True)
class ContinuationSettings:
    """How :func:`continue_curve` steps.

    Parameters
    ----------
    ds : float
        First step, in scaled arclength (> 0).
    ds_min, ds_max : float
        Smallest and largest step; a step that fails at ``ds_min`` ends the curve.
    max_points : int
        Most points on the curve.
    newton_tol : float
        Convergence of the corrector: max-norm of the scaled update.
    max_newton : int
        Most corrector iterations per step.
    max_turn : float
        Largest angle (rad) between consecutive tangents; a larger turn halves the step.
    locate_tol : float
        Tolerance of a located zero of a test function, in the parameter ``lam``.
    bounds : (float, float)
        The parameter range; the curve ends where it leaves it (the last point lies on the bound).
    direction : {1, -1}
        Initial direction of ``lam`` (+1: increasing).
    chord : bool
        Correct each step with the Jacobian of the last accepted point (a chord method: no new
        Jacobian during the iterations; full Newton only where the chord iteration fails). For
        residuals whose Jacobian costs many residual calls (the fold and Hopf curves).
    periodic : tuple of int
        Indices of unknowns that are angles (period 2 pi): a curve that comes back to its first
        point with such an angle a whole number of turns on is closed (it would otherwise go
        round again, e.g. a steady motion whose ball angles wind once around the race).
    """

    ds: float = 1e-2
    ds_min: float = 1e-9
    ds_max: float = 5e-2
    max_points: int = 400
    newton_tol: float = 1e-10
    max_newton: int = 10
    max_turn: float = 0.35
    locate_tol: float = 1e-9
    bounds: tuple[float, float] = (-math.inf, math.inf)
    direction: int = 1
    chord: bool = False
    periodic: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        if not (0 < self.ds_min <= self.ds <= self.ds_max):
            raise ValueError(f"need 0 < ds_min <= ds <= ds_max, got {self.ds_min}, {self.ds}, {self.ds_max}")
        if self.max_points < 2 or self.max_newton < 1:
            raise ValueError("max_points must be >= 2 and max_newton >= 1")
        if self.direction not in (1, -1):
            raise ValueError(f"direction must be 1 or -1, got {self.direction!r}")
        lo, hi = self.bounds
        if not lo < hi:
            raise ValueError(f"bounds must be (lo, hi) with lo < hi, got {self.bounds!r}")


@dataclass(frozen=True)
class CurvePoint:
    """One point of a curve: ``u = (x, lam)``, its unit tangent (scaled), the Jacobian ``dF/du``
    (n, n + 1) and the arclength from the first point (scaled)."""

    u: np.ndarray
    tangent: np.ndarray
    jacobian: np.ndarray
    s: float

    @property
    def lam(self) -> float:
        return float(self.u[-1])

    @property
    def x(self) -> np.ndarray:
        return self.u[:-1]


@dataclass(frozen=True)
class Crossing:
    """A located zero of the test function ``name`` between points ``index - 1`` and ``index``
    of the curve, at ``point``."""

    name: str
    index: int
    point: CurvePoint
    converged: bool


@dataclass(frozen=True)
class Curve:
    """A continued curve: its points in order, the located zeros of the test functions, and why
    it ended (``"bound"``, ``"max_points"``, ``"step"``: the corrector failed at ``ds_min``,
    ``"closed"``: it returned to its first point)."""

    points: tuple[CurvePoint, ...]
    crossings: tuple[Crossing, ...]
    end: str
    test_values: Mapping[str, np.ndarray] = field(default_factory=dict)

    @property
    def u(self) -> np.ndarray:
        return np.array([p.u for p in self.points])

    @property
    def lam(self) -> np.ndarray:
        return np.array([p.lam for p in self.points])


Residual = Callable[[np.ndarray], np.ndarray]
Jacobian = Callable[[np.ndarray], np.ndarray]
TestFunction = Callable[[CurvePoint], float]


def numerical_jacobian(residual: Residual, scale: np.ndarray, rel: float = 1e-7) -> Jacobian:
    """A central-difference Jacobian of ``residual`` (n -> n, n + 1 unknowns), steps ``rel * scale``."""

    def jac(u: np.ndarray) -> np.ndarray:
        cols = []
        for j in range(u.size):
            h = rel * max(scale[j], abs(u[j]))
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            cols.append((residual(up) - residual(um)) / (2 * h))
        return np.array(cols).T

    return jac


def fold_test(point: CurvePoint) -> float:
    """Zero at a fold (limit point) of ``lam``: the parameter's component of the tangent."""
    return float(point.tangent[-1])


def branch_point_test(point: CurvePoint) -> float:
    """Zero at a simple branch point: the determinant of the bordered Jacobian ``[J; t]``
    (it keeps its sign through folds). Returned as ``sign(det) * |det|**(1/m)`` so that its size
    does not under- or overflow for large systems."""
    a = np.vstack([point.jacobian, point.tangent])
    sign, logdet = np.linalg.slogdet(a)
    return float(sign * math.exp(logdet / a.shape[0])) if sign != 0 else 0.0


class _Stepper:
    """Tangent, corrector and scaling shared by the continuation and the zero location."""

    def __init__(self, residual: Residual, jacobian: Jacobian | None, scale: np.ndarray,
                 settings: ContinuationSettings):
        self.F = residual
        self.scale = np.asarray(scale, dtype=float)
        self.J = jacobian if jacobian is not None else numerical_jacobian(residual, self.scale)
        self.st = settings

    def jac_scaled(self, u: np.ndarray) -> np.ndarray:
        return np.asarray(self.J(u), dtype=float) * self.scale[None, :]

    def tangent(self, js: np.ndarray, previous: np.ndarray) -> np.ndarray:
        """Unit null vector of the scaled Jacobian, oriented along ``previous``."""
        a = np.vstack([js, previous])
        rhs = np.zeros(a.shape[0])
        rhs[-1] = 1.0
        try:
            t = np.linalg.solve(a, rhs)
        except np.linalg.LinAlgError:
            t = np.linalg.svd(js)[2][-1]
        t /= np.linalg.norm(t)
        return t if t @ previous >= 0 else -t

    def correct(self, u_pred: np.ndarray, t: np.ndarray, chord: np.ndarray | None = None,
                stall: bool = False, radius: float = math.inf) -> tuple[np.ndarray | None, int]:
        """Newton on ``F(u) = 0, t . (u - u_pred) = 0`` (scaled); the point and the iterations.
        With ``chord`` (a Jacobian dF/du, unscaled) that matrix serves every iteration.

        ``stall``: also accept an update below ``1e3 * newton_tol`` once the residual stops
        falling (it is at round-off): next to a branch point ``[J; t]`` is nearly singular and
        the updates stay at round-off times its condition number (1e-10 at a condition of 3e10),
        above ``newton_tol``, while the point is known far better than the zero it brackets.
        ``radius``: no update longer than it (max-norm, scaled): there the nearly singular
        system's Newton step overshoots along its near-null direction."""
        w = u_pred / self.scale
        w_pred = w.copy()
        fixed = None if chord is None else np.vstack([chord * self.scale[None, :], t])
        f_prev = math.inf
        most = self.st.max_newton if math.isinf(radius) else 3 * self.st.max_newton  # shorter updates: more
        for k in range(1, most + 1):
            u = w * self.scale
            f = np.asarray(self.F(u), dtype=float)
            if not np.all(np.isfinite(f)):
                return None, k
            f_norm = float(np.max(np.abs(f)))
            stalled = stall and k > 1 and f_norm >= 0.5 * f_prev
            f_prev = f_norm
            a = fixed if fixed is not None else np.vstack([self.jac_scaled(u), t])
            r = np.concatenate([f, [t @ (w - w_pred)]])
            try:
                dw = np.linalg.solve(a, -r)
            except np.linalg.LinAlgError:
                return None, k
            big = float(np.max(np.abs(dw)))
            w = w + (dw if big <= radius else dw * (radius / big))
            tol = self.st.newton_tol * max(1.0, np.max(np.abs(w)))
            if np.max(np.abs(dw)) <= (1e3 * tol if stalled else tol):
                u = w * self.scale
                return (u, k) if np.all(np.isfinite(u)) else (None, k)
        return None, most

    def point(self, u: np.ndarray, previous_t: np.ndarray, s: float) -> CurvePoint:
        js = self.jac_scaled(u)
        t = self.tangent(js, previous_t)
        return CurvePoint(u=u, tangent=t, jacobian=js / self.scale[None, :], s=s)


def _first_point(stepper: _Stepper, u0: np.ndarray, tangent0: np.ndarray | None, direction: int) -> CurvePoint:
    u0 = np.asarray(u0, dtype=float)
    n1 = u0.size
    if tangent0 is None:
        guess = np.zeros(n1)
        guess[-1] = float(direction)
    else:
        guess = np.asarray(tangent0, dtype=float) / stepper.scale
        guess /= np.linalg.norm(guess)
    # put u0 on the curve: Newton at fixed lam (the bordering row fixes the parameter), or across
    # a given tangent (near a Hopf point the orbits at a fixed lam are nearly a fold: singular)
    fix = np.zeros(n1)
    fix[-1] = 1.0
    if tangent0 is not None:
        fix = guess.copy()
    u, _ = stepper.correct(u0, fix)
    if u is None:
        raise ValueError("the starting point does not converge onto a solution (Newton failed at fixed parameter)")
    return stepper.point(u, guess, 0.0)


def continue_curve(
    residual: Residual,
    u0: np.ndarray,
    *,
    jacobian: Jacobian | None = None,
    scale: np.ndarray | None = None,
    settings: ContinuationSettings = ContinuationSettings(),
    tests: Mapping[str, TestFunction] | None = None,
    tangent0: np.ndarray | None = None,
    on_point: Callable[[CurvePoint], None] | None = None,
    rescale: Callable[[np.ndarray], np.ndarray] | None = None,
) -> Curve:
    """Follow the solution curve of ``residual(u) = 0`` through ``u0``.

    Parameters
    ----------
    residual : callable
        ``F(u) -> (n,)`` for ``u = (x, lam)`` of size ``n + 1``.
    u0 : array_like, shape (n + 1,)
        A point on or near the curve; it is first corrected at fixed ``lam``.
    jacobian : callable, optional
        ``dF/du (u) -> (n, n + 1)``; default central differences.
    scale : array_like, shape (n + 1,), optional
        Typical size of each unknown (default 1); the arclength is measured in ``u / scale``.
    settings : ContinuationSettings
    tests : mapping of str to callable, optional
        Test functions ``tau(CurvePoint) -> float``; each sign change between consecutive points
        is located (:class:`Crossing`). Default: ``{"fold": fold_test, "branch":
        branch_point_test}``.
    tangent0 : array_like, optional
        Initial direction (unscaled); default along ``lam`` in ``settings.direction``.
    on_point : callable, optional
        Called with each accepted point (the first one included), after the test functions were
        evaluated there: a residual whose condition follows the curve (the phase condition of a
        periodic orbit against the previous orbit) updates itself here.
    rescale : callable, optional
        ``u -> scale`` (n + 1 positive numbers): the typical sizes at an accepted point, used
        from it on in place of ``scale`` (the arclength measured in the branch's own variables).

    Returns
    -------
    Curve

    Raises
    ------
    ValueError
        If ``u0`` does not converge onto the curve.

    Examples
    --------
    The circle ``x**2 + lam**2 = 1`` passes two folds of ``lam`` (at ``lam = +-1``):

    >>> import numpy as np
    >>> from rotorlab.continuation._core import ContinuationSettings, continue_curve
    >>> c = continue_curve(lambda u: np.array([u[0]**2 + u[1]**2 - 1.0]), [0.8, 0.5],
    ...                    settings=ContinuationSettings(ds=0.05, ds_max=0.1, max_points=200))
    >>> c.end, sorted(round(z.point.lam, 8) for z in c.crossings if z.name == "fold")
    ('closed', [-1.0, 1.0])
    """
    u0 = np.asarray(u0, dtype=float)
    scale = np.ones(u0.size) if scale is None else np.asarray(scale, dtype=float)
    if scale.shape != u0.shape or np.any(scale <= 0) or not np.all(np.isfinite(scale)):
        raise ValueError(f"scale must be {u0.size} positive finite numbers")
    tests = {"fold": fold_test, "branch": branch_point_test} if tests is None else dict(tests)
    st = settings
    stepper = _Stepper(residual, jacobian, scale, st)
    p = _first_point(stepper, u0, tangent0, st.direction)
    points = [p]
    values = {k: [fn(p)] for k, fn in tests.items()}
    if on_point is not None:
        on_point(p)
    crossings: list[Crossing] = []
    ds, end = st.ds, "max_points"
    lo, hi = st.bounds
    while len(points) < st.max_points:
        if rescale is not None:
            p = _rescaled(stepper, p, rescale(p.u))
            scale = stepper.scale
        q = None
        while ds >= st.ds_min:
            q, its = _step(stepper, p, ds)
            if q is not None:
                break
            ds *= 0.5
        if q is None:
            end = "step"
            break
        if lo <= q.lam <= hi and any(_changes(values[k][-1], fn(q)) for k, fn in tests.items()):
            walk = _walk(stepper, p, ds)
            if walk and not _same_branch(stepper, p, walk, q, ds):
                (q, its), ds = walk[0], ds / 8  # the full step jumped onto a branch passing close by
        if not lo <= q.lam <= hi:
            # the last point on the bound: solve at fixed lam = bound from the predicted point
            bound = hi if q.lam > hi else lo
            fix = np.zeros(u0.size)
            fix[-1] = 1.0
            frac = (bound - p.lam) / (q.lam - p.lam)
            guess = p.u + frac * (q.u - p.u)
            guess[-1] = bound
            u, _ = stepper.correct(guess, fix)
            if u is None:
                end = "bound"
                break
            q = stepper.point(u, p.tangent, p.s + frac * ds)
            end = "bound"
        for k, fn in tests.items():
            v = fn(q)
            if _changes(values[k][-1], v):
                z = _locate(stepper, p, q, fn, values[k][-1], v, st)
                crossings.append(Crossing(name=k, index=len(points), point=z[0], converged=z[1]))
            values[k].append(v)
        points.append(q)
        if on_point is not None:
            on_point(q)
        if end == "bound":
            break
        if len(points) > 3 and _passes(points[0].u, p.u, q.u, scale, st.periodic):
            end = "closed"
            break
        p = q
        if its <= (6 if st.chord else 3):  # a chord iteration contracts linearly: more of them
            ds = min(st.ds_max, 1.5 * ds)
        elif its >= st.max_newton - 2:
            ds = max(st.ds_min, 0.7 * ds)
    return Curve(points=tuple(points), crossings=tuple(crossings), end=end,
                 test_values={k: np.array(v) for k, v in values.items()})


def _changes(a: float, b: float) -> bool:
    return a != 0.0 and b != 0.0 and np.sign(a) != np.sign(b)


def _step(stepper: _Stepper, p: CurvePoint, ds: float) -> tuple[CurvePoint | None, int]:
    """One predictor-corrector step of length ``ds`` from ``p`` (None: the corrector failed or
    the tangent turned by more than ``max_turn``) and the corrector's iterations."""
    st, scale = stepper.st, stepper.scale
    u_pred = (p.u / scale + ds * p.tangent) * scale
    u, its = stepper.correct(u_pred, p.tangent, p.jacobian) if st.chord else (None, 0)
    if u is None:
        u, its = stepper.correct(u_pred, p.tangent)
    if u is None:
        return None, its
    q = stepper.point(u, p.tangent, p.s + ds)
    return (q, its) if q.tangent @ p.tangent >= math.cos(st.max_turn) else (None, its)


def _walk(stepper: _Stepper, p: CurvePoint, ds: float, n: int = 10) -> list[tuple[CurvePoint, int]]:
    """Up to ``n`` steps of ``ds / 8`` from ``p`` along the curve (fewer where one fails)."""
    out, cur = [], p
    for _ in range(n):
        nxt, its = _step(stepper, cur, ds / 8)
        if nxt is None:
            break
        out.append((nxt, its))
        cur = nxt
    return out


def _same_branch(stepper: _Stepper, p: CurvePoint, walk: list, q: CurvePoint, ds: float) -> bool:
    """Whether the end ``q`` of a step of ``ds`` from ``p`` lies on the path walked from p in
    eighths of the step (within 2 % of the step, scaled). Where a test function changes sign
    (a branch point is bracketed, where a second branch crosses) the corrector of the full step
    may have converged onto a branch passing close by. rcfw-two-plane's side 0001 near 0.983
    rad/s: a step of 0.025 landed 0.027 away from the walk, on a neighbouring branch (a spurious
    fold and a branch point "not converged", put at 0.961 rad/s); two half steps jumped with it.
    A walk that stops short, or a branch that turns sharply, is wrongly suspected at worst: the
    step is cut to an eighth."""
    if len(walk) < 10:
        return False
    path = [p.u / stepper.scale] + [w.u / stepper.scale for w, _ in walk]
    x = q.u / stepper.scale
    for a, b in zip(path[:-1], path[1:]):
        e = b - a
        t = min(max(float((x - a) @ e) / float(e @ e), 0.0), 1.0) if e @ e > 0 else 0.0
        if float(np.max(np.abs(x - a - t * e))) <= 0.02 * ds:
            return True
    return False


def _rescaled(stepper: _Stepper, p: CurvePoint, new: np.ndarray) -> CurvePoint:
    """``p`` with its tangent in the units ``new`` (which the stepper then uses)."""
    new = np.asarray(new, dtype=float)
    if new.shape != p.u.shape or np.any(new <= 0) or not np.all(np.isfinite(new)):
        raise ValueError(f"rescale must give {p.u.size} positive finite numbers, got {new!r}")
    if np.array_equal(new, stepper.scale):
        return p
    t = p.tangent * stepper.scale / new
    stepper.scale = new
    return replace(p, tangent=t / np.linalg.norm(t))


def _passes(u0: np.ndarray, a: np.ndarray, b: np.ndarray, scale: np.ndarray, periodic: tuple[int, ...] = ()) -> bool:
    """True if the chord from ``a`` to ``b`` passes (within 5 % of its length) through ``u0``
    (its ``periodic`` angles taken the whole number of turns nearest ``a``)."""
    u0 = np.array(u0, dtype=float)
    if periodic:
        i = list(periodic)
        u0[i] = a[i] + np.angle(np.exp(1j * (u0[i] - a[i])))
    d, e = (u0 - a) / scale, (b - a) / scale
    ee = float(e @ e)
    if ee == 0.0:
        return False
    tau = float(d @ e) / ee
    return 0.0 <= tau <= 1.0 and float(np.linalg.norm(d - tau * e)) <= 0.05 * math.sqrt(ee)


def _locate(stepper: _Stepper, p: CurvePoint, q: CurvePoint, fn: TestFunction, fp: float, fq: float,
            st: ContinuationSettings) -> tuple[CurvePoint, bool]:
    """The zero of ``fn`` between ``p`` and ``q``: Illinois regula falsi on the distance along the
    chord from p to q, each trial corrected on the plane normal to the chord (both ends lie on
    the curve: next to a branch point, where a second curve crosses, the tangent line of p can
    lead the corrector onto the other one)."""
    chord = (q.u - p.u) / stepper.scale
    a, b = 0.0, float(np.linalg.norm(chord))
    chord = chord / b
    fa, fb = fp, fq
    best, lam_prev, side = q, math.inf, 0
    for _ in range(60):
        s = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        if not (min(a, b) < s < max(a, b)):
            s = 0.5 * (a + b)
        u_pred = (p.u / stepper.scale + s * chord) * stepper.scale
        u, _ = stepper.correct(u_pred, chord, stall=True, radius=0.1 * b)
        if u is None:
            return best, False
        m = stepper.point(u, p.tangent, p.s + s)
        fm = fn(m)
        best = m
        if abs(m.lam - lam_prev) <= st.locate_tol * max(1.0, abs(m.lam)) or fm == 0.0:
            return m, True
        lam_prev = m.lam
        if np.sign(fm) == np.sign(fb):
            b, fb = s, fm
            if side == 1:
                fa *= 0.5
            side = 1
        else:
            a, fa = s, fm
            if side == -1:
                fb *= 0.5
            side = -1
    return best, False


def switch_branch(
    residual: Residual,
    crossing: Crossing,
    *,
    jacobian: Jacobian | None = None,
    scale: np.ndarray | None = None,
    settings: ContinuationSettings = ContinuationSettings(),
    tests: Mapping[str, TestFunction] | None = None,
    offset: float | None = None,
    side: int = 1,
    rescale: Callable[[np.ndarray], np.ndarray] | None = None,
) -> Curve:
    """Continue the other branch through a located simple branch point.

    At a simple branch point the Jacobian ``dF/du`` has a two-dimensional null space; the new
    branch leaves along the null vector orthogonal to the tangent of the branch that found it.
    The first point is predicted at ``offset`` (scaled; default ``10 * settings.ds``) along it
    and corrected with that direction bordering Newton's method, and the new branch is continued
    away from the branch point. The direction is the one in which the parameter increases
    (``settings.direction``) or, where the new branch leaves at constant parameter (a pitchfork),
    the one whose largest component is positive; ``side=-1`` takes the opposite one (the other
    half of a pitchfork). ``rescale`` as in :func:`continue_curve` (the new branch only).

    Raises
    ------
    ValueError
        If the first point of the new branch does not converge, or converges back onto the old
        branch.
    """
    if side not in (1, -1):
        raise ValueError(f"side must be 1 or -1, got {side!r}")
    bp = crossing.point
    u_bp = bp.u
    scale = np.ones(u_bp.size) if scale is None else np.asarray(scale, dtype=float)
    stepper = _Stepper(residual, jacobian, scale, settings)
    js = stepper.jac_scaled(u_bp)
    null = np.linalg.svd(js)[2][-2:]  # the two smallest right singular vectors
    t_old = bp.tangent
    # the null vector orthogonal to the old tangent, within the null space
    c = null @ t_old
    t_new = null[0] * c[1] - null[1] * c[0]
    t_new /= np.linalg.norm(t_new)
    lead = t_new[-1] if abs(t_new[-1]) > 1e-6 else t_new[np.argmax(np.abs(t_new))]
    t_new = t_new * (np.sign(lead) * settings.direction * side)
    h = 10 * settings.ds if offset is None else float(offset)
    u_pred = (u_bp / scale + h * t_new) * scale
    u, _ = stepper.correct(u_pred, t_new)
    if u is None:
        raise ValueError("the new branch does not converge from the branch point")
    on_old = np.linalg.norm((u - u_bp) / scale - ((u - u_bp) / scale @ t_old) * t_old)
    if on_old < 0.1 * h:
        raise ValueError("the corrected point fell back onto the old branch; not a simple branch point?")
    tangent = (u - u_bp) / scale
    return continue_curve(residual, u, jacobian=jacobian, scale=scale, settings=settings, tests=tests,
                          tangent0=tangent * scale, rescale=rescale)
