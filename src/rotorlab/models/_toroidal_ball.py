r"""One ball rolling in a toroidal balancer body offset from the rotation axis (``toroidal_ball``).

A rigid body turns at the constant speed omega about the vertical z axis. It carries a torus
(centre-line radius R, tube radius R1) whose geometric axis is parallel to the rotation axis at
the distance e. One ball of radius r rolls inside the tube; its centre lies on the torus of tube
radius ``a = R1 - r``, at the ring angle psi (about the torus axis, measured in the body from
the direction pointing *away* from the offset, so that psi = pi is the point of the ring
farthest from the rotation axis) and the cross-section angle alpha (from the downward vertical
through the tube centre; alpha = pi/2 is the outer wall). In the co-rotating frame (x along the
body's reference direction)::

    c = -e x + (R + a sin(alpha)) (cos(psi) x + sin(psi) y) - a cos(alpha) z

The model is Strautmanis' eqs. (4)-(6) (seed 004) in two forms sharing one kernel
(:mod:`rotorlab._kernels.toroidal_ball`):

``form="rolling"`` (default)
    Derived here for a ball rolling without slip and without pivoting relative to the body (its
    angular velocity relative to the body is tangent to the tube), by the Lagrange-d'Alembert
    principle (Kane's equations; ``tests/validation/test_toroidal_lagrange.py`` re-derives them
    with sympy)::

        psi''   = -(a cos(alpha) / rho) alpha' (2 psi' + 12/7 omega) + 5/7 e omega^2 sin(psi) / rho
                  - 5/7 k N / (rho r) sign(psi')
        alpha'' = (rho cos(alpha) / a) (psi'^2 + 12/7 omega psi' + 5/7 omega^2)
                  - 5/7 (e omega^2 cos(alpha) cos(psi) + g sin(alpha)) / a
                  - 5/7 k N / (a r) sign(alpha')
        N       = g cos(alpha) + rho (omega + psi')^2 sin(alpha) + a alpha'^2
                  - e omega^2 sin(alpha) cos(psi)                      (m/s^2, per unit mass)

    with ``rho = R + a sin(alpha)``. Without friction the Jacobi integral
    ``7/10 (rho^2 psi'^2 + a^2 alpha'^2) - 1/2 omega^2 |c_xy|^2 - g a cos(alpha)`` is conserved
    (:meth:`ToroidalBall.jacobi_integral`).

``form="paper"``
    Eqs. (4)-(6) exactly as printed: ``rho -> R`` everywhere, every inertial term scaled by 5/7
    (Coriolis coefficient 10/7 instead of 12/7, relative terms 5/7 instead of 1), no offset term
    in N, and the cross-section rolling resistance ``5 N k R1 / (7 a^2 r)``.

Comparison with the seed (checked in ``tests/validation/test_toroidal_lagrange.py``)
--------------------------------------------------------------------------------------
1. Sign of e. Coordinates (1)-(2) put the torus axis at ``+e`` along the spin angle phi = omega t;
   with them the derived ring equation has ``-5/7 e omega^2 sin(psi) / rho`` and the working
   position (the far point of the ring) is psi = 0. Eqs. (4)-(5), and the reported working
   position psi = 3.14156 rad, correspond to the axis at ``-e``: (4)'s bracket is
   ``cos(phi) sin(phi + psi) - sin(phi) cos(phi + psi) = +sin(psi)`` and (5)'s is ``+cos(psi)``
   with a minus in front. The model uses the equations' convention (offset towards psi = pi;
   coordinates (1)-(2) with e -> -e), so that psi means what the paper's results mean.
2. Inertia of rolling. The printed equations scale all inertial terms of a point mass by 5/7.
   The rolling ball gives 5/7 only on the centrifugal and gravity terms; the purely relative
   terms (``2 a cos(alpha) alpha' psi' / rho`` in (4), ``rho cos(alpha) psi'^2 / a`` in (5)) keep
   the point-mass coefficient 1, and the Coriolis terms have 12/7 omega instead of 10/7 omega
   (the ball's own spin, carried round by the body, adds a gyroscopic 2/7 omega).
3. Ring radius. (4)-(6) use R where the ball centre runs on ``rho = R + a sin(alpha)``
   (1.25 % larger on the outer wall with the seed's numbers).
4. Normal force (6) omits the offset term ``-e omega^2 sin(alpha) cos(psi)`` (10 % of N at the
   working position: the centre of the ball is at ``R + a + e`` from the axis, not ``R + a``).
5. Cross-section rolling resistance. The ball's rotation relative to the body is
   ``a alpha' / r`` (it rolls on the tube wall, radius R1, with its centre on radius a), so the
   resistance is ``5/7 k N / (a r)``; (5) prints ``5/7 k N R1 / (a^2 r)``, a factor
   ``R1 / a = 6`` larger with the seed's numbers. Along the ring both agree (up to R vs rho).
6. Naive substitution. Putting the rolling constraint into the kinetic energy and applying
   Euler-Lagrange equations (treating the constraint as holonomic) gives extra terms
   proportional to ``omega r cos(alpha)``; the constraint is non-holonomic, so those equations
   are wrong. Neither the printed nor the model's equations contain such terms.
7. Rolling resistance acts separately in the two directions, ``k N sign(psi')`` and
   ``k N sign(alpha')`` as printed (the model keeps this law; an isotropic law would use the
   direction of the relative velocity), with N clipped at 0 (no contact, no resistance). The
   eccentricity e of (4)-(5) is the offset of the body, not a mass property: the ball's mass
   drops out of the equations.

Stick/slip: a direction whose rate reaches zero stays stuck (rate and acceleration zero) while
its driving term ``|F|`` is within the bound ``B`` of rolling resistance, and rolls again when
it leaves it; the switches are events with reset maps of the integrator (kernel module). The
stuck equilibria around the working position form the *friction band*
(:meth:`ToroidalBall.working_point`).

References
----------
Strautmanis G. Par lodes autobalansiera autobalansesanas rezima stabilitati (On the stability of
the autobalancing conditions of a ball autoequalizer), Riga Technical University, eqs. (1)-(6),
Figs. 3, 5, 6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from rotorlab._kernels import toroidal_ball as _k
from rotorlab.models._base import EventSpec, Kernels
from rotorlab.models._checks import check_number
from rotorlab.models._parameters import toroidal_slots
from rotorlab.models._protocol import ParametrisedMixin

__all__ = ["ToroidalBall", "WorkingPoint", "strautmanis_torus", "EVENT_NAMES"]

Form = Literal["rolling", "paper"]

#: Event functions of the model, in kernel order.
EVENT_NAMES = ("stick_psi", "slip_psi", "stick_alpha", "slip_alpha", "lift_off")

_KERNELS = Kernels(
    rhs=_k.rhs,
    n_state=_k.N_STATE,
    n_discrete=_k.N_DISCRETE,
    events=_k.events,
    reset=_k.reset,
    event_specs=tuple(EventSpec(name, -1, "count" if name == "lift_off" else "reset") for name in EVENT_NAMES),
    vectorises=True,
)


@dataclass(frozen=True, slots=True)
class WorkingPoint:
    """The working equilibrium of the ball and its friction band.

    Attributes
    ----------
    psi, alpha : float
        Frictionless equilibrium: psi = pi (far point of the ring) and the cross-section angle
        where centrifugal force and gravity balance (rad).
    normal : float
        Specific normal force N there (m/s^2).
    psi_band : tuple of float
        Ring angles (lo, hi) around pi between which a stopped ball stays stopped, with alpha
        at its frictionless equilibrium for each psi (rad).
    alpha_band : tuple of float
        Cross-section angles (lo, hi) around ``alpha`` holding a stopped ball at psi = pi (rad).
    frequencies : ndarray, shape (2,)
        Angular frequencies of small frictionless oscillations (rad/s), ascending (ring, then
        cross-section mode).
    """

    psi: float
    alpha: float
    normal: float
    psi_band: tuple[float, float]
    alpha_band: tuple[float, float]
    frequencies: np.ndarray

    def to_dataset(self):
        """Return the point as an ``xarray.Dataset`` (scalars plus a ``bound`` dim lo/hi)."""
        import xarray as xr

        return xr.Dataset(
            {
                "psi": ((), self.psi, {"units": "rad"}),
                "alpha": ((), self.alpha, {"units": "rad"}),
                "normal": ((), self.normal, {"units": "m/s^2"}),
                "psi_band": (("bound",), list(self.psi_band), {"units": "rad"}),
                "alpha_band": (("bound",), list(self.alpha_band), {"units": "rad"}),
                "frequency": (("mode",), self.frequencies, {"units": "rad/s"}),
            },
            coords={"bound": ["lo", "hi"], "mode": ["ring", "cross_section"]},
        )


@dataclass(frozen=True, slots=True)
class ToroidalBall(ParametrisedMixin):
    """One ball rolling in a spinning torus offset from the rotation axis.

    Parameters
    ----------
    ring_radius : float
        R, radius of the torus' centre line (m), > tube_radius.
    tube_radius : float
        R1, radius of the tube's circular cross-section (m), > ball_radius.
    ball_radius : float
        r (m), > 0.
    spin_speed : float
        omega, constant angular speed of the body (rad/s), > 0.
    offset : float
        e, distance of the torus axis from the rotation axis, towards psi = pi (m), >= 0.
    rolling_friction : float
        k, coefficient of rolling friction (lever arm of the rolling resistance, m), >= 0.
    gravity : float
        g (m/s^2), >= 0, along -z.
    form : {"rolling", "paper"}
        Equations derived for a rolling ball, or seed 004 eqs. (4)-(6) as printed (see the module
        docstring).

    Notes
    -----
    State ``[psi, alpha, dpsi, dalpha, mode_psi, mode_alpha, t_switch]`` (rad, rad/s; modes
    +1/-1 rolling, 0 stuck; time of the last stick/slip switch, s). Packed parameters: see
    :mod:`rotorlab._kernels.toroidal_ball`.

    Examples
    --------
    >>> model = strautmanis_torus()
    >>> model.n_state, model.state_names[:2], round(model.tube_offset, 4)
    (7, ('psi', 'alpha'), 0.0025)
    >>> ToroidalBall(0.2, 0.01, 0.0125, 140.0, 0.02)
    Traceback (most recent call last):
    ...
    ValueError: ToroidalBall.ball_radius must be < tube_radius (0.01 m), got 0.0125
    """

    ring_radius: float
    tube_radius: float
    ball_radius: float
    spin_speed: float
    offset: float
    rolling_friction: float = 0.0
    gravity: float = 9.81
    form: Form = "rolling"

    def __post_init__(self) -> None:
        for name, unit, zero in (("ring_radius", "m", False), ("tube_radius", "m", False),
                                 ("ball_radius", "m", False), ("spin_speed", "rad/s", False),
                                 ("offset", "m", True), ("rolling_friction", "m", True),
                                 ("gravity", "m/s^2", True)):  # fmt: skip
            object.__setattr__(self, name, check_number("ToroidalBall", name, getattr(self, name), lo_open=not zero,
                                                         unit=unit))  # fmt: skip
        if self.ball_radius >= self.tube_radius:
            raise ValueError(
                f"ToroidalBall.ball_radius must be < tube_radius ({self.tube_radius:g} m), got {self.ball_radius!r}"
            )
        if self.tube_radius >= self.ring_radius:
            raise ValueError(
                f"ToroidalBall.tube_radius must be < ring_radius ({self.ring_radius:g} m), got {self.tube_radius!r}"
            )
        if self.form not in ("rolling", "paper"):
            raise ValueError(f"ToroidalBall.form must be 'rolling' or 'paper', got {self.form!r}")

    # ---- contract -----------------------------------------------------------------------------
    def _parameter_slots(self):
        return toroidal_slots(self)

    @property
    def kernels(self) -> Kernels:
        """Compiled kernels (shared by all instances)."""
        return _KERNELS

    @property
    def state_names(self) -> tuple[str, ...]:
        return ("psi", "alpha", "dpsi", "dalpha", "mode_psi", "mode_alpha", "t_switch")

    @property
    def n_state(self) -> int:
        return _k.N_STATE

    @property
    def tube_offset(self) -> float:
        """a = R1 - r, radius of the circle of the ball centre in the cross-section (m)."""
        return self.tube_radius - self.ball_radius

    def to_array(self) -> np.ndarray:
        """Packed parameters (order in :mod:`rotorlab._kernels.toroidal_ball`)."""
        if self.form == "rolling":
            coeffs = (1.0, 1.0, 12.0 / 7.0, 1.0, 1.0)
        else:
            coeffs = (0.0, 5.0 / 7.0, 10.0 / 7.0, 0.0, self.tube_radius / self.tube_offset)
        derived = (1.0 / self.tube_offset, 5.0 / 7.0 * self.rolling_friction / self.ball_radius)
        return np.array([self.ring_radius, self.tube_radius, self.ball_radius, self.spin_speed,
                         self.offset, self.rolling_friction, self.gravity, *coeffs, *derived])  # fmt: skip

    def revolution_times(self, t0: float, t1: float, p=None) -> np.ndarray:
        """Times in (t0, t1] after each whole revolution of the body since t0 (s).

        ``p`` (packed parameters) may give another spin speed than this model's.
        """
        om = self.spin_speed if p is None else float(np.asarray(p)[_k.P_OMEGA])
        period = 2.0 * math.pi / om
        n = int(math.floor((t1 - t0) / period * (1.0 + 1e-15)))
        return t0 + period * np.arange(1, n + 1)

    # ---- states and forces --------------------------------------------------------------------
    def initial_state(self, psi, alpha, dpsi=0.0, dalpha=0.0, t0: float = 0.0) -> np.ndarray:
        """Build states with consistent rolling modes.

        Parameters
        ----------
        psi, alpha : float or array_like
            Ring and cross-section angles (rad); broadcast together with the rates.
        dpsi, dalpha : float or array_like
            Rates relative to the body (rad/s).
        t0 : float
            Initial time (s), written into ``t_switch``.

        Returns
        -------
        ndarray, shape (..., 7)
            A direction with nonzero rate rolls that way; at zero rate it is stuck if rolling
            resistance can hold it (judged with the other direction as given), else it rolls
            towards its driving term.
        """
        b = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (psi, alpha, dpsi, dalpha)))
        y = np.zeros((*b[0].shape, _k.N_STATE))
        for i, v in enumerate(b):
            y[..., i] = v
        y[..., _k.I_MPSI] = np.sign(y[..., _k.I_DPSI])
        y[..., _k.I_MALPHA] = np.sign(y[..., _k.I_DALPHA])
        y[..., _k.I_TSWITCH] = t0
        flat = y.reshape(-1, _k.N_STATE)
        p = self.to_array()
        out = np.empty(5)
        for row in flat:
            for i_mode, i_f, i_b in ((_k.I_MPSI, 0, 2), (_k.I_MALPHA, 1, 3)):
                if row[i_mode] == 0.0:
                    _k.forces(row, p, out)
                    if abs(out[i_f]) > out[i_b]:
                        row[i_mode] = 1.0 if out[i_f] > 0 else -1.0
        return y

    def forces(self, y) -> dict[str, np.ndarray]:
        """Driving terms, friction bounds and normal force at states ``y``.

        Parameters
        ----------
        y : array_like, shape (..., 7)

        Returns
        -------
        dict of ndarray, shape (...)
            ``F_psi``, ``F_alpha`` (rad/s^2, accelerations without rolling resistance),
            ``B_psi``, ``B_alpha`` (rad/s^2, bounds of rolling resistance) and ``N`` (m/s^2).
            Rates of stuck directions count as zero.
        """
        y = np.asarray(y, dtype=float)
        flat = np.ascontiguousarray(y.reshape(-1, _k.N_STATE))
        res = np.empty((flat.shape[0], 5))
        p = self.to_array()
        for i in range(flat.shape[0]):
            _k.forces(flat[i], p, res[i])
        names = ("F_psi", "F_alpha", "B_psi", "B_alpha", "N")
        return {n: res[:, j].reshape(y.shape[:-1]) for j, n in enumerate(names)}

    def holds(self, psi, alpha) -> np.ndarray:
        """True where a ball at rest relative to the body at (psi, alpha) stays at rest.

        Parameters
        ----------
        psi, alpha : float or array_like
            Angles (rad).

        Returns
        -------
        ndarray of bool
            ``|F_psi| <= B_psi`` and ``|F_alpha| <= B_alpha`` at zero rates.
        """
        psi, alpha = np.broadcast_arrays(np.asarray(psi, dtype=float), np.asarray(alpha, dtype=float))
        y = np.zeros((*psi.shape, _k.N_STATE))
        y[..., 0] = psi
        y[..., 1] = alpha
        f = self.forces(y)
        return (np.abs(f["F_psi"]) <= f["B_psi"]) & (np.abs(f["F_alpha"]) <= f["B_alpha"])

    def rhs(self, t: float, y) -> np.ndarray:
        """dy/dt from the compiled kernel (a convenience for SciPy; allocates)."""
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty_like(y)
        _k.rhs(float(t), y, self.to_array(), out)
        return out

    def jacobi_integral(self, y) -> np.ndarray:
        """Jacobi integral per unit mass of the frictionless rolling ball (J/kg).

        ``7/10 (rho^2 psi'^2 + a^2 alpha'^2) - 1/2 omega^2 |c_xy|^2 - g a cos(alpha)`` with
        ``|c_xy|^2 = rho^2 - 2 e rho cos(psi) + e^2``: constant along motions of
        ``form="rolling"`` with ``rolling_friction = 0``, non-increasing with friction.

        Parameters
        ----------
        y : array_like, shape (..., 7) or (..., 4)
        """
        y = np.asarray(y, dtype=float)
        psi, alpha, dpsi, dalpha = (y[..., i] for i in range(4))
        a = self.tube_offset
        rho = self.ring_radius + a * np.sin(alpha)
        xy2 = rho**2 - 2.0 * self.offset * rho * np.cos(psi) + self.offset**2
        kin = 0.7 * (rho**2 * dpsi**2 + a**2 * dalpha**2)
        return kin - 0.5 * self.spin_speed**2 * xy2 - self.gravity * a * np.cos(alpha)

    # ---- working regime -----------------------------------------------------------------------
    def _f(self, psi: float, alpha: float) -> dict[str, np.ndarray]:
        y = np.zeros(_k.N_STATE)
        y[0], y[1] = psi, alpha
        return self.forces(y)

    def equilibrium_alpha(self, psi: float = math.pi) -> float:
        """Cross-section angle where a ball at rest at ring angle ``psi`` is in balance (rad).

        Solves ``F_alpha(psi, alpha) = 0`` for alpha in (0, pi) (frictionless).
        """
        from scipy.optimize import brentq

        return float(brentq(lambda al: float(self._f(psi, al)["F_alpha"]), 1e-12, math.pi - 1e-12, xtol=1e-15))

    def linearize(self, psi: float, alpha: float) -> np.ndarray:
        """Jacobian of the frictionless equations in ``(psi, alpha, psi', alpha')`` (1/s, 1/s^2).

        Central differences (step 1e-7 rad and rad/s) of the kernel with ``rolling_friction``
        set to 0; returns an array of shape (4, 4).
        """
        smooth = replace(self, rolling_friction=0.0)
        base = np.array([psi, alpha, 0.0, 0.0, 1.0, 1.0, 0.0])
        jac = np.empty((4, 4))
        h = 1e-7
        for j in range(4):
            yp, ym = base.copy(), base.copy()
            yp[j] += h
            ym[j] -= h
            jac[:, j] = (smooth.rhs(0.0, yp)[:4] - smooth.rhs(0.0, ym)[:4]) / (2.0 * h)
        return jac

    def working_point(self) -> WorkingPoint:
        """Return the working equilibrium (psi = pi) and its friction band.

        Returns
        -------
        WorkingPoint

        Notes
        -----
        The bands are the intervals where ``|F| <= B`` (stuck equilibria), found by root
        bracketing; without friction they shrink to the point. Seed 004 section V reports
        psi = 3.14156 rad, alpha = 1.56825 rad for its parameters.

        Examples
        --------
        >>> wp = strautmanis_torus().working_point()
        >>> round(wp.alpha, 5), wp.psi_band[0] < 3.14156 < wp.psi_band[1]
        (1.56855, True)
        """
        from scipy.optimize import brentq

        alpha = self.equilibrium_alpha(math.pi)
        normal = float(self._f(math.pi, alpha)["N"])
        lam = np.linalg.eigvals(self.linearize(math.pi, alpha))
        freqs = np.sort(np.unique(np.round(np.abs(lam.imag), 9)))[-2:]

        def psi_margin(psi: float) -> float:
            f = self._f(psi, self.equilibrium_alpha(psi))
            return float(f["B_psi"] - abs(f["F_psi"]))

        def alpha_margin(al: float) -> float:
            f = self._f(math.pi, al)
            return float(f["B_alpha"] - abs(f["F_alpha"]))

        if self.rolling_friction == 0.0:
            return WorkingPoint(math.pi, alpha, normal, (math.pi, math.pi), (alpha, alpha), freqs)
        psi_band = (
            float(brentq(psi_margin, math.pi / 2, math.pi, xtol=1e-14)),
            float(brentq(psi_margin, math.pi, 1.5 * math.pi, xtol=1e-14)),
        )
        lo = brentq(alpha_margin, 1e-9, alpha, xtol=1e-15) if alpha_margin(1e-9) < 0 else 0.0
        hi = brentq(alpha_margin, alpha, math.pi - 1e-9, xtol=1e-15) if alpha_margin(math.pi - 1e-9) < 0 else math.pi
        return WorkingPoint(math.pi, alpha, normal, psi_band, (float(lo), float(hi)), freqs)

    def restoring_force(self, psi) -> "xarray.Dataset":  # noqa: F821
        """Forces per unit mass on a ball at rest at ring angle psi (seed Fig. 3).

        The ball sits at its frictionless cross-section equilibrium for each psi.

        Parameters
        ----------
        psi : array_like, shape (n,)
            Ring angles (rad).

        Returns
        -------
        xarray.Dataset
            Dim ``psi``; ``tangential`` = e omega^2 sin(psi), the component along the ring of
            the centrifugal force (positive towards increasing psi; it pushes the ball towards
            pi), ``radial`` = omega^2 (rho - e cos(psi)) (horizontal, away from the torus
            axis), ``friction_limit`` = k N / r (largest rolling resistance), ``normal`` = N
            (all N/kg = m/s^2) and ``alpha`` (rad).
        """
        import xarray as xr

        psi = np.atleast_1d(np.asarray(psi, dtype=float))
        alpha = np.array([self.equilibrium_alpha(float(v)) for v in psi])
        y = np.zeros((psi.size, _k.N_STATE))
        y[:, 0], y[:, 1] = psi, alpha
        normal = np.maximum(self.forces(y)["N"], 0.0)
        rho = self.ring_radius + (self.tube_offset * np.sin(alpha) if self.form == "rolling" else 0.0)
        om2 = self.spin_speed**2
        return xr.Dataset(
            {
                "tangential": ("psi", self.offset * om2 * np.sin(psi), {"units": "N/kg"}),
                "radial": ("psi", om2 * (rho - self.offset * np.cos(psi)), {"units": "N/kg"}),
                "friction_limit": ("psi", self.rolling_friction * normal / self.ball_radius, {"units": "N/kg"}),
                "normal": ("psi", normal, {"units": "N/kg"}),
                "alpha": ("psi", alpha, {"units": "rad"}),
            },
            coords={"psi": ("psi", psi, {"units": "rad"})},
            attrs={"form": self.form, "reference": "Strautmanis, seed 004, Fig. 3"},
        )


def strautmanis_torus(rolling_friction: float = 1e-5, *, form: Form = "rolling") -> ToroidalBall:
    """Return the balancer of seed 004 section IV.

    R = 0.2 m, R1 = 0.015 m, r = 0.0125 m, omega = 140 1/s, e = 0.02 m, g = 9.81 m/s^2 and the
    rolling friction k (m; the paper uses 1e-5 and 1e-4).

    Examples
    --------
    >>> strautmanis_torus(1e-4, form="paper").rolling_friction
    0.0001
    """
    return ToroidalBall(0.2, 0.015, 0.0125, 140.0, 0.02, rolling_friction, 9.81, form)
