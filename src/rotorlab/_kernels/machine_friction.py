"""The balls' stick/slip (Coulomb and rolling friction), generated into a machine's kernel
(``friction`` layouts): the Schur system with each ball's mode, the races' torques on the balls
and their friction bounds, and the ``terms``, ``events`` and ``reset`` functions of the
kernel module. :mod:`rotorlab._kernels.machine_codegen` calls them."""

from __future__ import annotations

from rotorlab._kernels.machine_emit import _DECO, _less_reactions, _sum
from rotorlab._kernels.machine_layout import Layout

__all__ = ["friction_solve", "friction_torques", "friction_functions"]


def friction_solve(lay: Layout, L: list[str], unknowns, t_vec) -> None:
    """Append the Schur system with the balls' stick/slip modes and its solution ``x``.

    Ball b with friction arm ``kap_b`` (``coulomb l + rolling``, m) and mode ``md_b`` (the state
    after the layout's clearance: -1 / +1 slipping with that sign of ``phi_b' - Omega``, 0 stuck;
    always free when ``kap_b == 0``), exactly the law of :mod:`rotorlab._kernels.jeffcott_balls`:

    - slipping: the race's torque ``-md_b kap_b N_b`` on the ball, with the normal force
      ``N_b = m_b (l w_b^2 + e_b . (g - a_r))`` (``e_b = (cos phi_b, sin phi_b)``, ``a_r`` the
      absolute acceleration of its station, linear in the unknowns: ``a_r = a0_r - sum_j E``),
      which adds ``md kap m e_b . L_(r, s_j) t_j m l_j`` to row b (S is no longer symmetric) and
      its reaction to the motor's row;
    - stuck (``md_b == 0``, or ``forced == b`` in the trial solves of the events; ``kst_b``, set
      where the prefix reads the state, which also takes ``phi_b' = Omega``): the row becomes
      ``x_b = Omega'`` (prescribed spin) or ``x_b - theta'' = 0`` (motor, whose row then takes the
      ball's row: the holding torque is internal).

    The system is solved by Gaussian elimination without pivoting (its diagonal is that of a
    Schur complement of the mass matrix, or 1 on a stuck row), straight-line code as the LDL^T.
    """
    nb, br, o = lay.n_balls, lay.ball_race, lay.offsets
    n_s = len(unknowns)
    a = L.append
    th = nb if lay.motor else -1

    def S(i, j):
        return f"S{max(i, j)}_{min(i, j)}"

    def E(b, j):  # ml_j e_b . L_(r_b, s_j) t_j (or the unbalances' sum for theta)
        kind, idx = unknowns[j]
        if kind == "b":
            pairs = [(f"ml{idx}", lay.pair_L(br[b], br[idx]), t_vec(idx))]
            if lay.tilt:
                pairs.append(("1.0", lay.pair_L(br[b], lay.tilt_station(br[idx])),
                              (f"nx{idx}", f"ny{idx}")))
        elif kind == "m":
            pairs = [("1.0", lay.pair_L(br[b], lay.tilt_station(br[idx])), (f"c{idx}", f"s{idx}"))]
        else:
            pairs = [(ld.coef, lay.pair_L(br[b], ld.station), (ld.tx, ld.ty)) for ld in lay.spin_loads]
        terms = [f"{w} * (c{b} * (p[{k}] * {t[0]} + p[{k + 1}] * {t[1]}) + "
                 f"s{b} * (p[{k + 2}] * {t[0]} + p[{k + 3}] * {t[1]}))" for w, k, t in pairs]
        return f"({_sum(terms)})"

    for b in range(nb):
        r = br[b]
        a(f"    kap{b} = p[{o['friction'] + b}]")
        a(f"    kmd{b} = y[{lay.i_modes + b}]")
        a(f"    ksg{b} = (1.0 - kst{b}) * kmd{b} * kap{b}")
        a(f"    kms{b} = ksg{b} * p[{o['balls'] + 4 * b}]")
        a(f"    kN0{b} = ml{b} * w{b} * w{b} + p[{o['balls'] + 4 * b}] * "
          f"(c{b} * (gx - ax{r}) + s{b} * (gy - ay{r}))")
    # rows of the balls: slip adds the friction, stuck replaces the row
    for b in range(nb):
        for j in range(n_s):
            delta = "1.0" if j == b else ("-1.0" if j == th else "0.0")
            a(f"    A{b}_{j} = (1.0 - kst{b}) * ({S(b, j)} + kms{b} * {E(b, j)}) + kst{b} * {delta}")
        stuck_rhs = "0.0" if lay.motor else "dom"
        a(f"    r{b} = (1.0 - kst{b}) * (q{b} - ksg{b} * kN0{b}) + kst{b} * {stuck_rhs}")
    if lay.motor:
        for j in range(n_s):
            terms = [S(th, j)]
            for b in range(nb):
                terms.append(f"kst{b} * {S(b, j)} - kms{b} * {E(b, j)}")
            a(f"    A{th}_{j} = " + " + ".join(terms))
        a(f"    r{th} = q{th}" + "".join(f" + kst{b} * q{b} + ksg{b} * kN0{b}" for b in range(nb)))
    for i in range(nb + (1 if lay.motor else 0), n_s):  # the axial unknowns of the balls
        for j in range(n_s):
            a(f"    A{i}_{j} = {S(i, j)}")
        a(f"    r{i} = q{i}")
    for k in range(n_s):
        for i in range(k + 1, n_s):
            a(f"    fe = A{i}_{k} / A{k}_{k}")
            for j in range(k + 1, n_s):
                a(f"    A{i}_{j} -= fe * A{k}_{j}")
            a(f"    r{i} -= fe * r{k}")
    for i in reversed(range(n_s)):
        a(f"    x{i} = (r{i}" + "".join(f" - A{i}_{j} * x{j}" for j in range(i + 1, n_s)) + f") / A{i}_{i}")


def friction_torques(lay: Layout, L: list[str], corr, zdd: str = "out") -> None:
    """Append ``tq{b}`` (the race's torque on ball b: friction, or the holding torque of a stuck
    ball) and ``bd{b}`` (the friction bound ``kap_b N_b``, with ``w_b = Omega`` when stuck) from
    the solution (the residual of the ball's equation, exact in every mode)."""
    nz, br, o = lay.n_z, lay.ball_race, lay.offsets
    a = L.append
    for r in list(range(lay.n_races)) + lay.tilt_stations:
        # station acceleration a_r = a0_r - sum_s L_(r, s) g_s
        for row, nm in ((0, "fax"), (1, "fay")):
            a(f"    {nm}{r} = " + " ".join([f"a{'xy'[row]}{r}", *_less_reactions(lay, r, row, corr)]))
    for b in range(lay.n_balls):
        r = br[b]
        m = f"p[{o['balls'] + 4 * b}]"
        tilt = ""
        if lay.tilt:  # + n_b . T_r z'' - D e.phi' t.phi' (rigid kinematics)
            tilt = f" + nx{b} * fax{lay.tilt_station(r)} + ny{b} * fay{lay.tilt_station(r)} - D{b} * ep{b} * tp{b}"
        a(f"    tq{b} = J{b} * x{b} + cb{b} * rel{b} - ml{b} * (-s{b} * (gx - fax{r}) + c{b} * (gy - fay{r}))" + tilt)
        a(f"    wn{b} = kst{b} * om + (1.0 - kst{b}) * w{b}")
        a(f"    bd{b} = kap{b} * (ml{b} * wn{b} * wn{b} + {m} * (c{b} * (gx - fax{r}) + s{b} * (gy - fay{r})))")


def friction_functions(lay: Layout, prefix) -> str:
    """Source of ``terms``, ``events`` and ``reset`` of the balls' stick/slip (friction layouts;
    ``prefix``: :func:`rotorlab._kernels.machine_codegen.prefix`, the lines ``terms`` starts with)."""
    nb, im, n = lay.n_balls, lay.i_modes, lay.n_state
    L: list[str] = []
    corr = prefix(lay, L)
    friction_torques(lay, L, corr)
    for b in range(nb):
        L.append(f"    buf[{2 * b}] = tq{b}")
        L.append(f"    buf[{2 * b + 1}] = bd{b}")
    src = (_DECO + "def terms(t, y, p, forced, buf):  # pragma: no cover - compiled\n"
           '    """buf[2 b], buf[2 b + 1]: the race\'s torque on ball b and its friction bound."""\n'
           + "\n".join(L) + "\n")
    ev = [f"    terms(t, y, p, -1, g)"]
    for b in range(nb):
        ev += [f"    md = y[{im + b}]",
               f"    if p[{lay.offsets['friction'] + b}] <= 0.0:",
               f"        g[{2 * b}] = 1.0", f"        g[{2 * b + 1}] = 1.0",
               "    elif md != 0.0:",
               f"        g[{2 * b}] = (y[{lay.i_w + b}] - om) * md", f"        g[{2 * b + 1}] = 1.0",
               "    else:",
               f"        g[{2 * b + 1}] = g[{2 * b + 1}] - abs(g[{2 * b}])", f"        g[{2 * b}] = 1.0"]
    spin = (f"    om = y[{lay.i_theta + 1}]" if lay.motor else
            f"    om = spin_speed(t, p)")
    src += (_DECO + "def events(t, y, p, g):  # pragma: no cover - compiled\n"
            '    """Events per ball b: 2 b stick, 2 b + 1 slip (direction -1), as jeffcott_balls."""\n'
            + spin + "\n" + "\n".join(ev) + "\n")
    src += (_DECO + f'''def reset(k, t, y, p, y_new):  # pragma: no cover - compiled
    """Stick or slip of ball k // 2 (trial solve with the ball stuck), relative speed set to 0."""
    b = k // 2
    terms(t, y, p, b, y_new)
    tq = y_new[2 * b]
    bd = y_new[2 * b + 1]
    for i in range({n}):
        y_new[i] = y[i]
    if k % 2 == 0 and abs(tq) <= bd:
        md = 0.0
    elif tq <= 0.0:
        md = 1.0
    else:
        md = -1.0
    y_new[{im} + b] = md
{spin.replace("    om", "    y_new[" + str(lay.i_w) + " + b]")}
    return 0
''')
    src += (_DECO + f'''def spin_speed(t, p):  # pragma: no cover - compiled
    theta, om, dom = profile(t, p, {lay.offsets['speed']})
    return om
''')
    return src
