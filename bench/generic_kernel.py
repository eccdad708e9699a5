"""Layout-generic compiled kernel against per-layout unrolling (issue 24 item 6).

The kernel under test is :func:`_generic_rhs.rhs_generic` (one compiled function for every layout
of the machine's common subset, lanes innermost); the reference is the machine's generated kernel
of each layout (:mod:`rotorlab._kernels.machine_codegen`) in the lane driver's loop over lanes
(``_rhs_lanes`` of :mod:`rotorlab.integrate._lanes`, the kernel inlined, as the driver runs it).

1. ``check``: the same right-hand side to 1e-12 (largest difference over the largest magnitude of
   each state block) on random states of pico21-balancer's layouts with races [0] and [0, 1]
   (tilting races) and of the planar one-mass machine of ``bench/machine.py`` (planar race).
2. ``compile``: CPU seconds to compile the generic kernel (once per install) and, per layout, the
   generated kernel plus the lane driver's loop over lanes with it inlined; each in a fresh
   process, the package's own numba caches warm, the rotorlab compile cache empty.
3. ``speed``: right-hand-side evaluations per CPU-second for 8 lanes, both kernels on both
   pico21-balancer layouts, in compiled timing loops, interleaved repeats (CPU time).
4. ``driver``: what a Dormand-Prince step of the lane driver costs on races [0] (64 starts,
   1 thread; run it twice, the second run loads the driver from the cache): the kernel's share.

Usage::

    ROTORLAB_CACHE_DIR=/tmp/rlcache python bench/generic_kernel.py check
    python bench/generic_kernel.py compile
    python bench/generic_kernel.py speed --repeats 5
    ROTORLAB_CACHE_DIR=/tmp/rlcache python bench/generic_kernel.py driver
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

L = 8
DENSE = ("loops", "blocked")  # the two forms of the generic kernel's dense products


def cpu():
    return time.process_time()


def pico21(races):
    from rotorlab.analyses._case import build_model
    from rotorlab.io import load_case

    m = build_model(load_case("pico21-balancer").model)
    return replace(m, races=tuple(m.races[i] for i in races))


def planar():
    from machine import planar_pair

    return planar_pair()[0]


MODELS = {"pico21[0]": lambda: pico21([0]), "pico21[0,1]": lambda: pico21([0, 1]), "planar": planar}


def random_states(model, n, seed=0):
    """``n`` random states and times: structure coordinates of the size of the unbalance response
    (0.1 mm, 10 mm/s), any ball angles, ball rates within 20 % of the spin."""
    rng = np.random.default_rng(seed)
    lay = model.layout
    om = model.to_array()[lay.offsets["speed"] + 1]
    y = np.empty((n, model.n_state))
    y[:, :lay.n_z] = rng.normal(0, 1e-4, (n, lay.n_z))
    y[:, lay.n_z:2 * lay.n_z] = rng.normal(0, 1e-2, (n, lay.n_z))
    y[:, lay.i_phi:lay.i_w] = rng.uniform(0, 2 * np.pi, (n, lay.n_balls))
    y[:, lay.i_w:lay.i_w + lay.n_balls] = om * rng.uniform(0.8, 1.2, (n, lay.n_balls))
    return rng.uniform(0, 1.0, n), y


def interleave(a):
    """Rows (lanes) of ``a`` (lanes x n) to the lane-interleaved vector (n x lanes, flat)."""
    return np.ascontiguousarray(a.T).ravel()


def generic_args(model, t, y):
    """The generic kernel's arguments for the lanes ``t``, ``y`` (rows) and the model's parameters."""
    from _generic_rhs import table

    tab, n_work = table(model.layout)
    p = np.tile(model.to_array(), (len(t), 1))
    return (np.ascontiguousarray(t), interleave(y), interleave(p), tab, np.zeros(n_work * L),
            np.zeros(model.n_state * L))


def check(args):
    from _generic_rhs import kernel, rhs_generic

    worst = 0.0
    for dense in ("loops", "blocked"):
        worst = max(worst, _check(args, rhs_generic if dense == "loops" else kernel(dense), dense))
    print(f"largest: {worst:.2e} (limit 1e-12): {'PASS' if worst <= 1e-12 else 'FAIL'}")
    return 0 if worst <= 1e-12 else 1


def _check(args, rhs_generic, dense):
    worst = 0.0
    for name, make in MODELS.items():
        model = make()
        rhs, lay = model.kernels.rhs, model.layout
        p = model.to_array()
        t, y = random_states(model, args.n)
        ref = np.empty_like(y)
        for i in range(len(t)):
            rhs(t[i], y[i], p, ref[i])
        got = np.empty_like(y)
        for k in range(0, len(t), L):
            a = generic_args(model, t[k:k + L], y[k:k + L])
            rhs_generic(*a, L)
            got[k:k + L] = a[5].reshape(-1, L).T
        blocks = {"z'": (0, lay.n_z), "z''": (lay.n_z, 2 * lay.n_z), "phi'": (lay.i_phi, lay.i_w),
                  "phi''": (lay.i_w, lay.i_w + lay.n_balls)}
        rel = {k: float(np.max(np.abs(got[:, i:j] - ref[:, i:j])) / np.max(np.abs(ref[:, i:j])))
               for k, (i, j) in blocks.items()}
        worst = max(worst, *rel.values())
        print(f"{dense:7s} {name:12s} layout {lay.key}, {model.n_state} states, {args.n} random states: "
              "largest difference / largest magnitude per block "
              + ", ".join(f"{k} {v:.1e}" for k, v in rel.items()))
    return worst


# ---- compile times, each in a fresh process ---------------------------------------------------

def _compile_generic():
    from numba import typeof

    import _generic_rhs as g

    model = pico21([0])
    t, y = random_states(model, L)
    a = generic_args(model, t, y) + (L,)
    sig = tuple(typeof(x) for x in a)
    out = {}
    for dense in DENSE:
        fresh = g.kernel(dense)
        c = cpu()
        fresh.compile(sig)
        out[f"generic kernel ({dense}), compiled"] = cpu() - c
    c = cpu()
    g.rhs_generic.compile(sig)  # from numba's cache when it holds it (the second child run)
    out["generic kernel, cache=True dispatcher (loaded or compiled)"] = cpu() - c
    return out


def _compile_generated(name):
    from numba import typeof

    from rotorlab.integrate._codegen import _in_memory
    from rotorlab.integrate._drivers import _lane_consts, _roles

    model = MODELS[name]()
    kernels = model.kernels  # generates and imports the kernel module (not compiled yet)
    t, y = random_states(model, 1)
    c = cpu()
    kernels.rhs.compile(tuple(typeof(x) for x in (t[0], y[0], model.to_array(), np.empty(model.n_state))))
    t_kernel = cpu() - c
    ns = _in_memory("rotorlab.integrate._lanes", _roles(kernels), _lane_consts(kernels, L))
    W = np.zeros(ns["_P"] + model.to_array().size * L)
    c = cpu()
    ns["_rhs_lanes"].compile((typeof(W), typeof(L)))
    return {f"{name}: generated kernel": t_kernel, f"{name}: loop over lanes, kernel inlined": cpu() - c}


def compile_times(args):
    rows = {}
    for what in ["generic", "generic"] + [f"generated:{n}" for n in ("pico21[0]", "pico21[0,1]")] * 2:
        with tempfile.TemporaryDirectory() as d:
            env = dict(os.environ, ROTORLAB_CACHE_DIR=d, PYTHONPATH=os.pathsep.join(
                [str(Path(__file__).resolve().parents[1] / "src"), os.environ.get("PYTHONPATH", "")]))
            c0 = os.times()
            r = subprocess.run([sys.executable, __file__, "_child", what], env=env, capture_output=True,
                               text=True, check=True)
            c1 = os.times()
        got = json.loads(r.stdout.strip().splitlines()[-1])
        got[f"{what}: whole child process"] = (c1.children_user - c0.children_user
                                               + c1.children_system - c0.children_system)
        for k, v in got.items():
            rows.setdefault(k, []).append(v)
            print(f"  {k:62s} {v:7.2f} CPU-s", flush=True)
    return 0


# ---- throughput --------------------------------------------------------------------------------

def _timing_loops():
    from numba import njit

    from _generic_rhs import kernel

    def loop_generic(rhs_generic):
        @njit(nogil=True)
        def loop(t, y, p, tab, w, out, nl, reps, k):
            for _ in range(reps):
                y[k] += 1e-12  # a ball angle moves: nothing can be hoisted out of the loop
                rhs_generic(t, y, p, tab, w, out, nl)
        return loop

    def loop_lanes(rhs_lanes):
        @njit(nogil=True)
        def loop(W, nl, reps, k):
            for _ in range(reps):
                W[k] += 1e-12
                rhs_lanes(W, nl)
        return loop

    # compiled in this process like the generated loop (and inspectable: numba does not show
    # the LLVM IR of a function loaded from its cache)
    generic = {dense: kernel(dense) for dense in DENSE}
    return {d: (k, loop_generic(k)) for d, k in generic.items()}, loop_lanes



def packed_ops(ir, name):
    body = "\n".join(f for f in re.split(r"^define ", ir, flags=re.M)
                     if re.match(rf"[^@\n]*@_ZN(?!7cpython)[^(\n]*{name}", f))
    return len(re.findall(r"= f(?:mul|add|sub|div) (?:[a-z]+ )*<\d+ x double>", body))


def speed(args):
    from numba import typeof

    from rotorlab.integrate._codegen import _in_memory
    from rotorlab.integrate._drivers import _lane_consts, _roles

    generic, loop_lanes = _timing_loops()
    cases = []
    for name in args.layouts:
        model = MODELS[name]()
        t, y = random_states(model, L, seed=1)
        kg = model.layout.i_phi * L
        ns = _in_memory("rotorlab.integrate._lanes", _roles(model.kernels), _lane_consts(model.kernels, L))
        p = model.to_array()
        W = np.zeros(ns["_P"] + p.size * L)
        W[ns["_tt"]:ns["_tt"] + L] = t
        W[ns["_T"]:ns["_T"] + model.n_state * L] = interleave(y)
        W[ns["_P"]:] = interleave(np.tile(p, (L, 1)))
        kw = ns["_T"] + model.layout.i_phi * L
        ns["_rhs_lanes"].compile((typeof(W), typeof(L)))
        ns["_rhs_lanes"](W, L)
        q = W[ns["_Q"]:ns["_Q"] + model.n_state * L].copy()
        loop = loop_lanes(ns["_rhs_lanes"])
        loop(W, L, 1, kw)
        rl = ns["_rhs_lanes"]
        print(f"{name}: {model.n_state} states; packed double ops: generated loop "
              f"{packed_ops(rl.inspect_llvm(rl.signatures[0]), '_rhs_lanes')}", flush=True)
        cases.append((name, "generated", lambda n, f=loop, W=W, kw=kw: f(W, L, n, kw)))
        for dense, (rhs_generic, lg) in generic.items():
            ga = generic_args(model, t, y)
            rhs_generic(*ga, L)
            diff = np.max(np.abs(q - ga[5])) / np.max(np.abs(q))
            lg(*ga, L, 1, kg)
            ops = packed_ops(rhs_generic.inspect_llvm(rhs_generic.signatures[0]), "rhs_generic")
            print(f"  generic ({dense}): {ops} packed double ops; against the generated loop {diff:.1e}")
            cases.append((name, f"generic {dense}", lambda n, f=lg, a=ga, kg=kg: f(*a, L, n, kg)))
    res = {}
    for _ in range(args.repeats):
        for name, kind, run in cases:
            c = cpu()
            run(args.reps)
            res.setdefault((name, kind), []).append(args.reps * L / (cpu() - c))
    for (name, kind), v in res.items():
        print(f"  {name:12s} {kind:15s} rhs evaluations per CPU-s: median {np.median(v):10.0f} "
              f"(min {min(v):.0f}, max {max(v):.0f}, {len(v)} repeats)")
    for name in args.layouts:
        for dense in DENSE:
            r = np.median(res[(name, f"generic {dense}")]) / np.median(res[(name, "generated")])
            print(f"  {name:12s} generic {dense} / generated = {r:.3f}")
    return 0


def driver(args):
    from rotorlab.integrate import StepControl, solve_ensemble
    from machine import starts

    model = pico21([0])
    y0 = starts(model, args.n)
    ctl = StepControl(rtol=1e-8, atol=1e-10)
    c = cpu()
    solve_ensemble(model, y0[:2], (0.0, 1e-3), control=ctl, lanes=L, threads=1)
    print(f"first call (compile or load the lane driver): {cpu() - c:.1f} CPU-s")
    best = None
    for _ in range(args.repeats):
        c = cpu()
        sol = solve_ensemble(model, y0, (0.0, args.t1), control=ctl, lanes=L, threads=1)
        dt = cpu() - c
        best = dt if best is None else min(best, dt)
    nfev = float(np.sum(sol.stats[:, 0]))
    print(f"pico21[0]: {args.n} starts, t = {args.t1} s, 8 lanes, 1 thread: {best:.3f} CPU-s (min of "
          f"{args.repeats}), {nfev / args.n:.0f} rhs evaluations per trajectory, "
          f"{nfev / best:.0f} evaluations per CPU-s in the driver, {args.n / best:.1f} trajectories per CPU-s")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("check")
    c.add_argument("--n", type=int, default=64)
    sub.add_parser("compile")
    s = sub.add_parser("speed")
    s.add_argument("--repeats", type=int, default=5)
    s.add_argument("--reps", type=int, default=100_000)
    s.add_argument("--layouts", nargs="+", default=["pico21[0]", "pico21[0,1]"])
    d = sub.add_parser("driver")
    d.add_argument("--n", type=int, default=64)
    d.add_argument("--t1", type=float, default=0.2)
    d.add_argument("--repeats", type=int, default=3)
    ch = sub.add_parser("_child")
    ch.add_argument("what")
    a = ap.parse_args(argv)
    if a.cmd == "_child":
        out = _compile_generic() if a.what == "generic" else _compile_generated(a.what.split(":", 1)[1])
        print(json.dumps(out))
        return 0
    return {"check": check, "compile": compile_times, "speed": speed, "driver": driver}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
