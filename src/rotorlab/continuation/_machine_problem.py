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
from rotorlab.continuation._anisotropic import ANISOTROPY, with_anisotropy
from rotorlab.continuation._frame import _Frame

__all__ = ["NAMED_PARAMETERS", "as_machine", "smooth_part_note", "with_value", "current_value", "parameter_unit", "format_value", "MachineEquilibria",
           "starting_motions", "START_KINDS"]

#: Parameters that set every ball at once (the stability chart's names): name -> (Ball field, unit,
#: the Ball fields scaled in proportion). ``ball_mass_scaled_damping`` keeps each ball's damping per
#: unit mass (Rodrigues et al. 2008 hold ``c_b = b / (m Omega_1 R^2)`` fixed as m varies, Fig. 5).
NAMED_PARAMETERS = {"ball_mass": ("mass", "kg", ()), "ball_damping": ("damping", "N*m*s/rad", ()),
                    "ball_mass_scaled_damping": ("mass", "kg", ("damping",))}

#: What ``start_from`` may name (besides a motion's label such as ``"side 01"``).
START_KINDS = ("balanced", "side", "all")


def _parse(model, name: str):
    """The setter and unit of parameter ``name`` of ``model`` (a Machine), or raise ValueError."""
    from rotorlab.models import ConstantSpeed

    if name == "drive.speed":  # a constant speed replaces any drive (steady motions need one)
        return (lambda m, v: m.with_drive(ConstantSpeed(v))), "rad/s"
    if name == ANISOTROPY:  # (k_yy - k_xx) / (k_xx + k_yy) from the isotropic machine
        return with_anisotropy, "1"
    if name in NAMED_PARAMETERS:
        key, unit, scaled = NAMED_PARAMETERS[name]

        def one(b, v):
            old = float(getattr(b, key))
            ratio = v / old if old != 0.0 else math.nan
            if scaled and not math.isfinite(ratio):
                raise ValueError(f"{name}: a ball of {key} 0 cannot scale its {', '.join(scaled)}")
            return replace(b, **{key: v}, **{f: getattr(b, f) * ratio for f in scaled})

        def every_ball(m, v):
            races = tuple(replace(r, balls=tuple(one(b, v) for b in r.balls)) for r in m.races)
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

    Names: ``drive.speed`` (rad/s; a constant speed replaces any drive), ``support_anisotropy``
    (``(k_yy - k_xx) / (k_xx + k_yy)`` at a fixed mean, from an isotropic machine:
    :func:`rotorlab.continuation.with_anisotropy`), ``ball_mass`` /
    ``ball_damping`` (every ball, the stability chart's names), ``ball_mass_scaled_damping``
    (every ball's mass, its damping scaled in proportion: damping per unit mass fixed), and every named parameter of the
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
    if name == ANISOTROPY:
        return 0.0  # measured from the isotropic machine (with_anisotropy refuses any other)
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
    """``model`` as a :class:`rotorlab.models.Machine` without ball friction: a Machine itself, or the
    planar machine a :class:`rotorlab.models.JeffcottBalls` rotor is (its preset
    :attr:`~rotorlab.models.JeffcottBalls.machine`: one node, its translations only, one race of
    its balls, the disc's unbalance ``M1 e``; the same right-hand side). Balls with Coulomb or rolling friction lose it: the smooth part
    of the model (:func:`smooth_part_note` says so).

    Raises
    ------
    ValueError
        Another model.
    """
    from rotorlab.models import JeffcottBalls, Machine

    if isinstance(model, JeffcottBalls):
        model = model.machine
    if not isinstance(model, Machine):
        raise ValueError(f"continuation of steady motions needs a machine with balls or a jeffcott_balls "
                         f"rotor, got {type(model).__name__}")
    if not model.has_friction:
        return model
    races = tuple(replace(r, balls=tuple(replace(b, coulomb=0.0, rolling=0.0) for b in r.balls))
                  for r in model.races)
    return replace(model, races=races)


def smooth_part_note(model) -> str:
    """What a continuation of ``model``'s steady motions computed when its balls have friction
    (empty if they have none): the steady motions of its smooth part, ball friction left out.

    In a steady motion of the co-rotating frame every ball rests on its race, so the stick-slip
    law's only smooth branch there is sticking with the torque it needs: none, where the smooth
    part is in equilibrium. Each equilibrium found is therefore also a steady motion of the model
    with friction (its balls stuck, within any friction cone); its eigenvalues, and so the
    stability labels, are those of the smooth part (a stuck ball resists small disturbances that
    these eigenvalues let it follow; stick-slip is not smooth, and no periodic orbit of it is
    continued).
    """
    from rotorlab.models import Machine

    if isinstance(model, Machine):
        rough = model.has_friction
    else:
        rough = any(getattr(b, "friction", 0.0) > 0 for b in getattr(model, "balls", ()))
    if not rough:
        return ""
    return ("the balls' Coulomb and rolling friction is left out: these are the steady motions of the smooth "
            "part of the model (each is also a steady motion with friction, its balls stuck with no friction "
            "torque needed); eigenvalues and stability labels are the smooth part's, not those of stick-slip")


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


def _refuse_anisotropy(machine, name: str, setter) -> None:
    """ValueError if changing ``name`` makes the supports anisotropic: an anisotropic machine has no
    co-rotating equilibria to continue (only the balanced state's stability, in speed x
    ``support_anisotropy``: :func:`rotorlab.continuation.floquet_boundary`)."""
    if name == "drive.speed":
        return
    if name != ANISOTROPY:
        value = current_value(machine, name)
        for probe in (value * (1.0 + 1e-3), value + 1.0):  # relative, and absolute where it is 0
            try:
                other = setter(machine, probe)
            except ValueError:
                continue  # a value the parameter refuses: nothing to learn about isotropy
            if not other.structure.is_isotropic:
                break
        else:
            return
    raise ValueError(
        f"{name} makes the supports anisotropic (x and y differ): the machine's equations in the co-rotating "
        "frame then depend on time (the supports turn against it, twice per revolution), so its steady motions "
        "are periodic there and their stability is a Floquet problem. The balanced state (rotor at rest on the "
        "axis) persists whatever the anisotropy: its stability boundary in speed x support_anisotropy "
        "((k_yy - k_xx) / (k_xx + k_yy) at a fixed mean) is continued by `rotorlab continue CASE --param "
        "drive.speed=A:B --param2 support_anisotropy=A:B` (rotorlab.continuation.floquet_boundary). Not "
        "implemented: the other steady motions (side motions, the forced periodic motions with the rotor "
        "off-centre, solved by shooting with their Floquet multipliers), folds or Hopf points continued in "
        "an anisotropy, and anisotropy set through one bearing's stiffness; simulate those instead (rotorlab "
        "run or basin with the supports' stiffnesses set)")


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
        for name, setter in zip(self.names, self.setters):
            _refuse_anisotropy(machine, name, setter)
        self.units = {n: _parse(machine, n)[1] for n in self.names}
        self.base = machine
        self.nz, self.nb = machine.n_coordinates, machine.n_balls
        self.n = self.nz + self.nb
        u = sum(x.magnitude for x in machine.unbalances) + sum(r.capacity for r in machine.races)
        self.z_scale = max(u / max(machine.structure.total_mass, 1e-300), 1e-12)
        self._machines: dict[tuple[float, ...], object] = {}
        self._frames: dict[tuple[float, ...], _Frame] = {}
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
                self._frames.clear()
            self._machines[key] = m
        return m

    def frame(self, values) -> _Frame:
        """The co-rotating right-hand side of the machine at parameter ``values`` (cached)."""
        key = tuple(float(v) for v in values)
        fr = self._frames.get(key)
        if fr is None:
            fr = self._frames[key] = _Frame(self.machine(key))
        return fr

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
            fr = self.frame(u[self.n:])
        except ValueError:
            return np.full(self.n, np.nan)
        return self._accelerations(fr, u[None, :self.n])[0]

    def _accelerations(self, fr, xs: np.ndarray) -> np.ndarray:
        """``(z'', psi'')`` at rest at each row ``x = (z, psi)`` of ``xs`` (one batched call)."""
        nz, nb = self.nz, self.nb
        ys = np.zeros((xs.shape[0], 2 * self.n))
        ys[:, :nz] = xs[:, :nz]
        ys[:, 2 * nz:2 * nz + nb] = xs[:, nz:self.n]
        f = fr.rhs_many(ys)
        return np.concatenate([f[:, nz:2 * nz], f[:, 2 * nz + nb:]], axis=1)

    def jacobian(self, u) -> np.ndarray:
        """``dF/du`` by central differences (steps 1e-6 of each unknown's scale; the state's
        columns from one batched call of the right-hand side)."""
        u = np.asarray(u, dtype=float)
        sc = self.scale(u[self.n:])
        n = self.n
        try:
            fr = self.frame(u[n:])
        except ValueError:
            return np.full((n, u.size), np.nan)
        h = 1e-6 * sc[:n]
        shift = np.diag(h)
        f = self._accelerations(fr, np.concatenate([u[:n] + shift, u[:n] - shift]))
        cols = list(((f[:n] - f[n:]) / (2.0 * h[:, None])))
        for j in range(n, u.size):
            h = 1e-6 * max(abs(u[j]), sc[j])
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            cols.append((self.residual(up) - self.residual(um)) / (2.0 * h))
        return np.array(cols).T

    def linearization(self, u):
        u = np.asarray(u, dtype=float)
        return self.machine(u[self.n:]).linearize(self.state(u[:self.n]))

    def matrix(self, u) -> np.ndarray:
        """The co-rotating linearization's matrix at ``u`` (that of :meth:`linearization`)."""
        u = np.asarray(u, dtype=float)
        return self.frame(u[self.n:]).matrix(self.state(u[:self.n]))

    def eigenvalues(self, u) -> np.ndarray:
        """Eigenvalues of the co-rotating linearization at ``u`` (cached)."""
        u = np.asarray(u, dtype=float)
        key = u.tobytes()
        ev = self._spectra.get(key)
        if ev is None:
            ev = np.linalg.eigvals(self.matrix(u))
            if len(self._spectra) > 4096:
                self._spectra.clear()
            self._spectra[key] = ev
        return ev

    def eigen_triplet(self, u, near: complex, previous=None) -> tuple[complex, np.ndarray, np.ndarray]:
        """The eigenvalue of the linearization at ``u`` that continues a tracked one, with its right
        and left eigenvectors (``w^H v = 1``).

        Without ``previous`` (the last right eigenvector) the eigenvalue nearest ``near``; with
        it, the one whose eigenvector is most parallel to ``previous`` among the eigenvalues
        within a quarter of the spectral radius of ``near``: two pairs passing close to one
        another are then told apart by their modes, not by their frequencies alone.
        """
        import scipy.linalg

        u = np.asarray(u, dtype=float)
        lam, w, v = scipy.linalg.eig(self.matrix(u), left=True, right=True)
        self._spectra[u.tobytes()] = lam
        dist = np.abs(lam - near)
        k = int(np.argmin(dist))
        if previous is not None:
            close = np.flatnonzero(dist <= max(0.25 * np.abs(lam).max(), dist[k]))
            overlap = np.abs(v[:, close].conj().T @ previous) / np.linalg.norm(v[:, close], axis=0)
            k = int(close[np.argmax(overlap)])
        vk, wk = v[:, k], w[:, k]
        vk = vk / np.linalg.norm(vk)
        wk = wk / np.conj(wk.conj() @ vk)
        return complex(lam[k]), vk, wk

    def eigenvalue_gradient(self, u, v: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``d lambda / d u`` of a simple eigenvalue with right and left eigenvectors ``v``, ``w``
        (``w^H v = 1``): ``w^H (dA/du_j) v`` (first-order perturbation theory).

        ``A(u) v`` is a directional derivative of the co-rotating right-hand side, so each entry
        is a mixed second difference of it (steps 1e-4 of the typical sizes along v and the state,
        the parameters' steps of :meth:`jacobian`):
        8 right-hand-side calls per unknown, where differencing two linearizations costs 256.
        """
        u = np.asarray(u, dtype=float)
        f0 = self.frame(u[self.n:])
        vs = v / np.max(np.abs(v) / (1e3 * f0.steps))  # largest entry one typical size
        h = 1e-4
        sc = self.scale(u[self.n:])
        # parameter steps those of :meth:`jacobian`: the machines built there are reused here
        eps = np.where(np.arange(u.size) < self.n, 1e-4 * sc, 1e-6 * np.maximum(np.abs(u), sc))
        y0 = self.state(u[:self.n])
        dirs = h * np.array([vs.real, -vs.real, vs.imag, -vs.imag])  # (+re, -re, +im, -im)

        def av(fr, ys):  # A v at each of the states ys, shape (k, n_state): (k, n_state) complex
            f = fr.rhs_many((ys[:, None, :] + dirs[None]).reshape(-1, y0.size)).reshape(len(ys), 4, -1)
            return ((f[:, 0] - f[:, 1]) + 1j * (f[:, 2] - f[:, 3])) / (2.0 * h)

        shift = np.zeros((self.n, y0.size))
        shift[np.arange(self.nz), np.arange(self.nz)] = eps[:self.nz]
        shift[np.arange(self.nz, self.n), 2 * self.nz + np.arange(self.nb)] = eps[self.nz:self.n]
        ys = np.concatenate([y0 + shift, y0 - shift])
        a = av(f0, ys)
        grad = np.empty(u.size, dtype=complex)
        grad[:self.n] = (a[:self.n] - a[self.n:]) @ np.conj(w) / (2.0 * eps[:self.n])
        for j in range(self.n, u.size):
            p_hi, p_lo = u[self.n:].copy(), u[self.n:].copy()
            p_hi[j - self.n] += eps[j]
            p_lo[j - self.n] -= eps[j]
            d = av(self.frame(p_hi), y0[None])[0] - av(self.frame(p_lo), y0[None])[0]
            grad[j] = np.conj(w) @ d / (2.0 * eps[j])
        return grad * (np.linalg.norm(v) / np.linalg.norm(vs))

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
