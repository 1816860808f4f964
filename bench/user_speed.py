"""On-demand benchmark: the speed a user feels (issue 13, section 7).

    .venv/bin/python bench/user_speed.py              # everything (the cold compilation takes a minute)
    .venv/bin/python bench/user_speed.py --no-compile # skip the cold compilation
    .venv/bin/python bench/user_speed.py --stack      # also compile the stack engine cold
    .venv/bin/python bench/user_speed.py --repeats 11

Prints, in one run, each against its target:

* ``rocking run examples/statue_alone_record.toml`` warm: wall time of the whole command in a new
  process (median and min of N; the run with ``--out`` is shown beside it, for information);
* ``import rocking`` in a new process, and which heavy optional libraries it loaded;
* the floor under both: a new process that imports numpy and numba and calls one trivial cached
  compiled function (what any numba program pays before it does anything);
* ``rocking.run(dict)`` against the compiled core on the same case (bench case (a), 25 s): the
  core is ``rocking.simulate(..., save=False)``, as in ``bench/run.py``; the compiled call alone
  and ``run_response(dict)`` (which keeps the time series) are shown beside it;
* the first-use compilation: a new process with an empty ``NUMBA_CACHE_DIR`` (wall and CPU time).

The machine's load average is printed first: with other processes on the two cores, the min
column is the most reproducible number. Not collected by pytest.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RECORD_CONFIG = "examples/statue_alone_record.toml"
HEAVY = ("matplotlib", "xarray", "pandas", "flask", "dask", "pydantic")

#: Targets of issue 13 §7.
RUN_TARGET = 0.5  # s, `rocking run` warm
RUN_DICT_TARGET = 1.20  # rocking.run(dict) / compiled core
COMPILE_TARGET = 15.0  # s, first use

#: Bench case (a) as a configuration dict: the paper's block under 30 cycles of 6.75 cos(2π·1.2 t).
CASE_A = {
    "statue": {"width": 1.0, "height": 4.0, "mass": 1.0, "restitution": 0.8},
    "motion": {"kind": "harmonic", "amplitude": 6.75, "frequency": 1.2, "cycles": 30},
    "simulation": {"duration": 25.0},
}

_FLOOR_MODULE = """
import numba

@numba.njit(cache=True)
def one(x):
    return x + 1.0
"""


def _rocking_command() -> list[str]:
    script = Path(sys.executable).with_name("rocking")
    return [str(script)] if script.exists() else [sys.executable, "-m", "rocking.cli"]


def _child_env(**extra: str) -> dict[str, str]:
    return {**os.environ, "NUMBA_NUM_THREADS": "1", **extra}


def _wall(cmd: list[str], repeats: int, **env: str) -> list[float]:
    """Wall times (s) of ``cmd`` in new processes, after one untimed run."""
    subprocess.run(cmd, cwd=ROOT, env=_child_env(**env), capture_output=True, check=True)
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, cwd=ROOT, env=_child_env(**env), capture_output=True, check=True)
        out.append(time.perf_counter() - t0)
    return out


def _child_seconds(code: str, repeats: int, **env: str) -> list[float]:
    """What ``code`` prints (a time in s, on its last line) in new processes, after one untimed run."""
    runs = []
    for _ in range(repeats + 1):
        done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=_child_env(**env), capture_output=True,
                              text=True, check=True)
        runs.append(float(done.stdout.split()[-1]))
    return runs[1:]


def _row(name: str, value: str, target: str, met: bool | None) -> None:
    verdict = "" if met is None else ("met" if met else "NOT MET")
    print(f"{name:<46} {value:>26}   {target:<26} {verdict}")


def _stats(xs: list[float]) -> str:
    return f"{statistics.median(xs):.3f} s (min {min(xs):.3f})"


def command_times(repeats: int) -> None:
    cmd = _rocking_command() + ["run", RECORD_CONFIG]
    times = _wall(cmd, repeats)
    _row("rocking run (record, summary only)", _stats(times), f"≤ {RUN_TARGET} s", statistics.median(times) <= RUN_TARGET)
    with tempfile.TemporaryDirectory() as out:
        with_out = _wall(cmd + ["--out", out], max(3, repeats // 2))
    _row("rocking run --out DIR (+ .csv .nc .png)", _stats(with_out), "(for information)", None)


def import_times(repeats: int) -> None:
    code = "import time; t = time.perf_counter(); import rocking; print(time.perf_counter() - t)"
    _row("import rocking (in a new process)", _stats(_child_seconds(code, repeats)), "(part of the run)", None)
    loaded = subprocess.run(
        [sys.executable, "-c", f"import rocking, sys; print(sorted({{m.split('.')[0] for m in sys.modules}} & {set(HEAVY)!r}))"],
        cwd=ROOT, env=_child_env(), capture_output=True, text=True, check=True,
    ).stdout.strip()
    _row("  heavy libraries it loads", loaded, "[]", loaded == "[]")


def floor_times(repeats: int) -> None:
    """A process that only imports numpy and numba and calls one cached compiled function."""
    with tempfile.TemporaryDirectory() as folder:
        Path(folder, "floor_module.py").write_text(_FLOOR_MODULE, encoding="utf-8")
        code = (f"import sys, time; t = time.perf_counter(); sys.path.insert(0, {folder!r}); import floor_module; "
                "floor_module.one(1.0); print(time.perf_counter() - t)")
        inside = _child_seconds(code, repeats, NUMBA_CACHE_DIR=folder)
        whole = _wall([sys.executable, "-c", code], repeats, NUMBA_CACHE_DIR=folder)
    _row("floor: numpy + numba + 1 cached call", _stats(inside), "(no numba program is faster)", None)
    _row("  the same, whole process", _stats(whole), "", None)


def run_dict_times(repeats: int) -> None:
    import numpy as np

    import rocking as rk
    from rocking.runner import run_response
    from rocking.simulation import prepare
    from rocking.solver.compiled import integrate

    spec = rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8))
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30)
    _, args = prepare(spec, motion, duration=25.0, save=False)
    flag = np.zeros(1, dtype=np.int64)
    contenders = {
        "integrate": lambda: integrate(*args, flag),
        "simulate": lambda: rk.simulate(spec, motion, duration=25.0, save=False),
        "run": lambda: rk.run(CASE_A),
        "run_response": lambda: run_response(CASE_A),
    }
    # interleaved rounds: a change of the machine's load hits every contender alike
    per_call = {name: [] for name in contenders}
    for fn in contenders.values():
        fn()
    for _ in range(repeats):
        for name, fn in contenders.items():
            n = 200
            t0 = time.perf_counter()
            for _ in range(n):
                fn()
            per_call[name].append((time.perf_counter() - t0) / n)
    t = {name: statistics.median(xs) for name, xs in per_call.items()}
    core, raw = t["simulate"], t["integrate"]
    ratio = t["run"] / core
    _row("compiled core: simulate(save=False), case (a)", f"{core * 1e3:.3f} ms", "(bench/run.py's figure)", None)
    _row("  its compiled call alone (integrate)", f"{raw * 1e3:.3f} ms", "", None)
    _row("rocking.run(dict), same case", f"{t['run'] * 1e3:.3f} ms = {ratio:.2f} × core",
         f"≤ {RUN_DICT_TARGET:.2f} × core", ratio <= RUN_DICT_TARGET)
    _row("  = × the compiled call alone", f"{t['run'] / raw:.2f}", "", None)
    _row("  run_response(dict), keeps the series", f"{t['run_response'] * 1e3:.3f} ms = {t['run_response'] / core:.2f} × core",
         "", None)


def compile_times(stack: bool) -> None:
    parts = [("solver", "warmup._compile()")] + ([("stack engine", "warmup._compile_stack()")] if stack else [])
    for name, call in parts:
        with tempfile.TemporaryDirectory() as cache:
            code = ("import time; import rocking; from rocking.solver import warmup; "
                    f"t = time.perf_counter(); {call}; print(time.perf_counter() - t)")
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=_child_env(NUMBA_CACHE_DIR=cache),
                                  capture_output=True, text=True, check=True)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
        wall = float(done.stdout.split()[-1])
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        _row(f"first-use compilation of the {name}", f"{wall:.1f} s (CPU {cpu:.1f} s)", f"≤ {COMPILE_TARGET:g} s, or at set-up",
             wall <= COMPILE_TARGET)
    print("  (scripts/env.sh compiles both at set-up, with a message; the first `rocking run` says so if it must)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7, help="timed repeats of each measurement (default 7)")
    parser.add_argument("--no-compile", action="store_true", help="skip the cold compilation (a minute)")
    parser.add_argument("--stack", action="store_true", help="also compile the stack engine cold (another minute)")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error(f"--repeats must be at least 1, got {args.repeats}")
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs; Python {sys.version.split()[0]}")
    print(f"{'measure':<46} {'value':>26}   {'target':<26}")
    command_times(args.repeats)
    import_times(args.repeats)
    floor_times(args.repeats)
    run_dict_times(args.repeats)
    if not args.no_compile:
        compile_times(args.stack)
    if shutil.which("rocking") is None and not Path(sys.executable).with_name("rocking").exists():
        print("(no `rocking` script beside this Python: timed `python -m rocking.cli` instead)")


if __name__ == "__main__":
    main()
