"""The common operations of the machine's generated kernel, for its generator and its parts.

Every part of the kernel (:mod:`rotorlab._kernels.machine_codegen`, the tilting races of
:mod:`~rotorlab._kernels.machine_tilt`, the balls' stick/slip of
:mod:`~rotorlab._kernels.machine_friction`, the clearance of
:mod:`~rotorlab._kernels.machine_contact`, the attachments of :mod:`rotorlab.models._parts`)
writes its lines through these functions: dense products with the packed matrices (a station's
``B_s z``, a sum of terms), the constrained solve (the unrolled LDL^T of the Schur system, its
forward and back substitution, the station forces of its solution) and the response to a unit
station force. They only read a :class:`~rotorlab._kernels.machine_layout.Layout`; no module of
the generator imports another's generator functions (the generator hands its ``prefix`` to the
parts that start functions of their own with it).
"""

from __future__ import annotations

from rotorlab._kernels.machine_layout import Layout

__all__ = ["ldl_lines", "solve_lines", "reactions", "unit_rhs", "station_rows", "dense_row"]


def _sum(terms: list[str]) -> str:
    return " + ".join(terms) if terms else "0.0"


def dense_row(offset: int, names: list[str]) -> str:
    """The expression ``sum_j p[offset + j] * names[j]`` (a row of a packed dense matrix times a
    vector of generated variables)."""
    return _sum([f"p[{offset + j}] * {v}" for j, v in enumerate(names)])


def station_rows(lay: Layout, s: int, vec: str) -> tuple[str, str]:
    """The two expressions of ``B_s v`` (the lateral x and y of station ``s``) for the structure
    vector whose entries are the variables ``{vec}0 ... {vec}{n_z - 1}`` (``z``: positions,
    ``v``: rates)."""
    nz, kb = lay.n_z, lay.station_B(s)
    names = [f"{vec}{j}" for j in range(nz)]
    return dense_row(kb, names), dense_row(kb + nz, names)


def _less_reactions(lay: Layout, r: int, row: int, corr: list[tuple[int, str, str]]) -> list[str]:
    """Terms ``-(L_(r, s) g_s)[row]`` of station ``r``'s acceleration for the station forces
    ``corr`` (``(s, gx name, gy name)``, from :func:`reactions`)."""
    out = []
    for s, gx, gy in corr:
        k = lay.pair_L(r, s) + 2 * row
        out.append(f"-(p[{k}] * {gx} + p[{k + 1}] * {gy})")
    return out


def ldl_lines(n_s: int, L: list[str]) -> None:
    """Append the unrolled LDL^T factors ``D{j}``, ``L{i}_{j}`` of the symmetric system ``S{i}_{j}``
    (i >= j) of size ``n_s`` (no pivoting: S is a Schur complement of a mass matrix, positive
    definite, or quasi-definite with the tilt unknowns)."""
    for j in range(n_s):
        L.append(f"    D{j} = S{j}_{j}" + "".join(f" - L{j}_{k} * L{j}_{k} * D{k}" for k in range(j)))
        for i in range(j + 1, n_s):
            L.append(f"    L{i}_{j} = (S{i}_{j}" + "".join(f" - L{i}_{k} * L{j}_{k} * D{k}" for k in range(j))
                     + f") / D{j}")


def unit_rhs(lay: Layout, L: list[str], tag: str, s: int, tq: str, ind: str) -> None:
    """Append ``{tag}q{i} = -X_i^T H B_s^T f`` for a unit force ``f = ({tag}fx, {tag}fy)`` at
    station ``s`` (and the spin torque ``tq`` on theta's row): the right-hand side of the
    Schur system for the response to a force (the clearance's Delassus terms)."""
    br, nb = lay.ball_race, lay.n_balls
    a = lambda x: L.append(ind + x)  # noqa: E731

    def proj(s2, vx, vy):
        kk = lay.pair_L(s2, s)
        return (f"{vx} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
                f" + {vy} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy)")

    for b in range(nb):
        kk = lay.pair_L(br[b], s)
        extra = ""
        if lay.tilt:
            extra = " + " + proj(lay.tilt_station(br[b]), f"nx{b}", f"ny{b}")
        a(f"{tag}q{b} = -ml{b} * (-s{b} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
          f" + c{b} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy))"
          + (f" - ({extra[3:]})" if extra else ""))
    if lay.motor:
        terms = []
        for ld in lay.spin_loads:  # the rotor's parts (unbalances) on the spin
            kk = lay.pair_L(ld.station, s)
            terms.append(f"{ld.coef} * ({ld.tx} * (p[{kk}] * {tag}fx + p[{kk + 1}] * {tag}fy)"
                         f" + {ld.ty} * (p[{kk + 2}] * {tag}fx + p[{kk + 3}] * {tag}fy))")
        a(f"{tag}q{nb} = {tq} - ({_sum(terms)})")
    if lay.tilt:
        i0 = nb + (1 if lay.motor else 0)
        for b in range(nb):
            a(f"{tag}q{i0 + b} = -({proj(lay.tilt_station(br[b]), f'c{b}', f's{b}')})")


def solve_lines(lay: Layout, L: list[str], x: str, q: str, indent: str = "    ") -> None:
    """Append the forward and back substitution ``S x = q`` with the LDL^T factors of :func:`prefix`."""
    n_s = lay.n_schur
    for i in range(n_s):
        L.append(f"{indent}{x}{i} = {q}{i}" + "".join(f" - L{i}_{k} * {x}{k}" for k in range(i)))
    for i in reversed(range(n_s)):
        L.append(f"{indent}{x}{i} = {x}{i} / D{i}" + "".join(f" - L{k}_{i} * {x}{k}" for k in range(i + 1, n_s)))


def reactions(lay: Layout, L: list[str], g: str, x: str, indent: str = "    ") -> list[tuple[int, str, str]]:
    """Append the station forces of the ball (and spin) accelerations ``x``: ``(g}x_s, g}y_s)``."""
    nb, br, nr = lay.n_balls, lay.ball_race, lay.n_races
    corr = []
    for r in range(nr):
        bs = [b for b in range(nb) if br[b] == r]
        L.append(f"{indent}{g}x{r} = {_sum([f'-ml{b} * {x}{b} * s{b}' for b in bs])}")
        L.append(f"{indent}{g}y{r} = {_sum([f'ml{b} * {x}{b} * c{b}' for b in bs])}")
        corr.append((r, f"{g}x{r}", f"{g}y{r}"))
    if lay.motor:
        for ld in lay.spin_loads:
            s = ld.station
            L.append(f"{indent}{g}x{s} = {ld.coef} * {x}{nb} * {ld.tx}")
            L.append(f"{indent}{g}y{s} = {ld.coef} * {x}{nb} * {ld.ty}")
            corr.append((s, f"{g}x{s}", f"{g}y{s}"))
    if lay.tilt:  # the balls' moments on their races' tilt: n_b phi_b'' + e_b mu_b
        i0 = nb + (1 if lay.motor else 0)
        for ts in lay.tilt_stations:
            bs = lay.tilt_balls(ts)
            L.append(f"{indent}{g}x{ts} = {_sum([f'nx{b} * {x}{b} + c{b} * {x}{i0 + b}' for b in bs])}")
            L.append(f"{indent}{g}y{ts} = {_sum([f'ny{b} * {x}{b} + s{b} * {x}{i0 + b}' for b in bs])}")
            corr.append((ts, f"{g}x{ts}", f"{g}y{ts}"))
    return corr


_DECO = '\n\n@njit(cache=True, nogil=True, error_model="numpy")\n'
