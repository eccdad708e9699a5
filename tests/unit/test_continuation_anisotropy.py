"""Speed x support anisotropy (issue 25): the balanced state's stability on anisotropic supports is
a Floquet problem, its boundary a curve, on the planar machine of test_continuation_equilibria.py.

References: at zero anisotropy the linearization is constant, so the largest Floquet exponent is
the largest real part of the co-rotating eigenvalues and the boundary passes through the
isotropic Hopf point (continue_equilibria). The co-rotating linearization is checked against an
independent chain rule through the fixed-frame right-hand side ``Machine.rhs`` of the machine with
``k_xx = k (1 - a)``, ``k_yy = k (1 + a)`` (``x_r' = T^-1 (J_fixed T - T') x_r``, T the frame map at
angle Omega t), and the monodromy against SciPy's DOP853 (rtol 1e-13) of that linear periodic system; near a
boundary point the full nonlinear machine's whirl grows or decays at the Floquet exponent.
Swapping x and y maps ``a`` to ``-a`` (a quarter turn of the frame): the boundary is symmetric.
"""

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.continuation import (
    BalancedFloquet,
    MachineEquilibria,
    continue_equilibria,
    floquet_boundary,
    with_anisotropy,
    with_value,
)
from rotorlab.report import PRESENTATIONS
from test_continuation_equilibria import machine
from test_continuation_interfaces import run_planar_speed_curves
from test_machine_common import PLANAR


def _fixed_frame_linearization(m, om, state, t):
    """``A_r(t)`` by the chain rule through ``Machine.rhs`` (fourth-order differences, fixed frame)."""
    nz, nb = m.n_coordinates, m.n_balls
    lay, th = m.layout, om * t
    c, s = math.cos(th), math.sin(th)
    rot = np.kron(np.eye(nz // 2), [[c, -s], [s, c]])
    jay = np.kron(np.eye(nz // 2), [[0.0, -1.0], [1.0, 0.0]])
    n = 2 * nz + 2 * nb
    T = np.zeros((lay.n_state, n))  # fixed state = T x_r + offsets (ball angle theta, rate Omega)
    T[:nz, :nz] = rot
    T[nz:2 * nz, :nz] = om * rot @ jay
    T[nz:2 * nz, nz:2 * nz] = rot
    T[lay.i_phi:lay.i_phi + nb, 2 * nz:2 * nz + nb] = np.eye(nb)
    T[lay.i_w:lay.i_w + nb, 2 * nz + nb:] = np.eye(nb)
    Td = np.zeros_like(T)
    Td[:nz, :nz] = om * rot @ jay
    Td[nz:2 * nz, :nz] = om * om * rot @ jay @ jay
    Td[nz:2 * nz, nz:2 * nz] = om * rot @ jay
    y = T @ state
    y[lay.i_phi:lay.i_phi + nb] += th
    y[lay.i_w:lay.i_w + nb] += om
    J = np.empty((lay.n_state, lay.n_state))
    for j in range(lay.n_state):
        h = 1e-5
        e = np.zeros(lay.n_state)
        e[j] = h
        f1 = m.rhs(t, y + e) - m.rhs(t, y - e)
        f2 = m.rhs(t, y + 2 * e) - m.rhs(t, y - 2 * e)
        J[:, j] = (8 * f1 - f2) / (12 * h)
    return np.linalg.pinv(T) @ (J @ T - Td)


def test_linearization_monodromy_and_the_isotropic_hopf_point():
    m = machine(0.5)
    bf = BalancedFloquet(m)
    np.testing.assert_allclose(np.abs(bf.state[4:6]), math.acos(-0.01 / (2 * 0.02)), atol=1e-9)
    om, a = 1.7, 0.3
    a0, ac, as_ = bf.system(om, a)
    for x, y in zip(bf.direct(om, a), (a0, ac, as_)):  # the speed polynomial against a direct evaluation
        np.testing.assert_allclose(x, y, atol=1e-10)
    assert np.abs(ac).max() > 0.05  # the turning supports do enter
    ma = with_anisotropy(with_value(m, "drive.speed", om), a)
    assert ma.structure.K[0, 0] == pytest.approx(0.7) and ma.structure.K[1, 1] == pytest.approx(1.3)
    for t in (0.3, 1.1):
        ref = _fixed_frame_linearization(ma, om, bf.state, t)
        np.testing.assert_allclose(a0 + ac * math.cos(2 * om * t) + as_ * math.sin(2 * om * t), ref, atol=1e-7)
    n = a0.shape[0]
    sol = solve_ivp(lambda t, y: ((a0 + ac * math.cos(2 * om * t) + as_ * math.sin(2 * om * t)) @ y.reshape(n, n))
                    .ravel(), (0.0, math.pi / om), np.eye(n).ravel(), method="DOP853", rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(bf.monodromy(om, a), sol.y[:, -1].reshape(n, n), atol=1e-8)
    # a = 0: constant linearization, exponent = the largest real part of the exact eigenvalues
    lam = np.linalg.eigvals(with_value(m, "drive.speed", om).linearize(bf.state).A)
    assert abs(bf.exponent(om, 0.0) - lam.real.max()) < 1e-9
    assert abs(bf.exponent(om, a) - bf.exponent(om, -a)) < 1e-9  # x <-> y symmetry


def test_boundary_meets_the_isotropic_hopf_point_and_a_parametric_tongue():
    m = machine(0.5)
    r = continue_equilibria(m, "drive.speed", 0.6, 3.0, start_from="main+", parameter2="support_anisotropy",
                            range2=(0.0, 0.5))
    (hopf,) = r.branches[0].special_points
    assert hopf.type == "hopf"
    main, *others = r.curves
    assert main.type == "floquet-boundary" and main.parameters == ("drive.speed", "support_anisotropy")
    assert main.values[0, 1] == 0.0 and abs(main.values[0, 0] - hopf.value) < 1e-6 * hopf.value
    assert main.end == "bound" and main.values[-1, 1] == pytest.approx(0.5) and len(main.values) > 5
    bf = BalancedFloquet(m)
    for w, a in main.values[1::6]:  # on the boundary; stable just above it in speed, unstable below
        assert abs(bf.exponent(w, a)) < 1e-7
        assert bf.exponent(w * 1.01, a) < 0.0 < bf.exponent(w * 0.99, a)
    assert set(main.crossing) == {"complex"}
    # the Hopf pair's frequency at a = 0: the multipliers exp(+-i omega pi / Omega)
    assert abs(main.frequency[0] - hopf.frequency) < 1e-6 * hopf.frequency
    # a tongue from the top edge (the critical speed 1 rad/s), closed within the range
    (tongue,) = others
    assert 0.9 < tongue.values[:, 0].min() < tongue.values[:, 0].max() < 1.0 and tongue.values[:, 1].min() > 0.3
    doc = r.to_dict()
    assert doc["curves"][0]["points"][0]["crossing"] == "complex"
    top = doc["findings"][0]
    assert top.startswith("balancing is stable for every support anisotropy from 0 to 0.5 at 28.65 rpm")
    w = 1.8  # half-way down the range (the findings' speeds: 3, 2.4, 1.8, 1.2): the main boundary crosses it
    a_star = np.interp(w, main.values[main.values[:, 1] > 0.1, 0], main.values[main.values[:, 1] > 0.1, 1])
    assert doc["findings"][2].startswith(f"balancing is stable for support anisotropy below {a_star:.3g} at "
                                         f"{w * 30 / math.pi:.4g} rpm")
    assert "lost through a complex pair of multipliers (Neimark-Sacker" in doc["findings"][2]
    assert doc["findings"][3] == "at 11.46 rpm the balanced state is unstable already at support anisotropy 0"
    assert doc["findings"][4] == (f"a stability boundary of the balanced state runs from {hopf.value * 30 / math.pi:.4g} "
                                  f"rpm at support anisotropy 0 to {main.values[-1, 0] * 30 / math.pi:.4g} rpm at 0.5")
    assert len(doc["findings"]) == 6


def test_full_nonlinear_machine_decays_inside_and_grows_outside_a_boundary_point():
    """The anisotropic machine's own fixed-frame equations (Machine.rhs, nonlinear, SciPy DOP853),
    started near the balanced state 10 % below and above the boundary speed at a = 0.45: the
    rotor's whirl radius grows and decays at the largest Floquet exponent (envelope over 450 s)."""
    m = machine(0.5)
    (main, *_) = floquet_boundary(m, 0.6, 3.0, 0.0, 0.5)
    k = int(np.argmin(np.abs(main.values[:, 1] - 0.45)))
    w_b, a = main.values[k]
    bf = BalancedFloquet(m)
    for w in (0.9 * w_b, 1.1 * w_b):
        ma = with_anisotropy(with_value(m, "drive.speed", w), a)
        lay = ma.layout
        y0 = np.zeros(lay.n_state)
        y0[0] = 1e-5
        y0[lay.i_phi:lay.i_phi + 2] = bf.state[4:6] + [1e-3, 0.0]
        y0[lay.i_w:lay.i_w + 2] = w
        sol = solve_ivp(ma.rhs, (0.0, 600.0), y0, method="DOP853", rtol=1e-10, atol=1e-13, dense_output=True)
        ts = np.linspace(0.0, 600.0, 6001)
        r = np.hypot(*sol.sol(ts)[:2])
        rate = math.log(r[ts > 550].max() / r[(ts > 100) & (ts < 150)].max()) / 450.0
        g = bf.exponent(w, a)
        assert abs(g) > 4e-3 and rate * g > 0 and abs(rate - g) < 0.05 * abs(g)


def test_other_steady_motions_in_anisotropy_are_refused_saying_what_works():
    with pytest.raises(ValueError) as err:
        MachineEquilibria(machine(1.0), ("drive.speed", "support_anisotropy"))
    text = str(err.value)
    assert "--param2 support_anisotropy" in text and "Not implemented: the other steady motions" in text
    with pytest.raises(ValueError, match="against drive.speed only"):
        continue_equilibria(machine(1.0), "ball_mass", 0.02, 0.03, parameter2="support_anisotropy",
                            range2=(0.0, 0.1))
    with pytest.raises(ValueError, match=r"support_anisotropy = 1: .* \(-1, 1\)"):
        with_anisotropy(machine(1.0), 1.0)


def test_case_file_and_cli_draw_the_boundary_over_the_floquet_chart(tmp_path):
    ds, rows = run_planar_speed_curves("aniso", 0.5, "support_anisotropy", ("0", "0.5"))
    assert str(ds.curve_type.values[0]) == "floquet-boundary" and ds.chart_stable.shape == (13, 41)
    assert bool(ds.chart_stable.values[0, -1]) and not bool(ds.chart_stable.values[0, 0])
    verdict = PRESENTATIONS["continuation"].findings(ds, rows).verdict
    assert verdict.startswith("Balancing is stable for")
    path = tmp_path / "planar.toml"
    path.write_text(PLANAR)
    png = tmp_path / "a.png"
    res = CliRunner().invoke(app, ["continue", str(path), "--param", "drive.speed=0.5:3", "--param2",
                                   "support_anisotropy=0:0.5", "--from", "balanced", "--json", "--plot", str(png)])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["curves"][0]["type"] == "floquet-boundary" and doc["findings"]
    assert (tmp_path / "a-curves.png").stat().st_size > 10_000
    bad = tmp_path / "bad.png"
    for extra, said in ((["drive.speed=0.5:3", "--param2", "support_anisotropy=0:1.2"],
                         "--param2 = [0.0, 1.2]: stop: support_anisotropy = 1.2 must lie strictly between -1 and 1"),
                        (["ball_mass=0.01:0.02", "--speed-rpm", "20", "--param2", "support_anisotropy=0:0.2"],
                         "--param2: is continued against drive.speed only")):
        res = CliRunner().invoke(app, ["continue", str(path), "--param", *extra, "--plot", str(bad)])
        assert res.exit_code == 2 and said in res.output and "Traceback" not in res.output and not bad.exists()


class _DampedMathieu:
    """``x'' + c x' + (delta + eps cos t) x = 0`` as a periodic linear system in ``(w, a) = (delta,
    eps)``, its monodromy over ``2 pi`` by the boundary code's own Magnus integrator (A(t) = A0 +
    Ac cos 2 Omega t with Omega = 1/2), Richardson-extrapolated as :class:`BalancedFloquet` does."""

    label, state = "mathieu", np.zeros(2)

    def __init__(self, c: float):
        self.c = c

    def multipliers(self, delta: float, eps: float) -> np.ndarray:
        from rotorlab.continuation._anisotropic import _magnus4

        a0 = np.array([[0.0, 1.0], [-delta, -self.c]])
        ac = np.array([[0.0, 0.0], [-eps, 0.0]])
        p1, p2 = (_magnus4(a0, ac, np.zeros((2, 2)), 0.5, n) for n in (100, 200))
        mu = np.linalg.eigvals(p2 + (p2 - p1) / 15.0)
        return mu[np.argsort(-np.abs(mu), kind="stable")]

    def exponent(self, delta: float, eps: float) -> float:
        return math.log(abs(self.multipliers(delta, eps)[0])) / (2.0 * math.pi)


def _dop853_exponent(c: float, delta: float, eps: float) -> float:
    """log max|mu| of the damped Mathieu equation over 2 pi, SciPy's DOP853 (rtol 1e-12)."""
    def f(t, y):
        x = y.reshape(2, 2)
        return (np.array([[0.0, 1.0], [-(delta + eps * math.cos(t)), -c]]) @ x).ravel()

    sol = solve_ivp(f, (0.0, 2 * math.pi), np.eye(2).ravel(), method="DOP853", rtol=1e-12, atol=1e-14)
    return math.log(np.abs(np.linalg.eigvals(sol.y[:, -1].reshape(2, 2))).max())


def test_floquet_boundary_labels_plus_and_minus_one_crossings_at_the_mathieu_tongues():
    """The boundary's crossing labels on a system with both real crossings: the damped Mathieu
    equation x'' + c x' + (delta + eps cos t) x = 0 (McLachlan 1947; Abramowitz & Stegun 20.1,
    with z = t / 2: a = 4 delta, q = -2 eps). Its tongue from delta = 1/4 has a multiplier through
    -1 (solutions of period 4 pi, ce_1 / se_1), the one from delta = 1 a multiplier through +1
    (period 2 pi, ce_2 / se_2). With c = 0.02 each tongue's boundary is one curve around its tip,
    both ends at eps = 0.4; there it lies inside the undamped tongue (edges a_m(2 eps) / 4 and
    b_m(2 eps) / 4, scipy.special.mathieu_a / mathieu_b) and equals the zero of the largest
    Floquet exponent by SciPy's DOP853 (an independent integrator) to 1e-6."""
    from scipy.optimize import brentq
    from scipy.special import mathieu_a, mathieu_b

    from rotorlab.continuation._anisotropic import boundaries

    c, top, q = 0.02, 0.4, 0.8
    curves = boundaries(_DampedMathieu(c), 0.02, 1.3, 0.02, top)
    assert len(curves) == 2 and all(x.end == "bound" for x in curves)
    for curve, m, label in zip(sorted(curves, key=lambda x: x.values[0, 0]), (1, 2), ("-1", "+1")):
        assert set(curve.crossing) == {label}
        ends = sorted(curve.values[np.isclose(curve.values[:, 1], top, atol=1e-12), 0])
        lo, hi = mathieu_b(m, q) / 4, mathieu_a(m, q) / 4  # the undamped tongue at eps = 0.4
        mid = 0.5 * (lo + hi)
        ref = [brentq(lambda d: _dop853_exponent(c, d, top), *br, xtol=1e-12) for br in ((lo, mid), (mid, hi))]
        assert lo < ends[0] < ends[1] < hi
        assert ends == pytest.approx(ref, abs=1e-6)
