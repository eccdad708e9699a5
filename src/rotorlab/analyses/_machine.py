"""Analyses of the composed machine (:class:`rotorlab.models.Machine`): simulation from many ball
starts, steady balanced states and their exact stability over speed, and run-ups.

All functions are pure: a model in, an :class:`xarray.Dataset` out (SI units in ``attrs``), with
an integer ``status`` per element (0: success) and, where the question has no answer for this
machine (no co-rotating equilibria), a failed status and the reason in ``attrs["message"]``.

The common analysis types run on a ``machine`` case through the machine's own entries
(:func:`machine_analysis_types`, the ``analyses`` of its :class:`~rotorlab.analyses.ModelType`):
``simulate``, ``steady`` (every balanced motion at one speed, :func:`machine_motions`),
``stability-chart`` and ``run-up``; ``basin`` and ``sweep`` through its regime mapper
(:func:`machine_mapper`, :class:`rotorlab.explore.MachineRegimes`); ``campbell``, ``modes`` and
the other structural analyses through the spec's ``linear_structure()``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["machine_simulate", "machine_steady", "machine_motions", "locked_structure",
           "orbit_amplitude", "machine_model", "machine_quantities", "machine_analysis_types",
           "jeffcott_limit", "structure_critical_speeds", "unbalance_amplitudes", "NO_STEADY_STATUS", "CLEARANCE_STATUS",
           "clearance_violation"]

#: Status of a steady analysis on a machine without co-rotating equilibria.
NO_STEADY_STATUS = 3
#: Status of a steady motion whose orbit at a clearance exceeds the gap (it cannot exist without
#: contact; simulate the rub instead).
CLEARANCE_STATUS = 4
#: Balls moving relative to the rotor faster than this fraction of its speed in the final window
#: of a simulation have not synchronised ("non-synchronous").
NON_SYNCHRONOUS_RATE = 1e-2
#: Samples per revolution in the final window of a simulation.
_SAMPLES_PER_REV = 32


def _outcome(status: int, amplitude, reference, max_rate: float, speed: float, n_balls: int) -> str:
    """Label where one simulation ended (see :func:`machine_simulate`)."""
    from rotorlab.analyses._outcome import BALANCED_FRACTION

    if status < 0:
        return "failed"
    if n_balls == 0:
        return "no balancer"
    if np.max(amplitude) <= BALANCED_FRACTION * np.max(reference) + 1e-15:
        return "balanced"
    if not max_rate <= NON_SYNCHRONOUS_RATE * abs(speed):
        return "non-synchronous"
    return "not balanced"


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


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


def locked_structure(machine, *, tilt_inertia: bool = False):
    """Return the structure with the balls locked at their races (``LinearSystem``).

    Each ball of mass m at race radius l and axial offset a from its node is a point mass on the
    race centre ``(x + a phi_x, y + a phi_y)``: the mass ``m e^T e`` (translation m, coupling
    m a, tilt m a^2), as in the kernel's ``M0``. With ``tilt_inertia`` the ball's inertia about
    its place off the axis is added, as for a ring locked to the rotor: ``m l^2 / 2`` about each
    diametral axis (the mean over the ball's angle of the tilting race's ``m l^2 (e_b . phi')^2``
    term) and the polar ``J_b = m l^2 + J_c`` in the gyroscopic matrix (``G[phi_x, phi_y] =
    J_b``, the convention of :class:`rotorlab.linear.RigidBody`; the race-frame term ``J_b phi_b'
    (phi_y phi_x' - phi_x phi_y') / 2`` with ``phi_b' = Omega``), see :mod:`rotorlab.models._machine`.
    """
    from rotorlab.linear import LinearSystem

    s = machine.structure
    M, G = s.M.copy(), s.G.copy()
    for r in machine.races:
        n = 4 * r.node
        e = np.zeros((2, s.n_dof))
        e[0, n], e[1, n + 1] = 1.0, 1.0
        e[0, n + 2] = e[1, n + 3] = r.axial_offset
        M += sum(b.mass for b in r.balls) * (e.T @ e)
        if tilt_inertia:
            for b in r.balls:
                M[n + 2, n + 2] += 0.5 * b.mass * r.radius**2
                M[n + 3, n + 3] += 0.5 * b.mass * r.radius**2
                G[n + 2, n + 3] += b.mass * r.radius**2 + b.inertia
                G[n + 3, n + 2] -= b.mass * r.radius**2 + b.inertia
    return LinearSystem(M=M, C=s.C, G=G, K=s.K, node_position=s.node_position,
                        node_label=s.node_label)


def structure_critical_speeds(machine, max_speed: float | None = None) -> np.ndarray:
    """Forward-whirl 1x critical speeds of the structure with the balls locked (rad/s), their
    inertia about the tilt axes included (:func:`locked_structure` with ``tilt_inertia``)."""
    from rotorlab.linear import critical_speeds

    cs = critical_speeds(locked_structure(machine, tilt_inertia=True), max_speed=max_speed)
    return cs.speed[cs.whirl >= 0]


def unbalance_amplitudes(machine, spin_speed: float) -> np.ndarray:
    """Steady radial amplitude per node (m) of the unbalance response without balls.

    The largest radius of each node's (elliptical) orbit, ``sqrt((|X|^2 + |Y|^2)/2 +
    |X^2 + Y^2|/2)``, from the full structure with the balls locked but not acting as balancers.
    """
    s = locked_structure(machine)
    om = float(spin_speed)
    D = s.K + 1j * om * (s.C + om * s.G) - om * om * s.M
    f = np.zeros(s.n_dof, dtype=complex)
    for u in machine.unbalances:
        ph = u.mass_eccentricity * om * om * np.exp(1j * u.phase)
        f[4 * u.node] += ph
        f[4 * u.node + 1] += -1j * ph
        f[4 * u.node + 2] += u.axial_offset * ph
        f[4 * u.node + 3] += -1j * u.axial_offset * ph
    q = np.linalg.solve(D, f)
    X, Y = q[0::4], q[1::4]
    return np.sqrt(0.5 * (np.abs(X) ** 2 + np.abs(Y) ** 2) + 0.5 * np.abs(X * X + Y * Y))


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


def machine_simulate(machine, initial_ball_angles, *, t_end: float, rtol: float = 1e-8,
                     atol: float = 1e-10, window_revolutions: float = 2.0,
                     threads: int | None = None,
                     progress: Callable[[int, int], None] | None = None):
    """Simulate the machine from many ball starts and report where each ends.

    Every trajectory starts with the structure at rest and the balls at rest relative to the
    rotor at the given angles (rad, from the rotor's reference direction, races in order).

    Parameters
    ----------
    machine : Machine
    initial_ball_angles : array_like, shape (n_starts, n_balls)
    t_end : float
        Simulated time (s).
    rtol, atol : float
        Integrator tolerances.
    window_revolutions : float
        Length of the final window (revolutions at the final speed) over which the vibration
        amplitude is taken (its maximum).

    Returns
    -------
    xarray.Dataset
        ``final_ball_angle`` (ic, ball): angle relative to the rotor (rad, wrapped to
        [-pi, pi)); ``amplitude`` (ic, station): vibration amplitude of each node in the final
        window (largest distance from its mean position, m); ``reference_amplitude`` (station): the same without balancing (the
        linear unbalance response at the final speed of each start, first start shown);
        ``final_speed`` (ic) (rad/s); ``max_final_rate`` (ic): largest ball rate relative to
        the rotor in the final window (rad/s); ``outcome`` (ic): "balanced" (every station's
        vibration at most :data:`~rotorlab.analyses.BALANCED_FRACTION` of the largest vibration
        without balancing), "non-synchronous" (balls still moving relative to the rotor faster
        than :data:`NON_SYNCHRONOUS_RATE` times its speed), "not balanced", "no balancer" or
        "failed"; ``status`` (ic).
    """
    import xarray as xr

    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    ang = np.asarray(initial_ball_angles, dtype=float)
    if ang.ndim == 1:
        ang = ang[None, :]
    if ang.ndim != 2 or ang.shape[1] != machine.n_balls:
        raise ValueError(f"initial_ball_angles must have shape (n_starts, {machine.n_balls}) "
                         f"(rad), got {np.shape(initial_ball_angles)}")
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0 (s), got {t_end!r}")
    y0 = np.array([machine.initial_state(a) for a in ang])
    lay = machine.layout
    if machine.is_motor:
        om_end = float(machine.drive.no_load_speed) if machine.drive.kind == "linear" else \
            float(max(machine.drive.torque[0]))
    else:
        om_end = float(machine.drive.spin_speed(t_end))
    window = min(t_end, window_revolutions * 2 * np.pi / max(abs(om_end), 1e-12))
    n_save = int(max(16, min(2000, window_revolutions * _SAMPLES_PER_REV)))
    ts = np.linspace(t_end - window, t_end, n_save)
    sol = solve_ensemble(machine, y0, (0.0, t_end), save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=rtol, atol=atol), threads=threads,
                         progress=progress)
    amp = orbit_amplitude(machine, sol.ys)
    th = np.array([machine.spin(t_end, y)[0] for y in sol.y_final])
    om = np.array([machine.spin(t_end, y)[1] for y in sol.y_final])
    rel = _wrap(sol.y_final[:, lay.i_phi:lay.i_phi + lay.n_balls] - th[:, None])
    ref = unbalance_amplitudes(machine, float(om[0])) if om.size else np.zeros(machine.structure.n_nodes)
    # ball rates relative to the rotor over the final window (largest |psi'|)
    om_t = np.array([[machine.spin(t, y)[1] for t, y in zip(ts, traj)] for traj in sol.ys])
    rates = sol.ys[:, :, lay.i_w:lay.i_w + lay.n_balls] - om_t[:, :, None]
    max_rate = np.abs(rates).reshape(len(ang), -1).max(axis=1, initial=0.0)
    outcome = [_outcome(int(st), a, ref, r, w, lay.n_balls)
               for st, a, r, w in zip(sol.status, amp, max_rate, om)]
    labels = list(machine.structure.node_label)
    ds = xr.Dataset(
        {
            "final_ball_angle": (("ic", "ball"), rel, {"units": "rad"}),
            "amplitude": (("ic", "station"), amp, {"units": "m"}),
            "reference_amplitude": (("station",), ref, {"units": "m"}),
            "final_speed": (("ic",), om, {"units": "rad/s"}),
            "initial_ball_angle": (("ic", "ball"), ang, {"units": "rad"}),
            "max_final_rate": (("ic",), max_rate, {"units": "rad/s"}),
            "outcome": (("ic",), np.asarray(outcome, dtype=str)),
            "status": (("ic",), np.asarray(sol.status, dtype=np.int64)),
        },
        coords={"ic": np.arange(ang.shape[0]), "station": labels, **_ball_coords(machine)},
        attrs={"analysis": "simulate", "model": "machine", "t_end": float(t_end),
               "window": float(window)},
    )
    return ds


def machine_steady(machine, speeds, *, ball_angles=None):
    """Balanced steady states over speed and their exact stability (co-rotating frame).

    Parameters
    ----------
    machine : Machine
        Its drive is replaced by each constant speed.
    speeds : array_like
        Spin speeds (rad/s), > 0.
    ball_angles : array_like, optional
        A guess of the balanced ball angles (rad).

    Returns
    -------
    xarray.Dataset
        ``exists`` (speed): a steady motion was found (the balanced one when the balls can
        cancel the unbalance, else the one that starts from the best partial balance);
        ``balanced`` (speed): it has no vibration; ``amplitude`` (speed, station): its whirl
        radius per node (m); ``ball_angle`` (speed, ball) (rad); ``max_real_eigenvalue`` (speed) (1/s) of the linearised co-rotating equations;
        ``stable`` (speed); ``status`` (speed): 0, or ``NO_STEADY_STATUS`` with
        ``attrs["message"]`` when the machine has no co-rotating equilibria (anisotropic
        structure, gravity across the axis) - simulate it instead; ``CLEARANCE_STATUS`` (and
        ``exists`` false) where the orbit at the machine's clearance exceeds the gap
        (:func:`clearance_violation`, named in ``attrs["message"]``).
    """
    import xarray as xr

    from rotorlab.models import ConstantSpeed

    om = np.atleast_1d(np.asarray(speeds, dtype=float))
    if om.ndim != 1 or om.size == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
        raise ValueError(f"speeds must be finite numbers > 0 (rad/s), got {speeds!r}")
    nb = machine.n_balls
    exists = np.zeros(om.size, bool)
    angles = np.full((om.size, nb), np.nan)
    lam_max = np.full(om.size, np.nan)
    stable = np.zeros(om.size, bool)
    balanced = np.zeros(om.size, bool)
    amplitude = np.full((om.size, machine.structure.n_nodes), np.nan)
    status = np.zeros(om.size, np.int64)
    probe = machine.with_drive(ConstantSpeed(float(om[0])))
    message = probe.why_no_rotating_frame()
    hits: list[str] = []
    if message is not None:
        status[:] = NO_STEADY_STATUS
    else:
        guess, near = ball_angles, None
        for i, w in enumerate(om):
            m = machine.with_drive(ConstantSpeed(float(w)))
            y = m.steady_state(guess, near=near)
            if y is None:
                continue
            nz = m.n_coordinates
            psi = y[2 * nz:2 * nz + nb]
            guess, near = psi, y
            lin = m.linearize(y)
            exists[i] = True
            balanced[i] = bool(np.all(y[:nz] == 0.0))
            angles[i] = _wrap(psi)
            lam_max[i] = float(lin.eigenvalues.real.max())
            stable[i] = lin.is_stable
            amp = m.station_amplitudes(m.rotating_to_fixed(y))
            amplitude[i] = amp
            _, hit = clearance_violation(m, y)
            if hit is not None:
                exists[i], stable[i], status[i] = False, False, CLEARANCE_STATUS
                hits.append(f"at {w:.6g} rad/s {hit}")
        if not exists.any() and not hits:
            message = "no steady motion found at any speed (the equilibrium solver did not converge)"
        elif hits:
            message = "; ".join(hits)
    ds = xr.Dataset(
        {
            "exists": (("speed",), exists),
            "ball_angle": (("speed", "ball"), angles, {"units": "rad"}),
            "max_real_eigenvalue": (("speed",), lam_max, {"units": "1/s"}),
            "stable": (("speed",), stable),
            "balanced": (("speed",), balanced),
            "amplitude": (("speed", "station"), amplitude, {"units": "m"}),
            "status": (("speed",), status),
        },
        coords={"speed": ("speed", om, {"units": "rad/s"}), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "steady", "model": "machine",
               **({"message": message} if message else {})},
    )
    return ds


# --------------------------------------------------------------------------- steady motions at one speed


def jeffcott_limit(machine):
    """The :class:`~rotorlab.models.JeffcottBalls` model this machine is, or None.

    The seeds' Hamilton-function (seed 003) and averaged (seed 002) stability verdicts are
    derived for a planar disc on an isotropic shaft with one race of balls in the disc's plane.
    A machine is that model when its structure is one node whose translation does not couple to
    its tilt (no cross terms in M, C, G, K), isotropic, with one race and every unbalance at that
    node's plane, no gravity across the axis and a constant speed. Then M1 = M_xx, c = K_xx,
    d = C_xx, e = (sum of the unbalances) / M1 (their resultant), and the ball angles of that
    model are measured from the unbalance (shifted by its phase).
    """
    from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, RotorParams

    s = machine.structure
    if (machine.why_no_rotating_frame() is not None or s.n_dof != 4 or len(machine.races) != 1
            or machine.races[0].axial_offset != 0.0 or any(u.axial_offset != 0.0 for u in machine.unbalances)):
        return None
    for name in ("M", "C", "K", "G"):
        a = getattr(s, name)
        if np.any(a[:2, 2:] != 0.0) or np.any(a[2:, :2] != 0.0) or (name == "G" and np.any(a[:2, :2] != 0.0)):
            return None
    race = machine.races[0]
    u = sum(x.mass_eccentricity * np.exp(1j * x.phase) for x in machine.unbalances)
    m1 = float(s.M[0, 0])
    rotor = RotorParams(disc_mass=m1, eccentricity=abs(u) / m1, stiffness=float(s.K[0, 0]),
                        damping=float(s.C[0, 0]))
    balls = tuple(BallParams(mass=b.mass, radius=race.radius, inertia=b.mass * race.radius ** 2 + b.inertia,
                             damping=b.damping) for b in race.balls)
    return JeffcottBalls(rotor, balls, speed=ConstantSpeed(float(machine.drive.speed)), frame="rotating"), \
        float(np.angle(u)) if abs(u) > 0 else 0.0


#: Why the seeds' verdicts are not given for a machine that is not the planar single-mass rotor.
SEED_VERDICTS_NOTE = ("the seeds' Hamilton (seed 003) and averaged (seed 002) verdicts assume a planar "
                      "disc on an isotropic shaft with one race in its plane; this machine is not that "
                      "rotor, so only the exact eigenvalues judge stability")


def machine_motions(machine, *, starts: int = 24, seed: int = 0, angle_tol: float = 1e-6):
    """Every balanced steady motion at the machine's constant speed (or the best partial one).

    Balanced motions are the ball angles that cancel the unbalance (:meth:`Machine.balance_residual`
    = 0, from ``starts`` seeded random starts, distinct ones kept); when the balls cannot cancel
    it, the steady motion that starts from the best partial balance. Each is judged by the exact
    eigenvalues of the co-rotating linearization; where the machine is the planar single-mass
    rotor (:func:`jeffcott_limit`) the seeds' Hamilton and averaged verdicts of the same motion
    are added, elsewhere they are "n/a" with the reason in ``attrs["seed_verdicts"]``.

    Returns
    -------
    xarray.Dataset
        Dim ``motion``: ``kind`` ("balanced" or "partly balanced"), ``exists``, ``ball_angle``
        (motion, ball) (rad, from the rotor's reference direction), ``amplitude`` (motion,
        station) whirl radius (m), ``max_real_eigenvalue`` (1/s), ``stable``,
        ``verdict_exact``, ``verdict_hamilton``, ``verdict_averaged``; ``status`` (0, or
        :data:`NO_STEADY_STATUS` with ``attrs["message"]`` when there is no co-rotating frame,
        or :data:`CLEARANCE_STATUS` when every motion's orbit at the clearance exceeds the gap).
        A motion whose orbit exceeds the gap (:func:`clearance_violation`) has ``exists`` false,
        verdict "absent (exceeds the clearance)", and ``attrs["message"]`` names the station, the
        radius and the gap.
    """
    import xarray as xr
    from scipy.optimize import least_squares

    nb, nz = machine.n_balls, machine.n_coordinates
    message = machine.why_no_rotating_frame()
    found: list[np.ndarray] = []
    kinds: list[str] = []
    if message is None and nb:
        scale = max(sum(u.mass_eccentricity for u in machine.unbalances), 1e-300)
        rng = np.random.default_rng(seed)
        for _ in range(starts):
            res = least_squares(lambda a: machine.balance_residual(a) / scale, rng.uniform(0, 2 * np.pi, nb),
                                xtol=1e-15, ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(res.fun)) < 1e-10:
                psi = _wrap(res.x)
                if not any(np.max(np.abs(_wrap(psi - f))) < angle_tol for f in found):
                    found.append(psi)
        ys = [machine.balanced_state(p) for p in sorted(found, key=lambda p: tuple(np.round(p, 6)))]
        kinds = ["balanced"] * len(ys)
        if not ys:
            y = machine.steady_state()
            if y is not None:
                ys, kinds = [y], ["partly balanced"]
        if not ys:
            message = "no steady motion found (the equilibrium solver did not converge); simulate instead"
    else:
        ys = []
        if message is None:
            message = "the machine has no balls"
    n = max(len(ys), 1)
    angles = np.full((n, nb), np.nan)
    amp = np.full((n, machine.structure.n_nodes), np.nan)
    lam = np.full(n, np.nan)
    stable = np.zeros(n, bool)
    exact = ["absent"] * n
    hamilton = ["n/a"] * n
    averaged = ["n/a"] * n
    states = list(ys)
    for j, y in enumerate(ys):
        lin = machine.linearize(y)
        angles[j] = _wrap(y[2 * nz:2 * nz + nb])
        amp[j] = machine.station_amplitudes(machine.rotating_to_fixed(y))
        lam[j] = float(lin.eigenvalues.real.max())
        stable[j] = lin.is_stable
        exact[j] = "stable" if stable[j] else "unstable"
    note = SEED_VERDICTS_NOTE
    limit = jeffcott_limit(machine) if message is None else None
    labels = [f"{k} {j}" for j, k in enumerate(kinds)] or ["none"]
    if limit is not None:
        # the planar single-mass rotor: every steady motion of seeds 002/003 (balanced and side
        # motions), each found again in the machine (root solve from the seeds' motion) and judged
        # by the machine's own eigenvalues, with the seeds' two verdicts beside
        from rotorlab.steady import analyze_steady

        jb, phase = limit
        doc = analyze_steady(jb).to_dict()
        note = "the machine is the planar single-mass rotor of seeds 002/003: their verdicts are given"
        n = len(doc["motions"])
        angles, amp = np.full((n, nb), np.nan), np.full((n, machine.structure.n_nodes), np.nan)
        lam, stable = np.full(n, np.nan), np.zeros(n, bool)
        exact, hamilton, averaged, kinds, labels, exists = [], [], [], [], [], []
        states = []
        for j, mo in enumerate(doc["motions"]):
            y = None
            if mo["exists"]:
                d = (mo["amplitude"] or 0.0) * np.exp(1j * ((mo["phase"] or 0.0) + phase))
                y = _equilibrium_near(machine, np.array([d.real, d.imag, 0.0, 0.0]),
                                      np.asarray(mo["ball_angles"]) + phase)
            exists.append(y is not None)
            states.append(y)
            if y is not None:
                lin = machine.linearize(y)
                angles[j] = _wrap(y[2 * nz:2 * nz + nb])
                amp[j] = machine.station_amplitudes(machine.rotating_to_fixed(y))
                lam[j] = float(lin.eigenvalues.real.max())
                stable[j] = lin.is_stable
            exact.append(("stable" if stable[j] else "unstable") if y is not None else "absent")
            hamilton.append(mo["verdicts"]["hamilton"] if mo["exists"] else "absent")
            averaged.append(mo["verdicts"]["averaged"] if mo["exists"] else "absent")
            kinds.append("balanced" if mo["kind"] == "main" else str(mo["kind"]))
            labels.append(str(mo["label"]))
        ys = [True] * sum(exists)  # found at least one
        exists_arr = np.asarray(exists)
    else:
        exists_arr = np.asarray([True] * len(ys) or [False])
        n = max(len(ys), 1)
    # a motion computed without contact whose orbit reaches past the clearance does not exist
    hits: list[str] = []
    for j, y in enumerate(states):
        hit = None if y is None else clearance_violation(machine, y)[1]
        if hit is not None:
            exists_arr[j], stable[j], exact[j] = False, False, "absent (exceeds the clearance)"
            hits.append(f"motion {labels[j] if j < len(labels) else j}: {hit}")
    if hits:
        message = "; ".join(hits) if message is None else message + "; " + "; ".join(hits)
    ds = xr.Dataset(
        {
            "kind": (("motion",), np.asarray(kinds or ["none"], dtype=str)),
            "label": (("motion",), np.asarray(labels, dtype=str)),
            "exists": (("motion",), exists_arr),
            "ball_angle": (("motion", "ball"), angles, {"units": "rad"}),
            "amplitude": (("motion", "station"), amp, {"units": "m"}),
            "max_real_eigenvalue": (("motion",), lam, {"units": "1/s"}),
            "stable": (("motion",), stable),
            "verdict_exact": (("motion",), np.asarray(exact, dtype=str)),
            "verdict_hamilton": (("motion",), np.asarray(hamilton, dtype=str)),
            "verdict_averaged": (("motion",), np.asarray(averaged, dtype=str)),
            "status": ((), np.int64(0 if exists_arr.any() else CLEARANCE_STATUS if hits else NO_STEADY_STATUS)),
        },
        coords={"motion": np.arange(len(labels)), "station": list(machine.structure.node_label),
                **_ball_coords(machine)},
        attrs={"analysis": "steady", "model": "machine", "seed_verdicts": note,
               "speed": float(machine.drive.speed) if hasattr(machine.drive, "speed") else math.nan,
               **({"message": message} if message else {})},
    )
    return ds


def _equilibrium_near(machine, q, psi):
    """The co-rotating equilibrium near node displacements ``q`` (full structure coordinates, m)
    and ball angles ``psi`` (rad), or None (SciPy's hybrid Powell method on the rotating-frame
    accelerations, as :meth:`Machine.steady_state`)."""
    from scipy.optimize import root

    nz, nb = machine.n_coordinates, machine.n_balls

    def state(x):
        y = np.zeros(2 * nz + 2 * nb)
        y[:nz], y[2 * nz:2 * nz + nb] = x[:nz], x[nz:]
        return y

    def residual(x):
        f = machine.rotating_rhs(state(x))
        return np.concatenate([f[nz:2 * nz], f[2 * nz + nb:]])

    z0 = np.linalg.lstsq(machine.basis, np.asarray(q, float), rcond=None)[0]
    sol = root(residual, np.concatenate([z0, psi]), method="hybr", options={"xtol": 1e-13})
    om = float(machine.drive.speed)
    scale = max(sum(u.mass_eccentricity for u in machine.unbalances) / max(machine.structure.total_mass, 1e-300),
                1e-300)
    return state(sol.x) if np.max(np.abs(residual(sol.x))) <= 1e-9 * scale * max(1.0, om * om) else None


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
    """Derived quantities: critical speeds (balls locked), unbalance, capacity per race."""
    m = machine_model(case_model)
    rows = [{"quantity": "critical speeds (forward 1x, balls locked)",
             "value": ", ".join(f"{w:.4g}" for w in structure_critical_speeds(m)[:6]),
             "unit": "rad/s", "sign": ""},
            {"quantity": "unbalance sum m e", "value": sum(u.mass_eccentricity for u in m.unbalances),
             "unit": "kg*m", "sign": ""}]
    for i, r in enumerate(m.races):
        rows.append({"quantity": f"capacity of race {i} (sum m l)", "value": r.capacity,
                     "unit": "kg*m", "sign": ""})
    return rows


def _variant(case_model, analysis, speed: float | None = None):
    """The case's machine with only the analysis' races (all when it names none), at a constant
    ``speed`` if given."""
    from dataclasses import replace

    from rotorlab.models import ConstantSpeed

    m = machine_model(case_model)
    races = getattr(analysis, "races", None)
    if races is not None:
        m = replace(m, races=tuple(m.races[i] for i in races))
    if speed is not None:
        m = m.with_drive(ConstantSpeed(float(speed)))
    return m


def _annotate(ds, case_model, analysis):
    ds = _with_units(ds)
    races = getattr(analysis, "races", None)
    if races is not None:
        ds.attrs["races"] = list(races)
    ds.attrs["n_races"] = len(case_model.races) if races is None else len(races)
    ds.attrs["name"] = analysis.name
    ds.attrs["analysis"] = analysis.type
    return ds


def _run_simulate(case_model, analysis, progress=None):
    omega = analysis.spin_speed(case_model)
    m = _variant(case_model, analysis, omega)
    sets = analysis.ball_angle_sets(m.n_balls)
    angles = np.array(sets, dtype=float).reshape(len(sets), m.n_balls)
    ds = machine_simulate(m, angles, t_end=analysis.duration(case_model), rtol=analysis.rtol,
                          atol=analysis.atol, progress=progress)
    return _annotate(ds, case_model, analysis)


def _simulate_task_size(case_model, analysis) -> int:
    return len(analysis.ball_angle_sets(case_model.balls_in(analysis.races)))


def _run_steady(case_model, analysis, progress=None):
    m = _variant(case_model, analysis, analysis.spin_speed(case_model))
    ds = machine_motions(m)
    if progress is not None:
        progress(1, 1)
    return _annotate(ds, case_model, analysis)


def _with_parameter(machine, name: str, value: float):
    """Every ball of the machine with ``mass`` or ``damping`` (``ball_mass``, ``ball_damping``) set."""
    from dataclasses import replace

    key = name.removeprefix("ball_")
    races = tuple(replace(r, balls=tuple(replace(b, **{key: float(value)}) for b in r.balls))
                  for r in machine.races)
    return replace(machine, races=races)


def _run_chart(case_model, analysis, progress=None):
    import xarray as xr

    speeds = analysis.spin_speeds(case_model)
    m = _variant(case_model, analysis, float(speeds[0]))
    values = analysis.parameter_values()
    if values is None:
        ds = machine_steady(m, speeds)
    else:
        parts = []
        for k, v in enumerate(values):
            parts.append(machine_steady(_with_parameter(m, analysis.param, v), speeds))
            if progress is not None:
                progress(k + 1, len(values))
        ds = xr.concat(parts, dim="parameter", combine_attrs="drop_conflicts")
        from rotorlab.io._steady_specs import STEADY_PARAMETERS

        ds = ds.assign_coords(parameter=("parameter", np.asarray(values, float),
                                         {"units": STEADY_PARAMETERS[analysis.param][2]}))
        ds.attrs["parameter"] = analysis.param
    ds.attrs["analysis"] = "stability-chart"
    return _annotate(ds, case_model, analysis)


def _chart_task_size(case_model, analysis) -> int:
    values = analysis.parameter_values()
    return 1 if values is None else len(values)


def _simulate_rows(ds) -> list[dict[str, Any]]:
    rows = []
    for i in range(ds.sizes["ic"]):
        rows.append({
            "ic": i, "final_speed": _num(ds.final_speed.values[i]),
            "final_speed_rpm": _num(ds.final_speed.values[i] * 30 / np.pi),
            "initial_ball_angles_deg": _per_race(ds, ds.initial_ball_angle.values[i]),
            "final_ball_angles_deg": _per_race(ds, ds.final_ball_angle.values[i]),
            "amplitude": _per_station(ds, ds.amplitude.values[i]),
            "reference_amplitude": _per_station(ds, ds.reference_amplitude.values),
            "outcome": str(ds.outcome.values[i]),
            "status": int(ds.status.values[i]),
        })
    return rows


def _steady_rows(ds) -> list[dict[str, Any]]:
    msg = ds.attrs.get("message")
    rows = []
    for j in range(ds.sizes["motion"]):
        exists = bool(ds.exists.values[j])
        rows.append({
            "motion": int(j), "label": str(ds.label.values[j]), "kind": str(ds.kind.values[j]), "exists": exists,
            "speed": _num(ds.attrs.get("speed", math.nan)),
            "ball_angles_deg": _per_race(ds, ds.ball_angle.values[j]) if exists else None,
            "amplitude": _per_station(ds, ds.amplitude.values[j]) if exists else None,
            "stable": bool(ds.stable.values[j]), "max_real_eigenvalue": _num(ds.max_real_eigenvalue.values[j]),
            **{f"verdict_{k}": str(ds[f"verdict_{k}"].values[j]) for k in ("exact", "hamilton", "averaged")},
            "seed_verdicts": ds.attrs.get("seed_verdicts", ""),
            "status": int(ds.status.values),
            **({"message": msg} if msg else {}),
        })
    return rows


def _chart_rows(ds) -> list[dict[str, Any]]:
    """One row per (parameter value and) speed: exists, balanced, exact stability."""
    msg = ds.attrs.get("message")
    param = ds.attrs.get("parameter")
    values = ds.parameter.values if param else [None]
    rows = []
    for k, v in enumerate(values):
        sub = ds.isel(parameter=k) if param else ds
        for w, e, b, st, lam, a, amp, code in zip(sub.speed.values, sub.exists.values, sub.balanced.values,
                                                  sub.stable.values, sub.max_real_eigenvalue.values,
                                                  sub.ball_angle.values, sub.amplitude.values, sub.status.values):
            rows.append({**({param: float(v)} if param else {}),
                         "speed": _num(w), "speed_rpm": _num(w * 30 / np.pi), "exists": bool(e),
                         "balanced": bool(b), "stable": bool(st), "max_real_eigenvalue": _num(lam),
                         "ball_angles_deg": _per_race(ds, a), "amplitude": _per_station(ds, amp),
                         "status": int(code), **({"message": msg} if msg and int(code) != 0 else {})})
    return rows


def machine_analysis_types() -> dict[str, Any]:
    """The machine's own implementations of the common analysis types (its ``ModelType.analyses``)."""
    from rotorlab.analyses._machine_run_up import _run_run_up, _run_up_rows, _run_up_task_size
    from rotorlab.analyses._registry import AnalysisType

    return {
        "simulate": AnalysisType("simulate", _run_simulate, _simulate_rows, "machine", _simulate_task_size,
                                 "trajectories"),
        "steady": AnalysisType("steady", _run_steady, _steady_rows, "machine"),
        "stability-chart": AnalysisType("stability-chart", _run_chart, _chart_rows, "machine", _chart_task_size),
        "run-up": AnalysisType("run-up", _run_run_up, _run_up_rows, "machine", _run_up_task_size),
    }


def machine_mapper(case_model, analysis, kw):
    """The regime mapper of a machine's basins and sweeps (:class:`rotorlab.explore.MachineRegimes`
    at the analysis' constant speed; None without balls)."""
    from rotorlab.explore import MachineRegimes
    from rotorlab.integrate import StepControl

    if case_model.n_balls == 0:
        return None
    omega = analysis.spin_speed(case_model)
    if omega is None:  # spin_speed is a coordinate of every start: any base speed will do
        omega = case_model.critical_speed()
    if analysis.rtol is not None or analysis.atol is not None:
        kw["control"] = StepControl(rtol=analysis.rtol or 1e-8, atol=analysis.atol or 1e-10)
    return MachineRegimes(_variant(case_model, analysis, omega), spec=case_model,
                          races=getattr(analysis, "races", None), **kw)
