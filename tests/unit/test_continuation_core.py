"""The pseudo-arclength core of rotorlab.continuation on curves with closed forms: folds of a
circle and of a saddle-node, branch points of a pitchfork and of a transcritical bifurcation
located to 1e-9 in the parameter, and branch switching onto the known other branch."""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.continuation import (
    Branch,
    ContinuationResult,
    ContinuationSettings,
    SpecialPoint,
    continue_curve,
    switch_branch,
)

S = ContinuationSettings(ds=0.05, ds_max=0.1, bounds=(-1.0, 1.0))


def test_circle_two_folds_and_closes():
    # x^2 + lam^2 = r^2 with scale: folds of lam at +-r
    r = 2.5e-3
    c = continue_curve(lambda u: np.array([u[0] ** 2 + u[1] ** 2 - r * r]), [0.6 * r, 0.8 * r],
                       scale=np.array([r, r]), settings=ContinuationSettings(ds=0.05, ds_max=0.2))
    folds = sorted(z.point.lam for z in c.crossings if z.name == "fold")
    assert c.end == "closed"
    np.testing.assert_allclose(folds, [-r, r], rtol=0, atol=1e-9 * r)
    assert all(z.converged for z in c.crossings)
    assert not [z for z in c.crossings if z.name == "branch"]  # a fold is not a branch point


def test_rescale_follows_a_state_that_grows_a_thousandfold():
    """The ellipse (x / R)^2 + lam^2 = 1 with R = 1000 and x's typical size 1 (a whirl that grows
    far beyond its balanced scale near a resonance): measured in the fixed scale its arclength is
    about 4000, out of reach of 400 steps of at most 0.1; measured in the branch's own size
    (``rescale``: x by max(1, |x|)) it closes, with its two folds at lam = +-1 to 1e-9, each once."""
    big = 1e3

    def f(u):
        return np.array([(u[0] / big) ** 2 + u[1] ** 2 - 1.0])

    st = ContinuationSettings(ds=0.05, ds_max=0.1, max_points=400)
    fixed = continue_curve(f, [0.6 * big, 0.8], settings=st)
    own = continue_curve(f, [0.6 * big, 0.8], settings=st, rescale=lambda u: np.array([max(1.0, abs(u[0])), 1.0]))
    assert fixed.end == "max_points" and own.end == "closed"
    folds = sorted(z.point.lam for z in own.crossings if z.name == "fold")
    np.testing.assert_allclose(folds, [-1.0, 1.0], rtol=0, atol=1e-9)
    with pytest.raises(ValueError, match="rescale must give 2 positive"):
        continue_curve(f, [0.6 * big, 0.8], settings=st, rescale=lambda u: np.array([0.0, 1.0]))


def test_a_curve_winding_a_whole_turn_in_an_angle_closes():
    # lam = 0.5 sin(theta): in the plane (theta, lam) a wave that never closes, on the circle of
    # theta (an angle) a closed curve: it closes after one turn, with its two folds at lam = +-0.5
    # located once each; without the angle marked it goes round again and again to max_points
    def f(u):
        return np.array([u[1] - 0.5 * np.sin(u[0])])

    st = ContinuationSettings(ds=0.05, ds_max=0.1, max_points=400)
    c = continue_curve(f, [0.0, 0.0], settings=ContinuationSettings(**{**st.__dict__, "periodic": (0,)}),
                       tangent0=np.array([1.0, 0.5]))
    folds = sorted(z.point.lam for z in c.crossings if z.name == "fold")
    assert c.end == "closed"
    np.testing.assert_allclose(folds, [-0.5, 0.5], atol=1e-9)
    assert 2 * np.pi - 0.2 < c.points[-1].x[0] - c.points[0].x[0] < 2 * np.pi + 0.2
    plain = continue_curve(f, [0.0, 0.0], settings=st, tangent0=np.array([1.0, 0.5]))
    assert plain.end == "max_points" and len([z for z in plain.crossings if z.name == "fold"]) > 2


def test_saddle_node_fold_located():
    # x^2 = lam - 0.3: one fold at lam = 0.3, x = 0
    c = continue_curve(lambda u: np.array([u[0] ** 2 - u[1] + 0.3]), [0.5, 0.55],
                       settings=ContinuationSettings(ds=0.05, ds_max=0.1, direction=-1, bounds=(0.0, 2.0)))
    (fold,) = [z for z in c.crossings if z.name == "fold"]
    assert abs(fold.point.lam - 0.3) < 1e-9 and abs(fold.point.x[0]) < 1e-4
    assert c.end == "bound" and c.points[-1].lam == pytest.approx(2.0)


@pytest.mark.parametrize("side", [1, -1])
def test_pitchfork_branch_point_and_switch(side):
    def F(u):
        return np.array([u[0] * (u[1] - 0.2 - u[0] ** 2)])

    c = continue_curve(F, [0.0, -1.0], settings=S)
    (bp,) = [z for z in c.crossings if z.name == "branch"]
    assert abs(bp.point.lam - 0.2) < 1e-9
    other = switch_branch(F, bp, settings=S, side=side)
    x, lam = other.u[:, 0], other.u[:, 1]
    np.testing.assert_allclose(lam, 0.2 + x**2, atol=1e-12)
    assert np.all(np.sign(x) == side) and other.end == "bound"


def test_transcritical_switch_follows_the_other_line():
    def F(u):
        return np.array([u[0] * (u[1] - u[0])])

    c = continue_curve(F, [0.0, -0.7], settings=S)
    (bp,) = [z for z in c.crossings if z.name == "branch"]
    assert abs(bp.point.lam) < 1e-9
    other = switch_branch(F, bp, settings=S)
    np.testing.assert_allclose(other.u[:, 0], other.u[:, 1], atol=1e-12)
    assert other.u[-1, 1] == pytest.approx(1.0)


def test_bad_start_and_settings():
    with pytest.raises(ValueError, match="does not converge"):
        continue_curve(lambda u: np.array([u[0] ** 2 + 1.0 + 0 * u[1]]), [0.0, 0.0])
    with pytest.raises(ValueError, match="ds_min"):
        ContinuationSettings(ds=1.0, ds_max=0.1)


def test_result_json_and_dataset():
    sp = SpecialPoint(type="hopf", parameter="drive.speed", value=150.0, state=np.zeros(2),
                      description="a whirl is born", index=3, frequency=12.0)
    b = Branch(kind="equilibrium", parameter="drive.speed", values=np.array([100.0, 200.0, np.nan]),
               states=np.zeros((3, 2)), stable=np.array([True, False, False]), amplitude=np.array([1e-3, 2e-3, 0]),
               spectrum=np.array([[-1 + 2j], [1 + 0j], [0j]]), period=np.full(3, np.nan), special_points=(sp,))
    d = ContinuationResult((b,), units={"drive.speed": "rad/s"}).to_dict()
    pt = d["branches"][0]["points"]
    assert pt[0] == {"drive.speed": 100.0, "stable": True, "amplitude_m": 1e-3, "max_real_eigenvalue": -1.0}
    assert pt[2]["drive.speed"] is None
    assert d["branches"][0]["special_points"] == [
        {"type": "hopf", "drive.speed": 150.0, "description": "a whirl is born", "frequency_rad_s": 12.0}]
    ds = ContinuationResult((b,), units={"drive.speed": "rad/s"}).to_dataset()
    assert ds["value"].attrs["units"] == "rad/s" and float(ds["spectral_abscissa"][0, 1]) == 1.0
    with pytest.raises(ValueError, match="unknown special point"):
        SpecialPoint(type="cusp", parameter="p", value=0.0, state=np.zeros(1), description="", index=0)
