"""Keep numba's on-disk cache honest.

Numba checks only the source file of each cached function, not the files of the functions it
calls or of the constants it reads, so an edited physics module could leave a stale compiled
solver behind. Before the compiled modules of either core (the solver of ``rocking.simulate``,
the stack engine) are imported, :func:`refresh` fingerprints every source file the two are built
from and drops their cache when any of them changed.

The two cores share one fingerprint because they share modules and cache folders (the record
kernels, the Runge–Kutta steps, ``solver/compiled.py``). With one fingerprint each, the first
import of the stack engine found none of its own and dropped the cache of ``solver/``, so the
solver that the set-up had just compiled was compiled again by the next command.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent

#: Every module with compiled code that the two-body solver reaches (tests/test_architecture.py).
SOLVER_CORE = [
    "models/dynamics.py", "models/modes.py", "models/parameters.py", "models/transitions.py", "contact/impact.py",
    "excitation/signal.py", "excitation/base.py", "integrators/dopri5.py", "integrators/dop853.py",
    "solver/compiled.py",
]
#: The same for the stack engine.
STACK_CORE = [
    "stack/kinematics.py", "stack/modes.py", "stack/engine.py", "excitation/signal.py", "excitation/base.py",
    "integrators/dop853.py", "integrators/dopri5.py", "solver/compiled.py",
]
STAMP = "__pycache__/numba-core.sha256"


def refresh() -> None:
    """Drop the cached machine code of every folder of :data:`SOLVER_CORE` and :data:`STACK_CORE`
    when the hash of those files differs from the one recorded in :data:`STAMP` (or none is)."""
    files = sorted(set(SOLVER_CORE) | set(STACK_CORE))
    digest = hashlib.sha256()
    for name in files:
        digest.update(name.encode())
        digest.update((PACKAGE / name).read_bytes())
    stamp_file = PACKAGE / STAMP
    new = digest.hexdigest()
    try:
        if stamp_file.exists() and stamp_file.read_text() == new:
            return
        for folder in {(PACKAGE / name).parent / "__pycache__" for name in files}:
            for f in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
                f.unlink(missing_ok=True)
        stamp_file.parent.mkdir(exist_ok=True)
        stamp_file.write_text(new)
    except OSError:
        pass  # read-only installation: numba then keeps its cache elsewhere or none
