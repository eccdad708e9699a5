"""The Hopf curves of the two-plane balancer against the stability chart Rodrigues et al. published.

Rodrigues, Champneys, Friswell & Wilson, "Automatic two-plane balancing for rigid rotors", Int. J.
Non-Linear Mech. 43 (2008) 527-541 (figure numbers of the authors' preprint, University of
Bristol, hdl 1983/946): Fig. 5(a), the (Omega, m) plane of the long rotor with a static imbalance
eps = 0.01, its stable regions of the balanced state B shaded, bounded by the Hopf curves H_cyl
and H_con computed with AUTO; Fig. 5(d), its enlargement 2 <= Omega <= 4.5, 0.002 <= m <= 0.007.
The boundaries were read from the figure's vector graphics (``dev/digitize_rcfw_fig5a.py``: a
line m = const sampled on a grid of 0.01 (a) and 0.005 (d) against the shaded polygons), so each
is a bracket of the grid; the check allows half a grid step more for the drawing.

The paper holds the scaled ball damping ``c_b = b / (m Omega_1 R^2) = 0.01`` as m varies, so the
curves are continued in ``ball_mass_scaled_damping`` (each ball's damping in proportion to its
mass); the built-in case ``rcfw-two-plane`` is the paper's long rotor at m = 0.005 (b = 5e-5).
With the damping held fixed instead (``ball_mass``) the boundaries move: at m = 0.01 the primary
region would start at 3.89 rad/s instead of the paper's 3.52.

The disc rotor (Jp > Jt: no conical critical speed) has no stable balanced state at any speed of
the chart for any eccentricity with m = eps: Rodrigues et al., "Two-plane automatic balancing: a
symmetry breaking analysis", Int. J. Non-Linear Mech. 46 (2011) 1139-1154, Section 5 and Fig.
13(b) (the 2008 paper has no disc rotor). Its inertia (Jt = 0.5, Jp = 0.9) is that of
``test_machine_rcfw.py``.
"""

import numpy as np
import pytest

from rotorlab.analyses import build_model
from rotorlab.continuation import continue_equilibria, equilibrium_settings, two_parameter_curves, with_value
from rotorlab.io import load_case
from test_machine_rcfw import long_rotor
from test_rcfw_reference import FIG5A_BOUNDARIES

P = "ball_mass_scaled_damping"

#: Fig. 5(d) of the preprint (its vector graphics, a 0.005 grid in Omega): where a line m = const
#: enters (+1) or leaves (-1) the stable region of B. At m = 0.0034 the line crosses the tongue of
#: instability that reaches out to Omega = 4.17 near m = 0.0035.
FIG5D_BOUNDARIES = {
    0.0026: [(2.79, 2.795, +1)],
    0.003: [(2.735, 2.74, +1)],
    0.0032: [(2.725, 2.73, +1)],
    0.0034: [(2.725, 2.73, +1), (2.8, 2.805, -1), (3.515, 3.52, +1)],
    0.0036: [(4.075, 4.08, +1)],
    0.0038: [(2.75, 2.755, +1)],
    0.0044: [(2.845, 2.85, +1)],
    0.006: [(3.085, 3.09, +1)],
    0.007: [(3.215, 3.22, +1)],
}
#: Fig. 5(a) at m = 0.015, left out of FIG5A_BOUNDARIES there (a secondary window 0.01 wide).
FIG5A_SLIVER = {0.015: [(2.02, 2.03, +1), (2.03, 2.04, -1), (3.93, 3.94, +1)]}


@pytest.fixture(scope="module")
def chart():
    """Every Hopf point of B between 1.5 and 6 rad/s at m = 0.025 (steps fine enough for the
    secondary region), continued in m over the chart's 0.0026 <= m <= 0.04."""
    model = with_value(build_model(load_case("rcfw-two-plane").model), P, 0.025)
    branch = continue_equilibria(model, "drive.speed", 1.5, 6.0, start_from="main 0",
                                 settings=equilibrium_settings(1.5, 6.0, ds=0.0025, ds_max=0.0025))
    return model, two_parameter_curves(model, branch, P, 0.0026, 0.04)


def _crossings(values: np.ndarray, m: float) -> list[float]:
    """Speeds where the curve crosses the line m = const: on the parabola (in chord length)
    through the two points around the crossing and the next one (the curve bends between its
    points; a straight chord misses by up to 0.005 rad/s where it runs almost along the line)."""
    d = values[:, 1] - m
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(values / values.std(axis=0), axis=0), axis=1))])
    out = []
    for k in np.flatnonzero(d[:-1] * d[1:] <= 0.0):
        if d[k] == d[k + 1]:
            continue
        j = np.arange(k, k + 3) if k + 2 < len(s) else np.arange(k - 1, k + 2)
        cm, co = np.polyfit(s[j], values[j, 1], 2), np.polyfit(s[j], values[j, 0], 2)
        roots = np.roots(cm - np.array([0.0, 0.0, m]))
        roots = roots[(np.abs(roots.imag) < 1e-12) & (roots.real >= s[k] - 1e-12) & (roots.real <= s[k + 1] + 1e-12)]
        t = float(roots.real[0]) if roots.size else s[k] + (s[k + 1] - s[k]) * d[k] / (d[k] - d[k + 1])
        out.append(float(np.polyval(co, t)))
    return out


def _stable_edges(model, m: float, lo: float, hi: float, step: float = 0.0025):
    """Stability-changing Hopf points of B over [lo, hi] rad/s at ball mass m (one parameter)."""
    r = continue_equilibria(with_value(model, P, m), "drive.speed", lo, hi, start_from="main 0",
                            settings=equilibrium_settings(lo, hi, ds=step, ds_max=step))
    return [s for s in r.branches[0].special_points if s.type == "hopf" and s.changes_stability]


def test_hopf_curves_are_the_published_stability_boundaries(chart):
    """Every boundary of B's stable regions in Fig. 5(a) and (d) lies on one of the Hopf curves,
    within the figure's reading; the curves are the ones AUTO drew (H_cyl, H_con), all of them
    continued to the chart's edges."""
    _, curves = chart
    assert [c.type for c in curves] == ["hopf"] * 3 and all(c.end == "bound/bound" for c in curves)
    table = {**FIG5A_BOUNDARIES, **FIG5A_SLIVER, **FIG5D_BOUNDARIES}
    grid = {m: (0.005 if m in FIG5D_BOUNDARIES else 0.01) for m in table}
    for m, edges in table.items():
        speeds = np.concatenate([_crossings(c.values, m) for c in curves])
        for lo, hi, _ in edges:
            miss = np.min(np.abs(speeds - 0.5 * (lo + hi)))
            assert miss <= 0.5 * (hi - lo) + 0.5 * grid[m], (m, lo, hi, np.sort(speeds))


@pytest.mark.parametrize(("m", "edges"), [(0.0034, FIG5D_BOUNDARIES[0.0034]), (0.0036, FIG5D_BOUNDARIES[0.0036]),
                                          (0.015, FIG5A_SLIVER[0.015]), (0.03, FIG5A_BOUNDARIES[0.03])])
def test_one_parameter_runs_change_stability_where_the_paper_does(m, edges):
    """Independent one-parameter runs in speed at the published masses: their stability-changing
    Hopf points are the figure's boundaries, in number, order and direction (+1: B becomes stable
    as the speed rises)."""
    model = build_model(load_case("rcfw-two-plane").model)
    found = _stable_edges(model, m, 1.5, 6.0)
    assert len(found) == len(edges), [(s.value, s.description) for s in found]
    for s, (lo, hi, sign) in zip(found, edges):
        assert lo - 0.0025 <= s.value <= hi + 0.0025, (m, s.value, lo, hi)
        assert s.description.startswith("balancing becomes stable above" if sign > 0 else "balancing is stable only below")


def test_the_curve_near_3_5_g_is_smooth_and_on_the_one_parameter_branches(chart):
    """The primary boundary H_con near m = 3.5 g: one arc through the tongue (no jump: the
    earlier code left it for its mirror image at negative speed), turning by at most 60 degrees
    between points in the axes of Fig. 5(d) (2.5 rad/s by 5 g); a point of it is a Hopf point of
    an independent one-parameter run at its mass to 1e-7."""
    _, curves = chart
    (h,) = [c for c in curves if np.any((np.abs(c.values[:, 1] - 0.0035) < 2e-4) & (c.values[:, 0] > 2.5))]
    v = h.values
    assert np.all(v[:, 0] > 2.5) and v[:, 1].min() == pytest.approx(0.0026) and v[:, 1].max() == pytest.approx(0.04)
    w = v / np.array([2.5, 0.005])
    d = np.diff(w, axis=0)
    length = np.linalg.norm(d, axis=1)
    assert length.max() < 1.0
    turn = np.arccos(np.clip(np.sum(d[1:] * d[:-1], axis=1) / (length[1:] * length[:-1]), -1.0, 1.0))
    assert np.degrees(turn.max()) < 60.0
    # the tongue's tip: the furthest speed of the arc between 3.4 and 3.7 g (Fig. 5(d): 4.17)
    tongue = v[(v[:, 1] > 0.0034) & (v[:, 1] < 0.0037)]
    assert 4.1 < tongue[:, 0].max() < 4.25
    k = int(np.argmin(np.abs(v[:, 1] - 0.0035) + 10 * (v[:, 0] < 3.5)))  # on the tongue's upper side
    om, m = v[k]
    model = build_model(load_case("rcfw-two-plane").model)
    r = continue_equilibria(with_value(model, P, m), "drive.speed", om - 0.05, om + 0.05, start_from="main 0")
    hopf = [s.value for s in r.branches[0].special_points if s.type == "hopf"]
    assert min(abs(x - om) for x in hopf) < 1e-7 * om, (om, hopf)


@pytest.mark.parametrize("eps", [1e-4, 1e-2, 0.1])
def test_disc_rotor_has_no_stable_balanced_state(eps):
    """Jp > Jt, m = eps (Rodrigues et al. 2011, Fig. 13(b): 0 < Omega <= 6, eps from 1e-6 to 1):
    the balanced branch continued over the chart's speeds is unstable at every point and has no
    Hopf or fold point where it would gain stability; so is the branch continued in the ball mass
    (its damping per unit mass fixed) from m = eps to 4 eps at the conical speed of the long rotor."""
    disc = long_rotor(eps, eps, jt=0.5, jp=0.9)
    r = continue_equilibria(disc, "drive.speed", 0.25, 6.0, start_from="main 0",
                            settings=equilibrium_settings(0.25, 6.0, ds_max=0.01))
    (b,) = [b for b in r.branches if b.label == "main 0"]
    assert b.values[0] == 0.25 and b.values[-1] == 6.0
    assert not np.any(b.stable) and not any(s.changes_stability for s in b.special_points)
    at = with_value(disc, "drive.speed", 1.81)
    r = continue_equilibria(at, P, eps, 4 * eps, start_from="main 0")
    (b,) = [b for b in r.branches if b.label == "main 0"]
    assert b.values[-1] == pytest.approx(4 * eps) and not np.any(b.stable)
