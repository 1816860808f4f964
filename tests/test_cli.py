"""The ``rocking`` command line, ``rocking.run`` and the output files.

The commands run in-process through ``rocking.cli.main(argv)``; one test also runs the
installed console script. Configurations are short (a few seconds of motion) so that,
once the core is compiled, every run takes milliseconds.
"""

from __future__ import annotations

import importlib
import io
import json
import math
import os
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import rocking as rk
from rocking import runner
from rocking.cli import main
from rocking.cli.progress import delayed_spinner
from rocking.io import output
from rocking.io.config import load_config
from rocking.io.output import OUTPUT_FILES, jsonable, write_outputs
from rocking.io.records import bundled_records

from test_config import BAD_TOML, TOML, _bad_toml_text

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
RINALDI = "Northridge1994_RinaldiReceivingSta_228"


@pytest.fixture
def short_toml(tmp_path) -> Path:
    """Statue on a pedestal, 2 cycles of shaking, 1.5 s."""
    f = tmp_path / "short.toml"
    f.write_text(TOML, encoding="utf-8")
    return f


def _run_cli(capsys, *args: str) -> tuple[int, str, str]:
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def _same(a, b) -> bool:
    """Equal summaries, with JSON's null standing for NaN."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return a == b


# ----------------------------------------------------------------------------- run
def test_run_is_exported_from_the_package():
    assert rk.run is runner.run


def test_run_returns_the_summary_contract(short_toml):
    s = runner.run(short_toml)
    for key in ("overturned", "overturn_time", "exceeded_alpha_time", "peak_rotation", "peak_sliding",
                "residual_sliding", "impacts", "first_rocking_time", "first_sliding_time",
                "required_top_friction"):
        assert key in s
    assert s["end_time"] == pytest.approx(1.5)


def test_run_response_accepts_path_dict_and_config(short_toml):
    import tomllib

    cfg, r1 = runner.run_response(short_toml)
    _, r2 = runner.run_response(tomllib.loads(TOML))
    _, r3 = runner.run_response(cfg)
    assert _same(r1.summary(), r2.summary()) and _same(r1.summary(), r3.summary())
    np.testing.assert_array_equal(r1.theta, r3.theta)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_run_json_matches_rocking_run(capsys, path):
    code, out, err = _run_cli(capsys, "run", path, "--json")
    assert code == 0, err
    printed = json.loads(out)  # nothing but JSON on stdout
    assert _same(printed, jsonable(runner.run(path)))
    assert err == ""  # not a terminal: no spinner, no chatter


def test_run_prints_a_readable_table(capsys, short_toml):
    code, out, err = _run_cli(capsys, "run", short_toml)
    assert code == 0, err
    for words in ("outcome", "peak rotation", "peak sliding", "impacts", "mm", "rad"):
        assert words in out


def test_run_out_writes_four_files_and_netcdf_round_trips(capsys, short_toml, tmp_path):
    import xarray as xr

    out_dir = tmp_path / "results" / "run1"  # parents are created
    code, out, err = _run_cli(capsys, "run", short_toml, "--json", "--out", out_dir)
    assert code == 0, err
    assert sorted(p.name for p in out_dir.iterdir()) == sorted(OUTPUT_FILES)
    assert not [p for p in out_dir.parent.iterdir() if p.name.startswith(".")]  # no temp left

    cfg, response = runner.run_response(short_toml)
    with xr.open_dataset(out_dir / "timeseries.nc", engine="h5netcdf") as ds:
        np.testing.assert_array_equal(ds["theta"].values, response.theta)
        np.testing.assert_array_equal(ds["time"].values, response.t)
        assert ds["theta"].attrs["units"] == "rad"
        assert json.loads(ds.attrs["config"])["statue"]["width"] == 0.3

    assert _same(json.loads((out_dir / "summary.json").read_text()), json.loads(out))
    csv = np.genfromtxt(out_dir / "timeseries.csv", delimiter=",", names=True)
    assert csv.dtype.names[:4] == ("time_s", "u_m", "u_dot_m_per_s", "theta_rad")
    np.testing.assert_allclose(csv["theta_rad"], response.theta, rtol=1e-9, atol=1e-15)
    np.testing.assert_array_equal(csv["regime"], response.regime)
    assert (out_dir / "response.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_out_replaces_own_files_and_keeps_others(capsys, short_toml, tmp_path):
    out_dir = tmp_path / "res"
    out_dir.mkdir()
    (out_dir / "notes.txt").write_text("mine")
    (out_dir / "summary.json").write_text("old")
    code, _, err = _run_cli(capsys, "run", short_toml, "--out", out_dir)
    assert code == 0, err
    assert (out_dir / "notes.txt").read_text() == "mine"
    assert json.loads((out_dir / "summary.json").read_text())["end_time"] == pytest.approx(1.5)


# ----------------------------------------------------------------- atomic outputs
def test_failed_write_leaves_nothing(monkeypatch, short_toml, tmp_path):
    _, response = runner.run_response(short_toml)

    def broken(*args, **kwargs):
        raise RuntimeError("disk full")

    monkeypatch.setattr(output, "plot_response", broken)  # the last file fails
    target = tmp_path / "new" / "out"
    with pytest.raises(RuntimeError, match="disk full"):
        write_outputs(response, target)
    # neither the folder, nor the parent it created, nor a temporary folder
    assert [p.name for p in tmp_path.iterdir()] == ["short.toml"]


def test_failed_write_keeps_previous_results(monkeypatch, short_toml, tmp_path):
    _, response = runner.run_response(short_toml)
    target = tmp_path / "out"
    write_outputs(response, target)
    before = {p.name: p.read_bytes() for p in target.iterdir()}

    monkeypatch.setattr(output, "_write_summary", lambda *a: (_ for _ in ()).throw(OSError("no space")))
    with pytest.raises(OSError, match="no space"):
        write_outputs(response, target)
    assert {p.name: p.read_bytes() for p in target.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "short.toml"]  # no temp left


def test_failed_move_restores_previous_results(monkeypatch, short_toml, tmp_path):
    _, response = runner.run_response(short_toml)
    target = tmp_path / "out"
    write_outputs(response, target)
    before = {p.name: p.read_bytes() for p in target.iterdir()}
    real_replace = os.replace
    calls = {"n": 0}

    def flaky(src, dst):
        calls["n"] += 1
        if calls["n"] == 4:  # fail halfway through moving the new files in
            raise OSError("device busy")
        return real_replace(src, dst)

    monkeypatch.setattr(output.os, "replace", flaky)
    with pytest.raises(OSError, match="device busy"):
        write_outputs(response, target)
    monkeypatch.undo()
    assert {p.name: p.read_bytes() for p in target.iterdir()} == before


def test_write_outputs_needs_time_series(tmp_path):
    import tomllib

    cfg = load_config(tomllib.loads(TOML))
    system, motion, options, duration = cfg.to_specs()
    response = rk.simulate(system, motion, duration=duration, options=options, save=False)
    with pytest.raises(ValueError, match="save=True"):
        write_outputs(response, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_write_outputs_refuses_a_file_as_folder(short_toml, tmp_path):
    _, response = runner.run_response(short_toml)
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(NotADirectoryError):
        write_outputs(response, f)


def test_jsonable_makes_strict_json():
    data = {"a": math.nan, "b": [np.float64(1.5), np.int64(2), (math.inf,)], "c": np.bool_(True)}
    assert json.loads(json.dumps(jsonable(data), allow_nan=False)) == {"a": None, "b": [1.5, 2, [None]], "c": True}


# --------------------------------------------------------------------- bad input
def _assert_one_error_line(err: str, *fragments: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("error: "), err
    assert "Traceback" not in err
    for frag in fragments:
        assert frag in lines[0], (frag, err)


@pytest.mark.parametrize(("old", "new", "field", "words"), [c[1:] for c in BAD_TOML], ids=[c[0] for c in BAD_TOML])
def test_cli_bad_config_exits_2_without_output(capsys, tmp_path, old, new, field, words):
    f = tmp_path / "bad.toml"
    f.write_text(_bad_toml_text(old, new), encoding="utf-8")
    out_dir = tmp_path / "out"
    code, out, err = _run_cli(capsys, "run", f, "--json", "--out", out_dir)
    assert code == 2
    assert out == ""
    _assert_one_error_line(err, str(f), f"{field}: ", words)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]  # no output, no temp folder


def test_cli_broken_record_reports_file_and_line(capsys, tmp_path):
    rec = tmp_path / "broken.AT2"
    rec.write_text("title\nevent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= 0.01 SEC\n0.1 x 0.3\n")
    f = tmp_path / "run.toml"
    f.write_text(TOML.replace('kind = "harmonic"\namplitude = 3.0\nfrequency = 1.5\ncycles = 2',
                              'kind = "record"\npath = "broken.AT2"'), encoding="utf-8")
    code, out, err = _run_cli(capsys, "run", f, "--out", tmp_path / "out")
    assert code == 2 and out == ""
    _assert_one_error_line(err, str(f), "motion.path", f"{rec}: line 5", "'x'")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["run", "missing.toml"], "missing.toml: no such file"),
        (["run"], "Missing argument"),
        (["run", "x.toml", "--colour"], "No such option"),
        (["frobnicate"], "No such command"),
        (["info", "NoSuchRecord"], "neither an existing file nor a bundled record"),
        (["info", RINALDI, "--format", "wav"], "unknown record format"),
    ],
)
def test_cli_usage_and_input_errors(capsys, args, fragment):
    code, out, err = _run_cli(capsys, *args)
    assert code == 2
    assert out == ""
    _assert_one_error_line(err, fragment)


def test_cli_out_must_be_a_folder(capsys, short_toml, tmp_path):
    f = tmp_path / "taken"
    f.write_text("x")
    code, out, err = _run_cli(capsys, "run", short_toml, "--out", f)
    assert code == 2 and out == ""
    _assert_one_error_line(err, "--out", "not a directory")
    assert f.read_text() == "x"


def test_cli_simulation_failure_exits_1(capsys, monkeypatch, short_toml):
    cli_main = importlib.import_module("rocking.cli.main")  # the package attribute `main` is the function

    def fail(cfg, **options):
        raise rk.SimulationError("step size underflow")

    monkeypatch.setattr(cli_main, "run_response", fail)
    code, out, err = _run_cli(capsys, "run", short_toml, "--json")
    assert code == 1 and out == ""
    _assert_one_error_line(err, "simulation failed", "step size underflow")


def test_cli_unexpected_error_is_one_line_unless_debugging(capsys, monkeypatch, short_toml):
    cli_main = importlib.import_module("rocking.cli.main")  # the package attribute `main` is the function

    monkeypatch.setattr(cli_main, "run_response", lambda cfg, **options: 1 / 0)
    code, _, err = _run_cli(capsys, "run", short_toml)
    assert code == 1
    _assert_one_error_line(err, "ZeroDivisionError", "ROCKING_DEBUG")
    monkeypatch.setenv("ROCKING_DEBUG", "1")
    with pytest.raises(ZeroDivisionError):
        main(["run", str(short_toml)])


# ----------------------------------------------------------------- records/info
def test_records_lists_every_bundled_record(capsys):
    code, out, err = _run_cli(capsys, "records", "--json")
    assert code == 0, err
    rows = json.loads(out)
    assert {r["name"] for r in rows} == set(bundled_records())
    rinaldi = next(r for r in rows if r["name"] == RINALDI)
    assert rinaldi["points"] == 1991 and rinaldi["dt"] == 0.01
    assert rinaldi["pga_g"] == pytest.approx(0.874, abs=5e-4)

    code, out, _ = _run_cli(capsys, "records")
    assert code == 0
    for name in bundled_records():
        assert name in out  # full names, not cut by the table


def test_info_shows_a_record(capsys):
    code, out, err = _run_cli(capsys, "info", RINALDI, "--json")
    assert code == 0, err
    info = json.loads(out)
    assert info["format"] == "peer" and info["points"] == 1991 and info["dt"] == 0.01
    assert info["duration"] == pytest.approx(19.9)
    assert info["pga_g"] == pytest.approx(0.874, abs=5e-4) and info["pgv"] > 0
    code, out, _ = _run_cli(capsys, "info", RINALDI)
    assert code == 0
    for words in ("peer", "0.01 s", "1991", "PGA", "PGV"):
        assert words in out


def test_help_and_version(capsys):
    code, out, _ = _run_cli(capsys, "--help")
    assert code == 0 and "run" in out and "records" in out and "info" in out
    code, out, _ = _run_cli(capsys, "--version")
    assert code == 0 and out.strip() == f"rocking {rk.__version__}"


# ------------------------------------------------------------------------ extras
def test_paper_command_is_optional(monkeypatch):
    cli_main = importlib.import_module("rocking.cli.main")  # the package attribute `main` is the function

    monkeypatch.setitem(sys.modules, "rocking.cli.paper", None)  # as if the file were absent
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cli_main._register_optional_commands()  # must neither fail nor warn


def test_spinner_appears_only_after_the_delay():
    from rich.console import Console

    buf = io.StringIO()
    with delayed_spinner("simulating", console=Console(file=buf, force_terminal=True), delay=0.05):
        time.sleep(0.3)
    assert "simulating" in buf.getvalue()

    buf = io.StringIO()
    with delayed_spinner("simulating", console=Console(file=buf, force_terminal=True), delay=5.0):
        pass
    assert buf.getvalue() == ""

    buf = io.StringIO()  # not a terminal: never drawn
    with delayed_spinner("simulating", console=Console(file=buf), delay=0.0):
        time.sleep(0.05)
    assert buf.getvalue() == ""


def test_console_script(tmp_path, short_toml):
    exe = Path(sys.executable).with_name("rocking")
    # scripts/test.sh installs the package, and with it the console script of [project.scripts]
    assert exe.exists(), f"no console script at {exe}: the package is not installed with its entry points"
    ok = subprocess.run([exe, "run", short_toml, "--json"], capture_output=True, text=True, timeout=300)
    assert ok.returncode == 0, ok.stderr
    assert _same(json.loads(ok.stdout), jsonable(runner.run(short_toml)))
    bad = tmp_path / "bad.toml"
    bad.write_text(TOML.replace("width = 0.3", "width = -1"), encoding="utf-8")
    ko = subprocess.run([exe, "run", bad, "--out", tmp_path / "o"], capture_output=True, text=True, timeout=300)
    assert ko.returncode == 2 and ko.stdout == ""
    assert ko.stderr == f"error: {bad}: statue.width: must be > 0, got -1\n"
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("command", ["run", "records", "info", "paper", "report", "animate", "design", "fragility",
                                     "spectrum"])
def test_help_shows_flags_as_flags(command):
    """A flag (--json, --animate, --help) takes no value, so --help shows no value type for it."""
    env = dict(os.environ, COLUMNS="120", TERM="dumb")
    done = subprocess.run([sys.executable, "-m", "rocking.cli", command, "--help"], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "<bool>" not in done.stdout and "--help" in done.stdout


def test_help_reads_as_written():
    """Help text as its docstring says it: square brackets kept (rich took ``[[blocks]]`` for
    markup and showed "[]"), and a paragraph broken where the terminal ends, not where the source
    line did ("write one figure per" ended a line of the command list)."""
    env = dict(os.environ, COLUMNS="200", TERM="dumb")

    def help_of(*command):
        done = subprocess.run([sys.executable, "-m", "rocking.cli", *command, "--help"], capture_output=True,
                              text=True, env=env, timeout=120)
        assert done.returncode == 0, done.stderr
        return done.stdout

    listing = help_of()
    assert "write one figure per case (paper_fig_<case>.png" in listing
    assert "run, and see the verdict, animation and plots" in listing
    design = help_of("design")
    assert "(or a [[blocks]] file) both faces are designed on the stack engine" in design
    assert "'local[:N]'" in design and "[]" not in design


def test_paper_takes_o_for_out():
    env = dict(os.environ, COLUMNS="120", TERM="dumb")
    done = subprocess.run([sys.executable, "-m", "rocking.cli", "paper", "--help"], capture_output=True, text=True,
                          env=env, timeout=120)
    option_row = next(line for line in done.stdout.splitlines() if line.lstrip("│ ").startswith("--out"))
    assert option_row.split()[2] == "-o"
