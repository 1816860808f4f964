"""``python -m rocking.cli``: the same as the ``rocking`` console script."""

from .main import main

raise SystemExit(main())
