"""Keep numba's on-disk cache honest.

Numba checks only the source file of each cached function, not the files of the functions it
calls or of the constants it reads, so an edited physics module could leave a stale compiled
solver behind. Each compiled core (the solver of ``rocking.simulate``, the stack engine)
fingerprints every source file it is built from before its compiled modules are imported, and
drops their cache when any of them changed.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent


def refresh(core: list[str], stamp: str) -> None:
    """Drop the cached machine code of the folders of ``core`` (paths under the package) when the
    hash of those files differs from the one recorded in ``stamp`` (a path under the package)."""
    digest = hashlib.sha256()
    for name in core:
        digest.update((PACKAGE / name).read_bytes())
    stamp_file = PACKAGE / stamp
    new = digest.hexdigest()
    try:
        if stamp_file.exists() and stamp_file.read_text() == new:
            return
        for folder in {(PACKAGE / name).parent / "__pycache__" for name in core}:
            for f in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
                f.unlink(missing_ok=True)
        stamp_file.parent.mkdir(exist_ok=True)
        stamp_file.write_text(new)
    except OSError:
        pass  # read-only installation: numba then keeps its cache elsewhere or none
