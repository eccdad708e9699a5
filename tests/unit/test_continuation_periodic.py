"""Periodic orbits by multiple shooting (rotorlab.continuation): textbook systems with known answers.

All models are :class:`rotorlab.models.examples.PlanarOscillator` (one compiled kernel): the Van
der Pol oscillator, the Hopf (Stuart–Landau) and Bautin normal forms, the damped Mathieu equation.
References are closed forms, published values, or scipy's ``solve_ivp`` (DOP853, rtol 1e-12) as
an independent integrator.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from rotorlab.continuation import (
    ContinuationSettings,
    continue_periodic,
    find_periodic_orbit,
    orbit_from_hopf,
)
from rotorlab.continuation._floquet import period_doubling_value, torus_value
from rotorlab.models.examples import BouncingBall, FrictionBlock, PlanarOscillator

# Van der Pol, mu = 1: period of the limit cycle (Grasman, "Asymptotic Methods for Relaxation
# Oscillations and Applications", Springer 1987; the 20-digit value quoted by e.g. Strogatz's
# exercises and computed to high precision by many authors) and the largest |x| on it.
VDP_PERIOD = 6.6632868593231301896
VDP_AMPLITUDE = 2.0086198608748431


def _scipy_vdp(mu, y0, t_end, **kw):
    return solve_ivp(lambda t, y: [y[1], -y[0] + mu * (1 - y[0] ** 2) * y[1]], (0, t_end), y0,
                     method="DOP853", rtol=1e-12, atol=1e-14, **kw)


def test_van_der_pol_period_and_amplitude():
    orbit = find_periodic_orbit(PlanarOscillator.van_der_pol(1.0), [2.0, 0.0], 6.6, segments=5, amplitude=(0,))
    assert orbit.period == pytest.approx(VDP_PERIOD, abs=1e-7)
    assert orbit.amplitude == pytest.approx(VDP_AMPLITUDE, abs=1e-6)
    assert orbit.stable and orbit.trivial_error < 1e-6
    # the phase-0 state is on the cycle: scipy returns to it after one period
    back = _scipy_vdp(1.0, orbit.state, orbit.period).y[:, -1]
    assert np.max(np.abs(back - orbit.state)) < 1e-7


@pytest.mark.parametrize("mu", [1.0, -1.0])
def test_floquet_labels_and_multipliers_do_not_depend_on_the_segments(mu):
    """mu = 1: stable cycle; mu = -1: the same cycle run backwards, unstable. The non-trivial
    multiplier is exp(int_0^T mu (1 - x^2) dt) (Liouville), integrated independently by scipy."""
    model = PlanarOscillator.van_der_pol(mu)
    labels, others = set(), []
    for m in (1, 3, 5, 10, 20):
        # (largest x, 0) lies on both cycles (mu = -1 is mu = 1 with y -> -y, t -> -t)
        orbit = find_periodic_orbit(model, [VDP_AMPLITUDE, 0.0], 6.66, segments=m)
        labels.add(orbit.stable)
        assert orbit.trivial_error < 1e-5  # 3e-6 next to the multiplier 1163 of mu = -1
        others.append(np.delete(orbit.multipliers, orbit.trivial)[0])
    assert labels == {mu > 0}
    sol = solve_ivp(lambda t, y: [y[1], -y[0] + mu * (1 - y[0] ** 2) * y[1], mu * (1 - y[0] ** 2)],
                    (0, VDP_PERIOD), [*orbit.state, 0.0], method="DOP853", rtol=1e-12, atol=1e-14)
    expected = math.exp(sol.y[2, -1])
    # one segment of the unstable cycle stretches the perturbations 1163 times: its central
    # differences are second-order accurate only to (1163 h)^2; three or more segments: 1e-6
    assert np.allclose(np.real(others[1:]), expected, rtol=1e-6)
    assert np.allclose(np.real(others[0]), expected, rtol=1e-6 if mu > 0 else 1e-3)
    assert np.allclose(np.imag(others), 0.0)


def test_stuart_landau_branch_from_its_hopf_point():
    """z' = (mu + i w) z - |z|^2 z: Hopf at mu = 0; orbits of radius sqrt(mu), period 2 pi / w,
    multipliers 1 and exp(-2 mu T)."""
    w = 2.0

    def at(mu):
        return PlanarOscillator.stuart_landau(mu, w).to_array()

    model = PlanarOscillator.stuart_landau(0.0, w)
    start = orbit_from_hopf(model, [0.0, 0.0], 0.0, at, amplitude=1e-2, segments=4)
    assert start.value == pytest.approx(1e-4, rel=1e-4)  # radius 1e-2
    branch = continue_periodic(model, start, at, parameter="mu", state_scale=1.0,
                               settings=ContinuationSettings(ds=0.02, ds_max=0.1, bounds=(-1.0, 1.0)))
    assert branch.end == "bound" and branch.values[-1] == pytest.approx(1.0)
    mu, period = branch.values, branch.period
    assert np.all(mu > 0) and branch.stable.all()
    assert np.max(np.abs(branch.amplitude[mu > 0.01] / np.sqrt(mu[mu > 0.01]) - 1.0)) < 1e-6
    assert np.max(np.abs(period * w / (2 * math.pi) - 1.0)) < 1e-6
    mods = np.sort(np.abs(branch.spectrum), axis=1)
    assert np.max(np.abs(mods[:, 1] - 1.0)) < 1e-6
    assert np.max(np.abs(mods[:, 0] / np.exp(-2 * mu * period) - 1.0)) < 1e-6
    assert branch.special_points == ()
    d = branch.to_dict()
    assert d["kind"] == "periodic" and set(d["points"][0]) >= {"mu", "stable", "amplitude_m", "period_s", "multipliers"}


def test_bautin_fold_of_cycles_located():
    """z' = (mu + i) z + |z|^2 z - |z|^4 z: unstable orbits from the subcritical Hopf at mu = 0 fold
    at mu = -1/4 (r^2 = 1/2) into the stable large orbits."""

    def at(mu):
        return PlanarOscillator.stuart_landau(mu, 1.0, cubic=1.0, quintic=-1.0).to_array()

    model = PlanarOscillator.stuart_landau(0.0, 1.0, cubic=1.0, quintic=-1.0)
    start = orbit_from_hopf(model, [0.0, 0.0], 0.0, at, amplitude=1e-2, segments=3)
    assert not start.stable and start.value < 0
    branch = continue_periodic(model, start, at, parameter="mu", state_scale=1.0,
                               settings=ContinuationSettings(ds=0.02, ds_max=0.1, max_points=80, bounds=(-1.0, 0.3)))
    (fold,) = branch.special_points
    assert fold.type == "fold-of-cycles" and fold.value == pytest.approx(-0.25, abs=1e-7)
    assert "unstable before it and stable after it" in fold.description
    r2 = branch.amplitude**2
    assert np.all(branch.stable == (r2 > 0.5))
    assert np.allclose(branch.values + r2 - r2**2, 0.0, atol=1e-7)  # mu = r^4 - r^2
    assert "at mu = -0.24999999" in fold.description  # no unit: the plain number
    # with the parameter's unit the sentence is in people's units (rad/s read as rpm)
    said = continue_periodic(model, start, at, parameter="mu", state_scale=1.0, unit="rad/s",
                             settings=ContinuationSettings(ds=0.02, ds_max=0.1, max_points=80, bounds=(-1.0, 0.3)))
    (fold2,) = said.special_points
    assert fold2.value == fold.value and f"at mu = {-0.25 * 30 / math.pi:.4g} rpm (period" in fold2.description
    _check_orbit_sentence(branch)


def _check_orbit_sentence(branch):
    """The report's sentence (orbit_sentence) against the branch it came from: mu = r^4 - r^2 has
    its stable orbits (r^2 > 1/2) from the fold of cycles at mu = -1/4 to the range's end 0.3 and
    its unstable ones from the fold to the first orbit continued from the Hopf point (r = 1e-2,
    mu = -1e-4 + 1e-8); the stable stretch starts at the located fold, not at the computed orbit
    nearest to it (-0.2496 here)."""
    import re

    from rotorlab.analyses._continuation_periodic import orbit_sentence

    d = branch.to_dict()
    text = orbit_sentence({**d, "label": "whirl"}, "")
    m = re.fullmatch(r"a whirl orbit exists and is stable from (\S+) to (\S+); stability changes at the "
                     r"fold-of-cycles at (\S+); the branch's unstable orbits lie between (\S+) and (\S+) "
                     r"\(the branch ended at (\S+): the range ends there\)", text)
    assert m, text
    got = [float(x) for x in m.groups()]
    np.testing.assert_allclose(got, [-0.25, 0.3, -0.25, -0.25, -1e-4 + 1e-8, 0.3], rtol=1e-4, atol=0)
    assert np.min(branch.values[branch.stable]) > -0.2499  # the grid alone would have said so
    # two stable stretches (stable, unstable, stable along the points) are both named
    flip = {**d, "label": "whirl", "special_points": [], "points": [
        {**p, "stable": bool(abs(i - len(d["points"]) // 2) > 2)} for i, p in enumerate(d["points"])]}
    ok = np.array([p["stable"] for p in flip["points"]])
    k = int(np.argmin(ok))  # the first unstable point
    v = branch.values
    first, second = (v[:k].min(), v[:k].max()), (v[k + 5:].min(), v[k + 5:].max())
    assert f"stable from {first[0]:.5g} to {first[1]:.5g} and from {second[0]:.5g} to {second[1]:.5g};" \
        in orbit_sentence(flip, "")


def _mathieu_monodromy(delta, eps, c):
    def f(t, y):
        return [y[1], -(delta + eps * math.cos(t)) * y[0] - c * y[1]]

    cols = [solve_ivp(f, (0, 2 * math.pi), e, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1] for e in np.eye(2)]
    return np.column_stack(cols)


@pytest.mark.parametrize("delta,eps,c", [(0.25, 0.2, 0.02), (0.5, 0.2, 0.02), (1.0, 0.3, 0.01)])
def test_mathieu_multipliers_against_scipy(delta, eps, c):
    """x'' + c x' + (delta + eps cos t) x = 0, the orbit x = 0 of the forced (2 pi-periodic) system:
    its multipliers are those of scipy's fundamental matrix; det M = exp(-2 pi c) (Liouville)."""
    ref = np.linalg.eigvals(_mathieu_monodromy(delta, eps, c))
    for m in (1, 4):
        orbit = find_periodic_orbit(PlanarOscillator.mathieu(delta, eps, c), [0.0, 0.0], 2 * math.pi, forced=True,
                                    segments=m, state_scale=1.0)
        got = orbit.multipliers
        assert orbit.trivial == -1
        assert np.max(np.abs(np.sort_complex(got) - np.sort_complex(ref))) < 1e-8
        assert abs(np.prod(got) - math.exp(-2 * math.pi * c)) < 1e-9
        assert orbit.stable == bool(np.max(np.abs(ref)) < 1)


def test_mathieu_period_doubling_and_torus_located():
    """Continuing the orbit x = 0 in delta crosses the first instability tongue (a multiplier
    through -1 at both edges: period doubling), located where scipy's monodromy has
    det(M + I) = 0; continuing in the damping c crosses |mu| = 1 of a complex pair at c = 0
    (|mu|^2 = det M = exp(-2 pi c)): a torus point."""
    def pd_edge(d):
        m = _mathieu_monodromy(d, 0.2, 0.02)
        return 1 + np.trace(m) + np.linalg.det(m)

    edges = [brentq(pd_edge, 0.1, 0.25, xtol=1e-13), brentq(pd_edge, 0.25, 0.4, xtol=1e-13)]
    model = PlanarOscillator.mathieu(0.1, 0.2, 0.02)
    orbit = find_periodic_orbit(model, [0.0, 0.0], 2 * math.pi, forced=True, segments=2, state_scale=1.0,
                                parameter="delta", value=0.1)
    branch = continue_periodic(model, orbit, lambda d: PlanarOscillator.mathieu(d, 0.2, 0.02).to_array(),
                               parameter="delta", settings=ContinuationSettings(ds=0.01, ds_max=0.02, bounds=(0.1, 0.4)))
    found = [(s.type, s.value) for s in branch.special_points]
    assert [t for t, _ in found] == ["period-doubling", "period-doubling"]
    assert np.allclose([v for _, v in found], edges, atol=1e-8)
    model = PlanarOscillator.mathieu(0.5, 0.2, -0.01)
    orbit = find_periodic_orbit(model, [0.0, 0.0], 2 * math.pi, forced=True, segments=3, state_scale=1.0,
                                parameter="c", value=-0.01)
    branch = continue_periodic(model, orbit, lambda c: PlanarOscillator.mathieu(0.5, 0.2, c).to_array(),
                               parameter="c", parameter_scale=0.01,
                               settings=ContinuationSettings(ds=0.1, ds_max=0.5, bounds=(-0.01, 0.01)))
    (torus,) = branch.special_points
    assert torus.type == "torus" and abs(torus.value) < 1e-8
    mu = np.linalg.eigvals(_mathieu_monodromy(0.5, 0.2, 0.0))
    assert torus.frequency == pytest.approx(abs(np.angle(mu[0])) / (2 * math.pi), rel=1e-6)
    assert np.array_equal(branch.stable, branch.values > 0)


def test_test_functions_vanish_at_their_bifurcations():
    assert period_doubling_value(np.array([-1.0, 0.5]), -1) == 0.0
    assert period_doubling_value(np.array([-1.1, 0.5]), -1) < 0 < period_doubling_value(np.array([-0.9, 0.5]), -1)
    pair = np.exp(np.array([0.7j, -0.7j]))
    assert abs(torus_value(np.concatenate([pair, [0.3, 1.0]]), 3)) < 1e-4  # (|mu|^2 - 1 = 2e-16)^(1/3)
    assert torus_value(np.concatenate([1.1 * pair, [0.3]]), -1) * torus_value(np.concatenate([0.9 * pair, [0.3]]), -1) < 0


@pytest.mark.parametrize("model,events", [(BouncingBall(), "impact, lift_off"), (FrictionBlock(), "stop, break_away")])
def test_models_with_events_are_refused(model, events):
    with pytest.raises(ValueError, match=f"periodic orbits of a model with events \\({events}\\) are not supported"):
        find_periodic_orbit(model, [1.0, 0.0, 0.0], 1.0)
    with pytest.raises(ValueError, match="equilibria of the smooth part"):
        orbit_from_hopf(model, [1.0, 0.0, 0.0], 0.0, lambda v: model.to_array())


def test_a_parameter_name_the_model_does_not_have_is_refused():
    model = PlanarOscillator.van_der_pol(1.0)
    with pytest.raises(ValueError, match="unknown parameter 'mu' of PlanarOscillator; its parameters: none"):
        orbit_from_hopf(model, [0.0, 0.0], 0.0, "mu")


def test_a_time_dependent_model_needs_forced():
    with pytest.raises(ValueError, match="depends on time .* give forced=True"):
        find_periodic_orbit(PlanarOscillator.mathieu(0.5, 0.2, 0.02), [0.1, 0.0], 2 * math.pi)
