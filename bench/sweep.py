"""Benchmark: overhead of the sweep machinery on the 256 x 256 autobalancer grid of the benchmark
(:data:`rotorlab.models.BENCHMARK`).

Usage::

    python bench/sweep.py [--n 256] [--revolutions 2000] [--workers 2] [--chunk 1024] [--json]

What it does (the benchmark problem, :data:`rotorlab.models.BENCHMARK`: a nondimensional Jeffcott rotor with
two balls, M = 1, m = 0.02, R = 1, eps = 0.01, k = 1, c = 0.02, beta = 0.01, Omega = 2.5, the
ball angles on an n x n grid over [0, 2 pi)^2, rtol 1e-8, atol 1e-10, 2000 revolutions):

1. writes that problem as a case file with a ``sweep`` analysis (``jeffcott_balls``, the grid
   as ``ic = {psi_1, psi_2}``) into a temporary folder;
2. **baseline**: the in-process ensemble: the same trajectories (the mapper's start states and
   save times) in one :func:`rotorlab.integrate.solve_ensemble` call on ``--workers`` threads;
3. **sweep**: ``rotorlab sweep CASE --workers N --out STORE.zarr`` as a subprocess (the whole
   command: Python start-up, the Dask LocalCluster, workers loading the compiled integrator,
   the chunks, features and labels, the Zarr store), and ``run_sweep`` in-process with a store;
4. prints wall times, the overhead ``sweep / baseline - 1`` (target < 10%), the physics check
   (every off-diagonal point balanced, the diagonal not), and that the sweep's final amplitudes
   equal the baseline's bit for bit.

Compilation is excluded from the baseline (a warm-up runs first) and from the sweep only as far
as the on-disk cache allows (workers load it). Machines are noisy: compare ratios from one run.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"

CASE = """\
schema_version = 1
name = "bench-autobalancer"
description = "benchmark autobalancer (nondimensional), ball angles on a grid"

[model]
type = "jeffcott_balls"
disc_mass = 0.96
eccentricity = {ecc!r}
stiffness = 1.0
damping = 0.02

[model.speed]
profile = "constant"
speed = 2.5

[[model.balls]]
mass = 0.02
radius = 1.0
damping = 0.01
count = 2

[[analysis]]
type = "sweep"
name = "grid"
ic = {{ psi_1 = [0.0, {top!r}, {n}], psi_2 = [0.0, {top!r}, {n}] }}
revolutions = {revs!r}
n_horizons = 1
window_revolutions = 10
chunk = {chunk}
rtol = 1e-8
atol = 1e-10
"""


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=256, help="grid points per angle (n x n trajectories)")
    ap.add_argument("--revolutions", type=float, default=2000.0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--chunk", type=int, default=1024)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(SRC))
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.integrate import SaveAt, solve_ensemble
    from rotorlab.io import parse_case
    from rotorlab.sweep import open_sweep, run_sweep

    n = args.n
    top = 2.0 * math.pi * (n - 1) / n
    text = CASE.format(ecc=0.01 / 0.96, top=top, n=n, revs=args.revolutions, chunk=args.chunk)
    tmp = Path(tempfile.mkdtemp(prefix="rotorlab-bench-sweep-"))
    case_file = tmp / "bench.toml"
    case_file.write_text(text)
    case = parse_case(text, origin=str(case_file))
    spec = case.analysis("grid")
    sweep = build_sweep(case.model, spec)
    mapper = sweep.analysis.mapper
    coords = sweep.coordinates()
    model, Y0, P = mapper.starts(coords)
    ts = mapper.save_times()
    t_end = float(mapper.horizons()[-1])

    # ---- baseline: the in-process ensemble (warm-up first) ---------------------------------
    solve_ensemble(model, Y0[:2], (0.0, 1.0), params=P[:2], control=mapper.control, threads=args.workers)
    w0 = time.perf_counter()
    sol = solve_ensemble(model, Y0, (0.0, t_end), params=P, save_at=SaveAt(ts=ts), control=mapper.control,
                         threads=args.workers)  # fmt: skip
    base = time.perf_counter() - w0
    amp_base = np.hypot(sol.y_final[:, 0], sol.y_final[:, 1])

    # ---- the sweep through the command line, 2 local workers --------------------------------
    store = tmp / "grid.zarr"
    env = {**os.environ, "PYTHONPATH": str(SRC) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    w0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-m", "rotorlab.cli", "sweep", str(case_file), "--workers",
                          str(args.workers), "--out", str(store), "--json"], env=env, capture_output=True,
                         text=True)  # fmt: skip
    cli = time.perf_counter() - w0
    if res.returncode != 0:
        print(res.stderr, file=sys.stderr)
        return 1
    doc = json.loads(res.stdout)
    ds = open_sweep(store)
    # ---- the sweep in-process with a store (no cluster) -------------------------------------
    w0 = time.perf_counter()
    run_sweep(sweep, store=tmp / "inproc.zarr", chunk_size=args.chunk)
    inproc = time.perf_counter() - w0

    # final amplitude of the sweep: the last saved state is at t_end

    amp_sweep = ds["amplitude"].values.reshape(-1)  # window mean at t_end (a feature)
    i, j = np.divmod(np.arange(n * n), n)
    diag = i == j
    balanced = amp_base < 1e-3
    physics = bool(np.all(balanced[~diag]) and not np.any(balanced[diag]))
    labels = ds["outcome"].values.reshape(-1)
    same_labels = bool(np.all((labels == 0) == balanced))
    out = {
        "grid": f"{n} x {n}", "trajectories": n * n, "revolutions": args.revolutions, "workers": args.workers,
        "chunk": args.chunk, "baseline_ensemble_wall_s": round(base, 3),
        "rotorlab_sweep_cli_wall_s": round(cli, 3), "sweep_inprocess_store_wall_s": round(inproc, 3),
        "overhead_cli_vs_ensemble": round(cli / base - 1.0, 4),
        "overhead_inprocess_store_vs_ensemble": round(inproc / base - 1.0, 4),
        "physics_check": physics, "labels_agree_with_baseline_amplitude": same_labels,
        "fractions": doc["fractions"], "max_offdiag_amplitude": float(amp_base[~diag].max()),
        "mean_window_amplitude_diag": float(amp_sweep[diag].mean()), "store": str(store),
    }  # fmt: skip
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        for k, v in out.items():
            print(f"{k:40s} {v}")
        print(f"target: overhead < 10%  ->  {'met' if out['overhead_cli_vs_ensemble'] < 0.10 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
