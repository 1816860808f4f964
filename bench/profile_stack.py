"""Where the stack engine's time goes: a per-function profile of its compiled code (on demand).

    .venv/bin/python bench/profile_stack.py b2                 # bench/stack.py's case b2, 10 s of runs
    .venv/bin/python bench/profile_stack.py r3m --seconds 20 --top 30

Needs Linux ``perf`` (``perf record`` on one's own process: kernel.perf_event_paranoid ≤ 2).
A Python profiler sees one opaque call into Numba; ``perf`` sees machine code but not the names
of functions compiled at run time. So a child process compiles the engine in a fresh, empty
NUMBA_CACHE_DIR (a library loaded from the cache keeps no LLVM module to read addresses from),
writes the address of every compiled function of ``rocking`` to /tmp/perf-<pid>.map (the file
``perf`` reads for JIT code), says it is ready, and runs the case over and over; the parent
samples it with ``perf record`` and prints the share of the samples per function.

Functions inlined into their caller (``inline="always"``, or by LLVM) count as the caller:
``evaluate_at`` holds the kinematics, the mass matrix and the mode solve; ``_step`` holds the
DOP853 stage arithmetic. libm's rows (sin, cos) are mostly the kinematics'. The first run of the
child compiles everything (a minute or more); it is not sampled.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent


def short_name(symbol: str) -> str:
    """``_ZN7rocking5stack6engine11evaluate_atB4v123…`` → ``stack.engine.evaluate_at`` (Numba's
    Itanium-style names: length-prefixed parts until the first non-digit)."""
    if not symbol.startswith("_ZN"):
        return symbol
    parts, i = [], 3
    while i < len(symbol) and symbol[i].isdigit():
        j = i
        while symbol[j].isdigit():
            j += 1
        n = int(symbol[i:j])
        parts.append(symbol[j:j + n])
        i = j + n
    if parts and parts[0] == "rocking":
        parts = parts[1:]
    return ".".join(parts) or symbol


def write_perf_map() -> int:
    """Write /tmp/perf-<pid>.map for every compiled function of every ``rocking`` dispatcher
    compiled in this process; returns how many addresses it holds."""
    from numba.core.registry import CPUDispatcher

    starts: dict[int, str] = {}
    seen: set[int] = set()
    for module in list(sys.modules.values()):
        if not getattr(module, "__name__", "").startswith("rocking"):
            continue
        for obj in list(vars(module).values()):
            if not isinstance(obj, CPUDispatcher) or id(obj) in seen:
                continue
            seen.add(id(obj))
            for cres in obj.overloads.values():
                library = cres.library
                for fn in library._final_module.functions:
                    if fn.is_declaration:
                        continue
                    address = library.get_pointer_to_function(fn.name)
                    if address:
                        starts[address] = fn.name
    addresses = sorted(starts)
    with open(f"/tmp/perf-{os.getpid()}.map", "w", encoding="utf-8") as fh:
        for i, a in enumerate(addresses):
            # the map wants a size: up to the next known function, at most 256 KiB
            size = min(addresses[i + 1] - a if i + 1 < len(addresses) else 1 << 16, 1 << 18)
            fh.write(f"{a:x} {size:x} {starts[a]}\n")
    return len(addresses)


def child(case: str, seconds: float) -> None:
    sys.path.insert(0, str(HERE))
    import rocking as rk
    from rocking.stack import simulate_stack
    from stack import cases

    found = {c[0]: c for c in cases()}
    if case not in found:
        raise SystemExit(f"case must be one of {', '.join(found)}, got {case!r}")
    _, label, stack, _, motion, duration = found[case]
    opts = rk.Options(save_dt=0.01)
    run = lambda: simulate_stack(stack, motion, duration=duration, options=opts)  # noqa: E731
    run()  # compiles
    n = write_perf_map()
    print(f"ready {os.getpid()} {n}", flush=True)
    time.sleep(1.0)  # the parent starts perf
    t0, runs = time.perf_counter(), 0
    while time.perf_counter() - t0 < seconds:
        run()
        runs += 1
    print(f"runs {runs} {(time.perf_counter() - t0) / runs * 1e3:.2f} {label}", flush=True)


_ROW = re.compile(r"^\s*([\d.]+)%\s+(\S.*?)\s+\[[.k]\]\s+(\S+)")


def parent(case: str, seconds: float, top: int) -> None:
    if shutil.which("perf") is None:
        raise SystemExit("this profile needs Linux `perf` on the PATH")
    with tempfile.TemporaryDirectory(prefix="rocking-profile-") as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp) / "numba"))
        proc = subprocess.Popen([sys.executable, __file__, "--child", case, "--seconds", str(seconds)],
                                stdout=subprocess.PIPE, text=True, env=env)
        print(f"compiling the engine in a fresh cache (case {case}) …", flush=True)
        line = proc.stdout.readline()
        if not line.startswith("ready"):
            proc.wait()
            raise SystemExit("the child process did not start (see its error above)")
        pid, n_map = line.split()[1:3]
        data = Path(tmp) / "perf.data"
        record = subprocess.run(["perf", "record", "-q", "-F", "1999", "-o", str(data), "-p", pid, "--",
                                 "sleep", str(seconds)], capture_output=True, text=True)
        tail = proc.stdout.read()
        proc.wait()
        if record.returncode != 0:
            raise SystemExit(f"perf record failed: {record.stderr.strip()}")
        report = subprocess.run(["perf", "report", "-i", str(data), "--stdio", "--no-children",
                                 "--sort", "dso,sym", "--percent-limit", "0.01"],
                                capture_output=True, text=True, check=True).stdout
        Path(f"/tmp/perf-{pid}.map").unlink(missing_ok=True)
    shares: dict[str, float] = defaultdict(float)
    for row in report.splitlines():
        m = _ROW.match(row)
        if not m:
            continue
        pct, dso, sym = float(m.group(1)), m.group(2), m.group(3)
        if dso.startswith("[JIT]"):
            shares[short_name(sym)] += pct
        elif dso.startswith("libm"):
            shares[f"libm {sym.split('_fma')[0].lstrip('_')}"] += pct
        else:
            shares["outside compiled code: Python, numpy, libc, kernel"] += pct
    runs = tail.split()
    if len(runs) >= 3 and runs[0] == "runs":
        print(f"{runs[1]} runs of case {case}, {runs[2]} ms each (while profiled); {n_map} compiled functions mapped")
    print(f"{'share':>7s}  function")
    for name, pct in sorted(shares.items(), key=lambda kv: -kv[1])[:top]:
        print(f"{pct:6.2f}%  {name}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", help="a case of bench/stack.py: b2, r1, r3, r3m, r3r")
    ap.add_argument("--seconds", type=float, default=10.0, help="how long to sample (s)")
    ap.add_argument("--top", type=int, default=20, help="rows to print")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args.case, args.seconds)
    else:
        parent(args.case, args.seconds, args.top)


if __name__ == "__main__":
    main()
