"""Resumable studies: fingerprints, atomic chunk files, and a study killed with SIGKILL that
finishes, after a restart, with exactly the results of an uninterrupted one."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import rocking as rk
from rocking.analyses.executors import LocalExecutor, SerialExecutor, as_executor
from rocking.analyses.store import ChunkStore, Run, StoreMismatchError, fingerprint, run_chunks, run_stored

G = 9.81


# --------------------------------------------------------------------------- fingerprints
def test_fingerprint_is_stable_and_sensitive():
    from rocking.io.records import read_record

    st = rk.Statue(width=0.4, height=1.6, mass=200.0)
    a = {"system": rk.System(statue=st), "levels": [1.0, 2.0], "options": rk.Options()}
    assert fingerprint(a) == fingerprint(dict(reversed(list(a.items()))))  # key order does not matter
    assert fingerprint(a) != fingerprint({**a, "levels": [1.0, 2.0000001]})
    assert fingerprint(a) != fingerprint({**a, "system": rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=201.0))})
    assert fingerprint(a) != fingerprint({**a, "options": rk.Options(gravity=G)})
    assert fingerprint([1, 2]) != fingerprint([2, 1]) and fingerprint(1) != fingerprint(1.0)
    rec = read_record("Northridge1994_RinaldiReceivingSta_228")
    assert fingerprint(rec) == fingerprint(read_record("Northridge1994_RinaldiReceivingSta_228"))
    assert fingerprint(rec) != fingerprint(rec.scaled(1.0000001))
    with pytest.raises(TypeError):
        fingerprint(object())


# ------------------------------------------------------------------------------ the store
def test_chunks_round_trip_and_a_foreign_folder_is_refused(tmp_path):
    store = ChunkStore(tmp_path / "s", study="demo", fingerprint="abc", n_chunks=3, meta={"x": 1})
    assert store.missing() == [0, 1, 2]
    store.save(1, np.arange(6.0).reshape(2, 3))
    store.save(2, {"a": np.array([1, 2]), "flag": np.array([True, False]), "name": np.array(["x", "yz"])})
    np.testing.assert_array_equal(store.load(1), np.arange(6.0).reshape(2, 3))
    got = store.load(2)
    assert got["name"].tolist() == ["x", "yz"] and got["flag"].dtype == bool
    assert store.done() == [1, 2] and store.missing() == [0]
    assert not [p for p in (tmp_path / "s").iterdir() if p.name.endswith(".tmp")]
    # reopening with the same inputs keeps the chunks; other inputs are refused or cleared
    assert ChunkStore(tmp_path / "s", study="demo", fingerprint="abc", n_chunks=3).done() == [1, 2]
    with pytest.raises(StoreMismatchError, match="fresh"):
        ChunkStore(tmp_path / "s", study="demo", fingerprint="other", n_chunks=3)
    fresh = ChunkStore(tmp_path / "s", study="demo", fingerprint="other", n_chunks=3, fresh=True)
    assert fresh.done() == []
    # a temporary file left by a killed writer is not a chunk and is cleaned up
    (tmp_path / "s" / ".chunk-000000.npz.123-abcd.tmp").write_bytes(b"partial")
    again = ChunkStore(tmp_path / "s", study="demo", fingerprint="other", n_chunks=3)
    assert again.done() == [] and not list((tmp_path / "s").glob(".*.tmp"))


def _square(x):
    return np.array([x * x])


def test_run_chunks_saves_each_result_and_skips_saved_ones(tmp_path):
    store = ChunkStore(tmp_path, study="sq", fingerprint="f", n_chunks=5)
    store.save(3, np.array([-1]))  # pretend chunk 3 finished earlier (with a marker value)
    seen = []
    out = run_chunks(_square, list(range(5)), store=store, workers=2, progress=lambda d, t: seen.append((d, t)))
    assert [int(r[0]) for r in out] == [0, 1, 4, -1, 16]
    assert seen[0] == (1, 5) and seen[-1] == (5, 5) and len(seen) == 5
    assert store.done() == [0, 1, 2, 3, 4]


def test_executors():
    assert isinstance(as_executor(1), SerialExecutor) and isinstance(as_executor(3), LocalExecutor)
    ex = LocalExecutor(2)
    assert list(ex.map(_square, range(6))) == [np.array([i * i]) for i in range(6)]
    got = dict(ex.as_completed(_square, range(7)))
    assert sorted(got) == list(range(7)) and all(int(got[i][0]) == i * i for i in got)
    with pytest.raises(ValueError):
        as_executor(0)


# ------------------------------------------------------------------ kill and resume
RECORDS = ("Northridge1994_RinaldiReceivingSta_228", "Kobe1995_Takatori_000", "LomaPrieta1989_Corralitos_000",
           "Northridge1994_CastaicOldRidgeRoute_090_2col")
CHUNK = 2


def run_study(folder, workers, progress=None):
    """The study of the kill test (also run by the subprocess): an IDA of 4 records × 2 systems
    × 12 levels in chunks of 2 runs."""
    from rocking.analyses.fragility import ida, load_record_set

    statue = rk.Statue(width=0.4, height=1.6, mass=200.0, friction=rk.Friction(static=0.5))
    pedestal = rk.Pedestal(mass=300.0, friction=rk.Friction(static=0.15, kinetic=0.12))
    systems = {"alone": rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0)),
               "on pedestal": rk.System(statue=statue, pedestal=pedestal)}
    records = load_record_set(list(RECORDS))
    return ida(systems, records, np.linspace(1.0, 12.0, 12), options=rk.Options(gravity=G), workers=workers,
               folder=folder, chunk_size=CHUNK, progress=progress)


N_CHUNKS = len(RECORDS) * 2 * 12 // CHUNK

SCRIPT = """
import sys
sys.path.insert(0, {tests!r})
import test_store
test_store.run_study({folder!r}, workers=2)
print("finished")
"""


def test_study_killed_with_sigkill_resumes_to_identical_results(tmp_path):
    folder = tmp_path / "study"
    script = tmp_path / "run.py"
    script.write_text(SCRIPT.format(tests=str(Path(__file__).parent), folder=str(folder)))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)  # its own process group: the kill reaches the workers too
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and proc.poll() is None:
            if folder.is_dir() and len(list(folder.glob("chunk-*.npz"))) >= 6:
                break
            time.sleep(0.005)
        assert proc.poll() is None, f"the study ended before it could be killed: {proc.communicate()}"
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == -signal.SIGKILL
    saved = sorted(folder.glob("chunk-*.npz"))
    assert 6 <= len(saved) < N_CHUNKS, "killed mid-way"
    for p in saved:  # every chunk on disk is complete (atomic rename), whatever the moment of the kill
        with np.load(p) as z:
            assert z["__array__"].shape[0] == CHUNK

    seen = []
    resumed = run_study(folder, workers=1, progress=lambda d, t: seen.append((d, t)))
    assert seen[0] == (len(saved) * CHUNK, N_CHUNKS * CHUNK)  # the saved chunks were not rerun
    assert seen[-1] == (N_CHUNKS * CHUNK, N_CHUNKS * CHUNK)
    uninterrupted = run_study(None, workers=1)
    xr.testing.assert_identical(resumed, uninterrupted)
    assert not list(folder.glob(".*.tmp"))


def test_run_stored_ships_each_record_once_per_chunk(tmp_path):
    from rocking.io.records import read_record

    rec = read_record(RECORDS[0])
    st = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0))
    runs = [Run(st, "r", f) for f in (0.5, 1.0, 2.0)]
    raw = run_stored(runs, {"r": rec}, options=rk.Options(gravity=G), folder=tmp_path / "s", chunk_size=2, workers=2)
    assert raw.shape[0] == 3
    again = run_stored(runs, {"r": rec}, options=rk.Options(gravity=G), folder=tmp_path / "s", chunk_size=2, workers=1)
    np.testing.assert_array_equal(raw, again)
    with pytest.raises(StoreMismatchError):
        run_stored(runs[:2], {"r": rec}, options=rk.Options(gravity=G), folder=tmp_path / "s", chunk_size=2)
