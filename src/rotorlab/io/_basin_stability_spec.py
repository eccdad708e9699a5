"""Case-file spec of the ``basin-stability`` analysis: the probability of every regime from seeded
random starts, with Wilson intervals, at each value of one parameter
(:mod:`rotorlab.analyses._basin_stability`; ``rotorlab basin-stability`` adds a Zarr store,
resume and Dask).

Layout::

    [[analysis]]
    type = "basin-stability"
    name = "speed-range"
    param = {spin_speed = ["1500 rpm", "3000 rpm", 16]}   # one parameter, START:STOP:N
    ci_width = 0.02           # target half-width of the Wilson 95 % intervals (or: starts = 500)
    seed = 0
    # starts over every ball angle in [0, 360 deg) unless `ranges` says otherwise:
    # ranges = {psi_1 = ["0 deg", "360 deg"], psi_2 = ["0 deg", "360 deg"]}

Examples
--------
>>> spec = BasinStabilitySpec(param={"ball_damping": ["0.2e-3 N*m*s", "2e-3 N*m*s", 4]}, starts=200)
>>> spec.param_axis, spec.ci_width is None
(('ball_damping', 0.0002, 0.002, 4), True)
"""

from __future__ import annotations

import math
from typing import Any, ClassVar, Literal

from pydantic import Field

from rotorlab._limits import MAX_STARTS
from rotorlab.io._coordinates import RecordsInputUnits, coordinate_dimensions, coordinates_text, mappable_text
from rotorlab.io._errors import Issue
from rotorlab.io._fields import AbstractModelSpec, RaceIndices, chosen_race_issues, integer, quantity
from rotorlab.io._sweep_specs import BaseSpeedSpec, _axes, sweep_coordinates

__all__ = ["BasinStabilitySpec", "default_start_ranges"]


def default_start_ranges(model: AbstractModelSpec, races: tuple[int, ...] | None = None) -> dict[str, tuple]:
    """Every ball angle (``psi_<i>``; a toroidal ball's ``psi``) over a whole turn, [0, 2 pi) rad.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> default_start_ranges(load_case("autobalancer").model)
    {'psi_1': (0.0, 6.283185307179586), 'psi_2': (0.0, 6.283185307179586)}
    """
    import re

    known = sweep_coordinates(model, "ic")
    n = model.balls_in(races) if races is not None else None
    names = [k for k in known if k == "psi" or (re.fullmatch(r"psi_(\d+)", k) and (n is None or int(k[4:]) <= n))]
    return {k: (0.0, 2.0 * math.pi) for k in names}


class BasinStabilitySpec(BaseSpeedSpec, RecordsInputUnits):
    """Probability of every regime from random starts at each value of one parameter.

    Parameters
    ----------
    param : {NAME: [start, stop, count]}
        The parameter and its values (SI or with units): one of the names ``rotorlab sweep
        --param`` takes (a rotor with balls: ``spin_speed``, ``ball_damping``, ...; a machine:
        ``model.<key path>``).
    starts : int, optional
        Random starts at every value, >= 1. Excludes ``ci_width``.
    ci_width : float, optional
        Target half-width of the Wilson intervals, in (0, 0.5): starts are added at each value
        until every regime's interval is at most this wide on either side (default 0.05).
    seed : int
        Seed of the starts (the same starts at every value).
    confidence : float
        Level of the Wilson intervals, in (0, 1).
    ranges : {NAME: [low, high]}, optional
        Start coordinates drawn uniformly (``psi_<i>`` in rad, ``dpsi_<i>`` in rad/s, a rotor
        with balls' start position ``rotor_u``, ``rotor_v`` in m (co-rotating frame, at rest in
        it); a toroidal ball's ``psi``, ``alpha``, ``dpsi``, ``dalpha``); default every ball angle
        over a turn, the rotor at rest on the axis.
    speed_ratio, speed, t_end, n_horizons, window_revolutions, spare_turns, rtol, atol, races
        As for ``sweep``; without ``t_end`` the horizon comes from the balanced state's slowest
        mode at every parameter value (the longest of them).
    chunk : int, optional
        Starts per chunk (adaptive: the step in which a value grows, default 128).
    """

    exclusive: ClassVar[tuple[tuple[str, str, bool], ...]] = (
        ("speed_ratio", "speed", False),
        ("starts", "ci_width", False),
    )

    type: Literal["basin-stability"] = "basin-stability"
    param: _axes("param") = Field(description="the parameter and its values {NAME = [start, stop, count]} (SI)")
    starts: integer(ge=1, le=MAX_STARTS) | None = Field(None, description="random starts at every value")
    ci_width: quantity("dimensionless", gt=0, lt=0.5) | None = Field(
        None, description="target half-width of the Wilson intervals (-); default 0.05")
    seed: integer(ge=0) = Field(0, description="seed of the random starts")
    confidence: quantity("dimensionless", gt=0, lt=1) = Field(0.95, description="level of the Wilson intervals (-)")
    ranges: _axes("ic") = Field(default_factory=dict, description="start coordinates drawn uniformly (rad, rad/s)")
    t_end: quantity("time", gt=0) | None = Field(None, description="simulated time (s)")
    n_horizons: integer(ge=1) = Field(10, description="classification horizons")
    window_revolutions: quantity("dimensionless", gt=0) | None = Field(None, description="classification window (-)")
    spare_turns: quantity("dimensionless", gt=0) | None = Field(
        None, description="turns in the window that make a moving ball spare (toroidal ball)")
    chunk: integer(ge=1, le=100_000) | None = Field(None, description="starts per chunk")
    rtol: quantity("dimensionless", gt=0, lt=1) | None = Field(None, description="relative tolerance")
    atol: quantity("dimensionless", gt=0) | None = Field(None, description="absolute tolerance")
    races: RaceIndices | None = Field(None, description="ball races that take part (machine; default all)")

    @classmethod
    def _written(cls, data: dict[str, Any]) -> list[tuple[str, list[Any]]]:
        return [(str(name), list(raw[:2])) for key in ("param", "ranges") if isinstance(data.get(key), dict)
                for name, raw in data[key].items() if isinstance(raw, (list, tuple))]  # fmt: skip

    @property
    def param_axis(self) -> tuple[str, float, float, int]:
        """The parameter as ``(name, start, stop, count)`` (SI)."""
        name, entry = next(iter(self.param.items()))
        return (name, *entry)

    def start_ranges(self, model: AbstractModelSpec) -> dict[str, tuple[float, float]]:
        """The start coordinates drawn and their ranges (SI): ``ranges`` or every ball angle."""
        return dict(self.ranges) if self.ranges else default_start_ranges(model, self.races)

    def case_issues(self, model: AbstractModelSpec) -> list[Issue]:
        """Check the model (one with a regime mapper), the parameter, the ranges and the speed."""
        kind = getattr(model, "type", None)
        if not coordinate_dimensions(model):
            return [Issue(("type",), f"needs {mappable_text(model)}", self.type)]
        issues = []
        if len(self.param) != 1:
            issues.append(Issue(("param",), "give exactly one parameter {NAME = [start, stop, count]}",
                                list(self.param)))  # fmt: skip
        for key, entries, want in (("param", self.param, 3), ("ranges", self.ranges, 2)):
            known = sweep_coordinates(model, "param" if key == "param" else "ic")
            for name, entry in entries.items():
                if name not in known:
                    reason = model.missing_coordinate(name)
                    what = "parameter" if key == "param" else "start coordinate"
                    issues.append(Issue((key, name), f"the model {reason}" if reason is not None else
                                        f"not a {what} of this {kind} model (allowed: {coordinates_text(known)})",
                                        name))  # fmt: skip
                elif len(entry) != want:
                    form = "[start, stop, count]" if want == 3 else "[low, high]"
                    issues.append(Issue((key, name), f"give {form}", list(entry)))
                elif key == "ranges" and not entry[1] > entry[0]:
                    issues.append(Issue((key, name), "high must be > low (fix a value with --set instead)",
                                        list(entry)))  # fmt: skip
        issues += chosen_race_issues(model, self.races, [(("ranges", k), k) for k in self.ranges])
        from rotorlab._wilson import min_half_width

        if self.ci_width is not None and self.ci_width < min_half_width(self.confidence):
            issues.append(Issue(("ci_width",), f"must be >= {min_half_width(self.confidence):.3g}: a narrower interval "
                                               f"needs more than {MAX_STARTS} starts per value", self.ci_width))
        if not issues and not self.start_ranges(model):
            issues.append(Issue(("ranges",), "give the start coordinates to draw {NAME = [low, high]}", None,
                                show_value=False))  # fmt: skip
        return issues + self.speed_issues(model)

    def describe(self, model: AbstractModelSpec) -> str:
        name, a, b, n = self.param_axis
        how = f"{self.starts} random starts" if self.starts is not None else \
            f"random starts until the 95 % intervals are within ±{self.ci_width or 0.05:g}"
        return f"basin stability over {name} ({n} values from {a:g} to {b:g}), {how} at each"
