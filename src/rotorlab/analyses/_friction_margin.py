r"""The ``friction-margin`` analysis: where friction holds the balls, and the vibration it leaves.

With friction on the balls a balancer does not need to reach its balanced state exactly: a ball
at rest relative to its race stays there while friction can hold it. Around the balanced
(working) state these stuck equilibria form the *friction band*; a ball stuck at its edge leaves
the largest residual vibration. Per speed this module returns the band (the extent of every ball
coordinate over it, from the balanced angle) and that worst residual, and checks the worst
point by simulation (a ball released at rest just inside stays; just outside it moves).

Rotor with balls (``jeffcott_balls``, Coulomb friction f_i in the race)
    All balls stuck at psi_i, the rotor stands still in the co-rotating frame at the locked
    response ``w = Omega^2 Z / (c - M Omega^2 + i d Omega)``, ``Z = M1 e + sum m_i l_i e^{i psi_i}``
    (:meth:`rotorlab.models.JeffcottBalls.locked_response`). O1 accelerates by ``-Omega^2 w``, so
    the race must hold ball i with the torque ``D_i = m_i l_i Omega^2 Im(w e^{-i psi_i})`` and
    presses it with ``N_i = m_i Omega^2 (l_i + Re(w e^{-i psi_i}))`` (the kernel's
    :func:`rotorlab._kernels.jeffcott_balls.stick_torques` at that state). Ball i sticks while
    ``|D_i| <= f_i l_i N_i``: ``|Im(w e^{-i psi_i})| <= f_i (l_i + Re(w e^{-i psi_i}))``. The band
    is the connected set of ball angles around the balanced ones where every ball sticks (found on
    a grid over the whole turn, then on a finer grid over its extent); the residual vibration is
    ``|w|`` (m).

Toroidal ball (``toroidal_ball``, rolling friction k; seed 004)
    The band is :meth:`rotorlab.models.ToroidalBall.working_point`'s ``psi_band`` and
    ``alpha_band`` (where the ring and cross-section forces stay within the rolling resistance);
    the body has no flexibility in this model, so the residual is the ball's offset from the
    working position, ``|rho_e e^{i psi_e} - rho_0 e^{i pi}|`` (m), its residual unbalance per kg
    of ball (kg m per kg).

Each model type is one entry of :data:`FRICTION_BANDS`; the analysis looks the case's type up.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from rotorlab._registry import Registry

__all__ = ["FRICTION_BANDS", "friction_margin", "jeffcott_band", "torus_band", "run_friction_margin_analysis",
           "friction_margin_rows"]  # fmt: skip

#: The simulation check releases the worst point at (1 -+ this) times its offset from the balanced state.
CHECK_STEP = 0.02
#: Revolutions simulated by the check.
CHECK_REVOLUTIONS = 200.0


def _ball_terms(model, om: float, psi: np.ndarray):
    """``(w, |D_i| - f_i l_i N_i)`` for stuck balls at angles ``psi`` (..., n), closed form above."""
    r = model.rotor
    ml = np.array([b.static_moment for b in model.balls])
    lb = np.array([b.radius for b in model.balls])
    fr = np.array([b.friction for b in model.balls])
    z = r.imbalance + np.sum(ml * np.exp(1j * psi), axis=-1)
    w = om * om * z / (r.stiffness - model.total_mass * om * om + 1j * r.damping * om)
    rel = w[..., None] * np.exp(-1j * psi)
    return w, np.abs(rel.imag) - fr * (lb + rel.real)


def _component(stuck: np.ndarray, seed: tuple[int, ...]) -> np.ndarray:
    from scipy import ndimage

    labels, _ = ndimage.label(stuck)
    lab = labels[seed]
    return labels == lab if lab > 0 else np.zeros_like(stuck)


def _band_on_grid(terms, om, centre, half, grid):
    """Stuck component around ``centre`` on a grid of +-``half`` (rad) per ball: (offsets, mask, |w|)."""
    n = centre.size
    axis = np.linspace(-1.0, 1.0, grid) * half[:, None]  # (n, grid)
    mesh = np.stack(np.meshgrid(*axis, indexing="ij"), axis=-1)  # (grid, ..., n)
    w, margin = terms(om, centre + mesh)
    stuck = np.all(margin <= 0.0, axis=-1)
    return mesh, _component(stuck, (grid // 2,) * n), np.abs(w), stuck


def _outside_neighbour(mesh, stuck, index):
    """A grid neighbour of ``index`` where some ball slips (its offsets), or None."""
    n = mesh.shape[-1]
    for step in np.ndindex(*(3,) * n):
        j = tuple(int(a) + int(b) - 1 for a, b in zip(index, step))
        if all(0 <= a < stuck.shape[k] for k, a in enumerate(j)) and not stuck[j]:
            return mesh[j]
    return None


def jeffcott_band(model, speeds, *, grid: int = 241, simulate: bool = True, threads: int | None = None):
    """Friction band and worst residual deflection of a rotor with one or two balls (module docstring).

    Returns
    -------
    dict
        Arrays over ``(speed, coordinate)``: ``band_low``, ``band_high`` (rad, from the balanced
        angle); over ``speed``: ``worst_residual`` (m), ``check_inside``, ``check_outside`` (1: the
        simulation agrees, 0: it does not, -1: not run or failed), ``worst_angles`` (speed,
        coordinate; rad); and ``coordinates``, ``residual`` (what the residual is), ``units``.
    """
    from rotorlab.analyses._shock_margin import balanced_angles
    from rotorlab.models import ConstantSpeed

    rot = model.with_frame("rotating")
    return stuck_band(
        model.n_balls, speeds, grid=grid, simulate=simulate,
        terms=lambda om, psi: _ball_terms(model, om, psi),
        centre=lambda om: balanced_angles(rot.with_speed(ConstantSpeed(om)), om),
        check=lambda om, centre, offset, beyond: _check_jeffcott(rot, om, centre, offset, beyond, threads))


def stuck_band(n: int, speeds, *, grid: int, simulate: bool, terms, centre, check) -> dict[str, Any]:
    """The band of ``n`` balls stuck around their balanced angles, per speed (what :func:`jeffcott_band`
    returns): ``terms(om, psi) -> (w, margin)`` (complex deflection or residual, and per ball the
    holding torque minus what friction can give, <= 0 where it sticks), ``centre(om)`` the balanced
    angles (or None), ``check(om, centre, offset, beyond) -> (inside, outside)`` the simulated check."""
    ns = len(speeds)
    low, high, worst_at = (np.full((ns, n), np.nan) for _ in range(3))
    worst = np.full(ns, np.nan)
    inside, outside = np.full(ns, -1, dtype=np.int64), np.full(ns, -1, dtype=np.int64)
    for i, om in enumerate(speeds):
        mid = centre(float(om))
        if mid is None:
            continue
        mesh, mask, amp, stuck = _band_on_grid(terms, om, mid, np.full(n, math.pi), grid)
        if not mask.any():
            continue
        span = np.array([np.abs(mesh[..., k][mask]).max() for k in range(n)])
        step = 2.0 * math.pi / (grid - 1)
        if np.all(span < math.pi - step):  # refine over the band's extent
            mesh, mask, amp, stuck = _band_on_grid(terms, om, mid, np.minimum(span + 2.0 * step, math.pi), grid)
        low[i] = [mesh[..., k][mask].min() for k in range(n)]
        high[i] = [mesh[..., k][mask].max() for k in range(n)]
        j = np.unravel_index(np.argmax(np.where(mask, amp, -1.0)), mask.shape)
        worst[i] = amp[j]
        worst_at[i] = mesh[j]
        beyond = _outside_neighbour(mesh, stuck, j)
        if simulate:
            inside[i], outside[i] = check(float(om), mid, worst_at[i], beyond)
    return {"band_low": low, "band_high": high, "worst_residual": worst, "worst_angles": worst_at,
            "check_inside": inside, "check_outside": outside,
            "coordinates": [f"psi_{k + 1}" for k in range(n)], "residual": "rotor deflection",
            "units": "m"}  # fmt: skip


def _check_jeffcott(rot, om, centre, offset, beyond, threads):
    """Release the balls at rest, the rotor on its locked response, at (1 - CHECK_STEP) times the worst
    ``offset`` (inside: must stay) and at ``beyond``, the next grid point where a ball slips (must move)."""
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble
    from rotorlab.models import ConstantSpeed

    m = rot.with_speed(ConstantSpeed(om))
    outside = (1.0 + CHECK_STEP) * offset if beyond is None else beyond
    starts = [m.initial_state(centre + (1.0 - CHECK_STEP) * offset, rotor="steady"),
              m.initial_state(centre + outside, rotor="steady")]
    t_end = CHECK_REVOLUTIONS * 2.0 * math.pi / om
    sol = solve_ensemble(m, np.array(starts), (0.0, t_end), save_at=SaveAt(ts=[t_end]),
                         control=StepControl(rtol=1e-9, atol=1e-12), threads=threads)  # fmt: skip
    ok = np.asarray(sol.status) >= 0
    moved = np.abs(np.asarray(sol.y_final)[:, 4 : 4 + m.n_balls] - np.array(starts)[:, 4 : 4 + m.n_balls]).max(axis=1)
    stays = int(moved[0] < 1e-9) if ok[0] else -1
    leaves = int(moved[1] > 1e-6) if ok[1] else -1
    return stays, leaves


def torus_band(model, speeds, *, grid: int = 241, simulate: bool = True, threads: int | None = None):
    """Friction band of the toroidal ball (seed 004) and its residual unbalance per kg, per speed."""
    ns = len(speeds)
    low, high, worst_at = (np.full((ns, 2), np.nan) for _ in range(3))
    worst = np.full(ns, np.nan)
    inside, outside = np.full(ns, -1, dtype=np.int64), np.full(ns, -1, dtype=np.int64)
    for i, om in enumerate(speeds):
        m = model.with_parameters(spin_speed=float(om))
        wp = m.working_point()
        low[i] = [wp.psi_band[0] - wp.psi, wp.alpha_band[0] - wp.alpha]
        high[i] = [wp.psi_band[1] - wp.psi, wp.alpha_band[1] - wp.alpha]
        rho0 = _rho(m, wp.alpha)
        edges = []
        for psi in wp.psi_band:
            al = m.equilibrium_alpha(psi)
            edges.append((abs(_rho(m, al) * np.exp(1j * psi) - rho0 * np.exp(1j * wp.psi)), psi, al))
        worst[i], psi_e, al_e = max(edges)
        worst_at[i] = [psi_e - wp.psi, al_e - wp.alpha]
        if simulate:
            inside[i], outside[i] = _check_torus(m, wp, psi_e, threads)
    return {"band_low": low, "band_high": high, "worst_residual": worst, "worst_angles": worst_at,
            "check_inside": inside, "check_outside": outside, "coordinates": ["psi", "alpha"],
            "residual": "ball offset (residual unbalance per kg of ball)", "units": "m"}  # fmt: skip


def _rho(model, alpha: float) -> float:
    """Radius of the ball centre's ring at cross-section angle alpha (m): R + a sin(alpha) (rolling)."""
    return model.ring_radius + (model.tube_offset * math.sin(alpha) if model.form == "rolling" else 0.0)


def _check_torus(model, wp, psi_edge, threads):
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    starts = []
    for factor in (1.0 - CHECK_STEP, 1.0 + CHECK_STEP):
        psi = wp.psi + factor * (psi_edge - wp.psi)
        starts.append(model.initial_state(psi, model.equilibrium_alpha(psi)))
    t_end = CHECK_REVOLUTIONS * 2.0 * math.pi / model.spin_speed
    sol = solve_ensemble(model, np.array(starts), (0.0, t_end), save_at=SaveAt(ts=[t_end]),
                         control=StepControl(rtol=1e-9, atol=1e-12), threads=threads)  # fmt: skip
    ok = np.asarray(sol.status) >= 0
    moved = np.abs(np.asarray(sol.y_final)[:, 0] - np.array(starts)[:, 0])
    return (int(moved[0] < 1e-9) if ok[0] else -1), (int(moved[1] > 1e-6) if ok[1] else -1)


#: How each model type gives its friction band: ``band(model, speeds, grid=, simulate=, threads=) -> dict``
#: (the keys of :func:`jeffcott_band`'s return value).
FRICTION_BANDS: Registry[Callable[..., dict[str, Any]]] = Registry("friction band of a model type")
FRICTION_BANDS.register("jeffcott_balls", jeffcott_band)
FRICTION_BANDS.register("toroidal_ball", torus_band)


def _machine_band(model, speeds, **kw):
    from rotorlab.analyses._friction_machine import machine_band

    return machine_band(model, speeds, **kw)


FRICTION_BANDS.register("machine", _machine_band)


def friction_margin(model_type: str, model, speeds, *, grid: int = 241, simulate: bool = True,
                    threads: int | None = None):  # fmt: skip
    """Friction band and worst residual vibration against speed (a Dataset; see the module docstring).

    Returns
    -------
    xarray.Dataset
        ``band_low``, ``band_high``, ``worst_angles`` (speed, coordinate; rad), ``worst_residual``
        (speed; m), ``check_inside``, ``check_outside`` (speed; 1 agrees, 0 disagrees, -1 not run
        or failed). Attributes: ``residual`` (what the residual is).
    """
    import xarray as xr

    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds) & (speeds > 0)):
        raise ValueError(f"speeds must be one or more finite numbers > 0 (rad/s), got {speeds!r}")
    out = FRICTION_BANDS[model_type](model, speeds, grid=grid, simulate=simulate, threads=threads)
    dims = ("speed", "coordinate")
    return xr.Dataset(
        {
            "band_low": (dims, out["band_low"], {"units": "rad"}),
            "band_high": (dims, out["band_high"], {"units": "rad"}),
            "worst_angles": (dims, out["worst_angles"], {"units": "rad"}),
            "worst_residual": (("speed",), out["worst_residual"], {"units": out["units"]}),
            "check_inside": (("speed",), out["check_inside"], {"units": "1"}),
            "check_outside": (("speed",), out["check_outside"], {"units": "1"}),
        },
        coords={"speed": ("speed", speeds, {"units": "rad/s"}), "coordinate": ("coordinate", out["coordinates"])},
        attrs={"residual": out["residual"], "model": model_type, "check_step": CHECK_STEP,
               "search": out.get("search", f"a grid of {grid} points per coordinate"),
               "simulated": int(bool(simulate))},
    )  # fmt: skip


def run_friction_margin_analysis(case_model: Any, analysis: Any,
                                 progress: Callable[[int, int], None] | None = None):  # fmt: skip
    """Run a case's ``friction-margin`` analysis."""
    from rotorlab.analyses._case import build_model

    ds = friction_margin(case_model.type, build_model(case_model), analysis.speed_values(case_model),
                         grid=analysis.grid, simulate=analysis.simulate)  # fmt: skip
    ds.attrs["name"] = analysis.name
    return ds


def friction_margin_rows(ds) -> list[dict[str, Any]]:
    """One row per speed: the band of every coordinate and the worst arrangement (deg, from the balanced
    one), the worst residual and the checks."""
    from rotorlab._constants import RPM_PER_RAD_S
    from rotorlab.analyses._shock_margin import _num

    rows = []
    for i, om in enumerate(ds.speed.values):
        row: dict[str, Any] = {"speed_rpm": float(om) * RPM_PER_RAD_S}
        for k, name in enumerate(ds.coordinate.values):
            row[f"{name}_low_deg"] = _num(np.degrees(ds.band_low.values[i, k]))
            row[f"{name}_high_deg"] = _num(np.degrees(ds.band_high.values[i, k]))
            row[f"{name}_worst_deg"] = _num(np.degrees(ds.worst_angles.values[i, k]))
        row["worst_residual"] = _num(ds.worst_residual.values[i])
        row["check_inside"] = int(ds.check_inside.values[i])
        row["check_outside"] = int(ds.check_outside.values[i])
        rows.append(row)
    return rows
