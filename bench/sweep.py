"""Benchmark: the `rotorlab sweep` user path on the benchmark autobalancer grid against dp5_simd.c,
and the CPU cost of ``--workers`` (issues 7 and 11).

Usage::

    python bench/sweep.py [--n 32] [--n-small 16] [--revolutions 2000] [--workers 2] [--chunk 256]
                          [--repeats 2] [--c-dir ../shared/bench] [--skip-cli] [--json]
    python bench/sweep.py --idle-cluster SECONDS   # CPU of an idle --workers cluster only

The problem (:data:`rotorlab.models.BENCHMARK`: nondimensional Jeffcott rotor with two balls,
M = 1, m = 0.02, R = 1, eps = 0.01, k = 1, c = 0.02, beta = 0.01, Omega = 2.5, rtol 1e-8,
atol 1e-10, 2000 revolutions) written as a case file with a ``sweep`` analysis
(``jeffcott_balls``, ``ic = {psi_1, psi_2}`` on an n x n grid over [0, 2 pi)). n must divide 256:
the grid is then a sub-grid of the one of ``../shared/bench`` (psi_i = phi_i at t = 0), and
``dp5_simd.c`` runs on exactly the same trajectories. In each of ``--repeats`` interleaved rounds,
all CPU time (user + system, all threads):

1. ``dp5_simd.c`` (built as ``bench/ensemble.py`` does, OMP_NUM_THREADS = --workers; its own
   getrusage figure), unless ``--c-dir`` is missing (then it says so);
2. ``run_sweep`` in this process, in memory (the user path without workers; ``time.process_time``);
3. the lane driver alone (``solve_ensemble``, the mapper's starts and save times) on 1 thread and
   on --workers threads;
4. ``rotorlab sweep CASE --out STORE`` as subprocesses, without and with ``--workers`` (CPU of the
   command and all its children via ``getrusage(RUSAGE_CHILDREN)``), on the n and the --n-small
   grid: CPU = fixed + points x per-point gives the start-up and per-point cost of each.

Prints medians, trajectories per CPU-second, the ratios, the frame the sweep integrates in and
its right-hand-side evaluations per trajectory, the physics check (every off-diagonal
start balanced, the diagonal not) and that the sweep's labels agree with the ensemble's final
amplitudes. Compilation is excluded by a warm-up (subprocesses load the on-disk cache).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import shutil
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


def _cpu_children() -> float:
    """CPU seconds (user + system) of this process's finished children, grandchildren included."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def _setup(n: int, revolutions: float, chunk: int, tmp: Path):
    """The benchmark as a sweep case of an n x n grid: (case file, Sweep, mapper)."""
    from rotorlab.analyses._sweep import build_sweep
    from rotorlab.io import parse_case

    top = 2.0 * math.pi * (n - 1) / n
    text = CASE.format(ecc=0.01 / 0.96, top=top, n=n, revs=revolutions, chunk=chunk)
    case_file = tmp / f"bench_{n}.toml"
    case_file.write_text(text)
    case = parse_case(text, origin=str(case_file))
    sweep = build_sweep(case.model, case.analysis("grid"))
    return case_file, sweep, sweep.analysis.mapper


def _bench_indices(n: int) -> np.ndarray | None:
    """Indices into the 256 x 256 grid of ``../shared/bench`` of the sweep's n x n grid (psi = phi at t = 0:
    ``jeffcott_balls`` writes phi_i = theta + psi_i with theta(0) = 0), row-major like the sweep."""
    from rotorlab.models import BENCHMARK

    ng = BENCHMARK.n_grid
    if ng % n:
        return None
    a, b = np.divmod(np.arange(n * n), n)
    return (a * (ng // n)) * ng + b * (ng // n)


def _cli(case_file: Path, store: Path, workers: int | None, env: dict) -> tuple[float, float, dict]:
    """``rotorlab sweep`` as a subprocess: (CPU s incl. all its children, wall s, its JSON)."""
    cmd = [sys.executable, "-m", "rotorlab.cli", "sweep", str(case_file), "--out", str(store), "--json"]
    if workers:
        cmd += ["--workers", str(workers)]
    shutil.rmtree(store, ignore_errors=True)
    c0, w0 = _cpu_children(), time.perf_counter()
    res = subprocess.run(cmd, env=env, capture_output=True, text=True)
    cpu, wall = _cpu_children() - c0, time.perf_counter() - w0
    if res.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{res.stderr}")
    return cpu, wall, json.loads(res.stdout)


def _idle_cluster(workers: int, seconds: float) -> dict:
    """CPU cost of an idle local Dask cluster (the one ``--workers`` starts): scheduler, client and
    (thread) workers in this process, per wall-second of waiting; worker processes and their
    nannies, where ``local_cluster`` starts them, as children."""
    from dask.distributed import Client

    from rotorlab.sweep._executors import local_cluster

    c0, k0 = time.process_time(), _cpu_children()
    cluster = local_cluster(workers)
    client = Client(cluster)
    c1 = time.process_time()
    time.sleep(seconds)
    idle_self = time.process_time() - c1
    client.close()
    cluster.close()
    return {"idle_seconds": seconds, "startup_self_cpu_s": round(c1 - c0, 3),
            "idle_self_cpu_s_per_s": round(idle_self / seconds, 4),
            "children_cpu_s_total": round(_cpu_children() - k0, 3)}  # fmt: skip


def _median(xs: list[float]) -> float:
    return float(np.median(xs)) if xs else float("nan")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=32, help="grid points per angle (n x n trajectories)")
    ap.add_argument("--n-small", type=int, default=16,
                    help="second grid for the start-up / per-point split of --workers (0: skip)")
    ap.add_argument("--revolutions", type=float, default=2000.0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--chunk", type=int, default=256)
    ap.add_argument("--repeats", type=int, default=2, help="interleaved rounds (medians reported)")
    ap.add_argument("--skip-cli", action="store_true", help="only the in-process figures (items 1 and 3)")
    ap.add_argument("--c-dir", type=Path, default=None,
                    help="folder of dp5_simd.c (default ../shared/bench beside the repository)")
    ap.add_argument("--idle-cluster", type=float, default=0.0, metavar="SECONDS",
                    help="only measure an idle --workers cluster for SECONDS (run twice, e.g. 2 and 30, "
                         "and difference the children's CPU)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    if args.idle_cluster:
        print(json.dumps(_idle_cluster(args.workers, args.idle_cluster)))
        return 0
    sys.path.insert(0, str(SRC))
    sys.path.insert(0, str(HERE))
    from rotorlab.integrate import SaveAt, solve_ensemble
    from rotorlab.sweep import run_sweep

    import ensemble as ens  # the C references' build and run (bench/ensemble.py)

    if args.c_dir is not None:
        ens.SHARED = args.c_dir.resolve()

    n = args.n
    tmp = Path(tempfile.mkdtemp(prefix="rotorlab-bench-sweep-"))
    case_file, sweep, mapper = _setup(n, args.revolutions, args.chunk, tmp)
    small = _setup(args.n_small, args.revolutions, args.chunk, tmp) if args.n_small else None
    model, Y0, P = mapper.starts(sweep.coordinates())
    ts, t_end = mapper.save_times(), float(mapper.horizons()[-1])
    env = {**os.environ, "PYTHONPATH": str(SRC) + os.pathsep + os.environ.get("PYTHONPATH", "")}

    idx = _bench_indices(n)
    c_note = ""
    if not ens.SHARED.is_dir():
        c_note = f"{ens.SHARED} (the C references) does not exist: dp5_simd.c not run"
    elif shutil.which("gcc") is None:
        c_note = "gcc not found: dp5_simd.c not run"
    elif idx is None:
        c_note = f"the {n} x {n} grid is not a sub-grid of the 256 x 256 benchmark grid: dp5_simd.c not run"
    elif args.revolutions != 2000.0:
        c_note = "dp5_simd.c integrates 2000 revolutions only: not run"
    idx_file = tmp / "idx.txt"
    if not c_note:
        np.savetxt(idx_file, idx, fmt="%d")

    # warm-up: compilation (scalar and lane drivers, both thread counts) and one small sweep
    for th in (1, args.workers):
        solve_ensemble(model, Y0[:16], (0.0, 1.0), params=P[:16], control=mapper.control, threads=th)
    run_sweep(small[1] if small else sweep, chunk_size=args.chunk)

    cpu: dict[str, list[float]] = {}

    def rec(key: str, v: float) -> None:
        cpu.setdefault(key, []).append(v)

    amp_c = amp_base = None
    for _ in range(args.repeats):
        if not c_note:
            r = ens.run_c("dp5_simd", idx_file, n * n, args.workers, 1)
            rec("dp5_simd", r["cpu_s"])
            amp_c = r["amplitude"]
        c0 = time.process_time()
        ds = run_sweep(sweep, chunk_size=args.chunk)  # the user path, in this process
        rec("run_sweep", time.process_time() - c0)
        for th in (1, args.workers):
            c0 = time.process_time()
            sol = solve_ensemble(model, Y0, (0.0, t_end), params=P, save_at=SaveAt(ts=ts),
                                 control=mapper.control, threads=th)  # fmt: skip
            rec(f"lanes_{th}_thread", time.process_time() - c0)
            amp_base = np.hypot(sol.y_final[:, 0], sol.y_final[:, 1])  # the same in either frame
            nfev = sol.stats[:, 0]
        if not args.skip_cli:
            for label, (cf, nn) in {"": (case_file, n), "_small": (small[0], args.n_small) if small else None}.items() \
                    if small else {"": (case_file, n)}.items():  # fmt: skip
                for w in (None, args.workers):
                    c, _, doc = _cli(cf, tmp / f"cli_{nn}_{w}.zarr", w, env)
                    rec(f"cli_{'workers' if w else 'inprocess'}{label}", c)

    med = {k: _median(v) for k, v in cpu.items()}
    N = n * n
    i, j = np.divmod(np.arange(N), n)
    diag = i == j
    balanced = amp_base < 1e-3
    out: dict = {
        "grid": f"{n} x {n}", "trajectories": N, "revolutions": args.revolutions, "workers": args.workers,
        "chunk": args.chunk, "repeats": args.repeats, "load_average": os.getloadavg(),
        "cpu_s_rounds": {k: [round(x, 3) for x in v] for k, v in cpu.items()},
        "physics_check": bool(np.all(balanced[~diag]) and not np.any(balanced[diag])),
        "labels_agree": bool(np.all((ds["outcome"].values.reshape(-1) == 0) == balanced)),
        "c_reference": c_note or "dp5_simd.c run on the same trajectories (OMP_NUM_THREADS = workers)",
        "frame": mapper.frame,
        "rhs_per_trajectory": {"mean": round(float(nfev.mean())), "off_diagonal": round(float(nfev[~diag].mean())),
                               "diagonal": round(float(nfev[diag].mean()))},
    }  # fmt: skip
    tp = {k: N / v for k, v in med.items() if not k.endswith("_small")}
    out["traj_per_cpu_s"] = {k: round(v, 2) for k, v in tp.items()}
    if "dp5_simd" in med:
        out["run_sweep_over_dp5_simd"] = round(tp["run_sweep"] / tp["dp5_simd"], 4)
        out["lanes_over_dp5_simd"] = round(tp[f"lanes_{args.workers}_thread"] / tp["dp5_simd"], 4)
        off = ~diag
        out["dp5_simd_physics"] = bool(np.all(amp_c[off] < 1e-3) and not np.any(amp_c[diag] < 1e-3))
    out["cpu_per_traj_1_over_2_threads"] = round(med["lanes_1_thread"] / med[f"lanes_{args.workers}_thread"], 4)
    if "cli_workers" in med:
        out["cli_workers_cpu_overhead"] = round(med["cli_workers"] / med["cli_inprocess"] - 1.0, 4)
        if "cli_workers_small" in med:
            ns = args.n_small**2
            # CPU(N) = fixed + N * per_point for each command: two grid sizes give both
            for k in ("cli_inprocess", "cli_workers"):
                per = (med[k] - med[k + "_small"]) / (N - ns)
                out[f"{k}_fixed_cpu_s"] = round(med[k] - N * per, 3)
                out[f"{k}_per_point_cpu_ms"] = round(1e3 * per, 4)
            out["workers_per_point_overhead"] = round(out["cli_workers_per_point_cpu_ms"]
                                                      / out["cli_inprocess_per_point_cpu_ms"] - 1.0, 4)  # fmt: skip
    print_figures(out, args.json)
    return 0


def print_figures(out: dict, as_json: bool) -> None:
    """Print a benchmark's figures as JSON or as one ``key value`` line each."""
    if as_json:
        print(json.dumps(out, indent=2))
    else:
        for k, v in out.items():
            print(f"{k:40s} {v}")


if __name__ == "__main__":
    raise SystemExit(main())
