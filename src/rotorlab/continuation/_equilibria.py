"""Branches of steady motions of a machine with balls, continued in one named parameter.

:func:`continue_equilibria` starts from steady motions of seeds 002/003's classification
(:func:`rotorlab.continuation.starting_motions`), follows each by pseudo-arclength continuation
(:func:`rotorlab.continuation.continue_curve`) with the exact eigenvalues at every point, locates
folds, Hopf points (with their frequency) and branch points, and switches at every branch point
onto the branch that crosses there (balls apart <-> balls together), both halves.

Notes
-----
Test functions along a branch: the fold test is the parameter's component of the tangent, the
branch-point test the determinant of the bordered Jacobian ``[dF/du; t]`` (both from
:mod:`rotorlab.continuation._core`), the Hopf test the bialternate-product determinant
``prod_{i<j} (lam_i + lam_j)`` of the co-rotating linearization's eigenvalues
(:meth:`MachineEquilibria.hopf_test`). A zero of the Hopf test where no complex pair lies on
the imaginary axis is a neutral saddle and is dropped; a fold located at a branch point (the
parabola of a pitchfork turns there) is reported once, as the branch point.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from rotorlab.continuation._anisotropic import ANISOTROPY, anisotropy_curves
from rotorlab.continuation._core import (
    ContinuationSettings,
    Curve,
    branch_point_test,
    continue_curve,
    fold_test,
    switch_branch,
)
from rotorlab.continuation._machine_problem import (
    MachineEquilibria,
    as_machine,
    format_value,
    parameter_unit,
    smooth_part_note,
    starting_motions,
    with_value,
)
from rotorlab.continuation._result import Branch, ContinuationResult, SpecialPoint

__all__ = ["continue_equilibria", "equilibrium_settings", "describe_branch"]


def equilibrium_settings(start: float, stop: float, **kw) -> ContinuationSettings:
    """Stepping for a branch from ``start`` to ``stop`` (the arclength's parameter unit is the range).

    Steps of at most 5 % of the range (in the scaled arclength, states included): two Hopf points
    closer together than a step leave the Hopf test's sign unchanged and are not seen, so a
    narrow stable window needs ``ds_max`` smaller (Rodrigues et al. 2008, Fig. 5(a): 0.012 rad/s
    wide at m = 0.015, found with ``ds_max=0.0025`` over 1.5-6 rad/s,
    tests/validation/test_continuation_rcfw.py).
    """
    lo, hi = min(start, stop), max(start, stop)
    base = dict(ds=0.01, ds_min=1e-7, ds_max=0.05, max_points=1000, newton_tol=1e-11, locate_tol=1e-10,
                bounds=(lo, hi), direction=1 if stop > start else -1)
    base.update(kw)
    return ContinuationSettings(**base)


def _scale(prob: MachineEquilibria, start: float, stop: float) -> np.ndarray:
    sc = prob.scale([1.0])
    sc[-1] = abs(stop - start)
    return sc


def _kind(prob: MachineEquilibria, u) -> str:
    """balanced / balls together / balls apart, from the state."""
    if prob.amplitude(u) <= 1e-9 * prob.z_scale:
        return "balanced"
    psi = np.asarray(u[prob.nz:prob.n])
    if psi.size > 1 and np.max(np.abs(np.angle(np.exp(1j * (psi - psi[0]))))) < 1e-6:
        return "balls together"
    return "balls apart"


def describe_branch(label: str) -> str:
    """Who a sentence speaks of: ``"balancing"`` for a balanced branch, else the branch's label."""
    return "balancing" if label.startswith(("main", "balanced")) else f"the {label} motion"


def _sentence(kind: str, who: str, value: str, before: bool, after: bool, up: bool, frequency: float,
              other: str = "") -> str:
    if kind == "hopf":
        pair = (f"a pair of eigenvalues crosses the imaginary axis at {value} with frequency "
                f"{frequency / (2 * math.pi):.4g} Hz ({frequency:.5g} rad/s, co-rotating frame)")
        if before == after:
            return f"{pair}; {who} stays {'stable' if after else 'unstable'} (another pair decides)"
        stable_above = after if up else before
        verb = "becomes stable above" if stable_above else "is stable only below"
        return f"{who} {verb} {value}: {pair}, where a whirl is born or dies"
    if kind == "fold":
        return (f"{who} turns back at {value}: it meets another steady motion and both vanish beyond "
                f"it (a fold)")
    return (f"{who} meets another branch of steady motions at {value}" + (f" ({other})" if other else "")
            + ": a symmetry-breaking branch point")


class _Builder:
    """Turns curves into Branches with their special points (one continuation run)."""

    def __init__(self, prob: MachineEquilibria, name: str, unit: str):
        self.prob, self.name, self.unit = prob, name, unit

    def branch(self, curve: Curve, label: str) -> Branch:
        prob = self.prob
        us = curve.u
        ev = [prob.eigenvalues(u) for u in us]
        stable = np.array([bool(np.all(e.real < 1e-9 * max(np.abs(e).max(), 1.0))) for e in ev])
        psi = us[:, prob.nz:prob.n]
        specials = []
        folds_at = [z for z in curve.crossings if z.name == "branch" and z.converged]
        for z in curve.crossings:
            sp = self.special(z, curve, stable, label, folds_at)
            if sp is not None:
                specials.append(sp)
        specials.sort(key=lambda s: s.index)
        return Branch(kind="equilibrium", parameter=self.name, values=us[:, -1],
                      states=np.array([prob.state(u[:prob.n]) for u in us]), stable=stable,
                      amplitude=np.array([prob.amplitude(u) for u in us]), spectrum=np.array(ev),
                      period=np.full(len(us), np.nan), special_points=tuple(specials), label=label, end=curve.end,
                      extra={"ball_angle": np.angle(np.exp(1j * psi))})

    def special(self, z, curve: Curve, stable, label: str, branch_points) -> SpecialPoint | None:
        prob = self.prob
        u = z.point.u
        i = z.index
        up = curve.points[i].lam >= curve.points[i - 1].lam
        value = format_value(z.point.lam, self.unit)
        who = describe_branch(label)
        freq = math.nan
        if z.name == "hopf":
            lam = prob.crossing_pair(u)
            big = max(np.abs(prob.eigenvalues(u)).max(), 1.0)
            if lam is None or abs(lam.real) > 1e-6 * big:
                return None  # a neutral saddle (two real eigenvalues of opposite sign), not a Hopf point
            freq = abs(lam.imag)
        if z.name == "fold" and any(abs(b.point.lam - z.point.lam) <= 1e-6 * max(1.0, abs(z.point.lam))
                                    for b in branch_points):
            return None  # the pitchfork's parabola turns at its branch point: reported as the branch point
        desc = _sentence(z.name, who, value, bool(stable[i - 1]), bool(stable[i]), up, freq)
        if not z.converged:
            desc += " (location not converged to the tolerance)"
        return SpecialPoint(type=z.name, parameter=self.name, value=z.point.lam, state=prob.state(u[:prob.n]),
                            description=desc, index=i, frequency=freq,
                            changes_stability=bool(stable[i - 1]) != bool(stable[i]), amplitude=prob.amplitude(u))


def _from(z, curve: Curve) -> Curve:
    """``curve`` with the branch point it started from as its first point."""
    crossings = tuple(replace(c, index=c.index + 1) for c in curve.crossings)
    values = {k: np.concatenate([[np.nan], v]) for k, v in curve.test_values.items()}
    return Curve(points=(z.point,) + curve.points, crossings=crossings, end=curve.end, test_values=values)


def _near(curve: Curve, other: Curve, scale: np.ndarray, angles: slice) -> bool:
    """Whether the second point of ``curve`` lies on ``other`` (within 5 % of a segment's length
    of one of its chords, scaled; ball angles compared modulo 2 pi)."""
    if len(curve.points) < 2:
        return True
    pts = other.u / scale
    for a, b in zip(pts[:-1], pts[1:]):
        x = curve.points[1].u / scale
        x[angles] = a[angles] + np.angle(np.exp(1j * (x[angles] - a[angles])))
        e = b - a
        ee = float(e @ e)
        t = 0.0 if ee == 0.0 else min(max(float((x - a) @ e) / ee, 0.0), 1.0)
        if float(np.linalg.norm(x - a - t * e)) <= max(0.05 * math.sqrt(ee), 1e-9):
            return True
    return False


def continue_equilibria(model, parameter: str, start: float, stop: float, *,
                        start_from: str | Sequence[tuple[str, np.ndarray]] = "balanced",
                        settings: ContinuationSettings | None = None, switch: bool = True,
                        max_branches: int = 12, parameter2: str | None = None,
                        range2: tuple[float, float] | None = None) -> ContinuationResult:
    """Continue steady motions of a machine with balls in one named parameter.

    Parameters
    ----------
    model : rotorlab.models.Machine or JeffcottBalls
        Isotropic, constant speed (its co-rotating frame has equilibria). Balls with friction:
        the steady motions of the smooth part, friction left out, and ``notes`` says so
        (:func:`rotorlab.continuation.smooth_part_note`).
    parameter : str
        ``drive.speed``, ``ball_mass``, ``ball_damping`` or a key path
        (:func:`rotorlab.continuation.with_value`), SI.
    start, stop : float
        The range; the starting motions are those at ``start`` or, where it has none of the
        kind asked for (``start_from`` a string), those at ``stop``, continued back.
    start_from : str or sequence of (label, state)
        ``"balanced"``, ``"side"``, ``"all"`` or a motion's label (``"side 01"``,
        :func:`rotorlab.continuation.starting_motions`), or given co-rotating states.
    settings : ContinuationSettings, optional
        Default :func:`equilibrium_settings`.
    switch : bool
        Follow the other branch at every branch point (both halves).
    max_branches : int
        Most branches in all.
    parameter2, range2 : optional
        A second parameter and its ``(start, stop)``: every fold and Hopf point found is
        continued in it (:func:`rotorlab.continuation.two_parameter_curves`), into
        ``ContinuationResult.curves``. The model's value of ``parameter2`` must lie in the range.
        ``support_anisotropy`` against ``drive.speed``: the balanced state's Floquet stability
        boundaries instead (:func:`rotorlab.continuation.floquet_boundary`), with findings.

    Returns
    -------
    ContinuationResult
        One :class:`Branch` per continued branch (``extra["ball_angle"]``: (n, n_balls) rad, from
        the rotor's reference direction), with its folds, Hopf points and branch points.

    Raises
    ------
    ValueError
        No co-rotating frame, an unknown parameter, ``start == stop``, a value the model refuses,
        or no steady motion of that kind at ``start``.

    Examples
    --------
    Two 20 g balls on a 1 m race against 0.01 kg m: the balanced state is born at the ball mass
    U / (2 l) = 5 g (balls together opposite the unbalance; a pitchfork):

    >>> import numpy as np
    >>> from rotorlab.linear import LinearSystem
    >>> from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance
    >>> s = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
    ...                  G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
    >>> m = Machine(s, races=(BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * 2),),
    ...             unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(2.0), n_modes=2)
    >>> r = continue_equilibria(m, "ball_mass", 0.02, 0.003, switch=False)
    >>> [(s.type, round(s.value, 9)) for s in r.branches[0].special_points]
    [('branch', 0.005)]
    """
    notes = tuple(n for n in (smooth_part_note(model),) if n)
    model = as_machine(model)
    start, stop = float(start), float(stop)
    if not (math.isfinite(start) and math.isfinite(stop)) or start == stop:
        raise ValueError(f"{parameter}: start and stop must be finite and differ, got {start:g} and {stop:g}")
    prob = MachineEquilibria(model, (parameter,))
    unit = prob.units[parameter]
    first = with_value(model, parameter, start)
    starts = starting_motions(first, start_from) if isinstance(start_from, str) else list(start_from)
    if not starts and isinstance(start_from, str):
        # none of that kind at the start of the range (e.g. balls too light to balance): start
        # from the other end and continue back, as a user asking for the range expects
        starts = starting_motions(with_value(model, parameter, stop), start_from)
        if starts:
            start, stop = stop, start
    if not starts:
        raise ValueError(f"no {start_from} steady motion at {parameter} = {start:g} {unit} nor at {stop:g} {unit}"
                         if isinstance(start_from, str) else "start_from: no starting states given")
    st = settings if settings is not None else equilibrium_settings(start, stop)
    if not st.periodic:  # the ball angles: a branch that winds a whole turn back to its start is closed
        st = replace(st, periodic=tuple(range(prob.nz, prob.n)))
    scale = _scale(prob, start, stop)
    tests = {"fold": fold_test, "branch": branch_point_test, "hopf": lambda p: prob.hopf_test(p.u)}
    build = _Builder(prob, parameter, unit)
    angles = slice(prob.nz, prob.n)  # ball angles (scale 1 rad)
    curves: list[tuple[Curve, str]] = []
    for label, y in starts:
        u0 = np.concatenate([prob.unknowns(y), [start]])
        curve = continue_curve(prob.residual, u0, jacobian=prob.jacobian, scale=scale, settings=st, tests=tests)
        if any(_near(curve, c, scale, angles) for c, _ in curves):
            continue
        curves.append((curve, label))
    k = 0
    while switch and k < len(curves) and len(curves) < max_branches:
        curve, label = curves[k]
        k += 1
        for z in curve.crossings:
            if z.name != "branch" or not z.converged:
                continue
            for side in (1, -1):
                if len(curves) >= max_branches:
                    break
                try:
                    new = switch_branch(prob.residual, z, jacobian=prob.jacobian, scale=scale, settings=st,
                                        tests=tests, side=side, offset=2 * st.ds)
                except ValueError:
                    continue
                if any(_near(new, c, scale, angles) for c, _ in curves):
                    continue
                new = _from(z, new)
                mid = new.points[len(new.points) // 2].u
                curves.append((new, f"{_kind(prob, mid)} (from {label} at "
                                    f"{format_value(z.point.lam, unit)})"))
    branches = tuple(build.branch(c, lab) for c, lab in curves)
    result = ContinuationResult(branches, units={parameter: unit}, notes=notes)
    if parameter2 is None:
        return result
    second = _SECOND_PARAMETER.get(parameter2, _fold_and_hopf_curves)
    lines, findings, note = second(model, result, parameter, start, stop, parameter2, *range2)
    return ContinuationResult(branches, units={parameter: unit, parameter2: parameter_unit(model, parameter2)},
                              curves=lines, notes=notes + ((note,) if note else ()), findings=findings)


def _fold_and_hopf_curves(model, result, parameter, start, stop, parameter2, start2, stop2):
    """The fold and Hopf curves through the points of ``result`` (no findings, no note)."""
    from rotorlab.continuation._two_parameter import two_parameter_curves

    return two_parameter_curves(model, result, parameter2, start2, stop2), (), ""


#: Second parameters whose curves are not fold and Hopf curves of the equilibria: name ->
#: ``f(model, result, parameter, start, stop, parameter2, start2, stop2) -> (curves, findings, note)``.
_SECOND_PARAMETER = {ANISOTROPY: anisotropy_curves}
