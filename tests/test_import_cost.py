"""What a user waits for (issue 13 §7): ``import rocking`` and ``rocking run`` load no plotting,
table or web library; ``rocking.run(dict)`` keeps no time series; the stack engine's first-run
compilation is announced like the solver's, and the set-up compiles both.

Behaviour, not timing: the times themselves are measured by ``bench/user_speed.py``.
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import rocking as rk
from rocking.cli import main
from rocking.runner import run_response
from rocking.solver import warmup

ROOT = Path(__file__).resolve().parents[1]
HEAVY = {"matplotlib", "xarray", "pandas", "flask", "dask"}

_LOADED = "import json, sys; print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in {names!r})))"


def _heavy_modules_after(code: str, names: set[str] = HEAVY) -> list[str]:
    """The modules of ``names`` a new Python process holds after running ``code``."""
    done = subprocess.run([sys.executable, "-c", f"{code}\n{_LOADED.format(names=names)}"], cwd=ROOT,
                          env={**os.environ, "NUMBA_NUM_THREADS": "1"}, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


# ------------------------------------------------------------------------------ imports
def test_import_rocking_loads_no_plotting_table_or_web_library():
    assert _heavy_modules_after("import rocking") == []


def test_import_rocking_leaves_the_configuration_layer_for_run():
    """pydantic (the configuration layer) and the stack engine come with the first rocking.run."""
    assert _heavy_modules_after("import rocking", {"pydantic"}) == []
    assert _heavy_modules_after("import rocking, rocking.runner", {"pydantic"}) == []
    assert _heavy_modules_after("import rocking; rocking.run_response", {"pydantic"}) == []


def test_cli_run_help_loads_no_plotting_table_or_web_library():
    code = "from rocking.cli.main import main\ntry:\n    main(['run', '--help'])\nexcept SystemExit:\n    pass"
    assert _heavy_modules_after(code) == []


def test_cli_run_without_out_loads_no_plotting_table_or_web_library(tmp_path):
    """The summary table needs neither matplotlib (response.png) nor xarray (timeseries.nc)."""
    code = (
        "import contextlib, io\nfrom rocking.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    assert main(['run', 'examples/statue_alone_record.toml']) == 0"
    )
    assert _heavy_modules_after(code) == []


@pytest.mark.parametrize("config", ["statue_alone_record.toml", "stack_statue_on_pedestal.toml"])
def test_cli_run_out_without_animate_leaves_the_animation_modules_alone(tmp_path, config):
    code = (
        "import contextlib, io, json, sys\nfrom rocking.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    assert main(['run', 'examples/{config}', '--out', {str(tmp_path / 'out')!r}]) == 0\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith(('rocking.viz.', 'matplotlib.figure')))))"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env={**os.environ, "NUMBA_NUM_THREADS": "1"},
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    loaded = json.loads(done.stdout.strip().splitlines()[-1])
    assert "matplotlib.figure" in loaded  # response.png was drawn
    assert not [m for m in loaded if m.endswith("animation")], loaded
    assert (tmp_path / "out" / "response.png").stat().st_size > 0


# ------------------------------------------------------------- run(dict) keeps no series
CASES = {
    "block, harmonic": {
        "statue": {"width": 1.0, "height": 4.0, "mass": 1.0, "restitution": 0.8},
        "motion": {"kind": "harmonic", "amplitude": 6.75, "frequency": 1.2, "cycles": 30},
        "simulation": {"duration": 25.0},
    },
    "pedestal, harmonic, until rest": {
        "statue": {"width": 1.0, "height": 4.0, "mass": 1.0, "restitution": 0.8},
        "pedestal": {"mass": 1.0, "friction": {"static": 0.4, "kinetic": 0.3}},
        "motion": {"kind": "harmonic", "amplitude": 6.75, "frequency": 1.2, "cycles": 10},
    },
    "sliding block, record": {
        "statue": {"width": 0.3, "height": 1.2, "mass": 100.0, "friction": {"static": 0.3, "kinetic": 0.25}},
        "motion": {"kind": "record", "path": "Northridge1994_RinaldiReceivingSta_228", "pga": 3.0},
    },
    "pedestal, pulse, paper options": {
        "statue": {"width": 0.3, "height": 1.2, "mass": 100.0},
        "pedestal": {"mass": 50.0, "friction": {"static": 0.2, "kinetic": 0.15}},
        "motion": {"kind": "pulse", "shape": "sine", "amplitude": 6.0, "frequency": 1.0},
        "simulation": {"normal_force": "paper", "impact": "paper"},
    },
}


@pytest.mark.parametrize("config", CASES.values(), ids=CASES.keys())
def test_run_summary_is_exactly_that_of_the_run_that_keeps_the_series(config):
    _, kept = run_response(config)
    assert kept.t.size > 100  # the comparison is with a run that did store its series
    summary = rk.run(config)
    assert summary == kept.summary()  # every key, to the last bit
    assert summary["impacts"] > 0 or summary["peak_sliding"] > 0  # cases where something happens


def test_run_asks_the_solver_for_the_summary_only(monkeypatch):
    import rocking.runner

    asked = []
    real = rocking.runner.simulate
    monkeypatch.setattr(rocking.runner, "simulate", lambda *a, **k: asked.append(k["save"]) or real(*a, **k))
    rk.run(CASES["block, harmonic"])
    assert asked == [False]
    _, response = run_response(CASES["block, harmonic"], save=False)
    assert response.t.size == 0 and response.event_table.shape[0] > 0  # events stay, samples go


def test_run_builds_the_api_objects_of_a_configuration_once(monkeypatch):
    """Validating a configuration builds its System, motion and Options; run() uses those."""
    from rocking.io.config import Config

    built = []
    real = Config.to_specs
    monkeypatch.setattr(Config, "to_specs", lambda self: built.append(1) or real(self))
    rk.run(CASES["block, harmonic"])
    assert built == [1]


def test_cli_run_keeps_the_series_only_for_out(monkeypatch, tmp_path):
    import importlib

    cli_main = importlib.import_module("rocking.cli.main")  # the module (rocking.cli.main is also the function)
    config = tmp_path / "short.toml"
    config.write_text(
        "[statue]\nwidth = 0.3\nheight = 1.2\nmass = 100.0\n"
        '[motion]\nkind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2\n'
        "[simulation]\nduration = 1.5\n",
        encoding="utf-8",
    )
    asked = []
    real = cli_main.run_response
    monkeypatch.setattr(cli_main, "run_response", lambda cfg, *, save: asked.append(save) or real(cfg, save=save))
    with pytest.MonkeyPatch.context() as quiet:
        quiet.setattr(sys, "stdout", io.StringIO())
        assert main(["run", str(config), "--json"]) == 0
        assert main(["run", str(config), "--out", str(tmp_path / "out")]) == 0
    assert asked == [False, True]
    assert (tmp_path / "out" / "timeseries.csv").read_text().count("\n") > 100


# --------------------------------------------------------------- first-run compilation
@pytest.fixture
def cold_stack(monkeypatch):
    """A process whose stack engine is not compiled and whose cache is cold; compiling takes no time."""
    calls = []
    monkeypatch.setattr(warmup, "_stack_done", False)
    monkeypatch.setattr(warmup, "stack_cache_is_warm", lambda: False)
    monkeypatch.setattr(warmup, "_compile_stack", lambda: calls.append("stack"))
    return calls


def test_ensure_stack_compiled_says_what_it_does_once(cold_stack):
    buf = io.StringIO()
    assert warmup.ensure_stack_compiled(stream=buf) is not None
    first, second = buf.getvalue().splitlines()
    assert first == (f"rocking: compiling the stack engine (first run on this machine, about "
                     f"{warmup.STACK_TYPICAL_SECONDS} s; cached afterwards)...")
    assert second.startswith("rocking: stack engine compiled in ") and second.endswith(" s")
    assert warmup.ensure_stack_compiled(stream=buf) is None and cold_stack == ["stack"]


def test_cli_run_of_a_stack_announces_the_stack_engine_compilation(capsys, cold_stack):
    code = main(["run", str(ROOT / "examples" / "stack_statue_on_pedestal.toml"), "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    json.loads(out)  # stdout is still nothing but the summary
    assert "rocking: compiling the stack engine (first run on this machine" in err
    assert cold_stack == ["stack"]


def test_the_stack_engine_is_warm_once_a_stack_has_run():
    warmup._compile_stack()
    assert warmup.stack_cache_is_warm() is True


def test_setup_compiles_both_cores_and_is_silent_when_they_are_warm(monkeypatch, capsys):
    calls = []
    monkeypatch.setattr(warmup, "_done", False)
    monkeypatch.setattr(warmup, "_stack_done", False)
    monkeypatch.setattr(warmup, "cache_is_warm", lambda: False)
    monkeypatch.setattr(warmup, "stack_cache_is_warm", lambda: False)
    monkeypatch.setattr(warmup, "_compile", lambda: calls.append("solver"))
    monkeypatch.setattr(warmup, "_compile_stack", lambda: calls.append("stack"))
    assert warmup.main() == 0
    err = capsys.readouterr().err
    assert calls == ["solver", "stack"]
    assert "compiling the solver" in err and "compiling the stack engine" in err
    monkeypatch.setattr(warmup, "_done", False)
    monkeypatch.setattr(warmup, "_stack_done", False)
    monkeypatch.setattr(warmup, "cache_is_warm", lambda: True)
    monkeypatch.setattr(warmup, "stack_cache_is_warm", lambda: True)
    assert warmup.main() == 0
    assert capsys.readouterr().err == "" and calls == ["solver", "stack"]


def test_setup_compiles_after_installing_and_before_the_demo_runs(tmp_path):
    """scripts/demo.sh (through env.sh) in a copy of the repository whose .venv only logs its calls."""
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    for name in ("demo.sh", "env.sh"):
        (repo / "scripts" / name).write_text((ROOT / "scripts" / name).read_text())
    log = tmp_path / "calls.log"
    (repo / ".venv" / "bin").mkdir(parents=True)
    for exe in ("python", "rocking"):
        fake = repo / ".venv" / "bin" / exe
        fake.write_text(f'#!/usr/bin/env bash\necho "{exe} $*" >> "{log}"\n')
        fake.chmod(0o755)
    done = subprocess.run(["bash", str(repo / "scripts" / "demo.sh"), "out"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    calls = log.read_text().splitlines()
    install = calls.index("python -m pip install --quiet -e .")
    warm = calls.index("python -c from rocking.solver.warmup import main; raise SystemExit(main())")
    first_command = next(i for i, c in enumerate(calls) if c.startswith("rocking "))
    assert install < warm < first_command
