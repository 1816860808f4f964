"""Imported once by the web app's fork server (see :mod:`rocking.web.jobs`).

It imports the package, matplotlib (Agg) and the report code, and runs one tiny simulation of a
statue and one of a stack so that the compiled solver and stack engine are loaded (or compiled and
cached, the very first time). Every worker process
is forked from that state and starts warm. Nothing here may raise: the fork server would die.
"""

from __future__ import annotations

import sys


def _warm_up() -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        from .. import Harmonic, Statue, System, simulate
        from ..io import config as _config  # noqa: F401
        from ..report import verdict  # noqa: F401
        from ..viz import animation, plots  # noqa: F401
        from . import tasks  # noqa: F401

        simulate(System(statue=Statue(width=1.0, height=4.0, mass=1.0)), Harmonic(amplitude=1.0, frequency=1.0))
        # the stack engine too: else every worker of a stack run would load (or compile) it anew
        from ..stack import Block, Interface, Stack, simulate_stack
        from ..viz import stack_animation, stack_plots  # noqa: F401

        simulate_stack(Stack(blocks=(Block(width=1.0, height=4.0, mass=1.0),), interfaces=(Interface(),)),
                       Harmonic(amplitude=1.0, frequency=1.0))
    except Exception as exc:  # noqa: BLE001 - a worker will meet the same problem and report it
        print(f"rocking web: warm-up of the worker processes failed: {exc}", file=sys.stderr)


_warm_up()
