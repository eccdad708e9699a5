"""Regimes of a composed machine's balancer (:class:`rotorlab.models.Machine`): balanced, not
balanced, non-synchronous.

Features at each horizon T, over a window of ``window_revolutions`` turns before T sampled at
``samples_per_window`` points: the vibration amplitude (the largest distance of any station from
its mean position in the window; in the fixed frame, so a static deflection under gravity does not
count), the largest ball rate relative to the rotor, and the ball angles at T relative to the
rotor. The labels follow :func:`rotorlab.analyses._machine.machine_simulate`: *balanced* (the
vibration at most :data:`~rotorlab.analyses.BALANCED_FRACTION` of the largest unbalance response
with the balls locked), *non-synchronous* (balls still moving relative to the rotor faster than
:data:`~rotorlab.analyses._machine.NON_SYNCHRONOUS_RATE` times its speed), *not balanced*
(settled elsewhere) and *other* (a failed integration).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from rotorlab.explore._mapper import Feature
from rotorlab.integrate import StepControl
from rotorlab.models import ConstantSpeed, Machine

__all__ = ["MachineRegimes", "MACHINE_LABELS"]

#: Labels of :class:`MachineRegimes`, in code order.
MACHINE_LABELS = ("balanced", "not balanced", "non-synchronous", "other")
_PARAMS = {"spin_speed": "rad/s", "ball_mass": "kg", "ball_damping": "N m s/rad"}


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
    """

    model: Machine
    t_end: float = 200.0
    n_horizons: int = 10
    window_revolutions: float = 2.0
    samples_per_window: int = 33
    base_angles: tuple[float, ...] | None = None
    control: StepControl = field(default_factory=lambda: StepControl(rtol=1e-8, atol=1e-10))

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
        n = self.model.n_balls
        units = {f"psi_{i}": "rad" for i in range(1, n + 1)}
        units.update({f"dpsi_{i}": "rad/s" for i in range(1, n + 1)})
        return {**units, **_PARAMS}

    @property
    def window(self) -> float:
        """Length of the classification window (s)."""
        return self.window_revolutions * 2.0 * math.pi / abs(self.model.drive.speed)

    def horizons(self) -> np.ndarray:
        return self.t_end * np.arange(1, self.n_horizons + 1) / self.n_horizons

    def save_times(self) -> np.ndarray:
        h = self.horizons()
        k = np.linspace(-1.0, 0.0, self.samples_per_window)
        return np.unique(np.maximum(h[:, None] + self.window * k[None, :], 0.0))

    def _variant(self, values: Mapping[str, float], masses=None) -> Machine:
        m = self.model
        if "spin_speed" in values:
            m = m.with_drive(ConstantSpeed(float(values["spin_speed"])))
        kw = {k[5:]: float(v) for k, v in values.items() if k in ("ball_mass", "ball_damping")}
        if kw or masses is not None:
            it = iter(masses) if masses is not None else None
            races = tuple(replace(r, balls=tuple(replace(b, **kw, **({} if it is None else {"mass": float(next(it))}))
                                                 for b in r.balls)) for r in m.races)
            m = replace(m, races=races)
        return m

    def starts(self, coords: Mapping[str, np.ndarray]):
        n_pts = max((v.size for v in coords.values()), default=1)
        nb = self.model.n_balls
        angles = np.stack([np.broadcast_to(coords.get(f"psi_{i + 1}", self.base_angles[i]), (n_pts,))
                           for i in range(nb)], axis=1)
        rates = np.stack([np.broadcast_to(coords.get(f"dpsi_{i + 1}", 0.0), (n_pts,)) for i in range(nb)], axis=1)
        params = [k for k in _PARAMS if k in coords]
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

    def _speed_and_masses(self, P: np.ndarray) -> np.ndarray:
        """Per trajectory: its spin speed and ball masses, read back from the packed parameters."""
        o = self.model.layout.offsets
        nb = self.model.n_balls
        return np.concatenate([P[:, o["speed"] + 1:o["speed"] + 2],
                               P[:, o["balls"]:o["balls"] + 4 * nb:4]], axis=1)

    def features(self, sol, P: np.ndarray) -> dict[str, Feature]:
        from rotorlab.analyses._machine import _wrap, unbalance_amplitudes

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
        uniq, inverse = np.unique(sm, axis=0, return_inverse=True)
        ref_u = np.array([unbalance_amplitudes(self._variant({"spin_speed": r[0]}, masses=r[1:]), r[0]).max()
                          for r in uniq])
        ref = ref_u[inverse.reshape(-1)]
        i_end = np.searchsorted(ts, h)
        out = {
            "amplitude": Feature(amplitude, "m", "largest vibration amplitude of any station over the window"),
            "max_rate": Feature(max_rate, "rad/s", "largest |ball rate relative to the rotor| over the window"),
            "reference_amplitude": Feature(ref, "m", "largest unbalance response with the balls locked"),
            "rotor_speed": Feature(omega, "rad/s", "constant spin speed of the trajectory"),
            "status_code": Feature(sol.status.astype(np.int32), "1", "integrator status"),
        }
        for i in range(nb):
            out[f"ball_angle_{i + 1}"] = Feature(_wrap(ys[:, i_end, lay.i_phi + i] - omega[:, None] * ts[i_end]),
                                                 "rad", f"angle of ball {i + 1} relative to the rotor at the horizon")
        return out

    def group(self, features: Mapping[str, np.ndarray]) -> np.ndarray:
        from rotorlab.analyses._machine import _outcome

        index = {name: k for k, name in enumerate(MACHINE_LABELS)}
        amp = features["amplitude"]
        out = np.empty(amp.shape, dtype=np.int16)
        nb = self.model.n_balls
        for i, j in np.ndindex(*amp.shape):
            text = _outcome(int(features["status_code"][i]), amp[i, j], features["reference_amplitude"][i],
                            float(features["max_rate"][i, j]), float(features["rotor_speed"][i]), nb)
            out[i, j] = index.get(text, index["other"])
        return out
