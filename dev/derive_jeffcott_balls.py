"""Derive the ``jeffcott_balls`` equations of motion from the Lagrangian with sympy.

Run ``python dev/derive_jeffcott_balls.py [n]`` to print the mass matrix and forcing of the
fixed-frame and co-rotating-frame equations for n balls (default 2). The same derivation backs
``tests/validation/test_jeffcott_lagrange.py`` (which imports :func:`derive`).

Each ball is a rigid body with mass centre P_i = O1 + l_i (cos phi_i, sin phi_i), central inertia
J_i - m_i l_i^2 and angular velocity phi_i' (Koenig's theorem); the disc's mass centre is
O1 + e (cos theta, sin theta). Non-conservative forces come from the Rayleigh function
Phi = 1/2 d |v_O1|^2 + 1/2 sum b_i (phi_i' - theta')^2 (Zhakash et al. 2024 eqs. (1)-(3);
Filimonikhin & Filimonikhina eqs. (4), (7)).
"""

from __future__ import annotations

import sys

import sympy as sp


def derive(n: int, frame: str):
    """Return ``(M, f, coords, speeds, params)``: ``M(q) q'' = f(q, q', theta, Omega, Omega')``.

    Parameters
    ----------
    n : int
        Number of balls.
    frame : {"fixed", "rotating"}
        Generalized coordinates (x, y, phi_i) or (u, v, psi_i).

    Returns
    -------
    M : sympy.Matrix, shape (2 + n, 2 + n)
    f : sympy.Matrix, shape (2 + n, 1)
    coords, speeds : list of sympy.Symbol
        Symbols standing for q and q'.
    params : dict
        Symbols: ``M1, e, c, d, m, l, J, b`` (the last four lists) and ``th, Om, dOm``.
    """
    t = sp.Symbol("t")
    M1, e, c, d = sp.symbols("M1 e c d", positive=True)
    m = sp.symbols(f"m0:{n}", positive=True)
    l = sp.symbols(f"l0:{n}", positive=True)
    J = sp.symbols(f"J0:{n}", positive=True)
    b = sp.symbols(f"b0:{n}", nonnegative=True)
    th = sp.Function("theta")(t)
    if frame == "fixed":
        q = [sp.Function("x")(t), sp.Function("y")(t)] + [sp.Function(f"phi{i}")(t) for i in range(n)]
        x, y = q[0], q[1]
        phi = q[2:]
    else:
        q = [sp.Function("u")(t), sp.Function("v")(t)] + [sp.Function(f"psi{i}")(t) for i in range(n)]
        x = q[0] * sp.cos(th) - q[1] * sp.sin(th)
        y = q[0] * sp.sin(th) + q[1] * sp.cos(th)
        phi = [th + psi for psi in q[2:]]
    xd, yd = x.diff(t), y.diff(t)
    cx, cy = x + e * sp.cos(th), y + e * sp.sin(th)
    T = sp.Rational(1, 2) * M1 * (cx.diff(t) ** 2 + cy.diff(t) ** 2)
    for i in range(n):
        px, py = x + l[i] * sp.cos(phi[i]), y + l[i] * sp.sin(phi[i])
        T += sp.Rational(1, 2) * m[i] * (px.diff(t) ** 2 + py.diff(t) ** 2)
        T += sp.Rational(1, 2) * (J[i] - m[i] * l[i] ** 2) * phi[i].diff(t) ** 2
    V = sp.Rational(1, 2) * c * (x**2 + y**2)
    Phi = sp.Rational(1, 2) * d * (xd**2 + yd**2)
    Phi += sum(sp.Rational(1, 2) * b[i] * (phi[i].diff(t) - th.diff(t)) ** 2 for i in range(n))
    L = T - V
    eqs = [
        L.diff(qk.diff(t)).diff(t) - L.diff(qk) + Phi.diff(qk.diff(t))
        for qk in q
    ]
    Q = sp.symbols(f"q0:{n + 2}")
    Qd = sp.symbols(f"qd0:{n + 2}")
    Qdd = sp.symbols(f"qdd0:{n + 2}")
    sth, Om, dOm = sp.symbols("th Om dOm")
    subs = [(qk.diff(t, 2), Qdd[k]) for k, qk in enumerate(q)]
    subs += [(th.diff(t, 2), dOm)]
    subs += [(qk.diff(t), Qd[k]) for k, qk in enumerate(q)] + [(th.diff(t), Om)]
    subs += [(qk, Q[k]) for k, qk in enumerate(q)] + [(th, sth)]
    eqs = [sp.expand(eq.subs(subs)) for eq in eqs]
    Mm, rhs = sp.linear_eq_to_matrix(eqs, list(Qdd))
    params = dict(M1=M1, e=e, c=c, d=d, m=list(m), l=list(l), J=list(J), b=list(b), th=sth, Om=Om, dOm=dOm)
    return Mm, rhs, list(Q), list(Qd), params


def main(argv: list[str]) -> None:
    n = int(argv[1]) if len(argv) > 1 else 2
    for frame in ("fixed", "rotating"):
        Mm, f, _, _, _ = derive(n, frame)
        print(f"--- {frame} frame, n = {n}: M(q) q'' = f")
        sp.pprint(sp.simplify(Mm))
        sp.pprint(sp.simplify(f))


if __name__ == "__main__":
    main(sys.argv)
