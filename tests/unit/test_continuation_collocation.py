"""Orthogonal collocation (the measured alternative to multiple shooting, issue 25) on Van der Pol.

References: the published period of the mu = 1 limit cycle (Grasman 1987, as in
test_continuation_periodic.py), the multiple-shooting orbit of :func:`find_periodic_orbit` on the
compiled integrator, scipy's DOP853 (an independent integrator) returning to the collocation's
state after its period, and the order of Gauss collocation at the mesh points, O(h^(2m))
(Ascher, Mattheij & Russell 1995, Thm. 5.142): halving h divides the error by about 2^8 at m = 4.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorlab.continuation import find_periodic_orbit
from rotorlab.continuation._collocation import collocate_orbit
from rotorlab.models.examples import PlanarOscillator
from test_continuation_periodic import VDP_PERIOD


def _vdp(x, mu=1.0):
    return np.array([x[1], -x[0] + mu * (1.0 - x[0] ** 2) * x[1]])


def _guess():
    """A rough start: one loose integration from (2, 0) over 6.6 s (the period is 6.663)."""
    sol = solve_ivp(lambda t, y: _vdp(y), (0.0, 6.6), [2.0, 0.0], rtol=1e-4, dense_output=True)
    ts = np.linspace(0.0, 6.6, 200)
    return ts, sol.sol(ts).T


def test_van_der_pol_by_collocation_against_shooting_and_the_published_period():
    ts, ys = _guess()
    col = collocate_orbit(_vdp, ts, ys, 6.6, intervals=40, degree=4)
    shoot = find_periodic_orbit(PlanarOscillator.van_der_pol(1.0), [2.0, 0.0], 6.6, segments=5, amplitude=(0,))
    assert abs(col.period - shoot.period) < 1e-6
    assert abs(col.period - VDP_PERIOD) < 1e-8 and col.residual < 1e-10
    # its states are on the cycle: DOP853 from the first returns to it after the period
    back = solve_ivp(lambda t, y: _vdp(y), (0.0, col.period), col.states[0], method="DOP853",
                     rtol=1e-12, atol=1e-14).y[:, -1]
    assert np.max(np.abs(back - col.states[0])) < 1e-7
    np.testing.assert_array_equal(col.states[-1], col.states[0])  # closed (no winding)


def test_collocation_error_falls_as_h_to_the_2m():
    ts, ys = _guess()
    err = [abs(collocate_orbit(_vdp, ts, ys, 6.6, intervals=n, degree=4).period - VDP_PERIOD) for n in (20, 40)]
    assert 2.0**8 / 4 < err[0] / err[1] < 2.0**8 * 4, err


def test_a_guess_too_far_is_refused():
    ts, ys = _guess()
    with pytest.raises(ValueError, match="did not converge"):
        collocate_orbit(_vdp, ts, 0.01 * ys, 2.0, intervals=10, degree=3, max_iterations=3)
