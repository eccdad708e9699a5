"""The design search finds a closed-form optimum: Den Hartog's tuning of a damped absorber on an
undamped single-mass primary under a harmonic force (Den Hartog, *Mechanical Vibrations*, 4th ed.
1956, Sec. 3.3, eqs. (3.14)-(3.22); Brock's damping). For a mass ratio mu the optimal frequency
ratio is f = 1 / (1 + mu) and the damping ratio zeta = sqrt(3 mu / (8 (1 + mu)^3)); every tuning's
peak response lies at or above the fixed points' height sqrt(1 + 2 / mu) x_st (the minimax
optimum's lower bound), which Den Hartog's tuning reaches to within a fraction of a percent.

The objective is the linear receptance of the machine (:func:`rotorlab.models.absorber_response`,
no ODE ensemble): the search varies ``absorbers[0].stiffness`` and ``absorbers[0].damping``, its
named parameters.
"""

import math

import numpy as np
import pytest

from rotorlab.analyses import DesignProblem, DesignVariable, design_search
from rotorlab.linear import LinearSystem
from rotorlab.models import ConstantSpeed, Machine, TunedMassAbsorber, Unbalance

MU, M1, K1 = 0.1, 1.0, 1.0  # mass ratio, primary mass (kg) and stiffness (N/m): p = 1 rad/s


def machine():
    structure = LinearSystem(M=np.diag([M1, M1, 0.1, 0.1]), C=np.zeros((4, 4)), G=np.zeros((4, 4)),
                             K=np.diag([K1, K1, 1.0, 1.0]))  # fmt: skip
    return Machine(structure, unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(1.0),
                   parts=(TunedMassAbsorber(0, MU * M1, 0.1, 0.02),))  # fmt: skip


F_OPT = 1.0 / (1.0 + MU)
ZETA_OPT = math.sqrt(3.0 * MU / (8.0 * (1.0 + MU) ** 3))
K_OPT = MU * M1 * F_OPT**2 * K1 / M1  # k_a = m_a (f p)^2
C_OPT = 2.0 * MU * M1 * ZETA_OPT * math.sqrt(K1 / M1)  # c_a = 2 m_a zeta p (Den Hartog's c_c = 2 m_a p)
FLOOR = math.sqrt(1.0 + 2.0 / MU) / K1  # the fixed points' height (m/N)


def problem():
    return DesignProblem(machine(), (DesignVariable("absorbers[0].stiffness", 0.5 * K_OPT, 1.5 * K_OPT),
                                     DesignVariable("absorbers[0].damping", 0.2 * C_OPT, 3.0 * C_OPT)),
                         ("receptance-peak",), np.array([0.6, 1.4]))  # fmt: skip


def test_den_hartog_s_tuning_is_the_floor_and_the_search_finds_it():
    # the objective at Den Hartog's tuning: just above the fixed points' height
    from rotorlab.design import DESIGN_OBJECTIVES, DesignPoint

    tuned = machine().with_parameters(**{"absorbers[0].stiffness": K_OPT, "absorbers[0].damping": C_OPT})
    at_opt = DESIGN_OBJECTIVES["receptance-peak"].value(DesignPoint(tuned, np.array([0.6, 1.4])))
    assert FLOOR <= at_opt <= 1.005 * FLOOR
    ds = design_search(problem(), optimizer="tpe", budget=60, optimizer_seed=0)
    best = int(ds.attrs["best"])
    k, c = ds.value.values[best]
    peak = float(ds.objective_value.values[best, 0])
    assert FLOOR * (1 - 1e-9) <= peak <= 1.015 * FLOOR  # within 1.5 % of the floor, never below it
    assert k == pytest.approx(K_OPT, rel=0.02)  # frequency ratio within 1 %: f ~ sqrt(k)
    assert c == pytest.approx(C_OPT, rel=0.15)  # the peak is flat in the damping near its optimum
    # without the absorber the undamped primary's peak is unbounded near p: the search is what helps
    assert np.all(ds.objective_value.values[:, 0] >= FLOOR * (1 - 1e-9))


def test_differential_evolution_runs_the_same_budget_and_the_same_seeds_give_the_same_designs():
    a = design_search(problem(), optimizer="differential-evolution", budget=40, optimizer_seed=2)
    b = design_search(problem(), optimizer="differential-evolution", budget=40, optimizer_seed=2)
    # 4 generations of 10 designs (5 per variable): exactly the budget
    assert a.sizes["trial"] == 40 and np.array_equal(a.value.values, b.value.values)
    # generations only improve on the first (Latin hypercube) one; the floor is never passed
    first, last = (float(np.min(a.objective_value.values[s, 0])) for s in (slice(0, 10), slice(0, 40)))
    assert FLOOR * (1 - 1e-9) <= last <= first


def test_a_limit_is_a_constraint_with_its_margin():
    # the peak bounded at twice the floor: feasible exactly where it holds, margin (limit - value) / limit
    limit = 2.0 * FLOOR
    base = problem()
    bounded = DesignProblem(base.model, base.variables, base.objectives, base.operating,
                            limits={"receptance-peak": limit})  # fmt: skip
    ds = design_search(bounded, optimizer="tpe", budget=12, optimizer_seed=1)
    peak = ds.objective_value.values[:, 0]
    assert list(ds.constraint.values) == ["limits.receptance-peak"]
    np.testing.assert_allclose(ds.margin.values[:, 0], (limit - peak) / limit, rtol=1e-12)
    np.testing.assert_array_equal(ds.feasible.values, peak <= limit)
    assert (~ds.feasible.values).any() and ds.feasible.values.any()
    best = int(ds.attrs["best"])
    assert peak[best] == peak[ds.feasible.values].min()
