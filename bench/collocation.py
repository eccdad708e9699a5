"""Benchmark: one periodic orbit by multiple shooting against orthogonal collocation (issue 25).

"Periodic orbits ... by multiple shooting on the compiled integrator or by collocation: measure
and choose." The same orbit is solved from the same rough guess by both methods, and each
result's period is compared with a reference:

- Van der Pol, mu = 1 (:class:`rotorlab.models.examples.PlanarOscillator`): the published period
  6.6632868593231301896 (Grasman 1987);
- ``zhakash-k2``'s whirl at 1.6 p in the co-rotating frame (both balls lagging, one turn back
  per period): reference the shooting solution at rtol 1e-12 with 10 segments, which the
  finest collocation meets (the table says by how much).

The guess: the orbit integrated once at rtol 1e-4 from a state near it, with the period off by
1e-3. Shooting: :func:`rotorlab.continuation.find_periodic_orbit` (5 segments, rtol 1e-9, its
defaults); collocation: :func:`rotorlab.continuation._collocation.collocate_orbit` (Gauss points,
uniform mesh of N intervals, degree 4). CPU seconds of this process (``time.process_time``),
the methods interleaved (A B C A B C ...), after a warm-up that compiles; median of the repeats.

Run: ``python bench/collocation.py [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from rotorlab.continuation import find_periodic_orbit  # noqa: E402
from rotorlab.continuation._collocation import collocate_orbit  # noqa: E402
from rotorlab.integrate import SaveAt, StepControl, solve_ensemble  # noqa: E402
from rotorlab.models.examples import PlanarOscillator  # noqa: E402

VDP_PERIOD = 6.6632868593231301896


def kernel_field(model, params):
    rhs, out = model.kernels.rhs, np.empty(model.kernels.n_state)

    def f(x):
        rhs(0.0, np.ascontiguousarray(x, dtype=float), params, out)
        return out.copy()

    return f


def guess(model, params, y0, period, samples=400):
    ts = np.linspace(0.0, period, samples)
    sol = solve_ensemble(model, y0, (0.0, period), params=params, save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=1e-4, atol=1e-6))
    return ts, sol.ys[0]


def problems():
    vdp = PlanarOscillator.van_der_pol(1.0)
    yield "Van der Pol, mu = 1", vdp, vdp.to_array(), np.array([2.0, 0.0]), 6.6, np.zeros(2, int), VDP_PERIOD, (0, 1)
    from periodic import setup, start  # bench/periodic.py: the whirl of zhakash-k2 at 1.6 p

    p, model, rot, y0 = setup()
    orb = start(p, rot, y0)
    params = model.with_speed(__import__("rotorlab.models", fromlist=["ConstantSpeed"]).ConstantSpeed(1.6 * p)).to_array()
    ref = find_periodic_orbit(rot, orb.state, orb.period, params=params, segments=10, rtol=1e-12,
                              winding=orb.winding, tol=1e-12)
    yield ("zhakash-k2 whirl at 1.6 p", rot, params, orb.state, orb.period, orb.winding, ref.period,
           (0, 1))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    for name, model, params, y0, period, winding, ref, _ in problems():
        period0 = period * (1 + 1e-3)
        ts, ys = guess(model, params, y0, period)
        ys = ys.copy()
        f = kernel_field(model, params)
        jump = 2 * math.pi * np.asarray(winding, dtype=float)
        step = 1e-7 * np.maximum(np.abs(ys).max(axis=0), 1e-3)
        methods = {
            "shooting, 5 segments": lambda: find_periodic_orbit(model, ys[0], period0, params=params, segments=5,
                                                                  winding=winding).period,
        }
        for n_int in (20, 40, 80):
            methods[f"collocation, N = {n_int}, m = 4"] = (
                lambda n_int=n_int: collocate_orbit(f, ts, ys, period0, intervals=n_int, degree=4, winding=jump,
                                                    jacobian_step=step).period)
        for fn in methods.values():
            fn()  # warm-up (compiles)
        times = {k: [] for k in methods}
        got = {}
        for _ in range(args.repeat):
            for k, fn in methods.items():
                c0 = time.process_time()
                got[k] = fn()
                times[k].append(time.process_time() - c0)
        print(f"{name}: reference period {ref:.15g} s")
        for k in methods:
            t = sorted(times[k])
            print(f"  {k:34s} CPU-s median {t[len(t) // 2]:.3f}  period error {abs(got[k] - ref):.2e} s "
                  f"(relative {abs(got[k] - ref) / ref:.1e})")


if __name__ == "__main__":
    main()
