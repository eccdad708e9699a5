"""Issue 28, item 12 (first half): a rub run on a rigid stator with restitution 1 that ends in a
failed integration (here the step budget: with e = 1 the impacts of a pressed rotor never die
out, and the built-in case spent all 10^7 steps on them) lost the whole run to a
ZeroDivisionError. The saved samples after a failed run's end are NaN; the compiled contact law
was called on them, found the centre at the NaN position and divided by its zero radius."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from rotorlab.analyses import run_case, summarize
from rotorlab.contact import JeffcottRub, RubRotor
from rotorlab.integrate import Status
from rotorlab.io import parse_case

# rub-jeffcott's rotor (10 kg, 1e6 N/m, 316 N s/m, 0.6 mm eccentricity, 474 rad/s) on a rigid
# 1 mm stator with restitution 1 and friction 0.3, started at rest at the centre
RIGID_E1 = """
schema_version = 1
name = "rigid-e1"
[model]
type = "rub_rotor"
mass = "10 kg"
stiffness = "1e6 N/m"
damping = "316.227766 N*s/m"
eccentricity = "0.6 mm"
clearance = "1 mm"
friction = 0.3
restitution = 1.0
rotor_radius = "50 mm"
spin_speed = "474.341649 rad/s"
[[analysis]]
type = "rub"
name = "full-rub"
t_end = "0.05 s"
window = "0.02 s"
"""

ROTOR = RubRotor(mass=10.0, stiffness=1e6, clearance=1e-3, damping=316.227766, eccentricity=6e-4,
                 friction=0.3, rotor_radius=0.05)


def test_contact_samples_are_nan_at_a_failed_runs_padding_and_the_rigid_stator_force_elsewhere():
    """Samples as a failed run saves them: two in sliding contact on the rigid stator, one free,
    two NaN rows (after the failure). The normal force is the rigid stator's constraint force
    ``N = m (a_n + v_t^2 / r)`` where in contact, 0 where free, NaN at the padding, never an
    exception (the old code raised ZeroDivisionError at the NaN rows)."""
    w = 474.341649
    model = JeffcottRub(ROTOR, w, restitution=1.0)
    ts = np.array([0.010, 0.011, 0.012, 0.013, 0.014])
    nan = [np.nan] * 9
    # x, y, vx, vy, dissipated, drive work, impacts, peak impulse, mode (+-1 sliding)
    ys = np.array([[1e-3, 0.0, -0.02, 0.3, 0.0, 0.0, 3.0, 0.01, 1.0],
                   [0.6e-3, 0.8e-3, -0.4, 0.3, 0.0, 0.0, 3.0, 0.01, -1.0],
                   [0.5e-3, 0.0, 0.1, 0.1, 0.0, 0.0, 3.0, 0.01, 0.0],
                   nan, nan])
    cs = model.contact_samples(ts, ys)
    assert np.isnan(cs.normal_force[3:]).all()
    assert cs.normal_force[2] == 0.0
    # the same force from the equations of motion (no contact law): the free acceleration
    # -k z/m - c v/m + eps W^2 e^{iWt} along the outward normal, plus the centripetal v_t^2 / r
    m, k, c, eps = ROTOR.mass, ROTOR.stiffness, ROTOR.damping, ROTOR.eccentricity
    x, y, vx, vy = (ys[:2, i] for i in range(4))
    r = np.hypot(x, y)
    nx, ny = x / r, y / r
    ax = (-k * x - c * vx) / m + eps * w * w * np.cos(w * ts[:2])
    ay = (-k * y - c * vy) / m + eps * w * w * np.sin(w * ts[:2])
    vt = -vx * ny + vy * nx
    expected = m * (ax * nx + ay * ny + vt * vt / r)
    assert cs.normal_force[:2] == pytest.approx(expected, rel=1e-12)
    # row 0: 10 (-100 + 0.632 + 0.6e-3 W^2 cos(4.7434) + 0.3^2 / 1e-3) = 10 (-100 + 0.632 + 4.188 + 90)
    assert cs.normal_force[0] == pytest.approx(-51.79502721592854, rel=1e-9)


def test_a_failed_rub_run_on_a_rigid_stator_with_restitution_one_is_reported_failed_not_lost(monkeypatch):
    """The rub analysis of the case, its integration ended by the step budget (a real failure of
    the real integrator, with a budget small enough for a test): the result says FAILED with the
    integrator's reason; on the old code the analysis raised ZeroDivisionError."""
    import rotorlab.integrate as integrate

    real_solve = integrate.solve

    # wraps: keeps the real solve's module (the generated driver copy's name hashes it)
    @functools.wraps(real_solve)
    def budget(model, y0, t_span, **kw):
        kw["control"] = dataclasses.replace(kw["control"], max_steps=2000)
        return real_solve(model, y0, t_span, **kw)

    monkeypatch.setattr(integrate, "solve", budget)
    ds = run_case(parse_case(RIGID_E1, origin="rigid-e1.toml"))["full-rub"]
    assert ds.attrs["status"] == int(Status.MAX_STEPS)
    assert ds.attrs["rigid_stator"] == 1
    rows = summarize(ds)
    assert rows[0]["measured"] == "integration failed"
    assert len(rows) == 1  # no measured numbers from a failed run
    from rotorlab.report._rub import rub_findings

    found = rub_findings(ds, rows)
    assert found.verdict.startswith(f"FAILED: {ds.attrs['status_message']}; closed forms allow: ")
    assert ds.attrs["status_message"] == "maximum number of steps reached"
    # the samples after the failure hold no state: NaN positions, mode marked as such
    after = ds.time.values > ds.attrs["t_final"]
    assert after.any() and np.isnan(ds.x.values[after]).all()
    assert (ds["mode"].values[after] == ds["mode"].attrs["no_state"]).all()
