"""Compiled kernels of the small example models in :mod:`rotorlab.models.examples`.

State layouts and parameter orders are documented on each model class.
"""

import math

from numba import njit

# ---- harmonic oscillator: y = [x, v], p = [omega] ----------------------------------------------


@njit(cache=True, nogil=True)
def oscillator_rhs(t, y, p, out):
    out[0] = y[1]
    out[1] = -p[0] * p[0] * y[0]


# ---- bouncing ball: y = [h, v, mode], p = [a, e, v_rest, f_amp, f_freq] --------------------------
# mode 0: flight, mode 1: resting on the ground (sustained contact)


@njit(cache=True, nogil=True)
def _ball_push(t, p):
    """External upward acceleration f_amp sin(f_freq t) (m/s^2)."""
    return p[3] * math.sin(p[4] * t)


@njit(cache=True, nogil=True)
def ball_rhs(t, y, p, out):
    out[2] = 0.0
    if y[2] == 0.0:
        out[0] = y[1]
        out[1] = -p[0] + _ball_push(t, p)
    else:
        out[0] = 0.0
        out[1] = 0.0


@njit(cache=True, nogil=True)
def ball_events(t, y, p, g):
    if y[2] == 0.0:
        g[0] = y[0]  # height: impact when it reaches zero from above
        g[1] = 1.0
    else:
        g[0] = 1.0
        g[1] = p[0] - _ball_push(t, p)  # contact force per unit mass: lift-off when it would pull


@njit(cache=True, nogil=True)
def ball_reset(k, t, y, p, y_new):
    y_new[0] = 0.0
    if k == 0:
        v_after = -p[1] * y[1]
        if v_after < p[2] and p[0] - _ball_push(t, p) > 0.0:
            y_new[1] = 0.0
            y_new[2] = 1.0
        else:
            y_new[1] = v_after
            y_new[2] = 0.0
    else:
        y_new[1] = 0.0
        y_new[2] = 0.0
    return 0


# ---- block with dry friction: y = [x, v, mode], p = [mu_g, omega0^2, f_amp, f_freq] --------------
# mode +1 / -1: sliding with positive / negative velocity; 0: stuck


@njit(cache=True, nogil=True)
def _block_drive(t, y, p):
    """Non-friction force per unit mass acting on the block (m/s^2)."""
    return -p[1] * y[0] + p[2] * math.sin(p[3] * t)


@njit(cache=True, nogil=True)
def block_rhs(t, y, p, out):
    out[2] = 0.0
    if y[2] == 0.0:
        out[0] = 0.0
        out[1] = 0.0
    else:
        out[0] = y[1]
        out[1] = _block_drive(t, y, p) - p[0] * y[2]


@njit(cache=True, nogil=True)
def block_events(t, y, p, g):
    if y[2] == 0.0:
        g[0] = 1.0
        g[1] = p[0] - abs(_block_drive(t, y, p))  # breaks away when the drive exceeds friction
    else:
        g[0] = y[1] * y[2]  # relative speed along the sliding direction reaches zero
        g[1] = 1.0


@njit(cache=True, nogil=True)
def block_reset(k, t, y, p, y_new):
    y_new[0] = y[0]
    y_new[1] = 0.0
    drive = _block_drive(t, y, p)
    if k == 0 and abs(drive) <= p[0]:
        y_new[2] = 0.0  # came to rest and friction can hold it: stick
    else:
        # break-away (k == 1): the drive is reaching the friction bound and will exceed it, so
        # slip whatever round-off says about |drive| <= mu g at the located zero
        y_new[2] = 1.0 if drive > 0.0 else -1.0
    return 0


# ---- planar polynomial oscillator: y = [x, y], p = [a11, a12, a21, a22, c1, c2, c3, c4,
#      q1, q2, q3, q4, d, e, w] (see rotorlab.models.examples.PlanarOscillator) ------------------


@njit(cache=True, nogil=True)
def planar_rhs(t, y, p, out):
    x = y[0]
    v = y[1]
    r2 = x * x + v * v
    r4 = r2 * r2
    out[0] = p[0] * x + p[1] * v + (p[4] * x + p[5] * v) * r2 + (p[8] * x + p[9] * v) * r4
    out[1] = ((p[2] + p[13] * math.cos(p[14] * t)) * x + p[3] * v + (p[6] * x + p[7] * v) * r2
              + (p[10] * x + p[11] * v) * r4 + p[12] * x * x * v)
