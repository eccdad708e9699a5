r"""Generator of the machine's compiled right-hand side in the co-rotating frame (one physics).

The co-rotating frame turns with the spin angle theta. A machine whose structure coordinates
come in lateral pairs ``(z_2j, z_2j+1)`` that turn like vectors about the shaft axis (the x/y
translations and tilts of an unreduced structure, the x/y mode pairs of an isotropic reduced
one: :meth:`rotorlab.models.Machine.why_no_rotating_kernel`) has the co-rotating state

    z_r = R^T z,   z_r' = R^T z' - w J z_r,   psi_b = phi_b - theta,   psi_b' = phi_b' - w

(``R`` the rotation by theta, ``J = [[0, -1], [1, 0]]``, ``w = theta'``); every other state (the
spin of a motor, energy states, stick/slip modes) is the same in both frames. The generated
``rhs_rotating(t, y, p, out)`` turns the state into the fixed frame, evaluates the fixed frame's
own lines (:func:`rotorlab._kernels.machine_codegen.rhs_lines`: no second set of equations) and
turns the accelerations back::

    z_r'' = R^T z'' - 2 w J z_r' - alpha J z_r + w^2 z_r,   psi_b'' = phi_b'' - alpha

with ``alpha`` the spin acceleration (the profile's, or a motor's computed ``theta''``). The
fixed-frame state lives in local variables ``_f<k>`` (the fixed lines' reads ``y[k]`` are
renamed to them), so that nothing is allocated and the kernel vectorises in lanes as the fixed
one does. The stick/slip event functions and reset (friction layouts) are the fixed frame's,
called on the fixed state as a tuple: their values (relative ball speeds, friction margins) do
not depend on the frame, and the reset's new ball speed is turned back.

The generated module holds the fixed frame's module (:func:`rotorlab._kernels.machine_codegen.generate`)
followed by ``rhs_rotating``, ``events_rotating`` and ``reset_rotating``; it is written, cached
and imported as the fixed one (:func:`rotorlab._kernels.machine_codegen.kernel_module`).
"""

from __future__ import annotations

import re

from rotorlab._kernels import machine_codegen as _cg
from rotorlab._kernels.machine_drive import spin_lines
from rotorlab._kernels.machine_emit import _DECO
from rotorlab._kernels.machine_layout import Layout

__all__ = ["generate_rotating", "rotating_kernel_module"]

_READ = re.compile(r"\by\[(\d+)\]")
_OUT = re.compile(r"\bout\[(\d+)\]")


def _frame_lines(lay: Layout) -> list[str]:
    """Lines defining ``theta``, ``om`` (``dom``), ``_s, _c = sincos(theta)`` and the fixed-frame
    state ``_f<k>`` of the co-rotating state ``y``."""
    nz, nb = lay.n_z, lay.n_balls
    L = list(spin_lines(lay))
    L.append("    _s, _c = sincos(theta)")
    for x in range(0, nz, 2):
        q = x + 1
        L += [f"    _f{x} = _c * y[{x}] - _s * y[{q}]", f"    _f{q} = _s * y[{x}] + _c * y[{q}]",
              f"    _a = y[{nz + x}] - om * y[{q}]", f"    _b = y[{nz + q}] + om * y[{x}]",
              f"    _f{nz + x} = _c * _a - _s * _b", f"    _f{nz + q} = _s * _a + _c * _b"]
    for b in range(nb):
        L.append(f"    _f{lay.i_phi + b} = y[{lay.i_phi + b}] + theta")
        L.append(f"    _f{lay.i_w + b} = y[{lay.i_w + b}] + om")
    L += [f"    _f{k} = y[{k}]" for k in range(lay.i_theta, lay.n_state)]
    return L


def _fixed_tuple(lay: Layout) -> str:
    return "(" + ", ".join(f"_f{k}" for k in range(lay.n_state)) + ",)"


def _fixed_body(lay: Layout) -> list[str]:
    """The fixed frame's rhs lines on the fixed state ``_f<k>``, writing ``_o<k>`` for ``out[k]``:
    its spin lines (the frame's already define them) and its sines of theta taken from the
    frame's, so that nothing is computed twice."""
    body, _ = _cg.rhs_lines(lay)
    spin = spin_lines(lay)
    for i in range(len(body) - len(spin) + 1):
        if body[i:i + len(spin)] == spin:
            del body[i:i + len(spin)]
            break
    body = [re.sub(r"^(\s+)(\w+), (\w+) = sincos\(theta\)$", r"\1\2, \3 = _s, _c", line) for line in body]
    body = [_OUT.sub(lambda m: f"_o{m.group(1)}", _READ.sub(lambda m: f"_f{m.group(1)}", line)) for line in body]
    left = [line for line in body if re.search(r"\b(y|out)\b", line)]
    if left:  # pragma: no cover - a generator change the renaming does not cover
        raise RuntimeError(f"co-rotating kernel: the fixed lines use the state otherwise: {left[0].strip()}")
    return body


def _rhs_rotating(lay: Layout) -> str:
    nz, nb = lay.n_z, lay.n_balls
    L = _frame_lines(lay) + _fixed_body(lay)
    o = {k: f"_o{k}" for k in range(lay.n_state)}
    L.append(f"    _al = _o{lay.i_theta + 1}" if lay.motor else "    _al = dom")
    for x in range(0, nz, 2):  # z_r'' = R^T z'' - 2 w J z_r' - alpha J z_r + w^2 z_r
        q = x + 1
        a, b = o[nz + x], o[nz + q]
        o[nz + x] = f"_c * {a} + _s * {b} + 2.0 * om * y[{nz + q}] + _al * y[{q}] + om * om * y[{x}]"
        o[nz + q] = f"_c * {b} - _s * {a} - 2.0 * om * y[{nz + x}] - _al * y[{x}] + om * om * y[{q}]"
    o.update({i: f"y[{nz + i}]" for i in range(nz)})
    for b in range(nb):
        o[lay.i_phi + b] = f"_o{lay.i_phi + b} - om" if lay.friction else f"y[{lay.i_w + b}]"
        o[lay.i_w + b] = f"_o{lay.i_w + b} - _al"
    L += [f"    out[{k}] = {o[k]}" for k in range(lay.n_state)]
    return (_DECO + "def rhs_rotating(t, y, p, out):  # pragma: no cover - compiled\n"
            '    """Right-hand side in the co-rotating frame (rotorlab._kernels.machine_corotating)."""\n'
            + "\n".join(L) + "\n")


def _friction_rotating(lay: Layout) -> str:
    frame = "\n".join(_frame_lines(lay))
    im, iw = lay.i_modes, lay.i_w
    return (_DECO + "def events_rotating(t, y, p, g):  # pragma: no cover - compiled\n"
            '    """The fixed frame\'s stick/slip events at the same motion."""\n'
            + frame + f"\n    events(t, {_fixed_tuple(lay)}, p, g)\n"
            + _DECO + "def reset_rotating(k, t, y, p, y_new):  # pragma: no cover - compiled\n"
            '    """The fixed frame\'s stick/slip reset, its new ball speed turned back."""\n'
            + frame + f"\n    r = reset(k, t, {_fixed_tuple(lay)}, p, y_new)\n"
            f"    b = k // 2\n    md = y_new[{im} + b]\n    wn = y_new[{iw} + b]\n"
            f"    for i in range({lay.n_state}):\n        y_new[i] = y[i]\n"
            f"    y_new[{im} + b] = md\n    y_new[{iw} + b] = wn - om\n    return r\n")


def generate_rotating(lay: Layout) -> str:
    """Return the source of the co-rotating kernel module for ``lay`` (see the module docstring).

    Raises
    ------
    ValueError
        If ``lay`` has an odd number of structure coordinates, a clearance or parts with states
        (the co-rotating frame does not carry them yet).
    """
    if lay.n_z % 2 or lay.clearance or any(part.n_states for part in lay.parts):
        raise ValueError(f"co-rotating kernel: layout {lay.key} has an odd number of structure "
                         "coordinates, a clearance or parts with states, which it does not carry")
    src = _cg.generate(lay).replace("machine_codegen for sizes", "machine_corotating for sizes", 1)
    src += _rhs_rotating(lay)
    if lay.friction:
        src += _friction_rotating(lay)
    return src


def rotating_kernel_module(lay: Layout):
    """Return the imported co-rotating kernel module for ``lay`` (generated on first use)."""
    return _cg.kernel_module(lay, generate_rotating)
