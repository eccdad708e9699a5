"""Benchmark: Campbell diagram of ``friswell-rotor`` over 101 speeds (issue 3).

Compares :func:`rotorlab.linear.campbell` (structure-exploiting eigen-solver, MAC tracking,
critical speeds refined to machine precision) with a baseline run in the same process: the full
dense generalised eigenproblem ``[[0, I], [-K, -Omega G]] x = lambda [[I, 0], [0, M]] x`` solved
with ``scipy.linalg.eig`` at each speed (eigenvectors included, as tracking needs them), then
sorted by frequency (no tracking). The baseline is timed twice: with the BLAS threading as
configured, and with OpenBLAS limited to one thread as rotorlab does internally.

Run: ``python bench/campbell.py [--speeds 101] [--repeat 7] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np
import scipy
import scipy.linalg

from rotorlab.linear import RPM, campbell
from rotorlab.linear._blas import single_threaded_blas
from rotorlab.linear.cases import friswell_rotor


def baseline(system, speeds, n_modes):
    """Dense generalised eigenproblem with scipy.linalg.eig at every speed."""
    n = system.n_dof
    B = scipy.linalg.block_diag(np.eye(n), system.M)
    out = np.empty((speeds.size, n_modes))
    for i, om in enumerate(speeds):
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-system.K, -(system.C + om * system.G)]])
        lam, _ = scipy.linalg.eig(A, B)
        f = np.sort(lam.imag[lam.imag > 0]) / (2 * np.pi)
        out[i] = f[:n_modes]
    return out


def _best(fn, repeat):
    times = []
    result = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return result, min(times), float(np.median(times))


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speeds", type=int, default=101, help="number of speeds (default 101)")
    ap.add_argument("--max-rpm", type=float, default=4000.0, help="top speed (rev/min)")
    ap.add_argument("--modes", type=int, default=8, help="tracked branches (default 8)")
    ap.add_argument("--repeat", type=int, default=7, help="timing repeats (best and median)")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    system = friswell_rotor()
    t_build = time.perf_counter() - t0
    speeds = RPM * np.linspace(0.0, args.max_rpm, args.speeds)
    campbell(system, speeds, n_modes=args.modes)  # warm-up (imports, caches)

    ds, fast_best, fast_med = _best(lambda: campbell(system, speeds, n_modes=args.modes),
                                    args.repeat)
    _, plain_best, plain_med = _best(
        lambda: campbell(system, speeds, n_modes=args.modes, refine=False), args.repeat)
    base, base_best, base_med = _best(lambda: baseline(system, speeds, args.modes),
                                      max(1, args.repeat // 2))

    def base_one_thread():
        with single_threaded_blas():
            return baseline(system, speeds, args.modes)

    _, base1_best, base1_med = _best(base_one_thread, max(1, args.repeat // 2))
    fast_sorted = np.sort(ds.frequency.values, axis=1)
    err = float(np.max(np.abs(fast_sorted - base) / base))
    result = {
        "case": "friswell-rotor", "n_dof": system.n_dof, "n_speeds": int(speeds.size),
        "max_rpm": args.max_rpm, "n_modes": args.modes, "method": ds.attrs["method"],
        "build_s": t_build,
        "campbell_best_s": fast_best, "campbell_median_s": fast_med,
        "campbell_no_refine_best_s": plain_best, "campbell_no_refine_median_s": plain_med,
        "baseline_best_s": base_best, "baseline_median_s": base_med,
        "baseline_one_thread_best_s": base1_best, "baseline_one_thread_median_s": base1_med,
        "speedup_vs_baseline": base_best / fast_best,
        "max_relative_frequency_difference": err,
        "critical_speeds_rpm": ds.critical_speed_rpm.values.round(4).tolist(),
        "cpu_count": os.cpu_count(), "python": platform.python_version(),
        "numpy": np.__version__, "scipy": scipy.__version__,
    }
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(f"friswell-rotor, {system.n_dof} DOF, {speeds.size} speeds 0..{args.max_rpm:g} "
              f"rev/min, {args.modes} branches, solver {ds.attrs['method']!r}")
        print(f"  model build                       {t_build * 1e3:8.2f} ms")
        print(f"  rotorlab campbell (refined crit.) {fast_best * 1e3:8.2f} ms best, "
              f"{fast_med * 1e3:8.2f} ms median")
        print(f"  rotorlab campbell (interpolated)  {plain_best * 1e3:8.2f} ms best, "
              f"{plain_med * 1e3:8.2f} ms median")
        print(f"  baseline scipy.linalg.eig(A, B)   {base_best * 1e3:8.2f} ms best, "
              f"{base_med * 1e3:8.2f} ms median")
        print(f"  baseline, one BLAS thread         {base1_best * 1e3:8.2f} ms best, "
              f"{base1_med * 1e3:8.2f} ms median")
        print(f"  speed-up vs baseline              {base_best / fast_best:8.1f} x")
        print(f"  max relative frequency difference {err:8.1e}")
        print(f"  critical speeds (rev/min)         {result['critical_speeds_rpm']}")
    return result


if __name__ == "__main__":
    main()
