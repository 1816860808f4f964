"""Solvers of the hybrid (regime-switching) equations: the compiled event-driven solver, and a
SciPy integrator cross-check of the same equations (``crosscheck``: tests and benchmarks only).

Numba's on-disk cache checks only the source file of each cached function, not the files of the
functions it calls, so an edited physics module could leave a stale compiled solver behind.
Before the compiled modules are imported we fingerprint every source file of the core and drop
the cache when any of them changed.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

_PKG = Path(__file__).resolve().parent.parent
_CORE = [
    "models/dynamics.py", "models/modes.py", "models/parameters.py", "models/transitions.py", "contact/impact.py",
    "excitation/signal.py", "excitation/base.py", "integrators/dopri5.py", "integrators/dop853.py",
    "solver/compiled.py",
]


def _refresh_numba_cache() -> None:
    digest = hashlib.sha256()
    for name in _CORE:
        digest.update((_PKG / name).read_bytes())
    stamp = _PKG / "solver" / "__pycache__" / "core.sha256"
    new = digest.hexdigest()
    try:
        if stamp.exists() and stamp.read_text() == new:
            return
        for folder in {(_PKG / name).parent / "__pycache__" for name in _CORE}:
            for f in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
                f.unlink(missing_ok=True)
        stamp.parent.mkdir(exist_ok=True)
        stamp.write_text(new)
    except OSError:
        pass  # read-only installation: numba then keeps its cache elsewhere or none


_refresh_numba_cache()
