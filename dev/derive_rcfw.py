"""Derive the two-plane ball balancer on a rigid rotor (Rodrigues et al. 2008) with sympy.

Run ``python dev/derive_rcfw.py [rigid|lateral]`` to print the fixed-frame equations of two races
with two balls each on a rotor with two supports. The same derivation backs ``tests/validation/test_rcfw_reference.py``
and ``tests/validation/test_machine_rcfw.py`` (which import :func:`derive`).

The model, from first principles (Rodrigues, Champneys, Friswell & Wilson, "Automatic two-plane
balancing for rigid rotors", Int. J. Non-Linear Mech. 43 (2008) 527-541, Sections 2.1-2.3):

- A rigid axisymmetric rotor of mass ``M`` and central inertias ``Jt, Jt, Jp`` (about its
  principal axes), its geometric centre C = (x, y, 0) and its tilt (phi_x, phi_y) in rotorlab's
  convention (``linear/_system.py``: phi_x turns about +y and equals dx/dz, phi_y turns about -x
  and equals dy/dz). Its orientation is ``E(v) Rz(theta)`` with the prescribed spin angle theta
  and the rotation vector ``v = (-phi_y, phi_x, 0)``, ``E(v) = exp([v]x)``. The centre of mass
  sits at the body point ``(eps, 0, 0)`` (static imbalance, phase 0).
- Supports: isotropic springs ``k_s`` and dampers ``c_s`` (fixed frame) at the body points
  ``(0, 0, z_s)``; their deflection is that of the body point.
- Balls: point masses ``m_i`` on a race of radius ``R_i`` at axial position ``z_i``, at the body
  angle ``alpha_i`` (absolute angle ``psi_i = theta + alpha_i``), with viscous damping on the
  relative rate, Rayleigh term ``1/2 b_i alpha_i'^2`` (the paper's nondimensional
  ``c_b = b / (m Omega_1 R^2)``).

``kinematics="rigid"`` places each ball at the rigid-body image of its body point (it moves
axially when the race tilts), as the paper's eqs. (9)-(13) do; ``kinematics="lateral"`` keeps
only the in-plane motion of the race centre, ``(x + z phi_x, y + z phi_y) + R e(psi)``, as the
authors' later model does (Rodrigues et al. 2011, IJNLM 46, eq. (2): mass matrix
``[[M + sum m, sum m z], [sum m z, Jt + sum m z^2]]``, ball forcing ``[m R, m R z]``).

As in the paper (Section 2.3.2), x, y, phi_x, phi_y and eps are small of order delta and the
Lagrangian is truncated after O(delta^2) (so the equations of motion are exact to O(delta) and
keep the ball angles exact); the truncated Lagrangian then defines the reference model exactly.
The rotation-vector parametrisation is frame covariant, so the same tilt coordinates read in the
co-rotating frame are the fixed ones turned by -theta (no Euler-angle asymmetry; it agrees with
the paper's Euler angles to first order, so linearisations about equilibria are identical).
"""

from __future__ import annotations

import sys

import sympy as sp


def _skew(v):
    return sp.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def _truncate(expr, d, order=2):
    """The terms of ``expr`` (a polynomial in ``d``) up to ``d**order``, with ``d = 1``."""
    poly = sp.Poly(sp.expand(expr), d)
    return sum(coef * d**k for (k,), coef in poly.terms() if k <= order).subs(d, 1)


def derive(n_balls: tuple[int, ...] = (2, 2), n_supports: int = 2, kinematics: str = "rigid"):
    """Return ``(M, f, coords, speeds, params)`` with ``M(q) q'' = f(q, q', theta, Omega, Omega')``.

    The coordinates are those of the fixed frame, ``(x, y, phi_x, phi_y, psi_i)``. The
    co-rotating frame (``u + i v = e^{-i theta} (x + i y)``, the same for the tilts,
    ``alpha_i = psi_i - theta``) follows by that change of variables, which
    ``tests/validation/_rcfw_reference.py`` applies numerically: deriving it symbolically gives
    the same equations but takes minutes.

    Parameters
    ----------
    n_balls : tuple of int
        Number of balls per race.
    n_supports : int
        Number of isotropic supports.
    kinematics : {"rigid", "lateral"}
        How a ball follows its tilting race (module docstring).

    Returns
    -------
    M : sympy.Matrix, shape (4 + n, 4 + n)
    f : sympy.Matrix, shape (4 + n, 1)
    coords, speeds : list of sympy.Symbol
    params : dict
        Symbols ``Mr, Jt, Jp, eps`` (rotor), lists ``k, c, zs`` (supports), lists ``m, R, z, b``
        (balls, one entry per ball), and ``th, Om, dOm`` (spin angle, speed, acceleration).
    """
    if kinematics not in ("rigid", "lateral"):
        raise ValueError(f"kinematics must be 'rigid' or 'lateral', got {kinematics!r}")
    n = sum(n_balls)
    t, d = sp.Symbol("t"), sp.Symbol("delta")
    Mr, Jt, Jp, eps = sp.symbols("Mr Jt Jp eps", positive=True)
    k = sp.symbols(f"k0:{n_supports}", positive=True)
    c = sp.symbols(f"c0:{n_supports}", nonnegative=True)
    zs = sp.symbols(f"zs0:{n_supports}", real=True)
    m = sp.symbols(f"m0:{n}", positive=True)
    R = sp.symbols(f"R0:{n}", positive=True)
    z = sp.symbols(f"z0:{n}", real=True)
    b = sp.symbols(f"b0:{n}", nonnegative=True)
    th = sp.Function("theta")(t)
    q = [sp.Function(s)(t) for s in ("x", "y", "px", "py")]
    q += [sp.Function(f"psi{i}")(t) for i in range(n)]
    co, si = sp.cos(th), sp.sin(th)
    x, y, px, py = (d * qk for qk in q[:4])
    psi = q[4:]
    rot = _skew([-py, px, 0])
    E = sp.eye(3) + rot + rot * rot / 2  # exp([v]x) to O(delta^2)
    Rz = sp.Matrix([[co, -si, 0], [si, co, 0], [0, 0, 1]])
    C = sp.Matrix([x, y, 0])

    def vel(r):
        return r.diff(t)

    # rotor: translation of the mass centre and rotation about it
    rG = C + E * Rz * sp.Matrix([d * eps, 0, 0])
    T = Mr / 2 * vel(rG).dot(vel(rG))
    Rb = E * Rz
    W = vel(Rb) * Rb.T
    w = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
    Jb = E * sp.diag(Jt, Jt, Jp) * E.T
    T += (w.T * Jb * w)[0, 0] / 2
    Vp = 0
    F = 0
    for s in range(n_supports):
        p = sp.Matrix([0, 0, zs[s]])
        ds = C + E * p - p
        Vp += k[s] / 2 * ds.dot(ds)
        F += c[s] / 2 * vel(ds).dot(vel(ds))
    for i in range(n):
        pb = sp.Matrix([R[i] * sp.cos(psi[i]), R[i] * sp.sin(psi[i]), z[i]])
        if kinematics == "rigid":
            rB = C + E * pb
        else:
            rB = sp.Matrix([x + z[i] * px + pb[0], y + z[i] * py + pb[1], z[i]])
        T += m[i] / 2 * vel(rB).dot(vel(rB))
        F += b[i] / 2 * (psi[i].diff(t) - th.diff(t)) ** 2
    L = _truncate(T - Vp, d)
    F = _truncate(F, d)
    eqs = [L.diff(qk.diff(t)).diff(t) - L.diff(qk) + F.diff(qk.diff(t)) for qk in q]
    Q = sp.symbols(f"q0:{n + 4}")
    Qd = sp.symbols(f"qd0:{n + 4}")
    Qdd = sp.symbols(f"qdd0:{n + 4}")
    sth, Om, dOm = sp.symbols("th Om dOm")
    subs = [(qk.diff(t, 2), Qdd[j]) for j, qk in enumerate(q)] + [(th.diff(t, 2), dOm)]
    subs += [(qk.diff(t), Qd[j]) for j, qk in enumerate(q)] + [(th.diff(t), Om)]
    subs += [(qk, Q[j]) for j, qk in enumerate(q)] + [(th, sth)]
    eqs = [sp.expand(eq.subs(subs)) for eq in eqs]
    Mm, rhs = sp.linear_eq_to_matrix(eqs, list(Qdd))
    params = dict(Mr=Mr, Jt=Jt, Jp=Jp, eps=eps, k=list(k), c=list(c), zs=list(zs), m=list(m),
                  R=list(R), z=list(z), b=list(b), th=sth, Om=Om, dOm=dOm)
    return Mm, rhs, list(Q), list(Qd), params


def main(argv: list[str]) -> None:
    kin = argv[1] if len(argv) > 1 else "rigid"
    Mm, f, _, _, _ = derive((2, 2), 2, kin)
    print(f"--- fixed frame, {kin} kinematics: M(q) q'' = f")
    sp.pprint(sp.simplify(Mm))
    sp.pprint(sp.simplify(f))


if __name__ == "__main__":
    main(sys.argv)
