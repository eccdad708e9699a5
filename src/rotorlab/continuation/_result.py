"""What a continuation returns: branches of equilibria or periodic orbits and their special points.

A :class:`Branch` is the user's view of one continued curve (SI units): the parameter's values
along it, the solution's states, its stability, the vibration amplitude, the period of a periodic
orbit, the eigenvalues (equilibria) or Floquet multipliers (periodic orbits), and the located
special points with a sentence each. :class:`ContinuationResult` holds every branch of one run
and gives the JSON document of ``rotorlab continue --json`` (:meth:`ContinuationResult.to_dict`)
and an :class:`xarray.Dataset` (:meth:`ContinuationResult.to_dataset`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

__all__ = ["SPECIAL_POINT_TYPES", "SpecialPoint", "Branch", "ContinuationResult"]

#: Special point types and what each means (the report explains them with these words).
SPECIAL_POINT_TYPES: dict[str, str] = {
    "fold": "fold (limit point): the branch turns back; two steady motions meet and vanish",
    "hopf": "Hopf point: a pair of eigenvalues crosses the imaginary axis; a periodic orbit (whirl) is born",
    "branch": "branch point: another branch of steady motions crosses this one (symmetry breaking)",
    "fold-of-cycles": "fold of periodic orbits: the orbit branch turns back",
    "period-doubling": "period doubling: a Floquet multiplier crosses -1",
    "torus": "torus (Neimark-Sacker) point: a complex pair of Floquet multipliers crosses the unit circle",
}


@dataclass(frozen=True)
class SpecialPoint:
    """A located special point of a branch.

    Parameters
    ----------
    type : str
        A key of :data:`SPECIAL_POINT_TYPES`.
    parameter : str
        The continued parameter's name (the model's key-path spelling).
    value : float
        The parameter's value there (SI).
    state : ndarray
        The solution there (an equilibrium's state, or a periodic orbit's state at phase 0).
    description : str
        One sentence for people ("balancing becomes stable above 1460 rpm").
    index : int
        Position on the branch: the special point lies between points ``index - 1`` and ``index``.
    frequency : float
        The crossing eigenvalue's imaginary part (rad/s) at a Hopf or torus point, else NaN.
    parameter2 : str, optional
        The second parameter of a two-parameter curve, and ``value2`` its value.
    changes_stability : bool, optional
        Whether the branch's stability differs on the two sides (a stability boundary).
    amplitude : float
        The largest whirl radius there (m), where known.
    """

    type: str
    parameter: str
    value: float
    state: np.ndarray
    description: str
    index: int
    frequency: float = math.nan
    parameter2: str | None = None
    value2: float = math.nan
    changes_stability: bool | None = None
    amplitude: float = math.nan

    def __post_init__(self) -> None:
        if self.type not in SPECIAL_POINT_TYPES:
            raise ValueError(f"unknown special point type {self.type!r}; known: {', '.join(SPECIAL_POINT_TYPES)}")

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"type": self.type, self.parameter: _num(self.value), "description": self.description}
        if math.isfinite(self.frequency):
            d["frequency_rad_s"] = self.frequency
        if self.parameter2 is not None:
            d[self.parameter2] = _num(self.value2)
        return d


@dataclass(frozen=True)
class Branch:
    """One continued branch.

    Parameters
    ----------
    kind : {"equilibrium", "periodic"}
    parameter : str
        The continued parameter (the model's key-path spelling, SI).
    values : ndarray, shape (n,)
        The parameter along the branch, in the order continued.
    states : ndarray, shape (n, n_state)
        The equilibrium (or the orbit's state at phase 0) at each point.
    stable : ndarray of bool, shape (n,)
    amplitude : ndarray, shape (n,)
        The largest whirl radius of the structure (m).
    spectrum : ndarray of complex, shape (n, m)
        Eigenvalues of the linearisation (1/s, equilibria) or Floquet multipliers (periodic).
    period : ndarray, shape (n,)
        Period of a periodic orbit (s); NaN for equilibria.
    special_points : tuple of SpecialPoint
    label : str
        What the branch is, for people ("balanced", "balls together", "whirl").
    end : str
        Why the continuation stopped (``"bound"``, ``"max_points"``, ``"step"``, ``"closed"``).
    extra : dict
        Further per-point arrays of the model (e.g. ``"ball_angle"``: (n, n_balls), rad).
    """

    kind: Literal["equilibrium", "periodic"]
    parameter: str
    values: np.ndarray
    states: np.ndarray
    stable: np.ndarray
    amplitude: np.ndarray
    spectrum: np.ndarray
    period: np.ndarray
    special_points: tuple[SpecialPoint, ...] = ()
    label: str = ""
    end: str = ""
    extra: dict[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.kind not in ("equilibrium", "periodic"):
            raise ValueError(f"kind must be 'equilibrium' or 'periodic', got {self.kind!r}")
        n = np.asarray(self.values).shape[0]
        for name in ("states", "stable", "amplitude", "spectrum", "period"):
            if np.asarray(getattr(self, name)).shape[0] != n:
                raise ValueError(f"Branch.{name} must have {n} rows (one per point)")

    def to_dict(self) -> dict[str, Any]:
        """The branch as JSON-ready data (SI; non-finite numbers as None)."""
        points = []
        for i in range(len(self.values)):
            pt: dict[str, Any] = {self.parameter: _num(self.values[i]), "stable": bool(self.stable[i]),
                                  "amplitude_m": _num(self.amplitude[i])}
            if self.kind == "periodic":
                pt["period_s"] = _num(self.period[i])
                pt["multipliers"] = [[_num(z.real), _num(z.imag)] for z in np.asarray(self.spectrum[i])]
            else:
                ev = np.asarray(self.spectrum[i])
                pt["max_real_eigenvalue"] = _num(float(np.max(ev.real))) if ev.size else None
            for k, v in self.extra.items():
                pt[k] = [_num(x) for x in np.atleast_1d(v[i])]
            points.append(pt)
        return {"kind": self.kind, "label": self.label, "parameter": self.parameter, "end": self.end,
                "points": points, "special_points": [s.to_dict() for s in self.special_points]}


@dataclass(frozen=True)
class ContinuationResult:
    """Every branch of one continuation run, with the model's units of the parameters, and the
    fold and Hopf curves in a second parameter (objects with ``type``, ``parameters``, ``values``
    (n, 2), ``frequency`` (n,), ``label`` and ``to_dict()``, e.g.
    :class:`rotorlab.continuation.TwoParameterCurve`), and notes on what was computed (the
    smooth part of a model with ball friction: JSON ``"notes"``), and findings the curves settle
    for people (JSON ``"findings"``: "balancing is stable for support anisotropy below ...")."""

    branches: tuple[Branch, ...]
    units: dict[str, str] = field(default_factory=dict)
    curves: tuple[Any, ...] = ()
    notes: tuple[str, ...] = ()
    findings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        d = {"branches": [b.to_dict() for b in self.branches], "units": dict(self.units)}
        if self.curves:
            d["curves"] = [c.to_dict() for c in self.curves]
        if self.notes:
            d["notes"] = list(self.notes)
        if self.findings:
            d["findings"] = list(self.findings)
        return d

    def to_dataset(self):
        """One Dataset: dims ``branch`` and ``point`` (padded with NaN), coordinates ``kind``,
        ``label`` and ``parameter`` per branch; the special points in ``attrs["special_points"]``
        (JSON text)."""
        import json

        import xarray as xr

        n = max((len(b.values) for b in self.branches), default=0)
        nb = len(self.branches)

        def pad(get, dtype=float, fill=math.nan):
            out = np.full((nb, n), fill, dtype=dtype)
            for i, b in enumerate(self.branches):
                v = np.asarray(get(b))
                out[i, : v.shape[0]] = v
            return out

        max_re = pad(lambda b: np.array([np.max(np.abs(z)) if b.kind == "periodic" else np.max(np.real(z))
                                         for z in b.spectrum]) if len(b.values) else np.array([]))
        ds = xr.Dataset(
            {
                "value": (("branch", "point"), pad(lambda b: b.values)),
                "stable": (("branch", "point"), pad(lambda b: b.stable, dtype=float)),
                "amplitude": (("branch", "point"), pad(lambda b: b.amplitude)),
                "period": (("branch", "point"), pad(lambda b: b.period)),
                "spectral_abscissa": (("branch", "point"), max_re),
            },
            coords={
                "branch": np.arange(nb),
                "kind": ("branch", [b.kind for b in self.branches]),
                "label": ("branch", [b.label for b in self.branches]),
                "parameter": ("branch", [b.parameter for b in self.branches]),
            },
            attrs={"analysis": "continuation", "notes": json.dumps(list(self.notes)),
                   "special_points": json.dumps([[{**s.to_dict(), "index": s.index, "boundary": s.changes_stability,
                                                   "amplitude_m": _num(s.amplitude)}
                                                  for s in b.special_points] for b in self.branches])},
        )
        units = {"amplitude": "m", "period": "s", "stable": "1 (true/false)",
                 "spectral_abscissa": "1/s (equilibria: largest real part) or 1 (orbits: largest |multiplier|)"}
        for k, u in units.items():
            ds[k].attrs["units"] = u
        params = {b.parameter for b in self.branches}
        ds["value"].attrs["units"] = self.units.get(params.pop(), "") if len(params) == 1 else "per branch"
        # per-point arrays of the branches (ball angles ...): dims branch, point, then their own;
        # NaN on a branch without it (a periodic branch has no ball angles of a steady motion)
        for key in sorted(set().union(*(set(b.extra) for b in self.branches))):
            have = [b for b in self.branches if key in b.extra]
            width = max(np.asarray(b.extra[key]).reshape(len(b.values), -1).shape[1] for b in have)
            arr = np.full((nb, n, width), math.nan)
            for i, b in enumerate(self.branches):
                if key not in b.extra:
                    continue
                v = np.asarray(b.extra[key], dtype=float).reshape(len(b.values), -1)
                arr[i, : v.shape[0], : v.shape[1]] = v
            ds[key] = (("branch", "point", f"{key}_index"), arr)
            ds[key].attrs["units"] = "rad" if "angle" in key else ""
        if self.curves:
            m = max(len(c.values) for c in self.curves)
            vals = np.full((len(self.curves), m, 2), math.nan)
            freq = np.full((len(self.curves), m), math.nan)
            for i, c in enumerate(self.curves):
                vals[i, : len(c.values)] = c.values
                freq[i, : len(c.values)] = c.frequency
            p1, p2 = self.curves[0].parameters
            ds["curve_value"] = (("curve", "curve_point", "curve_parameter"), vals,
                                 {"units": f"{self.units.get(p1, '')}, {self.units.get(p2, '')}"})
            ds["curve_frequency"] = (("curve", "curve_point"), freq, {"units": "rad/s"})
            ds = ds.assign_coords(curve_type=("curve", [c.type for c in self.curves]),
                                  curve_boundary=("curve", [bool(getattr(c, "boundary", True)) for c in self.curves]),
                                  curve_label=("curve", [c.label for c in self.curves]),
                                  curve_parameter=("curve_parameter", [p1, p2]))
            ds.attrs["parameter2"] = p2
            ds.attrs["units2"] = self.units.get(p2, "")
        for name in ds.variables:  # counts and labels: dimensionless
            ds[name].attrs.setdefault("units", "1")
        ds.attrs["units"] = self.units.get(self.branches[0].parameter, "") if self.branches else ""
        ds.attrs["descriptions"] = json.dumps([s.description for b in self.branches for s in b.special_points])
        return ds


def _num(x: Any) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None
