"""Regimes of the toroidal ball balancer (seed 004): working, spare, other.

Seed 004 names two regimes of the ball: the *working* regime, where it stops relative to the
body opposite the unbalance (psi = pi in the model's convention), and the *spare* regime, where
it keeps moving relative to the body round the ring. Everything else (the ball held by rolling
friction near the unstable point psi = 0, or still oscillating without circulating, or a failed
integration) is *other*.

Features at each horizon T (window W = ``window_revolutions`` turns of the body before T):

- ``stuck``: both directions stuck at T and no stick/slip switch in (T - W, T] (the state's
  ``t_switch`` is exact, so this is a statement about the whole window, not a sample);
- ``ring_rate``: mean ring rate over the window, (psi(T) - psi(T - W)) / W (psi is not wrapped);
- ``ring_angle``, ``section_angle``: psi (wrapped to [0, 2 pi)) and alpha at T.

Grouping: *working* = stuck with cos(ring_angle) < 0; *spare* = not stuck and at least
``spare_turns`` turns round the ring relative to the body in the window; *other* = the rest.
Per trajectory: ``settle_time`` = time of the last stick/slip switch if the ball is stuck at the
end (NaN otherwise), ``lift_off`` = how often the normal force crossed zero (the model then
leaves its validity: the ball would fly inside the tube).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from rotorlab.explore._mapper import KEY_PREFIX, Feature
from rotorlab.integrate import StepControl
from rotorlab.models._protocol import Parameter
from rotorlab.models._toroidal_ball import ToroidalBall

__all__ = ["TorusRegimes", "TORUS_LABELS"]

#: Labels of :class:`TorusRegimes`, in code order.
TORUS_LABELS = ("working", "spare", "other")

_STATE_UNITS = {"psi": "rad", "alpha": "rad", "dpsi": "rad/s", "dalpha": "rad/s"}
_PARAM_UNITS = {
    "ring_radius": "m",
    "tube_radius": "m",
    "ball_radius": "m",
    "spin_speed": "rad/s",
    "offset": "m",
    "rolling_friction": "m",
    "gravity": "m/s^2",
}


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Wrap to [-pi, pi), leaving angles already there untouched (bit for bit)."""
    inside = (angle >= -math.pi) & (angle < math.pi)
    return np.where(inside, angle, np.mod(angle + math.pi, 2.0 * math.pi) - math.pi)


@dataclass(frozen=True, slots=True)
class TorusRegimes:
    """Mapper of start points of a :class:`~rotorlab.models.ToroidalBall` to regimes.

    Parameters
    ----------
    model : ToroidalBall
        Base model; parameter coordinates set its named parameters (``with_parameters``): its
        fields by name (``offset``) or as ``model.<key path>`` (``model.offset``).
    t_end : float
        Simulated time (s), > 0; the last horizon.
    n_horizons : int
        Number of equally spaced horizons ``t_end * j / n_horizons``, j = 1..n, >= 1.
    window_revolutions : float
        Length of the classification window before each horizon, in turns of the base
        model's body (> 0); with the default 20 it is 0.9 s at omega = 140 1/s.
    spare_turns : float
        Turns round the ring (relative to the body) within the window that make a moving ball
        *spare* (> 0).
    base_state : tuple of 4 float
        ``(psi, alpha, dpsi, dalpha)`` for state coordinates not given (rad, rad/s).
    control : StepControl
        Integrator tolerances.

    Examples
    --------
    >>> from rotorlab.models._toroidal_ball import strautmanis_torus
    >>> m = TorusRegimes(strautmanis_torus(1e-4), t_end=8.0, n_horizons=4)
    >>> m.horizons().tolist(), m.labels
    ([2.0, 4.0, 6.0, 8.0], ('working', 'spare', 'other'))
    """

    model: ToroidalBall
    t_end: float = 60.0
    n_horizons: int = 12
    window_revolutions: float = 20.0
    spare_turns: float = 1.0
    base_state: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    control: StepControl = field(default_factory=lambda: StepControl(rtol=1e-6, atol=1e-8))

    def __post_init__(self) -> None:
        if not isinstance(self.model, ToroidalBall):
            raise ValueError(f"TorusRegimes.model must be a ToroidalBall, got {type(self.model).__name__}")
        if not (math.isfinite(self.t_end) and self.t_end > 0):
            raise ValueError(f"TorusRegimes.t_end must be a finite number > 0 (s), got {self.t_end!r}")
        if isinstance(self.n_horizons, bool) or int(self.n_horizons) != self.n_horizons or self.n_horizons < 1:
            raise ValueError(f"TorusRegimes.n_horizons must be an integer >= 1, got {self.n_horizons!r}")
        for name in ("window_revolutions", "spare_turns"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"TorusRegimes.{name} must be a finite number > 0, got {v!r}")
        base = tuple(float(v) for v in self.base_state)
        if len(base) != 4 or not all(math.isfinite(v) for v in base):
            raise ValueError(f"TorusRegimes.base_state must be 4 finite numbers, got {self.base_state!r}")
        object.__setattr__(self, "base_state", base)
        if not isinstance(self.control, StepControl):
            raise ValueError(f"TorusRegimes.control must be a StepControl, got {type(self.control).__name__}")

    # ---- AbstractMapper -----------------------------------------------------------------------
    @property
    def labels(self) -> tuple[str, ...]:
        return TORUS_LABELS

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        keys = {KEY_PREFIX + k: u for k, u in self.model.parameters.units.items()}
        return {**_STATE_UNITS, **_PARAM_UNITS, **keys}

    @property
    def window(self) -> float:
        """Length of the classification window (s)."""
        return self.window_revolutions * 2.0 * math.pi / self.model.spin_speed

    def horizons(self) -> np.ndarray:
        return self.t_end * np.arange(1, self.n_horizons + 1) / self.n_horizons

    def save_times(self) -> np.ndarray:
        h = self.horizons()
        return np.unique(np.concatenate([np.maximum(h - self.window, 0.0), h]))

    def start_value(self, name: str) -> float | None:
        """The value a start takes for coordinate ``name`` when not given (SI): the base state's
        entry or the base model's parameter; None for any other name."""
        if name in _STATE_UNITS:
            return self.base_state[list(_STATE_UNITS).index(name)]
        par = self.coordinate_parameter(name)
        return None if par is None else par.value

    @staticmethod
    def _key(name: str) -> str | None:
        """The named parameter a coordinate varies: ``model.<key path>``'s or the parameter of the
        coordinate's own name (an alias of ``model.<name>``); None for a state entry."""
        return name[len(KEY_PREFIX):] if name.startswith(KEY_PREFIX) else (name if name in _PARAM_UNITS else None)

    def coordinate_parameter(self, name: str) -> Parameter | None:
        """The model's :class:`~rotorlab.models.Parameter` a coordinate varies (None for a state)."""
        key = self._key(name)
        return replace(self.model.parameters[key], name=name) if key in self.model.parameters else None

    def starts(self, coords: Mapping[str, np.ndarray]):
        n = max((v.size for v in coords.values()), default=1)
        params = [k for k in _PARAM_UNITS if k in coords] + [k for k in coords if k.startswith(KEY_PREFIX)]
        named = [self._key(k) for k in params]
        if len(set(named)) < len(named):
            raise ValueError(f"{', '.join(params)}: two coordinates vary the same parameter")
        state = [np.broadcast_to(coords.get(k, b), (n,)) for k, b in zip(_STATE_UNITS, self.base_state)]
        Y0 = np.empty((n, 7))
        P = np.empty((n, self.model.to_array().size))
        if params:
            keys = np.stack([coords[k] for k in params], axis=1)
            uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
            inverse = inverse.reshape(-1)
        else:
            uniq, inverse = np.empty((1, 0)), np.zeros(n, dtype=np.int64)
        for j, row in enumerate(uniq):
            model = self.model.with_parameters(**dict(zip(named, (float(v) for v in row))))
            sel = inverse == j
            Y0[sel] = model.initial_state(*(s[sel] for s in state))
            P[sel] = model.to_array()
        return self.model, Y0, P

    def features(self, sol, P: np.ndarray) -> dict[str, Feature]:
        h = self.horizons()
        ts = self.save_times()
        i_end = np.searchsorted(ts, h)
        i_start = np.searchsorted(ts, np.maximum(h - self.window, 0.0))
        width = h - ts[i_start]
        ys = sol.ys
        psi_end = ys[:, i_end, 0]
        rate = (psi_end - ys[:, i_start, 0]) / width
        stuck = (ys[:, i_end, 4] == 0.0) & (ys[:, i_end, 5] == 0.0) & (ys[:, i_end, 6] <= ts[i_start])
        stuck_final = (sol.y_final[:, 4] == 0.0) & (sol.y_final[:, 5] == 0.0) & (sol.status >= 0)
        switches = sol.event_counts[:, :4].sum(axis=1)
        return {
            "stuck": Feature(stuck, "1", "both directions stuck over the whole window"),
            "ring_rate": Feature(rate, "rad/s", "mean ring rate relative to the body over the window"),
            "ring_angle": Feature(np.mod(psi_end, 2.0 * math.pi), "rad", "ring angle at the horizon"),
            "section_angle": Feature(_wrap(ys[:, i_end, 1]), "rad",
                                     "cross-section angle at the horizon, wrapped to [-pi, pi)"),
            "settle_time": Feature(np.where(stuck_final, sol.y_final[:, 6], np.nan), "s",
                                   "time of the last stick/slip switch of a ball stuck at the end"),
            "switches": Feature(switches, "1", "stick/slip switches"),
            "lift_off": Feature(sol.event_counts[:, 4], "1",
                                "zero crossings of the normal force (contact assumption violated)"),
        }  # fmt: skip

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray:
        stuck = np.asarray(features["stuck"], dtype=bool)
        turns = np.abs(features["ring_rate"]) * self.window / (2.0 * math.pi)
        working = stuck & (np.cos(features["ring_angle"]) < 0.0)
        spare = ~stuck & (turns >= self.spare_turns)
        return np.where(working, 0, np.where(spare, 1, 2)).astype(np.int16)

