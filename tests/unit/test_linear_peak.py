"""Peak unbalance response: located between grid speeds for a damped rotor, unbounded (with a
note) for an undamped one.

Closed form: a rigid disc (mass m) on an isotropic bearing (stiffness k, damping c) with an
unbalance m_u e has the orbit radius ``r(W) = m_u e W^2 / |k - m W^2 + i c W|``, largest at
``W* = wn / sqrt(1 - 2 zeta^2)`` with ``r* = m_u e / (2 m zeta sqrt(1 - zeta^2))``
(``wn = sqrt(k/m)``, ``zeta = c / (2 sqrt(k m))``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorlab.analyses import run_linear_analysis, summarize_linear
from rotorlab.io import load_case
from rotorlab.linear import Bearing, RigidBody, Unbalance, assemble, unbalance_response

M, K, ME = 10.0, 1e6, 1e-4  # kg, N/m, kg m


def _rotor(c: float):
    return assemble([RigidBody(0, M, 0.2, 0.05, spinning=False), Bearing(0, kxx=K, cxx=c,
                                                                        k_tilt_x=1e4)])


@pytest.mark.parametrize("zeta", [1e-3, 1e-2])
def test_damped_peak_between_grid_speeds(zeta):
    c = 2.0 * zeta * math.sqrt(K * M)
    wn = math.sqrt(K / M)
    speeds = np.linspace(0.5 * wn, 1.5 * wn, 40)  # steps of 2.6 % of wn, none at wn
    ds = unbalance_response(_rotor(c), speeds, [Unbalance(0, ME)])
    exact_w = wn / math.sqrt(1.0 - 2.0 * zeta**2)
    exact_r = ME / (2.0 * M * zeta * math.sqrt(1.0 - zeta**2))
    assert float(ds.peak_speed[0]) == pytest.approx(exact_w, rel=1e-7)
    assert float(ds.peak_orbit[0]) == pytest.approx(exact_r, rel=1e-7)
    assert float(ds.orbit_major[:, 0].max()) < 0.95 * exact_r  # the grid alone misses it
    assert "note" not in ds.attrs


def test_undamped_peak_is_unbounded_with_a_note():
    ds = unbalance_response(_rotor(0.0), np.linspace(100.0, 600.0, 201), [Unbalance(0, ME)])
    assert np.isinf(ds.peak_orbit[0]) and np.isnan(ds.peak_speed[0])
    # sqrt(k/m) = 316.228 rad/s = 3019.75 rpm (the tilt mode, 223.607 rad/s, takes no unbalance
    # force but is a critical speed too: 2135.29 rpm)
    assert ds.attrs["note"].startswith("undamped rotor: the response is unbounded at the "
                                       "critical speeds (2135.29, 3019.75 rpm)")


def test_friswell_case_reports_no_grid_artefact():
    # The undamped Friswell rotor: no peak value (it would depend on the speed grid), a note.
    case = load_case("friswell-rotor")
    rows = summarize_linear(run_linear_analysis(case.model, case.analysis("unbalance-response")))
    assert all(r["peak_amplitude"] is None and r["peak_speed_rpm"] is None for r in rows)
    assert rows[0]["note"].startswith("undamped rotor: the response is unbounded at the critical "
                                      "speeds (825.134")


def test_no_critical_speed_below_max_speed_is_an_empty_result():
    from rotorlab.linear import critical_speeds

    found = critical_speeds(_rotor(0.0), max_speed=100.0)  # the lowest is 223.6 rad/s
    assert found.speed.size == 0 and found.to_dataset().sizes["critical"] == 0
