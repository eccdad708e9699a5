"""Properties of the impact_rotor model (Hypothesis): energy, no penetration, frame of the guides."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorlab._kernels import impact_rotor as K
from rotorlab.integrate import SaveAt, StepControl, solve
from rotorlab.models import StoneSequence, krasnov_crusher

speeds = st.floats(-0.6, 0.6)


@settings(max_examples=12, deadline=None)
@given(du1=speeds, du2=speeds, dt1=st.floats(-2.0, 2.0), dt2=st.floats(-2.0, 2.0),
       translational=st.booleans())  # fmt: skip
def test_elastic_frictionless_motion_conserves_energy_and_never_penetrates(du1, du2, dt1, dt2, translational):
    model = krasnov_crusher(translational=translational, internal_friction=0.0, restitution=1.0, friction=0.0)
    y0 = model.initial_state(du=(du1, du2), dtilt=(dt1, dt2))
    ts = np.linspace(0.0, 0.5, 101)
    sol = solve(model, y0, (0.0, 0.5), save_at=SaveAt(ts=ts), control=StepControl(rtol=1e-10, atol=1e-14))
    h = model.jacobi_energy(sol.ys)
    assert np.max(np.abs(h - h[0])) <= 1e-7 * max(h[0], 1e-3)
    r = np.hypot(*model.gap_vector(sol.ys).T)
    assert np.max(r) <= model.housing.gap * (1.0 + 1e-9)
    assert sol.y_final[K.E_REST] == 0.0


@settings(max_examples=20, deadline=None)
@given(guide=st.integers(0, 5), n_guides=st.integers(6, 9), mass=st.floats(0.1, 5.0), dt=st.floats(0.0, 0.027))
def test_a_stone_on_guide_j_pushes_like_guide_0_turned_by_its_angle(guide, n_guides, mass, dt):
    base = krasnov_crusher(n_guides=n_guides)
    model = replace(base, sequence=StoneSequence([0.01], [mass], [guide], n_guides))
    p = model.to_array()
    y = model.initial_state()
    y[K.I_BP] = 1  # after the arrival: the stone is on its guide
    fx, fy = K.stone_force(0.01 + dt, y, p)
    a = 2.0 * math.pi * guide / n_guides
    # the same stone on guide 0: rotate back by alpha
    gx, gy = math.cos(a) * fx + math.sin(a) * fy, -math.sin(a) * fx + math.cos(a) * fy
    jx, jy = K.push(160.0 * dt, p)
    scale = mass * 160.0**2 * 0.6
    assert np.allclose([gx, gy], [scale * jx, scale * jy], rtol=1e-12, atol=1e-9)
