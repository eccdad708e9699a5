"""Benchmark of ``jeffcott_balls`` in the co-rotating frame (issue 24, item 3), ratios in one run.

The co-rotating frame runs the preset machine's generated co-rotating kernel
(:attr:`rotorlab.models.Machine.rotating_kernels`); the baseline is the hand-written co-rotating
kernel it replaced (:mod:`rotorlab._kernels.jeffcott_balls`: ``rhs_rotating_constant``, lane
friendly, the tests' oracle). CPU time of 64 constant-speed starts (random ball angles, rotor at
rest, 200 revolutions, rtol 1e-8) on the scalar and the lane driver (8 lanes), at 0.6 p, 1.2 p and
2 p on ``zhakash-k2`` and ``autobalancer``, the best of ``--repeats`` interleaved runs; target:
preset / hand-written <= 1.3. Both give the same trajectories (largest final-state difference
printed, relative to the largest entry).

Usage::

    python bench/corotating.py [--n 64] [--repeats 3] [--revolutions 200]
"""

from __future__ import annotations

import argparse
import os
import time
from dataclasses import replace

import numpy as np


class HandWritten:
    """``model`` on the hand-written co-rotating kernel (the baseline)."""

    def __init__(self, model):
        from rotorlab._kernels import jeffcott_balls as k
        from rotorlab.models import Kernels

        self.model = model
        self.kernels = Kernels(rhs=k.rhs_rotating_constant, n_state=model.n_state, vectorises=True)

    def to_array(self):
        return self.model.to_array()[: 12 + 6 * self.model.n_balls]


def models():
    from rotorlab.analyses._case import build_model
    from rotorlab.io import load_case
    from rotorlab.models import ConstantSpeed

    for name in ("zhakash-k2", "autobalancer"):
        jb = build_model(load_case(name).model)
        for ratio in (0.6, 1.2, 2.0):
            om = ratio * jb.critical_speed
            yield name, ratio, replace(jb, speed=ConstantSpeed(om), frame="rotating")


def run(model, y0, t1, lanes):
    from rotorlab.integrate import StepControl, solve_ensemble

    c = time.process_time()
    sol = solve_ensemble(model, y0, (0.0, t1), control=StepControl(rtol=1e-8, atol=1e-10), lanes=lanes, threads=1)
    return time.process_time() - c, sol


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--revolutions", type=float, default=200.0)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}, {len(os.sched_getaffinity(0))} cores")
    for name, ratio, model in models():
        rng = np.random.default_rng(0)
        y0 = np.array([model.initial_state(rng.uniform(0, 2 * np.pi, model.n_balls)) for _ in range(args.n)])
        t1 = args.revolutions * 2 * np.pi / model.speed.speed
        base = HandWritten(model)
        line = [f"{name} at {ratio:.1f} p:"]
        for lanes, label in ((None, "scalar"), (8, "lanes")):
            for m in (model, base):  # compile and load outside the measurement
                run(m, y0[:2], t1 / 100, lanes)
            tp, tb = [], []
            for _ in range(args.repeats):
                c, sp = run(model, y0, t1, lanes)
                tp.append(c)
                c, sb = run(base, y0, t1, lanes)
                tb.append(c)
            diff = np.abs(sp.y_final - sb.y_final).max() / np.abs(sb.y_final).max()
            line.append(f"{label} {1e3 * min(tp) / args.n:.2f} / {1e3 * min(tb) / args.n:.2f} ms = "
                        f"{min(tp) / min(tb):.3f} (final states differ by {diff:.1e})")
        print("  ".join(line), flush=True)


if __name__ == "__main__":
    main()
