"""Benchmark: a whirl branch of ``zhakash-k2`` with 50 periodic orbits (issue 25, target <= 30 CPU-s).

The non-synchronous whirl of the built-in case (both balls lag the rotor together and turn once
backwards per period in the co-rotating frame) is found by simulation at 1.6 p
(:func:`rotorlab.continuation.orbit_from_simulation`, start psi = (-30, -15) deg) and continued in
the speed by multiple shooting (:func:`rotorlab.continuation.continue_periodic`, 5 segments,
50 orbits, downwards from 1.6 p). The baseline, run in the same process, is what the project did
before: one simulation per speed, settled for 40 s (the whirl's own settling time) at the same
50 speeds, as one ensemble on the lane driver; it says whether each speed ends in a whirl but
gives no period, no multipliers and no unstable orbit.

The machine is shared: the two methods are timed in interleaved repeats (A B A B ...), in CPU
seconds of this process (``time.process_time``, all threads), after a warm-up run that compiles.

Run: ``python bench/periodic.py [--repeat 3] [--points 50] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from rotorlab.continuation import ContinuationSettings, continue_periodic, orbit_from_simulation
from rotorlab.integrate import Lanes, StepControl, solve_ensemble
from rotorlab.models import ConstantSpeed
from rotorlab.steady import steady_case


def setup():
    case = steady_case("zhakash-k2")
    p = case.critical_speed()
    model = case.model("enough")
    rot = model.with_speed(ConstantSpeed(1.6 * p)).with_frame("rotating")
    y0 = rot.initial_state(np.radians([-30.0, -15.0]))
    return p, model, rot, y0


def start(p, rot, y0):
    return orbit_from_simulation(rot, y0, t_settle=40.0, t_window=3.0, angles=(4, 5), segments=5,
                                 parameter="speed", value=1.6 * p)


def branch(p, model, rot, orbit, points):
    return continue_periodic(
        rot, orbit, lambda w: model.with_speed(ConstantSpeed(w)).to_array(), parameter="speed", label="whirl",
        settings=ContinuationSettings(ds=0.02, ds_max=0.2, max_points=points, direction=-1, bounds=(0.3 * p, 6 * p)))


def baseline(p, model, rot, y0, speeds):
    params = np.array([model.with_speed(ConstantSpeed(w)).to_array() for w in speeds])
    sol = solve_ensemble(rot, y0, (0.0, 40.0), params=params, control=StepControl(rtol=1e-10, atol=1e-12),
                         backend=Lanes(8))
    return sol


def _cpu(fn):
    c0 = time.process_time()
    out = fn()
    return out, time.process_time() - c0


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="interleaved timing repeats (default 3)")
    ap.add_argument("--points", type=int, default=50, help="orbits on the branch (default 50)")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    args = ap.parse_args(argv)
    p, model, rot, y0 = setup()
    orbit = start(p, rot, y0)  # warm-up: compiles the lane driver of the rotating-frame kernel
    br = branch(p, model, rot, orbit, args.points)
    baseline(p, model, rot, y0, br.values[:8])
    t_start, t_branch, t_base = [], [], []
    for _ in range(args.repeat):
        orbit, c = _cpu(lambda: start(p, rot, y0))
        t_start.append(c)
        br, c = _cpu(lambda: branch(p, model, rot, orbit, args.points))
        t_branch.append(c)
        _, c = _cpu(lambda: baseline(p, model, rot, y0, br.values))
        t_base.append(c)
    out = {
        "orbits": int(br.values.size),
        "speed_range_p": [float(br.values.min() / p), float(br.values.max() / p)],
        "stable": int(br.stable.sum()),
        "period_range_s": [float(br.period.min()), float(br.period.max())],
        "max_trivial_multiplier_error": float(br.extra["trivial_multiplier_error"].max()),
        "special_points": [(s.type, s.value / p) for s in br.special_points],
        "cpu_s_start_from_simulation": {"min": min(t_start), "median": float(np.median(t_start))},
        "cpu_s_branch": {"min": min(t_branch), "median": float(np.median(t_branch))},
        "cpu_s_baseline_50_settled_simulations": {"min": min(t_base), "median": float(np.median(t_base))},
        "target_cpu_s": 30.0,
    }
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        for k, v in out.items():
            print(f"{k}: {v}")
    return out


if __name__ == "__main__":
    main()
