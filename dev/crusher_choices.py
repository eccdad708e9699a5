"""Which modelling choice decides seed 001's Fig. 4 (issue 30): one choice changed at a time.

Fig. 4 (translational model, Delta t = 0.07 s, gamma = 0.5, k = 0.7, f = 0.3, 2 s): no impacts at
1.3 kg, sliding from 3 kg, strong sliding at 5 kg; an independent event-located simulation of
the same equations finds every one of 16 sequences sliding at 5 kg with about 250 impacts. This
script runs the case ``krasnov-crusher-translational`` at 3 and 5 kg over 16 seeded sequences
with each candidate choice changed on its own and prints, per mass, the median of every located
impact, the number of runs with any sustained contact, the median time in sustained contact and
the regimes (none / rebounds / sliding >= 2 % of the run / backward whirl).

Run: ``PYTHONPATH=src python dev/crusher_choices.py`` (about a minute after the compile).

Findings (2026-11, 16 sequences, seeds 0-15; medians of every located impact):

- where the stone lands on its guide (``start_radius``, not given in the paper) decides it. A
  sustained contact here whirls forwards (the housing holds the rotor on its circle at whirl
  speeds above the natural frequency sqrt(c/m) = 100.6 rad/s) and friction and the membranes
  slow it to lift-off within about 8 ms unless a stone is pushing; a stone landing at 0.15 m
  pushes for 27.5 ms of the 70 ms between stones, at 0.1 m for 34.5 ms, at 0.06 m for 43 ms.
  At 5 kg: 0.15 m, 157 impacts, no run slides for 2 % of the run (12 of 16 touch for a median
  8 ms); 0.1 m (the default), 282 impacts, 14 of 16 slide, and sustained contact begins at 3 kg
  (10 of 16 runs); 0.06 m, 254 impacts, 16 of 16 slide, but 3 kg hardly touches (2 of 16);
- with the stone landing at 0.15 m, the chatter -> sustained-contact rule (``rest_speed`` 1e-2
  m/s: 146 impacts), the count threshold (``count_speed`` 1e-3 m/s: 152, the chatter below it
  is ~3 % of the impacts), 8 guides (156) and the backward-whirl stop (no run reaches it) leave
  5 kg without sliding; guides taken in turn instead of at random make it milder (85, no
  contact); an irregular feed (``time_jitter`` 0.3: two stones sometimes close together) turns
  it into sliding (219, 13 of 16), but the paper's feed is regular;
- the ``sliding`` label (>= 2 % of the run in sustained contact; ``sliding_fraction``) is an
  engineer's reading of "the rotor slides on the housing for some time"; the column "contact"
  (any sustained contact) is the paper's "sliding begins".
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorlab.analyses import impact_model, impact_sweep
from rotorlab.io import load_case

MASSES = (3.0, 5.0)


def _variant(model, part: str | None, **changes):
    if part is None:
        return model
    return replace(model, **{part: replace(getattr(model, part), **changes)})


def main() -> None:
    base = impact_model(load_case("krasnov-crusher-translational").model)
    choices = {
        "case (stone lands at 0.1 m)": (None, {}),
        "stone lands at 0.15 m": ("stones", {"start_radius": 0.15}),
        "stone lands at 0.06 m": ("stones", {"start_radius": 0.06}),
        "0.15 m, rest_speed 1e-2 m/s": ("stones", {"start_radius": 0.15}, "housing", {"rest_speed": 1e-2}),
        "0.15 m, count_speed 1e-3 m/s": ("stones", {"start_radius": 0.15}, "housing", {"count_speed": 1e-3}),
        "0.15 m, 8 guides": ("stones", {"start_radius": 0.15, "n_guides": 8}),
        "0.15 m, guides in turn": ("stones", {"start_radius": 0.15, "guides": "cyclic"}),
        "0.15 m, time jitter 0.3": ("stones", {"start_radius": 0.15, "time_jitter": 0.3}),
        "0.15 m, whirl limit 2 omega0": ("stones", {"start_radius": 0.15}, "housing", {"whirl_limit": 320.0}),
    }
    for label, spec in choices.items():
        model = base
        for part, changes in zip(spec[0::2], spec[1::2]):
            model = _variant(model, part, **changes)
        ds = impact_sweep(model, list(MASSES), n_sequences=16, t_end=2.0, seed=0)
        cells = []
        for i, m in enumerate(ds.value.values):
            reg = np.bincount(ds.regime.values[i] + 1, minlength=5)[1:]
            st = ds.sliding_time.values[i]
            cells.append(f"{m:g} kg: {np.median(ds.impacts.values[i]):4.0f} impacts, contact {int((st > 0).sum()):2d}/16, "
                         f"{np.median(st) * 1e3:3.0f} ms, regimes {reg.tolist()}")  # fmt: skip
        print(f"{label:32s} " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main()
