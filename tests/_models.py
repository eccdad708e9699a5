"""Canonical test models shared by the test modules (the compile budget of ``tests/conftest.py``).

Every kernel set a test integrates costs a compiled driver copy per driver kind (scalar, each lane
width), 15-70 CPU-s each: a test that needs a model only to check something generic (a status
code, the lanes against the scalar driver, chunking) takes one from here instead of defining its
own, so that the suite compiles each copy once.
"""

import math

from numba import njit

from rotorlab.models import Kernels


@njit(cache=True, nogil=True)
def failing_rhs(t, y, p, out):
    """One state whose run fails, the way chosen by ``p[0]``.

    ``p[0] == 0``: ``y' = y**2``, which blows up at ``t = 1 / y0``; otherwise ``y' = -sqrt(y)``,
    which reaches ``y = 0`` at ``t = 2 sqrt(y0)``, after which the square root of a negative
    number is NaN."""
    if p[0] == 0.0:
        out[0] = y[0] * y[0]
    else:
        out[0] = -math.sqrt(y[0]) if y[0] >= 0.0 else math.nan


#: :func:`failing_rhs` as a model (one state, one parameter).
FAILING = Kernels(rhs=failing_rhs, n_state=1)
#: Its parameter for a blow-up (``y' = y**2``) and for a NaN (``y' = -sqrt(y)``).
BLOWUP_P, NAN_P = [0.0], [1.0]
