"""Stability chart: which steady motions exist and which are stable, over speed (and a parameter).

Each grid point is one :func:`rotorlab.steady.analyze_steady`; the chart keeps, per motion label,
its existence, the three verdicts, the exact growth rate, the deflection and H~*. The chart is a
use of the sweep engine: :class:`SteadyStability` is its per-point analysis (so a chart can also
run in chunks on local processes or Dask, into a resumable store, with
:func:`rotorlab.sweep.run_sweep`), and :func:`stability_chart` arranges the engine's result.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorlab.steady._analysis import analyze_steady
from rotorlab.steady._motions import motion_labels
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls

__all__ = ["PARAMETERS", "EXACT_VERDICTS", "SteadyStability", "stability_chart", "stable_intervals", "with_parameter"]

#: Second parameters of a chart and their units.
PARAMETERS = {
    "ball_mass": "kg",
    "ball_damping": "N m s/rad",
    "eccentricity": "m",
    "support_damping": "N s/m",
}

#: The exact verdicts of a steady motion (:attr:`rotorlab.steady.Stability.exact`), in the order
#: of the integer codes of :class:`SteadyStability`'s ``verdict_exact``.
EXACT_VERDICTS = ("stable", "unstable", "marginal", "partly stable", "absent")


def with_parameter(model: JeffcottBalls, name: str, value: float) -> JeffcottBalls:
    """Return a copy of ``model`` with one parameter changed.

    Parameters
    ----------
    model : JeffcottBalls
    name : {"ball_mass", "ball_damping", "eccentricity", "support_damping"}
        ``ball_mass`` and ``ball_damping`` set the value of ball 1; the other balls keep their
        ratio to ball 1 (equal balls stay equal); a ball's moment of inertia scales with its mass.
        ``eccentricity`` is e of the disc, ``support_damping`` the external damping d.
    value : float
        In the unit of :data:`PARAMETERS`.

    Returns
    -------
    JeffcottBalls

    Raises
    ------
    ValueError
        Unknown name, a model without balls for a ball parameter, or an invalid value.

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> m = JeffcottBalls(RotorParams(1.0, 1e-3, 100.0), (BallParams(0.02, 0.1), BallParams(0.04, 0.1)),
    ...                   speed=ConstantSpeed(1.0))
    >>> [b.mass for b in with_parameter(m, "ball_mass", 0.03).balls]
    [0.03, 0.06]
    """
    value = float(value)
    if name == "eccentricity":
        return replace(model, rotor=replace(model.rotor, eccentricity=value))
    if name == "support_damping":
        return replace(model, rotor=replace(model.rotor, damping=value))
    if name not in PARAMETERS:
        raise ValueError(f"unknown chart parameter {name!r}; choose one of {', '.join(PARAMETERS)}")
    if not model.balls:
        raise ValueError(f"parameter {name!r} needs a model with balls")
    first = model.balls[0]
    if name == "ball_mass":
        if not value > 0:
            raise ValueError(f"ball_mass must be > 0 (kg), got {value!r}")
        k = value / first.mass
        balls = tuple(replace(b, mass=b.mass * k, inertia=b.inertia * k) for b in model.balls)
    else:
        if first.damping > 0:
            k = value / first.damping
            balls = tuple(replace(b, damping=b.damping * k) for b in model.balls)
        else:
            balls = tuple(replace(b, damping=value) for b in model.balls)
    return replace(model, balls=balls)


@dataclass(frozen=True, eq=False)
class SteadyStability:
    """The per-point analysis of a stability chart: every steady motion at one spin speed (and one
    value of a parameter), for :func:`rotorlab.sweep.run_sweep`.

    Parameters
    ----------
    model : JeffcottBalls
        The rotor with balls (its speed profile is not used: the speed is a coordinate).
    param : str, optional
        A second coordinate (see :func:`with_parameter` and :data:`PARAMETERS`).
    family_samples : int
        Samples per free angle of a family of main motions (n >= 3).

    Notes
    -----
    Coordinates: the speed, as ``spin_speed`` (rad/s) or as ``speed_ratio`` (omega / p, p the
    critical speed of the point's model; give one of the two), and any of :data:`PARAMETERS`
    (applied with :func:`with_parameter` in the order of :data:`PARAMETERS`; ``param`` only
    names the chart's second one). Per point (trailing dims ``motion`` and
    ``ball``): ``exists``, ``stable_hamilton``, ``stable_averaged``, ``stable_exact``,
    ``disagreement`` (bool), ``verdict_exact`` (int code into :data:`EXACT_VERDICTS`),
    ``growth_rate`` (1/s), ``amplitude`` (m), ``phase`` (rad), ``h_tilde`` (J), ``ball_angle``
    (rad), and ``critical_speed`` (rad/s). Each point is computed on its own, so the values do
    not depend on the chunk or the executor.

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    >>> rotor = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
    >>> a = SteadyStability(JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0)))
    >>> out = a.run_chunk({"spin_speed": np.array([50.0, 300.0])})
    >>> out["stable_exact"].values[:, :2].tolist(), out["stable_exact"].dims
    ([[False, False], [True, True]], ('motion',))
    """

    model: Any
    param: str | None = None
    family_samples: int = 8

    def __post_init__(self) -> None:
        if self.param is not None and self.param not in PARAMETERS:
            raise ValueError(f"unknown chart parameter {self.param!r}; choose one of {', '.join(PARAMETERS)}")

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return {"spin_speed": "rad/s", "speed_ratio": "1", **PARAMETERS}

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        labels = motion_labels(self.model.n_balls)  # numbered (a Zarr store keeps no text arrays), named in attrs
        return {"motion": (np.arange(len(labels)), {"units": "1", "labels": list(labels)}),
                "ball": (np.arange(1, self.model.n_balls + 1), {"units": "1"})}  # fmt: skip

    def result_attrs(self) -> dict[str, Any]:
        return {"analysis": "stability-chart", "model": "jeffcott_balls", "verdicts": list(EXACT_VERDICTS)}

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, Any]:
        """Analyse the steady motions at every point of one chunk (``threads`` is not used)."""
        from rotorlab.sweep import ChunkVar

        if ("spin_speed" in coords) == ("speed_ratio" in coords):
            raise ValueError("a steady-stability point needs exactly one of spin_speed and speed_ratio")
        ratio = "speed_ratio" in coords
        om = np.asarray(coords["speed_ratio" if ratio else "spin_speed"], dtype=float)
        vals = {k: np.asarray(coords[k], dtype=float) for k in PARAMETERS if k in coords}
        n_pt, n = om.size, self.model.n_balls
        shape = (n_pt, len(motion_labels(n)))
        out_b = {k: np.zeros(shape, dtype=bool) for k in ("exists", "stable_hamilton", "stable_averaged",
                                                          "stable_exact", "disagreement")}  # fmt: skip
        out_f = {k: np.full(shape, np.nan) for k in ("growth_rate", "amplitude", "phase", "h_tilde")}
        verdict = np.zeros(shape, dtype=np.int8)
        angle = np.full(shape + (n,), np.nan)
        crit = np.empty(n_pt)
        for i in range(n_pt):
            mod = self.model
            for name, v in vals.items():
                mod = with_parameter(mod, name, float(v[i]))
            crit[i] = mod.critical_speed
            res = analyze_steady(mod, float(om[i] * crit[i] if ratio else om[i]), family_samples=self.family_samples)
            bad = {d.label for d in res.disagreements}
            for c, m in enumerate(res.motions):
                st = m.stability
                out_b["exists"][i, c] = m.exists
                for meth in ("hamilton", "averaged", "exact"):
                    out_b[f"stable_{meth}"][i, c] = st.is_stable(meth)
                out_b["disagreement"][i, c] = m.label in bad
                verdict[i, c] = EXACT_VERDICTS.index(st.exact)
                out_f["growth_rate"][i, c] = st.growth_rate
                if m.exists:
                    out_f["amplitude"][i, c] = m.amplitude
                    out_f["phase"][i, c] = m.phase
                    out_f["h_tilde"][i, c] = m.h_tilde
                    angle[i, c] = m.ball_angles
        out = {k: ChunkVar(("motion",), v, {"units": _VAR_ATTRS[k][0], "long_name": _VAR_ATTRS[k][1]})
               for k, v in {**out_b, **out_f}.items()}  # fmt: skip
        out["verdict_exact"] = ChunkVar(("motion",), verdict, {"units": "1", "long_name": "exact verdict (code)",
                                                               "flag_meanings": list(EXACT_VERDICTS)})  # fmt: skip
        out["ball_angle"] = ChunkVar(("motion", "ball"), angle, {"units": "rad",
                                                                 "long_name": "ball angle from the unbalance"})
        out["critical_speed"] = ChunkVar((), crit, {"units": "rad/s", "long_name": "critical speed p"})
        return out


_VAR_ATTRS = {
    "exists": ("1", "motion exists"),
    "stable_hamilton": ("1", "stable by seed 003's method (least H~*, Hessian of f)"),
    "stable_averaged": ("1", "stable by seed 002's averaged equations"),
    "stable_exact": ("1", "exactly stable (eigenvalues of the full Jacobian)"),
    "disagreement": ("1", "a first-order method disagrees with the exact eigenvalues"),
    "growth_rate": ("1/s", "largest real part of the exact eigenvalues"),
    "amplitude": ("m", "shaft deflection"),
    "phase": ("rad", "angle of the deflection from the unbalance"),
    "h_tilde": ("J", "H~* = Pi - T0 (seed 003 (10))"),
}


def stability_chart(model: JeffcottBalls, speeds: Any, *, param: str | None = None, values: Any = None,
                    family_samples: int = 8) -> xarray.Dataset:  # fmt: skip
    """Compute which steady motions exist and which are stable over a grid of speeds.

    Parameters
    ----------
    model : JeffcottBalls
    speeds : array_like, shape (n_speed,)
        Spin speeds Omega (rad/s), > 0.
    param : str, optional
        A second parameter (see :func:`with_parameter`), swept over ``values``.
    values : array_like, shape (n_value,), optional
        Its values, in the unit of :data:`PARAMETERS`.
    family_samples : int
        Samples per free angle of a family of main motions (n >= 3).

    Returns
    -------
    xarray.Dataset
        Dims ([param,] speed, motion, ball). Coordinates ``speed`` (rad/s), ``speed_rpm``,
        ``speed_ratio`` (omega / p; depends on ``ball_mass``), ``motion``, ``kind``, the
        parameter. Variables: ``exists``, ``stable_hamilton``, ``stable_averaged``,
        ``stable_exact`` (bool), ``verdict_exact`` (str), ``growth_rate`` (1/s), ``amplitude``
        (m), ``phase`` (rad), ``ball_angle`` (rad), ``h_tilde`` (J), ``disagreement`` (a
        first-order method disagrees with the exact eigenvalues), ``n_stable_exact`` and
        ``balanced`` (a main motion is exactly stable), ``critical_speed`` (rad/s).

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    >>> rotor = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
    >>> model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0))
    >>> ds = stability_chart(model, [50.0, 300.0])
    >>> ds.stable_exact.sel(speed=300.0).values.tolist()
    [True, True, False, False, False, False]
    """
    import xarray as xr

    om = np.atleast_1d(np.asarray(speeds, dtype=float))
    if om.ndim != 1 or om.size == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
        raise ValueError(f"speeds must be finite numbers > 0 (rad/s), got {speeds!r}")
    if (param is None) != (values is None):
        raise ValueError("give both param and values, or neither")
    if param is not None and param not in PARAMETERS:
        raise ValueError(f"unknown chart parameter {param!r}; choose one of {', '.join(PARAMETERS)}")
    vals = np.atleast_1d(np.asarray(values, dtype=float)) if param is not None else np.array([np.nan])
    from rotorlab.sweep import InProcess, ListAxis, Sweep, run_sweep

    n = model.n_balls
    labels = motion_labels(n)
    axes = (ListAxis("spin_speed", om),) if param is None else (ListAxis(param, vals), ListAxis("spin_speed", om))
    res = run_sweep(Sweep(SteadyStability(model, param, family_samples), axes=axes), executor=InProcess())
    shape = (vals.size, om.size, len(labels))
    dims = ("param", "speed", "motion")
    data = {k: (dims, res[k].values.reshape(shape), {"units": u, "long_name": d}) for k, (u, d) in _VAR_ATTRS.items()}
    verdict = np.array(EXACT_VERDICTS, dtype=object)[res["verdict_exact"].values.reshape(shape)]
    data["verdict_exact"] = (dims, verdict.astype(str), {"units": "1", "long_name": "exact verdict"})
    data["ball_angle"] = (dims + ("ball",), res["ball_angle"].values.reshape(shape + (n,)),
                          {"units": "rad", "long_name": "ball angle from the unbalance"})  # fmt: skip
    crit = res["critical_speed"].values.reshape(shape[:2])[:, 0]
    stable = data["stable_exact"][1]
    kinds = ["main" if lab.startswith("main") else "side" for lab in labels]
    main = np.array([k == "main" for k in kinds])
    n_stable = stable.sum(axis=2)
    balanced = stable[:, :, main].any(axis=2) if main.any() else np.zeros(shape[:2], bool)
    data["n_stable_exact"] = (dims[:2], n_stable, {"units": "1", "long_name": "exactly stable motions"})
    data["balanced"] = (dims[:2], balanced, {"units": "1", "long_name": "a main (balanced) motion is exactly stable"})
    data["critical_speed"] = (("param",), crit, {"units": "rad/s", "long_name": "critical speed p"})
    coords = {
        "speed": ("speed", om, {"units": "rad/s", "long_name": "spin speed"}),
        "speed_rpm": ("speed", om * _RPM, {"units": "rpm"}),
        "speed_ratio": (("param", "speed"), om[None, :] / crit[:, None], {"units": "1", "long_name": "omega / p"}),
        "motion": ("motion", list(labels), {"units": "1"}),
        "kind": ("motion", kinds, {"units": "1"}),
        "ball": ("ball", np.arange(1, n + 1), {"units": "1"}),
    }
    ds = xr.Dataset(data, coords=coords, attrs={"analysis": "stability-chart", "model": "jeffcott_balls"})
    if param is None:
        return ds.isel(param=0, drop=True).assign_attrs(critical_speed=float(crit[0]))
    ds = ds.rename({"param": param}).assign_coords({param: (param, vals, {"units": PARAMETERS[param]})})
    return ds.assign_attrs(parameter=param)


def stable_intervals(ds: xarray.Dataset, method: str = "exact") -> list[dict]:
    """Return the speed intervals of a stability chart in which each motion is stable.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`stability_chart`.
    method : {"exact", "hamilton", "averaged"}
        Whose verdict.

    Returns
    -------
    list of dict
        One per run of consecutive stable grid speeds: ``motion``, ``start`` and ``stop`` (first
        and last stable grid speed, rad/s), ``start_ratio`` and ``stop_ratio`` (omega / p), and,
        for a chart over a parameter, its name with the value (SI).

    Examples
    --------
    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    >>> rotor = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
    >>> model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(1.0))
    >>> ds = stability_chart(model, [50.0, 80.0, 120.0, 200.0, 300.0])
    >>> [(r["motion"], r["start"], r["stop"]) for r in stable_intervals(ds)]
    [('main+', 200.0, 300.0), ('main-', 200.0, 300.0), ('side 00', 50.0, 80.0)]
    """
    if method not in ("exact", "hamilton", "averaged"):
        raise ValueError(f"method must be 'exact', 'hamilton' or 'averaged', got {method!r}")
    var = ds[f"stable_{method}"]
    param = ds.attrs.get("parameter")
    values = ds[param].values if param else [None]
    speeds = ds.speed.values
    out = []
    for a, value in enumerate(values):
        sub = var.isel({param: a}) if param else var
        ratio = (ds.speed_ratio.isel({param: a}) if param else ds.speed_ratio).values
        for label in ds.motion.values:
            flags = np.asarray(sub.sel(motion=label).values, dtype=bool)
            edges = np.flatnonzero(np.diff(np.concatenate([[0], flags.astype(int), [0]])))
            for lo, hi in zip(edges[::2], edges[1::2] - 1):
                row = {"motion": str(label), "start": float(speeds[lo]), "stop": float(speeds[hi]),
                       "start_ratio": float(ratio[lo]), "stop_ratio": float(ratio[hi])}  # fmt: skip
                if param:
                    row[param] = float(value)
                out.append(row)
    return out
