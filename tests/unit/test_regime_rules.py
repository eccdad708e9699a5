"""One regime classifier: seed 001's labels and the rub maps' regimes are ``regime_codes`` under two
rules, and each rule reproduces the decision its analysis made before they were shared."""

import numpy as np

from rotorlab.analyses._impacts import (REGIMES, SEED001_RULE, SLIDING_CONVENTIONS, SLIDING_FRACTION, classify_impacts,
                                        impact_features)
from rotorlab.contact import WINDOW_RULE, RubRegime, regime_codes


def _seed_rule_before(impacts, sliding_time, duration, whirl, status, fraction):
    """Seed 001's rule as its analysis stated it (rotorlab.analyses._impacts, issue 14); sliding
    needs sliding contact also at fraction 0 (the paper's convention, issue 30)."""
    code = np.where(impacts > 0, 1, 0)
    code = np.where((sliding_time > 0) & (sliding_time >= fraction * duration), 2, code)
    code = np.where((impacts == 0) & (sliding_time == 0), 0, code)
    code = np.where(whirl > 0, 3, code)
    return np.where(status < 0, -1, code)


def _window_rule_before(onsets, cf, wr, rf):
    """The window rule of ``rub_features`` as it was written before sharing."""
    if cf == 0.0 and onsets == 0:
        return RubRegime.NO_CONTACT
    if cf < 1.0 or onsets > 0:
        return RubRegime.IMPACTS
    if wr > 0.0:
        return RubRegime.FULL_RUB
    return RubRegime.BACKWARD_ROLLING if rf >= 0.5 else RubRegime.BACKWARD_SLIDING


def test_seed001_labels_are_the_general_regimes_under_the_seed_rule():
    rng = np.random.default_rng(16)
    n = 20000
    impacts = rng.integers(0, 4, n) * rng.integers(0, 2, n)
    duration = rng.choice([10.0, 3.7, 0.5], n)
    sliding = duration * rng.choice([0.0, 0.005, 0.02, 0.3, 1.0], n) * rng.integers(0, 2, n)
    whirl = (rng.random(n) < 0.2).astype(int)
    status = rng.choice([0, 1, -2], n)
    for fraction in (0.02, 0.0, 0.5):
        got = classify_impacts(impacts, sliding, duration, whirl, status, fraction)
        assert np.array_equal(got, _seed_rule_before(impacts, sliding, duration, whirl, status, fraction))
    # the labels are the general regimes, code for code
    assert [RubRegime(c) for c in range(4)] == [RubRegime.NO_CONTACT, RubRegime.IMPACTS, RubRegime.FULL_RUB,
                                                RubRegime.BACKWARD_ROLLING]  # fmt: skip
    assert REGIMES == ("none", "rebounds", "sliding", "backward_whirl")
    f = impact_features(impacts, sliding, duration, whirl)
    assert np.array_equal(f["impact_rate"], impacts / duration)
    assert np.array_equal(regime_codes(impacts, f["contact_fraction"], f["whirl_ratio"], f["rolling_fraction"],
                                       status, SEED001_RULE),
                          classify_impacts(impacts, sliding, duration, whirl, status))  # fmt: skip


def test_window_rule_is_the_rub_map_rule():
    rng = np.random.default_rng(7)
    for _ in range(5000):
        onsets = int(rng.integers(0, 3)) * int(rng.integers(0, 2))
        cf = float(rng.choice([0.0, 0.3, 1.0]))
        wr = float(rng.choice([-0.4, 0.0, 0.7]))
        rf = float(rng.choice([0.0, 0.5, 0.9]))
        assert int(regime_codes(onsets, cf, wr, rf, 0, WINDOW_RULE)) == _window_rule_before(onsets, cf, wr, rf)
    assert int(regime_codes(0, 1.0, 0.3, 0.0, -1)) == RubRegime.FAILED


def test_the_papers_sliding_convention_labels_any_sliding_episode_and_only_those():
    # issue 30: sliding_fraction 0 (SLIDING_CONVENTIONS["paper"]) is "slides on the housing for
    # some interval of time"; before, a fraction of 0 made every run with an impact "sliding"
    impacts, sliding = [7, 7, 0], [0.0, 1e-4, 0.0]
    assert classify_impacts(impacts, sliding, 2.0, 0, 0, SLIDING_CONVENTIONS["paper"]).tolist() == [1, 2, 0]
    assert classify_impacts(impacts, sliding, 2.0, 0, 0).tolist() == [1, 1, 0]  # 0.005 % < 0.1 %
    assert SLIDING_FRACTION == SLIDING_CONVENTIONS["default"] == 0.001
