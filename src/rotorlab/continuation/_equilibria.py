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


def _rescale(prob: MachineEquilibria, scale: np.ndarray):
    """The branch's own sizes at ``u``: the structure's coordinates by the largest of them (at
    least the unbalance's scale), so that a step moves a whirl that has grown twenty-fold near a
    critical speed by a few per cent of itself, not of the balanced state's scale."""
    nz = prob.nz

    def sizes(u: np.ndarray) -> np.ndarray:
        sc = scale.copy()
        sc[:nz] = max(prob.z_scale, float(np.max(np.abs(u[:nz]))))
        return sc

    return sizes


def _exchanges(model, parameter: str, start: float, stop: float, nz: int) -> list[np.ndarray]:
    """Index permutations of ``u = (z, psi, lam)`` exchanging identical balls of one race (equal
    at both ends of the range: a parameter of one ball breaks the symmetry), the identity
    first. A steady motion's image under one is a steady motion; at most 120 of them."""
    import itertools

    ends = [as_machine(with_value(model, parameter, v)) for v in (start, stop)]
    groups = []  # per race, per class of identical balls: their indices
    k = 0
    for r, race in enumerate(ends[0].races):
        kinds: dict[int, list[int]] = {}
        for j, ball in enumerate(race.balls):
            same = next((i for i in kinds if all(m.races[r].balls[i - k] == m.races[r].balls[j] for m in ends)), None)
            kinds.setdefault(k + j if same is None else same, []).append(k + j)
        groups += [g for g in kinds.values() if len(g) > 1]
        k += len(race.balls)
    n = nz + k + 1
    if math.prod(math.factorial(len(g)) for g in groups) > 120:
        groups = []
    perms = []
    for choice in itertools.product(*(itertools.permutations(g) for g in groups)):
        perm = np.arange(n)
        for g, image in zip(groups, choice):
            perm[nz + np.array(g)] = nz + np.array(image)
        perms.append(perm)
    return perms or [np.arange(n)]


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
        specials = _unique(sorted(specials, key=lambda s: s.index), self.unit)
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


def _unique(specials: list[SpecialPoint], unit: str) -> list[SpecialPoint]:
    """One entry for a special point found twice: the same type in neighbouring intervals of the
    branch within 1e-6 of the value (a branch that turns back and forth within that, e.g. two
    folds 9e-8 rad/s apart on rcfw-two-plane's side branches near 0.99 rad/s, is one fold
    to anyone reading the diagram; the note says so)."""
    out: list[SpecialPoint] = []
    for sp in specials:
        last = next((o for o in reversed(out) if o.type == sp.type), None)
        if (last is not None and sp.index - last.index <= 2
                and abs(sp.value - last.value) <= 1e-6 * max(1.0, abs(sp.value))):
            gap = format_value(abs(sp.value - last.value), unit) if sp.value != last.value else "no distance"
            out[out.index(last)] = replace(last, description=f"{last.description} (found twice, {gap} apart)")
            continue
        out.append(sp)
    return out


def _from(z, curve: Curve) -> Curve:
    """``curve`` with the branch point it started from as its first point."""
    crossings = tuple(replace(c, index=c.index + 1) for c in curve.crossings)
    values = {k: np.concatenate([[np.nan], v]) for k, v in curve.test_values.items()}
    return Curve(points=(z.point,) + curve.points, crossings=crossings, end=curve.end, test_values=values)


def _near(curve: Curve, other: Curve, scale: np.ndarray, angles: slice) -> bool:
    """Whether the second point of ``curve`` lies on ``other`` (:func:`_on`)."""
    return len(curve.points) < 2 or _on(curve.points[1].u, other, scale, angles)


def _on(u: np.ndarray, other: Curve, scale: np.ndarray, angles: slice) -> bool:
    """Whether ``u`` lies on ``other`` (within 5 % of a segment's length of one of its chords,
    scaled; ball angles compared modulo 2 pi)."""
    pts = other.u / scale
    for a, b in zip(pts[:-1], pts[1:]):
        x = u / scale
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
    own = _rescale(prob, scale)
    tests = {"fold": fold_test, "branch": branch_point_test, "hopf": lambda p: prob.hopf_test(p.u)}
    build = _Builder(prob, parameter, unit)
    angles = slice(prob.nz, prob.n)  # ball angles (scale 1 rad)
    curves: list[tuple[Curve, str]] = []
    swaps = _exchanges(model, parameter, start, stop, prob.nz)
    copies: dict[str, list[str]] = {}
    for label, y in starts:
        u0 = np.concatenate([prob.unknowns(y), [start]])
        # a start on a branch already continued (it came back to the range's end there), or one
        # whose identical balls exchanged lie on one: the same branch, not continued again
        twin = next((lab for c, lab in curves for perm in swaps if _on(u0[perm], c, scale, angles)), None)
        if twin is not None:
            if not _on(u0, next(c for c, lab in curves if lab == twin), scale, angles):
                copies.setdefault(twin, []).append(label)
            continue
        curve = continue_curve(prob.residual, u0, jacobian=prob.jacobian, scale=scale, settings=st, tests=tests,
                               rescale=own)
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
                                        tests=tests, side=side, offset=2 * st.ds, rescale=own)
                except ValueError:
                    continue
                if any(_near(new, c, scale, angles) for c, _ in curves):
                    continue
                mid = new.points[len(new.points) // 2].u
                name = f"{_kind(prob, mid)} (from {label} at {format_value(z.point.lam, unit)})"
                twin = next((lab for c, lab in curves for perm in swaps[1:]
                             if len(new.points) > 1 and _on(new.points[1].u[perm], c, scale, angles)), None)
                if twin is not None:  # the other half of a pitchfork of identical balls: the same motion
                    copies.setdefault(twin, []).append(name)
                    continue
                curves.append((_from(z, new), name))
    branches = tuple(build.branch(c, lab) for c, lab in curves)
    notes += tuple(f"{', '.join(x for x in labs if x != lab)}: the {lab} branch with identical balls of a race "
                   "exchanged (not repeated)" if any(x != lab for x in labs) else
                   f"{lab}: its other half is the same branch with identical balls of a race exchanged (not repeated)"
                   for lab, labs in copies.items())
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
