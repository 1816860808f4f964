"""Where the chunks of a study run: this process, local processes, or a Dask cluster.

Every executor has ``map(fn, iterable)``, which yields ``fn(x)`` for each ``x`` in order (the
contract of :func:`rocking.analyses.batch.map_chunks`), and ``as_completed(fn, iterable)``,
which yields ``(index, fn(x))`` pairs as soon as each task finishes (what
:func:`rocking.analyses.store.run_chunks` uses to save every finished chunk at once, whatever
the order). ``fn`` must be a module-level function and its arguments picklable.

    >>> from dask.distributed import Client, LocalCluster          # doctest: +SKIP
    >>> from rocking.analyses.executors import DaskExecutor       # doctest: +SKIP
    >>> client = Client(LocalCluster(n_workers=2))                # doctest: +SKIP
    >>> ds = run_cases(cases, workers=DaskExecutor(client))       # doctest: +SKIP
"""

from __future__ import annotations

import os
import signal
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from typing import Any

__all__ = ["DaskExecutor", "LocalExecutor", "SerialExecutor", "as_executor", "default_workers"]


def default_workers() -> int:
    """The number of cores this process may use."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


class SerialExecutor:
    """Runs every task in this process, one after the other."""

    workers = 1

    def map(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[Any]:
        return map(fn, iterable)

    def as_completed(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[tuple[int, Any]]:
        for i, x in enumerate(iterable):
            yield i, fn(x)

    def __repr__(self) -> str:
        return "SerialExecutor()"


def _worker_init() -> None:
    """Signals in a local worker process.

    Ctrl-C in a terminal reaches every process of the group; only the main process acts on it (it
    stops the workers, below), so the workers ignore it, instead of each printing a traceback.
    SIGTERM and SIGHUP get back their default action (end at once): the workers are forked from
    the main process, whose command line turns them into exceptions for its own clean-up.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):
        sig = getattr(signal, name, None)
        if sig is not None:
            signal.signal(sig, signal.SIG_DFL)


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's processes: after an interrupt (or an error) the chunks they are running
    are lost anyway, and waiting for them could delay the exit by a whole chunk."""
    # the executor has no public way to stop running tasks (until Python 3.14)
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        try:
            proc.terminate()
        except (OSError, ValueError, AttributeError):  # already gone
            pass


class LocalExecutor:
    """``n`` local worker processes (a :class:`concurrent.futures.ProcessPoolExecutor` per call).

    At most ``2·n`` tasks are queued at a time, so an interrupted study has started little work
    that it then loses. On an interrupt (or any error) the workers are terminated at once; they
    ignore Ctrl-C themselves (see :func:`_worker_init`).
    """

    def __init__(self, workers: int | None = None):
        self.workers = int(workers) if workers is not None else default_workers()
        if self.workers < 1:
            raise ValueError(f"workers must be >= 1, got {workers!r}")

    def map(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[Any]:
        items = list(iterable)
        if self.workers == 1 or len(items) <= 1:
            yield from map(fn, items)
            return
        with ProcessPoolExecutor(max_workers=min(self.workers, len(items)), initializer=_worker_init) as pool:
            try:
                yield from pool.map(fn, items)
            except BaseException:
                _stop_workers(pool)
                raise

    def as_completed(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[tuple[int, Any]]:
        items = list(iterable)
        if self.workers == 1 or len(items) <= 1:
            for i, x in enumerate(items):
                yield i, fn(x)
            return
        pool = ProcessPoolExecutor(max_workers=min(self.workers, len(items)), initializer=_worker_init)
        pending: dict[Any, int] = {}
        queue = iter(enumerate(items))
        try:
            for i, x in queue:
                pending[pool.submit(fn, x)] = i
                if len(pending) >= 2 * self.workers:
                    break
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for fut in sorted(done, key=pending.__getitem__):
                    i = pending.pop(fut)
                    yield i, fut.result()
                    nxt = next(queue, None)
                    if nxt is not None:
                        pending[pool.submit(fn, nxt[1])] = nxt[0]
        except BaseException:
            _stop_workers(pool)
            raise
        finally:
            for fut in pending:
                fut.cancel()
            pool.shutdown(wait=True, cancel_futures=True)

    def __repr__(self) -> str:
        return f"LocalExecutor(workers={self.workers})"


class DaskExecutor:
    """Run tasks on a :class:`dask.distributed.Client` (a LocalCluster or a remote scheduler).

    Parameters
    ----------
    client : dask.distributed.Client
        Any connected client; the caller owns it (it is not closed here).
    pure : bool
        Passed to ``client.submit``. False (default) keeps every task a separate computation
        even if two payloads happen to be equal.

    Examples
    --------
    >>> from dask.distributed import Client, LocalCluster           # doctest: +SKIP
    >>> ex = DaskExecutor(Client(LocalCluster(n_workers=2, processes=False)))  # doctest: +SKIP
    >>> list(ex.map(abs, [-1, 2, -3]))                              # doctest: +SKIP
    [1, 2, 3]
    """

    def __init__(self, client: Any, *, pure: bool = False):
        if not hasattr(client, "submit"):
            raise TypeError(f"DaskExecutor needs a dask.distributed.Client, got {type(client).__name__}")
        self.client = client
        self.pure = pure

    @property
    def workers(self) -> int:
        """Threads available on the cluster now (at least 1)."""
        try:
            return max(1, sum(self.client.nthreads().values()))
        except Exception:  # noqa: BLE001 - a scheduler that does not answer: still usable
            return 1

    def _submit(self, fn: Callable[[Any], Any], items: list[Any]) -> list[Any]:
        return [self.client.submit(fn, x, pure=self.pure) for x in items]

    def map(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[Any]:
        """Submit every task now; yield the results in input order (each as soon as it and all
        earlier ones are done)."""
        futures = self._submit(fn, list(iterable))
        try:
            for k, fut in enumerate(futures):
                yield fut.result()
                futures[k] = None  # drop the reference: the scheduler may forget the result
        finally:
            self._cancel(futures)

    def as_completed(self, fn: Callable[[Any], Any], iterable: Iterable[Any]) -> Iterator[tuple[int, Any]]:
        """Submit every task now; yield ``(index, result)`` in completion order."""
        from distributed import as_completed

        futures = self._submit(fn, list(iterable))
        index = {fut.key: i for i, fut in enumerate(futures)}
        try:
            for fut in as_completed(futures):
                i = index[fut.key]
                yield i, fut.result()
                futures[i] = None
        finally:
            self._cancel(futures)

    def _cancel(self, futures: list[Any]) -> None:
        left = [f for f in futures if f is not None and not f.done()]
        if left:
            try:
                self.client.cancel(left)
            except Exception:  # noqa: BLE001 - the cluster may be gone already
                pass

    def __repr__(self) -> str:
        return f"DaskExecutor({self.client!r})"


def _is_dask_client(obj: Any) -> bool:
    return type(obj).__module__.split(".")[0] == "distributed" and hasattr(obj, "submit") and hasattr(obj, "gather")


def as_executor(workers: int | Any | None) -> Any:
    """An executor from the ``workers`` convention of :mod:`rocking.analyses.batch`.

    ``1``: this process; ``n > 1``: ``n`` local processes; ``None``: all cores; a Dask client:
    :class:`DaskExecutor`; any object with ``map`` is returned unchanged.
    """
    if workers is None:
        n = default_workers()
        return SerialExecutor() if n == 1 else LocalExecutor(n)
    if _is_dask_client(workers):  # before the `map` test: Client.map returns futures
        return DaskExecutor(workers)
    if hasattr(workers, "map"):
        return workers
    if isinstance(workers, bool) or not isinstance(workers, int):
        raise TypeError(f"workers must be an int, a Dask client or an executor, got {workers!r}")
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers}")
    return SerialExecutor() if workers == 1 else LocalExecutor(workers)
