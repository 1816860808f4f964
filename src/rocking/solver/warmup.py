"""Say so when the first simulation on a machine has to compile the solver.

The compiled cores — the two-body solver (:func:`rocking.solver.compiled.integrate`) and the
stack engine (:func:`rocking.stack.engine.integrate`) — are compiled by Numba on their first
call and kept in Numba's on-disk cache; on a machine (or after an upgrade) where that cache holds
nothing usable, the first run is silent for most of a minute. The command line calls
:func:`ensure_compiled` (or :func:`ensure_stack_compiled`) before its first simulation: when the
cache is cold it prints what is happening, compiles with one tiny simulation, and prints how long
it took. Worker processes started afterwards then load the cache instead of each compiling again.

The set-up (``scripts/env.sh``) runs :func:`main` once after installing,
so that the wait happens there, with its message, and not in the first command a user types.
Compilation cannot be split over several processes: Numba's cache files are not safe against two
processes writing the same function (the two cores share the record and Runge–Kutta kernels).
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable
from typing import TextIO

__all__ = ["cache_is_warm", "ensure_compiled", "ensure_stack_compiled", "main", "stack_cache_is_warm"]

#: What a cold start of the two-body solver costs on a quiet 2-core machine, s (for the message).
TYPICAL_SECONDS = 40
#: The same for the stack engine, s (50 s before its kinematics were inlined into the right-hand
#: side; that took a cold start from 83 to 119 s on a loaded machine, so about 70 s on a quiet one).
STACK_TYPICAL_SECONDS = 70

# Re-entrant: compiling runs a simulation, and ``simulate`` itself calls ensure_compiled (which
# then returns at once, _done being set); a plain Lock would deadlock the first run.
_lock = threading.RLock()
_done = False
_stack_done = False


def _index_is_warm(dispatcher) -> bool | None:
    """Whether ``dispatcher`` is compiled in this process or in Numba's cache for this CPU."""
    try:
        if dispatcher.overloads:  # compiled (or loaded from the cache) in this process
            return True
        # Numba's own index of the cached versions; _load_index returns {} when the index
        # is missing or was written for another version of the source file. A key is
        # (signature, target machine, ...): a cache from another CPU does not count.
        from numba.core.registry import cpu_target

        index = dispatcher._cache._cache_file._load_index()
        machine = cpu_target.target_context.codegen().magic_tuple()
        return any(key[1] == machine for key in index)
    except Exception:  # noqa: BLE001 - private Numba API: any change means "cannot tell"
        return None


def cache_is_warm() -> bool | None:
    """Whether the two-body solver is ready without compiling.

    Returns
    -------
    bool or None
        True if it is compiled in this process already, or Numba's on-disk cache holds it
        for this machine's CPU; False if it would be compiled; None if this cannot be told
        (Numba's JIT disabled, or a Numba whose cache internals differ).
    """
    from .compiled import integrate

    return _index_is_warm(integrate)


def stack_cache_is_warm() -> bool | None:
    """Whether the stack engine is ready without compiling (same answers as :func:`cache_is_warm`)."""
    from ..stack.engine import integrate

    return _index_is_warm(integrate)


def _compile_once(flag: str, what: str, seconds: int, is_warm: Callable[[], bool | None],
                  compile_: Callable[[], None], stream: TextIO | None) -> float | None:
    """Compile with a message before and after, unless the module flag ``flag`` is set or the
    cache is warm (or cannot be told); set the flag. Returns the compilation time, s, or None."""
    with _lock:
        if globals()[flag]:
            return None
        globals()[flag] = True
        if is_warm() is not False:
            return None
        out = stream if stream is not None else sys.stderr
        print(
            f"rocking: compiling the {what} (first run on this machine, about {seconds} s; cached afterwards)...",
            file=out,
            flush=True,
        )
        start = time.perf_counter()
        compile_()
        elapsed = time.perf_counter() - start
        print(f"rocking: {what} compiled in {elapsed:.0f} s", file=out, flush=True)
        return elapsed


def ensure_compiled(*, stream: TextIO | None = None) -> float | None:
    """Compile the two-body solver now, with a message, if the first simulation would have to.

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
    # the lambdas look the names up at call time: tests replace cache_is_warm and _compile
    return _compile_once("_done", "solver", TYPICAL_SECONDS, lambda: cache_is_warm(), lambda: _compile(), stream)


def ensure_stack_compiled(*, stream: TextIO | None = None) -> float | None:
    """Compile the stack engine (:mod:`rocking.stack`) now, with a message, if the first stack
    simulation would have to. Same parameters and return value as :func:`ensure_compiled`."""
    return _compile_once("_stack_done", "stack engine", STACK_TYPICAL_SECONDS, lambda: stack_cache_is_warm(),
                         lambda: _compile_stack(), stream)


def _compile() -> None:
    """One tiny simulation: it compiles :func:`integrate` for the argument types every run
    uses (the motion and the system are packed into arrays of fixed types)."""
    from ..excitation.harmonic import Harmonic
    from ..models.bodies import Statue, System
    from ..simulation import simulate

    simulate(System(statue=Statue(width=1.0, height=4.0, mass=1.0)), Harmonic(amplitude=1.0, frequency=1.0))


def _compile_stack() -> None:
    """One short two-block stack run: the stack engine packs every stack into arrays of the same
    types, so this one compilation serves every stack."""
    from ..contact.friction import Friction
    from ..excitation.pulses import SinePulse
    from ..stack import Block, Interface, Stack, simulate_stack

    stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=300.0),
                          Block(name="statue", width=0.3, height=1.2, mass=100.0)),
                  interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.25)), Interface()))
    simulate_stack(stack, SinePulse(amplitude=3.5, frequency=1.0))


def main() -> int:
    """Compile both cores now if the cache is cold, each with its message (nothing is printed
    when both are warm). Returns the exit code, 0.

    Run as ``python -c "from rocking.solver.warmup import main; raise SystemExit(main())"``
    (``python -m`` would run a second copy of this module beside the one ``rocking`` imports).
    """
    ensure_compiled()
    ensure_stack_compiled()
    return 0
