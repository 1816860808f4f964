"""On-demand benchmark of the stack engine (rocking.stack, issue 11 §7). Not collected by pytest.

    .venv/bin/python bench/stack.py            # 5 repeats per case
    .venv/bin/python bench/stack.py --quick    # 2 repeats
    .venv/bin/python bench/stack.py --cpu      # process CPU time instead of wall time (steadier on a busy machine)

Prints, per case, the median wall time of one run of the general engine and, where the case is
the seed's two-body model, of today's special-purpose solver (``rocking.simulate``) on the same
case, with their ratio (the issue's target: ≤ 2); and, for the three-block stack under a 30 s
record, the time against the issue's 5 ms target. JIT compilation is excluded (every case runs
once first). Optional peers (MuJoCo, compas-lmgc90) are not run here: bench/mujoco_peer.py
covers MuJoCo for the single block.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import rocking as rk  # noqa: E402
from cases import RECORD, RECORD_LENGTH, paper_motion  # noqa: E402
from rocking.io.records import read_record  # noqa: E402
from rocking.stack import Block, Interface, Stack, simulate_stack  # noqa: E402

FRICTION = rk.Friction(static=0.4, kinetic=0.3)


def _median_time(fn, repeats: int, clock=time.perf_counter) -> float:
    times = []
    for _ in range(repeats):
        t0 = clock()
        fn()
        times.append(clock() - t0)
    return statistics.median(times)


def cases():
    record = read_record(RECORD).trimmed(RECORD_LENGTH)
    statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    window = paper_motion().duration
    two = Stack(blocks=(Block(name="pedestal", width=4.0, height=0.2, mass=1.0),
                        Block(name="statue", width=1.0, height=4.0, mass=1.0)),
                interfaces=(Interface(friction=FRICTION), Interface(restitution=0.8)))
    three = Stack(blocks=(Block(name="plinth", width=1.2, height=0.4, mass=400.0),
                          Block(name="statue", width=0.4, height=1.4, mass=150.0),
                          Block(name="vase", width=0.2, height=0.45, mass=8.0)),
                  interfaces=(Interface(friction=FRICTION), Interface(friction=rk.Friction(static=0.6, kinetic=0.5)),
                              Interface(friction=rk.Friction(static=0.5, kinetic=0.4))))
    return [
        ("b2", "statue on pedestal (paper case b), 30 cycles", two,
         rk.System(statue=statue, pedestal=rk.Pedestal(mass=1.0, friction=FRICTION)), paper_motion(), window),
        ("r1", f"0.3×1.2 m block, {RECORD} {RECORD_LENGTH:g} s",
         Stack(blocks=(Block(width=0.3, height=1.2, mass=1.0),), interfaces=(Interface(),)),
         rk.System(statue=rk.Statue(width=0.3, height=1.2, mass=1.0)), record, record.duration),
        ("r3", f"plinth + statue + vase, {RECORD} {RECORD_LENGTH:g} s (the vase falls at 3.3 s: the run ends there)",
         three, None, record, record.duration),
        # the same stack through more of the record: the statue and the vase rock for 7 s (302
        # events) and come to rest; and at rest relative to the floor for the whole 30 s
        ("r3m", f"plinth + statue + vase, {RECORD} × 0.6 (statue and vase rock for 7 s, nothing falls)",
         three, None, record.scaled(0.6), record.duration),
        ("r3r", f"plinth + statue + vase, {RECORD} × 0.4 (nothing moves on the floor: 30 s of rest)",
         three, None, record.scaled(0.4), record.duration),
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--cpu", action="store_true", help="time with the process's CPU clock, not the wall clock")
    args = ap.parse_args()
    clock = time.process_time if args.cpu else time.perf_counter
    repeats = 2 if args.quick else 5
    opts = rk.Options(save_dt=0.01)
    print(f"{'case':5s} {'stack engine':>14s} {'rocking.simulate':>18s} {'ratio':>7s}  verdicts")
    for key, label, stack, system, motion, duration in cases():
        run_stack = lambda: simulate_stack(stack, motion, duration=duration, options=opts)  # noqa: E731
        r = run_stack()  # compile / warm
        t_stack = _median_time(run_stack, repeats, clock)
        line = f"{key:5s} {1e3 * t_stack:11.2f} ms"
        if system is not None:
            run_ref = lambda: rk.simulate(system, motion, duration=duration, options=opts)  # noqa: E731
            ref = run_ref()
            t_ref = _median_time(run_ref, repeats, clock)
            line += f" {1e3 * t_ref:15.2f} ms {t_stack / t_ref:7.2f}  {r.verdict} | {ref.verdict}"
        else:
            line += (f" {'-':>18s} {'-':>7s}  {r.verdict} (target ≤ 5 ms for a 30 s record: {t_stack / 5e-3:.1f}× "
                     f"the target, {r.end_time:.1f} s simulated)")
        print(line, "  —", label, f"[{len(r.events)} events]")


if __name__ == "__main__":
    main()
