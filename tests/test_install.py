"""Installation hygiene: what pyproject.toml declares, scripts/demo.sh's output argument, Dask as an
optional extra, the permissions of written animations and the first-run compilation message."""

from __future__ import annotations

import io
import json
import os
import re
import stat
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import rocking as rk
from rocking.cli import main
from rocking.solver import warmup

from test_config import TOML

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def _name(requirement: str) -> str:
    return re.split(r"[\[<>=!~; ]", requirement, maxsplit=1)[0].lower()


@pytest.fixture
def short_toml(tmp_path) -> Path:
    f = tmp_path / "short.toml"
    f.write_text(TOML, encoding="utf-8")
    return f


# ------------------------------------------------------------------------- pyproject
def test_license_is_an_spdx_string_with_a_setuptools_that_reads_it():
    assert PYPROJECT["project"]["license"] == "BSD-3-Clause"
    assert not any(c.startswith("License ::") for c in PYPROJECT["project"].get("classifiers", []))
    setuptools = next(r for r in PYPROJECT["build-system"]["requires"] if _name(r) == "setuptools")
    floor = re.search(r">=\s*(\d+)", setuptools)
    assert floor and int(floor.group(1)) >= 77, setuptools  # PEP 639 license strings: setuptools 77


def test_dask_is_an_optional_extra_without_a_year_cap():
    deps = {_name(r): r for r in PYPROJECT["project"]["dependencies"]}
    assert "dask" not in deps and "distributed" not in deps
    extras = PYPROJECT["project"]["optional-dependencies"]
    (dask,) = extras["dask"]
    assert _name(dask) == "dask" and "distributed" in dask
    assert "<" not in dask  # calendar versions: a cap would expire within the year
    test = extras["test"]
    assert "rocking[dask]" in test  # the suite tests the Dask executor
    assert any(_name(r) == "hypothesis" for r in test)


def test_packages_imported_directly_are_declared():
    deps = {_name(r) for r in PYPROJECT["project"]["dependencies"]}
    assert {"pandas", "pillow", "numpy", "scipy", "numba", "xarray", "matplotlib", "pydantic"} <= deps


def test_nothing_imports_dask_unless_asked():
    code = (
        "import sys\n"
        "import rocking, rocking.cli.main, rocking.cli.studies, rocking.analyses.batch, rocking.analyses.design\n"
        "import rocking.analyses.executors, rocking.analyses.fragility, rocking.analyses.spectra, rocking.web.app\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert out.stdout.strip() == "[]"


def test_scheduler_without_dask_says_what_to_install(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    study = (ROOT / "examples" / "studies" / "spectrum.toml")
    code = main(["spectrum", str(study), "--out", str(tmp_path / "out"), "--scheduler", "local"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err.startswith("error: ") and "pip install 'rocking[dask]'" in err and len(err.splitlines()) == 1


# -------------------------------------------------------------------------- demo.sh
def _fake_repo(tmp_path: Path) -> tuple[Path, Path]:
    """The scripts in a copy of the repository whose .venv only logs what it is asked to do."""
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    for name in ("demo.sh", "env.sh"):
        (repo / "scripts" / name).write_text((ROOT / "scripts" / name).read_text())
    log = tmp_path / "calls.log"
    bin_dir = repo / ".venv" / "bin"
    bin_dir.mkdir(parents=True)
    for exe in ("python", "rocking"):
        f = bin_dir / exe
        f.write_text(f'#!/usr/bin/env bash\necho "{exe} $*" >> "{log}"\n')
        f.chmod(0o755)
    return repo, log


def test_demo_takes_an_output_folder_not_a_pip_extra(tmp_path):
    repo, log = _fake_repo(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    run = subprocess.run(["bash", str(repo / "scripts" / "demo.sh"), "my-out"], cwd=elsewhere,
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    calls = log.read_text().splitlines()
    installs = [c for c in calls if "install" in c and "-e" in c]
    assert installs == ["python -m pip install --quiet -e ."]  # no ".[my-out]"
    out = elsewhere / "my-out"  # relative to where the user ran it, not to the repository
    assert f"rocking paper --out {out}" in calls
    assert f"rocking run examples/statue_alone_record.toml --out {out}/record-run" in calls
    assert f"are in {out}/" in run.stdout


def test_demo_default_folder_and_usage(tmp_path):
    repo, log = _fake_repo(tmp_path)
    run = subprocess.run(["bash", str(repo / "scripts" / "demo.sh")], cwd=tmp_path, capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 0, run.stderr
    assert f"rocking paper --out {tmp_path / 'paper-out'}" in log.read_text().splitlines()
    log.unlink()
    usage = subprocess.run(["bash", str(repo / "scripts" / "demo.sh"), "--help"], capture_output=True, text=True,
                           timeout=60)
    assert usage.returncode == 0 and "usage: bash scripts/demo.sh [OUT]" in usage.stdout
    assert not log.exists()  # nothing installed or run
    two = subprocess.run(["bash", str(repo / "scripts" / "demo.sh"), "a", "b"], capture_output=True, text=True,
                         timeout=60)
    assert two.returncode == 2 and "one output folder at most" in two.stderr


# ------------------------------------------------------------------ file permissions
def test_animation_gif_has_the_permissions_of_any_new_file(capsys, short_toml, tmp_path):
    old = os.umask(0o022)
    try:
        target = tmp_path / "statue.gif"
        code = main(["animate", str(short_toml), "--out", str(target), "--fps", "2"])
        _, err = capsys.readouterr()
        assert code == 0, err
        assert stat.S_IMODE(target.stat().st_mode) == 0o644  # 0666 less the umask, not mkstemp's 0600
        assert sorted(p.name for p in tmp_path.iterdir()) == ["short.toml", "statue.gif"]  # no temporary left
    finally:
        os.umask(old)


# -------------------------------------------------------------- first-run compilation
def test_the_cache_is_warm_once_the_solver_has_run():
    rk.simulate(rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0)), rk.Harmonic(amplitude=1.0, frequency=1.0))
    assert warmup.cache_is_warm() is True


def test_an_empty_numba_cache_is_seen_as_cold(tmp_path):
    # a cache folder of its own (NUMBA_CACHE_DIR comes first in Numba's search): nothing compiled there
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    code = "from rocking.solver.warmup import cache_is_warm; print(cache_is_warm())"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120,
                         check=True)
    assert out.stdout.strip() == "False"


def test_one_compiled_version_serves_every_kind_of_run():
    """The warm-up compiles one tiny harmonic run; that covers records, pulses, pedestals, vertical
    motion and batch runs only while they all call the solver with the same argument types."""
    from rocking.analyses.batch import run_cases
    from rocking.excitation.record import GroundMotion
    from rocking.io.records import read_record
    from rocking.solver.compiled import integrate

    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.3, kinetic=0.2))
    record = read_record("Kobe1995_Takatori_000")
    rec = GroundMotion(time=record.time[:300], values=record.values[:300], vertical=0.5 * record.values[:300])
    for system in (rk.System(statue=statue), rk.System(statue=statue, pedestal=pedestal)):
        for motion in (rk.Harmonic(amplitude=3.0, frequency=1.0), rec):
            rk.simulate(system, motion)
    run_cases([(rk.System(statue=statue), rk.Harmonic(amplitude=3.0, frequency=1.0))], workers=1)
    warmup._compile()
    assert len(integrate.signatures) == 1, integrate.signatures


@pytest.fixture
def cold(monkeypatch):
    """A process that has not compiled yet, whose cache is cold; compiling takes no time here."""
    calls = []
    monkeypatch.setattr(warmup, "_done", False)
    monkeypatch.setattr(warmup, "cache_is_warm", lambda: False)
    monkeypatch.setattr(warmup, "_compile", lambda: calls.append(1))
    return calls


def test_ensure_compiled_says_what_it_does_and_how_long_it_took(cold):
    buf = io.StringIO()
    seconds = warmup.ensure_compiled(stream=buf)
    lines = buf.getvalue().splitlines()
    assert cold == [1] and seconds is not None and seconds >= 0
    assert lines[0] == ("rocking: compiling the solver (first run on this machine, about 40 s; "
                        "cached afterwards)...")
    assert re.fullmatch(r"rocking: solver compiled in \d+ s", lines[1])
    buf2 = io.StringIO()
    assert warmup.ensure_compiled(stream=buf2) is None and buf2.getvalue() == ""  # once per process
    assert cold == [1]


def test_a_cold_start_compiles_without_deadlocking(monkeypatch):
    """The real compilation runs a simulation, and ``simulate`` calls ensure_compiled again from
    inside it: with a non-re-entrant lock the first run on a fresh machine hung for ever."""
    import threading

    warmup._compile()  # compiled (or loaded) first, so that the timeout below measures a hang only
    monkeypatch.setattr(warmup, "_done", False)
    monkeypatch.setattr(warmup, "cache_is_warm", lambda: False)
    result = []
    worker = threading.Thread(target=lambda: result.append(warmup.ensure_compiled(stream=io.StringIO())),
                              daemon=True)
    worker.start()
    worker.join(timeout=60)  # one tiny simulation of an already compiled solver: well under a second
    assert not worker.is_alive(), "ensure_compiled deadlocked on a cold cache"
    assert len(result) == 1 and result[0] is not None


def test_ensure_compiled_is_silent_when_warm(monkeypatch):
    monkeypatch.setattr(warmup, "_done", False)
    monkeypatch.setattr(warmup, "cache_is_warm", lambda: True)
    buf = io.StringIO()
    assert warmup.ensure_compiled(stream=buf) is None and buf.getvalue() == ""


def test_cli_run_shows_the_message_on_stderr_before_simulating(capsys, cold, short_toml):
    code = main(["run", str(short_toml), "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    json.loads(out)  # stdout is still nothing but the summary
    assert "rocking: compiling the solver (first run on this machine" in err
    assert "rocking: solver compiled in" in err
    assert cold == [1]


def test_cli_input_errors_come_before_the_compilation(capsys, cold, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TOML.replace("width = 0.3", "width = -1"), encoding="utf-8")
    assert main(["run", str(bad)]) == 2
    _, err = capsys.readouterr()
    assert "compiling" not in err and cold == []


def test_the_second_core_does_not_drop_the_first_cores_fresh_cache(tmp_path, monkeypatch):
    """The set-up compiles the solver, then the stack engine. Importing the stack engine used to
    find no fingerprint of its own and drop every cache in the folders of its sources, solver/
    among them: the solver just compiled was compiled again by the next command (seen in a fresh
    clone: its cache rewritten during the tests, 75 s). One fingerprint now covers both cores: a
    refresh with nothing changed keeps every cache, and an edit to any shared source drops both."""
    from rocking import _numba_cache as nc

    files = sorted(set(nc.SOLVER_CORE) | set(nc.STACK_CORE))
    for name in files:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_bytes((nc.PACKAGE / name).read_bytes())
    monkeypatch.setattr(nc, "PACKAGE", tmp_path)

    def cached(folder):
        return sorted(p.name for p in (tmp_path / folder / "__pycache__").glob("*.nb[ic]"))

    nc.refresh()  # the solver package's import: no fingerprint yet
    for folder, name in (("solver", "compiled.integrate-1.py311.nbi"), ("stack", "engine.integrate-1.py311.nbi")):
        (tmp_path / folder / "__pycache__").mkdir(exist_ok=True)
        (tmp_path / folder / "__pycache__" / name).write_text("compiled")
    nc.refresh()  # the stack package's import, and any later process: nothing changed
    assert cached("solver") == ["compiled.integrate-1.py311.nbi"]
    assert cached("stack") == ["engine.integrate-1.py311.nbi"]
    (tmp_path / "excitation" / "signal.py").write_text("# edited\n", encoding="utf-8")
    nc.refresh()  # a shared source changed: both cores are stale
    assert cached("solver") == [] and cached("stack") == []
