"""Benchmark: the rotor striking its housing (seed 001, ``krasnov-crusher``), against solve_ivp.

Usage::

    python bench/impacts.py [--masses 3,2,1.5] [--sequences 8] [--t-end 10] [--scipy-t-end 1]
                            [--threads 2] [--json]

What it does:

1. one-core time per 10 s run of the general case (:func:`rotorlab.analyses.impact_sweep` with
   ``threads=1``) at each stone mass over ``--sequences`` random stone sequences, with the
   number of contacts (impacts, chatter included, plus sliding episodes) and how the runs
   ended. At 3 kg most runs are stopped early by the dry-friction backward whirl, so the
   script also times 3 kg with the whirl detection off (``whirl_limit`` huge): those runs go on
   sliding until the small-motion model breaks down (reported, and timed as far as they get);
2. the same ensemble on ``--threads`` threads (trajectories per wall-second);
3. a plain ``scipy.integrate.solve_ivp`` baseline on a short run (``--scipy-t-end`` s, 1 kg,
   seed 0): RK45 at the same tolerances, a pure-Python right-hand side (stone pushes by
   ``numpy.interp`` of the same table), integration piecewise between stone arrivals and
   departures, impacts as terminal events with the same impact map and restarts (no sliding
   mode: what a user writes without rotorlab). Prints both times for that run, their ratio and
   the impact counts of both.

Compilation is excluded (a warm-up runs first). Machines are noisy: compare numbers from one run.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from dataclasses import replace

import numpy as np

from rotorlab.analyses import impact_sweep
from rotorlab.models import krasnov_crusher


# ---- the baseline: what a user writes with solve_ivp -------------------------------------------
def scipy_run(model, t_end, rtol, atol):
    """Impact count and CPU seconds of one run with solve_ivp (free flight + impact map only)."""
    from scipy.integrate import solve_ivp

    r, h, s = model.rotor, model.housing, model.stones
    m, a1, a3, w0 = r.mass, r.inertia_transverse, r.inertia_polar, r.spin_speed
    c, nm, cs, gam = r.stiffness, r.membrane_offset, r.tilt_stiffness, r.internal_friction
    gw = gam / w0
    sb, lp, hp, gap = math.sin(h.cone_angle), h.lever(), h.height, h.gap
    k, f = h.restitution, h.friction
    inv_ms = sb * sb / m + lp * lp / a1
    hq = s.height
    push = model.push()
    seq = model.sequence
    scale = seq.masses * w0 * w0 * s.radius
    ang = seq.angles()
    ca, sa = np.cos(ang), np.sin(ang)
    t_push = push.tau_end / w0

    def stones(t):
        fx = fy = 0.0
        for n in np.nonzero((seq.times <= t) & (t < seq.times + t_push))[0]:
            tau = w0 * (t - seq.times[n])
            jx = np.interp(tau, push.tau, push.jx)
            jy = np.interp(tau, push.tau, push.jy)
            fx += scale[n] * (ca[n] * jx - sa[n] * jy)
            fy += scale[n] * (sa[n] * jx + ca[n] * jy)
        return fx, fy

    def rhs(t, y):
        u1, u2, t1, t2, du1, du2, dt1, dt2 = y
        um1, um2, vm1, vm2 = u1 + nm * t1, u2 + nm * t2, du1 + nm * dt1, du2 + nm * dt2
        fm1 = -c * (um1 + gw * vm1 - gam * um2)
        fm2 = -c * (um2 + gw * vm2 + gam * um1)
        fq1, fq2 = stones(t)
        mm1 = nm * fm1 - cs * (t1 + gw * dt1 - gam * t2) + hq * fq1
        mm2 = nm * fm2 - cs * (t2 + gw * dt2 + gam * t1) + hq * fq2
        g = (a3 - 2 * a1) * w0
        kk = (a1 - a3) * w0 * w0
        return [du1, du2, dt1, dt2,
                2 * w0 * du2 + w0 * w0 * u1 + (fm1 + fq1) / m, -2 * w0 * du1 + w0 * w0 * u2 + (fm2 + fq2) / m,
                (-g * dt2 + kk * t1 + mm1) / a1, (g * dt1 + kk * t2 + mm2) / a1]  # fmt: skip

    def hit(t, y):
        return gap - math.hypot(sb * y[0] + lp * y[2], sb * y[1] + lp * y[3])

    hit.terminal = True
    hit.direction = -1
    edges = np.unique(np.concatenate([[0.0], seq.times, seq.times + t_push, [t_end]]))
    edges = edges[edges <= t_end]
    y = np.zeros(8)
    impacts = 0
    start = time.process_time()
    for lo, hi in zip(edges[:-1], edges[1:]):
        t = lo
        while t < hi:
            sol = solve_ivp(rhs, (t, hi), y, method="RK45", rtol=rtol, atol=atol, events=hit)
            y = sol.y[:, -1].copy()
            t = sol.t[-1]
            if sol.status == 1:  # impact: the map of rotorlab.models._impact_rotor, eq. (3.9)
                w = np.array([sb * y[0] + lp * y[2], sb * y[1] + lp * y[3]])
                e = w / np.hypot(*w)
                v = e @ np.array([sb * y[4] + lp * y[6], sb * y[5] + lp * y[7]])
                if v <= 0:
                    continue
                impacts += v >= h.count_speed
                sn = (1 + k) * v / inv_ms
                y[4] -= sn / m * (sb * e[0] - f * e[1])
                y[5] -= sn / m * (sb * e[1] + f * e[0])
                y[6] -= sn / a1 * (lp * e[0] - f * hp * e[1])
                y[7] -= sn / a1 * (lp * e[1] + f * hp * e[0])
                # step off the surface so that the event does not fire again at once
                t = np.nextafter(t, math.inf)
            elif sol.status < 0:
                raise RuntimeError(sol.message)
    return impacts, time.process_time() - start


def _contacts(ds):
    return ds.impacts_all.values + ds.slides.values


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--masses", default="3,2,1.5")
    ap.add_argument("--sequences", type=int, default=8)
    ap.add_argument("--t-end", type=float, default=10.0)
    ap.add_argument("--scipy-t-end", type=float, default=1.0)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    masses = [float(x) for x in args.masses.split(",")]
    base = krasnov_crusher()
    rtol, atol = 1e-8, 1e-11
    impact_sweep(base, [1.0], n_sequences=1, t_end=0.1, threads=1)  # compile / load the cache
    rows = []
    for mass in masses:
        for whirl in (True, False) if mass >= 3.0 else (True,):
            model = base if whirl else replace(base, housing=replace(base.housing, whirl_limit=1e12))
            t0 = time.process_time()
            ds = impact_sweep(model, [mass], n_sequences=args.sequences, t_end=args.t_end, threads=1,
                              rtol=rtol, atol=atol)  # fmt: skip
            cpu = time.process_time() - t0
            tf = ds.t_final.values[0]
            rows.append({
                "stone_mass_kg": mass, "whirl_detection": whirl, "runs": args.sequences,
                "cpu_s_per_run": cpu / args.sequences,
                "simulated_s_per_run": float(tf.mean()),
                "cpu_s_per_simulated_10s": cpu / float(tf.sum()) * 10.0,
                "contacts_per_run": float(_contacts(ds)[0].mean()),
                "steps_per_run": float(ds.n_steps.values.mean()),
                "ended": {k: int(v) for k, v in zip(*np.unique(
                    np.where(ds.status.values[0] < 0, "failed", np.where(ds.whirl.values[0] > 0, "whirl", "t_end")),
                    return_counts=True))},
            })  # fmt: skip
    t0 = time.perf_counter()
    ds = impact_sweep(base, [masses[-1]], n_sequences=8 * args.threads, t_end=args.t_end, threads=args.threads)
    wall = time.perf_counter() - t0
    parallel = {"threads": args.threads, "runs": 8 * args.threads, "runs_per_wall_s": 8 * args.threads / wall,
                "stone_mass_kg": masses[-1]}  # fmt: skip
    # ---- baseline on a short run ----
    short = base.with_stones(args.scipy_t_end, 0, mass=1.0)
    n_sp, cpu_sp = scipy_run(short, args.scipy_t_end, rtol, atol)
    t0 = time.process_time()
    reps = 20
    for _ in range(reps):
        ds1 = impact_sweep(replace(base, stones=replace(base.stones, mass=1.0)), [1.0], n_sequences=1,
                           t_end=args.scipy_t_end, seed=0, threads=1, rtol=rtol, atol=atol)  # fmt: skip
    cpu_rl = (time.process_time() - t0) / reps
    baseline = {"t_end_s": args.scipy_t_end, "stone_mass_kg": 1.0, "scipy_cpu_s": cpu_sp, "rotorlab_cpu_s": cpu_rl,
                "ratio": cpu_sp / cpu_rl, "scipy_impacts": int(n_sp), "rotorlab_impacts": int(ds1.impacts.values[0, 0])}  # fmt: skip
    doc = {"machine": platform.processor() or platform.machine(), "python": sys.version.split()[0],
           "runs": rows, "parallel": parallel, "baseline": baseline}  # fmt: skip
    if args.json:
        print(json.dumps(doc, indent=2))
        return
    print(f"krasnov-crusher, general case, {args.t_end:g} s runs, rtol {rtol:g}, one core:")
    print(f"{'mass':>5} {'whirl det.':>10} {'CPU s/run':>10} {'sim. s/run':>10} {'CPU s/10 s':>10} "
          f"{'contacts':>9} {'steps':>8}  ended")  # fmt: skip
    for r in rows:
        print(f"{r['stone_mass_kg']:5g} {str(r['whirl_detection']):>10} {r['cpu_s_per_run']:10.3f} "
              f"{r['simulated_s_per_run']:10.3f} {r['cpu_s_per_simulated_10s']:10.3f} {r['contacts_per_run']:9.0f} "
              f"{r['steps_per_run']:8.0f}  {r['ended']}")  # fmt: skip
    print(f"parallel: {parallel['runs']} runs at {parallel['stone_mass_kg']:g} kg on {parallel['threads']} threads: "
          f"{parallel['runs_per_wall_s']:.1f} runs per wall-second")  # fmt: skip
    b = baseline
    print(f"baseline, {b['t_end_s']:g} s at 1 kg, seed 0: solve_ivp {b['scipy_cpu_s']:.3f} CPU s "
          f"({b['scipy_impacts']} impacts), rotorlab {b['rotorlab_cpu_s']:.5f} CPU s ({b['rotorlab_impacts']} impacts): "
          f"ratio {b['ratio']:.0f}x")  # fmt: skip


if __name__ == "__main__":
    main()
