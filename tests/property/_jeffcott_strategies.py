"""Hypothesis strategies of a Jeffcott rotor with balls, shared by the property tests.

Each test module picks the ranges its property needs (the steady-motion tests keep the
eccentricity and the ball damping above zero, where the steady motions are isolated).
"""

from __future__ import annotations

from hypothesis import strategies as st

from rotorlab.models import BallParams, RotorParams


def rotors(*, eccentricity: tuple[float, float], damping: tuple[float, float]) -> st.SearchStrategy[RotorParams]:
    """A disc of 0.5-3 kg on a 100-1000 N/m shaft, with ``eccentricity`` (m) and ``damping`` (N s/m) in the ranges."""
    return st.builds(
        RotorParams,
        disc_mass=st.floats(0.5, 3.0),
        eccentricity=st.floats(*eccentricity),
        stiffness=st.floats(100.0, 1000.0),
        damping=st.floats(*damping),
    )


@st.composite
def ball_sets(draw, min_size: int, max_size: int, damping: tuple[float, float]) -> tuple[BallParams, ...]:
    """``min_size`` to ``max_size`` balls of 10-100 g on 50-150 mm, inertia m l^2 times 1-2,
    damping (N m s) in ``damping``."""
    n = draw(st.integers(min_size, max_size))
    out = []
    for _ in range(n):
        m, l = draw(st.floats(0.01, 0.1)), draw(st.floats(0.05, 0.15))
        out.append(BallParams(m, l, inertia=m * l * l * draw(st.floats(1.0, 2.0)), damping=draw(st.floats(*damping))))
    return tuple(out)
