"""Stability of the balanced state on anisotropic supports: a Floquet problem, continued in two parameters.

Support anisotropy (``support_anisotropy``, symbol ``a``): the relative difference of the two
directions' stiffness at a fixed mean, ``a = (k_yy - k_xx) / (k_xx + k_yy)``. The structure's
stiffness is scaled plane by plane: ``K_xx-plane (1 - a)``, ``K_yy-plane (1 + a)`` (every x-plane
and y-plane entry of ``K``; for a Jeffcott rotor, whose stiffness is its supports', exactly
``k_xx = k (1 - a)``, ``k_yy = k (1 + a)``); ``-1 < a < 1``, 0 is the isotropic machine. The mode
shapes of each plane do not change under such a scaling, so a machine with ``n_modes`` keeps the
isotropic machine's modes (x/y pairs), now exact modes of each plane.

The balanced state (structure at rest on the axis, every ball at its balancing angle, turning
with the rotor) is an exact motion whatever the anisotropy: a structure at rest feels no support
force. In the co-rotating frame (angle ``theta = Omega t``) the structure coordinates are
``u = R(-theta) z`` per x/y pair and the equations of the supports' stiffness become

    u'' = R(-theta) x''(R(theta) u, ...) - 2 Omega J u' + Omega^2 u,     psi'' = phi'',

with ``R(-theta) K R(theta) = K_mean + a Kbar (cos 2 theta S + sin 2 theta S J)`` (S = diag(-1, 1)
per pair): periodic with period ``T = pi / Omega``. The balanced state ``x0`` is an equilibrium of
it, and its linearization is exactly

    x' = A(t) x,   A(t) = A0 + Ac cos 2 Omega t + As sin 2 Omega t,

(the mass matrix at ``x0`` does not turn with theta in this frame: the balls rest there). ``A``
is found by central differences of the machine's compiled fixed-frame right-hand side
(:class:`_TurnedFrame`) at ``theta = 0, pi/4, pi/2``. The monodromy matrix ``Phi(T)`` is computed
by the fourth-order Magnus integrator (Blanes, Casas, Oteo & Ros 2009, eq. (253)) on ``n`` steps,
Richardson-extrapolated from ``n`` and ``2 n``; its eigenvalues are the Floquet multipliers.

The stability boundary is the zero set of the largest Floquet exponent
``g(Omega, a) = log max |mu| / T`` (1/s; at ``a = 0`` exactly the largest real part of the
co-rotating eigenvalues, so the boundary meets the isotropic Hopf point there), one equation in
two unknowns continued by :func:`rotorlab.continuation.continue_curve`. Each point is labelled by
where its critical multiplier leaves the unit circle: ``"+1"``, ``"-1"`` (period doubling: a
parametric resonance of the turning stiffness) or ``"complex"`` (Neimark-Sacker: a torus).

References
----------
Blanes S., Casas F., Oteo J.A., Ros J., The Magnus expansion and some of its applications,
Physics Reports 470 (2009) 151-238. Kuznetsov Yu.A., Elements of Applied Bifurcation Theory,
3rd ed., Springer 2004, sec. 1.5 (multipliers).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

__all__ = ["ANISOTROPY", "with_anisotropy", "BalancedFloquet", "floquet_boundary", "anisotropy_curves"]

ANISOTROPY = "support_anisotropy"


def with_anisotropy(machine, a: float):
    """``machine`` (isotropic) with its supports' anisotropy ``a = (k_yy - k_xx) / (k_xx + k_yy)``."""
    a = float(a)
    if not -1.0 < a < 1.0 or not math.isfinite(a):
        raise ValueError(f"{ANISOTROPY} = {a:g}: the relative stiffness difference must lie in (-1, 1)")
    s = machine.structure
    if not s.is_isotropic:
        raise ValueError(f"{ANISOTROPY} is measured from an isotropic machine: this one's supports already differ")
    if a == 0.0:
        return machine
    xp, yp = s.plane_indices
    k = np.array(s.K, dtype=float)
    k[np.ix_(xp, xp)] *= 1.0 - a
    k[np.ix_(yp, yp)] *= 1.0 + a
    out = replace(machine, structure=replace(s, K=k))
    out._cache["basis"] = machine.basis  # each plane's modes are unchanged (x/y pairs)
    if out.layout == machine.layout:
        out._cache.setdefault("kernels", machine.kernels)
    return out


class _TurnedFrame:
    """The co-rotating right-hand side of an (anisotropic) machine at frame angle ``theta``."""

    def __init__(self, machine, speed: float):
        lay = machine.layout
        self.om = float(speed)
        self.nz, self.nb, self.i_phi, self.i_w = lay.n_z, lay.n_balls, lay.i_phi, lay.i_w
        self.n_state = lay.n_state
        self.p = machine.to_array()
        self.kernel = machine.kernels.rhs
        nz, nb = self.nz, self.nb
        self.steps = np.repeat([machine._fd_step(j, self.om) for j in (0, nz, 2 * nz)], [nz, nz, 2 * nb])

    @staticmethod
    def _turn(a: np.ndarray, c: float, s: float) -> np.ndarray:
        out = np.empty_like(a)
        out[..., 0::2] = c * a[..., 0::2] - s * a[..., 1::2]
        out[..., 1::2] = s * a[..., 0::2] + c * a[..., 1::2]
        return out

    def rhs_many(self, yr: np.ndarray, theta: float) -> np.ndarray:
        nz, nb, om = self.nz, self.nb, self.om
        c, s = math.cos(theta), math.sin(theta)
        z, v = yr[:, :nz], yr[:, nz:2 * nz]
        jz = np.empty_like(z)
        jz[:, 0::2], jz[:, 1::2] = -z[:, 1::2], z[:, 0::2]
        y = np.zeros((yr.shape[0], self.n_state))
        y[:, :nz] = self._turn(z, c, s)
        y[:, nz:2 * nz] = self._turn(v + om * jz, c, s)
        y[:, self.i_phi:self.i_phi + nb] = yr[:, 2 * nz:2 * nz + nb] + theta
        y[:, self.i_w:self.i_w + nb] = yr[:, 2 * nz + nb:] + om
        f = np.empty_like(y)
        for k in range(y.shape[0]):
            self.kernel(theta / om, y[k], self.p, f[k])
        jv = np.empty_like(v)
        jv[:, 0::2], jv[:, 1::2] = -v[:, 1::2], v[:, 0::2]
        out = np.empty_like(yr)
        out[:, :nz] = v
        out[:, nz:2 * nz] = self._turn(f[:, nz:2 * nz], c, -s) - 2.0 * om * jv + om * om * z
        out[:, 2 * nz:2 * nz + nb] = yr[:, 2 * nz + nb:]
        out[:, 2 * nz + nb:] = f[:, self.i_w:self.i_w + nb]
        return out

    def matrix(self, yr: np.ndarray, theta: float) -> np.ndarray:
        """Jacobian at ``yr``: fourth-order central differences (the steps of Machine.linearize)."""
        n = yr.size
        e = np.diag(self.steps)
        f = self.rhs_many(np.concatenate([yr + e, yr - e, yr + 2 * e, yr - 2 * e]), theta)
        f1, f2 = f[:n] - f[n:2 * n], f[2 * n:3 * n] - f[3 * n:]
        return ((8.0 * f1 - f2) / (12.0 * self.steps[:, None])).T


def _magnus4(a0, ac, as_, om: float, steps: int) -> np.ndarray:
    """``Phi(pi / Omega)`` of ``x' = (a0 + ac cos 2 Omega t + as sin 2 Omega t) x``, Magnus order 4
    (two Gauss points per step: ``Omega_k = h (A1 + A2) / 2 + sqrt(3) h^2 [A2, A1] / 12``)."""
    h = math.pi / om / steps
    g = 0.5 - math.sqrt(3.0) / 6.0
    k = np.arange(steps)

    def at(t):
        return a0 + ac * np.cos(2 * om * t)[:, None, None] + as_ * np.sin(2 * om * t)[:, None, None]

    a1, a2 = at((k + g) * h), at((k + 1.0 - g) * h)
    e = _expm_many(0.5 * h * (a1 + a2) + (math.sqrt(3.0) / 12.0) * h * h * (a2 @ a1 - a1 @ a2))
    phi = np.eye(a0.shape[0])
    for ek in e:
        phi = ek @ phi
    return phi


def _expm_many(a: np.ndarray) -> np.ndarray:
    """``exp`` of each matrix of ``a`` (shape (k, n, n)): scaling and squaring of the Taylor series
    to order 12 (after scaling every norm is at most 1/4: truncation below 1e-16 of the sum)."""
    norm = float(np.abs(a).sum(axis=2).max())
    s = max(0, math.ceil(math.log2(norm / 0.25))) if norm > 0 else 0
    b = a / 2.0 ** s
    out = np.broadcast_to(np.eye(a.shape[1]), a.shape).copy()
    term = out.copy()
    for j in range(1, 13):
        term = term @ b / j
        out += term
    for _ in range(s):
        out = out @ out
    return out


class BalancedFloquet:
    """The Floquet multipliers of a machine's balanced state in (speed, support anisotropy).

    Parameters
    ----------
    machine : Machine
        Isotropic supports, balls, constant speed (the speed is replaced by each point's).
    steps : int
        Magnus steps per period (the monodromy is extrapolated from ``steps`` and ``2 steps``).
    """

    def __init__(self, machine, steps: int = 48):
        from rotorlab.continuation._machine_problem import as_machine, starting_motions

        machine = as_machine(machine)
        self.base = machine
        self.steps = int(steps)
        balanced = starting_motions(machine, "balanced")
        if not balanced:
            raise ValueError("the machine has no balanced state (its balls cannot cancel the unbalance)")
        self.label, state = balanced[0][0], balanced[0][1]
        self.state = np.array(state, dtype=float)
        self.state[:2 * machine.n_coordinates] = 0.0  # exactly at rest on the axis
        self.state[2 * machine.n_coordinates + machine.n_balls:] = 0.0
        self._cache: dict[tuple[float, float], tuple] = {}
        self._poly = self._fit()

    def _fit(self):
        """``A0 = P0 + Omega P1 + Omega^2 P2 + a B0``, ``Ac = a Bc``, ``As = a Bs`` (the speed enters the
        co-rotating linearization about the balanced state through Coriolis, centrifugal and gyroscopic
        terms only; the anisotropy through the turning stiffness, linear in ``a`` and independent of the
        speed) from direct evaluations at three speeds, checked at a fourth speed and anisotropy; None
        (direct evaluation each time) where the check fails by more than 1e-9 of the entries."""
        s = abs(float(self.base.drive.speed)) or 1.0
        ws = np.array([0.5 * s, s, 2.0 * s])
        iso = np.array([self.direct(w, 0.0)[0] for w in ws])
        p = np.linalg.solve(np.vander(ws, 3, increasing=True), iso.reshape(3, -1)).reshape(iso.shape)
        b = [(x - y) / 0.5 for x, y in zip(self.direct(s, 0.5), (iso[1], 0.0, 0.0))]
        fit = (p, b)
        w, a = 1.37 * s, -0.3
        ref = self.direct(w, a)
        big = max(np.abs(ref[0]).max(), 1e-300)
        if max(np.abs(x - y).max() for x, y in zip(self._from_fit(fit, w, a), ref)) > 1e-9 * big:
            return None
        return fit

    @staticmethod
    def _from_fit(fit, speed: float, a: float):
        p, (b0, bc, bs) = fit
        return p[0] + speed * p[1] + speed * speed * p[2] + a * b0, a * bc, a * bs

    def system(self, speed: float, a: float):
        """``(A0, Ac, As)`` of the co-rotating linearization at ``speed`` (rad/s) and anisotropy ``a``."""
        if self._poly is not None:
            return self._from_fit(self._poly, float(speed), float(a))
        return self.direct(speed, a)

    def direct(self, speed: float, a: float):
        """:meth:`system` by central differences of the machine's right-hand side at ``theta = 0,
        pi/4, pi/2`` (the machine built at ``speed`` and ``a``)."""
        from rotorlab.models import ConstantSpeed

        m = with_anisotropy(self.base.with_drive(ConstantSpeed(float(speed))), a)
        fr = _TurnedFrame(m, speed)
        x0 = self.state
        m0, m1, m2 = (fr.matrix(x0, th) for th in (0.0, math.pi / 4, math.pi / 2))
        a0 = 0.5 * (m0 + m2)
        return a0, 0.5 * (m0 - m2), m1 - a0

    def monodromy(self, speed: float, a: float) -> np.ndarray:
        a0, ac, as_ = self.system(speed, a)
        p1 = _magnus4(a0, ac, as_, speed, self.steps)
        p2 = _magnus4(a0, ac, as_, speed, 2 * self.steps)
        return p2 + (p2 - p1) / 15.0

    def multipliers(self, speed: float, a: float) -> np.ndarray:
        """Floquet multipliers over ``T = pi / speed``, largest modulus first (cached)."""
        key = (float(speed), float(a))
        mu = self._cache.get(key)
        if mu is None:
            mu = np.linalg.eigvals(self.monodromy(speed, a))
            mu = mu[np.argsort(-np.abs(mu), kind="stable")]
            if len(self._cache) > 256:
                self._cache.clear()
            self._cache[key] = mu
        return mu

    def exponent(self, speed: float, a: float) -> float:
        """The largest Floquet exponent ``log max|mu| / T`` (1/s): < 0 where the balanced state is stable."""
        return math.log(abs(self.multipliers(speed, a)[0])) * speed / math.pi


def crossing_type(mu: complex, tol: float = 1e-3) -> str:
    """Where the critical multiplier ``mu`` leaves the unit circle: ``"+1"``, ``"-1"`` or ``"complex"``."""
    arg = abs(math.atan2(mu.imag, mu.real))
    return "+1" if arg < tol else "-1" if math.pi - arg < tol else "complex"


class _LeftRange(Exception):
    """The boundary curve left the speed range (raised from ``on_point``)."""


def floquet_boundary(model, start: float, stop: float, start2: float, stop2: float, *, grid: int = 65,
                     steps: int = 48, settings=None) -> tuple:
    """The stability boundaries of the balanced state in (speed, support anisotropy).

    Each boundary speed found on a grid of ``grid`` speeds over ``[start, stop]`` (rad/s) on the line
    ``a = a_0`` (0 if in ``[start2, stop2]``, else the end nearer 0), and on the lines at both ends
    of the anisotropy range (tongues of parametric resonance that do not reach ``a_0``), is located
    (Brent, 1e-12) and continued both ways in ``a`` until the curve leaves the rectangle.

    Returns
    -------
    tuple of TwoParameterCurve
        ``type == "floquet-boundary"``, ``parameters == ("drive.speed", "support_anisotropy")``,
        ``crossing``: ``"+1"``, ``"-1"`` or ``"complex"`` per point, ``frequency``: the critical
        multiplier's angle over the period, ``|arg mu| Omega / pi`` (rad/s, in ``[0, Omega]``: the
        co-rotating frequency modulo ``2 Omega``, up to sign; 0 or ``Omega`` for a real multiplier).
    """
    return boundaries(BalancedFloquet(model, steps=steps), start, stop, start2, stop2, grid=grid, settings=settings)


def boundaries(bf, start: float, stop: float, start2: float, stop2: float, *, grid: int = 65,
               settings=None) -> tuple:
    """:func:`floquet_boundary` of any periodic linear system ``bf`` in two parameters ``(w, a)``:
    ``bf.multipliers(w, a)`` (largest modulus first), ``bf.exponent(w, a)`` (< 0: stable),
    ``bf.label`` and ``bf.state`` (what the curves carry); ``w`` plays the speed (> 0: the
    frequency of a curve is ``|arg mu| w / pi``), ``a`` the anisotropy (in (-1, 1)).
    ``tests/unit/test_continuation_anisotropy.py`` runs it on the damped Mathieu equation, whose
    boundaries carry both real labels."""
    from scipy.optimize import brentq

    from rotorlab.continuation._core import ContinuationSettings, continue_curve
    from rotorlab.continuation._two_parameter import TwoParameterCurve

    lo, hi = sorted((float(start), float(stop)))
    lo2, hi2 = sorted((float(start2), float(stop2)))
    if not 0.0 < lo < hi or not -1.0 < lo2 <= hi2 < 1.0:
        raise ValueError(f"speed x {ANISOTROPY}: speeds {lo:g} to {hi:g} rad/s (> 0) and anisotropies "
                         f"{lo2:g} to {hi2:g} (within (-1, 1)) needed")
    a0 = min(max(0.0, lo2), hi2)
    scale = np.array([hi - lo, max(hi2 - lo2, 1e-3)])
    base = settings or ContinuationSettings(ds=0.02, ds_min=1e-6, ds_max=0.1, max_points=300, newton_tol=1e-9,
                                            chord=True)

    def residual(u):
        if not (0.5 * lo < u[0] and -1.0 < u[1] < 1.0):
            return np.array([np.nan])
        return np.array([bf.exponent(u[0], u[1])])

    curves: list = []
    for line in dict.fromkeys((a0, lo2, hi2)):
        ws = np.linspace(lo, hi, grid)
        g = np.array([bf.exponent(w, line) for w in ws])
        for k in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
            w0 = brentq(lambda w: bf.exponent(w, line), ws[k], ws[k + 1], xtol=1e-12 * hi, rtol=1e-14)
            if any(_on_curve(c.values, w0, line, scale) for c in curves):
                continue
            halves, ends = [], []
            for direction in (-1, 1):
                if (direction < 0 and line <= lo2) or (direction > 0 and line >= hi2):
                    continue
                kept: list = []

                def keep(p):
                    kept.append(p.u.copy())
                    if not lo <= p.u[0] <= hi:
                        raise _LeftRange

                st = ContinuationSettings(**{**base.__dict__, "bounds": (lo2, hi2), "direction": direction})
                try:
                    c = continue_curve(residual, np.array([w0, line]), scale=scale, settings=st, tests={},
                                       on_point=keep)
                    ends.append(c.end)
                except _LeftRange:
                    ends.append("speed-bound")
                u = np.array(kept)
                halves.append(u if direction > 0 else u[::-1])
            u = np.concatenate([halves[0], halves[1][1:]]) if len(halves) == 2 else halves[0]
            u = u[(u[:, 0] >= lo) & (u[:, 0] <= hi)]
            mus = [bf.multipliers(w, a)[0] for w, a in u]
            curves.append(TwoParameterCurve(
                type="floquet-boundary", parameters=("drive.speed", ANISOTROPY), values=u,
                states=np.repeat(bf.state[None, :], len(u), axis=0),
                frequency=np.array([abs(math.atan2(m.imag, m.real)) * w / math.pi for m, (w, _) in zip(mus, u)]),
                label=bf.label, end="/".join(ends), crossing=tuple(crossing_type(m) for m in mus)))
    return tuple(curves)


def _on_curve(values: np.ndarray, w: float, a: float, scale: np.ndarray) -> bool:
    """Whether a found curve passes through ``(w, a)`` (within 1e-6 of the rectangle)."""
    d = np.abs((values - [w, a]) / scale).max(axis=1)
    return bool(d.min() < 1e-6)


_CROSSING_WORDS = {"+1": "a real multiplier through +1",
                   "-1": "a multiplier through -1 (period doubling: a parametric resonance with the turning supports)",
                   "complex": "a complex pair of multipliers (Neimark-Sacker: a second frequency, a torus)"}


def boundary_findings(model, curves, start: float, stop: float, start2: float, stop2: float) -> tuple[str, ...]:
    """Sentences for people: up to which anisotropy the balanced state is stable at the top speed of
    the range and 1/4, 1/2, 3/4 of the way down (read off the boundary ``curves`` where they cross
    those speeds); the speeds where it is unstable already at the range's anisotropy nearest 0; and
    where each boundary curve begins and ends."""
    from rotorlab._constants import RPM_PER_RAD_S

    bf = BalancedFloquet(model, steps=24)
    lo2, hi2 = sorted((float(start2), float(stop2)))
    side = 1.0 if abs(hi2) >= abs(lo2) else -1.0
    reach = hi2 if side > 0 else lo2
    out, unstable = [], []
    a0 = min(max(0.0, lo2), hi2)
    lo, hi = sorted((float(start), float(stop)))
    for w in hi - (hi - lo) * np.array([0.0, 0.25, 0.5, 0.75]):  # the top speed first
        rpm = f"{w * RPM_PER_RAD_S:.4g} rpm"
        if bf.exponent(w, a0) >= 0.0:
            unstable.append(rpm)
            continue
        hits = []
        for c in curves:
            v = c.values
            for k in np.flatnonzero((v[:-1, 0] - w) * (v[1:, 0] - w) <= 0.0):
                if v[k, 0] == v[k + 1, 0]:
                    continue
                t = (w - v[k, 0]) / (v[k + 1, 0] - v[k, 0])
                a = v[k, 1] + t * (v[k + 1, 1] - v[k, 1])
                if (a - a0) * side > 0:
                    hits.append((abs(a - a0), a, c.crossing[k] if c.crossing else "complex"))
        if not hits:
            out.append(f"balancing is stable for every support anisotropy from {a0:.3g} to {reach:.3g} at {rpm}")
            continue
        _, a, kind = min(hits)
        out.append(f"balancing is stable for support anisotropy below {abs(a):.3g} at {rpm} "
                   f"((k_yy - k_xx) / (k_xx + k_yy); stiffness ratio {max((1 + a) / (1 - a), (1 - a) / (1 + a)):.3g}), "
                   f"lost through {_CROSSING_WORDS[kind]}")
    if unstable:
        out.append(f"at {', '.join(unstable)} the balanced state is unstable already at support anisotropy {a0:.3g}")
    for c in curves:
        (w1, a1), (w2, a2) = c.values[0], c.values[-1]
        out.append(f"a stability boundary of the balanced state runs from {w1 * RPM_PER_RAD_S:.4g} rpm at support "
                   f"anisotropy {a1:.3g} to {w2 * RPM_PER_RAD_S:.4g} rpm at {a2:.3g}")
    return tuple(out)


def anisotropy_curves(model, result, parameter: str, start: float, stop: float, parameter2: str, start2: float,
                      stop2: float):
    """The second-parameter step of :func:`rotorlab.continuation.continue_equilibria` for
    ``support_anisotropy``: the balanced state's Floquet boundaries, their findings and a note."""
    if parameter != "drive.speed":
        raise ValueError(f"{ANISOTROPY} is continued against drive.speed only (the balanced state's stability "
                         f"boundary in speed x anisotropy), not against {parameter}")
    curves = floquet_boundary(model, start, stop, start2, stop2)
    note = ("support anisotropy: only the balanced state (rotor at rest on the axis) is followed; its stability on "
            "anisotropic supports is a Floquet problem (period pi/Omega in the co-rotating frame); the other "
            "steady motions are not continued in the anisotropy")
    return curves, boundary_findings(model, curves, start, stop, start2, stop2), note


def anisotropy_chart(model, speeds, values) -> tuple[np.ndarray, np.ndarray]:
    """The grid chart under the curves: ``(stable, exists)``, shape (values, speeds), of the balanced
    state (its largest Floquet exponent < 0; it exists everywhere the isotropic machine's does)."""
    bf = BalancedFloquet(model, steps=16)
    stable = np.array([[bf.exponent(float(w), float(a)) < 0.0 for w in speeds] for a in values])
    return stable, np.ones_like(stable)
