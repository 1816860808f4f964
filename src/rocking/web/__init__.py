"""A local web page for the package: ``rocking serve`` (or ``python -m rocking.web``).

Choose a bundled record or upload one, scale it, describe the statue and its pedestal, run, and
see the verdict, the summary, an animation and the plots; or run a friction design sweep of the
pedestal with a progress bar and download its report (HTML, PDF, CSV). Computations run in worker
processes with a time limit (:mod:`rocking.web.jobs`); the app itself computes no physics.

    >>> from rocking.web import create_app
    >>> app = create_app({"RUN_TIMEOUT": 30})            # doctest: +SKIP
    >>> from rocking.web import serve
    >>> serve("127.0.0.1", 8000)                          # doctest: +SKIP
"""

from __future__ import annotations

from typing import Any

__all__ = ["create_app", "serve"]


def __getattr__(name: str) -> Any:  # Flask loads on first use: `import rocking.web` stays cheap
    if name == "create_app":
        from .app import create_app

        return create_app
    if name == "serve":
        from .server import serve

        return serve
    raise AttributeError(f"module 'rocking.web' has no attribute {name!r}")
