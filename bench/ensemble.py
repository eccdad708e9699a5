"""Ensemble benchmark: rotorlab against the C references and SciPy, in one run.

Usage::

    python bench/ensemble.py [--n 4096] [--scipy-n 8] [--threads 2] [--lanes 8] [--repeats 1]

What it does (see ``bench/README.md``; the problem is :data:`rotorlab.models.BENCHMARK`):

1. builds the C references ``dp5.c`` and ``dp5_simd.c`` from ``../shared/bench`` (the
   development folder beside the repository) with gcc into ``bench/_build`` (flags of its
   README); without that folder or gcc it says so and runs only rotorlab and SciPy;
2. runs both on the first ``--n`` grid points of ``model.subset_indices`` with
   ``OMP_NUM_THREADS=--threads`` (they report their own CPU time);
3. runs rotorlab's ``solve_ensemble`` on the same trajectories with the benchmark kernel
   (``bench/_bench_kernel.py``): the scalar driver with ``math.sin``/``math.cos`` (the kernel as
   a user first writes it), the scalar driver with :func:`rotorlab._kernels._vmath.sincos`, and
   the lane driver (``lanes=--lanes``) with the same kernel;
4. runs SciPy ``solve_ivp(method="RK45")`` with the plain Python RHS on the first ``--scipy-n``;
5. prints trajectories per CPU-second (``time.process_time`` of this process, all threads; C:
   their own ``getrusage`` figure), the ratios, and the physics check of every method: all
   off-diagonal grid points balance (final amplitude <= 3e-9) and the diagonal ones end at
   0.0357191.

Timings of in-process work exclude compilation (a short warm-up run comes first). Machines are
noisy: compare ratios from one run, never absolute numbers across runs.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
SHARED = REPO.parent / "shared" / "bench"
BUILD = HERE / "_build"

sys.path.insert(0, str(HERE))


class model:  # noqa: N801 - the benchmark under the names of the C references' model.py
    from rotorlab.models import BENCHMARK as _B

    M, m, R, EPS, K, C = _B.total_mass, _B.ball_mass, _B.race_radius, _B.unbalance, _B.stiffness, _B.damping
    BETA, OMEGA, RTOL, ATOL, NGRID, T1 = _B.ball_damping, _B.spin_speed, _B.rtol, _B.atol, _B.n_grid, _B.t_end
    initial_state = staticmethod(_B.initial_state)
    subset_indices = staticmethod(_B.subset_indices)

    @staticmethod
    def rhs_python(t, s):
        """The benchmark kernel's plain-Python function (numba's ``py_func``), for SciPy."""
        from _bench_kernel import bench_rhs_libm

        out = np.empty(8)
        bench_rhs_libm.py_func(t, s, bench_params(), out)
        return out


DIAGONAL_AMPLITUDE = 0.0357191
BALANCED_MAX = 3e-9  # "about 2e-9" in the benchmark README

CFLAGS = {
    "dp5": ["-O3", "-march=native", "-fopenmp"],
    "dp5_simd": [
        "-O3", "-march=native", "-mprefer-vector-width=512", "-ffast-math", "-fno-builtin-sin",
        "-fno-builtin-cos", "-fopenmp",
    ],
}  # fmt: skip
LIBS = {"dp5": ["-lm"], "dp5_simd": ["-lmvec", "-lm"]}


def build(name: str) -> Path:
    """Compile ``shared/bench/<name>.c`` into ``bench/_build/<name>`` if it is out of date."""
    BUILD.mkdir(exist_ok=True)
    src = SHARED / f"{name}.c"
    exe = BUILD / name
    if not exe.exists() or exe.stat().st_mtime < src.stat().st_mtime:
        cmd = ["gcc", *CFLAGS[name], str(src), "-o", str(exe), *LIBS[name]]
        subprocess.run(cmd, check=True)
    return exe


def run_c(name: str, idx_file: Path, n: int, threads: int, repeats: int) -> dict:
    exe = build(name)
    out = BUILD / f"out_{name}_{n}.txt"
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    res = subprocess.run(
        [str(exe), str(n), str(idx_file), str(out), str(repeats)],
        check=True, capture_output=True, text=True, env=env,
    )  # fmt: skip
    info = json.loads(res.stdout.strip().splitlines()[-1])
    data = np.loadtxt(out)
    order = np.argsort(np.argsort(data[:, 0]))  # rows are in index order already; keep as is
    del order
    return {
        "traj_per_cpu_s": info["traj_per_cpu_s"],
        "cpu_s": info["median_cpu_s"],
        "amplitude": data[:, 1],
        "nfev": data[:, 2],
    }


def bench_params() -> np.ndarray:
    return np.array([model.M, model.m, model.R, model.EPS, model.K, model.C, model.BETA, model.OMEGA])


def run_rotorlab(rhs, idx: np.ndarray, threads: int, lanes: int | None) -> dict:
    from rotorlab.integrate import StepControl, solve_ensemble
    from rotorlab.models import Kernels

    kernels = Kernels(rhs=rhs, n_state=8)
    control = StepControl(rtol=model.RTOL, atol=model.ATOL)
    p = bench_params()
    y0 = model.initial_state(idx)
    # warm-up (compilation or cache load) on a short span, not timed
    solve_ensemble(kernels, y0[:2], (0.0, 1.0), params=p, control=control, threads=threads, lanes=lanes)
    c0 = time.process_time()
    w0 = time.perf_counter()
    sol = solve_ensemble(kernels, y0, (0.0, model.T1), params=p, control=control, threads=threads, lanes=lanes)
    cpu = time.process_time() - c0
    wall = time.perf_counter() - w0
    return {
        "traj_per_cpu_s": len(idx) / cpu,
        "cpu_s": cpu,
        "wall_s": wall,
        "amplitude": np.hypot(sol.y_final[:, 0], sol.y_final[:, 1]),
        "nfev": sol.stats[:, 0].astype(float),
        "status": sol.status,
        "y_final": sol.y_final,
        "stats": sol.stats,
    }


def run_scipy(idx: np.ndarray) -> dict:
    from scipy.integrate import solve_ivp

    y0 = model.initial_state(idx)
    amp = np.empty(len(idx))
    nfev = np.empty(len(idx))
    c0 = time.process_time()
    for i in range(len(idx)):
        sol = solve_ivp(model.rhs_python, (0.0, model.T1), y0[i], method="RK45", rtol=model.RTOL, atol=model.ATOL)
        amp[i] = np.hypot(sol.y[0, -1], sol.y[1, -1])
        nfev[i] = sol.nfev
    cpu = time.process_time() - c0
    return {"traj_per_cpu_s": len(idx) / cpu, "cpu_s": cpu, "amplitude": amp, "nfev": nfev}


def physics_check(idx: np.ndarray, amplitude: np.ndarray) -> tuple[bool, str]:
    """All off-diagonal points balance; the diagonal ones end at 0.0357191."""
    diag = idx // model.NGRID == idx % model.NGRID
    off = amplitude[~diag]
    on = amplitude[diag]
    ok_off = bool(np.all(off <= BALANCED_MAX)) if off.size else True
    ok_on = bool(np.all(np.abs(on - DIAGONAL_AMPLITUDE) <= 1e-7)) if on.size else True
    msg = f"off-diag max {off.max() if off.size else float('nan'):.2e} ({off.size})"
    if on.size:
        msg += f", diag {on.min():.7f}..{on.max():.7f} ({on.size})"
    return ok_off and ok_on, msg


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=4096, help="trajectories (prefix of subset_indices)")
    ap.add_argument("--scipy-n", type=int, default=8, help="trajectories for SciPy solve_ivp")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--lanes", type=int, default=8, help="lane width of rotorlab's lane driver")
    ap.add_argument("--repeats", type=int, default=1, help="repeats of the C programs (median)")
    ap.add_argument("--skip-libm", action="store_true", help="skip the scalar math.sin variant")
    args = ap.parse_args(argv)

    c_missing = ("../shared/bench (the C references) does not exist beside this repository"
                 if not SHARED.is_dir() else "gcc not found" if shutil.which("gcc") is None else "")
    if c_missing:
        print(f"{c_missing}: the C references are NOT run; rotorlab is compared with SciPy only.")
    import numba

    from _bench_kernel import bench_rhs, bench_rhs_libm

    idx = model.subset_indices(args.n)
    BUILD.mkdir(exist_ok=True)
    idx_file = BUILD / f"idx_{args.n}.txt"
    np.savetxt(idx_file, idx, fmt="%d")
    load = os.getloadavg()[0]
    print(
        f"n = {args.n}, threads = {args.threads}, lanes = {args.lanes}, scipy n = {args.scipy_n}; "
        f"{os.cpu_count()} CPUs, load average {load:.2f}; numba {numba.__version__}"
    )

    results: dict[str, dict] = {}
    order = []

    def record(name: str, res: dict, sub_idx: np.ndarray) -> None:
        ok, msg = physics_check(sub_idx, res["amplitude"])
        res["check"] = (ok, msg)
        results[name] = res
        order.append(name)
        print(f"  {name:34s} {res['traj_per_cpu_s']:9.2f} traj/CPU-s   physics {'ok' if ok else 'FAILED'}: {msg}", flush=True)

    if not c_missing:
        record("dp5.c (scalar, C)", run_c("dp5", idx_file, args.n, args.threads, args.repeats), idx)
        record("dp5_simd.c (SIMD lanes, C)", run_c("dp5_simd", idx_file, args.n, args.threads, args.repeats), idx)
    if not args.skip_libm:
        record("rotorlab scalar (math.sin)", run_rotorlab(bench_rhs_libm, idx, args.threads, None), idx)
    record("rotorlab scalar (vmath.sincos)", run_rotorlab(bench_rhs, idx, args.threads, None), idx)
    record(f"rotorlab lanes={args.lanes}", run_rotorlab(bench_rhs, idx, args.threads, args.lanes), idx)
    sidx = idx[: args.scipy_n]
    if args.scipy_n > 0:
        record("SciPy solve_ivp RK45 (Python RHS)", run_scipy(sidx), sidx)

    lane = results[f"rotorlab lanes={args.lanes}"]
    scal = results["rotorlab scalar (vmath.sincos)"]
    same = np.array_equal(lane["y_final"], scal["y_final"]) and np.array_equal(lane["stats"], scal["stats"])
    print(f"\nlane driver vs scalar driver (same kernel): bit-identical final states and step counts: {same}")
    dp5 = results.get("dp5.c (scalar, C)")
    if dp5 is not None:
        print(f"max |amplitude(rotorlab lanes) - amplitude(dp5.c)|: {np.max(np.abs(lane['amplitude'] - dp5['amplitude'])):.2e}")
        print(f"mean nfev: dp5.c {dp5['nfev'].mean():.1f}, rotorlab {lane['nfev'].mean():.1f}")

    print("\n| method | trajectories per CPU-second | physics check |")
    print("|---|---:|---|")
    for name in order:
        r = results[name]
        print(f"| {name} | {r['traj_per_cpu_s']:.2f} | {'ok' if r['check'][0] else 'FAILED'} |")
    rl = lane["traj_per_cpu_s"]
    print("\nratios (trajectories per CPU-second):")
    if dp5 is not None:
        print(f"  rotorlab lanes / dp5_simd.c = {rl / results['dp5_simd.c (SIMD lanes, C)']['traj_per_cpu_s']:.2f}  (target >= 0.7)")
        print(f"  rotorlab lanes / dp5.c      = {rl / dp5['traj_per_cpu_s']:.2f}")
    if args.scipy_n > 0:
        print(f"  rotorlab lanes / SciPy      = {rl / results['SciPy solve_ivp RK45 (Python RHS)']['traj_per_cpu_s']:.0f}")
    if dp5 is not None:
        print(f"  rotorlab scalar (sincos) / dp5.c = {scal['traj_per_cpu_s'] / dp5['traj_per_cpu_s']:.2f}")
    else:
        print("  (no ratios against the C references: they were not run, see above)")
    all_ok = all(r["check"][0] for r in results.values()) and same
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
