"""Periodic branches of a ``continuation`` analysis (``start_from = "hopf" | "simulation"``): whirl
orbits of a ``jeffcott_balls`` rotor in its co-rotating frame, continued in the speed by multiple
shooting (:func:`rotorlab.continuation.continue_periodic`).

- ``simulation``: ball starts on an offset grid (``GRID`` x ``GRID``, as the ``verify`` analysis)
  are simulated at the range's start; the first whose balls still turn against the rotor after
  ``T_SETTLE`` s is the whirl's start (said in ``start`` of the result), its orbit is found by
  :func:`rotorlab.continuation.orbit_from_simulation` and continued towards the range's stop.
- ``hopf``: the equilibria are continued first; from each Hopf point (mirror images once) the
  orbit born there (:func:`rotorlab.continuation.orbit_from_hopf`) is continued.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["PERIODIC_STARTS", "orbit_model", "orbit_sentence", "periodic_branches"]

#: The ``start_from`` values that continue periodic orbits.
PERIODIC_STARTS = ("hopf", "simulation")
GRID, T_SETTLE, T_WINDOW = 8, 40.0, 3.0
#: Orbits per branch born at a Hopf point (each Hopf point of every steady motion has one).
HOPF_ORBITS = 100


def orbit_model(case_model, analysis):
    """The case's ``jeffcott_balls`` rotor (fixed frame, constant speed ``range[0]``) whose
    co-rotating frame carries the orbits; ValueError for another model, another parameter than
    ``drive.speed`` or a model with events (the message of the shooting code)."""
    from rotorlab.analyses._case import build_model
    from rotorlab.models import ConstantSpeed, JeffcottBalls

    model = build_model(case_model)
    if not isinstance(model, JeffcottBalls):
        raise ValueError(f"periodic orbits (start_from = {analysis.start_from}) need a jeffcott_balls rotor, whose "
                         f"co-rotating frame makes a whirl periodic; this model is {case_model.type}")
    if analysis.param != "drive.speed":
        raise ValueError(f"periodic orbits are continued in drive.speed only, not {analysis.param}")
    from rotorlab.continuation._shooting import refuse_events

    model = model.with_speed(ConstantSpeed(analysis.range[0]))
    refuse_events(model.with_frame("rotating"))
    return model


def _settings(analysis, start: float, max_points: int = 300):
    from rotorlab.continuation import ContinuationSettings

    lo, hi = sorted(analysis.range)
    stop = analysis.range[1] if start == analysis.range[0] else (hi if start < hi else lo)
    return ContinuationSettings(ds=0.02, ds_max=0.2, max_points=max_points, bounds=(lo, hi),
                                direction=1 if stop > start else -1)


def _whirl_start(model, om: float) -> tuple[np.ndarray, str]:
    """The first ball start of the offset grid whose balls still turn after T_SETTLE s at ``om``."""
    from rotorlab.continuation._shooting import BACKEND
    from rotorlab.integrate import StepControl, solve_ensemble
    from rotorlab.models import ConstantSpeed

    rot = model.with_speed(ConstantSpeed(om)).with_frame("rotating")
    nb = model.n_balls
    a = (np.arange(GRID) + 0.5) * 2 * math.pi / GRID - math.pi
    angles = np.array(np.meshgrid(*([a] * nb), indexing="ij")).reshape(nb, -1).T
    y0 = np.array([rot.initial_state(g) for g in angles])
    sol = solve_ensemble(rot, y0, (0.0, T_SETTLE), control=StepControl(rtol=1e-8, atol=1e-10), backend=BACKEND)
    rates = np.abs(np.asarray(sol.y_final)[:, 4 + nb: 4 + 2 * nb]).max(axis=1)
    ok = np.asarray(sol.status) == 0
    hits = np.flatnonzero(ok & (rates > 1e-2 * om))
    if hits.size == 0:
        raise ValueError(f"none of the {len(angles)} ball starts ({GRID} x {GRID} offset grid) ends in a whirl at "
                         f"{om * 30 / math.pi:.6g} rpm (every one settles): start the range where a whirl exists")
    k = int(hits[0])
    used = ", ".join(f"{math.degrees(x):.1f}" for x in angles[k])
    return y0[k], (f"simulation at {om * 30 / math.pi:.6g} rpm from ball angles ({used}) deg, start {k + 1} of "
                   f"{len(angles)} of a {GRID} x {GRID} offset grid ({hits.size} end in a whirl)")


def _jeffcott_state(rot, at, value: float, machine_state: np.ndarray, basis: np.ndarray, nb: int) -> np.ndarray:
    """The co-rotating Jeffcott state of an equilibrium of the machine it equals (the disc's x, y =
    Phi z by the machine's basis, ball angles as they are), corrected by Newton's method on the
    rotor's own right-hand side."""
    p = at(value)
    n = rot.kernels.n_state
    y = np.zeros(n)
    nz = basis.shape[1]
    y[:2] = basis[:2] @ machine_state[:nz]
    y[4:4 + nb] = machine_state[2 * nz:2 * nz + nb]
    out = np.empty(n)
    free = [0, 1] + list(range(4, 4 + nb))  # velocities stay zero at an equilibrium
    for _ in range(30):
        rot.kernels.rhs(0.0, y, p, out)
        if np.max(np.abs(out)) < 1e-12 * max(1.0, value ** 2):
            return y
        jac = np.empty((n, len(free)))
        for j, i in enumerate(free):
            h = 1e-7 * max(1e-4, abs(y[i]))
            yp = y.copy()
            yp[i] += h
            o2 = np.empty(n)
            rot.kernels.rhs(0.0, yp, p, o2)
            jac[:, j] = (o2 - out) / h
        y[free] -= np.linalg.lstsq(jac, out, rcond=None)[0]
    raise ValueError(f"the Hopf point's equilibrium at {value * 30 / math.pi:.6g} rpm was not found in the rotor's "
                     "co-rotating frame")


def periodic_branches(case_model, analysis, equilibria=None, equilibria_basis=None) -> tuple[list[Any], str]:
    """The periodic branches of ``analysis`` and, from a simulation, a sentence saying which start
    was used (empty from Hopf points: each branch's label names its Hopf point).

    Raises
    ------
    ValueError
        Not a jeffcott_balls rotor, not the speed, a model with events, no whirl among the
        starts (simulation), or no Hopf point in the range (hopf).
    """
    from rotorlab.continuation import continue_periodic, orbit_from_hopf, orbit_from_simulation
    from rotorlab.models import ConstantSpeed

    model = orbit_model(case_model, analysis)
    nb = model.n_balls
    angles = tuple(range(4, 4 + nb))

    def at(om):
        return model.with_speed(ConstantSpeed(float(om))).to_array()

    rot = model.with_frame("rotating")
    if analysis.start_from == "simulation":
        om = analysis.range[0]
        y0, said = _whirl_start(model, om)
        orbit = orbit_from_simulation(rot, y0, t_settle=T_SETTLE, t_window=T_WINDOW, params=at(om), angles=angles,
                                      segments=5, parameter=analysis.param, value=om)
        return [continue_periodic(rot, orbit, at, parameter=analysis.param, label="whirl", unit="rad/s",
                                  settings=_settings(analysis, om))], said
    hopfs: list[Any] = []
    for b in equilibria.branches:
        for s in b.special_points:
            if s.type == "hopf" and not any(abs(s.value - h.value) <= 1e-7 * abs(s.value) for h, _ in hopfs):
                hopfs.append((s, b.label))
    if not hopfs:
        raise ValueError("no Hopf point on the continued steady motions in this range: no orbit is born there "
                         "(use simulation)")
    out = []
    for s, born in hopfs:
        x0 = _jeffcott_state(rot, at, s.value, np.asarray(s.state), np.asarray(equilibria_basis), nb)
        scale = np.r_[[1e-3] * 4, [1.0] * (2 * nb)]
        orbit = orbit_from_hopf(rot, x0, s.value, at, parameter=analysis.param, amplitude=1e-3, segments=5,
                                state_scale=scale)
        label = f"born at the Hopf point of {born}, {s.value * 30 / math.pi:.6g} rpm"
        out.append(continue_periodic(rot, orbit, at, parameter=analysis.param, label=label, unit="rad/s",
                                     settings=_settings(analysis, s.value, HOPF_ORBITS),
                                     state_scale=np.r_[[1e-3] * 2, [0.1] * 2, [1.0] * (2 * nb)]))
    return out, ""  # each branch's label says where it was born


_ENDS = {"bound": "the range ends there", "max_points": "the continuation stopped after its number of orbits",
         "step": "the step size fell below its minimum (the branch could not be followed further)",
         "closed": "the branch closed on itself"}


def orbit_sentence(branch: dict, units: str) -> str:
    """For people: over which values a periodic branch (its JSON, SI) exists and is stable, and why
    the stable stretch ends (a special point that changes stability, or the branch's end).

    A stretch of stable (unstable) orbits runs between the branch's points, extended to the
    located special point that changes stability where one lies between a stretch's last point
    and the next (the fold of cycles at its located value, not at the nearest computed orbit);
    several stable stretches are each named."""
    from rotorlab._constants import shown_unit

    f, unit = shown_unit(units)
    u = f" {unit}" if unit else ""
    param = branch["parameter"]
    pts = [p for p in branch["points"] if p[param] is not None]
    if not pts:
        return f"no {branch['label']} orbit was continued"
    who = "a whirl orbit" + ("" if branch["label"] == "whirl" else f" ({branch['label']})")
    vals = np.array([p[param] for p in pts]) * f
    stable = np.array([p["stable"] for p in pts])
    ended = f"the branch ended at {vals[-1]:.5g}{u}: {_ENDS.get(branch['end'], branch['end'])}"
    turns = [s for s in branch["special_points"]
             if "stable before it and" in s["description"] or "unstable before it and" in s["description"]]
    said = ("; stability changes at the " + ", ".join(f"{s['type']} at {f * s[param]:.5g}{u}" for s in turns)
            if turns else "")
    if stable.all():
        return f"{who} exists and is stable from {vals.min():.5g} to {vals.max():.5g}{u} " \
               f"(all of the continued stretch; {ended})"
    if not stable.any():
        return f"{who} exists from {vals.min():.5g} to {vals.max():.5g}{u} and is unstable " \
               f"all along it ({ended})"
    runs = _stretches(vals, stable, [f * s[param] for s in turns])
    good = " and from ".join(f"{a:.5g} to {b:.5g}" for a, b, ok in runs if ok)
    bad = [(a, b) for a, b, ok in runs if not ok]
    return f"{who} exists and is stable from {good}{u}{said}; the branch's unstable orbits lie between " \
           f"{min(a for a, _ in bad):.5g} and {max(b for _, b in bad):.5g}{u} ({ended})"


def _stretches(vals: np.ndarray, stable: np.ndarray, turns: list[float]) -> list[tuple[float, float, bool]]:
    """The runs of equal stability along a branch as (lowest, highest value, stable), each end
    pushed out to the stability-changing special point located at the change between it and the
    next run (each special point at the change nearest it: a fold of cycles lies beyond both
    orbits either side of it, a period doubling between them)."""
    cuts = np.flatnonzero(stable[1:] != stable[:-1]) + 1
    at: dict[int, list[float]] = {}
    for t in turns if len(cuts) else ():
        gap = [max(min(vals[j - 1], vals[j]) - t, t - max(vals[j - 1], vals[j]), 0.0) for j in cuts]
        at.setdefault(int(cuts[int(np.argmin(gap))]), []).append(t)
    bounds = [0, *cuts, len(vals)]
    runs = []
    for k in range(len(bounds) - 1):
        seg = [*vals[bounds[k]:bounds[k + 1]], *at.get(bounds[k], ()), *at.get(bounds[k + 1], ())]
        runs.append((min(seg), max(seg), bool(stable[bounds[k]])))
    return runs
