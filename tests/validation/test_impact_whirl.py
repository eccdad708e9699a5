"""Dry-friction backward whirl: flagged and stopped, not integrated into nonsense (seed 001).

In sliding contact the friction ``-f N e_perp`` drives the contact point backwards; the faster it
whirls, the larger the normal force and the friction. Past a threshold nothing in the linear
model limits it. The detection (contact point running backwards in the fixed frame faster than
``whirl_limit``, by default the theory's rolling speed ``r_P sin(beta) omega0 / Delta`` where the
slip the sliding law assumes vanishes: Black 1968, Crandall 1990) must flag exactly the runs that
run away without it, and count their impacts the same whichever speed stops them.
"""

import math

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import impact_sweep
from rotorlab.models import krasnov_crusher


def test_detection_flags_exactly_the_runs_that_run_away():
    base = krasnov_crusher()
    kw = dict(n_sequences=8, t_end=10.0, seed=0)
    flagged = impact_sweep(base, [2.0, 3.0], **kw)
    free = impact_sweep(replace(base, housing=replace(base.housing, whirl_limit=1e12)), [2.0, 3.0], **kw)
    stopped = flagged.whirl.values == 1
    # without the limit the same runs end with a whirl of 1e12 rad/s (or the integrator gives up)
    ran_away = (free.whirl.values == 1) | (free.status.values < 0)
    assert stopped.sum() >= 3
    assert np.array_equal(stopped, ran_away)
    # stopped shortly before the blow-up, with the counts up to there
    assert np.all(flagged.t_final.values[stopped] <= free.t_final.values[stopped])
    assert np.all(free.t_final.values[stopped] - flagged.t_final.values[stopped] < 1.0)
    assert np.all(flagged.regime.values[stopped] == 3)
    # the others are identical runs
    assert np.array_equal(flagged.impacts.values[~stopped], free.impacts.values[~stopped])
    assert np.all(flagged.t_final.values[~stopped] == 10.0)
    # the former empirical stop (2 omega0, tuned on 48 runs) flags the same runs, earlier, with the
    # same impact counts: a sliding contact makes no impacts, so the count does not depend on the stop
    early = impact_sweep(replace(base, housing=replace(base.housing, whirl_limit=2.0 * base.rotor.spin_speed)),
                         [2.0, 3.0], **kw)  # fmt: skip
    assert np.array_equal(early.whirl.values, flagged.whirl.values)
    assert np.all(early.t_final.values[stopped] < flagged.t_final.values[stopped])
    for name in ("impacts", "impacts_all", "slides"):
        assert np.array_equal(early[name].values, flagged[name].values), name
        assert np.array_equal(free[name].values, flagged[name].values), name


def test_the_default_stop_is_the_rolling_speed_of_the_theory():
    from rotorlab.contact import RubRotor, rolling_whirl

    base = krasnov_crusher(translational=True)
    h, w0 = base.housing, base.rotor.spin_speed
    # translational model: w = sin(beta) u, so u whirls on |u| = Delta / sin(beta) and rolls at
    # -(r_P / (Delta / sin(beta))) omega0, the rigid-stator rolling whirl of the closed forms
    rigid = RubRotor(mass=1.0, stiffness=1.0, clearance=h.gap / math.sin(h.cone_angle), rotor_radius=h.radius)
    assert h.rolling_whirl_speed(w0) == pytest.approx(-rolling_whirl(rigid, w0).whirl_speed, rel=1e-14)
    assert base.to_array()[21] == h.rolling_whirl_speed(w0)  # P_WHIRL


def test_without_friction_there_is_no_backward_whirl():
    ds = impact_sweep(krasnov_crusher(friction=0.0), [3.0], n_sequences=8, t_end=10.0, seed=0)
    assert np.all(ds.whirl.values == 0) and np.all(ds.t_final.values == 10.0)
    assert np.all(ds.regime.values == 2)  # sliding


def test_the_stop_is_where_the_slip_of_p_vanishes_which_with_tilt_is_not_the_rolling_speed():
    """The sliding law (friction -f N e_perp) holds while P slides forwards; the stop is the slip
    of P itself (``whirl_stop``). Without tilt the slip vanishes exactly at the whirl speed
    -r_P sin(beta) omega0 / Delta; with tilt, a tilt rate along e_perp that leaves the gap rate
    (and so the whirl speed) unchanged still moves P by (h_P - l_P / sin(beta)) per unit: at
    the rolling speed P still slips, and the stop waits for the slip to vanish."""
    from rotorlab._kernels import impact_rotor as k

    for translational in (True, False):
        model = krasnov_crusher(translational=translational)
        h, w0, p = model.housing, model.rotor.spin_speed, model.to_array()
        sb, lp, hp = math.sin(h.cone_angle), h.lever(), h.height
        roll = -h.rolling_whirl_speed(w0)
        th = 0.7
        e, ep = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
        y = model.initial_state()  # then on the housing, sliding, whirling at the rolling speed
        y[k.U1], y[k.U2] = h.gap / sb * e
        y[k.DU1], y[k.DU2] = (roll - w0) * h.gap / sb * ep  # rotating-frame rate: fixed minus omega0 k x u
        y[k.MODE] = 1.0
        assert k.whirl_speed(y, p) == pytest.approx(roll, rel=1e-12)
        assert k.slip_speed(y, p, *e) == pytest.approx(0.0, abs=1e-12 * h.radius * w0)
        assert k.whirl_stop(y, p, *e) == k.slip_speed(y, p, *e)  # the default stop is the slip
        p_lim = replace(model, housing=replace(h, whirl_limit=-roll)).to_array()
        assert k.whirl_stop(y, p_lim, *e) == pytest.approx(0.0, abs=1e-9 * -roll)  # the threshold, here equal
        if not translational:
            a = 0.01  # rad/s of tilt along e_perp, compensated in u' so that w' is unchanged
            y[k.DT1], y[k.DT2] = a * ep
            y[k.DU1] -= lp / sb * a * ep[0]
            y[k.DU2] -= lp / sb * a * ep[1]
            assert k.whirl_speed(y, p) == pytest.approx(roll, rel=1e-12)
            assert k.whirl_stop(y, p_lim, *e) == pytest.approx(0.0, abs=1e-9 * -roll)
            assert k.whirl_stop(y, p, *e) == pytest.approx((hp - lp / sb) * a, rel=1e-9)


def test_a_forward_sliding_contact_without_a_stone_lifts_off_at_the_closed_form_time():
    """Issue 30: why sliding contact in Fig. 4 lasts only while a stone pushes. Without tilt
    (the case ``krasnov-crusher-translational``, gamma = 0.5, f = 0.3) and without stones, P
    sliding forwards on the housing at radius Delta obeys m Delta Omega' = -f N - (c gamma /
    omega0) Delta Omega (friction and the non-rotating membranes' damping), with
    N = (m Omega^2 - c) Delta: the whirl Omega slows from omega0 (whirling with a stone's push)
    and the rotor lifts off where N = 0, Omega = sqrt(c / m) = 100.65 rad/s, after
    T = int dOmega / (f (Omega^2 - c/m) + c gamma Omega / (m omega0)) = 10.45 ms."""
    from scipy.integrate import quad

    from rotorlab._kernels import impact_rotor as k
    from rotorlab.analyses import impact_model
    from rotorlab.analyses._impacts import _control
    from rotorlab.integrate import SaveAt, solve_ensemble
    from rotorlab.io import load_case

    model = impact_model(load_case("krasnov-crusher-translational").model)
    h, r = model.housing, model.rotor
    w0, m, c, f = r.spin_speed, r.mass, r.stiffness_1 + r.stiffness_2, h.friction
    d = c * r.internal_friction / w0
    wc = math.sqrt(c / m)
    t_lift = quad(lambda om: 1.0 / (f * (om * om - wc * wc) + d * om / m), wc, w0, epsabs=0, epsrel=1e-12)[0]
    assert wc == pytest.approx(100.65, abs=0.01) and t_lift == pytest.approx(10.45e-3, abs=0.01e-3)
    y = model.initial_state()
    y[k.U1] = h.gap  # on the housing at angle 0, whirling forwards at omega0 in the fixed frame:
    y[k.DU1], y[k.DU2] = 0.0, 0.0  # at rest in the rotating frame
    y[k.MODE] = 1.0
    ts = np.linspace(0.0, 2 * t_lift, 4001)
    sol = solve_ensemble(model, y, (0.0, 2 * t_lift), save_at=SaveAt(ts=ts),
                         control=_control(1e-10, 1e-13), threads=1)  # fmt: skip
    mode = sol.ys[0][:, k.MODE]
    assert mode[0] == 1.0 and mode[-1] == 0.0
    t_off = ts[np.argmax(mode == 0.0)]
    assert t_off == pytest.approx(t_lift, abs=ts[1] + 1e-3 * t_lift)
    assert sol.y_final[0][k.N_IMP] == 0  # lifted off, not bounced
