"""Say so when the first simulation on a machine has to compile the solver.

The compiled core (:func:`rocking.solver.compiled.integrate`) is compiled by Numba on its
first call and kept in Numba's on-disk cache; on a machine (or after an upgrade) where that
cache holds nothing usable, the first run is silent for about half a minute. The command
line calls :func:`ensure_compiled` before its first simulation: when the cache is cold it
prints what is happening, compiles with one tiny simulation, and prints how long it took.
Worker processes started afterwards then load the cache instead of each compiling again.
"""

from __future__ import annotations

import sys
import threading
import time
from typing import TextIO

__all__ = ["cache_is_warm", "ensure_compiled"]

#: What a cold start costs on a typical 2-core machine, s (for the message only).
TYPICAL_SECONDS = 30

# Re-entrant: compiling runs a simulation, and ``simulate`` itself calls ensure_compiled (which
# then returns at once, _done being set); a plain Lock would deadlock the first run.
_lock = threading.RLock()
_done = False


def cache_is_warm() -> bool | None:
    """Whether the solver is ready without compiling.

    Returns
    -------
    bool or None
        True if it is compiled in this process already, or Numba's on-disk cache holds it
        for this machine's CPU; False if it would be compiled; None if this cannot be told
        (Numba's JIT disabled, or a Numba whose cache internals differ).
    """
    from .compiled import integrate

    try:
        if integrate.overloads:  # compiled (or loaded from the cache) in this process
            return True
        # Numba's own index of the cached versions; _load_index returns {} when the index
        # is missing or was written for another version of the source file. A key is
        # (signature, target machine, ...): a cache from another CPU does not count.
        from numba.core.registry import cpu_target

        index = integrate._cache._cache_file._load_index()
        machine = cpu_target.target_context.codegen().magic_tuple()
        return any(key[1] == machine for key in index)
    except Exception:  # noqa: BLE001 - private Numba API: any change means "cannot tell"
        return None


def ensure_compiled(*, stream: TextIO | None = None) -> float | None:
    """Compile the solver now, with a message, if the first simulation would have to.

    Cheap when the cache is warm (it only reads Numba's small index file) and a no-op after
    the first call in a process.

    Parameters
    ----------
    stream : text file, optional
        Where the two messages go (default ``sys.stderr``, so ``--json`` output stays clean).

    Returns
    -------
    float or None
        The compilation time (s) if this call compiled, else None.
    """
    global _done
    with _lock:
        if _done:
            return None
        _done = True
        if cache_is_warm() is not False:
            return None
        out = stream if stream is not None else sys.stderr
        print(
            f"rocking: compiling the solver (first run on this machine, about {TYPICAL_SECONDS} s; "
            "cached afterwards)...",
            file=out,
            flush=True,
        )
        start = time.perf_counter()
        _compile()
        seconds = time.perf_counter() - start
        print(f"rocking: solver compiled in {seconds:.0f} s", file=out, flush=True)
        return seconds


def _compile() -> None:
    """One tiny simulation: it compiles :func:`integrate` for the argument types every run
    uses (the motion and the system are packed into arrays of fixed types)."""
    from ..excitation.harmonic import Harmonic
    from ..models.bodies import Statue, System
    from ..simulation import simulate

    simulate(System(statue=Statue(width=1.0, height=4.0, mass=1.0)), Harmonic(amplitude=1.0, frequency=1.0))
