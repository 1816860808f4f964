"""Interrupting is safe (issue 10, section 4): Ctrl-C (SIGINT) and SIGTERM sent to the command line
while it simulates, writes its outputs or runs a study.

Each test starts ``python -m rocking.cli`` as a subprocess, waits until it is busy (CPU time spent
in the compiled loop, a temporary output folder, saved chunks), sends the signal and checks: the
exit code (130 Ctrl-C, 143 SIGTERM), a one-line message and no traceback or crash (a negative
return code would be a death by signal, e.g. a segmentation fault), and nothing temporary left.
A study interrupted this way resumes when the same command is run again.
"""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import rocking as rk
from rocking.analyses.store import chunk_ranges, default_chunk_size

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

# A pedestal sliding on very low friction under a slow harmonic, with a small largest step: about
# a million solver steps per simulated second, so the run stays inside the compiled loop for
# minutes; only every 10 s is saved (100 000 samples: little memory).
LONG_RUN = """\
[statue]
width = 0.3
height = 1.2
mass = 100.0

[pedestal]
mass = 50.0
friction = { static = 0.01, kinetic = 0.01 }

[motion]
kind = "harmonic"
amplitude = 1.0
frequency = 0.01
cycles = 10000

[simulation]
duration = 1000000.0
save_dt = 10.0
max_step = 0.001
"""

# At rest under a weak harmonic, saved every 5 ms for 10 000 s: 2 million samples, simulated in a
# second; writing timeseries.csv and timeseries.nc takes several seconds.
BIG_OUTPUT = """\
[statue]
width = 0.3
height = 1.2
mass = 100.0

[motion]
kind = "harmonic"
amplitude = 0.5
frequency = 1.5
cycles = 15000

[simulation]
duration = 10000.0
save_dt = 0.005
"""

# A friction design over a harmonic family: 4 motions x 9 frictions x 3 scatter levels = 108 runs
# of 65 s each at a small largest step, some 10 s of work in all.
SLOW_DESIGN = """\
[statue]
width = 0.4
height = 1.6
mass = 200.0

[pedestal]
mass = 300.0
friction = { static = 0.3, kinetic = 0.25 }

[motions]
family = "harmonic"
amplitude = [3.0, 4.0]
frequency = [1.0, 2.0]
cycles = 60

[design]
mu_s = { start = 0.05, stop = 0.45, num = 9 }
mu_k_ratio = 0.8
free_time = 5.0

[simulation]
max_step = 0.0005
"""

SAVED = re.compile(r"^interrupted: (\d+) of (\d+) runs saved; rerun the same command to resume$")


@pytest.fixture(scope="module", autouse=True)
def compiled():
    """Compile (or load) the solver here, so that the subprocesses find it in the disk cache."""
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    rk.simulate(rk.System(statue=statue), rk.Harmonic(amplitude=1.0, frequency=1.0, cycles=1))


def _as_at_a_terminal() -> None:
    # A command started in the background by a non-interactive shell (`pytest … &`, a CI runner, a
    # mutation worker) inherits SIGINT ignored, and Python then leaves it ignored, as it should: the
    # signal would do nothing. The tests are about a command started at a terminal.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _start(*args: str, cwd: Path) -> subprocess.Popen:
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    env.pop("ROCKING_DEBUG", None)
    return subprocess.Popen([sys.executable, "-m", "rocking.cli", *args], cwd=cwd, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=_as_at_a_terminal)


def _cpu_seconds(pid: int) -> float:
    """CPU time (user + system) the process has used, s (Linux /proc)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _wait_until(proc: subprocess.Popen, ready, timeout: float, what: str) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            out, err = proc.communicate()
            pytest.fail(f"the command ended before {what}: {proc.returncode}\n{out}\n{err}")
        if ready():
            return
        time.sleep(0.005)
    proc.kill()
    proc.communicate()
    pytest.fail(f"timed out waiting for {what}")


def _stop(proc: subprocess.Popen, sig: int, timeout: float = 15) -> tuple[str, str, float]:
    """Send ``sig``; return stdout, stderr and the seconds the process took to exit."""
    t0 = time.monotonic()
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail(f"still running {timeout} s after the signal:\n{err}")
    return out, err, time.monotonic() - t0


def _clean_exit(proc: subprocess.Popen, err: str, sig: int) -> None:
    assert proc.returncode == 128 + sig, (proc.returncode, err)  # not negative: no crash
    assert "Traceback" not in err and "Segmentation" not in err, err
    assert "error:" not in err, err


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".tmp" in p.name)


# ------------------------------------------------------------------------ rocking run
@pytest.mark.parametrize("sig, message", [(signal.SIGINT, "interrupted"), (signal.SIGTERM, "interrupted by SIGTERM")])
def test_a_signal_in_the_compiled_loop_stops_the_run_cleanly(tmp_path, sig, message):
    (tmp_path / "long.toml").write_text(LONG_RUN, encoding="utf-8")
    proc = _start("run", "long.toml", "--out", "out", cwd=tmp_path)
    # starting Python, importing and loading the cached solver take about 1 s of CPU; the run
    # itself minutes: past 3 s the process is in the compiled loop
    _wait_until(proc, lambda: _cpu_seconds(proc.pid) > 3.0, 60, "the solver was busy")
    out, err, seconds = _stop(proc, sig)
    _clean_exit(proc, err, sig)
    assert err.strip() == message
    assert seconds < 5, "the solver must notice the signal within milliseconds"
    assert out == ""
    assert not (tmp_path / "out").exists() and _leftovers(tmp_path) == []


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_while_writing_removes_the_temporary_folder(tmp_path, sig):
    (tmp_path / "big.toml").write_text(BIG_OUTPUT, encoding="utf-8")
    proc = _start("run", "big.toml", "--out", "out", "--json", cwd=tmp_path)
    _wait_until(proc, lambda: bool(list(tmp_path.glob(".out.tmp-*"))), 60, "the outputs were being written")
    time.sleep(0.3)  # into the CSV
    out, err, _ = _stop(proc, sig)
    _clean_exit(proc, err, sig)
    assert _leftovers(tmp_path) == [], "the temporary output folder must be removed"
    assert not (tmp_path / "out").exists(), "nothing half-written"
    assert out == ""


# ----------------------------------------------------------------------------- studies
def _saved_runs(chunks: Path, total: int) -> int:
    sizes = [len(r) for r in chunk_ranges(total, default_chunk_size(total))]
    return sum(sizes[int(p.stem.split("-")[1])] for p in chunks.glob("chunk-*.npz"))


def test_an_interrupted_study_says_what_is_saved_and_resumes(tmp_path):
    (tmp_path / "design.toml").write_text(SLOW_DESIGN, encoding="utf-8")
    chunks = tmp_path / "out" / "chunks"
    args = ("design", "design.toml", "--out", "out", "--workers", "2")
    proc = _start(*args, cwd=tmp_path)
    _wait_until(proc, lambda: len(list(chunks.glob("chunk-*.npz"))) >= 3, 60, "chunks were saved")
    out, err, seconds = _stop(proc, signal.SIGINT)
    _clean_exit(proc, err, signal.SIGINT)
    assert seconds < 5, "the workers are stopped, not waited for"
    m = SAVED.match(err.strip())
    assert m, err
    saved, total = int(m.group(1)), int(m.group(2))
    assert total == 108 and 0 < saved < total
    assert saved == _saved_runs(chunks, total)
    assert not list(chunks.glob(".*.tmp")) and not (tmp_path / "out" / "design_report.md").exists()
    first = {p.name: p.stat().st_mtime_ns for p in chunks.glob("chunk-*.npz")}

    # the same command resumes: the saved chunks are kept as they are, the others are run
    done = subprocess.run([sys.executable, "-m", "rocking.cli", *args], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert all((chunks / name).stat().st_mtime_ns == t for name, t in first.items())
    assert len(list(chunks.glob("chunk-*.npz"))) == math.ceil(total / default_chunk_size(total))
    assert (tmp_path / "out" / "design_report.md").is_file()


def test_sigterm_stops_a_serial_study_with_its_count(tmp_path):
    (tmp_path / "design.toml").write_text(SLOW_DESIGN, encoding="utf-8")
    chunks = tmp_path / "out" / "chunks"
    proc = _start("design", "design.toml", "--out", "out", "--workers", "1", cwd=tmp_path)
    _wait_until(proc, lambda: len(list(chunks.glob("chunk-*.npz"))) >= 2, 60, "chunks were saved")
    _, err, _ = _stop(proc, signal.SIGTERM)
    _clean_exit(proc, err, signal.SIGTERM)
    m = SAVED.match(err.strip())
    assert m, err
    assert int(m.group(1)) == _saved_runs(chunks, int(m.group(2)))
    assert not list(chunks.glob(".*.tmp"))


def test_a_corrupted_chunk_is_named_with_the_way_out(tmp_path):
    (tmp_path / "design.toml").write_text(SLOW_DESIGN, encoding="utf-8")
    chunks = tmp_path / "out" / "chunks"
    proc = _start("design", "design.toml", "--out", "out", "--workers", "1", cwd=tmp_path)
    _wait_until(proc, lambda: len(list(chunks.glob("chunk-*.npz"))) >= 1, 60, "a chunk was saved")
    _stop(proc, signal.SIGINT)
    bad = sorted(chunks.glob("chunk-*.npz"))[0]
    bad.write_bytes(b"not a chunk")
    again = subprocess.run([sys.executable, "-m", "rocking.cli", "design", "design.toml", "--out", "out",
                            "--workers", "1"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert again.returncode == 2
    assert again.stderr.startswith(f"error: {Path('out') / 'chunks' / bad.name}: corrupted chunk file")
    assert "--fresh" in again.stderr and "Traceback" not in again.stderr
