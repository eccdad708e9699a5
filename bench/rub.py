"""Benchmark of the rub rotor's preset machine against its hand-written kernel (issue 24, item 6).

``rub_rotor`` runs its preset machine's generated kernel (:mod:`rotorlab.models._rub_machine`);
the hand-written :mod:`rotorlab._kernels.jeffcott_rub` is the tests' oracle and the baseline here.
Both integrate the same ensemble (same starts, same packed parameters: the preset's vector, whose
first 15 entries are the hand-written kernel's), from rest with the start modes of a rub map, on
one thread, CPU time (``time.process_time``), the two models in turn (A B A B ...), the figure
is the ratio of the smallest times (preset / hand-written; target <= 1.3), the ratio of the
medians beside it.

Maps:

- ``elastic``: rub-jeffcott's own ``rub-map`` (9 speeds x 7 clearances, elastic stator);
- ``rigid``: the same rotor against a rigid stator (restitution 0.6), 5 speeds x 4 clearances.

Usage::

    python bench/rub.py [--t-end 1] [--repeats 3] [--maps elastic,rigid] [--scalar]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

import numpy as np


class HandWrittenRub:
    """The rub rotor on its hand-written kernel (the baseline): packed vector = the first 15."""

    def __init__(self, model):
        from rotorlab._kernels import jeffcott_rub as k
        from rotorlab.models import EventSpec, Kernels

        self.model = model
        self.kernels = Kernels(rhs=k.rhs, n_state=k.N_STATE, n_discrete=k.N_DISCRETE, events=k.events,
                               reset=k.reset, event_specs=tuple(EventSpec(n, -1, "reset") for n in
                                                                ("contact", "lift_off", "stick", "slip")))
        self.state_names = model.state_names

    def to_array(self):
        return self.model.to_array()[:15]


def rub_jeffcott():
    from rotorlab.analyses._registry import MODEL_TYPES
    from rotorlab.io import load_case

    case = load_case("rub-jeffcott")
    return MODEL_TYPES[case.model.type].build(case.model)


def maps():
    """name -> (model, speeds (rad/s), clearances (m))."""
    from rotorlab.contact import JeffcottRub

    el = rub_jeffcott()
    rigid = JeffcottRub(replace(el.rotor, stator_stiffness=np.inf), spin_speed=el.spin_speed,
                        restitution=0.6, rest_speed=1e-4)
    return {"elastic": (el, np.linspace(200.0, 600.0, 9), np.linspace(0.5e-3, 2e-3, 7)),
            "rigid": (rigid, np.linspace(200.0, 600.0, 5), np.linspace(0.5e-3, 2e-3, 4))}


def ensemble(model, speeds, clearances):
    """Starts and packed parameters of the map's points (as :class:`rotorlab.contact.RubRegimes`)."""
    from rotorlab.contact import RubRegimes

    rr = RubRegimes(model, t_end=1.0, window=0.1)
    sp, cl = np.meshgrid(speeds, clearances, indexing="ij")
    params = rr.point_parameters({"spin_speed": sp.ravel(), "clearance": cl.ravel()})
    base = model.gap_state(rr.position, rr.velocity)
    y0 = np.tile(base, (params.shape[0], 1))
    y0[:, -1] = [model.start_mode(base, row) for row in params]
    return y0, params


def run(model, y0, params, t_end, lanes):
    from rotorlab.integrate import SaveAt, StepControl, solve_ensemble

    ts = np.linspace(t_end - min(0.1, t_end / 2), t_end, 400)
    c = time.process_time()
    sol = solve_ensemble(model, y0, (0.0, t_end), params=params, save_at=SaveAt(ts=ts),
                         control=StepControl(rtol=1e-9, atol=1e-12), threads=1, lanes=lanes)
    return time.process_time() - c, sol


def bench(names, t_end, repeats, lanes):
    for name in names:
        model, speeds, clearances = maps()[name]
        hand = HandWrittenRub(model)
        y0, params = ensemble(model, speeds, clearances)
        hp = np.ascontiguousarray(params[:, :15])
        run(model, y0[:2], params[:2], 0.01, lanes), run(hand, y0[:2], hp[:2], 0.01, lanes)  # compile
        tm, th = [], []
        for _ in range(repeats):
            t, sm = run(model, y0, params, t_end, lanes)
            tm.append(t)
            t, sh = run(hand, y0, hp, t_end, lanes)
            th.append(t)
        # statuses, impact counts and contact modes (states 6 and 8) at every saved sample
        same = np.array_equal(sm.status, sh.status) and np.array_equal(sm.ys[..., 6::2], sh.ys[..., 6::2])
        dev = np.nanmax(np.abs(sm.ys[..., :4] - sh.ys[..., :4])) / np.nanmax(np.abs(sh.ys[..., :4]))
        nfev, nacc = (f"{int(sm.stats[:, i].sum())} / {int(sh.stats[:, i].sum())}" for i in (0, 1))
        steps = f"{nacc} accepted, rhs calls {nfev}"
        print(f"{name} map, {len(y0)} points, {t_end:g} s, {'lanes ' + str(lanes) if lanes else 'scalar'}, "
              f"1 thread, {repeats} interleaved repeats")
        print(f"  hand-written {min(th):8.3f} CPU-s (all: {', '.join(f'{t:.3f}' for t in th)})")
        print(f"  preset       {min(tm):8.3f} CPU-s (all: {', '.join(f'{t:.3f}' for t in tm)})")
        print(f"  ratio preset / hand-written = {min(tm) / min(th):.3f} (target <= 1.3; "
              f"of the medians {np.median(tm) / np.median(th):.3f})")
        print(f"  statuses, impact counts and modes identical: {same}; largest change of x, y, vx, vy "
              f"{dev:.2g} of the largest entry; steps {steps}")


def main(argv=None):
    ap = argparse.ArgumentParser(description="rub rotor: preset machine / hand-written kernel, CPU time")
    ap.add_argument("--t-end", type=float, default=1.0, help="simulated time of every point (s)")
    ap.add_argument("--repeats", type=int, default=3, help="interleaved repeats (the smallest time counts)")
    ap.add_argument("--maps", default="elastic,rigid", help="comma-separated: elastic, rigid")
    ap.add_argument("--scalar", action="store_true", help="the scalar driver instead of 8 lanes")
    a = ap.parse_args(argv)
    bench(a.maps.split(","), a.t_end, a.repeats, None if a.scalar else 8)


if __name__ == "__main__":
    main()
