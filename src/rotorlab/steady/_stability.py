r"""Stability of a steady motion, three ways: seed 003's Hamilton function, seed 002's averaged
equations, and the exact eigenvalues of the co-rotating-frame Jacobian.

1. **Hamilton function** (Filimonikhin & Filimonikhina). On the rotor constraint (first two of
   eqs. (11)) ``2 H~* = -Omega^4 |U|^2 / (c - M Omega^2) + const`` (eq. (16)), ``U = u + i v =
   M1 e + sum m_i l_i e^{i psi_i}`` (eq. (12)'s unbalance parameters). A motion "can be stable"
   when H~* is least among the steady motions (eqs. (14), (15)) and f = |U|^2 / 2 (eq. (18)) has
   a minimum there above ``omega_cr = sqrt(c / M)`` or a maximum below it (remarks 1-3 after
   (17)); the Hessian of f is eq. (19), here for any n::

       a_ii = (m_i l_i)^2 - m_i l_i Re(U e^{-i psi_i}),   a_ij = m_i l_i m_j l_j cos(psi_j - psi_i).

   Seed 003 assumes undamped supports, so this method is applied to the motion of the same label
   with d = 0 (eq. (13)); its verdict "stable" is what the seed's conclusions assert.
2. **Averaged equations** (Zhakash et al. eqs. (11), (14), (19)-(20), corrected as listed in
   :mod:`rotorlab.models._jeffcott_balls`, generalised to unequal balls). First-order averaging
   on the generating solution (9) (d neglected) gives ``psi_s' = P_s(psi) = Omega^2 m_s l_s
   Im(z0 e^{-i psi_s}) / b_s``, ``z0 = Omega^2 U / (c - M Omega^2)``, i.e. the gradient flow
   ``P = (Omega^4 / (c - M Omega^2)) B^{-1} grad f`` (B = diag b_s); its Jacobian is
   ``(Omega^4 / (c - M Omega^2)) B^{-1} a`` with the a of eq. (19). For n = 2, A = -trace and
   B = det of eq. (19); the motion is stable when every eigenvalue is negative ((20) for k = 2).
   Equal balls: ``K = Omega^2 W / beta0 = Omega^4 m / (beta0 (c - M Omega^2))``.
3. **Exact**: eigenvalues of the co-rotating linearization of the machine the rotor is
   (:meth:`rotorlab.models.Machine.linearize`, classified by
   :func:`rotorlab.models._machine_rotating.spectrum_verdict`, the
   implementation every isotropic machine uses; shaft and ball damping, ball inertia, support
   damping) at the exact steady motion. Along a family of main motions the n - 2 zero
   eigenvalues of the neutral directions are left out.

Methods 1 and 2 hold only for the planar point-mass balancer (one disc, one race in its plane,
isotropic supports): they run on :class:`rotorlab.models.JeffcottBalls` and, for a machine, only
where it is that rotor (:func:`rotorlab.analyses._machine_steady.jeffcott_limit`; elsewhere they
are "n/a" with the reason).

Methods 1 and 2 are both first-order (slow-ball) approximations; their local criteria coincide
(the averaged Jacobian is similar to ``a`` up to the sign of c - M Omega^2), and so do the
verdicts: f = |U|^2 / 2 on the torus of ball angles has no local minimum or maximum other than
the global ones (the distance function of a planar robot arm), so seed 003's "least H~*" clause
adds nothing to the Hessian test (a property test checks this). Both can disagree with the exact
eigenvalues: see :mod:`rotorlab.steady._corrections`.

References
----------
Filimonikhin & Filimonikhina eqs. (5), (10)-(19); Zhakash et al. 2024 eqs. (9)-(11), (14)-(23).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rotorlab.models._machine_rotating import EXACT_RTOL, _drop_neutral, spectrum_verdict
from rotorlab.steady._motions import _moments, main_motions_exist, motion_state, steady_machine, wrap
from rotorlab.steady._records import Stability, SteadyMotion

if TYPE_CHECKING:
    from rotorlab.models import JeffcottBalls

__all__ = [
    "Stability",
    "assess_stability",
    "hessian_f",
    "averaged_jacobian",
    "EXACT_RTOL",
]

_HESSIAN_RTOL = 1e-9


def hessian_f(imbalance: float, moments, angles) -> np.ndarray:
    """Return the Hessian of ``f = |U|^2 / 2`` in the ball angles (seed 003 eq. (19), any n).

    Parameters
    ----------
    imbalance : float
        M1 e (kg m).
    moments : array_like, shape (n,)
        m_i l_i (kg m).
    angles : array_like, shape (n,)
        psi_i (rad).

    Returns
    -------
    ndarray, shape (n, n)
        ``a_ij`` (kg^2 m^2).

    Examples
    --------
    First side motion of seed 003 (2a): ``a11 = -m1 l1 (m2 l2 + Me)``, ``a12 = m1 l1 m2 l2``.

    >>> hessian_f(1.0, [2.0, 3.0], [0.0, 0.0]).tolist()
    [[-8.0, 6.0], [6.0, -9.0]]
    """
    s = np.asarray(moments, dtype=float).reshape(-1)
    psi = np.asarray(angles, dtype=float).reshape(-1)
    unb = float(imbalance) + np.sum(s * np.exp(1j * psi))
    a = np.outer(s, s) * np.cos(psi[None, :] - psi[:, None])
    np.fill_diagonal(a, s * s - s * np.real(unb * np.exp(-1j * psi)))
    return a


def averaged_jacobian(model: JeffcottBalls, spin_speed: float, angles) -> np.ndarray | None:
    """Return the Jacobian dP_s/dpsi_j of the averaged ball equations (seed 002 (11), (14)).

    Parameters
    ----------
    model : JeffcottBalls
    spin_speed : float
        Omega (rad/s).
    angles : array_like, shape (n,)
        psi_i (rad).

    Returns
    -------
    ndarray, shape (n, n) or None
        ``(Omega^4 / (c - M Omega^2)) diag(1 / b_s) a`` (1/s); None when a ball has no viscous
        damping or at Omega = sqrt(c / M).
    """
    return _averaged_from_hessian(model, spin_speed, hessian_f(model.imbalance, _moments(model), angles))


def _averaged_from_hessian(model: JeffcottBalls, spin_speed: float, a: np.ndarray) -> np.ndarray | None:
    b = np.array([x.damping for x in model.balls], dtype=float)
    den = model.rotor.stiffness - model.total_mass * spin_speed**2
    if np.any(b <= 0.0) or den == 0.0:
        return None
    return (spin_speed**4 / den) * a / b[:, None]


def _exact(machine, motion: SteadyMotion) -> tuple[str, np.ndarray, float, float]:
    """Exact verdict, eigenvalues of the first member, growth rate and stable fraction of a motion
    (the machine's co-rotating linearization, the family's neutral directions left out)."""
    n = motion.ball_angles.size
    if not motion.exists:
        return "absent", np.full(4 + 2 * n, complex(np.nan, np.nan)), math.nan, 0.0
    verdicts, growths, eig0 = [], [], None
    for psi in motion.samples:
        lam = machine.linearize(motion_state(machine, motion.deflection, psi)).eigenvalues
        eig0 = lam if eig0 is None else eig0
        verdict, growth = spectrum_verdict(lam, motion.dimension, scale=motion.spin_speed)
        verdicts.append(verdict)
        growths.append(growth)
    frac = verdicts.count("stable") / len(verdicts)
    if frac == 1.0:
        exact = "stable"
    elif frac > 0.0:
        exact = "partly stable"
    else:
        exact = "unstable" if "unstable" in verdicts else "marginal"
    return exact, eig0, max(growths), frac


def _hessian_type(eig: np.ndarray, neutral: int) -> str:
    scale = max(float(np.max(np.abs(eig))) if eig.size else 0.0, 1e-300)
    rest = _drop_neutral(eig, neutral)
    tol = _HESSIAN_RTOL * scale
    if rest.size == 0 or np.any(np.abs(rest) <= tol):
        return "degenerate"
    if np.all(rest > 0):
        return "minimum"
    if np.all(rest < 0):
        return "maximum"
    return "saddle"


def _seed_geometry(model: JeffcottBalls, motion: SteadyMotion, om: float):
    """Ball angles and g = H~* - H~*(main) of the motion with the same label at d = 0."""
    s = _moments(model)
    me = model.imbalance
    den = model.rotor.stiffness - model.total_mass * om * om
    if motion.kind == "main":
        return motion.samples, 0.0
    bits = np.asarray(motion.bits, dtype=float)
    total = me + float(np.sum(s * (-1.0) ** bits))
    g = -0.5 * om**4 * total**2 / den if den != 0.0 else -math.inf
    return wrap(np.pi * bits)[None, :], g


def _seed_h_values(model: JeffcottBalls, om: float) -> list[float]:
    """g = H~* - H~*(main) of all steady motions at d = 0 (eq. (15) minus eq. (14))."""
    import itertools

    s = _moments(model)
    me = model.imbalance
    den = model.rotor.stiffness - model.total_mass * om * om
    vals = [0.0] if main_motions_exist(me, s) else []
    for bits in itertools.product((0, 1), repeat=s.size):
        total = me + float(np.sum(s * (-1.0) ** np.asarray(bits, dtype=float)))
        vals.append(-0.5 * om**4 * total**2 / den if den != 0.0 else -math.inf)
    return vals


def assess_stability(model: JeffcottBalls, motion: SteadyMotion, spin_speed: float | None = None,
                     *, seed_h_values: list[float] | None = None, machine=None) -> Stability:  # fmt: skip
    """Assess the stability of one steady motion by the three methods.

    Parameters
    ----------
    model : JeffcottBalls
    motion : SteadyMotion
        From :func:`rotorlab.steady.find_steady_motions` (any existence).
    spin_speed : float, optional
        Omega (rad/s); default ``motion.spin_speed``.
    seed_h_values : list of float, optional
        H~* of all undamped steady motions minus that of a main motion (J), to reuse across the
        motions of one speed.
    machine : Machine, optional
        The machine ``model`` is at the speed (:func:`rotorlab.steady._motions.steady_machine`),
        to reuse across the motions of one speed.

    Returns
    -------
    Stability

    References
    ----------
    Filimonikhin & Filimonikhina eqs. (14)-(19); Zhakash et al. 2024 eqs. (11), (14), (19)-(20).
    """
    om = float(motion.spin_speed if spin_speed is None else spin_speed)
    n = model.n_balls
    s = _moments(model)
    neutral = motion.dimension
    crit = math.sqrt(model.rotor.stiffness / model.total_mass)
    seed_angles, g = _seed_geometry(model, motion, om)
    values = _seed_h_values(model, om) if seed_h_values is None else seed_h_values
    seed_exists = seed_angles.shape[0] > 0 and math.isfinite(g)
    nan_n = np.full(n, np.nan)
    if seed_exists:
        finite = [v for v in values if math.isfinite(v)] or [g]
        span = max(abs(v) for v in finite)
        minimal = bool(g <= min(finite) + 1e-10 * max(span, 1e-300))
        hess = hessian_f(model.imbalance, s, seed_angles[0])
        h_eig = np.linalg.eigvalsh(hess)
        kind = _hessian_type(h_eig, neutral)
        wanted = "minimum" if om > crit else "maximum"
        hamilton = "stable" if (minimal and kind == wanted and om != crit) else "unstable"
        jac = _averaged_from_hessian(model, om, hess)
    else:
        minimal, h_eig, kind, hamilton, jac = False, nan_n, "degenerate", "unstable", None
    if jac is None:
        averaged, a_eig, a_a, a_b = "undefined", nan_n, math.nan, math.nan
    else:
        a_eig = np.sort(np.real(np.linalg.eigvals(jac)))
        rest = _drop_neutral(a_eig, neutral)
        tol = _HESSIAN_RTOL * max(float(np.max(np.abs(a_eig))), 1e-300)
        averaged = "stable" if rest.size and np.all(rest < -tol) else "unstable"
        a_a = -float(np.trace(jac)) if n == 2 else math.nan
        a_b = float(np.linalg.det(jac)) if n == 2 else math.nan
    exact, eig0, growth, frac = _exact(steady_machine(model, om) if machine is None else machine, motion)
    return Stability(
        hamilton=hamilton, hamilton_minimal=minimal, hessian=kind, hessian_eigenvalues=h_eig,
        averaged=averaged, averaged_eigenvalues=a_eig, averaged_a=a_a, averaged_b=a_b,
        exact=exact, eigenvalues=eig0, growth_rate=growth, stable_fraction=frac,
    )  # fmt: skip
