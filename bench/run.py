"""On-demand benchmark: the compiled solver against the SciPy reference, its integrator cross-check
(``rocking.solver.crosscheck``: the same physics integrated by ``solve_ivp``).

    .venv/bin/python bench/run.py            # cases (a)-(c), batch of 2 000 runs
    .venv/bin/python bench/run.py --full     # batch of 10 000 runs
    .venv/bin/python bench/run.py --quick    # fewer repeats, batch of 200 (a smoke run)

Prints, in one run: the median/min/max wall time per simulation of both solvers on the same
cases and their ratio; the throughput (runs per second) of a batch of runs over an
amplitude × frequency grid; and the accuracy max |θ_compiled − θ_reference| over the first 5 s.
JIT compilation is excluded (every code path is warmed up first). Not collected by pytest.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numba  # noqa: E402
import scipy  # noqa: E402

import rocking as rk  # noqa: E402
from cases import Case, batch_grid, cases, paper_motion  # noqa: E402
from rocking.analyses.batch import run_cases  # noqa: E402
from rocking.solver.crosscheck import simulate_crosscheck  # noqa: E402

ACCURACY_WINDOW = 5.0  # s


def _compiled(case: Case, options: rk.Options, save: bool = False):
    return rk.simulate(case.system, case.motion, duration=case.duration, options=options, save=save, throw=False)


def _reference(case: Case, options: rk.Options, save: bool = False, save_dt: float = 0.01):
    return simulate_crosscheck(case.system, case.motion, duration=case.duration, options=options, save=save,
                              save_dt=save_dt)


def _timed(fn, repeats: int) -> list[float]:
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


def _ms(x: float) -> str:
    return f"{1e3 * x:10.2f}"


def _outcome_compiled(r) -> str:
    return f"{r.status}, t_end={r.summary()['end_time']:.3f} s, {len(r.events)} events"


def _outcome_reference(r) -> str:
    return f"{r['status']}, t_end={r['end_time']:.3f} s, {len(r['events'])} events"


def _accuracy(case: Case, c_options: rk.Options, r_options: rk.Options) -> tuple[float, str]:
    """max |θ_c − θ_r| over the first 5 s on the common output grid, and an event summary."""
    dt = case.save_dt
    c = rk.simulate(case.system, case.motion, duration=case.duration,
                    options=rk.Options(**{**_fields(c_options), "save_dt": dt}), throw=False)
    r = simulate_crosscheck(case.system, case.motion, duration=case.duration, options=r_options, save_dt=dt)
    k = np.rint(c.t / dt)
    on = c.t == k * dt
    _, first = np.unique(k[on], return_index=True)
    rows = np.flatnonzero(on)[first]
    n = min(rows.size, r["t"].size)
    tc, thc = c.t[rows][:n], c.theta[rows][:n]
    if not np.array_equal(tc, r["t"][:n]):
        return math.nan, "grids differ"
    keep = tc <= ACCURACY_WINDOW + 1e-9
    d = float(np.max(np.abs(thc[keep] - r["theta"][:n][keep]))) if keep.any() else math.nan
    ec = [(e.time, e.kind) for e in c.events if e.time <= ACCURACY_WINDOW]
    er = [e for e in r["events"] if e[0] <= ACCURACY_WINDOW]
    same = len(ec) == len(er) and all(a[1] == b[1] for a, b in zip(ec, er))
    dt_ev = max((abs(a[0] - b[0]) for a, b in zip(ec, er)), default=0.0)
    verdict = f"overturned c={c.overturned} r={r['overturned']}"
    return d, f"{len(ec)} events ≤ {ACCURACY_WINDOW:g} s, kinds {'agree' if same else 'DIFFER'}, " \
              f"max |Δt_event| = {dt_ev:.1e} s; {verdict}"


def _fields(options: rk.Options) -> dict:
    return {name: getattr(options, name) for name in options.__dataclass_fields__}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=20, help="timed repeats of the compiled solver per case")
    ap.add_argument("--ref-repeats", type=int, default=3, help="timed repeats of the reference per case")
    ap.add_argument("--batch", type=int, default=2000, help="runs in the compiled batch (default 2000)")
    ap.add_argument("--full", action="store_true", help="batch of 10 000 runs")
    ap.add_argument("--ref-batch", type=int, default=10, help="runs of the reference batch estimate")
    ap.add_argument("--batch-repeats", type=int, default=3, help="timed repeats of the whole compiled batch")
    ap.add_argument("--quick", action="store_true", help="smoke run: 5/1 repeats, batch of 200, 2 reference runs")
    ap.add_argument("--rtol", type=float, default=rk.Options().rtol, help="tolerances of the timed runs (both solvers)")
    ap.add_argument("--atol", type=float, default=rk.Options().atol)
    ap.add_argument("--ref-rtol", type=float, default=1e-12, help="reference tolerance for the accuracy check")
    ap.add_argument("--ref-atol", type=float, default=1e-13)
    ap.add_argument("--cases", default="abcd", help="subset of cases to run, e.g. 'ab' or 'd'")
    args = ap.parse_args(argv)
    if args.quick:
        args.repeats, args.ref_repeats, args.batch, args.ref_batch, args.batch_repeats = 5, 1, 200, 3, 1
    if args.full:
        args.batch = 10_000

    timing = rk.Options(rtol=args.rtol, atol=args.atol)
    tight = rk.Options(rtol=args.ref_rtol, atol=args.ref_atol)
    print(f"rocking {rk.__version__} | Python {platform.python_version()} | numpy {np.__version__} | "
          f"scipy {scipy.__version__} | numba {numba.__version__}")
    print(f"{platform.processor() or platform.machine()} | {os.cpu_count()} CPUs | "
          f"load average {', '.join(f'{x:.2f}' for x in os.getloadavg())} (other processes skew timings)")
    print(f"timed runs: rtol={args.rtol:g} atol={args.atol:g} (both solvers); compiled save=False, reference "
          f"save=False; JIT compilation excluded (warm-up first)\n")

    all_cases = [c for c in cases() if c.key in args.cases]
    t0 = time.perf_counter()
    for case in all_cases:  # JIT warm-up (compiled core and the physics kernels called from Python)
        _compiled(case, timing)
        _compiled(case, timing, save=True)
    warm_compiled = time.perf_counter() - t0
    t0 = time.perf_counter()
    if all_cases:
        c0 = all_cases[0]
        simulate_crosscheck(c0.system, c0.motion, duration=1.0, options=timing)
    for case in all_cases:
        if case.system.pedestal is not None or case.system.statue.friction is not None:
            simulate_crosscheck(case.system, case.motion, duration=1.0, options=timing)
    warm_reference = time.perf_counter() - t0
    print(f"warm-up (JIT compilation or cache load): compiled {warm_compiled:.1f} s, "
          f"reference {warm_reference:.1f} s\n")

    if all_cases:
        header = f"{'case':4s} {'solver':10s} {'median ms':>10s} {'min ms':>10s} {'max ms':>10s} {'n':>4s} " \
                 f"{'ref/comp':>9s}  outcome"
        print("Per-simulation wall time")
        print(header)
        print("-" * len(header))
        for case in all_cases:
            tc = _timed(lambda: _compiled(case, timing), args.repeats)
            tr = _timed(lambda: _reference(case, timing), args.ref_repeats)
            rc = _compiled(case, timing)
            rr = _reference(case, timing)
            ratio = statistics.median(tr) / statistics.median(tc)
            print(f"{case.key:4s} {'compiled':10s} {_ms(statistics.median(tc))} {_ms(min(tc))} {_ms(max(tc))} "
                  f"{len(tc):4d} {'':>9s}  {_outcome_compiled(rc)}")
            print(f"{'':4s} {'reference':10s} {_ms(statistics.median(tr))} {_ms(min(tr))} {_ms(max(tr))} "
                  f"{len(tr):4d} {ratio:9.0f}  {_outcome_reference(rr)}")
        print()
        for case in all_cases:
            print(f"  ({case.key}) {case.label}")
        print()

    if "d" in args.cases:
        grid = batch_grid(args.batch)
        system = rk.System(statue=cases()[0].system.statue)
        motions = [paper_motion(a, f) for a, f in grid]
        # The batch API in this process (workers=1): summaries only, returned as a Dataset.
        run_cases([(system, motions[0])], options=timing, workers=1)  # warm-up (imports xarray)
        batch = [(system, m) for m in motions]
        elapsed = []
        for _ in range(args.batch_repeats):
            t0 = time.perf_counter()
            ds = run_cases(batch, options=timing, workers=1)
            elapsed.append(time.perf_counter() - t0)
        el_c = float(np.median(elapsed))
        n_over = int(ds.overturned.sum())
        mem_mb = ds.nbytes / 1e6
        # The reference on an evenly spaced subset of the same grid (it covers all amplitudes),
        # and the compiled solver on the same subset for a like-for-like ratio.
        k = max(1, min(args.ref_batch, len(motions)))
        picks = sorted({int(round(i)) for i in np.linspace(0, len(motions) - 1, k)})
        t0 = time.perf_counter()
        ref_over = [simulate_crosscheck(system, motions[i], options=timing, save=False)["overturned"] for i in picks]
        el_r = time.perf_counter() - t0
        t0 = time.perf_counter()
        reps = 5
        for _ in range(reps):
            comp_over = [rk.simulate(system, motions[i], options=timing, save=False).overturned for i in picks]
        el_cs = (time.perf_counter() - t0) / reps
        agree = sum(a == b for a, b in zip(ref_over, comp_over))
        ps_c, ps_r = len(motions) / el_c, len(picks) / el_r
        ratio = el_r / el_cs
        a_lo, a_hi = grid[0][0], grid[-1][0]
        f_lo, f_hi = min(f for _, f in grid), max(f for _, f in grid)
        print(f"(d) batch: case (a) block, 30 cycles of A cos(2πft), A = {a_lo:g}–{a_hi:g} m/s² × "
              f"f = {f_lo:g}–{f_hi:g} Hz (serial, one process)")
        print(f"    compiled : {len(motions):6d} runs in {el_c:8.2f} s -> {ps_c:9.1f} runs/s "
              f"({1e3 / ps_c:.2f} ms/run; {n_over} overturned; Dataset of summaries {mem_mb:.1f} MB)")
        print(f"               median of {len(elapsed)} batches; min {len(motions) / max(elapsed):.1f}, "
              f"max {len(motions) / min(elapsed):.1f} runs/s")
        print(f"    reference: {len(picks):6d} runs in {el_r:8.2f} s -> {ps_r:9.2f} runs/s "
              f"({1e3 / ps_r:.0f} ms/run; evenly spaced subset of the grid; verdicts agree on {agree}/{len(picks)})")
        print(f"    same subset, compiled: {len(picks) / el_cs:.1f} runs/s -> reference/compiled time ratio "
              f"{ratio:.0f}; the reference would need ~{ratio * el_c / 60:.1f} min for the whole batch\n")

    if all_cases:
        print(f"Accuracy: compiled (rtol={args.rtol:g}, atol={args.atol:g}) vs reference "
              f"(rtol={args.ref_rtol:g}, atol={args.ref_atol:g}), first {ACCURACY_WINDOW:g} s")
        for case in all_cases:
            d, note = _accuracy(case, timing, tight)
            print(f"  ({case.key}) max |θ_c − θ_r| = {d:.2e} rad; {note}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
