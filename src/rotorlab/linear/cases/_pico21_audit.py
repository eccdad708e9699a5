"""Cross-check of the printed tables of seed 000 against each other (findings 1-7).

See :mod:`rotorlab.linear.cases._pico21` for the findings and their resolutions; this module
recomputes the evidence for each from the printed numbers in :mod:`._pico21_data`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorlab.linear.cases._pico21 import RESOLVED_COMPLIANCE
from rotorlab.linear.cases._pico21_data import (
    PRINTED_COMPLIANCE,
    PRINTED_ENERGY_IN_DISPLACEMENTS,
    PRINTED_PARAMETERS,
    PRINTED_STIFFNESS,
    PRINTED_STIFFNESS_COLUMN_LABELS,
)

__all__ = ["Finding", "audit_pico21", "energy_in_displacements_matrix"]

_X_PLANE = ("xi1", "psi1", "xi2", "psi2", "xi3", "psi3")
_Y_PLANE = ("eta1", "theta1", "eta2", "theta2", "eta3", "theta3")


@dataclass(frozen=True, slots=True)
class Finding:
    """One inconsistency of the printed data.

    Attributes
    ----------
    key : str
        Short identifier (``"compliance-digits"``, ...).
    printed : str
        What the paper prints.
    resolved : str
        What the case uses instead.
    evidence : str
        The redundancy that shows it, with the numbers recomputed here.
    measure : float
        Size of the discrepancy (a relative error or ratio, see ``evidence``); NaN for findings
        about the text.
    """

    key: str
    printed: str
    resolved: str
    evidence: str
    measure: float


def _rel(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.abs(a - b) / np.abs(b)


def energy_in_displacements_matrix(plane: str = "x") -> tuple[np.ndarray, dict]:
    """Rebuild the stiffness of one plane from the printed potential energy in displacements.

    Parameters
    ----------
    plane : {"x", "y"}
        Which half of the printed sum (xi/psi or eta/theta terms).

    Returns
    -------
    C : ndarray, shape (6, 6)
        ``C_ii = 2 c_ii`` and ``C_ij = c_ij`` from the printed coefficients; entries that were
        printed twice keep the *last* value.
    counts : dict
        ``{(i, j): number of printed terms}`` for i <= j (1 everywhere if nothing is missing or
        duplicated).
    """
    names = _X_PLANE if plane == "x" else _Y_PLANE
    C = np.zeros((6, 6))
    counts: dict = {}
    for coef, a, b in PRINTED_ENERGY_IN_DISPLACEMENTS:
        if a not in names or b not in names:
            continue
        i, j = sorted((names.index(a), names.index(b)))
        counts[(i, j)] = counts.get((i, j), 0) + 1
        if i == j:
            C[i, i] = 2.0 * coef
        else:
            C[i, j] = C[j, i] = coef
    return C, counts


def audit_pico21() -> tuple[Finding, ...]:
    """Recompute the evidence for every inconsistency of the seed's printed data.

    Returns
    -------
    tuple of Finding
        In the order of the module docstring of :mod:`rotorlab.linear.cases._pico21`.

    Examples
    --------
    >>> [f.key for f in audit_pico21()][:3]
    ['compliance-digits', 'stiffness-labels', 'energy-in-displacements']
    """
    out = []
    d, dr, K = PRINTED_COMPLIANCE, RESOLVED_COMPLIANCE, PRINTED_STIFFNESS
    bad = np.argwhere(_rel(d, dr) > 1e-8)
    l1 = PRINTED_PARAMETERS["l_1"][0] * 1e-3
    ident_printed = np.abs(d[0, 1::2] / d[1, 1::2] - l1).max() / l1
    ident_resolved = np.abs(dr[0, 1::2] / dr[1, 1::2] - l1).max() / l1
    inv_p = _rel(np.linalg.inv(d), K).max()
    inv_r = _rel(np.linalg.inv(dr), K).max()
    out.append(Finding(
        "compliance-digits",
        printed="delta(M1,M1) = delta(M1,M2) = delta(M1,M3) = 107.193778999e-5",
        resolved="107.1893779e-5 (from the printed energy quadratic form)",
        evidence=(f"entries {sorted({tuple(sorted(map(int, b))) for b in bad})} differ from the "
                  f"energy form by {_rel(d, dr).max():.1e}; delta(P1,M_k)/delta(M1,M_k) - l_1 is "
                  f"{ident_printed:.1e} (printed) vs {ident_resolved:.1e} (resolved); "
                  f"inv(delta) vs printed stiffness: max relative error {inv_p:.2f} (printed) vs "
                  f"{inv_r:.1e} (resolved; condition number {np.linalg.cond(dr):.1e})"),
        measure=float(inv_p)))
    odd = [j for j, lab in enumerate(PRINTED_STIFFNESS_COLUMN_LABELS[0])
           if lab != PRINTED_STIFFNESS_COLUMN_LABELS[1][j]]
    out.append(Finding(
        "stiffness-labels",
        printed="P1 = ... (xi3 + eta2) ... (psi3 + theta2)",
        resolved="(xi3 + eta3), (psi3 + theta3)",
        evidence=(f"columns {odd} of row P1 name eta2/theta2 where rows M1..M3 name eta3/theta3; "
                  f"K(P1,xi3)/K(P3,xi1) - 1 = {K[0, 4] / K[4, 0] - 1:.1e}, "
                  f"K(P1,psi3)/K(M3,xi1) - 1 = {K[0, 5] / K[5, 0] - 1:.1e}"),
        measure=float(len(odd))))
    Cx, nx = energy_in_displacements_matrix("x")
    Cy, ny = energy_in_displacements_matrix("y")
    Ks = 0.5 * (K + K.T)
    dup = sorted(k for k, v in nx.items() if v > 1)
    missing = sorted((i, j) for i in range(6) for j in range(i, 6) if (i, j) not in nx)
    ex = _rel(Cy[0, 0], Ks[0, 0])
    others = _rel(Cy, Ks)
    others[0, 0] = 0.0
    out.append(Finding(
        "energy-in-displacements",
        printed="1.2333251673e8 xi1^2 (and eta1^2); 16203.81435 psi2^2; 5.229315675e6 psi1 xi1",
        resolved="1.233251673e8 xi1^2; 16203.81435 psi3^2; 5.229315675e6 psi1 xi2",
        evidence=(f"x-plane terms printed twice: {dup}, missing: {missing}; the y-plane half has "
                  f"all 21 terms; its eta1^2 coefficient x 2 differs from K11 by {ex:.1e}, all "
                  f"its other coefficients agree with K to {others.max():.0e}"),
        measure=float(ex)))
    out.append(Finding(
        "kinetic-energy-gyroscopic",
        printed="T = sum of m (xi'^2 + eta'^2)/2 + I_A (psi'^2 + theta'^2)/2 + I_P gamma'^2/2",
        resolved="T keeps I_PA gamma' psi2' theta2 + I_PR gamma' psi3' theta3 (from T_2A, T_3R)",
        evidence=("expanding I_P (gamma' + psi' theta)^2 / 2 in T_2A and T_3R gives the "
                  "gyroscopic term that the total omits; the paper's Fig. 7, abstract and "
                  "conclusion 2 report speed-dependent frequencies, which need it"),
        measure=math.nan))
    m_s, i_s = PRINTED_PARAMETERS["m_S"][0], PRINTED_PARAMETERS["I_S"][0]
    rg_printed = math.sqrt(i_s * 1e-6 / m_s)
    rg_resolved = math.sqrt(i_s / m_s)
    out.append(Finding(
        "stator-inertia-units",
        printed="I_S = I_S0 = 0.018 kg mm^2",
        resolved="0.018 kg m^2",
        evidence=(f"radius of gyration of the 2.4 kg housing: {rg_printed * 1e3:.3f} mm as "
                  f"printed, {rg_resolved * 1e3:.1f} mm in kg m^2 (l = 86 mm)"),
        measure=rg_printed / (PRINTED_PARAMETERS["l"][0] * 1e-3)))
    ia, ia0 = PRINTED_PARAMETERS["I_A"][0], PRINTED_PARAMETERS["I_A0"][0]
    ir, ir0 = PRINTED_PARAMETERS["I_R"][0], PRINTED_PARAMETERS["I_R0"][0]
    out.append(Finding(
        "armature-inertia-pair",
        printed="I_A = 93 (diametral), I_A0 = 425 kg mm^2 (polar)",
        resolved="diametral 425, polar 93 kg mm^2",
        evidence=(f"polar / diametral = {ia0 / ia:.2f} > 2 is impossible for a rigid body; "
                  f"the rotor's pair gives {ir0 / ir:.2f} (a flat rotor); swapped, the "
                  f"armature gives {ia / ia0:.2f} (a slender cylinder)"),
        measure=ia0 / ia))
    out.append(Finding(
        "degrees-of-freedom",
        printed="14 degrees of freedom",
        resolved="12 lateral DOFs (xi, eta, psi, theta of 3 bodies); phi prescribed",
        evidence="the listed coordinates xi_i, eta_i, psi_i, theta_i (i = 1..3) and phi are 13",
        measure=math.nan))
    return tuple(out)
