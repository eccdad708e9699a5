"""The rub case from a case file: ``rotorlab run`` reports the simulated regime with the closed-form
prediction beside it (Black 1968; Choy & Padovan 1987: synchronous full annular rub)."""

from __future__ import annotations

import functools
import math

import pytest
from typer.testing import CliRunner

from rotorlab.analyses import run_case, summarize
from rotorlab.cli import app
from rotorlab.contact import RubRotor, critical_friction, full_rub, no_rub_radius
from rotorlab.io import load_case, parse_case

# the case's rotor, written out: 10 kg, 1e6 N/m (316.2 rad/s), 5 % damping, 0.6 mm eccentricity,
# 1 mm clearance, 1e7 N/m stator, friction 0.02, at 1.5 times the natural frequency
ROTOR = RubRotor(mass=10.0, stiffness=1e6, clearance=1e-3, damping=316.227766, eccentricity=6e-4,
                 stator_stiffness=1e7, friction=0.02, rotor_radius=0.05)  # fmt: skip
SPIN = 474.341649


def _rows():
    results = run_case(load_case("rub-jeffcott"))
    return {r["quantity"]: r for r in summarize(results["full-rub"])}


def test_rub_case_lands_on_the_closed_form_full_rub():
    assert no_rub_radius(ROTOR, SPIN) > ROTOR.clearance  # no contact-free orbit
    (branch,) = full_rub(ROTOR, SPIN)
    rows = _rows()
    assert rows["regime"]["measured"] == "full rub (forward)"
    assert rows["regime"]["closed_form"] == "full rub (forward)"
    radius = rows["whirl radius (mean)"]
    assert radius["closed_form"] == pytest.approx(branch.radius, rel=1e-12)
    assert radius["measured"] == pytest.approx(branch.radius, rel=1e-5)
    force = rows["contact normal force (peak)"]
    assert force["closed_form"] == pytest.approx(branch.normal_force, rel=1e-12)
    assert force["measured"] == pytest.approx(branch.normal_force, rel=1e-3)
    assert rows["whirl speed / spin speed"]["measured"] == pytest.approx(1.0, abs=1e-6)
    mu_c = rows["critical friction of the full rub"]
    assert mu_c["closed_form"] == pytest.approx(critical_friction(ROTOR, SPIN), rel=1e-9)
    assert mu_c["measured"] == 0.02 < mu_c["closed_form"]
    # the same rub in nondimensional units (tests/validation/test_contact_theory.py): mu_c = 0.0484
    assert mu_c["closed_form"] == pytest.approx(0.048375, rel=1e-4)
    assert math.isclose(SPIN / math.sqrt(1e5), 1.5, rel_tol=1e-8)


def test_rotorlab_run_writes_the_regime_and_the_closed_form_in_the_report(tmp_path):
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["run", "rub-jeffcott", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "full rub (forward) (closed forms: full rub (forward))" in result.output
    report = (out / "report.html").read_text()
    assert "closed form" in report and "Black (1968), Choy &amp; Padovan (1987)" in report
    assert (out / "full-rub_orbit.png").exists() and (out / "full-rub.nc").exists()
    # the written result reads back into the same rows and figure (a one-branch list attribute comes
    # back from NetCDF as a scalar)
    from rotorlab.io import load_netcdf
    from rotorlab.plot._rub import rub_orbit_figure

    again = load_netcdf(out / "full-rub.nc")
    rows = {r["quantity"]: r for r in summarize(again)}
    assert rows["regime"]["source"] == "Black (1968), Choy & Padovan (1987)"
    assert rows["whirl radius (mean)"]["closed_form"] == pytest.approx(full_rub(ROTOR, SPIN)[0].radius, rel=1e-12)
    assert len(rub_orbit_figure(again).legends) == 1  # the legend below the orbit, not over it


BAD = """
[model]
type = "rub_rotor"
mass = "10 kg"
stiffness = "1e6 N/m"
clearance = "1 mm"
rotor_radius = "50 mm"
spin_speed = "100 rad/s"
stator_damping = "10 N*s/m"
[[analysis]]
type = "rub"
t_end = "1 s"
window = "2 s"
initial_radius = "2 mm"
"""


def test_bad_rub_case_names_every_problem(tmp_path):
    with pytest.raises(Exception) as err:
        parse_case(BAD, origin="bad.toml")
    text = str(err.value)
    assert "model.stator_damping" in text and "needs an elastic stator" in text
    assert "analysis[0].window" in text and "must be < t_end (1 s)" in text
    path = tmp_path / "bad.toml"
    path.write_text(BAD)
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2 and "Traceback" not in result.output


NO_CONTACT = """
[model]
type = "rub_rotor"
mass = "10 kg"
stiffness = "1e6 N/m"
damping = "316.227766 N*s/m"
eccentricity = "0.1 mm"
clearance = "1 mm"
rotor_radius = "50 mm"
restitution = 0.6
spin_speed = "100 rad/s"
[[analysis]]
type = "rub"
name = "quiet"
t_end = "1 s"
window = "0.1 s"
"""


def test_rigid_stator_below_grazing_is_the_jeffcott_orbit():
    rotor = RubRotor(mass=10.0, stiffness=1e6, clearance=1e-3, damping=316.227766, eccentricity=1e-4, rotor_radius=0.05)
    rows = {r["quantity"]: r for r in summarize(run_case(parse_case(NO_CONTACT, origin="quiet.toml"))["quiet"])}
    assert rows["regime"]["measured"] == "no contact"
    assert rows["regime"]["closed_form"].startswith("no contact")
    # m eps W^2 / |k - m W^2 + i c W| = 1e-4 * 1e5 / |1e6 - 1e5 + 31622.78 i| = 1.1101e-5 m
    assert rows["whirl radius (mean)"]["closed_form"] == pytest.approx(no_rub_radius(rotor, 100.0), rel=1e-12)
    assert rows["whirl radius (mean)"]["closed_form"] == pytest.approx(10.0 / abs(complex(9e5, 31622.7766)), rel=1e-6)
    assert rows["whirl radius (mean)"]["measured"] == pytest.approx(no_rub_radius(rotor, 100.0), rel=1e-3)
    assert rows["contacts begun per second"]["measured"] == 0.0


def test_a_rotor_beyond_a_rigid_stator_is_an_impossible_run():
    """The sanity monitor: a rotor started 0.5 mm beyond a 1 mm rigid clearance (its contact event
    can never fire) is a failed run that says where it was, not a regime."""
    import numpy as np

    from rotorlab.contact import JeffcottRub
    from rotorlab.integrate import SaveAt, Status, solve

    model = JeffcottRub(RubRotor(mass=10.0, stiffness=1e6, clearance=1e-3, rotor_radius=0.05), 100.0)
    y0 = np.array([1.5e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    sol = solve(model, y0, (0.0, 0.01), save_at=SaveAt(ts=np.linspace(0.0, 0.01, 11)))
    assert sol.status == Status.IMPOSSIBLE
    assert "passed through the rigid stator: radius 0.0015 m, 0.0005 m beyond the clearance 0.001 m" in sol.note
    inside = solve(model, model.initial_state((0.9e-3, 0.0)), (0.0, 0.01), save_at=SaveAt(ts=np.linspace(0.0, 0.01, 11)))
    assert inside.status == Status.SUCCESS and inside.note == ""


def test_the_rub_analysis_reports_an_impossible_run_as_failed(monkeypatch):
    import rotorlab.integrate as integrate
    from rotorlab.integrate import Status

    real_solve = integrate.solve

    # wraps: the stand-in keeps the real solve's module, which the name of a generated driver copy
    # hashes (rotorlab.integrate's globals); a function of this test module would give the rub
    # model a driver copy of its own, compiled again
    @functools.wraps(real_solve)
    def impossible(model, y0, t_span, **kw):
        sol = real_solve(model, y0, t_span, **kw)
        fields = {k: getattr(sol, k) for k in sol.__dataclass_fields__}
        return type(sol)(**{**fields, "status": Status.IMPOSSIBLE, "note": "the rotor passed through the rigid stator"})

    monkeypatch.setattr(integrate, "solve", impossible)
    ds = run_case(parse_case(NO_CONTACT, origin="through.toml"))["quiet"]
    assert ds.attrs["status"] == int(Status.IMPOSSIBLE)
    assert ds.attrs["status_message"] == "the rotor passed through the rigid stator"
    assert summarize(ds)[0]["measured"] == "integration failed"
    # the report's box says FAILED with the reason, not a regime or a number
    from rotorlab.report._rub import rub_findings

    found = rub_findings(ds, summarize(ds))
    assert found.verdict.startswith("FAILED: the rotor passed through the rigid stator; closed forms allow: ")
    assert found.numbers == ()
