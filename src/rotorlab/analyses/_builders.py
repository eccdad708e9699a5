"""How the built-in model specs become models, and the quantities derived from each model.

These are the ``build`` and ``quantities`` of the built-in entries of
:data:`rotorlab.analyses.MODEL_TYPES` (see :mod:`rotorlab.analyses._registry`). A derived quantity
is physics (seed 002's eta, the balanced ball angle, the critical speed), so it is computed here
and carried in every result's ``attrs["model_quantities"]``, never recomputed by the report.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rotorlab.models import JeffcottBalls, ToroidalBall

__all__ = ["jeffcott_balls_model", "toroidal_ball_model", "speed_profile", "jeffcott_quantities",
           "linear_quantities", "reference_speed_quantities"]  # fmt: skip


def speed_profile(spec: Any) -> Any:
    """The :mod:`rotorlab.models` speed profile of a case's ``[model.speed]`` (at rest if None)."""
    from rotorlab.models import ConstantSpeed, HillRunUp, LinearRamp

    if spec is None:
        return ConstantSpeed(0.0)
    build = {"constant": lambda s: ConstantSpeed(s.speed),
             "ramp": lambda s: LinearRamp(s.start, s.stop, s.duration),
             "hill": lambda s: HillRunUp(s.max_speed, s.t_half, s.exponent)}  # fmt: skip
    if spec.profile not in build:
        raise ValueError(f"unknown speed profile {spec.profile!r}")
    return build[spec.profile](spec)


def jeffcott_balls_model(case_model: Any) -> JeffcottBalls:
    """The :class:`~rotorlab.models.JeffcottBalls` of a ``jeffcott_balls`` spec.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> model = jeffcott_balls_model(load_case("autobalancer").model)
    >>> model.n_balls, round(model.critical_speed / (2 * math.pi), 3)
    (2, 20.001)
    """
    from rotorlab.models import BallParams, JeffcottBalls, RotorParams

    rotor = RotorParams(disc_mass=case_model.disc_mass, eccentricity=case_model.eccentricity,
                        stiffness=case_model.stiffness, damping=case_model.damping)  # fmt: skip
    balls = tuple(
        BallParams(mass=b.mass, radius=b.radius, inertia=b.inertia, damping=b.damping,
                   friction=b.friction)  # fmt: skip
        for b in case_model.balls
    )
    return JeffcottBalls(rotor, balls, speed=speed_profile(case_model.speed), frame=case_model.frame)


def toroidal_ball_model(case_model: Any) -> ToroidalBall:
    """The :class:`~rotorlab.models.ToroidalBall` of a ``toroidal_ball`` spec."""
    from rotorlab.models import ToroidalBall

    return ToroidalBall(case_model.ring_radius, case_model.tube_radius, case_model.ball_radius,
                        case_model.spin_speed, case_model.offset, case_model.rolling_friction,
                        case_model.gravity, case_model.form)  # fmt: skip


def _quantity(name: str, value: float, unit: str, sign: str = "") -> dict[str, Any]:
    return {"quantity": name, "value": float(value), "unit": unit, "sign": sign}


def reference_speed_quantities(case_model: Any) -> list[dict[str, Any]]:
    """The model's reference (critical) speed p, if it has one (rad/s)."""
    p = case_model.critical_speed()
    return [] if p is None else [_quantity("critical speed p = sqrt(c / M)", p, "rad/s")]


def jeffcott_quantities(case_model: Any) -> list[dict[str, Any]]:
    """Derived quantities of a rotor with balls (seed 002).

    Returns
    -------
    list of dict
        Keys ``quantity`` (its name and formula), ``value`` (SI), ``unit``, ``sign`` ("" or
        "±" for a symmetric pair): the critical speed p, the total mass, the unbalance M1 e,
        the balancing capacity sum m_i R_i and, for two equal balls, eta = M1 e / (m R)
        (seed 002 eq. (10)) and the balanced ball angles ±(pi - arccos(eta / 2)) when eta < 2.

    Examples
    --------
    >>> from rotorlab.io import load_case
    >>> rows = jeffcott_quantities(load_case("autobalancer").model)
    >>> [(r["quantity"][:3], round(r["value"], 4), r["sign"]) for r in rows[-2:]]
    [('eta', 1.0, ''), ('bal', 2.0944, '±')]
    """
    rows = reference_speed_quantities(case_model)
    rows.append(_quantity("total mass M = M1 + sum m_i", case_model.total_mass, "kg"))
    imbalance = case_model.disc_mass * case_model.eccentricity
    rows.append(_quantity("unbalance M1 e", imbalance, "kg*m"))
    balls = case_model.balls
    if balls:
        rows.append(_quantity("balancing capacity sum m_i R_i", sum(b.mass * b.radius for b in balls), "kg*m"))
    if len(balls) == 2 and balls[0] == balls[1]:
        eta = imbalance / (balls[0].mass * balls[0].radius)
        rows.append(_quantity("eta = M1 e / (m R) (seed 002 eq. (10))", eta, "1"))
        if eta < 2:
            rows.append(_quantity("balanced ball angles ±(pi - arccos(eta/2))", math.pi - math.acos(eta / 2),
                                  "rad", "±"))  # fmt: skip
    return rows


def linear_quantities(case_model: Any) -> list[dict[str, Any]]:
    """Derived quantities of a linear rotor: its degrees of freedom and nodes (name at position)."""
    z = case_model.node_positions()
    nodes = ", ".join(f"{lab}" + ("" if not math.isfinite(p) else f" ({p * 1e3:.6g} mm)")
                      for lab, p in zip(case_model.node_labels(), z))  # fmt: skip
    return [{"quantity": "degrees of freedom (x, y, phi_x, phi_y per node)", "value": case_model.n_dof,
             "unit": "1", "sign": ""},
            {"quantity": "nodes", "value": nodes, "unit": "", "sign": ""}]  # fmt: skip
