"""Helpers shared by the machine's analyses (:mod:`rotorlab.analyses._machine`,
``_machine_steady``, ``_machine_run_up``): status codes, the balls-locked structure and its
critical speeds and unbalance response, vibration amplitudes, and the glue from a ``machine``
case (its model, its variants per analysis, row formatting).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorlab.explore._outcome import BELOW_CRITICAL, NON_SYNCHRONOUS_RATE, wrap_machine_angle as _wrap  # noqa: F401
from rotorlab.explore._outcome import machine_outcome as _outcome  # noqa: F401
from rotorlab.models._machine_physics import locked_structure, structure_critical_speeds

__all__ = ["BELOW_CRITICAL", "NO_STEADY_STATUS", "CLEARANCE_STATUS", "NON_SYNCHRONOUS_RATE",
           "UNSTABLE_GROWTH", "clearance_violation", "check_saved_states", "structure_instability",
           "flag_unstable", "status_detail", "locked_structure", "structure_critical_speeds",
           "unbalance_amplitudes", "orbit_amplitude", "machine_model", "machine_quantities", "figure_variables", "add_figure_variables"]

#: Status of a steady analysis on a machine without co-rotating equilibria.
NO_STEADY_STATUS = 3
#: Status of a steady motion whose orbit at a clearance exceeds the gap (it cannot exist without
#: contact; simulate the rub instead).
CLEARANCE_STATUS = 4


def check_saved_states(machine, n_save: int, n_runs: int = 1) -> None:
    """Refuse (:class:`rotorlab._memory.TooLarge`, exit code 2 on the command line) a time history
    of ``n_save`` saved states of ``n_runs`` trajectories that would not fit in this machine's
    memory, stating what it needs: the saved states, their displacements and the integrator's
    copies, ``8 n_runs n_save (2 n_state + 8)`` bytes. The one check of every machine analysis
    that keeps a time history (``simulate``, ``run-up``)."""
    from rotorlab._memory import check_memory

    n = machine.n_state
    check_memory(8.0 * n_runs * int(n_save) * (2 * n + 8),
                 f"n_save = {int(n_save)} saved states of {n_runs} trajector{'y' if n_runs == 1 else 'ies'} "
                 f"x {n} entries", "save fewer states (n_save)")  # fmt: skip


def clearance_violation(machine, y_rotating) -> tuple[float, str | None]:
    """Whether a steady motion fits inside the machine's clearance.

    The steady motion is computed without contact; in the fixed frame the clearance point runs on
    the circle ``w(t) = R(Omega t) B z_r - c`` (``z_r`` the co-rotating coordinates, ``c`` the
    stator's centre; a moving housing rests at its centre without contact), so its largest
    distance from the stator's centre is ``|B z_r| + |c|``. Where that exceeds the gap the motion
    does not exist as computed: the rotor would touch its stator.

    Returns
    -------
    radius : float
        ``|B z_r| + |c|`` (m), NaN without a clearance.
    message : str or None
        Names the station, the radius and the gap when the radius exceeds the gap.
    """
    if not machine.clearances:
        return math.nan, None
    c = machine.clearances[0]
    nz = machine.n_coordinates
    w = machine.gap_matrix(c) @ np.asarray(y_rotating, dtype=float)[:nz]
    radius = float(math.hypot(w[0], w[1]) + math.hypot(*machine.clearance_center))
    if radius <= c.gap:
        return radius, None
    label = machine.structure.node_label[c.node]
    return radius, (f"the steady orbit at the clearance station {label!r} has radius {radius:.4g} m > gap "
                    f"{c.gap:.4g} m: this motion does not exist without contact (simulate the rub instead)")


def unbalance_amplitudes(machine, spin_speed: float) -> np.ndarray:
    """Steady radial amplitude per node (m) of the unbalance response without balls.

    The largest radius of each node's (elliptical) orbit, ``sqrt((|X|^2 + |Y|^2)/2 +
    |X^2 + Y^2|/2)``, from the full structure with the balls locked but not acting as balancers,
    and the linear parts' dynamic stiffness (a tuned mass absorber's,
    :meth:`rotorlab.models._parts.AbstractPart.dynamic_stiffness`).
    """
    s = locked_structure(machine)
    om = float(spin_speed)
    D = s.K + 1j * om * (s.C + om * s.G) - om * om * s.M
    for part in machine.attachments:
        Z = part.dynamic_stiffness(machine, om)
        D = D if Z is None else D + Z
    f = np.zeros(s.n_dof, dtype=complex)
    for u in machine.unbalances:
        f[4 * u.node:4 * u.node + 4] += om * om * u.node_force()
    q = np.linalg.solve(D, f)
    X, Y = q[0::4], q[1::4]
    return np.sqrt(0.5 * (np.abs(X) ** 2 + np.abs(Y) ** 2) + 0.5 * np.abs(X * X + Y * Y))


#: An eigenvalue of the balls-locked structure whose real part exceeds this fraction of the
#: largest eigenvalue's modulus makes it unstable (round-off leaves an undamped structure's real
#: parts near 1e-15 of it).
UNSTABLE_GROWTH = 1e-8


def structure_instability(machine, spin_speed: float) -> tuple[float, str | None]:
    """Whether the machine's linear structure is self-excited at a spin speed.

    The eigenvalues of the structure with the balls locked (:func:`locked_structure`, their
    inertia about the tilt axes included), ``(lambda^2 M + lambda (C + Omega G) + K) q = 0``
    (:func:`rotorlab.linear.modal`): one with a positive real part (beyond
    :data:`UNSTABLE_GROWTH` times the largest modulus) grows without bound (cross-coupled
    bearing stiffness, rotating damping above its threshold speed), so a run at that speed ends
    in no steady motion.

    Returns
    -------
    growth : float
        The largest real part of the eigenvalues (1/s).
    message : str or None
        The speed, the growth rate and its frequency when unstable.
    """
    from rotorlab.linear import modal

    lam = np.asarray(modal(locked_structure(machine, tilt_inertia=True), float(spin_speed)).eigenvalues)
    if not lam.size:
        return -math.inf, None
    k = int(np.argmax(lam.real))
    growth = float(lam.real[k])
    if not growth > UNSTABLE_GROWTH * float(np.abs(lam).max()):
        return growth, None
    return growth, (f"the structure (balls locked) is unstable at {spin_speed * 30 / math.pi:.5g} rpm: an "
                    f"eigenvalue grows at {growth:.4g} 1/s ({abs(lam.imag[k]) / (2 * math.pi):.4g} Hz), "
                    "self-excited (cross-coupled stiffness or rotating damping), so its response grows "
                    "without bound and the run ends in no steady motion")


def flag_unstable(machine, status, final_speeds, notes=()) -> tuple[np.ndarray, list[str]]:
    """Mark the usable runs (``status >= 0``) that end at a speed where the structure is unstable
    (:func:`structure_instability`) :attr:`rotorlab.integrate.Status.UNSTABLE`, a failure.

    Returns
    -------
    status : ndarray of int64
        A copy of ``status`` with those runs marked.
    notes : list of str
        Per run, why it failed: ``notes`` (the integrator's sanity notes) with the instability's
        message added where it marked one.
    """
    from rotorlab.integrate import Status

    status = np.array(status, dtype=np.int64).reshape(-1)
    notes = list(notes) if len(notes) else [""] * status.size
    seen: dict[float, str | None] = {}
    for i, w in enumerate(np.asarray(final_speeds, dtype=float).reshape(-1)):
        if status[i] < 0 or not math.isfinite(w):
            continue
        if w not in seen:
            seen[w] = structure_instability(machine, w)[1]
        if seen[w]:
            status[i], notes[i] = int(Status.UNSTABLE), seen[w]
    return status, notes


def status_detail(notes) -> str:
    """The first non-empty note of the failed runs (``attrs["status_detail"]``, printed by the
    command line with the failure), or ""."""
    return next((str(n) for n in notes if n), "")


def orbit_amplitude(machine, ys) -> np.ndarray:
    """Largest distance of each node from its mean position over the saved states (m).

    Parameters
    ----------
    ys : array_like, shape (..., n_times, n_state)

    Returns
    -------
    ndarray, shape (..., n_nodes)
        The vibration amplitude, without the static deflection (e.g. under gravity).
    """
    q = machine.displacements(np.asarray(ys, dtype=float))
    x, y = q[..., 0::4], q[..., 1::4]
    dx = x - x.mean(axis=-2, keepdims=True)
    dy = y - y.mean(axis=-2, keepdims=True)
    return np.hypot(dx, dy).max(axis=-2)


def _with_units(ds):
    """Give every variable and coordinate without a unit the unit "1" (counts, flags, labels)."""
    for name in (*ds.data_vars, *ds.coords):
        ds[name].attrs.setdefault("units", "1")
    return ds


def _ball_coords(machine) -> dict[str, Any]:
    race = [i for i, r in enumerate(machine.races) for _ in r.balls]
    return {"ball": np.arange(machine.n_balls), "race": ("ball", np.asarray(race, dtype=int))}


# --------------------------------------------------------------------------- case files


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def _deg(values) -> list[float | None]:
    return [None if not np.isfinite(v) else round(float(np.degrees(v)), 6) for v in np.ravel(values)]


def _per_race(ds, values) -> dict[str, list[float | None]]:
    """Angles (rad) by race, in degrees: ``{"race 0": [...], ...}``."""
    race = ds.race.values
    values = np.asarray(values, dtype=float)
    return {f"race {r}": _deg(values[race == r]) for r in np.unique(race)}


def _per_station(ds, values) -> dict[str, float | None]:
    return {str(s): _num(v) for s, v in zip(ds.station.values, np.ravel(values))}


def machine_model(case_model):
    """Build the :class:`~rotorlab.models.Machine` of a ``machine`` spec."""
    from rotorlab.io._machine_spec import build_machine

    return build_machine(case_model)


def machine_quantities(case_model) -> list[dict[str, Any]]:
    """Derived quantities: critical speeds (balls locked), the static unbalance (the resultant of
    every unbalance, what the races together must cancel; a couple adds nothing to it), capacity
    per race and, for a reduced structure, how much the unbalance response moves when ``n_modes``
    doubles (:meth:`~rotorlab.models.Machine.reduction_change`, at a constant drive's speed, else
    at the first critical speed)."""
    from rotorlab.models import ConstantSpeed

    m = machine_model(case_model)
    crit = structure_critical_speeds(m)
    static = abs(sum(u.magnitude * np.exp(1j * u.phase) for u in m.unbalances))
    rows = [{"quantity": "critical speeds (forward 1x, balls locked)",
             "value": ", ".join(f"{w:.4g}" for w in crit[:6]),
             "unit": "rad/s", "sign": ""},
            {"quantity": "static unbalance |sum m e exp(i phase)|", "value": float(static),
             "unit": "kg*m", "sign": ""}]
    for i, r in enumerate(m.races):
        rows.append({"quantity": f"capacity of race {i} (sum m l)", "value": r.capacity,
                     "unit": "kg*m", "sign": ""})
    if m.n_modes is not None and m.n_modes < m.structure.n_dof and m.unbalances:
        if isinstance(m.drive, ConstantSpeed):
            om, where = float(m.drive.speed), "the drive speed"
        elif crit.size:
            om, where = float(crit[0]), "the first critical speed"
        else:
            om = None
        if om is not None:
            rows.append({"quantity": f"change of the unbalance response at {where} when n_modes "
                                     f"= {m.n_modes} doubles", "value": m.reduction_change(om),
                         "unit": "1", "sign": ""})
    return rows


def _variant(case_model, analysis, speed: float | None = None, *, source=None):
    """The case's machine with only the analysis' races (all when it names none), at a constant
    ``speed`` if given (made from ``source``, the case's machine, when it is built already)."""
    from dataclasses import replace

    from rotorlab.models import ConstantSpeed

    m = machine_model(case_model) if source is None else source
    races = getattr(analysis, "races", None)
    if races is not None:
        m = replace(m, races=tuple(m.races[i] for i in races))
    if speed is not None:
        m = m.with_drive(ConstantSpeed(float(speed)))
    _check_rest(m, case_model)
    return m


def _check_rest(machine, case_model) -> None:
    """Refuse (:class:`rotorlab.io.CaseError`, exit code 2) a machine whose rotor rests on its
    stator under gravity (:meth:`~rotorlab.models.Machine.rest_clearance`).

    The balancer's analyses (simulate, run-up, basins, sweeps, knock) judge a rotor that runs
    free of its stator: resting on it, the stator carries the rotor for the whole run and the
    small vibration about that position reads as "balanced". Refused rather than reported: the
    usual cause is a stator built around the axis of a rotor that sags (``center_at_rest``
    forgotten), and a rotor meant to rest on its stator (a rotor dropped onto its catcher
    bearing) is the question of the ``rub`` and ``rub-map`` analyses, which do not check this.
    """
    radius, why = machine.rest_clearance()
    if why is None:
        return
    from rotorlab.io import CaseError

    c = case_model.clearances[0]
    key = "model.clearances[0]"
    fix = (f"give {key}.gap > {radius * 1e3:.4g} mm" + ("" if c.center_at_rest else
           f", or centre the stator where the station rests ({key}.center_at_rest = true)"))
    raise CaseError(f"{key}.gap = {c.gap * 1e3:.4g} mm: {why}; a balancer analysis needs a rotor free of its "
                    f"stator: {fix} (a rotor resting on its stator is the question of the rub analyses)")


def _annotate(ds, case_model, analysis):
    ds = _with_units(ds)
    races = getattr(analysis, "races", None)
    if races is not None:
        ds.attrs["races"] = list(races)
    ds.attrs["n_races"] = len(case_model.races) if races is None else len(races)
    ds.attrs["name"] = analysis.name
    ds.attrs["analysis"] = analysis.type
    return ds


def figure_variables(machine, ys) -> dict[str, Any]:
    """What the figures of a time history need beyond each node's distance from the axis.

    Parameters
    ----------
    machine : rotorlab.models.Machine
    ys : ndarray, shape (..., n_time, n_state)
        Saved fixed-frame states.

    Returns
    -------
    dict
        ``"from_rest"``: each node's distance from its rest position under gravity (m, shape
        (..., n_time, n_nodes)), where gravity moves the structure at rest (else absent: the
        distance from the axis is that distance); ``"clearance_distance"`` (m, shape
        (..., n_time)): the clearance station's distance from the stator's centre, with
        ``"gap"`` (m) and ``"clearance_station"``, where the machine has a clearance.
    """
    out: dict[str, Any] = {}
    try:
        zs, _ = machine._rest_position()
    except ValueError:  # supports that do not hold the structure: no rest position
        zs = None
    if zs is not None and np.any(zs):
        rest = machine.basis @ zs
        q = machine.displacements(ys)
        out["from_rest"] = np.hypot(q[..., 0::4] - rest[0::4], q[..., 1::4] - rest[1::4])
    if machine.clearances:
        c = machine.clearances[0]
        w = machine.gap_vector(ys)
        out.update(clearance_distance=np.hypot(w[..., 0], w[..., 1]), gap=float(c.gap),
                   clearance_station=str(machine.structure.node_label[c.node]))
    return out


def add_figure_variables(ds, machine, ys, dims: tuple[str, ...]):
    """``ds`` with ``displacement_from_rest`` (``dims`` + station) and ``clearance_distance``
    (``dims``, with ``attrs`` ``gap`` and ``clearance_station``) of the saved states ``ys``
    (:func:`figure_variables`), where the machine has them."""
    extra = figure_variables(machine, ys)
    if "from_rest" in extra:
        ds["displacement_from_rest"] = ((*dims, "station"), extra["from_rest"], {"units": "m"})
    if "gap" in extra:
        ds["clearance_distance"] = (dims, extra["clearance_distance"], {"units": "m"})
        ds.attrs.update(gap=extra["gap"], clearance_station=extra["clearance_station"])
    return ds
