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
3. **Exact**: eigenvalues of :meth:`rotorlab.models.JeffcottBalls.linearize` (shaft and ball
   damping, ball inertia, support damping) at the exact steady motion. Along a family of main
   motions the n - 2 zero eigenvalues of the neutral directions are left out.

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
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from rotorlab.steady._motions import SteadyMotion, main_motions_exist, wrap

if TYPE_CHECKING:
    from rotorlab.models import JeffcottBalls

__all__ = [
    "Stability",
    "assess_stability",
    "hessian_f",
    "averaged_jacobian",
    "exact_eigenvalues",
    "EXACT_RTOL",
]

#: Real parts within this fraction of the spectral radius count as zero ("marginal").
EXACT_RTOL = 1e-10
_HESSIAN_RTOL = 1e-9


@dataclass(frozen=True)
class Stability:
    """Stability of one steady motion by the three methods.

    Attributes
    ----------
    hamilton : {"stable", "unstable"}
        Seed 003's verdict: H~* least among the (undamped) steady motions and f of eq. (18) a
        minimum above / maximum below omega_cr = sqrt(c / M).
    hamilton_minimal : bool
        H~* is least among the steady motions at d = 0 (eqs. (14), (15)).
    hessian : {"minimum", "maximum", "saddle", "degenerate"}
        Type of the critical point of f (eq. (19)); a family's n - 2 neutral directions are left
        out.
    hessian_eigenvalues : ndarray, shape (n,)
        Eigenvalues of the matrix a of eq. (19) (kg^2 m^2).
    averaged : {"stable", "unstable", "undefined"}
        Seed 002's verdict from the averaged equations (undefined when a ball has no damping).
    averaged_eigenvalues : ndarray, shape (n,)
        Eigenvalues of dP_s / dpsi_j (1/s), real.
    averaged_a, averaged_b : float
        A and B of eq. (19) (corrected), for n = 2 (1/s, 1/s^2); NaN otherwise.
    exact : {"stable", "unstable", "marginal", "partly stable", "absent"}
        From the eigenvalues of the full linearization; "partly stable" for a family whose
        members differ; "absent" when the motion does not exist with the support damping.
    eigenvalues : ndarray, shape (4 + 2 n,)
        Eigenvalues of the representative member (1/s, complex); NaN when absent.
    growth_rate : float
        Largest real part of the eigenvalues, neutral family directions left out, over all
        members (1/s); NaN when absent.
    stable_fraction : float
        Fraction of the family's members that are exactly stable (1 or 0 for isolated motions).
    """

    hamilton: str
    hamilton_minimal: bool
    hessian: str
    hessian_eigenvalues: np.ndarray
    averaged: str
    averaged_eigenvalues: np.ndarray
    averaged_a: float
    averaged_b: float
    exact: str
    eigenvalues: np.ndarray
    growth_rate: float
    stable_fraction: float

    def is_stable(self, method: str) -> bool:
        """Return the verdict of ``method`` ("hamilton", "averaged" or "exact") as a bool."""
        if method not in ("hamilton", "averaged", "exact"):
            raise ValueError(f"method must be 'hamilton', 'averaged' or 'exact', got {method!r}")
        return getattr(self, method) == "stable"


def _moments(model: JeffcottBalls) -> np.ndarray:
    return np.array([b.static_moment for b in model.balls], dtype=float)


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


def exact_eigenvalues(model: JeffcottBalls, spin_speed: float, state) -> np.ndarray:
    """Return the eigenvalues of the co-rotating-frame Jacobian at a steady state (1/s).

    Coulomb friction, if any, is switched off (the balls free, viscous damping kept).
    """
    if model.has_friction:
        model = replace(model, balls=tuple(replace(b, friction=0.0) for b in model.balls))
    return model.linearize(np.asarray(state, dtype=float), spin_speed=spin_speed).eigenvalues


def _drop_neutral(values: np.ndarray, count: int) -> np.ndarray:
    if count <= 0:
        return values
    order = np.argsort(np.abs(values))
    return values[np.sort(order[count:])]


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
                     *, seed_h_values: list[float] | None = None) -> Stability:  # fmt: skip
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
    if not motion.exists:
        exact, eig0, growth, frac = "absent", np.full(4 + 2 * n, complex(np.nan, np.nan)), math.nan, 0.0
    else:
        verdicts, growths, eig0 = [], [], None
        for y in motion.states():
            eig = exact_eigenvalues(model, om, y)
            eig0 = eig if eig0 is None else eig0
            rest = _drop_neutral(eig, neutral)
            gr = float(np.max(rest.real))
            tol = EXACT_RTOL * max(float(np.max(np.abs(eig))), om)
            growths.append(gr)
            verdicts.append("stable" if gr < -tol else ("unstable" if gr > tol else "marginal"))
        growth = max(growths)
        frac = verdicts.count("stable") / len(verdicts)
        if frac == 1.0:
            exact = "stable"
        elif frac > 0.0:
            exact = "partly stable"
        else:
            exact = "unstable" if "unstable" in verdicts else "marginal"
    return Stability(
        hamilton=hamilton, hamilton_minimal=minimal, hessian=kind, hessian_eigenvalues=h_eig,
        averaged=averaged, averaged_eigenvalues=a_eig, averaged_a=a_a, averaged_b=a_b,
        exact=exact, eigenvalues=eig0, growth_rate=growth, stable_fraction=frac,
    )  # fmt: skip
