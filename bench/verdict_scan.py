"""On-demand scan: the two engines' verdicts on random museum-like statues, alone or on pedestals,
under the bundled records. Not collected by pytest.

    .venv/bin/python bench/verdict_scan.py --seed 1 --runs 2000      # about 40 s of one core
    .venv/bin/python bench/verdict_scan.py --seed 1 --runs 2000 --json scan.json

Each case: a statue 0.15–0.6 × 0.5–2.2 m of 20–800 kg, alone on a frictional floor one time in
five, else on a pedestal 0.6–1.6 × 0.3–1.0 m of 100–1600 kg whose top face never slips; μs
0.12–0.7 (μk 0.7–1 of it); Housner's restitution or one of 0.6–0.95; 20 s of a bundled record at a
PGA of 0.8–8 m/s². It runs ``rocking.simulate`` (the two-body model) and ``simulate_stack`` (the
general engine, whose pedestal may rock) and prints the pairs of statuses, the runs either
engine leaves undetermined, and where the verdicts differ, whether the stack engine's pedestal
rocked and whether the two-body model warned of it (a force uplift, or an impact whose floor
impulse leaves the base). docs/theory/stack.md §9 gives what it found on 2026-12-06.
"""

from __future__ import annotations

import argparse
import collections
import json
import time

import numpy as np

import rocking as rk
from rocking.io.records import bundled_records, read_record
from rocking.stack import Block, Interface, Stack, simulate_stack


def cases(seed: int, runs: int):
    rng = np.random.default_rng(seed)
    names = sorted(bundled_records())
    records = {n: read_record(n).trimmed(20.0) for n in names}
    for i in range(runs):
        pw, ph, pm = rng.uniform(0.6, 1.6), rng.uniform(0.3, 1.0), 10 ** rng.uniform(2, 3.2)
        sw, sh, sm = rng.uniform(0.15, 0.6), rng.uniform(0.5, 2.2), 10 ** rng.uniform(1.3, 2.9)
        mu = rng.uniform(0.12, 0.7)
        fr = rk.Friction(static=float(mu), kinetic=float(mu * rng.uniform(0.7, 1.0)))
        rest = None if rng.random() < 0.5 else float(rng.uniform(0.6, 0.95))
        alone = rng.random() < 0.2
        name = names[rng.integers(len(names))]
        motion = records[name].scaled(pga=float(rng.uniform(0.8, 8.0)))
        statue = rk.Statue(width=float(sw), height=float(sh), mass=float(sm), restitution=rest,
                           friction=fr if alone else None)
        if alone:
            system = rk.System(statue=statue)
            stack = Stack(blocks=(Block(width=float(sw), height=float(sh), mass=float(sm)),),
                          interfaces=(Interface(friction=fr, restitution=rest),))
        else:
            pedestal = rk.Pedestal(mass=float(pm), friction=fr, width=float(pw), height=float(ph))
            system = rk.System(statue=statue, pedestal=pedestal)
            stack = Stack(blocks=(Block(width=float(pw), height=float(ph), mass=float(pm)),
                                  Block(width=float(sw), height=float(sh), mass=float(sm))),
                          interfaces=(Interface(friction=fr), Interface(restitution=rest)))
        yield i, name, alone, system, stack, motion


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--runs", type=int, default=2000)
    ap.add_argument("--json", help="write one row per run to this file")
    args = ap.parse_args()
    rows, t0 = [], time.perf_counter()
    for i, name, alone, system, stack, motion in cases(args.seed, args.runs):
        two = rk.simulate(system, motion)
        a, b, lifts = two.summary(), simulate_stack(stack, motion).summary(), two.impact_uplifts()
        rows.append(dict(i=i, record=name, alone=alone, two_body=a["status"], stack=b["status"],
                         two_body_verdict=a["verdict"], stack_verdict=b["verdict"],
                         force_uplift=a["pedestal_uplift_time"],
                         impact_uplift=float(lifts[0]) if lifts.size else None,
                         stack_pedestal_rocks=None if alone else b["blocks"][0]["first_rocking_time"]))
    print(f"{len(rows)} runs in {time.perf_counter() - t0:.0f} s (seed {args.seed})")
    for pair, n in collections.Counter((r["two_body"], r["stack"]) for r in rows).most_common():
        print(f"  two-body {pair[0]:>13s}, stack engine {pair[1]:>13s}: {n}")
    decided = ("completed", "overturned")
    for r in rows:
        if r["two_body"] not in decided or r["stack"] not in decided:
            print(f"  undetermined: run {r['i']} ({r['record']}): {r['two_body_verdict']} | {r['stack_verdict']}")
    differ = [r for r in rows if r["two_body"] in decided and r["stack"] in decided and r["two_body"] != r["stack"]]
    print(f"verdicts differ in {len(differ)} runs both engines decide:")
    for r in differ:
        print(f"  run {r['i']} ({r['record']}, {'alone' if r['alone'] else 'on a pedestal'}): {r['two_body_verdict']} | "
              f"{r['stack_verdict']}; stack pedestal rocks from {r['stack_pedestal_rocks']}, two-body warns of a force "
              f"uplift from {r['force_uplift']}, of an impact's from {r['impact_uplift']}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(rows, f)


if __name__ == "__main__":
    main()
