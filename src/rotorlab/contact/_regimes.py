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

Any model with a clearance provides the samples these features are computed from
(:class:`ContactSamples`, through its ``contact_samples(ts, ys, params)``) and the parameters a map
may vary (``rub_parameters``: name -> (index in the packed parameters, unit); a map sets them
through the model's named parameters, :meth:`RubRegimes.point_parameters`):
:class:`rotorlab.contact.JeffcottRub` and the composed :class:`rotorlab.models.Machine` with a
:class:`~rotorlab.models.Clearance`. Nothing here branches on the model's type.

Regimes (:class:`RubRegime`): no contact; intermittent impacts (contact begun and left in the
window); full rub (contact in every sample, whirling forward); backward whirl in permanent
contact, rolling (stick in most samples: the theory's ``omega_w = -R_r Omega / r``) or sliding.
The backward-whirl label is thus the theory's criterion (permanent contact whirling backwards)
rather than a speed threshold. The decision from the features is :func:`regime_codes` under a
:class:`RegimeRule`: :data:`WINDOW_RULE` here, and seed 001's whole-run rule
(:data:`rotorlab.analyses._impacts.SEED001_RULE`, whose labels ``none, rebounds, sliding,
backward_whirl`` are the codes 0-3 of :class:`RubRegime`).

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

from rotorlab.models._checks import check_number as _num
from rotorlab.models._rub_rotor import ContactSamples
from rotorlab.sweep._spec import ChunkVar

__all__ = ["RubRegime", "RubFeatures", "RubRegimes", "ContactSamples", "RegimeRule", "WINDOW_RULE",
           "regime_codes", "classify_rub", "rub_features"]


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


@dataclass(frozen=True, slots=True)
class RegimeRule:
    """How features become a regime (:func:`regime_codes`); one rule per kind of record.

    Parameters
    ----------
    sustained_fraction : float
        Contact fraction from which the contact is sustained (full rub or backward whirl).
    impacts_in_sustained : bool
        Whether contacts begun in the record still allow "sustained" (a whole run with
        episodes of sliding between impacts) or not (a window in permanent contact).
    uncounted_contact_is_impact : bool
        Whether contact without a counted onset (contact already at the window's start, or
        impacts below a counting speed) makes the record intermittent.
    backward_at_stop : bool
        Whether a backward whirl ratio alone gives the backward-whirl regime (a run stopped at
        the onset of the backward whirl), or only in sustained contact.
    """

    sustained_fraction: float = 1.0
    impacts_in_sustained: bool = False
    uncounted_contact_is_impact: bool = True
    backward_at_stop: bool = False


#: The rule of a simulated window (:func:`rub_features`): full rub and backward whirl need contact
#: in every sample and no contact begun in the window; any other contact is intermittent.
WINDOW_RULE = RegimeRule()


def regime_codes(onsets, contact_fraction, whirl_ratio, rolling_fraction, status=0,
                 rule: RegimeRule = WINDOW_RULE) -> np.ndarray:  # fmt: skip
    """Regime codes (:class:`RubRegime`) from the features of records (array_like, broadcast).

    No contact; intermittent impacts where contacts began (``onsets > 0``) or, under
    ``rule.uncounted_contact_is_impact``, any contact; sustained contact where the contact
    fraction reaches ``rule.sustained_fraction`` (and no contact began, unless
    ``rule.impacts_in_sustained``): full rub, or backward whirl where ``whirl_ratio <= 0``
    (rolling if ``rolling_fraction >= 0.5``, else sliding); under ``rule.backward_at_stop`` a
    ``whirl_ratio <= 0`` gives the backward whirl without the contact fraction (NaN: not
    measured, never backward); failed where ``status < 0``.

    Examples
    --------
    >>> regime_codes([0, 3, 0, 0], [0.0, 0.4, 1.0, 1.0], [0.0, 0.1, 0.2, -0.3], [0, 0, 0, 0.9]).tolist()
    [0, 1, 2, 3]
    """
    onsets, cf, wr, rf, status = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (onsets, contact_fraction, whirl_ratio, rolling_fraction, status))
    )
    code = np.full(onsets.shape, int(RubRegime.NO_CONTACT), dtype=np.int64)
    intermittent = (onsets > 0) | ((cf > 0) & rule.uncounted_contact_is_impact)
    code[intermittent] = int(RubRegime.IMPACTS)
    # sustained needs contact (cf > 0) even where sustained_fraction is 0 (seed 001's paper convention)
    sustained = (cf > 0) & (cf >= rule.sustained_fraction) & ((onsets == 0) | rule.impacts_in_sustained)
    code[sustained] = int(RubRegime.FULL_RUB)
    with np.errstate(invalid="ignore"):
        backward = (wr <= 0) & (sustained | rule.backward_at_stop)
    code[backward] = np.where(rf[backward] >= 0.5, int(RubRegime.BACKWARD_ROLLING), int(RubRegime.BACKWARD_SLIDING))
    code[status < 0] = int(RubRegime.FAILED)
    return code


def rub_features(model: Any, ts, ys, params=None) -> RubFeatures:
    """Reduce samples ``ys`` (shape (n, n_state)) at times ``ts`` (shape (n,), n >= 2) to features.

    ``model`` is any model with a clearance (``contact_samples``); ``params`` (the packed
    vector, default ``model.to_array()``) lets a sweep vary parameters of one model. The normal
    force at each sample comes from the model's compiled contact law.
    """
    ts = np.asarray(ts, dtype=float)
    ys = np.asarray(ys, dtype=float)
    p = model.to_array() if params is None else np.asarray(params, dtype=float)
    cs = model.contact_samples(ts, ys, p)
    mode = cs.mode
    contact = mode != 0.0
    span = ts[-1] - ts[0]
    onsets = cs.impacts[-1] - cs.impacts[0]
    x, y, vx, vy = cs.w[:, 0], cs.w[:, 1], cs.dw[:, 0], cs.dw[:, 1]
    r2 = x * x + y * y
    omega = np.where(r2 > 0.0, (x * vy - y * vx) / np.where(r2 > 0.0, r2, 1.0), 0.0)
    spin = float(np.mean(cs.spin_speed))
    whirl_ratio = float(np.mean(omega) / spin) if spin != 0.0 else 0.0
    peak = float(np.max(cs.normal_force[contact])) if np.any(contact) else 0.0
    cf = float(np.mean(contact))
    rf = float(np.mean(mode == 2.0))
    regime = RubRegime(int(regime_codes(onsets, cf, whirl_ratio, rf)))
    return RubFeatures(regime, float(onsets / span), cf, rf, whirl_ratio, peak, float(cs.peak_impulse[-1]))


def classify_rub(model: Any, y0, t_end: float, window: float, n_samples: int = 400,
                 control=None) -> RubFeatures:  # fmt: skip
    """Simulate ``model`` from ``y0`` to ``t_end`` and classify the last ``window`` seconds."""
    from rotorlab.integrate import SaveAt, StepControl, solve

    ts = np.linspace(t_end - window, t_end, int(n_samples))
    sol = solve(model, y0, (0.0, t_end), save_at=SaveAt(ts=ts), control=control or StepControl(rtol=1e-9, atol=1e-12),
                max_events_recorded=0)  # fmt: skip
    if sol.status < 0:
        return RubFeatures(RubRegime.FAILED, *(np.nan,) * 6)
    return rub_features(model, ts, sol.ys)


#: The key path a rub-map coordinate varies on a model whose named parameters do not have the
#: coordinate's own name (a :class:`rotorlab.models.Machine`: its first clearance, its first
#: unbalance, its constant speed).
RUB_KEYS = {"clearance": "clearances[0].gap", "restitution": "clearances[0].restitution",
            "friction": "clearances[0].friction", "stator_stiffness": "clearances[0].stator.stiffness",
            "spin_speed": "drive.speed", "unbalance": "unbalances[0].magnitude"}


@dataclass(frozen=True, slots=True)
class RubRegimes:
    """Per-point analysis of a sweep: simulate the rub model and classify its last window.

    Parameters
    ----------
    model : JeffcottRub or Machine
        The base model, any model with a clearance; a sweep varies any of its
        ``rub_parameters`` (JeffcottRub: ``spin_speed`` (rad/s), ``clearance`` (m),
        ``eccentricity`` (m), ``friction``, ``stator_stiffness`` (N/m, elastic stator only) and
        ``restitution``; Machine: see :meth:`rotorlab.models.Machine.rub_parameters`).
    t_end : float
        Simulated time (s).
    window : float
        Length of the classified window at the end (s), < ``t_end``.
    position, velocity : (float, float)
        Initial gap vector and its rate at every point (m, m/s; the model's ``gap_state``);
        inside the clearance for a rigid stator. A start pressed into an elastic stator takes
        each point's contact mode (the model's ``start_mode``: the sign of the slip at that
        point's spin speed, or free where that point's clearance holds it).
    n_samples : int
        Samples in the window.
    rtol, atol : float
        Integrator tolerances.
    """

    model: Any
    t_end: float
    window: float
    position: tuple[float, float] = (0.0, 0.0)
    velocity: tuple[float, float] = (0.0, 0.0)
    n_samples: int = 400
    rtol: float = 1e-9
    atol: float = 1e-12

    def __post_init__(self) -> None:
        o = "RubRegimes"
        if not callable(getattr(self.model, "contact_samples", None)) or not self.model.rub_parameters:
            raise ValueError(f"{o}.model must be a model with a clearance (JeffcottRub, or a Machine "
                             f"with a Clearance), got {type(self.model).__name__}")
        object.__setattr__(self, "t_end", _num(o, "t_end", self.t_end, unit="s"))
        object.__setattr__(self, "window", _num(o, "window", self.window, hi=self.t_end, hi_open=True, unit="s"))
        if int(self.n_samples) < 2:
            raise ValueError(f"{o}.n_samples must be >= 2, got {self.n_samples!r}")
        self.model.gap_state(self.position, self.velocity)  # validates the start
        self.parameter_keys()  # every coordinate is a named parameter of the model

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        return {name: unit for name, (_, unit) in self.model.rub_parameters.items()}

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
        params = self.point_parameters(coords)
        # a start pressed into the stator slides along its slip, which depends on the point's spin
        # speed and clearance: its contact mode is set per point, as the model's own start would
        base_y0 = self.model.gap_state(self.position, self.velocity)
        y0 = np.tile(base_y0, (n, 1))
        y0[:, -1] = [self.model.start_mode(base_y0, row) for row in params]
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

    def parameter_keys(self) -> dict[str, str]:
        """The named parameter (:attr:`model.parameters`) each coordinate of a map varies: the
        coordinate's own name where the model has it (a ``JeffcottRub``: ``clearance``,
        ``spin_speed`` ...), else the key path of :data:`RUB_KEYS` (a machine)."""
        space = self.model.parameters
        out = {}
        for name in self.model.rub_parameters:
            key = name if name in space else RUB_KEYS.get(name)
            if key not in space:
                raise ValueError(f"{type(self.model).__name__} has no named parameter for the rub-map "
                                 f"coordinate {name!r} (tried {name!r} and {RUB_KEYS.get(name)!r})")
            out[name] = key
        return out

    def point_parameters(self, coords: Mapping[str, np.ndarray]) -> np.ndarray:
        """The packed parameters of every point, shape (n, P): the base model's with the
        coordinates set through its named parameters (:meth:`model.pack`, each value checked
        against the parameter's range)."""
        keys = self.parameter_keys()
        names = list(coords)
        columns = np.stack([np.asarray(coords[k], dtype=float) for k in names], axis=1)
        return np.array([self.model.pack({keys[k]: float(v) for k, v in zip(names, row)}) for row in columns])

    def with_model(self, model: Any) -> RubRegimes:
        """The same analysis on another model."""
        return replace(self, model=model)
