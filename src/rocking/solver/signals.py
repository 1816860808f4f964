"""Ctrl-C and SIGTERM while compiled code runs.

A Python signal handler runs at the next point where the interpreter checks for signals. While
the compiled solver runs, the first such point used to be inside Numba's conversion of the
results back to Python objects; a ``KeyboardInterrupt`` raised there left a NULL inside the
returned tuple, and the process died with a segmentation fault.

So while compiled code runs, :func:`deferred_signals` replaces the handlers of SIGINT and SIGTERM
with one that only records the signal in a flag array. The solver polls the handlers every few
thousand iterations (``PyErr_CheckSignals``), sees the flag and returns early. When the block
ends, the original handlers are back and the signal is delivered to them: SIGINT raises
``KeyboardInterrupt``, SIGTERM goes to its previous handler (or, with the default disposition,
terminates the process as it would have).

Outside the main thread nothing is replaced: Python delivers signals to the main thread only.
Nor is a signal that is ignored (a background job of a shell script, ``nohup``): it stays ignored.
"""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

__all__ = ["deferred_signals"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)


@contextmanager
def deferred_signals() -> Iterator[np.ndarray]:
    """Yield an int64[1] flag that becomes the signal number once SIGINT or SIGTERM arrives;
    deliver that signal to the original handler when the block exits."""
    flag = np.zeros(1, dtype=np.int64)
    if threading.current_thread() is not threading.main_thread():
        yield flag
        return

    def record(signum, frame):
        if flag[0] == 0:
            flag[0] = signum

    previous = {}
    try:
        for sig in _SIGNALS:
            if signal.getsignal(sig) == signal.SIG_IGN:
                continue  # ignored on purpose (a background job, nohup): it must stay ignored
            previous[sig] = signal.signal(sig, record)
        yield flag
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    if flag[0] != 0:
        _deliver(int(flag[0]), previous[int(flag[0])])


def _deliver(signum: int, handler) -> None:
    if callable(handler):
        handler(signum, None)  # the default SIGINT handler raises KeyboardInterrupt
        return
    if handler == signal.SIG_IGN:
        return
    # SIG_DFL (or a handler not installed from Python): let the operating system act on it.
    os.kill(os.getpid(), signum)
