"""Regimes of a ball balancer on a Jeffcott rotor (``jeffcott_balls``): balanced, side motions,
non-synchronous.

Features at each horizon T, over a window of ``window_revolutions`` turns before T sampled at
``samples_per_window`` points: the mean deflection of the disc centre, the largest relative rate
of any ball, and the ball angles at T. The labels are those of
:func:`rotorlab.analyses.classify` (seed 002 eqs. (15)-(16)): *balanced*; each *side* motion
(balls on the line through the unbalance, e.g. ``side (0°, 180°)``); *non-synchronous* (balls
still moving relative to the rotor); *not settled* (not balanced yet, but its deflection is
still falling towards the balanced state: :func:`~rotorlab.explore._settle.settle_estimate`, whose
estimated time to settle is the feature ``settle_estimate``); *other* (held elsewhere by
friction, or a failed integration).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from rotorlab._kernels import jeffcott_balls as _jk
from rotorlab.explore._outcome import (BALANCED_FRACTION, SETTLE_RATE, SIDE_TOLERANCE, reference_amplitude,
                                      wrap_angle)
from rotorlab.explore._settle import NOT_SETTLED, settle_estimate, slowest_decay_rate
from rotorlab.explore._mapper import KEY_PREFIX, Feature, ball_coordinate_units, ball_start_value, window_save_times
from rotorlab.integrate import StepControl
from rotorlab.models import BallParams, ConstantSpeed, JeffcottBalls, Parameter, fixed_to_rotating


__all__ = ["BalancerRegimes", "balancer_labels"]

_ROTOR_UNITS = {"disc_mass": "kg", "eccentricity": "m", "stiffness": "N/m", "damping": "N s/m"}
_BALL_UNITS = {"ball_mass": "kg", "ball_radius": "m", "ball_damping": "N m s/rad", "ball_friction": "1"}
#: The rotor's start: disc centre position (u, v) in the co-rotating frame, at rest relative to it.
_ROTOR_STATE = {"rotor_u": "m", "rotor_v": "m"}


#: The named parameter (:attr:`JeffcottBalls.parameters`) a coordinate that is not a key path
#: stands for: the speed, the rotor's fields (their own names); ``ball_<field>`` stands for that
#: field of every ball (:func:`_ball_keys`).
_ALIASES = {"spin_speed": "speed.speed", **{k: k for k in _ROTOR_UNITS}}


def _ball_keys(balls, kw: Mapping[str, float]) -> dict[str, float]:
    """The named parameters of ``ball_<field>`` values ``kw`` (field -> value): that field of every
    ball; a new mass or radius keeps each ball's J / (m l^2) (its ``inertia`` set to match)."""
    out = {}
    for i, ball in enumerate(balls):
        out.update({f"balls[{i}].{k}": v for k, v in kw.items()})
        if "mass" in kw or "radius" in kw:
            mass, radius = kw.get("mass", ball.mass), kw.get("radius", ball.radius)
            ratio = ball.inertia / (ball.mass * ball.radius**2)
            out[f"balls[{i}].inertia"] = ratio * mass * radius**2
    return out


def _distance(amplitude, reference, max_rate, omega) -> np.ndarray:
    """Distance to the balanced state in units of its thresholds (balanced below 1): the larger of
    the deflection over :data:`BALANCED_FRACTION` of the unbalance response and the ball rate over
    :data:`SETTLE_RATE` of the spin speed (both decay at the balanced state's slowest mode)."""
    ref = np.asarray(reference, dtype=float).reshape(-1, 1)
    om = np.abs(np.asarray(omega, dtype=float)).reshape(-1, 1)
    return np.maximum(amplitude / (BALANCED_FRACTION * ref), max_rate / (SETTLE_RATE * om))


def balancer_labels(n_balls: int) -> tuple[str, ...]:
    """Labels of :class:`BalancerRegimes` for ``n_balls`` balls, in code order.

    Examples
    --------
    >>> balancer_labels(2)
    ('balanced', 'side (0°, 0°)', 'side (0°, 180°)', 'side (180°, 180°)', 'non-synchronous', 'not settled', 'other')
    """
    sides = []
    for combo in itertools.combinations_with_replacement((0, 180), n_balls):
        sides.append("side (" + ", ".join(f"{d}°" for d in combo) + ")")
    return ("balanced", *sides, "non-synchronous", NOT_SETTLED, "other")


@dataclass(frozen=True, slots=True)
class BalancerRegimes:
    """Mapper of start points of a :class:`~rotorlab.models.JeffcottBalls` model to regimes.

    Trajectories start with the disc centre on the axis (or at ``rotor_u``, ``rotor_v`` in the
    co-rotating frame, m), at rest relative to the co-rotating frame, and the balls at given
    angles and rates relative to the rotor. They are integrated in ``frame``; the features are taken
    from the states in the co-rotating frame (converted where integrated in the fixed one).

    Parameters
    ----------
    model : JeffcottBalls
        Base model (any frame) at a constant speed; coordinates set its named parameters
        (:attr:`JeffcottBalls.parameters`, through ``with_parameters``): ``model.<key path>``
        (``model.balls[1].mass``), or the aliases ``spin_speed`` (``speed.speed``), the rotor
        fields, and ``ball_<field>`` (that field of every ball; a new ball mass or radius keeps
        the ratio J / (m l^2)).
    t_end : float
        Simulated time (s), > 0.
    n_horizons : int
        Number of equally spaced horizons, >= 1.
    window_revolutions : float
        Classification window before each horizon in turns of the base model's rotor at t = 0
        (> 0).
    samples_per_window : int
        States saved per window, >= 2.
    base_angles : tuple of float or None
        Ball angles from the unbalance for angle coordinates not given (rad); default equally
        spaced, 2 pi i / n.
    control : StepControl
        Integrator tolerances.
    frame : {"fixed", "rotating"} or None
        Frame the trajectories are integrated in; None (default) chooses from the base model
        (:meth:`JeffcottBalls.cheapest_frame`: ``"fixed"`` where it spins at >=
        ``FIXED_FRAME_ABOVE`` (1.8) times its critical speed with the capacity to balance it,
        else ``"rotating"``). Results agree to the tolerance; the work differs.

    Examples
    --------
    >>> from rotorlab.models import RotorParams
    >>> rotor = RotorParams(disc_mass=1.0, eccentricity=1.5e-3, stiffness=16740.0, damping=13.32)
    >>> model = JeffcottBalls(rotor, (BallParams(0.03, 0.05, damping=2e-3),) * 2,
    ...                       speed=ConstantSpeed(251.3))
    >>> sorted(BalancerRegimes(model).coordinate_units)[:3]
    ['ball_damping', 'ball_friction', 'ball_mass']
    """

    model: JeffcottBalls
    t_end: float = 20.0
    n_horizons: int = 10
    window_revolutions: float = 10.0
    samples_per_window: int = 16
    base_angles: tuple[float, ...] | None = None
    control: StepControl = field(default_factory=lambda: StepControl(rtol=1e-8, atol=1e-10))
    frame: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.model, JeffcottBalls):
            raise ValueError(f"BalancerRegimes.model must be a JeffcottBalls, got {type(self.model).__name__}")
        if not (math.isfinite(self.t_end) and self.t_end > 0):
            raise ValueError(f"BalancerRegimes.t_end must be a finite number > 0 (s), got {self.t_end!r}")
        for name, low in (("n_horizons", 1), ("samples_per_window", 2)):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < low:
                raise ValueError(f"BalancerRegimes.{name} must be an integer >= {low}, got {v!r}")
        if not (math.isfinite(self.window_revolutions) and self.window_revolutions > 0):
            raise ValueError(
                f"BalancerRegimes.window_revolutions must be a finite number > 0, got {self.window_revolutions!r}"
            )
        if not isinstance(self.model.speed, ConstantSpeed) or self.model.speed.speed == 0.0:
            raise ValueError("BalancerRegimes.model must spin at a constant nonzero speed (ConstantSpeed)")
        n = self.model.n_balls
        base = (tuple(2.0 * math.pi * i / n for i in range(n)) if self.base_angles is None
                else tuple(float(a) for a in self.base_angles))  # fmt: skip
        if len(base) != n or not all(math.isfinite(a) for a in base):
            raise ValueError(f"BalancerRegimes.base_angles must be {n} finite angles (rad), got {self.base_angles!r}")
        object.__setattr__(self, "base_angles", base)
        if not isinstance(self.control, StepControl):
            raise ValueError(f"BalancerRegimes.control must be a StepControl, got {type(self.control).__name__}")
        if self.frame is None:
            object.__setattr__(self, "frame", self.model.cheapest_frame(self.model.speed.speed))
        elif self.frame not in ("fixed", "rotating"):
            raise ValueError(f"BalancerRegimes.frame must be 'fixed', 'rotating' or None, got {self.frame!r}")

    # ---- AbstractMapper -----------------------------------------------------------------------
    @property
    def labels(self) -> tuple[str, ...]:
        return balancer_labels(self.model.n_balls)

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        units = ball_coordinate_units(self.model.n_balls)
        keys = {KEY_PREFIX + k: u for k, u in self.model.parameters.units.items()}
        return {**units, **_ROTOR_STATE, "spin_speed": "rad/s", **_ROTOR_UNITS, **_BALL_UNITS, **keys}

    @property
    def window(self) -> float:
        """Length of the classification window (s)."""
        return self.window_revolutions * 2.0 * math.pi / abs(self.model.speed.spin_speed(0.0))

    def horizons(self) -> np.ndarray:
        return self.t_end * np.arange(1, self.n_horizons + 1) / self.n_horizons

    def save_times(self) -> np.ndarray:
        return window_save_times(self.horizons(), self.window, self.samples_per_window)

    def coordinate_parameter(self, name: str) -> Parameter | None:
        """The :class:`~rotorlab.models.Parameter` whose range a coordinate's values must keep
        (None for a start angle or rate): ``model.<key path>``'s, the speed's or the rotor's, the
        first ball's (``ball_<field>``, every ball takes the value)."""
        space = self.model.parameters
        key = f"balls[0].{name[5:]}" if name in _BALL_UNITS else self._key(name)
        return replace(space[key], name=name) if key in space else None

    @staticmethod
    def _key(name: str) -> str | None:
        """The named parameter a coordinate other than ``ball_<field>`` varies (None: a state)."""
        return name[len(KEY_PREFIX):] if name.startswith(KEY_PREFIX) else _ALIASES.get(name)

    def _named(self, values: Mapping[str, float]) -> dict[str, float]:
        """The named parameters of a point's coordinates (aliases resolved)."""
        out = _ball_keys(self.model.balls, {k[5:]: v for k, v in values.items() if k in _BALL_UNITS})
        for name, v in values.items():
            key = self._key(name)
            if key is None:
                continue
            if key in out:
                raise ValueError(f"{name} varies {key}, which another coordinate of the point varies too")
            out[key] = v
        return out

    def _variant(self, values: Mapping[str, float]) -> JeffcottBalls:
        """The base model in the mapper's frame with a point's coordinates set (its named
        parameters, :meth:`JeffcottBalls.with_parameters`)."""
        try:
            return self.model.with_frame(self.frame).with_parameters(**self._named(values))
        except KeyError as exc:
            raise ValueError(exc.args[0]) from None

    def balanced_decay_rate(self) -> float | None:
        """``-max Re(lambda)`` (1/s) of the base model's balanced state (the main motion, seed 003
        eq. (12), free balls at their base angles) from the co-rotating linearisation; None if the
        balls cannot balance or the state is not asymptotically stable."""
        from rotorlab.steady._motions import main_family_angles, main_motions_exist

        m = self.model
        moments = [b.mass * b.radius for b in m.balls]
        if m.has_friction or not main_motions_exist(m.imbalance, moments):
            return None
        angles = main_family_angles(m.imbalance, moments, self.base_angles[2:], +1)
        if angles is None:
            return None
        y = np.zeros(m.n_state)
        y[4 : 4 + m.n_balls] = angles
        return slowest_decay_rate(m.linearize(y).eigenvalues)

    def start_value(self, name: str) -> float | None:
        """The value a start takes for coordinate ``name`` when not given (SI): the base ball
        angle, rest, the base model's speed or rotor field, the field shared by all balls (None
        if the balls differ in it); None for any other name."""
        if self._key(name) in self.model.parameters:
            return self.model.parameters[self._key(name)].value
        if name in _ROTOR_STATE:
            return 0.0
        if name in _BALL_UNITS:
            values = {float(getattr(b, name[5:])) for b in self.model.balls}
            return values.pop() if len(values) == 1 else None
        return ball_start_value(name, self.base_angles)

    def starts(self, coords: Mapping[str, np.ndarray]):
        n_pts = max((v.size for v in coords.values()), default=1)
        nb = self.model.n_balls
        angles = np.stack([np.broadcast_to(coords.get(f"psi_{i + 1}", self.base_angles[i]), (n_pts,))
                           for i in range(nb)], axis=1) if nb else np.empty((n_pts, 0))  # fmt: skip
        rates = np.stack([np.broadcast_to(coords.get(f"dpsi_{i + 1}", 0.0), (n_pts,))
                          for i in range(nb)], axis=1) if nb else np.empty((n_pts, 0))  # fmt: skip
        rotor = [np.broadcast_to(coords.get(k, 0.0), (n_pts,)) for k in _ROTOR_STATE]
        order = (*_ALIASES, *_BALL_UNITS)  # the aliases first, in this order (the chunk's model: the first row's)
        params = [k for k in order if k in coords] + [k for k in coords if k.startswith(KEY_PREFIX)]
        if params:
            keys = np.stack([coords[k] for k in params], axis=1)
            uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
            inverse = inverse.reshape(-1)
        else:
            uniq, inverse = np.empty((1, 0)), np.zeros(n_pts, dtype=np.int64)
        first = None
        Y0 = P = None
        for j, row in enumerate(uniq):
            model = self._variant(dict(zip(params, (float(v) for v in row))))
            if first is None:
                first = model
                Y0 = np.empty((n_pts, model.n_state))
                P = np.empty((n_pts, model.to_array().size))
            elif model.has_friction != first.has_friction:
                raise ValueError("ball_friction must be either zero everywhere or positive everywhere")
            sel = np.flatnonzero(inverse == j)
            if model.has_friction:  # each start's stick/slip modes settled one at a time
                Y0[sel] = [model.initial_state(angles[i], ball_rates=rates[i]) for i in sel]
            shifted = model.has_friction and (np.any(rotor[0][sel]) or np.any(rotor[1][sel]))
            if not model.has_friction or shifted:  # all starts at once (0.18 ms a start one at a time)
                yr = np.zeros((sel.size, model.n_state))  # the starts in the co-rotating frame
                yr[:, 0], yr[:, 1] = rotor[0][sel], rotor[1][sel]
                yr[:, 4 : 4 + nb] = angles[sel]
                yr[:, 4 + nb : 4 + 2 * nb] = rates[sel]
                fixed = model.with_frame("rotating").to_frame(0.0, yr, model.frame)
                if shifted:  # with friction only the rotor moves: the balls keep their modes
                    Y0[sel, :4] = fixed[:, :4]
                else:
                    Y0[sel] = fixed
            P[sel] = model.to_array()
        return first, Y0, P

    def features(self, sol, P: np.ndarray) -> dict[str, Feature]:
        nb = int(P[0, _jk.P_N])
        h = self.horizons()
        ts = self.save_times()
        omega = P[:, _jk.P_SPEED + 1]
        ys = sol.ys
        if self.frame == "fixed":  # to the co-rotating frame: constant speed, theta = omega t
            ys = fixed_to_rotating(omega[:, None] * ts[None, :], omega[:, None], ys, nb)
        amp = np.hypot(ys[:, :, 0], ys[:, :, 1])
        rate = np.abs(ys[:, :, 4 + nb : 4 + 2 * nb]).max(axis=2, initial=0.0)
        n, nh = ys.shape[0], h.size
        amplitude = np.empty((n, nh))
        max_rate = np.empty((n, nh))
        for j, t in enumerate(h):
            cols = np.flatnonzero((ts >= t - self.window * (1 + 1e-12)) & (ts <= t))
            total = np.zeros(n)
            for c in cols:  # fixed summation order: the same bits whatever the chunk
                total += amp[:, c]
            amplitude[:, j] = total / cols.size
            max_rate[:, j] = rate[:, cols].max(axis=1)
        i_end = np.searchsorted(ts, h)
        masses = P[:, _jk.P_BALLS + _jk.B_M :: _jk.BALL_STRIDE][:, :nb]
        ref = reference_amplitude(P[:, _jk.P_M1] * P[:, _jk.P_E], P[:, _jk.P_C],
                                  P[:, _jk.P_M1] + masses.sum(axis=1), P[:, _jk.P_D], omega)  # fmt: skip
        out = {
            "amplitude": Feature(amplitude, "m", "mean deflection of the disc centre over the window"),
            "max_rate": Feature(max_rate, "rad/s", "largest |ball rate relative to the rotor| over the window"),
            "reference_amplitude": Feature(ref, "m", "deflection the unbalance alone causes"),
            "rotor_speed": Feature(omega, "rad/s", "constant spin speed of the trajectory"),
            "status_code": Feature(sol.status.astype(np.int32), "1", "integrator status"),
            "settle_estimate": Feature(settle_estimate(_distance(amplitude, ref, max_rate, omega), np.ones(n), h), "s",
                                       "estimated time to balance of a start still converging (NaN: not converging)"),
        }  # fmt: skip
        for i in range(nb):
            out[f"ball_angle_{i + 1}"] = Feature(wrap_angle(ys[:, i_end, 4 + i]), "rad",
                                                 f"angle of ball {i + 1} from the unbalance at the horizon")
        return out

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray:
        """The labels of :func:`~rotorlab.analyses.classify` (then *not settled* where a start is
        still converging), for all starts and horizons at once: the same rules as one
        ``classify`` call per start and horizon (``tests/unit/test_basin_stability.py`` checks),
        in array operations, since this runs in Python holding the GIL on every chunk."""
        names = self.labels
        nb = self.model.n_balls
        amp = np.asarray(features["amplitude"], dtype=float)
        status = np.asarray(features["status_code"]).reshape(-1, 1)
        omega = np.abs(np.asarray(features["rotor_speed"], dtype=float)).reshape(-1, 1)
        ref = np.asarray(features["reference_amplitude"], dtype=float).reshape(-1, 1)
        angles = wrap_angle(np.stack([features[f"ball_angle_{b + 1}"] for b in range(nb)], axis=-1)) if nb else \
            np.empty((*amp.shape, 0))  # fmt: skip
        moving = ~(np.asarray(features["max_rate"]) <= SETTLE_RATE * omega) | ~np.all(np.isfinite(angles), axis=-1)
        balanced = amp <= BALANCED_FRACTION * ref + 1e-15
        near_zero = np.abs(angles) <= SIDE_TOLERANCE
        side = np.all(near_zero | (np.abs(angles) >= math.pi - SIDE_TOLERANCE), axis=-1) & (nb > 0)
        # side motions are listed by the number of balls at 180 deg (balancer_labels), after "balanced"
        code = np.where(side, 1 + np.sum(~near_zero, axis=-1), names.index("other"))
        code = np.where(balanced, names.index("balanced"), code)
        code = np.where(moving, names.index("non-synchronous"), code)
        waiting = np.isfinite(np.asarray(features["settle_estimate"], dtype=float))
        code = np.where((code != names.index("balanced")) & waiting, names.index(NOT_SETTLED), code)
        return np.where(status < 0, names.index("other"), code).astype(np.int16)
