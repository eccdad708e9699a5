"""Tolerances of ``pico21-balancer`` (issue 27 item 3, Speed): the CPU time of the built-in
``tolerances`` analysis, and what sample size gives what interval width.

The built-in example (N = 32 base samples, 9 inputs: 352 machines x 4 ball starts of 8 s at 10000
rpm) runs once on the sweep engine (in-process, numba threads). SALib's Sobol design of N base
samples is the first N (D + 2) rows of the design of any larger N (the same scrambled Sobol
sequence; checked here), so the indices at N = 8 and 16 come from the first rows of the N = 32
run: the half-widths of their bootstrap 95 % intervals show how they shrink with N. The same
table for the Ishigami function (no integration) extends it to large N and gives the error
against the analytic indices.

    python bench/tolerances.py            # the built-in example, then Ishigami
    python bench/tolerances.py --samples 8  # a smaller design of the same case
    python bench/tolerances.py --save /tmp/tol  # also the result and its figures
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

ISHIGAMI_ST = np.array([0.5576, 0.4424, 0.2437])  # a = 7, b = 0.1 (Saltelli et al. 2010, section 4)


def _widths(names, values, n, d, confidence=0.95):
    from rotorlab.explore._sensitivity import sobol_indices

    si = sobol_indices(names, values[: n * (d + 2)], confidence=confidence, resamples=200, seed=0)
    return float(np.nanmean(si["ST_conf"])), float(np.nanmax(si["ST_conf"])), si


def machine(samples: int, save: str | None) -> None:
    from rotorlab.analyses._tolerances import run_tolerances_analysis
    from rotorlab.explore._sensitivity import UncertainInput, sobol_sample
    from rotorlab.io import load_case

    case = load_case("pico21-balancer")
    spec = next(a for a in case.analyses if a.type == "tolerances").model_copy(update={"samples": samples})
    cpu, wall = time.process_time(), time.perf_counter()
    ds = run_tolerances_analysis(case.model, spec)
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    if save:
        from pathlib import Path

        from rotorlab.io import save_netcdf
        from rotorlab.plot._tolerances import tolerances_figures

        Path(save).mkdir(parents=True, exist_ok=True)
        save_netcdf(ds, Path(save) / "tolerances.nc")
        for stem, fig in tolerances_figures(ds, "tolerances").items():
            fig.savefig(Path(save) / f"{stem}.png", dpi=110)
    d = int(ds.attrs["n_inputs"])
    names = [str(v) for v in ds["input"].values]
    trajectories = int(ds.sizes["sample"]) * int(ds.attrs["starts"])
    print(f"pico21-balancer tolerances: N = {samples}, {ds.sizes['sample']} machines x {ds.attrs['starts']} starts "
          f"= {trajectories} trajectories of {ds.attrs['t_end']:g} s; CPU {cpu:.1f} s ({1e3 * cpu / trajectories:.0f} "
          f"ms per trajectory, compiling included), wall {wall:.1f} s; failed {ds.attrs['failed']}")  # fmt: skip
    print(f"P(balanced): mean {float(ds['p_balanced'].mean()):.3f}; residual median "
          f"{1e6 * float(ds['residual_vibration'].median()):.3g} um; peak median "
          f"{1e6 * float(ds['transient_peak'].median()):.3g} um")  # fmt: skip
    small = [UncertainInput(n, _dist(spec, n, case)) for n in names]
    print("| output | N | machines | mean ST half-width | largest ST half-width | top input (ST) |")
    print("|---|---:|---:|---:|---:|---|")
    for out in [str(o) for o in ds["output"].values]:
        values = np.asarray(ds[out].values, dtype=float)
        n = 8
        while n <= samples:
            if n < samples:  # the design of n is the first rows of the design of samples
                head = sobol_sample(small, n, spec.seed)
                assert all(np.array_equal(head[k], np.asarray(ds[k].values)[: n * (d + 2)]) for k in names)
            mean_w, max_w, si = _widths(names, values, n, d)
            if math.isnan(mean_w):
                print(f"| {out} | {n} | {n * (d + 2)} | – | – | (no variance) |")
            else:
                j = int(np.nanargmax(si["ST"]))
                print(f"| {out} | {n} | {n * (d + 2)} | {mean_w:.3f} | {max_w:.3f} | {names[j]} "
                      f"({si['ST'][j]:.2f} ± {si['ST_conf'][j]:.2f}) |")  # fmt: skip
            n *= 2


def _dist(spec, name, case):
    from rotorlab.analyses._machine_common import machine_model

    return spec.distribution(name, machine_model(case.model))[0]


def ishigami() -> None:
    from rotorlab.explore._sensitivity import Distribution, UncertainInput, sobol_indices, sobol_sample

    d = Distribution("uniform", low=-math.pi, high=math.pi)
    inputs = [UncertainInput(f"x{i}", d) for i in (1, 2, 3)]
    print("| Ishigami N | points | mean ST half-width | largest |ST - exact| |")
    print("|---:|---:|---:|---:|")
    for n in (64, 256, 1024, 4096):
        x = sobol_sample(inputs, n, 0)
        y = np.sin(x["x1"]) + 7.0 * np.sin(x["x2"]) ** 2 + 0.1 * x["x3"] ** 4 * np.sin(x["x1"])
        si = sobol_indices(["x1", "x2", "x3"], y, resamples=200, seed=0)
        print(f"| {n} | {n * 5} | {np.mean(si['ST_conf']):.3f} | {np.max(np.abs(si['ST'] - ISHIGAMI_ST)):.3f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=32, help="base samples of the machine run (a power of 2)")
    parser.add_argument("--skip-machine", action="store_true")
    parser.add_argument("--save", metavar="DIR", help="write the result (NetCDF) and its figures (PNG) there")
    args = parser.parse_args()
    if not args.skip_machine:
        machine(args.samples, args.save)
    ishigami()


if __name__ == "__main__":
    main()
