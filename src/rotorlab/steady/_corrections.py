r"""Typos of seeds 002 and 003 and the conclusions the exact analysis contradicts.

The typos of the model equations already found are listed (and tested) in
:mod:`rotorlab.models._jeffcott_balls` ("Corrections to the seeds"): seed 002 (1)-(3) axes, (5),
(6), (10) W with M, (11) no factor 1/2 and a minus sign, (14), (21), (23), (24), (25); seed 003
line before (2) and (2), (6), case 2b, fourth side motion case ii, (17) vs (18). They are used
here as corrected. :data:`SEED_NOTES` adds what the steady-motion analysis finds; each entry names
the test that checks it.

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
  stable and the balls do not synchronise (in simulation they lag behind the rotor at about
  0.35 omega); likewise the third solution for eta > 2 (``short``: unstable for
  1.100 p < omega < 1.582 p). Averaging assumes the balls drift slowly compared with the decay
  of the rotor's free whirl; near p, ``W = m omega^2 / (c - M omega^2)`` is large and the
  assumption fails.
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
    printed : str
        What the paper says.
    corrected : str
        What holds (corrected formula, or the exact result).
    test : str
        The test that checks it (``tests/...::name``).
    """

    seed: str
    where: str
    printed: str
    corrected: str
    test: str


_V2 = "tests/validation/test_steady_seed002.py::"
_V3 = "tests/validation/test_steady_seed003.py::"

SEED_NOTES: tuple[SeedNote, ...] = (
    SeedNote("002", "(4), (7)", "mu_{omega^2 phi}, mu_{beta'} = beta", "omega^2 mu Phi, mu beta' = beta",
             _V2 + "test_averaged_jacobian_is_the_corrected_P_s"),
    SeedNote("002", "after (23)", "the main solution is unstable beyond the critical region",
             "stable for omega > p by (21)-(22) (averaged equations)", _V2 + "test_main_solution_stable_above_p_by_22"),
    SeedNote("002", "conclusion after (25)", "minima of D give (9)", "stationarity of D gives (11), hence (12)",
             _V2 + "test_averaged_jacobian_is_the_corrected_P_s"),
    SeedNote("002", "(20)-(22)", "main solution stable for every omega > p",
             "exactly unstable for p < omega < omega* (window), balls do not synchronise",
             _V2 + "test_window_above_critical_speed_exact_and_simulated"),
    SeedNote("002", "(23), solution 2", "stable for every omega < p",
             "with beta > 0 it merges with solution 3 and vanishes for 0.97 p < omega < 1.03 p",
             _V2 + "test_solutions_2_and_3_vanish_near_p"),
    SeedNote("002", "(2)-(3), (20)-(22)", "beta (support damping) a small parameter, dropped",
             "with beta = 0 the main solution is unstable at every omega > p",
             _V2 + "test_no_support_damping_destabilises_the_main_solution"),
    SeedNote("002", "(22), run-up", "balancing above p", "a slow run-up can leave the balls captured at about p",
             _V2 + "test_run_up_capture_and_synchronisation"),
    SeedNote("003", "Russian abstract", "на критических скоростях", "на закритических (supercritical)",
             _V3 + "test_supercritical_main_motions_need_support_damping"),
    SeedNote("003", "case 2a", "Me <= sum m_i l_i: main motions", "polygon inequality for every ball as well",
             _V3 + "test_dominating_pendulum_no_main_motion"),
    SeedNote("003", "second side motion, case ii", "this is the main motion",
             "a side motion (13) with nonzero deflection, the least unbalanced", _V3 + "test_dominating_pendulum_no_main_motion"),
    SeedNote("003", "(16)", "2 H~* = -omega^4 f / (c - M omega^2)", "plus the constant -omega^2 [J_O + sum J_Oi]",
             _V3 + "test_h_tilde_on_the_constraint_eq_16"),
    SeedNote("003", "case 1, (13)", "below omega_cr the first side motion is stable",
             "with support damping side motions vanish near p; none stable, no synchronisation",
             _V3 + "test_damping_removes_side_motions_below_p"),
    SeedNote("003", "conclusion 3, abstract, (5)", "supercritical: only the main motions are stable (d = 0)",
             "with d = 0 no steady motion is stable above omega_cr; with d > 0 only above omega*",
             _V3 + "test_supercritical_main_motions_need_support_damping"),
)  # fmt: skip
