"""Rub-regime maps from a case file (``rub-map`` on the sweep engine): every point where the
closed forms allow only one regime shows that regime (Black 1968; Choy & Padovan 1987)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import run_analysis, summarize
from rotorlab.analyses._rub import rub_prediction
from rotorlab.contact import RubRegime, RubRotor, full_rub, no_rub_radius
from rotorlab.io import CaseError, load_case, parse_case
from rotorlab.report._rub import rub_map_findings

ROTOR = RubRotor(mass=10.0, stiffness=1e6, clearance=1e-3, damping=316.227766, eccentricity=6e-4,
                 stator_stiffness=1e7, friction=0.02, rotor_radius=0.05)  # fmt: skip


def test_the_speed_by_clearance_map_agrees_with_the_closed_forms():
    case = load_case("rub-jeffcott")
    ds = run_analysis(case.model, case.analysis("map"))
    assert ds.regime.shape == (9, 7) and np.all(ds.status.values == 0)
    single = 0
    for i, w in enumerate(ds.spin_speed.values):
        q0 = no_rub_radius(ROTOR, float(w))
        assert ds.grazing_boundary.values[i] == pytest.approx(q0, rel=1e-12)
        for j, d in enumerate(ds.clearance.values):
            allowed = rub_prediction(replace(ROTOR, clearance=float(d)), float(w))["regimes"]
            label = RubRegime(int(ds.regime.values[i, j])).label
            if len(allowed) == 1:
                single += 1
                assert label == allowed[0], (w, d, label, allowed)
    assert single >= 30  # most of the map is decided by the closed forms alone
    assert ds.attrs["closed_form_decided"] == ds.attrs["closed_form_agree"] == single
    (finding,) = rub_map_findings(ds, summarize(ds)).numbers
    assert finding == (f"at the {single} points where the closed forms allow one regime, the map shows it at {single}; "
                       f"at the other {63 - single} they allow several (coexistence: the map shows where the runs "
                       "land) or none, or the run failed")
    rows = {r["regime"]: r for r in summarize(ds)}
    assert set(rows) == {"no contact", "full rub (forward)"}
    assert sum(r["points"] for r in rows.values()) == 63


def test_bad_map_entries_name_the_key():
    text = load_case("rub-jeffcott").text
    with pytest.raises(CaseError, match="exactly one of clearance, eccentricity or unbalance"):
        parse_case(text.replace('clearance = ["0.5 mm", "2 mm", 7]', 'clearance = ["0.5 mm", "2 mm", 7]\neccentricity = ["0 mm", "1 mm", 2]'))
    with pytest.raises(CaseError, match=r"analysis\[1\].unbalance"):
        parse_case(text.replace('clearance = ["0.5 mm", "2 mm", 7]', 'unbalance = ["0 kg*mm", "1 kg*mm", 2]'))


def test_the_speed_by_eccentricity_map_changes_regime_at_the_grazing_eccentricity():
    """rub_rotor's second axis is the eccentricity: below the critical speed (316 rad/s) the map
    is no contact up to the eccentricity whose no-rub orbit eps w^2 m / |k - m w^2 + i c w| just
    reaches the clearance, and full rub with the closed-form contact force beyond it."""
    text = load_case("rub-jeffcott").text.replace('clearance = ["0.5 mm", "2 mm", 7]',
                                                  'eccentricity = ["0.2 mm", "1.8 mm", 9]\nsamples = 100')
    text = text.replace('spin_speed = ["200 rad/s", "600 rad/s", 9]', 'spin_speed = ["200 rad/s", "300 rad/s", 3]')
    case = parse_case(text)
    ds = run_analysis(case.model, case.analysis("map"))
    m, k, c, delta = ROTOR.mass, ROTOR.stiffness, ROTOR.damping, ROTOR.clearance
    assert ds.regime.shape == (3, 9) and np.all(ds.status.values == 0)
    # the grazing lines are in the unit of the axis they bound (SI: m)
    assert ds.grazing_boundary.attrs["units"] == ds.grazing_curve.attrs["units"] == ds.eccentricity.attrs["units"] == "m"
    for i, w in enumerate(ds.spin_speed.values):
        grazing = delta * abs(k - m * w**2 + 1j * c * w) / (m * w**2)
        assert ds.grazing_boundary.values[i] == pytest.approx(grazing, rel=1e-9)
        for j, eps in enumerate(ds.eccentricity.values):
            label = RubRegime(int(ds.regime.values[i, j]))
            assert label == (RubRegime.NO_CONTACT if eps < grazing else RubRegime.FULL_RUB), (w, eps)
            if label == RubRegime.FULL_RUB:
                (branch,) = full_rub(replace(ROTOR, eccentricity=float(eps)), float(w))
                assert ds.peak_force.values[i, j] == pytest.approx(branch.normal_force, rel=2e-3), (w, eps)
    assert [int((ds.regime.values[i] == RubRegime.NO_CONTACT).sum()) for i in range(3)] == [7, 3, 0]
    assert ds.attrs["closed_form_decided"] == ds.attrs["closed_form_agree"] == 27
