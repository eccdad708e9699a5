"""Upper limits of the counts and speeds a user gives (no imports: read by the command line and
by the case-file schema alike).

A typo such as ``--workers 100000`` or ``chunk = 1e30`` would otherwise start a cluster that
never answers or allocate a chunk no machine holds; these bounds are named in the messages.
"""

from __future__ import annotations

__all__ = ["MAX_WORKERS", "MAX_CHUNK", "MAX_COUNT", "MAX_SEED", "MAX_SPEED_RPM", "MAX_STARTS"]

#: Workers of a local Dask cluster (threads of one command).
MAX_WORKERS = 256

#: Points (or runs) per chunk of a sweep: a chunk is allocated whole in a store.
MAX_CHUNK = 1_000_000

#: Any other count option (random starts, samples, sequences, modes, harmonics).
MAX_COUNT = 1_000_000_000

#: A random seed (a signed 64-bit integer).
MAX_SEED = 2**63 - 1

#: Fastest spin speed an option takes (rpm): ten times the fastest machine rotors (turbine and
#: dental-drill rotors, ~1e6 rpm); beyond it the structure's matrices overflow.
MAX_SPEED_RPM = 1e7

#: Random starts at one value of a basin-stability parameter (``--starts``, and what a target
#: ``--ci-width`` may need).
MAX_STARTS = 200_000
