"""Rub-regime maps from a case file (``rub-map`` on the sweep engine): every point where the
closed forms allow only one regime shows that regime (Black 1968; Choy & Padovan 1987)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rotorlab.analyses import run_analysis, summarize
from rotorlab.analyses._rub import rub_prediction
from rotorlab.contact import RubRegime, RubRotor, no_rub_radius
from rotorlab.io import CaseError, load_case, parse_case

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
    rows = {r["regime"]: r for r in summarize(ds)}
    assert set(rows) == {"no contact", "full rub (forward)"}
    assert sum(r["points"] for r in rows.values()) == 63


def test_bad_map_entries_name_the_key():
    text = load_case("rub-jeffcott").text
    with pytest.raises(CaseError, match="exactly one of clearance, eccentricity or unbalance"):
        parse_case(text.replace('clearance = ["0.5 mm", "2 mm", 7]', 'clearance = ["0.5 mm", "2 mm", 7]\neccentricity = ["0 mm", "1 mm", 2]'))
    with pytest.raises(CaseError, match=r"analysis\[1\].unbalance"):
        parse_case(text.replace('clearance = ["0.5 mm", "2 mm", 7]', 'unbalance = ["0 kg*mm", "1 kg*mm", 2]'))
