"""On-demand benchmark: this working tree's compiled solver against another commit's, alternately.

    .venv/bin/python bench/compare_builds.py                      # against HEAD~1, 12 rounds
    .venv/bin/python bench/compare_builds.py --baseline a8758c0 --rounds 20

A change to the compiled core is judged by ratios measured in one run, on one CPU, with the two
builds taking turns, so that the machine's load weighs on both alike. The baseline's source is
checked out with ``git worktree`` into a folder of its own, with a numba cache of its own (the
first round compiles it: a few minutes). Each round starts a new process per build (the order
alternates) that runs ``bench/cases.py``'s cases (a)–(c) seven times each and the first 200 runs
of the batch grid (d) once, with ``save=False``, and reports process CPU times. Printed: per case
the medians over the rounds and their ratio (this tree / baseline). Not collected by pytest.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def worker() -> None:
    sys.path.insert(0, str(ROOT / "bench"))
    import rocking as rk
    from cases import STATUE, batch_grid, cases, paper_motion

    runs = cases()
    for c in runs:  # warm: load the cache, touch every path
        rk.simulate(c.system, c.motion, duration=c.duration, save=False)
    out = {}
    for c in runs:
        times = []
        for _ in range(7):
            t0 = time.process_time()
            rk.simulate(c.system, c.motion, duration=c.duration, save=False)
            times.append(time.process_time() - t0)
        out[c.key] = statistics.median(times)
    t0 = time.process_time()
    for amplitude, frequency in batch_grid(200):
        rk.simulate(rk.System(statue=STATUE), paper_motion(amplitude, frequency), save=False)
    out["d"] = time.process_time() - t0
    out["rocking"] = str(Path(rk.__file__).resolve())
    print(json.dumps(out))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="HEAD~1", help="commit to compare with (default HEAD~1)")
    ap.add_argument("--rounds", type=int, default=12)
    ap.add_argument("--cpu", type=int, default=None, help="pin both to this CPU (taskset; default: the last one)")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        worker()
        return
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", args.baseline], check=True,
                         capture_output=True, text=True).stdout.strip()
    base = Path(tempfile.gettempdir()) / f"rocking-baseline-{sha}"
    if not base.exists():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), sha], check=True,
                       capture_output=True)
    builds = {"this tree": (ROOT / "src", None), f"baseline {sha}": (base / "src", base / ".numba-cache")}
    cpu = args.cpu if args.cpu is not None else (os.cpu_count() or 1) - 1
    pin = ["taskset", "-c", str(cpu)] if os.path.exists("/usr/bin/taskset") else []
    results = {name: [] for name in builds}
    for rnd in range(args.rounds):
        order = list(builds.items()) if rnd % 2 == 0 else list(reversed(builds.items()))
        for name, (src, cache) in order:
            env = dict(os.environ, PYTHONPATH=str(src), NUMBA_NUM_THREADS="1")
            if cache is not None:
                env["NUMBA_CACHE_DIR"] = str(cache)
            proc = subprocess.run(pin + [sys.executable, __file__, "--worker"], env=env, capture_output=True,
                                  text=True)
            if proc.returncode != 0:
                sys.exit(f"{name}: the worker failed:\n{proc.stderr[-2000:]}")
            row = json.loads(proc.stdout.strip().splitlines()[-1])
            if not row.pop("rocking").startswith(str(src)):
                sys.exit(f"{name}: rocking was not imported from {src}")
            results[name].append(row)
        print(f"round {rnd + 1} of {args.rounds} done", file=sys.stderr)
    ours, theirs = results.values()
    print(f"{'case':5s} {'this tree':>12s} {'baseline ' + sha:>18s} {'ratio':>7s}   (CPU time, medians of "
          f"{args.rounds} rounds; load {os.getloadavg()[0]:.1f})")
    for key in ours[0]:
        a = statistics.median(r[key] for r in ours)
        b = statistics.median(r[key] for r in theirs)
        print(f"{key:5s} {a * 1e3:10.2f} ms {b * 1e3:16.2f} ms {a / b:7.3f}")


if __name__ == "__main__":
    main()
