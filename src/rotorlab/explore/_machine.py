"""Regimes of a composed machine's balancer (:class:`rotorlab.models.Machine`): balanced, not
balanced, non-synchronous.

Features at each horizon T, over a window of ``window_revolutions`` turns before T sampled at
``samples_per_window`` points: the vibration amplitude (the largest distance of any station from
its mean position in the window; in the fixed frame, so a static deflection under gravity does not
count), the largest ball rate relative to the rotor, and the ball angles at T relative to the
rotor. The labels follow :func:`rotorlab.analyses._machine.machine_simulate`: *balanced* (the
vibration at most :data:`~rotorlab.analyses.BALANCED_FRACTION` of the largest unbalance response
with the balls locked), *non-synchronous* (balls still moving relative to the rotor faster than
:data:`~rotorlab.explore._outcome.NON_SYNCHRONOUS_RATE` times its speed), *not balanced*
(settled elsewhere) and *other* (a failed integration).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from rotorlab.explore._outcome import BALANCED_FRACTION, machine_outcome, wrap_machine_angle
from rotorlab.explore._settle import NOT_SETTLED, settle_estimate, slowest_decay_rate
from rotorlab.explore._mapper import KEY_PREFIX, Feature, ball_coordinate_units, ball_start_value, window_save_times
from rotorlab.integrate import StepControl
from rotorlab.models import ConstantSpeed, Machine, Parameter

__all__ = ["MachineRegimes", "MACHINE_LABELS"]

#: Labels of :class:`MachineRegimes`, in code order.
MACHINE_LABELS = ("balanced", "not balanced", "non-synchronous", NOT_SETTLED, "other")
_PARAMS = {"spin_speed": "rad/s", "ball_mass": "kg", "ball_damping": "N m s/rad"}
#: Ranges of the coordinates of :data:`_PARAMS` (gt, ge, lt, le), those of a ball's keys.
_PARAM_BOUNDS = {"spin_speed": (0.0, None, None, None), "ball_mass": (0.0, None, None, None),
                 "ball_damping": (None, 0.0, None, None)}


@dataclass(frozen=True)
class MachineRegimes:
    """Mapper of start points of a :class:`~rotorlab.models.Machine` to balancer regimes.

    Trajectories start with the structure at rest and the balls at given angles and rates
    relative to the rotor (``psi_<i>``, ``dpsi_<i>``, i = 1..n over the races in order), at a
    constant speed.

    Parameters
    ----------
    model : Machine
        Base machine with a ``ConstantSpeed`` drive and at least one ball; coordinates replace
        its speed (``spin_speed``) or the mass or damping of every ball (``ball_mass``,
        ``ball_damping``).
    t_end : float
        Simulated time (s), > 0.
    n_horizons : int
        Number of equally spaced horizons, >= 1.
    window_revolutions : float
        Classification window before each horizon in turns of the base machine's rotor (> 0).
    samples_per_window : int
        States saved per window (>= 8 per revolution resolves the orbit), >= 2.
    base_angles : tuple of float or None
        Ball angles for angle coordinates not given (rad); default equally spaced in each race.
    control : StepControl
        Integrator tolerances.
    source : Machine, optional
        The whole machine ``model`` was made from (every race, the case's drive; a machine built
        from a case, :func:`rotorlab.io.build_machine`): then each of its named parameters
        (:attr:`Machine.parameters <rotorlab.models.Machine.parameters>`) is a coordinate too,
        as ``model.<key path>`` (e.g. ``model.unbalances[0].magnitude``, SI); a value makes the
        variant with :meth:`~rotorlab.models.Machine.with_parameters` (checked against the key's
        range), never from the case document.
    races : tuple of int, optional
        The races of ``source`` that take part (default all), as in ``model``.
    """

    model: Machine
    t_end: float = 200.0
    n_horizons: int = 10
    window_revolutions: float = 2.0
    samples_per_window: int = 33
    base_angles: tuple[float, ...] | None = None
    control: StepControl = field(default_factory=lambda: StepControl(rtol=1e-8, atol=1e-10))
    source: Machine | None = None
    races: tuple[int, ...] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.model, Machine):
            raise ValueError(f"MachineRegimes.model must be a Machine, got {type(self.model).__name__}")
        if not isinstance(self.model.drive, ConstantSpeed) or self.model.drive.speed == 0.0:
            raise ValueError("MachineRegimes.model must spin at a constant nonzero speed (ConstantSpeed)")
        if self.model.n_balls == 0:
            raise ValueError("MachineRegimes.model has no balls: there is no balancer to map")
        if not (math.isfinite(self.t_end) and self.t_end > 0):
            raise ValueError(f"MachineRegimes.t_end must be a finite number > 0 (s), got {self.t_end!r}")
        for name, low in (("n_horizons", 1), ("samples_per_window", 2)):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < low:
                raise ValueError(f"MachineRegimes.{name} must be an integer >= {low}, got {v!r}")
        if not (math.isfinite(self.window_revolutions) and self.window_revolutions > 0):
            raise ValueError("MachineRegimes.window_revolutions must be a finite number > 0, got "
                             f"{self.window_revolutions!r}")
        n = self.model.n_balls
        lay = self.model.layout
        base = (tuple(float(a) for a in self.model.initial_state()[lay.i_phi:lay.i_phi + n])
                if self.base_angles is None else tuple(float(a) for a in self.base_angles))
        if len(base) != n or not all(math.isfinite(a) for a in base):
            raise ValueError(f"MachineRegimes.base_angles must be {n} finite angles (rad), got {self.base_angles!r}")
        object.__setattr__(self, "base_angles", base)

    # ---- AbstractMapper -----------------------------------------------------------------------
    @property
    def labels(self) -> tuple[str, ...]:
        return MACHINE_LABELS

    @property
    def coordinate_units(self) -> Mapping[str, str]:
        units = {**ball_coordinate_units(self.model.n_balls), **_PARAMS}
        if self.source is not None:
            units.update({KEY_PREFIX + k: u for k, u in self.source.parameters.units.items()})
        return units

    @property
    def window(self) -> float:
        """Length of the classification window (s)."""
        return self.window_revolutions * 2.0 * math.pi / abs(self.model.drive.speed)

    def horizons(self) -> np.ndarray:
        return self.t_end * np.arange(1, self.n_horizons + 1) / self.n_horizons

    def save_times(self) -> np.ndarray:
        return window_save_times(self.horizons(), self.window, self.samples_per_window)

    def coordinate_parameter(self, name: str) -> Parameter | None:
        """The :class:`~rotorlab.models.Parameter` whose range a coordinate's values must keep
        (None for a start angle or rate): a ``model.<key path>`` of ``source``, or the speed, mass
        or damping of the balls."""
        if name.startswith(KEY_PREFIX) and self.source is not None and name[len(KEY_PREFIX):] in self.source.parameters:
            return self.source.parameters[name[len(KEY_PREFIX):]]
        if name in _PARAM_BOUNDS:
            return Parameter(name, _PARAMS[name], float("nan"), _PARAM_BOUNDS[name])
        return None

    def _rebuilt(self, keys: Mapping[str, float]) -> Machine:
        """The variant of ``source`` with the ``model.<key path>`` values set (its named
        parameters), with ``model``'s races and drive."""
        if self.source is None:
            raise ValueError(f"{', '.join(keys)}: a machine built from a case (source) is needed for model.<key path>")
        try:
            m = self.source.with_parameters(**{k[len(KEY_PREFIX):]: float(v) for k, v in keys.items()})
        except (KeyError, ValueError) as exc:
            text = exc.args[0] if exc.args else str(exc)
            raise ValueError(f"at {', '.join(f'{k} = {v:g}' for k, v in keys.items())}: {text}") from None
        if self.races is not None:
            m = replace(m, races=tuple(m.races[i] for i in self.races))
        m = m.with_drive(self.model.drive)
        if m.layout != self.model.layout or not np.array_equal(m.basis, self.model.basis):
            raise ValueError(f"{', '.join(keys)}: changes the machine's size or the modes it keeps (n_modes); "
                             "a basin or sweep varies numbers that keep both")
        return m

    def _variant(self, values: Mapping[str, float], masses=None) -> Machine:
        keys = {k: v for k, v in values.items() if k.startswith("model.")}
        m = self._rebuilt(keys) if keys else self.model
        if "spin_speed" in values:
            m = m.with_drive(ConstantSpeed(float(values["spin_speed"])))
        kw = {k[5:]: float(v) for k, v in values.items() if k in ("ball_mass", "ball_damping")}
        if kw or masses is not None:
            it = iter(masses) if masses is not None else None
            races = tuple(replace(r, balls=tuple(replace(b, **kw, **({} if it is None else {"mass": float(next(it))}))
                                                 for b in r.balls)) for r in m.races)
            m = replace(m, races=races)
        return m

    def balanced_decay_rate(self) -> float | None:
        """``-max Re(lambda)`` (1/s) of the base machine's balanced state
        (:meth:`~rotorlab.models.Machine.balanced_state`, its co-rotating linearisation); None
        without a co-rotating frame, if the balls cannot balance or the state is not
        asymptotically stable."""
        m = self.model
        if m.why_no_rotating_frame() is not None:
            return None
        try:
            y = m.balanced_state()
        except ValueError:
            return None
        return slowest_decay_rate(m.linearize(y).eigenvalues)

    def start_value(self, name: str) -> float | None:
        """The value a start takes for coordinate ``name`` when not given (SI): the base ball
        angle, rest, the base machine's speed, the mass or damping shared by all its balls (None
        if they differ); None for any other name."""
        if name == "spin_speed":
            return float(self.model.drive.speed)
        if name in _PARAMS:
            values = {float(getattr(b, name[5:])) for r in self.model.races for b in r.balls}
            return values.pop() if len(values) == 1 else None
        return ball_start_value(name, self.base_angles)

    def starts(self, coords: Mapping[str, np.ndarray]):
        n_pts = max((v.size for v in coords.values()), default=1)
        nb = self.model.n_balls
        angles = np.stack([np.broadcast_to(coords.get(f"psi_{i + 1}", self.base_angles[i]), (n_pts,))
                           for i in range(nb)], axis=1)
        rates = np.stack([np.broadcast_to(coords.get(f"dpsi_{i + 1}", 0.0), (n_pts,)) for i in range(nb)], axis=1)
        params = [k for k in _PARAMS if k in coords] + sorted(k for k in coords if k.startswith("model."))
        if params:
            keys = np.stack([coords[k] for k in params], axis=1)
            uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
            inverse = inverse.reshape(-1)
        else:
            uniq, inverse = np.empty((1, 0)), np.zeros(n_pts, dtype=np.int64)
        Y0 = np.empty((n_pts, self.model.n_state))
        P = np.empty((n_pts, self.model.to_array().size))
        for j, row in enumerate(uniq):
            model = self._variant(dict(zip(params, (float(v) for v in row))))
            sel = np.flatnonzero(inverse == j)
            Y0[sel] = [model.initial_state(angles[i], ball_rates=rates[i]) for i in sel]
            P[sel] = model.to_array()
        return self.model, Y0, P

    def _locked_response(self, p: np.ndarray) -> np.ndarray:
        """Largest orbit radius per node of the unbalance response with the balls locked (m), from
        one row of packed parameters alone (so that it holds for every variant of a chunk).

        With ``H = M0^-1`` (balls locked on the structure) the packed ``H K``, ``H C``, ``H G``,
        ``H B_u^T`` give ``(H K + i w H C + i w^2 H G - w^2 I) q = w^2 sum_u U_u e^(i phi_u)
        H B_u^T (1, -i)`` (as :func:`rotorlab.analyses._machine.unbalance_amplitudes`, in the kept
        modes).
        """
        lay = self.model.layout
        o, nz = lay.offsets, lay.n_z
        om = float(p[o["speed"] + 1])
        HK = p[o["HK"]:o["HK"] + nz * nz].reshape(nz, nz)
        HC = p[o["HC"]:o["HC"] + nz * nz].reshape(nz, nz)
        HG = p[o["HG"]:o["HG"] + nz * nz].reshape(nz, nz) if lay.gyroscopic else np.zeros((nz, nz))
        f = np.zeros(nz, dtype=complex)
        for part, place in lay.placed(True):  # each point unbalance: (U, cos, sin) and its station
            for j in range(part.n_stations):
                U, c, s = p[place.param + 3 * j:place.param + 3 * j + 3]
                k = lay.station_HBT(place.station + j)
                HBt = p[k:k + 2 * nz].reshape(nz, 2)
                f += om * om * U * (c + 1j * s) * (HBt @ np.array([1.0, -1j]))
        D = HK + 1j * om * (HC + om * HG) - om * om * np.eye(nz)
        q = self.model.basis @ np.linalg.solve(D, f)
        X, Y = q[0::4], q[1::4]
        return np.sqrt(0.5 * (np.abs(X) ** 2 + np.abs(Y) ** 2) + 0.5 * np.abs(X * X + Y * Y))

    def _speed_and_masses(self, P: np.ndarray) -> np.ndarray:
        """Per trajectory: its spin speed and ball masses, read back from the packed parameters."""
        o = self.model.layout.offsets
        nb = self.model.n_balls
        return np.concatenate([P[:, o["speed"] + 1:o["speed"] + 2],
                               P[:, o["balls"]:o["balls"] + 4 * nb:4]], axis=1)

    def features(self, sol, P: np.ndarray) -> dict[str, Feature]:
        lay = self.model.layout
        nb = lay.n_balls
        h = self.horizons()
        ts = self.save_times()
        ys = sol.ys
        n, nh = ys.shape[0], h.size
        sm = self._speed_and_masses(P)
        omega = sm[:, 0]
        q = self.model.displacements(ys)  # (n, nt, n_dof) of the full structure
        x, y = q[..., 0::4], q[..., 1::4]
        rate = np.abs(ys[:, :, lay.i_w:lay.i_w + nb] - omega[:, None, None]).max(axis=2)
        amplitude = np.empty((n, nh))
        max_rate = np.empty((n, nh))
        for j, t in enumerate(h):
            cols = np.flatnonzero((ts >= t - self.window * (1 + 1e-12)) & (ts <= t))
            sx, sy = np.zeros(x.shape[::2]), np.zeros(y.shape[::2])
            for c in cols:  # fixed summation order: the same bits whatever the chunk
                sx += x[:, c]
                sy += y[:, c]
            mx, my = sx / cols.size, sy / cols.size
            far = np.zeros(x.shape[::2])
            for c in cols:
                far = np.maximum(far, np.hypot(x[:, c] - mx, y[:, c] - my))
            amplitude[:, j] = far.max(axis=1)
            max_rate[:, j] = rate[:, cols].max(axis=1)
        uniq, inverse = np.unique(P, axis=0, return_inverse=True)
        ref = np.array([self._locked_response(row).max() for row in uniq])[inverse.reshape(-1)]
        i_end = np.searchsorted(ts, h)
        out = {
            "amplitude": Feature(amplitude, "m", "largest vibration amplitude of any station over the window"),
            "max_rate": Feature(max_rate, "rad/s", "largest |ball rate relative to the rotor| over the window"),
            "reference_amplitude": Feature(ref, "m", "largest unbalance response with the balls locked"),
            "rotor_speed": Feature(omega, "rad/s", "constant spin speed of the trajectory"),
            "status_code": Feature(sol.status.astype(np.int32), "1", "integrator status"),
            "settle_estimate": Feature(settle_estimate(amplitude, BALANCED_FRACTION * ref, h), "s",
                                       "estimated time to balance of a start still converging (NaN: not converging)"),
        }
        for i in range(nb):
            out[f"ball_angle_{i + 1}"] = Feature(wrap_machine_angle(ys[:, i_end, lay.i_phi + i] - omega[:, None] * ts[i_end]),
                                                 "rad", f"angle of ball {i + 1} relative to the rotor at the horizon")
        return out

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray:
        index = {name: k for k, name in enumerate(MACHINE_LABELS)}
        amp = features["amplitude"]
        out = np.empty(amp.shape, dtype=np.int16)
        nb = self.model.n_balls
        for i, j in np.ndindex(*amp.shape):
            text = machine_outcome(int(features["status_code"][i]), amp[i, j], features["reference_amplitude"][i],
                            float(features["max_rate"][i, j]), float(features["rotor_speed"][i]), nb)
            if text not in ("balanced", "failed") and np.isfinite(features["settle_estimate"][i, j]):
                text = NOT_SETTLED
            out[i, j] = index.get(text, index["other"])
        return out
