"""All steady motions at one speed with their three stability verdicts and every disagreement.

See :mod:`rotorlab.steady._motions` (which motions exist) and :mod:`rotorlab.steady._stability`
(the three methods).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from rotorlab.steady._motions import find_steady_motions, resolve_speed, steady_machine
from rotorlab.steady._records import SteadyMotion
from rotorlab.steady._stability import _seed_h_values, assess_stability
from rotorlab._constants import RPM_PER_RAD_S as _RPM

if TYPE_CHECKING:
    import xarray

    from rotorlab.models import JeffcottBalls

__all__ = ["Disagreement", "SteadyAnalysis", "analyze_steady"]

_METHOD_NAMES = {
    "hamilton": "seed 003 (least H~*, Hessian of f, eqs. (14)-(19))",
    "averaged": "seed 002 (averaged equations, A and B of eqs. (19)-(20) corrected)",
}


@dataclass(frozen=True)
class Disagreement:
    """A steady motion on which two of the three stability methods disagree.

    Attributes
    ----------
    label : str
        The motion.
    method : {"hamilton", "averaged"}
        The first-order method whose verdict is questioned.
    predicted : str
        Its verdict.
    exact : str
        The exact verdict (``"absent"``: the motion does not exist with the support damping).
    message : str
        One line, with the speed ratio and the exact growth rate.
    against : {"exact", "averaged"}
        What ``method`` disagrees with: the exact eigenvalues, or (for ``method="hamilton"``) the
        averaged equations.
    """

    label: str
    method: str
    predicted: str
    exact: str
    message: str
    against: str = "exact"


@dataclass(frozen=True)
class SteadyAnalysis:
    """Every steady motion of a rotor with balls at one constant speed, with its stability.

    Attributes
    ----------
    spin_speed : float
        Omega (rad/s).
    critical_speed : float
        p = sqrt(c / M), M = M1 + sum m_i (rad/s).
    imbalance : float
        M1 e (kg m).
    capacity : float
        sum m_i l_i (kg m).
    moments : ndarray, shape (n,)
        Static moments m_i l_i of the balls (kg m).
    motions : tuple of SteadyMotion
        In the order of :func:`rotorlab.steady.motion_labels`, each with its ``stability``.
    disagreements : tuple of Disagreement
        Every motion on which a first-order method disagrees with the exact eigenvalues, or the
        two first-order methods disagree with each other.
    friction : str
        Empty without ball friction; else what was computed (the smooth part's motions and
        eigenvalues: :func:`rotorlab.continuation.smooth_part_note`).
    """

    spin_speed: float
    critical_speed: float
    imbalance: float
    capacity: float
    moments: np.ndarray
    motions: tuple[SteadyMotion, ...]
    disagreements: tuple[Disagreement, ...]
    friction: str = ""

    @property
    def labels(self) -> tuple[str, ...]:
        """Labels of all motions (existing or not)."""
        return tuple(m.label for m in self.motions)

    def motion(self, label: str) -> SteadyMotion:
        """Return the motion called ``label``.

        Raises
        ------
        KeyError
            If there is no such motion.
        """
        for m in self.motions:
            if m.label == label:
                return m
        raise KeyError(f"no steady motion {label!r}; motions: {', '.join(self.labels)}")

    def stable(self, method: str = "exact") -> tuple[str, ...]:
        """Return the labels of the motions that ``method`` calls stable.

        The first-order methods judge the undamped motion of the same label (seed 003 assumes
        supports without damping), which may not exist with the support damping; "exact" lists
        existing motions only.
        """
        return tuple(m.label for m in self.motions if m.stability.is_stable(method))

    def to_dict(self) -> dict:
        """Return the analysis as plain Python values (JSON-ready), in SI units.

        Returns
        -------
        dict
            ``spin_speed`` (rad/s), ``critical_speed`` (rad/s), ``speed_ratio``, ``imbalance``
            and ``capacity`` (kg m), ``motions`` (one dict per motion: ``label``, ``kind``,
            ``exists``, ``dimension``, ``ball_angles`` (rad; None when absent), ``amplitude``
            (m), ``phase`` (rad), ``h_tilde`` (J), ``verdicts`` {hamilton, averaged, exact},
            ``hessian``, ``hamilton_minimal``, ``averaged_A`` (1/s), ``averaged_B`` (1/s^2),
            ``growth_rate`` (1/s), ``stable_fraction``) and ``disagreements`` (``label``,
            ``method``, ``against``, ``predicted``, ``exact``, ``message``), and ``friction``
            (:attr:`friction`) where the balls have friction. NaN becomes None.
        """

        def num(x):
            x = float(x)
            return x if math.isfinite(x) else None

        motions = []
        for m in self.motions:
            st = m.stability
            motions.append({
                "label": m.label, "kind": m.kind, "exists": bool(m.exists), "dimension": int(m.dimension),
                "ball_angles": [float(a) for a in m.ball_angles] if m.exists else None,
                "amplitude": num(m.amplitude) if m.exists else None,
                "phase": num(m.phase) if m.exists else None,
                "h_tilde": num(m.h_tilde) if m.exists else None,
                "verdicts": {"hamilton": st.hamilton, "averaged": st.averaged, "exact": st.exact},
                "hessian": st.hessian, "hamilton_minimal": bool(st.hamilton_minimal),
                "averaged_A": num(st.averaged_a), "averaged_B": num(st.averaged_b),
                "growth_rate": num(st.growth_rate), "stable_fraction": float(st.stable_fraction),
            })  # fmt: skip
        return {
            "spin_speed": self.spin_speed,
            "critical_speed": self.critical_speed,
            "speed_ratio": self.spin_speed / self.critical_speed,
            "imbalance": self.imbalance,
            "capacity": self.capacity,
            "motions": motions,
            "disagreements": [
                {"label": d.label, "method": d.method, "against": d.against, "predicted": d.predicted,
                 "exact": d.exact, "message": d.message}
                for d in self.disagreements
            ],  # fmt: skip
            **({"friction": self.friction} if self.friction else {}),
        }

    def to_dataset(self) -> xarray.Dataset:
        """Return the motions as an ``xarray.Dataset`` with dims ``motion`` and ``ball``."""
        import xarray as xr

        ms = self.motions
        n = ms[0].ball_angles.size if ms else 0
        st = [m.stability for m in ms]

        def var(dims, values, units, long_name):
            return (dims, np.asarray(values), {"units": units, "long_name": long_name})

        data = {
            "exists": var(("motion",), [m.exists for m in ms], "1", "motion exists"),
            "kind": var(("motion",), [m.kind for m in ms], "1", "main or side motion"),
            "dimension": var(("motion",), [m.dimension for m in ms], "1", "dimension of the family"),
            "ball_angle": var(("motion", "ball"), np.array([m.ball_angles for m in ms]).reshape(len(ms), n),
                              "rad", "ball angle from the unbalance"),
            "amplitude": var(("motion",), [m.amplitude for m in ms], "m", "shaft deflection"),
            "phase": var(("motion",), [m.phase if m.exists else np.nan for m in ms], "rad",
                         "angle of the deflection from the unbalance"),
            "h_tilde": var(("motion",), [m.h_tilde for m in ms], "J", "H~* = Pi - T0 (seed 003 (10))"),
            "verdict_hamilton": var(("motion",), [s.hamilton for s in st], "1", _METHOD_NAMES["hamilton"]),
            "verdict_averaged": var(("motion",), [s.averaged for s in st], "1", _METHOD_NAMES["averaged"]),
            "verdict_exact": var(("motion",), [s.exact for s in st], "1", "eigenvalues of the full Jacobian"),
            "stable_hamilton": var(("motion",), [s.is_stable("hamilton") for s in st],
                                   "1", "stable by seed 003's method"),
            "stable_averaged": var(("motion",), [s.is_stable("averaged") for s in st],
                                   "1", "stable by seed 002's averaged equations"),
            "stable_exact": var(("motion",), [s.is_stable("exact") for s in st], "1", "exactly stable"),
            "hamilton_minimal": var(("motion",), [s.hamilton_minimal for s in st], "1",
                                    "least H~* among the undamped steady motions"),
            "hessian": var(("motion",), [s.hessian for s in st], "1", "critical point type of f (seed 003 (19))"),
            "averaged_A": var(("motion",), [s.averaged_a for s in st], "1/s", "A of seed 002 (19), corrected"),
            "averaged_B": var(("motion",), [s.averaged_b for s in st], "1/s^2", "B of seed 002 (19), corrected"),
            "growth_rate": var(("motion",), [s.growth_rate for s in st], "1/s",
                               "largest real part of the exact eigenvalues"),
            "stable_fraction": var(("motion",), [s.stable_fraction for s in st], "1",
                                   "fraction of the family exactly stable"),
            "disagreement": var(("motion",), [any(d.label == m.label for d in self.disagreements) for m in ms],
                                "1", "two of the three methods disagree"),
        }  # fmt: skip
        return xr.Dataset(
            data,
            coords={
                "motion": ("motion", [m.label for m in ms], {"units": "1"}),
                "ball": ("ball", np.arange(1, n + 1), {"units": "1"}),
            },
            attrs={
                "analysis": "steady",
                "spin_speed": self.spin_speed,
                "spin_speed_units": "rad/s",
                "speed_rpm": self.spin_speed * _RPM,
                "critical_speed": self.critical_speed,
                "speed_ratio": self.spin_speed / self.critical_speed,
                "imbalance": self.imbalance,
                "capacity": self.capacity,
                "disagreements": "\n".join(d.message for d in self.disagreements),
                **({"friction": self.friction} if self.friction else {}),
            },
        )


def _disagreements(motions, ratio: float) -> tuple[Disagreement, ...]:
    out = []
    for m in motions:
        st = m.stability
        for method in ("hamilton", "averaged"):
            pred = getattr(st, method)
            if pred == "undefined":
                continue
            if (pred == "stable") == (st.exact == "stable"):
                continue
            if st.exact == "absent" and pred != "stable":
                continue
            if st.exact == "absent":
                detail = "the motion does not exist with the support damping"
            else:
                extra = f", {st.stable_fraction:.0%} of the family stable" if m.dimension else ""
                detail = f"exact eigenvalues say {st.exact} (largest real part {st.growth_rate:.3g} 1/s{extra})"
            msg = f"{m.label} at omega/p = {ratio:.4g}: {_METHOD_NAMES[method]} says {pred}; {detail}"
            out.append(Disagreement(m.label, method, pred, st.exact, msg))
        if st.averaged != "undefined" and (st.hamilton == "stable") != (st.averaged == "stable"):
            why = "" if st.hamilton_minimal else " (H~* is not the least among the steady motions)"
            msg = (f"{m.label} at omega/p = {ratio:.4g}: {_METHOD_NAMES['hamilton']} says {st.hamilton}{why}; "
                   f"{_METHOD_NAMES['averaged']} says {st.averaged}")  # fmt: skip
            out.append(Disagreement(m.label, "hamilton", st.hamilton, st.exact, msg, against="averaged"))
    return tuple(out)


def analyze_steady(model: JeffcottBalls, spin_speed: float | None = None, *,
                   family_samples: int = 12, machine=None) -> SteadyAnalysis:  # fmt: skip
    """Find every steady motion at a constant speed and assess its stability three ways.

    Parameters
    ----------
    model : JeffcottBalls
        Rotor and balls (any frame). With ball friction, the motions and eigenvalues are those of
        the smooth part, friction left out (each motion is also one with friction, its balls
        stuck with no friction torque needed); :attr:`SteadyAnalysis.friction` says so.
    spin_speed : float, optional
        Omega (rad/s), > 0; default the model's constant speed.
    family_samples : int
        Sample points per free angle of the family of main motions (n >= 3).
    machine : Machine, optional
        The machine that solves and judges the motions, the model's own
        (:func:`rotorlab.steady._motions.steady_machine`) by default; another machine must be
        this rotor (its first node's translations the disc's, the unbalance at angle 0, the
        spin speed set), e.g. with uncoupled tilt modes of its own.

    Returns
    -------
    SteadyAnalysis

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (10)-(19); Zhakash et al. 2024 eqs. (9)-(23).

    Examples
    --------
    Two equal balls, eta = 1.2, well above the critical speed: only the two balanced motions are
    stable, by all three methods.

    >>> from rotorlab.models import JeffcottBalls, RotorParams, BallParams, ConstantSpeed
    >>> ball = BallParams(mass=0.03, radius=0.06, damping=2e-3)
    >>> rotor = RotorParams(disc_mass=2.0, eccentricity=1.08e-3, stiffness=2e4, damping=8.0)
    >>> res = analyze_steady(JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(300.0)))
    >>> res.stable("exact"), res.stable("hamilton"), len(res.disagreements)
    (('main+', 'main-'), ('main+', 'main-'), 0)
    """
    from rotorlab.continuation import smooth_part_note

    om = resolve_speed(model, spin_speed)
    machine = steady_machine(model, om) if machine is None else machine
    motions = find_steady_motions(model, om, family_samples=family_samples, machine=machine)
    values = _seed_h_values(model, om)
    motions = tuple(replace(m, stability=assess_stability(model, m, om, seed_h_values=values, machine=machine))
                    for m in motions)
    p = model.critical_speed
    return SteadyAnalysis(
        spin_speed=om, critical_speed=p, imbalance=model.imbalance, capacity=model.capacity,
        moments=np.array([b.static_moment for b in model.balls]), motions=motions,
        disagreements=_disagreements(motions, om / p), friction=smooth_part_note(model),
    )  # fmt: skip
