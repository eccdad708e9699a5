r"""Planar Jeffcott rotor with n automatic-balancer balls or pendulums (model ``jeffcott_balls``).

A disc of mass M1 sits on a shaft of lateral stiffness c; its centre O1 = (x, y) moves in the
plane, its mass centre is at distance e from O1 along the direction theta(t) of the prescribed
spin (counter-clockwise positive, unbalance along +x at t = 0). Ball (pendulum) i of mass m_i
runs on a circle of radius l_i about O1 at the absolute angle phi_i, with moment of inertia J_i
about the shaft axis, viscous damping b_i and optional Coulomb friction f_i on its motion relative
to the rotor. External viscous damping d acts on the velocity of O1.

Equations (fixed frame; M = M1 + sum m_i)
-----------------------------------------
From T = 1/2 M1 |v_C|^2 + sum_i [1/2 m_i |v_O1|^2 + m_i l_i phi_i' (-x' sin phi_i + y' cos phi_i)
+ 1/2 J_i phi_i'^2], Pi = 1/2 c (x^2 + y^2) and the Rayleigh function
Phi = 1/2 d (x'^2 + y'^2) + 1/2 sum_i b_i (phi_i' - theta')^2::

    M x'' + d x' + c x = M1 e (theta'^2 cos theta + theta'' sin theta)
                         + sum_i m_i l_i (phi_i'' sin phi_i + phi_i'^2 cos phi_i)
    M y'' + d y' + c y = M1 e (theta'^2 sin theta - theta'' cos theta)
                         + sum_i m_i l_i (phi_i'^2 sin phi_i - phi_i'' cos phi_i)
    J_i phi_i''        = m_i l_i (x'' sin phi_i - y'' cos phi_i) - b_i (phi_i' - theta') + T_i

T_i is the Coulomb torque. For point masses (J_i = m_i l_i^2) these are Zhakash et al. 2024
eqs. (1)-(3) (beta_0 = b / (m R^2), beta = d, r = e, R = l) written in their mirrored axes:
x_s = x, y_s = -y, phi_s = phi (their y axis and angle sense are both reversed, so the printed
clockwise angle is numerically our counter-clockwise one); for n = 2 they are exactly
the project's benchmark problem (:data:`rotorlab.models.BENCHMARK`) with M1 e = eps, beta = b. The rotating frame uses
x + i y = e^{i theta}(u + i v), phi_i = theta + psi_i; steady motions at constant speed are its
equilibria. The model is a preset of the composed machine (:attr:`JeffcottBalls.machine`,
:mod:`rotorlab.models._jeffcott_machine`): in both frames it integrates on the machine's
generated kernels (the co-rotating one turns the fixed frame's lines with the spin,
:mod:`rotorlab._kernels.machine_corotating`). Its hand-written kernels,
:mod:`rotorlab._kernels.jeffcott_balls`, are the tests' oracle and document the first
``12 + 6 n`` packed parameters (the machine's follow them).

Coulomb friction uses the exact normal force of the race on the ball,
N_i = m_i (l_i phi_i'^2 - x'' cos phi_i - y'' sin phi_i) (radial equation of the ball's mass
centre): it is linear in the rotor acceleration, so it is solved together with the motion (no
implicit equation). The model assumes N_i >= 0 (ball pressed on its race, true while the
centripetal term dominates the radial acceleration of O1). Slip: T_i = -mode_i f_i l_i N_i; stick:
the ball turns with the rotor, the race holds the driving torque D_i (see the kernel module).

Inertia of a ball: J_i is Filimonikhin & Filimonikhina's J_Oi, the axial moment of inertia about
the shaft axis; the body turns with phi_i' (pendulum: exact; ball: J_i = m_i l_i^2 + J_c, which
gives the seed's T0 and all steady motions). A ball rolling without slip on a race of radius
l_i + r_b spins at theta' - (l_i / r_b) psi_i' instead; at constant speed its motion is
reproduced exactly by J_i = m_i l_i^2 + J_c (l_i / r_b)^2 (the remaining difference, a constant
times psi_i' in T1, is a null Lagrangian), with H* then shifted by a constant only.

H* (Filimonikhin & Filimonikhina eq. (4)) in the rotating frame, constant speed Omega::

    T2 = 1/2 M (u'^2 + v'^2) + sum_i [m_i l_i psi_i' (-u' sin psi_i + v' cos psi_i) + 1/2 J_i psi_i'^2]
    T0 = 1/2 Omega^2 [M (u^2 + v^2) + 2 M1 e u + M1 e^2 + 2 sum_i m_i l_i (u cos psi_i + v sin psi_i)
                      + sum_i J_i],   H* = T2 + Pi - T0,   H~* = Pi - T0 (eq. (10))

The disc's own spin energy 1/2 J_C theta'^2 is prescribed and left out of T0, H*, the energy and
the drive torque.

Corrections to the seeds
------------------------
Each was found by re-deriving the printed formula and is checked in
``tests/validation/test_jeffcott_seed002.py`` or ``test_jeffcott_seed003.py``.

Zhakash et al. 2024 (seed 002):

- (1)-(3), axes: the equations hold for x_s = x, y_s = -y, phi_s = phi at the same omega > 0
  (or y_s = y, phi_s = -phi for a model spun at -omega); the reading "y -> -y and phi -> -phi"
  does not satisfy them. Checked: kernel against (1)-(3) at random states.
- (5): printed ``M x'' + c x'`` -> ``M x'' + c x`` (and z -> r); (6): printed forcing
  ``+M1 z omega^2 sin(omega t)`` -> ``-M1 r omega^2 sin(omega t)`` as in (3) and (9).
- (10): printed ``W = m/M1 * omega^2/(p^2 - omega^2)`` -> ``W = m/M * omega^2/(p^2 - omega^2)``,
  M = M1 + k m: substituting (9) into (2)-(3) gives it. Checked: the steady rotor amplitude with
  the balls held by friction at alpha_j equals ``W R |eta + sum_j e^{i alpha_j}|`` (damped form
  ``omega^2 |U| / |c - M omega^2 + i d omega|``) in a long simulation, and not the printed M1.
- (11): printed ``P_s = 1/(beta0 R) int_0^{2pi/omega}(...) dt = +1/2 omega^2/beta0 W [...]`` ->
  ``P_s = 1/(beta0 R) <x0'' sin phi_s + y0'' cos phi_s> = -(omega^2 W / beta0) [eta sin alpha_s
  + sum_j sin(alpha_s - alpha_j)]`` with <.> the mean over a period: the integrand is constant on
  (9), so there is no factor 1/2, and the sign is negative. (15) has the sign right but keeps the
  1/2, which carries into (19), (21), (23) (``omega^2 W/(2 beta0)``, ``omega^4 W^2/(4 beta0^2)``);
  the signs of A, B, hence the stability conclusions, are unaffected. Checked: quadrature of (9)
  and the drift of the ball phases in a simulation with strongly damped balls.
- (14): printed ``|dP_s/dalpha_j - delta_sj theta c| = theta`` -> ``det(dP_s/dalpha_j -
  kappa delta_sj) = 0``.
- (21): printed ``A = (omega W / beta0)(-eta cos gamma + cos 2 gamma)`` -> ``omega^2 W / beta0``
  and ``eta cos gamma^2`` -> ``eta cos^2 gamma``; with the corrected P_s (no 1/2),
  ``A^(1) = -2 K`` and ``B^(1) = (1 - eta^2/4) K^2 eta^2``, ``K = omega^2 W / beta0``. Positivity
  of A^(1) means ``W < 0`` (printed "W > 0"), which by the corrected (10) is omega > p, (22).
- (23): corrected, ``A^(2) = 2 K (1 + eta)``, ``B^(2) = K^2 eta (eta + 2)``,
  ``A^(3) = 2 K (1 - eta)``, ``B^(3) = K^2 eta (eta - 2)``, ``A^(4) = -2 K``,
  ``B^(4) = -K^2 eta^2``. Printed: a spurious leading minus on A^(3), B^(3), A^(4); in B^(3) the
  last factor cos pi for cos(alpha_1 - alpha_2) = 1; B^(4) with eta for eta^2. The third solution
  (both balls on the light side) is stable above p only for eta > 2 (capacity short, seed 003
  case 2b); under (17), eta < 2, it is unstable (printed: stable for omega > p). Checked: A, B
  from the Jacobian of the corrected P_s, and the eigenvalues of the full model (eta = 1.2, 2.6).
- (24): potential printed ``1/2 C[(x0')^2 + (y0')^2]`` -> ``1/2 c[(x0)^2 + (y0)^2]``; (25):
  ``D = -M m omega^2 R^2 / M1 W [...]`` -> ``D = -m omega^2 R^2 W [eta sum_s cos alpha_s + 1/2
  sum_s sum_j cos(alpha_s - alpha_j)]`` (plus the constant ``-1/2 m omega^2 R^2 W eta^2``), which is
  seed 003's H~* (16) up to a constant, and ``P_s = -dD/dalpha_s / (beta0 m R^2)``.

Filimonikhin & Filimonikhina (seed 003):

- Line before (2) and (2): printed ``... - q_i' dL/dq_i'`` and ``d/dt(...) = sum q_i' dL/dq_i'``
  -> ``sum q_i' Q_i`` (Lagrange's equations (1)); only then does (5) ``dH*/dt = -2 Phi``
  follow. Checked: H* along damped trajectories.
- (6): ``i = 1..n`` -> ``i = 1..N`` (all coordinates; (11) differentiates by x, y too).
- Case 2b: printed ``H~*(2^n) > H~*(k)`` -> ``H~*(2^n) < H~*(k)``: with c < M_S omega^2, (15)
  gives ``2 H~*(k) = omega^4 (Me + s(k))^2 / |c - M_S omega^2| + const``, least for all k_i = 1.
  Checked: H~* on all 2^3 side motions of an example with Me > sum m_i l_i.
- Fourth side motion, case ii: printed ``Me < m1 l1 + m2 l2`` (repeats case i) ->
  ``Me > m1 l1 + m2 l2``. Checked: numerical Hessian of f against (19) and its definiteness.
- (17) defines f = u^2 + v^2, (18) f = (u^2 + v^2)/2; (19) is the Hessian of the latter (a factor
  2, signs unaffected). The seed's M is the disc mass (our M1), M_S = M1 + sum m_i, its J_O the
  disc's inertia about O (constant, left out here).

References
----------
Zhakash A.T., Dzhakashova E.A., Yesilkhankyzy A. Mathematical model of autobalancer movement.
Mechanics and Technologies 3(85), 2024, 440-446, eqs. (1)-(25).

Filimonikhin G.B., Filimonikhina I.I. Application of the Hamilton function to the conditions of
auto-balancing (Kirovohrad National Technical University), eqs. (1)-(19).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np

from rotorlab._kernels import jeffcott_balls as _k
from rotorlab.models._base import Kernels
from rotorlab.models._jeffcott_frames import fixed_to_rotating, rotating_to_fixed
from rotorlab.models._jeffcott_params import BallParams, RotorParams
from rotorlab.models._parameters import jeffcott_slots
from rotorlab.models._protocol import ParametrisedMixin
from rotorlab.models._speed import ConstantSpeed, SpeedProfile, speed_from_array  # noqa: F401

__all__ = ["JeffcottBalls", "fixed_to_rotating", "rotating_to_fixed", "FIXED_FRAME_ABOVE"]

Frame = Literal["fixed", "rotating"]
#: Speed ratio Omega / p from which :meth:`JeffcottBalls.cheapest_frame` chooses the fixed frame
#: (where the balls can balance the rotor). Between 1.5 p and 2 p the co-rotating frame stops
#: being the cheaper one on the benchmark problem and the ``autobalancer`` case
#: (``bench/README.md``, issue 11).
FIXED_FRAME_ABOVE = 1.8


@dataclass(frozen=True, slots=True)
class JeffcottBalls(ParametrisedMixin):
    """Jeffcott rotor with n >= 0 balls or pendulums, in the fixed or the co-rotating frame.

    Parameters
    ----------
    rotor : RotorParams
        Disc and shaft.
    balls : sequence of BallParams
        The balls (pendulums), possibly unequal; stored as a tuple.
    speed : ConstantSpeed or LinearRamp or HillRunUp
        Prescribed spin (keyword only).
    frame : {"fixed", "rotating"}
        Frame of the state vector (keyword only), see the module docstring.

    Notes
    -----
    States: fixed ``[x, y, vx, vy, phi_1..phi_n, w_1..w_n]``, rotating
    ``[u, v, du, dv, psi_1..psi_n, dpsi_1..dpsi_n]`` (m, m/s, rad, rad/s); when any ball has
    friction > 0, n trailing stick/slip modes in {-1, 0, +1} follow.

    Both frames integrate on the preset machine's generated kernels (:attr:`machine`,
    :attr:`kernels`): the fixed frame on :attr:`Machine.kernels`, the co-rotating frame on
    :attr:`Machine.rotating_kernels` (the fixed frame's equations turned with the spin), with one
    packed vector (:meth:`to_array`).

    Examples
    --------
    >>> rotor = RotorParams(disc_mass=0.96, eccentricity=0.01 / 0.96, stiffness=1.0, damping=0.02)
    >>> ball = BallParams(mass=0.02, radius=1.0, damping=0.01)
    >>> model = JeffcottBalls(rotor, (ball, ball), speed=ConstantSpeed(2.5))
    >>> model.n_state, round(model.critical_speed, 12), model.state_names[4]
    (8, 1.0, 'phi_1')
    """

    rotor: RotorParams
    balls: tuple[BallParams, ...] = ()
    speed: SpeedProfile = field(kw_only=True)
    frame: Frame = field(default="fixed", kw_only=True)

    def __post_init__(self) -> None:
        if not isinstance(self.rotor, RotorParams):
            raise ValueError(f"JeffcottBalls.rotor must be a RotorParams, got {type(self.rotor).__name__}")
        balls = tuple(self.balls)
        for i, b in enumerate(balls):
            if not isinstance(b, BallParams):
                raise ValueError(f"JeffcottBalls.balls[{i}] must be a BallParams, got {type(b).__name__}")
        object.__setattr__(self, "balls", balls)
        if not hasattr(self.speed, "to_array") or not hasattr(self.speed, "spin_speed"):
            raise ValueError(
                "JeffcottBalls.speed must be ConstantSpeed, LinearRamp or HillRunUp, "
                f"got {type(self.speed).__name__}"
            )
        if self.frame not in ("fixed", "rotating"):
            raise ValueError(f"JeffcottBalls.frame must be 'fixed' or 'rotating', got {self.frame!r}")

    # ---- sizes and names ----------------------------------------------------------------------
    @property
    def n_balls(self) -> int:
        """Number of balls n."""
        return len(self.balls)

    @property
    def has_friction(self) -> bool:
        """True when some ball has Coulomb friction (the state then carries n modes)."""
        return any(b.friction > 0.0 for b in self.balls)

    @property
    def machine(self):
        """The :class:`~rotorlab.models.Machine` this rotor is, ball friction included (shared, cached).

        Its state is this model's fixed-frame state entry for entry and its right-hand side, events
        and energy are this model's (:mod:`rotorlab.models._jeffcott_machine`).
        """
        from rotorlab.models._jeffcott_machine import jeffcott_machine

        return jeffcott_machine(replace(self, frame="fixed"))

    @property
    def kernels(self) -> Kernels:
        """Compiled kernels (shared, cached): the preset machine's (:attr:`machine`) of this
        model's frame, :attr:`Machine.kernels` or :attr:`Machine.rotating_kernels`
        (:func:`rotorlab.models._jeffcott_machine.jeffcott_kernels`)."""
        from rotorlab.models._jeffcott_machine import jeffcott_kernels

        return jeffcott_kernels(self)

    @property
    def n_state(self) -> int:
        """Length of the state vector (modes included)."""
        return 4 + (3 if self.has_friction else 2) * self.n_balls

    @property
    def state_names(self) -> tuple[str, ...]:
        """Name of each state entry, in order."""
        n = range(1, self.n_balls + 1)
        if self.frame == "fixed":
            names = ["x", "y", "vx", "vy"] + [f"phi_{i}" for i in n] + [f"w_{i}" for i in n]
        else:
            names = ["u", "v", "du", "dv"] + [f"psi_{i}" for i in n] + [f"dpsi_{i}" for i in n]
        if self.has_friction:
            names += [f"mode_{i}" for i in n]
        return tuple(names)

    # ---- derived quantities -------------------------------------------------------------------
    @property
    def total_mass(self) -> float:
        """M = M1 + sum m_i (kg)."""
        return self.rotor.disc_mass + sum(b.mass for b in self.balls)

    @property
    def critical_speed(self) -> float:
        """sqrt(c / M), the critical speed of the rotor with the balls locked (rad/s)."""
        return math.sqrt(self.rotor.stiffness / self.total_mass)

    @property
    def imbalance(self) -> float:
        """M1 e (kg m)."""
        return self.rotor.imbalance

    @property
    def capacity(self) -> float:
        """Balancing capacity sum m_i l_i (kg m)."""
        return sum(b.static_moment for b in self.balls)

    def cheapest_frame(self, spin_speed: float) -> Frame:
        """Return the frame in which start-ups at ``spin_speed`` (rad/s) integrate cheapest.

        ``"fixed"`` at >= :data:`FIXED_FRAME_ABOVE` (1.8) times the critical speed with the
        capacity to balance (sum m_i l_i >= M1 e), else ``"rotating"``. A start that ends balanced
        takes about a third of the right-hand-side evaluations in the fixed frame (in the
        co-rotating one the decaying relative motion oscillates at p +- Omega instead of p); one
        that ends in a steady whirl (side motions, below or near p) 1.4-5x more (its whirl is
        constant in the co-rotating frame). Measured in ``bench/README.md`` (issue 11).
        """
        balances = abs(float(spin_speed)) >= FIXED_FRAME_ABOVE * self.critical_speed \
            and self.capacity >= self.imbalance
        return "fixed" if balances else "rotating"

    # ---- packing --------------------------------------------------------------------------------
    def to_array(self) -> np.ndarray:
        """Return the packed parameters: the ``12 + 6 n`` of :mod:`rotorlab._kernels.jeffcott_balls`
        followed by the preset machine's (its kernels' in both frames, ``param_base``)."""
        r = self.rotor
        head = [float(self.n_balls), 1.0 if self.has_friction else 0.0, r.disc_mass,
                r.eccentricity, r.stiffness, r.damping]  # fmt: skip
        balls = [[b.mass, b.radius, b.inertia, b.damping, b.friction, 1.0 / b.inertia if b.inertia else math.inf]
                 for b in self.balls]  # fmt: skip
        own = np.concatenate([head, self.speed.to_array(), np.ravel(balls)]).astype(float)
        p = self.machine.to_array()
        p[:own.size] = own
        return p

    @classmethod
    def from_array(cls, p, *, frame: Frame = "fixed") -> JeffcottBalls:
        """Rebuild a model from its packed parameters (inverse of :meth:`to_array`).

        Parameters
        ----------
        p : array_like, shape (12 + 6 n,) or longer
            Only the first ``12 + 6 n`` entries are read (:meth:`to_array` puts the machine's
            after them).
        frame : {"fixed", "rotating"}

        Returns
        -------
        JeffcottBalls
        """
        p = np.asarray(p, dtype=float)
        n = int(p[_k.P_N]) if p.size else -1
        if p.ndim != 1 or n < 0 or p.size < _k.P_BALLS + _k.BALL_STRIDE * n:
            raise ValueError(f"p must have at least 12 + 6 n entries with n = p[0]; got shape {p.shape}")
        rotor = RotorParams(p[_k.P_M1], p[_k.P_E], p[_k.P_C], p[_k.P_D])
        balls = tuple(
            BallParams(*p[_k.P_BALLS + _k.BALL_STRIDE * i : _k.P_BALLS + _k.BALL_STRIDE * i + _k.B_IJ])
            for i in range(n)
        )
        speed = speed_from_array(p[_k.P_SPEED : _k.P_SPEED + 6])
        return cls(rotor, balls, speed=speed, frame=frame)

    def with_speed(self, speed: SpeedProfile) -> JeffcottBalls:
        """Return a copy with another speed profile."""
        return replace(self, speed=speed)

    def _parameter_slots(self):
        return jeffcott_slots(self)

    def _compiled_layout(self):
        from rotorlab.models._jeffcott_machine import jeffcott_layout

        return jeffcott_layout(self)

    def with_frame(self, frame: Frame) -> JeffcottBalls:
        """Return a copy whose states are in ``frame``."""
        return replace(self, frame=frame)

    # ---- spin and frames ----------------------------------------------------------------------
    def spin(self, t):
        """Return ``(theta, omega, domega)`` at times ``t`` (rad, rad/s, rad/s^2)."""
        return self.speed.spin_angle(t), self.speed.spin_speed(t), self.speed.spin_acceleration(t)

    def revolution_times(self, t0: float, t1: float, p=None) -> np.ndarray:
        """Return the times in (t0, t1] after each whole revolution since t0 (s).

        Parameters
        ----------
        t0, t1 : float
            Time span (s).
        p : array_like, optional
            Packed parameters whose speed block is used (default: this model's).
        """
        speed = self.speed if p is None else speed_from_array(np.asarray(p)[_k.P_SPEED : _k.P_SPEED + 6])
        return speed.revolution_times(t0, t1)

    def to_frame(self, t, y, frame: Frame) -> np.ndarray:
        """Convert states from this model's frame to ``frame``.

        Parameters
        ----------
        t : float or array_like, shape (...)
            Times of the states (s).
        y : array_like, shape (..., n_state)
        frame : {"fixed", "rotating"}

        Returns
        -------
        ndarray, shape (..., n_state)
        """
        y = np.asarray(y, dtype=float)
        if y.shape[-1] != self.n_state:
            raise ValueError(f"y must have n_state = {self.n_state} entries last, got {y.shape}")
        if frame not in ("fixed", "rotating"):
            raise ValueError(f"frame must be 'fixed' or 'rotating', got {frame!r}")
        if frame == self.frame:
            return np.array(y, copy=True)
        th, om, _ = self.spin(np.broadcast_to(np.asarray(t, dtype=float), y.shape[:-1]))
        conv = rotating_to_fixed if frame == "fixed" else fixed_to_rotating
        return conv(th, om, y, self.n_balls)

    # ---- evaluation helpers -------------------------------------------------------------------
    def rhs(self, t: float, y) -> np.ndarray:
        """Return dy/dt from the compiled kernel (a convenience for SciPy; allocates)."""
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty_like(y)
        self.kernels.rhs(float(t), y, self.to_array(), out)
        return out

    def stick_torques(self, t: float, y, forced: int = -1):
        """Return the stick/slip quantities of the balls at one state.

        Parameters
        ----------
        t : float
            Time (s).
        y : array_like, shape (n_state,)
            State in this model's frame.
        forced : int
            Ball index (0-based) treated as stuck in addition to the stuck modes; -1: none.

        Returns
        -------
        drive : ndarray, shape (n,)
            Driving torque D_i the race must hold for a stuck ball (N m).
        bound : ndarray, shape (n,)
            Friction limit f_i l_i N_i (N m).
        normal : ndarray, shape (n,)
            Normal force N_i (N).
        acceleration : ndarray, shape (2,)
            Absolute acceleration of O1 in the frame's axes (m/s^2).
        """
        n = self.n_balls
        y = np.ascontiguousarray(y, dtype=float)
        drive, bound, acc = np.empty(n), np.empty(n), np.empty(2 + n)
        _k.stick_torques(float(t), y, self.to_array(), self.frame == "rotating", int(forced), drive, bound, acc)
        return drive, bound, acc[2:], acc[:2]

    def initial_modes(self, t: float, y) -> np.ndarray:
        """Return a copy of state ``y`` with stick/slip modes consistent with it.

        A ball with nonzero relative speed slips in that direction; a ball at zero relative
        speed sticks if the race can hold it (decided jointly, stuck balls first), otherwise it
        slips with the sign of its driving torque. Without friction ``y`` is returned unchanged.
        """
        y = np.array(y, dtype=float)
        if not self.has_friction:
            return y
        n = self.n_balls
        th, om, _ = self.spin(float(t))
        rel = y[4 + n : 4 + 2 * n] - (0.0 if self.frame == "rotating" else float(om))
        fr = np.array([b.friction for b in self.balls])
        y[4 + 2 * n :] = np.where(rel > 0, 1.0, np.where(rel < 0, -1.0, 0.0))
        y[4 + 2 * n :][fr == 0.0] = 1.0
        for _ in range(n + 1):
            drive, bound, _, _ = self.stick_torques(t, y)
            stuck = np.flatnonzero(y[4 + 2 * n :] == 0.0)
            bad = [i for i in stuck if abs(drive[i]) > bound[i]]
            if not bad:
                break
            worst = max(bad, key=lambda i: abs(drive[i]) - bound[i])
            y[4 + 2 * n + worst] = 1.0 if drive[worst] >= 0 else -1.0
        return y

    def locked_response(self, ball_angles=(), spin_speed: float | None = None) -> complex:
        """Return the steady rotor displacement u + i v with the balls locked at ``ball_angles``.

        Parameters
        ----------
        ball_angles : array_like, shape (n,)
            psi_i, angles of the balls from the unbalance direction (rad).
        spin_speed : float, optional
            Omega (rad/s); default the speed at t = 0.

        Returns
        -------
        complex
            ``u + i v = Omega^2 U / (c - M Omega^2 + i d Omega)`` (m) in the co-rotating frame,
            ``U = M1 e + sum m_i l_i e^{i psi_i}``.

        Notes
        -----
        With d = 0 this is Zhakash et al. 2024 eq. (9) with the corrected W of eq. (10).
        """
        psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        if psi.size != self.n_balls:
            raise ValueError(f"ball_angles must have {self.n_balls} entries, got {psi.size}")
        om = float(self.speed.spin_speed(0.0)) if spin_speed is None else float(spin_speed)
        r = self.rotor
        unb = r.imbalance + sum(b.static_moment * np.exp(1j * a) for b, a in zip(self.balls, psi))
        return complex(om * om * unb / (r.stiffness - self.total_mass * om * om + 1j * r.damping * om))

    def initial_state(self, ball_angles=(), *, rotor: Literal["rest", "steady"] = "rest",
                      ball_rates=None, t0: float = 0.0) -> np.ndarray:  # fmt: skip
        """Build an initial state in this model's frame.

        Parameters
        ----------
        ball_angles : array_like, shape (n,)
            Angles psi_i of the balls from the unbalance direction (rad).
        rotor : {"rest", "steady"}
            ``"rest"``: O1 at the origin with zero absolute velocity; ``"steady"``: O1 on the
            steady unbalance response with the balls locked (:meth:`locked_response`).
        ball_rates : array_like, shape (n,), optional
            Rates psi_i' relative to the rotor (rad/s); default 0 (co-rotating).
        t0 : float
            Initial time (s).

        Returns
        -------
        ndarray, shape (n_state,)
            With consistent stick/slip modes when the model has friction.
        """
        n = self.n_balls
        psi = np.asarray(ball_angles, dtype=float).reshape(-1)
        if psi.size != n:
            raise ValueError(f"ball_angles must have {n} entries, got {psi.size}")
        rates = np.zeros(n) if ball_rates is None else np.asarray(ball_rates, dtype=float).reshape(-1)
        if rates.size != n:
            raise ValueError(f"ball_rates must have {n} entries, got {rates.size}")
        if rotor not in ("rest", "steady"):
            raise ValueError(f"rotor must be 'rest' or 'steady', got {rotor!r}")
        th, om, _ = (float(v) for v in self.spin(float(t0)))
        y = np.zeros(4 + 3 * n if self.has_friction else 4 + 2 * n)
        if rotor == "steady":  # at rest in the co-rotating frame
            z = self.locked_response(psi, om)
            y[0], y[1] = z.real, z.imag
        y[4 : 4 + n] = psi
        y[4 + n : 4 + 2 * n] = rates
        if self.has_friction:
            y[4 + 2 * n :] = 1.0
        rot = replace(self, frame="rotating")
        y = rot.initial_modes(t0, y)
        return y if self.frame == "rotating" else rot.to_frame(t0, y, "fixed")

    # ---- physics (see _jeffcott_physics) ------------------------------------------------------
    def energy(self, t, y):
        """Total mechanical energy T + Pi in the fixed frame (J); see :func:`energy`."""
        from rotorlab.models._jeffcott_physics import energy

        return energy(self, t, y)

    def hamiltonian(self, y, t=0.0):
        """Filimonikhin & Filimonikhina's H* = T2 + Pi - T0 (J); see :func:`hamiltonian`."""
        from rotorlab.models._jeffcott_physics import hamiltonian

        return hamiltonian(self, y, t)

    def reduced_hamiltonian(self, y, t=0.0):
        """H~* = Pi - T0 of eq. (10) (J); see :func:`reduced_hamiltonian`."""
        from rotorlab.models._jeffcott_physics import reduced_hamiltonian

        return reduced_hamiltonian(self, y, t)

    def dissipation(self, y, t=0.0):
        """Rayleigh function Phi (W); see :func:`dissipation`."""
        from rotorlab.models._jeffcott_physics import dissipation

        return dissipation(self, y, t)

    def hamiltonian_rate(self, y, t=0.0):
        """dH*/dt = sum q_i' Q_i at constant speed (W); see :func:`hamiltonian_rate`."""
        from rotorlab.models._jeffcott_physics import hamiltonian_rate

        return hamiltonian_rate(self, y, t)

    def drive_torque(self, t, y):
        """Torque the drive applies to keep the prescribed spin (N m); see :func:`drive_torque`."""
        from rotorlab.models._jeffcott_physics import drive_torque

        return drive_torque(self, t, y)

    def linearize(self, y_eq, spin_speed: float | None = None):
        """Linearize about a steady motion (rotating frame); see :func:`linearize`."""
        from rotorlab.models._jeffcott_physics import linearize

        return linearize(self, y_eq, spin_speed)
