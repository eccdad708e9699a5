"""Design search (issue 27): two optimisers on the same budget, and the speed of a two-parameter
design of ``zhakash-k2`` (ball mass x ball damping, 1000 starts per evaluation).

1. Den Hartog's absorber (closed-form optimum, linear objective): Optuna's TPE against SciPy's
   differential evolution, ``--dh-seeds`` optimiser seeds each, budget ``--dh-budget``:
   evaluations until the peak is within 1 % of the floor sqrt(1 + 2 / mu), the best at the
   budget, CPU seconds.
2. ``zhakash-k2``: least ball mass with P(balanced) >= 0.99 (95 % Wilson lower bound) at 1.8 p,
   2.2 p and 2.6 p, ball mass 15-60 g x ball damping 0.3e-3-5e-3 N m s, ``--starts`` starts per
   speed (the same for every design), both optimisers, ``--seeds`` seeds, budget ``--budget``:
   evaluations to come within 2 % of the closed-form least mass (2 m R >= 0.95 M1 e: the
   classifier's balanced threshold with both balls together), CPU seconds of
   the search and of each evaluation. The TPE run is the speed target's design (<= 30
   CPU-minutes).
3. The same case with two objectives (ball mass, settle time): TPE's Pareto front, its figure.
4. Dask scaling (``--skip`` the others): the TPE design of part 2 (``--scaling-budget`` designs,
   ``--scaling-starts`` starts per speed, chunks of ``--scaling-chunk`` starts) on a local Dask
   cluster of 1 and of 2 single-threaded workers, ``--repeats`` times each, interleaved
   (1, 2, 2, 1, 1, 2, ...), one cluster per search: wall and CPU seconds of this process, the
   load average before each run, and whether every run gave the same bits.

    python bench/design.py --starts 1000 --budget 30 --seeds 3 --out bench/_out
    python bench/design.py --skip dh,zhakash,pareto --scaling-starts 1000 --scaling-budget 6 --repeats 3
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path

import numpy as np


def _cpu() -> float:
    return time.process_time()


def den_hartog(seeds: int, budget: int) -> dict:
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "validation"))
    from test_design_den_hartog import FLOOR, problem  # the closed form of the validation test

    from rotorlab.analyses import design_search

    out = {}
    for opt in ("tpe", "differential-evolution"):
        runs = []
        for seed in range(seeds):
            t = _cpu()
            ds = design_search(problem(), optimizer=opt, budget=budget, optimizer_seed=seed)
            cpu = _cpu() - t
            obj = ds.objective_value.values[:, 0] / FLOOR
            within = np.flatnonzero(obj <= 1.01)
            runs.append({"seed": seed, "best_over_floor": float(obj.min()),
                         "evals_to_1pct": int(within[0]) + 1 if within.size else None, "cpu_s": cpu,
                         "curve": np.fmin.accumulate(obj).tolist()})  # fmt: skip
        out[opt] = runs
    return out


def _spec(objectives, starts, budget, optimizer, seed):
    from rotorlab.io import DesignSpec

    p = 98.53
    return DesignSpec.model_validate({
        "name": "zhakash-balls", "vary": {"ball_mass": ["15 g", "60 g"], "ball_damping": ["0.3e-3 N*m*s", "5e-3 N*m*s"]},
        "objectives": objectives, "param": {"spin_speed": [1.8 * p, 2.6 * p, 3]}, "starts": starts, "min_balanced": 0.99,
        "budget": budget, "optimizer": optimizer, "optimizer_seed": seed})  # fmt: skip


def zhakash(starts: int, budget: int, seeds: int, out: Path) -> dict:
    from rotorlab.analyses._design_case import run_design_analysis
    from rotorlab.io import load_case

    case = load_case("zhakash-k2")
    runs = {}
    for opt in ("tpe", "differential-evolution"):
        for seed in range(seeds):
            t = _cpu()
            ds = run_design_analysis(case.model, _spec(["ball-mass"], starts, budget, opt, seed))
            cpu = _cpu() - t
            ds.to_netcdf(out / f"zhakash_{opt}_{seed}.nc")
            runs[f"{opt}/{seed}"] = ds
            print(f"  {opt} seed {seed}: {cpu:.1f} CPU-s, best {ds.attrs['best']}, "
                  f"{ds.sizes['trial']} designs, load {os.getloadavg()[0]:.1f}", flush=True)  # fmt: skip
    return runs


def dask_scaling(starts: int, budget: int, chunk: int, repeats: int) -> dict:
    """Wall and CPU seconds of one design search on 1 and 2 local Dask workers, interleaved."""
    from rotorlab.analyses._design_case import run_design_analysis
    from rotorlab.io import DesignSpec, load_case
    from rotorlab.sweep import DaskExecutor

    case = load_case("zhakash-k2")
    spec = DesignSpec.model_validate({**_spec(["ball-mass"], starts, budget, "tpe", 0).model_dump(), "chunk": chunk})
    warm = DesignSpec.model_validate({**spec.model_dump(), "budget": 1, "starts": 8, "chunk": 4, "verify": False})
    run_design_analysis(case.model, warm, executor=DaskExecutor(workers=2, threads=1))  # imports, driver load
    order = [w for k in range(repeats) for w in ((1, 2) if k % 2 == 0 else (2, 1))]
    runs, first = [], None
    for workers in order:
        load = os.getloadavg()[0]
        cpu, wall = _cpu(), time.perf_counter()
        ds = run_design_analysis(case.model, spec, executor=DaskExecutor(workers=workers, threads=1))
        cpu, wall = _cpu() - cpu, time.perf_counter() - wall
        data = ds.copy()
        data.attrs = {k: v for k, v in ds.attrs.items() if not k.endswith("cpu_s")}
        same = True if first is None else bool(data.identical(first))
        first = data if first is None else first
        runs.append({"workers": workers, "wall_s": wall, "cpu_s": cpu, "load_before": load, "same_bits": same})
        print(f"  {workers} worker(s): {wall:.1f} s wall, {cpu:.1f} CPU-s, load before {load:.1f}, "
              f"same bits as the first: {same}", flush=True)
    return {"runs": runs, "load_after": os.getloadavg()[0], "starts": starts, "budget": budget, "chunk": chunk}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dh-seeds", type=int, default=10)
    parser.add_argument("--dh-budget", type=int, default=60)
    parser.add_argument("--starts", type=int, default=1000)
    parser.add_argument("--budget", type=int, default=30)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--pareto-budget", type=int, default=40)
    parser.add_argument("--out", type=Path, default=Path("bench/_out"))
    parser.add_argument("--scaling-starts", type=int, default=1000)
    parser.add_argument("--scaling-budget", type=int, default=6)
    parser.add_argument("--scaling-chunk", type=int, default=250)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--skip", default="", help="comma-separated parts to skip: dh, zhakash, pareto, dask")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    skip = set(filter(None, args.skip.split(",")))
    print(f"load average {os.getloadavg()[0]:.1f}, {len(os.sched_getaffinity(0))} cores", flush=True)
    summary: dict = {}
    if "dh" not in skip:
        dh = den_hartog(args.dh_seeds, args.dh_budget)
        summary["den_hartog"] = dh
        print(f"\nDen Hartog absorber, budget {args.dh_budget}, {args.dh_seeds} optimiser seeds")
        print("| optimiser | evaluations to within 1 % (median, runs reaching it) | best / floor at the budget (median, worst) "
              "| CPU-s per search (median) |")
        for opt, runs in dh.items():
            hit = [r["evals_to_1pct"] for r in runs if r["evals_to_1pct"] is not None]
            best = [r["best_over_floor"] for r in runs]
            print(f"| {opt} | {np.median(hit) if hit else '-'} ({len(hit)}/{len(runs)}) | {np.median(best):.4f}, "
                  f"{max(best):.4f} | {np.median([r['cpu_s'] for r in runs]):.2f} |")
    if "zhakash" not in skip:
        print(f"\nzhakash-k2: least ball mass, P(balanced) >= 0.99 at 1.8/2.2/2.6 p, {args.starts} starts, "
              f"budget {args.budget}", flush=True)  # fmt: skip
        runs = zhakash(args.starts, args.budget, args.seeds, args.out)
        masses = [float(ds.objective_value.values[int(ds.attrs["best"]), 0]) for ds in runs.values()
                  if int(ds.attrs["best"]) >= 0]  # fmt: skip
        # closed form: the rotor counts as balanced when its deflection is below BALANCED_FRACTION of
        # the unbalance's alone, i.e. 2 m R >= (1 - BALANCED_FRACTION) M1 e (both balls together)
        from rotorlab.explore._outcome import BALANCED_FRACTION

        ref = 2.0 * (1.0 - BALANCED_FRACTION) * 2.0 * 1.08e-3 / (2.0 * 0.060)
        rows = {}
        print(f"closed-form least ball mass: {ref * 1e3:.2f} g of balls ({ref * 500:.2f} g each); lightest feasible "
              f"found by any run: {min(masses) * 1e3 if masses else math.nan:.2f} g")  # fmt: skip
        print("| run | best (g) | evaluations to within 2 % of the closed form | feasible designs | search CPU-s | "
              "CPU-s per evaluation (mean, max) | check P(balanced) inside |")
        from rotorlab.analyses._design_case import check_agrees

        for key, ds in runs.items():
            obj = np.where(ds.feasible.values, ds.objective_value.values[:, 0], np.inf)
            within = np.flatnonzero(obj <= 1.02 * ref)
            best = int(ds.attrs["best"])
            each = json.loads(ds.attrs["trial_cpu_s"])
            per = (float(np.mean(each)), float(np.max(each)))
            rows[key] = {"best_g": float(obj.min() * 1e3), "evals_to_2pct": int(within[0]) + 1 if within.size else None,
                         "feasible": int(ds.feasible.values.sum()), "cpu_s": float(ds.attrs["cpu_s"]),
                         "verify_cpu_s": float(ds.attrs["verify_cpu_s"]), "curve_g": (np.minimum.accumulate(obj) * 1e3).tolist(),
                         "best_values": ds.value.values[best].tolist() if best >= 0 else None,
                         "check": check_agrees(ds)}  # fmt: skip
            r = rows[key]
            print(f"| {key} | {r['best_g']:.2f} | {r['evals_to_2pct'] or '-'} | {r['feasible']}/{ds.sizes['trial']} | "
                  f"{r['cpu_s']:.0f} (+{r['verify_cpu_s']:.0f} check) | {per[0]:.1f}, {per[1]:.1f} | {r['check']} |")
        summary["zhakash"] = rows
        summary["zhakash_closed_form_g"] = ref * 1e3
        _convergence_figure(summary, args.out)
    if "pareto" not in skip:
        from rotorlab.analyses._design_case import run_design_analysis
        from rotorlab.io import load_case
        from rotorlab.plot._design import design_figure, tradeoff_figure

        t = _cpu()
        ds = run_design_analysis(load_case("zhakash-k2").model,
                                 _spec(["ball-mass", "settle-time"], args.starts, args.pareto_budget, "tpe", 0))
        cpu = _cpu() - t
        ds.to_netcdf(args.out / "zhakash_pareto.nc")
        tradeoff_figure(ds).savefig(args.out / "zhakash_tradeoff.png", dpi=110)
        design_figure(ds).savefig(args.out / "zhakash_pareto_designs.png", dpi=110)
        front = np.flatnonzero(ds.pareto.values)
        print(f"\nPareto (ball mass, settle time), budget {args.pareto_budget}: {front.size} designs on the front, "
              f"{cpu:.0f} CPU-s")  # fmt: skip
        for i in front[np.argsort(ds.objective_value.values[front, 0])]:
            m, b = ds.value.values[i]
            print(f"  ball_mass {m * 1e3:.1f} g, ball_damping {b:.3g} N m s: balls {ds.objective_value.values[i, 0] * 1e3:.1f} g, "
                  f"settle {ds.objective_value.values[i, 1]:.2f} s")  # fmt: skip
        summary["pareto_cpu_s"] = cpu
    if "dask" not in skip:
        print(f"\nDask scaling: zhakash-k2 TPE design, {args.scaling_budget} designs x 3 speeds x {args.scaling_starts} "
              f"starts, chunks of {args.scaling_chunk}, {args.repeats} repeats interleaved", flush=True)
        sc = dask_scaling(args.scaling_starts, args.scaling_budget, args.scaling_chunk, args.repeats)
        wall = {w: [r["wall_s"] for r in sc["runs"] if r["workers"] == w] for w in (1, 2)}
        cpu = {w: [r["cpu_s"] for r in sc["runs"] if r["workers"] == w] for w in (1, 2)}
        print(f"median wall 1 worker {np.median(wall[1]):.1f} s, 2 workers {np.median(wall[2]):.1f} s: speed-up "
              f"{np.median(wall[1]) / np.median(wall[2]):.2f} (2.0 linear); median CPU-s {np.median(cpu[1]):.1f}, "
              f"{np.median(cpu[2]):.1f}; load after {sc['load_after']:.1f}")
        summary["dask_scaling"] = sc
    (args.out / "design_bench.json").write_text(json.dumps(summary, indent=1, default=float))


def _convergence_figure(summary: dict, out: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 4.0), layout="constrained")
    a, b = fig.subplots(1, 2)
    colours = {"tpe": "tab:blue", "differential-evolution": "tab:orange"}
    for opt, runs in summary.get("den_hartog", {}).items():
        for k, r in enumerate(runs):
            a.plot(np.arange(1, len(r["curve"]) + 1), r["curve"], color=colours[opt], alpha=0.5,
                   label=opt if k == 0 else None)  # fmt: skip
    a.axhline(1.01, color="0.5", ls=":", label="1 % above the floor")
    a.set_ylim(0.99, 1.3)
    a.set(xlabel="evaluation", ylabel="best peak / sqrt(1 + 2/mu)", title="Den Hartog absorber")
    a.legend(fontsize=8)
    for key, r in summary.get("zhakash", {}).items():
        opt = key.split("/")[0]
        b.plot(np.arange(1, len(r["curve_g"]) + 1), r["curve_g"], color=colours[opt], alpha=0.7,
               label=opt if key.endswith("/0") else None)  # fmt: skip
    if summary.get("zhakash_closed_form_g"):
        b.axhline(summary["zhakash_closed_form_g"], color="0.5", ls=":", label="closed form")
    b.set(xlabel="evaluation", ylabel="lightest feasible balls so far (g)", title="zhakash-k2, P(balanced) >= 0.99")
    b.legend(fontsize=8)
    fig.savefig(out / "design_optimizers.png", dpi=110)


if __name__ == "__main__":
    main()
