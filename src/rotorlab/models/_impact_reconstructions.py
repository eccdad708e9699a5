"""The formulas of seed 001 garbled by the OCR and rebuilt from mechanics, as data (the report shows
them; the model's docstring, :mod:`rotorlab.models._impact_rotor`, explains them)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Reconstruction", "RECONSTRUCTIONS"]


@dataclass(frozen=True, slots=True)
class Reconstruction:
    """One formula of seed 001 garbled by the OCR and rebuilt from mechanics.

    Attributes
    ----------
    equation : str
        Equation number in the paper.
    printed : str
        What the OCR'd text shows.
    reconstructed : str
        The formula the model uses.
    check : str
        How it was checked.
    test : str
        The test that checks it.
    """

    equation: str
    printed: str
    reconstructed: str
    check: str
    test: str


#: The reconstructions documented in this module's docstring, as data (shown in the report).
RECONSTRUCTIONS = (
    Reconstruction(
        "(3.9)", "Sn = (1 + k)m* vp; 'sin^ ll_ m* m Ai''; '«+ = «p Sn m', 't+ = t1- Sn'",
        "S_n = (1 + k) m* v, 1/m* = sin^2(beta)/m + l_P^2/A1; u'+ = u'- - (S_n/m)(sin(beta) e + f e_perp), "
        "t'+ = t'- - (S_n/A1)(l_P e + f h_P e_perp)",
        "normal speed after = -k x before; elastic frictionless impacts conserve the Jacobi energy; "
        "restitution loss = sum 1/2 m* (1 - k^2) v^2",
        "tests/validation/test_impact_energy.py",
    ),
    Reconstruction(
        "(4.1)", "Fm = -c I ит + — {ит + x ит) ), ^о; м = -сЛ t + ^-(t + c¿¿0 xt) )+hmF",
        "F_m = -c (u_m + (gamma/w0)(u_m' + w0 x u_m)), u_m = u + n_m t; "
        "M_m = -c_* (t + (gamma/w0)(t' + w0 x t)) + n_m F_m",
        "sum over the two membranes gives c, n_m, c_*; rotating-frame solution = fixed-frame equations "
        "(viscous dampers c gamma/w0 on fixed membranes) integrated by scipy and rotated",
        "tests/validation/test_impact_frames.py",
    ),
    Reconstruction(
        "(4.3)", "dv/dT = r cos a - Ft, dr/dT = v cos a, Fn = Kv +2v + r sin a",
        "F_n = kappa v^2 + 2 v + r sin a, kappa = sin(a)/r on the logarithmic spiral",
        "frictionless guide: v_exit = sqrt(1 - r0^2) (stone's Jacobi integral); motor work = kinetic "
        "gain in the fixed frame + guide friction heat",
        "tests/validation/test_impact_stones.py",
    ),
    Reconstruction(
        "J(tau)", "J_x = F_n sin(phi + a) - [..] cos(phi + a), J_y = -F_n cos(phi + a) - [..] sin(phi + a)",
        "J_x = F_n sin(phi + a) + F_t cos(phi + a), J_y = -F_n cos(phi + a) + F_t sin(phi + a) "
        "(-F_n e_n + F_t e_t, Newton's third law)",
        "the torque of J on the rotor does the motor work = kinetic gain + friction heat; the printed "
        "sign of F_t gives 81 % too much",
        "tests/validation/test_impact_stones.py",
    ),
)
