"""Basin stability of ``zhakash-k2`` over its speed range (issue 26 item 2, Speed).

The target: 50 speeds x 2000 random starts on the lane driver in <= 10 CPU-minutes, and linear
in the number of workers of a local Dask cluster. This script measures a uniform subset of the 50
speeds (every ``--every``-th) with ``--starts`` starts each, with the horizon of the whole
50-speed run (the longest default horizon over the speeds), and extrapolates the CPU time of the
full run linearly (the starts of a speed are independent, and the subset spreads over the same
speeds). Then it runs a smaller set on a local Dask cluster of 1 and of 2 single-threaded workers
and prints the wall-time ratio (1.0 means no gain; 2.0 linear).

    python bench/basin_stability.py --every 5 --starts 200 --scaling-starts 100
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np


def _run(mapper, speeds, starts, chunk, executor=None):
    from rotorlab.explore import basin_stability_over
    from rotorlab.sweep import ListAxis

    ranges = {"psi_1": (0.0, 2.0 * math.pi), "psi_2": (0.0, 2.0 * math.pi)}
    cpu, wall = time.process_time(), time.perf_counter()
    ds = basin_stability_over(mapper, ListAxis("spin_speed", speeds), ranges, seed=0, starts=starts, chunk_size=chunk,
                              executor=executor)  # fmt: skip
    return ds, time.process_time() - cpu, time.perf_counter() - wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=int, default=50)
    parser.add_argument("--every", type=int, default=5, help="measure every N-th of the speeds")
    parser.add_argument("--starts", type=int, default=200, help="starts per measured speed")
    parser.add_argument("--full-starts", type=int, default=2000)
    parser.add_argument("--scaling-speeds", type=int, default=4)
    parser.add_argument("--scaling-starts", type=int, default=100)
    args = parser.parse_args()

    from rotorlab.analyses._basin_stability import stability_mapper
    from rotorlab.io import BasinStabilitySpec, load_case
    from rotorlab.sweep import DaskExecutor

    case = load_case("zhakash-k2")
    p = case.model.critical_speed()
    spec = BasinStabilitySpec(param={"spin_speed": [0.5 * p, 3.0 * p, args.speeds]}, starts=args.full_starts,
                              speed_ratio=2.0)  # fmt: skip
    mapper, _, rule = stability_mapper(case.model, spec)
    speeds = np.linspace(0.5 * p, 3.0 * p, args.speeds)
    print(f"zhakash-k2, spin_speed 0.5 p to 3 p ({args.speeds} speeds), {rule}")
    print(f"load average {os.getloadavg()[0]:.1f}, {len(os.sched_getaffinity(0))} cores")
    _run(mapper, speeds[:1], 8, 8)  # compile / load the driver outside the measurement
    subset = speeds[:: args.every]
    ds, cpu, wall = _run(mapper, subset, args.starts, args.starts)
    n = int(ds["n"].sum())
    full = cpu * (args.speeds * args.full_starts) / n
    print(f"measured: {subset.size} speeds x {args.starts} starts = {n} trajectories: {cpu:.1f} CPU-s, "
          f"{wall:.1f} s wall, {1e3 * cpu / n:.2f} CPU-ms per start")
    print(f"extrapolated: {args.speeds} x {args.full_starts} = {args.speeds * args.full_starts} starts: "
          f"{full / 60:.1f} CPU-minutes (target <= 10)")
    bal = ds.probability.sel(regime="balanced").values
    print("P(balanced) at the measured speeds / p: " + ", ".join(f"{s / p:.2f}: {b:.2f}" for s, b in zip(subset, bal)))

    few = speeds[:: max(1, args.speeds // args.scaling_speeds)][: args.scaling_speeds]
    chunk = max(1, args.scaling_starts // 2)
    times = {}
    _run(mapper, few[:1], 8, 4, DaskExecutor(workers=2, threads=1))  # Dask's imports outside the measurement
    for workers in (1, 2):
        ds_w, cpu_w, wall_w = _run(mapper, few, args.scaling_starts, chunk, DaskExecutor(workers=workers, threads=1))
        times[workers] = wall_w
        print(f"local Dask cluster, {workers} worker(s) x 1 thread: {few.size} speeds x {args.scaling_starts} starts, "
              f"{wall_w:.1f} s wall, {cpu_w:.1f} CPU-s")
    print(f"speed-up 2 workers / 1 worker: {times[1] / times[2]:.2f} (2.0 is linear)")


if __name__ == "__main__":
    main()
