"""Terms of the balls on a tilting race, generated into a machine's kernel (``tilt`` layouts):
the race node's tilt and its rate, each ball's axial motion and moment arm, and the Schur
matrix with one axial unknown per ball (rigid ball kinematics, :mod:`rotorlab.models._machine`).
:func:`rotorlab._kernels.machine_codegen.prefix` calls them."""

from __future__ import annotations

from rotorlab._kernels.machine_emit import _sum
from rotorlab._kernels.machine_layout import Layout

__all__ = ["tilt_lines", "loads", "tilt_schur"]


def tilt_lines(lay: Layout, L: list[str]) -> None:
    """Append the tilt ``(tx, ty)`` and its rate ``(tvx, tvy)`` of each race's node and per ball
    ``D = m l^2``, ``ep = e . phi'``, ``tp = t . phi'`` and its moment arm on the race's tilt
    ``(nx, ny) = J_b / 2 (phi_y, -phi_x)`` (rigid ball kinematics, :mod:`rotorlab.models._machine`)."""
    nz, br, o = lay.n_z, lay.ball_race, lay.offsets
    a = L.append
    for r in lay.tilt_stations:  # named by the tilt station
        kb = lay.station_B(r)
        for name, row, src in (("tx", 0, "z"), ("ty", 1, "z"), ("tvx", 0, "v"), ("tvy", 1, "v")):
            a(f"    {name}{r} = {_sum([f'p[{kb + row * nz + j}] * {src}{j}' for j in range(nz)])}")
    for b in range(lay.n_balls):
        r = lay.tilt_station(br[b])
        a(f"    D{b} = p[{o['tilt'] + b}]")
        a(f"    ep{b} = c{b} * tvx{r} + s{b} * tvy{r}")
        a(f"    tp{b} = c{b} * tvy{r} - s{b} * tvx{r}")
        a(f"    nx{b} = 0.5 * J{b} * ty{r}")
        a(f"    ny{b} = -0.5 * J{b} * tx{r}")


def loads(lay: Layout, kind: str, idx: int) -> list[tuple[int, str, str]]:
    """Where a unit of Schur unknown ``(kind, idx)`` acts on the structure: ``(station, vx, vy)``
    with ``X_j = sum B_s^T (vx, vy)`` (its column of the mass matrix's coupling block)."""
    br = lay.ball_race
    if kind == "b":
        out = [(br[idx], f"mtx{idx}", f"mty{idx}")]
        if lay.tilt:
            out.append((lay.tilt_station(br[idx]), f"nx{idx}", f"ny{idx}"))
        return out
    if kind == "th":
        return [(ld.station, f"({ld.coef} * {ld.tx})", f"({ld.coef} * {ld.ty})") for ld in lay.spin_loads]
    return [(lay.tilt_station(br[idx]), f"c{idx}", f"s{idx}")]


def tilt_schur(lay: Layout, L: list[str], unknowns) -> None:
    """Append the Schur matrix ``S = diag(J_b, J, -1 / D_b) - X^T H X`` of a ``tilt`` layout
    (lower triangle ``S{i}_{j}``); ``P{j}_{s} = B_s H X_j`` is formed once per unknown."""
    a = L.append
    for b in range(lay.n_balls):
        a(f"    mtx{b} = -ml{b} * s{b}")
        a(f"    mty{b} = ml{b} * c{b}")
    lds = [loads(lay, k, i) for k, i in unknowns]
    used = sorted({s for ld in lds for s, _, _ in ld})
    # B_s H B_s2^T = B_s (H B_s2^T) from the packed B and H B^T that the kernel reads anyway
    # (for s <= s2; the other half by symmetry): fewer distinct loads of p than reading the
    # packed pairs, which keeps the lane loop within LLVM's runtime alias-check budget
    nz = lay.n_z
    for i1, s1 in enumerate(used):
        for s2 in used[i1:]:
            kb, kh = lay.station_B(s1), lay.station_HBT(s2)
            for k in range(4):
                row, col = divmod(k, 2)
                a(f"    Lv{s1}_{s2}_{k} = " + _sum([f"p[{kb + row * nz + j}] * p[{kh + 2 * j + col}]"
                                                   for j in range(nz)]))

    def lv(s1, s2, k):
        return f"Lv{s1}_{s2}_{k}" if s1 <= s2 else f"Lv{s2}_{s1}_{2 * (k % 2) + k // 2}"

    for j, ld in enumerate(lds):
        for s in used:
            for row, nm in ((0, "Px"), (1, "Py")):
                terms = [f"{lv(s, s2, 2 * row)} * {vx} + {lv(s, s2, 2 * row + 1)} * {vy}"
                         for s2, vx, vy in ld]
                a(f"    {nm}{j}_{s} = {_sum(terms)}")
    km = lay.offsets["motor"]
    for i, (ki, ii) in enumerate(unknowns):
        for j in range(i + 1):
            quad = _sum([f"{vx} * Px{j}_{s} + {vy} * Py{j}_{s}" for s, vx, vy in lds[i]])
            diag = ""
            if i == j:
                diag = {"b": f"J{ii}", "th": f"p[{km}]", "m": f"-1.0 / D{ii}"}[ki] + " "
            a(f"    S{i}_{j} = {diag}- ({quad})")
