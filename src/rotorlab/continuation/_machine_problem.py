"""Equilibria of an isotropic machine with balls in its co-rotating frame, as ``F(x, lam) = 0``.

The unknowns are the structure coordinates ``z`` and the ball angles ``psi`` of a co-rotating
state at rest (``x = (z, psi)``, velocities zero); the residual is the co-rotating accelerations
``(z'', psi'')`` of :meth:`rotorlab.models.Machine.rotating_rhs` (as
``rotorlab.analyses._machine_steady._equilibrium_near`` solves them). The continued parameters
are named (:func:`with_value`); each value builds the machine once (a small cache), and no
integrator is compiled: the residual and the exact eigenvalues (:meth:`Machine.linearize`) use the
machine's right-hand-side kernel only.

Starting points (:func:`starting_motions`) are the steady motions of seeds 002/003's
classification: the *balanced* (main) motions, ball angles that cancel the unbalance with the
structure at rest, and the *side* motions, every ball on the line of its race centre's
displacement, towards it (bit 0) or away from it (bit 1), 2^n of them; each is solved from its
classification's layout and labelled by where it converged.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from rotorlab._constants import RPM_PER_RAD_S

__all__ = ["NAMED_PARAMETERS", "as_machine", "with_value", "current_value", "parameter_unit", "format_value", "MachineEquilibria",
           "starting_motions", "START_KINDS"]

#: Parameters that set every ball at once (the stability chart's names): name -> (Ball field, unit).
NAMED_PARAMETERS = {"ball_mass": ("mass", "kg"), "ball_damping": ("damping", "N*m*s/rad")}

#: What ``start_from`` may name (besides a motion's label such as ``"side 01"``).
START_KINDS = ("balanced", "side", "all")


def _parse(model, name: str):
    """The setter and unit of parameter ``name`` of ``model`` (a Machine), or raise ValueError."""
    from rotorlab.models import ConstantSpeed

    if name == "drive.speed":  # a constant speed replaces any drive (steady motions need one)
        return (lambda m, v: m.with_drive(ConstantSpeed(v))), "rad/s"
    if name in NAMED_PARAMETERS:
        key, unit = NAMED_PARAMETERS[name]

        def every_ball(m, v):
            races = tuple(replace(r, balls=tuple(replace(b, **{key: v}) for b in r.balls)) for r in m.races)
            return replace(m, races=races)

        return every_ball, unit
    space = model.parameters  # the model's named parameters (rotorlab.models._protocol)
    if name not in space:
        shown = ", ".join(list(space.names)[:6])
        raise ValueError(f"{name!r} is not a continuation parameter of this machine; use drive.speed, "
                         f"{', '.join(NAMED_PARAMETERS)} or one of its named parameters ({shown}, ...)")
    if space.structural(name):
        raise ValueError(f"{name} is structural (a new value changes the compiled layout): it takes integer "
                         "values and cannot be continued")
    return (lambda m, v: m.with_parameters(**{name: v})), space[name].unit


def with_value(model, name: str, value: float):
    """Return ``model`` (a :class:`rotorlab.models.Machine`) with parameter ``name`` = ``value`` (SI).

    Names: ``drive.speed`` (rad/s; a constant speed replaces any drive), ``ball_mass`` /
    ``ball_damping`` (every ball, the stability chart's names), and every named parameter of the
    model (:attr:`Machine.parameters`: the case file's key paths ``races[i].balls[j].mass``,
    ``unbalances[i].magnitude``, ``structure.bearings[0].kxx`` ...), set with
    ``model.with_parameters``.

    Raises
    ------
    ValueError
        An unknown or structural name, or a value outside the parameter's range (its message).

    Examples
    --------
    >>> import numpy as np
    >>> from rotorlab.linear import LinearSystem
    >>> from rotorlab.models import Ball, BallRace, ConstantSpeed, Machine, Unbalance
    >>> s = LinearSystem(M=np.eye(4), C=0.02 * np.eye(4), G=np.zeros((4, 4)), K=np.eye(4))
    >>> m = Machine(s, races=(BallRace(0, 1.0, (Ball(0.02),) * 2),), unbalances=(Unbalance(0, 0.01),),
    ...             drive=ConstantSpeed(2.0))
    >>> [b.mass for b in with_value(m, "ball_mass", 0.03).races[0].balls]
    [0.03, 0.03]
    >>> with_value(m, "drive.speed", 3.0).drive.speed
    3.0
    """
    setter, _ = _parse(model, name)
    return setter(model, float(value))


def current_value(model, name: str) -> float:
    """The value (SI) of parameter ``name`` of ``model``; for ``ball_mass`` / ``ball_damping`` that of
    the first ball (ValueError if the balls differ: the name sets them all)."""
    _parse(model, name)  # known name, indices in range
    if name == "drive.speed":
        return float(model.drive.speed)
    if name in NAMED_PARAMETERS:
        key = NAMED_PARAMETERS[name][0]
        vals = {float(getattr(b, key)) for r in model.races for b in r.balls}
        if len(vals) != 1:
            raise ValueError(f"{name}: the balls differ ({', '.join(f'{v:g}' for v in sorted(vals))}); "
                             "it sets every ball: name one, races[i].balls[j]." + key)
        return vals.pop()
    return float(model.parameters[name].value)


def parameter_unit(model, name: str) -> str:
    """The SI unit of parameter ``name`` (raises ValueError for an unknown name)."""
    return _parse(model, name)[1]


def as_machine(model):
    """``model`` as a :class:`rotorlab.models.Machine`: a Machine itself, or the planar machine a
    :class:`rotorlab.models.JeffcottBalls` rotor is (one node, its translation modes only, one race
    of its balls, the disc's unbalance ``M1 e``; the same right-hand side, tests/unit/test_machine.py).

    Raises
    ------
    ValueError
        Another model, balls of different radii or with friction (no co-rotating equilibria).
    """
    from rotorlab.linear import LinearSystem
    from rotorlab.models import Ball, BallRace, JeffcottBalls, Machine, Unbalance

    if isinstance(model, Machine):
        return model
    if not isinstance(model, JeffcottBalls):
        raise ValueError(f"continuation of steady motions needs a machine with balls or a jeffcott_balls "
                         f"rotor, got {type(model).__name__}")
    r = model.rotor
    radii = {b.radius for b in model.balls}
    if len(radii) != 1:
        raise ValueError("the balls run on races of different radii: build the machine with one race per radius")
    if any(getattr(b, "friction", 0.0) > 0 for b in model.balls):
        raise ValueError("the balls have friction (stick-slip): steady motions are not equilibria of a smooth "
                         "system; simulate instead")
    radius = radii.pop()
    m1, c, d = r.disc_mass, r.stiffness, r.damping
    # the tilt of the single node carries nothing (n_modes = 2 keeps the translations: stiffer tilt)
    s = LinearSystem(M=np.diag([m1, m1, m1, m1]), C=np.diag([d, d, 0.0, 0.0]), G=np.zeros((4, 4)),
                     K=np.diag([c, c, 4.0 * c, 4.0 * c]))
    balls = tuple(Ball(b.mass, inertia=b.inertia - b.mass * radius ** 2, damping=b.damping) for b in model.balls)
    return Machine(s, races=(BallRace(0, radius, balls),), unbalances=(Unbalance(0, m1 * r.eccentricity),),
                   drive=model.speed, n_modes=2)


def format_value(value: float, unit: str) -> str:
    """A parameter value for people: rad/s as rpm, kg below 1 kg as g, else SI with its unit.

    >>> format_value(152.89, "rad/s"), format_value(0.0125, "kg"), format_value(0.002, "N*m*s/rad")
    ('1460 rpm', '12.5 g', '0.002 N*m*s/rad')
    """
    if unit == "rad/s":
        return f"{value * RPM_PER_RAD_S:.4g} rpm"
    if unit == "kg" and abs(value) < 1.0:
        return f"{value * 1e3:.4g} g"
    if unit == "rad":
        return f"{math.degrees(value):.4g} deg"
    return f"{value:.4g} {unit}"


class MachineEquilibria:
    """The residual, Jacobian and spectrum of a machine's co-rotating equilibria in named parameters.

    Parameters
    ----------
    machine : Machine
        Isotropic, constant speed, no lateral gravity, no ball friction (else ValueError with
        :meth:`Machine.why_no_rotating_frame`).
    names : sequence of str
        The continued parameters; ``u = (z, psi, p_1, ..., p_k)``.
    """

    def __init__(self, machine, names):
        machine = as_machine(machine)
        why = machine.why_no_rotating_frame()
        if why is not None:
            raise ValueError(f"no co-rotating equilibria to continue: {why}")
        if machine.n_balls == 0:
            raise ValueError("the machine has no balls: its only steady motion is the unbalance response")
        self.names = tuple(names)
        self.setters = [_parse(machine, n)[0] for n in self.names]
        self.units = {n: _parse(machine, n)[1] for n in self.names}
        self.base = machine
        self.nz, self.nb = machine.n_coordinates, machine.n_balls
        self.n = self.nz + self.nb
        u = sum(x.magnitude for x in machine.unbalances) + sum(r.capacity for r in machine.races)
        self.z_scale = max(u / max(machine.structure.total_mass, 1e-300), 1e-12)
        self._machines: dict[tuple[float, ...], object] = {}
        self._spectra: dict[bytes, np.ndarray] = {}

    # ------------------------------------------------------------------ building blocks
    def machine(self, values) -> object:
        key = tuple(float(v) for v in values)
        m = self._machines.get(key)
        if m is None:
            m = self.base
            for setter, v in zip(self.setters, key):
                m = setter(m, v)
            if m.layout == self.base.layout:  # the same compiled kernel: skip its look-up per value
                m._cache.setdefault("kernels", self.base.kernels)
            if len(self._machines) > 64:
                self._machines.clear()
            self._machines[key] = m
        return m

    def state(self, x) -> np.ndarray:
        """The co-rotating state at rest ``[z, 0, psi, 0]`` of ``x = (z, psi)``."""
        y = np.zeros(2 * self.n)
        y[:self.nz] = x[:self.nz]
        y[2 * self.nz:2 * self.nz + self.nb] = x[self.nz:self.n]
        return y

    def unknowns(self, y) -> np.ndarray:
        """``x = (z, psi)`` of a co-rotating state."""
        y = np.asarray(y, dtype=float)
        return np.concatenate([y[:self.nz], y[2 * self.nz:2 * self.nz + self.nb]])

    def scale(self, values) -> np.ndarray:
        """Typical sizes of ``u``: z by the unbalance over the mass, psi 1 rad, parameters their value."""
        p = [max(abs(float(v)), 1e-12) for v in values]
        return np.concatenate([np.full(self.nz, self.z_scale), np.ones(self.nb), p])

    def residual(self, u) -> np.ndarray:
        """The co-rotating accelerations ``(z'', psi'')`` at rest; NaN where a parameter value is
        refused by the model (a negative mass or damping: the corrector then shortens its step)."""
        u = np.asarray(u, dtype=float)
        try:
            m = self.machine(u[self.n:])
        except ValueError:
            return np.full(self.n, np.nan)
        f = m.rotating_rhs(self.state(u[:self.n]))
        return np.concatenate([f[self.nz:2 * self.nz], f[2 * self.nz + self.nb:]])

    def jacobian(self, u) -> np.ndarray:
        """``dF/du`` by central differences (steps 1e-6 of each unknown's scale)."""
        u = np.asarray(u, dtype=float)
        sc = self.scale(u[self.n:])
        cols = []
        for j in range(u.size):
            h = 1e-6 * (sc[j] if j < self.n else max(abs(u[j]), sc[j]))
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            cols.append((self.residual(up) - self.residual(um)) / (2.0 * h))
        return np.array(cols).T

    def linearization(self, u):
        u = np.asarray(u, dtype=float)
        return self.machine(u[self.n:]).linearize(self.state(u[:self.n]))

    def eigenvalues(self, u) -> np.ndarray:
        """Eigenvalues of the co-rotating linearization at ``u`` (cached)."""
        u = np.asarray(u, dtype=float)
        key = u.tobytes()
        ev = self._spectra.get(key)
        if ev is None:
            ev = self.linearization(u).eigenvalues
            if len(self._spectra) > 4096:
                self._spectra.clear()
            self._spectra[key] = ev
        return ev

    def amplitude(self, u) -> float:
        """The largest whirl radius of the structure's nodes (m)."""
        u = np.asarray(u, dtype=float)
        m = self.machine(u[self.n:])
        return float(np.max(m.station_amplitudes(m.rotating_to_fixed(self.state(u[:self.n])))))

    def hopf_test(self, u) -> float:
        """Zero where a pair of eigenvalues sums to zero: ``prod_{i<j} (lam_i + lam_j)``.

        The determinant of the bialternate product ``2A (.) I`` (Guckenheimer, Myers & Sturmfels
        1997; Kuznetsov 2004, sec. 10.2), evaluated from the eigenvalues: it changes sign where a
        complex pair crosses the imaginary axis (Hopf) or two real eigenvalues sum to zero (a
        neutral saddle, told apart after location). Returned as ``sign * |prod|**(1/N)`` over the
        N pairs, so that its size neither under- nor overflows.
        """
        ev = self.eigenvalues(u)
        i, j = np.triu_indices(ev.size, 1)
        s = ev[i] + ev[j]
        # conjugate pairs of factors multiply to |.|^2 > 0: the sign is that of the real factors
        real = np.abs(s.imag) <= 1e-12 * max(np.abs(ev).max(), 1e-300)
        sign = -1.0 if np.count_nonzero(s.real[real] < 0) % 2 else 1.0
        mag = np.abs(s)
        if np.any(mag == 0.0):
            return 0.0
        return float(sign * math.exp(float(np.mean(np.log(mag)))))

    def crossing_pair(self, u) -> complex | None:
        """The eigenvalue with positive imaginary part nearest the imaginary axis, or None."""
        ev = self.eigenvalues(u)
        big = max(np.abs(ev).max(), 1e-300)
        cx = ev[ev.imag > 1e-7 * big]
        if cx.size == 0:
            return None
        return complex(cx[np.argmin(np.abs(cx.real))])


def _distinct(found: list[np.ndarray], psi: np.ndarray, tol: float) -> bool:
    return not any(np.max(np.abs(np.angle(np.exp(1j * (psi - f))))) < tol for f in found)


def starting_motions(machine, which: str = "balanced", *, starts: int = 24, seed: int = 0) -> list[tuple[str, np.ndarray]]:
    """Steady motions of seeds 002/003's classification at the machine's speed: (label, co-rotating state).

    Parameters
    ----------
    machine : Machine
    which : str
        ``"balanced"`` (the main motions: ``main+``, ``main-``, ... from ``starts`` seeded least-squares
        solves of :meth:`Machine.balance_residual`), ``"side"`` (``side k_1...k_n``: ball i towards
        (0) or away from (1) its race centre's displacement, each solved from the layout on the
        balls-locked response and labelled by where it converged), ``"all"``, or one label.

    Returns
    -------
    list of (str, ndarray)
        Distinct motions (possibly none: no balanced state when the balls cannot cancel the
        unbalance).
    """
    from scipy.optimize import least_squares, root

    machine = as_machine(machine)
    prob = MachineEquilibria(machine, ())
    nz, nb = prob.nz, prob.nb
    out: list[tuple[str, np.ndarray]] = []
    if which in ("balanced", "all") or which.startswith("main"):
        scale = max(sum(u.magnitude for u in machine.unbalances), 1e-300)
        rng = np.random.default_rng(seed)
        found: list[np.ndarray] = []
        for _ in range(starts):
            res = least_squares(lambda a: machine.balance_residual(a) / scale, rng.uniform(0, 2 * np.pi, nb),
                                xtol=1e-15, ftol=1e-15, gtol=1e-15)
            psi = np.angle(np.exp(1j * res.x))
            if np.max(np.abs(res.fun)) < 1e-10 and _distinct(found, psi, 1e-6):
                found.append(psi)
        found.sort(key=lambda p: -p[0])
        for k, psi in enumerate(found):
            label = "main" + ("+-"[k] if len(found) == 2 else f" {k}")
            out.append((label, machine.balanced_state(psi)))
    if which in ("side", "all") or which.startswith("side"):
        om = float(machine.drive.speed)
        # the balls-locked static response to the unbalances (damping left out) as the layout's line
        K0 = machine.reduced["K"] - om * om * machine._m0()
        st = machine._stations
        f = np.zeros(nz)
        for u, un in enumerate(machine.unbalances):
            f += un.magnitude * (st[len(machine.races) + u].T @ np.array([math.cos(un.phase), math.sin(un.phase)]))
        zr = np.linalg.lstsq(K0, om * om * f, rcond=None)[0]
        heavy = np.linalg.lstsq(machine.reduced["K"], f, rcond=None)[0]  # the heavy side (quasi-static)
        race_of = machine._ball_arrays[4]
        seen: list[np.ndarray] = []
        for bits in range(2 ** nb):
            k = [(bits >> (nb - 1 - b)) & 1 for b in range(nb)]
            psi0 = []
            for b in range(nb):
                c = st[race_of[b]] @ zr
                psi0.append(math.atan2(c[1], c[0]) + math.pi * k[b])
            x0 = np.concatenate([zr, psi0])
            sol = root(lambda x: prob.residual(np.asarray(x)), x0, method="hybr", options={"xtol": 1e-13})
            if np.max(np.abs(prob.residual(sol.x))) > 1e-9 * prob.z_scale * max(1.0, om * om):
                continue
            y = prob.state(sol.x)
            if np.max(machine.station_amplitudes(machine.rotating_to_fixed(y))) < 1e-9 * prob.z_scale:
                continue  # a balanced state
            psi = sol.x[nz:]
            if not _distinct(seen, psi, 1e-6):
                continue
            seen.append(psi)
            out.append(("side " + "".join(str(b) for b in _side_bits(machine, y, heavy)), y))
    if which not in START_KINDS:
        out = [(lab, y) for lab, y in out if lab == which]
    return out


def _side_bits(machine, y, heavy) -> list[int]:
    """Per ball: 0 if it lies towards the heavy side at its race (the quasi-static deflection
    under the unbalances, seed 003's k_i = 0 of an undamped rotor), 1 if away from it."""
    nz = machine.n_coordinates
    race_of = machine._ball_arrays[4]
    st = machine._stations
    bits = []
    for b, r in enumerate(race_of):
        c = st[r] @ heavy
        psi = y[2 * nz + b]
        bits.append(0 if c[0] * math.cos(psi) + c[1] * math.sin(psi) >= 0 else 1)
    return bits
