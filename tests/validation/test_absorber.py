"""The tuned mass absorber part of the machine (:class:`rotorlab.models.TunedMassAbsorber`).

Closed forms: an undamped absorber tuned to the spin speed (``k_a = m_a w^2``) cancels the
station's unbalance response at that speed, and then carries the unbalance force alone (its
amplitude ``U w^2 / k_a = U / m_a``); the Den Hartog optimum of an absorber on a single-mass
primary under a constant harmonic force: fixed points of the response at the roots of ``(2 + mu)
g^4 - 2 (1 + (1 + mu) f^2) g^2 + 2 f^2 = 0``, at equal height ``sqrt(1 + 2 / mu)`` for ``f = 1 /
(1 + mu)``, and Brock's damping ``zeta = sqrt(3 mu / (8 (1 + mu)^3))`` whose peaks lie just above
them (Den Hartog, *Mechanical Vibrations*, 4th ed. 1956, Sec. 3.3, eqs. (3.14)-(3.22)). The
simulated machine (its generated kernel) is checked against these and against the independent
linear response, and its energy ledger closes.

One compiled layout for every simulation here (4 structure coordinates, one unbalance, constant
speed, energy states, one absorber).
"""

import math
import tomllib

import numpy as np
import pytest

from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed, Gravity, Machine, TunedMassAbsorber, Unbalance, absorber_response

W, U, M1, K1, C1 = 1.5, 0.01, 1.0, 1.0, 0.1  # speed (rad/s), unbalance (kg m), primary m, k, c
MU = 0.1


def structure(c=C1):
    return LinearSystem(M=np.diag([M1, M1, 0.1, 0.1]), C=np.diag([c, c, 0.0, 0.0]), G=np.zeros((4, 4)),
                        K=np.diag([K1, K1, 1.0, 1.0]))


def machine(ka, ca=0.0, gravity=None, c=C1):
    return Machine(structure(c), unbalances=(Unbalance(0, U),), drive=ConstantSpeed(W), gravity=gravity,
                   parts=(TunedMassAbsorber(0, MU * M1, ka, ca),), energy_states=True)


def steady(m, periods=300):
    """Simulate from rest; the station's and the absorber's amplitudes over the last period."""
    T = 2 * math.pi / W
    ts = np.linspace((periods - 1) * T, periods * T, 201)
    sol = solve(m, m.initial_state(), (0.0, ts[-1]), save_at=SaveAt(ts=ts),
                control=StepControl(rtol=1e-10, atol=1e-13))
    assert sol.status.name == "SUCCESS"
    i = m.state_names.index("x_absorber_1")
    return np.hypot(sol.ys[:, 0], sol.ys[:, 1]).max(), np.hypot(sol.ys[:, i], sol.ys[:, i + 1]).max()


def test_a_tuned_undamped_absorber_cancels_the_station_s_unbalance_response():
    """k_a = m_a W^2, c_a = 0: the linear response at W is zero (to round-off) against 17.9 mm
    without it (``U W^2 / |K - M W^2 + i W C|``), and the simulated machine, from rest, settles
    there: the station within 1e-5 of the unabsorbed amplitude after 300 periods, the absorber on
    the circle of radius ``U / m_a``."""
    m = machine(MU * M1 * W * W)
    ds = absorber_response(m, 0, [W])
    without = U * W * W / abs(K1 - M1 * W * W + 1j * W * C1)
    assert float(ds.amplitude_without[0]) == pytest.approx(without, rel=1e-12)
    assert float(ds.amplitude[0]) < 1e-12 * without
    station, absorber = steady(m)
    assert station < 1e-5 * without
    assert absorber == pytest.approx(U / (MU * M1), rel=1e-5)


def test_the_simulated_machine_settles_on_the_linear_response_of_a_detuned_damped_absorber():
    """A detuned (``k_a = 1.3 m_a W^2``) damped absorber: the simulated steady amplitude of the
    station is the linear response's (locked DOFs, the absorber's dynamic stiffness), to 1e-5."""
    m = machine(1.3 * MU * M1 * W * W, ca=0.02)
    expected = float(absorber_response(m, 0, [W]).amplitude[0])
    without = float(absorber_response(m, 0, [W]).amplitude_without[0])
    assert 0.1 * without < expected < 0.9 * without  # a real, partial reduction
    station, _ = steady(m)
    assert station == pytest.approx(expected, rel=1e-5)


def test_the_energy_ledger_closes_with_a_damped_absorber_under_gravity():
    """``work = E - E0 + dissipated`` with the absorber's kinetic, spring and gravity energy and its
    damper's dissipation, a lateral gravity, during the transient from rest (50 s)."""
    m = machine(0.8 * MU * M1 * W * W, ca=0.03, gravity=Gravity((0.3, -0.5, 0.0)))
    ts = np.linspace(0.0, 50.0, 101)
    sol = solve(m, m.initial_state(), (0.0, 50.0), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-11, atol=1e-14))
    res = m.energy_balance(sol.ts, sol.ys)
    ie = m.layout.i_energy
    scale = max(np.abs(sol.ys[:, ie + 1]).max(), 1e-30)
    assert sol.ys[-1, ie + 1] > 0.0 and np.max(np.abs(res)) < 1e-7 * scale


@pytest.mark.parametrize("mu", [0.05, 0.1, 0.25])
def test_den_hartog_optimum_on_a_single_mass_primary(mu):
    """Undamped primary (M = 1 kg, K = 1 N/m), constant force: the machine's receptance at the
    station is Den Hartog's closed form (to 1e-12), its fixed points do not move with the damping
    and, tuned to ``f = 1 / (1 + mu)``, lie at equal height ``sqrt(1 + 2 / mu)``; with Brock's
    damping the peak is above them by less than 1 % (0.08-0.4 % found), while a detuned absorber's
    fixed points differ by more than 10 %."""
    f, zeta = 1.0 / (1.0 + mu), math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3))
    s = structure(c=0.0)

    def ratio(z, g, ff=f):
        part = TunedMassAbsorber(0, mu * M1, mu * M1 * ff * ff, 2.0 * z * mu * M1 * math.sqrt(K1 / M1))
        return absorber_response(Machine(s, drive=ConstantSpeed(1.0), parts=(part,)), 0, g).receptance.values * K1

    g = np.array([0.7, 0.93, 1.0, 1.08, 1.3])
    closed = np.sqrt(((2 * zeta * g) ** 2 + (g * g - f * f) ** 2)
                     / ((2 * zeta * g) ** 2 * (g * g - 1 + mu * g * g) ** 2
                        + (mu * f * f * g * g - (g * g - 1) * (g * g - f * f)) ** 2))
    np.testing.assert_allclose(ratio(zeta, g), closed, rtol=1e-12)

    def fixed_points(ff):
        return np.sqrt(np.sort(np.roots([2 + mu, -2 * (1 + (1 + mu) * ff * ff), 2 * ff * ff]).real))

    gp = fixed_points(f)
    low, high = ratio(0.01, gp), ratio(5.0, gp)
    np.testing.assert_allclose(low, high, rtol=1e-9)
    np.testing.assert_allclose(low, math.sqrt(1 + 2 / mu), rtol=1e-9)
    peak = ratio(zeta, np.linspace(0.5, 1.5, 4001)).max()
    assert math.sqrt(1 + 2 / mu) <= peak < 1.01 * math.sqrt(1 + 2 / mu)
    detuned = ratio(0.01, fixed_points(1.1 * f), ff=1.1 * f)
    assert abs(detuned[0] / detuned[1] - 1) > 0.1
