"""``friction-margin`` (issue 26 item 4): the friction band and its worst residual, against seed 004's
published band and closed forms, checked by simulation.

Seed 004 (Strautmanis, section V, Fig. 5): with R = 0.2 m, R1 = 0.015 m, r = 0.0125 m,
omega = 140 1/s, e = 0.02 m, k = 1e-5 m the ball stops at psi = 3.14156 rad, alpha = 1.56825 rad;
the model's band around the working position is |psi - pi| <= 0.0089 rad (rolling form, the
number ``tests/validation/test_toroidal_seed004.py`` holds), with the closed form
``sin(half band) = k N / (e omega^2 r)``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import build_model
from rotorlab.analyses._friction_margin import _ball_terms, friction_margin
from rotorlab.io import load_case
from rotorlab.models import ConstantSpeed
from rotorlab.models._toroidal_ball import strautmanis_torus

PAPER_PSI = 3.14156  # seed 004 section V


def test_torus_band_against_seed_004():
    model = strautmanis_torus(1e-5)
    ds = friction_margin("toroidal_ball", model, [100.0, 140.0, 200.0])
    lo, hi = ds.band_low.sel(coordinate="psi").values, ds.band_high.sel(coordinate="psi").values
    # the published stopping point lies in the band at the paper's speed
    assert lo[1] < PAPER_PSI - math.pi < hi[1]
    assert hi[1] == pytest.approx(0.0089, abs=1e-4) and -lo[1] == pytest.approx(0.0089, abs=1e-4)
    wp = model.working_point()
    half = math.asin(1e-5 * wp.normal / (0.02 * 140.0**2 * 0.0125))
    assert hi[1] == pytest.approx(half, rel=2e-3)
    # centrifugal drive and rolling resistance both scale with omega^2: the band hardly moves with speed
    np.testing.assert_allclose(hi, hi[1], rtol=2e-3)
    # residual unbalance per kg of ball: the chord rho * 2 sin(band / 2), rho = R + a sin(alpha) = 0.2025 m
    np.testing.assert_allclose(ds.worst_residual.values, 0.2025 * 2.0 * np.sin(0.5 * hi), rtol=2e-3)
    # checked by simulation: released at rest just inside it stays, just outside it rolls
    assert ds.check_inside.values.tolist() == [1, 1, 1] and ds.check_outside.values.tolist() == [1, 1, 1]
    # ten times the rolling friction, ten times the band (seed 004's k = 1e-4 m)
    wide = friction_margin("toroidal_ball", strautmanis_torus(1e-4), [140.0], simulate=False)
    assert float(wide.band_high.sel(coordinate="psi")[0]) == pytest.approx(0.0891, abs=1e-4)


@pytest.fixture(scope="module")
def rotor():
    base = build_model(load_case("autobalancer").model)
    return base


def test_stick_condition_is_the_kernels(rotor):
    # the closed-form stick margin against the kernel's stick_torques at stuck states
    model = replace(rotor, balls=tuple(replace(b, friction=0.05) for b in rotor.balls))
    om = 2.0 * model.critical_speed
    rot = model.with_frame("rotating").with_speed(ConstantSpeed(om))
    rng = np.random.default_rng(3)
    for psi in rng.uniform(-math.pi, math.pi, (6, 2)):
        w, margin = _ball_terms(model, om, psi)
        y = rot.initial_state(psi, rotor="steady")
        y[-2:] = 0.0  # both stuck
        drive, bound, normal, _ = rot.stick_torques(0.0, y)
        assert complex(y[0], y[1]) == pytest.approx(w, rel=1e-12)
        scale = model.balls[0].static_moment * om**2  # torque per metre of w
        np.testing.assert_allclose(margin * scale, np.abs(drive) - bound, atol=1e-9 * scale * 1e-3)


def test_small_friction_band_closed_form(rotor):
    # Small f: ball i sticks while the rotor deflection's component across it is within f l. Two
    # strips of half-width f l whose normals are 120 deg apart (balls at +-120 deg, eta = 1) meet in a
    # parallelogram whose far corner is f l / cos(60 deg) = 2 f l from the centre: worst |w| -> 2 f l.
    f = 1e-3
    model = replace(rotor, balls=tuple(replace(b, friction=f) for b in rotor.balls))
    om = 2.0 * model.critical_speed
    ds = friction_margin("jeffcott_balls", model, [om], grid=241)
    assert float(ds.worst_residual[0]) == pytest.approx(2.0 * f * 0.05, rel=0.03)
    # the band in ball angle: |w| = |H| m l |sum delta_i e^{i psi_i}|, a few degrees here
    assert 1.0 < np.degrees(float(ds.band_high.values[0, 0])) < 10.0
    assert ds.check_inside.values.tolist() == [1] and ds.check_outside.values.tolist() == [1]


def test_worst_residual_is_the_simulated_deflection(rotor):
    # released at rest just inside the band's worst point, the rotor stays at the locked response
    model = replace(rotor, balls=tuple(replace(b, friction=0.01) for b in rotor.balls))
    om = 2.0 * model.critical_speed
    ds = friction_margin("jeffcott_balls", model, [om], grid=121)
    from rotorlab.analyses._shock_margin import balanced_angles
    from rotorlab.integrate import SaveAt, StepControl, solve

    rot = model.with_frame("rotating").with_speed(ConstantSpeed(om))
    psi = balanced_angles(rot, om) + 0.98 * ds.worst_angles.values[0]
    y0 = rot.initial_state(psi, rotor="steady")
    sol = solve(rot, y0, (0.0, 2.0), save_at=SaveAt(ts=[2.0]), control=StepControl(rtol=1e-9, atol=1e-12))
    amp = math.hypot(sol.y_final[0], sol.y_final[1])
    assert np.all(sol.y_final[4:6] == y0[4:6])
    assert amp == pytest.approx(abs(rot.locked_response(psi, om)), rel=1e-9)
    assert amp == pytest.approx(float(ds.worst_residual[0]), rel=0.05)
    assert amp > 1e-4  # a residual deflection of the order of f l (0.5 mm) and more, not a balanced rotor


# --------------------------------------------------------------------------- the same on a machine


def _planar_machine(rotor, coulomb: float):
    """The autobalancer as a planar machine (its right-hand side, tests/unit/test_machine.py) with Coulomb
    friction on both balls."""
    from rotorlab.continuation import as_machine

    m = as_machine(rotor)
    race = m.races[0]
    return replace(m, races=(replace(race, balls=tuple(replace(b, coulomb=coulomb) for b in race.balls)),))


def test_machine_stick_condition_is_the_kernels(rotor):
    # the closed-form stuck-ball margin of a machine against the machine kernel's own stick test
    # (Machine.initial_modes: a ball at rest relative to its race sticks iff the race can hold it),
    # the structure on the locked response; and the locked response is jeffcott_balls' at the same angles
    from rotorlab.analyses._friction_machine import MachineStick
    from rotorlab.analyses._friction_margin import _ball_terms

    om = 2.0 * rotor.critical_speed
    m = _planar_machine(rotor, 0.05).with_drive(ConstantSpeed(om))
    jb = replace(rotor, balls=tuple(replace(b, friction=0.05) for b in rotor.balls))
    stick = MachineStick(m, om)
    lay = m.layout
    rng = np.random.default_rng(5)
    agree = []
    for psi in rng.uniform(-math.pi, math.pi, (12, 2)):
        amp, margin = stick.terms(psi)
        w, jmargin = _ball_terms(jb, om, psi)
        assert amp == pytest.approx(abs(w), rel=1e-9)
        np.testing.assert_allclose(margin, jmargin, atol=1e-12)
        y = np.zeros(lay.n_state)
        y[:2] = stick.coordinates(psi)
        y[2:4] = om * np.array([-y[1], y[0]])
        y[lay.i_phi : lay.i_phi + 2] = psi
        y[lay.i_w : lay.i_w + 2] = om
        modes = m.initial_modes(0.0, y)[lay.i_modes : lay.i_modes + 2]
        if np.all(margin < -1e-9) or np.any(margin > 1e-9):  # clear of the stick boundary
            agree.append(bool(np.all(modes == 0.0)) == bool(np.all(margin < 0.0)))
    assert len(agree) >= 8 and all(agree)


def test_machine_band_is_the_rotor_s(rotor):
    # friction 0.01 at 2 p and 3 p: the planar machine's band (its balls in the mirror arrangement
    # Machine.balanced_angles finds) and worst residual are the rotor's; checked by simulation
    om = [2.0 * rotor.critical_speed, 3.0 * rotor.critical_speed]
    jb = replace(rotor, balls=tuple(replace(b, friction=0.01) for b in rotor.balls))
    a = friction_margin("jeffcott_balls", jb, om, grid=61, simulate=False)
    b = friction_margin("machine", _planar_machine(rotor, 0.01), om, grid=61, simulate=True)
    np.testing.assert_allclose(b.worst_residual.values, a.worst_residual.values, rtol=1e-9)
    np.testing.assert_allclose(b.band_low.values, a.band_low.values[:, ::-1], atol=1e-12)
    np.testing.assert_allclose(b.band_high.values, a.band_high.values[:, ::-1], atol=1e-12)
    assert 1.0e-3 < float(b.worst_residual[0]) < 1.5e-3  # m: 1.21 mm at 2 p
    assert b.check_inside.values.tolist() == [1, 1] and b.check_outside.values.tolist() == [1, 1]
