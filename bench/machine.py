"""Benchmark of the composed machine model (issue 12), ratios against baselines in the same run.

1. Planar one-mass rotor with a two-ball race: ``machine`` (structure reduced to its 2 lateral
   modes, same 8 states) against ``jeffcott_balls``' hand-written fixed-frame kernel
   (:mod:`rotorlab._kernels.jeffcott_balls`, the tests' oracle since ``jeffcott_balls`` itself
   runs its preset machine's kernel) per trajectory (CPU time, interleaved repeats; target:
   machine / jeffcott_balls <= 1.3).
2. Trajectories per CPU-second of a 12-state two-plane rigid rotor (x, y, phi_x, phi_y and two
   one-ball races, 8 + 4 states) and of the Pico 21 centrifuge (seed 000, 12 DOFs) with one
   two-ball race at its rotor (28 states), scalar and lane drivers, against a SciPy
   ``solve_ivp`` (RK45, the compiled kernel as its right-hand side) loop on the same problems.
3. ``--sommerfeld``: bisection of the smallest stall torque that passes the critical speed in the
   torque-limited run-up of ``tests/validation/test_machine_sommerfeld.py``, with and without balls.

Usage::

    python bench/machine.py [--n 64] [--scipy-n 2] [--repeats 3] [--sommerfeld]
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def cpu():
    return time.process_time()


def planar_pair():
    from rotorlab.linear import LinearSystem
    from rotorlab.models import (Ball, BallParams, BallRace, ConstantSpeed, JeffcottBalls, Machine,
                                 RotorParams, Unbalance)

    s = LinearSystem(M=np.diag([1.0, 1.0, 0.3, 0.3]), C=np.diag([0.02, 0.02, 0.0, 0.0]),
                     G=np.zeros((4, 4)), K=np.diag([1.0, 1.0, 5.0, 5.0]))
    mac = Machine(s, races=(BallRace(0, 1.0, (Ball(0.02, damping=0.01),) * 2),),
                  unbalances=(Unbalance(0, 0.01),), drive=ConstantSpeed(2.5), n_modes=2)
    jb = JeffcottBalls(RotorParams(1.0, 0.01, 1.0, 0.02), (BallParams(0.02, 1.0, None, 0.01),) * 2,
                       speed=ConstantSpeed(2.5))
    return mac, jb


class HandWrittenJeffcott:
    """``jeffcott_balls`` on its hand-written fixed-frame kernel (the baseline of item 1)."""

    def __init__(self, jb):
        from rotorlab._kernels import jeffcott_balls as k
        from rotorlab.models import Kernels

        self.jb = jb
        self.kernels = Kernels(rhs=k.rhs_fixed_constant, n_state=jb.n_state, vectorises=True)

    def to_array(self):
        return self.jb.to_array()


def two_plane(balls_per_race=1):
    from rotorlab.linear import LinearSystem
    from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance

    M = np.diag([1.0, 1.0, 3.25, 3.25])
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = 0.5, -0.5
    K = np.zeros((4, 4))
    C = np.zeros((4, 4))
    for zs in (3.0, -3.0):
        for j in (0, 1):
            T = np.zeros((1, 4))
            T[0, j], T[0, j + 2] = 1.0, zs
            K += 0.5 * T.T @ T
            C += 0.01 * T.T @ T
    s = LinearSystem(M=M, C=C, G=G, K=K)
    ball = Ball(0.02, damping=0.01)
    races = tuple(BallRace(0, 1.0, (ball,) * balls_per_race, axial_offset=a) for a in (2.0, -2.0))
    return Machine(s, races=races, unbalances=(Unbalance(0, 0.01, 0.0, axial_offset=1.0),),
                   drive=ConstantSpeed(2.0))


def pico21_one_race():
    from rotorlab.linear.cases import pico21
    from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance

    s = pico21()
    rotor = list(s.node_label).index("rotor")
    return Machine(s, races=(BallRace(rotor, 0.05, (Ball(0.01, damping=1e-4),) * 2),),
                   unbalances=(Unbalance(rotor, 2e-4),), drive=ConstantSpeed(2 * np.pi * 50))


def starts(model, n, seed=0):
    rng = np.random.default_rng(seed)
    return np.array([model.initial_state(rng.uniform(0, 2 * np.pi, model.n_balls)) for _ in range(n)])


def time_ensemble(model, y0, t1, ctl, lanes=None):
    from rotorlab.integrate import solve_ensemble

    c = cpu()
    sol = solve_ensemble(model, y0, (0.0, t1), control=ctl, lanes=lanes, threads=1)
    return cpu() - c, sol


def time_scipy(model, y0, t1, rtol, atol):
    from scipy.integrate import solve_ivp

    p = model.to_array()
    rhs = model.kernels.rhs
    out = np.empty(model.kernels.n_state)

    def f(t, y):
        rhs(t, y, p, out)
        return out.copy()

    f(0.0, np.ascontiguousarray(y0[0]))  # compile (or load) the kernel outside the timing
    c = cpu()
    for y in y0:
        solve_ivp(f, (0.0, t1), y, rtol=rtol, atol=atol)
    return cpu() - c


def bench(n, scipy_n, repeats):
    from rotorlab.integrate import StepControl

    ctl = StepControl(rtol=1e-8, atol=1e-10)
    mac, preset = planar_pair()
    jb = HandWrittenJeffcott(preset)
    t1 = 2000 * 2 * np.pi / 2.5 / 10  # 200 revolutions
    rng = np.random.default_rng(1)
    angles = rng.uniform(0, 2 * np.pi, (n, 2))
    yj = np.array([preset.initial_state(a) for a in angles])
    ym = np.array([mac.initial_state(a) for a in angles])
    time_ensemble(mac, ym[:2], 1.0, ctl), time_ensemble(jb, yj[:2], 1.0, ctl)  # compile
    tm, tj = [], []
    for _ in range(repeats):
        tj.append(time_ensemble(jb, yj, t1, ctl)[0])
        tm.append(time_ensemble(mac, ym, t1, ctl)[0])
    print(f"planar one-mass, {n} trajectories, 200 revolutions (scalar driver, 1 thread)")
    print(f"  jeffcott_balls  {min(tj) / n * 1e3:8.3f} ms CPU per trajectory (hand-written kernel)")
    print(f"  machine         {min(tm) / n * 1e3:8.3f} ms CPU per trajectory")
    print(f"  ratio machine / jeffcott_balls = {min(tm) / min(tj):.3f} (target <= 1.3)")
    for name, model, t1 in (("two-plane rigid rotor, 2 x 1 ball (12 states)", two_plane(1), 100.0),
                            ("Pico 21 + one 2-ball race (28 states)", pico21_one_race(), 0.5)):
        y0 = starts(model, n)
        time_ensemble(model, y0[:2], t1 / 100, ctl, lanes=8)
        time_ensemble(model, y0[:2], t1 / 100, ctl)
        ts = min(time_ensemble(model, y0, t1, ctl)[0] for _ in range(repeats))
        tl = min(time_ensemble(model, y0, t1, ctl, lanes=8)[0] for _ in range(repeats))
        tsp = time_scipy(model, y0[:scipy_n], t1, 1e-8, 1e-10)
        print(f"{name}, t = {t1:g} s, n_state = {model.n_state}")
        print(f"  rotorlab scalar {n / ts:10.1f} trajectories per CPU-second")
        print(f"  rotorlab lanes  {n / tl:10.1f} trajectories per CPU-second")
        print(f"  SciPy solve_ivp {scipy_n / tsp:10.3f} trajectories per CPU-second")
        print(f"  ratio lanes / SciPy = {(n / tl) / (scipy_n / tsp):.1f}")


def sommerfeld():
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "validation"))
    from test_machine_sommerfeld import final_speeds

    for balls in (False, True):
        lo, hi = 0.005, 0.03
        for _ in range(3):  # 3 rounds of 9 interior points: width / 10^3
            grid = np.linspace(lo, hi, 11)
            om = final_speeds(grid, balls)
            passed = om > 2.0
            k = int(np.argmax(passed))
            lo, hi = grid[k - 1], grid[k]
        print(f"smallest passing stall torque {'with' if balls else 'without'} balls: "
              f"between {lo:.5f} and {hi:.5f} N m")


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--scipy-n", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sommerfeld", action="store_true")
    a = ap.parse_args()
    if a.sommerfeld:
        sommerfeld()
    else:
        bench(a.n, a.scipy_n, a.repeats)
