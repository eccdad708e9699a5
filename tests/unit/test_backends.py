"""The backend value of ``solve_ensemble``: ``Lanes(8)`` and ``Scalar()`` select the same compiled
drivers as the older ``lanes=8`` / ``lanes=None`` (same bits), a registered backend is selected
by name and reported in ``EnsembleSolution.driver``, and bad values are refused up front.

Only the oscillator's default drivers are used (width 8 and scalar), which the doctests and
``test_lanes.py`` compile anyway: this file adds no driver copy to the suite's compile budget.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorlab.integrate import BACKENDS, Lanes, Scalar, StepControl, register_backend, solve_ensemble
from rotorlab.integrate import _drivers
from rotorlab.models.examples import HarmonicOscillator

OSC = HarmonicOscillator(frequency=2.0)
Y0 = np.random.default_rng(7).normal(size=(11, 2))  # not a multiple of 8: a partly filled lane group
CONTROL = StepControl(rtol=1e-9, atol=1e-12)


def _run(**kw):
    return solve_ensemble(OSC, Y0, (0.0, 3.0), control=CONTROL, **kw)


def test_backend_values_are_the_lanes_spellings_bit_for_bit():
    lanes = _run(backend=Lanes(8))
    scalar = _run(backend=Scalar())
    assert (lanes.driver, scalar.driver) == ("lanes8", "scalar")
    np.testing.assert_array_equal(lanes.y_final, _run(lanes=8).y_final)
    np.testing.assert_array_equal(scalar.y_final, _run(lanes=None).y_final)
    np.testing.assert_array_equal(lanes.y_final, scalar.y_final)  # the lane driver's contract
    # the closed form of the oscillator, so that the comparison is not of two wrong answers
    w = OSC.frequency  # rad/s
    exact = Y0[:, 0] * np.cos(w * 3.0) + Y0[:, 1] / w * np.sin(w * 3.0)
    np.testing.assert_allclose(scalar.y_final[:, 0], exact, atol=1e-7)


def test_auto_picks_lanes_for_an_ensemble_and_scalar_for_one_trajectory():
    assert _run().driver == f"lanes{_drivers.DEFAULT_LANES}"
    one = solve_ensemble(OSC, Y0[0], (0.0, 1.0), control=CONTROL)
    assert one.driver == "scalar"
    assert _run(backend="scalar").driver == "scalar"
    assert _run(backend="lanes").driver == f"lanes{_drivers.DEFAULT_LANES}"


def test_a_registered_backend_is_selected_by_name(monkeypatch):
    calls = []

    class Counting:
        name = "counting"

        def driver(self, kernels, serial):
            calls.append(serial)
            return Scalar().driver(kernels, serial)

    monkeypatch.setitem(BACKENDS, "counting", Counting)
    sol = _run(backend="counting", threads=1)
    assert sol.driver == "counting" and calls == [True]
    np.testing.assert_array_equal(sol.y_final, _run(backend=Scalar()).y_final)


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"backend": "gpu"}, "unknown backend 'gpu'"),
        ({"backend": Lanes(8), "lanes": 8}, "not both"),
        ({"backend": "scalar", "lanes": None}, "not both"),
        ({"backend": 3.0}, "backend must be"),
    ],
)
def test_bad_backends_are_refused(kw, message):
    with pytest.raises((ValueError, TypeError), match=message):
        _run(**kw)


def test_bad_lane_width_and_backend_name():
    with pytest.raises(ValueError, match=r"\[2, 64\]"):
        Lanes(1)
    with pytest.raises(ValueError, match="identifier"):
        register_backend("auto", Scalar)
