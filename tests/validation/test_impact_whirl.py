"""Dry-friction backward whirl: flagged and stopped, not integrated into nonsense (seed 001).

In sliding contact the friction ``-f N e_perp`` drives the contact point backwards; the faster it
whirls, the larger the normal force and the friction. Past a threshold nothing in the linear
model limits it. The detection (contact point running backwards in the fixed frame faster than
``whirl_limit``, default 2 omega0) must flag exactly the runs that run away without it.
"""

from dataclasses import replace

import numpy as np

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
    assert stopped.sum() >= 4
    assert np.array_equal(stopped, ran_away)
    # stopped shortly before the blow-up, with the counts up to there
    assert np.all(flagged.t_final.values[stopped] <= free.t_final.values[stopped])
    assert np.all(free.t_final.values[stopped] - flagged.t_final.values[stopped] < 1.0)
    assert np.all(flagged.regime.values[stopped] == 3)
    # the others are identical runs
    assert np.array_equal(flagged.impacts.values[~stopped], free.impacts.values[~stopped])
    assert np.all(flagged.t_final.values[~stopped] == 10.0)


def test_without_friction_there_is_no_backward_whirl():
    ds = impact_sweep(krasnov_crusher(friction=0.0), [3.0], n_sequences=8, t_end=10.0, seed=0)
    assert np.all(ds.whirl.values == 0) and np.all(ds.t_final.values == 10.0)
    assert np.all(ds.regime.values == 2)  # sliding
