"""Results of the integrator: per-trajectory :class:`Status` codes, one trajectory
(:class:`Solution`) and an ensemble (:class:`EnsembleSolution`), with their ``to_dataset``."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

__all__ = ["Status", "Solution", "EnsembleSolution"]


class Status(enum.IntEnum):
    """Per-trajectory outcome codes (``>= 0`` means the trajectory is usable)."""

    SUCCESS = 0
    EVENT_STOP = 1
    MAX_STEPS = -1
    STEP_UNDERFLOW = -2
    NONFINITE = -3
    EVENT_LOOP = -4
    IMPOSSIBLE = -5
    UNSTABLE = -6

    @property
    def message(self) -> str:
        """Human-readable explanation of the code."""
        return _STATUS_MESSAGES[self]


_STATUS_MESSAGES = {
    Status.SUCCESS: "reached the end time",
    Status.EVENT_STOP: "stopped by an event",
    Status.MAX_STEPS: "maximum number of steps reached",
    Status.STEP_UNDERFLOW: "step size fell below the round-off limit of the time",
    Status.NONFINITE: "state or derivative became non-finite (NaN or inf)",
    Status.EVENT_LOOP: "events kept firing without time advancing (unresolved accumulation)",
    Status.IMPOSSIBLE: "the trajectory reached a physically impossible state (sanity check; see the note)",
    Status.UNSTABLE: "the linear structure is unstable (self-excited) at the trajectory's final speed: its "
                     "response grows without bound, the end is no steady motion (see the note)",
}

_STAT_NAMES = ("nfev", "naccept", "nreject", "nevents")


@dataclass(frozen=True)
class Solution:
    """One trajectory.

    Attributes
    ----------
    ts : ndarray, shape (n_save,)
        Save times (s).
    ys : ndarray, shape (n_save, n_state)
        States at ``ts`` (NaN where the trajectory ended before).
    t_final : float
        Time at which the trajectory ended (s).
    y_final : ndarray, shape (n_state,)
    status : Status
    stats : dict
        ``nfev``, ``naccept``, ``nreject``, ``nevents``.
    event_counts : dict
        Occurrences of each event, by name.
    event_times : ndarray
        Times of the first recorded events (s), with ``event_names`` alongside.
    event_names : tuple of str
    state_names : tuple of str
    note : str
        Why the status is :attr:`Status.IMPOSSIBLE` (which sanity check failed, with numbers);
        empty otherwise.
    """

    ts: np.ndarray
    ys: np.ndarray
    t_final: float
    y_final: np.ndarray
    status: Status
    stats: dict[str, int]
    event_counts: dict[str, int]
    event_times: np.ndarray
    event_names: tuple[str, ...]
    state_names: tuple[str, ...]
    note: str = ""

    @property
    def success(self) -> bool:
        """True when the trajectory reached its end time or a stopping event."""
        return self.status >= 0

    def to_dataset(self):
        """Return the saved trajectory as an ``xarray.Dataset`` (dims ``time``, ``state``)."""
        import xarray as xr

        return xr.Dataset(
            {
                "y": (("time", "state"), self.ys, {"units": "SI (see state)"}),
                "y_final": (("state",), self.y_final, {"units": "SI (see state)"}),
                "status": ((), int(self.status), {"units": "1", "flag_meanings": _flag_meanings()}),
            },
            coords={"time": ("time", self.ts, {"units": "s"}), "state": list(self.state_names)},
            attrs={"t_final": self.t_final, **{f"n_{k}": v for k, v in self.stats.items()}},
        )


@dataclass(frozen=True)
class EnsembleSolution:
    """Many trajectories integrated together (first axis ``ic`` = trajectory).

    Attributes
    ----------
    ts : ndarray, shape (n_save,) or (N, n_save)
    ys : ndarray, shape (N, n_save, n_state)
    t_final : ndarray, shape (N,)
    y_final : ndarray, shape (N, n_state)
    status : ndarray of int, shape (N,)
        :class:`Status` codes.
    stats : ndarray of int, shape (N, 4)
        ``nfev``, ``naccept``, ``nreject``, ``nevents`` per trajectory.
    event_counts : ndarray of int, shape (N, n_events)
    event_times : ndarray, shape (N, max_events)
        Times of the first recorded events (NaN-padded); ``event_index`` gives which event.
    event_index : ndarray of int, shape (N, max_events)
        Index into ``event_names`` (-1 where unused).
    event_names, state_names : tuple of str
    driver : str
        The compiled driver that ran: ``"scalar"`` or ``"lanes8"`` (lane width).
    notes : tuple of str, shape (N,)
        Per trajectory, why its status is :attr:`Status.IMPOSSIBLE` (empty string otherwise).
    """

    ts: np.ndarray
    ys: np.ndarray
    t_final: np.ndarray
    y_final: np.ndarray
    status: np.ndarray
    stats: np.ndarray
    event_counts: np.ndarray
    event_times: np.ndarray
    event_index: np.ndarray
    event_names: tuple[str, ...]
    state_names: tuple[str, ...]
    driver: str = "scalar"
    notes: tuple[str, ...] = ()

    def __len__(self) -> int:
        return int(self.status.shape[0])

    @property
    def success(self) -> np.ndarray:
        """Boolean mask of usable trajectories."""
        return self.status >= 0

    def trajectory(self, i: int) -> Solution:
        """Return trajectory ``i`` as a :class:`Solution`."""
        ts = self.ts if self.ts.ndim == 1 else self.ts[i]
        rec = self.event_index[i] >= 0
        return Solution(
            ts=ts,
            ys=self.ys[i],
            t_final=float(self.t_final[i]),
            y_final=self.y_final[i],
            status=Status(int(self.status[i])),
            stats=dict(zip(_STAT_NAMES, (int(v) for v in self.stats[i]))),
            event_counts={n: int(c) for n, c in zip(self.event_names, self.event_counts[i])},
            event_times=self.event_times[i][rec],
            event_names=tuple(self.event_names[k] for k in self.event_index[i][rec]),
            state_names=self.state_names,
            note=self.notes[i] if self.notes else "",
        )

    def to_dataset(self):
        """Return an ``xarray.Dataset`` with dims ``ic``, ``time``, ``state`` (and ``event``)."""
        import xarray as xr

        time_dims = ("time",) if self.ts.ndim == 1 else ("ic", "time")
        data = {
            "y": (("ic", "time", "state"), self.ys, {"units": "SI (see state)"}),
            "y_final": (("ic", "state"), self.y_final, {"units": "SI (see state)"}),
            "t_final": (("ic",), self.t_final, {"units": "s"}),
            "status": (("ic",), self.status.astype(np.int32), {"units": "1", "flag_meanings": _flag_meanings()}),
            "nfev": (("ic",), self.stats[:, 0], {"units": "1"}),
            "naccept": (("ic",), self.stats[:, 1], {"units": "1"}),
            "nreject": (("ic",), self.stats[:, 2], {"units": "1"}),
        }
        coords = {"state": list(self.state_names), "ic": np.arange(len(self))}
        if self.ts.ndim == 1:
            coords["time"] = ("time", self.ts, {"units": "s"})
        else:
            data["save_time"] = (time_dims, self.ts, {"units": "s"})
        if self.event_names:
            data["event_count"] = (("ic", "event"), self.event_counts, {"units": "1"})
            coords["event"] = list(self.event_names)
        return xr.Dataset(data, coords=coords)


def _flag_meanings() -> str:
    return " ".join(f"{int(s)}:{s.name.lower()}" for s in Status)
