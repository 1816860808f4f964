"""Computations of the web app in worker processes, each with a time limit.

Every job runs in its own process (forked from a preloaded fork server, so it starts warm in a few
milliseconds), which keeps the server responsive: a request that waits for its run blocks only its
own thread, and a run that overruns its limit is stopped by terminating its process, without
touching anybody else's. A job reports progress and its result through a pipe; the supervising
thread in the server keeps the latest state in a :class:`Job` that a page can poll.

    >>> runner = JobRunner(max_workers=4)                                  # doctest: +SKIP
    >>> job = runner.run(tasks.run_task, {"config": cfg, "out_dir": d}, timeout=60)   # doctest: +SKIP
    >>> job.state, job.result["verdict"]                                   # doctest: +SKIP
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import threading
import time
import traceback
import uuid
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["Job", "JobRunner", "UserError"]

log = logging.getLogger("rocking.web")

#: Module imported once by the fork server: loads the package and the compiled solver.
PRELOAD = "rocking.web._preload"

QUEUED, RUNNING, DONE, FAILED, TIMEOUT = "queued", "running", "done", "failed", "timeout"


class UserError(ValueError):
    """A problem with the user's input, shown on the page as is."""


@dataclass
class Job:
    """State of one computation; updated by the supervising thread, read by the pages."""

    id: str
    kind: str
    timeout: float
    state: str = QUEUED
    done: int = 0
    total: int = 0
    label: str = ""
    result: Any = None
    error: str | None = None
    #: "input" for a problem with the inputs, "timeout", "busy" or "internal" otherwise
    error_kind: str | None = None
    created: float = field(default_factory=time.time)
    started: float | None = None
    finished: float | None = None
    _event: threading.Event = field(default_factory=threading.Event, repr=False)

    @property
    def finished_flag(self) -> bool:
        return self._event.is_set()

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the job has finished (whatever the outcome); True if it has."""
        return self._event.wait(timeout)

    def status(self) -> dict[str, Any]:
        """What a progress poll returns (JSON-ready)."""
        elapsed = None
        if self.started is not None:
            elapsed = (self.finished or time.time()) - self.started
        return {
            "id": self.id,
            "kind": self.kind,
            "state": self.state,
            "done": self.done,
            "total": self.total,
            "label": self.label,
            "error": self.error,
            "elapsed": elapsed,
        }


def _child(conn, fn: Callable[..., Any], kwargs: Mapping[str, Any]) -> None:
    """Body of a worker process: run ``fn(progress=..., **kwargs)`` and send back the outcome."""

    def progress(done: int, total: int, label: str = "") -> None:
        conn.send(("progress", int(done), int(total), str(label)))

    try:
        from ..simulation import SimulationError

        try:
            result = fn(progress=progress, **kwargs)
        except (UserError, ValueError) as exc:  # ConfigError and RecordError are ValueErrors
            conn.send(("error", "input", " ".join(str(exc).split())))
        except SimulationError as exc:
            conn.send(("error", "input", f"the simulation failed: {exc}"))
        else:
            conn.send(("result", result))
    except KeyboardInterrupt:  # Ctrl+C in the server's terminal reaches the workers too
        pass
    except BaseException as exc:  # noqa: BLE001 - the page gets one line, the log the traceback
        traceback.print_exc()
        try:
            conn.send(("error", "internal", f"unexpected {type(exc).__name__}: {exc}"))
        except Exception:  # noqa: BLE001
            pass
    finally:
        conn.close()


class JobRunner:
    """Start jobs in worker processes, at most ``max_workers`` at a time, each with a time limit.

    Parameters
    ----------
    max_workers : int, optional
        Processes running at once (default: the number of CPUs, at least 4). A job that finds
        them all busy waits for a free one up to ``queue_timeout`` seconds, then fails with
        "the server is busy".
    queue_timeout : float
        Longest wait for a free worker, s.
    context : str
        multiprocessing start method: "forkserver" (default; workers are forked from a server
        that has imported the package and loaded the compiled solver once) or "spawn".
    keep : float
        Finished jobs are forgotten after this many seconds.
    """

    def __init__(
        self,
        max_workers: int | None = None,
        *,
        queue_timeout: float = 60.0,
        context: str = "forkserver",
        keep: float = 3600.0,
    ):
        self.max_workers = max_workers or max(4, os.cpu_count() or 1)
        self.queue_timeout = queue_timeout
        self.keep = keep
        if context not in multiprocessing.get_all_start_methods():  # no fork server on Windows
            context = "spawn"
        self._ctx = multiprocessing.get_context(context)
        if context == "forkserver":
            self._ctx.set_forkserver_preload([PRELOAD])
        self._slots = threading.BoundedSemaphore(self.max_workers)
        self._lock = threading.Lock()
        self._jobs: dict[str, Job] = {}
        self._procs: dict[str, Any] = {}
        self._closed = False

    # ---------------------------------------------------------------------------- public
    def start(
        self,
        fn: Callable[..., Any],
        kwargs: Mapping[str, Any],
        *,
        timeout: float,
        kind: str = "run",
        job_id: str | None = None,
        on_done: Callable[[Job], None] | None = None,
    ) -> Job:
        """Start ``fn(progress=..., **kwargs)`` in a worker process and return its :class:`Job`
        at once. ``fn`` must be a module-level function; kwargs and result must pickle."""
        if self._closed:
            raise RuntimeError("the job runner is shut down")
        job = Job(id=job_id or uuid.uuid4().hex, kind=kind, timeout=float(timeout))
        self._prune()
        with self._lock:
            self._jobs[job.id] = job
        thread = threading.Thread(
            target=self._supervise, args=(job, fn, dict(kwargs), on_done), name=f"job-{job.id[:8]}", daemon=True
        )
        thread.start()
        return job

    def run(self, fn: Callable[..., Any], kwargs: Mapping[str, Any], *, timeout: float, kind: str = "run",
            job_id: str | None = None) -> Job:
        """Like :meth:`start`, but wait for the job to finish."""
        job = self.start(fn, kwargs, timeout=timeout, kind=kind, job_id=job_id)
        job.wait()
        return job

    def get(self, job_id: str) -> Job | None:
        with self._lock:
            return self._jobs.get(job_id)

    def active(self) -> int:
        """Worker processes alive now."""
        with self._lock:
            return sum(1 for p in self._procs.values() if p.is_alive())

    def warm_up(self) -> None:
        """Start the fork server now (in the background), so the first run does not pay for it."""
        if self._ctx.get_start_method() != "forkserver":
            return

        def go() -> None:
            try:
                from multiprocessing import forkserver

                forkserver.ensure_running()
            except Exception:  # noqa: BLE001 - the first job will try again and report
                log.exception("could not start the fork server")

        threading.Thread(target=go, name="forkserver-warm-up", daemon=True).start()

    def shutdown(self) -> None:
        """Stop every running worker (the server is going down)."""
        self._closed = True
        with self._lock:
            procs = list(self._procs.values())
        for p in procs:
            if p.is_alive():
                p.terminate()
        for p in procs:
            p.join(timeout=5)

    # --------------------------------------------------------------------------- private
    def _prune(self) -> None:
        now = time.time()
        with self._lock:
            old = [k for k, j in self._jobs.items() if j.finished is not None and now - j.finished > self.keep]
            for k in old:
                del self._jobs[k]

    def _finish(self, job: Job, state: str, *, result: Any = None, error: str | None = None,
                error_kind: str | None = None) -> None:
        job.state, job.result, job.error, job.error_kind = state, result, error, error_kind
        job.finished = time.time()
        job._event.set()

    def _supervise(self, job: Job, fn: Callable[..., Any], kwargs: dict[str, Any],
                   on_done: Callable[[Job], None] | None) -> None:
        try:
            self._supervise_inner(job, fn, kwargs)
        except Exception as exc:  # noqa: BLE001 - never leave a job hanging
            log.exception("job %s failed in the supervisor", job.id)
            if not job.finished_flag:
                self._finish(job, FAILED, error=f"unexpected {type(exc).__name__}: {exc}", error_kind="internal")
        finally:
            if on_done is not None:
                try:
                    on_done(job)
                except Exception:  # noqa: BLE001
                    log.exception("job %s: on_done failed", job.id)

    def _supervise_inner(self, job: Job, fn: Callable[..., Any], kwargs: dict[str, Any]) -> None:
        if not self._slots.acquire(timeout=self.queue_timeout):
            self._finish(
                job, FAILED, error_kind="busy",
                error=f"the server is busy ({self.max_workers} runs in progress); try again in a moment",
            )
            return
        try:
            recv, send = self._ctx.Pipe(duplex=False)
            proc = self._ctx.Process(target=_child, args=(send, fn, kwargs), name=f"rocking-{job.kind}", daemon=True)
            proc.start()
            send.close()  # the child holds the only writer: EOF when it dies
            with self._lock:
                self._procs[job.id] = proc
            job.state, job.started = RUNNING, time.time()
            deadline = time.monotonic() + job.timeout
            outcome: dict[str, Any] = {"state": FAILED, "error_kind": "internal", "error": "the worker was lost"}
            try:
                outcome = self._watch(job, proc, recv, deadline)
            finally:
                # reap the worker before the job counts as finished
                if proc.is_alive():
                    proc.terminate()
                    proc.join(timeout=5)
                    if proc.is_alive():
                        proc.kill()
                proc.join(timeout=5)
                recv.close()
                with self._lock:
                    self._procs.pop(job.id, None)
                self._finish(job, **outcome)
        finally:
            self._slots.release()

    def _watch(self, job: Job, proc, recv, deadline: float) -> dict[str, Any]:
        """Follow the worker until it answers, dies or overruns; return the job's outcome."""
        what = "design sweep" if job.kind == "sweep" else "run"
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                proc.terminate()
                return {"state": TIMEOUT, "error_kind": "timeout",
                        "error": f"the {what} took longer than {job.timeout:g} s and was stopped"}
            if not recv.poll(min(remaining, 0.5)):
                continue
            try:
                msg = recv.recv()
            except (EOFError, OSError):
                proc.join(timeout=5)
                return {"state": FAILED, "error_kind": "internal",
                        "error": f"the worker process stopped unexpectedly (exit code {proc.exitcode})"}
            tag = msg[0]
            if tag == "progress":
                job.done, job.total, job.label = msg[1], msg[2], msg[3]
            elif tag == "result":
                return {"state": DONE, "result": msg[1]}
            elif tag == "error":
                return {"state": FAILED, "error_kind": msg[1], "error": msg[2]}
