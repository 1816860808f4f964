"""``python -m rocking.validation [--out docs/validation.md] [--quick] [--no-peer] [--check]``:
regenerate the validation manual: about 20 s on one core once the solver is compiled, MuJoCo's
section (when installed) included; progress goes to stderr."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .manual import all_rows, build, parse, render
from .rows import ACCEPTED


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m rocking.validation", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, help="write the manual there (default: print it)")
    ap.add_argument("--quick", action="store_true", help="a subset of the cases (seconds; for tests)")
    ap.add_argument("--no-peer", action="store_true", help="leave out the MuJoCo section even if installed")
    ap.add_argument("--check", type=Path, metavar="FILE",
                    help="compare the computed rows with those of FILE (a committed manual) instead of writing")
    args = ap.parse_args(argv)

    start = time.perf_counter()

    def progress(message: str) -> None:
        print(f"[{time.perf_counter() - start:6.1f} s] {message}", file=sys.stderr, flush=True)

    sections = build(args.quick, progress, with_peer=not args.no_peer)
    rows = all_rows(sections)
    bad = [r for r in rows if r.status not in ACCEPTED]
    for r in bad:
        print(f"{r.id}: {r.status}: {r.case}: {r.detail}", file=sys.stderr)
    if args.check is not None:
        committed = parse(args.check.read_text(encoding="utf-8"))
        stale = [r.id for r in rows if r.id not in committed or committed[r.id]["status"] != r.status
                 or not _close(committed[r.id]["ours"], r.ours)]
        for rid in stale:
            print(f"{rid}: differs from {args.check}", file=sys.stderr)
        progress(f"checked {len(rows)} rows: {len(stale)} stale, {len(bad)} not accepted")
        return 1 if stale or bad else 0
    text = render(sections)
    if args.out is None:
        sys.stdout.write(text)
    else:
        args.out.write_text(text, encoding="utf-8")
        progress(f"wrote {args.out} ({len(rows)} rows)")
    return 1 if bad else 0


def _close(a: float | None, b: float | None, rtol: float = 1e-5) -> bool:
    """Numbers of the manual (printed to 10 digits) against a fresh computation."""
    if a is None or b is None:
        return a is None and b is None
    return abs(a - b) <= rtol * max(abs(a), abs(b)) + 1e-12


if __name__ == "__main__":
    raise SystemExit(main())
