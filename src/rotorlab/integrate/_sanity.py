"""The sanity monitor run after each compiled call: trajectories that reached a physically
impossible state get :attr:`~rotorlab.integrate.Status.IMPOSSIBLE` and a note saying why."""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorlab.integrate._results import Status

__all__ = ["ABSURD_MAGNITUDE", "sanity_check"]

#: Largest magnitude of any state entry that :func:`~rotorlab.integrate.solve_ensemble` accepts as physical (SI). Far
#: beyond anything a machine reaches (1e30 m, m/s, rad/s): a state this large is a numerical
#: blow-up even if it is still finite.
ABSURD_MAGNITUDE = 1e30


def sanity_check(model: Any, n_cont: int, ys: np.ndarray, y_final: np.ndarray, t_final: np.ndarray,
                 status: np.ndarray, params: np.ndarray) -> tuple[str, ...]:  # fmt: skip
    """Mark trajectories that reached a physically impossible state (in place) and say why.

    Runs in Python after the compiled call, on every usable trajectory (``status >= 0``):

    - generic, for every model: saved and final continuous states finite and below
      :data:`ABSURD_MAGNITUDE`;
    - the model's own check, when it defines ``impossible_states`` (see the kernel contract,
      :mod:`rotorlab.models._base`, "For implementers" item 6): e.g. penetration beyond the
      clearance, energy above what the sources can supply.

    Such trajectories get :attr:`Status.IMPOSSIBLE`; the returned notes (one per trajectory,
    empty where nothing failed) name the check and its numbers.
    """
    N = status.shape[0]
    notes = [""] * N
    usable = status >= 0
    if not usable.any():
        return tuple(notes)
    cont_f = y_final[:, :n_cont]
    big_f = ~np.all(np.isfinite(cont_f) & (np.abs(cont_f) <= ABSURD_MAGNITUDE), axis=1)
    saved = ys[:, :, :n_cont]  # NaN after a trajectory ended: NaN compares False (not flagged)
    beyond = (saved > ABSURD_MAGNITUDE) | (saved < -ABSURD_MAGNITUDE)  # inf included; no copy of ys
    big_s = beyond.any(axis=(1, 2)) if saved.size else np.zeros(N, dtype=bool)
    for i in np.flatnonzero(usable & (big_f | big_s)):
        if big_f[i]:
            row = cont_f[i]
            bad = int(np.argmax(~np.isfinite(row) | (np.abs(row) > ABSURD_MAGNITUDE)))
        else:
            k, bad = (int(j) for j in np.argwhere(beyond[i])[0])
            row = saved[i, k]
        notes[i] = (f"state entry {bad} reached {row[bad]:.3g} (SI) by t = {t_final[i]:.6g} s, beyond any physical "
                    f"magnitude ({ABSURD_MAGNITUDE:.0e})")  # fmt: skip
    check = getattr(model, "impossible_states", None)
    rows = np.flatnonzero(usable & ~(big_f | big_s))
    if check is not None and rows.size:
        p = params if params.shape[0] == 1 else params[rows]
        found = check(ys[rows], y_final[rows], t_final[rows], p)
        for i, text in zip(rows, found):
            if text:
                notes[i] = str(text)
    for i, text in enumerate(notes):
        if text:
            status[i] = Status.IMPOSSIBLE
    return tuple(notes)
