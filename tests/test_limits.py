"""Resources are bounded (issue 10, section 3): the saved series, the ``--out`` files, animations,
record files and study chunks are checked before the work starts, and a refusal is one line that
names what to change, with exit code 2.

The runs here are a few seconds of motion: the checks are about counts, not about long runs.
"""

from __future__ import annotations

import os
from collections import namedtuple
from pathlib import Path

import numpy as np
import pytest

import rocking as rk
from rocking.analyses.executors import SerialExecutor
from rocking.analyses.store import ChunkStore, CorruptChunkError, StudyInterrupted, run_chunks
from rocking.cli import main
from rocking.io import output
from rocking.io.config import ConfigError, load_config
from rocking.io.output import estimate_output_bytes, planned_samples, write_outputs
from rocking.io.records import MAX_RECORD_BYTES, RecordError, read_record, record_size_limit
from rocking.runner import run_response

TOML = """\
[statue]
width = 0.3
height = 1.2
mass = 100.0

[pedestal]
mass = 50.0
friction = { static = 0.2, kinetic = 0.15 }

[motion]
kind = "harmonic"
amplitude = 3.0
frequency = 1.5
cycles = 2

[simulation]
duration = 2.0
"""
# duration 2 s at save_dt 0.01 s: 201 samples on the grid


def _toml(tmp_path: Path, extra: str = "") -> Path:
    f = tmp_path / "run.toml"
    f.write_text(TOML + extra, encoding="utf-8")
    return f


def _cli(capsys, *args) -> tuple[int, str, str]:
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


# ----------------------------------------------------------------------- saved samples
def test_a_run_over_max_samples_is_refused_naming_the_fields(tmp_path, capsys):
    out = tmp_path / "out"
    code, stdout, err = _cli(capsys, "run", _toml(tmp_path), "--max-samples", "100", "--out", out)
    assert code == 2
    assert stdout == ""
    line = err.strip()
    assert line.startswith("error: simulation.save_dt") and "\n" not in line
    assert "201 samples" in line and "max_samples" in line
    assert "Traceback" not in err
    assert not out.exists() and not list(tmp_path.glob(".out*"))  # refused before anything is written


def test_max_samples_from_the_config_and_the_flag_overrides_it(tmp_path, capsys):
    cfg = _toml(tmp_path, "max_samples = 150\n")
    code, _, err = _cli(capsys, "run", cfg, "--json")
    assert code == 2 and "simulation.max_samples = 150" in err
    code, out, err = _cli(capsys, "run", cfg, "--json", "--max-samples", "1000")
    assert code == 0, err
    assert '"overturned"' in out


def test_the_flag_is_on_every_command_that_keeps_the_series(tmp_path, capsys):
    cfg = _toml(tmp_path)
    for command, extra in (("report", ["--out", tmp_path / "rep"]), ("animate", ["--out", tmp_path / "a.gif"])):
        code, _, err = _cli(capsys, command, cfg, "--max-samples", "10", *extra)
        assert code == 2, (command, err)
        assert "simulation.max_samples = 10" in err
    assert not (tmp_path / "rep").exists() and not (tmp_path / "a.gif").exists()


def test_planned_samples_match_the_solver(tmp_path):
    cfg = load_config(_toml(tmp_path))
    system, motion, options, duration = cfg.to_specs()
    n = planned_samples(motion, options, duration)
    assert n == 201
    r = rk.simulate(system, motion, duration=duration, options=options)
    assert n <= r.t.size <= n + 2 * len(r.events) + 2  # the grid, plus a row per event


# ------------------------------------------------------------------------------ --out
def test_output_estimate_bounds_the_files(tmp_path):
    cfg = load_config(_toml(tmp_path))
    _, response = run_response(cfg)
    files = write_outputs(response, tmp_path / "o", config=cfg)
    est = estimate_output_bytes(response.t.size)
    for name in ("timeseries.csv", "timeseries.nc"):
        size = files[name].stat().st_size
        assert size <= est[name], name
    total = sum(p.stat().st_size for p in files.values())
    assert total <= est["total"]


def test_out_larger_than_the_free_space_is_refused_before_running(tmp_path, capsys, monkeypatch):
    Usage = namedtuple("Usage", "total used free")
    monkeypatch.setattr(output.shutil, "disk_usage", lambda path: Usage(10**9, 10**9 - 20_000, 20_000))
    out = tmp_path / "deep" / "out"
    code, stdout, err = _cli(capsys, "run", _toml(tmp_path), "--out", out)
    assert code == 2
    assert err.startswith("error: --out: 201 saved samples would write up to")
    assert "is free on" in err and "save_dt" in err
    assert not (tmp_path / "deep").exists()


def test_csv_written_in_blocks_is_the_same_file(tmp_path, monkeypatch):
    cfg = load_config(_toml(tmp_path))
    _, response = run_response(cfg)
    write_outputs(response, tmp_path / "whole", config=cfg)
    monkeypatch.setattr(output, "_CSV_BLOCK_ROWS", 7)  # 201 rows in 29 blocks
    write_outputs(response, tmp_path / "blocks", config=cfg)
    assert (tmp_path / "blocks" / "timeseries.csv").read_bytes() == (tmp_path / "whole" / "timeseries.csv").read_bytes()


def test_the_figure_draws_a_bounded_envelope_keeping_the_peaks():
    t = np.linspace(0.0, 1000.0, 1_000_001)
    y = np.sin(2 * np.pi * 3 * t) * np.exp(-t / 300)
    y[123_457] = 5.0  # one spike
    ts, ys = output._envelope(t, y, points=2000)
    assert ys.size <= 2000 + 2 + 1000
    assert ys.max() == 5.0 and ys.min() == y.min()
    assert np.all(np.diff(ts) > 0) and ts[0] == t[0] and ts[-1] == t[-1]
    short_t, short_y = output._envelope(t[:100], y[:100], points=2000)
    assert short_y.size == 100  # short series are drawn as they are


def test_regime_patches_closer_than_a_pixel_are_merged():
    t = np.arange(10.0)
    regime = np.array([1, 0, 1, 0, 1, 1, 0, 0, 0, 1])
    assert output._regime_intervals(t, regime, 1).tolist() == [[0, 1], [2, 3], [4, 6], [9, 9]]
    assert output._regime_intervals(t, regime, 1, resolution=1.5).tolist() == [[0, 6], [9, 9]]


# ------------------------------------------------------------------------- animations
def test_an_animation_over_the_frame_limit_is_refused_before_running(tmp_path, capsys):
    cfg = _toml(tmp_path)  # 2 s at 25 frames/s: 50 frames
    gif = tmp_path / "a.gif"
    code, _, err = _cli(capsys, "animate", cfg, "--out", gif, "--max-frames", "20")
    assert code == 2
    assert "would draw 50 frames" in err and "over the limit of 20 frames" in err
    assert "raise --speed to 2.5 or more" in err
    assert not gif.exists()
    code, _, err = _cli(capsys, "animate", cfg, "--out", gif, "--max-frames", "20", "--speed", "2.5")
    assert code == 0, err
    assert gif.stat().st_size > 0


# ---------------------------------------------------------------------------- records
def _two_column(path: Path, rows: int) -> Path:
    t = np.arange(rows) * 0.01
    with open(path, "w", encoding="ascii") as f:
        f.write("Time[s] Accel[g]\n")
        np.savetxt(f, np.column_stack([t, 0.1 * np.sin(t)]), fmt="%.4f %.6f")
    return path


def test_a_record_over_the_size_limit_is_refused_before_reading(tmp_path, monkeypatch):
    rec = _two_column(tmp_path / "long.txt", 20_000)
    size = rec.stat().st_size
    assert read_record(rec).n == 20_000  # under the default limit
    with pytest.raises(RecordError) as info:
        read_record(rec, max_bytes=100_000)
    msg = str(info.value)
    assert msg.startswith(f"{rec}: the file is {size / 1e6:.3g} MB, over the 0.1 MB limit")
    assert "ROCKING_MAX_RECORD_MB=1" in msg
    monkeypatch.setenv("ROCKING_MAX_RECORD_MB", "0.1")
    assert record_size_limit() == 100_000
    with pytest.raises(RecordError, match="over the 0.1 MB limit"):
        read_record(rec)
    # the file is never opened: the reader that would parse it is not reached
    monkeypatch.setattr("rocking.io.records._read_lines", lambda path: pytest.fail("read a refused file"))
    with pytest.raises(RecordError):
        read_record(rec)


def test_the_record_limit_reaches_the_config_and_the_cli(tmp_path, monkeypatch, capsys):
    _two_column(tmp_path / "long.txt", 20_000)
    cfg = tmp_path / "rec.toml"
    cfg.write_text('[statue]\nwidth = 0.3\nheight = 1.2\nmass = 100.0\n[motion]\nkind = "record"\npath = "long.txt"\n',
                   encoding="utf-8")
    monkeypatch.setenv("ROCKING_MAX_RECORD_MB", "0.1")
    with pytest.raises(ConfigError, match="motion.path.*over the 0.1 MB limit"):
        load_config(cfg)
    code, _, err = _cli(capsys, "run", cfg)
    assert code == 2 and "over the 0.1 MB limit for a record" in err
    monkeypatch.setenv("ROCKING_MAX_RECORD_MB", "lots")
    with pytest.raises(ValueError, match="ROCKING_MAX_RECORD_MB must be a positive number"):
        record_size_limit()
    monkeypatch.delenv("ROCKING_MAX_RECORD_MB")
    assert record_size_limit() == MAX_RECORD_BYTES == 50_000_000


# ----------------------------------------------------------------------------- studies
def _square(x):
    return np.array([x * x])


def test_a_corrupted_chunk_names_its_file_and_suggests_fresh(tmp_path):
    store = ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=3)
    run_chunks(_square, [1, 2, 3], store=store, workers=1)
    bad = store.path(1)
    bad.write_bytes(bad.read_bytes()[:40])  # a truncated file
    store = ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=3)
    with pytest.raises(CorruptChunkError) as info:
        run_chunks(_square, [1, 2, 3], store=store, workers=1)
    assert str(info.value).startswith(f"{bad}: corrupted chunk file")
    assert "--fresh" in str(info.value) and info.value.path == bad
    # deleting the file reruns its runs only
    bad.unlink()
    assert [int(r[0]) for r in run_chunks(_square, [1, 2, 3], store=store, workers=1)] == [1, 4, 9]


def test_an_unreadable_manifest_is_named_and_fresh_clears_it(tmp_path):
    ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=2).save(0, np.zeros(1))
    (tmp_path / "s" / "manifest.json").write_text("{not json", encoding="utf-8")
    with pytest.raises(CorruptChunkError, match=r"manifest.json: unreadable manifest.*--fresh"):
        ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=2)
    again = ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=2, fresh=True)
    assert again.done() == []


class _StopAt:
    """A serial executor whose third task is interrupted (as Ctrl-C would)."""

    def map(self, fn, items):  # pragma: no cover - run_chunks uses as_completed
        return (x for _, x in self.as_completed(fn, items))

    def as_completed(self, fn, items):
        for i, x in enumerate(items):
            if i == 2:
                raise KeyboardInterrupt
            yield i, fn(x)


def test_an_interrupted_study_says_how_many_runs_are_saved(tmp_path):
    store = ChunkStore(tmp_path / "s", study="demo", fingerprint="f", n_chunks=4)
    with pytest.raises(StudyInterrupted) as info:
        run_chunks(_square, [1, 2, 3, 4], store=store, workers=_StopAt(), sizes=[5, 5, 5, 5])
    assert (info.value.saved, info.value.total) == (10, 20)
    assert str(info.value) == "interrupted: 10 of 20 runs saved; rerun the same command to resume"
    assert isinstance(info.value, KeyboardInterrupt)
    seen = []
    out = run_chunks(_square, [1, 2, 3, 4], store=store, workers=SerialExecutor(), sizes=[5, 5, 5, 5],
                     progress=lambda d, t: seen.append(d))
    assert seen[0] == 10 and [int(r[0]) for r in out] == [1, 4, 9, 16]
    # without a folder nothing is saved: a plain KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt) as plain:
        run_chunks(_square, [1, 2, 3, 4], workers=_StopAt())
    assert not isinstance(plain.value, StudyInterrupted)


def test_the_fragility_count_covers_every_intensity_measure():
    from rocking.cli.studies import _whole_study

    with pytest.raises(StudyInterrupted) as info, _whole_study({"pga": 30, "pgv": 20}, "pgv"):
        raise StudyInterrupted(4, 20, "x/chunks-pgv")
    assert (info.value.saved, info.value.total) == (34, 50)


def test_help_documents_the_limits(capsys):
    assert main(["run", "--help"]) == 0
    assert "--max-samples" in capsys.readouterr().out
    assert main(["animate", "--help"]) == 0
    assert "--max-frames" in capsys.readouterr().out
    assert os.environ.get("ROCKING_MAX_RECORD_MB") is None


def test_run_animate_plays_a_long_run_faster_within_the_frame_limit(tmp_path, capsys, monkeypatch):
    import sys

    from PIL import Image

    limits = sys.modules["rocking.cli.limits"]  # where the GIF's speed rule lives

    monkeypatch.setattr(limits, "MAX_FRAMES", 20)  # 2 s at 25 frames/s would be 50
    code, _, err = _cli(capsys, "run", _toml(tmp_path), "--out", tmp_path / "o", "--animate", "--json")
    assert code == 0, err
    assert "animation.gif plays 2.5 times faster than real time (at most 20 frames)" in err
    with Image.open(tmp_path / "o" / "animation.gif") as gif:
        assert gif.n_frames <= 20
