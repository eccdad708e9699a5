r"""Typos of seeds 002 and 003 and the conclusions the exact analysis contradicts.

The typos of the model equations already found are listed (and tested) in
:mod:`rotorlab.models._jeffcott_balls` ("Corrections to the seeds"): seed 002 (1)-(3) axes, (5),
(6), (10) W with M, (11) no factor 1/2 and a minus sign, (14), (21), (23), (24), (25); seed 003
line before (2) and (2), (6), case 2b, fourth side motion case ii, (17) vs (18). They are used
here as corrected. The sections below add what the steady-motion analysis finds.
:data:`SEED_NOTES` lists both (``origin`` "model" or "steady"), each entry with the test that
checks it, for case-file comments and reports.

Seed 002 (Zhakash et al. 2024)
------------------------------
- (4), (7): ``mu_{omega^2 phi}`` and ``mu_{beta'} = beta`` stand for ``omega^2 mu Phi`` and
  ``mu beta' = beta``.
- Sentence after (23): the main solution is printed "орнықсыз" (unstable) beyond the critical
  region, contradicting (21)-(22) of the same paper; the averaged equations make it the only
  stable solution for omega > p when (17) holds (read "орнықты", stable).
- Conclusion: "from these conditions [minima of D] we obtain (9), the main equations": the
  stationarity of D gives (11) (``P_s = -dD/dalpha_s / (beta0 m R^2) = 0``), hence (12), not (9).
- (20)-(22) "the main solution is stable for omega > p" (first-order averaging, beta dropped) is
  contradicted by the exact eigenvalues just above p: the main motions are unstable in a window
  ``p < omega < omega*`` (``zhakash-k2`` enough: omega* = 1.457 p) where no steady motion is
  stable and the balls do not synchronise (in simulation they whirl together at about 0.95 p,
  captured near the critical speed, with a deflection of 10-15 mm); likewise the third solution
  for eta > 2 (``short``: unstable for 1.100 p < omega < 1.582 p). Averaging assumes the balls
  drift slowly compared with the decay of the rotor's free whirl; near p,
  ``W = m omega^2 / (c - M omega^2)`` is large and the assumption fails.
- Above omega* the balanced motions are stable but, up to about 1.7 p, not the only attractor:
  the non-synchronous whirl near p coexists with them (``zhakash-k2`` enough at 1.6 p: 14 % of
  the starts from rest of a 6 x 6 grid end there, deflection 18 mm). No local (eigenvalue)
  criterion can see this; only simulation (:func:`rotorlab.steady.verify`) does.
- (23) "the second solution is stable for omega < p": with beta > 0 the side motions (13) come in
  pairs k, k' (all bits flipped) that merge and vanish near p when ``|s(k)| > M1 r`` (see the
  seed 003 note below): solutions 2 and 3 do not exist for 0.97 p < omega < 1.03 p
  (``zhakash-k2`` enough), where again nothing is stable.
- The support damping beta of (2)-(3) is a small parameter that the first-order averaged
  equations drop, so (20)-(22) do not depend on it; the exact stability does: with beta = 0 the
  main solution is unstable at *every* speed above p (the balls' damping acts as rotating damping
  on the forward whirl at about p and destabilises it).
- A slow run-up through p can leave the balls captured in a non-synchronous whirl at about p
  (``zhakash-k2`` enough, ramp 0.3 p -> 2.5 p at 2 p per second: deflection 30 mm at 2.5 p
  instead of balancing), although the main solution is stable at the final speed: its basin does
  not contain the state the passage produces. A faster ramp (10 p per second) synchronises.

Seed 003 (Filimonikhin & Filimonikhina)
---------------------------------------
- Russian abstract: "на критических скоростях" -> "на закритических" (supercritical), as in
  the Ukrainian abstract and conclusion 3.
- Case 2a: ``Me <= sum m_i l_i`` is necessary, not sufficient, for the main motions (12): they
  exist iff the polygon inequality holds, also ``m_j l_j <= Me + sum_{i != j} m_i l_i`` for every
  j. With one pendulum dominating (``filimonikhin-n2`` dominant) no main motion exists although
  ``Me < sum m_i l_i``.
- Second side motion, case ii (``m2 l2 > Me + m1 l1``): "But this is the main motion" -- it is a
  side motion by (13) (``u = Me + m1 l1 - m2 l2 != 0``, deflection
  ``x = omega^2 (Me + m1 l1 - m2 l2) / (c - M_S omega^2) != 0``); it is the least unbalanced one.
- (16) drops the constant ``-omega^2 [J_O + sum J_Oi]`` of (10) (harmless for the extrema);
  the fourth side motion is headed "b)" a second time (read "c)").
- Case 1 ("below omega_cr only the first side motion, all k_i = 0, can be stable") and the
  side motions (13) themselves assume undamped supports. With support damping d the side
  motions k and k' (all bits flipped) with ``|s(k)| > Me`` merge and vanish where
  ``d omega |s(k)| > Me |c - M_S omega^2 + i d omega|``: with a small unbalance this reaches far
  below p (``filimonikhin-n2`` dominant: the first side motion vanishes above 0.782 p, and for
  0.782 p < omega < p no steady motion is stable and the pendulums do not synchronise).
- Conclusion 3 and the abstract ("at supercritical speeds only the main motions are stable"), for
  the seed's own assumption of supports without resistance, is contradicted by the exact
  eigenvalues: with d = 0 *no* steady motion is stable above omega_cr (``filimonikhin-n2``
  undamped: main motions, and the side motions of the short / dominant regimes, all grow, e.g.
  at 0.11 1/s at 2 p). Reason: in (10) the (x, y) block ``c - M_S omega^2`` is negative above
  omega_cr, so H* is never a local minimum there; the motion is only gyroscopically stabilised,
  and the dissipation of (5) (dH*/dt = -2 Phi <= 0, pervasive through the coupling) destroys
  that (Kelvin-Tait-Chetaev). The "least H~* among steady motions" comparison (and the
  conditional extremum (16)-(19)) therefore gives necessary conditions at best; with support
  damping d > 0 the main motions are stable only above a speed omega* > omega_cr
  (``filimonikhin-n2`` enough: omega* = 1.395 p; dominant: the side motion 01 above 1.459 p).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["SeedNote", "SEED_NOTES"]


@dataclass(frozen=True)
class SeedNote:
    """One typo or contradicted conclusion of a seed paper.

    Attributes
    ----------
    seed : {"002", "003"}
    where : str
        Equation number or place in the paper.
    kind : {"typo", "conclusion"}
        A misprinted formula or text, or a conclusion the exact analysis contradicts.
    printed : str
        What the paper says.
    corrected : str
        What holds (corrected formula, or the exact result).
    test : str
        The test that checks it (``tests/...::name``).
    origin : {"model", "steady"}
        Found with the model (listed in :mod:`rotorlab.models._jeffcott_balls`) or here.
    """

    seed: str
    where: str
    kind: str
    printed: str
    corrected: str
    test: str
    origin: str


_M2 = "tests/validation/test_jeffcott_seed002.py::"
_M3 = "tests/validation/test_jeffcott_seed003.py::"
_V2 = "tests/validation/test_steady_seed002.py::"
_V3 = "tests/validation/test_steady_seed003.py::"


def _model(seed, where, printed, corrected, test):
    return SeedNote(seed, where, "typo", printed, corrected, test, "model")


def _new(seed, where, kind, printed, corrected, test):
    return SeedNote(seed, where, kind, printed, corrected, test, "steady")


#: Every typo and contradicted conclusion of seeds 002 and 003, those of the model's list first.
SEED_NOTES: tuple[SeedNote, ...] = (
    _model("002", "(1)-(3)", "axes read as y -> -y, phi -> -phi", "x_s = x, y_s = -y, phi_s = phi (mirrored axes)",
           _M2 + "test_equations_1_to_3_in_mirrored_axes"),
    _model("002", "(5)", "M x'' + c x'", "M x'' + c x (and z -> r)", _M2 + "test_equations_1_to_3_in_mirrored_axes"),
    _model("002", "(6)", "+M1 z omega^2 sin(omega t)", "-M1 r omega^2 sin(omega t)",
           _M2 + "test_equations_1_to_3_in_mirrored_axes"),
    _model("002", "(10)", "W = m / M1 omega^2 / (p^2 - omega^2)", "W = m / M omega^2 / (p^2 - omega^2)",
           _M2 + "test_steady_response_eqs_9_10_use_the_total_mass"),
    _model("002", "(11), (15), (19), (21), (23)", "P_s = +1/2 omega^2 W / beta0 [...]",
           "P_s = -(omega^2 W / beta0) [...] (no 1/2, minus sign)", _M2 + "test_averaged_equation_11_by_simulation"),
    _model("002", "(14)", "|dP_s/dalpha_j - delta_sj theta c| = theta", "det(dP_s/dalpha_j - kappa delta_sj) = 0",
           _V2 + "test_averaged_jacobian_is_the_corrected_P_s"),
    _model("002", "(21)", "(omega W / beta0)(-eta cos gamma + cos 2 gamma), eta cos gamma^2, 'W > 0'",
           "A(1) = -2 K, B(1) = (1 - eta^2/4) K^2 eta^2, K = omega^2 W / beta0; W < 0",
           _M2 + "test_stability_coefficients_19_to_23"),
    _model("002", "(23)", "leading minus on A(3), B(3), A(4); cos pi in B(3); eta in B(4); (3) stable above p",
           "A(3) = 2K(1 - eta), B(3) = K^2 eta(eta - 2), B(4) = -K^2 eta^2; (3) stable only for eta > 2",
           _M2 + "test_light_side_motion_needs_short_capacity"),
    _model("002", "(24)-(25)", "1/2 C[(x0')^2 + (y0')^2]; D = -M m omega^2 R^2 / M1 W [...]",
           "1/2 c[x0^2 + y0^2]; D = -m omega^2 R^2 W [...] = H~* + const",
           _M2 + "test_eq_25_corrected_equals_reduced_hamiltonian"),
    _model("003", "line before (2), (2)", "d/dt(...) = sum q_i' dL/dq_i'", "= sum q_i' Q_i, hence (5)",
           _M3 + "test_hamiltonian_rate_equals_minus_twice_rayleigh"),
    _model("003", "(6)", "i = 1..n", "i = 1..N (all coordinates)", _M3 + "test_steady_motions_and_their_hamiltonian"),
    _model("003", "case 2b", "H~*(2^n) > H~*(k)", "H~*(2^n) < H~*(k)",
           _M3 + "test_case_2b_corrected_least_hamiltonian_when_capacity_is_short"),
    _model("003", "fourth side motion, case ii", "Me < m1 l1 + m2 l2", "Me > m1 l1 + m2 l2",
           _M3 + "test_fourth_side_motion_corrected_condition"),
    _model("003", "(17), (18)", "f = u^2 + v^2 and f = (u^2 + v^2) / 2", "(19) is the Hessian of the latter",
           _M3 + "test_fourth_side_motion_corrected_condition"),
    _new("002", "(4), (7)", "typo", "mu_{omega^2 phi}, mu_{beta'} = beta", "omega^2 mu Phi, mu beta' = beta",
         _V2 + "test_averaged_jacobian_is_the_corrected_P_s"),
    _new("002", "after (23)", "typo", "the main solution is unstable beyond the critical region",
         "stable for omega > p by (21)-(22) (averaged equations)", _V2 + "test_main_solution_stable_above_p_by_22"),
    _new("002", "conclusion after (25)", "typo", "minima of D give (9)", "stationarity of D gives (11), hence (12)",
         _V2 + "test_averaged_jacobian_is_the_corrected_P_s"),
    _new("002", "(20)-(22)", "conclusion", "main solution stable for every omega > p",
         "exactly unstable for p < omega < omega* (window), balls do not synchronise",
         _V2 + "test_window_above_critical_speed_exact_and_simulated"),
    _new("002", "(23), solution 2", "conclusion", "stable for every omega < p",
         "with beta > 0 it merges with solution 3 and vanishes for 0.97 p < omega < 1.03 p",
         _V2 + "test_solutions_2_and_3_vanish_near_p"),
    _new("002", "(2)-(3), (20)-(22)", "conclusion", "beta (support damping) a small parameter, dropped",
         "with beta = 0 the main solution is unstable at every omega > p",
         _V2 + "test_no_support_damping_destabilises_the_main_solution"),
    _new("002", "(20)-(22), above omega*", "conclusion", "the main solution is where the balls go above p",
         "up to about 1.7 p a non-synchronous whirl near p coexists and captures part of the starts",
         _V2 + "test_coexisting_whirl_above_the_window"),
    _new("002", "(22), run-up", "conclusion", "balancing above p",
         "a slow run-up can leave the balls captured at about p", _V2 + "test_run_up_capture_and_synchronisation"),
    _new("003", "Russian abstract", "typo", "на критических скоростях", "на закритических (supercritical)",
         _V3 + "test_supercritical_main_motions_need_support_damping"),
    _new("003", "case 2a", "conclusion", "Me <= sum m_i l_i: main motions",
         "polygon inequality for every ball as well", _V3 + "test_dominating_pendulum_no_main_motion"),
    _new("003", "second side motion, case ii", "conclusion", "this is the main motion",
         "a side motion (13) with nonzero deflection, the least unbalanced",
         _V3 + "test_dominating_pendulum_no_main_motion"),
    _new("003", "(16); fourth side motion heading", "typo", "2 H~* = -omega^4 f / (c - M omega^2); 'b)' twice",
         "plus the constant -omega^2 [J_O + sum J_Oi]; read 'c)'", _V3 + "test_h_tilde_on_the_constraint_eq_16"),
    _new("003", "case 1, (13)", "conclusion", "below omega_cr the first side motion is stable",
         "with support damping side motions vanish near p; none stable, no synchronisation",
         _V3 + "test_damping_removes_side_motions_below_p"),
    _new("003", "conclusion 3, abstract, (5)", "conclusion", "supercritical: only the main motions are stable (d = 0)",
         "with d = 0 no steady motion is stable above omega_cr; with d > 0 only above omega*",
         _V3 + "test_supercritical_main_motions_need_support_damping"),
)  # fmt: skip
