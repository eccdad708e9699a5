"""Rub regimes: what a rotor does at its clearance, from a simulated window, and maps of it.

A window of a trajectory (samples of the state at times ``ts``) is reduced to features and a
regime:

==================  =========================================================================
feature             meaning
==================  =========================================================================
``impact_rate``     contacts begun per second in the window (impacts, or contact onsets) (1/s)
``contact_fraction`` share of the samples in contact (mode != 0)
``rolling_fraction`` share of the samples rolling on the stator (stick)
``whirl_ratio``     mean angular speed of the rotor centre over the spin speed (> 0 forward)
``peak_force``      largest sampled contact normal force (N)
``peak_impulse``    largest normal impulse of the run (N s)
==================  =========================================================================

Regimes (:class:`RubRegime`): no contact; intermittent impacts (contact begun and left in the
window); full rub (contact in every sample, whirling forward); backward whirl in permanent
contact, rolling (stick in most samples: the theory's ``omega_w = -R_r Omega / r``) or sliding.
The backward-whirl label is thus the theory's criterion (permanent contact whirling backwards)
rather than a speed threshold.

:class:`RubRegimes` runs this at every point of a :class:`rotorlab.sweep.Sweep` (speed x
clearance, speed x unbalance, ... maps); :func:`classify_rub` is the same reduction for one
trajectory.
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from rotorlab._kernels import jeffcott_rub as _k
from rotorlab.contact._model import JeffcottRub
from rotorlab.models._checks import check_number as _num
from rotorlab.sweep._spec import ChunkVar

__all__ = ["RubRegime", "RubFeatures", "RubRegimes", "classify_rub", "rub_features"]


class RubRegime(enum.IntEnum):
    """What the rotor does at its clearance (codes stored in results)."""

    FAILED = -1
    NO_CONTACT = 0
    IMPACTS = 1
    FULL_RUB = 2
    BACKWARD_ROLLING = 3
    BACKWARD_SLIDING = 4

    @property
    def label(self) -> str:
        return _LABELS[self]


_LABELS = {
    RubRegime.FAILED: "integration failed",
    RubRegime.NO_CONTACT: "no contact",
    RubRegime.IMPACTS: "intermittent impacts",
    RubRegime.FULL_RUB: "full rub (forward)",
    RubRegime.BACKWARD_ROLLING: "backward whirl, rolling",
    RubRegime.BACKWARD_SLIDING: "backward whirl, sliding",
}


@dataclass(frozen=True, slots=True)
class RubFeatures:
    """Features of one window and its regime (see the module docstring for each)."""

    regime: RubRegime
    impact_rate: float
    contact_fraction: float
    rolling_fraction: float
    whirl_ratio: float
    peak_force: float
    peak_impulse: float


def rub_features(model: JeffcottRub, ts, ys, params=None) -> RubFeatures:
    """Reduce samples ``ys`` (shape (n, 9)) at times ``ts`` (shape (n,), n >= 2) to features.

    ``params`` (the packed vector, default ``model.to_array()``) lets a sweep vary parameters
    of one model. The normal force at each sample comes from the model's compiled contact law.
    """
    ts = np.asarray(ts, dtype=float)
    ys = np.asarray(ys, dtype=float)
    p = model.to_array() if params is None else np.asarray(params, dtype=float)
    mode = ys[:, _k.MODE]
    contact = mode != 0.0
    span = ts[-1] - ts[0]
    onsets = ys[-1, _k.N_IMP] - ys[0, _k.N_IMP]
    x, y, vx, vy = ys[:, _k.X], ys[:, _k.Y], ys[:, _k.VX], ys[:, _k.VY]
    r2 = x * x + y * y
    omega = np.where(r2 > 0.0, (x * vy - y * vx) / np.where(r2 > 0.0, r2, 1.0), 0.0)
    spin = p[_k.P_W]
    whirl_ratio = float(np.mean(omega) / spin) if spin != 0.0 else 0.0
    forces = [_k.contact_forces(float(t), row, p)[0] for t, row in zip(ts[contact], ys[contact])]
    peak = float(max(forces)) if forces else 0.0
    cf = float(np.mean(contact))
    rf = float(np.mean(mode == 2.0))
    if cf == 0.0 and onsets == 0:
        regime = RubRegime.NO_CONTACT
    elif cf < 1.0 or onsets > 0:
        regime = RubRegime.IMPACTS
    elif whirl_ratio > 0.0:
        regime = RubRegime.FULL_RUB
    else:
        regime = RubRegime.BACKWARD_ROLLING if rf >= 0.5 else RubRegime.BACKWARD_SLIDING
    return RubFeatures(regime, float(onsets / span), cf, rf, whirl_ratio, peak, float(ys[-1, _k.P_MAX]))


def classify_rub(model: JeffcottRub, y0, t_end: float, window: float, n_samples: int = 400,
                 control=None) -> RubFeatures:  # fmt: skip
    """Simulate ``model`` from ``y0`` to ``t_end`` and classify the last ``window`` seconds."""
    from rotorlab.integrate import SaveAt, StepControl, solve

    ts = np.linspace(t_end - window, t_end, int(n_samples))
    sol = solve(model, y0, (0.0, t_end), save_at=SaveAt(ts=ts), control=control or StepControl(rtol=1e-9, atol=1e-12),
                max_events_recorded=0)  # fmt: skip
    if sol.status < 0:
        return RubFeatures(RubRegime.FAILED, *(np.nan,) * 6)
    return rub_features(model, ts, sol.ys)


#: coordinates a map can vary, their packed-parameter index and unit
_COORDS = {
    "spin_speed": (_k.P_W, "rad/s"),
    "clearance": (_k.P_D, "m"),
    "eccentricity": (_k.P_EPS, "m"),
    "friction": (_k.P_MU, "1"),
    "stator_stiffness": (_k.P_KS, "N/m"),
    "restitution": (_k.P_E, "1"),
}


@dataclass(frozen=True, slots=True)
class RubRegimes:
    """Per-point analysis of a sweep: simulate the rub model and classify its last window.

    Parameters
    ----------
    model : JeffcottRub
        The base model; a sweep varies any of ``spin_speed`` (rad/s), ``clearance`` (m),
        ``eccentricity`` (m), ``friction``, ``stator_stiffness`` (N/m, elastic stator only) and
        ``restitution``.
    t_end : float
        Simulated time (s).
    window : float
        Length of the classified window at the end (s), < ``t_end``.
    position, velocity : (float, float)
        Initial state of every point (m, m/s); inside the clearance for a rigid stator.
    n_samples : int
        Samples in the window.
    rtol, atol : float
        Integrator tolerances.
    """

    model: JeffcottRub
    t_end: float
    window: float
    position: tuple[float, float] = (0.0, 0.0)
    velocity: tuple[float, float] = (0.0, 0.0)
    n_samples: int = 400
    rtol: float = 1e-9
    atol: float = 1e-12

    def __post_init__(self) -> None:
        o = "RubRegimes"
        if not isinstance(self.model, JeffcottRub):
            raise ValueError(f"{o}.model must be a JeffcottRub, got {type(self.model).__name__}")
        object.__setattr__(self, "t_end", _num(o, "t_end", self.t_end, unit="s"))
        object.__setattr__(self, "window", _num(o, "window", self.window, hi=self.t_end, hi_open=True, unit="s"))
        if int(self.n_samples) < 2:
            raise ValueError(f"{o}.n_samples must be >= 2, got {self.n_samples!r}")
        self.model.initial_state(self.position, self.velocity)  # validates the start

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return {name: unit for name, (_, unit) in _COORDS.items()}

    def trailing_coords(self) -> dict[str, tuple[np.ndarray, dict[str, Any]]]:
        return {}

    def result_attrs(self) -> dict[str, Any]:
        return {
            "analysis": "rub regimes",
            "regime_codes": "; ".join(f"{int(r)}: {r.label}" for r in RubRegime),
            "t_end": self.t_end,
            "window": self.window,
        }

    def run_chunk(self, coords: Mapping[str, np.ndarray], threads: int | None = None) -> dict[str, ChunkVar]:
        from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

        n = len(next(iter(coords.values())))
        base = self.model.to_array()
        params = np.tile(base, (n, 1))
        for name, values in coords.items():
            idx, _ = _COORDS[name]
            if name == "stator_stiffness" and self.model.rotor.rigid_stator:
                raise ValueError("RubRegimes: stator_stiffness can vary only with an elastic stator")
            params[:, idx] = np.asarray(values, dtype=float)
        y0 = self.model.initial_state(self.position, self.velocity)
        ts = np.linspace(self.t_end - self.window, self.t_end, int(self.n_samples))
        ens = solve_ensemble(self.model, y0, (0.0, self.t_end), params=params, save_at=SaveAt(ts=ts),
                             control=StepControl(rtol=self.rtol, atol=self.atol), threads=threads)  # fmt: skip
        out = {k: np.full(n, np.nan) for k in ("impact_rate", "contact_fraction", "rolling_fraction",
                                                 "whirl_ratio", "peak_force", "peak_impulse")}  # fmt: skip
        regime = np.full(n, int(RubRegime.FAILED), dtype=np.int8)
        for i in range(n):
            if ens.status[i] < 0:
                continue
            f = rub_features(self.model, ts, ens.ys[i], params[i])
            regime[i] = int(f.regime)
            for k in out:
                out[k][i] = getattr(f, k)
        units = {"impact_rate": "1/s", "contact_fraction": "1", "rolling_fraction": "1", "whirl_ratio": "1",
                 "peak_force": "N", "peak_impulse": "N s"}  # fmt: skip
        res = {k: ChunkVar((), v, {"units": units[k]}) for k, v in out.items()}
        res["regime"] = ChunkVar((), regime, {"units": "1", "flag_meanings": self.result_attrs()["regime_codes"]})
        res["status"] = ChunkVar((), np.asarray(ens.status, dtype=np.int8), {"units": "1"})
        return res

    def with_model(self, model: JeffcottRub) -> RubRegimes:
        """The same analysis on another model."""
        return replace(self, model=model)
