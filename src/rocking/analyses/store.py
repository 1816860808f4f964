"""Resumable studies: every finished chunk of runs is saved at once, and a restart runs only the
missing ones.

A study folder holds ``manifest.json`` (the study's name, the hash of its inputs, the number of
chunks) and one ``chunk-NNNNNN.npz`` per finished chunk. Every file is written to a temporary
name in the same folder and then renamed with :func:`os.replace`, so a file either is complete
or does not exist, even if the process is killed (SIGKILL, power cut) while writing it. On a
restart the manifest's hash must match the inputs of the study being run: the folder of a
different study (or of the same study with changed inputs) is refused unless ``fresh=True``,
which empties it first.

An interrupted :func:`run_chunks` (Ctrl-C, or SIGTERM turned into a ``KeyboardInterrupt`` by the
command line) raises :class:`StudyInterrupted`, which says how many runs are saved; a chunk file
that cannot be read (a damaged disk, an edited file) raises :class:`CorruptChunkError` naming it.

    >>> store = ChunkStore("out/chunks", study="demo", fingerprint=fingerprint({"a": 1}), n_chunks=3)  # doctest: +SKIP
    >>> results = run_chunks(task, payloads, store=store, workers=2)                                   # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import re
import signal
import time
import uuid
import zipfile
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .executors import as_executor

__all__ = [
    "ChunkStore", "CorruptChunkError", "Run", "StoreMismatchError", "StudyInterrupted", "chunk_ranges",
    "default_chunk_size", "fingerprint", "run_chunks", "run_stored", "scale_motion",
]

MANIFEST = "manifest.json"
_CHUNK = re.compile(r"^chunk-(\d{6})\.npz$")
_ARRAY_KEY = "__array__"
_FORMAT = 1


class StoreMismatchError(ValueError):
    """The study folder holds the chunks of other inputs (or of another study)."""


class CorruptChunkError(StoreMismatchError):
    """A saved chunk (or the manifest) cannot be read; the message names the file.

    Chunks are written atomically, so this means a damaged disk or a file changed by hand; the
    way out is to delete that file (its runs are redone) or to start afresh (``--fresh``).

    Attributes
    ----------
    path : pathlib.Path
        The unreadable file.
    """

    def __init__(self, path: Path, problem: str):
        self.path = Path(path)
        super().__init__(
            f"{path}: {problem}; delete this file to rerun its runs, or start the study afresh "
            f"with --fresh (fresh=True in Python)"
        )


class StudyInterrupted(KeyboardInterrupt):
    """A study stopped by Ctrl-C (or SIGTERM) after saving ``saved`` of its ``total`` runs.

    A ``KeyboardInterrupt``, so that code that handles Ctrl-C handles it; its text is the line the
    command line prints.

    Attributes
    ----------
    saved, total : int
        Runs saved in the study folder (including those of earlier sessions), and all its runs.
    folder : pathlib.Path
        The study folder (the chunks).
    signum : int
        The signal that stopped it (``signal.SIGINT`` for Ctrl-C).
    """

    def __init__(self, saved: int, total: int, folder: str | os.PathLike[str],
                 signum: int = signal.SIGINT):
        self.saved, self.total = int(saved), int(total)
        self.folder = Path(folder)
        self.signum = int(signum)
        super().__init__(f"interrupted: {self.saved} of {self.total} runs saved; "
                         f"rerun the same command to resume")


# --------------------------------------------------------------------------- fingerprint
def _feed(h: Any, obj: Any) -> None:
    """Feed a canonical encoding of ``obj`` into the hash ``h`` (type-tagged, order-stable)."""
    if obj is None or isinstance(obj, (bool, str)):
        h.update(f"{type(obj).__name__}:{obj!r};".encode())
    elif isinstance(obj, (int, np.integer)):
        h.update(f"int:{int(obj)};".encode())
    elif isinstance(obj, (float, np.floating)):
        h.update(f"float:{float(obj)!r};".encode())
    elif isinstance(obj, os.PathLike):
        h.update(f"path:{os.fspath(obj)!r};".encode())
    elif isinstance(obj, np.ndarray):
        arr = np.ascontiguousarray(obj)
        h.update(f"ndarray:{arr.dtype.str}:{arr.shape};".encode())
        h.update(arr.tobytes())
    elif type(obj).__name__ == "GroundMotion":
        # the samples and the name decide the results; the file's location does not
        h.update(b"GroundMotion{")
        for name in ("name", "time", "values", "vertical"):
            h.update(name.encode())
            _feed(h, getattr(obj, name))
        h.update(b"}")
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        h.update(f"{type(obj).__module__}.{type(obj).__qualname__}{{".encode())
        for f in dataclasses.fields(obj):
            if f.compare:
                h.update(f.name.encode() + b"=")
                _feed(h, getattr(obj, f.name))
        h.update(b"}")
    elif isinstance(obj, Mapping):
        h.update(b"{")
        for key in sorted(obj, key=str):
            _feed(h, str(key))
            _feed(h, obj[key])
        h.update(b"}")
    elif isinstance(obj, (list, tuple)):
        h.update(f"seq{len(obj)}[".encode())
        for item in obj:
            _feed(h, item)
        h.update(b"]")
    else:
        raise TypeError(f"cannot fingerprint a {type(obj).__name__}")


def fingerprint(obj: Any) -> str:
    """SHA-256 (hex) of a canonical encoding of nested numbers, strings, arrays, mappings,
    sequences and dataclasses (specs, motions, options). Equal inputs give equal hashes in any
    process; a recorded motion is identified by its samples and name, not its file path."""
    h = hashlib.sha256()
    _feed(h, obj)
    return h.hexdigest()


# ----------------------------------------------------------------------------- the store
def _atomic_write(path: Path, write: Callable[[Any], None]) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:8]}.tmp")
    try:
        with open(tmp, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            tmp.unlink()
        except OSError:
            pass
        raise


class ChunkStore:
    """A folder of finished chunks for one study.

    Parameters
    ----------
    folder : path-like
        Created if needed.
    study : str
        The study's kind ("design", "fragility", "spectrum", …), stored in the manifest.
    fingerprint : str
        Hash of everything that decides the results (see :func:`fingerprint`), including how
        the work is cut into chunks.
    n_chunks : int
    meta : mapping, optional
        JSON-serialisable description of the inputs, kept in the manifest for the reader.
    fresh : bool
        Empty a folder that holds another study instead of refusing it.

    Raises
    ------
    StoreMismatchError
        If the folder's manifest belongs to other inputs and ``fresh`` is False.
    """

    def __init__(
        self,
        folder: str | os.PathLike[str],
        *,
        study: str,
        fingerprint: str,
        n_chunks: int,
        meta: Mapping[str, Any] | None = None,
        fresh: bool = False,
    ):
        self.folder = Path(folder)
        self.study = str(study)
        self.fingerprint = str(fingerprint)
        self.n_chunks = int(n_chunks)
        if self.folder.exists() and not self.folder.is_dir():
            raise StoreMismatchError(f"{self.folder} exists and is not a directory")
        self.folder.mkdir(parents=True, exist_ok=True)
        try:
            manifest = self._read_manifest()
        except CorruptChunkError:
            if not fresh:
                raise
            manifest = {}  # fresh: an unreadable manifest is cleared like a foreign one
        if manifest is not None:
            same = (
                manifest.get("fingerprint") == self.fingerprint
                and manifest.get("study") == self.study
                and int(manifest.get("n_chunks", -1)) == self.n_chunks
            )
            if not same:
                if not fresh:
                    raise StoreMismatchError(
                        f"{self.folder} holds the chunks of another {manifest.get('study', 'study')} "
                        f"(its inputs differ from these); choose another folder or start afresh "
                        f"(fresh=True, --fresh on the command line)"
                    )
                self.clear()
                manifest = None
        elif fresh:
            self.clear()
        elif any(self._chunk_files()):
            raise StoreMismatchError(f"{self.folder} holds chunk files but no manifest; refusing to mix them")
        self._remove_temporaries()
        if manifest is None:
            self._write_manifest(
                {
                    "format": _FORMAT,
                    "study": self.study,
                    "fingerprint": self.fingerprint,
                    "n_chunks": self.n_chunks,
                    "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
                    "rocking_version": _version(),
                    "inputs": dict(meta or {}),
                }
            )

    # -- files
    def _read_manifest(self) -> dict[str, Any] | None:
        path = self.folder / MANIFEST
        if not path.exists():
            return None
        try:
            manifest = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise CorruptChunkError(path, f"unreadable manifest ({exc})") from None
        if not isinstance(manifest, dict):
            raise CorruptChunkError(path, "unreadable manifest (not a JSON object)")
        return manifest

    def _write_manifest(self, manifest: Mapping[str, Any]) -> None:
        text = json.dumps(manifest, indent=2, sort_keys=True, default=str) + "\n"
        _atomic_write(self.folder / MANIFEST, lambda f: f.write(text.encode("utf-8")))

    def _chunk_files(self) -> Iterable[Path]:
        return (p for p in self.folder.iterdir() if _CHUNK.match(p.name))

    def _remove_temporaries(self) -> None:
        for p in self.folder.iterdir():
            if p.name.startswith(".") and p.name.endswith(".tmp"):
                try:
                    p.unlink()
                except OSError:
                    pass

    def clear(self) -> None:
        """Delete the manifest and every chunk (the folder itself stays)."""
        for p in list(self._chunk_files()):
            p.unlink()
        (self.folder / MANIFEST).unlink(missing_ok=True)
        self._remove_temporaries()

    def path(self, index: int) -> Path:
        return self.folder / f"chunk-{int(index):06d}.npz"

    # -- chunks
    def done(self) -> list[int]:
        """Indices of the chunks already saved."""
        found = sorted(int(_CHUNK.match(p.name).group(1)) for p in self._chunk_files())  # type: ignore[union-attr]
        return [i for i in found if i < self.n_chunks]

    def missing(self) -> list[int]:
        have = set(self.done())
        return [i for i in range(self.n_chunks) if i not in have]

    def save(self, index: int, result: np.ndarray | Mapping[str, np.ndarray]) -> None:
        """Save one chunk's result (an array, or a mapping of names to arrays) atomically."""
        if not 0 <= index < self.n_chunks:
            raise IndexError(f"chunk {index} out of range 0..{self.n_chunks - 1}")
        arrays = {_ARRAY_KEY: np.asarray(result)} if not isinstance(result, Mapping) else {
            str(k): np.asarray(v) for k, v in result.items()
        }
        for key, arr in arrays.items():
            if arr.dtype == object:
                raise TypeError(f"chunk {index}: {key!r} is an object array; only plain arrays are stored")
        _atomic_write(self.path(index), lambda f: np.savez(f, **arrays))

    def load(self, index: int) -> np.ndarray | dict[str, np.ndarray]:
        """A saved chunk, as it was given to :meth:`save`.

        Raises
        ------
        CorruptChunkError
            If the file cannot be read (naming it, and suggesting ``--fresh``).
        """
        path = self.path(index)
        try:
            with np.load(path, allow_pickle=False) as z:
                data = {k: z[k] for k in z.files}
        except MemoryError:
            raise
        except Exception as exc:  # noqa: BLE001 - zipfile, zlib, numpy and OS errors alike
            if isinstance(exc, OSError) or zipfile.is_zipfile(path):
                problem = f"{type(exc).__name__}: {exc}"
            else:  # numpy's own words for it ("pickled data") would mislead
                problem = "not a NumPy .npz archive"
            raise CorruptChunkError(path, f"corrupted chunk file ({problem})") from None
        if not data:
            raise CorruptChunkError(path, "corrupted chunk file (no arrays in it)")
        if set(data) == {_ARRAY_KEY}:
            return data[_ARRAY_KEY]
        return data

    def mark_complete(self, **extra: Any) -> None:
        """Note in the manifest that every chunk is done (with optional extra fields)."""
        manifest = self._read_manifest() or {}
        manifest.update(complete=True, finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"), **extra)
        self._write_manifest(manifest)

    def __repr__(self) -> str:
        return f"ChunkStore({str(self.folder)!r}, study={self.study!r}, done={len(self.done())}/{self.n_chunks})"


def _version() -> str:
    try:
        from .. import __version__

        return str(__version__)
    except ImportError:  # pragma: no cover
        return "unknown"


# ------------------------------------------------------------------------------ running
def run_chunks(
    fn: Callable[[Any], Any],
    payloads: Sequence[Any],
    *,
    store: ChunkStore | None = None,
    workers: int | Any | None = None,
    sizes: Sequence[int] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> list[Any]:
    """``[fn(p) for p in payloads]`` on the chosen workers, saving each result as it finishes.

    Parameters
    ----------
    fn : callable
        A module-level function (it is pickled to the workers); returns an array or a mapping
        of arrays.
    payloads : sequence
        One per chunk.
    store : ChunkStore, optional
        Where finished chunks are saved; chunks already in it are loaded instead of run.
    workers : int, executor or Dask client, optional
        As in :mod:`rocking.analyses.batch`.
    sizes : sequence of int, optional
        Runs in each chunk, for the progress count (default 1 per chunk).
    progress : callable, optional
        ``progress(done, total)`` once at the start (counting the chunks found in the store)
        and after every finished chunk.

    Returns
    -------
    list
        The results, in the order of ``payloads``.

    Raises
    ------
    StudyInterrupted
        On Ctrl-C (or any ``KeyboardInterrupt``) with a ``store``: the finished chunks are saved,
        and rerunning with the same store resumes.
    CorruptChunkError
        If a saved chunk cannot be read.
    """
    n = len(payloads)
    if store is not None and store.n_chunks != n:
        raise ValueError(f"the store expects {store.n_chunks} chunks, got {n} payloads")
    weights = [1] * n if sizes is None else [int(s) for s in sizes]
    total = int(sum(weights))
    results: list[Any] = [None] * n
    have = store.done() if store is not None else []
    for i in have:
        results[i] = store.load(i)  # type: ignore[union-attr]
    todo = [i for i in range(n) if results[i] is None]
    done = total - sum(weights[i] for i in todo)
    if progress is not None:
        progress(done, total)
    if todo:
        try:
            executor = as_executor(workers)
            items = [payloads[i] for i in todo]
            if hasattr(executor, "as_completed"):
                stream = executor.as_completed(fn, items)
            else:
                stream = enumerate(executor.map(fn, items))
            for k, result in stream:
                i = todo[k]
                if store is not None:
                    store.save(i, result)
                results[i] = result
                done += weights[i]
                if progress is not None:
                    progress(done, total)
        except KeyboardInterrupt as exc:
            if store is None or isinstance(exc, StudyInterrupted):
                raise
            # counted from the folder: a chunk saved just before the interrupt counts too
            saved = sum(weights[i] for i in store.done())
            raise StudyInterrupted(saved, total, store.folder,
                                   signum=getattr(exc, "signum", signal.SIGINT)) from exc
    if store is not None:
        store.mark_complete()
    return results


def chunk_ranges(n: int, size: int) -> list[range]:
    """``range(n)`` cut into consecutive pieces of at most ``size``."""
    size = max(1, int(size))
    return [range(i, min(n, i + size)) for i in range(0, n, size)]


def default_chunk_size(n: int, *, chunks: int = 48, cap: int = 200) -> int:
    """Runs per chunk for a study of ``n`` runs: about ``chunks`` chunks, at most ``cap`` runs each.

    It depends on the study only, never on the workers, so that a study resumed with other
    workers (or on a cluster) finds its chunks.
    """
    return max(1, min(cap, math.ceil(n / max(1, chunks))))


# ------------------------------------------------------------------- runs of the solver
@dataclasses.dataclass(frozen=True)
class Run:
    """One simulation of a study: ``system`` (a System or a Stack) under ``motions[motion]``
    scaled by ``factor``.

    ``factor`` multiplies the floor acceleration (a record's samples, or a pulse's or harmonic's
    amplitude); ``duration`` (s) defaults to the motion's duration.
    """

    system: Any
    motion: str
    factor: float = 1.0
    duration: float | None = None


def scale_motion(motion: Any, factor: float) -> Any:
    """``motion`` with its acceleration multiplied by ``factor`` > 0."""
    if factor == 1.0:
        return motion
    if hasattr(motion, "scaled"):
        return motion.scaled(factor)
    if dataclasses.is_dataclass(motion) and hasattr(motion, "amplitude"):
        return dataclasses.replace(motion, amplitude=motion.amplitude * factor)
    raise TypeError(f"cannot scale a {type(motion).__name__}")


class _PortableRecord:
    """A GroundMotion in picklable form (its ``meta`` is a mappingproxy, which pickle refuses)."""

    def __init__(self, motion: Any):
        self.fields = {
            "time": np.asarray(motion.time), "values": np.asarray(motion.values), "name": motion.name,
            "source": motion.source, "units": motion.units, "meta": dict(motion.meta),
            "vertical": None if motion.vertical is None else np.asarray(motion.vertical),
        }

    def restore(self) -> Any:
        from ..excitation.record import GroundMotion

        return GroundMotion(**self.fields)


def _portable(motion: Any) -> Any:
    return _PortableRecord(motion) if type(motion).__name__ == "GroundMotion" else motion


def _run_runs(payload: tuple[Sequence[Run], Mapping[str, Any], Any]) -> np.ndarray:
    """Worker task: the raw summary vectors of a chunk of runs (NaN-padded to one width when the
    chunk holds stacks, see :func:`rocking.analyses.batch.pad_rows`)."""
    from ..solver.compiled import S_STATUS, STATUS_INTERRUPTED
    from ..stack.model import Stack
    from .batch import pad_rows, run_spec_raw

    runs, shipped, options = payload
    motions = {k: (m.restore() if isinstance(m, _PortableRecord) else m) for k, m in shipped.items()}
    rows = []
    for run in runs:
        motion = scale_motion(motions[run.motion], run.factor)
        row = run_spec_raw(run.system, motion, options, run.duration)
        if not isinstance(run.system, Stack) and row[S_STATUS] == STATUS_INTERRUPTED:
            # a run cut short by a signal is not a result: never let it into a saved chunk (the
            # signal normally raises on its own; this holds even where it was ignored)
            raise KeyboardInterrupt("a run of the chunk was interrupted")
        rows.append(row)
    return pad_rows(rows)


def run_stored(
    runs: Sequence[Run],
    motions: Mapping[str, Any],
    *,
    options: Any,
    study: str = "runs",
    folder: str | os.PathLike[str] | None = None,
    fresh: bool = False,
    workers: int | Any | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    meta: Mapping[str, Any] | None = None,
) -> np.ndarray:
    """Raw summary vectors (one row per run) of ``runs``, chunked, and saved to ``folder``.

    A run's ``system`` is a :class:`~rocking.models.bodies.System` (the compiled solver) or a
    :class:`~rocking.stack.Stack` (the stack engine); rows of stacks are NaN-padded to one width,
    and :func:`rocking.analyses.batch.specs_dataset` turns them into summaries. Each chunk
    carries only the motions its runs use (a record is sent once per chunk, not once per run).
    With ``folder`` the study resumes where it stopped; see :class:`ChunkStore`.
    """
    from ..solver.compiled import N_SUMMARY
    from .batch import STACK_BLOCK_FIELDS, STACK_INTERFACE_FIELDS, STACK_RUN_FIELDS, pad_rows, spec_kind

    runs = list(runs)
    if not runs:
        raise ValueError("a study needs at least one run")
    for i, run in enumerate(runs):
        spec_kind(run.system, f"runs[{i}].system")
    size = int(chunk_size) if chunk_size is not None else default_chunk_size(len(runs))
    pieces = chunk_ranges(len(runs), size)
    payloads = []
    for r in pieces:
        part = [runs[i] for i in r]
        keys = sorted({run.motion for run in part})
        payloads.append((part, {k: _portable(motions[k]) for k in keys}, options))
    store = None
    if folder is not None:
        fp = fingerprint({"study": study, "runs": runs, "motions": dict(motions), "options": options,
                          "chunk_size": size, "version": _version(),
                          # a store written with another layout of the raw rows is not resumed
                          "summary_width": N_SUMMARY,
                          "stack_layout": (STACK_RUN_FIELDS, STACK_BLOCK_FIELDS, STACK_INTERFACE_FIELDS)})
        store = ChunkStore(folder, study=study, fingerprint=fp, n_chunks=len(payloads), meta=meta, fresh=fresh)
    parts = run_chunks(_run_runs, payloads, store=store, workers=workers, sizes=[len(r) for r in pieces],
                       progress=progress)
    return pad_rows(parts)
