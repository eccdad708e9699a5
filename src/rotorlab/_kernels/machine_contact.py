r"""Generated clearance (rotor-stator contact) of the composed machine: the code that
:mod:`rotorlab._kernels.machine_codegen` adds to a machine's kernel module when it has a
:class:`rotorlab.models.Clearance`.

The contact law is the shared one of :mod:`rotorlab._kernels.contact`, written for a general
structure through the contact point's *Delassus matrix*. The contact force ``-N n + F_t t`` acts
on the generalised coordinates as ``G^T (-N, F_t)`` where ``G`` maps the generalised velocities
to the contact point's normal speed and slip, ``[v_n, s] = G q' + (0, R_r Omega)``: on the
structure through the station matrix ``B`` of the clearance (``v_n = n . B z'``, slip ``t . B z'``),
on a motor's spin through the surface radius (``s`` contains ``R_r Omega``, the friction torque is
``R_r F_t``), and on a moving housing with the opposite sign. ``W = G M^-1 G^T`` (2 x 2, in the
``(n, t)`` basis) is evaluated at every call from two solves of the machine's mass-matrix system
(the LDL^T factors of the ball/spin Schur complement are shared with the free solve), so the
balls' and the motor's inertia enter impacts and sustained contact exactly.

Generated functions (besides ``rhs``)
-------------------------------------
``contact_terms(t, y, p, mode)``
    ``(N, F_t, n_x, n_y, s, v_n, gap, b_n, w_nn, w_nt, w_tt, surface_speed)`` with the contact in
    ``mode`` (0: only the geometry).
``apply_impulse(t, y, p, P_n, P_t, n_x, n_y)``
    Adds the velocity jump ``M^-1 G^T (-P_n, P_t)`` to ``y``.
``events(t, y, p, g)``, ``reset(k, t, y, p, y_new)``
    As :mod:`rotorlab._kernels.jeffcott_rub`: events ``0 contact``, ``1 lift_off``, ``2 stick``,
    ``3 slip`` (all direction -1), the same reset maps (restitution and Coulomb impulse, chatter
    as one plastic impulse below the rest speed when the rotor is pressed, then sustained
    contact; rolling while the cone holds).

A rigid and a massless elastic stator share one kernel (layout kind ``"massless"``): the stator's
stiffness ``k_s`` (0 for a rigid one) picks the law at run time; a moving housing has its own.

Clearance parameters (11, at ``offsets["clearance"]``): ``delta, e, mu, R_r, v_rest, k_s, c_s,
m_s, c_x, c_y, a`` (:meth:`rotorlab.models.Clearance.to_array`, then the stator's centre: the gap
vector is ``w = B z - (x_h, y_h) - c``, then the rate ``a`` (1/s) of the Baumgarte stabilisation
of a rigid sustained contact, ``r'' + 2 a r' + a^2 (r - delta) = 0`` instead of ``r'' = 0``). Clearance states (from
``Layout.i_clearance``): a moving housing's ``x_h, y_h, vx_h, vy_h``; ``dissipated`` (restitution,
friction, stator damping, J) and ``drive_work`` (the work of a prescribed spin against the friction
torque, J); then the three discrete states ``impacts`` (impacts, or contact onsets with a
massless elastic stator), ``peak_impulse`` (N s) and ``mode`` (0 free, +-1 sliding with the sign of
the slip, 2 rolling) at the end of the state.
"""

from __future__ import annotations

from rotorlab._kernels.machine_emit import _DECO, _less_reactions, _sum, reactions, solve_lines, unit_rhs

__all__ = ["IMPORTS", "rhs_contact_lines", "rhs_tail_lines", "extra_functions"]

_DECO_INLINE = _DECO.replace("error_model=", 'inline="always", error_model=')

IMPORTS = ("from rotorlab._kernels.contact import (circular_gap, contact_velocities, delassus_forces,\n"
           "    impulse_energy, newton_coulomb_impulse, penalty_normal_force)\n")


def _station(lay) -> int:
    return lay.n_stations - 1


def _unit(lay, L: list[str], ind: str, tag: str, fx: str, fy: str, tq: str, full: bool) -> None:
    """Lines of the response to the contact-point force (fx, fy) and spin torque tq.

    Defines ``{tag}acx, {tag}acy`` (contact point's acceleration), ``{tag}dom`` (spin's) and
    with ``full`` ``{tag}z{i}`` (structure) and ``{tag}x{b}`` (balls, spin).
    """
    nz, nb, br, nr, nu = lay.n_z, lay.n_balls, lay.ball_race, lay.n_races, lay.n_unbalance
    sc = _station(lay)
    a = lambda s: L.append(ind + s)  # noqa: E731
    a(f"{tag}fx = {fx}")
    a(f"{tag}fy = {fy}")
    unit_rhs(lay, L, tag, sc, tq, ind)
    solve_lines(lay, L, f"{tag}x", f"{tag}q", ind)
    corr = reactions(lay, L, f"{tag}g", f"{tag}x", ind)
    kc = lay.pair_L(sc, sc)
    for row, name in ((0, "acx"), (1, "acy")):
        terms = [f"p[{kc + 2 * row}] * {tag}fx + p[{kc + 2 * row + 1}] * {tag}fy"]
        a(f"{tag}{name} = " + " ".join(terms + _less_reactions(lay, sc, row, corr)))
    a(f"{tag}dom = {tag}x{nb}" if lay.motor else f"{tag}dom = 0.0")
    if full:
        for i in range(nz):
            k = lay.station_HBT(sc) + 2 * i
            terms = [f"p[{k}] * {tag}fx + p[{k + 1}] * {tag}fy"]
            for s, gx, gy in corr:
                k2 = lay.station_HBT(s) + 2 * i
                terms.append(f"-(p[{k2}] * {gx} + p[{k2 + 1}] * {gy})")
            a(f"{tag}z{i} = " + " ".join(terms))


def _geometry(lay, L: list[str], ind: str) -> None:
    """Lines of the gap vector, its normal, the normal speed and the slip."""
    nz, kc = lay.n_z, lay.offsets["clearance"]
    kb = lay.station_B(_station(lay))
    house = lay.clearance == "housing"
    ih = lay.i_clearance
    a = lambda s: L.append(ind + s)  # noqa: E731
    a(f"dl = p[{kc}]")
    a(f"mu = p[{kc + 2}]")
    a(f"Rr = p[{kc + 3}]")
    for name, row, src, h in (("wx", 0, "z", 0), ("wy", 1, "z", 1),
                              ("uvx", 0, "v", 2), ("uvy", 1, "v", 3)):
        expr = _sum([f"p[{kb + row * nz + j}] * {src}{j}" for j in range(nz)])
        centre = f" - p[{kc + 8 + row}]" if src == "z" else ""
        a(f"{name} = {expr}" + (f" - y[{ih + h}]" if house else "") + centre)
    a("gap, nx, ny = circular_gap(wx, wy, dl)")
    a("rad = dl - gap")
    a("ss = Rr * om")
    a("vn, sl = contact_velocities(nx, ny, uvx, uvy, ss)")
    a("vt = sl - ss")


def _core(lay, corr, L: list[str], ind: str, md: str, full: bool) -> None:
    """Geometry, then in contact (``md != 0``) the free accelerations, W and the forces cN, cF."""
    nz, nb = lay.n_z, lay.n_balls
    kc = lay.offsets["clearance"]
    sc = _station(lay)
    kb = lay.station_B(sc)
    house = lay.clearance == "housing"
    ih = lay.i_clearance
    a = lambda s: L.append(ind + s)  # noqa: E731
    _geometry(lay, L, ind)
    if house:
        a(f"ms = p[{kc + 7}]")
        a(f"ahx = (-p[{kc + 5}] * y[{ih}] - p[{kc + 6}] * y[{ih + 2}]) / ms + gx")
        a(f"ahy = (-p[{kc + 5}] * y[{ih + 1}] - p[{kc + 6}] * y[{ih + 3}]) / ms + gy")
    for v in ("cN", "cF", "bn"):
        a(f"{v} = 0.0")
    a("wnn = 1.0")
    a("wnt = 0.0")
    a("wtt = 1.0")
    if full:
        for i in range(nz):
            a(f"cz{i} = 0.0")
        for b in range(nb + (1 if lay.motor else 0)):
            a(f"cx{b} = 0.0")
    a(f"if {md} != 0.0:")
    i2 = ind + "    "
    b2 = lambda s: L.append(i2 + s)  # noqa: E731
    for row, name in ((0, "a0x"), (1, "a0y")):
        terms = [_sum([f"p[{kb + row * nz + j}] * h{j}" for j in range(nz)])]
        for s, gx, gy in corr:
            k = lay.pair_L(sc, s) + 2 * row
            terms.append(f"-(p[{k}] * {gx} + p[{k + 1}] * {gy})")
        if house:
            terms.append("-ahx" if row == 0 else "-ahy")
        b2(f"{name} = " + " ".join(terms))
    dom0 = f"x{nb}" if lay.motor else "dom"
    b2("bn = a0x * nx + a0y * ny + vt * vt / rad")
    b2(f"bs = -a0x * ny + a0y * nx - vt * vn / rad + Rr * {dom0}")
    _unit(lay, L, i2, "rn_", "nx", "ny", "0.0", full)
    _unit(lay, L, i2, "rt_", "-ny", "nx", "Rr", full)
    inv = " + 1.0 / ms" if house else ""
    b2(f"wnn = rn_acx * nx + rn_acy * ny{inv}")
    b2("wnt = -rn_acx * ny + rn_acy * nx + Rr * rn_dom")
    b2(f"wtt = -rt_acx * ny + rt_acy * nx + Rr * rt_dom{inv}")
    # a massless stator is rigid or elastic at run time: elastic where its stiffness k_s > 0
    el = "elastic" if lay.clearance == "massless" else "False"
    if lay.clearance == "massless":
        b2(f"elastic = p[{kc + 5}] > 0.0")
        b2(f"npen = penalty_normal_force(-gap, vn, p[{kc + 5}], p[{kc + 6}]) if elastic else 0.0")
    else:
        b2("npen = 0.0")
    # Baumgarte stabilisation of the rigid contact: the constraint r'' = 0 becomes
    # r'' + 2 a r' + a^2 (r - delta) = 0, which brings the integration's drift back (a: the
    # structure's highest natural frequency, so that it adds no stiffer time scale)
    b2(f"bnc = bn if {el} else bn + 2.0 * p[{kc + 10}] * vn - p[{kc + 10}] * p[{kc + 10}] * gap")
    b2(f"cN, cF = delassus_forces(bnc, bs, wnn, wnt, wtt, mu, {md}, not {el}, npen)")
    if full:
        for i in range(nz):
            b2(f"cz{i} = -cN * rn_z{i} + cF * rt_z{i}")
        for b in range(nb + (1 if lay.motor else 0)):
            b2(f"cx{b} = -cN * rn_x{b} + cF * rt_x{b}")


def rhs_contact_lines(lay, corr) -> list[str]:
    """Lines of ``rhs`` after the free solve: the contact's accelerations and powers."""
    L: list[str] = []
    kc = lay.offsets["clearance"]
    ih = lay.i_clearance
    L.append("    # ---- clearance (rotorlab._kernels.machine_contact)")
    L.append(f"    md = y[{lay.n_state - 1}]")
    _core(lay, corr, L, "    ", "md", True)
    diss = ["-cF * sl"]
    if lay.clearance == "massless":  # c_s = 0 for a rigid stator
        L.append(f"    cdamp = p[{kc + 6}] * vn * vn if cN > 0.0 else 0.0")
        diss.append("cdamp")
    if lay.clearance == "housing":
        L.append(f"    ahx += (cN * nx + cF * ny) / ms")
        L.append(f"    ahy += (cN * ny - cF * nx) / ms")
        diss.append(f"p[{kc + 6}] * (y[{ih + 2}] * y[{ih + 2}] + y[{ih + 3}] * y[{ih + 3}])")
    L.append(f"    cdiss = {' + '.join(diss)}")
    L.append("    cdrive = 0.0" if lay.motor else "    cdrive = -cF * ss")
    return L


def rhs_tail_lines(lay) -> list[str]:
    """Lines writing the clearance states' derivatives."""
    ih = lay.i_clearance
    L = []
    k = ih
    if lay.clearance == "housing":
        L += [f"    out[{ih}] = y[{ih + 2}]", f"    out[{ih + 1}] = y[{ih + 3}]",
              f"    out[{ih + 2}] = ahx", f"    out[{ih + 3}] = ahy"]
        k += 4
    L += [f"    out[{k}] = cdiss", f"    out[{k + 1}] = cdrive"]
    L += [f"    out[{k + 2 + j}] = 0.0" for j in range(3)]
    return L


def extra_functions(lay, corr, prefix) -> str:
    """Source of ``contact_terms``, ``apply_impulse``, ``project``, ``enter_mode``, ``events``, ``reset``
    (``prefix``: :func:`rotorlab._kernels.machine_codegen.prefix`, the lines every function starts with)."""
    nz, nb = lay.n_z, lay.n_balls
    kc = lay.offsets["clearance"]
    sc = _station(lay)
    ih = lay.i_clearance
    house = lay.clearance == "housing"
    massless = lay.clearance == "massless"
    i_diss = ih + (4 if house else 0)
    i_drive, i_imp, i_pmax, i_mode = i_diss + 1, i_diss + 2, i_diss + 3, i_diss + 4
    n = lay.n_state
    out = []

    # contact_terms
    L: list[str] = []
    c = prefix(lay, L)
    _core(lay, c, L, "    ", "md", False)
    L.append("    return cN, cF, nx, ny, sl, vn, gap, bn, wnn, wnt, wtt, ss")
    # inlined (numba IR) into its callers: the lane driver's loop over the lanes' events then
    # vectorises as the rhs does (a call is opaque to LLVM, and costs the arrays' reference counts)
    out.append(_DECO_INLINE + "def contact_terms(t, y, p, md):  # pragma: no cover - compiled\n"
               '    """Contact force, geometry and Delassus matrix in mode md (see the module docstring)."""\n'
               + "\n".join(L) + "\n")

    # apply_impulse
    L = []
    prefix(lay, L, solve=False)
    L.append(f"    Rr = p[{kc + 3}]")
    _unit(lay, L, "    ", "ri_", "-pn * nx - pt * ny", "-pn * ny + pt * nx", "Rr * pt", True)
    for i in range(nz):
        L.append(f"    y[{nz + i}] += ri_z{i}")
    for b in range(nb):
        L.append(f"    y[{lay.i_w + b}] += ri_x{b}")
    if lay.motor:
        L.append(f"    y[{lay.i_theta + 1}] += ri_x{nb}")
    if house:
        L.append(f"    y[{ih + 2}] -= ri_fx / p[{kc + 7}]")
        L.append(f"    y[{ih + 3}] -= ri_fy / p[{kc + 7}]")
    out.append(_DECO + "def apply_impulse(t, y, p, pn, pt, nx, ny):  # pragma: no cover - compiled\n"
               '    """Add the velocity jump of the contact impulse -pn n + pt t (and torque R pt)."""\n'
               + "\n".join(L) + "\n")

    # project: put the gap vector back on the circle by the mass-weighted shortest move of z
    kb = lay.station_B(sc)
    kl = lay.pair_L(sc, sc)
    L = [f"    dl = p[{kc}]"]
    for name, row in (("wx", 0), ("wy", 1)):
        L.append(f"    {name} = {_sum([f'p[{kb + row * nz + j}] * y[{j}]' for j in range(nz)])}"
                 + (f" - y[{ih + row}]" if house else "") + f" - p[{kc + 8 + row}]")
    L += ["    gap, nx, ny = circular_gap(wx, wy, dl)",
          "    dx = gap * nx", "    dy = gap * ny",
          f"    det = p[{kl}] * p[{kl + 3}] - p[{kl + 1}] * p[{kl + 2}]",
          f"    lx = (p[{kl + 3}] * dx - p[{kl + 1}] * dy) / det",
          f"    ly = (p[{kl}] * dy - p[{kl + 2}] * dx) / det"]
    for i in range(nz):
        k = lay.station_HBT(sc) + 2 * i
        L.append(f"    y[{i}] += p[{k}] * lx + p[{k + 1}] * ly")
    out.append(_DECO + "def project(y, p):  # pragma: no cover - compiled\n"
               '    """Move the structure so that |w| = delta (B dz = gap n, dz = H B^T lambda)."""\n'
               + "\n".join(L) + "\n")

    # enter_mode
    out.append(_DECO + f'''def enter_mode(t, y, p, s):  # pragma: no cover - compiled
    """Rolling if the friction cone holds the rolling force, else sliding along the slip."""
    mu = p[{kc + 2}]
    if mu > 0.0 and s == 0.0:
        y[{i_mode}] = 2.0
        r = contact_terms(t, y, p, 2.0)
        if abs(r[1]) <= mu * r[0]:
            return
        y[{i_mode}] = -1.0 if r[1] > 0.0 else 1.0
        return
    y[{i_mode}] = 1.0 if s > 0.0 else -1.0
''')

    # events
    L = [f"    dl = p[{kc}]", f"    md = y[{i_mode}]", "    if md == 0.0:"]
    for name, row in (("wx", 0), ("wy", 1)):
        L.append(f"        {name} = {_sum([f'p[{kb + row * nz + j}] * y[{j}]' for j in range(nz)])}"
                 + (f" - y[{ih + row}]" if house else "") + f" - p[{kc + 8 + row}]")
    L += ["        gap, _, _ = circular_gap(wx, wy, dl)",
          "        g[0] = gap if abs(gap) > 8.0 * 2.220446049250313e-16 * dl else 0.0",
          "        g[1] = 1.0", "        g[2] = 1.0", "        g[3] = 1.0", "        return",
          "    r = contact_terms(t, y, p, md)",
          "    g[0] = 1.0",
          f"    g[1] = -r[6] if p[{kc + 5}] > 0.0 else r[0]" if massless else "    g[1] = r[0]",
          "    if md == 2.0:", "        g[2] = 1.0", f"        g[3] = p[{kc + 2}] * r[0] - abs(r[1])",
          "    else:", f"        g[2] = md * r[4] if p[{kc + 2}] > 0.0 else 1.0", "        g[3] = 1.0"]
    out.append(_DECO + "def events(t, y, p, g):  # pragma: no cover - compiled\n"
               '    """Events: 0 contact, 1 lift_off, 2 stick, 3 slip (all direction -1)."""\n'
               + "\n".join(L) + "\n")

    # reset
    ss_drive = "0.0" if lay.motor else "r[11]"
    proj = (f"        if p[{kc + 5}] == 0.0:\n            project(y_new, p)\n" if massless
            else "        project(y_new, p)\n")
    elastic_branch = f'''        if p[{kc + 5}] > 0.0:  # elastic: no impulse, sliding along the slip
            r = contact_terms(t, y, p, 0.0)
            enter_mode(t, y_new, p, r[4])
            return 0
''' if massless else ""
    contact_branch = elastic_branch + f'''        project(y_new, p)
        r = contact_terms(t, y_new, p, 1.0)
        vn, sl, bn = r[5], r[4], r[7]
        e = p[{kc + 1}]
        # an approach speed below rest_speed is the end of an accumulation (or integration noise
        # at a grazing touch): sustained contact if the stator has to push, else nothing happens
        settle = e * vn < p[{kc + 4}] and bn > 0.0
        if vn <= 0.0 and not settle:
            return 0
        if settle:
            e = 0.0  # the rest of the accumulation (chatter) as one plastic impulse
        pn, pt, stuck = newton_coulomb_impulse(vn, sl, r[8], r[9], r[10], e, p[{kc + 2}])
        ln, lt, dr = impulse_energy(vn, sl, pn, pt, r[8], r[9], r[10], {ss_drive})
        apply_impulse(t, y_new, p, pn, pt, r[2], r[3])
        y_new[{i_diss}] += ln + lt
        y_new[{i_drive}] += dr
        if pn > y_new[{i_pmax}]:
            y_new[{i_pmax}] = pn
        if settle:
            r2 = contact_terms(t, y_new, p, 0.0)
            enter_mode(t, y_new, p, 0.0 if stuck else r2[4])
        return 0
'''
    out.append(_DECO + f'''def reset(k, t, y, p, y_new):  # pragma: no cover - compiled
    """Reset maps of the clearance's events (see the module docstring)."""
    for i in range({n}):
        y_new[i] = y[i]
    if k == 0:
        y_new[{i_imp}] += 1.0
{contact_branch}    if k == 1:
{proj}        y_new[{i_mode}] = 0.0
        return 0
    if k == 2:
        enter_mode(t, y_new, p, 0.0)
        return 0
    # slip: slide against the tangential force of the state's mode (rolling, where it fires)
    r = contact_terms(t, y, p, y[{i_mode}])
    y_new[{i_mode}] = -1.0 if r[1] > 0.0 else 1.0
    return 0
''')
    return "".join(out)
