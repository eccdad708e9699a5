"""From a validated case to results: build the model, run every analysis, summarize outcomes.

Simulations run on the ``jeffcott_balls`` model (:mod:`rotorlab.analyses._simulate`); basins on
it and on the ``toroidal_ball`` model (:mod:`rotorlab.analyses._basin`); the linear
analyses (Campbell diagram, modes, critical speeds, unbalance response, identification, data
audit) on the ``multibody`` and ``fe_rotor`` models (:mod:`rotorlab.analyses._linear`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.analyses._basin import BASIN_ANALYSES
from rotorlab.analyses._impacts import IMPACT_ANALYSES
from rotorlab.analyses._linear import LINEAR_ANALYSES
from rotorlab.analyses._steady import STEADY_ANALYSES

if TYPE_CHECKING:
    import xarray

    from rotorlab.io import Case
    from rotorlab.linear import LinearSystem
    from rotorlab.models import JeffcottBalls, ToroidalBall

__all__ = ["RUNNABLE_ANALYSES", "build_model", "run_analysis", "run_case", "summarize"]

#: Analysis types (the ``type`` of a case's ``[[analysis]]``) that :func:`run_case` can run.
RUNNABLE_ANALYSES = ("simulate", *LINEAR_ANALYSES, *STEADY_ANALYSES, *BASIN_ANALYSES, *IMPACT_ANALYSES, "sweep")

_RPM = 60.0 / (2.0 * math.pi)


def _speed_profile(spec: Any) -> Any:
    from rotorlab.models import ConstantSpeed, HillRunUp, LinearRamp

    if spec is None:
        return ConstantSpeed(0.0)
    if spec.profile == "constant":
        return ConstantSpeed(spec.speed)
    if spec.profile == "ramp":
        return LinearRamp(spec.start, spec.stop, spec.duration)
    if spec.profile == "hill":
        return HillRunUp(spec.max_speed, spec.t_half, spec.exponent)
    raise ValueError(f"unknown speed profile {spec.profile!r}")


def build_model(case_model: Any) -> JeffcottBalls | LinearSystem | ToroidalBall:
    """Build the model object of a validated case's ``[model]`` table.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec, MultibodySpec, FeRotorSpec or ToroidalBallSpec
        ``Case.model`` (SI values, balls expanded).

    Returns
    -------
    JeffcottBalls or rotorlab.linear.LinearSystem or rotorlab.models.ToroidalBall
        A ball balancer in the case's frame; its speed profile is the case's
        ``[model.speed]``, or a rotor at rest (``ConstantSpeed(0)``) when the case gives none
        (analyses set their own speed). For a linear rotor model, its
        :class:`~rotorlab.linear.LinearSystem`; for a toroidal ball, the
        :class:`~rotorlab.models.ToroidalBall`.

    Raises
    ------
    ValueError
        The model type is not one rotorlab can build.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> model = build_model(load_case("autobalancer").model)
    >>> model.n_balls, round(model.critical_speed / (2 * math.pi), 3)
    (2, 20.001)
    """
    from rotorlab.models import BallParams, JeffcottBalls, RotorParams

    if getattr(case_model, "type", None) == "impact_rotor":
        from rotorlab.analyses._impacts import impact_model

        return impact_model(case_model)
    if getattr(case_model, "type", None) in ("multibody", "fe_rotor"):
        from rotorlab.analyses._linear_build import build_linear_system

        return build_linear_system(case_model)
    if getattr(case_model, "type", None) == "toroidal_ball":
        from rotorlab.models import ToroidalBall

        return ToroidalBall(case_model.ring_radius, case_model.tube_radius, case_model.ball_radius,
                            case_model.spin_speed, case_model.offset, case_model.rolling_friction,
                            case_model.gravity, case_model.form)  # fmt: skip
    if getattr(case_model, "type", None) != "jeffcott_balls":
        raise ValueError(f"cannot build a model of type {getattr(case_model, 'type', None)!r}")
    rotor = RotorParams(
        disc_mass=case_model.disc_mass,
        eccentricity=case_model.eccentricity,
        stiffness=case_model.stiffness,
        damping=case_model.damping,
    )
    balls = tuple(
        BallParams(mass=b.mass, radius=b.radius, inertia=b.inertia, damping=b.damping,
                   friction=b.friction)  # fmt: skip
        for b in case_model.balls
    )
    return JeffcottBalls(rotor, balls, speed=_speed_profile(case_model.speed),
                         frame=case_model.frame)  # fmt: skip


def run_analysis(case_model: Any, analysis: Any,
                 progress: Callable[[int, int], None] | None = None) -> xarray.Dataset:  # fmt: skip
    """Run one analysis of a case.

    Parameters
    ----------
    case_model : rotorlab.io.JeffcottBallsSpec, rotorlab.io.MultibodySpec or FeRotorSpec
        ``Case.model``.
    analysis : rotorlab.io.SimulateSpec or a linear analysis spec
        One entry of ``Case.analyses``.
    progress : callable, optional
        ``progress(done, total)``: trajectories finished (a linear analysis reports 0 of 1,
        then 1 of 1).

    Returns
    -------
    xarray.Dataset
        See :func:`rotorlab.analyses.simulate` and
        :func:`rotorlab.analyses.run_linear_analysis`; ``attrs["name"]`` is the analysis name.
    """
    from rotorlab.analyses._simulate import simulate

    if analysis.type == "sweep":
        from rotorlab.analyses._sweep import run_sweep_analysis

        return run_sweep_analysis(case_model, analysis, progress=progress)
    if analysis.type not in RUNNABLE_ANALYSES:
        raise ValueError(
            f"analysis {analysis.name}: type {analysis.type!r} cannot be run here "
            f"(runnable: {', '.join(RUNNABLE_ANALYSES)})"
        )
    if analysis.type in IMPACT_ANALYSES:
        from rotorlab.analyses._impacts import run_impact_analysis

        return run_impact_analysis(case_model, analysis, progress=progress)
    if analysis.type in STEADY_ANALYSES:
        from rotorlab.analyses._steady import run_steady_analysis

        return run_steady_analysis(case_model, analysis, progress=progress)
    if analysis.type in BASIN_ANALYSES:
        from rotorlab.analyses._basin import run_basin_analysis

        return run_basin_analysis(case_model, analysis, progress=progress)
    if analysis.type in LINEAR_ANALYSES:
        from rotorlab.analyses._linear import run_linear_analysis

        if progress is not None:
            progress(0, 1)
        ds = run_linear_analysis(case_model, analysis)
        ds.attrs["name"] = analysis.name
        if progress is not None:
            progress(1, 1)
        return ds
    model = build_model(case_model)
    omega = analysis.spin_speed(case_model)
    sets = analysis.ball_angle_sets(model.n_balls)
    angles = np.array(sets, dtype=float).reshape(len(sets), model.n_balls)
    ds = simulate(
        model,
        speeds=None if omega is None else [omega],
        initial_ball_angles=angles,
        t_end=analysis.duration(case_model),
        n_save=analysis.n_save,
        rtol=analysis.rtol,
        atol=analysis.atol,
        progress=progress,
    )
    ds.attrs["name"] = analysis.name
    return ds


def run_case(case: Case,
             progress: Callable[[str, int, int], None] | None = None) -> dict[str, xarray.Dataset]:  # fmt: skip
    """Run every analysis of a case, in file order.

    Parameters
    ----------
    case : rotorlab.io.Case
        A validated case (:func:`rotorlab.io.load_case`).
    progress : callable, optional
        Called as ``progress(analysis_name, done, total)`` as trajectories finish.

    Returns
    -------
    dict of str to xarray.Dataset
        Results by analysis name, in the case's order.

    Raises
    ------
    ValueError
        An analysis type is not in :data:`RUNNABLE_ANALYSES` (checked before anything runs).
    """
    for analysis in case.analyses:
        if analysis.type not in RUNNABLE_ANALYSES:
            raise ValueError(
                f"analysis {analysis.name}: type {analysis.type!r} cannot be run here "
                f"(runnable: {', '.join(RUNNABLE_ANALYSES)})"
            )
    results = {}
    for analysis in case.analyses:
        report = None
        if progress is not None:

            def report(done: int, total: int, name: str = analysis.name) -> None:
                progress(name, done, total)

        ds = run_analysis(case.model, analysis, progress=report)
        ds.attrs["case"] = case.name
        results[analysis.name] = ds
    return results


def _degrees(values: np.ndarray) -> list[float | None]:
    return [None if not np.isfinite(v) else round(float(np.degrees(v)), 2) for v in values]


def _number(value: float) -> float | None:
    return float(value) if np.isfinite(value) else None


def summarize(ds: xarray.Dataset) -> list[dict[str, Any]]:
    """Tabulate a result: for a simulation, one row per (speed, initial configuration).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`rotorlab.analyses.simulate`, or from a linear analysis (see
        :func:`rotorlab.analyses.summarize_linear` for its rows).

    Returns
    -------
    list of dict
        Simulation keys: ``speed`` (rad/s), ``speed_rpm``, ``speed_hz``, ``speed_ratio``
        (omega / p), ``ic``, ``initial_ball_angles_deg``, ``final_amplitude`` (m),
        ``reference_amplitude`` (m), ``amplitude_ratio`` (final / reference),
        ``final_ball_angles_deg``, ``outcome``, ``status``. Plain Python values (JSON-ready;
        NaN becomes None).
    """
    if ds.attrs.get("analysis") == "impacts":
        from rotorlab.analyses._impacts import impact_summary

        return [impact_summary(ds)]
    if ds.attrs.get("analysis") == "impacts-sweep":
        from rotorlab.analyses._impacts import sweep_summary

        return sweep_summary(ds)["rows"]
    if ds.attrs.get("analysis") in STEADY_ANALYSES:
        from rotorlab.analyses._steady import steady_rows

        return steady_rows(ds)
    if ds.attrs.get("analysis") in (*BASIN_ANALYSES, "sweep"):
        from rotorlab.analyses._basin import basin_rows

        return basin_rows(ds)
    if ds.attrs.get("analysis") in LINEAR_ANALYSES:
        from rotorlab.analyses._linear import summarize_linear

        return summarize_linear(ds)
    rows = []
    for k in range(ds.sizes["speed"]):
        om = float(ds.speed.values[k])
        ref = float(ds.reference_amplitude.values[k])
        for i in range(ds.sizes["ic"]):
            amp = float(ds.final_amplitude.values[k, i])
            rows.append(
                {
                    "speed": om,
                    "speed_rpm": om * _RPM,
                    "speed_hz": om / (2.0 * math.pi),
                    "speed_ratio": float(ds.speed_ratio.values[k]),
                    "ic": int(ds.ic.values[i]),
                    "initial_ball_angles_deg": _degrees(ds.initial_ball_angle.values[i]),
                    "final_amplitude": _number(amp),
                    "reference_amplitude": ref,
                    "amplitude_ratio": _number(amp / ref) if ref > 0 else None,
                    "final_ball_angles_deg": _degrees(ds.final_ball_angle.values[k, i]),
                    "outcome": str(ds.outcome.values[k, i]),
                    "status": int(ds.status.values[k, i]),
                }
            )
    return rows
