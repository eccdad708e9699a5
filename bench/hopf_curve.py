"""Benchmark: a Hopf curve of ``rcfw-two-plane`` over speed x ball mass (issue 25, target <= 10 CPU-s).

The balanced branch of the built-in case (Rodrigues et al. 2008's long rotor, m = 5 g) is
continued in the speed from 2.5 to 3.5 rad/s (:func:`rotorlab.continuation.continue_equilibria`);
the Hopf point where balancing becomes stable (2.944 rad/s) is continued in the ball mass from
2.6 to 40 g (:func:`rotorlab.continuation.continue_special_point`), with the ball damping fixed
(``ball_mass``, the case file's balls) or scaled with the mass (``ball_mass_scaled_damping``, the
paper's Fig. 5). The curve turns through the tongue of instability near 3.5 g (Fig. 5(d)).

``--compare PATH``: time the same calls of another checkout's ``src`` (for instance the code
before this change) in a child process, interleaved with this one (A B A B ...). CPU seconds of
each process (``time.process_time``) around the continuation only, after a warm-up that compiles.

Run: ``python bench/hopf_curve.py [--repeat 3] [--compare /path/to/old/src] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

CHILD = r"""
import json, sys, time
from rotorlab.analyses import build_model
from rotorlab.continuation import continue_equilibria, continue_special_point
from rotorlab.io import load_case
name = sys.argv[1]
model = build_model(load_case("rcfw-two-plane").model)
continue_equilibria(model, "drive.speed", 2.9, 3.0, start_from="main 0")  # warm-up (compiles)
c0 = time.process_time()
r = continue_equilibria(model, "drive.speed", 2.5, 3.5, start_from="main 0")
(edge,) = [s for s in r.branches[0].special_points if s.changes_stability]
c1 = time.process_time()
curve = continue_special_point(model, edge, name, 0.0026, 0.04)
c2 = time.process_time()
v = curve.values
tongue = v[(v[:, 1] > 0.0034) & (v[:, 1] < 0.0037), 0]
print(json.dumps({"branch_s": c1 - c0, "curve_s": c2 - c1, "points": len(v), "end": curve.end,
                  "min_speed": float(v[:, 0].min()),
                  "max_speed_3p4_3p7g": float(tongue.max()) if tongue.size else float("nan")}))
"""


def run(src: str, name: str, cache: str | None) -> dict:
    env = {**os.environ, "PYTHONPATH": src}
    if cache:  # the other checkout's compiled drivers in a folder of their own
        env["ROTORLAB_CACHE_DIR"] = cache
    out = subprocess.run([sys.executable, "-c", CHILD, name], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--compare", default=None, help="another checkout's src folder (the old code)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
    jobs = [("new", here, "ball_mass"), ("new", here, "ball_mass_scaled_damping")]
    if args.compare:
        jobs.insert(0, ("old", args.compare, "ball_mass"))
    rows = {f"{who} {name}": [] for who, _, name in jobs}
    for _ in range(args.repeat):
        for who, src, name in jobs:
            cache = os.environ.get("ROTORLAB_CACHE_DIR", "/tmp/rotorlab-bench") + "-compare" if who == "old" else None
            rows[f"{who} {name}"].append(run(src, name, cache))
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    for key, rs in rows.items():
        tot = sorted(r["branch_s"] + r["curve_s"] for r in rs)
        r = rs[0]
        print(f"{key:32s} total CPU-s median {tot[len(tot) // 2]:.2f} (min {tot[0]:.2f}, max {tot[-1]:.2f}); "
              f"curve {r['points']} points, end {r['end']}, slowest speed {r['min_speed']:.3f} rad/s, "
              f"furthest speed 3.4-3.7 g {r['max_speed_3p4_3p7g']:.3f} rad/s")


if __name__ == "__main__":
    main()
