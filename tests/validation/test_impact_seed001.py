"""Seed 001, section 5: the stone-crusher rotor's regimes and impact counts (Krasnov et al. 2003).

The paper's results come from one random stone sequence each and depend on parameters it does
not give (start radius of a stone on its guide, number of guides, guide sequence); here every
number is a median or a fraction over many seeded sequences with the documented defaults, and
the comparison with the printed numbers is stated with the factor it holds to.

Printed table (impacts in 10 s at Delta t = 0.035 s)::

    m_q (kg)  0.5  0.6  0.7  0.8  0.9  1.0  3.0
    N         0    2    12   23   43   400  34000 ("sliding, a series of very frequent impacts")
"""

import numpy as np
import pytest

from rotorlab.analyses import REGIMES, SLIDING_CONVENTIONS, classify_impacts, impact_sweep
from rotorlab.models import krasnov_crusher

PAPER = {0.5: 0, 0.6: 2, 0.7: 12, 0.8: 23, 0.9: 43, 1.0: 400}


@pytest.fixture(scope="module")
def table():
    masses = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 2.0, 3.0]
    return impact_sweep(krasnov_crusher(), masses, n_sequences=16, t_end=10.0, seed=100)


def _fraction(ds, mass, regime):
    i = int(np.argmin(np.abs(ds.value.values - mass)))
    return float(ds.regime_fraction.values[i, REGIMES.index(regime)])


def test_section5_parameters():
    m = krasnov_crusher()
    assert m.housing.lever() == pytest.approx(0.625 * np.cos(np.radians(55)) - 0.2 * np.sin(np.radians(55)))
    assert m.rotor.membrane_offset == pytest.approx(0.075)
    # 28 stones have fallen in the first second (Fig. 3: "28 камней")
    assert len(m.with_stones(1.0, seed=0).sequence) == 28


def test_fig3_no_impact_in_the_first_second_then_impacts(table):
    ds = impact_sweep(krasnov_crusher(), [0.7], n_sequences=16, t_end=1.0, seed=100)
    # the paper's sequence had no impact in the first second; so have about half of ours
    assert (ds.impacts.values[0] == 0).mean() >= 0.4
    # and over 10 s every sequence strikes the housing, with rebounds only
    assert _fraction(table, 0.7, "rebounds") == 1.0


def test_table_impacts_grow_with_stone_mass_as_printed(table):
    med = table.impacts_median.values
    masses = table.value.values
    light = masses <= 1.0
    assert np.all(np.diff(med[light]) > 0)  # strictly growing from 0.5 to 1.0 kg
    assert med[0] <= 2  # 0.5 kg: (almost) no impacts
    for m, n in PAPER.items():
        if n:
            got = med[np.argmin(np.abs(masses - m))]
            assert n / 3.5 <= got <= 3.5 * n, (m, got, n)  # within a factor 3.5 of the table


def test_three_regimes_appear_as_stone_mass_grows(table):
    assert _fraction(table, 0.5, "none") >= 0.25
    assert _fraction(table, 0.7, "rebounds") == 1.0
    assert _fraction(table, 0.8, "rebounds") >= 0.5
    # under the default convention (sustained sliding contact >= 0.1 % of the run) most runs
    # slide from 1 kg on (not yet at 0.9 kg), where the printed count jumps from 43 to 400
    assert _fraction(table, 0.9, "sliding") <= 0.5 < _fraction(table, 1.0, "sliding")
    assert _fraction(table, 2.0, "sliding") >= 0.75
    # at 3 kg ("sliding, a series of very frequent impacts") every sequence is in sustained
    # contact: most slide for the 10 s (~950 impacts, median), some run into the dry-friction
    # backward whirl, where they are stopped (4 of 16 with these seeds)
    assert _fraction(table, 3.0, "sliding") >= 0.5
    assert 0.1 <= _fraction(table, 3.0, "backward_whirl") <= 0.5
    assert _fraction(table, 3.0, "rebounds") == 0.0
    assert 600 <= table.impacts_median.values[-1] <= 1500
    assert table.max_penetration.values.max() < 1e-6 * 4.5e-3


def _fig4_case():
    from rotorlab.analyses import impact_model
    from rotorlab.io import load_case

    return impact_model(load_case("krasnov-crusher-translational").model)


FIG4_MASSES = [1.3, 1.8, 2.3, 3.0, 3.75, 5.0]


@pytest.fixture(scope="module")
def fig4():
    """Fig. 4 (Delta t = 0.07 s, gamma = 0.5, k = 0.7, f = 0.3, 2 s) from the case
    ``krasnov-crusher-translational``, 16 seeded sequences (seeds 0-15) per stone mass."""
    return impact_sweep(_fig4_case(), FIG4_MASSES, n_sequences=16, t_end=2.0, seed=0)


def _onset(sliding: np.ndarray) -> float:
    """First stone mass of FIG4_MASSES at which most runs (> 8 of 16) are ``sliding``."""
    most = np.flatnonzero(sliding.mean(axis=1) > 0.5)
    return FIG4_MASSES[most[0]] if most.size else np.inf


def test_fig4_translational_regimes(fig4):
    """"at 1.3 kg no impacts, at 3 kg the sliding regime begins, at 5 kg it is strongly
    expressed". Sustained contact begins between 2.3 and 3 kg (no run touches in sustained
    contact at 2.3 kg, most do at 3 kg), and at 5 kg every run slides, with 200-350 impacts
    (median; every located impact counted) where an independent event-located simulation of
    the same equations finds about 250 and all 16 sliding. Landing the stones at 0.15 m instead
    (the former default) no run slides for 2 % of the run at 5 kg (~150 impacts): see
    dev/crusher_choices.py."""
    ds = fig4
    assert _fraction(ds, 1.3, "none") == 1.0
    assert _fraction(ds, 1.8, "rebounds") == 1.0
    touched = (ds.sliding_time.values > 0).mean(axis=1)
    assert touched[2] < 0.25 and touched[3] >= 0.5, touched
    assert _fraction(ds, 5.0, "sliding") >= 0.75
    med = ds.impacts_median.values
    assert np.all(np.diff(med[:4]) > 0) and med[-1] > med[-2] and 200 <= med[-1] <= 350, med
    assert np.array_equal(ds.impacts.values, ds.impacts_all.values)  # every located impact counts
    assert ds.sliding_time_median.values[-1] > 0.02 * 2.0


def test_fig4_sliding_onset_under_the_default_convention(fig4):
    """Issue 30: under the default ``sliding`` convention (sustained slipping contact for
    >= 0.1 % of the run) the first stone mass where most of 16 seeded runs slide lies within a
    factor 1.3 of the paper's 3 kg ("at 3 kg the sliding regime begins"), and at 5 kg ("strongly
    expressed") most runs slide (an independent simulation: 16 of 16). The paper's own
    convention (any sustained sliding episode) gives the same onset; the former 2 % puts it at
    5 kg (at 4 kg no run slides for 40 ms although 15 of 16 touch): the label, not the motion,
    moved the onset."""
    ds = fig4
    sliding = ds.regime.values == REGIMES.index("sliding")
    assert 3.0 / 1.3 <= _onset(sliding) <= 3.0 * 1.3, sliding.sum(axis=1)
    assert sliding[-1].mean() >= 0.75
    args = (ds.impacts.values, ds.sliding_time.values, ds.t_final.values, ds.whirl.values, ds.status.values)
    paper = classify_impacts(*args, SLIDING_CONVENTIONS["paper"]) == REGIMES.index("sliding")
    assert _onset(paper) == _onset(sliding) and paper[-1].all()
    noticeable = classify_impacts(*args, SLIDING_CONVENTIONS["noticeable"]) == REGIMES.index("sliding")
    assert _onset(noticeable) == 5.0
    # the convention only labels: no run without sustained contact is sliding under any of them
    assert not paper[ds.sliding_time.values == 0].any()


def test_fig5_friction_losses_rise_earlier_with_tilt():
    # Fig. 5: Delta t = 0.07 s, gamma = 0.3, k = 0.7, f = 0.3, 10 s; curve 1 (with tilt) rises
    # at much smaller stone masses than curve 2 (translational)
    kw = dict(interval=0.07, internal_friction=0.3, restitution=0.7, friction=0.3)
    masses = [1.0, 2.0, 3.0, 5.0]
    gen = impact_sweep(krasnov_crusher(**kw), masses, n_sequences=8, t_end=10.0, seed=100)
    tra = impact_sweep(krasnov_crusher(translational=True, **kw), masses, n_sequences=8, t_end=10.0, seed=100)
    eg, et = gen.eta_median.values, tra.eta_median.values
    assert np.all(eg > et)
    assert np.all(np.diff(et) > 0)
    assert eg[1] > 1.0 > et[1]  # at 2 kg friction costs more than the stones only with tilt
    assert et[-1] > 1.0  # the translational rotor gets there at 5 kg (sliding)


def test_tilt_vibrations_decay_much_slower_than_translational_ones():
    # Section 5: "the tilt vibrations decay much more slowly than the translational ones"
    # (hyperboloidal precession). Slowest decay rate of the free rotor, with and without tilt:
    gen = np.linalg.eigvals(krasnov_crusher().state_matrix()).real
    tra = np.linalg.eigvals(krasnov_crusher(translational=True).state_matrix())
    tra = tra[np.abs(tra) > 0].real
    assert -gen.max() == pytest.approx(0.035, abs=0.001)  # 1/s: the slow backward tilt whirl
    assert -tra.max() == pytest.approx(6.44e6 * 0.2 / 160.0 / (2 * 635.7), rel=1e-9)  # c gamma / (2 m w0)
    assert -tra.max() / -gen.max() > 100


def test_translational_amplitude_is_smaller_than_with_tilt():
    # Section 5 says "several times smaller" at otherwise equal conditions; with this model and
    # the documented defaults the largest |w| (no housing, 0.7 kg stones, 5 s, 4 sequences) is
    # smaller by a factor of 1.1 to 1.5 only -- the claim holds in direction, not in size.
    from dataclasses import replace

    from rotorlab.analyses import impact_run

    ratios = []
    for seed in range(4):
        amp = []
        for tr in (False, True):
            m = krasnov_crusher(translational=tr)
            m = replace(m, housing=replace(m.housing, gap=1.0))
            ds = impact_run(m, t_end=5.0, seed=seed, n_save=5001)
            amp.append(float(np.hypot(ds.p_x, ds.p_y).max()))
        ratios.append(amp[0] / amp[1])
    assert all(1.05 < r < 1.6 for r in ratios), ratios
