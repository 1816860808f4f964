"""Solvers of the hybrid (regime-switching) equations: the compiled event-driven solver, and a
SciPy integrator cross-check of the same equations (``crosscheck``: tests and benchmarks only).

Numba's on-disk cache checks only the source file of each cached function, not the files of the
functions it calls, so an edited physics module could leave a stale compiled solver behind.
Before the compiled modules are imported we fingerprint every source file of the core and drop
the cache when any of them changed.
"""

from __future__ import annotations

from .._numba_cache import refresh

refresh()
