"""Stopping a command cleanly: Ctrl-C (SIGINT), ``kill`` (SIGTERM) and a closed terminal (SIGHUP).

Python turns SIGINT into ``KeyboardInterrupt``, so ``finally`` blocks and ``except BaseException``
clean-ups run (the temporary folder of :func:`rocking.io.output.write_outputs`, a study's
half-written files). SIGTERM and SIGHUP, by default, end the process at once and leave those
behind. :func:`stop_signals` makes them raise :class:`Terminated` instead, a
``KeyboardInterrupt`` subclass, so that every clean-up written for Ctrl-C runs for them too, and
the command exits with the shell's code for the signal (128 + its number: 143 for SIGTERM).

The compiled solver defers these signals while it runs (:mod:`rocking.solver.signals`) and
delivers them to the handlers installed here as soon as it returns, within milliseconds.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["Terminated", "exit_code", "signal_name", "stop_signals"]

#: Signals turned into :class:`Terminated` (SIGHUP does not exist on Windows).
_STOP_SIGNALS = tuple(s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None)) if s is not None)


class Terminated(KeyboardInterrupt):
    """The process was asked to stop by SIGTERM or SIGHUP.

    A ``KeyboardInterrupt`` so that the clean-ups written for Ctrl-C (and ``except Exception``
    blocks that must not swallow it) treat it the same way.

    Attributes
    ----------
    signum : int
        The signal's number.
    """

    def __init__(self, signum: int):
        self.signum = int(signum)
        super().__init__(f"terminated by {signal.Signals(self.signum).name}")


def exit_code(exc: BaseException) -> int:
    """The exit code for an interrupt: 128 + the signal's number (130 for Ctrl-C, 143 for SIGTERM)."""
    return 128 + int(getattr(exc, "signum", signal.SIGINT))


def signal_name(exc: BaseException) -> str:
    """``"SIGTERM"`` for a :class:`Terminated`, ``"Ctrl-C"`` otherwise."""
    signum = getattr(exc, "signum", None)
    return "Ctrl-C" if signum in (None, signal.SIGINT) else signal.Signals(signum).name


@contextmanager
def stop_signals() -> Iterator[None]:
    """Within the block, SIGTERM and SIGHUP raise :class:`Terminated` in the main thread.

    Only signals left at their default action are taken over: one the parent chose to ignore
    (``nohup`` ignores SIGHUP) stays ignored. The first signal raises; later ones are ignored
    while the clean-up runs (SIGKILL still ends the process). The previous handlers come back when
    the block exits, so tests may call the command line in-process.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    raised = []

    def handler(signum, frame):
        if raised:
            return  # already unwinding: let the clean-up finish
        raised.append(signum)
        raise Terminated(signum)

    previous = {}
    try:
        for sig in _STOP_SIGNALS:
            if signal.getsignal(sig) == signal.SIG_DFL:
                previous[sig] = signal.signal(sig, handler)
        yield
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)
