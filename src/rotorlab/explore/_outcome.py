"""Classify where a trajectory of a ball balancer ended: balanced, a side motion, or non-synchronous.

At constant spin speed the steady motions of the ``jeffcott_balls`` model are equilibria of its
co-rotating frame (seed 002, eq. (9)): the rotor stands still at ``u + i v`` and every ball at a
fixed angle psi_i from the unbalance. For two equal balls, seed 002 (eqs. (15)-(16)) lists four:
the *balanced* one, psi = +-(pi - gamma), gamma = arccos(eta / 2), and three *side motions* with
the balls on the line through the unbalance, (0, 0), (pi, pi) and (0, pi). With shaft damping the
side motions turn by the phase lag of the rotor's response (a ball settles where the rotor's
deflection points), so "on the line" is judged with a tolerance.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "BALANCED_FRACTION",
    "SETTLE_RATE",
    "SIDE_TOLERANCE",
    "reference_amplitude",
    "classify",
    "wrap_angle",
    "NON_SYNCHRONOUS_RATE",
    "machine_outcome",
    "BELOW_CRITICAL",
    "wrap_machine_angle",
]

#: A rotor counts as balanced when its deflection is below this fraction of the deflection the
#: unbalance alone would cause (:func:`reference_amplitude`).
BALANCED_FRACTION = 0.05

#: Balls count as settled when every relative rate |psi_i'| stays below this fraction of the spin
#: speed (rad/s per rad/s) over the final window.
SETTLE_RATE = 1e-4

#: A ball is "on the line through the unbalance" when its angle is within this many radians of
#: 0 or pi (30 degrees: damping turns the side motions by the rotor's phase lag).
SIDE_TOLERANCE = math.radians(30.0)


def wrap_angle(angle):
    """Wrap angles to (-pi, pi].

    Parameters
    ----------
    angle : float or array_like
        Angles (rad).

    Returns
    -------
    float or ndarray
        ``pi - mod(pi - angle, 2 pi)``; NaN stays NaN.

    Examples
    --------
    >>> import numpy as np
    >>> wrap_angle(np.array([np.pi, -np.pi, 3 * np.pi / 2, 0.0])) / np.pi
    array([ 1. ,  1. , -0.5,  0. ])
    """
    return np.pi - np.mod(np.pi - np.asarray(angle, dtype=float), 2.0 * np.pi)


def reference_amplitude(imbalance: float, stiffness: float, total_mass: float, damping: float,
                        spin_speed) -> np.ndarray:  # fmt: skip
    """Return the steady deflection the unbalance alone causes (balls balanced out or absent).

    Parameters
    ----------
    imbalance : float
        Static unbalance M1 e of the disc (kg m).
    stiffness : float
        Shaft stiffness c (N/m).
    total_mass : float
        M = M1 + sum m_i (kg), the mass moving with the disc centre.
    damping : float
        External viscous damping d (N s/m).
    spin_speed : float or array_like
        omega (rad/s).

    Returns
    -------
    ndarray
        ``M1 e omega^2 / |c - M omega^2 + i d omega|`` (m), the damped form of seed 002 eq. (9)
        with the balls' static moments summing to zero.

    Examples
    --------
    >>> round(float(reference_amplitude(1e-3, 100.0, 1.0, 0.0, 20.0)), 12)  # 1e-3 * 400 / 300
    0.001333333333
    """
    om = np.asarray(spin_speed, dtype=float)
    return imbalance * om**2 / np.abs(stiffness - total_mass * om**2 + 1j * damping * om)


def _degrees_label(angles: np.ndarray) -> str:
    degs = (int(round(math.degrees(a))) for a in angles)
    return ", ".join(f"{d}°" for d in sorted(180 if d == -180 else d for d in degs))


def classify(status: int, status_message: str, final_amplitude: float, reference: float,
             final_angles, max_rate: float, spin_speed: float, *,
             balanced_fraction: float = BALANCED_FRACTION, settle_rate: float = SETTLE_RATE,
             side_tolerance: float = SIDE_TOLERANCE) -> str:  # fmt: skip
    """Label the end of one trajectory.

    Parameters
    ----------
    status : int
        Integrator status code (< 0: failed).
    status_message : str
        Its message, used in ``"failed: <message>"``.
    final_amplitude : float
        Mean rotor deflection over the final window (m).
    reference : float
        Deflection the unbalance alone causes at this speed (m), :func:`reference_amplitude`.
    final_angles : array_like, shape (n,)
        Ball angles from the unbalance at the end (rad).
    max_rate : float
        Largest ``|psi_i'|`` over the final window (rad/s); NaN counts as moving.
    spin_speed : float
        omega (rad/s) at the end.
    balanced_fraction, settle_rate, side_tolerance : float
        Thresholds, see :data:`BALANCED_FRACTION`, :data:`SETTLE_RATE`, :data:`SIDE_TOLERANCE`.

    Returns
    -------
    str
        ``"failed: ..."``, ``"non-synchronous"``, ``"balanced"``, ``"side (0°, 180°)"`` (balls on the
        line through the unbalance; nominal angles, sorted), ``"steady (a°, b°)"`` (settled
        elsewhere, e.g. held by friction; measured angles, sorted) or, for a rotor without
        balls, ``"unbalanced"``.

    Examples
    --------
    >>> import numpy as np
    >>> classify(0, "", 1e-9, 1e-3, np.radians([120.0, -120.0]), 1e-8, 250.0)
    'balanced'
    >>> classify(0, "", 3e-3, 1e-3, np.radians([-16.0, -16.0]), 1e-8, 75.0)
    'side (0°, 0°)'
    >>> classify(0, "", 2e-3, 1e-3, np.radians([-16.0, 170.0]), 50.0, 250.0)
    'non-synchronous'
    """
    if status < 0:
        return f"failed: {status_message}"
    angles = wrap_angle(np.asarray(final_angles, dtype=float).reshape(-1))
    if not (max_rate <= settle_rate * abs(spin_speed)) or not np.all(np.isfinite(angles)):
        return "non-synchronous"
    if final_amplitude <= balanced_fraction * reference + 1e-15:
        return "balanced"
    if angles.size == 0:
        return "unbalanced"
    near_zero = np.abs(angles) <= side_tolerance
    near_pi = np.abs(angles) >= math.pi - side_tolerance
    if np.all(near_zero | near_pi):
        return f"side ({_degrees_label(np.where(near_zero, 0.0, math.pi))})"
    return f"steady ({_degrees_label(angles)})"


def true_runs(values, mask) -> list[tuple[float, float]]:
    """The runs of consecutive ``values`` where ``mask`` holds, as ``(first, last)`` pairs.

    Examples
    --------
    >>> true_runs([10.0, 20.0, 30.0, 40.0, 50.0], [True, True, False, True, False])
    [(10.0, 20.0), (40.0, 40.0)]
    """
    runs: list[list[float]] = []
    prev = False
    for v, m in zip(values, mask):
        if m and prev:
            runs[-1][1] = v
        elif m:
            runs.append([v, v])
        prev = bool(m)
    return [(a, b) for a, b in runs]


#: Balls moving relative to the rotor faster than this fraction of its speed in the final window
#: of a simulation have not synchronised ("non-synchronous").
NON_SYNCHRONOUS_RATE = 1e-2


#: Outcome of a machine run that would count as balanced but ended at or below its first critical
#: speed (a machine that did not spin up, or a run below the critical speed): a ball balancer
#: balances only above it (below it the balls move to the heavy side; Thearle 1950), and at rest
#: the unbalance has no response to balance.
BELOW_CRITICAL = "below critical speed"


def machine_outcome(status: int, amplitude, reference, max_rate: float, speed: float, n_balls: int,
                    first_critical: float = 0.0) -> str:
    """Label where one simulation of a machine ended (see :func:`rotorlab.analyses.machine_simulate`);
    never "balanced" at or below ``first_critical`` (rad/s), see :data:`BELOW_CRITICAL`."""
    if status < 0:
        return "failed"
    if n_balls == 0:
        return "no balancer"
    if np.max(amplitude) <= BALANCED_FRACTION * np.max(reference) + 1e-15:
        return "balanced" if abs(speed) > first_critical else BELOW_CRITICAL
    if not max_rate <= NON_SYNCHRONOUS_RATE * abs(speed):
        return "non-synchronous"
    return "not balanced"


def wrap_machine_angle(angle):
    """Wrap angles to [-pi, pi) (``(angle + pi) mod 2 pi - pi``): the convention of the machine's
    ball angles (:func:`rotorlab.analyses.machine_simulate`); :func:`wrap_angle` is that of
    ``jeffcott_balls``, (-pi, pi]."""
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi
