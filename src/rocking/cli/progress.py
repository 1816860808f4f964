"""A spinner on stderr that appears only if the work takes longer than a second.

Short runs (a few ms once the core is compiled) print nothing extra; the first run on a
machine compiles the core for ~10 s, and then the user sees that something is going on.
The spinner never touches stdout, so ``--json`` output stays clean.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager

from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

__all__ = ["delayed_spinner"]


@contextmanager
def delayed_spinner(
    message: str, *, console: Console | None = None, delay: float = 1.0
) -> Iterator[None]:
    """Show ``message`` with a spinner and the elapsed time if the block lasts > ``delay``.

    Parameters
    ----------
    message : str
        What is being done (rich markup is not interpreted).
    console : rich.console.Console, optional
        Where to draw; default: a console on stderr. Nothing is drawn when it is not
        a terminal (pipes, CI logs, tests).
    delay : float
        Seconds before the spinner appears.
    """
    console = console if console is not None else Console(stderr=True)
    if not console.is_terminal:
        yield
        return
    progress = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}", markup=False),
        TimeElapsedColumn(),
        console=console,
        transient=True,  # erase the line when done: the result is what stays on screen
    )
    progress.add_task(message, total=None)
    lock = threading.Lock()
    state = {"started": False, "done": False}

    def start() -> None:
        # runs on the timer thread; the lock orders it against the stop below
        with lock:
            if not state["done"]:
                progress.start()
                state["started"] = True

    timer = threading.Timer(delay, start)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
        with lock:
            state["done"] = True
            if state["started"]:
                progress.stop()
