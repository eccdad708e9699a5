"""``steady`` on a machine with a clearance: a steady motion whose orbit at the clearance exceeds
the gap does not exist without contact and is flagged, with the station, its radius and the gap.

Closed forms (any rotor-dynamics text, e.g. Genta, *Dynamics of Rotating Systems* (2005), sec. 4.3):
the unbalance response of the Jeffcott rotor ``r = U Omega^2 / |k - M Omega^2 + i c Omega|``;
with one ball of mass m_b on a race of radius R that cannot cancel U, the ball rests in line with
the rotor's displacement (its centrifugal force then has no tangential part), so with
``H = Omega^2 / (k - (M + m_b) Omega^2 + i c Omega) = h e^{i alpha}`` and the ball on the side
of the displacement ``|rho - H m_b R| = h U``, or opposite it ``|rho + H m_b R| = h U``:
``rho_-+ = +-h m_b R cos(alpha) + sqrt(h^2 U^2 - (h m_b R sin(alpha))^2)``.
"""

import math

import numpy as np
import pytest

from rotorlab.analyses._machine import CLEARANCE_STATUS, clearance_violation, machine_motions, machine_steady
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed
from rotorlab.models._machine import Ball, BallRace, Clearance, Machine, Unbalance

M, K, C, U = 2.0, 2.0e4, 20.0, 1e-4  # kg, N/m, N s/m, kg m: critical speed 100 rad/s


def _machine(gap, races=(), speed=100.0):
    s = LinearSystem(M=np.diag([M, M, 1.0, 1.0]), C=np.diag([C, C, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([K, K, 1.0, 1.0]))  # fmt: skip
    return Machine(s, races=races, unbalances=(Unbalance(0, U),), drive=ConstantSpeed(speed),
                   clearances=(Clearance(0, gap),))  # fmt: skip


def test_unbalance_response_beyond_the_gap_is_flagged():
    speeds = np.array([50.0, 100.0, 150.0])
    radius = U * speeds**2 / np.abs(K - M * speeds**2 + 1j * C * speeds)  # 1.66e-5, 5e-4, 8.94e-5 m
    gap = 1e-4
    ds = machine_steady(_machine(gap), speeds)
    assert np.allclose(ds.amplitude.values[:, 0], radius, rtol=1e-9)
    hit = radius > gap
    assert hit.tolist() == [False, True, False]
    assert np.array_equal(ds.exists.values, ~hit)
    assert np.array_equal(ds.status.values, np.where(hit, CLEARANCE_STATUS, 0))
    msg = ds.attrs["message"]
    assert "at 100 rad/s" in msg and "gap 0.0001 m" in msg and f"{radius[1]:.4g} m" in msg
    assert repr(_machine(gap).structure.node_label[0]) in msg
    # a gap just above the resonant radius: the motion exists
    ok = machine_steady(_machine(radius[1] * 1.001), speeds)
    assert ok.exists.values.all() and (ok.status.values == 0).all() and "message" not in ok.attrs


def test_side_motions_beyond_the_gap_are_flagged():
    """One ball too light to balance: the two side motions (seeds 002/003), ball on the side of the
    displacement (radius rho_-) or opposite (rho_+); a gap between them flags only the larger."""
    mb, rr, om = 0.02, 2e-3, 150.0  # capacity 4e-5 < U = 1e-4 kg m
    race = (BallRace(0, rr, (Ball(mb, damping=1e-4),)),)
    h = om**2 / (K - (M + mb) * om**2 + 1j * C * om)
    a, al = abs(h), np.angle(h)
    root = math.sqrt((a * U) ** 2 - (a * mb * rr * math.sin(al)) ** 2)
    rho = np.array([a * mb * rr * math.cos(al) + root, -a * mb * rr * math.cos(al) + root])  # 5.28e-5, 1.23e-4 m
    gap = float(np.mean(rho))
    m = _machine(gap, race, om)
    ds = machine_motions(m)
    got = ds.amplitude.values[:, 0]
    assert np.allclose(np.sort(got), rho, rtol=1e-7)
    big = got > gap
    assert big.sum() == 1
    assert np.array_equal(ds.exists.values, ~big)
    assert ds.verdict_exact.values[big][0] == "absent (exceeds the clearance)"
    assert int(ds.status) == 0  # the smaller motion exists
    assert f"{rho[1]:.4g} m > gap {gap:.4g} m" in ds.attrs["message"]
    none_fit = machine_motions(_machine(0.9 * rho[0], race, om))
    assert not none_fit.exists.values.any() and int(none_fit.status) == CLEARANCE_STATUS
    assert machine_motions(_machine(1.1 * rho[1], race, om)).exists.values.all()
    r, msg = clearance_violation(m, m.steady_state())
    assert min(abs(r - rho)) < 1e-7 * rho[1] and (msg is not None) == (r > gap)


def test_report_findings_name_the_motion_beyond_the_gap():
    from rotorlab.analyses import summarize
    from rotorlab.report._machine import machine_findings

    race = (BallRace(0, 2e-3, (Ball(0.02, damping=1e-4),)),)
    ds = machine_motions(_machine(9e-5, race, 150.0))  # between the side motions' 5.3e-5 and 1.2e-4 m
    ds.attrs["model_type"] = "machine"  # as run_analysis sets it
    found = machine_findings(ds, summarize(ds))
    assert "has radius" in found.verdict and "gap 9e-05 m" in found.verdict, found
