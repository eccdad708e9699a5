"""Benchmark: ``rotorlab.analyses.simulate`` on the benchmark autobalancer against dp5_simd.c, with
the start-ups integrated in the co-rotating frame (the path before issue 28) and where they are
cheapest (the fixed frame at this speed, the default since issue 28).

Usage::

    python bench/simulate.py [--n 64] [--repeats 3] [--threads 2] [--n-save 200] [--c-dir DIR] [--json]

The problem is :data:`rotorlab.models.BENCHMARK` (``BENCHMARK.model()``: nondimensional Jeffcott
rotor with two balls, Omega = 2.5 = 2.5 p, 2000 revolutions, rtol 1e-8, atol 1e-10), started from an
n x n grid of ball angles over [0, 2 pi) (n must divide 256: every (256 / n)-th point of the grid of
``../shared/bench``, psi_i = phi_i at t = 0, so ``dp5_simd.c`` runs on exactly the same
trajectories). In each of ``--repeats`` interleaved rounds, CPU time (user + system, all threads):

1. ``dp5_simd.c`` (built as ``bench/ensemble.py`` does, OMP_NUM_THREADS = --threads; its own
   getrusage figure), unless the C references are missing (then it says so);
2. ``simulate(model, speeds=[Omega], ..., frame="rotating")``: the integration of the previous
   ``simulate`` (co-rotating frame), with its saved states converted as before;
3. ``simulate(model, speeds=[Omega], ...)``: the default (``frame="auto"``, here the fixed frame).

``simulate`` runs in this process (``time.process_time``), whole call: integration, the saved
history of ``--n-save`` points, the outcome labels and the Dataset. Prints the medians, trajectories
per CPU-second, the ratios, the mean integrator steps per trajectory, the agreement of the two
frames (final ball angles and amplitudes) and the physics check (every off-diagonal start
balanced, the diagonal not). Compilation is excluded by a warm-up.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=64, help="grid points per angle (n x n starts); must divide 256")
    ap.add_argument("--repeats", type=int, default=3, help="interleaved rounds (medians reported)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--n-save", type=int, default=200, help="saved points of simulate's history")
    ap.add_argument("--c-dir", type=Path, default=None,
                    help="folder of dp5_simd.c (default ../shared/bench beside the repository)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(SRC))
    sys.path.insert(0, str(HERE))
    from rotorlab.analyses import simulate
    from rotorlab.models import BENCHMARK

    import ensemble as ens  # the C references' build and run (bench/ensemble.py)
    from sweep import print_figures

    if args.c_dir is not None:
        ens.SHARED = args.c_dir.resolve()
    n, ng = args.n, BENCHMARK.n_grid
    if ng % n:
        raise SystemExit(f"--n must divide {ng}, got {n}")
    a, b = np.divmod(np.arange(n * n), n)
    idx = (a * (ng // n)) * ng + b * (ng // n)
    angles = np.stack(BENCHMARK.grid_angles(idx), axis=1)
    model = BENCHMARK.model()
    om, t_end = BENCHMARK.spin_speed, BENCHMARK.t_end
    kw = dict(speeds=[om], initial_ball_angles=angles, t_end=t_end, n_save=args.n_save,
              rtol=BENCHMARK.rtol, atol=BENCHMARK.atol, threads=args.threads)  # fmt: skip

    c_note = ""
    if not ens.SHARED.is_dir():
        c_note = f"{ens.SHARED} (the C references) does not exist: dp5_simd.c not run"
    elif shutil.which("gcc") is None:
        c_note = "gcc not found: dp5_simd.c not run"
    tmp = Path(tempfile.mkdtemp(prefix="rotorlab-bench-simulate-"))
    idx_file = tmp / "idx.txt"
    np.savetxt(idx_file, idx, fmt="%d")

    for frame in ("rotating", "auto"):  # warm-up: compilation or cache load, not timed
        simulate(model, **{**kw, "initial_ball_angles": angles[:16], "t_end": 1.0}, frame=frame)

    cpu: dict[str, list[float]] = {}
    res = {}
    amp_c = None
    for _ in range(args.repeats):
        if not c_note:
            r = ens.run_c("dp5_simd", idx_file, n * n, args.threads, 1)
            cpu.setdefault("dp5_simd", []).append(r["cpu_s"])
            amp_c = r["amplitude"]
        for key, frame in (("simulate_rotating", "rotating"), ("simulate", "auto")):
            c0 = time.process_time()
            res[key] = simulate(model, **kw, frame=frame)
            cpu.setdefault(key, []).append(time.process_time() - c0)

    med = {k: float(np.median(v)) for k, v in cpu.items()}
    N = n * n
    diag = a == b
    new, old = res["simulate"], res["simulate_rotating"]
    balanced = new.outcome.values[0] == "balanced"
    tp = {k: N / v for k, v in med.items()}
    out: dict = {
        "grid": f"{n} x {n}", "trajectories": N, "revolutions": BENCHMARK.revolutions, "threads": args.threads,
        "n_save": args.n_save, "repeats": args.repeats, "load_average": [round(x, 2) for x in os.getloadavg()],
        "cpu_s_rounds": {k: [round(x, 3) for x in v] for k, v in cpu.items()},
        "traj_per_cpu_s": {k: round(v, 2) for k, v in tp.items()},
        "integration_frame": {"simulate": new.attrs["integration_frame"],
                              "simulate_rotating": old.attrs["integration_frame"]},
        "steps_per_trajectory": {"simulate": round(float(new.n_steps.mean())),
                                 "simulate_rotating": round(float(old.n_steps.mean()))},
        "speedup_over_rotating": round(med["simulate_rotating"] / med["simulate"], 3),
        "max_final_ball_angle_difference_rad": float(np.abs(new.final_ball_angle - old.final_ball_angle).max()),
        "max_final_amplitude_difference": float(np.abs(new.final_amplitude - old.final_amplitude).max()),
        "same_outcomes": bool(np.array_equal(new.outcome.values, old.outcome.values)),
        "physics_check": bool(np.all(balanced[~diag]) and not np.any(balanced[diag])),
        "c_reference": c_note or f"dp5_simd.c run on the same trajectories (OMP_NUM_THREADS = {args.threads})",
    }  # fmt: skip
    if "dp5_simd" in med:
        out["simulate_over_dp5_simd"] = round(tp["simulate"] / tp["dp5_simd"], 4)
        out["simulate_rotating_over_dp5_simd"] = round(tp["simulate_rotating"] / tp["dp5_simd"], 4)
        out["dp5_simd_physics"] = bool(np.all(amp_c[~diag] < 1e-3) and not np.any(amp_c[diag] < 1e-3))
    print_figures(out, args.json)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
