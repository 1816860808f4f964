"""The stack engine's own invariants on many random stacks: which runs break one, and how.

The random stacks are the test suite's (``tests/test_stack_engine.py::_random_stacks``: one to
three blocks, friction on four faces in five, a sine pulse, a harmonic or 15 s of a bundled record);
the suite checks a few seeds, this script as many as asked. For every run it checks what the
suite's random-stack tests check:

* the status (anything but ``completed`` and ``overturned`` is listed: an undetermined verdict);
* no corner deeper than 1e-5 m into the face below it (the saved poses);
* the ledger balances to 3e-7 of the run's energy scale, max |W_in| + max |E − E₀|;
* no impact and no friction gives energy (1e-8 and 1e-9 of the scale);
* no face that can slip reports needing more than its μs (to the report's 1e-6).

Usage: ``.venv/bin/python bench/stack_invariants.py --seeds 1-12 --runs 150`` (about 2 minutes
once the engine is compiled; docs/theory/stack.md §7 and §9 give what it found on 2026-12-07).

``--floors jumping`` puts the same stacks under floors whose acceleration jumps, which the suite's
motions never do (their sine pulses, harmonics and records are continuous): a rectangle pulse, a
one-cosine pulse, a cos harmonic (each jumps at its start, the pulses at their end too) or a sine
pulse with a phase, drawn from a generator of its own (seed 1000 + the seed), so the stacks are the
suite's. About a minute for seeds 1–12.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from test_stack_engine import _deepest_sink, _jumping_floor, _random_stacks  # noqa: E402

from rocking.stack import simulate_stack  # noqa: E402


def _seeds(spec: str) -> list[int]:
    out = []
    for part in spec.split(","):
        lo, _, hi = part.partition("-")
        out.extend(range(int(lo), int(hi or lo) + 1))
    return out


def check(stack, motion) -> tuple[str, list[str]]:
    """(status, the invariants the run breaks, each with its figure)."""
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    broken = []
    sink = _deepest_sink(r)
    if sink < -1e-5:
        broken.append(f"a corner {-sink:.2e} m into the face below")
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    if r.status in ("completed", "overturned") and np.max(np.abs(r.balance_error())) > 3e-7 * scale:
        broken.append(f"ledger off by {np.max(np.abs(r.balance_error())) / scale:.1e} of the scale")
    impacts = r.events[r.events[:, 2] == -1]
    if len(impacts) and impacts[:, 5].min() < -1e-8 * scale:
        broken.append(f"an impact gave {-impacts[:, 5].min() / scale:.1e} of the scale")
    fall = np.diff(r.friction_loss)
    if len(fall) and fall.min() < -1e-9 * scale:
        broken.append(f"friction gave {-fall.min() / scale:.1e} of the scale between samples, "
                      f"from t = {r.t[int(np.argmin(fall))]:.3f} s")
    for summary, interface in zip(r.interfaces, stack.interfaces):
        if interface.friction is not None and summary["required_friction"] > interface.friction.mu_s * (1 + 1e-6):
            broken.append(f"{summary['name']} needs {summary['required_friction']:.6g} > μs = "
                          f"{interface.friction.mu_s:.6g}")
    return r.status, broken


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="1-12", help="seeds of _random_stacks, e.g. 1-12 or 1,4,7")
    parser.add_argument("--runs", type=int, default=150, help="stacks per seed")
    parser.add_argument("--floors", choices=("suite", "jumping"), default="suite",
                        help="the suite's motions, or floors that jump (the same stacks)")
    args = parser.parse_args(argv)
    total, undetermined, broken_runs = Counter(), 0, 0
    t0 = time.perf_counter()
    for seed in _seeds(args.seeds):
        floors = np.random.default_rng(1000 + seed)
        for i, (stack, motion) in enumerate(_random_stacks(seed, args.runs)):
            if args.floors == "jumping":
                motion = _jumping_floor(floors)
            status, broken = check(stack, motion)
            total[status] += 1
            undetermined += status not in ("completed", "overturned")
            broken_runs += bool(broken)
            if status not in ("completed", "overturned") or broken:
                print(f"seed {seed:3d} run {i:4d}: {status}" + (f" ({motion!r})" if args.floors == "jumping" else "")
                      + "".join(f"; {b}" for b in broken), flush=True)
    runs = sum(total.values())
    print(f"\n{runs} runs in {time.perf_counter() - t0:.0f} s: " + ", ".join(f"{k} {v}" for k, v in total.most_common()))
    print(f"undetermined {undetermined}, breaking an invariant {broken_runs}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
