"""``jeffcott_balls`` on the project's benchmark problem (:data:`rotorlab.models.BENCHMARK`), physics check.

The benchmark's published behaviour (bench/README.md): with rtol 1e-8, atol 1e-10 and 2000
revolutions, every off-diagonal grid point balances (final amplitude <= about 2e-9) and the
diagonal phi1 = phi2 (the two balls move together and cannot balance) ends at amplitude 0.0357191.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.models import BENCHMARK


def test_benchmark_physics_check():
    from rotorlab.integrate import StepControl, solve_ensemble

    bench = BENCHMARK
    model = bench.model()
    assert model.total_mass == pytest.approx(bench.total_mass, rel=1e-15)
    assert model.imbalance == pytest.approx(bench.unbalance, rel=1e-15)
    idx = np.concatenate([bench.subset_indices(4, offdiag=True), [37 * bench.n_grid + 37]])
    y0 = bench.initial_state(idx)
    np.testing.assert_array_equal(model.initial_state(y0[0, 4:6])[4:], y0[0, 4:])  # same layout
    sol = solve_ensemble(model, y0, (0.0, bench.t_end), control=StepControl(rtol=bench.rtol, atol=bench.atol))
    assert np.all(sol.status == 0)
    amplitude = np.hypot(sol.y_final[:, 0], sol.y_final[:, 1])
    assert np.all(amplitude[:-1] < 3e-9)
    assert amplitude[-1] == pytest.approx(0.0357191, abs=1e-7)
