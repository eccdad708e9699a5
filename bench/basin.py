"""Benchmark: basin of ``strautmanis-torus`` (seed 004 Fig. 6) against a ``solve_ivp`` loop.

Usage::

    python bench/basin.py [--n 256] [--t-end 20] [--k 1e-5] [--form rolling]
                          [--scipy-n 32] [--threads 2] [--json] [--save basin.nc]
                          [--scalar] [--repeats R]

What it does:

1. :func:`rotorlab.explore.basin_map` on an ``n x n`` grid of the (psi0, psi0') plane,
   psi0 in [0, 2 pi], psi0' in [-280, 140] 1/s, alpha0 = alpha0' = 0, for the toroidal ball with
   the paper's parameters and rolling friction ``k`` (stick/slip by events and reset maps);
2. the same trajectories, for a subset of ``--scipy-n`` grid points drawn at random (seed 0)
   from the grid, with a plain ``scipy.integrate.solve_ivp``
   loop: RK45 at the same tolerances, a pure-Python right-hand side, stick/slip by terminal
   events and restarts with the same reset rules, the normal-force zero crossings counted by a
   non-terminal event (what a user writes without rotorlab);
3. prints trajectories per CPU-second of both (``time.process_time``: all threads of this
   process), their ratio (target: >= 500), and how often the two agree on the label.

Compilation is excluded (a 2 x 2 warm-up grid runs first). Machines are noisy: compare ratios
from one run. The spare regime is chaotic (the ball bounces round the tube), so individual
labels of the two integrators can differ near the end of long transients; the agreement is
reported, not required.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time

import numpy as np

from rotorlab.explore import GridAxis, TorusRegimes, basin_fractions, basin_map
from rotorlab.models._toroidal_ball import strautmanis_torus

PSI = (0.0, 2.0 * math.pi)
DPSI = (-280.0, 140.0)


# ---- the baseline: what a user writes with solve_ivp -------------------------------------------
def _terms(y, p):
    """F_psi, F_alpha, B_psi, B_alpha, N of the model (see rotorlab._kernels.toroidal_ball)."""
    R, R1, rb, om, e, k, g, c_rho, c_rel, c_cor, c_nrm, fac_alpha = p
    a = R1 - rb
    psi, alpha, dpsi, dalpha = y
    sa, ca, sp, cp = math.sin(alpha), math.cos(alpha), math.sin(psi), math.cos(psi)
    rho = R + c_rho * a * sa
    w = om + dpsi
    eo2 = e * om * om
    normal = g * ca + rho * w * w * sa + a * dalpha * dalpha - c_nrm * eo2 * sa * cp
    f_psi = -(a * ca / rho) * dalpha * (2.0 * c_rel * dpsi + c_cor * om) + 5.0 / 7.0 * eo2 * sp / rho
    f_alpha = (rho * ca / a) * (c_rel * dpsi * dpsi + c_cor * om * dpsi + 5.0 / 7.0 * om * om)
    f_alpha -= 5.0 / 7.0 * (eo2 * ca * cp + g * sa) / a
    nk = 5.0 / 7.0 * k * max(normal, 0.0) / rb
    return f_psi, f_alpha, nk / rho, nk * fac_alpha / a, normal


def _make_rhs(p, modes):
    def rhs(t, y):
        dpsi = 0.0 if modes[0] == 0 else y[2]
        dalpha = 0.0 if modes[1] == 0 else y[3]
        f_psi, f_alpha, b_psi, b_alpha, _ = _terms((y[0], y[1], dpsi, dalpha), p)
        return [dpsi, dalpha, 0.0 if modes[0] == 0 else f_psi - b_psi * modes[0],
                0.0 if modes[1] == 0 else f_alpha - b_alpha * modes[1]]  # fmt: skip

    return rhs


def _make_events(p, modes):
    def event(j, kind):
        def fn(t, y):
            dpsi = 0.0 if modes[0] == 0 else y[2]
            dalpha = 0.0 if modes[1] == 0 else y[3]
            f = _terms((y[0], y[1], dpsi, dalpha), p)
            if kind == "lift":
                return f[4]
            if kind == "stick":
                return y[2 + j] * modes[j] if modes[j] != 0 else 1.0
            return f[2 + j] - abs(f[j]) if modes[j] == 0 else 1.0

        fn.terminal = kind != "lift"
        fn.direction = -1
        return fn

    return [event(0, "stick"), event(0, "slip"), event(1, "stick"), event(1, "slip"), event(0, "lift")]


def solve_ivp_trajectory(model, y0, t_end, rtol, atol, window):
    """One trajectory with stick/slip by restarts; returns ``(label, nfev, switches, lift_offs)``.

    solve_ivp restarts on each terminal event with the new modes. A start exactly on an event
    surface can fire the same event again at once (a ball at the edge of its friction band:
    round-off decides between stick and slip); after such a restart without progress the
    other choice is taken, and after two the offending event is switched off for 1e-9 s. This
    is the user's side of what the compiled integrator does by probing g(s)/s after a reset.
    """
    from scipy.integrate import solve_ivp

    p = tuple(model.to_array()[:12])
    y = np.array(y0[:4], dtype=float)
    modes = [float(y0[4]), float(y0[5])]
    t, t_switch, lift, switches, nfev, stalls = 0.0, 0.0, 0, 0, 0, 0
    psi_window = None
    t_window = max(t_end - window, 0.0)
    while t < t_end:
        events = _make_events(p, modes)
        t_stop = t_end
        if stalls >= 2:  # step over the edge of the band with that event off
            events = [ev for j, ev in enumerate(events) if j != k]
            t_stop = min(t_end, t + 1e-9)
        sol = solve_ivp(_make_rhs(p, modes), (t, t_stop), y, method="RK45", rtol=rtol, atol=atol,
                        events=events, dense_output=True)  # fmt: skip
        nfev += sol.nfev
        lift += len(sol.t_events[-1])
        if psi_window is None and sol.t[-1] >= t_window:
            psi_window = float(sol.sol(t_window)[0])
        if sol.status != 1:
            t, y = float(sol.t[-1]), sol.y[:, -1]
            stalls = 0
            if sol.status < 0 or t >= t_end:
                break
            continue
        names = [0, 1, 2, 3, 4] if len(events) == 5 else [j for j in range(5) if j != k]
        hits = [(sol.t_events[i][0], names[i]) for i in range(len(events)) if names[i] < 4 and len(sol.t_events[i])]
        t_ev, k = min(hits)
        y = np.array(sol.y_events[names.index(k)][0], dtype=float)
        stalls = stalls + 1 if t_ev <= t + 1e-12 * max(1.0, t) else 0
        t = float(t_ev)
        j = k // 2
        y[2 + j] = 0.0
        before = modes[j]
        modes[j] = 0.0
        f = _terms((y[0], y[1], y[2] if modes[0] else 0.0, y[3] if modes[1] else 0.0), p)
        roll = k % 2 == 1 or abs(f[j]) > f[2 + j]
        if stalls == 1:
            roll = before == 0.0  # the other choice than the one that stalled
        if roll:
            modes[j] = 1.0 if f[j] > 0 else -1.0
        t_switch = t
        switches += 1
    stuck = modes == [0.0, 0.0] and t_switch <= t_window
    turns = abs(y[0] - (psi_window if psi_window is not None else y[0])) / (2.0 * math.pi)
    label = 0 if stuck and math.cos(y[0]) < 0 else (1 if not stuck and turns >= 1.0 else 2)
    return label, nfev, switches, lift


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=256, help="grid points per axis (default 256)")
    ap.add_argument("--t-end", type=float, default=20.0, help="simulated time (s, default 20)")
    ap.add_argument("--k", type=float, default=1e-5, help="rolling friction (m, default 1e-5)")
    ap.add_argument("--form", default="rolling", choices=("rolling", "paper"))
    ap.add_argument("--scipy-n", type=int, default=32, help="solve_ivp subset size (default 32)")
    ap.add_argument("--threads", type=int, default=None, help="integrator threads (default: numba's)")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    ap.add_argument("--save", default=None, help="write the basin Dataset to this NetCDF file")
    ap.add_argument("--scalar", action="store_true", help="also run the grid on the scalar driver")
    ap.add_argument("--repeats", type=int, default=1, help="interleaved rounds (default 1; the least CPU counts)")
    args = ap.parse_args(argv)

    model = strautmanis_torus(args.k, form=args.form)
    mapper = TorusRegimes(model, t_end=args.t_end, n_horizons=max(1, int(round(args.t_end / 5.0))))
    fixed = {"alpha": 0.0, "dalpha": 0.0}
    x, y = GridAxis("psi", *PSI, args.n), GridAxis("dpsi", *DPSI, args.n)
    basin_map(TorusRegimes(model, t_end=1.0, n_horizons=1), GridAxis("psi", *PSI, 2), GridAxis("dpsi", *DPSI, 2),
              fixed=fixed, threads=args.threads)  # warm-up: compile or load the cached driver

    from rotorlab.integrate import _drivers

    def run(lanes: bool):
        """The basin on the lane driver (the default) or, for comparison, the scalar driver."""
        real = _drivers.default_lanes
        if not lanes:
            _drivers.default_lanes = lambda kernels, n_traj: None
        try:
            c0, w0 = time.process_time(), time.perf_counter()
            out = basin_map(mapper, x, y, fixed=fixed, threads=args.threads)
            return out, time.process_time() - c0, time.perf_counter() - w0
        finally:
            _drivers.default_lanes = real

    if args.scalar:  # warm-up of the scalar driver too
        _drivers.default_lanes, real = (lambda kernels, n_traj: None), _drivers.default_lanes
        basin_map(TorusRegimes(model, t_end=1.0, n_horizons=1), GridAxis("psi", *PSI, 2),
                  GridAxis("dpsi", *DPSI, 2), fixed=fixed, threads=args.threads)  # fmt: skip
        _drivers.default_lanes = real
    cpu_scalar = []
    cpu_lanes = []
    for _ in range(args.repeats):  # interleaved rounds: the load of the machine hits both alike
        ds, cpu, wall = run(True)
        cpu_lanes.append(cpu)
        if args.scalar:
            ds_scalar, c_s, _ = run(False)
            cpu_scalar.append(c_s)
            assert np.array_equal(ds_scalar.outcome.values, ds.outcome.values)  # bit-identical drivers
    cpu = min(cpu_lanes)
    n_traj = args.n * args.n

    labels = ds.outcome.values.ravel()
    subset = np.sort(np.random.default_rng(0).choice(n_traj, min(args.scipy_n, n_traj), replace=False))
    P, D = np.meshgrid(x.values, y.values)
    y0 = model.initial_state(P.ravel()[subset], 0.0, D.ravel()[subset], 0.0)
    c0 = time.process_time()
    base = [solve_ivp_trajectory(model, row, args.t_end, mapper.control.rtol, mapper.control.atol, mapper.window)
            for row in y0]  # fmt: skip
    cpu_ivp = time.process_time() - c0
    agree = float(np.mean([b[0] == labels[i] for b, i in zip(base, subset)]))
    fr = basin_fractions(ds).fraction.isel(horizon=-1)
    res = {
        "grid": f"{args.n}x{args.n}", "t_end_s": args.t_end, "k_m": args.k, "form": args.form,
        "trajectories": n_traj, "cpu_s": cpu, "wall_s": wall,
        "rotorlab_traj_per_cpu_s": n_traj / cpu,
        "rotorlab_cpu_s_rounds": cpu_lanes,
        "scalar_driver_traj_per_cpu_s": n_traj / min(cpu_scalar) if cpu_scalar else None,
        "scalar_cpu_s_rounds": cpu_scalar,
        "load_average": list(__import__("os").getloadavg()),
        "scipy_trajectories": int(subset.size), "scipy_cpu_s": cpu_ivp,
        "scipy_traj_per_cpu_s": subset.size / cpu_ivp,
        "rotorlab_subset_traj_per_cpu_s": None,
        "ratio": (n_traj / cpu) / (subset.size / cpu_ivp),
        "label_agreement": agree,
        "fractions": {str(k): float(v) for k, v in zip(fr.regime.values, fr.values)},
        "mean_steps": float(ds.n_steps.mean()),
        "scipy_mean_nfev": float(np.mean([b[1] for b in base])),
        "python": sys.version.split()[0], "machine": platform.processor() or platform.machine(),
    }  # fmt: skip
    # the subset alone with rotorlab (a fair per-trajectory comparison: same starts)
    from rotorlab.explore import map_starts

    sub = {"psi": P.ravel()[subset], "dpsi": D.ravel()[subset], **fixed}
    c0 = time.process_time()
    map_starts(mapper, sub, threads=args.threads)
    res["rotorlab_subset_traj_per_cpu_s"] = subset.size / (time.process_time() - c0)
    res["ratio_same_subset"] = res["rotorlab_subset_traj_per_cpu_s"] / res["scipy_traj_per_cpu_s"]
    if args.save:
        ds.to_netcdf(args.save)
    if args.json:
        print(json.dumps(res, indent=2))
    else:
        print(f"basin {res['grid']}, t_end = {args.t_end:g} s, k = {args.k:g} m, form = {args.form}")
        print(f"  rotorlab : {n_traj} trajectories, {cpu:.1f} CPU-s ({wall:.1f} s wall): "
              f"{res['rotorlab_traj_per_cpu_s']:.1f} traj/CPU-s, mean {res['mean_steps']:.0f} steps")
        if cpu_scalar:
            print(f"  scalar driver: {res['scalar_driver_traj_per_cpu_s']:.1f} traj/CPU-s "
                  f"(lanes / scalar = {res['rotorlab_traj_per_cpu_s'] / res['scalar_driver_traj_per_cpu_s']:.2f})")
        print(f"  load average {res['load_average']}")
        print(f"  solve_ivp: {subset.size} trajectories, {cpu_ivp:.1f} CPU-s: "
              f"{res['scipy_traj_per_cpu_s']:.3f} traj/CPU-s, mean {res['scipy_mean_nfev']:.0f} nfev")
        print(f"  ratio {res['ratio']:.0f}x (whole grid vs subset), {res['ratio_same_subset']:.0f}x (same subset)")
        print(f"  labels agree on {agree:.0%} of the subset; fractions {res['fractions']}")
    return res


if __name__ == "__main__":
    main()
