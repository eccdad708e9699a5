r"""A tuned mass absorber on a machine's station: a point mass on an isotropic spring and damper
(a part of the composed machine, :mod:`rotorlab.models._parts`).

The absorber's mass ``m_a`` moves in the lateral plane at the fixed-frame position ``x_a =
(x_a, y_a)``; its spring ``k_a`` and damper ``c_a`` join it to the station ``u = B z`` (``(x + a
phi_x, y + a phi_y)`` of its node, a: axial offset). With ``d = x_a - u`` ::

    m_a x_a'' = -(k_a d + c_a d') + m_a g,        force on the station  F = k_a d + c_a d'

Its energy is ``1/2 m_a |x_a'|^2 + 1/2 k_a |d|^2 - m_a g . x_a`` and it dissipates ``c_a |d'|^2``
(both enter the machine's energy ledger). It does not spin: it needs no state of the rotor.

Under a harmonic station motion ``u e^{i w t}`` it puts ``-Z(w) u`` on the station, ``Z(w) = -m_a
w^2 k^* / (k^* - m_a w^2)`` with ``k^* = k_a + i w c_a`` (:func:`absorber_response`): tuned
(``k_a = m_a w^2``) and undamped it cancels the station's motion at ``w`` (the anti-resonance);
on a single-mass primary (mass M, stiffness K) under a constant force the Den Hartog optimum is
``f = w_a / w_p = 1 / (1 + mu)``, ``c_a / (2 m_a w_p) = sqrt(3 mu / (8 (1 + mu)^3))`` (mu = m_a /
M, w_p = sqrt(K / M)), the response's two fixed points then at equal height ``sqrt(1 + 2 / mu)``
times the static deflection (Den Hartog, *Mechanical Vibrations*, 4th ed., 1956, Sec. 3.3).

The co-rotating frame of the machine has no place for the absorber's states yet: a machine with
an absorber has no co-rotating equilibria (:meth:`TunedMassAbsorber.rotating_refusal`); simulate
it, or use its linear response.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from rotorlab._kernels.machine_emit import station_rows
from rotorlab.models._parameters import _FREE, _GE0, _GT0
from rotorlab.models._parts import AbstractKernelPart, AbstractPart

__all__ = ["TunedMassAbsorber", "absorber_response"]


@dataclass(frozen=True)
class _AbsorberLines(AbstractKernelPart):
    """Kernel lines of one absorber: states (x_a, y_a, x_a', y_a'), parameters (m_a, k_a, c_a)."""

    key: ClassVar[str] = "ta"
    n_states: ClassVar[int] = 4
    n_param: ClassVar[int] = 3
    n_stations: ClassVar[int] = 1

    def force_lines(self, lay, L, place):
        i, k, s, n = place.state, place.param, place.station, place.state
        ux, uy = station_rows(lay, s, "z")
        vx, vy = station_rows(lay, s, "v")
        L += [f"    ta_m{n} = p[{k}]", f"    ta_k{n} = p[{k + 1}]", f"    ta_c{n} = p[{k + 2}]",
              f"    ta_dx{n} = y[{i}] - ({ux})", f"    ta_dy{n} = y[{i + 1}] - ({uy})",
              f"    ta_dvx{n} = y[{i + 2}] - ({vx})", f"    ta_dvy{n} = y[{i + 3}] - ({vy})",
              f"    ta_fx{n} = ta_k{n} * ta_dx{n} + ta_c{n} * ta_dvx{n}",
              f"    ta_fy{n} = ta_k{n} * ta_dy{n} + ta_c{n} * ta_dvy{n}"]
        return [(s, f"ta_fx{n}", f"ta_fy{n}")]

    def rate_lines(self, lay, place):
        i, n = place.state, place.state
        return [f"    out[{i}] = y[{i + 2}]", f"    out[{i + 1}] = y[{i + 3}]",
                f"    out[{i + 2}] = gx - ta_fx{n} / ta_m{n}", f"    out[{i + 3}] = gy - ta_fy{n} / ta_m{n}"]

    def dissipation_terms(self, lay, place):
        n = place.state
        return [f"ta_c{n} * (ta_dvx{n} * ta_dvx{n} + ta_dvy{n} * ta_dvy{n})"]


@dataclass(frozen=True)
class TunedMassAbsorber(AbstractPart):
    """A point mass on an isotropic spring and damper at a station (case key ``absorbers``).

    Parameters
    ----------
    node : int
        Node of the structure it is attached to.
    mass : float
        m_a (kg), > 0.
    stiffness : float
        k_a (N/m), > 0, the same in x and y.
    damping : float
        c_a (N*s/m), >= 0.
    axial_offset : float
        Station along +z from the node (m).

    Examples
    --------
    >>> a = TunedMassAbsorber(0, mass=0.1, stiffness=1000.0, damping=0.5)
    >>> round(a.natural_frequency, 6)
    100.0
    """

    key: ClassVar[str] = "absorbers"
    fields: ClassVar[tuple] = (("mass", "kg", _GT0), ("stiffness", "N/m", _GT0), ("damping", "N*s/m", _GE0),
                               ("axial_offset", "m", _FREE))

    node: int
    mass: float
    stiffness: float
    damping: float = 0.0
    axial_offset: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.node, bool) or not isinstance(self.node, (int, np.integer)) or self.node < 0:
            raise ValueError(f"TunedMassAbsorber.node must be a node index >= 0, got {self.node!r}")
        for name, _, (gt, ge, _, _) in self.fields:
            v = getattr(self, name)
            if not np.isfinite(v) or (gt is not None and v <= gt) or (ge is not None and v < ge):
                raise ValueError(f"TunedMassAbsorber.{name} must be {'> 0' if gt is not None else '>= 0'}"
                                 f" and finite, got {v!r}")

    @property
    def natural_frequency(self) -> float:
        """sqrt(k_a / m_a) (rad/s): the speed it cancels the station's motion at, undamped."""
        return float(np.sqrt(self.stiffness / self.mass))

    def kernel(self) -> _AbsorberLines:
        return _AbsorberLines()

    def stations(self, machine) -> list[np.ndarray]:
        return [machine.station_matrix(self.node, self.axial_offset)]

    def pack(self, machine) -> np.ndarray:
        return np.array([self.mass, self.stiffness, self.damping])

    def state_names(self, index: int) -> list[str]:
        return [f"{q}_absorber_{index + 1}" for q in ("x", "y", "vx", "vy")]

    def initial(self, machine, y, place) -> None:
        """At its station, moving with it (spring unstretched)."""
        B = self.stations(machine)[0]
        nz = machine.n_coordinates
        y[place.state:place.state + 2] = B @ y[:nz]
        y[place.state + 2:place.state + 4] = B @ y[nz:2 * nz]

    def energy(self, machine, y, place, t: float = 0.0) -> float:
        B = self.stations(machine)[0]
        nz = machine.n_coordinates
        xa, va = y[place.state:place.state + 2], y[place.state + 2:place.state + 4]
        d = xa - B @ y[:nz]
        g = np.asarray(machine.lateral_gravity)
        return float(0.5 * self.mass * va @ va + 0.5 * self.stiffness * d @ d - self.mass * g @ xa)

    def rotating_refusal(self) -> str | None:
        return ("the machine has a tuned mass absorber, whose states the co-rotating frame does not "
                "carry yet: simulate instead, or use its linear response (rotorlab.models.absorber_response)")

    def dynamic_stiffness(self, machine, omega: float) -> np.ndarray:
        """``Z(w) e^T e`` over the structure's DOFs (``e``: its station, :meth:`harmonic_stiffness`)."""
        e = machine.station_matrix(self.node, self.axial_offset, dofs=True)
        return self.harmonic_stiffness(omega) * (e.T @ e)

    def harmonic_stiffness(self, omega: float) -> complex:
        """``Z(w) = -m_a w^2 k^* / (k^* - m_a w^2)``, ``k^* = k_a + i w c_a``: the station force per
        unit harmonic station motion is ``-Z`` (N/m)."""
        ks = self.stiffness + 1j * omega * self.damping
        return -self.mass * omega ** 2 * ks / (ks - self.mass * omega ** 2)


def absorber_response(machine, node: int, speeds, *, axial_offset: float = 0.0):
    """Linear unbalance response of a station with and without the machine's absorbers.

    The balls are locked in their races (point masses on the structure, as in the kernel's
    ``M0``); each absorber adds its :meth:`TunedMassAbsorber.harmonic_stiffness` at its station.
    The larger of the x and y amplitudes of the station at ``(node, axial_offset)`` under the
    machine's unbalances at each speed (an isotropic structure whirls in a circle of that radius).

    Parameters
    ----------
    machine : rotorlab.models.Machine
    node : int
    speeds : array_like, shape (n,)
        Spin speeds (rad/s).
    axial_offset : float
        Station along +z from the node (m).

    Returns
    -------
    xarray.Dataset
        ``amplitude`` (with the absorbers) and ``amplitude_without`` (m) over ``speed`` (rad/s);
        ``receptance`` (m/N, complex magnitude of the station's x response to a unit x force at
        the station, with the absorbers).
    """
    import xarray as xr

    speeds = np.asarray(speeds, dtype=float).reshape(-1)
    red = machine.reduced
    m0 = machine._m0()
    B = machine.station_matrix(node, axial_offset)
    absorbers = [p for p in machine.parts if isinstance(p, TunedMassAbsorber)]
    out = np.zeros((3, speeds.size))
    for n, om in enumerate(speeds):
        D0 = red["K"] + 1j * om * (red["C"] + om * red["G"]) - om * om * m0
        D = D0.astype(complex)
        for a in absorbers:
            Ba = a.stations(machine)[0]
            D = D + a.harmonic_stiffness(om) * (Ba.T @ Ba)
        f = np.zeros(machine.n_coordinates, dtype=complex)
        for u in machine.unbalances:
            for a_off, me, beta in u.point_unbalances():
                Bu = machine.station_matrix(u.node, a_off)
                f += me * om * om * np.exp(1j * beta) * (Bu.T @ np.array([1.0, -1j]))
        for k, DD in enumerate((D, D0)):
            out[k, n] = _largest(B, DD, f)[0]
        out[2, n] = _largest(B, D, B[0].astype(complex))[1]
    return xr.Dataset(
        {"amplitude": ("speed", out[0], {"units": "m"}),
         "amplitude_without": ("speed", out[1], {"units": "m"}),
         "receptance": ("speed", out[2], {"units": "m/N"})},
        coords={"speed": ("speed", speeds, {"units": "rad/s"})},
        attrs={"node": int(node), "axial_offset": float(axial_offset), "absorbers": len(absorbers)})


def _largest(B: np.ndarray, D: np.ndarray, f: np.ndarray) -> tuple[float, float]:
    """``w = B D^-1 f``: (max |w|, |w_x|); infinite at an undamped resonance (D singular)."""
    try:
        w = B @ np.linalg.solve(D, f)
    except np.linalg.LinAlgError:
        return np.inf, np.inf
    return float(np.max(np.abs(w))), float(abs(w[0]))
