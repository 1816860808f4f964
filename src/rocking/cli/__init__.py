"""The ``rocking`` command line (console script ``rocking = "rocking.cli:main"``)."""

from .main import app, main

__all__ = ["app", "main"]
